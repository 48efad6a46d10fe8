//! Seeded poses of B relative to A (A at the identity): separated, near-touching, overlapping
//! and random placements inside A's bounding cylinder (interlocked, nested or crossing, as the
//! shapes allow).

use super::shapes::Prepared;
use crate::queries::PoseSpec;
use nalgebra::{Isometry3, Quaternion, UnitQuaternion, Vector3};
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;

/// Gap range (length units) of separated poses.
pub const SEPARATED_GAPS: (f64, f64) = (0.1, 1.0);
/// Gap range of near-touching poses.
pub const NEAR_GAPS: (f64, f64) = (1e-4, 1e-1);
/// Depth range (relative to the smaller solid's radius) by which overlapping poses push B
/// past contact.
pub const OVERLAP_DEPTHS: (f64, f64) = (1e-3, 0.5);
/// Conservative-advancement steps when sliding B towards A (each step keeps the gap above the
/// target, see `approach`); the final pose is accepted whatever its gap, which is recorded.
pub const ADVANCE_STEPS: usize = 30;
/// Advancement stops when the gap is within this factor of the target.
pub const ADVANCE_ACCEPT: f64 = 1.5;

/// How B was placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PoseKind {
    Separated,
    NearTouching,
    Overlapping,
    /// B's centre uniform in A's bounding cylinder, random rotation.
    Inside,
}

impl PoseKind {
    pub const ALL: [PoseKind; 4] = [
        PoseKind::Separated,
        PoseKind::NearTouching,
        PoseKind::Overlapping,
        PoseKind::Inside,
    ];

    pub fn name(self) -> &'static str {
        match self {
            PoseKind::Separated => "separated",
            PoseKind::NearTouching => "near-touching",
            PoseKind::Overlapping => "overlapping",
            PoseKind::Inside => "inside-box",
        }
    }

    /// The kind of pose number `i`: a fixed cycle of 20 (8 near-touching, 6 separated, 3
    /// overlapping, 3 inside A's box) ordered so that any 4 consecutive poses from the start
    /// cover all kinds.
    pub fn of_index(i: usize) -> PoseKind {
        use PoseKind::{Inside as I, NearTouching as N, Overlapping as O, Separated as S};
        const CYCLE: [PoseKind; 20] = [N, S, O, I, N, S, N, S, N, O, I, N, S, N, S, N, O, I, N, S];
        CYCLE[i % CYCLE.len()]
    }
}

/// What placing B relative to A needs of a shape: its solid at the identity, the height of its
/// axis centre and the radius of a ball about that centre holding it.
pub trait PoseTarget {
    fn solid(&self) -> &Solid;
    fn centre_z(&self) -> f64;
    fn radius(&self) -> f64;
}

impl PoseTarget for Prepared {
    fn solid(&self) -> &Solid {
        &self.solid
    }
    fn centre_z(&self) -> f64 {
        self.centre_z
    }
    fn radius(&self) -> f64 {
        self.radius
    }
}

fn spec(t: Vector3<f64>, q: &UnitQuaternion<f64>) -> PoseSpec {
    PoseSpec::from_isometry(&Isometry3::from_parts(t.into(), *q))
}

/// B's pose with its axis centre at `A's centre + u s`, rotated by `q`.
fn along<T: PoseTarget>(
    a: &T,
    b: &T,
    q: &UnitQuaternion<f64>,
    u: &Vector3<f64>,
    s: f64,
) -> PoseSpec {
    let t = Vector3::new(0.0, 0.0, a.centre_z()) + u * s - q * Vector3::new(0.0, 0.0, b.centre_z());
    spec(t, q)
}

/// Slides B from far away along `u` towards A by conservative advancement: the distance is
/// 1-Lipschitz in the slide parameter, so stepping by `lower - gap` never passes below `gap`.
/// Returns the parameter reached (or `None` when A and B already meet far away, which cannot
/// happen for bounded solids).
fn approach<T: PoseTarget>(
    a: &T,
    b: &T,
    q: &UnitQuaternion<f64>,
    u: &Vector3<f64>,
    gap: f64,
) -> Option<f64> {
    let opts = QueryOptions::default();
    let mut s = a.radius() + b.radius() + gap + 1.0;
    for _ in 0..ADVANCE_STEPS {
        let pose = along(a, b, q, u, s).isometry();
        let d = distance(a.solid(), &b.solid().with_pose(pose), &opts);
        if d.overlap {
            return None;
        }
        if d.lower <= gap * ADVANCE_ACCEPT {
            break;
        }
        s -= d.lower - gap;
    }
    Some(s)
}

/// A pose of B of the given kind, drawn from `rng`.
pub fn make_pose(a: &Prepared, b: &Prepared, kind: PoseKind, rng: &mut SplitMix64) -> PoseSpec {
    make_pose_in(a, b, kind, NEAR_GAPS, rng)
}

/// As [`make_pose`], with near-touching gaps drawn log-uniformly from `near`.
pub fn make_pose_in<T: PoseTarget>(
    a: &T,
    b: &T,
    kind: PoseKind,
    near: (f64, f64),
    rng: &mut SplitMix64,
) -> PoseSpec {
    let r = rng.quaternion();
    let q = UnitQuaternion::from_quaternion(Quaternion::new(r[0], r[1], r[2], r[3]));
    let u = rng.direction();
    match kind {
        PoseKind::Separated | PoseKind::NearTouching => {
            let (lo, hi) = if kind == PoseKind::Separated {
                SEPARATED_GAPS
            } else {
                near
            };
            let gap = rng.log_range(lo, hi);
            let s = approach(a, b, &q, &u, gap).unwrap_or(a.radius() + b.radius() + 1.0);
            along(a, b, &q, &u, s)
        }
        PoseKind::Overlapping => {
            let depth =
                rng.log_range(OVERLAP_DEPTHS.0, OVERLAP_DEPTHS.1) * a.radius().min(b.radius());
            let s = approach(a, b, &q, &u, near.0).unwrap_or(0.0);
            along(a, b, &q, &u, s - depth)
        }
        PoseKind::Inside => {
            // Uniform in A's bounding ball about its axis centre.
            let r = a.radius() * rng.next_f64().cbrt();
            along(a, b, &q, &u, r)
        }
    }
}

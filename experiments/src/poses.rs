//! Seeded poses of solid B near solid A at a chosen gap, for timing queries near contact
//! (the regime where a distance query does real work).

use crate::shapes::centre;
use crate::SplitMix;
use nalgebra::{Isometry3, Translation3, Vector3};
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;

/// Bisection steps when sliding B towards A to reach the requested gap: the slide range
/// halves each step, so 60 steps reach double precision on any range below 1e15.
const PLACEMENT_STEPS: usize = 60;

/// Relative accuracy at which a placed gap is accepted.
const GAP_ACCEPT_REL: f64 = 0.05;

/// A pose of `b` (relative to `a`, which sits at the identity) with a random rotation and a
/// random approach direction, slid along that direction until the certified distance is
/// within [`GAP_ACCEPT_REL`] of `gap` (the query's own value is used to place it; timing
/// does not depend on how exactly the gap is hit). `centres` are the mid-height axis points
/// `z` of both solids; `reach` bounds the sum of both solids' radii about them.
pub fn pose_at_gap(
    a: &Solid,
    b: &Solid,
    centres: (f64, f64),
    reach: f64,
    gap: f64,
    rng: &mut SplitMix,
) -> Option<Isometry3<f64>> {
    let rot = rng.rotation();
    let dir = rng.unit_vector();
    let at = |s: f64| {
        let t =
            Vector3::new(0.0, 0.0, centres.0) + dir * s - rot * Vector3::new(0.0, 0.0, centres.1);
        Isometry3::from_parts(Translation3::from(t), rot)
    };
    let opts = QueryOptions::default();
    let gap_of = |s: f64| {
        let d = distance(a, &b.with_pose(at(s)), &opts);
        if d.overlap {
            -1.0
        } else {
            d.value
        }
    };
    // Distance is 0 (or overlap) at s = 0 only if the axis points overlap; search from the
    // far side, where the solids are certainly apart.
    let (mut lo, mut hi) = (0.0, reach + 2.0 * gap + 1.0);
    if gap_of(hi) < gap {
        return None;
    }
    for _ in 0..PLACEMENT_STEPS {
        let mid = 0.5 * (lo + hi);
        let g = gap_of(mid);
        if (g - gap).abs() <= GAP_ACCEPT_REL * gap {
            return Some(at(mid));
        }
        if g < gap {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

/// Log-uniform gap in `[lo, hi]`.
pub fn log_uniform(rng: &mut SplitMix, lo: f64, hi: f64) -> f64 {
    (lo.ln() + (hi.ln() - lo.ln()) * rng.next_f64()).exp()
}

/// Gap range of the close poses (log-uniform), as in issue 11.
pub const CLOSE_GAPS: (f64, f64) = (1e-3, 1e-1);

/// Eps of the trees that place the close poses: far below the smallest gap, so the placed gaps
/// are within a few percent of the drawn ones whatever eps the timed solids use.
pub const PLACEMENT_EPS: f64 = 1e-6;

/// Seed of the close-pose sequences of the FCL comparisons (`fcl_bench`, `pareto`): both
/// time the same poses of a pair.
pub const CLOSE_SEED: u64 = 0x12_2026;

/// Draws per pose before [`close_poses`] gives up (a draw fails only when the bisection does
/// not reach the gap, which is rare).
const MAX_DRAWS_PER_POSE: usize = 100;

/// The seed of the pose sequence of the pair named `pair` (e.g. `pawn-cup`): `seed` xor a
/// hash of the name, so every pair has its own sequence and every run the same ones.
pub fn pair_seed(seed: u64, pair: &str) -> u64 {
    seed ^ pair
        .bytes()
        .fold(0u64, |h, c| h.wrapping_mul(31) ^ u64::from(c))
}

/// `n` seeded poses of the solid of `pb` near the solid of `pa` (at the identity), gaps drawn
/// log-uniform in `gaps`, placed by [`pose_at_gap`] with trees of [`PLACEMENT_EPS`]. The same
/// `seed` gives the same poses, and a shorter `n` a prefix of a longer one. `on_pose` is
/// called after each pose is placed (for a progress bar).
pub fn close_poses(
    pa: &Arc<Profile>,
    pb: &Arc<Profile>,
    n: usize,
    gaps: (f64, f64),
    seed: u64,
    mut on_pose: impl FnMut(),
) -> Result<Vec<Isometry3<f64>>, Box<dyn std::error::Error>> {
    let ((za, ra), (zb, rb)) = (centre(pa), centre(pb));
    let place_a = Solid::from_profile(Arc::clone(pa), PLACEMENT_EPS)?;
    let place_b = Solid::from_profile(Arc::clone(pb), PLACEMENT_EPS)?;
    let mut rng = SplitMix(seed);
    let mut poses = Vec::with_capacity(n);
    let mut draws = 0;
    while poses.len() < n {
        draws += 1;
        if draws > MAX_DRAWS_PER_POSE * n {
            return Err(format!(
                "placed only {} of {n} poses of {} near {} in {draws} draws",
                poses.len(),
                pb.name(),
                pa.name()
            )
            .into());
        }
        let gap = log_uniform(&mut rng, gaps.0, gaps.1);
        if let Some(p) = pose_at_gap(&place_a, &place_b, (za, zb), ra + rb, gap, &mut rng) {
            poses.push(p);
            on_pose();
        }
    }
    Ok(poses)
}

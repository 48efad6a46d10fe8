//! Corner contacts: B posed so that a corner circle of A (a G0 join of two pieces, a kink at
//! an interior knot of a degree-1 piece or at a knot of full multiplicity) touches a corner
//! circle of B, a smooth point of B or B's tip or cap on the axis, at a chosen gap along a
//! direction of A's normal cone there (`docs/verification.md`, "Corner contacts").
//!
//! The features are found from the profile's pieces and knots alone; which side is outside
//! is asked of the oracle's planar index (a point a little along each candidate normal), so
//! nothing here depends on the query's trees. Whether the two solids really touch only at
//! the chosen points is not assumed: the oracle decides the truth of every case.

use super::placement::spec;
use super::pool::Shape;
use super::pose_spec::PoseSpec;
use crate::contact::contact_pose;
use nalgebra::{Point2, Vector2, Vector3};
use revdist::nurbs::NurbsCurve;
use revdist::rng::SplitMix64;

/// Smallest turn between the one-sided tangents (radians) for a knot to count as a corner.
const MIN_TURN: f64 = 1e-3;
/// Step, relative to a piece's parameter domain, of the one-sided tangent differences.
const TANGENT_STEP: f64 = 1e-7;
/// Step, relative to the profile's size, of the outside test along a candidate normal.
const SIDE_STEP: f64 = 1e-6;

/// What kind of point of a profile a contact is aimed at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeatureKind {
    /// A G0 join of pieces or a kink inside a piece.
    Corner,
    /// A point of a piece's interior with a continuous tangent.
    Smooth,
    /// A piece's end on the axis: a tip or a flat cap.
    Axis,
}

impl FeatureKind {
    pub fn name(self) -> &'static str {
        match self {
            FeatureKind::Corner => "corner",
            FeatureKind::Smooth => "smooth",
            FeatureKind::Axis => "axis",
        }
    }
}

/// A point of a profile with an outward direction of its normal cone (meridian plane).
#[derive(Debug, Clone, Copy)]
pub struct Feature {
    pub kind: FeatureKind,
    pub point: Point2<f64>,
    pub normal: Vector2<f64>,
}

/// One-sided unit tangents of `c` just before and just after parameter `t`.
fn one_sided_tangents(c: &NurbsCurve, t: f64) -> (Vector2<f64>, Vector2<f64>) {
    let (t0, t1) = c.domain();
    let h = TANGENT_STEP * (t1 - t0);
    let p = c.eval(t);
    let before = (p - c.eval((t - h).max(t0))).normalize();
    let after = (c.eval((t + h).min(t1)) - p).normalize();
    (before, after)
}

/// The unit normal of `tangent` pointing out of the solid at `p` (the oracle's side test);
/// `None` when neither side is told apart.
fn outward(shape: &Shape, p: Point2<f64>, tangent: Vector2<f64>) -> Option<Vector2<f64>> {
    let n = Vector2::new(tangent.y, -tangent.x);
    let step = SIDE_STEP * shape.size.max(1e-3);
    let side = |v: Vector2<f64>| {
        let q = p + v * step;
        if q.x < 0.0 {
            return None;
        }
        Some(shape.index.signed([q.x, q.y]).value > 0.0)
    };
    match (side(n), side(-n)) {
        (Some(true), _) => Some(n),
        (_, Some(true)) => Some(-n),
        _ => None,
    }
}

/// Every corner of the profile: joins of consecutive pieces (and of a closed profile's last
/// and first) that turn by more than [`MIN_TURN`], and interior knots of a degree-1 piece or
/// of full multiplicity where the piece turns as much. The normal is the bisector of the two
/// one-sided outward normals.
pub fn corners(shape: &Shape) -> Vec<Feature> {
    let pieces = shape.profile.pieces();
    let mut out = Vec::new();
    let mut push = |p: Point2<f64>, before: Vector2<f64>, after: Vector2<f64>| {
        if before.angle(&after) <= MIN_TURN || p.x <= 0.0 {
            return;
        }
        if let (Some(n0), Some(n1)) = (outward(shape, p, before), outward(shape, p, after)) {
            let bis = n0 + n1;
            if bis.norm() > 1e-9 {
                out.push(Feature {
                    kind: FeatureKind::Corner,
                    point: p,
                    normal: bis.normalize(),
                });
            }
        }
    };
    for (k, c) in pieces.iter().enumerate() {
        let knots = c.knots();
        let deg = c.degree();
        let (t0, t1) = c.domain();
        let mut i = deg + 1;
        while i < knots.len() - deg - 1 {
            let t = knots[i];
            let mult = knots.iter().filter(|&&x| x == t).count();
            if t > t0 && t < t1 && (deg == 1 || mult >= deg) {
                let (before, after) = one_sided_tangents(c, t);
                push(c.eval(t), before, after);
            }
            i += mult.max(1);
        }
        let next = match (k + 1 < pieces.len(), shape.profile.kind()) {
            (true, _) => Some(&pieces[k + 1]),
            (false, revdist::profile::ProfileKind::Closed) => Some(&pieces[0]),
            _ => None,
        };
        if let Some(n) = next {
            let (before, _) = one_sided_tangents(c, t1);
            let (_, after) = one_sided_tangents(n, n.domain().0);
            push(c.eval(t1), before, after);
        }
    }
    out
}

/// The ends of the profile on the axis: the normal is vertical (the bisector of a piece's
/// outward normal and its mirror image's), up or down as the piece leaves the axis.
pub fn axis_ends(shape: &Shape) -> Vec<Feature> {
    let mut out = Vec::new();
    for c in shape.profile.pieces() {
        let (t0, t1) = c.domain();
        for (t, sign) in [(t0, 1.0), (t1, -1.0)] {
            let p = c.eval(t);
            if p.x != 0.0 {
                continue;
            }
            let (before, after) = one_sided_tangents(c, t);
            let tangent = if sign > 0.0 { after } else { before };
            if let Some(n) = outward(shape, p + tangent * 1e-3 * shape.size.max(1e-3), tangent) {
                if n.y != 0.0 {
                    out.push(Feature {
                        kind: FeatureKind::Axis,
                        point: p,
                        normal: Vector2::new(0.0, n.y.signum()),
                    });
                }
            }
        }
    }
    out
}

/// A smooth point of a random piece at a random parameter, with its outward normal.
fn smooth_point(rng: &mut SplitMix64, shape: &Shape) -> Option<Feature> {
    let pieces = shape.profile.pieces();
    let c = &pieces[rng.int(0, pieces.len() - 1)];
    let (t0, t1) = c.domain();
    let t = rng.range(t0 + 0.05 * (t1 - t0), t1 - 0.05 * (t1 - t0));
    let (before, after) = one_sided_tangents(c, t);
    let p = c.eval(t);
    if p.x <= 0.0 || before.angle(&after) > MIN_TURN {
        return None;
    }
    outward(shape, p, before + after).map(|normal| Feature {
        kind: FeatureKind::Smooth,
        point: p,
        normal,
    })
}

/// A feature of B to meet A's corner: another corner (half the cases), an axis end or a
/// smooth point, falling back to a smooth point.
fn partner(rng: &mut SplitMix64, b: &Shape) -> Option<Feature> {
    let u = rng.next_f64();
    let pick = |rng: &mut SplitMix64, v: Vec<Feature>| -> Option<Feature> {
        (!v.is_empty()).then(|| v[rng.int(0, v.len() - 1)])
    };
    let chosen = if u < 0.5 {
        pick(rng, corners(b))
    } else if u < 0.7 {
        pick(rng, axis_ends(b))
    } else {
        None
    };
    chosen.or_else(|| (0..8).find_map(|_| smooth_point(rng, b)))
}

/// The gap a corner contact aims at: touching (0), a tiny gap or overlap of either sign
/// (1e-13..1e-5), or a real overlap (1e-4..1e-1 of the larger size).
fn draw_gap(rng: &mut SplitMix64, size: f64) -> f64 {
    let u = rng.next_f64();
    if u < 0.25 {
        0.0
    } else if u < 0.55 {
        rng.log_range(1e-13, 1e-5)
    } else if u < 0.85 {
        -rng.log_range(1e-13, 1e-5)
    } else {
        -rng.log_range(1e-4, 1e-1) * size
    }
}

/// A corner contact between shapes `a` and `b`: A's corner at a random angle, B's feature
/// met along the negated normal, rotated about the contact normal by a random angle; with
/// a note naming the features and the gap. `None` when A has no corner or B no feature.
pub fn corner_contact(rng: &mut SplitMix64, a: &Shape, b: &Shape) -> Option<(PoseSpec, String)> {
    let ca = corners(a);
    if ca.is_empty() {
        return None;
    }
    let fa = ca[rng.int(0, ca.len() - 1)];
    let fb = partner(rng, b)?;
    let gap = draw_gap(rng, a.size.max(b.size));
    let theta = rng.range(0.0, std::f64::consts::TAU);
    let (s, c) = theta.sin_cos();
    let pa = Vector3::new(fa.point.x * c, fa.point.x * s, fa.point.y);
    let na = Vector3::new(fa.normal.x * c, fa.normal.x * s, fa.normal.y);
    // B's feature in its meridian plane at angle 0.
    let pb = Vector3::new(fb.point.x, 0.0, fb.point.y);
    let nb = Vector3::new(fb.normal.x, 0.0, fb.normal.y);
    let spin = rng.range(0.0, std::f64::consts::TAU);
    let pose = contact_pose((pa, na), (pb, nb), gap, spin);
    let (t, q) = (pose.translation.vector, pose.rotation.into_inner());
    let note = format!(
        "corner ({:.4}, {:.4}) of A against {} ({:.4}, {:.4}) of B, gap {gap:e}",
        fa.point.x,
        fa.point.y,
        fb.kind.name(),
        fb.point.x,
        fb.point.y
    );
    Some((spec(t, [q.w, q.i, q.j, q.k]), note))
}

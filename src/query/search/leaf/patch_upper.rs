//! Stage 1 of a leaf pair, the upper half: a realised upper bound of the distance between
//! two patches, and both halves together ([`patch_bounds`]).
//!
//! **Upper bound.** Two points that lie on the patches: the tori's closest points (or the
//! disks' major circles' closest points for cones) projected onto the patches in their
//! meridian planes, alternated once. Their distance is a true upper bound of the patch
//! distance whatever the projection does.

use super::patch_lower::{
    arc_tori, mid_and_hull_starts, mid_point, patch_lower, CoreMemo, PatchLower,
};
use crate::bvh::patch::Patch;
use nalgebra::{Isometry3, Point3};

/// Bounds of one patch pair's distance (A's frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchBounds {
    /// A rigorous lower bound of the patch distance.
    pub lower: f64,
    /// The distance between `point_a` and `point_b`, two points on the patches.
    pub upper: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
}

/// Alternations at most of [`polish`].
pub const POLISH_STEPS: usize = 16;

/// A realised pair `(pa, pb)` of two patches (A's frame, on the patches) moved by
/// alternating closest points (B's point closest to A's, then A's closest to that) while
/// each alternation shortens it by more than `min_gain`, at most [`POLISH_STEPS`] times:
/// the distance never grows, and every pair is on the patches, so it stays an upper bound.
/// Stage 1's realised pair takes one alternation from its start ([`realised`]); near
/// contact between a wide arc and a nearly straight one (the cup's waist against the
/// bottle) that left it 1e-4 to 1e-3 above the patch distance, the leaf pair holding the
/// query's minimum then had to be tightened and solved exactly for its upper bound.
pub fn polish(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    (pa, pb): (Point3<f64>, Point3<f64>),
    min_gain: f64,
) -> (Point3<f64>, Point3<f64>, f64) {
    let on_a = |x: &Point3<f64>| a.point_distance(x).1;
    let on_b = |x: &Point3<f64>| closest_on_placed(b, pos_ab, x);
    let mut best = (pa, pb, (pa - pb).norm());
    for _ in 0..POLISH_STEPS {
        let q = on_b(&best.0);
        let p = on_a(&q);
        let d = (p - q).norm();
        if d.is_nan() || d >= best.2 {
            break;
        }
        let gain = best.2 - d;
        best = (p, q, d);
        if gain <= min_gain {
            break;
        }
    }
    best
}

/// A realised upper bound of a patch pair alone, without a lower bound (a cold query's
/// first leaf pair, [`crate::query::search`]): the pieces' points projected from the arcs' tori's
/// near points (one circle/circle minimum, memoised for the pair's later stage 1), or, with
/// a straight piece, from the pieces' mid points and the hulls' nearest points after a few
/// support points ([`crate::query::bound::hull_bound::UNBOUNDED_ITERATIONS`]; a converged iteration cost twice
/// the rest of this bound for no better start). `lower` is `-inf`. Stage 1 without a level
/// (what the first leaf pair got before) cost 12-19 us of a 38-87 us query at eps 1e-4 for
/// a lower bound nothing used; this costs well under a microsecond per patch pair.
pub fn patch_upper(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    memo: &mut CoreMemo,
) -> PatchBounds {
    let starts = match arc_tori(a, b, pos_ab, memo) {
        Some(t) => PatchLower {
            lower: f64::NEG_INFINITY,
            near: Some((t.near_a, t.near_b)),
            hull_near: None,
        },
        None => PatchLower {
            lower: f64::NEG_INFINITY,
            ..mid_and_hull_starts(a, b, pos_ab, f64::INFINITY, false)
        },
    };
    realised(a, b, pos_ab, &starts)
}

/// Stage-1 bounds of a patch pair (module doc).
pub fn patch_bounds(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    memo: &mut CoreMemo,
) -> PatchBounds {
    realised(
        a,
        b,
        pos_ab,
        &patch_lower(a, b, pos_ab, f64::INFINITY, 0.0, memo),
    )
}

/// Stage-1 bounds from a lower bound already computed by [`patch_lower`]: the realised pair
/// is projected from its start points (or from the pieces' mid points when the lower bound
/// stopped early).
pub fn realised(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>, lower: &PatchLower) -> PatchBounds {
    let (start_a, start_b) = lower
        .near
        .unwrap_or_else(|| (mid_point(a), pos_ab * mid_point(b)));
    let (mut pa, mut pb) = realise(a, b, pos_ab, start_a, start_b);
    if let Some((ha, hb)) = lower.hull_near {
        let (qa, qb) = realise(a, b, pos_ab, ha, hb);
        if (qa - qb).norm() < (pa - pb).norm() {
            (pa, pb) = (qa, qb);
        }
    }
    PatchBounds {
        lower: lower.lower,
        upper: (pa - pb).norm(),
        point_a: pa,
        point_b: pb,
    }
}

/// The closest point to `x` (A's frame) of patch `b` placed by `pos_ab`, in A's frame: the
/// projection onto B of [`realised`] and [`polish`] (A's is [`Patch::point_distance`]).
fn closest_on_placed(b: &Patch, pos_ab: &Isometry3<f64>, x: &Point3<f64>) -> Point3<f64> {
    pos_ab * b.point_distance(&pos_ab.inverse_transform_point(x)).1
}

/// Two points on the patches near `xa` (A's frame, near A) and `xb` (A's frame, near B):
/// each projected onto its patch, then each patch's point projected against the other's,
/// keeping the closest of the realised pairs.
fn realise(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    xa: Point3<f64>,
    xb: Point3<f64>,
) -> (Point3<f64>, Point3<f64>) {
    let on_a = |x: &Point3<f64>| a.point_distance(x).1;
    let on_b = |x: &Point3<f64>| closest_on_placed(b, pos_ab, x);
    let pa = on_a(&xa);
    let pb = on_b(&xb);
    let mut best = (pa, pb, (pa - pb).norm());
    let qb = on_b(&pa);
    let d = (pa - qb).norm();
    if d < best.2 {
        best = (pa, qb, d);
    }
    let qa = on_a(&pb);
    let d = (qa - pb).norm();
    if d < best.2 {
        best = (qa, pb, d);
    }
    (best.0, best.1)
}

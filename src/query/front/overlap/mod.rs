//! Solid semantics of a query (solids, not surfaces: overlapping or nested solids are at distance 0): when the boundary surfaces
//! may meet, or are apart but one solid may contain the other, decide whether the solids
//! certainly overlap, certainly do not, or cannot be told apart at the trees' accuracy.
//!
//! **Certificates of overlap.** Let `e_a`, `e_b` be the trees' bounds (the true boundary
//! of each solid is within `e` of its approximating boundary, both ways) and `margin_A(x)`
//! the distance of `x` to A's approximating chain (revolved), with `x` inside A's
//! approximating region.
//! * A point `x` of B's *approximating surface* inside A with `margin_A(x) > e_a + e_b`: the
//!   ball of radius `e_b` about `x` holds a point `y` of B's true surface, and the whole
//!   ball is inside A's true region (its distance to A's true boundary exceeds
//!   `margin - e_a > e_b`). A boundary point of B interior to A: the solids overlap.
//! * A point `x` *inside B* with clearance `c_B(x) > e_b` from B's approximating chain and
//!   inside A with `margin_A(x) > e_a`: `x` lies in both true solids.
//!
//! **Nesting.** When the surfaces are certainly apart (positive certified lower bound), B's
//! boundary (a connected surface) lies entirely inside or entirely outside true A, so one
//! point of B's approximating surface whose classification in A has margin above
//! `e_a + e_b` decides it for all of B (same argument as above, with the outside case
//! symmetric).
//!
//! Every margin comparison adds the query's rounding slack (see [`mod@crate::query::front::distance`]).

use super::deep_point::{deep_point, DeepPoint, Direction};
use crate::bvh::containment::{point_in_solid_capped, signed_depth_capped};
use crate::bvh::offset_solid::{Core, OffsetSolid};
use crate::bvh::patch::{e_rho, lift};
use crate::bvh::QueryTree;
use crate::query::closed_form::offset_distance;
use nalgebra::{Isometry3, Point2, Point3};
use std::f64::consts::TAU;

/// Revolution angles at which interior and nesting sample points are lifted to 3-D (the
/// surface search, [`deep_point`], bounds every angle).
const SAMPLE_THETAS: usize = 12;

/// Cap of the margins a certificate compares with its threshold, in thresholds
/// ([`crate::bvh::containment::point_in_profile_capped`]): any cap above the threshold gives the same comparisons
/// (the classification is exact, the margin exact below the cap); twice the threshold keeps
/// the comparison clear of the cap itself.
const CAP_OVER_THRESHOLD: f64 = 2.0;

/// What the overlap analysis concluded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// The solids certainly overlap; a point (A's frame) inside both.
    Overlap(Point3<f64>),
    /// Neither solid can contain the other (only meaningful when the surfaces are apart).
    Apart,
    /// The trees' accuracy does not decide it.
    Undecided,
}

/// Meridian points of the approximating surface: each patch's ends (the poles of the solid
/// among them, where coaxial contacts are deepest) and midpoint.
fn surface_meridian_points(tree: &QueryTree) -> Vec<Point2<f64>> {
    tree.patches
        .iter()
        .flat_map(|p| {
            [
                p.arc.point_at(0.0),
                p.arc.point_at(0.5),
                p.arc.point_at(1.0),
            ]
        })
        .collect()
}

/// Depth evaluations the branch and bound over both surfaces ([`deep_point`]) may spend when
/// the cheap searches found no certificate and the traversal found the approximating
/// surfaces meeting. Near a touching contact without overlap the search refines the band
/// around the contact until its budget is spent (0.8 ms on average over the 30 of the
/// 2,000 tail-benchmark queries that spend it); crossings whose overlap clears the
/// certificate's threshold are found within it (three corner crossings the campaign found
/// needed 123, 365 and 783 evaluations: 1.04 and 50 times the verification band deep, the
/// last at eps 1e-6).
const CROSSING_BUDGET: usize = 1024;

/// The same budget when the approximating surfaces were not found meeting: each is then
/// entirely inside or entirely outside the other's approximating region, and a surface point
/// deeper than the threshold exists only if a whole surface is nested that deep, which the
/// best-first order reaches among its first regions.
const NESTED_BUDGET: usize = 256;

/// Parameters at which the patches of the leaf where the surfaces met are sampled.
const FOCUS_PARAMS: usize = 9;

/// Revolution angles for the focus leaf's samples.
const FOCUS_THETAS: usize = 48;

/// The meridian point `m` lifted at revolution angle `theta` (tree frame).
fn lift_at(m: Point2<f64>, theta: f64) -> Point3<f64> {
    lift(m, &e_rho(theta))
}

fn thetas() -> impl Iterator<Item = f64> {
    (0..SAMPLE_THETAS).map(|k| k as f64 * TAU / SAMPLE_THETAS as f64)
}

/// A point of `inner`'s approximating surface or interior (frame of `inner`, mapped to
/// `outer`'s frame by `pos`) that certifies overlap with `outer` (module doc), from the cheap
/// searches: the focus leaf and the interior points.
#[allow(clippy::too_many_arguments)]
fn overlap_point(
    outer: &QueryTree,
    inner: &QueryTree,
    pos: &Isometry3<f64>,
    focus: Option<u32>,
    witness: Option<Point3<f64>>,
    e_outer: f64,
    e_inner: f64,
    slack: f64,
) -> Option<Point3<f64>> {
    let threshold = e_outer + e_inner + slack;
    let cap = CAP_OVER_THRESHOLD * threshold;
    if let Some(leaf) = focus {
        if let Some(x) = search_leaf(outer, inner, pos, leaf, witness, threshold) {
            return Some(x);
        }
    }
    // Interior points before the surface samples: a few hundred capped classifications
    // that certify coincident and nested solids at once, where the surface samples (every
    // lifted disk near the other surface, nothing skipped) visit the whole tree.
    for &(m, clearance) in &inner.deep_interior().points {
        if clearance <= e_inner + slack {
            continue;
        }
        for th in thetas() {
            let x = pos * lift_at(m, th);
            let c = point_in_solid_capped(outer, &x, cap);
            if c.inside && c.margin > e_outer + slack {
                return Some(x);
            }
        }
    }
    None
}

/// Pattern-search iterations of [`search_leaf`]'s ascent.
const ASCENT_ITERS: usize = 400;

/// Searches the patches of `inner`'s leaf `leaf` (where the traversal found the surfaces
/// meeting: a penetration, if any, is nearby) for a point deeper in `outer` than
/// `threshold`: first a dense grid of samples, then a local ascent of the signed depth from
/// the surface point nearest `witness` (inner's frame) and from the deepest grid sample.
/// Where the surfaces cross, the cap of one solid inside the other may be narrower than any
/// fixed sampling, and its deepest point is a local maximum of the depth. Returns the point
/// in outer's frame: the same certificate as any sample.
fn search_leaf(
    outer: &QueryTree,
    inner: &QueryTree,
    pos: &Isometry3<f64>,
    leaf: u32,
    witness: Option<Point3<f64>>,
    threshold: f64,
) -> Option<Point3<f64>> {
    let n = inner.nodes.get(leaf as usize)?;
    let patches = &inner.patches[n.patch_start as usize..n.patch_end as usize];
    let point = |k: usize, s: f64, th: f64| pos * lift_at(patches[k].arc.point_at(s), th);
    // Depths are capped at twice the threshold on both sides: above, a sample certifies
    // anyway; below, a sample farther outside than that neither certifies nor guides the
    // ascent, which climbs from near the surfaces' contact (the witness, the best sample).
    // With the exact depth of far samples, each classification opened most of the tree
    // (12,000 instructions a call with a cap of the leaf's size, 3,300 with this one).
    let (c, r) = (n.bound.center, n.bound.radius);
    let cap = CAP_OVER_THRESHOLD * threshold;
    let depth = |k: usize, s: f64, th: f64| signed_depth_capped(outer, &point(k, s, th), cap);
    // The grid, evaluated once: a deep sample certifies at once, the deepest seeds an ascent.
    // Per angle, the leaf's disk lifted there is a ball of radius `r` holding that angle's
    // samples, whose depths are at most the centre's plus `r` (1-Lipschitz; capped depths
    // keep this an upper bound, see `deep_surface_sample`). Angles are visited by that
    // bound, largest first; once it is neither above the threshold nor above the deepest
    // sample so far, no later angle can certify or give a deeper seed.
    let mut starts: Vec<(usize, f64, f64)> = Vec::new();
    let mut best_sample = (f64::NEG_INFINITY, 0, 0.0, 0.0);
    let mut angles: Vec<(f64, f64)> = (0..FOCUS_THETAS)
        .map(|j| {
            let th = j as f64 * TAU / FOCUS_THETAS as f64;
            let centre = pos * lift_at(c, th);
            (signed_depth_capped(outer, &centre, cap + r) + r, th)
        })
        .collect();
    angles.sort_by(|x, y| y.0.total_cmp(&x.0));
    for (bound, th) in angles {
        if bound <= threshold && bound <= best_sample.0 {
            break;
        }
        for k in 0..patches.len() {
            for i in 0..FOCUS_PARAMS {
                let s = i as f64 / (FOCUS_PARAMS - 1) as f64;
                let d = depth(k, s, th);
                if d > threshold {
                    return Some(point(k, s, th));
                }
                if d > best_sample.0 {
                    best_sample = (d, k, s, th);
                }
            }
        }
    }
    if let Some(w) = witness {
        let th = w.y.atan2(w.x);
        let m = Point2::new(w.x.hypot(w.y), w.z);
        let mut best = (f64::INFINITY, 0, 0.0);
        for (k, p) in patches.iter().enumerate() {
            for i in 0..=32 {
                let s = i as f64 / 32.0;
                let d = (p.arc.point_at(s) - m).norm();
                if d < best.0 {
                    best = (d, k, s);
                }
            }
        }
        if best.0.is_finite() {
            starts.push((best.1, best.2, th));
        }
    }
    if best_sample.0.is_finite() {
        starts.push((best_sample.1, best_sample.2, best_sample.3));
    }
    for (k, mut s, mut th) in starts {
        let mut d = depth(k, s, th);
        let (mut hs, mut ht) = (0.125, TAU / FOCUS_THETAS as f64);
        for _ in 0..ASCENT_ITERS {
            if d > threshold {
                return Some(point(k, s, th));
            }
            let mut moved = false;
            for (ds, dt) in [
                (1.0, 0.0),
                (-1.0, 0.0),
                (0.0, 1.0),
                (0.0, -1.0),
                (1.0, 1.0),
                (1.0, -1.0),
                (-1.0, 1.0),
                (-1.0, -1.0),
            ] {
                let (s2, t2) = ((s + ds * hs).clamp(0.0, 1.0), th + dt * ht);
                let d2 = depth(k, s2, t2);
                if d2 > d {
                    (s, th, d) = (s2, t2, d2);
                    moved = true;
                    break;
                }
            }
            if !moved {
                hs *= 0.5;
                ht *= 0.5;
                // Stuck at a scale whose moves reach less than the depth still missing: no
                // point within one step clears the threshold (the depth is 1-Lipschitz;
                // a parameter step moves at most `hs` times the arc's length, an angle
                // step at most the largest radius times `ht`). Halving on from here used to
                // run down to `hs = 1e-9` near every contact without an overlap.
                let reach = 2.0 * hs * patches[k].arc.length() + 2.0 * ht * (c.x + r);
                if hs < 1e-9 || d + reach <= threshold {
                    break;
                }
            }
        }
        if d > threshold {
            return Some(point(k, s, th));
        }
    }
    None
}

/// Certified overlap of A and B (`pos_ab` places B in A's frame); the point is in A's frame.
/// `focus` is the leaf pair where the traversal found the surfaces meeting (sampled densely
/// and searched for the deepest point), `witness` the traversal's closest pair there (A's
/// frame).
pub fn certify_overlap(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    focus: Option<(u32, u32)>,
    witness: Option<(Point3<f64>, Point3<f64>)>,
    surfaces_meet: bool,
    slack: f64,
) -> Option<Point3<f64>> {
    let (ea, eb) = (ta.eps, tb.eps);
    let (fa, fb) = (focus.map(|f| f.0), focus.map(|f| f.1));
    let pos_ba = pos_ab.inverse();
    let (wa, wb) = (witness.map(|w| w.0), witness.map(|w| pos_ba * w.1));
    let threshold = ea + eb + slack;
    let dirs = [
        Direction {
            outer: ta,
            inner: tb,
            pos: pos_ab,
            threshold,
        },
        Direction {
            outer: tb,
            inner: ta,
            pos: &pos_ba,
            threshold,
        },
    ];
    overlap_point(ta, tb, pos_ab, fb, wb, ea, eb, slack)
        .or_else(|| overlap_point(tb, ta, &pos_ba, fa, wa, eb, ea, slack).map(|x| pos_ab * x))
        .or_else(|| {
            let budget = if surfaces_meet {
                CROSSING_BUDGET
            } else {
                NESTED_BUDGET
            };
            match deep_point(&dirs, budget) {
                DeepPoint::Found { dir: 0, point } => Some(point),
                DeepPoint::Found { point, .. } => Some(pos_ab * point),
                DeepPoint::Absent | DeepPoint::Undecided => None,
            }
        })
}

/// Overlap certified before the traversal by the solids' inscribed balls or solid tori
/// ([`crate::bvh::inscribed`]), answered in closed form ([`offset_distance`]): a point (A's
/// frame) inside both true solids. Nested, coincident and deeply overlapping solids need
/// no traversal; for solids whose inscribed solids' bounding spheres are apart it costs
/// one distance between two points.
pub fn inscribed_overlap(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    slack: f64,
) -> Option<Point3<f64>> {
    let ia = ta.deep_interior().inscribed?;
    let ib = tb.deep_interior().inscribed?;
    // Centre and radius of a sphere around an inscribed solid (its core on the axis).
    let sphere = |o: &OffsetSolid| match o.core {
        Core::Point { z } => (Point3::new(0.0, 0.0, z), o.radius),
        Core::Segment { z0, z1 } => (
            Point3::new(0.0, 0.0, 0.5 * (z0 + z1)),
            0.5 * (z1 - z0) + o.radius,
        ),
        Core::Circle { rho, z } => (Point3::new(0.0, 0.0, z), rho + o.radius),
    };
    let ((ca, ra), (cb, rb)) = (sphere(&ia), sphere(&ib));
    if (pos_ab * cb - ca).norm() >= ra + rb {
        return None;
    }
    let answer = offset_distance(&ia, &ib, pos_ab, slack)?;
    answer.overlap.then_some(answer.point_a)
}

/// Whether `inner`'s boundary is certainly outside `outer` (surfaces known to be apart):
/// `Some(true)` outside, `Some(false)` inside, `None` undecided at these margins.
fn boundary_side(
    outer: &QueryTree,
    inner: &QueryTree,
    pos: &Isometry3<f64>,
    witness: &Point3<f64>,
    e_sum: f64,
) -> Option<bool> {
    let decide = |x: &Point3<f64>| {
        let c = point_in_solid_capped(outer, x, CAP_OVER_THRESHOLD * e_sum);
        (c.margin > e_sum).then_some(!c.inside)
    };
    if let Some(side) = decide(witness) {
        return Some(side);
    }
    surface_meridian_points(inner)
        .into_iter()
        .flat_map(|m| thetas().map(move |th| lift_at(m, th)))
        .find_map(|x| decide(&(pos * x)))
}

/// Solids whose surfaces are certainly apart: nested (overlap), apart, or undecided.
/// `point_a`, `point_b` are the traversal's witnesses in A's frame.
pub fn nesting(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    point_a: &Point3<f64>,
    point_b: &Point3<f64>,
    slack: f64,
) -> Verdict {
    let e_sum = ta.eps + tb.eps + slack;
    let pos_ba = pos_ab.inverse();
    let b_outside_a = boundary_side(ta, tb, pos_ab, point_b, e_sum);
    if b_outside_a == Some(false) {
        return Verdict::Overlap(*point_b);
    }
    let a_outside_b = boundary_side(tb, ta, &pos_ba, &(pos_ba * point_a), e_sum);
    if a_outside_b == Some(false) {
        return Verdict::Overlap(*point_a);
    }
    match (b_outside_a, a_outside_b) {
        (Some(true), Some(true)) => Verdict::Apart,
        _ => Verdict::Undecided,
    }
}

#[cfg(test)]
mod tests;

//! The distance query between two posed solids: Algorithm 2 over the boundary surfaces
//! ([`super::traverse`]), then solid semantics (overlap and nesting give 0), optional
//! refinement on the exact surfaces, and frame coherence through a [`QueryCache`].
//!
//! Certification: `surface lower <= dist(dA, dB) <= surface upper`. Solids that do not
//! overlap have distance `dist(dA, dB)`; overlapping or nested solids have distance 0. The
//! result reports `lower = 0` whenever overlap cannot be excluded, and `overlap = true` with
//! `lower = upper = 0` only when it is certified (a point of one boundary lies inside the
//! other solid with a classification margin larger than the trees' eps).

use super::bounds::BoundKind;
use super::containment::point_in_solid;
use super::refine::refine_on_profiles;
use super::traverse::{traverse, Budget, TraversalOptions, TraversalStats};
use super::tree::QueryTree;
use crate::solid::Solid;
use nalgebra::{Isometry3, Point3};

/// What the caller asks of a query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QueryOptions {
    /// Target gap `upper - lower` (the trees' eps limit what is reachable: a leaf pair
    /// cannot be resolved below `2 (eps_a + eps_b)`).
    pub tolerance: f64,
    /// Anytime budget.
    pub budget: Budget,
    /// Node-pair bound used for inner nodes.
    pub bound: BoundKind,
    /// Refine the witness points on the exact NURBS surfaces (needs the profiles).
    pub refine: bool,
}

impl Default for QueryOptions {
    fn default() -> Self {
        QueryOptions {
            tolerance: 0.0,
            budget: Budget::default(),
            bound: BoundKind::default(),
            refine: false,
        }
    }
}

/// Result of a distance query. Points are in the world frame (A's frame when A sits at
/// the identity, as in the CLI).
#[derive(Debug, Clone, PartialEq)]
pub struct Distance {
    /// Best estimate, inside `[lower, upper]`.
    pub value: f64,
    /// Certified lower bound of the distance between the solids.
    pub lower: f64,
    /// Certified upper bound.
    pub upper: f64,
    /// Witness point on A (approximating surface, or exact surface after refinement).
    pub point_a: Point3<f64>,
    /// Witness point on B.
    pub point_b: Point3<f64>,
    /// The solids certainly overlap or nest (then `value = lower = upper = 0`).
    pub overlap: bool,
    pub stats: TraversalStats,
}

/// Frame coherence for sequences of queries on the same pair: the best leaf pair of the
/// last query is measured first, which gives a tight upper bound before the traversal.
#[derive(Debug, Clone, Default)]
pub struct QueryCache {
    last_pair: Option<(u32, u32)>,
}

/// Distance between two posed solids.
pub fn distance(a: &Solid, b: &Solid, opts: &QueryOptions) -> Distance {
    distance_cached(a, b, opts, &mut QueryCache::default())
}

/// [`distance`] with a warm start from `cache`, which is updated.
pub fn distance_cached(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    cache: &mut QueryCache,
) -> Distance {
    let pos_ab = a.relative_pose(b);
    let topts = TraversalOptions {
        tolerance: opts.tolerance,
        budget: opts.budget,
        bound: opts.bound,
    };
    let s = traverse(&a.tree, &b.tree, &pos_ab, &topts, cache.last_pair);
    cache.last_pair = s.best_pair.or(cache.last_pair);
    let eps_sum = a.tree.eps + b.tree.eps;
    let world = |p: &Point3<f64>| a.pose * p;
    let certain_overlap = |margin: f64| margin > eps_sum;

    // Interpenetrating approximations: overlap when deep enough, else undecided.
    if s.surfaces_meet {
        if let Some((p, q, m)) = s.penetration {
            if certain_overlap(m) {
                return overlap_result(world(&p), world(&q), s.stats);
            }
        }
        if let Some((la, lb)) = s.best_pair {
            if let Some(x) = deep_point(&a.tree, &b.tree, la, lb, &pos_ab, eps_sum) {
                return overlap_result(world(&x), world(&x), s.stats);
            }
        }
        let upper = s.upper;
        return Distance {
            value: 0.0,
            lower: 0.0,
            upper,
            point_a: world(&s.point_a),
            point_b: world(&s.point_b),
            overlap: false,
            stats: s.stats,
        };
    }
    // Surfaces apart: nested when a point of one boundary is inside the other solid.
    let pos_ba = pos_ab.inverse();
    let q_in_a = point_in_solid(&a.tree, &s.point_b);
    let p_in_b = point_in_solid(&b.tree, &(pos_ba * s.point_a));
    if q_in_a.inside || p_in_b.inside {
        let margin = if q_in_a.inside {
            q_in_a.margin
        } else {
            p_in_b.margin
        };
        if certain_overlap(margin) {
            return overlap_result(world(&s.point_a), world(&s.point_b), s.stats);
        }
        return Distance {
            value: 0.0,
            lower: 0.0,
            upper: s.upper,
            point_a: world(&s.point_a),
            point_b: world(&s.point_b),
            overlap: false,
            stats: s.stats,
        };
    }
    // Separated (up to classification margins).
    let undecided = !certain_overlap(q_in_a.margin) || !certain_overlap(p_in_b.margin);
    let mut lower = if undecided { 0.0 } else { s.lower };
    let mut upper = s.upper;
    let (mut pa, mut pb) = (s.point_a, s.point_b);
    let mut value = s.approx;
    if opts.refine {
        if let Some(r) = refine_on_profiles(a, b, &pos_ab, &pa, &pb) {
            // Two points on the exact boundaries: their distance is an upper bound.
            if r.distance <= upper {
                upper = r.distance;
                value = r.distance;
                pa = r.point_a;
                pb = r.point_b;
            }
        }
    }
    lower = lower.min(upper);
    Distance {
        value: value.clamp(lower, upper),
        lower,
        upper,
        point_a: world(&pa),
        point_b: world(&pb),
        overlap: false,
        stats: s.stats,
    }
}

fn overlap_result(pa: Point3<f64>, pb: Point3<f64>, stats: TraversalStats) -> Distance {
    Distance {
        value: 0.0,
        lower: 0.0,
        upper: 0.0,
        point_a: pa,
        point_b: pb,
        overlap: true,
        stats,
    }
}

/// Revolution angles sampled by [`deep_point`].
const DEEP_THETAS: usize = 16;
/// Arc parameters sampled by [`deep_point`].
const DEEP_PARAMS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];

/// A point of one leaf's patches (A's frame) inside the other solid with a classification
/// margin above `eps_sum`: a certificate that the solids overlap. Used when the
/// approximating surfaces meet at leaves `la`, `lb`.
fn deep_point(
    ta: &QueryTree,
    tb: &QueryTree,
    la: u32,
    lb: u32,
    pos_ab: &Isometry3<f64>,
    eps_sum: f64,
) -> Option<Point3<f64>> {
    let pos_ba = pos_ab.inverse();
    let samples = |t: &QueryTree, leaf: u32| {
        let n = &t.nodes[leaf as usize];
        let mut pts = Vec::new();
        for patch in &t.patches[n.patch_start as usize..n.patch_end as usize] {
            for s in DEEP_PARAMS {
                let m = patch.arc.point_at(s);
                for k in 0..DEEP_THETAS {
                    let th = k as f64 * std::f64::consts::TAU / DEEP_THETAS as f64;
                    pts.push(Point3::new(m.x * th.cos(), m.x * th.sin(), m.y));
                }
            }
        }
        pts
    };
    for x in samples(tb, lb) {
        let xa = pos_ab * x;
        let c = point_in_solid(ta, &xa);
        if c.inside && c.margin > eps_sum {
            return Some(xa);
        }
    }
    for x in samples(ta, la) {
        let c = point_in_solid(tb, &(pos_ba * x));
        if c.inside && c.margin > eps_sum {
            return Some(x);
        }
    }
    None
}

//! Algorithm 2 of the paper (section 4.2): best-first traversal of node pairs with a
//! priority queue, upper bound from leaf patch distances plus their eps, lower bound from
//! the queue's top; with the anytime budget of Johnson and Cohen (1997, section 3.1.3).
//!
//! Invariant (DESIGN.md): every queue key is a lower bound of the distance between the
//! original surface pieces under its node pair; pairs dropped because their key reached
//! `upper - tolerance` are remembered in `pruned_min`. At any moment
//! `min(queue top, pruned_min, upper)` is a lower bound of the surface distance, and
//! `upper` is an upper bound (a measured patch distance plus both leaves' eps). A leaf pair
//! is evaluated once and re-inserted as "resolved" with key `d - eps_a - eps_b`; popping a
//! resolved pair means nothing can be refined further.

use super::bounds::{node_pair_bound, BoundKind};
use super::certify::{patch_lower_bound, CERTIFY_MAX_PAIRS};
use super::containment::point_in_solid;
use super::patch::Patch;
use super::patch_distance::{patch_distance_memo, BoundaryMemo, MemoSlot, PatchOptions};
use super::tree::Disk;
use super::tree::QueryTree;
use nalgebra::{Isometry3, Point2, Point3, Vector3};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::{Duration, Instant};

/// Budget of an anytime query: stop after this many node pairs or this much time and
/// return the certified bounds reached so far.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Budget {
    pub max_node_pairs: Option<usize>,
    pub max_time: Option<Duration>,
}

/// Counters of one traversal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct TraversalStats {
    /// Node pairs popped from the queue.
    pub node_pairs: usize,
    /// Leaf pairs whose patch distances were computed.
    pub leaf_tests: usize,
    /// Patch pairs measured (up to 4 per leaf pair for biarcs).
    pub patch_tests: usize,
    /// Node-pair bounds computed.
    pub bound_tests: usize,
    /// Largest queue length.
    pub max_queue: usize,
    /// Patch pairs whose kernel needed a sampled scan, bounded below by subdivision
    /// ([`super::certify`]).
    pub subdivided_pairs: usize,
    /// The budget stopped the traversal before the tolerance was reached.
    pub budget_exhausted: bool,
}

/// Result of a traversal over the two boundary surfaces.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceBounds {
    /// Lower bound of the distance between the original boundary surfaces.
    pub lower: f64,
    /// Upper bound of the same.
    pub upper: f64,
    /// Distance between the approximating surfaces at the best leaf pair.
    pub approx: f64,
    /// Closest points on the approximating surfaces (A's frame).
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Best leaf pair (for warm starts).
    pub best_pair: Option<(u32, u32)>,
    /// The approximating surfaces meet or interpenetrate.
    pub surfaces_meet: bool,
    /// Deepest verified interpenetration: a point of A inside B and a point of B inside A,
    /// with the smaller of their classification margins.
    pub penetration: Option<(Point3<f64>, Point3<f64>, f64)>,
    pub stats: TraversalStats,
}

#[derive(Debug, Clone, Copy)]
struct Entry {
    key: f64,
    a: u32,
    b: u32,
    resolved: bool,
}

impl PartialEq for Entry {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Entry {
    /// Reversed: the smallest key is the greatest (BinaryHeap is a max-heap); resolved
    /// entries first among equal keys.
    fn cmp(&self, o: &Self) -> Ordering {
        o.key
            .total_cmp(&self.key)
            .then(self.resolved.cmp(&o.resolved))
    }
}

/// Exact distance between the approximating patches of two leaves, with interpenetration
/// checks of the interior common normals (see [`super::patch_distance`]); or, when every
/// patch pair's solid-torus bound already reaches the caller's pruning level, only that
/// lower bound (`exact == false`).
pub(crate) struct LeafResult {
    /// The patch distance (`exact`), else a lower bound of it. When a patch pair needed
    /// the sampled scan, `d` is a distance between two real surface points (an upper bound).
    pub d: f64,
    /// A rigorous lower bound of the leaves' patch distance: `d` itself where every patch
    /// pair was computed exactly, a subdivision bound ([`super::certify`]) where a pair was
    /// sampled, the solid-torus bound for pairs skipped.
    pub lower: f64,
    pub exact: bool,
    pub pa: Point3<f64>,
    pub pb: Point3<f64>,
    pub penetration: Option<(Point3<f64>, Point3<f64>, f64)>,
    pub patch_tests: usize,
    pub subdivided_pairs: usize,
}

/// Outward unit normal (3-D, tree frame) of a patch at its surface point `x`.
fn outward(tree: &QueryTree, patch: &Patch, orient: f64, x: &Point3<f64>) -> Vector3<f64> {
    let rho = x.x.hypot(x.y);
    let e = if rho > 0.0 {
        Vector3::new(x.x / rho, x.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    let n = tree.outward_normal(&patch.arc, Point2::new(rho, x.z), orient);
    e * n.x + Vector3::z() * n.y
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn leaf_pair(
    ta: &QueryTree,
    tb: &QueryTree,
    orient_a: f64,
    orient_b: f64,
    na: u32,
    nb: u32,
    pos_ab: &Isometry3<f64>,
    pos_ba: &Isometry3<f64>,
    prune_at: f64,
    memo: &mut BoundaryMemo,
) -> LeafResult {
    let (la, lb) = (&ta.nodes[na as usize], &tb.nodes[nb as usize]);
    let mut r = LeafResult {
        d: f64::INFINITY,
        lower: f64::INFINITY,
        exact: true,
        pa: Point3::origin(),
        pb: Point3::origin(),
        penetration: None,
        patch_tests: 0,
        subdivided_pairs: 0,
    };
    // Solid-torus lower bounds of the patch pairs (bounds.rs; disks around the pieces),
    // cheapest first. A pair whose bound is positive and not below the best distance so
    // far can neither lower the minimum nor interpenetrate, so it is skipped.
    let mut order: Vec<(f64, u32, u32)> = (la.patch_start..la.patch_end)
        .flat_map(|ia| (lb.patch_start..lb.patch_end).map(move |ib| (ia, ib)))
        .map(|(ia, ib)| {
            let (pa, pb) = (&ta.patches[ia as usize], &tb.patches[ib as usize]);
            let bound = node_pair_bound(
                &Disk::around(&pa.arc),
                &Disk::around(&pb.arc),
                pos_ab,
                BoundKind::Torus,
                prune_at,
            );
            (bound, ia, ib)
        })
        .collect();
    order.sort_by(|x, y| x.0.total_cmp(&y.0));
    if order.first().is_some_and(|&(b, _, _)| b >= prune_at) {
        r.d = order[0].0;
        r.lower = r.d;
        r.exact = false;
        return r;
    }
    // Subdivision precision for sampled patch pairs: the leaves' eps (a lower bound that
    // close costs no accuracy the leaves have), but not below rounding of the pose.
    let precision = (la.eps + lb.eps).max(1e-9 * (1.0 + pos_ab.translation.vector.norm()));
    for (bound, ia, ib) in order {
        if bound > 0.0 && bound >= r.d {
            r.lower = r.lower.min(bound);
            continue;
        }
        let (pa, pb) = (&ta.patches[ia as usize], &tb.patches[ib as usize]);
        r.patch_tests += 1;
        let slot = MemoSlot {
            memo: &mut *memo,
            index_a: ia,
            index_b: ib,
        };
        // A positive solid-torus bound proves the patches disjoint: no crossing scan.
        let popts = PatchOptions {
            may_intersect: bound <= 0.0,
            ..PatchOptions::default()
        };
        let pd = patch_distance_memo(pa, pb, pos_ab, popts, Some(slot));
        let pair_lower = if pd.sampled {
            r.subdivided_pairs += 1;
            patch_lower_bound(
                &pa.arc,
                &pb.arc,
                pos_ab,
                pd.distance,
                precision,
                CERTIFY_MAX_PAIRS,
            )
        } else {
            pd.distance
        };
        r.lower = r.lower.min(pair_lower);
        if pd.distance < r.d {
            r.d = pd.distance;
            r.pa = pd.point_a;
            r.pb = pd.point_b;
        }
        for (p, q) in &pd.interior_pairs {
            let w = q - p;
            let n_a = outward(ta, pa, orient_a, p);
            let q_b = pos_ba * q;
            let n_b = pos_ab.rotation * outward(tb, pb, orient_b, &q_b);
            if n_a.dot(&w) >= 0.0 || n_b.dot(&w) <= 0.0 {
                continue;
            }
            let in_a = point_in_solid(ta, q);
            let in_b = point_in_solid(tb, &(pos_ba * p));
            if in_a.inside || in_b.inside {
                // An interpenetrating common normal with an end inside the other solid: the
                // patches may cross in a loop that no sampled meridian met, so the solids
                // may overlap here and this leaf pair cannot bound the distance above 0.
                r.lower = r.lower.min(0.0);
            }
            if in_a.inside && in_b.inside {
                let m = in_a.margin.min(in_b.margin);
                if r.penetration.is_none_or(|(_, _, m0)| m > m0) {
                    r.penetration = Some((*p, *q, m));
                }
            }
        }
    }
    r
}

/// The two child pairs of the node pair `(a, b)` (not both leaves): the node with the larger
/// disk is split, a leaf never.
fn child_pairs(ta: &QueryTree, tb: &QueryTree, a: u32, b: u32) -> [(u32, u32); 2] {
    let (na, nb) = (&ta.nodes[a as usize], &tb.nodes[b as usize]);
    let split_a = !na.is_leaf() && (nb.is_leaf() || na.bound.radius >= nb.bound.radius);
    if split_a {
        [(na.children[0], b), (na.children[1], b)]
    } else {
        [(a, nb.children[0]), (a, nb.children[1])]
    }
}

/// Options of the traversal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraversalOptions {
    /// Stop when `upper - lower <= tolerance`.
    pub tolerance: f64,
    pub budget: Budget,
    pub bound: BoundKind,
}

/// Algorithm 2 over the boundary surfaces of two trees; `pos_ab` places B in A's frame.
/// `warm` is a leaf pair evaluated first (frame coherence).
pub fn traverse(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    opts: &TraversalOptions,
    warm: Option<(u32, u32)>,
) -> SurfaceBounds {
    let start = Instant::now();
    let pos_ba = pos_ab.inverse();
    let (orient_a, orient_b) = (ta.orientation(), tb.orientation());
    let mut stats = TraversalStats::default();
    let mut out = SurfaceBounds {
        lower: 0.0,
        upper: f64::INFINITY,
        approx: f64::INFINITY,
        point_a: Point3::origin(),
        point_b: Point3::origin(),
        best_pair: None,
        surfaces_meet: false,
        penetration: None,
        stats,
    };
    if ta.nodes.is_empty() || tb.nodes.is_empty() {
        out.lower = f64::INFINITY;
        return out;
    }
    let tol = opts.tolerance.max(0.0);
    let mut heap = BinaryHeap::new();
    let mut pruned_min = f64::INFINITY;
    let mut memo = BoundaryMemo::default();
    let mut evaluate =
        |a: u32, b: u32, key: f64, out: &mut SurfaceBounds, stats: &mut TraversalStats| {
            stats.leaf_tests += 1;
            let e = ta.nodes[a as usize].eps + tb.nodes[b as usize].eps;
            // A leaf pair whose patches are all at least `upper - tol + e` apart cannot
            // improve the answer: its bound is enough.
            let prune_at = out.upper - tol + e;
            let r = leaf_pair(
                ta, tb, orient_a, orient_b, a, b, pos_ab, &pos_ba, prune_at, &mut memo,
            );
            stats.patch_tests += r.patch_tests;
            stats.subdivided_pairs += r.subdivided_pairs;
            if !r.exact {
                return key.max(r.lower - e);
            }
            if r.d + e < out.upper {
                out.upper = r.d + e;
            }
            if r.d < out.approx {
                out.approx = r.d;
                out.point_a = r.pa;
                out.point_b = r.pb;
                out.best_pair = Some((a, b));
            }
            let meets = r.d == 0.0 || r.penetration.is_some();
            if let Some(p) = r.penetration {
                if out.penetration.is_none_or(|(_, _, m)| p.2 > m) {
                    out.penetration = Some(p);
                }
            }
            if meets {
                out.surfaces_meet = true;
                f64::NEG_INFINITY
            } else {
                key.max(r.lower - e)
            }
        };
    // Warm start: evaluate the last best leaf pair first for a tight upper bound; its
    // resolved key is kept so the traversal does not measure it twice.
    let mut warm_key: Option<(u32, u32, f64)> = None;
    if let Some((a, b)) = warm {
        if (a as usize) < ta.nodes.len()
            && (b as usize) < tb.nodes.len()
            && ta.nodes[a as usize].is_leaf()
            && tb.nodes[b as usize].is_leaf()
        {
            let key = evaluate(a, b, f64::NEG_INFINITY, &mut out, &mut stats);
            if out.surfaces_meet {
                out.lower = 0.0;
                out.stats = stats;
                return out;
            }
            warm_key = Some((a, b, key));
        }
    }
    let root_key = {
        stats.bound_tests += 1;
        node_pair_bound(
            &ta.nodes[ta.root as usize].bound,
            &tb.nodes[tb.root as usize].bound,
            pos_ab,
            opts.bound,
            f64::INFINITY,
        )
    };
    heap.push(Entry {
        key: root_key,
        a: ta.root,
        b: tb.root,
        resolved: false,
    });
    let lower;
    loop {
        let Some(e) = heap.pop() else {
            lower = out.upper;
            break;
        };
        if e.resolved || e.key >= out.upper - tol {
            lower = e.key;
            break;
        }
        let over_pairs = opts
            .budget
            .max_node_pairs
            .is_some_and(|m| stats.node_pairs >= m);
        let over_time = opts.budget.max_time.is_some_and(|t| start.elapsed() >= t);
        if over_pairs || over_time {
            stats.budget_exhausted = true;
            lower = e.key;
            break;
        }
        stats.node_pairs += 1;
        let (na, nb) = (&ta.nodes[e.a as usize], &tb.nodes[e.b as usize]);
        if na.is_leaf() && nb.is_leaf() {
            let key = match warm_key {
                Some((a, b, k)) if (a, b) == (e.a, e.b) => k.max(e.key),
                _ => evaluate(e.a, e.b, e.key, &mut out, &mut stats),
            };
            if out.surfaces_meet {
                // Lower bound can only be <= 0 now.
                lower = f64::NEG_INFINITY;
                break;
            }
            if key < out.upper - tol {
                heap.push(Entry {
                    key,
                    a: e.a,
                    b: e.b,
                    resolved: true,
                });
            } else {
                pruned_min = pruned_min.min(key);
            }
            continue;
        }
        for (a, b) in child_pairs(ta, tb, e.a, e.b) {
            stats.bound_tests += 1;
            let prune_at = out.upper - tol;
            let key = e.key.max(node_pair_bound(
                &ta.nodes[a as usize].bound,
                &tb.nodes[b as usize].bound,
                pos_ab,
                opts.bound,
                prune_at,
            ));
            if key < prune_at {
                heap.push(Entry {
                    key,
                    a,
                    b,
                    resolved: false,
                });
            } else {
                pruned_min = pruned_min.min(key);
            }
        }
        stats.max_queue = stats.max_queue.max(heap.len());
    }
    if out.upper.is_infinite() && !out.surfaces_meet {
        // The budget ran out before any leaf pair: measure one, reached by a greedy descent
        // along the smaller node-pair bound, so that an anytime answer always has a finite
        // upper bound and witness points (the lower bound is unchanged).
        let (mut a, mut b) = (ta.root, tb.root);
        loop {
            let (na, nb) = (&ta.nodes[a as usize], &tb.nodes[b as usize]);
            if na.is_leaf() && nb.is_leaf() {
                break;
            }
            let pairs = child_pairs(ta, tb, a, b);
            let mut bound = |(x, y): (u32, u32)| {
                stats.bound_tests += 1;
                node_pair_bound(
                    &ta.nodes[x as usize].bound,
                    &tb.nodes[y as usize].bound,
                    pos_ab,
                    opts.bound,
                    f64::INFINITY,
                )
            };
            let (b0, b1) = (bound(pairs[0]), bound(pairs[1]));
            (a, b) = if b0 <= b1 { pairs[0] } else { pairs[1] };
        }
        evaluate(a, b, f64::NEG_INFINITY, &mut out, &mut stats);
    }
    out.lower = lower.min(pruned_min).min(out.upper).max(0.0);
    out.stats = stats;
    out
}

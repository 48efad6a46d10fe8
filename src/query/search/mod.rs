//! The search: Algorithm 2 of the paper (section 4.2), the path of every pair the closed
//! form ([`crate::query::closed_form`]) and the convex path ([`crate::query::convex`]) do not
//! answer. Best-first traversal of node pairs with a priority queue, upper bound from leaf
//! patch distances plus their eps, lower bound from the queue's top; with the anytime budget
//! of Johnson and Cohen (1997, section 3.1.3). It bounds the distance between the two
//! boundary *surfaces* ([`SurfaceBounds`]); what that means for the solids (overlap and
//! nesting) is decided by the front door ([`crate::query`]).
//!
//! **Its levels.** This file orders and prunes node pairs; [`leaf`] bounds a leaf pair in
//! stages, cheap bounds before exact ones; [`kernel`] measures one patch pair exactly, by
//! case. Each calls only the ones after it.
//!
//! **What it may call.** [`leaf`] and [`kernel`], the shared volume bounds
//! ([`crate::query::bound`]) and circle-level solvers ([`crate::query::angles`]), the
//! counters of [`crate::query::TraversalStats`], and the trees of [`crate::bvh`]. Never the
//! other two paths or the front door.
//!
//! Invariant: every queue key is a lower bound of the distance between the
//! original surface pieces under its node pair; pairs dropped because their key reached
//! `upper - tolerance` are remembered in `pruned_min`. At any moment
//! `min(queue top, pruned_min, upper)` is a lower bound of the surface distance, and
//! `upper` is an upper bound (a realised patch distance plus both leaves' eps). A leaf pair
//! is first given its stage-1 bounds ([`leaf`]) and re-inserted as "bounded" with key
//! `lower - eps_a - eps_b`, or as "resolved" when the bounds are already tight; a bounded
//! pair popped again gets the exact solve and becomes resolved; popping a resolved pair
//! means nothing can be refined further.

pub mod kernel;
pub mod leaf;

use crate::biarc::Disk;
use crate::bvh::QueryTree;
use crate::query::bound::node_pair::{axis_direction, node_pair_bound, sphere_bound, BoundKind};
use crate::query::certified::TraversalStats;
use leaf::{LeafPair, LeafResult};
use nalgebra::{Isometry3, Point3};
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::time::{Duration, Instant};

/// Initial capacity of the traversal's priority queue (entries; it grows beyond when
/// needed).
const QUEUE_CAPACITY: usize = 128;

/// Support points per hull bound of a node pair over several spirals ([`node_key`]): one
/// step is the separating-plane bound along the direction between the disks' axis points.
const UPPER_HULL_STEPS: usize = 1;

/// Budget of an anytime query: stop after this many node pairs or this much time and
/// return the certified bounds reached so far.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Budget {
    pub max_node_pairs: Option<usize>,
    pub max_time: Option<Duration>,
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
    state: State,
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
    /// Reversed: the smallest key is the greatest (BinaryHeap is a max-heap); among equal
    /// keys the most evaluated entry first (resolved, then bounded).
    fn cmp(&self, o: &Self) -> Ordering {
        o.key.total_cmp(&self.key).then(self.state.cmp(&o.state))
    }
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

/// Key of the node pair `(a, b)` whose parent's key is `parent`: [`node_pair_bound`] with the
/// nodes' fat-biarc hulls ([`QueryTree::hulls`]), each step only while the key is below
/// `prune_at` (the parent's key always is: it was popped below the same level).
#[allow(clippy::too_many_arguments)]
fn node_key(
    ta: &QueryTree,
    tb: &QueryTree,
    a: u32,
    b: u32,
    pos_ab: &Isometry3<f64>,
    kind: BoundKind,
    parent: f64,
    prune_at: f64,
) -> f64 {
    // A node over several spirals (the tree's upper level: no biarc) has a disk around all
    // of them, whose solid torus is about as fat as its sphere: the torus is not tried (the
    // check that skips one that cannot reach the level cost more there than the few tori
    // it let through saved). Its hull is the union of the spirals' fat-biarc hulls
    // ([`QueryTree::hull_ref`]), tried for one support step ([`UPPER_HULL_STEPS`]): nine in
    // ten node pairs of a query involve the upper level, and on spheres alone their keys
    // were too loose to prune it (`query_cost --poses 150`, eps 1e-4, node pairs per query:
    // pawn-pawn 37 -> 18, pawn-cup 57 -> 26, cup-bottle 46 -> 24, table-lightmill 34 -> 19).
    let (da, db) = (&ta.nodes[a as usize].bound, &tb.nodes[b as usize].bound);
    if ta.over_spirals(a) || tb.over_spirals(b) {
        let s = sphere_bound(da, db, pos_ab);
        if kind == BoundKind::Sphere || s >= prune_at {
            return parent.max(s);
        }
        let hull = match (ta.hull_ref(a), tb.hull_ref(b)) {
            (Some(ha), Some(hb)) => {
                let dir = axis_direction(da, db, pos_ab);
                ha.bound_capped(&hb, pos_ab, &dir, prune_at, UPPER_HULL_STEPS)
            }
            _ => f64::NEG_INFINITY,
        };
        return parent.max(s.max(hull));
    }
    let hulls = ta
        .hulls
        .get(a as usize)
        .and_then(Option::as_ref)
        .zip(tb.hulls.get(b as usize).and_then(Option::as_ref));
    parent.max(node_pair_bound(da, db, pos_ab, kind, prune_at, hulls))
}

/// A leaf pair reached from the roots by always taking the child pair with the smaller
/// `key` of the two nodes' disks.
///
/// A cold query dives along the sphere bound ([`sphere_bound`], closed form) and takes a
/// realised upper bound of the leaf pair first ([`LeafPair::upper`]: only that is used; its
/// stage-1 bounds without a level cost 12-19 us of a 38-87 us query at eps 1e-4, the upper
/// bound of its nearest patch pair about 2 us), so that the node keys of the traversal have
/// a finite pruning level from the start: each key then stops at the first bound that
/// reaches the level, and the solid-torus bound is skipped where it cannot
/// ([`node_pair_bound`]).
/// Before, about 65 of a query's 75 node keys were computed in full while the upper bound
/// was still infinite. Measured (`query_cost --poses 100`, eps 1e-4): pawn-cup 102 -> 72
/// us, cup-bottle 112 -> 98 us, pawn-pawn 50 -> 42 us. A query whose budget ran out before
/// any leaf pair dives along the full node-pair bound for its anytime witnesses.
fn dive(
    ta: &QueryTree,
    tb: &QueryTree,
    stats: &mut TraversalStats,
    key: impl Fn(&Disk, &Disk) -> f64,
) -> (u32, u32) {
    let (mut a, mut b) = (ta.root, tb.root);
    loop {
        let (na, nb) = (&ta.nodes[a as usize], &tb.nodes[b as usize]);
        if na.is_leaf() && nb.is_leaf() {
            return (a, b);
        }
        let pairs = child_pairs(ta, tb, a, b);
        let key_of =
            |(x, y): (u32, u32)| key(&ta.nodes[x as usize].bound, &tb.nodes[y as usize].bound);
        stats.bound_tests += 2;
        let (k0, k1) = (key_of(pairs[0]), key_of(pairs[1]));
        (a, b) = if k0 <= k1 { pairs[0] } else { pairs[1] };
    }
}

/// Whether `(a, b)` names a leaf of each tree (a warm start from another pair of trees
/// may not).
fn is_leaf_pair(ta: &QueryTree, tb: &QueryTree, a: u32, b: u32) -> bool {
    let leaf = |t: &QueryTree, n: u32| t.nodes.get(n as usize).is_some_and(|n| n.is_leaf());
    leaf(ta, a) && leaf(tb, b)
}

/// Records a leaf pair's realised distance `r.d` (leaves' eps sum `e`) in the traversal's
/// upper bound and witnesses, and its counters.
fn record_upper(
    (a, b): (u32, u32),
    r: &LeafResult,
    e: f64,
    out: &mut SurfaceBounds,
    stats: &mut TraversalStats,
) {
    stats.patch_bounds += r.patch_bounds;
    stats.patch_tests += r.patch_tests;
    stats.subdivided_pairs += r.subdivided_pairs;
    if r.d + e < out.upper {
        out.upper = r.d + e;
    }
    if r.d < out.approx {
        out.approx = r.d;
        out.point_a = r.pa;
        out.point_b = r.pb;
        out.best_pair = Some((a, b));
    }
}

/// Records a leaf pair's evaluation `r` (leaves' eps sum `e`) in the traversal's bounds and
/// counters ([`record_upper`]); returns the pair's new key (at least `key`) and state.
fn record_leaf(
    (a, b): (u32, u32),
    key: f64,
    r: &LeafResult,
    e: f64,
    out: &mut SurfaceBounds,
    stats: &mut TraversalStats,
) -> (f64, State) {
    record_upper((a, b), r, e, out, stats);
    if let Some(p) = r.penetration {
        if out.penetration.is_none_or(|(_, _, m)| p.2 > m) {
            out.penetration = Some(p);
        }
    }
    if r.d == 0.0 || r.penetration.is_some() {
        out.surfaces_meet = true;
        return (f64::NEG_INFINITY, State::Resolved);
    }
    let state = if r.complete {
        State::Resolved
    } else {
        State::Bounded
    };
    (key.max(r.lower - e), state)
}

/// Options of the traversal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TraversalOptions {
    /// Stop when `upper - lower <= tolerance`.
    pub tolerance: f64,
    /// Neither stop nor prune while the lower bound is at most this, whatever the tolerance:
    /// a query whose surfaces may meet within its width (lower bound at or below the
    /// rounding slack) would otherwise search both solids for an overlap; with the slack as
    /// the floor the same pass narrows until its lower bound clears it, or until every pair
    /// below it is resolved. `f64::NEG_INFINITY` for none.
    pub lower_floor: f64,
    pub budget: Budget,
    pub bound: BoundKind,
}

/// State of a queue entry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum State {
    /// Key from node bounds only.
    Open,
    /// Leaf pair with stage-1 bounds ([`leaf`]); an exact solve may narrow it.
    Bounded,
    /// Bounded leaf pair whose lower bound was sharpened by sub-piece bounds
    /// ([`leaf::LeafPair::tightened_lower`]); popped again, it is solved exactly.
    Tightened,
    /// Leaf pair whose interval nothing can narrow further.
    Resolved,
}

/// Algorithm 2 over the boundary surfaces of two trees; `pos_ab` places B in A's frame.
/// `warm` is a leaf pair whose realised upper bound starts the query instead of the dive's
/// (frame coherence: the last frame's best leaf pair).
///
/// Leaf pairs are evaluated in two stages ([`leaf`]): their stage-1 bounds when first
/// popped, the exact solve only if they are popped again, i.e. only while they still hold
/// the query's lower bound and the tolerance is not met.
pub fn traverse(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    opts: &TraversalOptions,
    warm: Option<(u32, u32)>,
) -> SurfaceBounds {
    let start = Instant::now();
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
    // The pruning level: pairs whose key reaches it are done, unless the key is still at or
    // below the floor ([`TraversalOptions::lower_floor`]).
    let level = |upper: f64| {
        let at = upper - tol;
        if at > opts.lower_floor {
            at
        } else {
            opts.lower_floor.next_up()
        }
    };
    // One allocation up front: growing from empty reallocated five or six times a query
    // (3.7% of the query time at eps 1e-4; queues peak at a few dozen entries).
    let mut heap = BinaryHeap::with_capacity(QUEUE_CAPACITY);
    let mut pruned_min = f64::INFINITY;
    let mut leaves = LeafPair::new(ta, tb, pos_ab);
    // The query's first level: a realised upper bound ([`LeafPair::upper`]) of one leaf
    // pair, the last best one for a warm query (frame coherence), else the one a dive along
    // the smaller sphere bound reaches ([`dive`]). A warm pair used to get its full stage-1
    // bounds first, without a level (nothing pruned, every patch pair realised); it now gets
    // the same cheap upper bound as the dive's and is bounded when the traversal reaches
    // it. Measured with the best leaf pair of the same pose as the warm pair (`query_cost
    // --best-first --poses 150 --eps 1e-4`, best of three alternating runs): medians
    // pawn-pawn 19.3 -> 15.6 us, pawn-cup 30.9 -> 24.1, cup-bottle 48.7 -> 27.1,
    // table-lightmill 19.1 -> 13.1 (cold: 19.3, 28.9, 32.9, 16.6: the old warm start was
    // slower than none); the motion experiment's blocked means at eps 1e-4 drop 20-50%.
    let first = match warm {
        Some((a, b)) if is_leaf_pair(ta, tb, a, b) => (a, b),
        _ => dive(ta, tb, &mut stats, |da, db| sphere_bound(da, db, pos_ab)),
    };
    {
        let (a, b) = first;
        let clock = Instant::now();
        let r = leaves.upper(a, b);
        stats.leaf_bounds_ns += clock.elapsed().as_nanos() as u64;
        stats.leaf_bounds += 1;
        let e = ta.nodes[a as usize].eps + tb.nodes[b as usize].eps;
        // Only the upper bound: a lower bound without a level would be loose (nothing
        // pruned), and the traversal reaches the pair again with a level if it matters. A
        // realised distance of 0 does not end the query here: the pair's stage 1 and exact
        // solve look for crossings and interpenetration when the traversal reaches it.
        record_upper((a, b), &r, e, &mut out, &mut stats);
    }
    // Evaluates the leaf pair (a, b): stage 1 from `Open`, stage 2 from `Bounded`. Returns
    // the new key and state.
    let mut evaluate = |a: u32,
                        b: u32,
                        key: f64,
                        from: State,
                        out: &mut SurfaceBounds,
                        stats: &mut TraversalStats| {
        let e = ta.nodes[a as usize].eps + tb.nodes[b as usize].eps;
        // Patch pairs at least `upper - tol + e` apart cannot improve the answer: their
        // bound is enough.
        let prune_at = level(out.upper) + e;
        let clock = Instant::now();
        let staged = match from {
            State::Open => leaves.bounds(a, b, prune_at, out.upper - e),
            _ => None,
        };
        if from == State::Bounded {
            let clock = Instant::now();
            let lower = leaves.tightened_lower(a, b, prune_at);
            stats.leaf_bounds_ns += clock.elapsed().as_nanos() as u64;
            stats.leaf_tightened += 1;
            return (key.max(lower - e), State::Tightened);
        }
        stats.leaf_bounds_ns += clock.elapsed().as_nanos() as u64;
        let r = match staged {
            Some(r) => {
                stats.leaf_bounds += 1;
                r
            }
            None => {
                stats.leaf_tests += 1;
                let clock = Instant::now();
                let r = leaves.exact(a, b, prune_at);
                stats.leaf_tests_ns += clock.elapsed().as_nanos() as u64;
                r
            }
        };
        record_leaf((a, b), key, &r, e, out, stats)
    };
    let root_key = {
        stats.bound_tests += 1;
        node_pair_bound(
            &ta.nodes[ta.root as usize].bound,
            &tb.nodes[tb.root as usize].bound,
            pos_ab,
            opts.bound,
            f64::INFINITY,
            None,
        )
    };
    heap.push(Entry {
        key: root_key,
        a: ta.root,
        b: tb.root,
        state: State::Open,
    });
    let lower;
    loop {
        let Some(e) = heap.pop() else {
            lower = out.upper;
            break;
        };
        if e.state == State::Resolved || e.key >= level(out.upper) {
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
            let (key, state) = evaluate(e.a, e.b, e.key, e.state, &mut out, &mut stats);
            if out.surfaces_meet {
                // Lower bound can only be <= 0 now.
                lower = f64::NEG_INFINITY;
                break;
            }
            if key < level(out.upper) {
                heap.push(Entry {
                    key,
                    a: e.a,
                    b: e.b,
                    state,
                });
            } else {
                pruned_min = pruned_min.min(key);
            }
            continue;
        }
        for (a, b) in child_pairs(ta, tb, e.a, e.b) {
            stats.bound_tests += 1;
            let prune_at = level(out.upper);
            let key = node_key(ta, tb, a, b, pos_ab, opts.bound, e.key, prune_at);
            if key < prune_at {
                heap.push(Entry {
                    key,
                    a,
                    b,
                    state: State::Open,
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
        let (a, b) = dive(ta, tb, &mut stats, |da, db| {
            node_pair_bound(da, db, pos_ab, opts.bound, f64::INFINITY, None)
        });
        evaluate(a, b, f64::NEG_INFINITY, State::Open, &mut out, &mut stats);
    }
    out.lower = lower.min(pruned_min).min(out.upper).max(0.0);
    out.stats = stats;
    out
}

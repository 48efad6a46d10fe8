//! Minimum distance between two posed solids of revolution (Son et al. 2020, sections 3
//! and 4.2; Johnson and Cohen 1997 for the lower/upper-bound paradigm and anytime queries).
//!
//! # Cost model (issue 11)
//!
//! A query is as fast as the number of expensive steps it cannot avoid. It spends, in this
//! order, and stops as soon as `upper - lower <= tolerance` ([`Tolerance`]; by default the
//! trees' own accuracy `eps_a + eps_b`):
//!
//! | step | where | measured cost (per pair, 2-core EPYC) | what it gives |
//! | --- | --- | --- | --- |
//! | closed form | [`offset`] | one core distance, ~0.7 us per query | the whole answer when both solids are balls or solid tori (one circle per profile); no traversal |
//! | first leaf (cold query) | [`traverse`], [`leaf`] | a dive along sphere bounds and a realised upper bound of one patch pair of the leaf pair reached (~2 us: the arcs' tori's near points or a 3-step hull witness, projected, then polished; the leaf pair's stage-1 bounds without a level cost 12-19 us and were never used) | a finite upper bound before any node key, so every key can stop at the pruning level |
//! | node-pair bound | [`bounds`] | 0.1 us (spheres), then the nodes' hull bound ([`hull`], a few support points), then ~0.4 us for the solid-torus circle minimum, skipped when two points of the circles show it cannot reach the level | a valid lower bound; prunes most pairs |
//! | leaf stage 1 | [`leaf`], [`patch_bound`] | ~1-5 us per patch pair (closed-form sphere, shell and slab bounds; the arcs' tori or a circle/cone solve; the pieces' converged hull bound) | lower bound and a realised upper bound (started from the tori's or the hulls' nearest points); settles the pair when they meet |
//! | stage 1, split | [`leaf`], [`certify`] | up to 8 sub-piece bounds (~1-2 us each) | a positive lower bound for a pair whose tori and hulls overlap, instead of "may intersect" |
//! | stage 1b, tightened | [`leaf`], [`certify`] | up to 8 sub-piece bounds per patch pair | a leaf pair popped again is first given a sharper bound against the current pruning level; most are then pruned |
//! | leaf stage 2 | [`leaf`], [`mod@patch_distance`] | a converged hull bound against the leaf's best distance (~1 us), then ~20-50 us per patch pair (degree-8 boundary solves, crossing scan) | the exact patch distance and interpenetration checks |
//! | boundary pre-bounds | [`mod@patch_distance`] | ~1 us per boundary parallel | skip a degree-8 solve whose parallel cannot beat the best candidate |
//! | closed forms | [`mod@patch_distance`], [`planar`] | < 1 us | coaxial patches, parallels outside a torus whose closest point is on the patch |
//!
//! Costs from `cargo bench --bench query -- patch_distance_64` (64 leaf-sized patch pairs
//! 1e-4 from contact: `stage1_bounds`, `node_pair_bound`, `binormals_gauss`) and
//! `cargo bench --bench circle`; counts per query from the `query_cost` experiment
//! (`TraversalStats`: `bound_tests`, `leaf_bounds`, `leaf_tightened`, `leaf_tests`,
//! `patch_bounds`, `patch_tests`). A leaf pair is measured exactly only when its sharpened
//! lower bound still holds the query's lower bound; on the exact torus that never happens.
//!
//! **Where the time goes now** (close poses, eps 1e-4, `query_cost --poses 150`, medians
//! 20-37 us on pawn-pawn, pawn-cup, cup-bottle, table-lightmill; perf over the timed
//! queries of the four pairs): stage-1 leaf bounds 40% of the time, node keys 25% (spheres
//! 9%, node hulls most of the rest), the cold query's first leaf 7%, stage 1b 6% and the
//! exact stage 10% (0.0-0.3 patch pairs per query). Across the stages, hull iterations
//! take a third (support points 14%, the simplex step 15%), certified circle/circle minima
//! 9%, circle/cone solves 5% and closest-point projections (realised pairs,
//! [`patch_bound::polish`]) 7%. What is left is spread over primitives
//! that each cost 0.02-1 us and are each called a few to a hundred times per query; no
//! single step holds more than a seventh of the time. Before the dive, about 65 of a
//! query's 75 node keys were computed in full while the upper bound was still infinite, and
//! the node tori were 39% of all the time. What made the exact stage rare (exact patch
//! solves per query at eps 1e-4: pawn-cup 2.9 -> 0.2, cup-bottle 4.7 -> 0.3,
//! table-lightmill 3.9 -> 0.0):
//!
//! * the hull bound of [`hull`] iterates its direction to convergence (support points on
//!   the hulls' Minkowski difference, stopped at the caller's level or once the level is
//!   out of reach); three naive steps left it short of the level in 72% of the pairs that
//!   then went to an exact solve;
//! * a piece's hull holds eight chords of an arc, so it loses a sixty-fourth of the
//!   sagitta, which for leaf arcs near contact (3e-4 to 4e-3 at eps 1e-4) was above the
//!   distance the bound had to prove;
//! * the realised pair of two cones starts from the hulls' nearest points (it started from
//!   the pieces' mid points, 34% too long at the median), so the query's upper bound and
//!   the settle test see the true distance;
//! * before a pair's exact solve, its hull bound is searched to the leaf's best distance so
//!   far, below the pruning level the cheap bound stopped at.
//! * the realised pair that would lower the query's upper bound is polished by
//!   alternating closest points: near the cup's waist (an arc of radius 5-11 bulging
//!   towards the axis) one alternation left it 1e-4 to 1e-3 long, and the leaf pair that
//!   held the minimum was tightened and solved exactly for its upper bound alone.
//! * where both pieces' hulls lie within the leaves' eps of the pieces, the hull bound and
//!   the hulls' nearest points stand in for the arcs' tori and their near points
//!   ([`leaf::HULL_PRECISION_SHARE`]): the tori's near points on the cup's waist started
//!   realised pairs far from the minimum (cup-bottle 43 -> 37 us at eps 1e-4).
//!
//! **The search's floor.** A query that starts from the best leaf pair of its own pose
//! (`query_cost --best-first`: the warm start of [`distance_cached`] primed by an untimed
//! query on every pose first) knows where the minimum is before it starts; what it still
//! spends is the proof. At eps 1e-4 (best of three alternating runs of 150 poses) its
//! medians are pawn-pawn 15.4, pawn-cup 24.0, cup-bottle 27.2, table-lightmill 13.1 us
//! against 19.3, 28.9, 32.9, 16.6 cold: about a fifth of a cold query is its search order
//! (the dive's first pair is a median 2.5-4.5 times the distance away), four fifths are the
//! proof. The proof pops as many node pairs (18-26: every node pair above the minimum's
//! leaf pair has a key below the distance, so the traversal must split it) and bounds 2-3
//! leaf pairs near the minimum (one holds it, the others are pruned by their stage-1
//! bounds). So the node keys and stage-1 bounds above are what a query costs, whatever it
//! knows. Two ways to find the best pair sooner did not pay for themselves: alternating
//! nearest points between the two surfaces from the dive's pair (each a planar
//! nearest-point search down one tree, about 0.1 us; four round trips brought the median
//! first upper bound within 0.5% of the distance on pawn-pawn, but a quarter of the poses
//! stayed in a local minimum 50% away, and the medians did not move), and a dive along the
//! one-step hull bound instead of the sphere bound (first pairs 6-70% away instead of
//! 150-350%, medians within noise). Priming matters when measuring this: the same query
//! run just before the timed one made cold medians 15-25% faster by itself (the pose's code
//! path and tree nodes stay in the caches and branch predictors), so `--best-first` primes
//! all poses before the timed loop.
//!
//! **Cold caches.** The times above are warm: the same query loop keeps the trees and the
//! code in cache. Run after unrelated work, a query also fetches both from memory:
//! `query_cost --cold` (64 MB written before each query) gives medians of 43-58 us against
//! 17-33 us warm at eps 1e-4 on the four pairs. Warming only the code (a query on copies of
//! the two solids first) brings them to 25-45 us: about 12-18 us of a cold query is fetching
//! its code (some 120 functions, 100-200 KB of machine code; fat LTO with one codegen unit
//! gave -4% warm and cold within noise) and 8-12 us its trees. Prefetching a popped pair's
//! children (nodes, hulls, first patch) before their keys made no measurable difference.
//! FCL's cold/warm ratio is only 1.03-1.25 (its meshes stay out of cache either way), so
//! `fcl_bench` reports both: its headline ratio is cold, and the warm ratio is 1.5-2.5x
//! higher.
//!
//! Earlier (before the hull bounds): 3-9 leaf pairs per query went to the exact solve,
//! 80% of them as "may intersect" only because a straight piece's or a wide arc's solid
//! torus overlapped the other piece; the node hulls (a biarc's chords grown by their
//! sagittas, second order in the piece length where the disks are first order) cut the leaf
//! pairs a query evaluates by 2.5-3x.
//!
//! Tried and dropped (each measured with `query_cost --poses 100`, same counters or within
//! the machine's 25% noise): cutting arcs that bulge towards the axis (a convex hull cannot
//! follow them) into three for the stage-1 hull bound (the pairs it could prune were rare:
//! those leaf pairs mostly hold the minimum); starting a leaf pair's piece hulls from its
//! previous patch pair's direction, or from the major circles' near points (same support
//! points per bound); splitting both nodes of a pair (half the node pairs, same time); the
//! arcs' tori's near points skipped in the first leaf's upper bound (same time); a
//! closed-form threshold test of the circle/circle bounds against the pruning level (it
//! proved the level in 3-7% of the calls); a cheaper
//! circle/circle lower bound in front of the solver; a smooth-junction mode of the exact
//! kernel (branch `exp/smooth-junctions`: skipping G1 junction parallels needs one eps per
//! tree and trees at eps/4, oracle-clean, -15% to +10%); sub-piece splits before every
//! exact solve (16 cells cost as much as the solves they spared); the dive alone, or the
//! circles' reach test alone (each needs the other: without a level nothing is skipped,
//! and with a level but no skip the keys are computed in full anyway); keeping the dive
//! leaf's key (its bounds without a level are loose, more exact solves); skipping the node
//! torus bound whenever the hulls are apart (-5%, within noise); two or four
//! chords per arc in node hulls (no change, up to 3x the hull memory); trees built to eps/4
//! under the same tolerance (no change: the leaves' eps is not what sends pairs to the
//! exact stage); a regula-falsi crossing scan (the bisection is not where the time goes);
//! lazy node keys (children queued on their sphere bound, the hull and torus bounds computed
//! only when a pair reaches the top of the queue: same time, since a query computes only
//! 10-20 hull keys and nearly all of them are for pairs it expands anyway); starting a node
//! pair's hull iteration from the direction that gave its parent's bound (with one support
//! step over spirals this pins every upper pair to the root's direction: pawn-pawn node
//! pairs 18 -> 25; inside spirals only: same counters, same time); a Nesterov-accelerated
//! direction in the hull iteration (Montaut et al. 2022: on these hulls of circles it took
//! 2-7% more support points); skipping the node torus bound once the hulls are apart, or
//! always (same counters, -2 to -3.5%, within noise); each patch's disk kept in the tree
//! instead of recomputed (no measurable change, 50% more patch memory); fat LTO with one
//! codegen unit (-2.5%).
//!
//! # Layout
//!
//! * [`offset`] answers pairs of balls and solid tori in closed form before any traversal;
//! * the traversal [`traverse`] only orders and prunes node pairs (Algorithm 2 with an
//!   anytime budget); [`mod@distance`] adds solid semantics and frame coherence; [`batch`] runs
//!   independent queries on all cores;
//! * leaf pairs: [`leaf`] (the two stages), [`patch_bound`] (stage-1 bounds: patch/patch via
//!   the arcs' tori, torus/cone via the circle/segment distance), [`mod@patch_distance`] (the
//!   exact kernel: a driver and one file per case: interior normals of tori and of cones,
//!   boundary parallel/patch, parallel/parallel, crossings), with the circle/patch kernels [`planar`] (coaxial case), [`sweep`]
//!   (critical points along a circle), [`binormal_kernel`], [`line_field`], [`gauss`], and
//!   [`certify`] (subdivision lower bounds where a kernel had to sample);
//! * node bounds [`bounds`] and convex-hull bounds [`hull`] on the query tree [`tree`];
//! * solids: [`containment`] (point-in-solid through the tree), [`overlap`] (certificates of
//!   overlap and nesting); [`refine`] (witnesses on the exact NURBS surfaces).

pub mod batch;
pub mod binormal_kernel;
pub mod bounds;
pub mod certify;
pub mod containment;
pub mod distance;
pub mod gauss;
pub mod hull;
pub mod leaf;
pub mod line_field;
pub mod offset;
pub mod overlap;
pub mod patch;
pub mod patch_bound;
pub mod patch_distance;
pub mod planar;
pub mod refine;
pub mod sweep;
pub mod traverse;
pub mod tree;

pub use distance::{
    distance, distance_cached, try_distance, try_distance_cached, Distance, QueryCache, QueryError,
    QueryOptions, Tolerance,
};
pub use patch::{Patch, ProfileArc};
pub use patch_distance::{patch_distance, PatchDistance};
pub use traverse::{Budget, TraversalStats};
pub use tree::QueryTree;

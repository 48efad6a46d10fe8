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
//! | node-pair bound | [`bounds`] | 0.1 us (spheres), ~1-3 us with the solid-torus circle minimum | a valid lower bound; prunes most pairs |
//! | leaf stage 1 | [`leaf`], [`patch_bound`] | ~1-5 us per patch pair (one circle/circle minimum, or a circle/cone solve; closed-form shell and slab bounds first) | lower bound and a realised upper bound; settles the pair when they meet |
//! | stage 1, split | [`leaf`], [`certify`] | up to 24 sub-piece torus bounds (~1-3 us each) | a positive lower bound for a pair whose tori overlap (long, flat or wide pieces), instead of "may intersect" |
//! | stage 1b, tightened | [`leaf`], [`certify`] | up to 32 sub-piece torus bounds per patch pair | a leaf pair popped again is first given a sharper bound against the current pruning level; most are then pruned |
//! | leaf stage 2 | [`leaf`], [`mod@patch_distance`] | ~30-300 us per patch pair (degree-8 boundary solves, crossing scan) | the exact patch distance and interpenetration checks |
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
//! Where the time goes now (close poses, eps 1e-4, `query_cost --repeat 15` under `perf`):
//! on the paper models 1-2 leaf pairs per query still need the exact solve (about 40% of
//! the time: boundary-parallel binormals, crossing scans of pairs that may intersect), the
//! remaining leaf bounds and sub-piece bounds about a third, node bounds about a sixth;
//! circle/circle minima are about 30% of all of it. The convex-hull bounds
//! ([`bounds::hull_bound`], [`bounds::ParallelHull`]) cut the leaf pairs a query evaluates
//! by a factor 2.5-3 (cup-bottle 13.6 -> 4.6, table-lightmill 14.2 -> 5.8): a node's biarc
//! chords grown by their sagittas bound its surface to second order in the piece length,
//! where the disks of the node bounds are first order, and they separate the short straight
//! or flat pieces whose solid tori overlap, which fed the sub-piece splits.
//! Before the stage-1 split and stage 1b, 3-9 leaf pairs per query
//! went to the exact solve, 80% of them as "may intersect" only because a straight piece's
//! or a wide arc's solid torus overlapped the other piece. A closed-form threshold test of
//! the circle/circle bounds against the pruning level (the certificate quartic at the
//! level, no descent) was tried too: it proved the level in only 3-7% of the bound calls
//! (the minima a query computes are the ones below its pruning level) and was dropped. A cheaper closed-form
//! circle/circle lower bound in front of the solver was tried and was slower (it rarely
//! prunes near contact, where the solver is needed anyway). A smooth-junction mode of the
//! exact kernel was tried too (branch `exp/smooth-junctions`): boundary parallels that are
//! G1 junctions of the approximating surface are skipped, since a minimum there is a
//! common normal of the neighbours' tori, which makes the key a bound of the surfaces'
//! global minimum and so needs one uniform eps per tree and trees built to eps/4. It passed
//! the oracle (2,014 cases, 0 violations) but moved query times by -15% to +10%, within
//! noise: exact leaves per query stayed at 1-2, because the pairs that reach the exact stage
//! are mostly straight pieces at creases and pairs whose solid-torus bounds overlap (both
//! measured before the hull bounds, which then went after the bounds' cost instead).
//!
//! # Layout
//!
//! * [`offset`] answers pairs of balls and solid tori in closed form before any traversal;
//! * the traversal [`traverse`] only orders and prunes node pairs (Algorithm 2 with an
//!   anytime budget); [`mod@distance`] adds solid semantics and frame coherence; [`batch`] runs
//!   independent queries on all cores;
//! * leaf pairs: [`leaf`] (the two stages), [`patch_bound`] (stage-1 bounds: patch/patch via
//!   the arcs' tori, torus/cone via the circle/segment distance), [`mod@patch_distance`] (the
//!   exact kernel), with the circle/patch kernels [`planar`] (coaxial case), [`sweep`]
//!   (critical points along a circle), [`binormal_kernel`], [`line_field`], [`gauss`], and
//!   [`certify`] (subdivision lower bounds where a kernel had to sample);
//! * node bounds [`bounds`] on the query tree [`tree`];
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

//! Minimum distance between two posed solids of revolution (Son et al. 2020, sections 3
//! and 4.2; Johnson and Cohen 1997 for the lower/upper-bound paradigm and anytime queries).
//!
//! * [`patch`], [`patch_distance`]: toroidal patches and their exact pairwise distance,
//!   with the kernels [`planar`] (coaxial case) and [`sweep`] (critical points along a
//!   circle);
//! * [`tree`]: the query's view of a solid's bounding hierarchy;
//! * [`bounds`]: provably valid node-pair lower bounds;
//! * [`certify`]: subdivision lower bounds for patch pairs whose kernel had to sample (a
//!   sampled value never resolves a lower bound);
//! * [`traverse`]: Algorithm 2 (best-first over node pairs) with an anytime budget;
//! * [`containment`]: point-in-solid tests (solids, not surfaces), through the tree;
//! * [`overlap`]: certificates of overlap and nesting (points inside both true solids);
//! * [`refine`]: witness refinement on the exact NURBS surfaces;
//! * [`distance`]: the query itself, with frame coherence.

pub mod binormal_kernel;
pub mod bounds;
pub mod certify;
pub mod containment;
pub mod distance;
pub mod gauss;
pub mod leaf;
pub mod line_field;
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

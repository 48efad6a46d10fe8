//! Minimum distance between two posed solids of revolution (Son et al. 2020, sections 3
//! and 4.2; Johnson and Cohen 1997 for the lower/upper-bound paradigm and anytime queries).
//!
//! A query walks down five levels; each is a folder whose `mod.rs` says what it decides and
//! what it may call, and each calls only the levels below it:
//!
//! 1. [`traverse`]: the search (Algorithm 2 with an anytime budget), solid semantics
//!    (overlap and nesting), the interval's rounding slack, frame coherence, batches and
//!    refinement on the exact surfaces. The public entry points live here.
//! 2. [`leaf`]: a leaf pair in stages: cheap patch bounds from both sides, subdivision
//!    bounds for pairs that may intersect, then the exact kernel.
//! 3. [`kernel`]: exact patch/patch distance by case, the coaxial case, and the closed form
//!    between balls and solid tori.
//! 4. [`bound`]: lower bounds between bounding volumes (solid tori, spheres, shells, slabs,
//!    convex hulls), shared by node keys, leaf stages and the kernel's pre-bounds.
//! 5. [`angles`]: circle-level solvers: where along a circle a distance is critical or meets
//!    a level, where a common normal of two tori can be.
//!
//!
//! Above the distance, [`penetration`] bounds the translational penetration depth and the
//! signed distance of overlapping solids; it calls the distance query's entry points and
//! the containment tests of [`crate::bvh`], nothing of the levels below.
//!
//! Below the query: the solid's hierarchy [`crate::bvh`] (patches, disks, hulls, the tree,
//! point-in-solid), circle/circle distances [`crate::circle`], and every slack and tolerance
//! in [`crate::tolerances`]. What a query costs, step by step, and what was tried to make it
//! cheaper is recorded in `docs/performance.md`.

pub mod angles;
pub mod bound;
pub mod convex;
pub mod kernel;
pub mod leaf;
pub mod penetration;
pub mod traverse;

pub use crate::tolerances;

pub use traverse::{
    distance, distance_cached, query_slack, try_distance, try_distance_cached, Budget, Distance,
    Gradient, QueryCache, QueryError, QueryOptions, Tolerance, TraversalStats,
};

pub use penetration::{penetration, signed_distance, Penetration, SignedDistance};

pub use crate::bvh::{Patch, ProfileArc, QueryTree};
pub use kernel::{patch_distance, PatchDistance};

// The paths other crates of the workspace name (verify, experiments): kept at their old
// places.
pub use crate::bvh::containment;

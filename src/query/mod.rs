//! Minimum distance between two posed solids of revolution (Son et al. 2020, sections 3
//! and 4.2; Johnson and Cohen 1997 for the lower/upper-bound paradigm and anytime queries).
//!
//! **A front door over three paths.** The entry points ([`distance`], [`try_distance`], the
//! cached and batch forms) check the input, compute the interval's rounding slack and choose
//! a path, the first that applies:
//!
//! 1. [`closed_form`]: two balls or solid tori, from their cores;
//! 2. [`convex`]: two solids certified convex, by GJK on their hulls (unless refinement is
//!    asked for); it may decline;
//! 3. [`search`]: Algorithm 2 over the two boundary surfaces, whose bounds the front door
//!    turns into a distance between *solids* (the overlap verdict), then refines on the exact
//!    surfaces when asked.
//!
//! Each path answers with one type, [`Certified`] (returned as [`Distance`]); the front door
//! (`front/`, not public: its items are re-exported here) also holds the gradient, the
//! width diagnosis and the batches.
//!
//! **Below the paths.** The search has its own levels (the traversal, [`search::leaf`],
//! [`search::kernel`]); two levels are shared: [`bound`] (lower bounds between bounding
//! volumes, used by the search and named by [`QueryOptions`]) and [`angles`] (circle-level
//! solvers, used by the search, the bounds and the closed form). Each folder's `mod.rs` says
//! what it decides and what it may call; no path calls another, and none calls the front
//! door.
//!
//! Above the distance, [`penetration()`] bounds the translational penetration depth and the
//! signed distance of overlapping solids; it calls the front door's entry points and the
//! containment tests of [`crate::bvh`], nothing of the paths.
//!
//! Below the query: the solid's hierarchy [`crate::bvh`] (patches, disks, hulls, the tree,
//! point-in-solid), circle/circle distances [`crate::circle`], and every slack and tolerance
//! in [`crate::tolerances`]. What a query costs, step by step, and what was tried to make it
//! cheaper is recorded in `docs/performance.md`.

pub mod angles;
pub mod bound;
mod certified;
pub mod closed_form;
pub mod convex;
mod front;
pub mod penetration;
pub mod search;
mod simplex;

pub use certified::{Certified, TraversalStats};
pub use front::batch::{distances, try_distances};
pub use front::distance::{
    check_query, distance, distance_cached, query_slack, try_distance, try_distance_cached,
    Distance, QueryCache, QueryError, QueryOptions, Tolerance, MAX_SCALE,
};
pub use front::gradient::Gradient;
pub use front::width::{width_limit, WidthLimit};
pub use penetration::{
    penetration, signed_distance, LowerCertificate, Penetration, SignedDistance,
};
pub use search::kernel::{patch_distance, PatchDistance};
pub use search::Budget;

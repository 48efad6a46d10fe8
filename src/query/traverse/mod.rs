//! The search (paper section 4.2, Algorithm 2) and what turns it into a query between solids.
//!
//! **What this level decides.** Which node pairs to open and in what order, when to stop
//! ([`search`]: best-first over a priority queue of lower bounds with an anytime budget,
//! Johnson and Cohen 1997); what a distance between *solids* is ([`overlap`]: overlap and
//! nesting certificates give 0); the interval's rounding slack, frame coherence and the
//! public entry points ([`mod@distance`]); parallel batches ([`batch`]); and witnesses on the
//! exact NURBS surfaces ([`refine`]).
//!
//! **What it may call.** Every level below: [`super::leaf`] for leaf pairs, [`super::kernel`]
//! for the closed form of balls and solid tori, [`super::bound`] for node keys, and the
//! trees and containment tests of [`crate::bvh`].

pub mod batch;
mod deep_point;
pub mod distance;
pub mod gradient;
pub mod overlap;
pub mod refine;
pub mod search;
pub mod width;

pub use distance::{
    distance, distance_cached, query_slack, try_distance, try_distance_cached, Distance,
    QueryCache, QueryError, QueryOptions, Tolerance,
};
pub use gradient::Gradient;
pub use search::{traverse, Budget, SurfaceBounds, TraversalOptions, TraversalStats};
pub use width::{width_limit, WidthLimit};

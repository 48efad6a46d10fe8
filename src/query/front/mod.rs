//! The query's front door: what a caller asks, which path answers, and what the answer
//! means for two *solids*.
//!
//! **What it decides.** The entry points, their checks and the interval's rounding slack,
//! and the choice of path, closed form -> convex -> search ([`distance`]); whether solids
//! whose surfaces the search bounds overlap, nest or are apart ([`overlap`], its surface
//! search in `deep_point`); witnesses on the exact NURBS surfaces ([`refine`]); the
//! gradient of a certified distance ([`gradient`]); what limited an interval's width
//! ([`width`]); parallel batches ([`batch`]). Its public items are re-exported by
//! [`crate::query`], their one public path.
//!
//! **What it may call.** The three paths ([`crate::query::closed_form`],
//! [`crate::query::convex`], [`crate::query::search`]), the answer type of
//! [`crate::query::Certified`], the node-pair bound kinds of [`crate::query::bound`] (an
//! option of the search), and the trees and containment tests of [`crate::bvh`].

pub mod batch;
mod deep_point;
pub mod distance;
pub mod gradient;
pub mod overlap;
pub mod refine;
pub mod width;

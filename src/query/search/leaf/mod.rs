//! Leaf pairs: the bounds of two leaves' patches, from cheap to exact (paper section 4.2:
//! a leaf pair's priority is its patches' distance).
//!
//! **What this level decides.** How much a leaf pair is worth: stage 1 ([`patch_lower`],
//! [`patch_upper`]) bounds every patch pair from both sides with closed forms, one
//! circle/circle minimum and a hull bound, and settles the pair when they meet; pairs that
//! may intersect get a subdivision lower bound ([`subdivision`]), and pairs the kernel
//! answered by sampling one by sectors first ([`sectors`]); stage 2 asks the exact
//! kernel ([`super::kernel`]) only for the pairs still holding the query's lower bound. The
//! stages and their budgets are in [`stages`].
//!
//! **What it may call.** [`super::kernel`] (exact patch distance), [`crate::query::bound`] (volume
//! bounds), [`crate::query::angles`] (circle-level solvers), and [`crate::bvh`] (patches, disks,
//! hulls, point-in-solid). Never the traversal above it ([`super`]).

pub mod patch_lower;
pub mod patch_upper;
pub mod sectors;
pub mod stages;
pub mod subdivision;

pub use stages::{LeafPair, LeafResult};

#[cfg(test)]
mod tests;

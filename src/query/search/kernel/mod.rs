//! Exact distances between two revolved pieces, by case (paper section 3: "the distance
//! between two toroidal patches is l +- r1 +- r2").
//!
//! **What this level decides.** The exact distance of one patch pair
//! ([`mod@patch_distance`]: a driver and one file per case of the minimum: interior common
//! normals, a boundary parallel against a patch, two parallels, crossings), and the coaxial case
//! by the planar distance of the profile pieces ([`planar`]). Each candidate is measured as the distance of two
//! points on the patches, so extra candidates never make an answer too small.
//!
//! **What it may call.** [`crate::query::bound`] (cheap pre-bounds that skip a solve),
//! [`crate::query::angles`] (the angles along a circle where a distance is critical), and the
//! patches of [`crate::bvh`] and circles of [`crate::circle`]. Never the leaf stages or the
//! traversal above it.

pub mod patch_distance;
pub mod planar;

pub use patch_distance::{patch_distance, PatchDistance};

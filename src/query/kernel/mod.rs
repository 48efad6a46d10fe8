//! Exact distances between two revolved pieces, by case (paper section 3: "the distance
//! between two toroidal patches is l +- r1 +- r2").
//!
//! **What this level decides.** The exact distance of one patch pair
//! ([`mod@patch_distance`]: a driver and one file per case of the minimum: interior common
//! normals, a boundary parallel against a patch, two parallels, crossings), the coaxial case
//! by the planar distance of the profile pieces ([`planar`]), and the closed form between two
//! balls or solid tori ([`ball_torus`]). Each candidate is measured as the distance of two
//! points on the patches, so extra candidates never make an answer too small.
//!
//! **What it may call.** [`super::bound`] (cheap pre-bounds that skip a solve),
//! [`super::angles`] (the angles along a circle where a distance is critical), and the
//! patches of [`crate::bvh`] and circles of [`crate::circle`]. Never the leaf stages or the
//! traversal above it.

pub mod ball_torus;
pub mod patch_distance;
pub mod planar;

pub use patch_distance::{patch_distance, PatchDistance};

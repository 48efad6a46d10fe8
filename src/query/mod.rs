//! Minimum distance between two posed solids of revolution (paper sections 3 and 4.2).
//!
//! * [`patch`]: toroidal patches (revolved profile arcs and segments);
//! * [`patch_distance`]: the exact distance between two patches;
//! * [`planar`], [`sweep`]: the planar and one-dimensional kernels it uses.

pub mod patch;
pub mod patch_distance;
pub mod planar;
pub mod sweep;

pub use patch::{Patch, ProfileArc};
pub use patch_distance::{patch_distance, PatchDistance};

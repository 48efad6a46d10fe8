//! Circle-level solvers of the patch distance (paper sections 3.2, 3.3 and Appendix A): the
//! angles along one circle where a distance to a surface of revolution is critical or meets
//! a level, and the angles of two major circles where a common normal can lie.
//!
//! **What this level decides.** Candidate angles, never distances: [`radial_field`] (fields
//! `a rho + b rho^2 + c1 z + c2 z^2` along a circle: distance to a profile circle's centre or
//! a meridian line, bracketed and bisected), [`meridian_line`] (the same for a cone's line
//! field, as polynomial roots), [`common_normals`] (binormals of two circles: torus/torus
//! interior normals and circle/torus critical angles) and [`normal_range`] (the Gauss-map
//! restriction of the major-circle angles). Callers turn every angle into two points on the
//! patches and measure them, so extra angles are harmless and none may be lost.
//!
//! **What it may call.** [`crate::circle`] (binormals and circle minima),
//! [`crate::poly`] (Bernstein root finding) and the patches of [`crate::bvh`].

pub mod common_normals;
pub mod meridian_line;
pub mod normal_range;
pub mod radial_field;

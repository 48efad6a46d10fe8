//! Lower bounds between bounding volumes: the solid tori of disks, bounding spheres,
//! spherical shells, height slabs ([`node_pair`], paper section 4.2), convex hulls of
//! parallels ([`mod@hull_bound`], iterated on their Minkowski difference, with the simplex step
//! of `crate::query::simplex`) and the support functions of patch sectors ([`sector`]).
//!
//! **What this level decides.** A valid lower bound for everything inside two volumes,
//! whatever they hold: the traversal uses them as node keys, the leaf stages for pieces and
//! sub-pieces, the exact kernel to skip a solve that cannot win. Every bound subtracts the
//! rounding slack of [`crate::tolerances::BOUND_SLACK`].
//!
//! **What it may call.** [`super::angles`] (a parallel as a circle in space),
//! [`crate::circle`] (circle/circle minima) and the disks, pieces and hulls of
//! [`crate::bvh`].

pub mod hull_bound;
pub mod node_pair;
pub mod sector;

pub use hull_bound::{hull_bound, hull_bound_until};
pub use node_pair::{node_pair_bound, BoundKind};

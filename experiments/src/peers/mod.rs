//! The peers of the `peers` benchmark beside FCL (`crate::baseline_mesh`): coal 3 in a process
//! of its own ([`coal`]), parry3d in this one ([`parry`]), and the convex solids of revolution
//! as the exact primitives both know ([`convex`]).

pub mod coal;
pub mod convex;
pub mod parry;

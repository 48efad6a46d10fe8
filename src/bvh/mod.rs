//! The solid's bounding-volume hierarchy (paper section 4.1): the profile's biarcs revolved
//! into toroidal patches, and a binary tree over them whose every node holds a disk of the
//! (rho, z) half-plane (revolved: a solid torus) and, below the upper level, a convex hull of
//! its fat biarc.
//!
//! **What this level decides.** The shape of everything the query searches: which pieces
//! (arcs and segments, [`patch`]), which disks and hulls bound them ([`hull`],
//! [`crate::biarc::Disk`]), how the nodes nest ([`tree`]), whether the solid is a ball or a
//! solid torus answered in closed form ([`offset_solid`]), which points lie inside it
//! ([`containment`]) and which ball or solid torus lies deep inside it ([`inscribed`], kept in the tree as a
//! [`deep_interior`]). It
//! holds no pose: a tree lives in its solid's own frame.
//!
//! **What it may call.** Only the levels below it: [`crate::biarc`] (the trees it copies),
//! [`crate::profile`], [`crate::num`] and [`crate::tolerances`]. The solid
//! ([`crate::solid`]) holds a tree; the query ([`crate::query`]) reads trees and poses them.
//! Data flows one way: profile -> biarc -> bvh -> solid -> query.

pub mod containment;
pub mod convex;
pub mod deep_interior;
pub mod descent;
pub mod hull;
pub mod inscribed;
pub mod offset_solid;
pub mod patch;
pub mod tree;

pub use patch::{Patch, ProfileArc};
pub use tree::QueryTree;

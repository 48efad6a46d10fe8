//! A posed solid of revolution: a shared bounding hierarchy, optionally the exact profile,
//! and a rigid pose.
//!
//! Pose convention: a point `x` of the solid's own frame (axis of revolution =
//! local z axis) is at `R x + t` in the world frame, `R` a unit quaternion. For a pair of
//! solids the relative pose `pos_ab = pose_a^-1 * pose_b` places B in A's frame.

use crate::biarc::{BiarcTree, TreeError};
use crate::bvh::convex::ConvexHullData;
use crate::bvh::QueryTree;
use crate::profile::Profile;
use nalgebra::{Isometry3, Point3};
use std::sync::Arc;

/// A solid of revolution placed in the world.
#[derive(Debug, Clone)]
pub struct Solid {
    /// Bounding hierarchy of the profile (shared between instances of the same shape).
    pub tree: Arc<QueryTree>,
    /// The exact profile, used for refinement on the original surfaces.
    pub profile: Option<Arc<Profile>>,
    /// Local frame to world.
    pub pose: Isometry3<f64>,
}

impl Solid {
    /// A solid from a tree and an optional exact profile, at the identity pose.
    pub fn new(tree: Arc<QueryTree>, profile: Option<Arc<Profile>>) -> Solid {
        Solid {
            tree,
            profile,
            pose: Isometry3::identity(),
        }
    }

    /// A solid from an exact profile: builds the biarc tree with bound `eps` (paper 4.1),
    /// and certifies convexity for the convex fast path.
    pub fn from_profile(profile: Arc<Profile>, eps: f64) -> Result<Solid, TreeError> {
        let bt = BiarcTree::build(&profile, eps)?;
        let mut tree = QueryTree::from_biarc_tree(&bt, profile.kind());
        tree.convex = ConvexHullData::certify(&profile, &tree);
        Ok(Solid::new(Arc::new(tree), Some(profile)))
    }

    /// The same shape at another pose (the tree is shared, not copied).
    pub fn with_pose(&self, pose: Isometry3<f64>) -> Solid {
        Solid {
            tree: Arc::clone(&self.tree),
            profile: self.profile.clone(),
            pose,
        }
    }

    /// Pose of `other` in this solid's frame.
    pub fn relative_pose(&self, other: &Solid) -> Isometry3<f64> {
        self.pose.inverse() * other.pose
    }

    /// World point of a local point.
    pub fn to_world(&self, p: &Point3<f64>) -> Point3<f64> {
        self.pose * p
    }
}

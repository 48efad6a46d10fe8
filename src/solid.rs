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

/// Share of the requested bound `eps` a leaf of a solid's tree may take.
///
/// A leaf pair's own interval is `2 (e_a + e_b)` wide (the patches' distance, minus and plus
/// the leaves' bounds `e`), and the default query width is `eps_a + eps_b`
/// ([`crate::query::Tolerance::Trees`]). With leaves at the full `eps` a leaf pair holding
/// the minimum fits that width only once its patch distance is known exactly, so every
/// such pair near the minimum went to the exact solve (degree-8 boundary solves), and so
/// did its neighbours within `e`. B-spline profiles met this at coarse eps, where a leaf's
/// bound is close to `eps` (`cup_ff`'s largest leaf at eps 1e-3: 0.93 eps), and a query
/// at 1e-3 cost more than one at 1e-4. At half of `eps`, the stage-1 bounds settle the
/// pair. Measured (`docs/performance.md`, 2026-11-27): pawn_ff-cup_ff medians at eps
/// 1e-3 / 1e-4 64 / 42 -> 29 / 32 us; a quarter gives the same.
pub const LEAF_EPS_SHARE: f64 = 0.5;

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

    /// A solid from an exact profile for the requested bound `eps` (paper 4.1): its biarc
    /// tree's leaves are built to [`LEAF_EPS_SHARE`] of `eps` (no finer than the profile
    /// allows, [`BiarcTree::min_eps`]), its [`QueryTree::target_eps`] is `eps` (the default
    /// query width `eps_a + eps_b`), and convexity is certified for the convex fast path.
    ///
    /// # Errors
    /// [`TreeError`] naming the requested `eps` when it is out of range, or the profile's
    /// problem when a spiral cannot be fitted.
    pub fn from_profile(profile: Arc<Profile>, eps: f64) -> Result<Solid, TreeError> {
        BiarcTree::check_eps(&profile, eps)?;
        let leaf_eps = (LEAF_EPS_SHARE * eps).max(BiarcTree::min_eps(&profile));
        let bt = BiarcTree::build_merged(&profile, leaf_eps)?;
        let mut tree = QueryTree::from_biarc_tree(&bt, profile.kind());
        tree.target_eps = tree.target_eps.max(eps);
        tree.convex = ConvexHullData::certify(&profile, &tree);
        // Part of the build, not of the first query that needs it (overlap certificates).
        tree.deep_interior();
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

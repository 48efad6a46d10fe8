//! The distance's derivative with respect to B's pose, from a query's witness pair.
//!
//! Where the closest pair `(a, b)` of two separated solids is unique, the distance is
//! differentiable in B's pose: moving B by a small translation `dt` moves `b` by `dt`, and
//! turning B by a small rotation vector `dr` about its frame origin `o_B` moves `b` by
//! `dr x (b - o_B)`; the distance changes by `n . db` (first variation of `|b - a|`, the
//! surfaces' normals at a closest pair being parallel to `n`), so
//!
//! `dd/dt = n`, `dd/dr = (b - o_B) x n`, `n = (b - a) / |b - a|`.
//!
//! What the library can decide: the query certifies separation (`lower > 0`), not that the
//! closest pair is unique. So [`Distance::gradient`] answers only for certified separated
//! results, and its value is the gradient of the distance between the *witness* points.
//! Where the closest pair is unique and the witness points are a closest pair (refined on
//! the exact surfaces, [`crate::query::QueryOptions::refine`]) it is the distance's
//! gradient; where several pairs are closest the distance is not differentiable, and it is
//! one element of the superdifferential: `d(B moved) <= d + n . db + O(|db|^2)` still holds
//! for the witness pair. Unrefined witness points lie on the approximating surfaces and
//! tilt `n` by up to about `sqrt(w / rho)` (`w` the interval's width, `rho` the smaller
//! curvature radius at the closest points).

use super::distance::Distance;
use nalgebra::{Point3, Vector3};

/// Derivatives of the distance with respect to B's pose (world frame, see the module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gradient {
    /// Unit normal `n = (point_b - point_a) / |point_b - point_a|`.
    pub normal: Vector3<f64>,
    /// Derivative with respect to B's translation (`= normal`).
    pub translation: Vector3<f64>,
    /// Derivative with respect to a rotation vector of B about its frame origin.
    pub rotation: Vector3<f64>,
}

impl Distance {
    /// The gradient with respect to B's pose, B's frame origin at `origin_b` (the
    /// translation of B's pose, in the frame of the points); `None` unless the solids are
    /// certified apart (`lower > 0`, no overlap) with distinct witness points.
    pub fn gradient(&self, origin_b: &Point3<f64>) -> Option<Gradient> {
        if self.overlap || self.lower.is_nan() || self.lower <= 0.0 {
            return None;
        }
        let gap = self.point_b - self.point_a;
        let len = gap.norm();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let normal = gap / len;
        Some(Gradient {
            normal,
            translation: normal,
            rotation: (self.point_b - origin_b).cross(&normal),
        })
    }
}

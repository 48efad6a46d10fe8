//! The nearest point of a planar curve to a point of the (rho, z) half-plane: the one
//! capability the profile's piece types share (as kurbo's `ParamCurveNearest`).
//!
//! The pieces answer it in the form that suits them: a biarc's arc by its start, tangent and
//! signed curvature, without its centre ([`crate::biarc::Arc`], exact as the curvature goes
//! to 0); a query tree's piece by its centre and angles ([`crate::bvh::ProfileArc`]); the
//! convex path's piece by precomputed end directions, without `atan2`
//! ([`crate::bvh::convex::MeridianPiece`]). The tree's descent for the nearest point of a
//! whole chain ([`crate::bvh::descent`]) takes any of them.

use nalgebra::Point2;

/// A planar curve (closed point set) that can give its point nearest to a given point.
pub trait NearestPoint {
    /// The distance from `m` to the curve and the curve's point at that distance (one of
    /// them when several are equally near).
    fn nearest(&self, m: Point2<f64>) -> (f64, Point2<f64>);

    /// The distance from `m` to the curve; a piece type may compute it without the point.
    fn distance_to(&self, m: Point2<f64>) -> f64 {
        self.nearest(m).0
    }
}

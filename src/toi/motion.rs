//! Interpolated rigid motion over `t in [0, 1]`: the motion FCL calls "interpolated"
//! (Johnson and Cohen's conservative advancement needs nothing more than a bound on its
//! speed, [`super::speed`]).
//!
//! The frame origin moves with the constant linear velocity `v = p1 - p0`; the frame turns
//! with the constant angular velocity `w` (world frame) of the shortest arc from the start
//! quaternion `q0` to the end quaternion `q1`: `q1 q0^-1 = exp(w / 2)` with the rotation
//! angle `|w|` in `[0, pi]` (the quaternion is negated first when its scalar part is
//! negative; at exactly half a turn either direction is shortest and the one with the
//! positive vector part is taken). So
//!
//! `pose(t) = (exp(t w) q0, p0 + t v)`.
//!
//! The motion is *defined* by the floating-point `q0, p0, w, v` this module computes;
//! `pose(1)` equals the requested end pose up to rounding. Evaluating `pose(t)` rounds too:
//! [`MOTION_ROUNDING_REL`] bounds how far the computed pose places a point from where the
//! motion places it.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

/// Bound on the displacement of a point of a solid between the computed `pose(t)` and the
/// exact motion, relative to `1 + |p(t)| + r` (`r` the point's distance from the frame
/// origin). Where the value comes from: `pose(t)` takes about 60 floating-point operations
/// on quantities of magnitude at most `pi` (the angle), 1 (unit quaternions) or `|p0| +
/// |p1|` (the translation), each off by at most one unit roundoff `1.1e-16` of its
/// magnitude: `60 x 1.1e-16 = 6.7e-15`; applying the rotation to a point adds the
/// query's own pose rounding, which the query's slack covers. `1e-13` keeps a factor 15 of
/// margin.
pub const MOTION_ROUNDING_REL: f64 = 1e-13;

/// Why a motion cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// A start or end pose has a NaN or infinite component.
    #[error("{which} pose of the motion is not finite")]
    NonFinite { which: &'static str },
}

/// A rigid motion from a start pose to an end pose over `t in [0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    start: Isometry3<f64>,
    /// Linear velocity of the frame origin (world frame, per unit of t).
    velocity: Vector3<f64>,
    /// Angular velocity (world frame, radians per unit of t), `|w| <= pi`.
    angular: Vector3<f64>,
}

fn finite(p: &Isometry3<f64>) -> bool {
    p.translation.vector.iter().all(|x| x.is_finite())
        && p.rotation.coords.iter().all(|x| x.is_finite())
}

impl Motion {
    /// The interpolated motion from `start` to `end` (see the module doc).
    pub fn new(start: Isometry3<f64>, end: Isometry3<f64>) -> Result<Motion, MotionError> {
        if !finite(&start) {
            return Err(MotionError::NonFinite { which: "start" });
        }
        if !finite(&end) {
            return Err(MotionError::NonFinite { which: "end" });
        }
        let mut q = (end.rotation * start.rotation.inverse()).into_inner();
        if q.w < 0.0
            || (q.w == 0.0
                && q.imag()
                    .iter()
                    .find(|x| **x != 0.0)
                    .is_some_and(|x| *x < 0.0))
        {
            q = -q;
        }
        let s = q.imag().norm();
        let angular = if s > 0.0 {
            q.imag() * (2.0 * s.atan2(q.w) / s)
        } else {
            Vector3::zeros()
        };
        Ok(Motion {
            start,
            velocity: end.translation.vector - start.translation.vector,
            angular,
        })
    }

    /// A solid that does not move.
    pub fn fixed(pose: Isometry3<f64>) -> Result<Motion, MotionError> {
        Motion::new(pose, pose)
    }

    /// The pose at time `t` (any finite `t`; the motion is meant for `[0, 1]`).
    pub fn pose_at(&self, t: f64) -> Isometry3<f64> {
        let rotation = UnitQuaternion::from_scaled_axis(self.angular * t) * self.start.rotation;
        let translation = self.start.translation.vector + self.velocity * t;
        Isometry3::from_parts(Translation3::from(translation), rotation)
    }

    /// The frame origin at time `t`.
    pub fn origin_at(&self, t: f64) -> Point3<f64> {
        Point3::from(self.start.translation.vector + self.velocity * t)
    }

    /// Linear velocity of the frame origin (world frame, per unit of t).
    pub fn velocity(&self) -> Vector3<f64> {
        self.velocity
    }

    /// Angular velocity (world frame, radians per unit of t; its norm is the rotation
    /// angle from start to end, at most pi).
    pub fn angular_velocity(&self) -> Vector3<f64> {
        self.angular
    }

    /// The start pose.
    pub fn start(&self) -> Isometry3<f64> {
        self.start
    }

    /// Largest distance of the frame origin from the world origin over `[t0, 1]` (the
    /// origin moves on a segment, so the largest is at an end).
    pub fn max_origin_norm(&self, t0: f64) -> f64 {
        self.origin_at(t0)
            .coords
            .norm()
            .max(self.origin_at(1.0).coords.norm())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn pose(t: [f64; 3], axis: Vector3<f64>, angle: f64) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::new(t[0], t[1], t[2]),
            UnitQuaternion::from_scaled_axis(axis * angle),
        )
    }

    #[test]
    fn ends_and_midpoint_match_slerp() {
        let a = pose(
            [1.0, -2.0, 0.5],
            Vector3::new(0.3, 0.4, 0.5).normalize(),
            0.7,
        );
        let b = pose(
            [-3.0, 1.0, 2.0],
            Vector3::new(-1.0, 0.2, 0.1).normalize(),
            2.9,
        );
        let m = Motion::new(a, b).unwrap();
        let e0 = m.pose_at(0.0);
        let e1 = m.pose_at(1.0);
        assert!((e0.rotation.angle_to(&a.rotation)) < 1e-14);
        assert!((e1.rotation.angle_to(&b.rotation)) < 1e-12);
        assert!((e1.translation.vector - b.translation.vector).norm() < 1e-14);
        // nalgebra's slerp (independent formula) along the shortest arc.
        for t in [0.25, 0.5, 0.9] {
            let s = a.rotation.slerp(&b.rotation, t);
            assert!(m.pose_at(t).rotation.angle_to(&s) < 1e-12, "t = {t}");
        }
        assert!(m.angular_velocity().norm() <= PI);
    }

    #[test]
    fn shortest_arc_for_a_negated_end_quaternion() {
        let a = pose([0.0; 3], Vector3::z(), 0.0);
        let q = UnitQuaternion::from_scaled_axis(Vector3::z() * 0.5);
        let neg = UnitQuaternion::new_unchecked(-q.into_inner());
        let m = Motion::new(a, Isometry3::from_parts(Translation3::identity(), neg)).unwrap();
        assert!((m.angular_velocity() - Vector3::z() * 0.5).norm() < 1e-15);
    }

    #[test]
    fn rejects_non_finite_poses() {
        let mut bad = Isometry3::identity();
        bad.translation.vector.x = f64::NAN;
        assert_eq!(
            Motion::new(Isometry3::identity(), bad),
            Err(MotionError::NonFinite { which: "end" })
        );
    }
}

//! A proved bound on how fast the distance between two moving solids can change.
//!
//! Let solid X move by `pose_X(t) = (R_X(t), p_X(t))` with constant linear velocity `v_X`
//! of its origin and constant angular velocity `w_X` ([`super::motion`]), and let `r_X`
//! bound the distance of every point of X from X's frame origin (the rotation centre).
//!
//! *World frame.* A point `x` of X is at `R_X x + p_X` with velocity
//! `v_X + w_X x (R_X x)`, of norm at most `|v_X| + |w_X| r_X`. For any pair of points
//! `a in A`, `b in B`, `|d/dt |b - a|| <= |b' - a'|`, so
//! `L_world = |v_A| + |w_A| r_A + |v_B| + |w_B| r_B`.
//!
//! *A's frame.* There A is at rest and a point `w = R_B x + p_B` of B is at
//! `y = R_A^T (w - p_A)`. With `R_A' = [w_A]x R_A`,
//! `y' = R_A^T (w' - v_A - w_A x (w - p_A))`, and writing `w - p_A = (w - p_B) + (p_B - p_A)`,
//! `|y'| = |(v_B - v_A) - w_A x (p_B - p_A) + (w_B - w_A) x (w - p_B)|
//!       <= |v_rel - w_A x (p_B - p_A)| + |w_B - w_A| r_B`, with `v_rel = v_B - v_A`.
//! `p_B - p_A` is affine in t, so the first term is the norm of an affine function of t,
//! convex, and its largest value on `[t0, 1]` is at `t0` or at 1. That gives `L_A(t0)`; the
//! same argument in B's frame gives `L_B(t0)` (roles swapped). When only one solid turns,
//! about its own origin, this is `|v_rel| + |w| r` in the turning solid's frame.
//!
//! The distance `d(t)` between the solids is the infimum over pairs of points of their
//! distance, each pair's distance `L`-Lipschitz on `[t0, 1]` for each of the three bounds,
//! so `d` is Lipschitz with `L = min(L_world, L_A, L_B)` there:
//! `d(s) >= d(t0) - L (s - t0)`. That is the step of conservative advancement
//! ([`super::advance`]).

use super::motion::Motion;

/// Relative widening of the computed speed bound to cover its rounding: each of the three
/// bounds takes about 30 floating-point operations on nonnegative terms, each off by at
/// most a unit roundoff (`1.1e-16`); `30 x 1.1e-16 = 3.3e-15`, and `1e-12` leaves a factor
/// of 300.
pub const SPEED_ROUNDING_REL: f64 = 1e-12;

/// A bound on `|d'(t)|` for `t in [t0, 1]` (see the module doc). `ra`, `rb`: bounds on the
/// distance of any point of A (B) from its frame origin.
pub fn speed_bound(ma: &Motion, ra: f64, mb: &Motion, rb: f64, t0: f64) -> f64 {
    let (va, wa) = (ma.velocity(), ma.angular_velocity());
    let (vb, wb) = (mb.velocity(), mb.angular_velocity());
    let world = va.norm() + wa.norm() * ra + vb.norm() + wb.norm() * rb;
    let gap = |t: f64| mb.origin_at(t) - ma.origin_at(t);
    let in_a = |t: f64| ((vb - va) - wa.cross(&gap(t))).norm();
    let in_b = |t: f64| ((va - vb) + wb.cross(&gap(t))).norm();
    let frame_a = in_a(t0).max(in_a(1.0)) + (wb - wa).norm() * rb;
    let frame_b = in_b(t0).max(in_b(1.0)) + (wa - wb).norm() * ra;
    world.min(frame_a).min(frame_b) * (1.0 + SPEED_ROUNDING_REL)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::SplitMix64;
    use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

    fn random_pose(rng: &mut SplitMix64) -> Isometry3<f64> {
        let t = Translation3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        let r = UnitQuaternion::from_scaled_axis(rng.unit() * rng.range(0.0, 3.0));
        Isometry3::from_parts(t, r)
    }

    /// Finite differences of the distance between random pairs of points (one on a sphere
    /// of radius r about each origin) along random motions never exceed the bound.
    #[test]
    fn bounds_point_pair_speeds() {
        let mut rng = SplitMix64(0x5eed_0032);
        let (ra, rb) = (0.7, 1.3);
        for _ in 0..200 {
            let ma = Motion::new(random_pose(&mut rng), random_pose(&mut rng)).unwrap();
            let mb = Motion::new(random_pose(&mut rng), random_pose(&mut rng)).unwrap();
            let t0 = rng.range(0.0, 0.9);
            let bound = speed_bound(&ma, ra, &mb, rb, t0);
            let xa = Point3::from(rng.unit() * ra);
            let xb = Point3::from(rng.unit() * rb);
            let h = 1e-6;
            for k in 0..20 {
                let t = t0 + (1.0 - t0 - h) * f64::from(k) / 19.0;
                let d = |t: f64| (mb.pose_at(t) * xb - ma.pose_at(t) * xa).norm();
                let rate = (d(t + h) - d(t)).abs() / h;
                assert!(
                    rate <= bound * (1.0 + 1e-6) + 1e-8,
                    "rate {rate} > bound {bound}"
                );
            }
        }
    }

    #[test]
    fn rotation_about_own_origin_is_omega_r() {
        let fixed = Motion::fixed(Isometry3::translation(5.0, 0.0, 0.0)).unwrap();
        let turn = Motion::new(
            Isometry3::identity(),
            Isometry3::rotation(Vector3::z() * 1.5),
        )
        .unwrap();
        let b = speed_bound(&fixed, 1.0, &turn, 2.0, 0.0);
        assert!((b - 3.0).abs() < 1e-11, "{b}");
    }
}

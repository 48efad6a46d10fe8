//! Pose tracks of kinematic bodies: keyframes (linear, or a smooth C1 Catmull-Rom spline
//! for the translation, spherical linear interpolation for the rotation) and a seeded smooth
//! random motion (a few sinusoids per coordinate, C-infinity, bounded by its amplitude).

use crate::format::Track;
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;
use std::f64::consts::TAU;

/// The pose of a track at `time`; `base` is the body's pose (the random motion moves about
/// it). Keyframe tracks hold their first pose before the first key and the last after it.
pub fn pose_at(track: &Track, base: &Isometry3<f64>, time: f64) -> Isometry3<f64> {
    match track {
        Track::Keyframes {
            times,
            poses,
            smooth,
        } => keyframe_pose(times, poses, *smooth, time),
        Track::Random {
            seed,
            amplitude,
            angle,
            period,
        } => random_pose(*seed, *amplitude, *angle, *period, base, time),
    }
}

fn keyframe_pose(
    times: &[f64],
    poses: &[Isometry3<f64>],
    smooth: bool,
    time: f64,
) -> Isometry3<f64> {
    let n = times.len();
    if time <= times[0] {
        return poses[0];
    }
    if time >= times[n - 1] {
        return poses[n - 1];
    }
    let k = times.partition_point(|&t| t <= time) - 1;
    let (t0, t1) = (times[k], times[k + 1]);
    let s = (time - t0) / (t1 - t0);
    let p = |i: usize| poses[i].translation.vector;
    let translation = if smooth {
        // Catmull-Rom with tangents from the neighbouring keys (non-uniform times), the
        // end tangents one-sided: C1 through every keyframe.
        let tangent = |i: usize| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (p(b) - p(a)) / (times[b] - times[a])
        };
        let h = t1 - t0;
        let (m0, m1) = (tangent(k) * h, tangent(k + 1) * h);
        let (s2, s3) = (s * s, s * s * s);
        p(k) * (2.0 * s3 - 3.0 * s2 + 1.0)
            + m0 * (s3 - 2.0 * s2 + s)
            + p(k + 1) * (-2.0 * s3 + 3.0 * s2)
            + m1 * (s3 - s2)
    } else {
        p(k).lerp(&p(k + 1), s)
    };
    let rotation = poses[k].rotation.slerp(&poses[k + 1].rotation, s);
    Isometry3::from_parts(Translation3::from(translation), rotation)
}

/// Harmonics per coordinate of the random motion (periods `period / 1, / 2, / 3`).
const HARMONICS: usize = 3;

fn random_pose(
    seed: u64,
    amplitude: f64,
    angle: f64,
    period: f64,
    base: &Isometry3<f64>,
    time: f64,
) -> Isometry3<f64> {
    // The motion is a function of the seed alone: the shared generator's stream
    // (`revdist::rng`), not a crate's whose stream may change with its version.
    let mut rng = SplitMix64(seed);
    // Each coordinate: sum over harmonics of weight * sin(2 pi h t / period + phase), the
    // weights summing to 1, so |offset| <= amplitude per coordinate.
    let wave = |rng: &mut SplitMix64| {
        let mut v = 0.0;
        let mut total = 0.0;
        let mut terms = [(0.0, 0.0); HARMONICS];
        for (h, term) in terms.iter_mut().enumerate() {
            let w = 1.0 / (h + 1) as f64;
            *term = (w, TAU * rng.next_f64());
            total += w;
        }
        for (h, (w, phase)) in terms.iter().enumerate() {
            v += w / total * (TAU * (h + 1) as f64 * time / period + phase).sin();
        }
        v
    };
    let offset = Vector3::new(wave(&mut rng), wave(&mut rng), wave(&mut rng)) * amplitude;
    let axis = Vector3::new(
        rng.next_f64() - 0.5,
        rng.next_f64() - 0.5,
        rng.next_f64() - 0.5,
    );
    let turn = angle * wave(&mut rng);
    let rotation = match Unit::try_new(axis, 1e-9) {
        Some(a) => UnitQuaternion::from_axis_angle(&a, turn),
        None => UnitQuaternion::identity(),
    };
    Isometry3::from_parts(
        Translation3::from(base.translation.vector + offset),
        rotation * base.rotation,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(x: f64) -> Isometry3<f64> {
        Isometry3::translation(x, 0.0, 0.0)
    }

    #[test]
    fn keyframes_pass_through_their_poses_and_hold_at_the_ends() {
        for smooth in [false, true] {
            let track = Track::Keyframes {
                times: vec![0.0, 1.0, 3.0],
                poses: vec![key(0.0), key(1.0), key(-1.0)],
                smooth,
            };
            let id = Isometry3::identity();
            for (t, x) in [
                (-1.0, 0.0),
                (0.0, 0.0),
                (1.0, 1.0),
                (3.0, -1.0),
                (9.0, -1.0),
            ] {
                let p = pose_at(&track, &id, t);
                assert!((p.translation.vector.x - x).abs() < 1e-12, "t {t}");
            }
            // Linear halfway point.
            if !smooth {
                let p = pose_at(&track, &id, 0.5);
                assert!((p.translation.vector.x - 0.5).abs() < 1e-12);
            }
        }
    }

    /// The smooth track is continuous with a continuous first derivative at a keyframe.
    #[test]
    fn smooth_keyframes_are_c1() {
        let track = Track::Keyframes {
            times: vec![0.0, 1.0, 2.0],
            poses: vec![key(0.0), key(1.0), key(0.0)],
            smooth: true,
        };
        let id = Isometry3::identity();
        let x = |t: f64| pose_at(&track, &id, t).translation.vector.x;
        let h = 1e-6;
        let left = (x(1.0) - x(1.0 - h)) / h;
        let right = (x(1.0 + h) - x(1.0)) / h;
        assert!((left - right).abs() < 1e-4, "{left} vs {right}");
    }

    /// The random motion stays within its amplitude, is seeded (same seed, same path),
    /// and moves continuously (small steps for small time steps).
    #[test]
    fn random_motion_is_bounded_seeded_and_continuous() {
        let track = Track::Random {
            seed: 5,
            amplitude: 0.3,
            angle: 0.4,
            period: 2.0,
        };
        let base = Isometry3::translation(1.0, 2.0, 3.0);
        let mut prev = pose_at(&track, &base, 0.0);
        for i in 1..=1000 {
            let t = i as f64 * 0.004;
            let p = pose_at(&track, &base, t);
            let off = p.translation.vector - base.translation.vector;
            assert!(off.amax() <= 0.3 + 1e-12);
            assert!(p.rotation.angle() <= 0.4 + 1e-12);
            assert!((p.translation.vector - prev.translation.vector).norm() < 0.02);
            assert_eq!(p, pose_at(&track, &base, t));
            prev = p;
        }
    }
}

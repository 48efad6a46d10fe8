//! The distance's gradient with respect to B's pose (`Distance::gradient`) against central
//! finite differences of the certified distance at random separated poses.
//!
//! Tolerance: with step `h` along a unit direction `e` (a translation, or a rotation about
//! B's origin), the true distances at `+h` and `-h` lie in the queries' intervals
//! `[l+, u+]`, `[l-, u-]`, so the true central difference lies in
//! `[(l+ - u-) / 2h, (u+ - l-) / 2h]`; it differs from the derivative by `h^2 d''' / 6`,
//! and for the models' curvature radii (>= 0.05) at gaps >= 0.2 the third derivative of the
//! distance along a unit motion stays below `1 / 0.05^2 = 400` (each derivative of the
//! distance to a surface of curvature radius `rho` gains at most a factor `1 / rho` here),
//! so `h^2 d''' / 6 <= 400 h^2 / 6`. The witness points are refined on the exact surfaces;
//! the test asserts the gradient's component within both allowances.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::models::model;
use revdist::query::{try_distance, QueryOptions, Tolerance};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::sync::Arc;

/// Bound on the third derivative of the distance along a unit motion (see the module doc).
const THIRD_DERIVATIVE: f64 = 400.0;
/// Finite-difference step.
const STEP: f64 = 1e-3;
/// Trees' eps.
const EPS: f64 = 1e-6;

/// A random unit vector (rejection sampling in the unit ball's shell above 0.1).
fn unit(rng: &mut SplitMix64) -> Vector3<f64> {
    loop {
        let v = Vector3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 2.0
            - Vector3::repeat(1.0);
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

fn solid(name: &str) -> Solid {
    Solid::from_profile(Arc::new(model(name).unwrap()), EPS).unwrap()
}

#[test]
fn gradient_matches_central_differences() {
    let opts = QueryOptions {
        tolerance: Tolerance::Absolute(0.0),
        refine: true,
        ..QueryOptions::default()
    };
    let names = ["pawn", "cup", "capsule", "cone", "ring"];
    let solids: Vec<Solid> = names.iter().map(|n| solid(n)).collect();
    let mut rng = SplitMix64(0x32_6ad1);
    let mut checked = 0;
    for k in 0..12 {
        let a = &solids[k % names.len()];
        let b0 = &solids[(k * 3 + 1) % names.len()];
        let rot = UnitQuaternion::from_scaled_axis(unit(&mut rng) * (3.0 * rng.next_f64()));
        // Push B out along a random direction until the certified gap is in [0.2, 1].
        let dir = unit(&mut rng);
        let mut s = 0.0;
        let mut found = None;
        while s < 6.0 {
            let pose = Isometry3::from_parts(Translation3::from(dir * s), rot);
            let b = b0.with_pose(pose);
            let d = try_distance(a, &b, &opts).unwrap();
            if d.lower >= 0.2 {
                found = (d.upper <= 1.0).then_some((pose, d));
                break;
            }
            s += 0.1;
        }
        let Some((pose, d)) = found else { continue };
        let origin = Point3::from(pose.translation.vector);
        let g = d.gradient(&origin).expect("separated: a gradient");
        assert!((g.normal.norm() - 1.0).abs() < 1e-12);
        for axis in [Vector3::x(), Vector3::y(), Vector3::z(), unit(&mut rng)] {
            for rotation in [false, true] {
                let moved = |h: f64| {
                    let p = if rotation {
                        let r = UnitQuaternion::from_scaled_axis(axis * h);
                        Isometry3::from_parts(pose.translation, r * pose.rotation)
                    } else {
                        Isometry3::from_parts(
                            Translation3::from(pose.translation.vector + axis * h),
                            pose.rotation,
                        )
                    };
                    try_distance(a, &b0.with_pose(p), &opts).unwrap()
                };
                let (p, m) = (moved(STEP), moved(-STEP));
                let lo = (p.lower - m.upper) / (2.0 * STEP);
                let hi = (p.upper - m.lower) / (2.0 * STEP);
                let curve = THIRD_DERIVATIVE * STEP * STEP / 6.0;
                let want = if rotation { g.rotation } else { g.translation }.dot(&axis);
                assert!(
                    lo - curve <= want && want <= hi + curve,
                    "pair {k} ({} / {}), rotation {rotation}: gradient {want} outside [{lo}, {hi}] +- {curve}",
                    names[k % names.len()],
                    names[(k * 3 + 1) % names.len()]
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} separated poses found");
}

#[test]
fn no_gradient_without_certified_separation() {
    let a = solid("sphere");
    let d = try_distance(
        &a,
        &a.with_pose(Isometry3::translation(0.5, 0.0, 0.0)),
        &QueryOptions::default(),
    )
    .unwrap();
    assert!(d.overlap);
    assert!(d.gradient(&Point3::new(0.5, 0.0, 0.0)).is_none());
}

//! The pruned searches of [`super`] against the flat loops they replace: the same samples,
//! tested one by one with the exact (uncapped) classification.

use super::super::deep_point::{deep_point, DeepPoint, Direction};
use super::*;
use crate::bvh::containment::point_in_solid;
use crate::models::model;
use crate::solid::Solid;
use crate::test_rng::SplitMix64;
use nalgebra::{Translation3, UnitQuaternion};
use std::sync::Arc;

fn solid(name: &str, eps: f64) -> Solid {
    Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap()
}

/// Exact signed depth (no cap).
fn exact_depth(outer: &QueryTree, x: &Point3<f64>) -> f64 {
    let c = point_in_solid(outer, x);
    if c.inside {
        c.margin
    } else {
        -c.margin
    }
}

/// The deepest of dense samples of `inner`'s approximating surface in `outer`: every patch
/// at 17 parameters and 192 angles (a lower estimate of the surface's deepest point).
fn dense_deepest(outer: &QueryTree, inner: &QueryTree, pos: &Isometry3<f64>) -> f64 {
    let mut best = f64::NEG_INFINITY;
    for p in &inner.patches {
        for i in 0..17 {
            let m = p.arc.point_at(i as f64 / 16.0);
            for k in 0..192 {
                let th = k as f64 * TAU / 192.0;
                best = best.max(exact_depth(outer, &(pos * lift_at(m, th))));
            }
        }
    }
    best
}

/// The branch and bound ([`deep_point`]) against dense sampling: every point it returns is
/// deeper than the threshold (exact classification), `Absent` only where no sample is, and
/// it finds a certificate wherever a sample clears the threshold by a margin.
#[test]
fn deep_point_search_agrees_with_dense_samples() {
    let pairs = [
        ("pawn", "cup"),
        ("bottle_ff", "cup_ff"),
        ("sphere", "table"),
    ];
    let mut rng = SplitMix64(27);
    let (mut found, mut absent, mut cases) = (0, 0, 0);
    for (a, b) in pairs {
        let (sa, sb) = (solid(a, 1e-3), solid(b, 1e-3));
        for _ in 0..6 {
            let pos = Isometry3::from_parts(
                Translation3::from(rng.unit() * rng.range(0.0, 1.0)),
                UnitQuaternion::from_scaled_axis(rng.unit() * rng.range(0.0, 3.0)),
            );
            let deepest = dense_deepest(&sa.tree, &sb.tree, &pos);
            for threshold in [1e-3, 2e-2, 0.2] {
                cases += 1;
                let dir = Direction {
                    outer: &sa.tree,
                    inner: &sb.tree,
                    pos: &pos,
                    threshold,
                };
                match deep_point(&[dir], 1 << 20) {
                    DeepPoint::Found { dir: 0, point } => {
                        found += 1;
                        assert!(exact_depth(&sa.tree, &point) > threshold, "{a}-{b}");
                    }
                    DeepPoint::Absent => {
                        absent += 1;
                        assert!(deepest <= threshold, "{a}-{b}: {deepest} > {threshold}");
                    }
                    // Only a surface whose deepest point is within rounding of the
                    // threshold may keep the search refining until its budget.
                    other => assert!(
                        (deepest - threshold).abs() < 1e-9,
                        "{a}-{b} {threshold}: {other:?} (deepest sample {deepest})"
                    ),
                }
            }
        }
    }
    // Both outcomes occur: the comparison can fail either way.
    assert!(
        found > 0 && absent > 0,
        "{found} found, {absent} absent of {cases}"
    );
}

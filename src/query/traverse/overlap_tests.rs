//! The pruned searches of [`super`] against the flat loops they replace: the same samples,
//! tested one by one with the exact (uncapped) classification.

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

/// The flat loop: every patch's ends and midpoint at every angle of [`thetas`].
fn flat_deepest(outer: &QueryTree, inner: &QueryTree, pos: &Isometry3<f64>) -> f64 {
    let mut best = f64::NEG_INFINITY;
    for m in surface_meridian_points(inner) {
        for th in thetas() {
            best = best.max(exact_depth(outer, &(pos * lift_at(m, th))));
        }
    }
    best
}

#[test]
fn surface_samples_through_the_tree_match_the_flat_loop() {
    let pairs = [
        ("pawn", "cup"),
        ("bottle_ff", "cup_ff"),
        ("sphere", "table"),
    ];
    let mut rng = SplitMix64(27);
    let mut found = 0;
    let mut cases = 0;
    for (a, b) in pairs {
        let (sa, sb) = (solid(a, 1e-3), solid(b, 1e-3));
        for _ in 0..12 {
            let pos = Isometry3::from_parts(
                Translation3::from(rng.unit() * rng.range(0.0, 1.0)),
                UnitQuaternion::from_scaled_axis(rng.unit() * rng.range(0.0, 3.0)),
            );
            let deepest = flat_deepest(&sa.tree, &sb.tree, &pos);
            for threshold in [1e-3, 2e-2, 0.2] {
                // Stay clear of ties within rounding of the threshold.
                if (deepest - threshold).abs() < 1e-9 {
                    continue;
                }
                cases += 1;
                let hit = thetas().find_map(|th| {
                    deep_surface_sample(&sa.tree, &sb.tree, &pos, sb.tree.root, th, threshold)
                });
                assert_eq!(hit.is_some(), deepest > threshold, "{a}-{b} {threshold}");
                if let Some(x) = hit {
                    found += 1;
                    assert!(exact_depth(&sa.tree, &x) > threshold);
                }
            }
        }
    }
    // Both outcomes occur: the comparison can fail either way.
    assert!(found > 0 && found < cases, "{found} of {cases}");
}

//! Distance queries on NURBS profiles (biarc trees with eps > 0) against the independent
//! dense-sampling reference of `tests/reference`: separated, nearly touching and
//! overlapping poses. Asserts the certified interval contains the reference (up to the
//! reference's own error) and the value is within the interval width of it.

mod reference;

use nalgebra::{Isometry3, Point2, Translation3, UnitQuaternion, Vector3};
use reference::{brackets, check_query, reference, ring_profile, Rng};
use revdist::nurbs::NurbsCurve;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;

fn p(x: f64, y: f64) -> Point2<f64> {
    Point2::new(x, y)
}

/// Vase: flat bottom, a cubic wall with a concave neck, flat top (open on the axis).
fn vase() -> Profile {
    let pieces = vec![
        NurbsCurve::line(p(0.0, 0.0), p(0.5, 0.0)).unwrap(),
        NurbsCurve::bezier(vec![p(0.5, 0.0), p(0.9, 0.4), p(0.1, 0.8), p(0.4, 1.2)]).unwrap(),
        NurbsCurve::line(p(0.4, 1.2), p(0.0, 1.2)).unwrap(),
    ];
    Profile::new("vase", pieces).unwrap()
}

fn ring() -> Profile {
    ring_profile(0.6, 0.0, 0.15)
}

fn check(a: &Solid, b: &Solid, label: &str) {
    if let Err(e) = check_query(a, b, &QueryOptions::default(), label) {
        panic!("{e}");
    }
}

fn pose(t: Vector3<f64>, r: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), r)
}

#[test]
fn vase_and_ring_random_poses() {
    let mut rng = Rng(5);
    let eps = 1e-3;
    let vase = Solid::from_profile(Arc::new(vase()), eps).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), eps).unwrap();
    for i in 0..8 {
        let (a, b) = if i % 2 == 0 {
            (&vase, &ring)
        } else {
            (&ring, &vase)
        };
        let t = Vector3::new(
            rng.f() * 2.4 - 1.2,
            rng.f() * 2.4 - 1.2,
            rng.f() * 2.4 - 0.6,
        );
        let b = b.with_pose(pose(t, rng.rotation()));
        check(a, &b, &format!("case {i}"));
    }
}

#[test]
fn ring_hanging_in_the_vase_neck() {
    // The ring's axis horizontal, its hole around the vase wall at the neck height.
    let eps = 1e-4;
    let vase = Solid::from_profile(Arc::new(vase()), eps).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), eps).unwrap();
    // The ring (hole radius 0.45) slid over the top (radius 0.4) onto the neck (radius
    // about 0.36 near z = 0.85), tilted and pushed sideways against the neck.
    for (k, (dx, tilt)) in [(0.0, 0.0), (0.05, 0.2), (0.08, 0.3), (0.09, 0.1)]
        .iter()
        .enumerate()
    {
        let rot = UnitQuaternion::from_scaled_axis(Vector3::y() * *tilt);
        let b = ring.with_pose(pose(Vector3::new(*dx, 0.0, 0.85), rot));
        check(&vase, &b, &format!("neck {k}"));
    }
}

/// Anytime queries: with a tiny budget the bounds are still certified, and wider.
#[test]
fn anytime_budget_keeps_bounds_certified() {
    let mut rng = Rng(8);
    let vase = Solid::from_profile(Arc::new(vase()), 1e-4).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), 1e-4).unwrap();
    for i in 0..12 {
        let t = rng.unit() * (0.6 + rng.f());
        let b = ring.with_pose(pose(t, rng.rotation()));
        let r = reference(
            vase.profile.as_deref().unwrap(),
            b.profile.as_deref().unwrap(),
            &vase.relative_pose(&b),
        );
        let full = distance(&vase, &b, &QueryOptions::default());
        for budget in [1, 3, 10] {
            let opts = QueryOptions {
                budget: revdist::query::Budget {
                    max_node_pairs: Some(budget),
                    max_time: None,
                },
                ..QueryOptions::default()
            };
            let d = distance(&vase, &b, &opts);
            assert!(d.stats.node_pairs <= budget, "case {i}: budget {budget}");
            assert!(
                brackets(&d, r.distance),
                "case {i} budget {budget}: {} outside [{}, {}]",
                r.distance,
                d.lower,
                d.upper
            );
            assert!(d.upper - d.lower >= full.upper - full.lower - 1e-15);
            if d.stats.budget_exhausted {
                assert!(d.stats.node_pairs == budget);
            }
        }
    }
}

/// Frame coherence: a moving sequence with a warm start gives certified results with
/// no more node pairs in total than cold queries.
#[test]
fn warm_start_sequence() {
    let vase = Solid::from_profile(Arc::new(vase()), 1e-4).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), 1e-4).unwrap();
    let mut cache = revdist::query::QueryCache::default();
    let (mut warm, mut cold) = (0, 0);
    for k in 0..30 {
        let s = k as f64 * 0.01;
        let b = ring.with_pose(pose(
            Vector3::new(1.2 - s, 0.1 * s, 0.4 + s),
            UnitQuaternion::from_scaled_axis(Vector3::new(s, 0.3, 0.0)),
        ));
        let dw = revdist::query::distance_cached(&vase, &b, &QueryOptions::default(), &mut cache);
        let dc = distance(&vase, &b, &QueryOptions::default());
        assert!(
            dw.lower <= dc.upper + 1e-12 && dc.lower <= dw.upper + 1e-12,
            "step {k}"
        );
        if k % 5 == 0 {
            // Warm and cold intervals both hold the reference.
            let r = reference(
                vase.profile.as_deref().unwrap(),
                ring.profile.as_deref().unwrap(),
                &vase.relative_pose(&b),
            );
            for (what, d) in [("warm", &dw), ("cold", &dc)] {
                assert!(
                    brackets(d, r.distance),
                    "step {k} {what}: reference {} outside [{}, {}]",
                    r.distance,
                    d.lower,
                    d.upper
                );
                assert!(
                    !d.overlap || r.distance == 0.0,
                    "step {k} {what}: overlap claimed at reference {}",
                    r.distance
                );
            }
        }
        warm += dw.stats.leaf_tests + dw.stats.bound_tests;
        cold += dc.stats.leaf_tests + dc.stats.bound_tests;
    }
    assert!(warm <= cold, "warm {warm} > cold {cold}");
}

/// Refinement on the exact surfaces: the value is accurate far below eps.
#[test]
fn refinement_is_accurate_below_eps() {
    let mut rng = Rng(9);
    let eps = 1e-2;
    let vase = Solid::from_profile(Arc::new(vase()), eps).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), eps).unwrap();
    let mut checked = 0;
    for i in 0..7 {
        let t = rng.unit() * 1.4;
        let b = ring.with_pose(pose(t, rng.rotation()));
        let r = reference(
            vase.profile.as_deref().unwrap(),
            b.profile.as_deref().unwrap(),
            &vase.relative_pose(&b),
        );
        if r.distance <= 1e-3 {
            continue;
        }
        let opts = QueryOptions {
            refine: true,
            ..QueryOptions::default()
        };
        let d = distance(&vase, &b, &opts);
        assert!(
            (d.value - r.distance).abs() <= 1e-7,
            "case {i}: refined {} vs reference {} (interval [{}, {}])",
            d.value,
            r.distance,
            d.lower,
            d.upper
        );
        assert!(brackets(&d, r.distance));
        checked += 1;
    }
    assert!(checked >= 3, "only {checked} separated cases");
}

/// A warm start only chooses the traversal's first leaf pair: from the best leaf pair of a
/// nearby pose, from a pair that is not a leaf pair, from indices outside the trees, or
/// from none, the surface bounds all hold the reference distance, and the invalid starts
/// give exactly the cold traversal (both dive).
#[test]
fn warm_starts_only_choose_the_first_leaf_pair() {
    use revdist::query::bound::BoundKind;
    use revdist::query::search::{traverse, Budget, TraversalOptions};
    let vase = Solid::from_profile(Arc::new(vase()), 1e-4).unwrap();
    let ring = Solid::from_profile(Arc::new(ring()), 1e-4).unwrap();
    let (ta, tb) = (&vase.tree, &ring.tree);
    let opts = TraversalOptions {
        tolerance: ta.target_eps + tb.target_eps,
        lower_floor: f64::NEG_INFINITY,
        budget: Budget::default(),
        bound: BoundKind::Torus,
    };
    let mut previous = None;
    for k in 0..12 {
        let s = k as f64 * 0.025;
        let b = ring.with_pose(pose(
            Vector3::new(1.2 - s, 0.1 * s, 0.4 + s),
            UnitQuaternion::from_scaled_axis(Vector3::new(s, 0.3, 0.0)),
        ));
        let pos = vase.relative_pose(&b);
        let truth = reference(
            vase.profile.as_deref().unwrap(),
            ring.profile.as_deref().unwrap(),
            &pos,
        )
        .distance;
        let cold = traverse(ta, tb, &pos, &opts, None);
        for (what, warm) in [
            ("previous best", previous),
            ("roots", Some((ta.root, tb.root))),
            ("outside", Some((u32::MAX, u32::MAX))),
        ] {
            let w = traverse(ta, tb, &pos, &opts, warm);
            // The surface bounds carry the trees' eps; the reference is the exact solids'.
            assert!(
                w.lower <= truth + 1e-9 && truth <= w.upper + 1e-9,
                "step {k} {what}: {truth} outside [{}, {}]",
                w.lower,
                w.upper
            );
            if what != "previous best" {
                // Everything but the timings in the counters.
                let same = |x: &revdist::query::search::SurfaceBounds| {
                    (
                        x.lower,
                        x.upper,
                        x.approx,
                        x.point_a,
                        x.point_b,
                        x.best_pair,
                    )
                };
                assert_eq!(same(&w), same(&cold), "step {k} {what}");
                assert_eq!(w.stats.node_pairs, cold.stats.node_pairs, "step {k} {what}");
            }
        }
        previous = cold.best_pair;
    }
}

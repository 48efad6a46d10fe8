//! Circle/circle tests: analytic catalogue (research notes section 2.1 table), an independent
//! sampling oracle, perturbations, rigid motions and property tests.

use super::*;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use proptest::prelude::*;
use std::f64::consts::{PI, TAU};

fn circle(c: [f64; 3], n: [f64; 3], r: f64) -> Circle3 {
    Circle3::new(Point3::from(c), Vector3::from(n), r).unwrap()
}

/// Independent reference: min over theta of the closed-form point-to-circle distance,
/// sampled densely, each sampled local minimum refined by golden section.
pub(crate) fn oracle_min(a: &Circle3, b: &Circle3) -> f64 {
    const N: usize = 4096;
    let f = |t: f64| point_circle_distance(&b.point_at(t), a).distance;
    let vals: Vec<f64> = (0..N).map(|k| f(TAU * k as f64 / N as f64)).collect();
    let mut best = f64::INFINITY;
    let h = TAU / N as f64;
    for k in 0..N {
        let (l, m, r) = (vals[(k + N - 1) % N], vals[k], vals[(k + 1) % N]);
        if m <= l && m <= r {
            let (mut lo, mut hi) = (k as f64 * h - h, k as f64 * h + h);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..100 {
                let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                if f(m1) < f(m2) {
                    hi = m2;
                } else {
                    lo = m1;
                }
            }
            best = best.min(f(0.5 * (lo + hi))).min(m);
        }
    }
    best
}

fn unit_a() -> Circle3 {
    circle([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0)
}

fn check_witness(a: &Circle3, b: &Circle3, m: &MinDistance, scale: f64) {
    let tol = 1e-12 * scale;
    assert!((m.point_a - a.point_at(m.angle_a)).norm() <= tol);
    assert!((m.point_b - b.point_at(m.angle_b)).norm() <= tol);
    assert!(((m.point_a - m.point_b).norm() - m.distance).abs() <= tol);
}

/// The catalogue: (name, circle B against the unit circle A, true min distance, continuum?).
pub(crate) fn catalogue() -> Vec<(&'static str, Circle3, f64, bool)> {
    let s5 = 5f64.sqrt();
    vec![
        ("D1 centre on axis", circle([0.0, 0.0, 0.5], [0.6, 0.0, 0.8], 0.5), (s5 - 1.0) / 2.0, false),
        ("D1b centre on axis", circle([0.0, 0.0, 0.5], [0.0, 0.6, 0.8], 0.5), (s5 - 1.0) / 2.0, false),
        ("D6 centre on axis", circle([0.0, 0.0, 1.0 / 3.0], [0.0, 0.8, 0.6], 0.9), 0.1540925533894598, false),
        ("D2 meridian", circle([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.5), 0.5, true),
        ("D3 Villarceau", circle([0.0, 0.6, 0.0], [-0.6, 0.0, 0.8], 1.0), 0.6, true),
        ("D4 through centre", circle([0.5, 0.0, 0.0], [0.0, 1.0, 0.0], 0.5), 0.0, false),
        ("D5", circle([0.5, 0.0, 0.0], [0.0, 1.0, 0.0], 0.75), 0.25, false),
        ("coaxial", circle([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 0.5), 0.5f64.hypot(2.0), true),
        ("concentric coplanar", circle([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], 0.25), 0.75, true),
        ("coplanar separated", circle([3.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5), 1.5, false),
        ("coplanar tangent", circle([1.5, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5), 0.0, false),
        ("coplanar intersecting", circle([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5), 0.0, false),
        ("coplanar nested", circle([0.25, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5), 0.25, false),
        ("parallel planes", circle([3.0, 0.0, 1.0], [0.0, 0.0, 1.0], 0.5), 1.5f64.hypot(1.0), false),
        ("through centre, tangent on axis", circle([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0), 1.0, true),
        ("linked", circle([1.0, 0.0, 0.1], [0.0, 1.0, 0.0], 0.5), f64::NAN, false),
        ("intersecting 3-D", circle([0.7, 0.0, 0.4], [0.0, 1.0, 0.0], 0.5), 0.0, false),
        ("perpendicular separated", circle([3.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0), 1.0, false),
        ("large centre on small axis", circle([0.0, 0.0, 0.5], [0.6, 0.0, 0.8], 3.0), f64::NAN, false),
    ]
}

#[test]
fn catalogue_matches_analytic_and_oracle() {
    let a = unit_a();
    for (name, b, expect, continuum) in catalogue() {
        let oracle = oracle_min(&a, &b);
        let truth = if expect.is_nan() { oracle } else { expect };
        assert!((oracle - truth).abs() < 1e-9, "{name}: oracle {oracle} vs {truth}");
        for (x, y) in [(&a, &b), (&b, &a)] {
            let m = min_distance(x, y);
            assert!(
                (m.distance - truth).abs() <= 1e-12,
                "{name}: got {} expected {truth}",
                m.distance
            );
            check_witness(x, y, &m, 1.0);
            assert_eq!(
                m.multiplicity != Multiplicity::Finite,
                continuum,
                "{name}: multiplicity {:?}",
                m.multiplicity
            );
        }
    }
}

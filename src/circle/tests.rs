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
    // Sample the smaller circle so the sampling step is small in length.
    let (a, b) = if b.radius <= a.radius { (a, b) } else { (b, a) };
    const N: usize = 4096;
    let f = |t: f64| point_circle_distance(&b.point_at(t), a).distance;
    let vals: Vec<f64> = (0..N).map(|k| f(TAU * k as f64 / N as f64)).collect();
    let h = TAU / N as f64;
    // Sampled local minima, lowest first; refining the 6 lowest covers the at most 4 local
    // minima of a generic pair (flat, constant-distance cases have many equal ones).
    let mut minima: Vec<(f64, usize)> = (0..N)
        .filter(|&k| vals[k] <= vals[(k + N - 1) % N] && vals[k] <= vals[(k + 1) % N])
        .map(|k| (vals[k], k))
        .collect();
    minima.sort_by(|x, y| x.0.total_cmp(&y.0));
    minima
        .iter()
        .take(6)
        .map(|&(m, k)| f(binormal::golden_min(f, k as f64 * h - h, k as f64 * h + h)).min(m))
        .fold(f64::INFINITY, f64::min)
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
        (
            "D1 centre on axis",
            circle([0.0, 0.0, 0.5], [0.6, 0.0, 0.8], 0.5),
            (s5 - 1.0) / 2.0,
            false,
        ),
        (
            "D1b centre on axis",
            circle([0.0, 0.0, 0.5], [0.0, 0.6, 0.8], 0.5),
            (s5 - 1.0) / 2.0,
            false,
        ),
        (
            "D6 centre on axis",
            circle([0.0, 0.0, 1.0 / 3.0], [0.0, 0.8, 0.6], 0.9),
            0.1540925533894598,
            false,
        ),
        (
            "D2 meridian",
            circle([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.5),
            0.5,
            true,
        ),
        (
            "D3 Villarceau",
            circle([0.0, 0.6, 0.0], [-0.6, 0.0, 0.8], 1.0),
            0.6,
            true,
        ),
        (
            "D4 through centre",
            circle([0.5, 0.0, 0.0], [0.0, 1.0, 0.0], 0.5),
            0.0,
            false,
        ),
        (
            "D5",
            circle([0.5, 0.0, 0.0], [0.0, 1.0, 0.0], 0.75),
            0.25,
            false,
        ),
        (
            "coaxial",
            circle([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 0.5),
            0.5f64.hypot(2.0),
            true,
        ),
        (
            "concentric coplanar",
            circle([0.0, 0.0, 0.0], [0.0, 0.0, -1.0], 0.25),
            0.75,
            true,
        ),
        (
            "coplanar separated",
            circle([3.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5),
            1.5,
            false,
        ),
        (
            "coplanar tangent",
            circle([1.5, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5),
            0.0,
            false,
        ),
        (
            "coplanar intersecting",
            circle([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5),
            0.0,
            false,
        ),
        (
            "coplanar nested",
            circle([0.25, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5),
            0.25,
            false,
        ),
        (
            "parallel planes",
            circle([3.0, 0.0, 1.0], [0.0, 0.0, 1.0], 0.5),
            1.5f64.hypot(1.0),
            false,
        ),
        (
            "through centre, tangent on axis",
            circle([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0),
            1.0,
            true,
        ),
        (
            "linked",
            circle([1.0, 0.0, 0.1], [0.0, 1.0, 0.0], 0.5),
            f64::NAN,
            false,
        ),
        (
            "intersecting 3-D",
            circle([0.7, 0.0, 0.4], [0.0, 1.0, 0.0], 0.5),
            0.0,
            false,
        ),
        (
            "perpendicular separated",
            circle([3.0, 0.0, 0.0], [0.0, 1.0, 0.0], 1.0),
            1.0,
            false,
        ),
        (
            "large centre on small axis",
            circle([0.0, 0.0, 0.5], [0.6, 0.0, 0.8], 3.0),
            f64::NAN,
            false,
        ),
    ]
}

#[test]
fn catalogue_matches_analytic_and_oracle() {
    let a = unit_a();
    for (name, b, expect, continuum) in catalogue() {
        let oracle = oracle_min(&a, &b);
        let truth = if expect.is_nan() { oracle } else { expect };
        assert!(
            (oracle - truth).abs() < 1e-9,
            "{name}: oracle {oracle} vs {truth}"
        );
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

/// Deterministic generator for test configurations (SplitMix64).
pub(crate) struct Rng(u64);
impl Rng {
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
    pub fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
    pub fn motion(&mut self, shift: f64) -> Isometry3<f64> {
        let axis = nalgebra::Unit::new_normalize(self.unit());
        let rot = UnitQuaternion::from_axis_angle(&axis, self.range(0.0, TAU));
        let t = self.unit() * self.range(0.0, shift);
        Isometry3::from_parts(Translation3::from(t), rot)
    }
}

/// Perturbations applied to circle B: centre x, centre y, tilt of the normal, radius.
fn perturbed(b: &Circle3, kind: usize, eps: f64) -> Circle3 {
    let mut out = *b;
    match kind {
        0 => out.center.x += eps,
        1 => out.center.y += eps,
        2 => {
            let n = b.normal.into_inner() + eps * b.u_axis.into_inner();
            out = Circle3::new(b.center, n, b.radius).unwrap();
        }
        _ => out.radius += eps,
    }
    out
}

#[test]
fn catalogue_perturbed_and_moved() {
    let a = unit_a();
    let mut rng = Rng(7);
    let mut worst = 0.0f64;
    for (name, b, _, _) in catalogue() {
        for kind in 0..4 {
            for e in [0.0, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2] {
                let bp = perturbed(&b, kind, e);
                let truth = oracle_min(&a, &bp);
                for _ in 0..2 {
                    let iso = rng.motion(10.0);
                    let (am, bm) = (a.transformed(&iso), bp.transformed(&iso));
                    for (x, y) in [(&am, &bm), (&bm, &am)] {
                        let m = min_distance(x, y);
                        let err = (m.distance - truth).abs();
                        worst = worst.max(err);
                        assert!(
                            err <= 1e-11,
                            "{name} kind {kind} eps {e}: {} vs {truth}",
                            m.distance
                        );
                        check_witness(x, y, &m, 20.0);
                    }
                }
            }
        }
    }
    eprintln!("worst error over perturbed catalogue: {worst:e}");
}

#[test]
fn nearly_parallel_planes() {
    let a = unit_a();
    for tilt in [1e-9, 1e-7, 1e-5, 1e-3] {
        for (c, r) in [
            ([0.0, 0.0, 0.5], 0.7),
            ([0.3, 0.0, 0.5], 0.7),
            ([2.5, 0.0, 0.0], 1.0),
            ([0.2, 0.1, 0.0], 0.5),
        ] {
            let b = circle(c, [tilt, 0.0, 1.0], r);
            let truth = oracle_min(&a, &b);
            for (x, y) in [(&a, &b), (&b, &a)] {
                let m = min_distance(x, y);
                assert!(
                    (m.distance - truth).abs() <= 1e-12,
                    "tilt {tilt} c {c:?}: {} vs {truth}",
                    m.distance
                );
            }
        }
    }
}

#[test]
fn radius_ratios_and_distances() {
    let mut rng = Rng(11);
    for ratio in [1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6] {
        for gap in [1e-12, 1e-6, 1.0, 1e3, 1e6] {
            // B of radius `ratio` placed so that its nearest point to A is `gap` away along
            // a generic direction: a point of A pushed outward, B tilted.
            let a = unit_a();
            let n = rng.unit();
            let b0 = Circle3::new(Point3::origin(), n, ratio).unwrap();
            let pb = b0.point_at(rng.range(0.0, TAU));
            let target = Point3::new(1.0 + gap, 0.0, 0.0);
            let b = Circle3 {
                center: b0.center + (target - pb),
                ..b0
            };
            let scale = 1f64.max(ratio).max((b.center - a.center).norm());
            let truth = oracle_min(&a, &b);
            for (x, y) in [(&a, &b), (&b, &a)] {
                let m = min_distance(x, y);
                assert!(
                    (m.distance - truth).abs() <= 1e-12 * scale,
                    "ratio {ratio} gap {gap}: {} vs {truth}",
                    m.distance
                );
                assert!(m.distance <= gap * (1.0 + 1e-9) + 1e-15 * scale);
                check_witness(x, y, &m, scale);
            }
        }
    }
}

#[test]
fn points_and_point_on_axis() {
    let a = unit_a();
    let p = circle([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 0.0);
    let m = min_distance(&p, &a);
    assert!((m.distance - 5f64.sqrt()).abs() < 1e-15);
    assert_eq!(m.multiplicity, Multiplicity::ContinuumOnB);
    let q = circle([3.0, 4.0, 1.0], [0.0, 1.0, 0.0], 0.0);
    let m = min_distance(&a, &q);
    assert!((m.distance - 4f64.hypot(1.0)).abs() < 1e-15);
    assert_eq!(m.multiplicity, Multiplicity::Finite);
    let pc = point_circle_distance(&Point3::new(0.0, 0.0, 1.0), &a);
    assert!(pc.on_axis && (pc.distance - 2f64.sqrt()).abs() < 1e-15);
    assert_eq!(min_distance(&p, &p).distance, 0.0);
}

#[test]
fn bad_input_is_an_error() {
    let c = Point3::origin();
    assert!(Circle3::new(c, Vector3::zeros(), 1.0).is_err());
    assert!(Circle3::new(c, Vector3::z(), -1.0).is_err());
    assert!(Circle3::new(c, Vector3::z(), f64::NAN).is_err());
    assert!(Circle3::new(Point3::new(f64::INFINITY, 0.0, 0.0), Vector3::z(), 1.0).is_err());
    assert!(Circle3::with_u_axis(c, Vector3::z(), Vector3::z(), 1.0).is_err());
    assert!(AngleInterval::new(0.0, 7.0).is_err());
}

/// Residual check of a binormal on world data.
fn assert_binormal(a: &Circle3, b: &Circle3, bn: &Binormal, scale: f64) {
    let d = bn.point_a - bn.point_b;
    let ta = a.tangent_at(bn.angle_a);
    let tb = b.tangent_at(bn.angle_b);
    let tol = 1e-9 * scale;
    assert!(d.dot(&ta).abs() <= tol * ta.norm().max(1e-300), "{bn:?}");
    assert!(d.dot(&tb).abs() <= tol * tb.norm().max(1e-300), "{bn:?}");
    assert!((d.norm() - bn.distance).abs() <= 1e-12 * scale);
}

#[test]
fn random_pairs_have_4_6_or_8_binormals_and_restriction_is_consistent() {
    let mut rng = Rng(3);
    let mut counts = [0usize; 17];
    for _ in 0..2000 {
        let a = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 1.0)),
            rng.unit(),
            rng.range(0.2, 1.5),
        )
        .unwrap();
        let b = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 1.5)),
            rng.unit(),
            rng.range(0.2, 1.5),
        )
        .unwrap();
        if min_distance(&a, &b).distance < 1e-3 {
            continue; // touching circles have fewer proper binormals
        }
        let all = binormals(&a, &b, None, None);
        counts[all.items.len()] += 1;
        for bn in all.items.iter() {
            assert_binormal(&a, &b, bn, 3.0);
        }
        // Restricting to ranges keeps exactly the binormals inside them.
        let ra = AngleInterval::new(rng.range(-PI, PI), rng.range(0.5, 5.0)).unwrap();
        let rb = AngleInterval::new(rng.range(-PI, PI), rng.range(0.5, 5.0)).unwrap();
        let part = binormals(&a, &b, Some(ra), Some(rb));
        let expected = all
            .items
            .iter()
            .filter(|x| ra.contains(x.angle_a, 1e-7) && rb.contains(x.angle_b, 1e-7))
            .count();
        let strict = all
            .items
            .iter()
            .filter(|x| ra.contains(x.angle_a, -1e-7) && rb.contains(x.angle_b, -1e-7))
            .count();
        assert!(
            part.items.len() <= expected && part.items.len() >= strict,
            "{} vs {expected}",
            part.items.len()
        );
    }
    eprintln!("binormal counts {counts:?}");
    let generic: usize = counts[4] + counts[6] + counts[8];
    let total: usize = counts.iter().sum();
    assert_eq!(generic, total, "counts {counts:?}");
    assert!(counts[8] > 0 && counts[6] > 0 && counts[4] > 0);
}

fn arb_circle(max_c: f64) -> impl Strategy<Value = Circle3> {
    (
        proptest::array::uniform3(-max_c..max_c),
        proptest::array::uniform3(-1.0f64..1.0),
        0.05f64..2.0,
    )
        .prop_filter_map("normal", |(c, n, r)| {
            let n = Vector3::from(n);
            (n.norm() > 0.1).then(|| Circle3::new(Point3::from(c), n, r).unwrap())
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn symmetric_and_witnesses_valid(a in arb_circle(2.0), b in arb_circle(2.0)) {
        let ab = min_distance(&a, &b);
        let ba = min_distance(&b, &a);
        prop_assert!((ab.distance - ba.distance).abs() <= 1e-12 * 4.0);
        let scale = a.radius.max(b.radius).max((a.center - b.center).norm());
        check_witness(&a, &b, &ab, scale.max(1.0) * 4.0);
        prop_assert!((ab.distance - oracle_min(&a, &b)).abs() <= 1e-11 * scale);
    }

    #[test]
    fn rigid_motion_and_scale_invariant(a in arb_circle(2.0), b in arb_circle(2.0), seed in 0u64..1000, s in 1e-3f64..1e3) {
        let iso = Rng(seed).motion(100.0);
        let d = min_distance(&a, &b).distance;
        let dm = min_distance(&a.transformed(&iso), &b.transformed(&iso)).distance;
        let ds = min_distance(&a.scaled(s), &b.scaled(s)).distance;
        let scale = a.radius.max(b.radius).max((a.center - b.center).norm());
        prop_assert!((d - dm).abs() <= 1e-12 * (scale + 100.0));
        prop_assert!((d * s - ds).abs() <= 1e-12 * scale * s);
    }

    #[test]
    fn lipschitz_in_centres(a in arb_circle(2.0), b in arb_circle(2.0), dir in proptest::array::uniform3(-1.0f64..1.0), h in 1e-12f64..1e-1) {
        let d0 = min_distance(&a, &b).distance;
        let mut b2 = b;
        b2.center += Vector3::from(dir) * h;
        let dh = (Vector3::from(dir) * h).norm();
        let d1 = min_distance(&a, &b2).distance;
        let scale = a.radius.max(b.radius).max((a.center - b.center).norm());
        prop_assert!((d1 - d0).abs() <= dh + 2e-12 * scale);
    }
}

#[test]
fn tangent_coplanar_circles_tilted_about_the_contact_tangent() {
    // Coplanar externally tangent circles, B tilted by 2e-12 about the line through its
    // centre and the contact point: they still touch. The contact is a triple root of the
    // binormal polynomial (known to ~eps^(1/3)); Newton polishing must bring the distance to
    // rounding level (found by `verify circles`).
    let a = Circle3::with_u_axis(
        Point3::new(-7.5, 0.875, -3.5),
        Vector3::new(
            -0.7563719862227325,
            -0.6103329506314581,
            -0.23536165327210107,
        ),
        Vector3::new(-0.547646383467279, 0.7876004592422504, -0.28243398392652125),
        1.0,
    )
    .unwrap();
    let b = Circle3::with_u_axis(
        Point3::new(-8.321469575200918, 2.0564006888633752, -3.9236509758897817),
        Vector3::new(
            -0.756371986223448,
            -0.6103329506312887,
            -0.23536165327024114,
        ),
        Vector3::new(-0.547646383467279, 0.7876004592422504, -0.28243398392652125),
        0.5,
    )
    .unwrap();
    for (x, y) in [(&a, &b), (&b, &a)] {
        let m = min_distance(x, y);
        assert!(m.distance <= 1e-13, "{m:?}");
    }
}

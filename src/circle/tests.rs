//! Circle/circle tests: analytic catalogue (`docs/numerics.md` section 2.1), an independent
//! sampling oracle, perturbations, rigid motions and property tests.

use super::*;
use crate::test_rng::SplitMix64;
use nalgebra::{Point3, Vector3};
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
        .map(|&(m, k)| {
            f(min_distance::golden_min(
                f,
                k as f64 * h - h,
                k as f64 * h + h,
            ))
            .min(m)
        })
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
    let mut rng = SplitMix64(7);
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
    let mut rng = SplitMix64(11);
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
    let mut rng = SplitMix64(3);
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
        let iso = SplitMix64(seed).motion(100.0);
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

/// A vector from the bit patterns of its coordinates (pinned regression inputs).
fn bits(b: [u64; 3]) -> [f64; 3] {
    b.map(f64::from_bits)
}

fn circle_u(c: [f64; 3], n: [f64; 3], u: [f64; 3], r: f64) -> Circle3 {
    Circle3::with_u_axis(Point3::from(c), Vector3::from(n), Vector3::from(u), r).unwrap()
}

/// Accuracy requirement (`docs/numerics.md`): distance error relative to the configuration scale
/// max(ra, rb, |Cb - Ca|).
const REL_TOL: f64 = 1e-12;

/// The first 24 of the 28 failures of `verify circles --count 100000 --seed 3 --motions 20`
/// before the fix (the run was cut off before the rest were printed), pinned
/// bit-exactly: (A, B, distance of the exact rational configuration, from rug/MPFR). The
/// inputs are the f64 roundings the solver saw (rounding moves the true distance by ~1e-15
/// of the scale). Causes: a root on a subdivision split point (gap 1e-9), noise-level
/// clusters of roots whose representative was a maximum (nearly tangent contact), the
/// ill-conditioned choice of parametrised circle (radius ratio 1e6), and cancellation in the
/// coplanar intersection formula (parallel planes, gap 1e-12).
fn verify_regressions() -> Vec<(Circle3, Circle3, f64)> {
    vec![
        // tangent along axis at centre kind 2 eps 1e-4: exact 9.999999600079984e-1
        (
            circle_u(
                bits([0xc011000000000000, 0xc002000000000000, 0x4014000000000000]),
                bits([0x3fd36561ce33ff73, 0x3feb07d748381fea, 0x3fdc3bf9f284e227]),
                bits([0xbfdf311becbdd55c, 0x3fe12053a30256aa, 0xbfe61415759d3b4a]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0xc012f311becbdd55, 0xbffb6fd62e7ed4ab, 0x40113d7d514c5896]),
                bits([0xbfea340d29dd526b, 0xbf7784c690c58861, 0x3fe25dfd1ac383fa]),
                bits([0xbfdf311becbdd55c, 0x3fe12053a30256aa, 0xbfe61415759d3b4a]),
                f64::from_bits(0x3ff0000000000000),
            ),
            9.999999600079984e-1,
        ),
        // tangent along axis at centre kind 2 eps 1e-4: exact 9.999999600079984e-1
        (
            circle_u(
                bits([0xc023000000000000, 0x401b800000000000, 0x4014000000000000]),
                bits([0xbfce025e80b95202, 0xbfe01f96b4519aa7, 0x3fea9a8576537261]),
                bits([0xbfea9a8576537261, 0xbfd5b79bf81a52ec, 0xbfdc2aa50d07c3fc]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0xc024a9a857653726, 0x401a2486407e5ad1, 0x40123d55af2f83c0]),
                bits([0x3fe01f34595258e1, 0xbfe96c1866443ae7, 0xbfd5b4e28b164518]),
                bits([0xbfea9a8576537261, 0xbfd5b79bf81a52ed, 0xbfdc2aa50d07c3fd]),
                f64::from_bits(0x3ff0000000000000),
            ),
            9.999999600079984e-1,
        ),
        // gap 1e-9 rb~1e1: exact 7.999999999803077e-10
        (
            circle_u(
                bits([0x4013000000000000, 0xc013800000000000, 0xc016800000000000]),
                bits([0x3fd91f1a515885fb, 0xbfcc91cd9dc40bd3, 0x3fec8d4cb3947a29]),
                bits([0xbfea04c8f8d28ac5, 0xbfe1347ea9ba79e1, 0x3fcc91cd9dc40bd3]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x4017183387f380ee, 0x3ff9e7752b0a492a, 0xc0236060a7514d28]),
                bits([0xbfe1ce4f2326d51f, 0x3fe1133cd4a9f773, 0x3fe46190200b6ea2]),
                bits([0xbfcbdd1b20a613f4, 0xbfeaab12222516eb, 0x3fe041b7aff52822]),
                f64::from_bits(0x4020e00000000000),
            ),
            7.999999999803077e-10,
        ),
        // gap 1e-12 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0xc019000000000000, 0x3ff8000000000000, 0xbff8000000000000]),
                bits([0xbfd026d6bbd86a10, 0x3fd317b6cdc55e4c, 0x3fed74b400bf34d8]),
                bits([0xbfd6bbd86a0f4fbc, 0x3feb66e2af25e7ba, 0xbfd7fe8196504ab2]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0xc01a6bbd8d189bd6, 0x4002d9b83bc0d8c0, 0xbffdffa0240da420]),
                bits([0x3fd026d6bbd86a0f, 0xbfd317b6cdc55e4c, 0xbfed74b400bf34d8]),
                bits([0x3fbc320ad47e39e4, 0x3fee86dc0189a908, 0xbfd1daad4d834a28]),
                f64::from_bits(0x3ead5c31593e5fb7),
            ),
            0e0,
        ),
        // gap 1e-8 rb~1e-4: exact 9.931196304393793e-9
        (
            circle_u(
                bits([0x4023400000000000, 0x401d800000000000, 0xc003000000000000]),
                bits([0x3fd211a45ffcf6fd, 0x3fe26cb2b281f1c5, 0xbfe88de54097c28a]),
                bits([0xbfc656503e38b863, 0x3fea27a5b3ee2b10, 0x3fe19229ec75fe4b]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x4022e6ac3abc2457, 0x40206283087b901e, 0xbffd376389723d82]),
                bits([0x3fc1f23e55303695, 0xbfec22766bcf9f63, 0xbfdd24598a7c9f54]),
                bits([0xbfd340f3dccb585f, 0xbfde765306ed8f7f, 0x3fea71ea5a1ad62f]),
                f64::from_bits(0x3f223a29c779a6b5),
            ),
            9.931196304393793e-9,
        ),
        // gap 1e-8 rb~1e-2: exact 9.503345159475924e-9
        (
            circle_u(
                bits([0x4022c00000000000, 0xc013000000000000, 0xbfec000000000000]),
                bits([0xbfee9870caae7bd0, 0xbfd2c03b8b7c99bb, 0xbf712d28dd935c21]),
                bits([0x3fcf3d558630cf45, 0xbfe93a5405706f13, 0xbfe2122da91db36c]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x402335a3f7e70b87, 0xc016279c3eef6437, 0xbff6fe6c9158ef9c]),
                bits([0x3fb447eaa14cb237, 0x3feae7a53e5bf79f, 0x3fe1234190f7eda3]),
                bits([0x3fef797f779440bd, 0x3f95f931f8dccd4a, 0xbfc6ef8b8a7725d5]),
                f64::from_bits(0x3f8dc28f5c28f5c2),
            ),
            9.503345159475924e-9,
        ),
        // gap 1e-11 rb~1e-4: exact 0e0
        (
            circle_u(
                bits([0x401e800000000000, 0x4001000000000000, 0x4017000000000000]),
                bits([0x3fe2a3192a3192a3, 0xbfd27ec527ec527f, 0xbfe8503985039851]),
                bits([0x3fbe7671e7671e76, 0x3fee8ea9e8ea9e8f, 0xbfd1684116841169]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x401ef9d5d3c6583a, 0x4008a3a9cf1c389e, 0x4015e979078598fc]),
                bits([0x3fe2a3192a3192a3, 0xbfd27ec527ec527f, 0xbfe8503985039851]),
                bits([0x3fe9bb819bb819bc, 0x3fb1684116841168, 0x3fe2e5b32e5b32e6]),
                f64::from_bits(0x3ef3a92a30553261),
            ),
            0e0,
        ),
        // rb~1e6 |c|~1e0: exact 1.499997265706065e6
        (
            circle_u(
                bits([0x401d000000000000, 0x3fd8000000000000, 0x4023400000000000]),
                bits([0xbfbb95f0111f458e, 0x3feead5ca0484b26, 0xbfd0dac878ce6ac7]),
                bits([0x3fd61db9d8c30099, 0xbfcb2b66604fe745, 0xbfed4016d45cbeb9]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x40204225cfb99be2, 0xbfe41ba5284ef3c0, 0x402642d5ca0484b2]),
                bits([0x3fe587581eefd367, 0xbfe57554f8fdc072, 0xbfd4016d45cbeb8c]),
                bits([0x3fe4d863374b6e95, 0x3fd58a7c64111e28, 0x3fe5c26865c81d7d]),
                f64::from_bits(0x4136e36000000000),
            ),
            1.499997265706065e6,
        ),
        // gap 1e-12 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x3ff2000000000000, 0xc012800000000000, 0x401d000000000000]),
                bits([0xbfe50e425d8d2062, 0xbfe28a53f4ce4ae5, 0xbfdec8b20a65039a]),
                bits([0x3fbec8b20a65039c, 0x3fe197412a82dd7c, 0xbfea73f08a982ff9]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x3ff3ec8c59ff6348, 0xc0104d17ff7be869, 0x4019b181afd691fa]),
                bits([0x3fe50e425d8d2062, 0x3fe28a53f4ce4ae5, 0x3fdec8b20a65039a]),
                bits([0xbfe7701330a42e61, 0x3fd604f0e671af33, 0x3fe2cceb3dd83f11]),
                f64::from_bits(0x3ebabd1aa821f299),
            ),
            0e0,
        ),
        // gap 1e-9 rb~1e-5: exact 0e0
        (
            circle_u(
                bits([0x4023000000000000, 0xc01d800000000000, 0xc008000000000000]),
                bits([0xbfe12627242d1263, 0x3fe70e0917eb70e1, 0x3fdc2b7d8769c2b7]),
                bits([0x3feac2ea73d7ac2f, 0x3fd869f5533986a0, 0x3fd93462d7799347]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x4024ac2e1693adfa, 0xc01bf9612ec5a028, 0xc004d974b58fc2eb]),
                bits([0x3fe12627242d1263, 0xbfe70e0917eb70e1, 0xbfdc2b7d8769c2b7]),
                bits([0x3feac2ea73d7ac2f, 0x3fd869f5533986a0, 0x3fd93462d7799347]),
                f64::from_bits(0x3ed5a07b352a8438),
            ),
            0e0,
        ),
        // gap 1e-10 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x4008000000000000, 0x3fe8000000000000, 0xbffa000000000000]),
                bits([0xbfeb65533c6d954e, 0xbfdffbce307fef3a, 0x3fc0d8053e436015]),
                bits([0x3fd57f477055fd1e, 0xbfd60de4ff583794, 0x3fec0d1ba870346f]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x400aafe8a08f7183, 0x3fd9f21d7c926bf6, 0xbfe7f2e78065079b]),
                bits([0xbfeb65533c6d954e, 0xbfdffbce307fef3a, 0x3fc0d8053e436015]),
                bits([0x3fd57f477055fd1e, 0xbfd60de4ff583794, 0x3fec0d1ba870346f]),
                f64::from_bits(0x3ebcd5f99c38b04a),
            ),
            0e0,
        ),
        // gap 1e-10 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x4023400000000000, 0xc010800000000000, 0xc023800000000000]),
                bits([0x3fe7e573fb24d367, 0xbfe4f1305195539c, 0xbfbe59d6b904efe5]),
                bits([0x3fe47ca42349bb89, 0x3fe82df8b73d1b46, 0xbfc1b995f95cfecb]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x402487ca3b374e3d, 0xc00af481d672e114, 0xc023c6e67e0b424c]),
                bits([0x3fe7e573fb24d367, 0xbfe4f1305195539c, 0xbfbe59d6b904efe5]),
                bits([0x3fc71113d44b6ea5, 0x3f9c2a690e007c4d, 0x3fef76bb9bf69c88]),
                f64::from_bits(0x3eb3660e51d25aab),
            ),
            0e0,
        ),
        // gap 1e-7 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x401c000000000000, 0x3ffe000000000000, 0x401c000000000000]),
                bits([0x3fece434a9b10177, 0xbfd4a05442b4cf25, 0xbfd2366b14c5c73e]),
                bits([0xbfb974269e92def3, 0xbfe99d584c4d7911, 0x3fe2ea2c967fad9d]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x401b9a2f4d57cc5b, 0x3ff1315382abed20, 0x401e5d455ec81047]),
                bits([0x3fece434a9b10177, 0xbfd4a05442b4cf23, 0xbfd2366b14c5c73e]),
                bits([0x3fd7eaef52cc3701, 0x3fd0b4b12e66de3d, 0x3fec7b591e04906a]),
                f64::from_bits(0x3eaf75104d551d68),
            ),
            0e0,
        ),
        // gap 1e-6 rb~1e-6: exact 8.636168555094445e-78
        (
            circle_u(
                bits([0xbfe4000000000000, 0xc001000000000000, 0xc020c00000000000]),
                bits([0xbfdc3860dc8bd40a, 0x3fc1925909bf8cc3, 0xbfec621a735d5285]),
                bits([0x3fc3a6d67618b64d, 0x3fef86cc86dc6c0a, 0x3fb37f1984efab8f]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0xbfde2c8f1ffcaf2b, 0xbff23c9a123b6f8c, 0xc0209901e5110e97]),
                bits([0xbfdc3860dc8bd40c, 0x3fc1925909bf8cc3, 0xbfec621a735d5285]),
                bits([0xbfe3b0c5b262f8fc, 0x3fe58ad8e5307174, 0x3fda3ee909f26a22]),
                f64::from_bits(0x3ec040bfe3b03e20),
            ),
            8.636168555094445e-78,
        ),
        // gap 1e-9 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0xc024000000000000, 0x401e000000000000, 0x4001000000000000]),
                bits([0x3feea43380403582, 0xbfcf003bedac761e, 0x3fc403e119731319]),
                bits([0x3fc7537032d506da, 0x3fedb8c4a3dde393, 0x3fd4a68ac8fcd2b0]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0xc023a2b24359662b, 0x4020db8c4b4092be, 0x400394d1c4e079a2]),
                bits([0xbfeea43380403582, 0x3fcf003bedac761f, 0xbfc403e119731318]),
                bits([0x3fc37b7a809b9b0a, 0xbfa264a937ae66aa, 0xbfef9b34132df706]),
                f64::from_bits(0x3eab43526527a205),
            ),
            0e0,
        ),
        // gap 1e-11 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x401d800000000000, 0x3ffc000000000000, 0xc000000000000000]),
                bits([0x3feef7bdef7bdef8, 0x3f8a6d01a6d01a72, 0x3fd01a6d01a6d01b]),
                bits([0xbfbddb280514f67b, 0x3fed0fe182392bd5, 0x3fd9ba1fc3047258]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x401d08934a45c256, 0x400543f79b2089c0, 0xbff99176adf2e9e7]),
                bits([0x3feef7bdef7bdef8, 0x3f8a6d01a6d01a6a, 0x3fd01a6d01a6d01b]),
                bits([0x3fc4a5294a5294a6, 0x3fe789157891578a, 0xbfe50edd50edd50f]),
                f64::from_bits(0x3ec0c6f7a0b5ed8d),
            ),
            0e0,
        ),
        // gap 1e-6 rb~1e-4: exact 8.636168555094445e-78
        (
            circle_u(
                bits([0x4024000000000000, 0x401b000000000000, 0x4022400000000000]),
                bits([0x3fda50475bdfe375, 0x3fb00e45932d7dc7, 0xbfed19de1ac273f5]),
                bits([0xbfc8e2ebd7534fbe, 0xbfeeff1ba6cd2824, 0xbfc3cd55cf1e8187]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x40239c7553245cca, 0x401720269af309c7, 0x4021f0cb76750504]),
                bits([0x3fda50475bdfe375, 0x3fb00e45932d7dc7, 0xbfed19de1ac273f5]),
                bits([0xbfc8e2ebd7534fbe, 0xbfeeff1ba6cd2824, 0xbfc3cd55cf1e8187]),
                f64::from_bits(0x3f054c985f06f694),
            ),
            8.636168555094445e-78,
        ),
        // gap 1e-11 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x400c000000000000, 0xbff8000000000000, 0x3fd0000000000000]),
                bits([0x3fb71242287d49b9, 0x3feeb115778eef6c, 0xbfd12b7804473342]),
                bits([0xbfefcf1b6d040c87, 0x3fba6ec5dd02d39d, 0x3fa2077c99b4fae1]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x40040c39cd3ab2b2, 0xbff659140064db22, 0x3fd240ec14ce7af7]),
                bits([0x3fb71242287d49bb, 0x3feeb115778eef6c, 0xbfd12b7804473343]),
                bits([0xbfe9f7e86b1d5593, 0x3fcd0a4c865b7c9c, 0x3fe13b55ffd00796]),
                f64::from_bits(0x3eb9f3c70c996b76),
            ),
            0e0,
        ),
        // gap 1e-8 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x4003000000000000, 0x4023800000000000, 0x401f000000000000]),
                bits([0x3fe8142ac4a0fd22, 0x3fe06de02f49cd10, 0x3fda677170920990]),
                bits([0xbfda677170920990, 0x3feb61caf97b006f, 0xbfd3fe42ef0c9abb]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x3fff6623455e0b96, 0x4025361caa64eee5, 0x401dc01c0914e721]),
                bits([0x3fe8142ac4a0fd22, 0x3fe06de02f49cd10, 0x3fda677170920990]),
                bits([0x3fd826a326cb351e, 0x3fc6b2c8d444cdf0, 0xbfed15f52fb02a8f]),
                f64::from_bits(0x3eaeeed8904f6dfc),
            ),
            0e0,
        ),
        // gap 1e-9 rb~1e-5: exact 0e0
        (
            circle_u(
                bits([0xbfd0000000000000, 0xc023400000000000, 0x401a800000000000]),
                bits([0x3fdcb03d33b5c3a7, 0x3fec6c3ca2a37d19, 0x3fb9c8bf8a2126ae]),
                bits([0x3feb92a138cf6821, 0xbfdd65940be67fcb, 0x3fcba03aef6ca971]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x3fe392a6ae99b391, 0xc0242b2ca40b0880, 0x401b5cff0e9d9e07]),
                bits([0xbfdcb03d33b5c3a7, 0xbfec6c3ca2a37d19, 0xbfb9c8bf8a2126ae]),
                bits([0xbfce7596502f99ff, 0x3f846691ebe1f737, 0x3fef14424d5a3e9e]),
                f64::from_bits(0x3ee6f0068db8bac7),
            ),
            0e0,
        ),
        // rb~1e4 |c|~1e-3: exact 1.281149837485173e4
        (
            circle_u(
                bits([0x4023400000000000, 0xc022800000000000, 0x401f000000000000]),
                bits([0x3febb0b349441823, 0x3fdda6b3a187abe0, 0xbfc87abdf972fc09]),
                bits([0x3fdfe46ae1d4e701, 0xbfe8227a65b5df3f, 0x3fdb5df3eec2cd26]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x40234077dc166cb0, 0xc0227f0a6afbf531, 0x401f01054452092d]),
                bits([0xbfdfa4b3270e1e61, 0x3fe9e8cc5045c4cc, 0xbfd43c8c3f984171]),
                bits([0xbfbdb87dc73ea7be, 0xbfdb0270590e1af5, 0xbfecc59826c124ee]),
                f64::from_bits(0x40c9064000000000),
            ),
            1.281149837485173e4,
        ),
        // gap 1e-7 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x4021c00000000000, 0x4022c00000000000, 0xbfec000000000000]),
                bits([0xbfe212200b99a106, 0xbfb0acd778dbd278, 0x3fea53aa72fc728e]),
                bits([0x3fc24e721db9aca0, 0xbfefaa28bed265a6, 0x3f944cd9cac8d3b2]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x40220939a1add487, 0x4020c55d766a66d2, 0xbfeb5d9ad8a7b0a6]),
                bits([0xbfe212200b99a107, 0xbfb0acd778dbd279, 0x3fea53aa72fc728d]),
                bits([0x3fea55fc5ffdae12, 0xbfbe61dbad104b7a, 0x3fe1c6be06854630]),
                f64::from_bits(0x3eb7dae81882adc4),
            ),
            0e0,
        ),
        // gap 1e-10 rb~1e-6: exact 0e0
        (
            circle_u(
                bits([0x4022c00000000000, 0xc017000000000000, 0x4024000000000000]),
                bits([0xbfef3fb3146e92a2, 0x3faf3fb3146e92a0, 0xbfca70f9fd98a376]),
                bits([0x3fca70f9fd98a375, 0x3fe12fd5b1a3370c, 0xbfea2bbf944fce01]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x402329c3f322c2a7, 0xc014da05418839b4, 0x40225d43d321bc62]),
                bits([0xbfef3fb3146e92a2, 0x3faf3fb3146e92a2, 0xbfca70f9fd98a377]),
                bits([0xbfcb01c478c0ddb9, 0xbfb3f71ec83f3ba1, 0x3fef2e0d9a38debb]),
                f64::from_bits(0x3eba79fec99f1ae2),
            ),
            0e0,
        ),
        // gap 1e-11 rb~1e-6: exact 8.636168555094445e-78
        (
            circle_u(
                bits([0x4011800000000000, 0x4021800000000000, 0x4010000000000000]),
                bits([0xbfecfb2b78c13522, 0xbf9fd28a16297b99, 0xbfdb103201b46bf8]),
                bits([0x3fd95bc609a90e7e, 0x3fd2c0a3a87d0444, 0xbfebd838d3644c26]),
                f64::from_bits(0x3ff0000000000000),
            ),
            circle_u(
                bits([0x401315bc3726d2ca, 0x402216052e80d996, 0x400909f277a4b4c0]),
                bits([0xbfecfb2b78c13522, 0xbf9fd28a16297b9a, 0xbfdb103201b46bf9]),
                bits([0x3fda1540b97aafd2, 0xbfd5b177812a38b7, 0xbfeb22612c0a3a88]),
                f64::from_bits(0x3eb96d8f4f93bc0a),
            ),
            8.636168555094445e-78,
        ),
    ]
}

#[test]
fn verify_failures_are_fixed() {
    for (k, (a, b, exact)) in verify_regressions().into_iter().enumerate() {
        let scale = a.radius.max(b.radius).max((a.center - b.center).norm());
        for (x, y) in [(a, b), (b, a)] {
            let m = min_distance(&x, &y);
            let err = (m.distance - exact).abs() / scale;
            assert!(
                err <= REL_TOL,
                "case {k}: {} vs exact {exact}, rel err {err:e}",
                m.distance
            );
            check_witness(&x, &y, &m, scale);
        }
    }
}

/// Pinned configurations with exactly 8 binormals (Neff's bound), found by
/// `verify eight --count 400 --seed 11 --min-gap 0.1`: the exact Sturm count of the degree-8
/// polynomial over the rationals is 8, and the angles on B and lengths come from its roots
/// refined in 256-bit MPFR. Data: (ra, B centre, B u-axis, B v-axis, rb, [(theta, length)]).
type EightCase = (f64, [f64; 3], [f64; 3], [f64; 3], f64, [(f64, f64); 8]);

fn eight_binormal_cases() -> [EightCase; 2] {
    [
        // 91/64; (37/64, -37/64, -19/32); (6, -7, 42)/43; (-7, -42, -6)/43; 85/64.
        (
            1.421875,
            [0.578125, -0.578125, -0.59375],
            [6.0 / 43.0, -7.0 / 43.0, 42.0 / 43.0],
            [-7.0 / 43.0, -42.0 / 43.0, -6.0 / 43.0],
            1.328125,
            [
                (-3.0784214626471953, 2.0934961639099985),
                (-2.684292283813148, 2.5811573465436757),
                (-2.211369342415087, 2.598142280269636),
                (-1.3040142069614793, 0.3905583523051815),
                (-0.6914256521088108, 2.3438351216851747),
                (-0.3521770665607225, 0.8685861001231913),
                (0.7858672266806093, 0.37151538368900033),
                (1.6458502515667874, 3.423757944911822),
            ],
        ),
        // 87/64; (-17/32, -17/64, 7/64); (17, 0, -144)/145; (-144, 0, -17)/145; 7/4.
        (
            1.359375,
            [-0.53125, -0.265625, 0.109375],
            [17.0 / 145.0, 0.0, -144.0 / 145.0],
            [-144.0 / 145.0, 0.0, -17.0 / 145.0],
            1.75,
            [
                (-2.786569899024375, 2.101866666820266),
                (-2.6402348866899414, 2.3939277598503246),
                (-1.5898142316748676, 2.614037616435917),
                (-1.394526350990929, 0.11515487126384753),
                (-0.25296285613572184, 2.2403189450369623),
                (-0.12794338017936507, 1.9168812269986966),
                (1.5555271692725143, 0.9300645098001759),
                (1.7463750752703613, 3.659192514709866),
            ],
        ),
    ]
}

/// Pinned binormal lengths: the solver's promised accuracy, 1e-12 of the configuration's
/// scale (`verify circles`, `docs/verification.md`; the f64 rounding of the rational
/// axes moves them by ~1e-16).
const PIN_LENGTH_TOL: f64 = 1e-12;
/// Pinned angles: simple roots at least 0.1 apart are located to ~1e-15 rad; 1e-10 leaves
/// margin for the rounding of the data.
const PIN_ANGLE_TOL: f64 = 1e-10;

#[test]
fn eight_binormals_pinned() {
    for (ra, c, u, v, rb, expected) in eight_binormal_cases() {
        let a = circle_u([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], ra);
        let (u, v) = (Vector3::from(u), Vector3::from(v));
        let b = circle_u(c, u.cross(&v).into(), u.into(), rb);
        for (x, y, swapped) in [(a, b, false), (b, a, true)] {
            let bn = binormals(&x, &y, None, None);
            assert_eq!(bn.multiplicity, Multiplicity::Finite);
            assert_eq!(bn.items.len(), 8, "{:?}", bn.items);
            for &(theta, len) in &expected {
                let hit = bn.items.iter().find(|item| {
                    let t = if swapped { item.angle_a } else { item.angle_b };
                    let d = (t - theta).rem_euclid(TAU);
                    d.min(TAU - d) <= PIN_ANGLE_TOL
                });
                let hit = hit.unwrap_or_else(|| panic!("theta {theta} missing: {:?}", bn.items));
                assert!(
                    (hit.distance - len).abs() <= PIN_LENGTH_TOL,
                    "{hit:?} vs {len}"
                );
            }
            let min = expected.iter().map(|e| e.1).fold(f64::INFINITY, f64::min);
            assert!((min_distance(&x, &y).distance - min).abs() <= PIN_LENGTH_TOL);
        }
    }
}

/// Random general pairs (radii 0.2..1.2, centres within 1.5) take the certified fast path,
/// and its answer agrees with the dense-sampling oracle (to the oracle's accuracy, 1e-9).
#[test]
fn general_pairs_are_certified_and_agree_with_the_oracle() {
    let mut rng = SplitMix64(5);
    let mut certified_count = 0;
    for _ in 0..300 {
        let a = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 1.0)),
            rng.unit(),
            rng.range(0.2, 1.2),
        )
        .unwrap();
        let b = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 1.5)),
            rng.unit(),
            rng.range(0.2, 1.2),
        )
        .unwrap();
        let (x, y) = if b.radius <= a.radius { (a, b) } else { (b, a) };
        let lp = frame::LocalPair::new(&x, &y).unwrap();
        let oracle = oracle_min(&a, &b);
        if let Some(m) = certified::certified_min(&lp) {
            certified_count += 1;
            assert!(
                (m.dist * lp.scale - oracle).abs() <= 1e-9,
                "{} vs {oracle}",
                m.dist * lp.scale
            );
        }
        assert!((min_distance(&a, &b).distance - oracle).abs() <= 1e-9);
    }
    assert!(certified_count >= 290, "{certified_count}");
}

/// Circles whose axes meet (the closed form of `intersecting_axes_min`): random meeting
/// points, axis directions, offsets along the axes (including the centre at the meeting
/// point and nearly parallel axes) and radii, against the sampled-and-polished oracle.
#[test]
fn intersecting_axes_match_the_oracle() {
    let mut rng = SplitMix64(77);
    let mut cases = 0;
    for k in 0..400 {
        let o = Point3::from(rng.unit() * rng.range(0.0, 2.0));
        let ua = rng.unit();
        let tilt = [1.0, 1e-3, 1e-6][k % 3];
        let ub = (ua + rng.unit() * tilt).normalize();
        let da = if k % 5 == 0 {
            0.0
        } else {
            rng.range(-1.0, 1.0)
        };
        let db = rng.range(-1.0, 1.0);
        let (ra, rb) = (rng.range(0.1, 1.1), rng.range(0.1, 1.6));
        let a = Circle3::new(o + ua * da, ua, ra).unwrap();
        let b = Circle3::new(o + ub * db, ub, rb).unwrap();
        let truth = oracle_min(&a, &b);
        for (x, y) in [(&a, &b), (&b, &a)] {
            let m = min_distance(x, y);
            let scale = 1.0 + o.coords.norm() + ra + rb;
            assert!(
                (m.distance - truth).abs() <= 1e-12 * scale,
                "case {k}: {} vs {truth}",
                m.distance
            );
            let pd = (m.point_a - m.point_b).norm();
            assert!(
                (pd - m.distance).abs() <= 1e-12 * scale,
                "case {k}: witnesses {pd}"
            );
        }
        cases += 1;
    }
    assert_eq!(cases, 400);
}

/// `min_distance_value` is `min_distance` without the points: the same number, bit for
/// bit, on random pairs (general, intersecting axes, parallel) and the degenerate catalogue.
#[test]
fn value_only_matches_min_distance() {
    let mut rng = SplitMix64(91);
    let mut pairs = verify_regressions()
        .into_iter()
        .map(|(a, b, _)| (a, b))
        .collect::<Vec<_>>();
    for i in 0..500 {
        let a = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 1.0)),
            rng.unit(),
            rng.range(0.05, 1.2),
        )
        .unwrap();
        let n = match i % 3 {
            0 => rng.unit(),
            1 => a.normal.into_inner(),
            _ => (a.center.coords - Point3::origin().coords + rng.unit()).normalize(),
        };
        let b = Circle3::new(
            Point3::from(rng.unit() * rng.range(0.0, 2.0)),
            n,
            rng.range(0.05, 1.2),
        )
        .unwrap();
        pairs.push((a, b));
    }
    for (a, b) in pairs {
        let full = min_distance(&a, &b).distance;
        assert_eq!(
            min_distance_value(&a, &b).to_bits(),
            full.to_bits(),
            "{a:?} {b:?}"
        );
    }
}

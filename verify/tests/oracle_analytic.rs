//! The oracle itself against analytic truths: spheres, tori, a sphere in a torus's hole,
//! nested solids, point-in-region of a square and of an open chain.

use nalgebra::{Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::nurbs::NurbsCurve;
use revdist::profile::Profile;
use std::f64::consts::FRAC_1_SQRT_2 as W;
use verify::oracle::{index, surface_distance, OracleOptions, PlanarIndex};

fn p(x: f64, y: f64) -> Point2<f64> {
    Point2::new(x, y)
}

/// Ball of radius `r` centred at `(0, 0, zc)`: a rational semicircle, south to north.
fn ball(r: f64, zc: f64) -> Profile {
    let c = NurbsCurve::new(
        2,
        vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0],
        vec![
            p(0.0, zc - r),
            p(r, zc - r),
            p(r, zc),
            p(r, zc + r),
            p(0.0, zc + r),
        ],
        Some(vec![1.0, W, 1.0, W, 1.0]),
    )
    .unwrap();
    Profile::new("ball", vec![c]).unwrap()
}

/// Torus: tube of radius `r` about the circle of radius `big_r` at height `zc`.
fn torus(big_r: f64, r: f64, zc: f64) -> Profile {
    let (a, b, c) = (big_r + r, big_r, big_r - r);
    let c = NurbsCurve::new(
        2,
        vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ],
        vec![
            p(a, zc),
            p(a, zc + r),
            p(b, zc + r),
            p(c, zc + r),
            p(c, zc),
            p(c, zc - r),
            p(b, zc - r),
            p(a, zc - r),
            p(a, zc),
        ],
        Some(vec![1.0, W, 1.0, W, 1.0, W, 1.0, W, 1.0]),
    )
    .unwrap();
    Profile::new("torus", vec![c]).unwrap()
}

fn pose(t: [f64; 3], axis: [f64; 3], angle: f64) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(t[0], t[1], t[2]),
        UnitQuaternion::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(axis[0], axis[1], axis[2])),
            angle,
        ),
    )
}

/// Checks the oracle's estimates against a known separation `truth > 0`.
fn assert_apart(a: &PlanarIndex, b: &PlanarIndex, pos: &Isometry3<f64>, truth: f64) {
    let r = surface_distance(a, b, pos, &OracleOptions::full());
    assert!(!r.overlap(), "false overlap, truth {truth}: {r:?}");
    assert!(
        (r.upper - truth).abs() <= 1e-10 * (1.0 + truth),
        "upper {} vs truth {truth}",
        r.upper
    );
    assert!(
        r.lower <= truth + 1e-12,
        "lower {} > truth {truth}",
        r.lower
    );
    assert!(
        r.budget_hit || r.lower >= truth - 2e-4 * (a.geom.size.max(b.geom.size)),
        "lower {} far below truth {truth}",
        r.lower
    );
    // The witness pair realises the distance and lies on the surfaces.
    assert!(((r.point_a - r.point_b).norm() - r.upper).abs() < 1e-12);
    let on = |idx: &PlanarIndex, q: Point3<f64>| idx.closest([q.x.hypot(q.y), q.z]).dist;
    assert!(on(a, r.point_a) < 1e-12);
    assert!(on(b, pos.inverse() * r.point_b) < 1e-12);
}

#[test]
fn sphere_vs_sphere() {
    let s = index(&ball(0.75, 0.75));
    let ca = Vector3::new(0.0, 0.0, 0.75);
    for (i, (t, axis, ang)) in [
        ([3.0, 0.0, 0.0], [1.0, 0.0, 0.0], 0.0),
        ([1.0, 2.0, -0.5], [1.0, 2.0, 3.0], 1.1),
        ([0.0, 0.0, 1.6], [0.0, 0.0, 1.0], 0.3),
        ([1.2, -0.9, 0.4], [-1.0, 0.5, 0.2], 2.9),
        ([1e3, 2.0, -7.0], [0.3, 0.5, 0.2], 0.7),
    ]
    .into_iter()
    .enumerate()
    {
        let pos = pose(t, axis, ang);
        let cb = pos * Point3::new(0.0, 0.0, 0.75);
        let truth = (cb.coords - ca).norm() - 1.5;
        assert!(truth > 0.0, "case {i}");
        assert_apart(&s, &s, &pos, truth);
    }
}

#[test]
fn sphere_overlap_and_nesting() {
    let big = index(&ball(0.75, 0.75));
    let small = index(&ball(0.2, 0.0));
    // Crossing spheres: centres 1.2 apart, radii 0.75 each: depth 0.3.
    let r = surface_distance(
        &big,
        &big,
        &pose([1.2, 0.0, 0.0], [0., 0., 1.], 0.0),
        &OracleOptions::full(),
    );
    assert!(r.overlap() && r.solid_upper() == 0.0);
    assert!(r.min_signed < -0.2, "{}", r.min_signed);
    // Small ball nested inside the big one (centre (0.1, 0, 0.8)): gap 0.75 - 0.2 - |d| .
    let pos = pose([0.1, 0.0, 0.8], [1.0, 1.0, 0.0], 0.4);
    let r = surface_distance(&big, &small, &pos, &OracleOptions::full());
    assert!(r.b_in_a && !r.a_in_b);
    let truth_surface = 0.75 - 0.2 - (0.1f64.hypot(0.05));
    assert!((r.upper - truth_surface).abs() < 1e-10, "{}", r.upper);
    // Swapped roles: A inside B.
    let r = surface_distance(&small, &big, &pos.inverse(), &OracleOptions::full());
    assert!(r.a_in_b && r.overlap());
}

#[test]
fn sphere_vs_torus() {
    let ring = index(&torus(0.9, 0.6, 0.6));
    let ball_idx = index(&ball(0.75, 0.0));
    let small = index(&ball(0.2, 0.0));
    // Distance from a point c to the torus solid, minus the ball radius.
    let truth = |c: Vector3<f64>, rb: f64| {
        let rho = c.x.hypot(c.y);
        ((rho - 0.9).hypot(c.z - 0.6) - 0.6) - rb
    };
    for (t, rb, idx) in [
        ([0.0, 0.0, 2.0], 0.75, &ball_idx),
        ([2.6, 0.4, 0.9], 0.75, &ball_idx),
        ([-1.0, 1.0, -1.2], 0.75, &ball_idx),
        // In the hole: touches the inner equator along a circle if rb = 0.3.
        ([0.0, 0.0, 0.6], 0.2, &small),
        ([0.05, 0.0, 0.7], 0.2, &small),
    ] {
        let pos = pose(t, [0.3, 0.2, 1.0], 0.8);
        let c = Vector3::new(t[0], t[1], t[2]);
        assert_apart(&ring, idx, &pos, truth(c, rb));
        assert_apart(idx, &ring, &pos.inverse(), truth(c, rb));
    }
}

#[test]
fn torus_vs_torus_coaxial() {
    let ring = index(&torus(0.9, 0.6, 0.6));
    // Stacked: tube circles (0.9, 0.6) and (0.9, 0.6 + h): gap h - 1.2.
    for (h, spin) in [(1.5, 0.0), (1.25, 1.3), (2.0, -0.4)] {
        let pos = pose([0.0, 0.0, h], [0.0, 0.0, 1.0], spin);
        assert_apart(&ring, &ring, &pos, h - 1.2);
    }
    // Concentric and coplanar: a thin torus around the ring: gap 2.0 - 0.3 - 1.5.
    let outer = index(&torus(2.0, 0.3, 0.0));
    let pos = pose([0.0, 0.0, 0.6], [0.0, 0.0, 1.0], 0.7);
    assert_apart(&ring, &outer, &pos, 0.2);
    // Interlocked (not coaxial): overlap.
    let pos = pose(
        [0.9, 0.0, 0.6],
        [1.0, 0.0, 0.0],
        std::f64::consts::FRAC_PI_2,
    );
    let r = surface_distance(&ring, &ring, &pos, &OracleOptions::full());
    assert!(r.overlap() || r.upper < 1e-9);
}

#[test]
fn point_in_region_square_and_open_chain() {
    let line = |a: Point2<f64>, b: Point2<f64>| NurbsCurve::line(a, b).unwrap();
    let (a, b, c, d) = (p(1., 0.), p(2., 0.), p(2., 1.), p(1., 1.));
    let sq = index(
        &Profile::new(
            "square ring",
            vec![line(a, b), line(b, c), line(c, d), line(d, a)],
        )
        .unwrap(),
    );
    for (q, want) in [
        ([1.5, 0.5], -0.5),
        ([1.1, 0.3], -0.1),
        ([1.9, 0.95], -0.05),
        ([2.5, 0.5], 0.5),
        ([0.0, 0.5], 1.0),
        ([3.0, 2.0], 2f64.sqrt()),
        ([1.5, -0.25], 0.25),
    ] {
        let s = sq.signed(q);
        assert!(
            (s.value - want).abs() < 1e-14,
            "{q:?}: {} vs {want}",
            s.value
        );
    }
    // Open chain: bottom disk, a slanted side, top disk; closed by the axis.
    let (a, b, c, d) = (p(0., 0.), p(1., 0.), p(0.5, 1.), p(0., 1.));
    let cup = index(&Profile::new("frustum", vec![line(a, b), line(b, c), line(c, d)]).unwrap());
    for (q, inside) in [
        ([0.0, 0.5], true),
        ([0.3, 0.9], true),
        ([0.7, 0.5], true),
        ([0.8, 0.5], false),
        ([0.0, 1.2], false),
        ([0.0, -0.1], false),
        ([0.4, 0.01], true),
    ] {
        assert_eq!(sq_sign(&cup, q), inside, "{q:?}");
    }
    // On the axis inside: the distance is to the curve, not to the axis.
    assert!((cup.signed([0.0, 0.5]).value + 0.5).abs() < 1e-14);
}

fn sq_sign(idx: &PlanarIndex, q: [f64; 2]) -> bool {
    let s = idx.signed(q);
    assert_eq!(s.value < 0.0, idx.inside_poly(q));
    s.value < 0.0
}

/// The oracle against brute force on random freeform pairs: every sample of a dense grid of
/// A's surface (polyline vertices x 720 angles, both directions) gives `poly_distance`; the
/// oracle's realised distance must not exceed the best sample (plus the sagitta), must not
/// undercut the grid's lower bound, and must see the same overlap.
#[test]
fn oracle_agrees_with_brute_force_on_random_profiles() {
    use revdist::rng::SplitMix64;
    use verify::random_profiles::random_profile;
    let mut rng = SplitMix64(2024);
    for case in 0..6 {
        let (sa, sb) = (rng.range(0.6, 1.5), rng.range(0.6, 1.5));
        let (pa, _) = random_profile(&mut rng, "a", sa);
        let (pb, _) = random_profile(&mut rng, "b", sb);
        let (ia, ib) = (index(&pa), index(&pb));
        let q = rng.quaternion();
        let dir = rng.direction();
        let s = rng.range(0.2, 1.2) * (ia.geom.radius + ib.geom.radius);
        let pos = Isometry3::from_parts(
            Translation3::new(dir[0] * s, dir[1] * s, dir[2] * s),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3])),
        );
        let r = surface_distance(&ia, &ib, &pos, &OracleOptions::full());
        let mut best = f64::INFINITY;
        let mut inside_depth: f64 = 0.0;
        let mut h: f64 = 0.0;
        let n_th = 720;
        for (src, dst, map) in [(&ia, &ib, pos.inverse()), (&ib, &ia, pos)] {
            let smp = &src.geom.samples;
            for w in smp.windows(2) {
                h = h.max(0.5 * ((w[1].p[0] - w[0].p[0]).hypot(w[1].p[1] - w[0].p[1])));
            }
            let rho_max = src.geom.max[0];
            h = h.max(rho_max * (std::f64::consts::PI / n_th as f64));
            for sm in smp {
                for k in 0..n_th {
                    let th = k as f64 * std::f64::consts::TAU / n_th as f64;
                    let y = Point3::new(sm.p[0] * th.cos(), sm.p[0] * th.sin(), sm.p[1]);
                    let x = map * y;
                    let q2 = [x.x.hypot(x.y), x.z];
                    let d = dst.poly_distance(q2);
                    best = best.min(d);
                    if d > 2.0 * dst.geom.sag && dst.inside_poly(q2) {
                        inside_depth = inside_depth.max(d - dst.geom.sag);
                    }
                }
            }
        }
        let sag = ia.geom.sag.max(ib.geom.sag);
        let overlap = inside_depth > 2.0 * h;
        if overlap {
            assert!(
                r.overlap(),
                "case {case}: brute force finds depth {inside_depth}"
            );
            continue;
        }
        if inside_depth == 0.0 {
            assert!(
                !r.overlap(),
                "case {case}: oracle overlap, brute force none"
            );
        }
        assert!(
            r.upper <= best + sag + 1e-12,
            "case {case}: oracle {} above a brute-force sample {best}",
            r.upper
        );
        assert!(
            r.upper >= best - sag - 2.0 * h - 1e-12,
            "case {case}: oracle {} below brute-force bound {best} - {h}",
            r.upper
        );
        assert!(r.lower <= r.upper);
    }
}

/// Within a sagitta of the curve the sign comes from the tangent side, not the polygon: a
/// circle's chords cut inside it, so points just inside the circle near a chord midpoint
/// are outside the polygon. Both orientations.
#[test]
fn sign_next_to_a_curved_boundary() {
    let ring = torus(0.9, 0.6, 0.6);
    let reversed = Profile::new(
        "cw torus",
        ring.pieces().iter().rev().map(|c| c.reversed()).collect(),
    )
    .unwrap();
    for prof in [&ring, &reversed] {
        let idx = index(prof);
        assert!(idx.geom.sag > 1e-9, "{}", idx.geom.sag);
        for k in 0..97 {
            let phi = k as f64 * 0.0647;
            for off in [1e-11, 1e-9, 0.3 * idx.geom.sag, 3.0 * idx.geom.sag, 0.2] {
                for sgn in [-1.0, 1.0] {
                    let r = 0.6 + sgn * off;
                    let q = [0.9 + r * phi.cos(), 0.6 + r * phi.sin()];
                    let s = idx.signed(q);
                    assert!(
                        (s.value - sgn * off).abs() < 1e-13,
                        "{}: phi {phi} offset {}: {}",
                        prof.name(),
                        sgn * off,
                        s.value
                    );
                }
            }
        }
    }
}

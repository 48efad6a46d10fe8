use super::*;
use proptest::prelude::*;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

fn p(x: f64, y: f64) -> Point2<f64> {
    Point2::new(x, y)
}

/// The unit-radius full circle as nine-point rational quadratic (exact conic).
fn unit_circle(center: Point2<f64>, r: f64) -> NurbsCurve {
    let w = FRAC_1_SQRT_2;
    let pts = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    NurbsCurve::new(
        2,
        vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.],
        pts.iter()
            .map(|&(x, y)| p(center.x + r * x, center.y + r * y))
            .collect(),
        Some(vec![1., w, 1., w, 1., w, 1., w, 1.]),
    )
    .unwrap()
}

#[test]
fn quadratic_bezier_hand_values() {
    let c = NurbsCurve::bezier(vec![p(0., 0.), p(1., 2.), p(2., 0.)]).unwrap();
    let d = c.derivatives(0.5);
    assert_eq!(d[0], Vector2::new(1.0, 1.0));
    assert_eq!(d[1], Vector2::new(2.0, 0.0));
    assert_eq!(d[2], Vector2::new(0.0, -8.0));
    assert_eq!(d[3], Vector2::zeros());
    // Curvature at the apex: |x' z'' - z' x''| / |C'|^3 = 16 / 8.
    assert!((c.curvature(0.5) + 2.0).abs() < 1e-15);
}

#[test]
fn cubic_bspline_derivatives_match_finite_differences() {
    let c = NurbsCurve::new(
        3,
        vec![0., 0., 0., 0., 0.3, 0.7, 1., 1., 1., 1.],
        vec![
            p(0., 0.),
            p(1., 2.),
            p(2., -1.),
            p(3., 3.),
            p(4., 0.),
            p(5., 1.),
        ],
        Some(vec![1.0, 2.0, 0.5, 1.5, 1.0, 0.7]),
    )
    .unwrap();
    let h = 1e-5;
    for &t in &[0.1, 0.35, 0.5, 0.8] {
        let d = c.derivatives(t);
        let (dm, dp) = (c.derivatives(t - h), c.derivatives(t + h));
        for k in 1..=3 {
            let fd = (dp[k - 1] - dm[k - 1]) / (2.0 * h);
            assert!(
                (fd - d[k]).norm() <= 1e-5 * (1.0 + d[k].norm()),
                "order {k} at t={t}: {fd} vs {}",
                d[k]
            );
        }
        let fd_kappa = (c.curvature(t + h) - c.curvature(t - h)) / (2.0 * h);
        assert!((fd_kappa - c.curvature_derivative(t)).abs() < 1e-4 * (1.0 + fd_kappa.abs()));
    }
}

#[test]
fn rational_circle_points_are_at_radius() {
    let center = p(3.0, -1.0);
    let c = unit_circle(center, 0.75);
    for i in 0..=1000 {
        let t = i as f64 / 1000.0;
        let dist = (c.eval(t) - center).norm();
        assert!((dist - 0.75).abs() <= 1e-15, "t={t}: {dist}");
        assert!((c.curvature(t) - 1.0 / 0.75).abs() < 1e-12);
    }
    assert!((c.arc_length(1e-12) - 2.0 * PI * 0.75).abs() < 1e-10);
}

#[test]
fn line_length_and_box() {
    let c = NurbsCurve::line(p(1.0, 1.0), p(4.0, 5.0)).unwrap();
    assert!((c.arc_length(1e-12) - 5.0).abs() < 1e-12);
    let b = c.bounding_box();
    assert_eq!((b.min, b.max), (p(1., 1.), p(4., 5.)));
}

#[test]
fn errors_name_the_problem() {
    let pts = vec![p(0., 0.), p(1., 1.), p(2., 0.)];
    let k = vec![0., 0., 0., 1., 1., 1.];
    use CurveError::*;
    assert!(matches!(
        NurbsCurve::new(0, k.clone(), pts.clone(), None),
        Err(ZeroDegree(0))
    ));
    assert!(matches!(
        NurbsCurve::new(2, vec![0., 0., 0., 1., 1.], pts.clone(), None),
        Err(WrongKnotCount {
            expected: 6,
            found: 5,
            ..
        })
    ));
    assert!(matches!(
        NurbsCurve::new(1, vec![0., 0., 0.6, 0.4, 1.], pts.clone(), None),
        Err(DecreasingKnots { index: 3, .. })
    ));
    assert!(matches!(
        NurbsCurve::new(2, vec![0., 0., 0.5, 1., 1., 1.], pts.clone(), None),
        Err(NotClamped { .. })
    ));
    assert!(matches!(
        NurbsCurve::new(2, k.clone(), pts.clone(), Some(vec![1., 0., 1.])),
        Err(NonPositiveWeight { index: 1, .. })
    ));
    assert!(matches!(
        NurbsCurve::new(2, k.clone(), pts.clone(), Some(vec![1., 1.])),
        Err(WrongWeightCount { .. })
    ));
    assert!(matches!(
        NurbsCurve::new(
            2,
            k.clone(),
            vec![p(0., 0.), p(f64::NAN, 1.), p(2., 0.)],
            None
        ),
        Err(NonFinite {
            what: "control point",
            index: 1
        })
    ));
    assert!(matches!(
        NurbsCurve::new(
            2,
            vec![0., 0., 0., f64::INFINITY, f64::INFINITY, f64::INFINITY],
            pts.clone(),
            None
        ),
        Err(NonFinite {
            what: "knot",
            index: 3
        })
    ));
    assert!(matches!(
        NurbsCurve::new(2, vec![1., 1., 1., 1., 1., 1.], pts.clone(), None),
        Err(EmptyDomain { .. })
    ));
    assert!(matches!(
        NurbsCurve::new(
            1,
            vec![0., 0., 0.5, 0.5, 0.5, 1., 1.],
            vec![p(0., 0.); 5],
            None
        ),
        Err(KnotMultiplicity {
            multiplicity: 3,
            ..
        })
    ));
    assert!(matches!(
        NurbsCurve::new(2, k.clone(), vec![p(0., 0.), p(1., 1.)], None),
        Err(TooFewPoints { .. })
    ));
    let c = NurbsCurve::new(2, k, pts, None).unwrap();
    assert!(matches!(c.split(0.0), Err(ParameterOutOfRange { .. })));
    assert!(matches!(c.split(f64::NAN), Err(ParameterOutOfRange { .. })));
}

/// A random clamped B-spline: degree 1..=4, 0..=4 interior knots, optional weights.
fn arb_curve() -> impl Strategy<Value = NurbsCurve> {
    (1usize..=4, 0usize..=4, any::<bool>()).prop_flat_map(|(degree, interior, rational)| {
        let n = degree + 1 + interior;
        (
            proptest::collection::vec(0.05f64..0.95, interior),
            proptest::collection::vec((0.0f64..3.0, -2.0f64..2.0), n),
            proptest::collection::vec(0.2f64..5.0, n),
            -3.0f64..3.0,
            0.5f64..4.0,
        )
            .prop_map(move |(mut ks, pts, ws, shift, scale)| {
                ks.sort_by(f64::total_cmp);
                let mut knots = vec![shift; degree + 1];
                knots.extend(ks.iter().map(|k| shift + scale * k));
                knots.extend(std::iter::repeat_n(shift + scale, degree + 1));
                let pts = pts.into_iter().map(|(x, y)| p(x, y)).collect();
                NurbsCurve::new(degree, knots, pts, rational.then_some(ws)).unwrap()
            })
    })
}

/// Relative tolerance for curve identities that only reorder floating-point operations
/// (knot insertion, reversal, Bezier extraction): a few hundred ulps of the coordinates.
const REWRITE_TOLERANCE: f64 = 1e-12;

proptest! {
    #[test]
    fn split_preserves_the_curve(c in arb_curve(), u in 0.01f64..0.99) {
        let (a, b) = c.domain();
        let t = a + u * (b - a);
        let (l, r) = c.split(t).unwrap();
        prop_assert_eq!(l.domain(), (a, t));
        prop_assert_eq!(r.domain(), (t, b));
        prop_assert!((l.end() - r.start()).norm() <= REWRITE_TOLERANCE * 10.0);
        for i in 0..=50 {
            let s = a + (b - a) * i as f64 / 50.0;
            let piece = if s <= t { &l } else { &r };
            prop_assert!((piece.eval(s) - c.eval(s)).norm() <= REWRITE_TOLERANCE * 10.0);
        }
    }

    #[test]
    fn reversal_traces_backwards(c in arb_curve(), u in 0.0f64..=1.0) {
        let (a, b) = c.domain();
        let t = a + u * (b - a);
        let r = c.reversed();
        prop_assert!((r.eval(a + b - t) - c.eval(t)).norm() <= REWRITE_TOLERANCE);
        let (dc, dr) = (c.derivatives(t), r.derivatives(a + b - t));
        prop_assert!((dc[1] + dr[1]).norm() <= 1e-9 * (1.0 + dc[1].norm()));
        prop_assert!((c.curvature(t) + r.curvature(a + b - t)).abs() <= 1e-8 * (1.0 + c.curvature(t).abs()));
    }

    #[test]
    fn bezier_spans_trace_the_curve(c in arb_curve(), u in 0.0f64..=1.0) {
        for span in c.bezier_spans() {
            prop_assert_eq!(span.homogeneous.len(), c.degree() + 1);
            let t = span.t0 + u * (span.t1 - span.t0);
            prop_assert!((span.eval_local(u) - c.eval(t)).norm() <= REWRITE_TOLERANCE * 10.0);
        }
    }

    #[test]
    fn control_box_contains_curve(c in arb_curve(), u in 0.0f64..=1.0) {
        let (a, b) = c.domain();
        let q = c.eval(a + u * (b - a));
        let bx = c.bounding_box();
        prop_assert!(q.x >= bx.min.x - 1e-12 && q.x <= bx.max.x + 1e-12);
        prop_assert!(q.y >= bx.min.y - 1e-12 && q.y <= bx.max.y + 1e-12);
    }

    #[test]
    fn basis_is_a_partition_of_unity(c in arb_curve(), u in 0.0f64..=1.0) {
        let (a, b) = c.domain();
        let (_, n) = basis_functions(c.degree(), c.knots(), a + u * (b - a));
        prop_assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        prop_assert!(n.iter().all(|&v| v >= -1e-15));
    }
}

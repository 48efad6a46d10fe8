//! Checks of the built-in models against dense sampling and hand-derived geometry.

use nalgebra::Point2;

use super::morph::{Morph, KEYFRAME_NAMES, MORPH_BLOCKS};
use super::primitives::{arc, deg};
use super::sampling::sample_profile;
use super::validate::{min_interior_rho, polyline_self_intersection};
use super::*;
use crate::nurbs::NurbsCurve;
use crate::profile::ProfileKind;

/// Samples per knot span for the polyline checks: chord error below 1e-5 for the models'
/// tightest curvature radius (0.025) and spans of at most a quarter turn.
const CHECK_SAMPLES_PER_SPAN: usize = 128;
/// Curvature magnitude (1/units) above which a sample counts as clearly curved. The models'
/// curved pieces have radii of curvature below 20 units; straight pieces evaluate to
/// |curvature| of rounding size (about 1e-12).
const CURVED: f64 = 0.05;
/// Fraction of the samples at each end of an open profile left out when checking that the
/// interior stays off the axis (the ends lie on it by definition).
const END_FRACTION: f64 = 0.005;
/// Tangent turn (radians) above which a join is a crease (about 3 degrees).
const CREASE: f64 = 0.05;
/// Curvature below which every sample of a piece makes it straight: rounding of the curvature
/// of a straight NURBS piece of size 1 (about 1e-13), with margin.
const STRAIGHT_CURVATURE: f64 = 1e-9;
/// Coordinate difference below which a straight piece is vertical or horizontal (the models
/// write such pieces with equal coordinates, so the difference is exactly 0).
const AXIS_ALIGNED: f64 = 1e-12;
/// Distance bound for points of exact rational circles and straight lines: a few ulps of
/// coordinates of size 1 (the rational evaluation rounds each of its few operations once).
const EXACT: f64 = 1e-15;
/// Bound on the chord error of the dense source samples (see [`SOURCE_SAMPLES_PER_SPAN`]),
/// with margin: 1e-6.
const SOURCE_CHORD_ERROR: f64 = 1e-6;

fn signed_curvature(piece: &NurbsCurve, t: f64) -> f64 {
    let d = piece.derivatives(t);
    d[1].perp(&d[2]) / d[1].norm().powi(3)
}

fn unit_tangent(piece: &NurbsCurve, t: f64) -> nalgebra::Vector2<f64> {
    piece.derivatives(t)[1].normalize()
}

/// Parameters at which a piece is sampled for curvature: interior of every knot span.
fn interior_params(piece: &NurbsCurve, per_span: usize) -> Vec<f64> {
    piece
        .distinct_spans()
        .into_iter()
        .flat_map(|(t0, t1)| {
            (1..per_span).map(move |k| t0 + (t1 - t0) * k as f64 / per_span as f64)
        })
        .collect()
}

/// Features found in one profile.
#[derive(Debug, Default)]
struct Features {
    inflections: usize,
    concave_samples: usize,
    creases: usize,
    cylinders: usize,
    cones: usize,
    disks: usize,
    axis_contacts: usize,
}

fn features(profile: &Profile) -> Features {
    let mut f = Features::default();
    for piece in profile.pieces() {
        let kappas: Vec<f64> = interior_params(piece, 64)
            .into_iter()
            .map(|t| signed_curvature(piece, t))
            .collect();
        f.concave_samples += kappas.iter().filter(|&&k| k < -CURVED).count();
        let signs: Vec<f64> = kappas
            .iter()
            .filter(|k| k.abs() > CURVED)
            .map(|k| k.signum())
            .collect();
        f.inflections += signs.windows(2).filter(|w| w[0] != w[1]).count();
        let (t0, t1) = piece.domain();
        let (a, b) = (piece.eval(t0), piece.eval(t1));
        let straight = kappas.iter().all(|k| k.abs() < STRAIGHT_CURVATURE);
        if straight {
            let d = b - a;
            if d.x.abs() < AXIS_ALIGNED {
                f.cylinders += 1;
            } else if d.y.abs() < AXIS_ALIGNED {
                f.disks += 1;
            } else {
                f.cones += 1;
            }
        }
    }
    for pair in profile.pieces().windows(2) {
        let before = unit_tangent(&pair[0], pair[0].domain().1);
        let after = unit_tangent(&pair[1], pair[1].domain().0);
        if before.perp(&after).atan2(before.dot(&after)).abs() > CREASE {
            f.creases += 1;
        }
    }
    let pieces = profile.pieces();
    let start = pieces[0].eval(pieces[0].domain().0);
    let last = &pieces[pieces.len() - 1];
    let end = last.eval(last.domain().1);
    f.axis_contacts = usize::from(start.x == 0.0) + usize::from(end.x == 0.0);
    f
}

/// Signed area enclosed by the sampled profile closed along the axis (shoelace formula).
fn signed_area(profile: &Profile) -> f64 {
    let pts = sample_profile(profile, CHECK_SAMPLES_PER_SPAN);
    let n = pts.len();
    (0..n)
        .map(|i| {
            let (p, q) = (pts[i], pts[(i + 1) % n]);
            p.x * q.y - q.x * p.y
        })
        .sum::<f64>()
        * 0.5
}

#[test]
fn every_model_is_a_valid_profile_of_height_one_to_two() {
    for name in model_names() {
        let profile = model(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(profile.name(), *name);
        let pts = sample_profile(&profile, CHECK_SAMPLES_PER_SPAN);
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.y), hi.max(p.y))
            });
        let height = hi - lo;
        assert!((1.0..=2.0).contains(&height), "{name}: height {height}");
        let expected = if *name == "ring" {
            ProfileKind::Closed
        } else {
            ProfileKind::OpenOnAxis
        };
        assert_eq!(profile.kind(), expected, "{name}");
        assert!(pts.iter().all(|p| p.x >= 0.0), "{name}: rho < 0");
        assert_eq!(
            polyline_self_intersection(&profile, CHECK_SAMPLES_PER_SPAN),
            None,
            "{name} crosses itself"
        );
        // Only the ends touch the axis.
        assert!(
            min_interior_rho(&profile, CHECK_SAMPLES_PER_SPAN, END_FRACTION) > 0.0,
            "{name}"
        );
        assert!(
            signed_area(&profile) > 0.0,
            "{name} is not counter-clockwise"
        );
    }
}

#[test]
fn model_heights_match_their_documentation() {
    let expected = [
        ("pawn", 1.48),
        ("cup", 1.225),
        ("bottle", 1.70),
        ("table", 1.46),
        ("lightmill", 1.94),
        ("ring", 1.2),
        ("sphere", 1.5),
        ("capsule", 1.6),
        ("cylinder", 1.5),
        ("cone", 1.5),
    ];
    for (name, height) in expected {
        let pts = sample_profile(&model(name).unwrap(), CHECK_SAMPLES_PER_SPAN);
        let top = pts.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        let bottom = pts.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        assert!(
            (top - bottom - height).abs() < SOURCE_CHORD_ERROR,
            "{name}: {}",
            top - bottom
        );
    }
}

#[test]
fn paper_models_together_have_every_required_feature() {
    let found: Vec<(&str, Features)> = KEYFRAME_NAMES
        .iter()
        .map(|name| (*name, features(&model(name).unwrap())))
        .collect();
    let get = |name: &str| &found.iter().find(|(n, _)| *n == name).unwrap().1;
    // Per model, as documented in paper.rs.
    assert!(get("pawn").inflections >= 1, "{:?}", get("pawn"));
    assert!(get("bottle").inflections >= 1, "{:?}", get("bottle"));
    for name in ["pawn", "cup", "table", "lightmill"] {
        assert!(get(name).concave_samples > 0, "{name}: {:?}", get(name));
    }
    assert!(get("pawn").creases >= 3, "{:?}", get("pawn"));
    assert!(get("lightmill").creases >= 8, "{:?}", get("lightmill"));
    assert!(get("lightmill").cones >= 2, "{:?}", get("lightmill"));
    assert!(get("table").cylinders >= 3, "{:?}", get("table"));
    for (name, f) in &found {
        assert_eq!(f.axis_contacts, 2, "{name}");
        assert!(f.disks >= 1, "{name}: {f:?}");
        assert!(f.creases >= 1, "{name}: {f:?}");
    }
}

#[test]
fn analytic_models_are_exact() {
    // Every sample of the ring lies on the circle of radius 0.6 about (0.9, 0.6).
    let ring = model("ring").unwrap();
    for p in sample_profile(&ring, 97) {
        let r = (p - Point2::new(0.9, 0.6)).norm();
        assert!((r - 0.6).abs() < EXACT, "r = {r}");
    }
    let sphere = model("sphere").unwrap();
    for p in sample_profile(&sphere, 97) {
        assert!(((p - Point2::new(0.0, 0.75)).norm() - 0.75).abs() < EXACT);
    }
    // The cone's degree-2 slant is the straight line rho = 0.6 (1 - z / 1.5).
    let cone = model("cone").unwrap();
    assert_eq!(cone.pieces()[1].degree(), 2);
    for p in sample_profile(&cone, 50).iter().skip(1) {
        if p.y > 0.0 {
            assert!((p.x - 0.6 * (1.0 - p.y / 1.5)).abs() < EXACT, "{p}");
        }
    }
    // Clockwise arcs (used for the cup's fillet) run the other way round.
    let cw = arc([0.0, 0.0], 1.0, 0.0, deg(-90.0)).unwrap();
    let mid = cw.eval(0.5 * (cw.domain().0 + cw.domain().1));
    assert!((mid - Point2::new(0.5f64.sqrt(), -(0.5f64.sqrt()))).norm() < EXACT);
}

#[test]
fn unknown_names_list_the_valid_ones() {
    let err = model("knight").unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, ModelError::UnknownModel { .. }));
    for name in model_names() {
        assert!(text.contains(name), "{text}");
    }
    assert!(matches!(
        model("morph@abc"),
        Err(ModelError::BadMorphName(_))
    ));
    assert!(matches!(
        model("morph@nan"),
        Err(ModelError::BadMorphName(_))
    ));
    assert!(model("morph@0.3").is_ok());
}

/// Bound on the maximum deviation of each fitted keyframe from its source profile (units;
/// the models are 1.2 to 2 units tall). Measured: pawn 4.0e-5, cup 5.4e-5, bottle 2.6e-6,
/// table 1.4e-5, lightmill 1.9e-6 (printed by the test).
const MORPH_FIT_BOUND: f64 = 1e-4;

#[test]
fn morph_keyframes_fit_their_sources() {
    let morph = Morph::shared().unwrap();
    for report in morph.fit_reports() {
        println!("{report:?}");
        assert!(report.max_deviation < MORPH_FIT_BOUND, "{report:?}");
    }
    // Independent check of the reported error: closest-point distance from dense samples of
    // each fitted keyframe frame to the dense source polyline.
    for (k, name) in KEYFRAME_NAMES.iter().enumerate() {
        let fitted = morph.frame(k as f64 / 5.0).unwrap();
        let source = sample_profile(&model(name).unwrap(), SOURCE_SAMPLES_PER_SPAN);
        let worst = sample_profile(&fitted, 16)
            .iter()
            .map(|p| distance_to_polyline(*p, &source))
            .fold(0.0, f64::max);
        assert!(
            worst <= morph.fit_reports()[k].max_deviation + SOURCE_CHORD_ERROR,
            "{name}: {worst}"
        );
        // Interior control points have rho > 0: the premise of the convex-hull argument.
        let points = morph.keyframe_points(k).unwrap();
        assert_eq!(points[0].x, 0.0);
        assert_eq!(points[points.len() - 1].x, 0.0);
        assert!(
            points[1..points.len() - 1].iter().all(|p| p.x > 0.0),
            "{name}"
        );
    }
}

/// Source samples per knot span for the closest-point check: the chord error
/// (curvature * step^2 / 8) stays below 1e-7 for the sharpest source span (the bottle's
/// shoulder, curvature about 10 over length 0.5).
const SOURCE_SAMPLES_PER_SPAN: usize = 2048;

fn distance_to_polyline(p: Point2<f64>, line: &[Point2<f64>]) -> f64 {
    line.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let s = ((p - w[0]).dot(&d) / d.norm_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
            (p - (w[0] + d * s)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn morph_frames_are_valid_profiles_at_1000_frames() {
    let morph = Morph::shared().unwrap();
    let mut points = Vec::new();
    for j in 0..1000 {
        let t = j as f64 / 1000.0;
        let frame = morph.frame(t).unwrap_or_else(|e| panic!("t = {t}: {e}"));
        assert_eq!(frame.kind(), ProfileKind::OpenOnAxis);
        assert_eq!(frame.pieces().len(), MORPH_BLOCKS);
        assert_eq!(
            polyline_self_intersection(&frame, 16),
            None,
            "frame t = {t} crosses itself"
        );
        assert!(min_interior_rho(&frame, 16, END_FRACTION) > 0.0, "t = {t}");
        // The allocation-reusing variant gives the same control points.
        morph.control_points_into(t, &mut points).unwrap();
        let flat: Vec<Point2<f64>> = frame
            .pieces()
            .iter()
            .enumerate()
            .flat_map(|(i, p)| p.points().iter().skip(usize::from(i > 0)).copied())
            .collect();
        assert_eq!(flat, points);
    }
}

/// Control point difference allowed between t and t + 1 (or t - 1): wrapping t rounds it
/// by an ulp of 1, which moves control points by about 1e-15.
const WRAP_ROUNDING: f64 = 1e-12;

/// Largest distance between corresponding points of two control point lists.
fn max_gap(a: &[Point2<f64>], b: &[Point2<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

#[test]
fn morph_interpolates_keyframes_wraps_and_moves_continuously() {
    let morph = Morph::shared().unwrap();
    let mut a = Vec::new();
    let mut b = Vec::new();
    for k in 0..5 {
        morph.control_points_into(k as f64 / 5.0, &mut a).unwrap();
        assert_eq!(a.as_slice(), morph.keyframe_points(k).unwrap());
    }
    morph.control_points_into(0.37, &mut a).unwrap();
    morph.control_points_into(1.37, &mut b).unwrap();
    let gap = max_gap(&a, &b);
    assert!(gap < WRAP_ROUNDING, "{gap}");
    morph.control_points_into(-0.63, &mut b).unwrap();
    let gap = max_gap(&a, &b);
    assert!(gap < WRAP_ROUNDING, "{gap}");
    // Lipschitz in t: the smootherstep blend moves a control point by at most
    // 5 * 1.875 * max |P_k - P_k+1| * dt (1.875 = max slope of smootherstep, 5 keyframes).
    let widest = (0..5)
        .map(|k| {
            max_gap(
                morph.keyframe_points(k).unwrap(),
                morph.keyframe_points((k + 1) % 5).unwrap(),
            )
        })
        .fold(0.0, f64::max);
    let dt = 1e-4;
    for j in 0..200 {
        let t = j as f64 / 200.0;
        morph.control_points_into(t, &mut a).unwrap();
        morph.control_points_into(t + dt, &mut b).unwrap();
        let step = max_gap(&a, &b);
        assert!(
            step <= 5.0 * 1.875 * widest * dt * (1.0 + 1e-9),
            "t = {t}: {step}"
        );
    }
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            morph::morph(bad),
            Err(ModelError::NonFiniteMorphParameter(_))
        ));
    }
}

/// Fraction of the keyframes' narrowest [`clearance`] that every frame must keep: a frame
/// coming much closer to itself than any keyframe would be pinching on its way to a crossing.
const MORPH_MIN_CLEARANCE_FRACTION: f64 = 0.9;

/// Arc length along the profile beyond which two points count as "far apart along the curve"
/// for the clearance check (about twice the models' thinnest features, 0.05 to 0.08 thick).
const CLEARANCE_SEPARATION: f64 = 0.15;

/// Smallest distance between two samples of the profile that lie at least
/// [`CLEARANCE_SEPARATION`] apart along it: how close the profile comes to touching itself.
fn clearance(profile: &Profile) -> f64 {
    let points = sample_profile(profile, 8);
    let mut along = vec![0.0];
    for w in points.windows(2) {
        along.push(along[along.len() - 1] + (w[1] - w[0]).norm());
    }
    let mut gap = f64::INFINITY;
    for i in 0..points.len() {
        let first = along.partition_point(|&s| s < along[i] + CLEARANCE_SEPARATION);
        for j in first..points.len() {
            gap = gap.min((points[i] - points[j]).norm());
        }
    }
    gap
}

#[test]
fn morph_frames_keep_their_pieces_apart() {
    let morph = Morph::shared().unwrap();
    let keyframe_gap = (0..5)
        .map(|k| clearance(&morph.frame(k as f64 / 5.0).unwrap()))
        .fold(f64::INFINITY, f64::min);
    println!("narrowest keyframe clearance {keyframe_gap}");
    assert!(keyframe_gap > 0.03, "{keyframe_gap}");
    let mut narrowest = f64::INFINITY;
    for j in 0..200 {
        let t = (j as f64 + 0.5) / 200.0;
        let gap = clearance(&morph.frame(t).unwrap());
        narrowest = narrowest.min(gap);
        assert!(
            gap > MORPH_MIN_CLEARANCE_FRACTION * keyframe_gap,
            "t = {t}: gap {gap}, keyframes {keyframe_gap}"
        );
    }
    println!("narrowest frame clearance {narrowest}");
}

#[test]
fn every_model_and_morph_frames_build_biarc_trees() {
    use crate::biarc::tree::BiarcTree;
    for name in model_names() {
        for eps in [1e-3, 1e-5] {
            let tree = BiarcTree::build(&model(name).unwrap(), eps)
                .unwrap_or_else(|e| panic!("{name} at eps {eps}: {e}"));
            println!("{name} eps {eps}: {:?}", tree.stats());
        }
    }
    let morph = Morph::shared().unwrap();
    let mut tree = BiarcTree::build(&morph.frame(0.0).unwrap(), 1e-4).unwrap();
    for j in 0..50 {
        let t = (j as f64 + 0.5) / 50.0;
        tree.rebuild(&morph.frame(t).unwrap(), 1e-4)
            .unwrap_or_else(|e| panic!("morph@{t}: {e}"));
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Any finite t (wrapped into [0, 1)) gives a simple open profile whose interior stays off
    /// the axis, and `morph@t` by name is the same frame.
    #[test]
    fn morph_at_any_finite_t_is_a_simple_profile(t in -10.0f64..10.0) {
        let frame = morph::morph(t).unwrap();
        proptest::prop_assert_eq!(frame.kind(), ProfileKind::OpenOnAxis);
        proptest::prop_assert_eq!(polyline_self_intersection(&frame, 16), None);
        proptest::prop_assert!(min_interior_rho(&frame, 16, END_FRACTION) > 0.0);
        let named = model(&format!("morph@{t}")).unwrap();
        proptest::prop_assert_eq!(named.pieces(), frame.pieces());
    }
}
/// Tangent turn (radians) allowed at a frame's block joint that is smooth in both keyframes
/// being blended: rounding of the handle alignment (about 1e-13 measured).
const FRAME_G1_TURN: f64 = 1e-9;

#[test]
fn morph_frames_are_g1_where_both_keyframes_are() {
    let morph = Morph::shared().unwrap();
    let keyframes: Vec<Profile> = (0..5)
        .map(|k| morph.frame(k as f64 / 5.0).unwrap())
        .collect();
    let turn = |p: &Profile, i: usize| {
        let (a, b) = (&p.pieces()[i], &p.pieces()[i + 1]);
        let u = unit_tangent(a, a.domain().1);
        let v = unit_tangent(b, b.domain().0);
        u.perp(&v).atan2(u.dot(&v)).abs()
    };
    let mut checked = 0;
    for j in 0..500 {
        let t = (j as f64 + 0.5) / 500.0;
        let frame = morph.frame(t).unwrap();
        let k = (t * 5.0).floor() as usize;
        for i in 0..MORPH_BLOCKS - 1 {
            let smooth = |p: &Profile| turn(p, i) < FRAME_G1_TURN;
            if smooth(&keyframes[k]) && smooth(&keyframes[(k + 1) % 5]) {
                checked += 1;
                assert!(
                    turn(&frame, i) < FRAME_G1_TURN,
                    "t = {t}, joint {i}: {}",
                    turn(&frame, i)
                );
            }
        }
    }
    assert!(checked > 1000, "{checked}");
}

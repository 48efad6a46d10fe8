//! Checks of the freeform variants ([`super`]) against their exact models.

use std::sync::Arc;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};

use super::{fit_report, FREEFORM_FIT_TOLERANCE, FREEFORM_NAMES, FREEFORM_SOURCES};
use crate::biarc::tree::BiarcTree;
use crate::models::fit::{chain_tangents, unit_tangent, Join};
use crate::models::validate::{min_interior_rho, polyline_self_intersection, sampled_hausdorff};
use crate::models::*;
use crate::profile::ProfileKind;
use crate::query::{distance, QueryOptions};
use crate::solid::Solid;

/// Bound on the two-sided Hausdorff distance between each variant and its exact model
/// (units; the models are 1.2 to 2 units tall), measured by [`sampled_hausdorff`]: the
/// accuracy asked of the variants' silhouettes. The fit aims at half of it
/// ([`FREEFORM_FIT_TOLERANCE`]).
const FREEFORM_HAUSDORFF_BOUND: f64 = 1e-4;

/// Samples per knot span for the Hausdorff measurement. The exact models' spans are at most a
/// quarter turn of radius 0.26 or a straight or gently curved piece up to 0.85 long, so the
/// chord error is below 1e-7; the variants' spans are shorter still.
const HAUSDORFF_SAMPLES_PER_SPAN: usize = 1024;

/// Relative amount by which the sampled Hausdorff distance may exceed the fit's reported
/// deviation: the deviation is a maximum over [`super::ERROR_SAMPLES_PER_SPAN`]
/// samples per span and can miss the peak between two of them by about a percent.
const DEVIATION_SAMPLING_MARGIN: f64 = 0.05;

/// Samples per span for the polyline checks (self-intersection, clearance of the axis).
const CHECK_SAMPLES_PER_SPAN: usize = 64;

/// Fraction of the samples at each end left out when checking that the interior stays off
/// the axis (the ends lie on it by definition).
const END_FRACTION: f64 = 0.005;

/// Angle (radians) allowed between a variant's end tangent and the exact model's one-sided
/// tangent at the same crease or axis end: the fit puts the handle exactly on the tangent
/// line, so only rounding (about 1e-15) separates them.
const TANGENT_MATCH: f64 = 1e-9;

fn variants() -> Vec<(&'static str, Profile, Profile)> {
    FREEFORM_NAMES
        .iter()
        .zip(FREEFORM_SOURCES)
        .map(|(ff, exact)| (*ff, model(ff).unwrap(), model(exact).unwrap()))
        .collect()
}

fn angle(u: Vector2<f64>, v: Vector2<f64>) -> f64 {
    u.perp(&v).atan2(u.dot(&v)).abs()
}

#[test]
fn variants_are_valid_profiles_on_the_axis_in_the_half_plane() {
    for (name, ff, exact) in variants() {
        assert_eq!(ff.name(), name);
        assert_eq!(ff.kind(), ProfileKind::OpenOnAxis, "{name}");
        let pieces = ff.pieces();
        assert_eq!(pieces[0].start(), exact.pieces()[0].start(), "{name}");
        assert_eq!(pieces[0].start().x, 0.0, "{name}");
        assert_eq!(pieces[pieces.len() - 1].end().x, 0.0, "{name}");
        for (i, piece) in pieces.iter().enumerate() {
            assert_eq!(piece.degree(), 3, "{name} piece {i}");
            assert!(piece.weights().is_none(), "{name} piece {i} is rational");
            assert!(
                piece.points().iter().all(|p| p.x >= 0.0),
                "{name} piece {i}"
            );
            // Clamped, interior knots simple: each piece is C2 inside.
            let knots = piece.knots();
            assert!(knots[..4].iter().all(|&k| k == 0.0), "{name} piece {i}");
            assert!(knots[knots.len() - 4..].iter().all(|&k| k == 1.0));
            let interior = &knots[4..knots.len() - 4];
            assert!(interior.windows(2).all(|w| w[0] < w[1]), "{name} piece {i}");
        }
        assert_eq!(
            polyline_self_intersection(&ff, CHECK_SAMPLES_PER_SPAN),
            None,
            "{name} crosses itself"
        );
        assert!(
            min_interior_rho(&ff, CHECK_SAMPLES_PER_SPAN, END_FRACTION) > 0.0,
            "{name}"
        );
        // Same model from the cache: identical.
        assert_eq!(model(name).unwrap(), ff);
    }
}

#[test]
fn variants_have_one_piece_per_smooth_run_with_the_exact_corners() {
    for (name, ff, exact) in variants() {
        let source = chain_tangents(exact.pieces()).unwrap();
        let ours = chain_tangents(ff.pieces()).unwrap();
        let creases: Vec<(usize, Vector2<f64>, Vector2<f64>)> = source
            .joins
            .iter()
            .enumerate()
            .filter_map(|(i, j)| match *j {
                Join::Crease { before, after } => Some((i, before, after)),
                Join::Smooth(_) => None,
            })
            .collect();
        assert_eq!(ff.pieces().len(), creases.len() + 1, "{name}");
        // Every join of the variant is one of the source's creases: same point, same
        // one-sided tangents.
        for (k, (join, &(i, before, after))) in ours.joins.iter().zip(&creases).enumerate() {
            let Join::Crease {
                before: b,
                after: a,
            } = *join
            else {
                panic!("{name}: join {k} is smooth");
            };
            assert!(angle(b, before) < TANGENT_MATCH, "{name} crease {k}");
            assert!(angle(a, after) < TANGENT_MATCH, "{name} crease {k}");
            assert_eq!(ff.pieces()[k].end(), exact.pieces()[i].end(), "{name}");
        }
        // Axis ends: the exact model's tangent, perpendicular to the axis (no cone point).
        for (t, s) in [(ours.start, source.start), (ours.end, source.end)] {
            assert!(angle(t, s) < TANGENT_MATCH, "{name}: {t:?} vs {s:?}");
            assert!(t.x.abs() > 1.0 - 1e-12, "{name}: end tangent {t:?}");
        }
        // G1 inside pieces: the tangent turns continuously across every interior knot
        // (simple knots of a cubic make it C2; checked here on the curve itself).
        for piece in ff.pieces() {
            let knots = piece.knots();
            for &k in &knots[4..knots.len() - 4] {
                let (before, after) = (
                    unit_tangent(piece, k - 1e-9).unwrap(),
                    unit_tangent(piece, k + 1e-9).unwrap(),
                );
                assert!(angle(before, after) < 1e-6, "{name} at knot {k}");
            }
        }
        let report = fit_report(name).unwrap().unwrap();
        println!(
            "{name}: {} pieces, control points per piece {:?}",
            ff.pieces().len(),
            report
                .runs
                .iter()
                .map(|r| r.control_points)
                .collect::<Vec<_>>()
        );
    }
}

#[test]
fn variants_are_within_the_hausdorff_bound_of_their_exact_models() {
    for (name, ff, exact) in variants() {
        let report = fit_report(name).unwrap().unwrap();
        let fitted = report.max_deviation();
        let measured = sampled_hausdorff(&ff, &exact, HAUSDORFF_SAMPLES_PER_SPAN);
        println!("{name}: fit deviation {fitted:.2e}, sampled Hausdorff {measured:.2e}");
        assert!(fitted <= FREEFORM_FIT_TOLERANCE, "{name}: {fitted}");
        assert!(measured <= FREEFORM_HAUSDORFF_BOUND, "{name}: {measured}");
        // The parametric deviation bounds the Hausdorff distance (up to sampling).
        assert!(
            measured <= fitted * (1.0 + DEVIATION_SAMPLING_MARGIN),
            "{name}: {measured} vs {fitted}"
        );
    }
}

#[test]
fn variants_build_larger_trees_than_their_exact_models() {
    for (name, ff, exact) in variants() {
        for eps in [1e-3, 1e-4, 1e-5] {
            let ours = BiarcTree::build(&ff, eps).unwrap().stats();
            let theirs = BiarcTree::build(&exact, eps).unwrap().stats();
            println!(
                "{name} eps {eps:e}: {} nodes, {} leaves, depth {} (exact: {} nodes)",
                ours.nodes, ours.leaves, ours.depth, theirs.nodes
            );
            assert!(ours.nodes > theirs.nodes, "{name} eps {eps}");
        }
    }
}

/// Certified queries between variants: the interval is ordered, and the distance differs from
/// the exact models' by at most the two silhouettes' Hausdorff distances (the distance between
/// separated solids is 1-Lipschitz in each boundary) plus the two intervals' widths.
#[test]
fn certified_queries_between_variants_agree_with_the_exact_models() {
    let eps = 1e-4;
    let solid = |name: &str| Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap();
    let opts = QueryOptions::default();
    let cases = [
        ("pawn_ff", "cup_ff", Vector3::new(0.95, 0.0, 0.1), 0.3),
        (
            "bottle_ff",
            "lightmill_ff",
            Vector3::new(0.6, 0.2, -0.2),
            1.1,
        ),
        ("table_ff", "pawn_ff", Vector3::new(0.0, 0.75, 0.5), 2.0),
    ];
    for (a, b, t, angle) in cases {
        let pose = Isometry3::from_parts(
            Translation3::from(t),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 1.0, 0.2).normalize() * angle),
        );
        let ours = distance(&solid(a), &solid(b).with_pose(pose), &opts);
        let exact_a = a.trim_end_matches("_ff");
        let exact_b = b.trim_end_matches("_ff");
        let theirs = distance(&solid(exact_a), &solid(exact_b).with_pose(pose), &opts);
        println!(
            "{a} / {b}: [{}, {}] ({} node pairs); exact models [{}, {}]",
            ours.lower, ours.upper, ours.stats.node_pairs, theirs.lower, theirs.upper
        );
        assert!(!ours.overlap && !theirs.overlap, "{a} / {b}");
        assert!(0.0 < ours.lower && ours.lower <= ours.value, "{a} / {b}");
        assert!(ours.value <= ours.upper, "{a} / {b}");
        assert!(
            ours.upper - ours.lower <= 2.0 * eps * (1.0 + 1e-9),
            "{a} / {b}"
        );
        let slack = 2.0 * FREEFORM_HAUSDORFF_BOUND;
        assert!(ours.lower <= theirs.upper + slack, "{a} / {b}");
        assert!(theirs.lower <= ours.upper + slack, "{a} / {b}");
    }
}

#[test]
fn freeform_names_are_registered_and_bad_names_still_fail() {
    for name in freeform_names() {
        assert!(model_names().contains(name), "{name}");
    }
    for bad in ["pawn_f", "pawn_ff_ff", "knight_ff", "_ff"] {
        let err = model(bad).unwrap_err();
        assert!(matches!(err, ModelError::UnknownModel { .. }), "{bad}");
        assert!(err.to_string().contains("lightmill_ff"), "{err}");
    }
}

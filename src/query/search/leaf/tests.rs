//! Tests of the stage-1 patch bounds ([`super::patch_lower`], [`super::patch_upper`]).

use super::patch_lower::circle_segment_distance;
use super::patch_lower::*;
use super::patch_upper::*;
use crate::bvh::patch::{Patch, ProfileArc};
use crate::query::angles::radial_field::ParamCircle;
use crate::query::search::kernel::patch_distance::patch_distance;
use crate::query::search::kernel::patch_distance::tests::{random_piece, random_pose, reference};
use crate::test_rng::Lcg;
use nalgebra::{Isometry3, Point2, Point3};
use std::f64::consts::TAU;

/// A realised upper bound: `pa` lies on patch `a`, `pb` on patch `b` (placed by `pose`),
/// within 1e-12, and `upper` is their distance.
fn assert_realised(
    a: &Patch,
    b: &Patch,
    pose: &Isometry3<f64>,
    (pa, pb): (&Point3<f64>, &Point3<f64>),
    upper: f64,
    case: usize,
) {
    let on_a = a.point_distance(pa).0;
    let on_b = b.point_distance(&pose.inverse_transform_point(pb)).0;
    assert!(
        on_a <= 1e-12 && on_b <= 1e-12,
        "case {case}: off the patches {on_a} {on_b}"
    );
    assert!(((pa - pb).norm() - upper).abs() <= 1e-15, "case {case}");
}

/// Stage-1 bounds bracket the exact patch distance and the independent reference (a
/// grid over both patches refined by pattern search: a realised distance, so an upper
/// estimate of the truth): `lower <= exact <= upper`, `lower <= reference`, and the
/// upper bound is realised by points on both patches.
#[test]
fn stage_one_bounds_bracket_the_patch_distance() {
    let mut rng = Lcg(77);
    let mut settled = 0;
    for i in 0..400 {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let pose = random_pose(&mut rng, if i % 2 == 0 { 1.5 } else { 3.0 });
        let mut memo = CoreMemo::default();
        let bounds = patch_bounds(&a, &b, &pose, &mut memo);
        let lower = patch_lower(&a, &b, &pose, f64::INFINITY, 0.0, &mut memo).lower;
        assert_eq!(lower.to_bits(), bounds.lower.to_bits(), "case {i}");
        let exact = patch_distance(&a, &b, &pose).distance;
        let slack = 1e-10 * (1.0 + pose.translation.vector.norm());
        assert!(
            bounds.lower <= exact + slack,
            "case {i}: lower {} > exact {exact}",
            bounds.lower
        );
        assert!(
            bounds.upper >= exact - slack,
            "case {i}: upper {} < exact {exact}",
            bounds.upper
        );
        let r = reference(&a, &b, &pose);
        assert!(
            bounds.lower <= r + slack,
            "case {i}: lower {} > reference {r}",
            bounds.lower
        );
        assert_realised(
            &a,
            &b,
            &pose,
            (&bounds.point_a, &bounds.point_b),
            bounds.upper,
            i,
        );
        if bounds.upper - bounds.lower <= 1e-9 {
            settled += 1;
        }
    }
    // The bound is tight (settles the pair) in a good share of random configurations.
    assert!(settled >= 10, "only {settled} of 400 pairs settled");
}

/// The upper bound alone ([`patch_upper`], a cold query's first leaf pair): realised by
/// points on both patches, never below the exact distance, and for most separated pairs
/// close to it (it only has to give the traversal a useful first level).
#[test]
fn upper_bound_alone_is_realised() {
    let mut rng = Lcg(78);
    let (mut separated, mut close) = (0, 0);
    for i in 0..400 {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let pose = random_pose(&mut rng, if i % 2 == 0 { 1.5 } else { 3.0 });
        let up = patch_upper(&a, &b, &pose, &mut CoreMemo::default());
        let exact = patch_distance(&a, &b, &pose).distance;
        let slack = 1e-10 * (1.0 + pose.translation.vector.norm());
        assert!(up.lower == f64::NEG_INFINITY, "case {i}");
        assert!(
            up.upper >= exact - slack,
            "case {i}: upper {} < exact {exact}",
            up.upper
        );
        assert_realised(&a, &b, &pose, (&up.point_a, &up.point_b), up.upper, i);
        if exact > 0.05 {
            separated += 1;
            if up.upper <= 1.1 * exact {
                close += 1;
            }
        }
    }
    assert!(separated > 150, "{separated} separated pairs");
    assert!(
        close * 4 >= separated * 3,
        "upper within 10% in only {close} of {separated} separated pairs"
    );
}

/// Polishing a realised pair ([`polish`]) never lengthens it, keeps both points on their
/// patches (so it stays an upper bound of the exact distance), and brings it closer to
/// the exact distance than the one-alternation pair of stage 1.
#[test]
fn polish_approaches_the_patch_distance() {
    let mut rng = Lcg(79);
    let (mut before, mut after, mut separated) = (0, 0, 0);
    for i in 0..400 {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let pose = random_pose(&mut rng, if i % 2 == 0 { 1.5 } else { 3.0 });
        let start = patch_bounds(&a, &b, &pose, &mut CoreMemo::default());
        let (p, q, d) = polish(&a, &b, &pose, (start.point_a, start.point_b), 0.0);
        let exact = patch_distance(&a, &b, &pose).distance;
        let slack = 1e-10 * (1.0 + pose.translation.vector.norm());
        assert!(d <= start.upper, "case {i}: {d} > {}", start.upper);
        assert!(d >= exact - slack, "case {i}: {d} < exact {exact}");
        assert_realised(&a, &b, &pose, (&p, &q), d, i);
        if exact > 0.05 {
            separated += 1;
            before += usize::from(start.upper - exact <= 1e-6 * exact);
            after += usize::from(d - exact <= 1e-6 * exact);
        }
    }
    assert!(separated > 150, "{separated} separated pairs");
    assert!(
        after > before && after * 10 >= separated * 8,
        "within 1e-6: {before} -> {after} of {separated}"
    );
}

/// Two cones (revolved segments) have no closed-form nearest points: the realised pair
/// starts from the nearest points of their frusta's hulls. It is then within 1e-5 of the
/// exact distance (relative; median 2e-8) in over 90% of separated configurations (255
/// of 270 here), where the former start, the pieces' mid points, was never within 1e-3
/// (median 34% too long): the query then had to solve the pair exactly (on
/// table-lightmill 1.1 -> 0.1 exact leaf pairs per query).
#[test]
fn two_cones_realise_their_distance() {
    let mut rng = Lcg(91);
    let segment = |rng: &mut Lcg| ProfileArc::Segment {
        start: Point2::new(0.05 + rng.f(), rng.f() - 0.5),
        end: Point2::new(0.05 + rng.f(), rng.f() - 0.5),
    };
    let (mut separated, mut exact_ones) = (0, 0);
    for i in 0..300 {
        let (a, b) = (Patch::new(segment(&mut rng)), Patch::new(segment(&mut rng)));
        let pose = random_pose(&mut rng, 4.0);
        let exact = patch_distance(&a, &b, &pose).distance;
        if exact < 0.05 {
            continue;
        }
        separated += 1;
        let bounds = patch_bounds(&a, &b, &pose, &mut CoreMemo::default());
        assert!(
            bounds.upper >= exact - 1e-12,
            "case {i}: {} < {exact}",
            bounds.upper
        );
        if bounds.upper - exact <= 1e-5 * exact {
            exact_ones += 1;
        }
    }
    assert!(separated > 150, "{separated} separated pairs");
    assert!(
        exact_ones * 10 >= separated * 9,
        "realised pair within 1e-5 in only {exact_ones} of {separated} separated cone pairs"
    );
}

/// The circle/segment distance against a dense sampling of the circle (each sample's
/// exact planar distance to the segment): never above it, and within its resolution.
#[test]
fn circle_segment_distance_matches_sampling() {
    let mut rng = Lcg(5);
    for i in 0..300 {
        let pose = random_pose(&mut rng, 2.0);
        let (rho, z) = (0.05 + rng.f(), rng.f() - 0.5);
        let circle = ParamCircle::parallel(rho, z, &pose);
        let seg = match i % 3 {
            0 => (
                Point2::new(rng.f(), rng.f() - 0.5),
                Point2::new(rng.f(), rng.f() - 0.5),
            ),
            1 => {
                let h = rng.f() - 0.5;
                (Point2::new(0.0, h), Point2::new(0.3 + rng.f(), h))
            }
            _ => {
                let r = 0.2 + rng.f();
                (Point2::new(r, -0.4), Point2::new(r, 0.4))
            }
        };
        let found = circle_segment_distance(&circle, seg.0, seg.1).unwrap();
        let (mine, theta) = (found.distance, found.theta);
        let planar = |t: f64| {
            let p = circle.point(t);
            let q = Point2::new(p.x.hypot(p.y), p.z);
            let d = seg.1 - seg.0;
            let s = ((q - seg.0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
            (q - (seg.0 + d * s)).norm()
        };
        let n = 20_000;
        let sampled = (0..n)
            .map(|k| planar(k as f64 * TAU / n as f64))
            .fold(f64::INFINITY, f64::min);
        let resolution = rho * TAU / n as f64;
        assert!(
            mine <= sampled + 1e-12,
            "case {i}: {mine} above sampled {sampled}"
        );
        assert!(
            mine >= sampled - resolution,
            "case {i}: {mine} below sampled {sampled}"
        );
        assert!(
            (planar(theta) - mine).abs() <= 1e-9,
            "case {i}: angle does not attain it"
        );
    }
}

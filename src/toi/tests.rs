//! Time-of-impact searches against closed-form contact times (two balls, whose distance
//! is the centres' distance minus the radii) and the edge cases of the search.

use super::*;
use crate::models::model;
use crate::solid::Solid;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::sync::Arc;

/// Radius of the built-in "sphere" (centred at (0, 0, 0.75) of its frame).
const R: f64 = 0.75;

fn solid(name: &str) -> Solid {
    Solid::from_profile(Arc::new(model(name).unwrap()), 1e-4).unwrap()
}

fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::translation(x, y, z)
}

fn opts(d: f64) -> ToiOptions {
    ToiOptions {
        contact_distance: d,
        ..ToiOptions::default()
    }
}

fn fixed() -> Motion {
    Motion::fixed(Isometry3::identity()).unwrap()
}

/// The interval must contain the closed-form first contact time and be narrow.
fn assert_brackets(r: &TimeOfImpact, exact: f64, width: f64) {
    assert_eq!(r.outcome, ToiOutcome::Contact, "{r:?}");
    let hi = r.t_upper.unwrap();
    assert!(
        r.t_lower <= exact && exact <= hi,
        "{exact} not in [{}, {hi}]",
        r.t_lower
    );
    assert!(
        hi - r.t_lower <= width,
        "interval [{}, {hi}] wider than {width}",
        r.t_lower
    );
}

#[test]
fn head_on_balls_with_and_without_contact_distance() {
    let s = solid("sphere");
    let mb = Motion::new(at(3.0, 0.0, 0.0), at(0.0, 0.0, 0.0)).unwrap();
    for d in [0.0, 0.1] {
        let r = time_of_impact(&s, &fixed(), &s, &mb, &opts(d)).unwrap();
        // Centres 3 - 3t apart; contact at distance 2R + D.
        assert_brackets(&r, (3.0 - 2.0 * R - d) / 3.0, 1e-3);
        let c = r.contact.unwrap();
        assert!(c.upper <= d + 1e-12);
    }
}

#[test]
fn rotation_only_swings_a_ball_into_another() {
    // B's frame origin at (2, 0, 0.75), turning by -pi/2 about y: its ball's centre is at
    // (2 - R sin phi, 0, 0.75 + R cos phi), phi = t pi/2; A's centre at (0, 0, 0.75).
    // Contact when (2 - R s)^2 + (R c)^2 = (2R)^2, i.e. s = (4 + R^2 - 4R^2) / (4R).
    let s = solid("sphere");
    let half = std::f64::consts::FRAC_PI_2;
    let end = Isometry3::from_parts(
        Translation3::new(2.0, 0.0, 0.75),
        UnitQuaternion::from_scaled_axis(Vector3::y() * -half),
    );
    let mb = Motion::new(at(2.0, 0.0, 0.75), end).unwrap();
    let r = time_of_impact(&s, &fixed(), &s, &mb, &opts(0.0)).unwrap();
    let phi = ((4.0 - 3.0 * R * R) / (4.0 * R)).asin();
    assert_brackets(&r, phi / half, 1e-3);
}

#[test]
fn never_touching_is_certified_apart() {
    let s = solid("sphere");
    // Passing by at centre distance 2 > 2R.
    let mb = Motion::new(at(-3.0, 2.0, 0.0), at(3.0, 2.0, 0.0)).unwrap();
    let r = time_of_impact(&s, &fixed(), &s, &mb, &opts(0.0)).unwrap();
    assert_eq!(r.outcome, ToiOutcome::Apart, "{r:?}");
    assert!(r.t_upper.is_none() && r.contact.is_none());
    // With D above the gap (2 - 2R = 0.5) it is a contact, at centre distance 2R + D = 2.1:
    // x = -sqrt(2.1^2 - 4) = -0.640..., t = (x + 3) / 6.
    let r = time_of_impact(&s, &fixed(), &s, &mb, &opts(0.6)).unwrap();
    assert_brackets(&r, (3.0 - (2.1f64.powi(2) - 4.0).sqrt()) / 6.0, 1e-3);
}

#[test]
fn touching_at_the_start_and_standing_still() {
    let s = solid("pawn");
    let c = solid("cup");
    let overlapping = Motion::fixed(at(0.1, 0.0, 0.2)).unwrap();
    let r = time_of_impact(&s, &fixed(), &c, &overlapping, &opts(0.0)).unwrap();
    assert_eq!(r.outcome, ToiOutcome::Contact);
    assert_eq!((r.t_lower, r.t_upper), (0.0, Some(0.0)));
    // Identical start and end poses far apart: one query, apart on [0, 1].
    let far = Motion::fixed(at(5.0, 0.0, 0.0)).unwrap();
    let r = time_of_impact(&s, &fixed(), &c, &far, &opts(0.0)).unwrap();
    assert_eq!((r.outcome, r.queries), (ToiOutcome::Apart, 1));
}

#[test]
fn grazing_is_never_called_apart() {
    // Centres pass at exactly 2R + D: the distance reaches D at t = 1/2 and no earlier.
    let s = solid("sphere");
    let d = 0.05;
    let y = 2.0 * R + d;
    let mb = Motion::new(at(-2.0, y, 0.0), at(2.0, y, 0.0)).unwrap();
    let r = time_of_impact(&s, &fixed(), &s, &mb, &opts(d)).unwrap();
    assert_ne!(r.outcome, ToiOutcome::Apart, "{r:?}");
    assert!(r.t_lower <= 0.5, "{r:?}");
    assert!(r.queries <= DEFAULT_MAX_QUERIES);
}

#[test]
fn both_solids_moving_curved_models() {
    // The pawn falls onto the cup's rim while the cup slides under it: the search ends with
    // a certified contact whose witness points are within D of each other.
    let pawn = solid("pawn");
    let cup = solid("cup");
    let ma = Motion::new(at(-0.5, 0.0, 0.0), at(0.0, 0.0, 0.0)).unwrap();
    let mb = Motion::new(
        at(0.0, 0.0, 3.0),
        Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 0.5),
            UnitQuaternion::from_scaled_axis(Vector3::x() * 0.6),
        ),
    )
    .unwrap();
    let r = time_of_impact(&cup, &ma, &pawn, &mb, &opts(0.01)).unwrap();
    assert_eq!(r.outcome, ToiOutcome::Contact, "{r:?}");
    let c = r.contact.unwrap();
    assert!(c.overlap || (c.point_b - c.point_a).norm() <= c.upper + 1e-12);
    assert!(c.upper <= 0.01 + 1e-12);
    assert!(r.t_lower <= r.t_upper.unwrap());
}

#[test]
fn bad_options_are_errors() {
    let s = solid("sphere");
    let m = fixed();
    let bad = |o: ToiOptions| time_of_impact(&s, &m, &s, &m, &o).unwrap_err();
    assert_eq!(bad(opts(-1.0)), ToiError::ContactDistance(-1.0));
    assert!(matches!(bad(opts(f64::NAN)), ToiError::ContactDistance(_)));
    let o = ToiOptions {
        time_tolerance: 0.0,
        ..ToiOptions::default()
    };
    assert_eq!(bad(o), ToiError::TimeTolerance(0.0));
    let o = ToiOptions {
        max_queries: 0,
        ..ToiOptions::default()
    };
    assert_eq!(bad(o), ToiError::MaxQueries);
    let far = Motion::new(at(1e200, 0.0, 0.0), Isometry3::identity()).unwrap();
    assert!(matches!(
        time_of_impact(&s, &m, &s, &far, &ToiOptions::default()),
        Err(ToiError::Query { .. })
    ));
}

/// The carried certificate against the closed form: for random witness pairs carried along
/// random motions of two balls, every certified time has the balls within `D` (the centres within
/// `2R + D`), and the points it names are in (or on) the balls. Many tested times are apart,
/// so a certificate granted there would fail.
#[test]
fn carried_certificates_hold_in_closed_form() {
    use super::contact::{ContactTest, Witness};
    use crate::query::{try_distance, QueryOptions};
    use crate::test_rng::SplitMix64;
    let ball = Solid::from_profile(Arc::new(model("sphere").unwrap()), 1e-2).unwrap();
    let centre = nalgebra::Point3::new(0.0, 0.0, 0.75);
    let mut rng = SplitMix64(0x70_1c_e7);
    let (mut granted, mut tried) = (0, 0);
    for _ in 0..300 {
        let d = [0.0, 0.0, 0.05][rng.int(0, 2)];
        let pose = |rng: &mut SplitMix64, r: f64| {
            Isometry3::from_parts(
                Translation3::from(rng.unit() * r),
                UnitQuaternion::from_scaled_axis(rng.unit() * rng.range(0.0, 3.0)),
            )
        };
        let ma = Motion::new(pose(&mut rng, 0.2), pose(&mut rng, 0.2)).unwrap();
        let mb = Motion::new(pose(&mut rng, 2.2), pose(&mut rng, 0.6)).unwrap();
        // Witnesses of a query at a random time (the search's starting point).
        let t0 = rng.range(0.0, 0.5);
        let (pa, pb) = (ma.pose_at(t0), mb.pose_at(t0));
        let q = try_distance(
            &ball.with_pose(pa),
            &ball.with_pose(pb),
            &QueryOptions::default(),
        )
        .unwrap();
        let w = Witness::new(&q, &pa, &pb);
        let test = ContactTest {
            a: &ball,
            b: &ball,
            ma: &ma,
            mb: &mb,
            ra: 1.5,
            rb: 1.5,
            contact_distance: d,
        };
        for k in 0..40 {
            let t = t0 + (1.0 - t0) * f64::from(k) / 39.0;
            tried += 1;
            let Some(c) = test.certify(t, &w) else {
                continue;
            };
            granted += 1;
            let (ca, cb) = (ma.pose_at(t) * centre, mb.pose_at(t) * centre);
            let gap = (cb - ca).norm() - 2.0 * R;
            assert!(
                gap <= d + 1e-9,
                "certified at t {t} with the balls {gap} apart (D {d})"
            );
            // Points inside (or, for a surface point deep in the other ball, within the
            // tree's eps of) each ball.
            let near =
                |p: &nalgebra::Point3<f64>, c: &nalgebra::Point3<f64>| (p - c).norm() < R + 0.02;
            assert!(near(&c.point_a, &ca) && near(&c.point_b, &cb));
            assert!(c.upper <= d);
        }
    }
    // The test must exercise both answers.
    assert!(granted > 100 && granted < tried, "{granted} of {tried}");
}

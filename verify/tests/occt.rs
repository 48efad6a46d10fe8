//! OpenCASCADE as the reference on the true surfaces (`verify::baselines::occt`,
//! `verify::crosscheck::occt`): closed forms for tori (OCCT's exact torus and its revolution of
//! the rational circle), a nested pair (OCCT's inner solution), bad input, and a slice of the
//! cross-check's OCCT sweep in which revdist must never be the side the evidence blames.
//! Needs OCCT (scripts/deps.sh installs it); without it every test fails with "OCCT missing".

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::models::primitives::arc;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;
use verify::baselines::occt::{Construction, OcctSolid, OCCT_TOLERANCE};
use verify::crosscheck::criterion::Verdict;
use verify::crosscheck::{occt, Options};

/// The built-in `ring`: a circle of radius 0.6 about (rho, z) = (0.9, 0.6).
const RING: (f64, f64, f64) = (0.9, 0.6, 0.6);

/// Eps of the revdist trees compared with the closed forms (interval width <= 2e-7).
const EPS: f64 = 1e-7;

fn ring_solid() -> Solid {
    Solid::from_profile(Arc::new(revdist::models::model("ring").unwrap()), EPS).unwrap()
}

/// Coaxial stacked rings `dz` apart (distance `dz - 2r`, attained on a whole circle), side by
/// side with centres `c` apart (distance `c - 2R - 2r`), and an overlapping stack.
fn torus_cases() -> Vec<(&'static str, Isometry3<f64>, f64)> {
    let (big, _, small) = RING;
    let t = |x: f64, z: f64| {
        Isometry3::from_parts(Translation3::new(x, 0.0, z), UnitQuaternion::identity())
    };
    vec![
        ("stacked, gap 0.3", t(0.0, 2.0 * small + 0.3), 0.3),
        ("stacked, gap 1e-5", t(0.0, 2.0 * small + 1e-5), 1e-5),
        (
            "side by side, gap 0.25",
            t(2.0 * (big + small) + 0.25, 0.0),
            0.25,
        ),
        (
            "stacked, overlapping by 0.2",
            t(0.0, 2.0 * small - 0.2),
            0.0,
        ),
    ]
}

#[test]
fn tori_match_the_closed_form() {
    let profile = revdist::models::model("ring").unwrap();
    let exact = OcctSolid::from_profile(&profile).expect("OCCT torus");
    match exact.construction() {
        Construction::Torus {
            major,
            minor,
            centre_z,
        } => assert!(
            (major - RING.0).abs() < 1e-12
                && (centre_z - RING.1).abs() < 1e-12
                && (minor - RING.2).abs() < 1e-12,
            "the ring is the torus {RING:?}: {:?}",
            exact.construction()
        ),
        c => panic!("the ring is recognised as a torus, got {c:?}"),
    }
    let revolved = OcctSolid::revolved(&profile).expect("OCCT revolution of the ring");
    let solid = ring_solid();
    for (what, pose, truth) in torus_cases() {
        for (how, s) in [("MakeTorus", &exact), ("MakeRevol", &revolved)] {
            let o = s.distance(s, &pose).expect("OCCT distance");
            assert!(
                (o.distance - truth).abs() <= OCCT_TOLERANCE,
                "{how}, {what}: OCCT {} vs closed form {truth}",
                o.distance
            );
        }
        let d = distance(&solid, &solid.with_pose(pose), &QueryOptions::default());
        assert!(
            d.lower <= truth + 1e-12 && truth <= d.upper + 1e-12,
            "{what}: revdist {d:?}"
        );
    }
}

#[test]
fn nested_solids_are_an_inner_solution() {
    let torus = |r: f64| {
        let p = Profile::new(
            "t",
            vec![arc(
                [1.0, 0.0],
                r,
                -0.5 * std::f64::consts::PI,
                1.5 * std::f64::consts::PI,
            )
            .unwrap()],
        )
        .unwrap();
        (
            OcctSolid::revolved(&p).unwrap(),
            Solid::from_profile(Arc::new(p), 1e-5).unwrap(),
        )
    };
    let (thick, thick_rev) = torus(0.5);
    let (thin, thin_rev) = torus(0.1);
    let pose = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, 0.05),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3),
    );
    let o = thick.distance(&thin, &pose).unwrap();
    assert!(o.inner && o.distance == 0.0, "OCCT: {o:?}");
    let d = distance(
        &thick_rev,
        &thin_rev.with_pose(pose),
        &QueryOptions::default(),
    );
    assert!(d.overlap && d.upper == 0.0, "revdist: {d:?}");
}

/// The shim's inner-solution test with cached classifiers and BRepExtrema on the shells gives
/// OCCT's own answer (BRepExtrema on the solids, classifying itself).
#[test]
fn cached_classifiers_give_occts_answer() {
    let pawn = OcctSolid::from_profile(&revdist::models::model("pawn").unwrap()).unwrap();
    let cup = OcctSolid::from_profile(&revdist::models::model("cup").unwrap()).unwrap();
    let rot = UnitQuaternion::from_euler_angles(0.3, -0.7, 1.1);
    for (x, z) in [(1.5, 0.2), (0.9, 0.4), (0.2, 0.3), (0.0, 0.5)] {
        let pose = Isometry3::from_parts(Translation3::new(x, 0.1, z), rot);
        let c = pawn.distance(&cup, &pose).unwrap();
        let u = pawn.distance_uncached(&cup, &pose).unwrap();
        assert_eq!(
            (c.distance, c.inner, c.point_a, c.point_b),
            (u.distance, u.inner, u.point_a, u.point_b),
            "pose ({x}, {z})"
        );
    }
}

#[test]
fn bad_input_is_an_error() {
    let e = OcctSolid::torus(0.5, 1.0, 0.0).unwrap_err().to_string();
    assert!(e.contains("major > minor"), "{e}");
    let e = OcctSolid::torus(f64::NAN, 0.1, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("finite"), "{e}");
}

#[test]
fn sweep_slice_never_blames_revdist() {
    let opts = Options {
        // Poses 0..4: near-touching, separated, overlapping, inside the bounding ball.
        occt_poses: 4,
        occt_pairs: [
            ("pawn", "cup"),
            ("bottle_ff", "table_ff"),
            ("morph@0.5", "lightmill"),
        ]
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect(),
        ..Options::default()
    };
    let records: Vec<_> = occt::run(&opts, 2, (0, &|_| true))
        .expect("OCCT sweep runs")
        .into_iter()
        .map(|(_, r)| r)
        .collect();
    assert_eq!(records.len(), 3 * 4 * opts.occt_eps.len());
    let mut passed = 0;
    for r in &records {
        match r.judgement.verdict {
            Verdict::Passed => passed += 1,
            // OCCT is numerical: it may miss a minimum (proven by revdist's witnesses on the
            // true surfaces), or report a nested pair's surface distance.
            Verdict::Explained => assert!(
                r.note == occt::OCCT_MISSED
                    || r.note == occt::OCCT_FALSE_INNER
                    || r.note.starts_with("nested"),
                "{}: {}",
                r.note,
                r.reproducer()
            ),
            Verdict::Failed => panic!("{}: {}", r.note, r.reproducer()),
        }
        assert!(r.baseline_time.is_some());
    }
    assert!(
        passed + 2 >= records.len(),
        "{passed} of {} passed",
        records.len()
    );
}

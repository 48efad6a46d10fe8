//! Every pair of built-in models under random poses (separated, nearly touching with gaps
//! 1e-9..1e-2, overlapping or nested) and hard poses (a thin ring in the bottle's neck, crossing
//! axes, a sphere on another solid's axis, parallel flat faces), against the
//! independent dense-sampling reference (`tests/reference`).

mod reference;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use reference::{check_query, closest_point, reference, ring_profile, RefProfile, Rng};
use revdist::models::{model, model_names, FREEFORM_NAMES};
use revdist::query::QueryOptions;
use revdist::solid::Solid;
use std::sync::Arc;

/// Tree bound for the all-pairs sweep (the coarsest of the benchmarked levels).
const EPS: f64 = 1e-3;

fn solids(eps: f64) -> Vec<Solid> {
    model_names()
        .iter()
        .map(|n| Solid::from_profile(Arc::new(model(n).unwrap()), eps).unwrap())
        .collect()
}

fn pose(t: Vector3<f64>, r: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), r)
}

/// Runs `f` on every unordered pair (including a model with itself), or on the pairs with
/// `(i + j) % 2 == parity` to share the test time, and reports all failures at once. The
/// freeform variants (`pawn_ff`, ...) are paired with each other only: pairing them with the
/// other models too would more than double the sweep, and `verify queries` checks them
/// against every built-in model with its independent oracle.
fn all_pairs(
    seed: u64,
    parity: Option<usize>,
    f: impl Fn(&Solid, &Solid, &mut Rng, &str) -> Result<(), String>,
) {
    let s = solids(EPS);
    let names = model_names();
    let mut rng = Rng(seed);
    let mut fails = Vec::new();
    for i in 0..s.len() {
        for j in i..s.len() {
            if parity.is_some_and(|p| (i + j) % 2 != p) {
                continue;
            }
            let freeform = |k: usize| FREEFORM_NAMES.contains(&names[k]);
            if freeform(i) != freeform(j) {
                continue;
            }
            let label = format!("{} / {}", names[i], names[j]);
            let t0 = std::time::Instant::now();
            let res = f(&s[i], &s[j], &mut rng, &label);
            if std::env::var("QM_TIME").is_ok() {
                eprintln!("{label}: {:?}", t0.elapsed());
            }
            if let Err(e) = res {
                fails.push(e);
            }
        }
    }
    assert!(
        fails.is_empty(),
        "{} failures:\n{}",
        fails.len(),
        fails.join("\n")
    );
}

#[test]
fn all_pairs_separated() {
    all_pairs(21, None, |a, b, rng, label| {
        let t = rng.unit() * (2.2 + rng.f());
        let b = b.with_pose(pose(t + Vector3::new(0.0, 0.0, 0.5), rng.rotation()));
        check_query(a, &b, &QueryOptions::default(), label).map(|_| ())
    });
}

#[test]
fn all_pairs_nearly_touching() {
    all_pairs(22, Some(0), |a, b, rng, label| {
        // Random separated pose, then B moved towards A along the reference's closest
        // direction so that the closest pair is `gap` apart.
        let rot = rng.rotation();
        let t = rng.unit() * 2.5 + Vector3::new(0.0, 0.0, 0.5);
        let gap = 10f64.powf(-9.0 + 7.0 * rng.f());
        let p0 = pose(t, rot);
        let (pa_prof, pb_prof) = (a.profile.as_deref().unwrap(), b.profile.as_deref().unwrap());
        let r0 = reference(pa_prof, pb_prof, &p0);
        let qa = closest_point(&RefProfile::new(pa_prof), &r0.point_b);
        let dir = (qa - r0.point_b).normalize();
        let moved = pose(t + dir * (r0.surface_distance - gap), rot);
        let b = b.with_pose(moved);
        check_query(
            a,
            &b,
            &QueryOptions::default(),
            &format!("{label} gap {gap:e}"),
        )
        .map(|_| ())
    });
}

#[test]
fn all_pairs_overlapping_or_nested() {
    all_pairs(23, Some(1), |a, b, rng, label| {
        let t = rng.unit() * rng.f() * 0.4 + Vector3::new(0.0, 0.0, 0.5);
        let b = b.with_pose(pose(t, rng.rotation()));
        let (d, r) = check_query(a, &b, &QueryOptions::default(), label)?;
        if r.distance == 0.0 && d.upper > 2.0 * EPS {
            return Err(format!("{label}: overlapping but upper {}", d.upper));
        }
        Ok(())
    });
}

/// Interlocked rings (exact NURBS circles) with clearance down to 1e-9. Two unit circles,
/// each through the other's centre in perpendicular planes, are at constant distance 1
/// (a continuum of closest pairs: |(1 + cos t, sin t)| - 1 ... = 1 for every t), so tubes
/// of radius (1 - c) / 2 have clearance exactly c.
#[test]
fn interlocked_nurbs_rings() {
    let rot = UnitQuaternion::from_scaled_axis(Vector3::x() * std::f64::consts::FRAC_PI_2);
    for clearance in [1e-2, 1e-5, 1e-7, 1e-9] {
        let ring = Solid::from_profile(
            Arc::new(ring_profile(1.0, 0.0, 0.5 * (1.0 - clearance))),
            1e-4,
        )
        .unwrap();
        let b = ring.with_pose(pose(Vector3::new(1.0, 0.0, 0.0), rot));
        let (d, _) = check_query(
            &ring,
            &b,
            &QueryOptions::default(),
            &format!("rings {clearance:e}"),
        )
        .unwrap();
        assert!(
            d.lower <= clearance && clearance <= d.upper,
            "rings {clearance:e}: [{}, {}]",
            d.lower,
            d.upper
        );
        assert!(!d.overlap);
    }
}

/// Coaxial solids: a continuum of closest points (pawn above a cylinder, cup on a table).
#[test]
fn coaxial_continuum() {
    let s = solids(1e-4);
    let idx = |n: &str| model_names().iter().position(|m| *m == n).unwrap();
    for (a, b, z) in [
        ("cylinder", "pawn", 1.5 + 1e-6),
        ("table", "cup", 1.46 + 1e-3),
        ("cylinder", "cylinder", 1.5 + 1e-9),
    ] {
        let bb = s[idx(b)].with_pose(pose(Vector3::new(0.0, 0.0, z), UnitQuaternion::identity()));
        check_query(
            &s[idx(a)],
            &bb,
            &QueryOptions::default(),
            &format!("{a}/{b} coaxial"),
        )
        .unwrap();
        // Flipped upside down: still coaxial.
        let flip = UnitQuaternion::from_scaled_axis(Vector3::x() * std::f64::consts::PI);
        let bb = s[idx(b)].with_pose(pose(Vector3::new(0.0, 0.0, -0.05), flip));
        check_query(
            &s[idx(a)],
            &bb,
            &QueryOptions::default(),
            &format!("{a}/{b} flipped"),
        )
        .unwrap();
    }
}

/// A thin ring hanging in the concave neck of the bottle and around the table's stem;
/// solids whose axes intersect; a sphere centred on another solid's axis; parallel flat
/// faces with offset axes.
#[test]
fn hard_poses() {
    let s = solids(1e-4);
    let idx = |n: &str| model_names().iter().position(|m| *m == n).unwrap();
    let opts = QueryOptions::default();
    let thin = Solid::from_profile(Arc::new(ring_profile(0.26, 0.0, 0.03)), 1e-4).unwrap();
    for (host, z, dx, tilt) in [
        ("bottle", 1.2, 0.02, 0.25),
        ("bottle", 1.3, 0.0, 0.0),
        ("table", 0.7, 0.05, 0.4),
    ] {
        let b = thin.with_pose(pose(
            Vector3::new(dx, 0.0, z),
            UnitQuaternion::from_scaled_axis(Vector3::y() * tilt),
        ));
        check_query(
            &s[idx(host)],
            &b,
            &opts,
            &format!("thin ring on {host} z {z}"),
        )
        .unwrap();
    }
    let mut rng = Rng(31);
    for (a, b) in [
        ("pawn", "cone"),
        ("lightmill", "capsule"),
        ("cup", "bottle"),
    ] {
        // B's origin on A's axis, axes crossing.
        let bb = s[idx(b)].with_pose(pose(Vector3::new(0.0, 0.0, 2.2), rng.rotation()));
        check_query(&s[idx(a)], &bb, &opts, &format!("{a}/{b} crossing axes")).unwrap();
    }
    for a in ["ring", "cup", "table"] {
        let bb = s[idx("sphere")].with_pose(pose(
            Vector3::new(0.0, 0.0, 1.7),
            UnitQuaternion::identity(),
        ));
        check_query(
            &s[idx(a)],
            &bb,
            &opts,
            &format!("sphere on the axis of {a}"),
        )
        .unwrap();
    }
    for (a, b, dz) in [
        ("cylinder", "cylinder", 1.5 + 1e-7),
        ("table", "cylinder", 1.46 + 1e-4),
    ] {
        let bb = s[idx(b)].with_pose(pose(
            Vector3::new(0.35, 0.2, dz),
            UnitQuaternion::identity(),
        ));
        check_query(&s[idx(a)], &bb, &opts, &format!("{a}/{b} parallel faces")).unwrap();
    }
}

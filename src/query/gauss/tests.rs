use super::*;
use crate::circle::{binormals, Multiplicity};
use crate::query::binormal_kernel::parallel_circle;
use crate::query::patch_distance::tests::Rng;
use nalgebra::{Point2, Translation3, UnitQuaternion};

/// A toroidal patch in the half-plane rho >= 0 with `|sweep| <= max_sweep`; the arc centre
/// may lie left of the axis.
fn random_torus(rng: &mut Rng, max_sweep: f64) -> Patch {
    loop {
        let arc = ProfileArc::Arc {
            center: Point2::new(rng.f() * 1.2 - 0.2, rng.f() - 0.5),
            radius: 0.05 + rng.f() * 0.5,
            phi_start: rng.f() * TAU,
            sweep: (2.0 * rng.f() - 1.0) * max_sweep,
        };
        if arc.length() > 1e-4 && (0..=50).all(|i| arc.point_at(i as f64 / 50.0).x >= 0.0) {
            return Patch::new(arc);
        }
    }
}

fn random_pose(rng: &mut Rng) -> Isometry3<f64> {
    let axis = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5);
    let t = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5) * 3.0;
    Isometry3::from_parts(
        Translation3::from(t),
        UnitQuaternion::from_scaled_axis(axis * 6.0),
    )
}

/// Interior common normals of two patches found WITHOUT the restriction: binormals of
/// the full major circles whose line meets both patches inside their arc ranges.
fn unrestricted_normals(a: &Patch, b: &Patch, pos: &Isometry3<f64>) -> Option<Vec<(f64, f64)>> {
    let (
        super::super::patch::Core::Circle {
            r_major: ra, z: za, ..
        },
        super::super::patch::Core::Circle {
            r_major: rb, z: zb, ..
        },
    ) = (a.core(), b.core())
    else {
        return None;
    };
    let ma = parallel_circle(ra, za, &Isometry3::identity());
    let mb = parallel_circle(rb, zb, pos);
    let bn = binormals(&ma, &mb, None, None);
    if bn.multiplicity != Multiplicity::Finite {
        return None;
    }
    let pos_ba = pos.inverse();
    let mut out = Vec::new();
    for item in bn.items.iter() {
        let w = item.point_b - item.point_a;
        if w.norm() < 1e-9 {
            continue;
        }
        let dir = w.normalize();
        let (mut pa, mut pb) = (Vec::new(), Vec::new());
        a.points_on_normal_line(&item.point_a, &dir, &mut pa);
        b.points_on_normal_line(&(pos_ba * item.point_b), &(pos_ba.rotation * dir), &mut pb);
        if !pa.is_empty() && !pb.is_empty() {
            out.push((item.angle_a, item.angle_b));
        }
    }
    Some(out)
}

/// The restriction is conservative: every interior common normal of the unrestricted
/// computation starts inside the restricted ranges on both major circles.
#[test]
fn restriction_keeps_every_interior_common_normal() {
    let mut rng = Rng(2024);
    let mut found = 0;
    for max_sweep in [0.05, 0.5, 2.0, 6.0] {
        for i in 0..600 {
            let (a, b) = (
                random_torus(&mut rng, max_sweep),
                random_torus(&mut rng, max_sweep),
            );
            let pos = random_pose(&mut rng);
            let Some(normals) = unrestricted_normals(&a, &b, &pos) else {
                continue;
            };
            let ranges = major_angle_ranges(&a, &b, &pos);
            for (ta, tb) in normals {
                found += 1;
                let MajorRanges::Ranges { a: ra, b: rb } = ranges else {
                    panic!("case {i} (sweep {max_sweep}): disjoint but normal at {ta}, {tb}: {a:?} {b:?} {pos:?}");
                };
                assert!(
                    ra.is_none_or(|r| r.contains(ta)),
                    "case {i} (sweep {max_sweep}): theta_a {ta} outside {ra:?}: {a:?} {b:?} {pos:?}"
                );
                assert!(
                    rb.is_none_or(|r| r.contains(tb)),
                    "case {i} (sweep {max_sweep}): theta_b {tb} outside {rb:?}: {a:?} {b:?} {pos:?}"
                );
            }
        }
    }
    // The check is not vacuous: many normals were tested.
    assert!(found > 300, "only {found} interior normals");
}

/// Fraction of the major circle left to search (the driving side: the smaller of the
/// two), averaged over random pairs with arcs of at most `max_sweep`.
fn mean_searched_fraction(max_sweep: f64, n: usize) -> f64 {
    let mut rng = Rng(99);
    let mut sum = 0.0;
    for _ in 0..n {
        let (a, b) = (
            random_torus(&mut rng, max_sweep),
            random_torus(&mut rng, max_sweep),
        );
        let pos = random_pose(&mut rng);
        sum += match major_angle_ranges(&a, &b, &pos) {
            MajorRanges::Disjoint => 0.0,
            MajorRanges::Ranges { a, b } => {
                let f = |r: Option<AngleArcs>| r.map_or(1.0, |r| r.total_len() / TAU);
                f(a).min(f(b))
            }
        };
    }
    sum / n as f64
}

/// On leaf-sized arcs the restriction removes most of the circle (paper 3.3), and less
/// the wider the arcs.
#[test]
fn restriction_narrows_small_arcs() {
    let small = mean_searched_fraction(0.05, 2000);
    let medium = mean_searched_fraction(0.5, 2000);
    let large = mean_searched_fraction(6.0, 2000);
    eprintln!("searched fraction: sweep 0.05 {small:.3}, 0.5 {medium:.3}, 6 {large:.3}");
    assert!(small < 0.1, "{small}");
    assert!(small < medium && medium < large, "{small} {medium} {large}");
}

#[test]
fn covering_arcs_handles_wrap_and_two_gaps() {
    // Two separate arcs: kept apart.
    let mut arcs = [(0.1, 0.2), (3.0, 0.3)];
    let c = covering_arcs(&mut arcs).unwrap();
    assert_eq!(c.arcs().len(), 2);
    assert!(c.contains(0.2) && c.contains(3.2) && !c.contains(1.5) && !c.contains(5.0));
    // An arc across 0 merged with one just after it; three pieces reduce to two arcs.
    let mut arcs = [(6.0, 0.5), (0.3, 0.2), (2.0, 0.1), (4.0, 0.1)];
    let c = covering_arcs(&mut arcs).unwrap();
    for t in [6.1, 0.1, 0.4, 2.05, 4.05] {
        assert!(c.contains(t), "{t} {c:?}");
    }
    assert!(c.total_len() < TAU - 1.0);
    // Covering everything.
    let mut arcs = [(0.0, 3.5), (3.0, 3.5)];
    assert!(covering_arcs(&mut arcs).is_none());
}

#[test]
fn latitude_parts_split_at_the_poles() {
    // phi in [0.5, 2.5] crosses pi/2: a cos>=0 part [0.5, pi/2] and a cos<=0 part with
    // latitudes pi - phi in [pi - 2.5, pi/2], longitude shifted by pi.
    let parts: Vec<_> = latitude_parts(0.5, 2.5).collect();
    assert_eq!(parts.len(), 2);
    assert!((parts[0].0 - 0.5).abs() < 1e-15 && (parts[0].1 - FRAC_PI_2).abs() < 1e-15);
    assert_eq!(parts[0].2, 0.0);
    assert!((parts[1].0 - (PI - 2.5)).abs() < 1e-15 && (parts[1].1 - FRAC_PI_2).abs() < 1e-15);
    assert_eq!(parts[1].2, PI);
    // A full turn has three parts covering all latitudes.
    assert_eq!(latitude_parts(-1.0, -1.0 + TAU).count(), 3);
}

#[test]
fn sin_range_covers_extrema() {
    assert_eq!(sin_range(0.0, 3.0).1, 1.0);
    assert_eq!(sin_range(3.0, 5.0).0, -1.0);
    let (lo, hi) = sin_range(0.1, 0.2);
    assert!((lo - 0.1f64.sin()).abs() < 1e-16 && (hi - 0.2f64.sin()).abs() < 1e-16);
    assert_eq!(sin_range(-10.0, -3.0), (-1.0, 1.0));
}

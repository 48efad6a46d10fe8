use super::*;
use nalgebra::{Translation3, UnitQuaternion};
use std::f64::consts::{PI, TAU};

pub(crate) use crate::test_rng::Lcg;

/// Random piece in the half-plane rho >= 0.
pub(crate) fn random_piece(rng: &mut Lcg) -> ProfileArc {
    loop {
        let p = match (rng.f() * 5.0) as u32 {
            0 => ProfileArc::Segment {
                start: Point2::new(rng.f(), rng.f() - 0.5),
                end: Point2::new(rng.f(), rng.f() - 0.5),
            },
            1 => {
                // flat annulus or disk
                let z = rng.f() - 0.5;
                let r0 = if rng.f() < 0.5 { 0.0 } else { rng.f() * 0.5 };
                ProfileArc::Segment {
                    start: Point2::new(r0, z),
                    end: Point2::new(r0 + 0.2 + rng.f() * 0.5, z),
                }
            }
            2 => {
                // sphere-like: centre on the axis
                let r = 0.2 + rng.f() * 0.5;
                let a = -PI / 2.0 + rng.f() * PI * 0.5;
                ProfileArc::Arc {
                    center: Point2::new(0.0, rng.f() - 0.5),
                    radius: r,
                    phi_start: a,
                    sweep: rng.f() * (PI / 2.0 - a),
                }
            }
            _ => ProfileArc::Arc {
                center: Point2::new(rng.f() * 1.2 - 0.2, rng.f() - 0.5),
                radius: 0.05 + rng.f() * 0.5,
                phi_start: rng.f() * TAU,
                sweep: (rng.f() - 0.5) * 3.0,
            },
        };
        if p.length() > 1e-3 && (0..=50).all(|i| p.point_at(i as f64 / 50.0).x >= 0.0) {
            return p;
        }
    }
}

pub(crate) fn random_pose(rng: &mut Lcg, spread: f64) -> Isometry3<f64> {
    let axis = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5);
    let rot = UnitQuaternion::from_scaled_axis(axis * 6.0);
    let t = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5) * spread;
    Isometry3::from_parts(Translation3::from(t), rot)
}

fn surface_point(p: &Patch, s: f64, th: f64) -> Point3<f64> {
    lift(p.arc.point_at(s.clamp(0.0, 1.0)), &e_rho(th))
}

/// Reference: grid over B (frame B) measured exactly against A, refined by pattern
/// search; and the same with roles swapped.
pub(crate) fn reference(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> f64 {
    let one_side = |a: &Patch, b: &Patch, pos: &Isometry3<f64>| {
        let pos_inv = pos.inverse();
        let f = |s: f64, th: f64| {
            let x = pos * surface_point(b, s, th);
            a.point_distance(&x).0
        };
        let (ns, nt) = (24, 64);
        let mut cand = Vec::new();
        for i in 0..=ns {
            for j in 0..nt {
                let (s, th) = (i as f64 / ns as f64, j as f64 * TAU / nt as f64);
                cand.push((f(s, th), s, th));
            }
        }
        cand.sort_by(|x, y| x.0.partial_cmp(&y.0).unwrap());
        let mut best = f64::INFINITY;
        for &(mut v, mut s, mut th) in cand.iter().take(6) {
            let (mut hs, mut ht) = (1.0 / ns as f64, TAU / nt as f64);
            while hs > 1e-13 {
                let mut moved = false;
                for (ds, dt) in [(hs, 0.0), (-hs, 0.0), (0.0, ht), (0.0, -ht)] {
                    let s2 = (s + ds).clamp(0.0, 1.0);
                    let v2 = f(s2, th + dt);
                    if v2 < v {
                        (v, s, th) = (v2, s2, th + dt);
                        moved = true;
                    }
                }
                if !moved {
                    hs *= 0.5;
                    ht *= 0.5;
                }
            }
            best = best.min(v);
        }
        let _ = pos_inv;
        best
    };
    one_side(a, b, pos_ab).min(one_side(b, a, &pos_ab.inverse()))
}

fn check(a: &Patch, b: &Patch, pos: &Isometry3<f64>, label: &str) {
    if let Err(e) = try_check(a, b, pos, label) {
        panic!("{e}");
    }
}

fn try_check(a: &Patch, b: &Patch, pos: &Isometry3<f64>, label: &str) -> Result<(), String> {
    let r = patch_distance(a, b, pos);
    let reference = reference(a, b, pos);
    let on_a = a.point_distance(&r.point_a).0;
    let on_b = b.point_distance(&(pos.inverse() * r.point_b)).0;
    if !(on_a < 1e-9 && on_b < 1e-9) {
        return Err(format!("{label}: witnesses off surfaces {on_a} {on_b}"));
    }
    if ((r.point_a - r.point_b).norm() - r.distance).abs() > 1e-12 {
        return Err(format!("{label}: witness distance"));
    }
    if (r.distance - reference).abs() > 1e-7 * (1.0 + reference) {
        return Err(format!(
            "{label}: patch {} vs reference {} (a {:?}, b {:?}, pose {:?})",
            r.distance, reference, a, b, pos
        ));
    }
    Ok(())
}

#[test]
fn random_patch_pairs_match_reference() {
    let mut rng = Lcg(7);
    let mut fails = Vec::new();
    for i in 0..150 {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let pos = random_pose(&mut rng, 3.0);
        if let Err(e) = try_check(&a, &b, &pos, &format!("case {i}")) {
            fails.push(e);
        }
    }
    assert!(fails.is_empty(), "{} failures: {fails:#?}", fails.len());
}

/// Long sweep: `PATCH_STRESS=5000 cargo test --release -- --ignored patch_stress`.
#[test]
#[ignore]
fn patch_stress() {
    let n: usize = std::env::var("PATCH_STRESS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1000);
    let mut rng = Lcg(12345);
    let mut fails = Vec::new();
    for i in 0..n {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let pos = random_pose(&mut rng, 2.0);
        if let Err(e) = try_check(&a, &b, &pos, &format!("case {i}")) {
            fails.push(e);
        }
    }
    assert!(
        fails.is_empty(),
        "{} failures of {n}: {fails:#?}",
        fails.len()
    );
}

/// Arc centres a hair off the axis (round-off of a fitted sphere), snapped or not.
#[test]
fn near_axis_centres_match_reference() {
    let mut rng = Lcg(17);
    let mut fails = Vec::new();
    for i in 0..60 {
        let off = [1e-16, -1e-13, 1e-9, -1e-7, 1e-5][i % 5];
        let piece = |rng: &mut Lcg| ProfileArc::Arc {
            center: Point2::new(off, rng.f() - 0.5),
            radius: 0.3 + 0.5 * rng.f(),
            phi_start: -1.5,
            sweep: 1.0 + 2.0 * rng.f(),
        };
        let a = Patch::new(piece(&mut rng));
        let b = if i % 2 == 0 {
            Patch::new(piece(&mut rng))
        } else {
            Patch::new(random_piece(&mut rng))
        };
        let pos = random_pose(&mut rng, 3.0);
        if let Err(e) = try_check(&a, &b, &pos, &format!("case {i} off {off:e}")) {
            fails.push(e);
        }
    }
    assert!(fails.is_empty(), "{} failures: {fails:#?}", fails.len());
}

#[test]
fn degenerate_poses_match_reference() {
    let mut rng = Lcg(11);
    for i in 0..40 {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let t = Vector3::new(0.0, 0.0, rng.f() * 2.0 - 1.0);
        let poses = [
            // coaxial, same and flipped orientation
            Isometry3::from_parts(Translation3::from(t), UnitQuaternion::identity()),
            Isometry3::from_parts(
                Translation3::from(t),
                UnitQuaternion::from_scaled_axis(Vector3::x() * PI),
            ),
            // parallel axes, offset
            Isometry3::from_parts(
                Translation3::new(rng.f() * 2.0, 0.0, t.z),
                UnitQuaternion::identity(),
            ),
            // axes intersecting at a right angle
            Isometry3::from_parts(
                Translation3::from(t),
                UnitQuaternion::from_scaled_axis(Vector3::x() * PI / 2.0),
            ),
            // B's origin on A's axis, oblique
            Isometry3::from_parts(
                Translation3::from(t),
                UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.7, 0.0)),
            ),
        ];
        for (k, pos) in poses.iter().enumerate() {
            check(&a, &b, pos, &format!("case {i} pose {k}"));
        }
    }
}

fn with_kernel(kernel: Kernel, gauss_restriction: bool) -> PatchOptions {
    PatchOptions {
        kernel,
        gauss_restriction,
        ..PatchOptions::default()
    }
}

/// Agreement tolerance of the kernels: both measure exact point pairs on the patches; they
/// differ only in where their angles converge (to ~1e-15 rad), which moves a distance at a
/// boundary minimum by about that times the patch size.
const KERNEL_AGREEMENT_REL: f64 = 1e-10;

/// The circle-binormal kernel (with and without the Gauss-map restriction, paper 3.3) and
/// the sampled kernel are independent computations of the same exact distance. On random
/// separated pairs they must agree. On pairs slid to within `gap` (1e-9..1e-2) of touching,
/// the true distance is at most `gap` (a pair of patch points at that distance exists): the
/// binormal kernel must find it; the sampled kernel may miss a near-double root between its
/// samples (counted, and it must never beat the binormal kernel).
#[test]
fn kernels_and_gauss_restriction_agree() {
    let n: usize = std::env::var("KERNEL_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(400);
    let mut rng = Lcg(31);
    let mut fails = Vec::new();
    let mut sweep_misses = 0;
    for i in 0..n {
        let a = Patch::new(random_piece(&mut rng));
        let b = Patch::new(random_piece(&mut rng));
        let mut pos = random_pose(&mut rng, 2.0);
        let mut gap = None;
        if i % 2 == 1 {
            // Slide B towards A until a known pair of points is `g` apart.
            let r = patch_distance_with(&a, &b, &pos, with_kernel(Kernel::Sweep, false));
            if r.distance > 0.0 {
                let g = 10f64.powi(-2 - (i / 2 % 8) as i32);
                let shift = (r.point_a - r.point_b) * ((r.distance - g) / r.distance);
                pos = Translation3::from(shift) * pos;
                gap = Some(g);
            }
        }
        let sweep = patch_distance_with(&a, &b, &pos, with_kernel(Kernel::Sweep, false));
        let tol = KERNEL_AGREEMENT_REL * (1.0 + sweep.distance);
        for restrict in [false, true] {
            let bn = patch_distance_with(&a, &b, &pos, with_kernel(Kernel::Binormals, restrict));
            let label = format!("case {i} restrict {restrict} gap {gap:?}");
            let detail = format!("{a:?}, {b:?}, {pos:?}");
            if let Some(g) = gap {
                // Round-off of sliding: ~1e-16 of the pose size.
                if bn.distance > g + 1e-14 {
                    fails.push(format!(
                        "{label}: binormals {} above {g}: {detail}",
                        bn.distance
                    ));
                }
                if sweep.distance < bn.distance - tol {
                    fails.push(format!(
                        "{label}: sweep {} below binormals {}: {detail}",
                        sweep.distance, bn.distance
                    ));
                }
                if !restrict && sweep.distance > bn.distance + tol {
                    sweep_misses += 1;
                }
            } else if (bn.distance - sweep.distance).abs() > tol {
                fails.push(format!(
                    "{label}: binormals {} sweep {}: {detail}",
                    bn.distance, sweep.distance
                ));
            }
        }
    }
    eprintln!(
        "sampled kernel above the binormal kernel near contact: {sweep_misses} of {}",
        n / 2
    );
    assert!(fails.is_empty(), "{} failures: {fails:#?}", fails.len());
}

/// A cone tip (an arc ending on its axis with a steep tangent) poking 7.8e-4 through a
/// flat annulus whose segment is tilted by rounding (1e-18): the patches cross, so their
/// distance is 0. The crossing scan once multiplied the two mirror halves of the annulus'
/// implicit function, a square with no sign change when the halves nearly coincide, and
/// returned the tip-to-plane distance 7.8e-4 (campaign seed 1206, case 16931, a certified
/// lower bound above the true distance 0).
#[test]
fn cone_tip_through_a_nearly_flat_annulus_crosses() {
    let tip = Patch::new(ProfileArc::Arc {
        center: Point2::new(0.25247347735529013, 1.0319028408927775),
        radius: 0.4205752142817924,
        phi_start: -2.214678958174935,
        sweep: 0.027670121627622377,
    });
    let annulus = Patch::new(ProfileArc::Segment {
        start: Point2::new(0.3983674691812611, -2.665102487030627e-18),
        end: Point2::new(0.42173493836252207, -1.2173649133985668e-18),
    });
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        0.8108565397064,
        0.0,
        0.0,
        0.58524496752673,
    ));
    let pos = Isometry3::from_parts(
        Translation3::new(
            -0.26577150075868694,
            -0.3096366496004632,
            0.6947616256937329,
        ),
        rot,
    );
    let d = patch_distance(&tip, &annulus, &pos);
    assert!(d.distance <= 1e-12, "{}", d.distance);
    // Both ways round.
    let d = patch_distance(&annulus, &tip, &pos.inverse());
    assert!(d.distance <= 1e-12, "{}", d.distance);
}

/// A ring's piece wrapped about a bottle's neck (a nearly straight arc of radius 6,073),
/// 2.0e-4 apart on one side: the common normal across the neck, 0.72 long, is a local
/// maximum of the distance along the ring, and the second-order lens test flagged it, sending
/// the pair to subdivision (campaign seed 20261128, shard 4). Both pieces are shorter than
/// that normal, so no crossing lens can have it as its extremum (`second_order.rs`, "Reach"):
/// the answer is exact.
#[test]
fn far_side_of_a_ring_is_no_lens() {
    let neck = Patch::new(ProfileArc::Arc {
        center: Point2::new(-6072.987678786061, 0.48441217474033255),
        radius: 6073.3476809045005,
        phi_start: 0.0,
        sweep: 4.032664654662406e-5,
    });
    let ring = Patch::new(ProfileArc::Arc {
        center: Point2::new(1.2326894217625468, -0.13472827249694064),
        radius: 0.5518571889543366,
        phi_start: -1.718346232781196,
        sweep: 0.009841826080321601,
    });
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        -0.6288193470402367,
        -0.5205210437682127,
        -0.5320044605998354,
        -0.22497850049331133,
    ));
    let pos = Isometry3::from_parts(
        Translation3::new(
            1.1502920205895724,
            0.25118364298827495,
            -0.36013618444839623,
        ),
        rot,
    );
    let d = patch_distance(&neck, &ring, &pos);
    assert!(!d.sampled, "{d:?}");
    assert!(
        d.interior_pairs.iter().any(|(p, q)| (q - p).norm() > 0.7),
        "the far-side normal is among the candidates"
    );
    check(&neck, &ring, &pos, "neck-ring");
}

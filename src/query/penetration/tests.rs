//! Exact cases of the penetration depth: two balls (`r_1 + r_2 - |c_1 - c_2|`), a ball
//! against the side of a cylinder (`r - (|c_xy| - R)` away from the rims), coaxial stacked
//! cylinders (the axial overlap), solids apart (0); and on the paper's models, the
//! certificates themselves re-checked (the clearances of the common point, the separated pose).

use super::*;
use crate::bvh::containment::point_in_solid;
use crate::models::model;
use crate::models::primitives::{arc, deg};
use crate::profile::Profile;
use crate::query::{distance, QueryOptions};
use crate::solid::Solid;
use crate::test_rng::SplitMix64;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::sync::Arc;

fn ball(r: f64, eps: f64) -> Solid {
    let p = Profile::new(
        "ball",
        vec![arc([0.0, 0.0], r, deg(-90.0), deg(90.0)).unwrap()],
    )
    .unwrap();
    Solid::from_profile(Arc::new(p), eps).unwrap()
}

fn named(name: &str, eps: f64) -> Solid {
    Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap()
}

fn random_rotation(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    let axis = Vector3::new(
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    );
    UnitQuaternion::from_scaled_axis(axis * 3.0)
}

/// The target width for the exact cases.
fn target(a: &Solid, b: &Solid, pd: f64) -> f64 {
    (2.0 * (a.tree.target_eps + b.tree.target_eps)).max(0.05 * pd)
}

/// The lower bound's certificate re-checked from the outside: `x` classified against both
/// trees by `point_in_solid`, each true signed margin bounded below by its chain margin less
/// the tree's bound (inside by more than the bound), or minus the margin plus the bound
/// (anywhere else); their sum (module doc of [`mod@crate::query::penetration`]).
fn recheck_certificate(a: &Solid, b: &Solid, x: &nalgebra::Point3<f64>) -> f64 {
    let margin = |s: &Solid| {
        let c = point_in_solid(&s.tree, &(s.pose.inverse() * x));
        if c.inside && c.margin > s.tree.eps {
            c.margin - s.tree.eps
        } else {
            -(c.margin + s.tree.eps)
        }
    };
    margin(a) + margin(b)
}

fn check(a: &Solid, b: &Solid, exact: f64, what: &str) -> Penetration {
    let p = penetration(a, b, &QueryOptions::default()).unwrap();
    assert!(
        p.lower <= exact && exact <= p.upper,
        "{what}: exact {exact} outside [{}, {}]",
        p.lower,
        p.upper
    );
    assert!(
        p.upper - p.lower <= target(a, b, exact),
        "{what}: width {:e} above target {:e} (exact {exact}, [{}, {}])",
        p.upper - p.lower,
        target(a, b, exact),
        p.lower,
        p.upper
    );
    p
}

#[test]
fn two_balls() {
    let mut rng = SplitMix64(4001);
    for k in 0..40 {
        let eps = [1e-3, 1e-4, 1e-5][k % 3];
        let (r1, r2) = (rng.range(0.2, 1.0), rng.range(0.2, 1.0));
        let d = rng.range(0.05 * (r1 + r2), (r1 + r2) * 0.999);
        let dir = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        )
        .normalize();
        let ca = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let a = ball(r1, eps).with_pose(Isometry3::from_parts(
            Translation3::from(ca),
            random_rotation(&mut rng),
        ));
        let b = ball(r2, eps).with_pose(Isometry3::from_parts(
            Translation3::from(ca + dir * d),
            random_rotation(&mut rng),
        ));
        let p = check(&a, &b, r1 + r2 - d, &format!("balls {r1} {r2} at {d}"));
        assert!(
            p.direction.dot(&dir) > 0.99,
            "direction {:?} vs {dir:?}",
            p.direction
        );
    }
}

#[test]
fn ball_against_cylinder_side() {
    // The cylinder model: radius 0.5, z in [0, 1.5].
    let mut rng = SplitMix64(4002);
    for k in 0..30 {
        let eps = [1e-3, 1e-4][k % 2];
        let cyl = named("cylinder", eps);
        let r = rng.range(0.1, 0.3);
        let depth = rng.range(1e-3, 0.5 * r);
        let th = rng.range(0.0, std::f64::consts::TAU);
        let c = Vector3::new(
            (0.5 + r - depth) * th.cos(),
            (0.5 + r - depth) * th.sin(),
            rng.range(0.6, 0.9),
        );
        let b = ball(r, eps).with_pose(Isometry3::from_parts(
            Translation3::from(c),
            random_rotation(&mut rng),
        ));
        check(&cyl, &b, depth, &format!("ball {r} depth {depth}"));
    }
}

#[test]
fn coaxial_stacked_cylinders() {
    // B on top of A with an axial overlap delta: PD = delta (sideways needs 1.0).
    let mut rng = SplitMix64(4003);
    for k in 0..12 {
        let eps = [1e-3, 1e-4][k % 2];
        let cyl = named("cylinder", eps);
        let delta = rng.range(1e-3, 0.3);
        let b = cyl.with_pose(Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 1.5 - delta),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rng.range(0.0, 6.0)),
        ));
        let p = check(&cyl, &b, delta, &format!("stacked delta {delta}"));
        assert!(p.direction.z > 0.99, "{:?}", p.direction);
    }
}

/// A ball in the hole of the `ring` torus (tube radius 0.6 about the circle of radius 0.9 at
/// z = 0.6), centred on the axis at the tube's height: a concave contact, pressed into the
/// tube all around. Its only ways out are along the axis, to where the tube is `r` away:
/// `PD = sqrt((r + 0.6)^2 - 0.9^2)`, while one point's bound `r - d(c, A) = r - 0.3` is far
/// below. The covering of the ball's ways out must reach the exact depth within the width.
#[test]
fn ball_in_the_hole_of_a_torus() {
    for (k, r) in [0.35, 0.5, 0.8].into_iter().enumerate() {
        let eps = [1e-3, 1e-4][k % 2];
        let ring = named("ring", eps);
        let exact = ((r + 0.6_f64).powi(2) - 0.81).sqrt();
        let b = ball(r, eps).with_pose(Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 0.6),
            UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1),
        ));
        let p = check(&ring, &b, exact, &format!("ball {r} in the ring"));
        assert!(p.direction.z.abs() > 0.99, "{:?}", p.direction);
        assert!(p.lower > r - 0.3 + 0.5 * (exact - (r - 0.3)), "{p:?}");
    }
}

/// The covering alone against exact depths, off the axis: a ball touching the ring's tube
/// from outside and from the hole at random heights. The exact depth is the planar distance
/// from the ball's meridian point to the complement of the two disks of radius `0.6 + r`
/// about the tube's meridian centres `(+-0.9, 0.6)` (mirrored across the axis): the bound
/// must stay below it and within its resolution plus the trees' bound of it.
#[test]
fn ball_covering_against_exact_torus_depths() {
    use super::ball_depth::{ball_depth_lower, MAX_CELLS};
    let mut rng = SplitMix64(4005);
    let ring = named("ring", 1e-4);
    let mut resolved = 0;
    let outside_both = |q: (f64, f64), rr: f64| {
        let d1 = (q.0 - 0.9).hypot(q.1 - 0.6);
        let d2 = (q.0 + 0.9).hypot(q.1 - 0.6);
        d1 >= rr && d2 >= rr
    };
    for _ in 0..40 {
        let r = rng.range(0.1, 0.6);
        let rr = 0.6 + r;
        // A meridian point inside the enlarged tube, then the exact depth by a fine polar
        // scan of the nearest point outside both enlarged disks (each ray's exit solved in
        // closed form, the minimum over 20,000 rays refined by the circle's own geometry:
        // the nearest point of the complement lies on a circle's far side or at their
        // crossing on the axis).
        let (rho, z) = loop {
            let q = (rng.range(0.0, 2.0), rng.range(-0.5, 1.7));
            if !outside_both(q, rr) {
                break q;
            }
        };
        let exact = {
            // Candidates: leaving disk 1 straight out (when then outside disk 2), leaving
            // disk 2 likewise, and the two crossings of the circles (on the axis).
            let mut best = f64::INFINITY;
            for (cx, sign) in [(0.9, 1.0), (-0.9, 1.0)] {
                let (dx, dz) = (rho - cx, z - 0.6);
                let n = dx.hypot(dz);
                if n > 0.0 {
                    let q = (cx + sign * rr * dx / n, 0.6 + sign * rr * dz / n);
                    if outside_both(q, rr - 1e-12) {
                        best = best.min((q.0 - rho).hypot(q.1 - z));
                    }
                }
            }
            let h = (rr * rr - 0.81).max(0.0).sqrt();
            for zc in [0.6 + h, 0.6 - h] {
                best = best.min(rho.hypot(z - zc));
            }
            best
        };
        let resolution = 1e-4;
        let got = ball_depth_lower(
            &ring.tree,
            &nalgebra::Point3::new(rho, 0.0, z),
            r,
            4.0,
            resolution,
            0.0,
        );
        assert!(
            got.lower <= exact,
            "r {r} at ({rho}, {z}): lower {} above exact {exact}",
            got.lower
        );
        assert!(
            got.lower >= exact - 4.0 * resolution - 2.0 * ring.tree.eps,
            "r {r} at ({rho}, {z}): lower {} far below exact {exact} ({} cells)",
            got.lower,
            got.cells
        );
        // Capped at the resolution (not by the cell budget), the cell that capped the bound
        // is a way out: no point there is held in (its centre lies within the resolution
        // and the trees' bound of the level set `d(., A) >= r`, outside both disks shrunk
        // by that much), at the bound's radius.
        let Some(off) = got.capped_at else {
            assert_eq!(
                got.cells, MAX_CELLS,
                "r {r} at ({rho}, {z}): no cap below 4"
            );
            continue;
        };
        resolved += 1;
        let q = (rho + off.x, z + off.y);
        let tol = resolution + 2.0 * ring.tree.eps + 1e-9;
        assert!(
            outside_both(q, rr - tol),
            "r {r} at ({rho}, {z}): capped at {q:?}, inside the disks of radius {rr} ({} cells)",
            got.cells
        );
        assert!(
            got.lower - 1e-9 <= off.norm() && off.norm() <= got.lower + resolution + 1e-9,
            "r {r} at ({rho}, {z}): capped at radius {}, bound {}",
            off.norm(),
            got.lower
        );
    }
    assert!(
        resolved >= 20,
        "only {resolved} of 40 capped at the resolution"
    );
}

/// A ball's way out lifted to B's translation (`DetectedBall::capped_translation`), both
/// ways round: the ball in B against the ring, and the ball as A with the ring as B, at
/// rotated poses with the ball's centre off every axis. Moved by it, the ball's centre lies
/// about `r` from the ring's true surface (the tube's distance in the ring's frame), within
/// the covering's resolution, the trees' bounds and the ball's detection error: a wrong
/// sign or a missing rotation puts it deep inside the tube.
#[test]
fn a_balls_way_out_frees_the_ball_both_ways_round() {
    use super::ball_depth::detected_ball_lower;
    let eps = 1e-4;
    let ring = named("ring", eps);
    let tube = |p: &nalgebra::Point3<f64>| (p.x.hypot(p.y) - 0.9).hypot(p.z - 0.6) - 0.6;
    let mut rng = SplitMix64(4007);
    let resolution = 1e-3;
    let (mut ball_in_b, mut ball_in_a) = (0, 0);
    for _ in 0..16 {
        let r = rng.range(0.2, 0.5);
        let b = ball(r, eps);
        let error = b.tree.offset.as_ref().expect("a ball is detected").error;
        let tol = resolution + 2.0 * eps + error + 1e-9;
        // The ball's centre in the ring's frame: pressed into the tube, off the axes.
        let c = loop {
            let q = nalgebra::Point3::new(
                rng.range(-1.6, 1.6),
                rng.range(-1.6, 1.6),
                rng.range(-0.3, 1.5),
            );
            if tube(&q) < r - 0.05 && q.x.abs() > 0.1 && q.y.abs() > 0.1 {
                break q;
            }
        };
        let rot = random_rotation(&mut rng);
        // The ball's own centre is its frame's origin: B's pose in A's (the ring's) frame.
        let pos_ab = Isometry3::from_parts(Translation3::from(c.coords), rot);
        let found = detected_ball_lower(&ring.tree, &b.tree, &pos_ab, 4.0, resolution, 0.0)
            .expect("B is a ball");
        if let Some(t) = found.capped_translation {
            ball_in_b += 1;
            let moved = found.centre + t;
            assert!(
                tube(&moved) >= r - tol,
                "ball in B, r {r} at {c:?}: {moved:?}"
            );
        }
        // Roles swapped: the ring is B, placed by the inverse pose in the ball's frame;
        // moved by `t` there, the ball's centre (A's origin) seen from the ring.
        let pos_ba = pos_ab.inverse();
        let found = detected_ball_lower(&b.tree, &ring.tree, &pos_ba, 4.0, resolution, 0.0)
            .expect("A is a ball");
        if let Some(t) = found.capped_translation {
            ball_in_a += 1;
            let moved_ring = Isometry3::from_parts(
                Translation3::from(pos_ba.translation.vector + t),
                pos_ba.rotation,
            );
            let centre_in_ring = moved_ring.inverse() * found.centre;
            assert!(
                tube(&centre_in_ring) >= r - tol,
                "ball in A, r {r} at {c:?}: {centre_in_ring:?}"
            );
        }
    }
    assert!(
        ball_in_b >= 8 && ball_in_a >= 8,
        "{ball_in_b} and {ball_in_a} of 16 capped"
    );
}

#[test]
fn apart_solids_have_depth_zero() {
    let a = named("pawn", 1e-4);
    let b = named("cup", 1e-4).with_pose(Isometry3::translation(3.0, 0.0, 0.0));
    let p = penetration(&a, &b, &QueryOptions::default()).unwrap();
    assert_eq!((p.lower, p.upper), (0.0, 0.0));
    let s = signed_distance(&a, &b, &QueryOptions::default()).unwrap();
    assert!(s.lower > 0.0 && s.lower <= s.upper && s.penetration.is_none());
}

/// Random overlapping poses of the paper's models: both certificates re-checked from the
/// outside (`point` classified inside both solids with clearances summing to at least
/// `lower`; B moved just past `upper` along `direction` certified apart).
#[test]
fn certificates_hold_on_models() {
    let mut rng = SplitMix64(4004);
    let names = [
        "pawn",
        "cup",
        "bottle",
        "lightmill",
        "table",
        "pawn_ff",
        "cup_ff",
    ];
    let mut overlapping = 0;
    for k in 0..60 {
        let eps = [1e-3, 1e-4][k % 2];
        let a = named(names[k % names.len()], eps);
        let b = named(names[(k / 2 + 3) % names.len()], eps).with_pose(Isometry3::from_parts(
            Translation3::new(
                rng.range(-0.6, 0.6),
                rng.range(-0.6, 0.6),
                rng.range(-0.6, 0.6),
            ),
            random_rotation(&mut rng),
        ));
        let s = signed_distance(&a, &b, &QueryOptions::default()).unwrap();
        assert!(s.lower <= s.upper);
        let Some(p) = s.penetration else { continue };
        assert!(p.lower <= p.upper && p.upper.is_finite());
        if let Some(x) = p.point {
            overlapping += 1;
            let sum = recheck_certificate(&a, &b, &x);
            // A point's certificate gives `lower` itself; a covering of translations starts
            // from it (the ball about no translation) and certifies more.
            let certified = match p.certificate {
                LowerCertificate::Point => p.lower,
                LowerCertificate::TranslationCovering => 0.0,
                other => panic!("case {k}: {other:?} between models"),
            };
            assert!(
                0.0 < sum && certified <= sum,
                "case {k}: lower {} ({:?}) above the re-checked certificate {sum}",
                p.lower,
                p.certificate
            );
        }
        let moved = b.with_pose(Isometry3::from_parts(
            Translation3::from(
                b.pose.translation.vector + p.direction * (p.upper * (1.0 + 1e-9) + 1e-9),
            ),
            b.pose.rotation,
        ));
        if p.direction.norm() > 0.0 {
            let d = distance(&a, &moved, &QueryOptions::default());
            assert!(
                !d.overlap,
                "case {k}: B moved past the upper bound still overlaps"
            );
        }
    }
    assert!(overlapping > 20, "only {overlapping} overlapping cases");
}

/// The distance query's overlap point of this pose lies on a surface, where the margins have
/// no gradient: an ascent of the smaller margin stays there, and the certificate comes from
/// the retry about the seed or the sum's ascents ([`deepest::Pair::ascend`]; B pushed 1.6e-2
/// into A from a touching pose; the interval was `[0, 1.09]` before the retry).
#[test]
fn an_overlap_point_on_a_surface_still_gives_a_certificate() {
    let a = named("bottle", 1e-4);
    let pose = Isometry3::from_parts(
        Translation3::new(
            -0.12995793838283798,
            0.6284350704471169,
            -0.3095548929809142,
        ),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            -0.017255518081219823,
            0.6011224288451708,
            0.1367090717686597,
            0.787187844374634,
        )),
    );
    let b = named("table", 1e-4).with_pose(pose);
    let p = penetration(&a, &b, &QueryOptions::default()).unwrap();
    let x = p.point.expect("a certificate's point");
    let sum = recheck_certificate(&a, &b, &x);
    assert!(
        0.0 < p.lower && p.lower <= sum,
        "lower {} certificate {sum}",
        p.lower
    );
    assert!(
        p.upper - p.lower <= target(&a, &b, p.lower),
        "[{}, {}]",
        p.lower,
        p.upper
    );
}

/// The covering of translations alone, on the ball in the torus's hole (see
/// [`ball_in_the_hole_of_a_torus`]): started from one point's bound `r - 0.3` (the ball's
/// centre), it must reach the exact depth `sqrt((r + 0.6)^2 - 0.81)` within its resolution
/// and the trees' bounds, and never pass it; with a goal below the depth it must certify
/// the goal itself.
#[test]
fn translation_covering_reaches_the_depth_of_a_ball_in_a_hole() {
    use super::translation_cover::{translation_cover_lower, CoverSpec};
    for (r, eps) in [(0.4, 1e-3), (0.6, 1e-4)] {
        let ring = named("ring", eps);
        let b = ball(r, eps);
        let pos_ab = Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 0.6),
            UnitQuaternion::from_euler_angles(0.3, -0.2, 0.1),
        );
        let exact = ((r + 0.6_f64).powi(2) - 0.81).sqrt();
        let from = r - 0.3 - 2.0 * eps;
        let resolution = 2e-3;
        let centre = [nalgebra::Point3::new(0.0, 0.0, 0.6)];
        let spec = |goal: f64| CoverSpec {
            from,
            goal,
            resolution,
            anchors: &centre,
            step_tol: 1e-6,
            deadline: None,
        };
        let past = translation_cover_lower(&ring.tree, &b.tree, &pos_ab, &spec(exact + 0.05));
        assert!(past.lower <= exact, "r {r}: {past:?} above exact {exact}");
        assert!(
            past.lower >= exact - 2.0 * resolution - 4.0 * eps,
            "r {r}: {past:?} far below exact {exact} (from {from})"
        );
        // Capped below its goal: the cell that capped it lies past the bound, within the
        // goal (its centre translation is where the search for a way out looks next).
        let t = past.capped_at.expect("capped below the goal");
        assert!(
            past.lower <= t.norm() && t.norm() <= exact + 0.05,
            "r {r}: capped at {t:?}, lower {}",
            past.lower
        );
        // The ball's only ways out are along the ring's axis (A's z).
        assert!(
            t.z.abs() > 0.9 * t.norm(),
            "r {r}: capped at {t:?}, off the axis"
        );
        let short = translation_cover_lower(&ring.tree, &b.tree, &pos_ab, &spec(exact - 0.02));
        assert!(
            (short.lower - (exact - 0.02)).abs() < 1e-9,
            "r {r}: {short:?} short of the goal {}",
            exact - 0.02
        );
        assert!(
            short.capped_at.is_none(),
            "r {r}: {short:?} reached its goal"
        );
    }
}

//! Closed form of the distance between two balls, capsules or solid tori (both solids
//! offsets of a point, a segment of the axis or a circle, [`crate::bvh::offset_solid`]),
//! before any traversal; a capsule against a solid torus is left to the other paths.
//!
//! A profile that is one circle of radius `r` revolves into a ball (an open profile: a half
//! circle centred on the axis) or a solid torus (a closed profile: the full circle, off the
//! axis). Either solid is the set of points within `r` of its *core*, a point on the axis or
//! a circle coaxial with it, so the distance between two such solids is the distance between
//! their cores minus both radii, clamped at 0 (balls of radius `r` about every core point;
//! the Minkowski argument). This needs one point/point, point/circle or circle/circle
//! distance ([`mod@crate::circle::min_distance`]) instead of a traversal. A capsule (a quarter
//! circle, a side parallel to the axis, a quarter circle) is the offset of a segment of the
//! axis: its distances to a ball's or a capsule's core are those of segments, with a
//! separating slab for the lower bound (`segments.rs`).
//!
//! Certification: the tree's approximating chain (biarcs) lies within the tree's `eps` of
//! the true profile, and is detected to lie within `detect_error` of the circle (each arc's
//! centre and radius off by at most that, consecutive arcs joined, sweeps of one sign adding
//! up to the full or half turn; for a capsule, its side's ends off the side by at most that,
//! [`crate::bvh::offset_solid`]). So the true boundary is within `h = eps + detect_error` of
//! the offset surface, and the true solid contains the core's offset by `r - h` and lies in
//! its offset by `r + h` (the profile curve winds once about the circle's centre). The
//! distance between the true solids is therefore within `h_a + h_b` of the closed form.
//!
//! **What it may call.** The cores of [`crate::bvh::offset_solid`], the circle distances of
//! [`crate::circle`] and the parallel circles of [`crate::query::angles`]; it answers with
//! the query's [`Certified`] type. Never the other paths or the front door.

mod segments;

use crate::bvh::offset_solid::{Core, OffsetSolid};
use crate::circle::{min_distance, point_circle_distance};
use crate::query::angles::common_normals::parallel_circle;
use crate::query::certified::{Certified, TraversalStats};
use nalgebra::{Isometry3, Point3, Vector3};
use segments::{segment_distance, Segment3};

/// Closest points of two cores (A's frame; B placed by `pos_ab`): a realised distance, a
/// lower bound of the cores' distance up to the caller's slack (the circle solver's is its
/// value, [`crate::tolerances::POSE_SLACK_REL`]; segments have their separating slab,
/// `segments.rs`) and the points. `None` for a segment against a circle (no closed form here;
/// the traversal answers capsules against solid tori).
fn core_distance(
    a: &Core,
    b: &Core,
    pos_ab: &Isometry3<f64>,
) -> Option<(f64, f64, Point3<f64>, Point3<f64>)> {
    let on_axis = |z: f64, pos: &Isometry3<f64>| pos * Point3::new(0.0, 0.0, z);
    let axis_segment = |a: &Core, pos: &Isometry3<f64>| match *a {
        Core::Point { z } => Some(Segment3 {
            start: on_axis(z, pos),
            end: on_axis(z, pos),
        }),
        Core::Segment { z0, z1 } => Some(Segment3 {
            start: on_axis(z0, pos),
            end: on_axis(z1, pos),
        }),
        Core::Circle { .. } => None,
    };
    let realised = |(d, pa, pb): (f64, Point3<f64>, Point3<f64>)| Some((d, d, pa, pb));
    match (*a, *b) {
        (Core::Point { z: za }, Core::Point { z: zb }) => {
            let (pa, pb) = (on_axis(za, &Isometry3::identity()), on_axis(zb, pos_ab));
            realised(((pb - pa).norm(), pa, pb))
        }
        (Core::Circle { rho, z }, Core::Point { z: zb }) => {
            let pb = on_axis(zb, pos_ab);
            let m = point_circle_distance(&pb, &parallel_circle(rho, z, &Isometry3::identity()));
            realised((m.distance, m.closest, pb))
        }
        (Core::Point { z: za }, Core::Circle { rho, z }) => {
            let pa = on_axis(za, &Isometry3::identity());
            let m = point_circle_distance(&pa, &parallel_circle(rho, z, pos_ab));
            realised((m.distance, pa, m.closest))
        }
        (Core::Circle { rho: ra, z: za }, Core::Circle { rho: rb, z: zb }) => {
            let ca = parallel_circle(ra, za, &Isometry3::identity());
            let cb = parallel_circle(rb, zb, pos_ab);
            let m = min_distance(&ca, &cb);
            realised((m.distance, m.point_a, m.point_b))
        }
        (Core::Segment { .. }, _) | (_, Core::Segment { .. }) => {
            let sa = axis_segment(a, &Isometry3::identity())?;
            let sb = axis_segment(b, pos_ab)?;
            let d = segment_distance(&sa, &sb);
            Some((d.value, d.lower, d.point_a, d.point_b))
        }
    }
}

/// Distance between two offset solids, certified (A's frame); `slack` is the caller's
/// rounding slack (it covers the circle solver's relative error,
/// [`crate::tolerances::POSE_SLACK_REL`]). Overlap only with a point inside both true
/// solids (the offsets overlap by more than `slack` plus both errors); `lower = 0` in the
/// band around touching where neither overlap nor separation is certain. The value is the
/// distance between the offset surfaces (`core distance - radii`, 0 when they meet), and
/// the witnesses their closest points. `None` for a capsule against a solid torus.
pub fn offset_distance(
    a: &OffsetSolid,
    b: &OffsetSolid,
    pos_ab: &Isometry3<f64>,
    slack: f64,
) -> Option<Certified> {
    let (d_core, d_core_lower, ca, cb) = core_distance(&a.core, &b.core, pos_ab)?;
    let dir = if d_core > 0.0 {
        (cb - ca) / d_core
    } else {
        Vector3::x()
    };
    let value = d_core - a.radius - b.radius;
    let h = a.error + b.error + slack;
    // A point on the core segment, at equal margins inside the two shrunk offsets
    // (radius - error): t from A's core, d_core - t from B's.
    let inner = a.radius - a.error + b.radius - b.error - d_core;
    let inside_both = (inner > slack).then(|| {
        let t = (0.5 * (a.radius - a.error - b.radius + b.error + d_core)).clamp(0.0, d_core);
        ca + dir * t
    });
    // Offset surfaces that meet (within the band around touching): both witnesses at one
    // point, on both spheres' circle of intersection for two balls (on both surfaces), else
    // at the core-segment point between them, within |value| / 2 of each surface.
    let balls = matches!((a.core, b.core), (Core::Point { .. }, Core::Point { .. }));
    let (point_a, point_b) = if value > 0.0 {
        (ca + dir * a.radius, cb - dir * b.radius)
    } else if let Some(x) = balls
        .then(|| sphere_intersection(ca, a.radius, cb, b.radius))
        .flatten()
    {
        (x, x)
    } else {
        let x = ca + dir * (0.5 * (a.radius - b.radius + d_core)).clamp(0.0, d_core);
        (x, x)
    };
    let stats = TraversalStats {
        closed_forms: 1,
        ..TraversalStats::default()
    };
    if let Some(x) = inside_both {
        return Some(Certified::overlap_at(x, stats));
    }
    let value_lower = d_core_lower - a.radius - b.radius;
    let (lower, upper) = ((value_lower - h).max(0.0), (value + h).max(0.0));
    Some(Certified {
        value: value.max(0.0).clamp(lower, upper),
        lower,
        upper,
        point_a,
        point_b,
        overlap: false,
        stats,
    })
}

/// A point on both spheres (centres `ca`, `cb`, radii `ra`, `rb`), on their circle of
/// intersection: at `s = (d^2 + ra^2 - rb^2) / (2 d)` along the centre line and `sqrt(ra^2 -
/// s^2)` across it, so that `|x - ca|^2 = ra^2` and `|x - cb|^2 = rb^2` up to rounding; `None`
/// when the spheres do not meet (one inside the other) or share a centre.
fn sphere_intersection(ca: Point3<f64>, ra: f64, cb: Point3<f64>, rb: f64) -> Option<Point3<f64>> {
    let axis = cb - ca;
    let d = axis.norm();
    if d.is_nan() || d <= 0.0 || d < (ra - rb).abs() {
        return None;
    }
    let dir = axis / d;
    let s = (d * d + ra * ra - rb * rb) / (2.0 * d);
    let h = (ra * ra - s * s).max(0.0).sqrt();
    // Any unit vector across the centre line.
    let helper = if dir.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let across = dir.cross(&helper).normalize();
    Some(ca + dir * s + across * h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::offset_solid::detect;
    use crate::bvh::patch::ProfileArc;
    use crate::profile::ProfileKind;
    use crate::test_rng::Lcg;
    use nalgebra::{Point2, Translation3, UnitQuaternion};
    use std::f64::consts::{PI, TAU};

    /// Balls whose surfaces cross by less than the touching band: the witnesses lie on both
    /// spheres (the oracle's check d), not between them (they were `|value| / 2` off).
    #[test]
    fn touching_balls_have_witnesses_on_both_surfaces() {
        let ball = |z: f64, r: f64| OffsetSolid {
            core: Core::Point { z },
            radius: r,
            error: 1e-13,
        };
        let (a, b) = (ball(0.0, 3.5), ball(1.0, 3.5));
        let mut rng = Lcg(91);
        for depth in [1e-10, 3e-11, 1e-12] {
            let dir = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5).normalize();
            // B's centre (its core is at z = 1 of its frame) at 7 - depth from A's.
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(rng.f(), rng.f(), rng.f()));
            let centre = dir * (7.0 - depth);
            let shift = centre - rot * Vector3::new(0.0, 0.0, 1.0);
            let pos = Isometry3::from_parts(Translation3::from(shift), rot);
            let r = offset_distance(&a, &b, &pos, 1e-9).unwrap();
            assert!(!r.overlap && r.value == 0.0, "{depth}: {r:?}");
            assert_eq!(r.point_a, r.point_b);
            let on_a = (r.point_a.coords.norm() - 3.5).abs();
            let on_b = ((r.point_b.coords - centre).norm() - 3.5).abs();
            assert!(on_a < 1e-14 && on_b < 1e-14, "{depth}: {on_a:e} {on_b:e}");
        }
    }

    fn arc(c: [f64; 2], r: f64, phi0: f64, sweep: f64) -> ProfileArc {
        ProfileArc::Arc {
            center: Point2::new(c[0], c[1]),
            radius: r,
            phi_start: phi0,
            sweep,
        }
    }

    fn quarters(c: [f64; 2], r: f64, phi0: f64, n: usize, total: f64) -> Vec<ProfileArc> {
        (0..n)
            .map(|i| arc(c, r, phi0 + total * i as f64 / n as f64, total / n as f64))
            .collect()
    }

    #[test]
    fn detects_tori_and_balls_only() {
        let torus = quarters([1.0, 0.2], 0.25, 0.0, 4, TAU);
        let t = detect(&torus, ProfileKind::Closed, 0.0).unwrap();
        assert_eq!(t.core, Core::Circle { rho: 1.0, z: 0.2 });
        assert!(t.error < 1e-14);
        let ball = quarters([0.0, 0.5], 0.7, -PI / 2.0, 2, PI);
        let s = detect(&ball, ProfileKind::OpenOnAxis, 1e-6).unwrap();
        assert_eq!(s.core, Core::Point { z: 0.5 });
        assert!(s.error >= 1e-6);
        // Not one circle: a second radius, an arc short of the full turn, a segment, a
        // back-tracking arc, a centre off the axis for an open profile.
        let mut two = torus.clone();
        two[1] = arc([1.0, 0.2], 0.26, PI / 2.0, PI / 2.0);
        assert!(detect(&two, ProfileKind::Closed, 0.0).is_none());
        assert!(detect(&torus[..3], ProfileKind::Closed, 0.0).is_none());
        let seg = vec![ProfileArc::Segment {
            start: Point2::new(0.0, 0.0),
            end: Point2::new(0.0, 1.0),
        }];
        assert!(detect(&seg, ProfileKind::OpenOnAxis, 0.0).is_none());
        let mut back = torus.clone();
        back.push(arc([1.0, 0.2], 0.25, 0.0, 0.1));
        back.push(arc([1.0, 0.2], 0.25, 0.1, -0.1));
        assert!(detect(&back, ProfileKind::Closed, 0.0).is_none());
        let off_axis = quarters([0.1, 0.5], 0.7, -PI / 2.0, 2, PI);
        assert!(detect(&off_axis, ProfileKind::OpenOnAxis, 0.0).is_none());
    }

    /// Dense sampling of both offset surfaces: the closed form's value is the sampled
    /// minimum up to the sampling resolution, never above it by more than that, and the
    /// witness points lie on the surfaces.
    #[test]
    fn matches_dense_sampling_of_tori_and_balls() {
        let solids = [
            OffsetSolid {
                core: Core::Circle { rho: 1.0, z: 0.0 },
                radius: 0.25,
                error: 0.0,
            },
            OffsetSolid {
                core: Core::Point { z: 0.3 },
                radius: 0.5,
                error: 0.0,
            },
            OffsetSolid {
                core: Core::Circle { rho: 0.6, z: -0.2 },
                radius: 0.1,
                error: 0.0,
            },
        ];
        let surface = |s: &OffsetSolid, u: f64, v: f64, w: f64| -> Point3<f64> {
            // u: angle about the axis, (v, w): direction of the offset ball.
            let d = Vector3::new(w.cos() * v.cos(), w.cos() * v.sin(), w.sin());
            let c = match s.core {
                Core::Point { z } => Point3::new(0.0, 0.0, z),
                Core::Circle { rho, z } => Point3::new(rho * u.cos(), rho * u.sin(), z),
                Core::Segment { .. } => unreachable!("balls and tori here"),
            };
            c + d * s.radius
        };
        let mut seed = Lcg(7);
        let mut rnd = move || seed.f();
        for ia in 0..solids.len() {
            for ib in 0..solids.len() {
                for _ in 0..3 {
                    let rot =
                        UnitQuaternion::from_euler_angles(TAU * rnd(), TAU * rnd(), TAU * rnd());
                    let t =
                        Translation3::new(2.5 * (rnd() - 0.5), 2.5 * (rnd() - 0.5), 1.5 + rnd());
                    let pos = Isometry3::from_parts(t, rot);
                    let (a, b) = (&solids[ia], &solids[ib]);
                    let r = offset_distance(a, b, &pos, 0.0).unwrap();
                    assert!(((r.point_a - r.point_b).norm() - r.value).abs() < 1e-12);
                    // Sampled minimum over a grid of both surfaces (coarse), refined near the
                    // best cell: an upper bound of the true distance.
                    let n = 16;
                    let mut best = f64::INFINITY;
                    let grid =
                        |i: usize, m: usize, lo: f64, hi: f64| lo + (hi - lo) * i as f64 / m as f64;
                    let pts = |s: &OffsetSolid| {
                        let mut v = Vec::new();
                        for i in 0..n {
                            for j in 0..n {
                                for k in 0..=n / 2 {
                                    v.push(surface(
                                        s,
                                        grid(i, n, 0.0, TAU),
                                        grid(j, n, 0.0, TAU),
                                        grid(k, n / 2, -PI / 2.0, PI / 2.0),
                                    ));
                                }
                            }
                        }
                        v
                    };
                    let (pa, pb) = (pts(a), pts(b));
                    for p in &pa {
                        for q in &pb {
                            best = best.min((p - pos * q).norm());
                        }
                    }
                    if r.value > 0.0 {
                        // The closed form is never above a realised distance, and the grid
                        // (spacing <= 2 pi 1.25 / 16 ~ 0.5) comes within its spacing.
                        assert!(r.value <= best + 1e-12, "{} > {best}", r.value);
                        assert!(best - r.value < 0.5, "{} vs {best}", r.value);
                    }
                }
            }
        }
    }

    /// The built-in ring and sphere (rational NURBS circles through the biarc tree) are
    /// detected; profiles with a segment or a second radius are not; a query between two
    /// detected solids takes the closed form.
    #[test]
    fn built_in_tori_and_balls_take_the_closed_form() {
        use crate::models::model;
        use crate::query::{distance, QueryOptions};
        use crate::solid::Solid;
        use std::sync::Arc;
        let solid = |n: &str| Solid::from_profile(Arc::new(model(n).unwrap()), 1e-5).unwrap();
        let (ring, sphere, pawn) = (solid("ring"), solid("sphere"), solid("pawn"));
        assert!(matches!(
            ring.tree.offset.unwrap().core,
            Core::Circle { .. }
        ));
        assert!(matches!(
            sphere.tree.offset.unwrap().core,
            Core::Point { .. }
        ));
        for n in ["pawn", "cylinder", "cone", "cup"] {
            assert!(solid(n).tree.offset.is_none(), "{n}");
        }
        let far = Isometry3::translation(5.0, 0.5, 0.3);
        let d = distance(&ring, &sphere.with_pose(far), &QueryOptions::default());
        assert_eq!(d.stats.closed_forms, 1);
        assert_eq!(d.stats.node_pairs, 0);
        assert!(d.lower > 0.0 && d.lower <= d.value && d.value <= d.upper);
        let d = distance(&ring, &pawn.with_pose(far), &QueryOptions::default());
        assert_eq!(d.stats.closed_forms, 0);
    }

    #[test]
    fn overlap_witness_is_inside_both() {
        let a = OffsetSolid {
            core: Core::Circle { rho: 1.0, z: 0.0 },
            radius: 0.25,
            error: 1e-3,
        };
        let b = OffsetSolid {
            core: Core::Point { z: 0.0 },
            radius: 0.3,
            error: 1e-3,
        };
        // Ball centred on the torus core circle: deep overlap.
        let pos = Isometry3::translation(1.0, 0.0, 0.0);
        let r = offset_distance(&a, &b, &pos, 1e-12).unwrap();
        assert!(r.overlap);
        let x = r.point_a;
        let to_core_a = (x.coords.xy().norm() - 1.0).hypot(x.z);
        let to_core_b = (x - Point3::new(1.0, 0.0, 0.0)).norm();
        assert!(to_core_a <= 0.25 - 1e-3 && to_core_b <= 0.3 - 1e-3);
        assert_eq!(r.lower, 0.0);
        // Ball in the hole, touching: no overlap certificate, interval around 0.
        let pos = Isometry3::translation(0.0, 0.0, 0.0);
        let b2 = OffsetSolid { radius: 0.75, ..b };
        let r = offset_distance(&a, &b2, &pos, 1e-12).unwrap();
        assert!(!r.overlap);
        assert!(r.lower == 0.0 && r.upper >= 2e-3 && r.upper < 2.1e-3);
    }

    /// The built-in capsule (radius 0.4, caps centred at z 0.4 and 1.2) is detected at every
    /// eps, and pairs of capsules and balls take the closed form; a capsule against a solid
    /// torus does not.
    #[test]
    fn built_in_capsule_takes_the_closed_form() {
        use crate::models::model;
        use crate::query::{distance, QueryOptions};
        use crate::solid::Solid;
        use std::sync::Arc;
        let solid =
            |n: &str, eps: f64| Solid::from_profile(Arc::new(model(n).unwrap()), eps).unwrap();
        for eps in [1e-2, 1e-4, 1e-6] {
            let o = solid("capsule", eps).tree.offset.expect("a capsule");
            let Core::Segment { z0, z1 } = o.core else {
                panic!("{o:?}");
            };
            assert!(
                (z0 - 0.4).abs() < 1e-12 && (z1 - 1.2).abs() < 1e-12,
                "{o:?}"
            );
            // The tree's own bound (below eps: the circles are fitted exactly) plus rounding.
            assert!(
                (o.radius - 0.4).abs() < 1e-12 && o.error <= eps + 1e-12,
                "{o:?}"
            );
        }
        let (capsule, sphere, ring) = (
            solid("capsule", 1e-5),
            solid("sphere", 1e-5),
            solid("ring", 1e-5),
        );
        let pose = Isometry3::new(Vector3::new(0.3, 0.9, 0.5), Vector3::new(1.1, 0.2, 0.4));
        for other in [&capsule, &sphere] {
            let d = distance(&capsule, &other.with_pose(pose), &QueryOptions::default());
            assert_eq!((d.stats.closed_forms, d.stats.node_pairs), (1, 0), "{d:?}");
            let search = QueryOptions {
                closed_form: false,
                convex_path: false,
                ..QueryOptions::default()
            };
            let s = distance(&capsule, &other.with_pose(pose), &search);
            // Both intervals hold the true distance.
            assert!(d.lower <= s.upper && s.lower <= d.upper, "{d:?} {s:?}");
        }
        let far = Isometry3::translation(5.0, 0.5, 0.3);
        let d = distance(&capsule, &ring.with_pose(far), &QueryOptions::default());
        assert_eq!(d.stats.closed_forms, 0);
        assert!(d.stats.node_pairs > 0 && d.lower > 0.0);
    }

    /// Chains that are not capsules: unequal radii, caps that turn the wrong way (a chain
    /// from the pole of the lower cap's centre that faces the side, denting the capsule), a
    /// side off the caps' radius, a closed profile.
    #[test]
    fn detects_capsules_only() {
        let cap = |c: [f64; 2], r: f64, phi0: f64, sweep: f64| arc(c, r, phi0, sweep);
        let side = |x: f64, z0: f64, z1: f64| ProfileArc::Segment {
            start: Point2::new(x, z0),
            end: Point2::new(x, z1),
        };
        let capsule = vec![
            cap([0.0, 0.4], 0.4, -PI / 2.0, PI / 4.0),
            cap([0.0, 0.4], 0.4, -PI / 4.0, PI / 4.0),
            side(0.4, 0.4, 0.8),
            side(0.4, 0.8, 1.2),
            cap([0.0, 1.2], 0.4, 0.0, PI / 2.0),
        ];
        let o = detect(&capsule, ProfileKind::OpenOnAxis, 1e-6).unwrap();
        assert_eq!(o.core, Core::Segment { z0: 0.4, z1: 1.2 });
        assert!(o.error >= 1e-6 && o.error < 1e-6 + 1e-14, "{o:?}");
        // The same capsule run from the top.
        let down: Vec<ProfileArc> = capsule.iter().rev().map(|p| p.reversed()).collect();
        let o = detect(&down, ProfileKind::OpenOnAxis, 0.0).unwrap();
        assert_eq!(o.core, Core::Segment { z0: 0.4, z1: 1.2 });
        let mut wide = capsule.clone();
        wide[4] = cap([0.0, 1.2], 0.41, 0.0, PI / 2.0);
        assert!(detect(&wide, ProfileKind::OpenOnAxis, 0.0).is_none());
        let mut off_side = capsule.clone();
        off_side[2] = side(0.4 + 1e-6, 0.4, 0.8);
        assert!(detect(&off_side, ProfileKind::OpenOnAxis, 0.0).is_none());
        let dented = vec![
            cap([0.0, 0.4], 0.4, PI / 2.0, -PI / 2.0),
            side(0.4, 0.4, 1.2),
            cap([0.0, 1.2], 0.4, 0.0, PI / 2.0),
        ];
        assert!(detect(&dented, ProfileKind::OpenOnAxis, 0.0).is_none());
        assert!(detect(&capsule, ProfileKind::Closed, 0.0).is_none());
    }

    /// Capsules and balls against each other, sampled densely (a grid over each core and the
    /// offset directions, which covers the solids): the closed form is never above a
    /// realised distance, comes within the grid's spacing of the minimum, and its lower
    /// bound is at most the upper.
    #[test]
    fn capsules_match_dense_sampling() {
        let solids = [
            OffsetSolid {
                core: Core::Segment { z0: 0.4, z1: 1.2 },
                radius: 0.4,
                error: 0.0,
            },
            OffsetSolid {
                core: Core::Segment { z0: -0.5, z1: 0.1 },
                radius: 0.15,
                error: 0.0,
            },
            OffsetSolid {
                core: Core::Point { z: 0.3 },
                radius: 0.5,
                error: 0.0,
            },
        ];
        let samples = |s: &OffsetSolid| {
            let (z0, z1) = match s.core {
                Core::Segment { z0, z1 } => (z0, z1),
                Core::Point { z } => (z, z),
                Core::Circle { .. } => unreachable!(),
            };
            let n = 12;
            let mut v = Vec::new();
            for i in 0..=n {
                let z = z0 + (z1 - z0) * i as f64 / n as f64;
                for j in 0..2 * n {
                    for k in 0..=n {
                        let (u, w) = (PI * j as f64 / n as f64, PI * (k as f64 / n as f64 - 0.5));
                        let d = Vector3::new(w.cos() * u.cos(), w.cos() * u.sin(), w.sin());
                        v.push(Point3::new(0.0, 0.0, z) + d * s.radius);
                    }
                }
            }
            v
        };
        let mut rng = Lcg(23);
        for a in &solids {
            for b in &solids {
                for _ in 0..4 {
                    let rot = UnitQuaternion::from_euler_angles(
                        TAU * rng.f(),
                        TAU * rng.f(),
                        TAU * rng.f(),
                    );
                    let t = Translation3::new(rng.f() - 0.5, rng.f() - 0.5, 1.0 + 1.5 * rng.f());
                    let pos = Isometry3::from_parts(t, rot);
                    let r = offset_distance(a, b, &pos, 0.0).unwrap();
                    assert!(r.lower <= r.upper);
                    if r.overlap {
                        continue;
                    }
                    let (pa, pb) = (samples(a), samples(b));
                    let mut best = f64::INFINITY;
                    for p in &pa {
                        for q in &pb {
                            best = best.min((p - pos * q).norm());
                        }
                    }
                    assert!(r.lower <= best + 1e-12, "{} > {best}", r.lower);
                    if r.value > 0.0 {
                        assert!(r.value <= best + 1e-12, "{} > {best}", r.value);
                        assert!(((r.point_a - r.point_b).norm() - r.value).abs() < 1e-12);
                        // Grid spacing: pi / 12 of the radius, 0.8 / 12 along the core.
                        assert!(best - r.value < 0.25, "{} vs {best}", r.value);
                    }
                }
            }
        }
        // A capsule against a solid torus has no closed form here.
        let torus = OffsetSolid {
            core: Core::Circle { rho: 1.0, z: 0.0 },
            radius: 0.2,
            error: 0.0,
        };
        assert!(offset_distance(&solids[0], &torus, &Isometry3::identity(), 0.0).is_none());
    }
}

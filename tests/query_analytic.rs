//! Distance queries on solids whose profiles are exactly arcs and segments (trees with
//! eps = 0: spheres, rings, capped cylinders), against closed-form distances. Independent
//! of the query code: the references use only elementary geometry (and, for two rings, a
//! dense 1-D sampling of the circle/circle distance refined by golden-section search).

use nalgebra::{Isometry3, Point2, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::bvh::{ProfileArc, QueryTree};
use revdist::profile::ProfileKind;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

/// Round-off allowance of a certified interval against an exact reference (eps = 0 trees:
/// the patch distances are exact up to a few hundred ulps of the scene size).
const SLACK: f64 = 1e-9;

struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn rotation(&mut self) -> UnitQuaternion<f64> {
        let v = Vector3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5);
        UnitQuaternion::from_scaled_axis(v * 7.0)
    }
    fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5);
            if v.norm() > 0.1 && v.norm() < 0.5 {
                return v.normalize();
            }
        }
    }
}

fn sphere(r: f64) -> Solid {
    let arc = ProfileArc::Arc {
        center: Point2::new(0.0, 0.0),
        radius: r,
        phi_start: -PI / 2.0,
        sweep: PI,
    };
    let tree = QueryTree::from_exact_pieces(&[arc], ProfileKind::OpenOnAxis, 0.2, 0.2);
    Solid::new(Arc::new(tree), None)
}

fn ring(big: f64, small: f64) -> Solid {
    let arc = ProfileArc::Arc {
        center: Point2::new(big, 0.0),
        radius: small,
        phi_start: -PI,
        sweep: TAU,
    };
    let tree = QueryTree::from_exact_pieces(&[arc], ProfileKind::Closed, 0.3, 0.3);
    Solid::new(Arc::new(tree), None)
}

fn cylinder(r: f64, half_h: f64) -> Solid {
    let p = |x: f64, y: f64| Point2::new(x, y);
    let pieces = [
        ProfileArc::Segment {
            start: p(0.0, -half_h),
            end: p(r, -half_h),
        },
        ProfileArc::Segment {
            start: p(r, -half_h),
            end: p(r, half_h),
        },
        ProfileArc::Segment {
            start: p(r, half_h),
            end: p(0.0, half_h),
        },
    ];
    let tree = QueryTree::from_exact_pieces(&pieces, ProfileKind::OpenOnAxis, 0.3, 0.25);
    Solid::new(Arc::new(tree), None)
}

fn pose(t: Vector3<f64>, r: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), r)
}

fn check(a: &Solid, b: &Solid, reference: f64, label: &str) {
    let d = distance(a, b, &QueryOptions::default());
    assert!(
        d.lower <= reference + SLACK && reference <= d.upper + SLACK,
        "{label}: reference {reference} outside [{}, {}]",
        d.lower,
        d.upper
    );
    assert!(
        (d.value - reference).abs() <= d.upper - d.lower + SLACK,
        "{label}: value {} vs reference {reference}",
        d.value
    );
    // Exact trees: the interval closes up to round-off, so the test is sharp.
    assert!(
        d.upper - d.lower <= 1e-8,
        "{label}: gap {} - {}",
        d.upper,
        d.lower
    );
    if reference > 1e-6 {
        assert!(
            !d.overlap,
            "{label}: overlap claimed at distance {reference}"
        );
        let w = (d.point_a - d.point_b).norm();
        assert!(
            (w - d.value).abs() < 1e-7,
            "{label}: witness distance {w} vs {}",
            d.value
        );
    }
}

/// Distance from a point to the circle of radius `r` in the plane z = 0 (local frame).
fn point_circle(p: &Point3<f64>, r: f64) -> f64 {
    (p.x.hypot(p.y) - r).hypot(p.z)
}

/// Distance between the circle (radius ra, z = 0) and B's circle (radius rb) placed by
/// `pos`: dense sampling of B's circle refined by golden-section search.
fn circle_circle(ra: f64, rb: f64, pos: &Isometry3<f64>) -> f64 {
    let f = |t: f64| point_circle(&(pos * Point3::new(rb * t.cos(), rb * t.sin(), 0.0)), ra);
    let n = 2000;
    let mut best = f64::INFINITY;
    for i in 0..n {
        let t = i as f64 * TAU / n as f64;
        if f(t) <= f(t - TAU / n as f64) && f(t) <= f(t + TAU / n as f64) {
            let (mut a, mut b) = (t - TAU / n as f64, t + TAU / n as f64);
            for _ in 0..100 {
                let (m1, m2) = (a + (b - a) / 3.0, b - (b - a) / 3.0);
                if f(m1) < f(m2) {
                    b = m2;
                } else {
                    a = m1;
                }
            }
            best = best.min(f(0.5 * (a + b)));
        }
    }
    best
}

#[test]
fn spheres_separated_touching_overlapping_nested() {
    let mut rng = Rng(1);
    let a = sphere(1.0);
    for i in 0..40 {
        let rb = 0.2 + rng.f();
        let dir = rng.unit();
        let gap = match i % 4 {
            0 => rng.f() * 2.0,
            1 => 10f64.powf(-9.0 + 7.0 * rng.f()),
            2 => -rng.f() * 0.5 * rb,
            _ => -(1.0 + rb) + rng.f() * (1.0 - rb).abs() * 0.5, // nested when rb < 1
        };
        let dist_centres = (1.0 + rb + gap).max(0.0);
        let b = sphere(rb).with_pose(pose(dir * dist_centres, rng.rotation()));
        let reference = (dist_centres - 1.0 - rb).max(0.0);
        check(&a, &b, reference, &format!("spheres {i} gap {gap}"));
    }
}

#[test]
fn interlocked_rings_down_to_1e9_clearance() {
    let mut rng = Rng(2);
    for i in 0..24 {
        let big = 1.0;
        let rot =
            UnitQuaternion::from_scaled_axis(Vector3::x() * (PI / 2.0 + (rng.f() - 0.5) * 0.6));
        let p = pose(
            Vector3::new(big * (0.7 + 0.6 * rng.f()), 0.1 * rng.f(), 0.0),
            rot,
        );
        let dmm = circle_circle(big, big, &p);
        let clearance = 10f64.powf(-9.0 + 8.0 * (i as f64 / 23.0));
        let small = 0.5 * (dmm - clearance);
        let a = ring(big, small);
        let b = ring(big, small).with_pose(p);
        check(
            &a,
            &b,
            clearance,
            &format!("rings {i} clearance {clearance:e}"),
        );
    }
}

#[test]
fn sphere_centred_on_ring_axis_and_inside_hole() {
    let a = ring(1.0, 0.3);
    for (z, rs) in [
        (0.0, 0.5),
        (0.0, 0.7),
        (0.5, 0.4),
        (1.2, 0.3),
        (0.0, 0.69999),
    ] {
        let b = sphere(rs).with_pose(pose(Vector3::new(0.0, 0.0, z), UnitQuaternion::identity()));
        let reference = ((1.0f64.hypot(z)) - 0.3 - rs).max(0.0);
        check(&a, &b, reference, &format!("sphere on axis z {z} r {rs}"));
    }
}

#[test]
fn capped_cylinders_parallel_faces_and_crossed_axes() {
    let a = cylinder(1.0, 0.5);
    // Coaxial stack: flat faces parallel, continuum of closest points.
    for gap in [1e-9, 1e-5, 0.3] {
        let b = cylinder(0.6, 0.2).with_pose(pose(
            Vector3::new(0.0, 0.0, 0.7 + gap),
            UnitQuaternion::identity(),
        ));
        check(&a, &b, gap, &format!("coaxial stack gap {gap}"));
    }
    // Parallel axes, offset, faces parallel.
    for gap in [1e-9, 1e-4, 0.2] {
        let b = cylinder(0.6, 0.2).with_pose(pose(
            Vector3::new(0.9, 0.3, 0.7 + gap),
            UnitQuaternion::identity(),
        ));
        check(&a, &b, gap, &format!("offset stack gap {gap}"));
    }
    // Side by side, parallel axes: distance between the cylindrical faces.
    let b = cylinder(0.6, 0.2).with_pose(pose(
        Vector3::new(1.8, 0.0, 0.1),
        UnitQuaternion::identity(),
    ));
    check(&a, &b, 0.2, "side by side");
    // Crossed axes (intersecting at a point above the top face).
    let rot = UnitQuaternion::from_scaled_axis(Vector3::x() * (PI / 2.0));
    let b = cylinder(0.3, 2.0).with_pose(pose(Vector3::new(0.0, 0.0, 0.5 + 0.3 + 0.05), rot));
    check(&a, &b, 0.05, "crossed axes");
    // Nested: small cylinder inside.
    let b = cylinder(0.3, 0.2).with_pose(pose(Vector3::new(0.1, 0.0, 0.0), rng_rot(3)));
    check(&a, &b, 0.0, "nested");
}

fn rng_rot(seed: u64) -> UnitQuaternion<f64> {
    Rng(seed).rotation()
}

#[test]
fn sphere_against_capped_cylinder_random_poses() {
    let mut rng = Rng(4);
    let a = cylinder(0.8, 0.6);
    for i in 0..60 {
        let rs = 0.1 + 0.4 * rng.f();
        let c = Vector3::new(
            rng.f() * 3.0 - 1.5,
            rng.f() * 3.0 - 1.5,
            rng.f() * 3.0 - 1.5,
        );
        // Distance from the centre to the solid cylinder.
        let rho = c.x.hypot(c.y);
        let dr = (rho - 0.8).max(0.0);
        let dz = (c.z.abs() - 0.6).max(0.0);
        let reference = (dr.hypot(dz) - rs).max(0.0);
        let b = sphere(rs).with_pose(pose(c, rng.rotation()));
        check(&a, &b, reference, &format!("sphere-cylinder {i}"));
    }
}

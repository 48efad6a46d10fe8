//! Interlocking of rings, checked topologically: the linking number of two tori's core
//! circles.
//!
//! Two disjoint circles `A`, `B` are linked when `B` crosses the flat disk spanned by `A`
//! exactly once (transversally): the linking number is the signed count of those crossings
//! (Rolfsen, *Knots and Links*, 5.D). Solid tori whose core circles are linked cannot be
//! separated without one passing through the other, so a link that is intact at the start
//! of a run stays intact as long as the solids never overlap; checking it at the end is a
//! check of the non-overlap certificate on the geometry.

use nalgebra::{Isometry3, Point3, Vector3};

/// A circle in space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    pub centre: Point3<f64>,
    /// Unit normal of the circle's plane.
    pub normal: Vector3<f64>,
    pub radius: f64,
}

/// The core circle of a torus of major radius `major` placed by `pose` (axis = local z).
pub fn core_circle(pose: &Isometry3<f64>, major: f64) -> Circle {
    Circle {
        centre: pose * Point3::origin(),
        normal: pose.rotation * Vector3::z(),
        radius: major,
    }
}

/// The linking number of two disjoint circles: signed crossings of `b` through the disk of
/// `a` (0 or +-1 for circles). Non-transversal configurations (`b` in the plane of `a`) count
/// no crossing.
pub fn linking_number(a: &Circle, b: &Circle) -> i32 {
    // b(t) = cb + rb (cos t u + sin t v), u, v an orthonormal basis of b's plane.
    let (u, v) = basis(&b.normal);
    let d = (b.centre - a.centre).dot(&a.normal);
    let (pu, pv) = (b.radius * u.dot(&a.normal), b.radius * v.dot(&a.normal));
    // d + pu cos t + pv sin t = 0: with amp = |(pu, pv)|, cos(t - phi) = -d / amp.
    let amp = pu.hypot(pv);
    if amp <= 1e-14 * b.radius || d.abs() >= amp {
        return 0;
    }
    let phi = pv.atan2(pu);
    let delta = (-d / amp).acos();
    let mut lk = 0;
    for t in [phi + delta, phi - delta] {
        let p = b.centre + b.radius * (t.cos() * u + t.sin() * v);
        if (p - a.centre).norm() < a.radius {
            let tangent = -t.sin() * u + t.cos() * v;
            lk += if tangent.dot(&a.normal) > 0.0 { 1 } else { -1 };
        }
    }
    lk
}

fn basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = n.cross(&helper).normalize();
    let v = n.cross(&u);
    (u, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};

    #[test]
    fn hopf_link_and_separate_circles() {
        let a = Circle {
            centre: Point3::origin(),
            normal: Vector3::z(),
            radius: 1.0,
        };
        // A circle in the xz plane through a's disk at x = 0.3 (and outside it at x = 2.3).
        let pose = Isometry3::from_parts(
            Translation3::new(1.3, 0.0, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
        );
        let b = core_circle(&pose, 1.0);
        assert_eq!(linking_number(&a, &b).abs(), 1);
        assert_eq!(linking_number(&b, &a).abs(), 1);
        // Moved away: unlinked.
        let far = core_circle(&(Isometry3::translation(3.0, 0.0, 0.0) * pose), 1.0);
        assert_eq!(linking_number(&a, &far), 0);
        // Coplanar circles: not linked.
        let flat = core_circle(&Isometry3::translation(0.5, 0.0, 0.0), 0.3);
        assert_eq!(linking_number(&a, &flat), 0);
    }
}

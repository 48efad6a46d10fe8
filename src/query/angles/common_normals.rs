//! The circle-binormal kernels of the patch distance (paper sections 3.2 and 3.3).
//!
//! * Torus patch against torus patch: every common normal line is a binormal of the two
//!   major circles; its surface points are the major-circle feet moved by `+-r` along the
//!   line (the `l +- r1 +- r2` of the paper), kept when their arc angle is in range. The
//!   Gauss-map restriction ([`crate::query::angles::normal_range`]) narrows the angles searched.
//! * A circle against a torus patch: the distance from `G(theta)` to the torus' major circle
//!   `M` (to the point of `M` in the meridian plane of `G(theta)`, or the opposite one) is
//!   critical exactly where `G(theta)` and that point span a binormal of `G` and `M`: the
//!   connecting vector lies in the meridian plane, so it is orthogonal to `M`'s tangent, and
//!   criticality makes it orthogonal to `G`'s tangent. Between consecutive critical angles
//!   both distances are monotone, so crossings of the torus surface are bracketed by them.
//! * Circle against circle: [`mod@crate::circle::min_distance`].
//!
//! Each function reports `false` (or `Err`) for configurations with a continuum of
//! binormals or a zero-length binormal, where the caller falls back to the sampled
//! kernels of [`crate::query::angles::radial_field`].

use super::normal_range::{major_angle_ranges, MajorRanges};
use super::radial_field::ParamCircle;
use crate::bvh::patch::{Core, Patch};
use crate::circle::{self, AngleInterval, Circle3, Multiplicity};
use crate::tolerances::MIN_BINORMAL_REL;
use nalgebra::{Isometry3, Point3, Unit, Vector3};

/// The configuration needs the sampled kernel (continuum or degenerate binormal).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NeedsFallback;

/// The parallel at meridian coordinates `(rho, z)` of a frame placed by `pos` (its angle is
/// the revolution angle; a negative `rho` is the circle of radius `|rho|` whose angle-0
/// point is `rho e_x`).
pub fn parallel_circle(rho: f64, z: f64, pos: &Isometry3<f64>) -> Circle3 {
    let sign = if rho < 0.0 { -1.0 } else { 1.0 };
    Circle3 {
        center: pos * Point3::new(0.0, 0.0, z),
        normal: Unit::new_unchecked(pos.rotation * Vector3::z()),
        radius: rho.abs(),
        u_axis: Unit::new_unchecked(pos.rotation * Vector3::new(sign, 0.0, 0.0)),
    }
}

/// A [`ParamCircle`] (orthogonal `u`, `v` of equal length) as a [`Circle3`] with the same
/// angle parameter; `None` for a point.
pub fn as_circle3(c: &ParamCircle) -> Option<Circle3> {
    let r = c.u.norm();
    let n = c.u.cross(&c.v);
    let nn = n.norm();
    if r == 0.0 || nn == 0.0 {
        return None;
    }
    Some(Circle3 {
        center: c.o,
        normal: Unit::new_unchecked(n / nn),
        radius: r,
        u_axis: Unit::new_unchecked(c.u / r),
    })
}

/// Size of a configuration of two circles, for relative tests.
fn scale(a: &Circle3, b: &Circle3) -> f64 {
    a.radius + b.radius + (a.center - b.center).norm() + a.center.coords.norm()
}

/// Interior common normals of two toroidal patches `a` (frame A) and `b` (placed by
/// `pos_ab`) from the binormals of their major circles, restricted by the Gauss map when
/// `restrict`. Emits (point on a, point on b) in A's frame.
pub fn interior_torus_torus(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    restrict: bool,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> Result<(), NeedsFallback> {
    let (
        Core::Circle {
            r_major: ra, z: za, ..
        },
        Core::Circle {
            r_major: rb, z: zb, ..
        },
    ) = (a.core(), b.core())
    else {
        return Err(NeedsFallback);
    };
    let ma = parallel_circle(ra, za, &Isometry3::identity());
    let mb = parallel_circle(rb, zb, pos_ab);
    let (arcs_a, arcs_b) = if restrict {
        match major_angle_ranges(a, b, pos_ab) {
            MajorRanges::Disjoint => return Ok(()),
            MajorRanges::Ranges { a, b } => (a, b),
        }
    } else {
        (None, None)
    };
    // Solve once per arc of the side with less total angle; the other side filters.
    let len_of = |r: &Option<super::normal_range::AngleArcs>| {
        r.map_or(std::f64::consts::TAU, |r| r.total_len())
    };
    let a_drives = len_of(&arcs_a) <= len_of(&arcs_b);
    let (drive, filter) = if a_drives {
        (arcs_a, arcs_b)
    } else {
        (arcs_b, arcs_a)
    };
    let drive_list: Vec<Option<AngleInterval>> = match drive {
        None => vec![None],
        Some(d) => d.arcs().iter().copied().map(Some).collect(),
    };
    let filter_hull = filter.map(|f| f.hull());
    let pos_ba = pos_ab.inverse();
    let size = scale(&ma, &mb);
    let mut pts_a = Vec::with_capacity(2);
    let mut pts_b = Vec::with_capacity(2);
    for range in drive_list {
        let (range_a, range_b) = if a_drives {
            (range, filter_hull)
        } else {
            (filter_hull, range)
        };
        let bn = circle::binormals(&ma, &mb, range_a, range_b);
        if bn.multiplicity != Multiplicity::Finite || (range.is_none() && bn.items.is_empty()) {
            return Err(NeedsFallback);
        }
        for item in bn.items.iter() {
            let other_angle = if a_drives { item.angle_b } else { item.angle_a };
            if filter.is_some_and(|f| !f.contains(other_angle)) {
                continue;
            }
            let w = item.point_b - item.point_a;
            let l = w.norm();
            if l <= MIN_BINORMAL_REL * size {
                return Err(NeedsFallback);
            }
            let dir = w / l;
            pts_a.clear();
            a.points_on_normal_line(&item.point_a, &dir, &mut pts_a);
            if pts_a.is_empty() {
                continue;
            }
            pts_b.clear();
            b.points_on_normal_line(
                &(pos_ba * item.point_b),
                &(pos_ba.rotation * dir),
                &mut pts_b,
            );
            for p in &pts_a {
                for q in &pts_b {
                    emit(*p, pos_ab * q);
                }
            }
        }
    }
    Ok(())
}

/// Critical angles of the distance from the circle `g` (frame O) to the major circle
/// `(r_major, z)` of a torus about O's z axis (both meridian branches), sorted and
/// de-duplicated, appended to `out`. `false` for a continuum (then `out` is unchanged).
pub fn circle_torus_critical(g: &ParamCircle, r_major: f64, z: f64, out: &mut Vec<f64>) -> bool {
    let Some(gc) = as_circle3(g) else {
        return false;
    };
    let m = parallel_circle(r_major, z, &Isometry3::identity());
    let bn = circle::binormals(&gc, &m, None, None);
    if bn.multiplicity != Multiplicity::Finite || bn.items.is_empty() {
        return false;
    }
    let start = out.len();
    out.extend(
        bn.items
            .iter()
            .map(|b| b.angle_a.rem_euclid(std::f64::consts::TAU)),
    );
    out[start..].sort_by(f64::total_cmp);
    let mut keep = start;
    for i in start..out.len() {
        if keep == start || out[i] - out[keep - 1] > 1e-15 {
            out[keep] = out[i];
            keep += 1;
        }
    }
    out.truncate(keep);
    true
}

/// Closest points of two parallels: `(rho, z)` of frame A and `(rho, z)` of frame B placed
/// by `pos_ab` (both radii > 0). Returns (point on A's parallel, point on B's), A's frame.
pub fn parallel_pair_closest(
    ea: (f64, f64),
    eb: (f64, f64),
    pos_ab: &Isometry3<f64>,
) -> (Point3<f64>, Point3<f64>) {
    let ca = parallel_circle(ea.0, ea.1, &Isometry3::identity());
    let cb = parallel_circle(eb.0, eb.1, pos_ab);
    let m = circle::min_distance(&ca, &cb);
    (m.point_a, m.point_b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};

    #[test]
    fn parallel_circle_angle_is_the_revolution_angle() {
        let pos = Isometry3::from_parts(
            Translation3::new(0.3, -0.2, 0.5),
            UnitQuaternion::from_scaled_axis(Vector3::new(0.4, -1.1, 0.2)),
        );
        for rho in [0.7, -0.7] {
            let c = parallel_circle(rho, 0.25, &pos);
            for k in 0..12 {
                let th = k as f64 * 0.5;
                let local = Point3::new(rho * th.cos(), rho * th.sin(), 0.25);
                assert!((c.point_at(th) - pos * local).norm() < 1e-15);
            }
        }
    }

    #[test]
    fn param_circle_converts_with_the_same_angles() {
        let pos = Isometry3::from_parts(
            Translation3::new(1.0, 2.0, -0.5),
            UnitQuaternion::from_scaled_axis(Vector3::new(-0.3, 0.8, 1.9)),
        );
        let pc = ParamCircle::parallel(0.9, -0.4, &pos);
        let c = as_circle3(&pc).unwrap();
        for k in 0..12 {
            let th = k as f64 * 0.55;
            assert!((c.point_at(th) - pc.point(th)).norm() < 1e-15);
        }
    }
}

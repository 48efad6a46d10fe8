//! Second-order type of an interior common normal (docs/verification.md, "Crossing
//! lenses"): whether the pair may be the extremum of a crossing lens.
//!
//! Two patches that cross in a loop inside both (touching no boundary) enclose, on each
//! patch, a region whose points are all on one side of the other surface. The point `p*` of
//! that region farthest from the other surface is an interior common normal whose length is
//! positive although the patches meet, and the distance from A's points to B's surface has a
//! local maximum there. A driver that takes the shortest candidate would report its length,
//! or a longer one, for patches at distance 0. This module finds the pairs that may be such
//! maxima; the driver then scans the pair's meridian from the pair itself and, when that
//! finds no crossing, reports an upper bound only.
//!
//! **The test.** At a common normal of length `d > 0` with unit direction `w` (from `p` on
//! A to `q` on B), write each surface as a graph over the common tangent plane:
//! `p(x) = p + x - (x' S_A x / 2) w` and `q(y) = q + y + (y' S_B y / 2) w`, where `S_A > 0`
//! means A bends away from `q` and `S_B > 0` means B bends away from `p`. Then
//! `|q(y) - p(x)|^2 = d^2 + d (x' S_A x + y' S_B y) + |x - y|^2 + O(3)`. With `q` following
//! the nearest point of B (`y = M_B^-1 x`, `M_B = I + d S_B`, positive definite at a nearest
//! point), the squared distance from `p(x)` to B is `d^2 + d x' R_A x + O(3)` with
//! `R_A = S_A + S_B M_B^-1` (`I - M_B^-1 = d S_B M_B^-1`, written so that nothing cancels
//! when `d` is small). A local maximum along A needs `R_A <= 0`: a pair whose `R_A` and
//! `R_B` (the same from B's side) both have a positive direction is a local minimum or a
//! saddle of both distance functions, never a lens's extremum. The shape operators are
//! closed forms for a surface of revolution: curvature `1 / r` along the meridian of an arc
//! (0 for a segment) and `n_rho / rho` along the parallel (Meusnier), with respect to the
//! outward-from-core normal.
//!
//! **Reach.** A lens region lies inside its patch, enclosed by the crossing loop, whose
//! points all lie on the other patch. If the pair `(p, q)` of length `d` were the region's
//! extremum, `q` would be `p`'s nearest point of the other patch, so every loop point would be
//! at least `d` from `p`; and every path on the patch from `p` to a boundary parallel must
//! cross the loop. The meridian from `p` to its nearer end is such a path, and all of it lies
//! within its arc length of `p`: when that arc length is below `d`, `p` is not the extremum
//! of a lens on its patch, whatever the curvatures say. This clears the far side of a ring
//! wrapped about a thinner solid (a common normal 0.72 long across a piece 0.25 long), whose
//! distance along the ring is a true local maximum.

use super::*;
use nalgebra::{Matrix2, Matrix3};

/// Relative margin by which the largest eigenvalue of `R_A` (and of `R_B`), and the smallest
/// of `M_A`, `M_B`, must clear zero, in units of the curvatures' size, for a pair to count
/// as no lens extremum. The curvatures are closed forms with relative error near 1e-15 and
/// the pair's direction is a root refined to about 1e-12; a pair closer to degenerate than
/// 1e-9 is treated as a possible lens (the safe side: the caller then subdivides).
const LENS_MARGIN: f64 = 1e-9;

/// Relative margin of the reach test ([`reaches_boundary_within`]): the arc length to the
/// nearer boundary, computed from a parameter placed to about 1e-15 and a closed-form length,
/// must fall short of the pair's length by this fraction (plus as much of the point's size).
const REACH_MARGIN: f64 = 1e-9;

/// A common normal's direction must agree with each surface normal to this cosine defect
/// for the second-order expansion to apply (a pair that is not a common normal to this
/// accuracy is treated as a possible lens).
const NORMAL_ALIGNMENT: f64 = 1e-6;

/// Unit normal (outward from the core) and shape operator with respect to it, in the
/// patch's frame, at the surface point `x`; `None` where the surface is not smooth (a cone
/// tip or an arc meeting the axis off its centre).
fn normal_and_shape(patch: &Patch, x: &Point3<f64>) -> Option<(Vector3<f64>, Matrix3<f64>)> {
    let rho = norm2(x.x, x.y);
    let e_r = if rho > 0.0 {
        Vector3::new(x.x / rho, x.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    let e_theta = Vector3::new(-e_r.y, e_r.x, 0.0);
    let m = Point2::new(rho, x.z);
    let n2 = patch.planar_normal(m);
    let (k_meridian, k_parallel) = match patch.arc {
        // n_rho / rho = (rho - c_rho) / (r rho): exactly 1 / r for a centre on the axis.
        ProfileArc::Arc { center, radius, .. } => {
            let k_parallel = if center.x == 0.0 {
                1.0 / radius
            } else if rho > 0.0 {
                (1.0 - center.x / rho) / radius
            } else {
                return None;
            };
            (1.0 / radius, k_parallel)
        }
        ProfileArc::Segment { .. } => {
            let k_parallel = if n2.x == 0.0 {
                0.0
            } else if rho > 0.0 {
                n2.x / rho
            } else {
                return None;
            };
            (0.0, k_parallel)
        }
    };
    if !k_parallel.is_finite() {
        return None;
    }
    let normal = e_r * n2.x + Vector3::z() * n2.y;
    let t_meridian = e_r * (-n2.y) + Vector3::z() * n2.x;
    let shape = t_meridian * t_meridian.transpose() * k_meridian
        + e_theta * e_theta.transpose() * k_parallel;
    Some((normal, shape))
}

/// Smallest and largest eigenvalues of a 2x2 matrix's symmetric part.
fn eigen_range(m: &Matrix2<f64>) -> (f64, f64) {
    let off = 0.5 * (m[(0, 1)] + m[(1, 0)]);
    let half_trace = 0.5 * (m[(0, 0)] + m[(1, 1)]);
    let radius = norm2(0.5 * (m[(0, 0)] - m[(1, 1)]), off);
    (half_trace - radius, half_trace + radius)
}

/// Whether the interior common normal `(p, q)` (A's frame; `q` on `b`, placed by `pos_ab`,
/// whose inverse is `pos_ba`)
/// may be a local maximum of the distance from one patch's points to the other's surface
/// (module docs), with the margin [`LENS_MARGIN`]. `true` for anything the test cannot
/// decide (a pair of length 0, a surface point that is not smooth, a direction off the
/// normals, a focal point).
pub(super) fn may_be_lens_extremum(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    pos_ba: &Isometry3<f64>,
    p: &Point3<f64>,
    q: &Point3<f64>,
) -> bool {
    let v = q - p;
    let d = v.norm();
    if d <= 0.0 || !d.is_finite() {
        return true;
    }
    // Sides whose lens region could not fit inside the patch (module doc, "Reach").
    let (short_a, short_b) = (
        reaches_boundary_within(a, p, d),
        reaches_boundary_within(b, &(pos_ba * q), d),
    );
    if short_a && short_b {
        return false;
    }
    let w = v / d;
    let Some((n_a, k_a)) = normal_and_shape(a, p) else {
        return true;
    };
    let Some((n_b, k_b)) = normal_and_shape(b, &(pos_ba * q)) else {
        return true;
    };
    let rot = pos_ab.rotation.to_rotation_matrix();
    let (n_b, k_b) = (rot * n_b, rot.matrix() * k_b * rot.matrix().transpose());
    let (c_a, c_b) = (n_a.dot(&w), n_b.dot(&w));
    if 1.0 - c_a.abs() > NORMAL_ALIGNMENT || 1.0 - c_b.abs() > NORMAL_ALIGNMENT {
        return true;
    }
    // A bends away from q when its outward normal points at q (c_a = +1); B bends away
    // from p when its outward normal points at p (c_b = -1).
    let s_a3 = k_a * c_a.signum();
    let s_b3 = k_b * (-c_b.signum());
    let b1 = w.cross(&Vector3::x());
    let b1 = if b1.norm_squared() > 0.25 {
        b1.normalize()
    } else {
        w.cross(&Vector3::y()).normalize()
    };
    let b2 = w.cross(&b1);
    let project = |s: &Matrix3<f64>| {
        Matrix2::new(
            b1.dot(&(s * b1)),
            b1.dot(&(s * b2)),
            b2.dot(&(s * b1)),
            b2.dot(&(s * b2)),
        )
    };
    let (s_a, s_b) = (project(&s_a3), project(&s_b3));
    let margin = LENS_MARGIN * (s_a.norm() + s_b.norm()).max(f64::MIN_POSITIVE);
    let identity = Matrix2::identity();
    // `R` of the side whose points move while the other side's foot follows.
    let reduced = |s_moving: &Matrix2<f64>, s_following: &Matrix2<f64>| {
        let m = identity + s_following * d;
        if eigen_range(&m).0 <= LENS_MARGIN {
            return None;
        }
        m.try_inverse().map(|inv| s_moving + s_following * inv)
    };
    let maximum_along = |r: Option<Matrix2<f64>>| r.is_none_or(|r| eigen_range(&r).1 <= margin);
    (!short_a && maximum_along(reduced(&s_a, &s_b)))
        || (!short_b && maximum_along(reduced(&s_b, &s_a)))
}

/// Whether the meridian of `patch` through its surface point `x` (patch frame) reaches a
/// boundary parallel within arc length `reach` (less [`REACH_MARGIN`]): then every point of
/// that meridian arc is nearer to `x` than `reach` (module doc, "Reach"). `false` when `x`'s
/// parameter cannot be placed on the piece.
fn reaches_boundary_within(patch: &Patch, x: &Point3<f64>, reach: f64) -> bool {
    let m = Point2::new(norm2(x.x, x.y), x.z);
    let s = match patch.arc {
        ProfileArc::Arc { center, .. } => {
            let r = m - center;
            match patch.arc.arc_param(r.y.atan2(r.x)) {
                Some(s) => s,
                None => return false,
            }
        }
        ProfileArc::Segment { start, end } => {
            let e = end - start;
            let l2 = e.norm_squared();
            if l2 == 0.0 {
                return false;
            }
            ((m - start).dot(&e) / l2).clamp(0.0, 1.0)
        }
    };
    let to_end = s.min(1.0 - s) * patch.arc.length();
    to_end * (1.0 + REACH_MARGIN) + REACH_MARGIN * (1.0 + x.coords.norm()) < reach
}

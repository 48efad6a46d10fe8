//! Node-pair lower bounds (paper section 4.2: the priority of a node pair is a lower bound
//! of the distance between everything below the two nodes).
//!
//! Every node stores a disk `D = (c_rho, c_z; s)` of the (rho, z) half-plane containing its
//! curve piece (original and approximation). Revolved about the axis it is the solid torus
//! `T = { x : dist(x, M) <= s }`, `M` the circle of radius `c_rho` at height `c_z`
//! (a disk centre with `c_rho < 0` is moved to the axis first: for points with `rho >= 0`
//! the distance to `(0, c_z)` is not larger than to `(c_rho, c_z)`, so containment holds).
//!
//! **Proof of validity.** For `x` in `T_A`, `y` in `T_B`, with `m_x`, `m_y` their nearest
//! points on `M_A`, `M_B`: `|x - y| >= |m_x - m_y| - |x - m_x| - |y - m_y| >=
//! dist(M_A, M_B) - s_A - s_B`. So `dist(T_A, T_B) >= dist(M_A, M_B) - s_A - s_B`, a lower
//! bound for everything in the two nodes. The circle/circle distance comes from the circle
//! module ([`mod@crate::circle::min_distance`]), verified against exact arithmetic.
//!
//! Cheaper, looser bounds: the bounding sphere of `T` (centre `(0, 0, c_z)`, radius
//! `c_rho + s`) gives sphere/sphere and sphere/torus bounds (point-to-circle distance in
//! closed form). [`node_pair_bound`] tries them first and only computes the torus bound when
//! they do not already prune the pair.

use crate::biarc::Disk;
use crate::bvh::hull::NodeHull;
use crate::bvh::patch::ProfileArc;
use crate::circle::min_distance_value;
use crate::nearest::NearestPoint;
use crate::num::norm2;
use crate::query::angles::common_normals::parallel_circle;
use crate::tolerances::BOUND_SLACK;
use nalgebra::{Isometry3, Point3, Vector3};

/// Which lower bound to use for inner node pairs (measured by `benches/query.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BoundKind {
    /// Bounding spheres only.
    Sphere,
    /// Sphere tests, then the hull and solid-torus bounds when the spheres do not prune
    /// (node pairs with a node over several spirals keep the sphere bound alone,
    /// [`crate::query::search`]'s node keys).
    #[default]
    Torus,
}

/// Solid torus of a disk: major radius (>= 0), height, tube radius.
fn torus_of(d: &Disk) -> (f64, f64, f64) {
    if d.center.x >= 0.0 {
        (d.center.x, d.center.y, d.radius)
    } else {
        (0.0, d.center.y, d.radius - d.center.x)
    }
}

/// Distance from point `p` (frame of the circle) to the circle of radius `r` at height `z`.
fn point_circle(p: &Point3<f64>, r: f64, z: f64) -> f64 {
    norm2(norm2(p.x, p.y) - r, p.z - z)
}

/// Sphere/sphere and sphere/torus lower bounds of the revolved disks.
///
/// Both centres lie on the axes, so B's axis direction `u` in A's frame (the rotation's
/// third column) and the translation `t` place everything: B's centre is `t + z_b u`, and
/// A's centre seen from B has height `u . w` and distance `|u x w|` from B's axis, `w = c_A
/// - t` (a cross product, free of the cancellation of `|w|^2 - (u . w)^2`). No full rotation.
pub fn sphere_bound(da: &Disk, db: &Disk, pos_ab: &Isometry3<f64>) -> f64 {
    let (ra, za, sa) = torus_of(da);
    let (rb, zb, sb) = torus_of(db);
    let u = axis_of(pos_ab);
    let t = pos_ab.translation.vector;
    let ca = Point3::new(0.0, 0.0, za);
    let cb_in_a = Point3::from(t + u * zb);
    let ss = (ca - cb_in_a).norm() - (ra + sa) - (rb + sb);
    // Sphere of B against torus of A, and sphere of A against torus of B.
    let st = point_circle(&cb_in_a, ra, za) - sa - (rb + sb);
    let w = ca.coords - t;
    let ts = norm2(u.cross(&w).norm() - rb, u.dot(&w) - zb) - sb - (ra + sa);
    let scale = 1.0 + ca.coords.norm() + cb_in_a.coords.norm() + ra + rb + sa + sb;
    ss.max(st).max(ts) - BOUND_SLACK * scale
}

/// The direction from A's disk's axis point `(0, 0, c_z)` to B's (A's frame): where the
/// hull iterations between the contents of two disks start.
pub fn axis_direction(da: &Disk, db: &Disk, pos_ab: &Isometry3<f64>) -> Vector3<f64> {
    pos_ab * Point3::new(0.0, 0.0, db.center.y) - Point3::new(0.0, 0.0, da.center.y)
}

/// B's axis direction in A's frame: the third column of `pos_ab`'s rotation, from the unit
/// quaternion `(w, x, y, z)` as `(2 (xz + wy), 2 (yz - wx), 1 - 2 (x^2 + y^2))`.
fn axis_of(pos_ab: &Isometry3<f64>) -> Vector3<f64> {
    let q = pos_ab.rotation.quaternion();
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    Vector3::new(
        2.0 * (x * z + w * y),
        2.0 * (y * z - w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

/// Spherical-shell lower bound of two revolved profile pieces: an arc with centre
/// `(c_rho, c_z)` and radius `r` revolves into a surface within `|c_rho|` of the sphere of
/// radius `r` about the axis point `c = (0, 0, c_z)` (a meridian point `m` of the arc has
/// `| |m - (0, c_z)| - r | <= |c_rho|`, and its revolved copies are as far from `c` as `m`).
/// So for every point `y` of the other piece's surface, `|x - y| >= |y - c| - r - |c_rho|`,
/// and the distance is at least `dist(c, other surface) - r - |c_rho|`; the distance from a
/// point to a revolved piece is the planar distance in its meridian plane (exact).
///
/// Exact for a spherical piece (`c_rho = 0`) whenever the other surface's point nearest to
/// `c` sees the sphere inside the piece's range, e.g. a ball resting in a ring's hole,
/// which touches along a whole circle: a continuum that [`crate::query::search::leaf::subdivision`] could only close
/// by thousands of torus bounds. `-inf` when neither piece is such an arc.
pub fn shell_bound(a: &ProfileArc, b: &ProfileArc, pos_ab: &Isometry3<f64>) -> f64 {
    let one_side = |arc: &ProfileArc, other: &ProfileArc, to_other: &Isometry3<f64>| {
        let ProfileArc::Arc { center, radius, .. } = *arc else {
            return f64::NEG_INFINITY;
        };
        if center.x.abs() >= radius {
            return f64::NEG_INFINITY;
        }
        let c = to_other * Point3::new(0.0, 0.0, center.y);
        let (d, _) = other.nearest(nalgebra::Point2::new(c.x.hypot(c.y), c.z));
        let scale = 1.0 + c.coords.norm() + radius + center.y.abs();
        d - radius - center.x.abs() - BOUND_SLACK * scale
    };
    let pos_ba = pos_ab.inverse();
    one_side(a, b, &pos_ba).max(one_side(b, a, pos_ab))
}

/// Height range `[min, max]` (z of frame A) of a revolved piece of frame B placed by
/// `pos_ab`. On the parallel of meridian point `(rho, z)` the height is
/// `a + rho (R_zx cos t + R_zy sin t)` with `a = t_z + R_zz z`, so it ranges over
/// `a -+ rho |(R_zx, R_zy)|`. Along a segment `a` is linear and `rho |.|` is linear and
/// non-negative, so the smallest height `a - rho |.|` is concave and the largest convex in
/// the segment parameter: both extremes sit at the end parallels. An arc's surface lies
/// within its radius of the parallel of its centre.
fn height_range(piece: &ProfileArc, pos_ab: &Isometry3<f64>) -> (f64, f64) {
    let r = pos_ab.rotation.to_rotation_matrix();
    let m = r.matrix();
    let tilt = m[(2, 0)].hypot(m[(2, 1)]);
    let tz = pos_ab.translation.vector.z;
    let parallel = |rho: f64, z: f64, grow: f64| {
        let a = tz + m[(2, 2)] * z;
        let b = rho.abs() * tilt;
        (a - b - grow, a + b + grow)
    };
    match *piece {
        ProfileArc::Segment { start, end } => {
            let (l0, h0) = parallel(start.x, start.y, 0.0);
            let (l1, h1) = parallel(end.x, end.y, 0.0);
            (l0.min(l1), h0.max(h1))
        }
        ProfileArc::Arc { center, radius, .. } => parallel(center.x, center.y, radius),
    }
}

/// Slab lower bound of two revolved profile pieces: a piece's surface lies between the
/// planes `z = z_min` and `z = z_max` of its own frame (its meridian points' heights), and
/// the other surface's heights in that frame lie in `height_range`; when the ranges are
/// disjoint, their gap bounds the distance (each point pair is at least its height
/// difference apart). Tried both ways. Exact for a flat disk or annulus (a horizontal
/// segment, e.g. a cup's bottom or a table's top) facing a cone whose nearest boundary
/// parallel lies over it: the pairs of straight pieces that no circle bound can separate
/// near contact. `-inf` when neither way separates.
pub fn slab_bound(a: &ProfileArc, b: &ProfileArc, pos_ab: &Isometry3<f64>) -> f64 {
    slab_bound_in(a, b, &a.bounding_disk(), &b.bounding_disk(), pos_ab)
}

/// [`slab_bound`] with the pieces' disks ([`ProfileArc::bounding_disk`]) already at hand.
pub fn slab_bound_in(
    a: &ProfileArc,
    b: &ProfileArc,
    da: &Disk,
    db: &Disk,
    pos_ab: &Isometry3<f64>,
) -> f64 {
    let own = |p: &ProfileArc, d: &Disk| match *p {
        ProfileArc::Segment { start, end } => (start.y.min(end.y), start.y.max(end.y)),
        ProfileArc::Arc { .. } => (d.center.y - d.radius, d.center.y + d.radius),
    };
    let gap = |(lo, hi): (f64, f64), (olo, ohi): (f64, f64)| {
        if olo > hi {
            olo - hi
        } else if ohi < lo {
            lo - ohi
        } else {
            f64::NEG_INFINITY
        }
    };
    let pos_ba = pos_ab.inverse();
    let ab = gap(own(a, da), height_range(b, pos_ab));
    let ba = gap(own(b, db), height_range(a, &pos_ba));
    let t = pos_ab.translation.vector.norm();
    let size = |d: &Disk| d.center.coords.norm() + d.radius;
    ab.max(ba) - BOUND_SLACK * (1.0 + t + size(da) + size(db))
}

/// Minimum distance between the circle of radius `ra` at height `za` (frame A) and the
/// circle of radius `rb` at height `zb` of frame B placed by `pos_ab`: the circle module's
/// degree-8 solver (paper Appendix A), whose root finder keeps even-multiplicity roots, so
/// the global minimum is not lost between samples (a lower bound must never be too high).
pub fn circle_circle_distance(ra: f64, za: f64, rb: f64, zb: f64, pos_ab: &Isometry3<f64>) -> f64 {
    if rb == 0.0 {
        return point_circle(&(pos_ab * Point3::new(0.0, 0.0, zb)), ra, za);
    }
    if ra == 0.0 {
        let p = pos_ab.inverse_transform_point(&Point3::new(0.0, 0.0, za));
        return point_circle(&p, rb, zb);
    }
    let ca = parallel_circle(ra, za, &Isometry3::identity());
    let cb = parallel_circle(rb, zb, pos_ab);
    min_distance_value(&ca, &cb)
}

/// Solid-torus lower bound (module doc).
pub fn torus_bound(da: &Disk, db: &Disk, pos_ab: &Isometry3<f64>) -> f64 {
    let (ra, za, sa) = torus_of(da);
    let (rb, zb, sb) = torus_of(db);
    let d = circle_circle_distance(ra, za, rb, zb, pos_ab);
    let scale = 1.0 + za.abs() + ra + rb + sa + sb + pos_ab.translation.vector.norm();
    d - sa - sb - BOUND_SLACK * scale
}

/// Lower bound for a node pair; `prune_above` lets cheap tests stop early when they already
/// show the pair cannot beat the current upper bound. The bounding spheres first, then, when
/// both nodes have one, the hulls of their fat biarcs ([`crate::bvh::hull::ParallelHull::bound`], closed form,
/// from the direction between the disks' axis points; the support points then steer it
/// towards the hulls' closest points), then the solid tori of the disks (a circle/circle
/// minimum).
pub fn node_pair_bound(
    da: &Disk,
    db: &Disk,
    pos_ab: &Isometry3<f64>,
    kind: BoundKind,
    prune_above: f64,
    hulls: Option<(&NodeHull, &NodeHull)>,
) -> f64 {
    let mut s = sphere_bound(da, db, pos_ab);
    if kind == BoundKind::Sphere || s >= prune_above {
        return s;
    }
    if let Some((ha, hb)) = hulls {
        s = s.max(ha.bound_until(hb, pos_ab, &axis_direction(da, db, pos_ab), prune_above));
        if s >= prune_above {
            return s;
        }
    }
    // The solid tori (a certified circle/circle minimum, the costliest step) only when two
    // points of the major circles do not already show that they cannot reach the level:
    // the key then stays the spheres' and hulls' (node keys order the search; measured,
    // the tori's sharper keys did not save node pairs, and with the traversal's first
    // leaf from [`crate::query::search`]'s dive most node keys have a level).
    if torus_cannot_reach(da, db, pos_ab, prune_above) {
        return s;
    }
    s.max(torus_bound(da, db, pos_ab))
}

/// Whether the solid-torus bound of the disks ([`torus_bound`]) is sure to stay below
/// `level`: two points on the disks' major circles (alternating closest points, closed
/// form) are closer than `level` plus both tube radii, so the circles' minimum is too.
fn torus_cannot_reach(da: &Disk, db: &Disk, pos_ab: &Isometry3<f64>, level: f64) -> bool {
    if !level.is_finite() {
        return false;
    }
    let (ra, za, sa) = torus_of(da);
    let (rb, zb, sb) = torus_of(db);
    // Closest point of a circle (radius r, height z, about the frame's z axis) to x.
    let on_circle = |x: &Point3<f64>, r: f64, z: f64| {
        let l = norm2(x.x, x.y);
        if l > 0.0 {
            Point3::new(x.x * r / l, x.y * r / l, z)
        } else {
            Point3::new(r, 0.0, z)
        }
    };
    let q = on_circle(
        &pos_ab.inverse_transform_point(&Point3::new(0.0, 0.0, za)),
        rb,
        zb,
    );
    let p = on_circle(&(pos_ab * q), ra, za);
    let q = on_circle(&pos_ab.inverse_transform_point(&p), rb, zb);
    let upper = (p - pos_ab * q).norm();
    upper - sa - sb < level
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::bound::hull_bound::hull_bound;
    use crate::test_rng::Lcg;
    use nalgebra::{Translation3, UnitQuaternion, Vector3};

    /// The circle/circle distance behind the solid-torus bound never exceeds a dense
    /// sampling of the distance (an independent upper estimate), and is within the
    /// sampling's resolution of it, including poses with a centre on the other axis and
    /// parallel or coaxial circles.
    #[test]
    fn circle_distance_is_a_valid_minimum() {
        let mut s = Lcg(3);
        let mut f = move || s.f();
        for i in 0..400 {
            let (ra, za, rb, zb) = (0.1 + f(), f() - 0.5, 0.1 + f(), f() - 0.5);
            let rot = match i % 4 {
                0 => UnitQuaternion::identity(),
                _ => UnitQuaternion::from_scaled_axis(
                    Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 6.0,
                ),
            };
            let t = match i % 3 {
                0 => Vector3::new(0.0, 0.0, f() - 0.5),
                _ => Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 2.0,
            };
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            let mine = circle_circle_distance(ra, za, rb, zb, &pos);
            // Dense sampling of B against the exact point/circle distance to A.
            let n = 20_000;
            let sampled = (0..n)
                .map(|k| {
                    let th = k as f64 * std::f64::consts::TAU / n as f64;
                    let p = pos * Point3::new(rb * th.cos(), rb * th.sin(), zb);
                    point_circle(&p, ra, za)
                })
                .fold(f64::INFINITY, f64::min);
            // Sampling step 3.1e-4 rad: a minimum is missed by at most rb * step.
            let resolution = rb * std::f64::consts::TAU / n as f64;
            assert!(
                mine <= sampled + 1e-12 && mine >= sampled - resolution,
                "case {i}: {mine} vs sampled {sampled}"
            );
        }
    }

    /// Dense sampling of A's revolved piece, each sample measured exactly against B's
    /// revolved piece (planar distance in B's meridian plane): an upper estimate of the
    /// distance, within the sampling's resolution of it.
    fn sampled_distance(a: &ProfileArc, b: &ProfileArc, pos_ab: &Isometry3<f64>) -> f64 {
        sampled_closest(a, b, pos_ab).0
    }

    /// [`sampled_distance`] with its closest pair (A's frame): the sample of A and its exact
    /// closest point on B.
    fn sampled_closest(
        a: &ProfileArc,
        b: &ProfileArc,
        pos_ab: &Isometry3<f64>,
    ) -> (f64, Point3<f64>, Point3<f64>) {
        let n = 300;
        let pos_ba = pos_ab.inverse();
        let b = crate::bvh::patch::Patch { arc: *b };
        let mut best = (f64::INFINITY, Point3::origin(), Point3::origin());
        for i in 0..=n {
            let m = a.point_at(i as f64 / n as f64);
            for k in 0..n {
                let th = k as f64 * std::f64::consts::TAU / n as f64;
                let p = Point3::new(m.x * th.cos(), m.x * th.sin(), m.y);
                let (d, q) = b.point_distance(&(pos_ba * p));
                if d < best.0 {
                    best = (d, p, pos_ab * q);
                }
            }
        }
        best
    }

    /// The hull bound never exceeds the sampled distance (an upper estimate of the true
    /// distance) for any direction: random arcs (up to and beyond a half turn) and
    /// segments in random poses, with random directions and with the direction of the
    /// sampled closest pair. With the latter it is not vacuous: for short pieces it comes
    /// within a fraction of the sampled distance in most separated cases.
    #[test]
    fn hull_bound_is_valid_for_every_direction() {
        let mut s = Lcg(23);
        let mut f = move || s.f();
        let (mut separated, mut tight) = (0, 0);
        for case in 0..300 {
            let piece = |f: &mut dyn FnMut() -> f64, k: usize| -> ProfileArc {
                if k.is_multiple_of(3) {
                    ProfileArc::Segment {
                        start: nalgebra::Point2::new(0.05 + f(), f() - 0.5),
                        end: nalgebra::Point2::new(0.05 + f(), f() - 0.5),
                    }
                } else {
                    ProfileArc::Arc {
                        center: nalgebra::Point2::new(0.6 + f(), f() - 0.5),
                        radius: 0.1 + 0.4 * f(),
                        phi_start: 6.0 * f(),
                        sweep: (4.0 * f() - 2.0) * if k % 3 == 1 { 0.3 } else { 1.0 },
                    }
                }
            };
            let (a, b) = (piece(&mut f, case), piece(&mut f, case / 3));
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(f(), f(), f()) * 3.0);
            let t = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 4.0;
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            let (sampled, pa, pb) = sampled_closest(&a, &b, &pos);
            for _ in 0..4 {
                let dir = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5);
                let h = hull_bound(&a, &b, &pos, &dir);
                assert!(
                    h <= sampled + 1e-12,
                    "case {case}: hull {h} > sampled {sampled}"
                );
            }
            // The direction from A's sampled closest point to B's.
            let h = hull_bound(&a, &b, &pos, &(pb - pa));
            assert!(
                h <= sampled + 1e-12,
                "case {case}: hull {h} > sampled {sampled}"
            );
            if sampled > 0.05 {
                separated += 1;
                if h > 0.5 * sampled {
                    tight += 1;
                }
            }
        }
        assert!(separated > 100, "{separated} separated cases");
        assert!(
            tight * 4 > separated,
            "hull bound tight in {tight} of {separated}"
        );
    }

    /// The shell and slab bounds never exceed the sampled distance, over random arcs
    /// centred on or near the axis (spheres), horizontal and slanted segments and poses;
    /// and they are not vacuous: each separates a good share of the pairs.
    #[test]
    fn shell_and_slab_bounds_are_valid() {
        let mut s = Lcg(17);
        let mut f = move || s.f();
        let (mut shell_hits, mut slab_hits) = (0, 0);
        for case in 0..300 {
            let piece = |f: &mut dyn FnMut() -> f64, kind: usize| match kind {
                0 => ProfileArc::Arc {
                    center: nalgebra::Point2::new(
                        if f() < 0.5 { 0.0 } else { 0.05 * f() },
                        f() - 0.5,
                    ),
                    radius: 0.2 + 0.5 * f(),
                    phi_start: -1.5 + 2.0 * f(),
                    sweep: 0.3 + 1.2 * f(),
                },
                1 => {
                    let (z, x0) = (f() - 0.5, 0.8 * f());
                    ProfileArc::Segment {
                        start: nalgebra::Point2::new(x0, z),
                        end: nalgebra::Point2::new(x0 + 0.1 + 0.6 * f(), z),
                    }
                }
                _ => ProfileArc::Segment {
                    start: nalgebra::Point2::new(0.8 * f(), f() - 0.5),
                    end: nalgebra::Point2::new(0.8 * f(), f() - 0.5),
                },
            };
            let a = piece(&mut f, case % 3);
            let b = piece(&mut f, (case / 3) % 3);
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(f(), f(), f()) * 3.0);
            let t = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 3.0;
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            let sampled = sampled_distance(&a, &b, &pos);
            let shell = shell_bound(&a, &b, &pos);
            let slab = slab_bound(&a, &b, &pos);
            assert!(
                shell <= sampled + 1e-12,
                "case {case}: shell {shell} > {sampled}"
            );
            assert!(
                slab <= sampled + 1e-12,
                "case {case}: slab {slab} > {sampled}"
            );
            shell_hits += usize::from(shell > 0.0);
            slab_hits += usize::from(slab > 0.0);
        }
        assert!(
            shell_hits >= 30 && slab_hits >= 30,
            "shell {shell_hits}, slab {slab_hits}"
        );
    }

    /// Tight cases: a ball resting in a torus's hole touches it along a circle (shell bound
    /// 0 up to slack, a continuum for the circle solvers); a flat annulus above a tilted
    /// cone at a known height gap (slab bound equals the gap).
    #[test]
    fn shell_and_slab_bounds_are_exact_where_claimed() {
        // Torus R 1, r 0.25 (A); ball of radius 0.75 centred on its axis at height 0 (B):
        // the ball touches the tube's inner equator.
        let tube = ProfileArc::Arc {
            center: nalgebra::Point2::new(1.0, 0.0),
            radius: 0.25,
            phi_start: 0.0,
            sweep: std::f64::consts::TAU,
        };
        let ball = ProfileArc::Arc {
            center: nalgebra::Point2::new(0.0, 0.0),
            radius: 0.75,
            phi_start: -std::f64::consts::FRAC_PI_2,
            sweep: std::f64::consts::PI,
        };
        let tilt = UnitQuaternion::from_scaled_axis(Vector3::new(0.7, -0.2, 0.1));
        let pos = Isometry3::from_parts(Translation3::identity(), tilt);
        let b = shell_bound(&tube, &ball, &pos);
        assert!(b <= 0.0 && b > -1e-10, "touching ball: {b}");
        // Lowered by 0.01: the bound is the gap.
        let lifted = ProfileArc::Arc {
            center: nalgebra::Point2::new(0.0, 0.0),
            radius: 0.74,
            phi_start: -std::f64::consts::FRAC_PI_2,
            sweep: std::f64::consts::PI,
        };
        let b = shell_bound(&tube, &lifted, &pos);
        assert!((b - 0.01).abs() < 1e-10, "ball with gap 0.01: {b}");
        // Annulus z = 0, rho in [0.5, 1] (A); a cone patch of B 0.02 above the plane at
        // its lowest point after tilting.
        let annulus = ProfileArc::Segment {
            start: nalgebra::Point2::new(0.5, 0.0),
            end: nalgebra::Point2::new(1.0, 0.0),
        };
        let cone = ProfileArc::Segment {
            start: nalgebra::Point2::new(0.2, 0.0),
            end: nalgebra::Point2::new(0.4, 0.3),
        };
        let rot = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.0, 0.0));
        let (s, c) = 0.3f64.sin_cos();
        // Lowest point of B's parallels: rho sin(0.3) below the tilted centre height.
        let low = (0.0 * c - 0.2 * s).min(0.3 * c - 0.4 * s);
        let pos = Isometry3::from_parts(Translation3::new(0.0, 0.0, 0.02 - low), rot);
        let b = slab_bound(&annulus, &cone, &pos);
        assert!((b - 0.02).abs() < 1e-10, "slab gap 0.02: {b}");
    }
}

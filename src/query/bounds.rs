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
//! module ([`crate::circle::min_distance`]), verified against exact arithmetic.
//!
//! Cheaper, looser bounds: the bounding sphere of `T` (centre `(0, 0, c_z)`, radius
//! `c_rho + s`) gives sphere/sphere and sphere/torus bounds (point-to-circle distance in
//! closed form). [`node_pair_bound`] tries them first and only computes the torus bound when
//! they do not already prune the pair.

use super::binormal_kernel::parallel_circle;
use super::tree::Disk;
use crate::circle::min_distance;
use nalgebra::{Isometry3, Point3};

/// Relative slack (of the configuration scale) subtracted from computed bounds: the circle
/// solver guarantees its minimum distance to `1e-12` of the scale
/// ([`crate::circle::TIE_REL_TOL`], checked against exact arithmetic by `verify circles`),
/// and composing the pose adds a few ulps; `1e-11` covers both with a 10x margin.
pub const BOUND_SLACK: f64 = 1e-11;

/// Which lower bound to use for inner node pairs (measured by `benches/query.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BoundKind {
    /// Bounding spheres only.
    Sphere,
    /// Sphere tests, then the solid-torus bound when the spheres do not prune.
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
    (p.x.hypot(p.y) - r).hypot(p.z - z)
}

/// Sphere/sphere and sphere/torus lower bounds of the revolved disks.
pub fn sphere_bound(da: &Disk, db: &Disk, pos_ab: &Isometry3<f64>) -> f64 {
    let (ra, za, sa) = torus_of(da);
    let (rb, zb, sb) = torus_of(db);
    let ca = Point3::new(0.0, 0.0, za);
    let cb_in_a = pos_ab * Point3::new(0.0, 0.0, zb);
    let ss = (ca - cb_in_a).norm() - (ra + sa) - (rb + sb);
    // Sphere of B against torus of A, and sphere of A against torus of B.
    let st = point_circle(&cb_in_a, ra, za) - sa - (rb + sb);
    let ca_in_b = pos_ab.inverse_transform_point(&ca);
    let ts = point_circle(&ca_in_b, rb, zb) - sb - (ra + sa);
    let scale = 1.0 + ca.coords.norm() + cb_in_a.coords.norm() + ra + rb + sa + sb;
    ss.max(st).max(ts) - BOUND_SLACK * scale
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
    min_distance(&ca, &cb).distance
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
/// show the pair cannot beat the current upper bound.
pub fn node_pair_bound(
    da: &Disk,
    db: &Disk,
    pos_ab: &Isometry3<f64>,
    kind: BoundKind,
    prune_above: f64,
) -> f64 {
    let s = sphere_bound(da, db, pos_ab);
    if kind == BoundKind::Sphere || s >= prune_above {
        return s;
    }
    s.max(torus_bound(da, db, pos_ab))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion, Vector3};

    /// The circle/circle distance behind the solid-torus bound never exceeds a dense
    /// sampling of the distance (an independent upper estimate), and is within the
    /// sampling's resolution of it, including poses with a centre on the other axis and
    /// parallel or coaxial circles.
    #[test]
    fn circle_distance_is_a_valid_minimum() {
        let mut s = 3u64;
        let mut f = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
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
}

//! Surface points of revolved pieces by their parameters, in f64: evaluation, normals, the
//! closest parameter of a piece to a meridian point. The search for near-minimising pairs
//! ([`super::nearest`]) and the pose constructions ([`super::pieces`]) work in these terms;
//! the reference ([`super::exact`]) re-evaluates the same parameters in MPFR.

use nalgebra::{Isometry3, Point2, Point3, Vector2, Vector3};
use revdist::bvh::ProfileArc;
use std::f64::consts::TAU;

/// A point of a revolved chain: piece index, normalised parameter `s` in [0, 1] along the
/// piece, revolution angle `theta`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub piece: usize,
    pub s: f64,
    pub theta: f64,
}

/// The meridian point of `piece` at `s` (the piece's own evaluation formula).
pub fn meridian(piece: &ProfileArc, s: f64) -> Point2<f64> {
    piece.point_at(s)
}

/// The surface point in the chain's frame.
pub fn point(chain: &[ProfileArc], p: &SurfacePoint) -> Point3<f64> {
    let m = meridian(&chain[p.piece], p.s);
    let (sin, cos) = p.theta.sin_cos();
    Point3::new(m.x * cos, m.x * sin, m.y)
}

/// Planar unit normal of a piece at `s` (outward from an arc's centre, left of a segment).
pub fn planar_normal(piece: &ProfileArc, s: f64) -> Vector2<f64> {
    match *piece {
        ProfileArc::Arc {
            phi_start, sweep, ..
        } => {
            let phi = phi_start + s * sweep;
            Vector2::new(phi.cos(), phi.sin())
        }
        ProfileArc::Segment { start, end } => {
            let d = (end - start).normalize();
            Vector2::new(-d.y, d.x)
        }
    }
}

/// The 3-D lift of a planar vector in the meridian plane of `theta`.
pub fn lift_vector(v: Vector2<f64>, theta: f64) -> Vector3<f64> {
    let (sin, cos) = theta.sin_cos();
    Vector3::new(v.x * cos, v.x * sin, v.y)
}

/// The parameter of `piece` closest to the meridian point `m` (`rho >= 0`), with the
/// planar distance: the radial foot when it lies in the arc's range or the segment's
/// parameter range, else the nearer end. Written here, not taken from the core, so that the
/// search does not share the code it tests.
pub fn closest_param(piece: &ProfileArc, m: Point2<f64>) -> (f64, f64) {
    let ends = |p: &ProfileArc| {
        let (d0, d1) = ((m - p.point_at(0.0)).norm(), (m - p.point_at(1.0)).norm());
        if d0 <= d1 {
            (d0, 0.0)
        } else {
            (d1, 1.0)
        }
    };
    match *piece {
        ProfileArc::Arc {
            center,
            radius,
            phi_start,
            sweep,
        } => {
            let d = m - center;
            let n = d.norm();
            let best_end = ends(piece);
            if n == 0.0 || sweep == 0.0 {
                return best_end;
            }
            let phi = d.y.atan2(d.x);
            let off = if sweep > 0.0 {
                (phi - phi_start).rem_euclid(TAU)
            } else {
                (phi_start - phi).rem_euclid(TAU)
            };
            if off <= sweep.abs() {
                let s = (off / sweep.abs()).clamp(0.0, 1.0);
                let foot = ((m - piece.point_at(s)).norm(), s);
                let _ = radius;
                if foot.0 <= best_end.0 {
                    return foot;
                }
            }
            best_end
        }
        ProfileArc::Segment { start, end } => {
            let e = end - start;
            let l2 = e.norm_squared();
            let t = if l2 > 0.0 {
                ((m - start).dot(&e) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            ((m - piece.point_at(t)).norm(), t)
        }
    }
}

/// The point of `chain` nearest to `x` (the chain's frame), exact in the revolution angle
/// (the nearest point of a surface of revolution lies in the meridian half-plane of `x`),
/// with its distance.
pub fn closest_on_chain(chain: &[ProfileArc], x: &Point3<f64>) -> (f64, SurfacePoint) {
    let rho = x.x.hypot(x.y);
    let theta = x.y.atan2(x.x);
    let m = Point2::new(rho, x.z);
    let mut best = (
        f64::INFINITY,
        SurfacePoint {
            piece: 0,
            s: 0.0,
            theta,
        },
    );
    for (k, piece) in chain.iter().enumerate() {
        let (d, s) = closest_param(piece, m);
        if d < best.0 {
            best = (d, SurfacePoint { piece: k, s, theta });
        }
    }
    // Recompute with the chosen point itself: the realised distance, not the planar one.
    let q = point(chain, &best.1);
    ((q - x).norm(), best.1)
}

/// A realised pair of the two chains, `p` on A, `q` on B, with its f64 distance.
#[derive(Debug, Clone, Copy)]
pub struct Pair {
    pub p: SurfacePoint,
    pub q: SurfacePoint,
    pub d: f64,
}

impl Pair {
    /// The pair's f64 distance (B placed by `pos_ab`).
    pub fn new(
        a: &[ProfileArc],
        b: &[ProfileArc],
        pos_ab: &Isometry3<f64>,
        p: SurfacePoint,
        q: SurfacePoint,
    ) -> Pair {
        let d = (point(a, &p) - pos_ab * point(b, &q)).norm();
        Pair { p, q, d }
    }
}

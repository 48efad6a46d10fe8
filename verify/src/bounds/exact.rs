//! The reference distance in MPFR: `|p - q|` for two surface points given by their exact
//! parameters, at [`PREC`] bits.
//!
//! A point of a revolved piece is `(piece, s, theta)`: the meridian point at normalised
//! parameter `s` of the piece as stored (an arc `centre + r (cos phi, sin phi)` with
//! `phi = phi_start + s sweep`, a segment `start + s (end - start)`), lifted to
//! `(rho cos theta, rho sin theta, z)`. Every f64 of the piece, of `s` and `theta`, and of the
//! pose (quaternion and translation) is taken as the exact binary number it is; the pose's
//! rotation is that of the quaternion divided by its norm (the f64 quaternion is unit to
//! about 1e-16, so this moves B's points by ~1e-16 of their size, far below the bounds' own
//! rounding slack). With `s` in [0, 1] the point lies on the exact piece, so `|p - q|` is a
//! distance actually realised by the two surfaces: the true minimum can only be smaller.

use super::chain::SurfacePoint;
use nalgebra::Isometry3;
use revdist::bvh::ProfileArc;
use rug::Float;

/// Bits of every MPFR number (the brief asks for at least 200).
pub const PREC: u32 = 256;

pub(super) fn f(x: f64) -> Float {
    Float::with_val(PREC, x)
}

/// A point of 3-space in MPFR.
pub(super) type P3 = [Float; 3];

/// The exact surface point `(piece, s, theta)` in its own frame.
fn surface_point(piece: &ProfileArc, s: f64, theta: f64) -> P3 {
    let (rho, z) = match *piece {
        ProfileArc::Arc {
            center,
            radius,
            phi_start,
            sweep,
        } => {
            let phi = f(phi_start) + f(s) * f(sweep);
            let (sin, cos) = phi.sin_cos(f(0.0));
            (f(center.x) + f(radius) * cos, f(center.y) + f(radius) * sin)
        }
        ProfileArc::Segment { start, end } => {
            let t = f(s);
            (
                f(start.x) + Float::with_val(PREC, &t * (f(end.x) - f(start.x))),
                f(start.y) + t * (f(end.y) - f(start.y)),
            )
        }
    };
    let (sin, cos) = f(theta).sin_cos(f(0.0));
    [
        Float::with_val(PREC, &rho * &cos),
        Float::with_val(PREC, &rho * &sin),
        z,
    ]
}

/// `pose * x` with the pose's quaternion normalised in MPFR.
pub(super) fn transformed(pose: &Isometry3<f64>, x: &P3) -> P3 {
    let q = pose.rotation.quaternion();
    let (w, i, j, k) = (f(q.w), f(q.i), f(q.j), f(q.k));
    let n2 = Float::with_val(
        PREC,
        w.clone().square() + i.clone().square() + j.clone().square() + k.clone().square(),
    );
    // Rotation matrix of (w, i, j, k) / |q|: entries are quadratic in q, divided by |q|^2.
    let m = |a: &Float, b: &Float| Float::with_val(PREC, a * b) / &n2;
    let (ww, ii, jj, kk) = (m(&w, &w), m(&i, &i), m(&j, &j), m(&k, &k));
    let (ij, ik, jk) = (m(&i, &j), m(&i, &k), m(&j, &k));
    let (wi, wj, wk) = (m(&w, &i), m(&w, &j), m(&w, &k));
    let two = |x: Float| x * 2u32;
    let r = [
        [
            Float::with_val(PREC, &ww + &ii) - &jj - &kk,
            two(Float::with_val(PREC, &ij - &wk)),
            two(Float::with_val(PREC, &ik + &wj)),
        ],
        [
            two(Float::with_val(PREC, &ij + &wk)),
            Float::with_val(PREC, &ww - &ii) + &jj - &kk,
            two(Float::with_val(PREC, &jk - &wi)),
        ],
        [
            two(Float::with_val(PREC, &ik - &wj)),
            two(Float::with_val(PREC, &jk + &wi)),
            Float::with_val(PREC, &ww - &ii) - &jj + &kk,
        ],
    ];
    let t = pose.translation.vector;
    std::array::from_fn(|row| {
        let mut acc = f(t[row]);
        for (col, x) in x.iter().enumerate() {
            acc += Float::with_val(PREC, &r[row][col] * x);
        }
        acc
    })
}

/// `|p - pose_ab * q|` in MPFR, rounded up to f64: `p` a point of A's surface (A's frame),
/// `q` a point of B's surface (B's frame). Rounding up keeps `bound <= distance` a sound test
/// (a bound is never excused by rounding of the reference).
pub fn pair_distance(
    a: &[ProfileArc],
    b: &[ProfileArc],
    pos_ab: &Isometry3<f64>,
    p: &SurfacePoint,
    q: &SurfacePoint,
) -> f64 {
    let x = surface_point(&a[p.piece], p.s, p.theta);
    let y = transformed(pos_ab, &surface_point(&b[q.piece], q.s, q.theta));
    let mut d2 = f(0.0);
    for k in 0..3 {
        let diff = Float::with_val(PREC, &x[k] - &y[k]);
        d2 += diff.square();
    }
    d2.sqrt().to_f64_round(rug::float::Round::Up)
}

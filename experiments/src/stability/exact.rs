//! Exact arithmetic of the solid level's closed forms: `f64` data as rationals, rigid
//! motions with exact data, and the ball-torus gap in MPFR.

use nalgebra::Isometry3;
use rug::{Float, Rational};
use verify::exact_circle::{rotation_from_rational_quaternion, RVec, PREC};

pub(super) fn exact(x: f64) -> Rational {
    Rational::from_f64(x).expect("finite f64")
}

pub(super) fn float(x: &Rational) -> Float {
    Float::with_val(PREC, x)
}

/// A rigid motion with exact data: the rotation of the stored quaternion normalised
/// exactly, and the stored translation.
pub(super) struct ExactPose {
    pub(super) rot: [RVec; 3],
    pub(super) t: RVec,
}

impl ExactPose {
    pub(super) fn of(p: &Isometry3<f64>) -> ExactPose {
        let q = p.rotation.quaternion();
        let rot = rotation_from_rational_quaternion(&[q.w, q.i, q.j, q.k].map(exact));
        let v = p.translation.vector;
        ExactPose {
            rot,
            t: [v.x, v.y, v.z].map(exact),
        }
    }

    /// Image of a local point, exact.
    pub(super) fn place(&self, local: [f64; 3]) -> RVec {
        let x = local.map(exact);
        let mut out = self.t.clone();
        for (k, o) in out.iter_mut().enumerate() {
            for (j, xj) in x.iter().enumerate() {
                *o += Rational::from(&self.rot[j][k] * xj);
            }
        }
        out
    }
}

/// `sqrt(x^2 + y^2)` in MPFR.
pub(super) fn hypot(x: &Float, y: &Float) -> Float {
    Float::with_val(PREC, x * x + y * y).sqrt()
}

/// Distance from a ball (centre `p`, radius `rs`) to the solid torus whose tube circle has
/// radius `big_r` at height `zc` on the z axis, tube radius `r`: the distance from `p` to the
/// solid torus is `dist(p, tube circle) - r` when positive, and
/// `dist(p, circle)^2 = (rho - big_r)^2 + (z - zc)^2`, `rho` the distance to the axis
/// (the nearest point of a circle lies in p's meridian half-plane); a ball subtracts its
/// radius.
pub(super) fn ball_torus_gap(p: &RVec, rs: f64, big_r: f64, zc: f64, r: f64) -> Float {
    let rho = hypot(&float(&p[0]), &float(&p[1]));
    let d_circle = hypot(
        &(rho - float(&exact(big_r))),
        &(float(&p[2]) - float(&exact(zc))),
    );
    d_circle - float(&exact(r)) - float(&exact(rs))
}

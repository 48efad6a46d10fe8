//! The degree-8 binormal polynomial of two circles in half-angle form (equivalent to paper
//! Appendix A; `docs/numerics.md` section 1b).
//!
//! Circle A: radius ra at the origin, normal +z. Circle B(theta) = C + rb (cos theta U +
//! sin theta V). With q the projection of B(theta) into A's plane and rho = |q|, a binormal
//! needs A = +-ra q / rho and `rho (C . w') = +-ra (q . w'_xy)` with w' = -sin U + cos V.
//! Squaring gives `P = |q|^2 (C . w')^2 - ra^2 (q . w'_xy)^2 = 0`, a trigonometric
//! polynomial of degree 4. On the half circle theta = theta0 + 2 atan(2s - 1), s in [0, 1],
//! cos and sin become quadratics over a common quadratic denominator, so P is a degree-8
//! polynomial in s, built here directly in Bernstein form (no power-basis conversion).
//! The near branch (`-`) is the derivative of the squared point-to-circle distance; the
//! squared form keeps the far branch too, so all binormals are roots.

use super::frame::LocalPair;
use crate::poly::solve::BINOM;

/// Bernstein coefficient count of the binormal polynomial.
pub const N_COEFFS: usize = 9;

/// Coefficient noise factor: P's coefficients are sums of products of O(1) terms (after the
/// frame is scaled to unit size); each carries a few ulps of the largest term, and the final
/// subtraction cancels. 64 eps of the largest term bounds the accumulated rounding with margin.
pub const COEFF_NOISE_FACTOR: f64 = 64.0 * f64::EPSILON;

/// Bernstein product of degrees M-1 and N-1 into degree M+N-2.
#[inline]
fn bmul<const M: usize, const N: usize, const R: usize>(a: &[f64; M], b: &[f64; N]) -> [f64; R] {
    let (m, n) = (M - 1, N - 1);
    let mut out = [0.0; R];
    for i in 0..M {
        let wa = BINOM[m][i] * a[i];
        for j in 0..N {
            out[i + j] += wa * BINOM[n][j] * b[j];
        }
    }
    for (k, o) in out.iter_mut().enumerate() {
        *o /= BINOM[m + n][k];
    }
    out
}

/// The polynomial on one half circle, with its absolute coefficient noise.
#[derive(Debug, Clone, Copy)]
pub struct HalfPoly {
    pub coeffs: [f64; N_COEFFS],
    pub noise: f64,
    /// Largest coefficient magnitude of the two squared terms before cancellation.
    pub term_scale: f64,
}

impl HalfPoly {
    /// All coefficients within noise: every theta of this half is a binormal parameter.
    pub fn is_zero(&self) -> bool {
        self.coeffs.iter().all(|c| c.abs() <= self.noise)
    }
}

/// Builds P on the half circle theta in [theta0 - pi/2, theta0 + pi/2] with theta0 = 0
/// (`flip = false`) or pi (`flip = true`): s = (tan((theta - theta0)/2) + 1) / 2.
pub(crate) fn half_poly(lp: &LocalPair, flip: bool) -> HalfPoly {
    let sg = if flip { -1.0 } else { 1.0 };
    let (u, v, c, rb) = (lp.u * sg, lp.v * sg, lp.c, lp.rb);
    // Homogeneous B(theta) * denominator: control points of the rational quadratic half circle
    // (weights 1, 0, 1): C - rb V, rb U, C + rb V.
    let q0 = c - rb * v;
    let q1 = rb * u;
    let q2 = c + rb * v;
    let qx = [q0.x, q1.x, q2.x];
    let qy = [q0.y, q1.y, q2.y];
    // w' * denominator: U, V, -U.
    let wx = [u.x, v.x, -u.x];
    let wy = [u.y, v.y, -u.y];
    let e = [c.dot(&u), c.dot(&v), -c.dot(&u)];
    let rho_sq: [f64; 5] = {
        let a: [f64; 5] = bmul(&qx, &qx);
        let b: [f64; 5] = bmul(&qy, &qy);
        std::array::from_fn(|k| a[k] + b[k])
    };
    let g: [f64; 5] = {
        let a: [f64; 5] = bmul(&qx, &wx);
        let b: [f64; 5] = bmul(&qy, &wy);
        std::array::from_fn(|k| a[k] + b[k])
    };
    let e_sq: [f64; 5] = bmul(&e, &e);
    let lhs: [f64; 9] = bmul(&rho_sq, &e_sq);
    let g_sq: [f64; 9] = bmul(&g, &g);
    let ra_sq = lp.ra * lp.ra;
    let mut coeffs = [0.0; 9];
    let mut term_scale = 0.0f64;
    for k in 0..9 {
        let r = ra_sq * g_sq[k];
        coeffs[k] = lhs[k] - r;
        term_scale = term_scale.max(lhs[k].abs() + r.abs());
    }
    HalfPoly {
        coeffs,
        noise: COEFF_NOISE_FACTOR * term_scale,
        term_scale,
    }
}

/// theta for parameter s on the half circle.
#[inline]
pub fn theta_of(s: f64, flip: bool) -> f64 {
    let t = 2.0 * (2.0 * s - 1.0).atan();
    if flip {
        t + std::f64::consts::PI
    } else {
        t
    }
}

/// s for an angle offset alpha = theta - theta0 in [-pi/2, pi/2].
#[inline]
pub fn s_of(alpha: f64) -> f64 {
    (0.5 * alpha).tan().mul_add(0.5, 0.5)
}

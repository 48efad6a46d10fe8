//! The exact pair's geometry: the swapped pair, the binormal polynomial `P(u)`, the
//! distance and binormal length at a root, and the coaxial distance.

use super::poly::{padd, pmul, pscale, psub, RPoly};
use super::{ExactPair, RVec, PREC};
use rug::{Float, Rational};
use std::cmp::Ordering;

impl ExactPair {
    /// The same pair with the roles of A and B exchanged (A expressed in B's frame; all
    /// data stay exact because B's axes are rational and orthonormal).
    pub fn swapped(&self) -> ExactPair {
        let n = [
            Rational::from(&self.u[1] * &self.v[2]) - Rational::from(&self.u[2] * &self.v[1]),
            Rational::from(&self.u[2] * &self.v[0]) - Rational::from(&self.u[0] * &self.v[2]),
            Rational::from(&self.u[0] * &self.v[1]) - Rational::from(&self.u[1] * &self.v[0]),
        ];
        let dot = |a: &RVec, b: &RVec| {
            let mut s = Rational::new();
            for k in 0..3 {
                s += Rational::from(&a[k] * &b[k]);
            }
            s
        };
        let neg_c = [0, 1, 2].map(|k| Rational::from(-&self.c[k]));
        let e = |k: usize| {
            let mut x = [Rational::new(), Rational::new(), Rational::new()];
            x[k] = Rational::from(1);
            x
        };
        let local = |x: &RVec| [dot(x, &self.u), dot(x, &self.v), dot(x, &n)];
        ExactPair {
            ra: self.rb.clone(),
            c: local(&neg_c),
            u: local(&e(0)),
            v: local(&e(1)),
            rb: self.ra.clone(),
        }
    }

    /// P(u) for theta = 2 atan(u), power basis, degree <= 8.
    pub fn binormal_poly(&self) -> RPoly {
        let one = Rational::from(1);
        let c_t: RPoly = vec![one.clone(), Rational::new(), Rational::from(-1)]; // 1 - u^2
        let s_t: RPoly = vec![Rational::new(), Rational::from(2)]; // 2u
        let d_t: RPoly = vec![one.clone(), Rational::new(), one]; // 1 + u^2
        let comp = |k: usize, x: &RVec| x[k].clone();
        let qk = |k: usize| {
            padd(
                &pscale(&d_t, &self.c[k]),
                &padd(
                    &pscale(&c_t, &Rational::from(&self.rb * &self.u[k])),
                    &pscale(&s_t, &Rational::from(&self.rb * &self.v[k])),
                ),
            )
        };
        let wk = |k: usize| {
            padd(
                &pscale(&s_t, &(-comp(k, &self.u))),
                &pscale(&c_t, &comp(k, &self.v)),
            )
        };
        let (qx, qy) = (qk(0), qk(1));
        let e = padd(
            &padd(&pscale(&wk(0), &self.c[0]), &pscale(&wk(1), &self.c[1])),
            &pscale(&wk(2), &self.c[2]),
        );
        let rho_sq = padd(&pmul(&qx, &qx), &pmul(&qy, &qy));
        let g = padd(&pmul(&qx, &wk(0)), &pmul(&qy, &wk(1)));
        let ra_sq = Rational::from(&self.ra * &self.ra);
        let mut p = psub(
            &pmul(&rho_sq, &pmul(&e, &e)),
            &pscale(&pmul(&g, &g), &ra_sq),
        );
        p.resize(9, Rational::new());
        p
    }

    /// True when B(theta) lies on A's axis (P vanishes there whatever the tangents) and no
    /// point of A satisfies the remaining binormal condition (A(phi) - B) . B' = 0, i.e.
    /// |z B'_z| > ra |B'_xy|: such a root of P is no binormal. On the axis every point of A
    /// is equidistant, so (A - B) . A' = 0 holds for all phi.
    pub(super) fn spurious_axis_root(&self, cos: &Float, sin: &Float) -> bool {
        let comp = |k: usize| {
            let mut x = Float::with_val(PREC, &self.c[k]);
            x += Float::with_val(PREC, &Rational::from(&self.rb * &self.u[k])) * cos;
            x += Float::with_val(PREC, &Rational::from(&self.rb * &self.v[k])) * sin;
            x
        };
        let tangent = |k: usize| {
            let mut x = Float::with_val(PREC, &Rational::from(&self.rb * &self.v[k])) * cos;
            x -= Float::with_val(PREC, &Rational::from(&self.rb * &self.u[k])) * sin;
            x
        };
        let rho = Float::with_val(PREC, comp(0).square() + comp(1).square()).sqrt();
        // A root of P at 256 bits: rho is either ~2^-200 (a true zero, the root being
        // refined to 2^-240) or of the order of the data.
        if rho > Float::with_val(PREC, 1e-50) {
            return false;
        }
        let lhs = Float::with_val(PREC, comp(2) * tangent(2)).abs();
        let bxy = Float::with_val(PREC, tangent(0).square() + tangent(1).square()).sqrt();
        lhs > Float::with_val(PREC, &self.ra) * bxy
    }

    /// Length of the binormal at a root theta of P (off A's axis): the foot on A is the near
    /// or the far point, whichever makes (B - K) . B' vanish.
    pub(super) fn binormal_length(&self, cos: &Float, sin: &Float) -> f64 {
        let q: Vec<Float> = (0..3)
            .map(|k| {
                let mut x = Float::with_val(PREC, &self.c[k]);
                x += Float::with_val(PREC, &Rational::from(&self.rb * &self.u[k])) * cos;
                x += Float::with_val(PREC, &Rational::from(&self.rb * &self.v[k])) * sin;
                x
            })
            .collect();
        let dq: Vec<Float> = (0..3)
            .map(|k| {
                let mut x = Float::with_val(PREC, &Rational::from(&self.rb * &self.v[k])) * cos;
                x -= Float::with_val(PREC, &Rational::from(&self.rb * &self.u[k])) * sin;
                x
            })
            .collect();
        let rho = Float::with_val(PREC, q[0].clone().square() + q[1].clone().square()).sqrt();
        let ra = Float::with_val(PREC, &self.ra);
        let mut best = (f64::INFINITY, f64::NAN);
        for sign in [1i32, -1] {
            let k = Float::with_val(PREC, &ra * sign) / &rho;
            let d: Vec<Float> = vec![
                Float::with_val(PREC, &q[0] - Float::with_val(PREC, &k * &q[0])),
                Float::with_val(PREC, &q[1] - Float::with_val(PREC, &k * &q[1])),
                q[2].clone(),
            ];
            let mut res = Float::with_val(PREC, 0);
            let mut len = Float::with_val(PREC, 0);
            for j in 0..3 {
                res += Float::with_val(PREC, &d[j] * &dq[j]);
                len += Float::with_val(PREC, d[j].clone().square());
            }
            let r = res.abs().to_f64();
            if r < best.0 {
                best = (r, len.sqrt().to_f64());
            }
        }
        best.1
    }

    /// Distance from B(theta) to circle A at precision PREC, theta given by (cos, sin).
    pub(super) fn dist_at(&self, cos: &Float, sin: &Float) -> Float {
        let comp = |k: usize| {
            let mut x = Float::with_val(PREC, &self.c[k]);
            let ru = Float::with_val(PREC, &Rational::from(&self.rb * &self.u[k]));
            let rv = Float::with_val(PREC, &Rational::from(&self.rb * &self.v[k]));
            x += ru * cos;
            x += rv * sin;
            x
        };
        let (x, y, z) = (comp(0), comp(1), comp(2));
        let rho = (x.square() + y.square()).sqrt();
        let dr = rho - Float::with_val(PREC, &self.ra);
        (dr.square() + z.square()).sqrt()
    }

    /// Coaxial pair (B's normal along z, centre on the z axis): the distance is constant,
    /// sqrt(h^2 + (ra - rb)^2). `None` when the pair is not coaxial.
    pub fn coaxial_distance(&self) -> Option<Float> {
        let zero = |x: &Rational| x.cmp0() == Ordering::Equal;
        if !(zero(&self.u[2]) && zero(&self.v[2]) && zero(&self.c[0]) && zero(&self.c[1])) {
            return None;
        }
        let h = Float::with_val(PREC, &self.c[2]);
        let dr = Float::with_val(PREC, &Rational::from(&self.ra - &self.rb));
        Some((h.square() + dr.square()).sqrt())
    }
}

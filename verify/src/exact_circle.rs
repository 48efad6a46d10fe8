//! Exact reference for circle/circle binormals and minimum distance.
//!
//! Circle A is the canonical circle (centre 0, normal +z, radius `ra`); circle B has a
//! rational centre, a rational rotation (from an integer quaternion, so its axes are exact
//! rationals) and a rational radius. The half-angle binormal polynomial
//! `P(u) = |q|^2 (C . w')^2 - ra^2 (q . w'_xy)^2` (u = tan(theta/2), the same formulation as
//! `revdist::circle::poly8`, but over all of R in exact rationals) is built with `rug`;
//! a Sturm sequence counts its distinct real roots (theta = pi is the root at infinity,
//! detected by a vanishing leading coefficient); the roots of its square-free part are
//! isolated with Sturm counts and refined in MPFR, and the minimum distance is the least
//! point-to-circle distance over them, accurate far beyond 1e-30.

use rug::ops::Pow;
use rug::{Float, Rational};
use std::cmp::Ordering;

/// MPFR working precision (bits) for root refinement and distances: 1e-30 needs ~100 bits;
/// 256 leave ample room for cancellation in the distance formula.
pub const PREC: u32 = 256;

/// Rational 3-vector.
pub type RVec = [Rational; 3];

/// A circle pair with exact data, A canonical.
#[derive(Debug, Clone)]
pub struct ExactPair {
    pub ra: Rational,
    pub c: RVec,
    pub u: RVec,
    pub v: RVec,
    pub rb: Rational,
}

/// Rotation matrix columns (as rows of the result) from an integer quaternion (w, x, y, z):
/// exact rationals with denominator w^2 + x^2 + y^2 + z^2.
pub fn rotation_from_quaternion(q: [i64; 4]) -> [RVec; 3] {
    rotation_from_rational_quaternion(&q.map(Rational::from))
}

/// Rotation matrix columns (as rows of the result) from a non-zero rational quaternion
/// (w, x, y, z), exact: the rotation of q / |q|, entries divided by |q|^2. Rational
/// quaternions reach rotations of any small angle, e.g. (2 / delta, 1, 0, 0) turns by about
/// `delta` about x.
pub fn rotation_from_rational_quaternion(q: &[Rational; 4]) -> [RVec; 3] {
    let [w, x, y, z] = q;
    let m = |a: &Rational, b: &Rational| Rational::from(a * b);
    let (ww, xx, yy, zz) = (m(w, w), m(x, x), m(y, y), m(z, z));
    let n = Rational::from(&ww + &xx) + &yy + &zz;
    let e = |num: Rational| num / &n;
    let two = |a: Rational, b: Rational| (a + b) * 2u32;
    let (r00, r11, r22) = (
        e(Rational::from(&ww + &xx) - &yy - &zz),
        e(Rational::from(&ww - &xx) + &yy - &zz),
        e(Rational::from(&ww - &xx) - &yy + &zz),
    );
    let (r01, r10) = (e(two(m(x, y), -m(w, z))), e(two(m(x, y), m(w, z))));
    let (r02, r20) = (e(two(m(x, z), m(w, y))), e(two(m(x, z), -m(w, y))));
    let (r12, r21) = (e(two(m(y, z), -m(w, x))), e(two(m(y, z), m(w, x))));
    // Columns: images of e_x, e_y, e_z.
    [[r00, r10, r20], [r01, r11, r21], [r02, r12, r22]]
}

/// Polynomial in power basis with rational coefficients (index = power).
pub type RPoly = Vec<Rational>;

fn trim(mut p: RPoly) -> RPoly {
    while p.len() > 1 && p.last().is_some_and(|c| c.cmp0() == Ordering::Equal) {
        p.pop();
    }
    p
}

fn padd(a: &RPoly, b: &RPoly) -> RPoly {
    let n = a.len().max(b.len());
    (0..n)
        .map(|i| {
            let mut s = Rational::new();
            if i < a.len() {
                s += &a[i];
            }
            if i < b.len() {
                s += &b[i];
            }
            s
        })
        .collect()
}

fn pscale(a: &RPoly, k: &Rational) -> RPoly {
    a.iter().map(|c| Rational::from(c * k)).collect()
}

fn pmul(a: &RPoly, b: &RPoly) -> RPoly {
    let mut out = vec![Rational::new(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += Rational::from(x * y);
        }
    }
    out
}

fn psub(a: &RPoly, b: &RPoly) -> RPoly {
    padd(a, &pscale(b, &Rational::from(-1)))
}

fn deg(p: &RPoly) -> usize {
    trim(p.clone()).len() - 1
}

fn is_zero(p: &RPoly) -> bool {
    p.iter().all(|c| c.cmp0() == Ordering::Equal)
}

/// Remainder of a / b (b non-zero).
fn prem(a: &RPoly, b: &RPoly) -> RPoly {
    let b = trim(b.clone());
    let mut r = trim(a.clone());
    let db = b.len() - 1;
    let lb = b[db].clone();
    while !is_zero(&r) && r.len() > db {
        let dr = r.len() - 1;
        let k = Rational::from(&r[dr] / &lb);
        for i in 0..=db {
            let t = Rational::from(&k * &b[i]);
            r[dr - db + i] -= t;
        }
        r[dr] = Rational::new();
        r = trim(r);
    }
    r
}

/// Quotient of a / b when b divides a exactly.
fn pdiv_exact(a: &RPoly, b: &RPoly) -> RPoly {
    let b = trim(b.clone());
    let mut r = trim(a.clone());
    let db = b.len() - 1;
    if r.len() <= db {
        return vec![Rational::new()];
    }
    let mut q = vec![Rational::new(); r.len() - db];
    while !is_zero(&r) && r.len() > db {
        let dr = r.len() - 1;
        let k = Rational::from(&r[dr] / &b[db]);
        for i in 0..=db {
            let t = Rational::from(&k * &b[i]);
            r[dr - db + i] -= t;
        }
        q[dr - db] = k;
        r[dr] = Rational::new();
        r = trim(r);
    }
    q
}

fn deriv(p: &RPoly) -> RPoly {
    if p.len() <= 1 {
        return vec![Rational::new()];
    }
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| Rational::from(c * i as u32))
        .collect()
}

fn eval_r(p: &RPoly, x: &Rational) -> Rational {
    let mut acc = Rational::new();
    for c in p.iter().rev() {
        acc *= x;
        acc += c;
    }
    acc
}

fn eval_f(p: &[Float], x: &Float) -> Float {
    let mut acc = Float::with_val(PREC, 0);
    for c in p.iter().rev() {
        acc *= x;
        acc += c;
    }
    acc
}

/// The Sturm sequence of p (ends with gcd(p, p') up to a constant).
pub fn sturm(p: &RPoly) -> Vec<RPoly> {
    let mut seq = vec![trim(p.clone()), trim(deriv(p))];
    loop {
        let n = seq.len();
        if is_zero(&seq[n - 1]) {
            seq.pop();
            break;
        }
        if deg(&seq[n - 1]) == 0 {
            break;
        }
        let r = prem(&seq[n - 2], &seq[n - 1]);
        if is_zero(&r) {
            break;
        }
        seq.push(pscale(&r, &Rational::from(-1)));
    }
    seq
}

fn sign_changes(signs: impl Iterator<Item = Ordering>) -> usize {
    let mut last = Ordering::Equal;
    let mut n = 0;
    for s in signs {
        if s != Ordering::Equal {
            if last != Ordering::Equal && s != last {
                n += 1;
            }
            last = s;
        }
    }
    n
}

/// Precision (bits) of the fast sign evaluation of Sturm polynomials; a sign is trusted only
/// when the value exceeds the Horner rounding bound, otherwise it is recomputed exactly.
const SIGN_PREC: u32 = 1024;

/// A Sturm sequence with MPFR copies of its coefficients for fast, certified sign evaluation.
struct SturmSeq {
    exact: Vec<RPoly>,
    approx: Vec<Vec<Float>>,
}

impl SturmSeq {
    fn new(p: &RPoly) -> Self {
        let exact = sturm(p);
        let approx = exact
            .iter()
            .map(|q| q.iter().map(|c| Float::with_val(SIGN_PREC, c)).collect())
            .collect();
        Self { exact, approx }
    }

    /// Sign of polynomial k at x: MPFR Horner with a running bound on the rounding error
    /// (each step adds at most 2 ulps of the magnitude), exact fallback when ambiguous.
    fn sign_at(&self, k: usize, x: &Rational) -> Ordering {
        let xf = Float::with_val(SIGN_PREC, x);
        let xa = Float::with_val(SIGN_PREC, xf.abs_ref());
        let mut acc = Float::with_val(SIGN_PREC, 0);
        let mut mag = Float::with_val(SIGN_PREC, 0);
        for c in self.approx[k].iter().rev() {
            acc *= &xf;
            acc += c;
            mag *= &xa;
            mag += Float::with_val(SIGN_PREC, c.abs_ref());
        }
        let n = self.approx[k].len() as u32 + 2;
        let bound = (mag * (4 * n)) >> (SIGN_PREC as i32 - 2);
        if Float::with_val(SIGN_PREC, acc.abs_ref()) > bound {
            acc.cmp0().unwrap_or(Ordering::Equal)
        } else {
            eval_r(&self.exact[k], x).cmp0()
        }
    }

    fn changes_at(&self, x: &Rational) -> usize {
        sign_changes((0..self.exact.len()).map(|k| self.sign_at(k, x)))
    }
}

fn changes_at_inf(seq: &[RPoly], positive: bool) -> usize {
    sign_changes(seq.iter().map(|p| {
        let p = trim(p.clone());
        let lc = p.last().unwrap().cmp0();
        if positive || (p.len() - 1).is_multiple_of(2) {
            lc
        } else {
            lc.reverse()
        }
    }))
}

/// Number of distinct real roots of p (p not identically zero).
pub fn count_real_roots(p: &RPoly) -> usize {
    let seq = sturm(p);
    changes_at_inf(&seq, false) - changes_at_inf(&seq, true)
}

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
    fn spurious_axis_root(&self, cos: &Float, sin: &Float) -> bool {
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
    fn binormal_length(&self, cos: &Float, sin: &Float) -> f64 {
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
    fn dist_at(&self, cos: &Float, sin: &Float) -> Float {
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

    /// Exact analysis: distinct real binormal parameters theta (the root count, including
    /// theta = pi) and the minimum distance over them. `None` when P vanishes identically
    /// (a continuum; use an analytic reference).
    pub fn analyse(&self) -> Option<ExactResult> {
        let p = trim(self.binormal_poly());
        if is_zero(&p) {
            return None;
        }
        let at_infinity = p.len() < 9;
        let seq = sturm(&p);
        let gcd = seq.last().unwrap().clone();
        let sqf = if deg(&gcd) == 0 {
            p.clone()
        } else {
            pdiv_exact(&p, &gcd)
        };
        let finite = count_real_roots(&p);
        let roots = isolate_and_refine(&sqf);
        debug_assert_eq!(roots.len(), finite);
        let mut min = Float::with_val(PREC, f64::INFINITY);
        let one = Float::with_val(PREC, 1);
        let mut thetas: Vec<f64> = roots.iter().map(|u| 2.0 * u.to_f64().atan()).collect();
        if at_infinity {
            thetas.push(std::f64::consts::PI);
        }
        let mut spurious = 0;
        let mut binormals = Vec::new();
        for u in &roots {
            let u2 = Float::with_val(PREC, u * u);
            let den = Float::with_val(PREC, &one + &u2);
            let cos = Float::with_val(PREC, &one - &u2) / &den;
            let sin = Float::with_val(PREC, u * 2u32) / &den;
            let sp = self.spurious_axis_root(&cos, &sin);
            spurious += usize::from(sp);
            if !sp {
                binormals.push((2.0 * u.to_f64().atan(), self.binormal_length(&cos, &sin)));
            }
            let d = self.dist_at(&cos, &sin);
            if d < min {
                min = d;
            }
        }
        if at_infinity {
            let (cos, sin) = (Float::with_val(PREC, -1), Float::with_val(PREC, 0));
            let sp = self.spurious_axis_root(&cos, &sin);
            spurious += usize::from(sp);
            if !sp {
                binormals.push((std::f64::consts::PI, self.binormal_length(&cos, &sin)));
            }
            let d = self.dist_at(&Float::with_val(PREC, -1), &Float::with_val(PREC, 0));
            if d < min {
                min = d;
            }
        }
        Some(ExactResult {
            root_count: finite + usize::from(at_infinity) - spurious,
            spurious_roots: spurious,
            binormals,
            min_distance: min,
            min_root_gap: min_circular_gap(&mut thetas),
        })
    }
}

/// Result of [`ExactPair::analyse`].
#[derive(Debug, Clone)]
pub struct ExactResult {
    /// Distinct real roots theta in [0, 2 pi) that are binormal parameters (spurious roots
    /// excluded).
    pub root_count: usize,
    /// Roots of P where B(theta) is on A's axis without a binormal there.
    pub spurious_roots: usize,
    /// (theta, binormal length) for each non-spurious root (theta = 2 atan(u) in (-pi, pi]).
    pub binormals: Vec<(f64, f64)>,
    /// Minimum distance (PREC bits).
    pub min_distance: Float,
    /// Smallest angular separation of two distinct roots theta (radians, on the circle);
    /// infinity with fewer than two roots.
    pub min_root_gap: f64,
}

/// Smallest separation of the angles in `thetas` around the circle (sorts them).
fn min_circular_gap(thetas: &mut [f64]) -> f64 {
    if thetas.len() < 2 {
        return f64::INFINITY;
    }
    thetas.sort_by(f64::total_cmp);
    let wrap = thetas[0] + std::f64::consts::TAU - thetas[thetas.len() - 1];
    thetas.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::min)
}

/// Roots of a square-free polynomial: Sturm isolation on rational intervals, then MPFR
/// bisection (its simple roots change sign) to 2^-(PREC - 16) relative width.
fn isolate_and_refine(p: &RPoly) -> Vec<Float> {
    let seq = SturmSeq::new(p);
    // Cauchy bound.
    let lc = Rational::from(p.last().unwrap().abs_ref());
    let mut bound = Rational::from(1);
    for c in &p[..p.len() - 1] {
        let r = Rational::from(c.abs_ref()) / &lc;
        if r > bound {
            bound = r;
        }
    }
    bound += 1;
    let mut out = Vec::new();
    let mut stack = vec![(Rational::from(-&bound), bound.clone())];
    let pf: Vec<Float> = p.iter().map(|c| Float::with_val(PREC, c)).collect();
    while let Some((a, b)) = stack.pop() {
        let n = seq.changes_at(&a) - seq.changes_at(&b);
        if n == 0 {
            continue;
        }
        let mid = Rational::from(&a + &b) / 2u32;
        if n == 1 {
            let fa = seq.sign_at(0, &a);
            let fb = seq.sign_at(0, &b);
            if fb == Ordering::Equal {
                out.push(Float::with_val(PREC, &b));
                continue;
            }
            if fa != Ordering::Equal && fa != fb {
                out.push(refine(&pf, &a, &b, fa));
                continue;
            }
        }
        let mut mid = mid;
        let mut k = 3u32;
        while seq.sign_at(0, &mid) == Ordering::Equal {
            // Never split on a root: Sturm counts are on half-open intervals (a, b].
            mid = Rational::from(&b - &a) / k + &a;
            k += 1;
        }
        stack.push((mid.clone(), b));
        stack.push((a, mid));
    }
    out.sort_by(|x, y| x.partial_cmp(y).unwrap());
    out
}

fn refine(pf: &[Float], a: &Rational, b: &Rational, sign_a: Ordering) -> Float {
    let mut lo = Float::with_val(PREC, a);
    let mut hi = Float::with_val(PREC, b);
    let tiny = Float::with_val(PREC, 2).pow(-(PREC as i32 - 16));
    for _ in 0..(PREC + 64) {
        let mid = Float::with_val(PREC, &lo + &hi) / 2u32;
        let width = Float::with_val(PREC, &hi - &lo);
        let scale = Float::with_val(PREC, mid.abs_ref()).max(&Float::with_val(PREC, 1));
        if width <= Float::with_val(PREC, &tiny * &scale) {
            return mid;
        }
        let s = eval_f(pf, &mid).cmp0();
        match s {
            Some(Ordering::Equal) | None => return mid,
            Some(o) if o == sign_a => lo = mid,
            _ => hi = mid,
        }
    }
    Float::with_val(PREC, &lo + &hi) / 2u32
}

//! Owned polynomials in Bernstein form on [0, 1] and their real roots.

use super::solve::{self as kernel, RootKind};

/// A polynomial `p(t) = sum_i b_i C(n, i) t^i (1 - t)^(n - i)` on [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct Bernstein {
    coeffs: Vec<f64>,
}

/// Binomial coefficient as f64 (exact for the degrees used here, n <= 60).
fn binomial(n: usize, k: usize) -> f64 {
    let k = k.min(n - k);
    let mut b = 1.0;
    for i in 0..k {
        b = b * (n - i) as f64 / (i + 1) as f64;
    }
    b.round()
}

impl Bernstein {
    /// A polynomial from its Bernstein coefficients; an empty vector means the zero constant.
    pub fn new(coeffs: Vec<f64>) -> Self {
        if coeffs.is_empty() {
            return Self { coeffs: vec![0.0] };
        }
        Self { coeffs }
    }

    /// Converts `p(t) = sum_i a_i t^i` to Bernstein form on [0, 1]:
    /// `b_k = sum_{i <= k} C(k, i) / C(n, i) a_i`.
    pub fn from_power(power_coeffs: &[f64]) -> Self {
        if power_coeffs.is_empty() {
            return Self::new(vec![0.0]);
        }
        let n = power_coeffs.len() - 1;
        let coeffs = (0..=n)
            .map(|k| {
                (0..=k)
                    .map(|i| binomial(k, i) / binomial(n, i) * power_coeffs[i])
                    .sum()
            })
            .collect();
        Self { coeffs }
    }

    /// Power-basis coefficients `a_i` with `p(t) = sum a_i t^i`.
    pub fn to_power(&self) -> Vec<f64> {
        let n = self.degree();
        (0..=n)
            .map(|i| {
                let s: f64 = (0..=i)
                    .map(|k| {
                        let sign = if (i - k) % 2 == 0 { 1.0 } else { -1.0 };
                        sign * binomial(i, k) * self.coeffs[k]
                    })
                    .sum();
                binomial(n, i) * s
            })
            .collect()
    }

    /// The Bernstein coefficients.
    pub fn coeffs(&self) -> &[f64] {
        &self.coeffs
    }

    /// The degree n (number of coefficients minus one).
    pub fn degree(&self) -> usize {
        self.coeffs.len() - 1
    }

    /// Value at `t` (O(n) Horner form of the Bernstein sum; stable for t in [0, 1]).
    pub fn eval(&self, t: f64) -> f64 {
        kernel::eval(&self.coeffs, t)
    }

    /// Value at `t` by the de Casteljau algorithm (the textbook reference evaluation).
    pub fn eval_de_casteljau(&self, t: f64) -> f64 {
        let mut b = self.coeffs.clone();
        let n = self.degree();
        for k in 1..=n {
            for i in 0..=(n - k) {
                b[i] = (1.0 - t) * b[i] + t * b[i + 1];
            }
        }
        b[0]
    }

    /// The derivative, a polynomial of degree n - 1 (degree 0 stays the zero constant).
    pub fn derivative(&self) -> Bernstein {
        let n = self.degree();
        if n == 0 {
            return Bernstein::new(vec![0.0]);
        }
        let mut out = vec![0.0; n];
        kernel::derivative_into(&self.coeffs, &mut out);
        Bernstein::new(out)
    }

    /// The pieces on [0, t] and [t, 1], each reparametrised to [0, 1] (de Casteljau).
    pub fn subdivide(&self, t: f64) -> (Bernstein, Bernstein) {
        let m = self.coeffs.len();
        let (mut l, mut r) = (vec![0.0; m], vec![0.0; m]);
        kernel::split(&self.coeffs, t, &mut l, &mut r);
        (Bernstein::new(l), Bernstein::new(r))
    }

    /// The same polynomial restricted to [a, b] and reparametrised to [0, 1]
    /// (q(s) = p(a + s (b - a))). Works for any a != b, also outside [0, 1] and with a > b.
    pub fn restrict(&self, a: f64, b: f64) -> Bernstein {
        let mut out = vec![0.0; self.coeffs.len()];
        if a == b {
            // Degenerate interval: the constant p(a).
            let v = self.eval_de_casteljau(a);
            return Bernstein::new(vec![v; self.coeffs.len()]);
        }
        if (0.0..b).contains(&a) && b <= 1.0 {
            kernel::restrict_into(&self.coeffs, a, b, &mut out);
            return Bernstein::new(out);
        }
        if b == 0.0 {
            // q(s) = p(a (1 - s)): the reversal of the restriction to [0, a].
            let mut r = self.restrict(0.0, a).coeffs;
            r.reverse();
            return Bernstein::new(r);
        }
        // De Casteljau is an affine identity, so it extrapolates outside [0, 1] as well.
        let (l, _) = self.subdivide(b);
        let (_, r) = l.subdivide(a / b);
        r
    }

    /// The product polynomial (degree m + n):
    /// `c_k = sum_{i + j = k} C(m, i) C(n, j) / C(m + n, k) a_i b_j`.
    pub fn product(&self, other: &Bernstein) -> Bernstein {
        let (m, n) = (self.degree(), other.degree());
        let mut out = vec![0.0; m + n + 1];
        for (i, &a) in self.coeffs.iter().enumerate() {
            let wi = binomial(m, i);
            for (j, &b) in other.coeffs.iter().enumerate() {
                out[i + j] += wi * binomial(n, j) * a * b;
            }
        }
        for (k, c) in out.iter_mut().enumerate() {
            *c /= binomial(m + n, k);
        }
        Bernstein::new(out)
    }

    /// The same polynomial written with degree n + 1.
    pub fn elevate(&self) -> Bernstein {
        let n = self.degree();
        let mut out = vec![0.0; n + 2];
        out[0] = self.coeffs[0];
        out[n + 1] = self.coeffs[n];
        for (i, o) in out.iter_mut().enumerate().take(n + 1).skip(1) {
            let a = i as f64 / (n + 1) as f64;
            *o = a * self.coeffs[i - 1] + (1.0 - a) * self.coeffs[i];
        }
        Bernstein::new(out)
    }

    /// True when every coefficient is exactly zero.
    pub fn is_zero(&self) -> bool {
        self.coeffs.iter().all(|&c| c == 0.0)
    }

    /// True when every coefficient is at most `abs_tol` in magnitude (so |p| <= abs_tol on
    /// [0, 1], because the Bernstein basis is a partition of unity).
    pub fn is_negligible(&self, abs_tol: f64) -> bool {
        self.coeffs.iter().all(|&c| c.abs() <= abs_tol)
    }

    /// Largest coefficient magnitude (bounds max |p| on [0, 1]).
    pub fn max_abs_coeff(&self) -> f64 {
        self.coeffs.iter().fold(0.0, |m, &c| m.max(c.abs()))
    }
}

/// The real roots of a polynomial on [0, 1], or the statement that it vanishes identically.
#[derive(Debug, Clone, PartialEq)]
pub enum RootSet {
    /// Finitely many roots, sorted.
    Isolated(Vec<f64>),
    /// Every coefficient is within the given noise of zero: every t is a root.
    IdenticallyZero,
}

/// Roots of odd multiplicity (sign changes) in (0, 1), sorted, each to within `t_tol`.
/// Returns nothing for the zero polynomial (it has no sign change); see [`solve`].
pub fn odd_roots(p: &Bernstein, t_tol: f64) -> Vec<f64> {
    let m = p.coeffs.len();
    let mut scratch = vec![0.0; kernel::odd_scratch_len(m)];
    let mut out = Vec::new();
    let noise = kernel::noise_of(&p.coeffs, 0.0);
    kernel::odd_roots_into(&p.coeffs, 0.0, 1.0, t_tol, noise, &mut scratch, &mut |x| {
        out.push(x)
    });
    out
}

/// All distinct real roots in [0, 1], including even multiplicity, sorted, each to within
/// `t_tol`. Values within the evaluation rounding bound of zero count as zero. For the zero
/// polynomial this returns an empty vector: call [`solve`] to tell the two apart.
pub fn roots(p: &Bernstein, t_tol: f64) -> Vec<f64> {
    match solve(p, t_tol, 0.0) {
        RootSet::Isolated(r) => r,
        RootSet::IdenticallyZero => Vec::new(),
    }
}

/// Like [`roots`], with `coeff_noise` the absolute uncertainty of each coefficient; reports
/// [`RootSet::IdenticallyZero`] when all coefficients are within `coeff_noise` of zero.
pub fn solve(p: &Bernstein, t_tol: f64, coeff_noise: f64) -> RootSet {
    if p.is_negligible(coeff_noise) {
        return RootSet::IdenticallyZero;
    }
    let m = p.coeffs.len();
    if m == 1 {
        return RootSet::Isolated(Vec::new());
    }
    let mut scratch = vec![0.0; kernel::roots_scratch_len(m)];
    let mut cand = vec![(0.0, RootKind::Odd); kernel::roots_candidate_len(m)];
    let mut out = Vec::new();
    kernel::roots_into(
        &p.coeffs,
        t_tol,
        coeff_noise,
        &mut scratch,
        &mut cand,
        &mut |x, _| out.push(x),
    );
    RootSet::Isolated(out)
}

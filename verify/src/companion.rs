//! Independent float reference: real roots of a polynomial as the real eigenvalues of its
//! companion matrix, used to triage disagreements between the Bernstein solver and the exact
//! reference. Two dense eigensolvers: faer (the project's dense linear algebra, used by
//! `verify circles`) and nalgebra's Schur decomposition (kept as a second opinion; nalgebra
//! otherwise serves geometry).

use faer::Mat;
use nalgebra::DMatrix;

/// Imaginary parts below this (relative to 1 + |root|) count as real. Double roots split into
/// complex pairs of size ~sqrt(eps) ~ 1e-8 under rounding, so the threshold must exceed that.
pub const IMAG_TOL: f64 = 1e-6;

/// Iteration cap for nalgebra's Schur decomposition (its default is unbounded and can cycle on
/// companion matrices with clustered roots). faer caps its QR iterations internally and
/// reports `NoConvergence` instead.
const MAX_SCHUR_ITER: usize = 10_000;

/// Companion matrix of `sum a_i x^i` (power basis, leading zeros dropped) in column-major
/// order: ones on the subdiagonal, `-a_i / a_deg` in the last column. `None` for degree < 1.
fn companion(power: &[f64]) -> Option<(usize, Vec<f64>)> {
    let mut n = power.len();
    while n > 0 && power[n - 1] == 0.0 {
        n -= 1;
    }
    if n <= 1 {
        return None;
    }
    let deg = n - 1;
    let lead = power[deg];
    let mut m = vec![0.0; deg * deg];
    for i in 1..deg {
        m[(i - 1) * deg + i] = 1.0; // (i, i - 1)
    }
    for (i, a) in power[..deg].iter().enumerate() {
        m[(deg - 1) * deg + i] = -a / lead; // (i, deg - 1)
    }
    Some((deg, m))
}

/// Keeps the (nearly) real eigenvalues, sorted.
fn real_parts(eigenvalues: impl Iterator<Item = (f64, f64)>) -> Vec<f64> {
    let mut out: Vec<f64> = eigenvalues
        .filter(|(re, im)| im.abs() <= IMAG_TOL * (1.0 + re.abs()))
        .map(|(re, _)| re)
        .collect();
    out.sort_by(f64::total_cmp);
    out
}

/// All complex roots of `sum a_i x^i` (power basis) as (re, im) pairs, in faer's order, from
/// faer's real nonsymmetric eigensolver (Hessenberg QR). Empty for degree < 1; `None` when the
/// iteration does not converge.
pub fn complex_roots(power: &[f64]) -> Option<Vec<(f64, f64)>> {
    let Some((deg, m)) = companion(power) else {
        return Some(Vec::new());
    };
    let a = Mat::<f64>::from_fn(deg, deg, |i, j| m[j * deg + i]);
    let ev = a.eigenvalues().ok()?;
    Some(ev.iter().map(|z| (z.re, z.im)).collect())
}

/// Real roots of `sum a_i x^i` (power basis), sorted, from faer's eigenvalues of the companion
/// matrix; leading zeros are dropped. `None` when the eigenvalue iteration does not converge.
pub fn real_roots(power: &[f64]) -> Option<Vec<f64>> {
    Some(real_parts(complex_roots(power)?.into_iter()))
}

/// Newton steps from `x` on `sum a_i x^i` (power basis), each kept only while it lowers
/// `|p|`: polishes an eigenvalue of the companion matrix to the root's f64 conditioning.
pub fn polish_root(power: &[f64], x: f64) -> f64 {
    let eval = |x: f64| {
        power
            .iter()
            .rev()
            .fold((0.0, 0.0), |(p, dp), &a| (p * x + a, dp * x + p))
    };
    let (mut x, (mut p, mut dp)) = (x, eval(x));
    for _ in 0..POLISH_STEPS {
        if dp == 0.0 || !p.is_finite() {
            break;
        }
        let next = x - p / dp;
        let (pn, dpn) = eval(next);
        if pn.is_nan() || pn.abs() >= p.abs() {
            break;
        }
        (x, p, dp) = (next, pn, dpn);
    }
    x
}

/// Newton steps of [`polish_root`]: quadratic convergence from an eigenvalue accurate to a
/// few digits reaches f64 in 4-5 steps; near multiple roots it is linear, and the cap bounds it.
const POLISH_STEPS: usize = 32;

/// As [`real_roots`], with nalgebra's Schur decomposition instead of faer.
pub fn real_roots_nalgebra(power: &[f64]) -> Option<Vec<f64>> {
    let Some((deg, m)) = companion(power) else {
        return Some(Vec::new());
    };
    let m = DMatrix::<f64>::from_column_slice(deg, deg, &m);
    let schur = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, MAX_SCHUR_ITER)?;
    Some(real_parts(
        schur.complex_eigenvalues().iter().map(|z| (z.re, z.im)),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::circles::random_case;
    use crate::exact_circle::count_real_roots;
    use revdist::rng::SplitMix64;
    use rug::Rational;
    use std::cmp::Ordering;

    /// (x - 1)(x + 2)(x - 3)(x^2 + 1)
    const KNOWN: [f64; 6] = [6.0, -5.0, 4.0, -4.0, -2.0, 1.0];
    const KNOWN_ROOTS: [f64; 3] = [-2.0, 1.0, 3.0];

    #[test]
    fn roots_of_known_polynomial() {
        for r in [
            real_roots(&KNOWN).unwrap(),
            real_roots_nalgebra(&KNOWN).unwrap(),
        ] {
            assert_eq!(r.len(), 3, "{r:?}");
            for (a, b) in r.iter().zip(&KNOWN_ROOTS) {
                assert!((a - b).abs() < 1e-10, "{r:?}");
            }
        }
        // The complex pair +-i.
        let z = complex_roots(&KNOWN).unwrap();
        assert_eq!(z.len(), 5);
        assert!(z
            .iter()
            .any(|&(re, im)| re.abs() < 1e-10 && (im - 1.0).abs() < 1e-10));
    }

    #[test]
    fn polishing_recovers_roots_and_never_worsens() {
        for &r in &KNOWN_ROOTS {
            let x = polish_root(&KNOWN, r + 1e-4);
            assert!((x - r).abs() < 1e-13, "{x} vs {r}");
        }
        // A double root (x - 1)^2 (x + 1): linear convergence, still closer than the start.
        let double = [1.0, -1.0, -1.0, 1.0];
        let x = polish_root(&double, 1.01);
        assert!((x - 1.0).abs() < 1e-6, "{x}");
        // Far from any root: |p| does not grow.
        let eval = |x: f64| KNOWN.iter().rev().fold(0.0, |p, &a| p * x + a);
        let x = polish_root(&KNOWN, 0.3);
        assert!(eval(x).abs() <= eval(0.3).abs());
    }

    #[test]
    fn degenerate_inputs() {
        assert_eq!(real_roots(&[]).unwrap(), Vec::<f64>::new());
        assert_eq!(real_roots(&[3.0, 0.0]).unwrap(), Vec::<f64>::new());
        assert_eq!(real_roots(&[-2.0, 1.0, 0.0, 0.0]).unwrap(), vec![2.0]);
    }

    fn eval_exact(p: &[Rational], x: &Rational) -> Rational {
        let mut acc = Rational::new();
        for c in p.iter().rev() {
            acc *= x;
            acc += c;
        }
        acc
    }

    /// Relative half-width of the exact bracket around each float root.
    const BRACKET_REL: f64 = 1e-8;
    /// Roots closer than this (in u = tan(theta/2), relative) are not compared: the brackets
    /// must be disjoint and the float roots resolvable.
    const MIN_SEPARATION_REL: f64 = 1e-4;
    /// faer and nalgebra agree to this (relative), on well-separated simple roots.
    const SOLVER_AGREEMENT_REL: f64 = 1e-9;
    const CASES: u64 = 300;

    /// The degree-8 circle polynomials of random rational circle pairs: faer's real roots agree
    /// with nalgebra's, and each lies within `BRACKET_REL` of an exact root (P changes sign
    /// across the bracket, evaluated in exact rationals), with the exact Sturm count of
    /// distinct real roots equal to the number of faer roots.
    #[test]
    fn faer_matches_nalgebra_and_exact_roots_on_circle_polynomials() {
        let mut rng = SplitMix64(0x5eed_fae5);
        let (mut compared, mut skipped) = (0, 0);
        for _ in 0..CASES {
            let case = random_case(&mut rng);
            let exact_poly = case.exact_pair().binormal_poly();
            let p: Vec<f64> = exact_poly.iter().map(|c| c.to_f64()).collect();
            let (Some(f), Some(n)) = (real_roots(&p), real_roots_nalgebra(&p)) else {
                skipped += 1;
                continue;
            };
            let clustered = f
                .windows(2)
                .any(|w| w[1] - w[0] <= MIN_SEPARATION_REL * (1.0 + w[1].abs()));
            if clustered || f.len() != n.len() {
                skipped += 1;
                continue;
            }
            for (a, b) in f.iter().zip(&n) {
                assert!(
                    (a - b).abs() <= SOLVER_AGREEMENT_REL * (1.0 + a.abs()),
                    "faer {f:?} vs nalgebra {n:?}"
                );
            }
            // Exact: the number of distinct real roots, and a sign change around each root.
            let mut trimmed = exact_poly.clone();
            while trimmed.len() > 1 && trimmed.last().unwrap().cmp0() == Ordering::Equal {
                trimmed.pop();
            }
            assert_eq!(count_real_roots(&trimmed), f.len(), "{f:?}");
            for &r in &f {
                let h = BRACKET_REL * (1.0 + r.abs());
                let lo = Rational::from_f64(r - h).unwrap();
                let hi = Rational::from_f64(r + h).unwrap();
                let (slo, shi) = (eval_exact(&trimmed, &lo), eval_exact(&trimmed, &hi));
                assert!(
                    slo.cmp0() != shi.cmp0() || slo.cmp0() == Ordering::Equal,
                    "no exact root within {h:e} of faer root {r}"
                );
            }
            compared += 1;
        }
        assert!(
            compared >= CASES as usize * 9 / 10,
            "compared {compared}, skipped {skipped}"
        );
    }
}

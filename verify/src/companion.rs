//! Independent float reference: real roots of a polynomial as the real eigenvalues of its
//! companion matrix (nalgebra's Schur decomposition), used to triage disagreements between
//! the Bernstein solver and the exact reference.

use nalgebra::DMatrix;

/// Imaginary parts below this (relative to 1 + |root|) count as real. Double roots split into
/// complex pairs of size ~sqrt(eps) ~ 1e-8 under rounding, so the threshold must exceed that.
pub const IMAG_TOL: f64 = 1e-6;

/// Iteration cap for the Schur decomposition (nalgebra's default is unbounded and can
/// cycle on companion matrices with clustered roots).
const MAX_SCHUR_ITER: usize = 10_000;

/// Real roots of `sum a_i x^i` (power basis), sorted; leading zeros are dropped. `None` when
/// the eigenvalue iteration does not converge.
pub fn real_roots(power: &[f64]) -> Option<Vec<f64>> {
    let mut n = power.len();
    while n > 0 && power[n - 1] == 0.0 {
        n -= 1;
    }
    if n <= 1 {
        return Some(Vec::new());
    }
    let deg = n - 1;
    let lead = power[deg];
    let mut m = DMatrix::<f64>::zeros(deg, deg);
    for i in 1..deg {
        m[(i, i - 1)] = 1.0;
    }
    for i in 0..deg {
        m[(i, deg - 1)] = -power[i] / lead;
    }
    let schur = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, MAX_SCHUR_ITER)?;
    let mut out: Vec<f64> = schur
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() <= IMAG_TOL * (1.0 + z.re.abs()))
        .map(|z| z.re)
        .collect();
    out.sort_by(f64::total_cmp);
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_known_polynomial() {
        // (x - 1)(x + 2)(x - 3)(x^2 + 1)
        let p = [6.0, -5.0, 4.0, -4.0, -2.0, 1.0];
        let r = real_roots(&p).unwrap();
        let expect = [-2.0, 1.0, 3.0];
        assert_eq!(r.len(), 3, "{r:?}");
        for (a, b) in r.iter().zip(&expect) {
            assert!((a - b).abs() < 1e-10);
        }
    }
}

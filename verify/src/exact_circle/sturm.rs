//! Sturm sequences: counts of distinct real roots, with a certified MPFR sign evaluation
//! and an exact fallback.

use super::poly::{deg, deriv, eval_r, is_zero, prem, pscale, trim, RPoly};
use rug::{Float, Rational};
use std::cmp::Ordering;

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
pub(super) struct SturmSeq {
    exact: Vec<RPoly>,
    approx: Vec<Vec<Float>>,
}

impl SturmSeq {
    pub(super) fn new(p: &RPoly) -> Self {
        let exact = sturm(p);
        let approx = exact
            .iter()
            .map(|q| q.iter().map(|c| Float::with_val(SIGN_PREC, c)).collect())
            .collect();
        Self { exact, approx }
    }

    /// Sign of polynomial k at x: MPFR Horner with a running bound on the rounding error
    /// (each step adds at most 2 ulps of the magnitude), exact fallback when ambiguous.
    pub(super) fn sign_at(&self, k: usize, x: &Rational) -> Ordering {
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

    pub(super) fn changes_at(&self, x: &Rational) -> usize {
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

//! Polynomials in power basis with rational coefficients: arithmetic, exact division,
//! derivative and evaluation (exact, or in MPFR at [`PREC`] bits).

use super::PREC;
use rug::{Float, Rational};
use std::cmp::Ordering;

/// Polynomial in power basis with rational coefficients (index = power).
pub type RPoly = Vec<Rational>;

pub(super) fn trim(mut p: RPoly) -> RPoly {
    while p.len() > 1 && p.last().is_some_and(|c| c.cmp0() == Ordering::Equal) {
        p.pop();
    }
    p
}

pub(super) fn padd(a: &RPoly, b: &RPoly) -> RPoly {
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

pub(super) fn pscale(a: &RPoly, k: &Rational) -> RPoly {
    a.iter().map(|c| Rational::from(c * k)).collect()
}

pub(super) fn pmul(a: &RPoly, b: &RPoly) -> RPoly {
    let mut out = vec![Rational::new(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += Rational::from(x * y);
        }
    }
    out
}

pub(super) fn psub(a: &RPoly, b: &RPoly) -> RPoly {
    padd(a, &pscale(b, &Rational::from(-1)))
}

pub(super) fn deg(p: &RPoly) -> usize {
    trim(p.clone()).len() - 1
}

pub(super) fn is_zero(p: &RPoly) -> bool {
    p.iter().all(|c| c.cmp0() == Ordering::Equal)
}

/// Remainder of a / b (b non-zero).
pub(super) fn prem(a: &RPoly, b: &RPoly) -> RPoly {
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
pub(super) fn pdiv_exact(a: &RPoly, b: &RPoly) -> RPoly {
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

pub(super) fn deriv(p: &RPoly) -> RPoly {
    if p.len() <= 1 {
        return vec![Rational::new()];
    }
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| Rational::from(c * i as u32))
        .collect()
}

pub(super) fn eval_r(p: &RPoly, x: &Rational) -> Rational {
    let mut acc = Rational::new();
    for c in p.iter().rev() {
        acc *= x;
        acc += c;
    }
    acc
}

pub(super) fn eval_f(p: &[Float], x: &Float) -> Float {
    let mut acc = Float::with_val(PREC, 0);
    for c in p.iter().rev() {
        acc *= x;
        acc += c;
    }
    acc
}

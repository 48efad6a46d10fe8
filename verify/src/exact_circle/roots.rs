//! The real roots of a square-free polynomial: Sturm isolation on rational intervals, then
//! MPFR bisection.

use super::poly::{eval_f, RPoly};
use super::sturm::SturmSeq;
use super::PREC;
use rug::ops::Pow;
use rug::{Float, Rational};
use std::cmp::Ordering;

/// Roots of a square-free polynomial: Sturm isolation on rational intervals, then MPFR
/// bisection (its simple roots change sign) to 2^-(PREC - 16) relative width.
pub(super) fn isolate_and_refine(p: &RPoly) -> Vec<Float> {
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

//! Small numeric helpers shared by the geometry kernels.

/// `sqrt(x^2 + y^2)`, correctly rounded to within 1.5 ulp, without the cost of libm's
/// `hypot` (a third of a node bound's time went to `hypot`). Squares overflow
/// above 1e154 and underflow below 1e-154; there, and for non-finite input, the sum is
/// out of the range kept here and `hypot` answers instead, so the result is always within
/// 1.5 ulp of the true length. Every bound that uses it subtracts
/// [`crate::tolerances::BOUND_SLACK`] (1e-11 of the scale), far above that rounding.
#[inline]
pub fn norm2(x: f64, y: f64) -> f64 {
    let s = x * x + y * y;
    if s > 1e-290 && s < 1e290 {
        s.sqrt()
    } else {
        x.hypot(y)
    }
}

/// The 2-D cross product `a x b` (the z component of the 3-D one).
#[inline]
pub fn cross2(a: nalgebra::Vector2<f64>, b: nalgebra::Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

#[cfg(test)]
mod tests {
    use super::norm2;
    use crate::test_rng::Lcg;

    /// Agrees with `hypot` to 1.5 ulp over magnitudes from 1e-200 to 1e200, including
    /// zeros, one-sided inputs and the fallback ranges.
    #[test]
    fn matches_hypot() {
        let mut rng = Lcg(0x2545_f491);
        let mut next = move || rng.f();
        for _ in 0..200_000 {
            let ex = (next() * 400.0 - 200.0).round() as i32;
            let ey = ex + (next() * 40.0 - 20.0).round() as i32;
            let x = (next() - 0.5) * 10f64.powi(ex);
            let y = (next() - 0.5) * 10f64.powi(ey);
            let (a, b) = (norm2(x, y), x.hypot(y));
            assert!(
                (a - b).abs() <= 1.5 * f64::EPSILON * b,
                "{x} {y}: {a} vs {b}"
            );
        }
        assert_eq!(norm2(0.0, 0.0), 0.0);
        assert_eq!(norm2(-3.0, 4.0), 5.0);
        assert!(norm2(f64::NAN, 1.0).is_nan());
        assert_eq!(norm2(f64::INFINITY, 1.0), f64::INFINITY);
    }
}

/// A heap entry that [`std::collections::BinaryHeap`] pops smallest `key` first, and among
/// equal keys smallest `tie` first (both ordered by [`f64::total_cmp`]; equality from the
/// same order).
#[derive(Debug, Clone, Copy)]
pub struct SmallestFirst<T> {
    pub key: f64,
    pub tie: f64,
    pub item: T,
}

impl<T> PartialEq for SmallestFirst<T> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == std::cmp::Ordering::Equal
    }
}
impl<T> Eq for SmallestFirst<T> {}
impl<T> PartialOrd for SmallestFirst<T> {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl<T> Ord for SmallestFirst<T> {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other
            .key
            .total_cmp(&self.key)
            .then(other.tie.total_cmp(&self.tie))
    }
}

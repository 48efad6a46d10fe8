//! Exact signs of small polynomial expressions in the coordinates: error-free products
//! (`fma`) and Shewchuk's expansion sums ("Adaptive precision floating-point arithmetic",
//! 1997). The convexity certificate ([`super::convexity`]) decides its left turns with them,
//! so that straight pieces (turns of exactly 0) are accepted and nothing is accepted by
//! rounding. Valid while no product underflows (coordinates of profiles far above 1e-150).

use nalgebra::Point2;
use std::cmp::Ordering;

/// `a + b = s + e` exactly (Knuth's two-sum).
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// `a * b = p + e` exactly.
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// Adds `x` to the non-overlapping expansion `e` (increasing magnitude), exactly
/// (Shewchuk's grow-expansion with zero elimination).
fn grow_expansion(e: &mut Vec<f64>, x: f64) {
    let mut q = x;
    let mut out = Vec::with_capacity(e.len() + 1);
    for &h in e.iter() {
        let (s, err) = two_sum(q, h);
        if err != 0.0 {
            out.push(err);
        }
        q = s;
    }
    if q != 0.0 {
        out.push(q);
    }
    *e = out;
}

/// The exact sign of `sum_i a_i * b_i`.
pub fn sign_of_products(terms: &[(f64, f64)]) -> Ordering {
    let mut expansion: Vec<f64> = Vec::with_capacity(2 * terms.len());
    for &(a, b) in terms {
        let (p, e) = two_product(a, b);
        grow_expansion(&mut expansion, e);
        grow_expansion(&mut expansion, p);
    }
    // The largest component decides the sign of a non-overlapping expansion.
    expansion.last().map_or(Ordering::Equal, |x| {
        x.partial_cmp(&0.0).unwrap_or(Ordering::Equal)
    })
}

/// Exact sign of `cross(b - a, d - c)`.
pub fn cross_sign(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>, d: Point2<f64>) -> Ordering {
    sign_of_products(&[
        (b.x, d.y),
        (-b.x, c.y),
        (-a.x, d.y),
        (a.x, c.y),
        (-b.y, d.x),
        (b.y, c.x),
        (a.y, d.x),
        (-a.y, c.x),
    ])
}

/// Exact sign of `dot(b - a, d - c)`.
pub fn dot_sign(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>, d: Point2<f64>) -> Ordering {
    sign_of_products(&[
        (b.x, d.x),
        (-b.x, c.x),
        (-a.x, d.x),
        (a.x, c.x),
        (b.y, d.y),
        (-b.y, c.y),
        (-a.y, d.y),
        (a.y, c.y),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collinear_points_are_exactly_straight() {
        // 0.1, 0.2, 0.3 are not exact; the points below are collinear in exact arithmetic on
        // their floating-point values, though naive cross products round to non-zero.
        let a = Point2::new(0.6, 0.0);
        let b = Point2::new(0.3, 0.75);
        let c = Point2::new(0.0, 1.5);
        assert_eq!(cross_sign(a, b, b, c), Ordering::Equal);
        assert_eq!(dot_sign(a, b, b, c), Ordering::Greater);
        let p = Point2::new(1e-17, 0.0);
        assert_eq!(
            cross_sign(
                Point2::origin(),
                Point2::new(1.0, 0.0),
                Point2::origin(),
                p + nalgebra::Vector2::new(1.0, 1e-30)
            ),
            Ordering::Greater
        );
        // 0.1 + 0.2 != 0.3: (0,0), (0.1, 0.1), (0.3, 0.3) collinear exactly? 0.1*0.3 vs 0.3*0.1.
        assert_eq!(
            cross_sign(
                Point2::origin(),
                Point2::new(0.1, 0.1),
                Point2::origin(),
                Point2::new(0.3, 0.3)
            ),
            Ordering::Equal
        );
        assert_eq!(
            cross_sign(
                Point2::origin(),
                Point2::new(0.1, 0.2),
                Point2::origin(),
                Point2::new(0.3, 0.6000000000000001)
            ),
            Ordering::Greater
        );
    }
}

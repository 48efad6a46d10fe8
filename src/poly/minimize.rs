//! One-dimensional minimisation shared by the circle, biarc and query code.

/// Golden-section search for the minimum of `f` on `[lo, hi]`, assumed unimodal there.
/// Each iteration reuses one of the two interior values, so `iterations` steps cost
/// `iterations + 2` evaluations and shrink the bracket by `0.618^iterations` (80 steps reach
/// adjacent doubles for brackets of size ~1). Returns the best interior point and its value.
pub fn golden_section_min(
    f: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    iterations: usize,
) -> (f64, f64) {
    const R: f64 = 0.618_033_988_749_894_8;
    let (mut a, mut b) = (lo, hi);
    let mut x1 = b - R * (b - a);
    let mut x2 = a + R * (b - a);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..iterations {
        if f1 <= f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - R * (b - a);
            f1 = f(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + R * (b - a);
            f2 = f(x2);
        }
    }
    if f1 <= f2 {
        (x1, f1)
    } else {
        (x2, f2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_vertex_of_a_parabola() {
        let (x, fx) = golden_section_min(|x| (x - 0.3).powi(2) + 2.0, -1.0, 2.0, 80);
        assert!((x - 0.3).abs() < 1e-7, "{x}");
        assert!((fx - 2.0).abs() < 1e-14);
    }
}

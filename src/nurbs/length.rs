//! Arc length of a NURBS curve by adaptive Gauss-Legendre quadrature of its speed.

use super::NurbsCurve;

impl NurbsCurve {
    /// Arc length to within `tolerance` (absolute), by adaptive Gauss-Legendre quadrature of
    /// the speed over each knot span.
    pub fn arc_length(&self, tolerance: f64) -> f64 {
        let tolerance = tolerance.max(f64::EPSILON);
        let spans = self.distinct_spans();
        let per_span = tolerance / spans.len() as f64;
        spans
            .iter()
            .map(|&(a, b)| self.adaptive_length(a, b, per_span, 0))
            .sum()
    }

    fn gauss_length(&self, a: f64, b: f64) -> f64 {
        let (h, m) = (0.5 * (b - a), 0.5 * (a + b));
        GAUSS_8
            .iter()
            .map(|&(x, w)| w * self.derivatives_up_to(m + h * x, 1)[1].norm())
            .sum::<f64>()
            * h
    }

    /// Adaptive Gauss-Legendre length of `[a, b]`; a non-finite estimate (a speed that
    /// overflows) ends the recursion at once instead of refining to the depth cap.
    fn adaptive_length(&self, a: f64, b: f64, tol: f64, depth: u32) -> f64 {
        let whole = self.gauss_length(a, b);
        let mid = 0.5 * (a + b);
        let halves = self.gauss_length(a, mid) + self.gauss_length(mid, b);
        if !halves.is_finite() || (whole - halves).abs() <= tol || depth >= MAX_LENGTH_DEPTH {
            halves
        } else {
            self.adaptive_length(a, mid, 0.5 * tol, depth + 1)
                + self.adaptive_length(mid, b, 0.5 * tol, depth + 1)
        }
    }
}

/// Eight-point Gauss-Legendre nodes and weights on [-1, 1].
const GAUSS_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

/// Recursion cap of the adaptive arc-length quadrature (2^30 sub-intervals per span).
const MAX_LENGTH_DEPTH: u32 = 30;

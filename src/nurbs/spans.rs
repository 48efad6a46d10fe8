//! A NURBS curve as Bezier spans in homogeneous form (every interior knot raised to the
//! degree), what Bernstein-form root isolation works on, and de Casteljau halving of a span.

use super::NurbsCurve;
use nalgebra::Point2;

/// One Bezier span of a NURBS curve, in homogeneous form.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSpan {
    /// Start of the span's parameter interval in the parent curve.
    pub t0: f64,
    /// End of the span's parameter interval in the parent curve.
    pub t1: f64,
    /// Homogeneous Bernstein control points `(w rho, w z, w)`, `degree + 1` of them; the span is
    /// `sum B_i(s) P_i` with `s = (t - t0) / (t1 - t0)` in [0, 1].
    pub homogeneous: Vec<[f64; 3]>,
}

/// The two halves of a Bezier span at its middle parameter, by de Casteljau's algorithm on
/// its homogeneous control points `(w rho, w z, w)` (each half keeps the degree).
pub fn halve_homogeneous(points: &[[f64; 3]]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let n = points.len();
    let mut work = points.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    left.push(work[0]);
    right.push(work[n - 1]);
    for r in 1..n {
        for i in 0..n - r {
            let next = work[i + 1];
            for (x, y) in work[i].iter_mut().zip(next) {
                *x = 0.5 * (*x + y);
            }
        }
        left.push(work[0]);
        right.push(work[n - 1 - r]);
    }
    right.reverse();
    (left, right)
}

impl BezierSpan {
    /// Point of the span at local parameter `s` in [0, 1] (de Casteljau, homogeneous).
    pub fn eval_local(&self, s: f64) -> Point2<f64> {
        let mut q = self.homogeneous.clone();
        let n = q.len();
        for r in 1..n {
            for i in 0..n - r {
                let next = q[i + 1];
                for (qc, nc) in q[i].iter_mut().zip(next) {
                    *qc = (1.0 - s) * *qc + s * nc;
                }
            }
        }
        Point2::new(q[0][0] / q[0][2], q[0][1] / q[0][2])
    }
}

impl NurbsCurve {
    /// The non-empty knot spans `[k_i, k_{i+1}]` of the domain.
    pub fn distinct_spans(&self) -> Vec<(f64, f64)> {
        let (start, end) = self.domain();
        let mut out = Vec::new();
        for w in self.knots.windows(2) {
            if w[1] > w[0] && w[0] >= start && w[1] <= end {
                out.push((w[0], w[1]));
            }
        }
        out
    }

    /// The curve as Bezier spans (every interior knot raised to multiplicity `degree`), in
    /// homogeneous form: what Bernstein-form root isolation works on.
    pub fn bezier_spans(&self) -> Vec<BezierSpan> {
        let p = self.degree;
        let mut curve = self.clone();
        let interior: Vec<f64> = {
            let (s, e) = self.domain();
            let mut v: Vec<f64> = self
                .knots
                .iter()
                .copied()
                .filter(|&k| k > s && k < e)
                .collect();
            v.dedup();
            v
        };
        for &t in &interior {
            curve = curve.with_knot_multiplicity(t, p);
        }
        let mut bounds = vec![self.domain().0];
        bounds.extend(interior);
        bounds.push(self.domain().1);
        bounds
            .windows(2)
            .enumerate()
            .map(|(i, w)| BezierSpan {
                t0: w[0],
                t1: w[1],
                homogeneous: (i * p..=i * p + p).map(|j| curve.homogeneous(j)).collect(),
            })
            .collect()
    }
}

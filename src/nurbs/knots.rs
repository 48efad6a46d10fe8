//! Knot insertion (Boehm's algorithm): splitting a curve, and reversing it.

use super::{find_span, CurveError, NurbsCurve};
use nalgebra::Point2;

impl NurbsCurve {
    /// Inserts knot `t` until it has multiplicity `degree` (Boehm's algorithm) and splits the
    /// curve there: the two pieces together trace exactly the original curve.
    pub fn split(&self, t: f64) -> Result<(NurbsCurve, NurbsCurve), CurveError> {
        let (start, end) = self.domain();
        if !(t > start && t < end) {
            return Err(CurveError::ParameterOutOfRange { t, start, end });
        }
        let p = self.degree;
        let refined = self.with_knot_multiplicity(t, p);
        let first_after = refined.knots.iter().position(|&k| k > t).unwrap_or(0);
        // The p copies of t sit just before `first_after`; the control point at the split is
        // the last one of the left piece and the first one of the right piece.
        let split_index = first_after - p - 1;
        let mut left_knots: Vec<f64> = refined.knots[..first_after].to_vec();
        left_knots.push(t);
        let mut right_knots = vec![t];
        right_knots.extend_from_slice(&refined.knots[first_after - p..]);
        let left_n = split_index + 1;
        let pts = &refined.points;
        let ws = refined.weights.as_ref();
        let left = NurbsCurve::new(
            p,
            left_knots,
            pts[..left_n].to_vec(),
            ws.map(|w| w[..left_n].to_vec()),
        )?;
        let right = NurbsCurve::new(
            p,
            right_knots,
            pts[split_index..].to_vec(),
            ws.map(|w| w[split_index..].to_vec()),
        )?;
        Ok((left, right))
    }

    /// This curve with knot `t` (inside the domain) raised to multiplicity `target`.
    pub(super) fn with_knot_multiplicity(&self, t: f64, target: usize) -> NurbsCurve {
        let mut curve = self.clone();
        let existing = curve.knots.iter().filter(|&&k| k == t).count();
        for _ in existing..target {
            curve = curve.insert_knot_once(t);
        }
        curve
    }

    /// Boehm knot insertion of `t` once, in homogeneous coordinates.
    fn insert_knot_once(&self, t: f64) -> NurbsCurve {
        let p = self.degree;
        let k = find_span(p, &self.knots, t);
        let n = self.points.len();
        let mut hom: Vec<[f64; 3]> = Vec::with_capacity(n + 1);
        for i in 0..=n {
            if i + p <= k {
                hom.push(self.homogeneous(i));
            } else if i > k {
                hom.push(self.homogeneous(i - 1));
            } else {
                let a = (t - self.knots[i]) / (self.knots[i + p] - self.knots[i]);
                let (q0, q1) = (self.homogeneous(i - 1), self.homogeneous(i));
                hom.push([
                    (1.0 - a) * q0[0] + a * q1[0],
                    (1.0 - a) * q0[1] + a * q1[1],
                    (1.0 - a) * q0[2] + a * q1[2],
                ]);
            }
        }
        let mut knots = self.knots.clone();
        knots.insert(k + 1, t);
        from_homogeneous(p, knots, &hom, self.is_rational())
    }

    /// The same point set traversed backwards, on the same domain.
    pub fn reversed(&self) -> NurbsCurve {
        let (a, b) = (self.knots[0], self.knots[self.knots.len() - 1]);
        NurbsCurve {
            degree: self.degree,
            knots: self.knots.iter().rev().map(|k| a + b - k).collect(),
            points: self.points.iter().rev().copied().collect(),
            weights: self
                .weights
                .as_ref()
                .map(|w| w.iter().rev().copied().collect()),
        }
    }
}

/// The curve of degree `p` over `knots` whose homogeneous control points are `hom`.
fn from_homogeneous(p: usize, knots: Vec<f64>, hom: &[[f64; 3]], rational: bool) -> NurbsCurve {
    NurbsCurve {
        degree: p,
        knots,
        points: hom
            .iter()
            .map(|h| Point2::new(h[0] / h[2], h[1] / h[2]))
            .collect(),
        weights: rational.then(|| hom.iter().map(|h| h[2]).collect()),
    }
}

//! Planar NURBS curves in the (rho, z) half-plane: the profile curves of paper section 4.1.
//!
//! A curve of degree `p` has `n` control points, `n + p + 1` non-decreasing knots and, when it
//! is rational, `n` positive weights. Knot vectors are *clamped* (the first and last knots have
//! multiplicity `p + 1`) so that a curve starts at its first control point and ends at its last,
//! which is what joining pieces end to start needs. Evaluation works in homogeneous coordinates
//! `(w rho, w z, w)` with the B-spline basis (de Boor / Cox recurrences), so circles and arcs
//! written as rational quadratics are exact.

use crate::limits::{
    check_coordinate, check_magnitude, RangeError, MAX_KNOT, MAX_WEIGHT_RATIO, MIN_KNOT_SPAN,
};
use crate::num::cross2;
use nalgebra::{Point2, Vector2};

mod aabb;
mod basis;
mod knots;
mod length;
mod spans;

pub use aabb::Aabb2;
pub use spans::{halve_homogeneous, BezierSpan};

use basis::{basis_derivatives, binomial};
pub use basis::{basis_functions, find_span};

/// Highest derivative order [`NurbsCurve::derivatives`] returns (curvature and its derivative
/// need the third).
pub const MAX_DERIVATIVE: usize = 3;

/// Why a set of NURBS data does not describe a curve.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// Degree zero curves are piecewise constant and have no tangent.
    #[error("degree must be at least 1, got {0}")]
    ZeroDegree(usize),
    /// Fewer than `degree + 1` control points.
    #[error("degree {degree} needs at least {needed} control points, got {found}")]
    TooFewPoints {
        degree: usize,
        needed: usize,
        found: usize,
    },
    /// The knot count must be `points + degree + 1`.
    #[error(
        "wrong knot count: {points} points of degree {degree} need {expected} knots, got {found}"
    )]
    WrongKnotCount {
        degree: usize,
        points: usize,
        expected: usize,
        found: usize,
    },
    /// Knots must be non-decreasing.
    #[error("knots decrease at index {index}: {previous} > {value}")]
    DecreasingKnots {
        index: usize,
        previous: f64,
        value: f64,
    },
    /// The first and last knots must each repeat `degree + 1` times.
    #[error("knot vector is not clamped: the first and last {multiplicity} knots must be equal")]
    NotClamped { multiplicity: usize },
    /// An interior knot repeated more than `degree` times breaks the curve apart.
    #[error("interior knot {value} has multiplicity {multiplicity} > degree {degree}")]
    KnotMultiplicity {
        value: f64,
        multiplicity: usize,
        degree: usize,
    },
    /// The parameter domain has zero length.
    #[error("empty parameter domain [{start}, {end}]")]
    EmptyDomain { start: f64, end: f64 },
    /// The weight count must equal the point count.
    #[error("{points} control points but {weights} weights")]
    WrongWeightCount { points: usize, weights: usize },
    /// Weights must be finite and positive (the convex-hull property and a pole-free curve).
    #[error("weight {index} is {value}: weights must be finite and > 0")]
    NonPositiveWeight { index: usize, value: f64 },
    /// A knot or coordinate is NaN or infinite.
    #[error("{what} {index} is not finite")]
    NonFinite { what: &'static str, index: usize },
    /// A coordinate, knot span or weight ratio outside the representable range
    /// ([`crate::limits`]).
    #[error(transparent)]
    Range(#[from] RangeError),
    /// The weights of a rational curve differ by more than [`MAX_WEIGHT_RATIO`].
    #[error("weights range from {min:e} (weight {min_index}) to {max:e} (weight {max_index}): ratio {ratio:e} is above {MAX_WEIGHT_RATIO:e}")]
    WeightRatio {
        min: f64,
        min_index: usize,
        max: f64,
        max_index: usize,
        ratio: f64,
    },
    /// A non-empty knot span shorter than [`MIN_KNOT_SPAN`]: the curve's derivatives, which
    /// grow as the inverse span cubed, would overflow.
    #[error("knot span [{start:e}, {end:e}] (knots {index} and {next}) is shorter than {MIN_KNOT_SPAN:e}: rescale the knot vector")]
    KnotSpanTooShort {
        index: usize,
        next: usize,
        start: f64,
        end: f64,
    },
    /// A split parameter outside the open domain.
    #[error("parameter {t} is not inside the open domain ({start}, {end})")]
    ParameterOutOfRange { t: f64, start: f64, end: f64 },
}

/// A NURBS curve of any degree in the (rho, z) plane; rational when weights are given.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Point2<f64>>,
    weights: Option<Vec<f64>>,
}

impl NurbsCurve {
    /// Builds a curve after checking every invariant listed in [`CurveError`].
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point2<f64>>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, CurveError> {
        if degree == 0 {
            return Err(CurveError::ZeroDegree(degree));
        }
        if points.len() < degree + 1 {
            return Err(CurveError::TooFewPoints {
                degree,
                needed: degree + 1,
                found: points.len(),
            });
        }
        let expected = points.len() + degree + 1;
        if knots.len() != expected {
            return Err(CurveError::WrongKnotCount {
                degree,
                points: points.len(),
                expected,
                found: knots.len(),
            });
        }
        if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
            return Err(CurveError::NonFinite {
                what: "knot",
                index,
            });
        }
        if let Some(index) = points
            .iter()
            .position(|p| !p.x.is_finite() || !p.y.is_finite())
        {
            return Err(CurveError::NonFinite {
                what: "control point",
                index,
            });
        }
        for (index, p) in points.iter().enumerate() {
            check_coordinate(&format!("control point {index}, rho"), p.x)?;
            check_coordinate(&format!("control point {index}, z"), p.y)?;
        }
        for (index, k) in knots.iter().enumerate() {
            check_magnitude(&format!("knot {index}"), *k, MAX_KNOT)?;
        }
        for i in 1..knots.len() {
            if knots[i] > knots[i - 1] && knots[i] - knots[i - 1] < MIN_KNOT_SPAN {
                return Err(CurveError::KnotSpanTooShort {
                    index: i - 1,
                    next: i,
                    start: knots[i - 1],
                    end: knots[i],
                });
            }
            if knots[i] < knots[i - 1] {
                return Err(CurveError::DecreasingKnots {
                    index: i,
                    previous: knots[i - 1],
                    value: knots[i],
                });
            }
        }
        let m = knots.len() - 1;
        if knots[degree] != knots[0] || knots[m - degree] != knots[m] {
            return Err(CurveError::NotClamped {
                multiplicity: degree + 1,
            });
        }
        let (start, end) = (knots[degree], knots[m - degree]);
        if start >= end {
            return Err(CurveError::EmptyDomain { start, end });
        }
        if knots[degree + 1] == start || knots[m - degree - 1] == end {
            return Err(CurveError::KnotMultiplicity {
                value: if knots[degree + 1] == start {
                    start
                } else {
                    end
                },
                multiplicity: degree + 2,
                degree,
            });
        }
        let mut i = degree + 1;
        while i < m - degree {
            let mult = knots[i..].iter().take_while(|&&k| k == knots[i]).count();
            if mult > degree && knots[i] < end {
                return Err(CurveError::KnotMultiplicity {
                    value: knots[i],
                    multiplicity: mult,
                    degree,
                });
            }
            i += mult;
        }
        if let Some(w) = &weights {
            if w.len() != points.len() {
                return Err(CurveError::WrongWeightCount {
                    points: points.len(),
                    weights: w.len(),
                });
            }
            if let Some(index) = w.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(CurveError::NonPositiveWeight {
                    index,
                    value: w[index],
                });
            }
            let by_value = |a: &(usize, &f64), b: &(usize, &f64)| a.1.total_cmp(b.1);
            let (min_index, &min) = w.iter().enumerate().min_by(by_value).expect("points");
            let (max_index, &max) = w.iter().enumerate().max_by(by_value).expect("points");
            let ratio = max / min;
            if ratio.is_nan() || ratio > MAX_WEIGHT_RATIO {
                return Err(CurveError::WeightRatio {
                    min,
                    min_index,
                    max,
                    max_index,
                    ratio,
                });
            }
        }
        Ok(NurbsCurve {
            degree,
            knots,
            points,
            weights,
        })
    }

    /// A polynomial Bezier curve of degree `points.len() - 1` on [0, 1].
    pub fn bezier(points: Vec<Point2<f64>>) -> Result<Self, CurveError> {
        let degree = points.len().saturating_sub(1);
        let knots = clamped_bezier_knots(degree);
        NurbsCurve::new(degree, knots, points, None)
    }

    /// The straight segment from `a` to `b` (degree 1 on [0, 1]).
    pub fn line(a: Point2<f64>, b: Point2<f64>) -> Result<Self, CurveError> {
        NurbsCurve::bezier(vec![a, b])
    }

    /// Polynomial degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Control points in (rho, z).
    pub fn points(&self) -> &[Point2<f64>] {
        &self.points
    }

    /// Weights, `None` for a polynomial (all weights 1) curve.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Whether the curve has weights.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }

    fn homogeneous(&self, i: usize) -> [f64; 3] {
        let w = self.weight(i);
        [w * self.points[i].x, w * self.points[i].y, w]
    }

    /// The parameter domain `[t_start, t_end]`.
    pub fn domain(&self) -> (f64, f64) {
        (
            self.knots[self.degree],
            self.knots[self.knots.len() - 1 - self.degree],
        )
    }

    /// First point (the first control point: the knot vector is clamped).
    pub fn start(&self) -> Point2<f64> {
        self.points[0]
    }

    /// Last point.
    pub fn end(&self) -> Point2<f64> {
        self.points[self.points.len() - 1]
    }

    /// Point at parameter `t` (clamped to the domain).
    pub fn eval(&self, t: f64) -> Point2<f64> {
        let d = self.derivatives_up_to(t, 0);
        Point2::from(d[0])
    }

    /// Point and derivatives 1..=3 at `t`: `[C, C', C'', C''']`, the point as a vector.
    pub fn derivatives(&self, t: f64) -> [Vector2<f64>; 4] {
        self.derivatives_up_to(t, MAX_DERIVATIVE)
    }

    /// `[C, C', ..., C^(order)]` at `t`, zero beyond `order`. Rational derivatives follow
    /// from the homogeneous ones by Leibniz' rule: `A^(k) = sum_i binom(k,i) w^(i) C^(k-i)`.
    fn derivatives_up_to(&self, t: f64, order: usize) -> [Vector2<f64>; 4] {
        let p = self.degree;
        let (start, end) = self.domain();
        let t = t.clamp(start, end);
        let span = find_span(p, &self.knots, t);
        let ders = basis_derivatives(p, &self.knots, span, t, order);
        let mut hom = [[0.0f64; 3]; 4];
        for (k, row) in ders.iter().enumerate().take(order + 1) {
            for (j, b) in row.iter().enumerate().take(p + 1) {
                let h = self.homogeneous(span - p + j);
                for c in 0..3 {
                    hom[k][c] += b * h[c];
                }
            }
        }
        let mut out = [Vector2::zeros(); 4];
        for k in 0..=order {
            let mut v = Vector2::new(hom[k][0], hom[k][1]);
            for i in 1..=k {
                v -= binomial(k, i) * hom[i][2] * out[k - i];
            }
            out[k] = v / hom[0][2];
        }
        out
    }

    /// Signed curvature `(x' z'' - z' x'') / |C'|^3` at `t` (positive when turning left in the
    /// (rho, z) plane); NaN where the speed vanishes.
    pub fn curvature(&self, t: f64) -> f64 {
        let d = self.derivatives_up_to(t, 2);
        cross2(d[1], d[2]) / d[1].norm().powi(3)
    }

    /// Derivative of the signed curvature with respect to the parameter.
    pub fn curvature_derivative(&self, t: f64) -> f64 {
        let d = self.derivatives(t);
        let speed_sq = d[1].norm_squared();
        let n = cross2(d[1], d[2]);
        let n_prime = cross2(d[1], d[3]);
        (n_prime * speed_sq - 3.0 * n * d[1].dot(&d[2])) / speed_sq.powf(2.5)
    }

    /// Box of the control points. With positive weights the curve lies in the convex hull of
    /// its control points, so this box certainly contains the curve.
    pub fn bounding_box(&self) -> Aabb2 {
        Aabb2::from_points(&self.points).expect("a curve has at least two control points")
    }
}

fn clamped_bezier_knots(degree: usize) -> Vec<f64> {
    let mut k = vec![0.0; degree + 1];
    k.extend(std::iter::repeat_n(1.0, degree + 1));
    k
}

#[cfg(test)]
mod tests;

//! Planar NURBS curves in the (rho, z) half-plane (paper section 4.1: the profile curve).
//! API skeleton: implementation in progress.

use nalgebra::{Point2, Vector2};

/// Errors building a NURBS curve.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    #[error("placeholder")]
    Placeholder,
}

/// Axis-aligned box in the (rho, z) plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb2 {
    pub min: Point2<f64>,
    pub max: Point2<f64>,
}

/// A NURBS curve of any degree; rational when weights are given.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Point2<f64>>,
    weights: Option<Vec<f64>>,
}

/// One rational Bezier span of a NURBS curve, in homogeneous form.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSpan {
    /// Parameter interval of the span in the parent curve.
    pub t0: f64,
    pub t1: f64,
    /// Homogeneous control points (w*rho, w*z, w).
    pub homogeneous: Vec<[f64; 3]>,
}

impl NurbsCurve {
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point2<f64>>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, CurveError> {
        let _ = (degree, knots, points, weights);
        todo!()
    }
    pub fn degree(&self) -> usize {
        self.degree
    }
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }
    pub fn points(&self) -> &[Point2<f64>] {
        &self.points
    }
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }
    pub fn domain(&self) -> (f64, f64) {
        todo!()
    }
    pub fn eval(&self, t: f64) -> Point2<f64> {
        let _ = t;
        todo!()
    }
    /// Point and derivatives 1..=3 at t: `[C, C', C'', C''']`.
    pub fn derivatives(&self, t: f64) -> [Vector2<f64>; 4] {
        let _ = t;
        todo!()
    }
    pub fn curvature(&self, t: f64) -> f64 {
        let _ = t;
        todo!()
    }
    pub fn split(&self, t: f64) -> (NurbsCurve, NurbsCurve) {
        let _ = t;
        todo!()
    }
    pub fn reversed(&self) -> NurbsCurve {
        todo!()
    }
    pub fn bounding_box(&self) -> Aabb2 {
        todo!()
    }
    pub fn arc_length(&self, tolerance: f64) -> f64 {
        let _ = tolerance;
        todo!()
    }
    pub fn bezier_spans(&self) -> Vec<BezierSpan> {
        todo!()
    }
}

//! Exact NURBS building blocks for the built-in profiles: line segments, circular arcs
//! (rational quadratic, exact), and polynomial Bezier pieces. All pieces use the parameter
//! domain [0, 1].

use nalgebra::Point2;

use crate::nurbs::{CurveError, NurbsCurve};

/// Largest sweep of one rational quadratic arc span. A span of sweep `delta` has middle weight
/// cos(delta / 2), which stays well away from zero for spans of at most a quarter turn.
const MAX_ARC_SPAN_SWEEP: f64 = std::f64::consts::FRAC_PI_2;

/// Straight segment from `a` to `b` as a degree-1 NURBS.
pub fn line(a: Point2<f64>, b: Point2<f64>) -> Result<NurbsCurve, CurveError> {
    NurbsCurve::line(a, b)
}

/// Straight segment from `a` to `b` as a degree-2 B-spline with collinear, evenly spaced
/// control points (linear parameterisation): exercises degree-2 straight pieces.
pub fn line_quadratic(a: Point2<f64>, b: Point2<f64>) -> Result<NurbsCurve, CurveError> {
    let mid = Point2::from((a.coords + b.coords) * 0.5);
    NurbsCurve::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![a, mid, b], None)
}

/// Polynomial Bezier curve with the given control points (degree = points - 1).
pub fn bezier(points: &[[f64; 2]]) -> Result<NurbsCurve, CurveError> {
    NurbsCurve::bezier(points.iter().map(|p| Point2::new(p[0], p[1])).collect())
}

/// Exact circular arc of radius `radius` about `center` from angle `phi0` to `phi1`
/// (radians, measured from the +rho direction towards +z; `phi1 < phi0` runs clockwise).
///
/// Rational quadratic NURBS with one span per at most a quarter turn: a span of sweep
/// `delta` has end weights 1 and middle weight cos(delta/2), its middle control point at
/// distance radius / cos(delta/2) from the centre on the bisector (Piegl & Tiller, The NURBS
/// Book, section 7.3).
pub fn arc(center: [f64; 2], radius: f64, phi0: f64, phi1: f64) -> Result<NurbsCurve, CurveError> {
    let sweep = phi1 - phi0;
    let spans = ((sweep.abs() / MAX_ARC_SPAN_SWEEP).ceil() as usize).max(1);
    let delta = sweep / spans as f64;
    let w_mid = (delta * 0.5).cos();
    let on_circle = |phi: f64| arc_point(center, radius, phi);
    let mut points = vec![on_circle(phi0)];
    let mut weights = vec![1.0];
    let mut knots = vec![0.0; 3];
    for i in 0..spans {
        let a = phi0 + delta * i as f64;
        let mid = a + delta * 0.5;
        let r_mid = radius / w_mid;
        points.push(Point2::new(
            center[0] + r_mid * mid.cos(),
            center[1] + r_mid * mid.sin(),
        ));
        weights.push(w_mid);
        // The last span ends exactly at phi1 (no accumulated rounding in the angle).
        let end = if i + 1 == spans { phi1 } else { a + delta };
        points.push(on_circle(end));
        weights.push(1.0);
        if i + 1 < spans {
            let k = (i + 1) as f64 / spans as f64;
            knots.extend([k, k]);
        }
    }
    knots.extend([1.0; 3]);
    NurbsCurve::new(2, knots, points, Some(weights))
}

/// Point at angle `phi` on the circle of radius `radius` about `center`. Angles that are
/// multiples of a quarter turn give exact axis-aligned offsets (cos(pi/2) is not 0 in floating
/// point), so arcs meet the axis rho = 0 and neighbouring straight pieces exactly.
pub fn arc_point(center: [f64; 2], radius: f64, phi: f64) -> Point2<f64> {
    let quarters = phi / std::f64::consts::FRAC_PI_2;
    let (cos, sin) = if (quarters - quarters.round()).abs() < QUARTER_SNAP {
        match (quarters.round() as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        }
    } else {
        (phi.cos(), phi.sin())
    };
    Point2::new(center[0] + radius * cos, center[1] + radius * sin)
}

/// Relative distance (in quarter turns) below which an angle is snapped to the exact quarter
/// turn: far above the rounding of `deg(90.0)` (about 1e-16) and far below any intended angle.
const QUARTER_SNAP: f64 = 1e-12;

/// Angle in radians from degrees (model tables are written in degrees for readability).
pub fn deg(degrees: f64) -> f64 {
    degrees.to_radians()
}

/// Shorthand for a profile point.
pub fn pt(rho: f64, z: f64) -> Point2<f64> {
    Point2::new(rho, z)
}

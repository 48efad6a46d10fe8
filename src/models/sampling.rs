//! Dense point samples of profile pieces, for drawing and cheap geometric checks.

use nalgebra::Point2;

use crate::nurbs::NurbsCurve;
use crate::profile::Profile;

/// Points of `piece` at `samples_per_span` equal parameter steps in every non-empty knot
/// span, first and last point included (consecutive spans share their end point).
pub fn sample_piece(piece: &NurbsCurve, samples_per_span: usize) -> Vec<Point2<f64>> {
    let steps = samples_per_span.max(1);
    let breaks = distinct_knots(piece);
    let mut points = Vec::with_capacity((breaks.len().max(2) - 1) * steps + 1);
    points.push(piece.eval(breaks[0]));
    for pair in breaks.windows(2) {
        for k in 1..=steps {
            let t = pair[0] + (pair[1] - pair[0]) * k as f64 / steps as f64;
            points.push(piece.eval(t));
        }
    }
    points
}

/// The whole profile as one polyline (pieces concatenated, shared end points kept once).
pub fn sample_profile(profile: &Profile, samples_per_span: usize) -> Vec<Point2<f64>> {
    let mut points: Vec<Point2<f64>> = Vec::new();
    for piece in profile.pieces() {
        let samples = sample_piece(piece, samples_per_span);
        let skip = usize::from(!points.is_empty());
        points.extend(samples.into_iter().skip(skip));
    }
    points
}

/// Distinct knot values inside the curve's domain (span boundaries), increasing.
pub fn distinct_knots(piece: &NurbsCurve) -> Vec<f64> {
    let (t0, t1) = piece.domain();
    let mut breaks = vec![t0];
    for &k in piece.knots() {
        if k > *breaks.last().unwrap_or(&t0) && k <= t1 {
            breaks.push(k);
        }
    }
    if breaks.len() == 1 {
        breaks.push(t1);
    }
    breaks
}

//! Dense point samples of profile pieces, for drawing and cheap geometric checks.

use nalgebra::Point2;

use crate::nurbs::NurbsCurve;
use crate::profile::Profile;

/// Points of `piece` at `samples_per_span` equal parameter steps in every non-empty knot
/// span, first and last point included (consecutive spans share their end point).
pub fn sample_piece(piece: &NurbsCurve, samples_per_span: usize) -> Vec<Point2<f64>> {
    let steps = samples_per_span.max(1);
    let spans = piece.distinct_spans();
    let mut points = Vec::with_capacity(spans.len() * steps + 1);
    points.push(piece.start());
    for (t0, t1) in spans {
        for k in 1..=steps {
            points.push(piece.eval(t0 + (t1 - t0) * k as f64 / steps as f64));
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

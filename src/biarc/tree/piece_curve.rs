//! A profile piece as consecutive Bezier spans evaluated in the piece's parameter: what the
//! spiral builder samples, and the certified deviations of a chord's or an arc's curve part
//! (control-polygon hull, arc deviation) it bounds nodes with.

use super::segment_distance;
use crate::biarc::arc::Arc;
use crate::biarc::arc_deviation::{ArcFrame, PieceArcDeviation};
use crate::biarc::bound::ulp_slack;
use crate::biarc::fit::{CurveSample, PlanarCurve};
use crate::biarc::span::{SpanCurve, MAX_SPAN_DEGREE};
use nalgebra::{Point2, Vector2};

#[derive(Debug, Clone, Copy)]
pub(super) struct SpanRecord {
    pub(super) piece: u32,
    pub(super) t0: f64,
    pub(super) t1: f64,
    pub(super) offset: u32,
    pub(super) len: u32,
}

/// Consecutive Bezier spans of one profile piece, evaluated in the piece's parameter `t`.
#[derive(Debug, Clone, Copy)]
pub(super) struct PieceCurve<'a> {
    pub(super) spans: &'a [SpanRecord],
    pub(super) coeffs: &'a [[f64; 3]],
}

impl PieceCurve<'_> {
    /// The span holding `t` (the last one whose start is <= t) and its local parameter.
    pub(super) fn locate(&self, t: f64) -> (SpanCurve<'_>, f64, f64) {
        self.span_at(self.spans.partition_point(|r| r.t0 <= t), t)
    }

    /// [`Self::locate`], but at a span boundary the span that ends there.
    pub(super) fn locate_before(&self, t: f64) -> (SpanCurve<'_>, f64, f64) {
        self.span_at(self.spans.partition_point(|r| r.t0 < t), t)
    }

    /// The span before index `after` (the first after it when `after` is 0), `t`'s local
    /// parameter in it, and its parameter length.
    pub(super) fn span_at(&self, after: usize, t: f64) -> (SpanCurve<'_>, f64, f64) {
        let r = &self.spans[after.saturating_sub(1)];
        let len = r.t1 - r.t0;
        let curve = SpanCurve {
            homogeneous: &self.coeffs[r.offset as usize..(r.offset + r.len) as usize],
        };
        (curve, ((t - r.t0) / len).clamp(0.0, 1.0), len)
    }

    /// A two-sided Hausdorff bound between the curve piece `[t0, t1]` and the segment from
    /// `a` to `b` (its end points as evaluated), needing no spiral property.
    ///
    /// Every part of a rational Bezier span with positive weights lies in the convex hull of
    /// its control points, so each curve point is within `d` = the largest distance from
    /// those points to the segment (distance to a convex set is convex). Conversely the curve
    /// runs from `a` to `b` within `d` of the segment's line, so it crosses every normal of
    /// the segment between them at distance `<= d`. The control points come from two de
    /// Casteljau cuts per span; their rounding, a few ulps of the homogeneous coordinates per
    /// level, is covered by [`ulp_slack`] of the coordinates times the weights' spread.
    pub(super) fn hull_deviation(&self, t0: f64, t1: f64, a: Point2<f64>, b: Point2<f64>) -> f64 {
        let mut deviation = 0.0f64;
        let mut scale = a.coords.amax().max(b.coords.amax());
        self.for_each_part(t0, t1, |part, part_scale| {
            for p in part {
                let q = Point2::new(p[0] / p[2], p[1] / p[2]);
                deviation = deviation.max(segment_distance(q, a, b));
            }
            scale = scale.max(part_scale);
        });
        deviation + ulp_slack(scale)
    }

    /// A two-sided Hausdorff bound between the curve piece `[t0, t1]` and `arc` as the query
    /// revolves it, needing no spiral property; `None` when the piece is too far from the
    /// arc's circle or outside its bisector half-plane ([`PieceArcDeviation::bound`]).
    ///
    /// A flat arc (a segment, or a radius above `flat_radius`, revolved as its chord) is
    /// bounded by the control polygon against the chord plus the sagitta, which covers the
    /// arc too; any other by [`PieceArcDeviation`] on each span's part. The rounding of the
    /// parts' control points is covered as in [`Self::hull_deviation`]; that of the arc's
    /// end points (evaluated on the curve, and as the query puts them on the circle) by two
    /// more [`ulp_slack`]s of `|c| + R`.
    pub(super) fn arc_deviation(
        &self,
        t0: f64,
        t1: f64,
        arc: &Arc,
        flat_radius: f64,
    ) -> Option<f64> {
        if arc.is_segment() || arc.radius() > flat_radius {
            let sagitta = if arc.is_segment() { 0.0 } else { arc.sagitta() };
            return Some(self.hull_deviation(t0, t1, arc.start, arc.end) + sagitta);
        }
        let frame = ArcFrame::of(arc)?;
        let mut deviation = PieceArcDeviation::new(frame);
        let mut scale = arc.start.coords.amax().max(arc.end.coords.amax());
        self.for_each_part(t0, t1, |part, part_scale| {
            deviation.add_part(part);
            scale = scale.max(part_scale);
        });
        Some(deviation.bound()? + ulp_slack(scale) + 2.0 * ulp_slack(frame.scale()))
    }

    /// Calls `f` with the homogeneous Bezier control points of each span's part of the curve
    /// piece `[t0, t1]` (two de Casteljau cuts) and the magnitude their rounding is relative
    /// to: the largest coordinate of the control points times the weights' spread
    /// `w_max / w_min`.
    pub(super) fn for_each_part(&self, t0: f64, t1: f64, mut f: impl FnMut(&[[f64; 3]], f64)) {
        let mut part = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
        for r in self.spans.iter().filter(|r| r.t1 > t0 && r.t0 < t1) {
            let len = r.t1 - r.t0;
            let u0 = ((t0 - r.t0) / len).clamp(0.0, 1.0);
            let u1 = ((t1 - r.t0) / len).clamp(0.0, 1.0);
            if u1 <= u0 {
                continue;
            }
            let h = &self.coeffs[r.offset as usize..(r.offset + r.len) as usize];
            let n = h.len() - 1;
            SpanCurve { homogeneous: h }.part(u0, u1, &mut part[..=n]);
            let (w_min, w_max) = part[..=n]
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
                    (lo.min(p[2]), hi.max(p[2]))
                });
            let part_scale = part[..=n].iter().fold(0.0f64, |m, p| {
                m.max(Point2::new(p[0] / p[2], p[1] / p[2]).coords.amax() * w_max / w_min)
            });
            f(&part[..=n], part_scale);
        }
    }

    pub(super) fn curvature(&self, t: f64) -> f64 {
        let (c, u, _) = self.locate(t);
        c.curvature(u)
    }

    /// The sample at a spiral's end `t`, with the derivative seen from inside the spiral
    /// (`leaving` at its start), and the curve-length slack of that choice. A spiral split
    /// lands on a stationary point of the curve (a cusp, a retrace) where the speed is
    /// rounding noise and only the one-sided limit gives the tangent; ignoring the dropped
    /// first-order term `|C'| dt` moves the curve by at most `|C'| (t1 - t0)` over the spiral
    /// `[t0, t1]`, which is returned as the slack (zero where nothing was dropped).
    pub(super) fn end_sample(
        &self,
        t: f64,
        leaving: bool,
        span_of_spiral: f64,
    ) -> (CurveSample, f64) {
        // Arriving at a knot, the span that ends there (the curve before it), not the next.
        let (c, u, len) = if leaving {
            self.locate(t)
        } else {
            self.locate_before(t)
        };
        let (point, _) = c.point_and_derivative(u);
        let (derivative, dropped) = c.one_sided_derivative(u, leaving);
        (
            CurveSample {
                t,
                point,
                derivative: derivative / len,
            },
            dropped / len * span_of_spiral,
        )
    }
}

impl PlanarCurve for PieceCurve<'_> {
    fn point_and_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>) {
        let (c, u, len) = self.locate(t);
        let (p, d) = c.point_and_derivative(u);
        (p, d / len)
    }
}

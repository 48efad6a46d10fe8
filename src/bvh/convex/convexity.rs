//! Certified convexity of a solid of revolution, decided on the exact NURBS profile.
//!
//! A solid of revolution is convex iff its meridian section is a convex planar region: for
//! an open-on-axis profile, the profile together with its mirror image across the axis; a
//! closed profile (a ring) has a hole on the axis and is never convex.
//!
//! **Certificate.** The section is a closed curve made of the profile's Bezier spans
//! ([`crate::nurbs::NurbsCurve::bezier_spans`], positive weights), their mirror images and
//! the corners at the axis. It bounds a convex region when it turns left everywhere and
//! its total turning is exactly one full turn:
//! * each span's control polygon turns left (exact orientation signs, [`super::exact`]) and
//!   by less than a half turn in all; then the span itself is convex and its tangent turns
//!   by the polygon's angle (convexity preservation of Bezier curves with positive weights,
//!   Farin, *Curves and Surfaces for CAGD*, variation diminishing property; its tangents lie
//!   in the cone of the polygon's legs). A span whose polygon is not convex is halved (de
//!   Casteljau) up to [`MAX_DEPTH`] times before the certificate gives up;
//! * at every joint (between spans, between pieces, at a gap between pieces: the bridging
//!   segment) the tangent turns left by less than a half turn;
//! * at the axis the end tangents point away from the axis and do not point outward past
//!   its perpendicular (the bottom tangent `(a, b)` has `a > 0, b >= 0`, the top one
//!   `a < 0, b >= 0`, for a profile running from the bottom of the axis to its top);
//! * the turning of the whole section, twice the profile's plus the two axis corners, is
//!   `2 pi` (it is a multiple of `2 pi`; all terms are non-negative, so one full turn means
//!   the curve winds once and is convex).
//!
//! Rounding. Orientation signs inside a span's polygon are exact for the control points as
//! computed (Bezier extraction and de Casteljau halving round them by a few ulps, far below
//! the query's rounding slack). Tangent angles at joints are compared in floating point:
//! a joint may turn right by at most [`KINK_TOLERANCE`] (rounding of the tangents of halved
//! spans, which are G1 exactly); the certificate records the sum `N` of such right turns and
//! bounds the section's distance from its convex hull by `N L`, `L` the section's length
//! (straightening a kink of angle `k` moves the rest of the curve by at most `k L`). Anything
//! else, including a degenerate tangent, makes the certificate inconclusive: the solid is
//! then treated as not convex.

use super::exact::{cross_sign, dot_sign};
use crate::num::cross2;
use crate::nurbs::NurbsCurve;
use crate::profile::{Profile, ProfileKind};
use nalgebra::{Point2, Vector2};
use std::cmp::Ordering;
use std::f64::consts::{PI, TAU};

/// How many times a span whose control polygon is not convex is halved before the
/// certificate gives up (up to 64 sub-spans per span).
pub const MAX_DEPTH: u32 = 6;

/// Largest right turn (radians) accepted at a joint: the tangents at the ends of halved
/// spans are parallel exactly but rounded to a few ulps of their coordinates; 1e-12 rad is
/// far above that and far below any real corner.
pub const KINK_TOLERANCE: f64 = 1e-12;

/// A certified convex profile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvexProfile {
    /// Bound on the distance of the meridian section from its convex hull (the right turns
    /// accepted at joints times the section's length; 0 for exact corners).
    pub dent: f64,
}

/// The turning of a run of the section that is certified to turn left.
#[derive(Debug, Clone, Copy)]
struct Run {
    start_tangent: Vector2<f64>,
    end_tangent: Vector2<f64>,
    /// Total turning angle (radians, >= 0 up to the accepted kinks).
    turning: f64,
    /// Sum of the right turns accepted at joints inside the run.
    kinks: f64,
    /// Length of the control polygons (bounds the curve's length).
    length: f64,
}

impl Run {
    /// `self` followed by `next`, joined at a point where the tangent turns by the angle
    /// from `self.end_tangent` to `next.start_tangent`; `None` when that is not a left turn
    /// of less than a half turn.
    fn then(self, next: Run) -> Option<Run> {
        let angle = joint_angle(self.end_tangent, next.start_tangent)?;
        Some(Run {
            start_tangent: self.start_tangent,
            end_tangent: next.end_tangent,
            turning: self.turning + angle + next.turning,
            kinks: self.kinks + next.kinks + (-angle).max(0.0),
            length: self.length + next.length,
        })
    }
}

/// Signed angle from `a` to `b` when it lies in `[-KINK_TOLERANCE, pi)` (a left turn, up
/// to rounding, that is not a cusp).
fn joint_angle(a: Vector2<f64>, b: Vector2<f64>) -> Option<f64> {
    let (a, b) = (a.normalize(), b.normalize());
    let angle = cross2(a, b).atan2(a.dot(&b));
    (-KINK_TOLERANCE..PI - 1e-9)
        .contains(&angle)
        .then_some(angle)
}

/// Certifies that the solid of revolution of `profile` is convex (module doc); `None` when
/// it is not convex or the certificate is inconclusive.
pub fn certify_convex(profile: &Profile) -> Option<ConvexProfile> {
    if profile.kind() != ProfileKind::OpenOnAxis {
        return None;
    }
    let pieces = profile.pieces();
    let (first, last) = (pieces.first()?.start(), pieces.last()?.end());
    // Mirror z so that the profile runs from the bottom of the axis to its top (the region
    // then lies to its left); a reflection keeps convexity.
    let flip = match first.y.partial_cmp(&last.y)? {
        Ordering::Less => 1.0,
        Ordering::Greater => -1.0,
        Ordering::Equal => return None,
    };
    let mut chain: Option<Run> = None;
    let mut previous_end: Option<Point2<f64>> = None;
    for piece in pieces {
        let start = flipped(piece.start(), flip);
        if let Some(end) = previous_end.filter(|&e| e != start) {
            // A gap between pieces: the segment bridging it is part of the section.
            chain = append(chain, segment_run(end, start)?)?;
        }
        for run in piece_runs(piece, flip)? {
            chain = append(chain, run?)?;
        }
        previous_end = Some(flipped(piece.end(), flip));
    }
    let chain = chain?;
    // Axis corners: the mirror image arrives at the bottom with tangent (a, -b) and leaves
    // the top with (a, -b) for tangents (a, b) of the profile; the section turns by twice the
    // angle between the profile's tangent and the axis' perpendicular there (also when an
    // end stands off the axis by rounding: two corners of that angle each).
    let (b0, b1) = (chain.start_tangent, chain.end_tangent);
    if !(b0.x > 0.0 && b1.x < 0.0) {
        return None;
    }
    let bottom = b0.y.atan2(b0.x);
    let top = b1.y.atan2(-b1.x);
    if bottom < -KINK_TOLERANCE || top < -KINK_TOLERANCE {
        return None;
    }
    let total = 2.0 * (chain.turning + bottom + top);
    if (total - TAU).abs() > 1e-6 {
        return None;
    }
    let kinks = 2.0 * (chain.kinks + (-bottom).max(0.0) + (-top).max(0.0));
    let height = (last.y - first.y).abs();
    let section_length = 2.0 * chain.length + height + 2.0 * (first.x.abs() + last.x.abs());
    Some(ConvexProfile {
        dent: kinks * section_length,
    })
}

fn flipped(p: Point2<f64>, flip: f64) -> Point2<f64> {
    Point2::new(p.x, flip * p.y)
}

fn append(chain: Option<Run>, run: Option<Run>) -> Option<Option<Run>> {
    Some(match (chain, run) {
        (Some(c), Some(r)) => Some(c.then(r)?),
        (c, None) => c,
        (None, r) => r,
    })
}

/// A straight segment as a run (`None` inside when it has no length).
fn segment_run(a: Point2<f64>, b: Point2<f64>) -> Option<Option<Run>> {
    if a == b {
        return Some(None);
    }
    let d = b - a;
    Some(Some(Run {
        start_tangent: d,
        end_tangent: d,
        turning: 0.0,
        kinks: 0.0,
        length: d.norm(),
    }))
}

/// Each Bezier span of `piece` as a certified run: the outer `Option` is `None` for a piece
/// whose weights are not all positive and finite; an inner `None` means the certificate
/// failed; `Some(None)` is a span of zero length.
fn piece_runs(piece: &NurbsCurve, flip: f64) -> Option<Vec<Option<Option<Run>>>> {
    let spans = piece.bezier_spans();
    let mut out = Vec::with_capacity(spans.len());
    for span in &spans {
        let mut h = span.homogeneous.clone();
        for q in &mut h {
            if !(q[2] > 0.0 && q.iter().all(|x| x.is_finite())) {
                return None;
            }
            q[1] *= flip;
        }
        out.push(span_run(&h, MAX_DEPTH));
    }
    Some(out)
}

/// A Bezier span (homogeneous control points, positive weights) as a certified run, halving
/// it while its control polygon is not convex; `None` when the certificate fails.
fn span_run(h: &[[f64; 3]], depth: u32) -> Option<Option<Run>> {
    let points: Vec<Point2<f64>> = h
        .iter()
        .map(|q| Point2::new(q[0] / q[2], q[1] / q[2]))
        .collect();
    match polygon_run(&points) {
        Some(run) => Some(run),
        None if depth > 0 => {
            let (left, right) = crate::nurbs::halve_homogeneous(h);
            let left = span_run(&left, depth - 1)?;
            let right = span_run(&right, depth - 1)?;
            append(left, right)
        }
        None => None,
    }
}

/// The run of a control polygon that turns left (exact signs) by less than a half turn:
/// then the Bezier span it controls is convex and turns by the same angle. `Some(None)` for
/// a polygon of one point; `None` when the polygon is not such a convex arc.
fn polygon_run(points: &[Point2<f64>]) -> Option<Option<Run>> {
    // Legs of non-zero length, as (tail, head) pairs for the exact predicates.
    let legs: Vec<(Point2<f64>, Point2<f64>)> = points
        .windows(2)
        .filter(|w| w[0] != w[1])
        .map(|w| (w[0], w[1]))
        .collect();
    let Some(&(f0, f1)) = legs.first() else {
        return Some(None);
    };
    let left_of =
        |(a, b): (Point2<f64>, Point2<f64>), (c, d): (Point2<f64>, Point2<f64>)| match cross_sign(
            a, b, c, d,
        ) {
            Ordering::Greater => true,
            Ordering::Equal => dot_sign(a, b, c, d) == Ordering::Greater,
            Ordering::Less => false,
        };
    let mut turning = 0.0;
    let mut length = 0.0;
    for (i, &leg) in legs.iter().enumerate() {
        // Each leg turns left from the previous one and stays within a half turn of the
        // first (so the total turning is below pi and the polygon is a convex arc).
        if !left_of((f0, f1), leg) {
            return None;
        }
        if i > 0 {
            let prev = legs[i - 1];
            if !left_of(prev, leg) {
                return None;
            }
            let (u, v) = (prev.1 - prev.0, leg.1 - leg.0);
            turning += cross2(u, v).atan2(u.dot(&v)).max(0.0);
        }
        length += (leg.1 - leg.0).norm();
    }
    let (l0, l1) = legs[legs.len() - 1];
    Some(Some(Run {
        start_tangent: f1 - f0,
        end_tangent: l1 - l0,
        turning,
        kinks: 0.0,
        length,
    }))
}

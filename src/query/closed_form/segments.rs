//! The distance between two segments of space (a point is a segment of length 0), with a
//! certified lower bound: the core distance of two capsules, or of a capsule and a ball
//! ([`super::offset_distance`]).
//!
//! **Closest points.** The squared distance between `a0 + s (a1 - a0)` and `b0 + t (b1 - b0)`
//! is a convex quadratic over the unit square of `(s, t)`; its minimum is the interior
//! stationary point when that lies in the square, else on an edge, where fixing `s` (or `t`)
//! at 0 or 1 leaves the distance from an end point to the other segment, whose minimum is the
//! end point's projection clamped to that segment. The candidates are these (at most five);
//! the nearest realised pair wins, so the value is a realised distance (an upper bound up to
//! the rounding of two points), whatever the conditioning of the stationary point (nearly
//! parallel segments).
//!
//! **Lower bound.** For any unit `u`, the segments are at least `min_j u.b_j - max_i u.a_i`
//! apart (a separating slab; a segment's extreme points along `u` are its end points). With
//! `u` along the winning pair this equals the value at the true closest points, and it is a
//! valid bound for any `u`: rounding and a poor candidate can only loosen it.

use nalgebra::{Point3, Vector3};

/// A segment `[start, end]` of space; `start == end` is a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment3 {
    pub start: Point3<f64>,
    pub end: Point3<f64>,
}

/// Closest points of two segments and bounds on their distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentDistance {
    /// `|point_b - point_a|`, a realised distance.
    pub value: f64,
    /// A certified lower bound (separating slab), `<= value` up to rounding.
    pub lower: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
}

impl Segment3 {
    /// The point of the segment nearest to `x` (the projection clamped to the segment).
    pub fn nearest(&self, x: &Point3<f64>) -> Point3<f64> {
        let along = self.end - self.start;
        let len2 = along.norm_squared();
        if len2 == 0.0 {
            return self.start;
        }
        let s = ((x - self.start).dot(&along) / len2).clamp(0.0, 1.0);
        self.start + along * s
    }

    /// The segment's point at parameter `s` of `[0, 1]`.
    fn at(&self, s: f64) -> Point3<f64> {
        self.start + (self.end - self.start) * s
    }

    /// The largest `u . x` over the segment.
    fn support(&self, u: &Vector3<f64>) -> f64 {
        u.dot(&self.start.coords).max(u.dot(&self.end.coords))
    }
}

/// The interior stationary point of the squared distance, when the segments are not
/// parallel and it lies in the unit square.
fn stationary_pair(a: &Segment3, b: &Segment3) -> Option<(Point3<f64>, Point3<f64>)> {
    let (da, db, r) = (a.end - a.start, b.end - b.start, a.start - b.start);
    let (aa, bb, ab) = (da.norm_squared(), db.norm_squared(), da.dot(&db));
    let (ar, br) = (da.dot(&r), db.dot(&r));
    // Normal equations: aa s - ab t = -ar, ab s - bb t = -br.
    let det = aa * bb - ab * ab;
    if det.is_nan() || det <= 0.0 {
        return None;
    }
    let s = (ab * br - bb * ar) / det;
    let t = (aa * br - ab * ar) / det;
    ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)).then(|| (a.at(s), b.at(t)))
}

/// Closest points of `a` and `b` and a certified lower bound of their distance (module doc).
pub fn segment_distance(a: &Segment3, b: &Segment3) -> SegmentDistance {
    let mut best = (a.start, b.nearest(&a.start));
    let mut best_d2 = (best.1 - best.0).norm_squared();
    let mut consider = |p: Point3<f64>, q: Point3<f64>| {
        let d2 = (q - p).norm_squared();
        if d2 < best_d2 {
            (best, best_d2) = ((p, q), d2);
        }
    };
    consider(a.end, b.nearest(&a.end));
    consider(a.nearest(&b.start), b.start);
    consider(a.nearest(&b.end), b.end);
    if let Some((p, q)) = stationary_pair(a, b) {
        consider(p, q);
    }
    let (point_a, point_b) = best;
    let value = (point_b - point_a).norm();
    let lower = if value > 0.0 {
        let u = (point_b - point_a) / value;
        // B's least extent along `u` minus A's greatest.
        (-b.support(&-u) - a.support(&u)).clamp(0.0, value)
    } else {
        0.0
    };
    SegmentDistance {
        value,
        lower,
        point_a,
        point_b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;

    fn random_segment(rng: &mut Lcg, scale: f64) -> Segment3 {
        let mut p = || Point3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5) * scale;
        Segment3 {
            start: p(),
            end: p(),
        }
    }

    /// Dense sampling of both segments: the value is never above a sampled pair's distance
    /// by more than rounding, comes within the sampling's resolution of the minimum, and the
    /// lower bound is below every sampled distance.
    #[test]
    fn matches_dense_sampling() {
        let mut rng = Lcg(0x5e6);
        for case in 0..400 {
            let a = random_segment(&mut rng, 2.0);
            let mut b = random_segment(&mut rng, 2.0);
            if case % 4 == 1 {
                // Nearly parallel, overlapping in extent.
                let tilt = Vector3::new(rng.f(), rng.f(), rng.f()) * 1e-9;
                let shift = Vector3::new(rng.f(), rng.f(), rng.f()) * 0.3;
                b = Segment3 {
                    start: a.start + shift,
                    end: a.end + shift + tilt,
                };
            } else if case % 4 == 2 {
                // A point.
                b.end = b.start;
            }
            let d = segment_distance(&a, &b);
            assert!(d.lower <= d.value);
            assert!(((d.point_b - d.point_a).norm() - d.value).abs() <= 1e-15);
            let n = 400;
            let mut sampled = f64::INFINITY;
            for i in 0..=n {
                let p = a.at(i as f64 / n as f64);
                for j in 0..=n {
                    let q = b.at(j as f64 / n as f64);
                    sampled = sampled.min((q - p).norm());
                }
            }
            assert!(
                d.value <= sampled + 1e-14,
                "case {case}: {} > {sampled}",
                d.value
            );
            assert!(d.lower <= sampled + 1e-14, "case {case}");
            // Grid spacing <= 3.5 / 400 on each segment.
            assert!(
                sampled - d.value <= 0.0175,
                "case {case}: {} vs {sampled}",
                d.value
            );
            // The slab bound is tight at the closest points.
            assert!(d.value - d.lower <= 1e-12, "case {case}: {d:?}");
        }
    }

    /// Crossing segments are 0 apart; parallel ones their offset; collinear disjoint ones
    /// their gap.
    #[test]
    fn exact_cases() {
        let seg = |a: [f64; 3], b: [f64; 3]| Segment3 {
            start: Point3::from(a),
            end: Point3::from(b),
        };
        let d = segment_distance(
            &seg([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            &seg([0.0, -1.0, 0.0], [0.0, 1.0, 0.0]),
        );
        assert_eq!((d.value, d.lower), (0.0, 0.0));
        let d = segment_distance(
            &seg([0.0, 0.0, 0.0], [0.0, 0.0, 2.0]),
            &seg([0.3, 0.4, 1.0], [0.3, 0.4, 5.0]),
        );
        assert!(
            (d.value - 0.5).abs() < 1e-15 && (d.lower - 0.5).abs() < 1e-15,
            "{d:?}"
        );
        let d = segment_distance(
            &seg([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            &seg([0.0, 0.0, 1.25], [0.0, 0.0, 3.0]),
        );
        assert_eq!((d.value, d.lower), (0.25, 0.25));
    }
}

//! Cheap geometric checks of a profile beyond what [`Profile::new`] validates: a dense
//! polyline self-intersection test and the smallest rho away from the ends.
//!
//! These are sampling checks, not proofs: they catch crossings and pinches larger than the
//! chord error of the sampling (about L * h^2 / 8 for a span of length L and curvature h).

use nalgebra::Point2;

use super::sampling::sample_profile;
use crate::profile::{Profile, ProfileKind};

/// First pair of non-adjacent polyline segments of the sampled profile that touch or cross,
/// as the two segment indices along the profile, or None. Segments are swept in order of
/// their lowest z, so the cost is close to linear for profiles without many overlaps in z.
pub fn polyline_self_intersection(
    profile: &Profile,
    samples_per_span: usize,
) -> Option<(usize, usize)> {
    let points = sample_profile(profile, samples_per_span);
    let closed = profile.kind() == ProfileKind::Closed;
    first_crossing(&points, closed)
}

/// Smallest rho of the sampled profile, leaving out the samples within `end_fraction` of the
/// sample count at each end of an open profile (the ends lie on the axis by definition).
pub fn min_interior_rho(profile: &Profile, samples_per_span: usize, end_fraction: f64) -> f64 {
    let points = sample_profile(profile, samples_per_span);
    let skip = if profile.kind() == ProfileKind::OpenOnAxis {
        ((points.len() as f64 * end_fraction).ceil() as usize).max(1)
    } else {
        0
    };
    points
        .iter()
        .skip(skip)
        .take(points.len().saturating_sub(2 * skip))
        .map(|p| p.x)
        .fold(f64::INFINITY, f64::min)
}

/// Sweep-and-prune search for touching or crossing non-adjacent segments of a polyline.
fn first_crossing(points: &[Point2<f64>], closed: bool) -> Option<(usize, usize)> {
    let n = points.len().checked_sub(1)?;
    let mut order: Vec<usize> = (0..n).collect();
    let z_range = |i: usize| {
        let (a, b) = (points[i].y, points[i + 1].y);
        (a.min(b), a.max(b))
    };
    order.sort_by(|&i, &j| z_range(i).0.total_cmp(&z_range(j).0));
    for (k, &i) in order.iter().enumerate() {
        let top = z_range(i).1;
        for &j in &order[k + 1..] {
            if z_range(j).0 > top {
                break;
            }
            let (lo, hi) = (i.min(j), i.max(j));
            let adjacent = hi == lo + 1 || (closed && lo == 0 && hi == n - 1);
            if !adjacent && segments_touch(points[i], points[i + 1], points[j], points[j + 1]) {
                return Some((lo, hi));
            }
        }
    }
    None
}

/// Twice the signed area of the triangle (a, b, c).
fn orient(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> f64 {
    (b - a).perp(&(c - a))
}

/// Whether c lies in the bounding box of the segment a-b (used for collinear cases).
fn in_box(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> bool {
    c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
}

/// Whether the closed segments p1-p2 and q1-q2 share a point.
fn segments_touch(p1: Point2<f64>, p2: Point2<f64>, q1: Point2<f64>, q2: Point2<f64>) -> bool {
    let d1 = orient(q1, q2, p1);
    let d2 = orient(q1, q2, p2);
    let d3 = orient(p1, p2, q1);
    let d4 = orient(p1, p2, q2);
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    (d1 == 0.0 && in_box(q1, q2, p1))
        || (d2 == 0.0 && in_box(q1, q2, p2))
        || (d3 == 0.0 && in_box(p1, p2, q1))
        || (d4 == 0.0 && in_box(p1, p2, q2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detects_a_figure_eight_and_accepts_a_square() {
        let p = |x: f64, y: f64| Point2::new(x, y);
        let square = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
            p(0.0, 0.0),
        ];
        assert_eq!(first_crossing(&square, true), None);
        let bow = [
            p(0.0, 0.0),
            p(1.0, 1.0),
            p(1.0, 0.0),
            p(0.0, 1.0),
            p(0.0, 0.0),
        ];
        assert_eq!(first_crossing(&bow, true), Some((0, 2)));
        // An open chain whose last segment comes back to touch its first one.
        let hook = [p(0.0, 0.0), p(2.0, 0.0), p(2.0, 1.0), p(1.0, 0.0)];
        assert_eq!(first_crossing(&hook, false), Some((0, 2)));
    }
}

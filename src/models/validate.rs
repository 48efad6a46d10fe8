//! Cheap geometric checks of a profile beyond what [`Profile::new`] validates: a dense
//! polyline self-intersection test, the smallest rho away from the ends, and the Hausdorff
//! distance between two profiles by dense sampling.
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

/// Two-sided Hausdorff distance between two profiles, measured by dense sampling of both: the
/// larger of the two one-sided distances from the samples of one profile (`samples_per_span`
/// per knot span) to the polyline through the samples of the other. The polylines are within
/// their chord error of the curves, and the one-sided distances are maxima over the samples,
/// so the result is the true distance up to the chord error and the sample spacing.
pub fn sampled_hausdorff(a: &Profile, b: &Profile, samples_per_span: usize) -> f64 {
    let (pa, pb) = (
        sample_profile(a, samples_per_span),
        sample_profile(b, samples_per_span),
    );
    one_sided_distance(&pa, &pb).max(one_sided_distance(&pb, &pa))
}

/// Largest distance from a point of `points` to the polyline `line`. Segments are sorted by
/// their lowest z; each point starts from the segments nearest to the previous point's
/// closest segment (consecutive samples have nearby closest points) and then scans only the
/// segments whose z-range can come closer than the best distance found.
fn one_sided_distance(points: &[Point2<f64>], line: &[Point2<f64>]) -> f64 {
    let Some(n) = line.len().checked_sub(1).filter(|&n| n > 0) else {
        return f64::INFINITY;
    };
    let z_range = |i: usize| (line[i].y.min(line[i + 1].y), line[i].y.max(line[i + 1].y));
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| z_range(i).0.total_cmp(&z_range(j).0));
    let lows: Vec<f64> = order.iter().map(|&i| z_range(i).0).collect();
    let tallest = (0..n)
        .map(|i| z_range(i).1 - z_range(i).0)
        .fold(0.0, f64::max);
    let to_segment = |p: Point2<f64>, i: usize| {
        let (a, d) = (line[i], line[i + 1] - line[i]);
        let s = ((p - a).dot(&d) / d.norm_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (p - (a + d * s)).norm()
    };
    let mut hint: usize = 0;
    let mut worst: f64 = 0.0;
    for &p in points {
        let (mut best, mut best_index) = (f64::INFINITY, hint);
        for i in hint.saturating_sub(2)..(hint + 3).min(n) {
            let d = to_segment(p, i);
            if d < best {
                (best, best_index) = (d, i);
            }
        }
        let first = lows.partition_point(|&lo| lo < p.y - best - tallest);
        for (&lo, &i) in lows[first..].iter().zip(&order[first..]) {
            if lo > p.y + best {
                break;
            }
            let d = to_segment(p, i);
            if d < best {
                (best, best_index) = (d, i);
            }
        }
        hint = best_index;
        worst = worst.max(best);
    }
    worst
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

    #[test]
    fn one_sided_distance_is_the_brute_force_maximum() {
        let p = |x: f64, y: f64| Point2::new(x, y);
        // A zigzag polyline and points scattered around it, in no particular order.
        let line: Vec<Point2<f64>> = (0..40)
            .map(|i| p(0.3 + 0.2 * ((i * 7 % 5) as f64), 0.05 * i as f64))
            .collect();
        let points: Vec<Point2<f64>> = (0..200)
            .map(|i| {
                p(
                    ((i * 37) % 101) as f64 / 100.0,
                    ((i * 53) % 97) as f64 / 48.0,
                )
            })
            .collect();
        let brute = points
            .iter()
            .map(|&q| {
                line.windows(2)
                    .map(|w| {
                        let d = w[1] - w[0];
                        let s = ((q - w[0]).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                        (q - (w[0] + d * s)).norm()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        assert_eq!(one_sided_distance(&points, &line), brute);
    }
}

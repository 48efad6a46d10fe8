//! Segments replacing one circular arc, each with a certified two-sided Hausdorff deviation
//! from the piece of the arc it stands for.
//!
//! **Lemma.** Let an arc of radius `R` about `c` be cut by polar angle into consecutive pieces
//! of sweep `< pi`, and let segment `sigma` join points on the rays of a piece's end angles,
//! at distances `r0, r1 >= R cos(sweep / 2)` from `c`. Every ray from `c` inside the piece's
//! angular range meets the segment once and the arc once, and every point of either set is on
//! such a ray; so the two-sided Hausdorff distance is at most the largest `| |x - c| - R |`
//! over the segment's points `x`. Along the segment `|x - c|` is convex (at most
//! `max(r0, r1)`), and the segment lies radially outside the inscribed chord between the rays
//! when `r0, r1 >= R`, whose distance from `c` is at least `R cos(sweep / 2)`. Hence:
//! - inscribed chord (`r0 = r1 = R`): deviation `R (1 - cos(sweep/2)) = 2 R sin^2(sweep/4)`;
//! - chord of the scaled polygon (`r0 = r1 = kappa R`, `kappa = 2 / (1 + cos(sweep/2))`): the
//!   distance from `c` ranges over `[kappa R cos(sweep/2), kappa R]`, deviation
//!   `R (kappa - 1) = R tan^2(sweep/4)` both ways, about half the sagitta;
//! - end segment from an arc end (`r0 = R`) to a scaled vertex (`r1 = kappa R`): deviation
//!   `max(R (kappa - 1), 2 R sin^2(sweep/4))`.
//!
//! A [`VertexPlacement::Balanced`] arc keeps its end points on the arc (they are shared with
//! the neighbouring arcs, possibly of another radius) and scales its interior vertices: two
//! inscribed end segments of sweep `delta_e` around `m` scaled segments of sweep `delta`.

use nalgebra::{Point2, Vector2};

use super::VertexPlacement;
use crate::biarc::Arc;

/// Largest sweep of one segment's arc piece (radians). The lemma needs `< pi`; a quarter turn
/// keeps every segment well inside it even when the tolerance is as large as the radius.
pub const MAX_SEGMENT_SWEEP: f64 = std::f64::consts::FRAC_PI_2;

/// Largest sweep of an inscribed chord with deviation `<= tol` on radius `r`:
/// `2 r sin^2(delta/4) <= tol`.
fn inscribed_sweep(r: f64, tol: f64) -> f64 {
    let s = (0.5 * tol / r).min(1.0).sqrt();
    (4.0 * s.asin()).min(MAX_SEGMENT_SWEEP)
}

/// Largest sweep of a scaled-polygon chord with deviation `<= tol` on radius `r`:
/// `r tan^2(delta/4) <= tol`.
fn scaled_sweep(r: f64, tol: f64) -> f64 {
    (4.0 * (tol / r).sqrt().atan()).min(MAX_SEGMENT_SWEEP)
}

/// `2 r sin^2(delta / 4)`: the sagitta of an arc piece of sweep `delta`, without cancellation.
fn sagitta(r: f64, delta: f64) -> f64 {
    let s = (0.25 * delta).sin();
    2.0 * r * s * s
}

/// Appends the segments replacing `arc` to a polyline that already ends at (or next to)
/// `arc.start`: pushes the vertices after the start (the last one is `arc.end`) to `points`
/// and one deviation per segment to `deviation`, each at most `tol` (> 0).
///
/// `max_edge` (> `tol`) caps the segment lengths: the arc is first cut into pieces short
/// enough that no segment of a piece exceeds it (a segment of a piece of length `l` is at
/// most `l (1 + tol / r) + tol` long), then each piece is cut as above.
pub fn push_arc_segments(
    arc: &Arc,
    tol: f64,
    placement: VertexPlacement,
    max_edge: Option<f64>,
    points: &mut Vec<Point2<f64>>,
    deviation: &mut Vec<f64>,
) {
    if arc.is_segment() {
        let pieces = max_edge.map_or(1, |m| (arc.length / m).ceil().max(1.0) as usize);
        for k in 1..=pieces {
            let p = if k == pieces {
                arc.end
            } else {
                arc.start + (arc.end - arc.start) * (k as f64 / pieces as f64)
            };
            points.push(p);
            deviation.push(0.0);
        }
        return;
    }
    let r = arc.radius();
    let pieces = max_edge.map_or(1, |m| {
        ((arc.length * (1.0 + tol / r)) / (m - tol)).ceil().max(1.0) as usize
    });
    let piece_len = arc.length / pieces as f64;
    for k in 0..pieces {
        let s0 = piece_len * k as f64;
        let s1 = if k + 1 == pieces {
            arc.length
        } else {
            piece_len * (k + 1) as f64
        };
        match placement {
            VertexPlacement::OnSurface => inscribed_piece(arc, s0, s1, tol, points, deviation),
            VertexPlacement::Balanced => balanced_piece(arc, s0, s1, tol, points, deviation),
        }
    }
    // The last vertex is the arc's own end point, not a re-evaluation of it.
    if let Some(last) = points.last_mut() {
        *last = arc.end;
    }
}

/// Sweep of the arc piece between arc lengths `s0 < s1`.
fn piece_sweep(arc: &Arc, s0: f64, s1: f64) -> f64 {
    arc.curvature.abs() * (s1 - s0)
}

/// Inscribed chords of equal sweep over `[s0, s1]`.
fn inscribed_piece(
    arc: &Arc,
    s0: f64,
    s1: f64,
    tol: f64,
    points: &mut Vec<Point2<f64>>,
    deviation: &mut Vec<f64>,
) {
    let r = arc.radius();
    let sweep = piece_sweep(arc, s0, s1);
    let m = (sweep / inscribed_sweep(r, tol)).ceil().max(1.0) as usize;
    let dev = sagitta(r, sweep / m as f64);
    for k in 1..=m {
        points.push(arc.point_at(s0 + (s1 - s0) * k as f64 / m as f64));
        deviation.push(dev);
    }
}

/// Two inscribed end segments and `m` scaled interior segments over `[s0, s1]` (module doc).
fn balanced_piece(
    arc: &Arc,
    s0: f64,
    s1: f64,
    tol: f64,
    points: &mut Vec<Point2<f64>>,
    deviation: &mut Vec<f64>,
) {
    let r = arc.radius();
    let sweep = piece_sweep(arc, s0, s1);
    let whole = sagitta(r, sweep);
    if whole <= tol && sweep <= MAX_SEGMENT_SWEEP {
        points.push(arc.point_at(s1));
        deviation.push(whole);
        return;
    }
    let (de_max, di_max) = (inscribed_sweep(r, tol), scaled_sweep(r, tol));
    let m = ((sweep - 2.0 * de_max).max(0.0) / di_max).ceil() as usize;
    if m == 0 {
        // Two inscribed chords of half the sweep (each within the end-segment limit).
        let dev = sagitta(r, 0.5 * sweep);
        points.push(arc.point_at(0.5 * (s0 + s1)));
        points.push(arc.point_at(s1));
        deviation.extend([dev, dev]);
        return;
    }
    // Shrink both sweeps by the same factor so that they fill the piece exactly.
    let lambda = sweep / (2.0 * de_max + m as f64 * di_max);
    let (de, di) = (lambda * de_max, lambda * di_max);
    let q = (0.25 * di).tan();
    let offset = r * q * q; // r (kappa - 1)
    let end_dev = offset.max(sagitta(r, de));
    let len_per_sweep = (s1 - s0) / sweep;
    for k in 0..=m {
        let s = s0 + len_per_sweep * (de + di * k as f64);
        points.push(scaled_point(arc, s.min(s1), offset));
        deviation.push(if k == 0 { end_dev } else { offset });
    }
    points.push(arc.point_at(s1));
    deviation.push(end_dev);
}

/// The point of `arc` at arc length `s`, moved `offset` away from the arc's centre (radially
/// outwards), computed without the (possibly far) centre: the unit vector from the point to
/// the centre is the left normal of the tangent times the sign of the curvature.
fn scaled_point(arc: &Arc, s: f64, offset: f64) -> Point2<f64> {
    let p = arc.point_at(s);
    let (sn, cs) = (arc.curvature * s).sin_cos();
    let t = arc.start_tangent;
    let tangent = Vector2::new(cs * t.x - sn * t.y, sn * t.x + cs * t.y);
    let to_centre = Vector2::new(-tangent.y, tangent.x) * arc.curvature.signum();
    p - to_centre * offset
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nearest::NearestPoint;
    use std::f64::consts::PI;

    /// Dense two-sided check of the lemma: every segment point is within its deviation of the
    /// arc, and every arc point within the polyline's deviation of the polyline.
    fn check(arc: &Arc, tol: f64, placement: VertexPlacement, max_edge: Option<f64>) -> usize {
        let mut pts = vec![arc.start];
        let mut dev = Vec::new();
        push_arc_segments(arc, tol, placement, max_edge, &mut pts, &mut dev);
        assert_eq!(pts.len(), dev.len() + 1);
        assert_eq!(*pts.last().unwrap(), arc.end);
        let worst = dev.iter().cloned().fold(0.0, f64::max);
        assert!(worst <= tol * (1.0 + 1e-12), "{worst} > {tol}");
        let slack = 1e-13;
        for (w, d) in pts.windows(2).zip(&dev) {
            if let Some(m) = max_edge {
                assert!(
                    (w[1] - w[0]).norm() <= m,
                    "edge {} > {m}",
                    (w[1] - w[0]).norm()
                );
            }
            for i in 0..=50 {
                let x = w[0] + (w[1] - w[0]) * (i as f64 / 50.0);
                let dist = arc.distance_to(x);
                assert!(dist <= d + slack, "segment point {dist} > {d}");
            }
        }
        for i in 0..=4000 {
            let y = arc.point_at(arc.length * i as f64 / 4000.0);
            let dist = pts
                .windows(2)
                .map(|w| seg_dist(y, w[0], w[1]))
                .fold(f64::INFINITY, f64::min);
            assert!(dist <= worst + slack, "arc point {dist} > {worst}");
        }
        dev.len()
    }

    fn seg_dist(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
        let d = b - a;
        let u = ((p - a).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
        (p - (a + d * u)).norm()
    }

    fn arc(sweep: f64, r: f64) -> Arc {
        let (s, c) = sweep.sin_cos();
        let end = Point2::new(1.0 + r * (s), 0.2 + r * (1.0 - c));
        Arc::from_point_tangent_point(Point2::new(1.0, 0.2), Vector2::new(1.0, 0.0), end).unwrap()
    }

    #[test]
    fn both_placements_meet_their_deviation() {
        for &(sweep, r) in &[(PI / 2.0, 1.0), (-1.2, 0.3), (0.01, 50.0), (3.0, 0.6)] {
            for &tol in &[1e-2, 1e-3, 1e-5] {
                let a = arc(sweep, r);
                let on = check(&a, tol, VertexPlacement::OnSurface, None);
                let bal = check(&a, tol, VertexPlacement::Balanced, None);
                assert!(bal <= on, "balanced {bal} > inscribed {on}");
                check(&a, tol, VertexPlacement::Balanced, Some(0.05));
                check(&a, tol, VertexPlacement::OnSurface, Some(0.05));
            }
        }
    }

    #[test]
    fn balanced_needs_about_one_over_sqrt2_of_the_chords() {
        let a = arc(3.0, 1.0);
        let on = check(&a, 1e-6, VertexPlacement::OnSurface, None) as f64;
        let bal = check(&a, 1e-6, VertexPlacement::Balanced, None) as f64;
        assert!((bal / on - 0.5f64.sqrt()).abs() < 0.02, "{bal} / {on}");
    }

    #[test]
    fn straight_segments_are_exact_and_capped() {
        let a = Arc::from_point_tangent_point(
            Point2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Point2::new(1.0, 0.0),
        )
        .unwrap();
        assert_eq!(check(&a, 1e-3, VertexPlacement::Balanced, None), 1);
        assert_eq!(check(&a, 1e-3, VertexPlacement::Balanced, Some(0.3)), 4);
    }
}

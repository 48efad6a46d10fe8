//! Planar circular arcs in the (rho, z) half-plane with signed curvature; `k = 0` is a segment
//! (paper section 4.1: the arcs of a biarc, revolved into toroidal patches).

use crate::nearest::NearestPoint;
use crate::num::cross2;
use nalgebra::{Point2, Vector2};

/// Below this absolute sweep (radians) an arc is stored as an exact segment (`k = 0`).
///
/// Snapping moves no point by more than the sagitta `length * |sweep| / 8 <= length * 1.25e-15`,
/// which is below the floating-point slack added to every bound (see `bound::BOUND_ULP_SLACK`),
/// and changes the end tangent by at most `1e-14` rad, far below the 1e-12 G1 requirement.
pub const STRAIGHT_SWEEP: f64 = 1e-14;

/// Arcs whose radius exceeds this multiple of the profile size are revolved as their chords
/// (see [`Arc::flattening_error`]).
///
/// Why: a query patch stores an arc by its centre and radius (paper 3.1). Evaluating
/// `centre + r (cos phi, sin phi)` loses about `eps_mach * (|centre| + r)` absolutely, and the
/// circle kernels see a major circle of radius `~r`: for the near-straight arcs a biarc fit
/// gives on straight spans (radii of 1e11 and more on the deforming model), both put patch
/// points 1e-5 away from the curve. Above `1e4 * size` the chord is the better-conditioned
/// primitive, and its distance to the arc (the sagitta) is counted in the node's bound.
pub const FLAT_RADIUS_REL: f64 = 1e4;

/// Above this absolute sweep the point-to-arc distance uses polar angles around the centre;
/// below it, the centre may be far away and half-plane tests around the end normals are used
/// (they stay exact as `k -> 0`). Any value in (0, pi) is correct; 0.5 keeps both branches
/// well conditioned.
const POLAR_SWEEP: f64 = 0.5;

/// A circular arc (or segment when `curvature == 0`) from `start` to `end`.
///
/// Orientation: the arc runs from `start` to `end`; positive curvature turns counter-clockwise
/// (centre on the left of the direction of travel), negative clockwise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// First point of the arc.
    pub start: Point2<f64>,
    /// Last point of the arc.
    pub end: Point2<f64>,
    /// Unit tangent at `start` (direction of travel).
    pub start_tangent: Vector2<f64>,
    /// Signed curvature `k = 1 / signed radius`; `0` for a segment.
    pub curvature: f64,
    /// Signed turning angle from `start` to `end` (`curvature * length`).
    pub sweep: f64,
    /// Arc length.
    pub length: f64,
}

/// sin(x)/x, stable at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// Left normal of a vector.
fn perp(v: Vector2<f64>) -> Vector2<f64> {
    Vector2::new(-v.y, v.x)
}

impl Arc {
    /// The arc that starts at `start` with unit tangent `tangent` and ends at `end`.
    ///
    /// Uses the chord-frame angle form (notes `biarcs.md` section 1.2b): if `theta` is the angle
    /// from the chord to the tangent, the sweep is `-2 theta`, the curvature `-2 sin(theta) / L`
    /// and the length `L theta / sin(theta)`, all smooth as `theta -> 0`. Returns `None` when
    /// `start == end` or the tangent points straight back along the chord (`|theta| = pi`: no
    /// minor arc exists).
    pub fn from_point_tangent_point(
        start: Point2<f64>,
        tangent: Vector2<f64>,
        end: Point2<f64>,
    ) -> Option<Arc> {
        let chord = end - start;
        let chord_len = chord.norm();
        let t_len = tangent.norm();
        if chord_len == 0.0 || t_len == 0.0 || !chord_len.is_finite() || !t_len.is_finite() {
            return None;
        }
        let t = tangent / t_len;
        let e = chord / chord_len;
        let theta = cross2(e, t).atan2(e.dot(&t));
        if theta.abs() >= std::f64::consts::PI * (1.0 - 1e-12) {
            return None;
        }
        let mut sweep = -2.0 * theta;
        let mut curvature = -2.0 * theta.sin() / chord_len;
        if sweep.abs() < STRAIGHT_SWEEP {
            sweep = 0.0;
            curvature = 0.0;
        }
        let length = chord_len / sinc(theta);
        Some(Arc {
            start,
            end,
            start_tangent: t,
            curvature,
            sweep,
            length,
        })
    }

    /// The same arc traversed from `end` to `start`.
    pub fn reversed(&self) -> Arc {
        Arc {
            start: self.end,
            end: self.start,
            start_tangent: -self.end_tangent(),
            curvature: -self.curvature,
            sweep: -self.sweep,
            length: self.length,
        }
    }

    /// True for a segment (`curvature == 0`, infinite radius).
    pub fn is_segment(&self) -> bool {
        self.curvature == 0.0
    }

    /// Signed radius `1 / curvature` (`+-inf` for a segment).
    pub fn signed_radius(&self) -> f64 {
        1.0 / self.curvature
    }

    /// Unsigned radius (`inf` for a segment).
    pub fn radius(&self) -> f64 {
        1.0 / self.curvature.abs()
    }

    /// Centre of the supporting circle; `None` for a segment.
    pub fn center(&self) -> Option<Point2<f64>> {
        (!self.is_segment()).then(|| self.start + perp(self.start_tangent) / self.curvature)
    }

    /// Polar angles `(phi_start, phi_end)` of `start` and `end` around the centre, with
    /// `phi_end - phi_start == sweep`; `None` for a segment.
    pub fn angle_range(&self) -> Option<(f64, f64)> {
        let c = self.center()?;
        let d = self.start - c;
        let phi0 = d.y.atan2(d.x);
        Some((phi0, phi0 + self.sweep))
    }

    /// Unit tangent at `end`.
    pub fn end_tangent(&self) -> Vector2<f64> {
        let (s, c) = self.sweep.sin_cos();
        let t = self.start_tangent;
        Vector2::new(c * t.x - s * t.y, s * t.x + c * t.y)
    }

    /// Point at arc length `s` from `start` (0 <= s <= length), stable for `k -> 0`.
    pub fn point_at(&self, s: f64) -> Point2<f64> {
        let x = self.curvature * s;
        let along = s * sinc(x);
        let half = 0.5 * x;
        let across = s * half.sin() * sinc(half);
        self.start + self.start_tangent * along + perp(self.start_tangent) * across
    }

    /// Midpoint of the arc.
    pub fn midpoint(&self) -> Point2<f64> {
        self.point_at(0.5 * self.length)
    }

    /// Largest distance between the arc and its chord: `r (1 - cos(sweep / 2))`.
    pub fn sagitta(&self) -> f64 {
        let half = 0.25 * self.sweep;
        // r (1 - cos(2 half)) = 2 r sin^2(half) = length/|sweep| * 2 sin^2(half)
        0.5 * self.length * sinc(half) * half.sin().abs()
    }

    /// Whether the arc is revolved as its chord: a segment, or radius above `flat_radius`.
    pub fn is_flat(&self, flat_radius: f64) -> bool {
        self.is_segment() || self.radius() > flat_radius
    }

    /// The arc as revolved by the query: its chord when it is flat for `flat_radius`
    /// ([`FLAT_RADIUS_REL`]), else itself.
    pub fn flattened(&self, flat_radius: f64) -> Arc {
        if self.is_segment() || !self.is_flat(flat_radius) {
            return *self;
        }
        let chord = self.end - self.start;
        let length = chord.norm();
        Arc {
            start: self.start,
            end: self.end,
            start_tangent: chord / length,
            curvature: 0.0,
            sweep: 0.0,
            length,
        }
    }

    /// How far the arc's chord is from the arc when the arc counts as flat for `flat_radius`
    /// (its sagitta, the two-sided Hausdorff distance between arc and chord), else 0.
    pub fn flattening_error(&self, flat_radius: f64) -> f64 {
        if !self.is_segment() && self.radius() > flat_radius {
            self.sagitta()
        } else {
            0.0
        }
    }

    /// Whether the foot of `p` on the arc's circle lies on the arc (else an end of the arc is
    /// its nearest point). Not for segments.
    fn foot_on_arc(&self, p: Point2<f64>) -> bool {
        if self.sweep.abs() > POLAR_SWEEP {
            let c = self.center().unwrap_or(self.start);
            let d0 = self.start - c;
            let dp = p - c;
            let rel = cross2(d0, dp).atan2(d0.dot(&dp));
            let rel = if self.sweep > 0.0 { rel } else { -rel };
            let rel = if rel < 0.0 {
                rel + 2.0 * std::f64::consts::PI
            } else {
                rel
            };
            rel <= self.sweep.abs()
        } else {
            // Between the normal lines at the two ends and on the arc's side of the centre.
            let mid = self.midpoint();
            let mid_t = {
                let (s, c) = (0.5 * self.sweep).sin_cos();
                let t = self.start_tangent;
                Vector2::new(c * t.x - s * t.y, s * t.x + c * t.y)
            };
            // Unit vector from the centre to the midpoint.
            let k = self.curvature;
            let u = -perp(mid_t) * k.signum();
            (p - self.start).dot(&self.start_tangent) >= 0.0
                && (p - self.end).dot(&self.end_tangent()) <= 0.0
                && k.abs() * (p - mid).dot(&u) + 1.0 > 0.0
        }
    }

    /// The signed distance from `p` to the arc's circle, written without the centre (exact
    /// as the curvature goes to 0): `pow(p) / (|p - c| + r)` with `a = p - start` and `n`
    /// the unit normal at `start`, and the vector `n - k a` along the line from `p` to the
    /// centre (length `|k| |p - c|`); `p` plus the offset times that line's unit vector is
    /// the foot on the circle, for either sign of `k`.
    fn circle_offset(&self, p: Point2<f64>) -> (f64, Vector2<f64>) {
        let k = self.curvature;
        let n = perp(self.start_tangent);
        let a = p - self.start;
        let to_centre = n - a * k;
        (
            (k * a.norm_squared() - 2.0 * a.dot(&n)) / (to_centre.norm() + 1.0),
            to_centre,
        )
    }
}

impl NearestPoint for Arc {
    fn nearest(&self, p: Point2<f64>) -> (f64, Point2<f64>) {
        if self.is_segment() {
            let d = self.end - self.start;
            let u = ((p - self.start).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
            let foot = self.start + d * u;
            return ((p - foot).norm(), foot);
        }
        let (da, db) = ((p - self.start).norm(), (p - self.end).norm());
        let nearer_end = if da <= db {
            (da, self.start)
        } else {
            (db, self.end)
        };
        if !self.foot_on_arc(p) {
            return nearer_end;
        }
        // The foot is `p` moved by the signed offset along the unit vector towards the centre.
        let (offset, to_centre) = self.circle_offset(p);
        let len = to_centre.norm();
        if offset.abs() > nearer_end.0 || len == 0.0 {
            return nearer_end;
        }
        (offset.abs(), p + to_centre * (offset / len))
    }

    /// Euclidean distance from `p` to the arc (the closed point set), without the foot.
    fn distance_to(&self, p: Point2<f64>) -> f64 {
        if self.is_segment() {
            return self.nearest(p).0;
        }
        let to_ends = (p - self.start).norm().min((p - self.end).norm());
        if !self.foot_on_arc(p) {
            return to_ends;
        }
        self.circle_offset(p).0.abs().min(to_ends)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn quarter_circle() {
        let a = Arc::from_point_tangent_point(
            Point2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Point2::new(0.0, 1.0),
        )
        .unwrap();
        assert!((a.curvature - 1.0).abs() < 1e-15, "k = {}", a.curvature);
        assert!((a.sweep - PI / 2.0).abs() < 1e-15);
        assert!((a.length - PI / 2.0).abs() < 1e-15);
        let c = a.center().unwrap();
        assert!(c.coords.norm() < 1e-15);
        let (p0, p1) = a.angle_range().unwrap();
        assert!(p0.abs() < 1e-15 && (p1 - PI / 2.0).abs() < 1e-15);
        let m = a.midpoint();
        assert!((m.coords.norm() - 1.0).abs() < 1e-15);
        assert!((a.end_tangent() - Vector2::new(-1.0, 0.0)).norm() < 1e-15);
        assert!((a.sagitta() - (1.0 - (PI / 4.0).cos())).abs() < 1e-15);
        // distances: outside point radially, point behind start, centre
        assert!((a.distance_to(Point2::new(2.0, 2.0)) - (8f64.sqrt() - 1.0)).abs() < 1e-14);
        assert!((a.distance_to(Point2::new(1.0, -1.0)) - 1.0).abs() < 1e-15);
        assert!((a.distance_to(Point2::origin()) - 1.0).abs() < 1e-15);
        let r = a.reversed();
        assert!((r.center().unwrap() - c).norm() < 1e-15);
        assert!((r.end_tangent() + a.start_tangent).norm() < 1e-15);
    }

    #[test]
    fn segment_is_exact() {
        let a = Arc::from_point_tangent_point(
            Point2::new(0.0, 0.0),
            Vector2::new(3.0, 0.0),
            Point2::new(2.0, 0.0),
        )
        .unwrap();
        assert!(a.is_segment() && a.center().is_none() && a.radius().is_infinite());
        assert_eq!(a.length, 2.0);
        assert_eq!(a.point_at(1.0), Point2::new(1.0, 0.0));
        assert!((a.distance_to(Point2::new(1.0, 0.5)) - 0.5).abs() < 1e-15);
        assert!((a.distance_to(Point2::new(3.0, 0.0)) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn degenerate_inputs_are_rejected() {
        let p = Point2::new(1.0, 1.0);
        assert!(Arc::from_point_tangent_point(p, Vector2::new(1.0, 0.0), p).is_none());
        assert!(
            Arc::from_point_tangent_point(p, Vector2::new(-1.0, 0.0), Point2::new(2.0, 1.0))
                .is_none()
        );
    }

    #[test]
    fn nearly_straight_distance_matches_dense_sampling() {
        // radius 1e6: the centre is far away; compare with the analytic arc sampled densely.
        for &theta in &[1e-7f64, -3e-4, 0.2, -0.9, 1.4] {
            let t = Vector2::new(theta.cos(), theta.sin());
            let a = Arc::from_point_tangent_point(Point2::new(0.3, 0.1), t, Point2::new(1.3, 0.1))
                .unwrap();
            for &p in &[
                Point2::new(0.8, 0.4),
                Point2::new(0.8, -0.3),
                Point2::new(-0.5, 0.2),
                Point2::new(1.9, 0.0),
            ] {
                let sampled = (0..=20000)
                    .map(|i| (a.point_at(a.length * i as f64 / 20000.0) - p).norm())
                    .fold(f64::INFINITY, f64::min);
                let d = a.distance_to(p);
                assert!(d <= sampled + 1e-14, "theta {theta}: {d} > {sampled}");
                assert!(sampled - d < 1e-7, "theta {theta}: {d} vs {sampled}");
                // The foot: at the same distance, and on the arc (its own distance to the
                // arc is rounding, though the centre is 1e7 away at theta 1e-7).
                let (dn, foot) = a.nearest(p);
                assert_eq!(dn, d, "theta {theta}");
                assert!(
                    ((foot - p).norm() - d).abs() < 1e-14,
                    "theta {theta}: {foot:?}"
                );
                assert!(a.distance_to(foot) < 1e-14, "theta {theta}: {foot:?}");
            }
            assert!((a.point_at(a.length) - a.end).norm() < 1e-14);
        }
    }
}

//! A certified two-sided distance between a rational Bezier piece and a circular arc that needs
//! no spiral property: the circle's implicit equation evaluated on the piece in Bernstein form.
//!
//! The bilens bound ([`super::bound`]) holds only on short spirals, and spiral segmentation
//! ([`super::spiral`]) cannot establish that property where its curvature-derivative test is
//! rounding noise: an exact circle written as a rational Bezier span, or a near-circle whose
//! curvature varies by 1e-11 of itself. There the bilens bound was measured 30 times too small
//! (a quarter circle whose middle control point moved by 1e-11: bound 3.2e-14, sampled error
//! 9.7e-13). This module bounds such pieces directly.
//!
//! **Radial part.** For a piece `C = (X, Y) / W` (`W > 0`) and the circle of centre `c` and
//! radius `R`, with `U = X - c_x W`, `V = Y - c_y W`:
//! `F = U^2 + V^2 - R^2 W^2` is a polynomial of twice the degree and
//! `| |C - c| - R | = |F| / (W^2 (|C - c| + R)) <= max_j |F_j| / (min_i W_i^2 R) = delta_0`, by
//! the convex-hull property of the Bernstein coefficients `F_j` of `F` and `W_i` of `W`; and
//! then, as `|C - c| + R >= 2R - delta_0`, the same with `2R - delta_0` in place of `R`. Forming
//! `U` first keeps the cancellation harmless: the rounding of `F_j` is a few ulps of `R^2 W^2`
//! plus `|U|` times the rounding of `U` (about `eps_mach |c| W`), i.e. `~eps_mach (|c| + R)` in
//! distance, which [`PieceArcDeviation::add_part`] adds with a running error bound.
//!
//! **Angular part.** The arc is the part of the circle between the rays from `c` through its
//! ends, `e_lo` and `e_hi` (sweep below pi). The linear forms `cross(e_lo, C - c)`,
//! `cross(C - c, e_hi)` and `dot(e_mid, C - c)` (`e_mid` the bisector) are `1/W` times
//! polynomials of the piece's degree whose Bernstein coefficients bound them. If the third is
//! positive everywhere, a curve point `q` whose angle lies past an end ray is within 90 degrees
//! of that ray, at distance `b <= sigma` from its line (`sigma` from the first two forms), and
//! then `|q - (c + R e)| <= delta + sigma + 2 sigma^2 / R` for `delta <= R / 2` (its radial
//! offset from the end point is at most `delta + b^2 / |q - c|`). A point whose angle lies
//! within the arc is at its radial distance `<= delta` from the arc.
//!
//! **Two-sided.** The piece runs from the arc's start to its end (to rounding) and stays in the
//! half-plane `dot(e_mid, C - c) > 0`, so its polar angle about `c` moves continuously across
//! the whole sweep without wrapping: every arc point is at radial distance `<= delta` from some
//! curve point, up to the rounding of the end points, which the tree adds as slack.

use super::arc::Arc;
use nalgebra::{Point2, Vector2};

/// Largest arc sweep (radians) the angular part accepts. Any value below pi works (the
/// bisector half-plane must contain the arc with a margin); the arcs of a biarc fitted to a
/// spiral, which turns at most 90 degrees, stay below it.
pub const MAX_SWEEP: f64 = 2.0;

/// Running rounding bound of one Bernstein coefficient of `F` in units of `eps_mach` times the
/// sum of the magnitudes of its terms: each term takes about six roundings (three products, two
/// sums, the binomial weight) and the sum over at most `n + 1` terms `n` more; doubled.
fn product_rounding_ulps(degree: usize) -> f64 {
    2.0 * (degree as f64 + 8.0)
}

/// The circle and end rays of an arc, as the query revolves it (centre form of
/// [`Arc::center`] and [`Arc::angle_range`]).
#[derive(Debug, Clone, Copy)]
pub struct ArcFrame {
    center: Point2<f64>,
    radius: f64,
    /// Unit rays to the ends, ordered counter-clockwise: the arc spans from `lo` to `hi`.
    lo: Vector2<f64>,
    hi: Vector2<f64>,
    /// Unit bisector of the sweep.
    mid: Vector2<f64>,
}

impl ArcFrame {
    /// The frame of `arc`; `None` for a segment or a sweep above [`MAX_SWEEP`].
    pub fn of(arc: &Arc) -> Option<ArcFrame> {
        let (center, (phi_start, phi_end)) = (arc.center()?, arc.angle_range()?);
        if !(arc.sweep.abs() <= MAX_SWEEP && arc.radius().is_finite()) {
            return None;
        }
        let (lo, hi) = if phi_start <= phi_end {
            (phi_start, phi_end)
        } else {
            (phi_end, phi_start)
        };
        let unit = |phi: f64| {
            let (s, c) = phi.sin_cos();
            Vector2::new(c, s)
        };
        Some(ArcFrame {
            center,
            radius: arc.radius(),
            lo: unit(lo),
            hi: unit(hi),
            mid: unit(0.5 * (lo + hi)),
        })
    }

    /// `|c| + R`: the magnitude the arc's own rounding is relative to.
    pub fn scale(&self) -> f64 {
        self.center.coords.amax() + self.radius
    }
}

/// The deviation of one or more curve parts from an arc, accumulated by
/// [`PieceArcDeviation::add_part`]; [`PieceArcDeviation::bound`] turns it into a distance.
#[derive(Debug, Clone, Copy)]
pub struct PieceArcDeviation {
    frame: ArcFrame,
    /// Largest radial offset `| |C - c| - R |` so far.
    radial: f64,
    /// Largest distance past an end ray's line so far.
    past_ends: f64,
    /// False once a part left the bisector half-plane (or had a non-positive weight).
    contained: bool,
}

impl PieceArcDeviation {
    /// No parts yet.
    pub fn new(frame: ArcFrame) -> Self {
        PieceArcDeviation {
            frame,
            radial: 0.0,
            past_ends: 0.0,
            contained: true,
        }
    }

    /// Adds the curve part with homogeneous Bernstein coefficients `h` (`[X, Y, W]`, degree at
    /// most 15): its radial offset and how far it strays past the end rays, both certified
    /// for the polynomial these coefficients define.
    pub fn add_part(&mut self, h: &[[f64; 3]]) {
        const N: usize = super::span::MAX_SPAN_DEGREE + 1;
        let e = f64::EPSILON;
        let n = h.len() - 1;
        let (c, r) = (self.frame.center, self.frame.radius);
        let (mut u, mut v, mut eu, mut ev) = ([0.0; N], [0.0; N], [0.0; N], [0.0; N]);
        let mut w_min = f64::INFINITY;
        for (i, p) in h.iter().enumerate() {
            let (cx, cy) = (c.x * p[2], c.y * p[2]);
            u[i] = p[0] - cx;
            v[i] = p[1] - cy;
            // |fl(X - fl(c_x W)) - (X - c_x W)| <= eps/2 (|X| + 2 |c_x W|), doubled
            eu[i] = e * (p[0].abs() + 2.0 * cx.abs());
            ev[i] = e * (p[1].abs() + 2.0 * cy.abs());
            w_min = w_min.min(p[2]);
        }
        // positive finite weights (`f64::min` skips NaN, so test every one)
        if !h.iter().all(|p| p[2] > 0.0 && p[2].is_finite()) {
            self.contained = false;
            return;
        }
        // Lower bound of the Bernstein coefficient `i` of the linear form `dot(k, (U, V))`.
        let form_low = |k: Vector2<f64>, i: usize| {
            let value = k.x * u[i] + k.y * v[i];
            let err = k.x.abs() * eu[i]
                + k.y.abs() * ev[i]
                + 2.0 * e * (k.x.abs() * u[i].abs() + k.y.abs() * v[i].abs());
            value - err
        };
        // cross(a, q - c) = dot(perp_right(a), q - c) with perp_right(a) = (-a.y, a.x)
        let left = |a: Vector2<f64>| Vector2::new(-a.y, a.x);
        let (lo, hi, mid) = (self.frame.lo, self.frame.hi, self.frame.mid);
        let mut past: f64 = 0.0;
        for i in 0..=n {
            if form_low(mid, i) <= 0.0 {
                self.contained = false;
                return;
            }
            // inside the wedge: cross(lo, q - c) >= 0 and cross(q - c, hi) >= 0
            past = past
                .max(-form_low(left(lo), i))
                .max(-form_low(-left(hi), i));
        }
        self.past_ends = self.past_ends.max(past.max(0.0) / w_min * (1.0 + 8.0 * e));

        // F = U^2 + V^2 - R^2 W^2 in Bernstein form, with a running error bound.
        let r2 = r * r;
        let gamma = product_rounding_ulps(n) * e;
        let (row_n, row_2n) = (binomial_row(n), binomial_row(2 * n));
        let (mut f, mut err) = ([0.0; 2 * N], [0.0; 2 * N]);
        for i in 0..=n {
            for k in 0..=n {
                let beta = row_n[i] * row_n[k] / row_2n[i + k];
                let (wi, wk) = (h[i][2], h[k][2]);
                f[i + k] += beta * (u[i] * u[k] + v[i] * v[k] - r2 * wi * wk);
                // rounding of U, V propagated through the products, and of R^2
                let input = u[i].abs() * eu[k]
                    + eu[i] * u[k].abs()
                    + eu[i] * eu[k]
                    + v[i].abs() * ev[k]
                    + ev[i] * v[k].abs()
                    + ev[i] * ev[k]
                    + e * r2 * wi * wk;
                let (ui, uk) = (u[i].abs() + eu[i], u[k].abs() + eu[k]);
                let (vi, vk) = (v[i].abs() + ev[i], v[k].abs() + ev[k]);
                let magnitude = ui * uk + vi * vk + r2 * wi * wk;
                err[i + k] += beta * (input + gamma * magnitude);
            }
        }
        let f_max = (0..=2 * n).fold(0.0f64, |m, j| m.max(f[j].abs() + err[j] * (1.0 + 1e-6)));
        // |q - c| + R >= R gives a first bound; with it, |q - c| + R >= 2R - that.
        let first = f_max / (w_min * w_min * r) * (1.0 + 8.0 * e);
        let radial = if first < r {
            f_max / (w_min * w_min * (2.0 * r - first)) * (1.0 + 8.0 * e)
        } else {
            first
        };
        self.radial = self.radial.max(radial);
    }

    /// The two-sided distance between the parts added and the arc (without the rounding of
    /// the parts' own control points and of the arc's end points, which the caller adds), or
    /// `None` when the parts are not within the arc's bisector half-plane or lie farther than
    /// half the radius from the circle (the angular argument needs both).
    pub fn bound(&self) -> Option<f64> {
        let (delta, sigma, r) = (self.radial, self.past_ends, self.frame.radius);
        (self.contained && delta <= 0.5 * r)
            .then(|| (delta + sigma + 2.0 * sigma * sigma / r) * (1.0 + 8.0 * f64::EPSILON))
    }
}

/// The binomial coefficients `C(n, 0..=n)` as exact `f64`s (`n <= 30`: at most 1.6e8).
fn binomial_row(n: usize) -> [f64; 2 * super::span::MAX_SPAN_DEGREE + 1] {
    let mut row = [0.0; 2 * super::span::MAX_SPAN_DEGREE + 1];
    let mut b: u64 = 1;
    for (k, slot) in row.iter_mut().enumerate().take(n + 1) {
        *slot = b as f64;
        b = b * (n - k) as u64 / (k as u64 + 1);
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::biarc::test_curves::circle_arc_quadratic as quadratic_arc;
    use crate::nearest::NearestPoint;

    fn point(h: &[[f64; 3]], t: f64) -> Point2<f64> {
        let b = [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t];
        let s = |k: usize| (0..3).map(|i| b[i] * h[i][k]).sum::<f64>();
        Point2::new(s(0) / s(2), s(1) / s(2))
    }

    /// The counter-clockwise arc of the circle from angle `a0` to `a1`.
    fn arc(c: Point2<f64>, r: f64, a0: f64, a1: f64) -> Arc {
        let at = |a: f64| c + Vector2::new(a.cos(), a.sin()) * r;
        Arc::from_point_tangent_point(at(a0), Vector2::new(-a0.sin(), a0.cos()), at(a1)).unwrap()
    }

    fn bound(h: &[[f64; 3]], arc: &Arc) -> Option<f64> {
        let mut d = PieceArcDeviation::new(ArcFrame::of(arc)?);
        d.add_part(h);
        d.bound()
    }

    /// Largest distance from 20,001 curve samples to the arc (its own point distance).
    fn sampled(h: &[[f64; 3]], arc: &Arc) -> f64 {
        (0..=20_000)
            .map(|i| arc.distance_to(point(h, i as f64 / 20_000.0)))
            .fold(0.0, f64::max)
    }

    const CIRCLES: [([f64; 2], f64); 4] = [
        ([0.0, 0.0], 1.0),
        ([5.0, -3.0], 0.01),
        ([100.0, 40.0], 3.0),
        ([0.3, 0.2], 1e3),
    ];

    #[test]
    fn exact_circles_are_bounded_at_rounding_level() {
        for (c, r) in CIRCLES {
            let c = Point2::new(c[0], c[1]);
            for (a0, a1) in [(0.1, 0.4), (-0.7, 0.8), (2.0, 3.5)] {
                let d = bound(&quadratic_arc(c, r, a0, a1, 0.0), &arc(c, r, a0, a1)).unwrap();
                let scale = c.coords.amax() + r;
                assert!(d <= 1e-13 * scale, "c {c:?} r {r}: {d}");
            }
        }
    }

    /// Against dense sampling: the bound covers the curve's distance to the arc and stays
    /// within a small factor of it (the convex hull of `F`'s coefficients is tight for a
    /// quadratic bump).
    #[test]
    fn perturbed_circles_are_bounded_and_tight() {
        for (c, r) in CIRCLES {
            let c = Point2::new(c[0], c[1]);
            for rel in [1e-3, 1e-6, 1e-9] {
                let bump = rel * r;
                let h = quadratic_arc(c, r, -0.7, 0.8, bump);
                let a = arc(c, r, -0.7, 0.8);
                let (d, truth) = (bound(&h, &a).unwrap(), sampled(&h, &a));
                assert!(d >= truth, "c {c:?} r {r} bump {bump}: {d} < {truth}");
                let slack = 1e-13 * (c.coords.amax() + r);
                assert!(
                    d <= 4.0 * truth + slack,
                    "c {c:?} r {r} bump {bump}: {d} vs {truth}"
                );
            }
        }
    }

    /// A curve that runs past the arc's end by 0.02 rad (radial offset zero): the angular part
    /// carries the bound.
    #[test]
    fn overshoot_past_an_end_ray_is_counted() {
        let c = Point2::new(1.0, 2.0);
        let h = quadratic_arc(c, 0.5, 0.2, 1.2, 0.0);
        for a in [arc(c, 0.5, 0.2, 1.18), arc(c, 0.5, 0.22, 1.2)] {
            let (d, truth) = (bound(&h, &a).unwrap(), sampled(&h, &a));
            assert!(
                truth > 9e-3 && d >= truth && d <= 1.5 * truth,
                "{d} vs {truth}"
            );
        }
    }

    /// No bound where the angular argument does not hold: a piece that reaches the far side of
    /// the circle (outside the bisector half-plane), or an arc sweeping more than MAX_SWEEP.
    #[test]
    fn far_side_and_wide_arcs_have_no_bound() {
        let c = Point2::new(0.0, 0.0);
        let h = quadratic_arc(c, 1.0, 0.0, 3.0, 0.0);
        assert_eq!(bound(&h, &arc(c, 1.0, 0.0, 0.3)), None);
        assert!(ArcFrame::of(&arc(c, 1.0, 0.0, 2.5)).is_none());
        // a curve 0.6 R away from the circle: the radial argument needs delta <= R / 2
        let h = quadratic_arc(c, 0.4, 0.1, 0.5, 0.0);
        assert_eq!(bound(&h, &arc(c, 1.0, 0.1, 0.5)), None);
    }
}

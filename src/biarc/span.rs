//! Fast evaluation of one rational Bezier span (homogeneous Bernstein coefficients) with its
//! first derivative: the inner loop of tree building.

use nalgebra::{Point2, Vector2};

use super::fit::PlanarCurve;

/// Largest supported span degree (fixed-size de Casteljau buffer; profile curves are cubic or
/// quadratic, the NURBS module allows any degree).
pub const MAX_SPAN_DEGREE: usize = 15;

/// Length, in ulps of the span's largest coordinate, below which a control leg counts as zero
/// when the limit tangent at an end is read off the control polygon: repeated control points
/// are exact zeros, and a de Casteljau cut at a stationary point leaves legs of a few ulps
/// (each level rounds once per coordinate, at most `MAX_SPAN_DEGREE` levels).
const STATIONARY_LEG_ULPS: f64 = 64.0;

/// Speed, relative to the span's hodograph size, at or below which the derivative at a spiral
/// end counts as zero: a split found as the root of a coordinate's derivative at a cusp leaves
/// a speed of rounding size (~1e-15 relative) whose direction is noise.
pub const STATIONARY_REL: f64 = 1e-13;

/// A rational Bezier span on the local parameter `u` in [0, 1], borrowed from homogeneous
/// coefficients `(w rho, w z, w)`.
#[derive(Debug, Clone, Copy)]
pub struct SpanCurve<'a> {
    /// Homogeneous control points, `degree + 1` of them (at most `MAX_SPAN_DEGREE + 1`).
    pub homogeneous: &'a [[f64; 3]],
}

impl PlanarCurve for SpanCurve<'_> {
    /// Point and derivative with respect to the local parameter `u`, by de Casteljau down to
    /// the last two homogeneous points `Q0, Q1`: `P = lerp(Q0, Q1, u)`, `P' = n (Q1 - Q0)`.
    fn point_and_derivative(&self, u: f64) -> (Point2<f64>, Vector2<f64>) {
        let h = self.homogeneous;
        let n = h.len() - 1;
        if n == 0 {
            return (
                Point2::new(h[0][0] / h[0][2], h[0][1] / h[0][2]),
                Vector2::zeros(),
            );
        }
        let v = 1.0 - u;
        // The last two de Casteljau points; a small fixed buffer for the usual degrees <= 3.
        let (q0, q1) = if n <= 3 {
            let mut q = [[0.0f64; 3]; 4];
            q[..=n].copy_from_slice(h);
            last_two(&mut q[..=n], u, v)
        } else {
            let mut q = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
            q[..=n].copy_from_slice(h);
            last_two(&mut q[..=n], u, v)
        };
        let q = [q0, q1];
        let p = [
            v * q[0][0] + u * q[1][0],
            v * q[0][1] + u * q[1][1],
            v * q[0][2] + u * q[1][2],
        ];
        let nf = n as f64;
        let dp = [
            nf * (q[1][0] - q[0][0]),
            nf * (q[1][1] - q[0][1]),
            nf * (q[1][2] - q[0][2]),
        ];
        let w = p[2];
        let point = Point2::new(p[0] / w, p[1] / w);
        let d = Vector2::new(
            (dp[0] * w - p[0] * dp[2]) / (w * w),
            (dp[1] * w - p[1] * dp[2]) / (w * w),
        );
        if d == Vector2::zeros() && (u == 0.0 || u == 1.0) {
            return (point, self.end_tangent_limit(u == 0.0, 0.0));
        }
        (point, d)
    }
}

impl SpanCurve<'_> {
    /// The limit of the tangent at an end where the derivative vanishes (repeated control
    /// points at the end of the span): near that end the hodograph is dominated by the first
    /// control leg of non-zero length, so the unit tangent tends to the direction from the end
    /// point to the first distinct control point (start) or from the last distinct one to the
    /// end (end). Returned with that leg's hodograph magnitude `n |P_k - P_end|`; zero when
    /// every control point coincides. Legs within rounding of zero ([`STATIONARY_LEG_ULPS`])
    /// or not longer than `skip_below` are skipped.
    fn end_tangent_limit(&self, at_start: bool, skip_below: f64) -> Vector2<f64> {
        let h = self.homogeneous;
        let n = h.len() - 1;
        let pt = |k: usize| Point2::new(h[k][0] / h[k][2], h[k][1] / h[k][2]);
        let (end, others): (usize, Vec<usize>) = if at_start {
            (0, (1..=n).collect())
        } else {
            (n, (0..n).rev().collect())
        };
        let scale = (0..=n).fold(0.0f64, |m, k| m.max(pt(k).coords.amax()));
        let noise = (STATIONARY_LEG_ULPS * f64::EPSILON * scale).max(skip_below);
        for k in others {
            let leg = pt(k) - pt(end);
            if leg.norm() > noise {
                let dir = if at_start { leg } else { -leg };
                return dir * n as f64;
            }
        }
        Vector2::zeros()
    }
}

impl SpanCurve<'_> {
    /// The derivative at `u` seen from one side: from above (`leaving`, the curve leaves the
    /// point as `u` grows) or from below (arriving), and the speed `|C'(u)|` it dropped.
    ///
    /// Where the speed inside the span is within rounding of zero ([`STATIONARY_REL`] of the
    /// hodograph's size: a cusp, a retrace, or a monotone point of zero speed, where a spiral
    /// split lands) the computed direction is noise and may even point backwards. The span is
    /// then cut there by de Casteljau and the half on that side gives its end limit (read off
    /// its control polygon, `end_tangent_limit`), rescaled to the span's parameter; the
    /// dropped speed is returned so that the caller can add the first-order term it ignores
    /// to its bounds.
    pub fn one_sided_derivative(&self, u: f64, leaving: bool) -> (Vector2<f64>, f64) {
        let (_, d) = self.point_and_derivative(u);
        let n = self.homogeneous.len() - 1;
        let size = self.hodograph_size();
        // The share of the span on the wanted side; none at its far end (the neighbouring
        // span holds that side).
        let share = if leaving { 1.0 - u } else { u };
        if n == 0 || d.norm() > STATIONARY_REL * size || share <= 0.0 {
            return (d, 0.0);
        }
        // At a span end (a knot placed on the stationary point) the half is the span itself:
        // de Casteljau at u = 0 or 1 returns its points unchanged.
        let mut half = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
        half_at(self.homogeneous, u, leaving, &mut half[..=n]);
        let piece = SpanCurve {
            homogeneous: &half[..=n],
        };
        // The half's first leg is `|C'(u)|` times its share of the span over `n`: skip it (and
        // any leg as short) with a factor 2 for rounding, so its noisy direction is never read.
        let skip = 2.0 * share * STATIONARY_REL * size / n as f64;
        let limit = piece.end_tangent_limit(leaving, skip) / share;
        (limit, d.norm())
    }

    /// `n` times the longest control leg: the size of the hodograph of a polynomial span (the
    /// scale against which a derivative counts as zero).
    fn hodograph_size(&self) -> f64 {
        let h = self.homogeneous;
        let pt = |k: usize| Point2::new(h[k][0] / h[k][2], h[k][1] / h[k][2]);
        let n = h.len() - 1;
        (1..=n).fold(0.0f64, |m, k| m.max((pt(k) - pt(k - 1)).norm())) * n as f64
    }

    /// Signed curvature at `u`: `det(P, P', P'') / (W^3 |C'|^3)` from the last three de
    /// Casteljau points (`P'' = n (n - 1) (Q2 - 2 Q1 + Q0)` at level `n - 2`).
    pub fn curvature(&self, u: f64) -> f64 {
        let h = self.homogeneous;
        let n = h.len() - 1;
        if n < 2 {
            return 0.0;
        }
        let v = 1.0 - u;
        let mut q = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
        q[..=n].copy_from_slice(h);
        for r in 1..n - 1 {
            for i in 0..=n - r {
                let next = q[i + 1];
                for (qc, nc) in q[i].iter_mut().zip(next) {
                    *qc = v * *qc + u * nc;
                }
            }
        }
        let (q0, q1, q2) = (q[0], q[1], q[2]);
        let nf = n as f64;
        let lerp = |a: [f64; 3], b: [f64; 3]| {
            [
                v * a[0] + u * b[0],
                v * a[1] + u * b[1],
                v * a[2] + u * b[2],
            ]
        };
        let (r0, r1) = (lerp(q0, q1), lerp(q1, q2));
        let p = lerp(r0, r1);
        let d1 = [
            nf * (r1[0] - r0[0]),
            nf * (r1[1] - r0[1]),
            nf * (r1[2] - r0[2]),
        ];
        let c = nf * (nf - 1.0);
        let d2 = [
            c * (q2[0] - 2.0 * q1[0] + q0[0]),
            c * (q2[1] - 2.0 * q1[1] + q0[1]),
            c * (q2[2] - 2.0 * q1[2] + q0[2]),
        ];
        let det = p[0] * (d1[1] * d2[2] - d1[2] * d2[1]) - p[1] * (d1[0] * d2[2] - d1[2] * d2[0])
            + p[2] * (d1[0] * d2[1] - d1[1] * d2[0]);
        let w = p[2];
        let sx = d1[0] * w - p[0] * d1[2];
        let sy = d1[1] * w - p[1] * d1[2];
        // |C'| = |(sx, sy)| / W^2, C' x C'' = det / W^3
        let speed = sx.hypot(sy) / (w * w);
        det / (w * w * w) / (speed * speed * speed)
    }
}

impl SpanCurve<'_> {
    /// The homogeneous control points of the part `[u0, u1]` of the span (`0 <= u0 < u1 <= 1`),
    /// by two de Casteljau cuts, written into `out` (`degree + 1` entries). The part lies in
    /// the convex hull of these points (positive weights), which gives a bound that needs no
    /// spiral property ([`crate::biarc::tree`]'s chord nodes).
    pub fn part(&self, u0: f64, u1: f64, out: &mut [[f64; 3]]) {
        let n = self.homogeneous.len() - 1;
        let mut below = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
        half_at(self.homogeneous, u1, false, &mut below[..=n]);
        // u0 in the parameter of [0, u1]
        let v = if u1 > 0.0 { (u0 / u1).min(1.0) } else { 0.0 };
        half_at(&below[..=n], v, true, out);
    }
}

/// Runs de Casteljau on `q` down to two points and returns them.
#[inline]
fn last_two(q: &mut [[f64; 3]], u: f64, v: f64) -> ([f64; 3], [f64; 3]) {
    let n = q.len() - 1;
    for r in 1..n {
        for i in 0..=n - r {
            let next = q[i + 1];
            for (qc, nc) in q[i].iter_mut().zip(next) {
                *qc = v * *qc + u * nc;
            }
        }
    }
    (q[0], q[1])
}

/// The homogeneous control points of the part of the span above `u` (`upper`) or below it,
/// by de Casteljau subdivision, written into `out` (`degree + 1` entries).
fn half_at(h: &[[f64; 3]], u: f64, upper: bool, out: &mut [[f64; 3]]) {
    let n = h.len() - 1;
    let v = 1.0 - u;
    out.copy_from_slice(h);
    // After level r, out[i] holds b_i^r for i <= n - r; the lower half is b_0^0..b_0^n and the
    // upper half b_0^n, b_1^(n-1), ..., b_n^0.
    let mut lower = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
    let mut upper_pts = [[0.0f64; 3]; MAX_SPAN_DEGREE + 1];
    lower[0] = out[0];
    upper_pts[n] = out[n];
    for r in 1..=n {
        for i in 0..=n - r {
            let next = out[i + 1];
            for (qc, nc) in out[i].iter_mut().zip(next) {
                *qc = v * *qc + u * nc;
            }
        }
        lower[r] = out[0];
        upper_pts[n - r] = out[n - r];
    }
    out.copy_from_slice(if upper {
        &upper_pts[..=n]
    } else {
        &lower[..=n]
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Down a vertical line and back up it: at the turning point the computed speed is
    /// rounding noise, and the one-sided derivatives must point down when arriving and up when
    /// leaving, whatever the noise's sign.
    #[test]
    fn one_sided_derivative_at_a_retrace() {
        let h = [
            [0.5, 0.0, 1.0],
            [0.5, -0.001, 1.0],
            [0.5, -0.002, 1.0],
            [0.5, 0.5, 1.0],
        ];
        let c = SpanCurve { homogeneous: &h };
        // z'(u) = 3 [(1-u)^2 (-0.001) + 2u(1-u)(-0.001) + u^2 (0.502)]: its root by bisection.
        let zp = |u: f64| c.point_and_derivative(u).1.y;
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if zp(m) < 0.0 {
                lo = m;
            } else {
                hi = m;
            }
        }
        for u in [lo, hi] {
            let (leave, dropped) = c.one_sided_derivative(u, true);
            let (arrive, _) = c.one_sided_derivative(u, false);
            assert!(leave.y > 0.0 && leave.x == 0.0, "{leave:?}");
            assert!(arrive.y < 0.0 && arrive.x == 0.0, "{arrive:?}");
            assert!(dropped <= STATIONARY_REL * 3.0 * 0.502);
        }
        // Away from it nothing changes.
        assert_eq!(
            c.one_sided_derivative(0.5, true),
            (c.point_and_derivative(0.5).1, 0.0)
        );
    }

    #[test]
    fn parabola_curvature() {
        // y = x^2 on [0, 1] as a polynomial quadratic: kappa = 2 / (1 + 4x^2)^(3/2)
        let h = [[0.0, 0.0, 1.0], [0.5, 0.0, 1.0], [1.0, 1.0, 1.0]];
        let c = SpanCurve { homogeneous: &h };
        for i in 0..=10 {
            let x = i as f64 / 10.0;
            let expect = 2.0 / (1.0 + 4.0 * x * x).powf(1.5);
            assert!((c.curvature(x) - expect).abs() < 1e-13);
        }
    }

    #[test]
    fn quarter_circle_rational_quadratic() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let h = [[1.0, 0.0, 1.0], [s, s, s], [0.0, 1.0, 1.0]];
        let c = SpanCurve { homogeneous: &h };
        for i in 0..=10 {
            let u = i as f64 / 10.0;
            let (p, d) = c.point_and_derivative(u);
            assert!((p.coords.norm() - 1.0).abs() < 1e-15);
            assert!(p.coords.dot(&d).abs() < 1e-14);
            // finite-difference check of the derivative
            let e = 1e-6;
            let fd = (c.point_and_derivative((u + e).min(1.0)).0
                - c.point_and_derivative((u - e).max(0.0)).0)
                / ((u + e).min(1.0) - (u - e).max(0.0));
            assert!((fd - d).norm() < 1e-5, "u {u}: {fd:?} vs {d:?}");
            assert!(
                (c.curvature(u) - 1.0).abs() < 1e-12,
                "kappa {}",
                c.curvature(u)
            );
        }
    }
}

//! Spiral segmentation of a rational Bezier span (Son et al. 2020, section 4.1): split where
//! `rho'`, `z'`, the curvature `kappa` or its derivative `kappa'` change sign, so that every
//! piece is monotone in rho and z (hence turns at most 90 degrees), of one convexity, and
//! curvature-monotone: a *short spiral*, which the bilens bound of [`super::bound`] needs.
//!
//! With homogeneous coordinates `P = (X, Y, W)` (`rho = X / W`, `z = Y / W`, `W > 0`):
//! - `rho' ~ X'W - XW'`, `z' ~ Y'W - YW'` (same sign, divided by `W^2`),
//! - `C' x C'' = det(P, P', P'') / W^3`, so `sign(kappa) = sign(D)`, `D = det(P, P', P'')`,
//! - `kappa = D W^3 / S^(3/2)` with `S = (X'W - XW')^2 + (Y'W - YW')^2`, so
//!   `sign(kappa') = sign(K)`, `K = 2 (D'W + 3DW') S - 3 D W S'`.
//!
//! All are polynomials, built exactly in Bernstein form and handed to the Bernstein root isolator
//! [`crate::poly::bernstein::odd_roots`]: only odd-multiplicity roots (sign changes) split.
//! A polynomial that vanishes identically up to rounding (a straight span has `D = 0`, an exact
//! circle `K = 0`, a vertical line `rho' = 0`) causes no split, so lines and circles never
//! split endlessly.

use crate::poly::bernstein::{odd_roots, Bernstein};

/// A polynomial whose coefficients are all below this fraction of the magnitude of the terms it
/// was computed from counts as identically zero (a straight span, an exact circle, an axis-
/// parallel line). Rounding of the products and differences is ~1e-15 relative for the degrees
/// here (<= 18); 1e-10 leaves a wide margin while any real curvature signal of a profile is far
/// larger. A span treated as straight may still bend at that level, so the tree bounds it by
/// its control polygon ([`SpanSplits::straight_within_noise`]); one whose other tests were
/// dismissed (an exact or near circle: `K`) by each arc's certified distance from its curve
/// part ([`SpanSplits::spiral_within_noise`]), since its curvature may be non-monotone at that
/// level and the bilens bound was measured 30 times too small there.
pub const SPLIT_NOISE_REL: f64 = 1e-10;

/// Root positions are isolated to this accuracy in the local parameter `u` (the bilens bound does
/// not depend on it; a split point off by 1e-13 leaves a sign-violating sliver of that width).
pub const SPLIT_ROOT_TOL: f64 = 1e-13;

/// Split parameters closer than this (in the local parameter) to each other or to a span end
/// are merged: slivers shorter than 1e-9 of a span carry no geometry worth a separate spiral.
pub const MIN_SPLIT_GAP: f64 = 1e-9;

/// Why a span was split at some parameter (for diagnostics and tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SplitReason {
    /// `rho' = 0`: a rho-extremum.
    RhoExtremum,
    /// `z' = 0`: a z-extremum.
    ZExtremum,
    /// `kappa = 0`: an inflection.
    Inflection,
    /// `kappa' = 0`: a curvature extremum.
    CurvatureExtremum,
}

fn coord(h: &[[f64; 3]], c: usize) -> Bernstein {
    Bernstein::new(h.iter().map(|p| p[c]).collect())
}

fn elevate_to(p: &Bernstein, degree: usize) -> Bernstein {
    let mut q = p.clone();
    while q.degree() < degree {
        q = q.elevate();
    }
    q
}

/// `a * ca + b * cb`, elevating to the common degree.
fn combine(a: &Bernstein, ca: f64, b: &Bernstein, cb: f64) -> Bernstein {
    let d = a.degree().max(b.degree());
    let (a, b) = (elevate_to(a, d), elevate_to(b, d));
    Bernstein::new(
        a.coeffs()
            .iter()
            .zip(b.coeffs())
            .map(|(x, y)| ca * x + cb * y)
            .collect(),
    )
}

/// `a * b - c * d` with the magnitude of the two products (for the noise test).
fn cross_diff(a: &Bernstein, b: &Bernstein, c: &Bernstein, d: &Bernstein) -> (Bernstein, f64) {
    let (ab, cd) = (a.product(b), c.product(d));
    let scale = ab.max_abs_coeff().max(cd.max_abs_coeff());
    (combine(&ab, 1.0, &cd, -1.0), scale)
}

/// Pushes the sign changes of `p` in (0, 1) tagged with `reason`, unless `p` is noise relative
/// to `scale`. Returns whether it was dismissed as noise.
fn push_roots(
    p: &Bernstein,
    scale: f64,
    reason: SplitReason,
    out: &mut Vec<(f64, SplitReason)>,
) -> bool {
    if p.is_negligible(SPLIT_NOISE_REL * scale) {
        return true;
    }
    // Bernstein coefficients of one strict sign: no root on [0, 1] (convex hull property).
    let c = p.coeffs();
    if c.iter().all(|&v| v > 0.0) || c.iter().all(|&v| v < 0.0) {
        return false;
    }
    out.extend(
        odd_roots(p, SPLIT_ROOT_TOL)
            .into_iter()
            .map(|u| (u, reason)),
    );
    false
}

/// Interior split parameters (local `u` in (0, 1), sorted, merged within [`MIN_SPLIT_GAP`]) that
/// cut the span with homogeneous Bernstein coefficients `h` into short spirals.
pub fn spiral_splits(h: &[[f64; 3]]) -> Vec<(f64, SplitReason)> {
    split_span(h).splits
}

/// The spiral splits of a span ([`spiral_splits`]) and whether its curvature numerator `D`
/// was dismissed as rounding noise.
#[derive(Debug, Clone, PartialEq)]
pub struct SpanSplits {
    /// Interior split parameters, as [`spiral_splits`] returns them.
    pub splits: Vec<(f64, SplitReason)>,
    /// True when the span has degree >= 2 and `D` is below [`SPLIT_NOISE_REL`] of its terms:
    /// straight to working precision, so neither inflections nor curvature extrema split it.
    /// Such a span may still bend by up to that noise level (a line whose control points are
    /// perturbed by 1e-11), and an unsplit inflection breaks the spiral property the bilens
    /// bound needs; the tree bounds it by its control polygon instead.
    pub straight_within_noise: bool,
    /// True when the span is not straight but one of the other sign tests (`rho'`, `z'` or
    /// `kappa'`) was below the noise test: an exact circle written as a rational span, a
    /// near-circle whose curvature varies by less than [`SPLIT_NOISE_REL`] of itself, or a
    /// span tiny against its coordinates. Its pieces are short spirals only to working
    /// precision, so the tree bounds them without the bilens
    /// ([`super::arc_deviation`]).
    pub spiral_within_noise: bool,
}

/// What the sign tests of a span dismissed as rounding noise.
#[derive(Debug, Clone, Copy)]
struct Dismissed {
    straight: bool,
    other: bool,
}

/// [`spiral_splits`] with the straightness flag of [`SpanSplits`].
pub fn split_span(h: &[[f64; 3]]) -> SpanSplits {
    let mut out = Vec::new();
    if h.len() < 3 {
        // degree <= 1: a segment, already a spiral
        return SpanSplits {
            splits: out,
            straight_within_noise: false,
            spiral_within_noise: false,
        };
    }
    let w0 = h[0][2];
    let dismissed = if h.iter().all(|p| p[2] == w0) {
        polynomial_splits(h, w0, &mut out)
    } else {
        rational_splits(h, &mut out)
    };
    SpanSplits {
        splits: merge(out),
        straight_within_noise: dismissed.straight,
        spiral_within_noise: dismissed.other && !dismissed.straight,
    }
}

/// Polynomial span (all weights equal): `rho' = x'`, `z' = y'`, `D = x'y'' - y'x''`,
/// `K = 2 D' S - 3 D S'` with `S = x'^2 + y'^2` (degree 4n - 6 instead of 8n - 6). Returns
/// which tests were noise.
fn polynomial_splits(h: &[[f64; 3]], w0: f64, out: &mut Vec<(f64, SplitReason)>) -> Dismissed {
    let x = Bernstein::new(h.iter().map(|p| p[0] / w0).collect());
    let y = Bernstein::new(h.iter().map(|p| p[1] / w0).collect());
    let (xd, yd) = (x.derivative(), y.derivative());
    let (xdd, ydd) = (xd.derivative(), yd.derivative());
    let scale = x.max_abs_coeff().max(y.max_abs_coeff());
    let mut other = push_roots(&xd, scale, SplitReason::RhoExtremum, out);
    other |= push_roots(&yd, scale, SplitReason::ZExtremum, out);
    let (d, d_scale) = cross_diff(&xd, &ydd, &yd, &xdd);
    if d.is_negligible(SPLIT_NOISE_REL * d_scale) {
        return Dismissed {
            straight: true,
            other,
        };
    }
    push_roots(&d, d_scale, SplitReason::Inflection, out);
    let s = combine(&xd.product(&xd), 1.0, &yd.product(&yd), 1.0);
    let lhs = d.derivative().product(&s);
    let rhs = d.product(&s.derivative());
    let k_scale = (2.0 * lhs.max_abs_coeff()).max(3.0 * rhs.max_abs_coeff());
    let k = combine(&lhs, 2.0, &rhs, -3.0);
    other |= push_roots(&k, k_scale, SplitReason::CurvatureExtremum, out);
    Dismissed {
        straight: false,
        other,
    }
}

/// Rational span: the homogeneous formulas of the module doc. Returns which tests were noise.
fn rational_splits(h: &[[f64; 3]], out: &mut Vec<(f64, SplitReason)>) -> Dismissed {
    let (x, y, w) = (coord(h, 0), coord(h, 1), coord(h, 2));
    let (xd, yd, wd) = (x.derivative(), y.derivative(), w.derivative());
    let (xdd, ydd, wdd) = (xd.derivative(), yd.derivative(), wd.derivative());

    let (rho_d, rho_scale) = cross_diff(&xd, &w, &x, &wd);
    let (z_d, z_scale) = cross_diff(&yd, &w, &y, &wd);
    let mut other = push_roots(&rho_d, rho_scale, SplitReason::RhoExtremum, out);
    other |= push_roots(&z_d, z_scale, SplitReason::ZExtremum, out);

    // D = X (Y'W'' - W'Y'') - Y (X'W'' - W'X'') + W (X'Y'' - Y'X'')
    let (m0, s0) = cross_diff(&yd, &wdd, &wd, &ydd);
    let (m1, s1) = cross_diff(&xd, &wdd, &wd, &xdd);
    let (m2, s2) = cross_diff(&xd, &ydd, &yd, &xdd);
    let (t0, t1, t2) = (x.product(&m0), y.product(&m1), w.product(&m2));
    let d_scale = x.max_abs_coeff() * (s0 + m0.max_abs_coeff())
        + y.max_abs_coeff() * (s1 + m1.max_abs_coeff())
        + w.max_abs_coeff() * (s2 + m2.max_abs_coeff());
    let d = combine(&combine(&t0, 1.0, &t1, -1.0), 1.0, &t2, 1.0);
    if d.is_negligible(SPLIT_NOISE_REL * d_scale) {
        return Dismissed {
            straight: true,
            other,
        };
    }
    push_roots(&d, d_scale, SplitReason::Inflection, out);

    // K = 2 (D'W + 3 D W') S - 3 D W S'
    let s = combine(&rho_d.product(&rho_d), 1.0, &z_d.product(&z_d), 1.0);
    let sd = s.derivative();
    let dd = d.derivative();
    let lhs = combine(&dd.product(&w), 2.0, &d.product(&wd), 6.0).product(&s);
    let rhs = d.product(&w).product(&sd);
    let k_scale = lhs.max_abs_coeff().max(3.0 * rhs.max_abs_coeff());
    let k = combine(&lhs, 1.0, &rhs, -3.0);
    other |= push_roots(&k, k_scale, SplitReason::CurvatureExtremum, out);
    Dismissed {
        straight: false,
        other,
    }
}

fn merge(mut v: Vec<(f64, SplitReason)>) -> Vec<(f64, SplitReason)> {
    v.retain(|&(u, _)| u > MIN_SPLIT_GAP && u < 1.0 - MIN_SPLIT_GAP);
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<(f64, SplitReason)> = Vec::with_capacity(v.len());
    for r in v {
        if out.last().is_none_or(|l| r.0 - l.0 > MIN_SPLIT_GAP) {
            out.push(r);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::biarc::fit::{fit_biarc, g1_tolerance, CurveSample, PlanarCurve};
    use crate::biarc::oracle::sampled_hausdorff;
    use crate::biarc::span::SpanCurve;
    use crate::num::cross2;
    use proptest::prelude::*;

    /// Samples per spiral piece for the sign / monotonicity checks.
    const SAMPLES: usize = 400;
    /// Relative size below which a sampled value counts as zero (rounding near split points).
    const SIGN_TOL_REL: f64 = 1e-7;

    /// Second derivative by central differences of the analytic first derivative (only used to
    /// get kappa at samples; the checks tolerate its ~1e-8 relative error).
    fn kappa(c: &SpanCurve, u: f64) -> f64 {
        let e = 1e-6;
        let (_, d) = c.point_and_derivative(u);
        let dd = (c.point_and_derivative(u + e).1 - c.point_and_derivative(u - e).1) / (2.0 * e);
        cross2(d, dd) / d.norm().powi(3)
    }

    fn h_scale(h: &[[f64; 3]]) -> f64 {
        h.iter().fold(0.0f64, |m, p| {
            m.max((p[0] / p[2]).abs()).max((p[1] / p[2]).abs())
        })
    }

    fn one_sign(v: &[f64]) -> bool {
        let m = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let tol = SIGN_TOL_REL * m;
        !(v.iter().any(|&x| x > tol) && v.iter().any(|&x| x < -tol))
    }

    /// Checks every spiral of the span: rho, z monotone, kappa one sign and monotone, turning
    /// <= 90 degrees, and the biarc bound against dense sampling. Returns the number of pieces.
    fn check_span(h: &[[f64; 3]]) -> usize {
        let c = SpanCurve { homogeneous: h };
        let mut cuts = vec![0.0];
        cuts.extend(spiral_splits(h).iter().map(|r| r.0));
        cuts.push(1.0);
        for w in cuts.windows(2) {
            let (u0, u1) = (w[0], w[1]);
            // stay off the exact split points where derivatives vanish
            let m = 1e-4 * (u1 - u0);
            let us: Vec<f64> = (0..=SAMPLES)
                .map(|i| u0 + m + (u1 - u0 - 2.0 * m) * i as f64 / SAMPLES as f64)
                .collect();
            let d: Vec<_> = us.iter().map(|&u| c.point_and_derivative(u).1).collect();
            let k: Vec<f64> = us.iter().map(|&u| kappa(&c, u)).collect();
            assert!(
                one_sign(&d.iter().map(|v| v.x).collect::<Vec<_>>()),
                "rho' changes sign"
            );
            assert!(
                one_sign(&d.iter().map(|v| v.y).collect::<Vec<_>>()),
                "z' changes sign"
            );
            assert!(one_sign(&k), "kappa changes sign on [{u0}, {u1}]");
            let dk: Vec<f64> = k.windows(2).map(|p| p[1] - p[0]).collect();
            let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            let dk_tol = 1e-6 * kmax;
            assert!(
                !(dk.iter().any(|&x| x > dk_tol) && dk.iter().any(|&x| x < -dk_tol)),
                "kappa not monotone on [{u0}, {u1}]"
            );
            let (t0, t1) = (d[0], d[SAMPLES]);
            let turn = cross2(t0, t1).atan2(t0.dot(&t1)).abs();
            assert!(turn <= std::f64::consts::FRAC_PI_2 + 1e-6, "turning {turn}");
            let (s0, s1) = (CurveSample::at(&c, u0), CurveSample::at(&c, u1));
            if (s1.point - s0.point).norm() < 1e-9 {
                continue;
            }
            let fit = fit_biarc(&c, &s0, &s1).unwrap();
            let hd = sampled_hausdorff(&c, u0, u1, &fit.arcs, 300);
            assert!(
                hd <= fit.eps,
                "sampled {hd} > bound {} on [{u0}, {u1}]",
                fit.eps
            );
            let allowed = g1_tolerance(&fit, h_scale(h));
            assert!(
                fit.joint_defect() <= allowed,
                "G1 defect {} > {allowed}",
                fit.joint_defect()
            );
        }
        cuts.len() - 1
    }

    fn pt() -> impl Strategy<Value = (f64, f64)> {
        (0.0f64..2.0, -1.0f64..1.0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]
        #[test]
        fn random_cubics_segment_into_spirals(
            p in proptest::collection::vec(pt(), 4),
            w in proptest::collection::vec(0.3f64..3.0, 4),
            rational in any::<bool>(),
        ) {
            let h: Vec<[f64; 3]> = p
                .iter()
                .zip(&w)
                .map(|(&(x, y), &wi)| {
                    let wi = if rational { wi } else { 1.0 };
                    [x * wi, y * wi, wi]
                })
                .collect();
            // skip near-degenerate control polygons (cusps, zero speed)
            let c = SpanCurve { homogeneous: &h };
            let min_speed = (0..=50)
                .map(|i| c.point_and_derivative(i as f64 / 50.0).1.norm())
                .fold(f64::INFINITY, f64::min);
            prop_assume!(min_speed > 0.05);
            check_span(&h);
        }
    }

    #[test]
    fn lines_and_circles_do_not_split() {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        // quarter circle (rational quadratic): one spiral, no kappa' split
        assert!(spiral_splits(&[[1.0, 0.0, 1.0], [s, s, s], [0.0, 1.0, 1.0]]).is_empty());
        // straight cubic (collinear control points, uneven speed): no split
        let line = [
            [0.0, 0.0, 1.0],
            [0.1, 0.2, 1.0],
            [0.9, 1.8, 1.0],
            [1.0, 2.0, 1.0],
        ];
        assert!(spiral_splits(&line).is_empty());
        // vertical line
        let vert = [[1.0, 0.0, 1.0], [1.0, 0.5, 1.0], [1.0, 2.0, 1.0]];
        assert!(spiral_splits(&vert).is_empty());
        check_span(&line);
        // S-curve: exactly one inflection
        let s_curve = [
            [0.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [2.0, -1.0, 1.0],
            [3.0, 0.0, 1.0],
        ];
        let r = spiral_splits(&s_curve);
        assert_eq!(
            r.iter().filter(|x| x.1 == SplitReason::Inflection).count(),
            1,
            "{r:?}"
        );
        assert!(r
            .iter()
            .any(|x| (x.0 - 0.5).abs() < 1e-12 && x.1 == SplitReason::Inflection));
        check_span(&s_curve);
    }
}

//! G1 biarc fitting of a spiral piece with the joint on the curve (Son et al. 2020, section 4.1,
//! after Sir, Feichtinger, Juttler 2006), and its bilens error bound.
//!
//! **Joint rule.** All G1 biarcs matching the end points and end tangents have their joint on
//! the *J-circle* through `A` and `B` (notes `biarcs.md` section 1.3). We take the joint where
//! the J-circle crosses the curve, `J = C(t_J)`. Why: with `J` on the curve, each arc is a wall
//! of the lens of its half of the spiral, so the cheap bilens bound of [`super::bound`] is
//! rigorous, and it is about 8x tighter than the single-lens bound available for other rules.
//! For a spiral the crossing is unique (the curve starts on one side of the J-circle and ends on
//! the other). `t_J` is the interior root of `q(t) = g(C(t)) / ((t - t_a)(t_b - t))`, where
//! `g(X) = sin(w) (A-X).(B-X) + cos(w) (A-X)x(B-X)` is the J-circle's implicit form (valid also
//! when it degenerates to the chord line) and the end values of `q` come from `grad g . C'`.
//!
//! The first arc is built from `(A, T_A)` to `J`, the second backwards from `(B, -T_B)` to `J`,
//! so the end tangents are exact and the joint defect is only the root's rounding. Degenerate
//! data (a straight piece, an exact circle: `q` vanishes identically) takes the mid parameter,
//! where every curve point is a valid joint.

use nalgebra::{Point2, Vector2};

use super::arc::Arc;
use super::bound::bilens_bound;
use super::BiarcError;
use crate::num::cross2;

/// A planar curve that can be evaluated with its first derivative.
pub trait PlanarCurve {
    /// Point and first derivative at parameter `t`.
    fn point_and_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>);
}

impl<F: Fn(f64) -> (Point2<f64>, Vector2<f64>)> PlanarCurve for F {
    fn point_and_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>) {
        self(t)
    }
}

/// A NURBS profile piece in its own parameter (de Boor evaluation).
impl PlanarCurve for crate::nurbs::NurbsCurve {
    fn point_and_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>) {
        let d = self.derivatives(t);
        (Point2::from(d[0]), d[1])
    }
}

/// A curve sample: parameter, point and first derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSample {
    /// Parameter.
    pub t: f64,
    /// Point `C(t)`.
    pub point: Point2<f64>,
    /// Derivative `C'(t)`.
    pub derivative: Vector2<f64>,
}

impl CurveSample {
    /// Evaluates `curve` at `t`.
    pub fn at<C: PlanarCurve + ?Sized>(curve: &C, t: f64) -> CurveSample {
        let (point, derivative) = curve.point_and_derivative(t);
        CurveSample {
            t,
            point,
            derivative,
        }
    }

    /// Evaluates `curve` at `t`, or, where the derivative vanishes there (a stationary point
    /// of the parametrisation), a little towards `toward` (by [`STATIONARY_NUDGE`] of the
    /// distance). For subdivision points and biarc joints any curve point will do: the bilens
    /// bound holds for every joint with its own tangent, and there the tangent is defined.
    pub fn off_stationary<C: PlanarCurve + ?Sized>(curve: &C, t: f64, toward: f64) -> CurveSample {
        let s = CurveSample::at(curve, t);
        if s.derivative != Vector2::zeros() {
            return s;
        }
        CurveSample::at(curve, t + STATIONARY_NUDGE * (toward - t))
    }
}

/// Fraction of the way to the interval's end by which a subdivision point or joint that falls
/// exactly on a stationary point moves (2^-20: far above rounding, far below any change in the
/// subdivision's balance).
pub const STATIONARY_NUDGE: f64 = 1.0 / 1048576.0;

/// Relative size of `|q|` at both ends, compared with `|C'| |B - A|`, below which the J-circle is
/// taken to contain the whole piece (exact circle or line): any curve point is then a joint.
/// Rounding of `g` is a few ulps of `|B-A|^2`, i.e. ~1e-15 relative; 1e-12 leaves margin.
pub const DEGENERATE_JOINT_REL: f64 = 1e-12;

/// `g` below this many ulps of `|A - X| |B - X|` is rounding noise (two products and a sum).
const G_NOISE_ULPS: f64 = 4.0;

/// Iteration cap of the joint solver; bisection alone halves the bracket 200 times, far past
/// double precision.
const JOINT_MAX_ITER: usize = 200;

/// The joint is kept at least this fraction of the bracket away from its ends, so both arcs
/// have a non-zero chord; it only matters when rounding pushes the root onto an end point.
const JOINT_END_MARGIN: f64 = 1e-9;

/// A biarc fitted to a curve piece, with its guaranteed bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedBiarc {
    /// The two arcs; `arcs[0].start` is the piece's start, `arcs[1].end` its end.
    pub arcs: [Arc; 2],
    /// Parameter of the joint on the curve.
    pub t_joint: f64,
    /// The joint sample (point on the curve and the curve's derivative there).
    pub joint: CurveSample,
    /// Guaranteed two-sided Hausdorff bound between the curve piece and the biarc (bilens).
    pub eps: f64,
}

impl FittedBiarc {
    /// Angle (radians) between the two arcs' tangents at the joint: the G1 defect.
    pub fn joint_defect(&self) -> f64 {
        let t0 = self.arcs[0].end_tangent();
        let t1 = self.arcs[1].start_tangent;
        cross2(t0, t1).atan2(t0.dot(&t1)).abs()
    }
}

/// Required G1 continuity at the joint: 1e-12 rad.
pub const G1_TOL: f64 = 1e-12;

/// The joint is a curve point known to a few ulps of the coordinates, so an arc of length `l`
/// has its end tangent known only to ~`ulp / l`; [`g1_tolerance`] allows this many ulps.
pub const G1_ULP_FACTOR: f64 = 64.0;

/// The G1 defect a fit can promise: [`G1_TOL`], or, for arcs so short that coordinate rounding
/// alone exceeds it, `G1_ULP_FACTOR * eps_mach * scale / shortest arc` (`scale` = largest
/// coordinate magnitude of the curve).
pub fn g1_tolerance(fit: &FittedBiarc, scale: f64) -> f64 {
    let shortest = fit.arcs[0].length.min(fit.arcs[1].length);
    G1_TOL.max(G1_ULP_FACTOR * f64::EPSILON * scale / shortest)
}

/// The signed J-circle function `g(X)` for end data `(a, ta)`, `(b, tb)` (unit tangents), as
/// `(sin w, cos w)` and a closure-free evaluator.
#[derive(Debug, Clone, Copy)]
struct JCircle {
    a: Point2<f64>,
    b: Point2<f64>,
    sin_w: f64,
    cos_w: f64,
}

impl JCircle {
    fn new(a: Point2<f64>, ta: Vector2<f64>, b: Point2<f64>, tb: Vector2<f64>) -> JCircle {
        let v = b - a;
        let theta0 = cross2(v, ta).atan2(v.dot(&ta));
        let theta1 = cross2(v, tb).atan2(v.dot(&tb));
        let (sin_w, cos_w) = (0.5 * (theta0 - theta1)).sin_cos();
        JCircle { a, b, sin_w, cos_w }
    }
    /// `g(x)` and whether it is within its rounding noise of zero (then `x` lies on the
    /// J-circle to working precision and refining the root further cannot reduce the joint's
    /// G1 defect).
    fn g_with_noise(&self, x: Point2<f64>) -> (f64, bool) {
        let (u, w) = (self.a - x, self.b - x);
        let g = self.sin_w * u.dot(&w) + self.cos_w * cross2(u, w);
        (
            g,
            g.abs() <= G_NOISE_ULPS * f64::EPSILON * u.norm() * w.norm(),
        )
    }
    /// Gradient of g at A and at B.
    fn grad_ends(&self) -> (Vector2<f64>, Vector2<f64>) {
        let v = self.b - self.a;
        let pv = Vector2::new(-v.y, v.x);
        (
            -v * self.sin_w + pv * self.cos_w,
            v * self.sin_w + pv * self.cos_w,
        )
    }
}

/// Fits the biarc of the piece between samples `s0` and `s1` of `curve` (see the module doc for
/// the joint rule) and returns it with its bilens bound.
///
/// The bound is a guarantee when the piece is a short spiral (one convexity, monotone curvature,
/// turning below pi), which spiral segmentation ensures.
pub fn fit_biarc<C: PlanarCurve + ?Sized>(
    curve: &C,
    s0: &CurveSample,
    s1: &CurveSample,
) -> Result<FittedBiarc, BiarcError> {
    let (a, b) = (s0.point, s1.point);
    let (da, db) = (s0.derivative, s1.derivative);
    let (na, nb) = (da.norm(), db.norm());
    if !(na > 0.0 && nb > 0.0 && na.is_finite() && nb.is_finite()) {
        return Err(BiarcError::ZeroTangent {
            t: if na > 0.0 { s1.t } else { s0.t },
        });
    }
    if s1.t.partial_cmp(&s0.t) != Some(std::cmp::Ordering::Greater) {
        return Err(BiarcError::EmptyInterval { t0: s0.t, t1: s1.t });
    }
    let (ta, tb) = (da / na, db / nb);
    let chord = (b - a).norm();
    if chord == 0.0 {
        return Err(BiarcError::ClosedPiece { t0: s0.t, t1: s1.t });
    }
    let jc = JCircle::new(a, ta, b, tb);
    let (ga, gb) = jc.grad_ends();
    let span = s1.t - s0.t;
    let qa = ga.dot(&da) / span;
    let qb = -gb.dot(&db) / span;
    let q = |t: f64, p: Point2<f64>| {
        let (g, settled) = jc.g_with_noise(p);
        (g / ((t - s0.t) * (s1.t - t)), settled)
    };
    let scale = DEGENERATE_JOINT_REL * chord * (na.max(nb) / span) * chord;

    let mid = || CurveSample::off_stationary(curve, 0.5 * (s0.t + s1.t), s1.t);
    let joint = if qa.abs() <= scale && qb.abs() <= scale {
        mid()
    } else {
        let j = solve_joint(curve, s0.t, s1.t, qa, qb, &q);
        if j.derivative == Vector2::zeros() {
            CurveSample::off_stationary(curve, j.t, s1.t)
        } else {
            j
        }
    };
    // On very short or straight pieces `q` is rounding noise and the root may land on an end
    // of the piece, where one arc would have no chord. Any curve point is a valid joint for
    // the bilens bound (`super::bound`), so the mid parameter replaces it; only the G1 defect
    // at the joint can grow, and it is bounded by the piece's tiny turning.
    let (joint, arcs) = match biarc_through(a, ta, &joint, b, tb)? {
        Some(arcs) => (joint, arcs),
        None => {
            let m = mid();
            match biarc_through(a, ta, &m, b, tb)? {
                Some(arcs) => (m, arcs),
                None => return Err(BiarcError::NotASpiral { t0: s0.t, t1: s1.t }),
            }
        }
    };
    let [arc0, arc1] = arcs;
    let (j, dj) = (joint.point, joint.derivative);
    let eps = bilens_bound(a, ta, j, dj, b, tb);
    Ok(FittedBiarc {
        arcs: [arc0, arc1],
        t_joint: joint.t,
        joint,
        eps,
    })
}

/// The two arcs of the biarc with joint `joint`: from `(a, ta)` to the joint, and backwards
/// from `(b, -tb)` to it; `None` when the joint coincides with an end or a tangent points
/// straight back along a chord (no minor arc).
fn biarc_through(
    a: Point2<f64>,
    ta: Vector2<f64>,
    joint: &CurveSample,
    b: Point2<f64>,
    tb: Vector2<f64>,
) -> Result<Option<[Arc; 2]>, BiarcError> {
    let dj = joint.derivative;
    if dj.norm() == 0.0 || !dj.norm().is_finite() {
        return Err(BiarcError::ZeroTangent { t: joint.t });
    }
    let arc0 = Arc::from_point_tangent_point(a, ta, joint.point);
    let arc1 = Arc::from_point_tangent_point(b, -tb, joint.point).map(|arc| arc.reversed());
    Ok(arc0.zip(arc1).map(|(x, y)| [x, y]))
}

/// Root of `q` on `(t0, t1)` by Brent's method with bracket end values `qa`, `qb`. Without a
/// sign change (not a spiral, or rounding on a near-degenerate piece) it returns the point of
/// smallest `|q|` among the bracket iterates; the bilens bound stays valid for any joint on the
/// curve, only the G1 defect grows.
fn solve_joint<C: PlanarCurve + ?Sized>(
    curve: &C,
    t0: f64,
    t1: f64,
    qa: f64,
    qb: f64,
    q: &impl Fn(f64, Point2<f64>) -> (f64, bool),
) -> CurveSample {
    if qa.signum() == qb.signum() {
        // No bracket: sample a few interior points for a sign change, else take the best.
        let mut best: Option<(f64, CurveSample)> = None;
        let mut prev = (t0, qa);
        for i in 1..16 {
            let t = t0 + (t1 - t0) * i as f64 / 16.0;
            let s = CurveSample::at(curve, t);
            let (v, _) = q(t, s.point);
            if v.signum() != prev.1.signum() {
                return brent(curve, prev.0, t, prev.1, v, q);
            }
            prev = (t, v);
            if best.is_none_or(|(bv, _)| v.abs() < bv) {
                best = Some((v.abs(), s));
            }
        }
        if qb.signum() != prev.1.signum() {
            return brent(curve, prev.0, t1, prev.1, qb, q);
        }
        return best
            .map(|(_, s)| s)
            .unwrap_or_else(|| CurveSample::at(curve, 0.5 * (t0 + t1)));
    }
    brent(curve, t0, t1, qa, qb, q)
}

/// Brent-Dekker root refinement of a bracketed sign change of `q` on `[a, b]`, returning the
/// curve sample at the root. End values are supplied (they may be limits).
fn brent<C: PlanarCurve + ?Sized>(
    curve: &C,
    mut a: f64,
    mut b: f64,
    mut fa: f64,
    mut fb: f64,
    q: &impl Fn(f64, Point2<f64>) -> (f64, bool),
) -> CurveSample {
    let (lo, hi) = (a, b);
    let mut sample_b: Option<CurveSample> = None;
    let mut c = a;
    let mut fc = fa;
    let mut d = b - a;
    let mut e = d;
    for _ in 0..JOINT_MAX_ITER {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
            sample_b = None;
        }
        let tol = 2.0 * f64::EPSILON * b.abs().max(1e-300);
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            break;
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut qq);
            if a == c {
                p = 2.0 * m * s;
                qq = 1.0 - s;
            } else {
                let r = fb / fc;
                let t = fa / fc;
                p = s * (2.0 * m * t * (t - r) - (b - a) * (r - 1.0));
                qq = (t - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                qq = -qq;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * qq - (tol * qq).abs()).min((e * qq).abs()) {
                e = d;
                d = p / qq;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        let margin = JOINT_END_MARGIN * (hi - lo);
        b = b.clamp(lo + margin, hi - margin);
        let s = CurveSample::at(curve, b);
        let (value, settled) = q(b, s.point);
        fb = value;
        if settled {
            return s;
        }
        sample_b = Some(s);
    }
    sample_b.unwrap_or_else(|| CurveSample::at(curve, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::biarc::oracle::sampled_hausdorff;
    use crate::biarc::test_curves::{Clothoid, Ellipse};
    use proptest::prelude::*;
    use std::f64::consts::FRAC_PI_2;

    /// Largest accepted `bound / sampled truth` on smooth spirals: the bilens is asymptotically
    /// ~1.7-1.9x the truth (notes `biarcs.md` section 2.2); 3 leaves room for coarse pieces.
    const MAX_BOUND_RATIO: f64 = 3.0;

    /// A clothoid spiral with one curvature sign and turning below 90 degrees.
    fn clothoid(theta0: f64, k0: f64, f: f64, length: f64) -> Clothoid {
        let k_end = k0 * f;
        let avg = 0.5 * (k0 + k_end).abs();
        let length = length.min(0.95 * FRAC_PI_2 / avg.max(1e-9));
        Clothoid::new(theta0, k0, (k_end - k0) / length, length)
    }

    fn check<C: PlanarCurve + ?Sized>(curve: &C, t0: f64, t1: f64) -> (f64, f64) {
        let s0 = CurveSample::at(curve, t0);
        let s1 = CurveSample::at(curve, t1);
        let fit = fit_biarc(curve, &s0, &s1).unwrap();
        assert!(
            fit.joint_defect() <= G1_TOL,
            "G1 defect {}",
            fit.joint_defect()
        );
        assert_eq!(fit.arcs[0].start, s0.point);
        assert_eq!(fit.arcs[1].end, s1.point);
        assert!((fit.arcs[0].end - fit.arcs[1].start).norm() == 0.0);
        let h = sampled_hausdorff(curve, t0, t1, &fit.arcs, 1500);
        assert!(h <= fit.eps, "sampled {h} > bound {}", fit.eps);
        (h, fit.eps)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        #[test]
        fn clothoid_bound_holds(
            theta0 in -3.1f64..3.1,
            k0 in prop_oneof![-4.0f64..-0.05, 0.05f64..4.0],
            f in 0.0f64..4.0,
            length in 0.05f64..2.0,
        ) {
            let c = clothoid(theta0, k0, f, length);
            let (h, eps) = check(&c, 0.0, c.length);
            prop_assert!(eps <= MAX_BOUND_RATIO * h + 1e-13, "bound {eps} vs sampled {h}");
        }
    }

    #[test]
    fn bound_ratio_and_cubic_rate_on_spirals() {
        // Halving the piece divides both the truth and the bound by ~8 (order 3).
        let c = clothoid(0.3, 0.5, 4.0, 1.5);
        let e = Ellipse { a: 2.0, b: 1.0 };
        let mut worst: f64 = 0.0;
        for (curve, t0, t1) in [
            (&c as &dyn PlanarCurve, 0.0, c.length),
            (&e as &dyn PlanarCurve, 0.05, 1.5),
        ] {
            let mut prev: Option<f64> = None;
            for level in 0..6 {
                let n = 1 << level;
                let mut hmax: f64 = 0.0;
                for i in 0..n {
                    let a = t0 + (t1 - t0) * i as f64 / n as f64;
                    let b = t0 + (t1 - t0) * (i + 1) as f64 / n as f64;
                    let (h, eps) = check(curve, a, b);
                    worst = worst.max(eps / h);
                    hmax = hmax.max(h);
                }
                // asymptotic range only: coarse pieces are pre-asymptotic
                if let (Some(p), true) = (prev, level >= 3) {
                    let rate: f64 = (p / hmax).log2();
                    assert!((2.7..3.3).contains(&rate), "level {level}: rate {rate}");
                }
                prev = Some(hmax);
            }
        }
        assert!(worst <= MAX_BOUND_RATIO, "worst bound/truth {worst}");
        eprintln!("worst bilens bound / sampled Hausdorff = {worst:.3}");
    }

    #[test]
    fn circle_and_line_are_exact() {
        let circle = |t: f64| {
            (
                Point2::new(2.0 + 3.0 * t.cos(), 3.0 * t.sin()),
                Vector2::new(-3.0 * t.sin(), 3.0 * t.cos()),
            )
        };
        let s0 = CurveSample::at(&circle, 0.2);
        let s1 = CurveSample::at(&circle, 1.4);
        let fit = fit_biarc(&circle, &s0, &s1).unwrap();
        assert!(fit.eps < 1e-12, "circle bound {}", fit.eps);
        for a in &fit.arcs {
            assert!((a.radius() - 3.0).abs() < 1e-12);
            assert!((a.center().unwrap() - Point2::new(2.0, 0.0)).norm() < 1e-12);
        }
        let line = |t: f64| (Point2::new(1.0 + t, 2.0 * t), Vector2::new(1.0, 2.0));
        let fit = fit_biarc(
            &line,
            &CurveSample::at(&line, 0.0),
            &CurveSample::at(&line, 1.0),
        )
        .unwrap();
        assert!(fit.eps < 1e-12 && fit.arcs.iter().all(|a| a.is_segment()));
        assert!(fit.joint_defect() == 0.0);
    }

    #[test]
    fn bad_input_is_an_error() {
        let pt = |_t: f64| (Point2::new(1.0, 1.0), Vector2::new(0.0, 0.0));
        let s = CurveSample::at(&pt, 0.0);
        assert!(matches!(
            fit_biarc(&pt, &s, &CurveSample::at(&pt, 1.0)),
            Err(BiarcError::ZeroTangent { .. })
        ));
        let line = |t: f64| (Point2::new(t, 0.0), Vector2::new(1.0, 0.0));
        let s0 = CurveSample::at(&line, 1.0);
        assert!(matches!(
            fit_biarc(&line, &s0, &s0),
            Err(BiarcError::EmptyInterval { .. })
        ));
    }
}

//! The nearest point of a rim circle to the other solid: where GJK converges slowly.
//!
//! A crease of a convex chain (a profile vertex where two pieces meet at an angle: a
//! cylinder's or a cone's edge) revolves into a rim circle, and the hull of the revolved
//! chain is curved only along it. When the closest points lie on a rim, GJK's simplex
//! approximates the circle by chords and its bounds close slowly (a dozen iterations for
//! a gap of 1e-4 of the size). The convex path therefore detects a rim in GJK's simplex
//! (every support point of that solid at the same meridian point, `rims` in [`super`]) and
//! minimises, over the rim's azimuth `theta`, the distance from the rim point `x(theta)` to
//! the other solid's approximating surface, which is planar in the other's meridian
//! ([`super::witness`]): `f(theta) = |x(theta) - q(theta)|`, `f'(theta) = x'(theta) . (x -
//! q) / |x - q|` (the distance's gradient is the unit vector from the nearest point). The
//! secant method on `f'` from GJK's azimuth converges in two or three steps.
//!
//! Nothing here is trusted: the pair found is two surface points, and the convex path
//! accepts it only with a lower bound from both supports that fits the width
//! (`Bounds` in [`super`]).

use super::witness::nearest_surface_point;
use crate::bvh::QueryTree;
use nalgebra::{Isometry3, Point3, Vector3};

/// Evaluations at most on a crease's rim (each one nearest-point descent and a
/// `sin_cos`): the secant converges in two or three from a near start; a far one takes a few
/// clamped steps first (measured on the convex bench: 8 answers a few more poses than 5 for
/// the same cost, 3 fewer).
pub const MAX_EVALUATIONS: usize = 8;

/// Evaluations at most on a guess (a single support point's parallel circle, GJK's first
/// iteration): worth a Newton step when GJK started along the exact direction (capsules and
/// balls: their cores' closest points), not more.
pub const GUESS_EVALUATIONS: usize = 2;

/// Largest azimuth step (radians): the secant's model is local.
const MAX_STEP: f64 = 0.5;

/// A rim of one solid: its meridian point `(rho, z)` and a start azimuth, in that solid's
/// frame; `pose` maps that frame to the other solid's (tree `other`).
pub struct Rim<'a> {
    pub meridian: (f64, f64),
    pub theta: f64,
    /// Evaluations at most ([`MAX_EVALUATIONS`], [`GUESS_EVALUATIONS`]).
    pub evaluations: usize,
    pub pose: Isometry3<f64>,
    pub other: &'a QueryTree,
}

/// One evaluation: the distance `n`, its slope in `theta`, the rim point (its own frame)
/// and the nearest surface point of the other solid (the other's frame).
struct Eval {
    n: f64,
    slope: f64,
    x: Point3<f64>,
    q: Point3<f64>,
}

impl Rim<'_> {
    fn eval(&self, theta: f64) -> Eval {
        let (rho, z) = self.meridian;
        let (s, c) = theta.sin_cos();
        let x = Point3::new(rho * c, rho * s, z);
        let xo = self.pose * x;
        let q = nearest_surface_point(self.other, &xo, &Vector3::x());
        let u = xo - q;
        let n = u.norm();
        let tangent = self.pose.rotation * Vector3::new(-rho * s, rho * c, 0.0);
        let slope = if n > 0.0 { tangent.dot(&u) / n } else { 0.0 };
        Eval { n, slope, x, q }
    }
}

/// The rim point nearest to the other solid's surface, minimised over the azimuth from the
/// rim's start until the predicted decrease `|f' step|` is below `tolerance`, from the
/// evaluation `start` at `rim.theta`: the rim point and its nearest surface point of the
/// other solid (frames as in [`Rim`]). `None` when an evaluation is not finite.
fn minimise(rim: &Rim, start: Eval, tolerance: f64) -> Option<(Point3<f64>, Point3<f64>)> {
    let mut e = start;
    let rho = rim.meridian.0;
    let mut best = (e.n, e.x, e.q);
    let mut theta = rim.theta;
    // First step: Newton with the curvature of a far target (`f'' ~ rho`).
    let mut step = if rho > 0.0 {
        (-e.slope / rho).clamp(-MAX_STEP, MAX_STEP)
    } else {
        0.0
    };
    for _ in 1..rim.evaluations {
        // Settled (or a NaN slope): stop.
        let decrease = (e.slope * step).abs();
        if decrease.is_nan() || decrease <= tolerance {
            break;
        }
        let (theta_prev, slope_prev) = (theta, e.slope);
        theta += step;
        e = rim.eval(theta);
        if !e.n.is_finite() {
            return None;
        }
        if e.n < best.0 {
            best = (e.n, e.x, e.q);
        }
        let curvature = (e.slope - slope_prev) / (theta - theta_prev);
        let model = if curvature > 0.0 { curvature } else { rho };
        step = (-e.slope / model).clamp(-MAX_STEP, MAX_STEP);
    }
    best.0.is_finite().then_some((best.1, best.2))
}

/// The rims given, the one whose start point is nearer to the other solid first, each
/// minimised (`minimise`) and handed to `accept` (with its index) until one is accepted.
pub fn first_accepted<T>(
    rims: &[Option<Rim>; 2],
    tolerance: f64,
    mut accept: impl FnMut(usize, Point3<f64>, Point3<f64>) -> Option<T>,
) -> Option<T> {
    let mut starts: [Option<(usize, Eval)>; 2] = [0, 1].map(|k| {
        rims[k]
            .as_ref()
            .map(|r| (k, r.eval(r.theta)))
            .filter(|(_, e)| e.n.is_finite())
    });
    if let [Some((_, a)), Some((_, b))] = &starts {
        if b.n < a.n {
            starts.swap(0, 1);
        }
    }
    for (k, start) in starts.into_iter().flatten() {
        let rim = rims[k].as_ref()?;
        if let Some((x, q)) = minimise(rim, start, tolerance) {
            if let Some(t) = accept(k, x, q) {
                return Some(t);
            }
        }
    }
    None
}

//! Local minimisation of the distance from B(theta) to circle A along B (1-D), with the
//! closed-form point-to-circle distance (paper section 3: every normal of a circle meets its
//! axis). Everything is evaluated in the numerically stable meridian form
//! `f = |(rho - ra, z)|`, never as a difference of squares, so distances far below the
//! configuration scale (nearly touching circles) keep full relative accuracy.

use super::frame::LocalPair;

/// Cap on descent iterations. Newton converges quadratically at a non-degenerate minimum
/// (5-6 steps from a root of the binormal polynomial); at a degenerate (flat) minimum it is
/// linear with ratio <= 2/3 and 64 steps shrink the start error by 5e-12.
const MAX_STEPS: usize = 64;

/// Largest angle step (radians): keeps a step from jumping across the circle when the
/// curvature is tiny or negative (at a local maximum of f).
const MAX_STEP: f64 = 0.25;

/// Step halvings tried before a step is declared useless (2^-40 ~ 1e-12 of `MAX_STEP`).
const MAX_HALVINGS: usize = 40;

/// A full Newton step below this (radians) ends the descent: the next step would be
/// ~1e-18 times the curvature ratio h'''/h''.
const NEWTON_DONE: f64 = 1e-9;

/// A step below this (radians) ends the descent: theta is then known to a few ulps.
const MIN_STEP: f64 = 1e-15;

/// f(theta) = distance from B(theta) to A, and the derivatives of h = f^2 / 2.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sample {
    pub f: f64,
    /// h'(theta) = (B - K) . B' with K the nearest point of A.
    pub dh: f64,
    /// h''(theta); -infinity on A's axis (where f has a ridge).
    pub ddh: f64,
}

/// Evaluates f and the derivatives of f^2 / 2 at `theta`.
#[inline]
pub(crate) fn sample(lp: &LocalPair, theta: f64) -> Sample {
    let (st, ct) = theta.sin_cos();
    sample_sc(lp, st, ct)
}

/// [`sample`] from sin theta and cos theta. Plain square roots instead of `hypot`: the
/// frame has unit scale, so squares neither overflow nor underflow for any distance above
/// 1e-150 of the scale.
#[inline]
pub(crate) fn sample_sc(lp: &LocalPair, st: f64, ct: f64) -> Sample {
    let w = ct * lp.u + st * lp.v;
    let q = lp.c + lp.rb * w;
    let dq = lp.rb * (ct * lp.v - st * lp.u);
    let rho = (q.x * q.x + q.y * q.y).sqrt();
    let dr = rho - lp.ra;
    let f = (dr * dr + q.z * q.z).sqrt();
    if rho == 0.0 {
        return Sample {
            f,
            dh: 0.0,
            ddh: f64::NEG_INFINITY,
        };
    }
    let inv = 1.0 / rho;
    let (ex, ey) = (q.x * inv, q.y * inv);
    let radial = ex * dq.x + ey * dq.y;
    let tangential = ex * dq.y - ey * dq.x;
    // D = B - K = (rho - ra) e + z e_z; B'' = -rb w.
    let dh = dr * radial + q.z * dq.z;
    let d_dot_ddq = -lp.rb * (dr * (ex * w.x + ey * w.y) + q.z * w.z);
    let ddh = dq.norm_squared() - lp.ra * inv * tangential * tangential + d_dot_ddq;
    Sample { f, dh, ddh }
}

/// Angle on A of the point nearest to B(theta) (0 when B(theta) is on A's axis).
pub(crate) fn foot_angle(lp: &LocalPair, theta: f64) -> f64 {
    let q = lp.pb(theta);
    if q.x == 0.0 && q.y == 0.0 {
        0.0
    } else {
        q.y.atan2(q.x)
    }
}

/// Descends f from `theta0` to a local minimum: Newton on h' where h'' > 0, otherwise a
/// bounded step downhill, each step halved until f does not increase. Returns the final
/// theta and its sample.
pub(crate) fn descend(lp: &LocalPair, theta0: f64) -> (f64, Sample) {
    let mut theta = theta0;
    let mut cur = sample(lp, theta);
    for _ in 0..MAX_STEPS {
        let mut step = if cur.ddh > 0.0 {
            -cur.dh / cur.ddh
        } else if cur.dh != 0.0 {
            -MAX_STEP.copysign(cur.dh)
        } else {
            // A critical point that is not a minimum (a maximum or A's axis): try both ways.
            let fwd = sample(lp, theta + MAX_STEP * 1e-3);
            let bwd = sample(lp, theta - MAX_STEP * 1e-3);
            if fwd.f.min(bwd.f) >= cur.f {
                break;
            }
            if fwd.f <= bwd.f {
                MAX_STEP * 1e-3
            } else {
                -MAX_STEP * 1e-3
            }
        };
        if !step.is_finite() {
            break;
        }
        step = step.clamp(-MAX_STEP, MAX_STEP);
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let next = sample(lp, theta + step);
            if next.f <= cur.f {
                accepted = Some(next);
                break;
            }
            step *= 0.5;
            if step.abs() <= MIN_STEP {
                break;
            }
        }
        let Some(next) = accepted else {
            break;
        };
        theta += step;
        // A Newton step below NEWTON_DONE leaves an error ~ step^2 (quadratic convergence):
        // far below rounding, also for h = f^2 / 2 when f itself is tiny.
        let newton = cur.ddh > 0.0;
        let done = step.abs() <= MIN_STEP
            || (newton && step.abs() <= NEWTON_DONE)
            || next.f == cur.f && step.abs() <= 1e-9;
        cur = next;
        if done {
            break;
        }
    }
    (theta, cur)
}

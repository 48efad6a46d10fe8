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

/// sin and cos of a step `x` with `|x| <= MAX_STEP` (0.25): Taylor polynomials to x^11 and
/// x^12, whose truncation errors (`|x|^13 / 13!` ~ 2.4e-18 and `|x|^14 / 14!` ~ 4e-20) are
/// below half an ulp of the results. The descent rotates (sin theta, cos theta) by the step
/// instead of calling `sin_cos` for every trial (a third of a circle minimum's time).
#[inline]
fn small_sin_cos(x: f64) -> (f64, f64) {
    debug_assert!(x.abs() <= MAX_STEP * (1.0 + 1e-12));
    let x2 = x * x;
    let s = x
        * (1.0
            + x2 * (-1.0 / 6.0
                + x2 * (1.0 / 120.0
                    + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0 + x2 * (-1.0 / 39_916_800.0))))));
    let c = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0
                    + x2 * (1.0 / 40_320.0
                        + x2 * (-1.0 / 3_628_800.0 + x2 * (1.0 / 479_001_600.0))))));
    (s, c)
}

/// (sin, cos) of `theta + x` from (sin, cos) of `theta` = `sc` and a step `|x| <= MAX_STEP`.
#[inline]
fn rotate(sc: (f64, f64), x: f64) -> (f64, f64) {
    let (sx, cx) = small_sin_cos(x);
    (sc.0 * cx + sc.1 * sx, sc.1 * cx - sc.0 * sx)
}

/// f^2 alone at the angle whose sine and cosine are `st`, `ct`: one square root instead of
/// [`sample_sc`]'s two and a division, for choosing a start among samples.
#[inline]
pub(crate) fn f_squared_sc(lp: &LocalPair, st: f64, ct: f64) -> f64 {
    let q = lp.c + lp.rb * (ct * lp.u + st * lp.v);
    let dr = (q.x * q.x + q.y * q.y).sqrt() - lp.ra;
    dr * dr + q.z * q.z
}

/// f and the derivatives of f^2 / 2 at the angle whose sine and cosine are `st`, `ct`. Plain square roots instead of `hypot`: the
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
    let (t, s, _) = descend_sc(lp, theta0);
    (t, s)
}

/// [`descend`], also returning (sin theta, cos theta) of the final angle.
pub(crate) fn descend_sc(lp: &LocalPair, theta0: f64) -> (f64, Sample, (f64, f64)) {
    let mut theta = theta0;
    // (sin theta, cos theta), carried along by rotations (`rotate`); the final sample is
    // re-evaluated from `theta` itself, so the returned pair is consistent to the last ulp.
    let mut sc = theta.sin_cos();
    let mut cur = sample_sc(lp, sc.0, sc.1);
    let mut moved = false;
    for _ in 0..MAX_STEPS {
        let mut step = if cur.ddh > 0.0 {
            -cur.dh / cur.ddh
        } else if cur.dh != 0.0 {
            -MAX_STEP.copysign(cur.dh)
        } else {
            // A critical point that is not a minimum (a maximum or A's axis): try both ways.
            let probe = MAX_STEP * 1e-3;
            let (sf, cf) = rotate(sc, probe);
            let (sb, cb) = rotate(sc, -probe);
            let fwd = sample_sc(lp, sf, cf);
            let bwd = sample_sc(lp, sb, cb);
            if fwd.f.min(bwd.f) >= cur.f {
                break;
            }
            if fwd.f <= bwd.f {
                probe
            } else {
                -probe
            }
        };
        if !step.is_finite() {
            break;
        }
        step = step.clamp(-MAX_STEP, MAX_STEP);
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let next_sc = rotate(sc, step);
            let next = sample_sc(lp, next_sc.0, next_sc.1);
            if next.f <= cur.f {
                accepted = Some((next, next_sc));
                break;
            }
            step *= 0.5;
            if step.abs() <= MIN_STEP {
                break;
            }
        }
        let Some((next, next_sc)) = accepted else {
            break;
        };
        theta += step;
        sc = next_sc;
        moved = true;
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
    if moved {
        sc = theta.sin_cos();
        cur = sample_sc(lp, sc.0, sc.1);
    }
    (theta, cur, sc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_sin_cos_matches_libm() {
        for k in -1000..=1000 {
            let x = MAX_STEP * k as f64 / 1000.0;
            let (s, c) = small_sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!(
                (s - s0).abs() <= 2.0 * f64::EPSILON * s0.abs().max(1e-300),
                "{x}: {s} vs {s0}"
            );
            assert!((c - c0).abs() <= 2.0 * f64::EPSILON, "{x}: {c} vs {c0}");
        }
    }

    #[test]
    fn rotations_track_the_angle() {
        let mut sc = 0.3f64.sin_cos();
        let mut theta = 0.3;
        for k in 0..200 {
            let step = MAX_STEP * ((k * 37 % 101) as f64 / 50.0 - 1.0);
            sc = rotate(sc, step);
            theta += step;
        }
        let (s0, c0) = theta.sin_cos();
        assert!((sc.0 - s0).abs() < 1e-13 && (sc.1 - c0).abs() < 1e-13);
    }
}

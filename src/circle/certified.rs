//! Fast certified minimum distance for circles in general position.
//!
//! Let f(theta) be the distance from B(theta) to circle A (closed form, see
//! [`super::descent`]). A descent from the best of a few samples gives a local minimum
//! m = f(t). Whether any theta has f(theta) < m is then decided exactly, up to rounding of a
//! few coefficients, by a quartic (Vranek 2002; `docs/numerics.md` section 1c): with
//! T1 = |B|^2 + ra^2 and T2 = Bx^2 + By^2 (A in its own frame),
//!
//! `Q(theta) = (T1 - m^2)^2 - 4 ra^2 T2 = (f^2 - m^2) (f_far^2 - m^2)`,
//!
//! a trigonometric polynomial of degree 2, where f_far is the distance to the farthest point
//! of A. When ra >= m, f < m implies f_far >= 2 ra - f > m, so {f < m} = {Q < 0}. In
//! u = tan((theta - t) / 2), `(1 + u^2)^2 Q = u^2 R(u) + (q0 + q1 u)` with q0, q1 ~ 0 (t is a
//! critical point with value m) and R quadratic. If R is positive for all u with a margin
//! above its rounding error, m is the global minimum; if R has two well-separated real roots
//! the arc between them holds a deeper basin, which is descended into and certified in turn.
//! Anything else (ties, flat or continuum minima, extreme radius ratios) is left to the
//! polynomial solver by returning `None`.

use super::descent::{descend_sc, f_squared_sc};
use super::frame::LocalPair;
use super::TIE_REL_TOL;
use std::f64::consts::TAU;

/// Number of equally spaced starting samples of f: a deeper basin missed by the samples is
/// found by the certificate anyway, so few are needed.
const N_SAMPLES: usize = 8;

/// (sin, cos) of 2 pi k / N_SAMPLES.
const SAMPLE_SIN_COS: [(f64, f64); N_SAMPLES] = {
    const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
    [
        (0.0, 1.0),
        (H, H),
        (1.0, 0.0),
        (H, -H),
        (0.0, -1.0),
        (-H, -H),
        (-1.0, 0.0),
        (-H, H),
    ]
};

/// Deeper basins followed before giving up (a generic pair has at most 2 local minima of f
/// per theta basin structure; 4 leaves margin).
const MAX_BASINS: usize = 4;

/// Rounding bound of Q's trigonometric coefficients relative to the sum of the magnitudes
/// of the terms they are built from: each is a sum of at most a dozen products of terms
/// with a few roundings each; 64 eps covers it with margin.
const Q_NOISE_FACTOR: f64 = 64.0 * f64::EPSILON;

/// The foot on A must be at least this far from B's axis and B(t) this far from A's axis
/// (local units, scale 1): closer, the minimum may belong to a continuum of closest pairs.
const AXIS_CLEARANCE: f64 = 1e-6;

/// Largest decrease of f (unit scale) still available by descending from the returned
/// angle: 1e-14, a hundredth of the solver's promised 1e-12 accuracy
/// ([`crate::circle::TIE_REL_TOL`]).
const MIN_GAIN: f64 = 1e-14;

/// A certified minimum in local units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Certified {
    pub phi: f64,
    pub theta: f64,
    pub dist: f64,
}

/// Trigonometric coefficients of Q: Q = c0 + c1 cos + s1 sin + c2 cos 2 + s2 sin 2.
struct TrigQ {
    c0: f64,
    c1: f64,
    s1: f64,
    c2: f64,
    s2: f64,
    /// Absolute rounding bound of each coefficient.
    noise: f64,
}

fn trig_q(lp: &LocalPair, m: f64) -> TrigQ {
    let (c, u, v, ra, rb) = (lp.c, lp.u, lp.v, lp.ra, lp.rb);
    // T1 - m^2 = a0 + a1 cos + b1 sin.
    let a0 = c.norm_squared() + rb * rb + ra * ra - m * m;
    let a1 = 2.0 * rb * c.dot(&u);
    let b1 = 2.0 * rb * c.dot(&v);
    // T2 = d0 + d1 cos + e1 sin + d2 cos 2 + e2 sin 2.
    let (uu, vv, uv) = (
        u.x * u.x + u.y * u.y,
        v.x * v.x + v.y * v.y,
        u.x * v.x + u.y * v.y,
    );
    let d0 = c.x * c.x + c.y * c.y + 0.5 * rb * rb * (uu + vv);
    let d1 = 2.0 * rb * (c.x * u.x + c.y * u.y);
    let e1 = 2.0 * rb * (c.x * v.x + c.y * v.y);
    let d2 = 0.5 * rb * rb * (uu - vv);
    let e2 = rb * rb * uv;
    let k = 4.0 * ra * ra;
    let mag = (a0.abs() + a1.abs() + b1.abs()).powi(2)
        + k * (d0.abs() + d1.abs() + e1.abs() + d2.abs() + e2.abs())
        + m * m * (a0.abs() + 1.0);
    TrigQ {
        c0: a0 * a0 + 0.5 * (a1 * a1 + b1 * b1) - k * d0,
        c1: 2.0 * a0 * a1 - k * d1,
        s1: 2.0 * a0 * b1 - k * e1,
        c2: 0.5 * (a1 * a1 - b1 * b1) - k * d2,
        s2: a1 * b1 - k * e2,
        noise: Q_NOISE_FACTOR * mag,
    }
}

/// True when the farthest point of A is farther than `m` from every B(theta):
/// f_far^2 = T1 + 2 ra rho >= T1 = |B|^2 + ra^2 >= m^2 whenever min T1 =
/// a0 - |(a1, b1)| exceeds m^2 (with margin). Then {f < m} = {Q < 0} even when ra < m.
fn far_points_beyond(lp: &LocalPair, m: f64) -> bool {
    let (c, rb) = (lp.c, lp.rb);
    let a0 = c.norm_squared() + rb * rb + lp.ra * lp.ra;
    let amp = (2.0 * rb * c.dot(&lp.u)).hypot(2.0 * rb * c.dot(&lp.v));
    a0 - amp > m * m * (1.0 + 1e-9) + Q_NOISE_FACTOR * (a0 + amp)
}

/// Outcome of the certificate at a local minimum.
enum Verdict {
    /// No theta has f < m.
    Global,
    /// A deeper basin lies around this angle.
    Deeper(f64),
    /// Too close to call.
    Unsure,
}

/// Decides whether some theta has f(theta) < m, given the local minimum f(t) = m.
fn certify(lp: &LocalPair, t: f64, (st, ct): (f64, f64), m: f64) -> Verdict {
    let q = trig_q(lp, m);
    let (s2t, c2t) = (2.0 * st * ct, ct * ct - st * st);
    // Q in alpha = theta - t.
    let a1 = q.c1 * ct + q.s1 * st;
    let b1 = q.s1 * ct - q.c1 * st;
    let a2 = q.c2 * c2t + q.s2 * s2t;
    let b2 = q.s2 * c2t - q.c2 * s2t;
    let a0 = q.c0;
    // (1 + u^2)^2 Q = q0 + q1 u + q2 u^2 + q3 u^3 + q4 u^4.
    let q2 = 2.0 * a0 - 6.0 * a2;
    let q3 = 2.0 * b1 - 4.0 * b2;
    let q4 = a0 - a1 + a2;
    // Rounding of the five coefficients reaches each q_k with weight <= 8. The margin also
    // covers ties: another basin within TIE_REL_TOL of m has |Q| <= 2 m TIE (f_far^2 - m^2)
    // there, with f_far^2 <= (2 ra + m + 2)^2 at unit scale; R = Q (1 + u^2)^2 / u^2 >= 4 Q.
    let tie = 8.0 * m * TIE_REL_TOL * (2.0 * lp.ra + m + 2.0).powi(2);
    let e = 8.0 * q.noise + tie;
    if q2 <= e {
        // Flat minimum: leave it to the polynomial solver.
        return Verdict::Unsure;
    }
    // R(u) = q4 u^2 + q3 u + q2 >= e (1 + |u| + u^2) for all u: certain positivity.
    if q4 > e && (q3.abs() + e).powi(2) < 4.0 * (q2 - e) * (q4 - e) {
        return Verdict::Global;
    }
    let disc = q3 * q3 - 4.0 * q2 * q4;
    if q4.abs() <= e || disc <= 4.0 * e * (q2 + q3.abs() + q4.abs()) {
        return Verdict::Unsure;
    }
    // Two separated real roots; R < 0 between them (q4 > 0) or beyond them (q4 < 0).
    let sq = disc.sqrt();
    let r1 = -2.0 * q2 / (q3 + sq.copysign(q3));
    let r2 = q2 / (q4 * r1);
    let (al1, al2) = (2.0 * r1.atan(), 2.0 * r2.atan());
    let to_circle = |a: f64| if a < 0.0 { a + TAU } else { a };
    let (x1, x2) = (to_circle(al1), to_circle(al2));
    // The arc not containing alpha = 0 (alpha in (0, 2 pi)).
    let mid = if q4 > 0.0 {
        0.5 * (x1 + x2)
    } else {
        // Roots of opposite signs: the arc through alpha = pi.
        0.5 * (al1.max(al2) + al1.min(al2) + TAU)
    };
    Verdict::Deeper(t + mid)
}

/// The certified global minimum of f along B, or `None` when the certificate cannot decide.
/// Meant for B the smaller circle (ra >= rb), so that ra >= m holds in general position.
pub(crate) fn certified_min(lp: &LocalPair) -> Option<Certified> {
    // Start from the best of a few samples.
    // f^2 at the samples (the vertex below is a start heuristic; the descent is
    // safeguarded either way).
    let f: [f64; N_SAMPLES] = std::array::from_fn(|k| {
        let (st, ct) = SAMPLE_SIN_COS[k];
        f_squared_sc(lp, st, ct)
    });
    let k = (0..N_SAMPLES).fold(0, |b, k| if f[k] < f[b] { k } else { b });
    // Vertex of the parabola through the best sample and its neighbours (a closer start
    // saves Newton steps; the descent is safeguarded either way).
    let (fm, f0, fp) = (
        f[(k + N_SAMPLES - 1) % N_SAMPLES],
        f[k],
        f[(k + 1) % N_SAMPLES],
    );
    let curv = fm - 2.0 * f0 + fp;
    let offset = if curv > 0.0 {
        (0.5 * (fm - fp) / curv).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    let start = TAU * (k as f64 + offset) / N_SAMPLES as f64;
    let (mut t, mut smp, mut sc) = descend_sc(lp, start);
    for _ in 0..MAX_BASINS {
        let m = smp.f;
        // A proper local minimum: convex, and the remaining Newton decrease of h = f^2 / 2,
        // h'^2 / (2 h''), moves f by less than MIN_GAIN (unit scale).
        let convex = smp.ddh > 0.0 && smp.dh * smp.dh <= 2.0 * smp.ddh * MIN_GAIN * m;
        let far_beyond = lp.ra >= m * (1.0 + 1e-6) || far_points_beyond(lp, m);
        if !convex || !far_beyond {
            return None;
        }
        match certify(lp, t, sc, m) {
            Verdict::Global => {
                // Continua of closest pairs are reported by the general solver. B(t) from
                // the descent's (sin, cos); the foot on A is B(t)'s radial direction
                // scaled to A's radius (no trigonometry).
                let qb = lp.c + lp.rb * (sc.1 * lp.u + sc.0 * lp.v);
                let rho = (qb.x * qb.x + qb.y * qb.y).sqrt();
                if rho <= AXIS_CLEARANCE {
                    return None;
                }
                let nb = lp.u.cross(&lp.v);
                let foot = nalgebra::Vector3::new(lp.ra * qb.x / rho, lp.ra * qb.y / rho, 0.0);
                if (foot - lp.c).cross(&nb).norm() <= AXIS_CLEARANCE {
                    return None;
                }
                return Some(Certified {
                    phi: qb.y.atan2(qb.x),
                    theta: t,
                    dist: m,
                });
            }
            Verdict::Deeper(th) => {
                let (t2, s2, sc2) = descend_sc(lp, th);
                let deeper = s2.f < m;
                if !deeper {
                    return None;
                }
                (t, smp, sc) = (t2, s2, sc2);
            }
            Verdict::Unsure => return None,
        }
    }
    None
}

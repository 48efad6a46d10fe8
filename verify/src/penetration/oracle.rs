//! Independent references for the penetration depth, on the exact profiles through the
//! query oracle's own planar distance ([`crate::oracle::PlanarIndex`]); nothing here calls
//! `revdist::query`.
//!
//! * [`ball_depth`]: the exact depth of a ball of radius `r` centred at `c` against a solid A:
//!   B + t is apart from A exactly when the centre `c + t` is at distance `>= r` from A, so
//!   `PD = dist(c, {y : d(y, A) >= r})`. That set is a solid of revolution about A's axis,
//!   and the nearest point of it to `c` lies in `c`'s meridian plane, so PD is a planar
//!   distance: from `c`'s meridian point to the level set `d >= r` of the profile's distance
//!   (the whole meridian plane, the half `rho < 0` mirrored). Each ray from the meridian
//!   point is marched to its first crossing (the distance is 1-Lipschitz, so a step of
//!   `r - d` never passes it) and the best ray refined by golden section.
//! * [`common_point_bound`]: the oracle's lower bound of PD, `c_A(x) + c_B(x)` at the best
//!   point it finds (random samples and a compass search), each clearance the exact
//!   profile's signed distance (positive inside, negative outside). A positive sum is a lower
//!   bound wherever `x` is: inside A with clearance `c_A`, the ball `U(x, c_A)` lies in A,
//!   and a translation `t` of B shorter than `c_A + c_B(x)` leaves B's signed distance at `x`
//!   above `-c_A` (it is 1-Lipschitz), so B still meets that ball.
//! * [`separating_length`]: the shortest separating translation the oracle finds along a
//!   direction (bisection on the oracle's quick census, the final length confirmed by the
//!   full oracle), an upper bound of PD.

use crate::oracle::{surface_distance, OracleOptions, PlanarIndex};
use nalgebra::{Isometry3, Point3, Translation3, Vector3};
use revdist::rng::SplitMix64;

/// Clearance of `x` (the solid's own frame) from the exact boundary: positive inside.
pub fn clearance(idx: &PlanarIndex, x: &Point3<f64>) -> f64 {
    -idx.signed([x.x.hypot(x.y), x.z]).value
}

/// Rays per full turn in [`ball_depth`].
const RAYS: usize = 1440;

/// Marching steps per ray.
const MARCH_STEPS: usize = 400;

/// Exact translational depth of the ball `U(c, r)` (A's frame) against A ([module doc]);
/// `size` is A's size (the marching tolerance is `1e-12 size`).
pub fn ball_depth(a: &PlanarIndex, c: &Point3<f64>, r: f64, size: f64) -> f64 {
    let m0 = [c.x.hypot(c.y), c.z];
    let tol = 1e-12 * size;
    let outside = |m: [f64; 2]| a.signed([m[0].abs(), m[1]]).value;
    if outside(m0) >= r {
        return 0.0;
    }
    let march = |phi: f64| -> f64 {
        let (dx, dz) = (phi.cos(), phi.sin());
        let mut s = 0.0;
        for _ in 0..MARCH_STEPS {
            let v = outside([m0[0] + s * dx, m0[1] + s * dz]);
            if v >= r - tol {
                return s;
            }
            s += (r - v).max(tol);
            if s > 100.0 * (size + r) {
                break;
            }
        }
        f64::INFINITY
    };
    let step = std::f64::consts::TAU / RAYS as f64;
    let (mut best_phi, mut best) = (0.0, f64::INFINITY);
    for k in 0..RAYS {
        let phi = k as f64 * step;
        let s = march(phi);
        if s < best {
            (best_phi, best) = (phi, s);
        }
    }
    // Golden section on the best ray's neighbourhood.
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (best_phi - step, best_phi + step);
    for _ in 0..40 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (f1, f2) = (march(x1), march(x2));
        best = best.min(f1).min(f2);
        if f1 < f2 {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    best
}

/// The oracle's lower bound of PD: the best positive `c_A(x) + c_B(x)` over points found
/// from `seeds` (A's frame) and `samples` random points in the box of half-size `reach`
/// about the first seed, then a compass search; 0 when no positive sum was found.
pub fn common_point_bound(
    a: &PlanarIndex,
    b: &PlanarIndex,
    pos_ab: &Isometry3<f64>,
    seeds: &[Point3<f64>],
    reach: f64,
    samples: usize,
    rng: &mut SplitMix64,
) -> f64 {
    let pos_ba = pos_ab.inverse();
    let value = |x: &Point3<f64>| {
        let (ca, cb) = (clearance(a, x), clearance(b, &(pos_ba * x)));
        (ca + cb).max(0.0)
    };
    let Some(&centre) = seeds.first() else {
        return 0.0;
    };
    let mut best = (0.0, centre);
    let consider = |x: Point3<f64>, best: &mut (f64, Point3<f64>)| {
        let v = value(&x);
        if v > best.0 {
            *best = (v, x);
        }
    };
    for s in seeds {
        consider(*s, &mut best);
    }
    for _ in 0..samples {
        let d = Vector3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        consider(centre + d * reach, &mut best);
    }
    let mut h = 0.125 * reach;
    while h > 1e-9 * reach {
        let x = best.1;
        let before = best.0;
        for d in [
            Vector3::x(),
            -Vector3::x(),
            Vector3::y(),
            -Vector3::y(),
            Vector3::z(),
            -Vector3::z(),
        ] {
            consider(x + d * h, &mut best);
        }
        if best.0 <= before {
            h *= 0.5;
        }
    }
    best.0
}

/// B moved by `t` (A's frame).
fn moved(pos_ab: &Isometry3<f64>, t: &Vector3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::from(pos_ab.translation.vector + t),
        pos_ab.rotation,
    )
}

/// The quick oracle's verdict at `pos`: no boundary sample inside the other solid and a
/// positive realised gap (optimistic: the full oracle confirms what matters).
fn apart_quick(a: &PlanarIndex, b: &PlanarIndex, pos: &Isometry3<f64>) -> bool {
    let r = surface_distance(a, b, pos, &OracleOptions::quick());
    !r.overlap() && r.upper > 0.0
}

/// The full oracle's verdict at `pos`: `Some(true)` apart (positive lower estimate and no
/// sample inside), `Some(false)` a boundary sample certainly inside the other solid,
/// `None` undecided.
pub fn apart_full(a: &PlanarIndex, b: &PlanarIndex, pos: &Isometry3<f64>) -> Option<bool> {
    let r = surface_distance(a, b, pos, &OracleOptions::full());
    if r.overlap() {
        Some(false)
    } else if r.lower > 0.0 {
        Some(true)
    } else {
        None
    }
}

/// Whether B moved by `t` is apart from A by the full oracle ([`apart_full`]).
pub fn apart_at(
    a: &PlanarIndex,
    b: &PlanarIndex,
    pos_ab: &Isometry3<f64>,
    t: &Vector3<f64>,
) -> Option<bool> {
    apart_full(a, b, &moved(pos_ab, t))
}

/// The shortest separating length the oracle finds along the unit direction `u`, starting
/// from `s_hi` (grown until apart): bisection on `apart_quick`, the result confirmed by
/// [`apart_full`]. `None` when nothing was confirmed.
pub fn separating_length(
    a: &PlanarIndex,
    b: &PlanarIndex,
    pos_ab: &Isometry3<f64>,
    u: &Vector3<f64>,
    mut s_hi: f64,
    steps: usize,
) -> Option<f64> {
    let mut grown = 0;
    while !apart_quick(a, b, &moved(pos_ab, &(u * s_hi))) {
        s_hi *= 2.0;
        grown += 1;
        if grown > 6 {
            return None;
        }
    }
    let mut s_lo = 0.0;
    for _ in 0..steps {
        let mid = 0.5 * (s_lo + s_hi);
        if apart_quick(a, b, &moved(pos_ab, &(u * mid))) {
            s_hi = mid;
        } else {
            s_lo = mid;
        }
    }
    (apart_at(a, b, pos_ab, &(u * s_hi)) == Some(true)).then_some(s_hi)
}

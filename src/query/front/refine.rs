//! Refinement of the witness points on the exact NURBS surfaces of revolution: alternating
//! closest-point projections between the two exact surfaces, started at the tree's witness
//! points. A point's closest point on a surface of revolution is the
//! planar closest point of its meridian coordinates `(rho, z)` on the profile, found by
//! Newton's method on `(C(t) - m) . C'(t) = 0` from the best of a coarse sampling. Each
//! projection does not increase the distance, so the iteration converges to a local
//! minimum (a common normal) near the witnesses; the two final points lie on the exact
//! boundaries, so their distance is a valid upper bound of the distance of the solids'
//! boundaries.

use crate::bvh::patch::lift;
use crate::nurbs::NurbsCurve;
use crate::profile::Profile;
use crate::solid::Solid;
use crate::tolerances::REFINE_CONVERGENCE;
use nalgebra::{Isometry3, Point2, Point3, Vector3};

/// Samples per profile piece for the initial closest-point search.
const SAMPLES_PER_PIECE: usize = 48;
/// Maximum alternating rounds.
const MAX_ROUNDS: usize = 200;

/// Refined witnesses on the exact surfaces (A's frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Refined {
    pub distance: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
}

/// Closest point of the profile to the meridian point `m`: (distance, point, piece, t).
fn closest_on_profile(
    profile: &Profile,
    m: Point2<f64>,
    hint: Option<(usize, f64)>,
) -> (f64, Point2<f64>, usize, f64) {
    let mut best = (f64::INFINITY, m, 0usize, 0.0);
    let mut starts: Vec<(usize, f64)> = Vec::new();
    if let Some(h) = hint {
        starts.push(h);
    } else {
        for (i, c) in profile.pieces().iter().enumerate() {
            let (t0, t1) = c.domain();
            let mut local = (f64::INFINITY, t0);
            for k in 0..=SAMPLES_PER_PIECE {
                let t = t0 + (t1 - t0) * k as f64 / SAMPLES_PER_PIECE as f64;
                let d = (c.eval(t) - m).norm();
                if d < local.0 {
                    local = (d, t);
                }
            }
            starts.push((i, local.1));
        }
    }
    for (i, t) in starts {
        let c = &profile.pieces()[i];
        let t = newton_project(c, m, t);
        let p = c.eval(t);
        let d = (p - m).norm();
        if d < best.0 {
            best = (d, p, i, t);
        }
    }
    best
}

/// Newton iteration for the foot of `m` on curve `c`, clamped to the domain.
fn newton_project(c: &NurbsCurve, m: Point2<f64>, mut t: f64) -> f64 {
    let (t0, t1) = c.domain();
    for _ in 0..30 {
        let [p, d1, d2, _] = c.derivatives(t);
        let r = p - m.coords;
        let g = r.dot(&d1);
        let h = d1.dot(&d1) + r.dot(&d2);
        if h <= 0.0 {
            break;
        }
        let tn = (t - g / h).clamp(t0, t1);
        if (tn - t).abs() <= 1e-15 * (t1 - t0) {
            t = tn;
            break;
        }
        t = tn;
    }
    t
}

/// Closest point on the exact surface of revolution of `profile` to `x` (profile frame).
fn project(
    profile: &Profile,
    x: &Point3<f64>,
    hint: Option<(usize, f64)>,
) -> (Point3<f64>, usize, f64) {
    let rho = x.x.hypot(x.y);
    let e = if rho > 0.0 {
        Vector3::new(x.x / rho, x.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    let m = Point2::new(rho, x.z);
    let mut r = closest_on_profile(profile, m, hint);
    if hint.is_some() {
        // Guard against the local search being stuck at a piece end.
        let (t0, t1) = profile.pieces()[r.2].domain();
        if r.3 <= t0 || r.3 >= t1 {
            let g = closest_on_profile(profile, m, None);
            if g.0 < r.0 {
                r = g;
            }
        }
    }
    (lift(r.1, &e), r.2, r.3)
}

/// Alternating projections from the witnesses `pa`, `pb` (A's frame).
pub fn refine_on_profiles(
    a: &Solid,
    b: &Solid,
    pos_ab: &Isometry3<f64>,
    pa: &Point3<f64>,
    pb: &Point3<f64>,
) -> Option<Refined> {
    let (prof_a, prof_b) = (a.profile.as_deref()?, b.profile.as_deref()?);
    let pos_ba = pos_ab.inverse();
    let (mut p, mut ha, _) = {
        let (p, i, t) = project(prof_a, pa, None);
        (p, Some((i, t)), ())
    };
    let (q_local, i, t) = project(prof_b, &(pos_ba * pb), None);
    let mut hb = Some((i, t));
    let mut q = pos_ab * q_local;
    let mut d = (p - q).norm();
    let scale = 1.0 + p.coords.norm() + q.coords.norm();
    for _ in 0..MAX_ROUNDS {
        let (np, i, t) = project(prof_a, &q, ha);
        ha = Some((i, t));
        let (nq_local, j, u) = project(prof_b, &(pos_ba * np), hb);
        hb = Some((j, u));
        let nq = pos_ab * nq_local;
        let nd = (np - nq).norm();
        if nd > d {
            break;
        }
        let moved = d - nd;
        p = np;
        q = nq;
        d = nd;
        if moved <= REFINE_CONVERGENCE * scale {
            break;
        }
    }
    Some(Refined {
        distance: d,
        point_a: p,
        point_b: q,
    })
}

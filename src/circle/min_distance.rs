//! The minimum distance of two circles (paper section 3.2): general pairs take the certified
//! fast path of `super::certified`; axes that meet take a closed form; the rest descend the
//! closed-form distance along B (`super::descent`) from every root and root cluster of the
//! binormal polynomial ([`super::binormal`]), with each circle parametrised in turn.

use super::binormal::{
    point_binormals, same_angle, swap_multiplicity, theta_roots, wrap, BASIN_ANGLE,
    CONTINUUM_SAMPLES,
};
use super::certified::certified_min;
use super::descent::{descend, foot_angle};
use super::frame::LocalPair;
use super::{parallel, Circle3, MinDistance, Multiplicity, PARALLEL_SIN_TOL, TIE_REL_TOL};
use crate::poly::FixedVec;
use nalgebra::{Point3, Vector3};
use std::f64::consts::TAU;

/// The minimum distance between two full circles, without the closest pair: the same
/// value as [`min_distance`], minus its angles and points (two `sin_cos` calls) on the fast
/// path of circles in general position. For bounds that only need the number.
pub fn min_distance_value(a: &Circle3, b: &Circle3) -> f64 {
    if a.radius > 0.0 && b.radius > 0.0 && a.normal.cross(&b.normal).norm() > PARALLEL_SIN_TOL {
        match general_fast(a, b) {
            Some(FastMin::Closed(m)) => return m.distance,
            Some(FastMin::Certified { distance, .. }) => return distance,
            None => {
                if let Some(lp) = LocalPair::new(a, b) {
                    return searched_min(a, b, &lp).distance;
                }
            }
        }
    }
    min_distance(a, b).distance
}

/// What the fast paths of circles in general position found ([`general_fast`]).
enum FastMin {
    /// The closed form for meeting axes, with its closest pair.
    Closed(MinDistance),
    /// The certified local minimum: the angles of the closest pair and the distance.
    Certified {
        angle_a: f64,
        angle_b: f64,
        distance: f64,
    },
}

/// The fast paths for circles in general position (both radii positive, planes not
/// parallel): the closed form for meeting axes, else a local minimum certified global by a
/// quartic; `None` when neither decides.
fn general_fast(a: &Circle3, b: &Circle3) -> Option<FastMin> {
    if let Some(m) = intersecting_axes_min(a, b) {
        return Some(FastMin::Closed(m));
    }
    let (x, y, param_b) = if b.radius <= a.radius {
        (a, b, true)
    } else {
        (b, a, false)
    };
    let lpx = LocalPair::new(x, y)?;
    let m = certified_min(&lpx)?;
    let (angle_a, angle_b) = if param_b {
        (m.phi, m.theta)
    } else {
        (m.theta, m.phi)
    };
    Some(FastMin::Certified {
        angle_a,
        angle_b,
        distance: m.dist * lpx.scale,
    })
}

/// The minimum distance between two full circles, with one closest pair, the number of
/// distinct closest pairs and a continuum flag.
pub fn min_distance(a: &Circle3, b: &Circle3) -> MinDistance {
    let Some(lp) = LocalPair::new(a, b) else {
        return MinDistance {
            distance: 0.0,
            angle_a: 0.0,
            angle_b: 0.0,
            point_a: a.center,
            point_b: b.center,
            closest_pairs: 1,
            multiplicity: Multiplicity::Finite,
        };
    };
    if a.radius == 0.0 || b.radius == 0.0 {
        let bn = point_binormals(a, b, None, None);
        let best =
            bn.items.iter().copied().fold(
                bn.items[0],
                |m, x| if x.distance < m.distance { x } else { m },
            );
        return MinDistance {
            distance: best.distance,
            angle_a: best.angle_a,
            angle_b: best.angle_b,
            point_a: best.point_a,
            point_b: best.point_b,
            closest_pairs: 1,
            multiplicity: bn.multiplicity,
        };
    }
    if a.normal.cross(&b.normal).norm() <= PARALLEL_SIN_TOL {
        let sol = parallel::solve(&lp);
        let c = sol.closest[0];
        return MinDistance {
            distance: c.dist * lp.scale,
            angle_a: c.phi,
            angle_b: c.theta,
            point_a: a.point_at(c.phi),
            point_b: b.point_at(c.theta),
            closest_pairs: sol.n_closest,
            multiplicity: sol.multiplicity,
        };
    }
    match general_fast(a, b) {
        Some(FastMin::Closed(m)) => m,
        Some(FastMin::Certified {
            angle_a,
            angle_b,
            distance,
        }) => MinDistance {
            distance,
            angle_a,
            angle_b,
            point_a: a.point_at(angle_a),
            point_b: b.point_at(angle_b),
            closest_pairs: 1,
            multiplicity: Multiplicity::Finite,
        },
        None => searched_min(a, b, &lp),
    }
}

/// The minimum for circles in general position that the fast paths could not decide: the
/// roots of the degree-8 polynomial with each circle parametrised in turn, or sampling when
/// both polynomials vanish identically. `lp` is B in A's frame.
fn searched_min(a: &Circle3, b: &Circle3, lp: &LocalPair) -> MinDistance {
    // Search with each circle parametrised in turn and keep the smaller distance. Either
    // search alone can be ill-conditioned (the parametrised circle much smaller or much
    // larger than the other, nearly touching circles); every candidate is a true distance
    // between two points of the circles, so the smaller one is never worse.
    let mut best: Option<(bool, LocalMin)> = None;
    for param_b in [true, false] {
        let (x, y) = if param_b { (a, b) } else { (b, a) };
        let Some(lpx) = LocalPair::new(x, y) else {
            continue;
        };
        if let Some(mut m) = local_min(&lpx) {
            m.dist *= lpx.scale;
            if best.as_ref().is_none_or(|(_, b)| m.dist < b.dist) {
                best = Some((param_b, m));
            }
        }
    }
    if let Some((param_b, m)) = best {
        let (x, y) = if param_b { (a, b) } else { (b, a) };
        let mut res = MinDistance {
            distance: m.dist,
            angle_a: m.phi,
            angle_b: m.theta,
            point_a: x.point_at(m.phi),
            point_b: y.point_at(m.theta),
            closest_pairs: m.pairs,
            multiplicity: m.multiplicity,
        };
        if !param_b {
            std::mem::swap(&mut res.angle_a, &mut res.angle_b);
            std::mem::swap(&mut res.point_a, &mut res.point_b);
            res.multiplicity = swap_multiplicity(res.multiplicity);
        }
        return res;
    }
    // Both polynomials vanish identically: the distance from B(theta) to A is constant along
    // B, or piecewise so; minimise it by sampling and polishing.
    let m = sampled_min(lp);
    MinDistance {
        distance: m.2 * lp.scale,
        angle_a: m.0,
        angle_b: m.1,
        point_a: a.point_at(m.0),
        point_b: b.point_at(m.1),
        closest_pairs: 1,
        multiplicity: m.3,
    }
}

/// Largest distance between the two axes, relative to the configuration scale, at which
/// [`intersecting_axes_min`] treats them as meeting: moving B onto the meeting point moves
/// every distance by at most that much, 1e3 below [`TIE_REL_TOL`].
const AXES_MEET_REL: f64 = 1e-15;

/// Farthest meeting point (relative to the scale) the closed form accepts: beyond it the
/// axes are nearly parallel and the sphere radii below lose digits to cancellation.
const AXES_MEET_FAR: f64 = 1e3;

/// Closed-form minimum for circles whose axes meet at a point `O`: both circles
/// lie on spheres about `O`, of radii `rho_a = |A(t) - O|`, `rho_b`, and as seen from `O`
/// they are small circles of angular radii `alpha_a`, `alpha_b` about their axis directions
/// `u_a`, `u_b` (oriented from `O` to each centre), `beta` apart. For points at angle
/// `gamma` as seen from `O`, `|x - y|^2 = (rho_a - rho_b)^2 + 4 rho_a rho_b sin^2(gamma/2)`,
/// increasing in `gamma`; the angle from `u_b` of a point of A ranges over
/// `[|beta - alpha_a|, min(beta + alpha_a, 2 pi - beta - alpha_a)]`, so the smallest `gamma`
/// is the gap of `alpha_b` to that range, attained (when positive) by the pair on the great
/// circle through `u_a` and `u_b` (the configuration is symmetric about that plane and the
/// pair is unique). No polynomial is solved.
///
/// When the cones from `O` meet (`gamma = 0`) the distance is `|rho_a - rho_b|`, attained
/// by the two mirror-image directions common to both cones, off the symmetry plane.
///
/// `None` (the general solver decides) when the axes do not meet within [`AXES_MEET_REL`],
/// meet too far away, or a closest point lies on the other circle's axis (a continuum).
fn intersecting_axes_min(a: &Circle3, b: &Circle3) -> Option<MinDistance> {
    let (na, nb) = (a.normal.into_inner(), b.normal.into_inner());
    let cross = na.cross(&nb);
    let sin_beta = cross.norm();
    let scale = a.center.coords.norm() + b.center.coords.norm() + a.radius + b.radius;
    let w = b.center - a.center;
    if sin_beta <= PARALLEL_SIN_TOL || w.dot(&cross).abs() > AXES_MEET_REL * scale * sin_beta {
        return None;
    }
    // Meeting point O = a.center + s na (closest point of A's axis to B's axis), in the
    // cross-product form whose error is ~ulp |w| / sin(beta) (the form with
    // `1 - cos^2(beta)` cancels for nearly parallel axes).
    let s = w.cross(&nb).dot(&cross) / (sin_beta * sin_beta);
    let o = a.center + na * s;
    if (o - a.center).norm() > AXES_MEET_FAR * scale
        || (o - b.center).norm() > AXES_MEET_FAR * scale
    {
        return None;
    }
    // Axis direction from O towards each centre (either way when O is the centre) and the
    // offset of the centre along it.
    let toward = |c: &Point3<f64>, n: Vector3<f64>| {
        let d = (c - o).dot(&n);
        if d >= 0.0 {
            (n, d)
        } else {
            (-n, -d)
        }
    };
    let (ua, da) = toward(&a.center, na);
    let (ub, db) = toward(&b.center, nb);
    let (rho_a, rho_b) = (a.radius.hypot(da), b.radius.hypot(db));
    let (alpha_a, alpha_b) = (a.radius.atan2(da), b.radius.atan2(db));
    let beta = ua.cross(&ub).norm().atan2(ua.dot(&ub));
    let (lo, hi) = (
        (beta - alpha_a).abs(),
        (beta + alpha_a).min(TAU - beta - alpha_a),
    );
    let gamma: f64 = (lo - alpha_b).max(alpha_b - hi).max(0.0);
    // In the plane of u_a and u_b: e_a is perpendicular to u_a towards u_b, e_b to u_b
    // towards u_a.
    let e_a = (ub - ua * ua.dot(&ub)).normalize();
    let e_b = (ua - ub * ua.dot(&ub)).normalize();
    let (pa, pb, pairs) = if gamma > 0.0 {
        let on_a = |sgn: f64| o + (ua * alpha_a.cos() + e_a * (sgn * alpha_a.sin())) * rho_a;
        let on_b = |sgn: f64| o + (ub * alpha_b.cos() + e_b * (sgn * alpha_b.sin())) * rho_b;
        let mut best = (f64::INFINITY, a.center, b.center);
        for pa in [on_a(1.0), on_a(-1.0)] {
            for pb in [on_b(1.0), on_b(-1.0)] {
                let d = (pa - pb).norm();
                if d < best.0 {
                    best = (d, pa, pb);
                }
            }
        }
        (best.1, best.2, 1)
    } else {
        // The cones meet: the directions of A's circle at angle alpha_b from u_b, at
        // azimuth +-t about u_a from e_a, with u_a . u_b = cos(beta) and e_a . u_b =
        // sin(beta); one closest pair on each of the two spheres' shared direction.
        let denom = alpha_a.sin() * beta.sin();
        if denom <= 1e-12 {
            return None;
        }
        let cos_t = ((alpha_b.cos() - alpha_a.cos() * beta.cos()) / denom).clamp(-1.0, 1.0);
        let sin_t = (1.0 - cos_t * cos_t).sqrt();
        let f_a = ua.cross(&e_a);
        let dir = ua * alpha_a.cos() + (e_a * cos_t + f_a * sin_t) * alpha_a.sin();
        let pairs = if sin_t > 1e-12 { 2 } else { 1 };
        (o + dir * rho_a, o + dir * rho_b, pairs)
    };
    // A closest point on the other circle's axis makes a continuum: leave it to the solver.
    let off_axis = |p: &Point3<f64>, c: &Circle3| {
        let r = p - c.center;
        (r - c.normal.into_inner() * r.dot(&c.normal)).norm() > 1e-9 * scale
    };
    if !off_axis(&pa, b) || !off_axis(&pb, a) {
        return None;
    }
    let distance = (rho_a - rho_b).hypot(2.0 * (rho_a * rho_b).sqrt() * (0.5 * gamma).sin());
    let (angle_a, angle_b) = (a.angle_of(&pa), b.angle_of(&pb));
    Some(MinDistance {
        distance,
        angle_a,
        angle_b,
        point_a: a.point_at(angle_a),
        point_b: b.point_at(angle_b),
        closest_pairs: pairs,
        multiplicity: Multiplicity::Finite,
    })
}

/// The minimum found with B parametrised (local units until scaled by the caller).
#[derive(Debug, Clone, Copy)]
struct LocalMin {
    phi: f64,
    theta: f64,
    dist: f64,
    /// Distinct closest pairs (local minima within [`TIE_REL_TOL`] of the minimum).
    pairs: usize,
    multiplicity: Multiplicity,
}

/// Local minima of the distance from B(theta) to A. Every critical point of that distance
/// is a root of B's binormal polynomial, so the global minimum is among the descents
/// started from the roots; a root that stands for a cluster (a stretch where the polynomial
/// is within noise of zero) is also descended from both ends of the cluster, because the
/// representative may be a maximum between two minima.
fn local_min(lp: &LocalPair) -> Option<LocalMin> {
    let thetas = theta_roots(lp, None)?;
    // (theta, phi, distance) of distinct local minima.
    let mut minima = FixedVec::<(f64, f64, f64), 64>::new();
    for r in thetas.iter() {
        for (k, start) in [r.theta, r.lo, r.hi].into_iter().enumerate() {
            if k > 0 && start == r.theta {
                continue;
            }
            let (t, smp) = descend(lp, start);
            let t = wrap(t);
            if !same_basin(lp, &minima, t, smp.f) {
                minima.try_push((t, foot_angle(lp, t), smp.f));
            }
        }
    }
    let Some(&(theta, phi, dist)) = minima.iter().min_by(|x, y| x.2.total_cmp(&y.2)) else {
        // A smooth function on a circle has a minimum, so the polynomial has roots; fall
        // back to sampling rather than return garbage.
        let m = sampled_min(lp);
        return Some(LocalMin {
            phi: m.0,
            theta: m.1,
            dist: m.2,
            pairs: 1,
            multiplicity: m.3,
        });
    };
    let pairs = minima.iter().filter(|m| m.2 <= dist + TIE_REL_TOL).count();
    let mut multiplicity = Multiplicity::Finite;
    // The foot on B lies on A's axis: every point of A is equally close.
    let qb = lp.pb(theta);
    if qb.x.hypot(qb.y) <= TIE_REL_TOL {
        multiplicity = Multiplicity::ContinuumOnA;
    }
    // The foot on A lies on B's axis: every point of B is equally close.
    let nb = lp.u.cross(&lp.v);
    let rel = lp.pa(phi) - lp.c;
    if rel.cross(&nb).norm() <= TIE_REL_TOL {
        multiplicity = Multiplicity::ContinuumOnB;
    }
    if pairs >= 2 && multiplicity == Multiplicity::Finite && constant_along_b(lp, dist) {
        multiplicity = Multiplicity::ContinuumOnBoth;
    }
    Some(LocalMin {
        phi,
        theta,
        dist,
        pairs,
        multiplicity,
    })
}

/// True when the local minimum at `theta` (value `d`) is one already in `minima`: the same
/// angle, or a neighbour with f at the midpoint no higher than both (within
/// [`TIE_REL_TOL`]), i.e. the same flat basin reached from two starts.
fn same_basin(lp: &LocalPair, minima: &[(f64, f64, f64)], theta: f64, d: f64) -> bool {
    minima.iter().any(|&(t, _, dm)| {
        if same_angle(t, theta) {
            return true;
        }
        let gap = wrap(theta - t);
        if gap.abs() > BASIN_ANGLE {
            return false;
        }
        let (mid, _) = lp.dist_b_to_a(t + 0.5 * gap);
        mid <= d.max(dm) + TIE_REL_TOL
    })
}

/// True when every sampled point of B is at distance `d` from A (to [`TIE_REL_TOL`]).
fn constant_along_b(lp: &LocalPair, d: f64) -> bool {
    (0..CONTINUUM_SAMPLES).all(|k| {
        let (dk, _) = lp.dist_b_to_a(TAU * k as f64 / CONTINUUM_SAMPLES as f64);
        (dk - d).abs() <= TIE_REL_TOL
    })
}

/// Minimum of the distance from B(theta) to A by dense sampling plus golden-section
/// refinement; used only when both binormal polynomials vanish identically.
fn sampled_min(lp: &LocalPair) -> (f64, f64, f64, Multiplicity) {
    const N: usize = 256;
    let f = |t: f64| lp.dist_b_to_a(t).0;
    let mut best_k = 0;
    let mut best = f64::INFINITY;
    let mut worst = 0.0f64;
    for k in 0..N {
        let v = f(TAU * k as f64 / N as f64);
        worst = worst.max(v);
        if v < best {
            best = v;
            best_k = k;
        }
    }
    let h = TAU / N as f64;
    let t = golden_min(f, best_k as f64 * h - h, best_k as f64 * h + h);
    let (d, phi) = lp.dist_b_to_a(t);
    let mult = if worst - d <= TIE_REL_TOL {
        Multiplicity::ContinuumOnBoth
    } else {
        Multiplicity::Finite
    };
    (phi, t, d.min(best), mult)
}

/// Golden-section search for a minimum of a unimodal `f` on [lo, hi] (80 steps shrink the
/// bracket by 0.618^80 ~ 1e-17, i.e. to adjacent doubles for brackets of size ~1).
pub fn golden_min(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    crate::poly::minimize::golden_section_min(f, lo, hi, 80).0
}

//! All binormals and the minimum distance of two circles (paper section 3.2, Appendix A).
//!
//! Binormals: express B in A's unit-size frame (`frame`); closed form for points
//! and parallel planes ([`super::parallel`]); otherwise the degree-8 half-angle polynomial on
//! the two half circles of B ([`super::poly8`]), restricted to the requested angle range,
//! solved with [`crate::poly::solve::root_clusters_into`] (keeps double roots: when A's
//! centre is on B's axis every root is double); each root gives the near/far foot on A (or,
//! when B(theta) is on A's axis, the feet solving the tangent condition); 2-D Newton on
//! (A-B).A' = 0, (A-B).B' = 0 polishes the pair; duplicates are merged. If B's polynomial
//! vanishes identically the roles are swapped; if both vanish the distance is constant along
//! the circles (Villarceau-type continuum).
//!
//! Minimum distance: general pairs take the certified fast path of `certified`;
//! the rest descend the closed-form distance along B (`descent`) from every root
//! and root cluster of the polynomial, with each circle parametrised in turn. Everything
//! runs on stack arrays.

use super::certified::certified_min;
use super::descent::{descend, foot_angle};
use super::frame::LocalPair;
use super::poly8::{half_poly, s_of, theta_of, N_COEFFS};
use super::{
    parallel, point_circle_distance, AngleInterval, Binormal, Binormals, Circle3, MinDistance,
    Multiplicity, PARALLEL_SIN_TOL, TIE_REL_TOL,
};
use crate::poly::solve::{
    restrict_into, root_clusters_into, roots_candidate_len, roots_scratch_len, RootCluster,
    RootKind,
};
use crate::poly::FixedVec;
use nalgebra::{Point3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Capacity for binormals of one pair: 8 isolated ones (Neff's bound) plus duplicates from
/// numerically double roots before merging.
pub const MAX_BINORMALS: usize = 16;

/// Root tolerance in the half-circle parameter s (|d theta / d s| <= 4): about machine
/// precision, so isolated roots come out to full double accuracy.
const S_TOL: f64 = 1e-15;

/// Cap on Newton iterations on the geometric equations (the loop exits as soon as a step is
/// below 1e-16). From a root accurate to ~1e-8 (double roots) quadratic convergence needs 3
/// steps. At degenerate critical points (tangent circles: the gradient vanishes to third
/// order) Newton converges linearly with ratio 2/3, and a triple root is only known to
/// ~eps^(1/3) ~ 5e-6; 64 steps shrink that by (2/3)^64 ~ 5e-12.
const NEWTON_STEPS: usize = 64;

/// Newton steps in a row without a smaller residual that end polishing (rounding level).
const POLISH_STALL: usize = 2;

/// A polished pair is accepted as a binormal when both residuals (A-B).A'/|A'| and
/// (A-B).B'/|B'| are below this (local units, configuration scale 1). Roots of the squared
/// polynomial that belong to no binormal leave residuals of order 1e-3 or more; accepted
/// ones reach ~1e-15, so the threshold sits far from both.
const RESIDUAL_TOL: f64 = 1e-8;

/// Two binormals are the same when both angles agree to this (radians). Distinct binormals
/// closer than this exist only within ~1e-14 of a bifurcation (a double root of P).
const DEDUP_ANGLE_TOL: f64 = 1e-7;

/// Below this distance from A's axis (local units) B(theta) also gets the exceptional feet
/// (every point of A is then nearly equidistant and the near/far foot is ill-conditioned).
const NEAR_AXIS: f64 = 1e-6;

/// Two local minima of the distance along B closer than this (radians) are checked for
/// being one flat basin reached from two starts (a degenerate minimum is only located to
/// ~eps^(1/4) ~ 1e-4); distinct closest pairs that close exist only within the tie
/// tolerance of a bifurcation.
const BASIN_ANGLE: f64 = 1e-2;

/// Samples of the distance function used to confirm a constant-distance continuum.
const CONTINUUM_SAMPLES: usize = 16;

/// A root of B's binormal polynomial in theta, with the span of the cluster it stands for
/// (see [`RootCluster`]; `lo == theta == hi` for a well-separated root).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ThetaRoot {
    pub theta: f64,
    pub lo: f64,
    pub hi: f64,
}

type Thetas = FixedVec<ThetaRoot, 40>;

/// Roots in theta of B's binormal polynomial within `range`; `None` when the polynomial
/// vanishes identically on a half circle that meets the range.
pub(crate) fn theta_roots(lp: &LocalPair, range: Option<&AngleInterval>) -> Option<Thetas> {
    let mut out = Thetas::new();
    for flip in [false, true] {
        let theta0 = if flip { PI } else { 0.0 };
        let mut pieces: FixedVec<(f64, f64), 2> = FixedVec::new();
        match range {
            None => {
                pieces.try_push((0.0, 1.0));
            }
            Some(r) => {
                if r.len >= TAU {
                    pieces.try_push((0.0, 1.0));
                } else {
                    let a0 = (r.start - theta0 + PI).rem_euclid(TAU) - PI;
                    for shift in [0.0, -TAU] {
                        let (lo, hi) = (
                            (a0 + shift).max(-FRAC_PI_2),
                            (a0 + r.len + shift).min(FRAC_PI_2),
                        );
                        if lo <= hi {
                            pieces.try_push((s_of(lo), s_of(hi)));
                        }
                    }
                }
            }
        }
        if pieces.is_empty() {
            continue;
        }
        let hp = half_poly(lp, flip);
        if hp.is_zero() {
            return None;
        }
        let mut restricted = [0.0; N_COEFFS];
        let mut scratch = [0.0; roots_scratch_len(N_COEFFS)];
        let mut cand = [(0.0, RootKind::Odd); roots_candidate_len(N_COEFFS)];
        for &(s1, s2) in pieces.iter() {
            if s2 - s1 <= 0.0 {
                // A single angle: test it directly.
                let th = theta_of(s1, flip);
                let v = crate::poly::solve::eval(&hp.coeffs, s1);
                if v.abs() <= crate::poly::solve::zero_tolerance(&hp.coeffs, s1, hp.noise) {
                    out.try_push(ThetaRoot {
                        theta: th,
                        lo: th,
                        hi: th,
                    });
                }
                continue;
            }
            restrict_into(&hp.coeffs, s1, s2, &mut restricted);
            let to_theta = |x: f64| theta_of(s1 + x * (s2 - s1), flip);
            root_clusters_into(
                &restricted,
                S_TOL / (s2 - s1),
                hp.noise,
                &mut scratch,
                &mut cand,
                &mut |r: RootCluster| {
                    out.try_push(ThetaRoot {
                        theta: to_theta(r.root),
                        lo: to_theta(r.lo),
                        hi: to_theta(r.hi),
                    });
                },
            );
        }
    }
    Some(out)
}

/// Gradient and Hessian of |A(phi) - B(theta)|^2 / 2 in local units.
#[inline]
fn newton_step(lp: &LocalPair, phi: f64, theta: f64) -> (f64, f64, f64, f64) {
    let (sp, cp) = phi.sin_cos();
    let (st, ct) = theta.sin_cos();
    let a = Vector3::new(lp.ra * cp, lp.ra * sp, 0.0);
    let da = Vector3::new(-lp.ra * sp, lp.ra * cp, 0.0);
    let w = ct * lp.u + st * lp.v;
    let b = lp.c + lp.rb * w;
    let db = lp.rb * (-st * lp.u + ct * lp.v);
    let d = a - b;
    let g1 = d.dot(&da);
    let g2 = -d.dot(&db);
    let h11 = da.dot(&da) - d.dot(&a);
    let h12 = -da.dot(&db);
    let h22 = db.dot(&db) + d.dot(&(lp.rb * w));
    let det = h11 * h22 - h12 * h12;
    if det == 0.0 || !det.is_finite() {
        return (0.0, 0.0, g1, g2);
    }
    (
        (h22 * g1 - h12 * g2) / det,
        (h11 * g2 - h12 * g1) / det,
        g1,
        g2,
    )
}

/// Normalised residuals (A-B).A'/|A'|, (A-B).B'/|B'| from the gradient (g1, g2).
#[inline]
fn residual_of(lp: &LocalPair, g1: f64, g2: f64) -> f64 {
    let r1 = if lp.ra > 0.0 { g1.abs() / lp.ra } else { 0.0 };
    let r2 = if lp.rb > 0.0 { g2.abs() / lp.rb } else { 0.0 };
    r1.max(r2)
}

/// Newton polishing; returns the best pair met and its residual (the start if Newton does
/// not reduce the residual). Each step evaluates the gradient once, at the current pair; the
/// loop ends after [`POLISH_STALL`] steps without a smaller residual (quadratic convergence
/// reaches rounding in ~4 steps from a double-precision root; at degenerate critical points
/// the residual keeps falling linearly and the loop runs on, up to [`NEWTON_STEPS`]).
fn polish(lp: &LocalPair, phi0: f64, theta0: f64) -> (f64, f64, f64) {
    let (mut phi, mut theta) = (phi0, theta0);
    let mut best = (phi, theta, f64::INFINITY);
    let mut stall = 0;
    for _ in 0..NEWTON_STEPS {
        let (dp, dt, g1, g2) = newton_step(lp, phi, theta);
        let r = residual_of(lp, g1, g2);
        if r < best.2 {
            best = (phi, theta, r);
            stall = 0;
        } else {
            stall += 1;
            if stall >= POLISH_STALL {
                break;
            }
        }
        if !(dp.abs() < 0.5 && dt.abs() < 0.5) || (dp.abs() <= 1e-16 && dt.abs() <= 1e-16) {
            break;
        }
        phi -= dp;
        theta -= dt;
    }
    best
}

fn same_angle(x: f64, y: f64) -> bool {
    let d = (x - y).rem_euclid(TAU);
    d.min(TAU - d) <= DEDUP_ANGLE_TOL
}

/// Feet on A for B(theta): near and far (when off A's axis) and, near the axis, the
/// solutions of (A(phi) - B) . B' = 0. Returns whether every phi is a foot (B(theta) at A's
/// centre with tangent along A's axis).
fn feet(lp: &LocalPair, theta: f64, out: &mut FixedVec<f64, 4>) -> bool {
    let q = lp.pb(theta);
    let rho = q.x.hypot(q.y);
    if rho > 0.0 {
        let phi = q.y.atan2(q.x);
        out.try_push(phi);
        out.try_push(phi + PI);
    }
    if rho <= NEAR_AXIS {
        let (st, ct) = theta.sin_cos();
        let db = lp.rb * (-st * lp.u + ct * lp.v);
        let (a, b, c) = (lp.ra * db.x, lp.ra * db.y, q.dot(&db));
        let r = a.hypot(b);
        if r <= TIE_REL_TOL * lp.rb.max(1e-300) && c.abs() <= TIE_REL_TOL * lp.rb.max(1e-300) {
            if rho == 0.0 {
                out.try_push(0.0);
            }
            return true;
        }
        if r > 0.0 && c.abs() <= r * (1.0 + 1e-9) {
            let base = b.atan2(a);
            let delta = (c / r).clamp(-1.0, 1.0).acos();
            out.try_push(base + delta);
            out.try_push(base - delta);
        }
    }
    false
}

fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(TAU);
    if y > PI {
        y - TAU
    } else {
        y
    }
}

/// Binormals in local angles (phi on A, theta on B) with local lengths.
type LocalList = FixedVec<(f64, f64, f64), MAX_BINORMALS>;

/// Binormals with B parametrised. `None` when B's polynomial vanishes identically.
fn local_binormals(
    lp: &LocalPair,
    range_a: Option<&AngleInterval>,
    range_b: Option<&AngleInterval>,
) -> Option<(LocalList, bool)> {
    let thetas = theta_roots(lp, range_b)?;
    let mut list = LocalList::new();
    let mut continuum_on_a = false;
    for &ThetaRoot { theta, .. } in thetas.iter() {
        let mut fs = FixedVec::<f64, 4>::new();
        continuum_on_a |= feet(lp, theta, &mut fs);
        for &phi in fs.iter() {
            let (p, t, r) = polish(lp, phi, theta);
            if r > RESIDUAL_TOL {
                continue;
            }
            let (p, t) = (wrap(p), wrap(t));
            let ang_tol = 1e-9;
            if range_a.is_some_and(|ra| !ra.contains(p, ang_tol))
                || range_b.is_some_and(|rb| !rb.contains(t, ang_tol))
            {
                continue;
            }
            if list
                .iter()
                .any(|&(p2, t2, _)| same_angle(p, p2) && same_angle(t, t2))
            {
                continue;
            }
            let d = (lp.pa(p) - lp.pb(t)).norm();
            list.try_push((p, t, d));
        }
    }
    Some((list, continuum_on_a))
}

fn to_binormal(a: &Circle3, b: &Circle3, lp: &LocalPair, phi: f64, theta: f64, d: f64) -> Binormal {
    Binormal {
        angle_a: phi,
        angle_b: theta,
        point_a: a.point_at(phi),
        point_b: b.point_at(theta),
        distance: d * lp.scale,
    }
}

fn swap_multiplicity(m: Multiplicity) -> Multiplicity {
    match m {
        Multiplicity::ContinuumOnA => Multiplicity::ContinuumOnB,
        Multiplicity::ContinuumOnB => Multiplicity::ContinuumOnA,
        other => other,
    }
}

/// All binormal lines of circles `a` and `b` whose feet lie in the given angle ranges
/// (`None` = whole circle). Continua are flagged in [`Binormals::multiplicity`] with
/// representatives in the list. A circle of radius 0 is a point: its "binormals" are the
/// critical points of its distance to the other circle.
pub fn binormals(
    a: &Circle3,
    b: &Circle3,
    range_a: Option<AngleInterval>,
    range_b: Option<AngleInterval>,
) -> Binormals {
    let mut out = Binormals::default();
    let Some(lp) = LocalPair::new(a, b) else {
        // Both are the same point.
        out.items
            .try_push(to_binormal(a, b, &LocalPair::unit(), 0.0, 0.0, 0.0));
        out.multiplicity = Multiplicity::ContinuumOnBoth;
        return out;
    };
    if a.radius == 0.0 || b.radius == 0.0 {
        return point_binormals(a, b, range_a.as_ref(), range_b.as_ref());
    }
    if a.normal.cross(&b.normal).norm() <= PARALLEL_SIN_TOL {
        let sol = parallel::solve(&lp);
        for bn in &sol.binormals[..sol.n_binormals] {
            let ok_a = range_a.is_none_or(|r| r.contains(bn.phi, 1e-9));
            let ok_b = range_b.is_none_or(|r| r.contains(bn.theta, 1e-9));
            if ok_a && ok_b {
                out.items
                    .try_push(to_binormal(a, b, &lp, bn.phi, bn.theta, bn.dist));
            }
        }
        out.multiplicity = sol.multiplicity;
        return out;
    }
    // Parametrise the circle with the shorter range (ties: the smaller radius).
    let len = |r: &Option<AngleInterval>| r.map_or(TAU, |r| r.len);
    let b_first = match len(&range_b).partial_cmp(&len(&range_a)) {
        Some(std::cmp::Ordering::Less) => true,
        Some(std::cmp::Ordering::Greater) => false,
        _ => b.radius <= a.radius,
    };
    for attempt in 0..2 {
        let param_b = b_first == (attempt == 0);
        let (x, y, rx, ry) = if param_b {
            (a, b, range_a.as_ref(), range_b.as_ref())
        } else {
            (b, a, range_b.as_ref(), range_a.as_ref())
        };
        let Some(lpx) = LocalPair::new(x, y) else {
            continue;
        };
        if let Some((list, cont_on_x)) = local_binormals(&lpx, rx, ry) {
            for &(p, t, d) in list.iter() {
                let bn = to_binormal(x, y, &lpx, p, t, d);
                out.items
                    .try_push(if param_b { bn } else { swap_binormal(bn) });
            }
            if cont_on_x {
                // A point of y on x's axis, at x's centre, tangent along x's axis.
                out.multiplicity = if param_b {
                    Multiplicity::ContinuumOnA
                } else {
                    Multiplicity::ContinuumOnB
                };
            }
            // A fixed point of the other circle on this one's axis pairs with all of it.
            return out;
        }
    }
    // Both polynomials vanish: every point of both circles has a binormal partner.
    out.multiplicity = Multiplicity::ContinuumOnBoth;
    let (_, phi) = lp.dist_b_to_a(0.0);
    let (p, t, _) = polish(&lp, phi, 0.0);
    let d = (lp.pa(p) - lp.pb(t)).norm();
    out.items.try_push(to_binormal(a, b, &lp, p, t, d));
    out
}

fn swap_binormal(bn: Binormal) -> Binormal {
    Binormal {
        angle_a: bn.angle_b,
        angle_b: bn.angle_a,
        point_a: bn.point_b,
        point_b: bn.point_a,
        distance: bn.distance,
    }
}

/// Binormals when at least one circle is a point: near and far points.
fn point_binormals(
    a: &Circle3,
    b: &Circle3,
    range_a: Option<&AngleInterval>,
    range_b: Option<&AngleInterval>,
) -> Binormals {
    let mut out = Binormals::default();
    if a.radius == 0.0 && b.radius == 0.0 {
        let d = (a.center - b.center).norm();
        out.items.try_push(Binormal {
            angle_a: 0.0,
            angle_b: 0.0,
            point_a: a.center,
            point_b: b.center,
            distance: d,
        });
        return out;
    }
    let swapped = a.radius != 0.0;
    let (pt, circ, range) = if swapped {
        (b, a, range_a)
    } else {
        (a, b, range_b)
    };
    let pc = point_circle_distance(&pt.center, circ);
    let push = |theta: f64, out: &mut Binormals| {
        if range.is_some_and(|r| !r.contains(theta, 1e-9)) {
            return;
        }
        let q = circ.point_at(theta);
        let bn = Binormal {
            angle_a: 0.0,
            angle_b: theta,
            point_a: pt.center,
            point_b: q,
            distance: (q - pt.center).norm(),
        };
        out.items
            .try_push(if swapped { swap_binormal(bn) } else { bn });
    };
    push(pc.angle, &mut out);
    if pc.on_axis {
        out.multiplicity = if swapped {
            Multiplicity::ContinuumOnA
        } else {
            Multiplicity::ContinuumOnB
        };
    } else {
        push(pc.angle + PI, &mut out);
    }
    out
}

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

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

use super::frame::LocalPair;
use super::poly8::{half_poly, s_of, theta_of, N_COEFFS};
use super::{
    parallel, point_circle_distance, AngleInterval, Binormal, Binormals, Circle3, Multiplicity,
    PARALLEL_SIN_TOL, TIE_REL_TOL,
};
use crate::poly::solve::{
    restrict_into, root_clusters_into, roots_candidate_len, roots_scratch_len, RootCluster,
    RootKind,
};
use crate::poly::FixedVec;
use nalgebra::Vector3;
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
pub(super) const BASIN_ANGLE: f64 = 1e-2;

/// Samples of the distance function used to confirm a constant-distance continuum.
pub(super) const CONTINUUM_SAMPLES: usize = 16;

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

pub(super) fn same_angle(x: f64, y: f64) -> bool {
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

pub(super) fn wrap(x: f64) -> f64 {
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

pub(super) fn swap_multiplicity(m: Multiplicity) -> Multiplicity {
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
pub(super) fn point_binormals(
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

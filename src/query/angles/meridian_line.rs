//! Critical and level angles of a cone's meridian-line field along a circle, as roots of
//! polynomials (the straight-piece counterpart of the circle binormals, paper 3.2).
//!
//! A circle `P(theta) = o + u cos theta + v sin theta` is given in the frame of a cone (or
//! cylinder, or flat annulus) about the z axis whose meridian line is `n . (rho, z) = c`.
//! The signed distance of `P(theta)` to the line and to its mirror image is
//! `F_s = s n_rho rho + n_z z` (minus `c`), with `rho^2 = q(theta) = |P_xy|^2`.
//! * Critical angles: `F_s' = s n_rho q' / (2 rho) + n_z z' = 0`; squaring removes both the
//!   root and the sign `s`: `n_rho^2 q'^2 - 4 n_z^2 q z'^2 = 0`, a trigonometric polynomial of
//!   degree 4 whose roots are the critical angles of both branches.
//! * Level angles: `F_s = c` gives `n_rho^2 q - (c - n_z z)^2 = 0`, degree 2.
//!
//! With the half-angle substitution `theta = theta0 + 2 atan(w)`, `w = 2 s - 1` on each half
//! circle (`theta0 = 0, pi`), `cos theta` and `sin theta` are quadratics over `1 + w^2`, so both
//! become polynomials in `s` of degree 8 and 4, built directly in Bernstein form and solved
//! by [`mod@crate::poly::solve`], which keeps roots of even multiplicity (a cylinder's critical
//! angles are double roots after squaring). Squaring can add angles of the other branch;
//! every caller measures each angle exactly, so extra angles are harmless.
//!
//! **Clusters.** Squaring multiplies the two branches' equations, so where the branches
//! nearly agree (a nearly flat cone, `|n_rho|` small, or a circle nearly parallel to it) a
//! simple root of one branch and a simple root of the other become a near-double root of
//! the product, and the solver can only report a cluster: a span of angles within which the
//! polynomial stays inside its coefficient noise. One representative angle of such a span
//! can lie far from both branches' roots (a case at eps 1e-6 put it 2.4e-4 rad from a
//! crossing, and a circle touching a cone was measured 1.1e-8 away from it). So every
//! cluster is resolved on the unsquared branch functions (sign changes at the span's ends
//! and representative, bisected to full precision), its ends are appended too, and the
//! solve reports [`FieldAngles::Clustered`]: the angle set is then not proven complete, and
//! callers that certify a lower bound from it must take that bound from elsewhere
//! (`docs/verification.md`, "The corner case").
//!
//! **Vanishing equations.** For a cone or cylinder (`n_rho != 0`) the field is constant
//! along a circle only when the circle is coaxial (a circle on a circular cone, or on a
//! level cone of its field, is a parallel). A squared equation that vanishes within its
//! noise along any other circle is a nearly flat cone with a circle nearly in its plane:
//! the unsquared field still varies (by 1e-8 in a case where the annuli crossed), so the
//! half circle is resolved on the branch functions and reported as a cluster
//! (`docs/verification.md`, "Crossing lenses").

use super::radial_field::{bisect, h_and_f, ParamCircle, RadialField};
use crate::poly::solve::{
    root_clusters_into, roots_candidate_len, roots_scratch_len, RootCluster, RootKind, BINOM,
};
use crate::tolerances::{COEFF_NOISE_FACTOR, S_TOL};
use nalgebra::Vector2;
use std::f64::consts::PI;

/// Angles per half circle at which a vanishing equation's branches are scanned for sign
/// changes (module docs, "Vanishing equations"); the result is marked clustered, so the
/// count bounds cost, not correctness.
const VANISHING_GRID: usize = 64;

/// Bernstein coefficients of a polynomial of degree `N - 1` on `s` in [0, 1].
type Poly<const N: usize> = [f64; N];

/// A quadratic in `s` from its values at `w = 2 s - 1 = -1, 0, 1`.
fn quadratic(f: impl Fn(f64) -> f64) -> Poly<3> {
    let (f0, fh, f1) = (f(-1.0), f(0.0), f(1.0));
    [f0, 2.0 * fh - 0.5 * (f0 + f1), f1]
}

/// `sum k_i p_i` (same degree).
fn lin<const N: usize>(terms: &[(f64, &Poly<N>)]) -> Poly<N> {
    std::array::from_fn(|i| terms.iter().map(|(k, p)| k * p[i]).sum())
}

fn abs<const N: usize>(p: &Poly<N>) -> Poly<N> {
    p.map(f64::abs)
}

fn max_abs<const N: usize>(p: &Poly<N>) -> f64 {
    p.iter().fold(0.0, |m, c| m.max(c.abs()))
}

/// Bernstein product: degrees `M - 1` and `N - 1` into `R - 1 = M + N - 2`.
fn mul<const M: usize, const N: usize, const R: usize>(a: &Poly<M>, b: &Poly<N>) -> Poly<R> {
    debug_assert_eq!(R, M + N - 1);
    let (m, n) = (M - 1, N - 1);
    let mut out = [0.0; R];
    for (i, ai) in a.iter().enumerate() {
        let wa = BINOM[m][i] * ai;
        for (j, bj) in b.iter().enumerate() {
            out[i + j] += wa * BINOM[n][j] * bj;
        }
    }
    for (k, o) in out.iter_mut().enumerate() {
        *o /= BINOM[m + n][k];
    }
    out
}

/// The circle on the half circle starting at `theta0`, as quadratics in `s` multiplied by
/// `D = 1 + w^2`.
struct HalfCircle {
    d: Poly<3>,
    x: Poly<3>,
    y: Poly<3>,
    xp: Poly<3>,
    yp: Poly<3>,
    z: Poly<3>,
    /// `q D^2` and `q' D^2` (degree 4), `z' D` (degree 2).
    q: Poly<5>,
    dq: Poly<5>,
    zp: Poly<3>,
}

impl HalfCircle {
    fn new(c: &ParamCircle, theta0: f64) -> Self {
        let (s0, c0) = theta0.sin_cos();
        // cos theta * D and sin theta * D.
        let cos_d = quadratic(|w| c0 * (1.0 - w * w) - s0 * 2.0 * w);
        let sin_d = quadratic(|w| s0 * (1.0 - w * w) + c0 * 2.0 * w);
        let d = quadratic(|w| 1.0 + w * w);
        let coord = |o: f64, u: f64, v: f64| lin(&[(o, &d), (u, &cos_d), (v, &sin_d)]);
        let deriv = |u: f64, v: f64| lin(&[(-u, &sin_d), (v, &cos_d)]);
        let (x, y) = (coord(c.o.x, c.u.x, c.v.x), coord(c.o.y, c.u.y, c.v.y));
        let (xp, yp) = (deriv(c.u.x, c.v.x), deriv(c.u.y, c.v.y));
        Self {
            q: lin(&[(1.0, &mul(&x, &x)), (1.0, &mul(&y, &y))]),
            dq: lin(&[(2.0, &mul(&x, &xp)), (2.0, &mul(&y, &yp))]),
            z: coord(c.o.z, c.u.z, c.v.z),
            zp: deriv(c.u.z, c.v.z),
            d,
            x,
            y,
            xp,
            yp,
        }
    }
}

/// Appends the solutions of `a cos theta + b sin theta = k`; `false` (nothing appended)
/// when `a = b = 0`, i.e. the left side is constant. Near tangency (`|k|` within
/// [`COEFF_NOISE_FACTOR`] of the amplitude) the double root is kept.
fn harmonic_roots(a: f64, b: f64, k: f64, out: &mut Vec<f64>) -> bool {
    let amp = a.hypot(b);
    if amp == 0.0 {
        return false;
    }
    let ratio = k / amp;
    if ratio.abs() > 1.0 + COEFF_NOISE_FACTOR * (1.0 + k.abs() / amp) {
        return true;
    }
    let (centre, half) = (b.atan2(a), ratio.clamp(-1.0, 1.0).acos());
    out.push(centre + half);
    out.push(centre - half);
    true
}

/// What a solve of [`line_field_critical`] or [`line_field_levels`] appended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldAngles {
    /// Every root of the squared equation was isolated to full precision: the angles
    /// contain every critical (or level) angle of both branches.
    Isolated,
    /// Some roots formed a cluster (an even-multiplicity candidate or a span of merged
    /// candidates inside the coefficient noise): the angles were resolved as well as the
    /// branch functions allow, but the set is not proven complete (module docs,
    /// "Clusters").
    Clustered,
    /// The equation vanishes identically (the field is constant along the circle, or the
    /// circle lies on the extended surface): nothing was appended.
    Constant,
}

impl FieldAngles {
    /// The weaker of two outcomes: `Constant` over `Clustered` over `Isolated`.
    pub fn and(self, other: FieldAngles) -> FieldAngles {
        match (self, other) {
            (FieldAngles::Constant, _) | (_, FieldAngles::Constant) => FieldAngles::Constant,
            (FieldAngles::Clustered, _) | (_, FieldAngles::Clustered) => FieldAngles::Clustered,
            _ => FieldAngles::Isolated,
        }
    }
}

/// Appends every sign change of `f` between consecutive angles of `pts` (ascending),
/// located to full precision ([`bisect`]).
fn bisect_sign_changes(f: &impl Fn(f64) -> f64, pts: &[f64], out: &mut Vec<f64>) {
    for w in pts.windows(2) {
        let (fa, fb) = (f(w[0]), f(w[1]));
        if fa.is_finite() && fb.is_finite() && fa != 0.0 && fa.signum() != fb.signum() {
            out.push(bisect(f, w[0], w[1], fa));
        }
    }
}

/// Roots in `s` of `p` mapped to angles. A cluster appends its representative, its span's
/// ends and the sign changes of each of `branches` (the unsquared equations whose product
/// `p` is) between them, and makes the outcome [`FieldAngles::Clustered`].
///
/// When `p` is within `noise` everywhere the outcome is [`FieldAngles::Constant`] only for a
/// `coaxial` circle, the one case where the field is truly constant along it (module docs,
/// "Vanishing equations"); otherwise the whole half circle is one cluster, resolved on the
/// branches at [`VANISHING_GRID`] angles.
fn push_roots<const N: usize>(
    p: &Poly<N>,
    noise: f64,
    theta0: f64,
    coaxial: bool,
    branches: &[&dyn Fn(f64) -> f64],
    out: &mut Vec<f64>,
) -> FieldAngles {
    let angle = |s: f64| theta0 + 2.0 * (2.0 * s - 1.0).atan();
    if p.iter().all(|c| c.abs() <= noise) {
        if coaxial {
            return FieldAngles::Constant;
        }
        let pts: Vec<f64> = (0..=VANISHING_GRID)
            .map(|i| angle(i as f64 / VANISHING_GRID as f64))
            .collect();
        for f in branches {
            bisect_sign_changes(f, &pts, out);
        }
        return FieldAngles::Clustered;
    }
    let mut scratch = [0.0; 64];
    let mut cand = [(0.0, RootKind::Odd); 32];
    debug_assert!(roots_scratch_len(N) <= 64 && roots_candidate_len(N) <= 32);
    let mut outcome = FieldAngles::Isolated;
    root_clusters_into(
        p,
        S_TOL,
        noise,
        &mut scratch[..roots_scratch_len(N)],
        &mut cand[..roots_candidate_len(N)],
        &mut |r: RootCluster| {
            let root = angle(r.root);
            out.push(root);
            if r.kind == RootKind::Odd && r.lo == r.hi {
                return;
            }
            outcome = FieldAngles::Clustered;
            let pts = [angle(r.lo), root, angle(r.hi)];
            out.extend([pts[0], pts[2]]);
            for f in branches {
                bisect_sign_changes(f, &pts, out);
            }
        },
    );
    outcome
}

/// The field `F_s = s n_rho rho + n_z z` of the meridian line with unit normal `n`, branch
/// `s` (`s = -1`: the mirror image), as a [`RadialField`].
fn line_field(n: Vector2<f64>, s: f64) -> RadialField {
    RadialField {
        a: s * n.x,
        b: 0.0,
        c1: n.y,
        c2: 0.0,
    }
}

/// Appends the critical angles of `F_s` (both branches) along `c` for the meridian line
/// with unit normal `n`. [`FieldAngles::Constant`] (with `out` unchanged) when the
/// polynomial vanishes identically: `F` is constant along the circle.
pub fn line_field_critical(c: &ParamCircle, n: Vector2<f64>, out: &mut Vec<f64>) -> FieldAngles {
    if n.x == 0.0 {
        // Flat annulus: F = n_z z, critical where z' = v_z cos - u_z sin = 0 (closed form).
        return isolated_or_constant(harmonic_roots(c.v.z, -c.u.z, 0.0, out));
    }
    // The unsquared equations of the two branches: 2 rho F_s' = s n_rho q' + 2 n_z rho z'.
    let branch = |s: f64| {
        let f = line_field(n, s);
        move |theta: f64| h_and_f(c, &f, theta).0
    };
    let (plus, minus) = (branch(1.0), branch(-1.0));
    let coaxial = c.is_coaxial();
    let start = out.len();
    let (nr2, nz2) = (n.x * n.x, n.y * n.y);
    let mut outcome = FieldAngles::Isolated;
    for theta0 in [0.0, PI] {
        let h = HalfCircle::new(c, theta0);
        let half = if n.y == 0.0 {
            // Cylinder: F = s n_rho rho, critical where q' = 0 (P = n_rho^2 q'^2: only the
            // square root of the double roots is needed).
            let mag = max_abs(&lin(&[
                (2.0, &mul::<3, 3, 5>(&abs(&h.x), &abs(&h.xp))),
                (2.0, &mul::<3, 3, 5>(&abs(&h.y), &abs(&h.yp))),
            ]));
            push_roots(
                &h.dq,
                COEFF_NOISE_FACTOR * mag,
                theta0,
                coaxial,
                &[&plus],
                out,
            )
        } else {
            let zp2: Poly<5> = mul(&h.zp, &h.zp);
            let dq2: Poly<9> = mul(&h.dq, &h.dq);
            let qzp2: Poly<9> = mul(&h.q, &zp2);
            let p = lin(&[(nr2, &dq2), (-4.0 * nz2, &qzp2)]);
            let mag_dq2: Poly<9> = mul(&abs(&h.dq), &abs(&h.dq));
            let mag_qzp2: Poly<9> = mul(&abs(&h.q), &abs(&zp2));
            let mag = max_abs(&lin(&[(nr2, &mag_dq2), (4.0 * nz2, &mag_qzp2)]));
            push_roots(
                &p,
                COEFF_NOISE_FACTOR * mag,
                theta0,
                coaxial,
                &[&plus, &minus],
                out,
            )
        };
        outcome = outcome.and(half);
        if outcome == FieldAngles::Constant {
            out.truncate(start);
            return outcome;
        }
    }
    outcome
}

/// Appends the angles where `F_s = level` (both branches) along `c` for the meridian line
/// with unit normal `n`. [`FieldAngles::Constant`] (with `out` unchanged) when the
/// polynomial vanishes identically (the circle lies on the extended surface).
pub fn line_field_levels(
    c: &ParamCircle,
    n: Vector2<f64>,
    level: f64,
    out: &mut Vec<f64>,
) -> FieldAngles {
    if n.x == 0.0 {
        // Flat annulus: z = o_z + u_z cos + v_z sin = level / n_z (closed form).
        return isolated_or_constant(harmonic_roots(c.u.z, c.v.z, level / n.y - c.o.z, out));
    }
    // The unsquared equations of the two branches: F_s - level = s n_rho rho + n_z z - level.
    let branch = |s: f64| {
        let f = line_field(n, s);
        move |theta: f64| h_and_f(c, &f, theta).1 - level
    };
    let (plus, minus) = (branch(1.0), branch(-1.0));
    let coaxial = c.is_coaxial();
    let start = out.len();
    let nr2 = n.x * n.x;
    let mut outcome = FieldAngles::Isolated;
    for theta0 in [0.0, PI] {
        let h = HalfCircle::new(c, theta0);
        // (c - n_z z)^2 D^2
        let r = lin(&[(level, &h.d), (-n.y, &h.z)]);
        let r2: Poly<5> = mul(&r, &r);
        let p = lin(&[(nr2, &h.q), (-1.0, &r2)]);
        let ra = lin(&[(level.abs(), &h.d), (n.y.abs(), &abs(&h.z))]);
        let ra2: Poly<5> = mul(&ra, &ra);
        let mag = max_abs(&lin(&[(nr2, &abs(&h.q)), (1.0, &ra2)]));
        let half = push_roots(
            &p,
            COEFF_NOISE_FACTOR * mag,
            theta0,
            coaxial,
            &[&plus, &minus],
            out,
        );
        outcome = outcome.and(half);
        if outcome == FieldAngles::Constant {
            out.truncate(start);
            return outcome;
        }
    }
    outcome
}

/// A closed-form solve's outcome: its roots are exact up to rounding.
fn isolated_or_constant(appended: bool) -> FieldAngles {
    if appended {
        FieldAngles::Isolated
    } else {
        FieldAngles::Constant
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;
    use nalgebra::{Point3, Vector3};
    use std::f64::consts::{FRAC_PI_2, TAU};

    fn random_circle(rng: &mut Lcg) -> ParamCircle {
        let g = |rng: &mut Lcg| Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5);
        let u = g(rng);
        let v = u.cross(&g(rng)).normalize() * u.norm();
        ParamCircle {
            o: Point3::from(g(rng)),
            u,
            v,
        }
    }

    fn field(c: &ParamCircle, n: Vector2<f64>, s: f64, t: f64) -> f64 {
        let p = c.point(t);
        s * n.x * p.x.hypot(p.y) + n.y * p.z
    }

    fn near(list: &[f64], t: f64, tol: f64) -> bool {
        list.iter().any(|&x| {
            let d = (x - t).rem_euclid(TAU);
            d.min(TAU - d) < tol
        })
    }

    /// Every local extremum of either branch on a fine grid is close to a returned angle;
    /// every sign change of `F_s - level` likewise. Includes cylinders (`n_z = 0`: double
    /// roots), flat annuli (`n_rho = 0`), and cones within 1e-9..1e-3 rad of either (the
    /// squared equation's pairs of roots closer than its noise).
    #[test]
    fn finds_every_extremum_and_crossing_of_a_fine_grid() {
        let mut rng = Lcg(5);
        for i in 0..250 {
            let mut c = random_circle(&mut rng);
            let n = match i % 5 {
                0 => Vector2::new(1.0, 0.0),
                1 => Vector2::new(0.0, 1.0),
                2 => {
                    let a = rng.f() * TAU;
                    Vector2::new(a.cos(), a.sin())
                }
                k => {
                    // Nearly a cylinder (k = 3) or a flat annulus (k = 4), at scales up to 100.
                    let tilt = (rng.f() - 0.5).signum() * 10f64.powf(-3.0 - 6.0 * rng.f());
                    let scale = 10f64.powf(2.0 * rng.f());
                    c = ParamCircle {
                        o: c.o * scale,
                        u: c.u * scale,
                        v: c.v * scale,
                    };
                    let a = if k == 3 { tilt } else { FRAC_PI_2 + tilt };
                    Vector2::new(a.cos(), a.sin())
                }
            };
            assert_extrema_found(&c, n, &format!("case {i}"));
        }
        // A cone 1.7e-6 rad from a cylinder and a circle of radius 67: two critical angles
        // 5e-7 apart whose squared equation dips below zero by less than its noise (found by
        // `verify bounds`, seed 20261128, family flat-cone).
        let rot = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            0.0016773016373958578,
            0.2249519942716609,
            0.6235776447735673,
            -0.7486953371506134,
        ));
        let t = Vector3::new(28.12310572249228, -37.99400890942317, 10.258814651152527);
        let pos = nalgebra::Isometry3::from_parts(t.into(), rot);
        let c = ParamCircle::parallel(66.60529295659464, -7.608318596651639, &pos);
        let n = Vector2::new(-0.9999999999985103, 1.7260668824118984e-6);
        assert_extrema_found(&c, n, "pinned near-cylinder");
    }

    /// [`finds_every_extremum_and_crossing_of_a_fine_grid`] for one circle and line.
    fn assert_extrema_found(c: &ParamCircle, n: Vector2<f64>, case: &str) {
        let m = 20_000;
        let step = TAU / m as f64;
        let scale = c.o.coords.norm() + c.u.norm();
        let level = (Lcg(m as u64).f() - 0.5) * scale;
        let (mut crit, mut lev) = (Vec::new(), Vec::new());
        assert_ne!(line_field_critical(c, n, &mut crit), FieldAngles::Constant);
        assert_ne!(
            line_field_levels(c, n, level, &mut lev),
            FieldAngles::Constant
        );
        {
            let i = case;
            let c = *c;
            for s in [1.0, -1.0] {
                for k in 0..m {
                    let t = k as f64 * step;
                    let (a, b, d) = (
                        field(&c, n, s, t - step),
                        field(&c, n, s, t),
                        field(&c, n, s, t + step),
                    );
                    if (b < a && b < d) || (b > a && b > d) {
                        assert!(near(&crit, t, 3.0 * step), "{i}: extremum at {t} missed");
                    }
                    if (b - level).signum() != (d - level).signum() {
                        assert!(near(&lev, t, 3.0 * step), "{i}: crossing at {t} missed");
                    }
                }
            }
        }
    }

    /// A circle coaxial with a cylinder: the field is constant, reported as such.
    #[test]
    fn constant_field_is_reported() {
        let c = ParamCircle {
            o: Point3::new(0.0, 0.0, 0.3),
            u: Vector3::new(0.5, 0.0, 0.0),
            v: Vector3::new(0.0, 0.5, 0.0),
        };
        let mut out = Vec::new();
        assert_eq!(
            line_field_critical(&c, Vector2::new(1.0, 0.0), &mut out),
            FieldAngles::Constant
        );
        assert!(out.is_empty());
    }
}

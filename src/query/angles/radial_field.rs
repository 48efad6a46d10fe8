//! Critical points of radial fields along a circle (paper section 3.2, Appendix A, in a
//! one-dimensional form).
//!
//! A circle `P(theta) = o + u cos theta + v sin theta` is given in the frame of a surface of
//! revolution about the z axis. Its meridian coordinates are `rho(theta) = |P_xy|` and
//! `z(theta) = P_z`. Every distance needed by the patch distance is a field
//! `F = a rho + b rho^2 + c1 z + c2 z^2`:
//! * squared distance to the mirrored profile-circle centre `(s R, c_z)`:
//!   `a = -2 s R, b = 1, c1 = -2 c_z, c2 = 1` (plus a constant);
//! * signed distance to a meridian line `s n_rho rho + n_z z = c`: `a = s n_rho, c1 = n_z`.
//!
//! With `q = rho^2` (a trigonometric polynomial of degree 2) the derivative is
//! `F' = (a / (2 rho) + b) q' + (c1 + 2 c2 z) z'`; the continuous function
//! `H = 2 rho F' = (a + 2 b rho) q' + 2 rho (c1 + 2 c2 z) z'` has the critical angles as roots.
//! Squaring `a q' = -2 rho (...)` gives the degree-8 polynomial of the paper; we keep the
//! two branches apart (their product is that polynomial) so that the double roots created
//! by squaring in symmetric poses (a circle centred on the other axis) stay simple roots of
//! one branch. Roots are bracketed on a uniform grid and refined by bisection; local
//! minima of `|H|` on the grid are refined by golden-section search and also returned, so
//! that tangential (double) roots are not lost. Extra angles are harmless: every caller
//! turns an angle into a pair of points on the surfaces and measures it exactly.

use crate::tolerances::AXIS_TOLERANCE;
use nalgebra::{Point3, Vector3};
use std::f64::consts::TAU;

/// Grid size for bracketing. H has at most 8 roots per branch (degree 8 after squaring);
/// 64 cells leave on average 8 cells per root, and clustered roots are caught by the
/// local-minimum refinement.
pub const SWEEP_SAMPLES: usize = 64;

/// A circle in a solid's local frame, `P(theta) = o + u cos theta + v sin theta`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamCircle {
    pub o: Point3<f64>,
    pub u: Vector3<f64>,
    pub v: Vector3<f64>,
}

impl ParamCircle {
    /// The parallel at meridian coordinates `(rho, z)` of a frame, mapped by `iso`.
    pub fn parallel(rho: f64, z: f64, iso: &nalgebra::Isometry3<f64>) -> Self {
        ParamCircle {
            o: iso * Point3::new(0.0, 0.0, z),
            u: iso * Vector3::new(rho, 0.0, 0.0),
            v: iso * Vector3::new(0.0, rho, 0.0),
        }
    }
    pub fn point(&self, theta: f64) -> Point3<f64> {
        self.o + self.u * theta.cos() + self.v * theta.sin()
    }
    pub fn radius(&self) -> f64 {
        self.u.norm()
    }
    /// Tangent (not normalised) at `theta`.
    pub fn tangent(&self, theta: f64) -> Vector3<f64> {
        -self.u * theta.sin() + self.v * theta.cos()
    }
    /// Whether the circle is coaxial with its frame's z axis, to [`AXIS_TOLERANCE`]
    /// (centre on the axis, plane perpendicular to it).
    pub fn is_coaxial(&self) -> bool {
        let n = self.u.cross(&self.v);
        let scale = 1.0 + self.o.coords.norm() + self.radius();
        self.o.x.hypot(self.o.y) <= AXIS_TOLERANCE * scale
            && n.x.hypot(n.y) <= AXIS_TOLERANCE * n.norm()
    }
}

/// Field `a rho + b rho^2 + c1 z + c2 z^2` on the meridian half-plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialField {
    pub a: f64,
    pub b: f64,
    pub c1: f64,
    pub c2: f64,
}

impl RadialField {
    fn value(&self, rho: f64, z: f64) -> f64 {
        self.a * rho + self.b * rho * rho + self.c1 * z + self.c2 * z * z
    }
}

/// `(sin, cos)` of the grid angles `i * TAU / SWEEP_SAMPLES`, computed once: the grid pass
/// of every sweep needs them and `sin_cos` dominated the query's profile.
fn grid_sin_cos() -> &'static [(f64, f64); SWEEP_SAMPLES] {
    static GRID: std::sync::OnceLock<[(f64, f64); SWEEP_SAMPLES]> = std::sync::OnceLock::new();
    GRID.get_or_init(|| {
        let step = TAU / SWEEP_SAMPLES as f64;
        std::array::from_fn(|i| (i as f64 * step).sin_cos())
    })
}

/// H = 2 rho F' at theta (see module doc), and F.
pub(super) fn h_and_f(c: &ParamCircle, f: &RadialField, theta: f64) -> (f64, f64) {
    let (s, co) = theta.sin_cos();
    h_and_f_sc(c, f, s, co)
}

/// [`h_and_f`] from the angle's sine and cosine.
fn h_and_f_sc(c: &ParamCircle, f: &RadialField, s: f64, co: f64) -> (f64, f64) {
    let p = c.o + c.u * co + c.v * s;
    let dp = -c.u * s + c.v * co;
    let q = p.x * p.x + p.y * p.y;
    let dq = 2.0 * (p.x * dp.x + p.y * dp.y);
    let rho = q.sqrt();
    let h = (f.a + 2.0 * f.b * rho) * dq + 2.0 * rho * (f.c1 + 2.0 * f.c2 * p.z) * dp.z;
    (h, f.value(rho, p.z))
}

/// Appends to `out` the angles where `F` is critical along the circle (see module doc),
/// including near-double roots and near-axis crossings. Returns `true` when `F` is
/// constant along the circle up to round-off (a continuum); then `out` gets the grid.
pub fn critical_angles(c: &ParamCircle, f: &RadialField, out: &mut Vec<f64>) -> bool {
    let n = SWEEP_SAMPLES;
    let step = TAU / n as f64;
    let mut hs = [0.0f64; SWEEP_SAMPLES];
    let mut fmin = f64::INFINITY;
    let mut fmax = f64::NEG_INFINITY;
    for (h, &(s, co)) in hs.iter_mut().zip(grid_sin_cos()) {
        let (hv, fv) = h_and_f_sc(c, f, s, co);
        *h = hv;
        fmin = fmin.min(fv);
        fmax = fmax.max(fv);
    }
    let scale = field_scale(c, f);
    if fmax - fmin <= 1e-13 * scale {
        out.extend((0..n).map(|i| i as f64 * step));
        return true;
    }
    for i in 0..n {
        let (t0, t1) = (i as f64 * step, (i + 1) as f64 * step);
        let (h0, h1) = (hs[i], hs[(i + 1) % n]);
        if h0 == 0.0 {
            out.push(t0);
        } else if h0.signum() != h1.signum() && h1 != 0.0 {
            out.push(bisect(|t| h_and_f(c, f, t).0, t0, t1, h0));
        }
        // Local minimum of |H| without a sign change: possible double root.
        let hp = hs[(i + n - 1) % n];
        if h0 != 0.0
            && h0.abs() <= hp.abs()
            && h0.abs() <= h1.abs()
            && h0.signum() == hp.signum()
            && h0.signum() == h1.signum()
        {
            let t = golden_min(|t| h_and_f(c, f, t).0.abs(), t0 - step, t1);
            out.push(t.rem_euclid(TAU));
        }
    }
    false
}

/// Appends the angles where `F = level` along the circle (sign changes of `F - level`,
/// plus near-tangential touches found as local minima of `|F - level|`).
pub fn level_angles(c: &ParamCircle, f: &RadialField, level: f64, out: &mut Vec<f64>) {
    let n = SWEEP_SAMPLES;
    let step = TAU / n as f64;
    let mut gs = [0.0f64; SWEEP_SAMPLES];
    for (g, &(s, co)) in gs.iter_mut().zip(grid_sin_cos()) {
        *g = h_and_f_sc(c, f, s, co).1 - level;
    }
    for i in 0..n {
        let (t0, t1) = (i as f64 * step, (i + 1) as f64 * step);
        let (g0, g1) = (gs[i], gs[(i + 1) % n]);
        if g0 == 0.0 {
            out.push(t0);
        } else if g0.signum() != g1.signum() && g1 != 0.0 {
            out.push(bisect(|t| h_and_f(c, f, t).1 - level, t0, t1, g0));
        }
        let gp = gs[(i + n - 1) % n];
        if g0 != 0.0 && g0.abs() <= gp.abs() && g0.abs() <= g1.abs() && g0.signum() == gp.signum() {
            let t = golden_min(|t| (h_and_f(c, f, t).1 - level).abs(), t0 - step, t1);
            out.push(t.rem_euclid(TAU));
        }
    }
}

/// Appends the angles where `F = level` along the circle, given every critical angle of
/// `F` (`critical`, sorted in `[0, 2 pi)`): `F` is monotone between consecutive critical
/// angles, so each gap holds at most one crossing, found by `bisect` when the ends differ
/// in sign. Touching without crossing happens at a critical angle, which the caller
/// already measures.
pub fn level_crossings(
    c: &ParamCircle,
    f: &RadialField,
    level: f64,
    critical: &[f64],
    out: &mut Vec<f64>,
) {
    let Some(&first) = critical.first() else {
        return;
    };
    let g = |t: f64| h_and_f(c, f, t).1 - level;
    let g_first = g(first);
    let mut g0 = g_first;
    for (i, &t0) in critical.iter().enumerate() {
        let (t1, g1) = match critical.get(i + 1) {
            Some(&t1) => (t1, g(t1)),
            None => (first + TAU, g_first),
        };
        if g0 == 0.0 {
            out.push(t0);
        } else if g0.signum() != g1.signum() && g1 != 0.0 {
            out.push(bisect(g, t0, t1, g0).rem_euclid(TAU));
        }
        g0 = g1;
    }
}

/// Magnitude of the field's terms along the circle, for relative tests.
fn field_scale(c: &ParamCircle, f: &RadialField) -> f64 {
    let ext = c.o.coords.norm() + c.u.norm();
    f.a.abs() * ext + f.b.abs() * ext * ext + f.c1.abs() * ext + f.c2.abs() * ext * ext + 1e-300
}

/// Root of a sign change of `g` on `[a, b]` (`ga = g(a)`) to full double precision, by the
/// Illinois variant of regula falsi: the bracket always holds a sign change (as bisection's
/// does), but convergence is superlinear, so a root costs ~10 evaluations instead of ~60.
/// A bisection step replaces false position whenever the previous step failed to halve the
/// bracket, which keeps the worst case linear.
pub(super) fn bisect(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64, mut ga: f64) -> f64 {
    let mut gb = g(b);
    if gb == 0.0 {
        return b;
    }
    let mut side = 0i8;
    let mut last_width = f64::INFINITY;
    for _ in 0..200 {
        let width = b - a;
        let mut m = if width > 0.5 * last_width {
            0.5 * (a + b)
        } else {
            (a * gb - b * ga) / (gb - ga)
        };
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
        }
        if m <= a || m >= b {
            break;
        }
        last_width = width;
        let gm = g(m);
        if gm == 0.0 {
            return m;
        }
        if gm.signum() == ga.signum() {
            a = m;
            ga = gm;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        } else {
            b = m;
            gb = gm;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// Golden-section minimisation of `g` on `[a, b]` (40 steps: the bracket shrinks by 4e-9,
/// and the caller polishes every candidate angle by exact measurement).
fn golden_min(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    crate::poly::minimize::golden_section_min(g, a, b, 40).0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force critical angles of F by a fine grid: every local extremum of the grid
    /// must be close to a returned angle.
    #[test]
    fn finds_all_grid_extrema_of_random_fields() {
        let mut seed = crate::test_rng::XorShift64(12345);
        let mut rnd = || seed.signed();
        for _ in 0..200 {
            let u = Vector3::new(rnd(), rnd(), rnd());
            let w = Vector3::new(rnd(), rnd(), rnd());
            let v = u.cross(&w).normalize() * u.norm();
            let c = ParamCircle {
                o: Point3::new(rnd(), rnd(), rnd()),
                u,
                v,
            };
            let f = RadialField {
                a: rnd() * 2.0,
                b: 1.0,
                c1: rnd(),
                c2: 1.0,
            };
            let mut out = Vec::new();
            critical_angles(&c, &f, &mut out);
            let m = 20000;
            let val = |t: f64| {
                let p = c.point(t);
                f.value(p.x.hypot(p.y), p.z)
            };
            for i in 0..m {
                let t = i as f64 * TAU / m as f64;
                let (a, b, d) = (val(t - TAU / m as f64), val(t), val(t + TAU / m as f64));
                if (b < a && b < d) || (b > a && b > d) {
                    let close = out.iter().any(|&s| {
                        let dd = (s - t).rem_euclid(TAU);
                        dd.min(TAU - dd) < 3.0 * TAU / m as f64
                    });
                    assert!(close, "missed extremum at {t}: {out:?}");
                }
            }
        }
    }
}

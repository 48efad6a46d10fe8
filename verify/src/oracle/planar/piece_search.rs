//! One-dimensional searches for the closest point of one profile piece to a point:
//! safeguarded Newton and derivative-free golden section (module documentation of
//! [`super`]).

use crate::oracle::profile_eval::{dist, dot, sub, ProfileGeom, P2};

/// Minimises `|C(t) - q|` over `[lo, hi]` on piece `k`, starting near `t0`: the bracket
/// ends, and safeguarded Newton on `h(t) = (C - q) . C'` when `h` changes sign (else plain
/// Newton steps kept inside the bracket). Returns the best realised parameter and point.
pub fn minimise_on_piece(
    geom: &ProfileGeom,
    k: usize,
    q: P2,
    lo: f64,
    hi: f64,
    t0: f64,
) -> (f64, P2) {
    let pc = &geom.pieces[k];
    let h_of = |t: f64| {
        let j = pc.jet(t);
        let r = sub(j.p, q);
        (dot(r, j.d1), dot(j.d1, j.d1) + dot(r, j.d2), j.p)
    };
    let (hlo, _, plo) = h_of(lo);
    let (hhi, _, phi) = h_of(hi);
    let mut best = if dist(plo, q) <= dist(phi, q) {
        (lo, plo)
    } else {
        (hi, phi)
    };
    let consider = |t: f64, p: P2, best: &mut (f64, P2)| {
        if dist(p, q) < dist(best.1, q) {
            *best = (t, p);
        }
    };
    if hlo < 0.0 && hhi > 0.0 {
        let (mut a, mut b) = (lo, hi);
        let mut t = t0.clamp(a, b);
        for _ in 0..100 {
            let (h, hp, p) = h_of(t);
            consider(t, p, &mut best);
            if h == 0.0 {
                break;
            }
            if h < 0.0 {
                a = t;
            } else {
                b = t;
            }
            let newton = if hp > 0.0 { t - h / hp } else { f64::NAN };
            let next = if newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - t).abs() <= 2.0 * f64::EPSILON * (t.abs() + (hi - lo)) || b - a <= 0.0 {
                break;
            }
            t = next;
        }
    } else {
        let mut t = t0.clamp(lo, hi);
        for _ in 0..20 {
            let (h, hp, p) = h_of(t);
            consider(t, p, &mut best);
            if hp <= 0.0 || h == 0.0 {
                break;
            }
            let next = (t - h / hp).clamp(lo, hi);
            if (next - t).abs() <= 2.0 * f64::EPSILON * (t.abs() + (hi - lo)) {
                break;
            }
            t = next;
        }
    }
    best
}

/// Golden-section search for the minimum of `|C(t) - q|` over `[ta, tb]` on piece `k`,
/// using curve points only (no derivatives, so a zero speed does not disturb it); the
/// iterates never leave `[ta, tb]`. Returns the best realised parameter and point seen,
/// the two ends included.
///
/// `PlanarIndex::refine_segment` calls it on one polyline segment's parameter range. That
/// range lies inside one knot span (every knot is a polyline vertex), and the closest curve
/// point lies in the range of some candidate segment (see the module documentation), so a
/// search confined to each candidate's own range loses nothing. The search finds the
/// minimum whenever `|C(t) - q|` is unimodal on the range, e.g. on a straight run however its
/// speed varies (`verify/regressions/near-stationary/zero-speed-knot.toml`: speed going to zero
/// at a knot); otherwise it still returns an actual curve point, a local minimum or an end,
/// i.e. an upper bound like every answer of [`super::PlanarIndex::closest`], and the caller
/// keeps the Newton answer when that is nearer.
///
/// It stops when the bracket is within [`GOLDEN_TOL_ULPS`] ulps of `t` (or after
/// [`GOLDEN_MAX_ITER`] steps): near the minimum `|C(t) - q|` changes by a second-order
/// amount only, so the realised distance is then exact to round-off even where the
/// comparisons can no longer order the iterates.
pub fn golden_on_piece(geom: &ProfileGeom, k: usize, q: P2, ta: f64, tb: f64) -> (f64, P2) {
    let pc = &geom.pieces[k];
    let g = |t: f64| {
        let p = pc.point(t);
        (dist(p, q), p)
    };
    let (ga, pa) = g(ta);
    let (gb, pb) = g(tb);
    let mut best = if ga <= gb { (ga, ta, pa) } else { (gb, tb, pb) };
    if tb <= ta {
        return (best.1, best.2);
    }
    // 1 / phi: the interior points split the bracket in the golden ratio, so one of them is
    // reused at every step.
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let (mut a, mut b) = (ta, tb);
    let mut x1 = b - INV_PHI * (b - a);
    let mut x2 = a + INV_PHI * (b - a);
    let (mut g1, mut p1) = g(x1);
    let (mut g2, mut p2) = g(x2);
    for _ in 0..GOLDEN_MAX_ITER {
        for (gx, x, px) in [(g1, x1, p1), (g2, x2, p2)] {
            if gx < best.0 {
                best = (gx, x, px);
            }
        }
        if b - a <= GOLDEN_TOL_ULPS * f64::EPSILON * (a.abs().max(b.abs()) + (tb - ta)) {
            break;
        }
        if g1 <= g2 {
            // The minimum is in [a, x2].
            (b, x2, g2, p2) = (x2, x1, g1, p1);
            x1 = b - INV_PHI * (b - a);
            (g1, p1) = g(x1);
        } else {
            (a, x1, g1, p1) = (x1, x2, g2, p2);
            x2 = a + INV_PHI * (b - a);
            (g2, p2) = g(x2);
        }
    }
    (best.1, best.2)
}

/// Stopping width of [`golden_on_piece`], in ulps of the parameter (plus the range): a few
/// ulps, where the search cannot order its points any more.
pub const GOLDEN_TOL_ULPS: f64 = 4.0;
/// Step cap of [`golden_on_piece`], a guard only: each step shrinks the bracket by 0.618 and
/// the stopping width is at least [`GOLDEN_TOL_ULPS`] ulps of the range, which about 73 steps
/// reach; the cap ends the loop should a non-finite value keep the test from holding.
pub const GOLDEN_MAX_ITER: usize = 100;

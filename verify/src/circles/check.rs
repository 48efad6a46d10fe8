//! One case of `verify circles`: the double-precision solver's distance and binormal count
//! against the exact reference (and the companion-matrix reference, informational).

use super::cases::Case;
use super::rcircle::RCircle;
use super::COUNT_MIN_GAP;
use crate::companion;
use crate::exact_circle::{ExactPair, RVec};
use nalgebra::Vector3;
use revdist::circle::{binormals, min_distance, Circle3, Multiplicity};

/// Outcome of one case.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub rel_err: f64,
    pub exact: f64,
    pub float: f64,
    pub count_exact: Option<usize>,
    pub count_float: usize,
    /// Smallest separation of the exact roots theta (see [`CLUSTER_GAP`](super::CLUSTER_GAP)).
    pub min_root_gap: f64,
    pub companion_rel_err: Option<f64>,
    /// The double-precision inputs the solver saw (for pinning failures as regression tests).
    pub inputs: (Circle3, Circle3),
}

/// Runs one case.
pub fn run_case(case: &Case) -> Outcome {
    let a = RCircle::canonical(case.ra.clone());
    let (am, bm) = match &case.motion {
        Some((rot, t)) => (a.moved(rot, t), case.b.moved(rot, t)),
        None => (a.clone(), case.b.clone()),
    };
    let (af, bf) = (am.to_f64(), bm.to_f64());
    let m = min_distance(&af, &bf);
    let pair = case.exact_pair();
    let cnorm = case
        .b
        .c
        .iter()
        .map(|x| x.to_f64().powi(2))
        .sum::<f64>()
        .sqrt();
    let scale = case.ra.to_f64().max(case.b.r.to_f64()).max(cnorm);
    let mut min_root_gap = f64::INFINITY;
    let (exact, count_exact) = match (case.analytic, pair.analyse()) {
        (Some(d), _) => (d, None),
        (None, Some(res)) => {
            min_root_gap = res.min_root_gap;
            (res.min_distance.to_f64(), Some(res.root_count))
        }
        // B's polynomial vanishes identically: parametrise A instead (the count is then of
        // parameters on A, so it is not compared).
        (None, None) => match (pair.swapped().analyse(), pair.coaxial_distance()) {
            (Some(res), _) => (res.min_distance.to_f64(), None),
            (None, Some(d)) => (d.to_f64(), None),
            (None, None) => (f64::NAN, None),
        },
    };
    let bn = binormals(&af, &bf, None, None);
    // The exact count is of distinct parameters theta on B; count distinct angle_b likewise.
    let count_float = if bn.multiplicity == Multiplicity::Finite {
        let mut seen: Vec<f64> = Vec::new();
        for x in bn.items.iter() {
            let same = |t: &f64| {
                let d = (x.angle_b - t).rem_euclid(std::f64::consts::TAU);
                d.min(std::f64::consts::TAU - d) <= 1e-7
            };
            if !seen.iter().any(same) {
                seen.push(x.angle_b);
            }
        }
        seen.len()
    } else {
        usize::MAX
    };
    let count_exact = count_exact.filter(|_| exact > COUNT_MIN_GAP * scale);
    let companion_rel_err = if case.analytic.is_none() {
        companion_min(&pair).map(|d| (d - exact).abs() / scale)
    } else {
        None
    };
    Outcome {
        rel_err: (m.distance - exact).abs() / scale,
        exact,
        float: m.distance,
        count_exact,
        count_float,
        min_root_gap,
        companion_rel_err,
        inputs: (af, bf),
    }
}

/// Minimum distance from the companion-matrix roots of the (exact, then rounded) polynomial.
///
/// Every eigenvalue's real part is a candidate angle, polished by Newton steps on the rounded
/// polynomial: near-double roots (nearly touching circles) split into complex pairs under
/// rounding, with imaginary parts far above any fixed threshold once the coefficients span
/// many orders of magnitude. A candidate is only ever evaluated as a realised distance, so
/// extra candidates cannot make the reference smaller than the true minimum.
fn companion_min(pair: &ExactPair) -> Option<f64> {
    let p: Vec<f64> = pair.binormal_poly().iter().map(|c| c.to_f64()).collect();
    let scale = p.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if scale == 0.0 {
        return None;
    }
    let f = |x: &RVec| Vector3::new(x[0].to_f64(), x[1].to_f64(), x[2].to_f64());
    let (c, u, v) = (f(&pair.c), f(&pair.u), f(&pair.v));
    let (ra, rb) = (pair.ra.to_f64(), pair.rb.to_f64());
    let dist = |theta: f64| {
        let q = c + rb * (theta.cos() * u + theta.sin() * v);
        q.z.hypot(q.x.hypot(q.y) - ra)
    };
    let mut best = dist(std::f64::consts::PI);
    for (re, _) in companion::complex_roots(&p)? {
        let x = companion::polish_root(&p, re);
        best = best.min(dist(2.0 * x.atan())).min(dist(2.0 * re.atan()));
    }
    Some(best)
}

//! Dense-sampling oracle for the two-sided Hausdorff distance between a curve piece and a chain
//! of arcs. For tests and experiments only: it *estimates* the truth, it never bounds it, and no
//! error bound in the tree comes from here.

use nalgebra::Point2;

use super::arc::Arc;
use super::fit::PlanarCurve;
use crate::nearest::NearestPoint;

/// Golden-section iterations used to refine the arc-to-curve distance between two neighbouring
/// curve samples: 60 iterations shrink the bracket by 0.618^60 ~ 3e-13.
const GOLDEN_ITERS: usize = 60;

/// Distance from `p` to the nearest of `arcs`.
pub fn distance_to_arcs(p: Point2<f64>, arcs: &[Arc]) -> f64 {
    arcs.iter()
        .map(|a| a.distance_to(p))
        .fold(f64::INFINITY, f64::min)
}

/// Sampled two-sided Hausdorff distance between `curve` on `[t0, t1]` and `arcs`, with
/// `samples` curve samples and `samples` samples per arc. The curve-to-arcs side uses exact
/// point-to-arc distances at curve samples; the arcs-to-curve side refines the nearest curve
/// sample by golden-section search on the neighbouring parameter interval.
pub fn sampled_hausdorff<C: PlanarCurve + ?Sized>(
    curve: &C,
    t0: f64,
    t1: f64,
    arcs: &[Arc],
    samples: usize,
) -> f64 {
    let n = samples.max(2);
    let ts: Vec<f64> = (0..=n)
        .map(|i| t0 + (t1 - t0) * i as f64 / n as f64)
        .collect();
    let pts: Vec<Point2<f64>> = ts
        .iter()
        .map(|&t| curve.point_and_derivative(t).0)
        .collect();
    let mut h = pts
        .iter()
        .map(|&p| distance_to_arcs(p, arcs))
        .fold(0.0, f64::max);
    for arc in arcs {
        for i in 0..=n {
            let x = arc.point_at(arc.length * i as f64 / n as f64);
            let (k, _) = pts
                .iter()
                .enumerate()
                .map(|(k, p)| (k, (p - x).norm_squared()))
                .fold(
                    (0, f64::INFINITY),
                    |acc, e| if e.1 < acc.1 { e } else { acc },
                );
            let lo = ts[k.saturating_sub(1)];
            let hi = ts[(k + 1).min(n)];
            h = h.max(golden_distance(curve, x, lo, hi));
        }
    }
    h
}

/// Minimum of `|C(t) - x|` on `[lo, hi]` by golden-section search (assumes one local minimum,
/// true for a bracket of two sample spacings around the nearest sample of a dense sampling).
fn golden_distance<C: PlanarCurve + ?Sized>(curve: &C, x: Point2<f64>, lo: f64, hi: f64) -> f64 {
    let f = |t: f64| (curve.point_and_derivative(t).0 - x).norm();
    let (_, inner) = crate::poly::minimize::golden_section_min(f, lo, hi, GOLDEN_ITERS);
    inner.min(f(lo)).min(f(hi))
}

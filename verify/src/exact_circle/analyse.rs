//! The exact analysis of a pair: root count (spurious axis roots excluded), binormals,
//! minimum distance and the smallest root separation.

use super::poly::{deg, is_zero, pdiv_exact, trim};
use super::roots::isolate_and_refine;
use super::sturm::{count_real_roots, sturm};
use super::{ExactPair, PREC};
use rug::Float;

impl ExactPair {
    /// Exact analysis: distinct real binormal parameters theta (the root count, including
    /// theta = pi) and the minimum distance over them. `None` when P vanishes identically
    /// (a continuum; use an analytic reference).
    pub fn analyse(&self) -> Option<ExactResult> {
        let p = trim(self.binormal_poly());
        if is_zero(&p) {
            return None;
        }
        let at_infinity = p.len() < 9;
        let seq = sturm(&p);
        let gcd = seq.last().unwrap().clone();
        let sqf = if deg(&gcd) == 0 {
            p.clone()
        } else {
            pdiv_exact(&p, &gcd)
        };
        let finite = count_real_roots(&p);
        let roots = isolate_and_refine(&sqf);
        debug_assert_eq!(roots.len(), finite);
        let mut min = Float::with_val(PREC, f64::INFINITY);
        let one = Float::with_val(PREC, 1);
        let mut thetas: Vec<f64> = roots.iter().map(|u| 2.0 * u.to_f64().atan()).collect();
        if at_infinity {
            thetas.push(std::f64::consts::PI);
        }
        let mut spurious = 0;
        let mut binormals = Vec::new();
        for u in &roots {
            let u2 = Float::with_val(PREC, u * u);
            let den = Float::with_val(PREC, &one + &u2);
            let cos = Float::with_val(PREC, &one - &u2) / &den;
            let sin = Float::with_val(PREC, u * 2u32) / &den;
            let sp = self.spurious_axis_root(&cos, &sin);
            spurious += usize::from(sp);
            if !sp {
                binormals.push((2.0 * u.to_f64().atan(), self.binormal_length(&cos, &sin)));
            }
            let d = self.dist_at(&cos, &sin);
            if d < min {
                min = d;
            }
        }
        if at_infinity {
            let (cos, sin) = (Float::with_val(PREC, -1), Float::with_val(PREC, 0));
            let sp = self.spurious_axis_root(&cos, &sin);
            spurious += usize::from(sp);
            if !sp {
                binormals.push((std::f64::consts::PI, self.binormal_length(&cos, &sin)));
            }
            let d = self.dist_at(&Float::with_val(PREC, -1), &Float::with_val(PREC, 0));
            if d < min {
                min = d;
            }
        }
        Some(ExactResult {
            root_count: finite + usize::from(at_infinity) - spurious,
            spurious_roots: spurious,
            binormals,
            min_distance: min,
            min_root_gap: min_circular_gap(&mut thetas),
        })
    }
}

/// Result of [`ExactPair::analyse`].
#[derive(Debug, Clone)]
pub struct ExactResult {
    /// Distinct real roots theta in [0, 2 pi) that are binormal parameters (spurious roots
    /// excluded).
    pub root_count: usize,
    /// Roots of P where B(theta) is on A's axis without a binormal there.
    pub spurious_roots: usize,
    /// (theta, binormal length) for each non-spurious root (theta = 2 atan(u) in (-pi, pi]).
    pub binormals: Vec<(f64, f64)>,
    /// Minimum distance (PREC bits).
    pub min_distance: Float,
    /// Smallest angular separation of two distinct roots theta (radians, on the circle);
    /// infinity with fewer than two roots.
    pub min_root_gap: f64,
}

/// Smallest separation of the angles in `thetas` around the circle (sorts them).
fn min_circular_gap(thetas: &mut [f64]) -> f64 {
    if thetas.len() < 2 {
        return f64::INFINITY;
    }
    thetas.sort_by(f64::total_cmp);
    let wrap = thetas[0] + std::f64::consts::TAU - thetas[thetas.len() - 1];
    thetas.windows(2).map(|w| w[1] - w[0]).fold(wrap, f64::min)
}

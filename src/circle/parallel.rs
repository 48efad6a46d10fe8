//! Circles in parallel planes (including coplanar and coaxial): closed-form 2-D analysis of
//! the projections along the common normal (`docs/numerics.md` section 3, "Coplanar circles").

use super::frame::LocalPair;
use super::{Multiplicity, TIE_REL_TOL};

/// A closest or binormal pair in local angles, with its local length.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LocalPairAngles {
    pub phi: f64,
    pub theta: f64,
    pub dist: f64,
}

/// Angle on B of a direction `(dx, dy)` of A's plane (B's plane is parallel to it).
fn theta_of_dir(lp: &LocalPair, dx: f64, dy: f64) -> f64 {
    let (cu, cv) = (dx * lp.u.x + dy * lp.u.y, dx * lp.v.x + dy * lp.v.y);
    cv.atan2(cu)
}

/// The parallel-plane solution: binormals (the four pairs on the centre line, plus the two
/// pairs over the crossings of the projected circles, joined along the common normal; one
/// representative when coaxial) and the closest pairs.
pub(crate) struct ParallelSolution {
    pub binormals: [LocalPairAngles; 6],
    pub n_binormals: usize,
    pub closest: [LocalPairAngles; 2],
    pub n_closest: usize,
    pub multiplicity: Multiplicity,
}

/// Solves the parallel case in local units (scale 1).
pub(crate) fn solve(lp: &LocalPair) -> ParallelSolution {
    let (ra, rb, h) = (lp.ra, lp.rb, lp.c.z);
    let delta = lp.c.x.hypot(lp.c.y);
    let zero = LocalPairAngles {
        phi: 0.0,
        theta: 0.0,
        dist: 0.0,
    };
    let mk = |phi: f64, ex: f64, ey: f64, sign_b: f64| {
        let theta = theta_of_dir(lp, sign_b * ex, sign_b * ey);
        let (s, c) = phi.sin_cos();
        let pa = nalgebra::Vector3::new(ra * c, ra * s, 0.0);
        let pb = lp.pb(theta);
        LocalPairAngles {
            phi,
            theta,
            dist: (pa - pb).norm(),
        }
    };
    if delta == 0.0 {
        // Coaxial: every pair at equal angle is a binormal; one representative.
        let rep = mk(0.0, 1.0, 0.0, 1.0);
        let rep_far = mk(0.0, 1.0, 0.0, -1.0);
        let mut closest = [rep, zero];
        closest[0].dist = h.hypot(ra - rb);
        return ParallelSolution {
            binormals: [rep, rep_far, zero, zero, zero, zero],
            n_binormals: 2,
            closest,
            n_closest: 1,
            multiplicity: Multiplicity::ContinuumOnBoth,
        };
    }
    let (ex, ey) = (lp.c.x / delta, lp.c.y / delta);
    let phi_e = ey.atan2(ex);
    let phi_o = phi_e + std::f64::consts::PI;
    let mut binormals = [
        mk(phi_e, ex, ey, 1.0),
        mk(phi_e, ex, ey, -1.0),
        mk(phi_o, ex, ey, 1.0),
        mk(phi_o, ex, ey, -1.0),
        zero,
        zero,
    ];
    let mut n_binormals = 4;
    let mut closest = [zero; 2];
    let n_closest;
    if delta >= ra + rb || delta <= (ra - rb).abs() {
        // Separated or nested projections: the closest pair is on the centre line.
        let best =
            binormals[..4]
                .iter()
                .copied()
                .fold(binormals[0], |m, b| if b.dist < m.dist { b } else { m });
        closest[0] = best;
        n_closest = 1;
    } else {
        // Overlapping projections: two symmetric pairs at the projected intersections.
        // x = (delta^2 + ra^2 - rb^2) / (2 delta), y = sqrt(ra^2 - x^2), written without
        // cancellation: with e = delta - ra, ra - x = (rb - e)(rb + e) / (2 delta). Near
        // tangency (y -> 0) the direct form loses half the digits of y, which moves the
        // witness points along the circles by ~sqrt(eps) and the distance with them.
        let e = delta - ra;
        let ra_minus_x = (rb - e) * (rb + e) / (2.0 * delta);
        let x = ra - ra_minus_x;
        let y = (ra_minus_x * (ra + x)).max(0.0).sqrt();
        for (k, sy) in [1.0, -1.0].into_iter().enumerate() {
            let (px, py) = (x * ex - sy * y * ey, x * ey + sy * y * ex);
            let phi = py.atan2(px);
            let (dx, dy) = (px - lp.c.x, py - lp.c.y);
            let theta = theta_of_dir(lp, dx, dy);
            let pa = lp.pa(phi);
            let pb = lp.pb(theta);
            closest[k] = LocalPairAngles {
                phi,
                theta,
                dist: (pa - pb).norm(),
            };
        }
        n_closest = if y <= TIE_REL_TOL { 1 } else { 2 };
        // The segments joining the crossings of the projections run along the common
        // normal, perpendicular to both circles: binormals too (distinct from the centre-line
        // ones unless the projections touch).
        if y > TIE_REL_TOL {
            binormals[4] = closest[0];
            binormals[5] = closest[1];
            n_binormals = 6;
        }
    }
    // Centres within the tie tolerance of a common axis: the distance above is exact for
    // the given data, but the closest pair is only determined up to that tolerance.
    let multiplicity = if delta <= TIE_REL_TOL {
        Multiplicity::ContinuumOnBoth
    } else {
        Multiplicity::Finite
    };
    ParallelSolution {
        binormals,
        n_binormals,
        closest,
        n_closest,
        multiplicity,
    }
}

//! Guaranteed two-sided Hausdorff bounds between a spiral and its biarc: the lens and the
//! bilens of Kurnosenko (2013), as used by Son et al. 2020, section 4.1.
//!
//! **Lens.** A *short spiral* (convex, curvature monotone, total turning below pi) from `A`
//! (unit tangent `T_A`) to `B` (unit tangent `T_B`) lies in the lens bounded by the two circular
//! arcs through `A` and `B`, one tangent to `T_A` at `A`, the other tangent to `T_B` at `B`
//! (Vogt's theorem). Both walls are symmetric about the chord's bisector; for minor arcs
//! (tangent-chord angles at most pi/2, guaranteed because segmented spirals turn at most 90
//! degrees) the distance from any point between the walls to either wall is a monotone function
//! of its height in the pencil of circles through `A, B`, so the two-sided Hausdorff distance
//! between the spiral and either wall is at most the apex separation
//! `w = h |tan(phi_a / 2) - tan(phi_b / 2)|` (`h` the half chord, `phi_a, phi_b` the
//! tangent-chord angles; derivation in `docs/numerics.md`, "Biarcs: the spiral lens").
//!
//! **Bilens.** With the joint `J = C(t_J)` *on the curve*, the first biarc arc is exactly the
//! `T_A` wall of lens(A, J) and the second exactly the `T_B` wall of lens(J, B); hence
//! `H(spiral, biarc) <= max(w(A, J), w(J, B))` using the *curve's* tangent at `J`
//! (notes section 2.2). This holds whatever joint rule picked `t_J`.

use nalgebra::{Point2, Vector2};

use crate::num::cross2;

/// Relative inflation of every lens width, covering the rounding of the few dozen floating-point
/// operations in [`lens_width`] (each contributes at most one ulp, ~1.1e-16 relative).
pub const BOUND_REL_SLACK: f64 = 1e-12;

/// Absolute slack, in units of `f64::EPSILON * scale` (scale = largest coordinate magnitude of
/// the three points involved plus the chord). It covers the error of evaluating the curve
/// points themselves (a few ulps of the coordinates for a stable de Casteljau evaluation) and the
/// straight-arc snap of `arc::STRAIGHT_SWEEP`.
pub const BOUND_ULP_SLACK: f64 = 64.0;

/// Width of the lens between a short spiral from `a` (tangent `ta`) to `b` (tangent `tb`): the
/// largest separation of its two walls. Tangents need not be unit length.
pub fn lens_width(a: Point2<f64>, ta: Vector2<f64>, b: Point2<f64>, tb: Vector2<f64>) -> f64 {
    let chord = b - a;
    let h = 0.5 * chord.norm();
    if h == 0.0 {
        return 0.0;
    }
    // phi_a = angle(T_A) - angle(AB), phi_b = angle(AB) - angle(T_B)
    let phi_a = cross2(chord, ta).atan2(chord.dot(&ta));
    let phi_b = cross2(tb, chord).atan2(tb.dot(&chord));
    h * ((0.5 * phi_a).tan() - (0.5 * phi_b).tan()).abs()
}

/// Absolute floating-point slack for points of magnitude up to `scale`.
pub fn ulp_slack(scale: f64) -> f64 {
    BOUND_ULP_SLACK * f64::EPSILON * scale
}

/// A lens width made safe against rounding: `w (1 + BOUND_REL_SLACK) + ulp_slack(scale)`.
pub fn inflate(width: f64, scale: f64) -> f64 {
    width * (1.0 + BOUND_REL_SLACK) + ulp_slack(scale)
}

/// The bilens bound of a biarc whose joint `j` lies on the curve, where the curve has tangent
/// `tj` (the curve's, not the biarc's). Includes the floating-point slack.
pub fn bilens_bound(
    a: Point2<f64>,
    ta: Vector2<f64>,
    j: Point2<f64>,
    tj: Vector2<f64>,
    b: Point2<f64>,
    tb: Vector2<f64>,
) -> f64 {
    let w = lens_width(a, ta, j, tj).max(lens_width(j, tj, b, tb));
    let scale = a.coords.amax().max(b.coords.amax()).max(j.coords.amax()) + (b - a).norm();
    inflate(w, scale)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn lens_of_a_circle_is_flat() {
        let p = |phi: f64| Point2::new(phi.cos(), phi.sin());
        let t = |phi: f64| Vector2::new(-phi.sin(), phi.cos());
        let w = lens_width(p(0.1), t(0.1), p(1.2), t(1.2));
        assert!(w < 1e-15, "w = {w}");
    }

    #[test]
    fn lens_width_is_the_apex_separation() {
        // Chord from (-1,0) to (1,0); wall a tangent at 30 deg, wall b at 50 deg.
        let (pa, pb) = (30f64.to_radians(), 50f64.to_radians());
        let ta = Vector2::new(pa.cos(), pa.sin());
        let tb = Vector2::new(pb.cos(), -pb.sin());
        let w = lens_width(Point2::new(-1.0, 0.0), ta, Point2::new(1.0, 0.0), tb);
        // sagitta of a minor arc with tangent-chord angle phi over half chord 1: tan(phi/2)
        let expect = (pb / 2.0).tan() - (pa / 2.0).tan();
        assert!((w - expect).abs() < 1e-15, "{w} vs {expect}");
        assert!(lens_width(Point2::new(1.0, 0.0), ta, Point2::new(1.0, 0.0), tb) == 0.0);
        assert!(inflate(w, 1.0) > w && inflate(0.0, 1.0) < 1e-13);
        let _ = PI;
    }
}

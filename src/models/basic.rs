//! Simple analytic solids: torus (`ring`), `sphere`, `capsule`, `cylinder`, `cone`.
//! Circles are exact rational quadratic arcs; straight pieces are degree-1 NURBS except the
//! cone's slant, which is a degree-2 B-spline with collinear control points.

use super::primitives::{arc, deg, line, line_quadratic, pt};
use super::ModelError;
use crate::profile::Profile;

/// Torus: a full circle of radius 0.6 about (rho, z) = (0.9, 0.6), counter-clockwise from its
/// lowest point. Closed profile, rho >= 0.3 > 0. Height 1.2.
pub fn ring() -> Result<Profile, ModelError> {
    let pieces = vec![arc([0.9, 0.6], 0.6, deg(-90.0), deg(270.0))?];
    Ok(Profile::new("ring", pieces)?)
}

/// Ball of radius 0.75 centred at z = 0.75: an exact semicircle from the south to the north
/// pole. Height 1.5.
pub fn sphere() -> Result<Profile, ModelError> {
    let pieces = vec![arc([0.0, 0.75], 0.75, deg(-90.0), deg(90.0))?];
    Ok(Profile::new("sphere", pieces)?)
}

/// Capsule: cylinder of radius 0.4 and length 0.8 capped by two hemispheres (G1 joins).
/// Height 1.6.
pub fn capsule() -> Result<Profile, ModelError> {
    let pieces = vec![
        arc([0.0, 0.4], 0.4, deg(-90.0), 0.0)?,
        line(pt(0.4, 0.4), pt(0.4, 1.2))?,
        arc([0.0, 1.2], 0.4, 0.0, deg(90.0))?,
    ];
    Ok(Profile::new("capsule", pieces)?)
}

/// Cylinder of radius 0.5 and height 1.5: bottom disk, side, top disk (two creases).
pub fn cylinder() -> Result<Profile, ModelError> {
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.5, 0.0))?,
        line(pt(0.5, 0.0), pt(0.5, 1.5))?,
        line(pt(0.5, 1.5), pt(0.0, 1.5))?,
    ];
    Ok(Profile::new("cylinder", pieces)?)
}

/// Cone of base radius 0.6 and height 1.5: bottom disk and a slant ending at the apex on the
/// axis (the profile meets the axis at an angle, not perpendicularly).
pub fn cone() -> Result<Profile, ModelError> {
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.6, 0.0))?,
        line_quadratic(pt(0.6, 0.0), pt(0.0, 1.5))?,
    ];
    Ok(Profile::new("cone", pieces)?)
}

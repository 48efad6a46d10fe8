//! The five static solids of the paper's experiments (section 5, Figure 7): pawn, cup,
//! bottle, table and lightmill. Each profile is open on the axis: it starts at the bottom
//! on rho = 0, runs counter-clockwise in the (rho, z) plane (the solid lies on its left) and
//! ends on rho = 0 at the top. Heights are between 1.2 and 2 units.
//!
//! Features, by model (a crease is a G0 join whose tangent turns; convex/concave is seen
//! from the solid):
//! - pawn: flat disk, cylinder, convex torus bead, concave cove with an inflection into a
//!   tapered body, collar (flat annuli and a torus), concave neck, spherical head meeting the
//!   axis; creases at the base edge, under and over the collar, and at the head.
//! - cup: flat bottom disk, conical chamfer, concave flaring outer wall, torus rim, inner wall,
//!   concave fillet and flat inner floor meeting the axis (the cavity is a concave region).
//! - bottle: flat bottom with a fillet, cylinder, S-shaped shoulder (inflection), cylindrical
//!   neck, torus lip, flat top.
//! - table: flat base disk and cylinder edge, concave flares into and out of a thin
//!   cylindrical stem, flat annulus and cylinder edge of a flat top.
//! - lightmill: plinth (cylinder and flat annuli), conical tower, gallery (flat annuli and
//!   cylinder), concave lantern waist, eave, conical roof, spherical finial meeting the axis;
//!   nearly every join is a crease.

use super::primitives::{arc, arc_point, bezier, deg, line, pt};
use super::ModelError;
use crate::profile::Profile;

/// Chess pawn, height 1.48.
pub fn pawn() -> Result<Profile, ModelError> {
    let head_center = [0.0, 1.22];
    let head_radius = 0.26;
    let head_start = arc_point(head_center, head_radius, deg(-60.0));
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.5, 0.0))?,
        line(pt(0.5, 0.0), pt(0.5, 0.12))?,
        arc([0.38, 0.12], 0.12, 0.0, deg(90.0))?,
        // Concave cove turning into the convex tapered body: one inflection.
        bezier(&[[0.38, 0.24], [0.24, 0.24], [0.24, 0.50], [0.16, 0.80]])?,
        line(pt(0.16, 0.80), pt(0.30, 0.80))?,
        arc([0.30, 0.84], 0.04, deg(-90.0), deg(90.0))?,
        line(pt(0.30, 0.88), pt(0.14, 0.88))?,
        // Concave neck.
        bezier(&[
            [0.14, 0.88],
            [0.09, 0.91],
            [0.10, 0.95],
            [head_start.x, head_start.y],
        ])?,
        arc(head_center, head_radius, deg(-60.0), deg(90.0))?,
    ];
    Ok(Profile::new("pawn", pieces)?)
}

/// Cup with a flat bottom, walls of thickness about 0.05 and a rounded rim, height 1.225.
pub fn cup() -> Result<Profile, ModelError> {
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.32, 0.0))?,
        line(pt(0.32, 0.0), pt(0.36, 0.05))?,
        // Concave outer wall flaring outwards.
        bezier(&[[0.36, 0.05], [0.38, 0.45], [0.42, 0.85], [0.50, 1.20]])?,
        arc([0.475, 1.20], 0.025, 0.0, deg(180.0))?,
        // Inner wall, ending vertically into the fillet.
        bezier(&[[0.45, 1.20], [0.38, 0.85], [0.30, 0.45], [0.30, 0.14]])?,
        // Concave fillet between the inner wall and the inner floor (clockwise arc).
        arc([0.24, 0.14], 0.06, 0.0, deg(-90.0))?,
        line(pt(0.24, 0.08), pt(0.0, 0.08))?,
    ];
    Ok(Profile::new("cup", pieces)?)
}

/// Bottle with a cylindrical body, S-shaped shoulder and a narrow neck, height 1.70.
pub fn bottle() -> Result<Profile, ModelError> {
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.31, 0.0))?,
        arc([0.31, 0.05], 0.05, deg(-90.0), 0.0)?,
        line(pt(0.36, 0.05), pt(0.36, 0.90))?,
        // Shoulder: convex then concave, tangent-continuous with body and neck.
        bezier(&[[0.36, 0.90], [0.36, 1.15], [0.12, 1.12], [0.12, 1.35]])?,
        line(pt(0.12, 1.35), pt(0.12, 1.62))?,
        line(pt(0.12, 1.62), pt(0.15, 1.62))?,
        arc([0.15, 1.66], 0.04, deg(-90.0), deg(90.0))?,
        line(pt(0.15, 1.70), pt(0.0, 1.70))?,
    ];
    Ok(Profile::new("bottle", pieces)?)
}

/// Pedestal table: flat base, thin stem (radius 0.05), flat top of radius 0.6, height 1.46.
pub fn table() -> Result<Profile, ModelError> {
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.45, 0.0))?,
        line(pt(0.45, 0.0), pt(0.45, 0.05))?,
        bezier(&[[0.45, 0.05], [0.15, 0.05], [0.05, 0.10], [0.05, 0.30]])?,
        line(pt(0.05, 0.30), pt(0.05, 1.15))?,
        bezier(&[[0.05, 1.15], [0.05, 1.33], [0.12, 1.40], [0.30, 1.40]])?,
        line(pt(0.30, 1.40), pt(0.60, 1.40))?,
        line(pt(0.60, 1.40), pt(0.60, 1.46))?,
        line(pt(0.60, 1.46), pt(0.0, 1.46))?,
    ];
    Ok(Profile::new("table", pieces)?)
}

/// Lighthouse-like lamp post ("lightmil" in the paper's tables), height 1.94.
pub fn lightmill() -> Result<Profile, ModelError> {
    let finial_center = [0.0, 1.86];
    let finial_radius = 0.08;
    let finial_start = arc_point(finial_center, finial_radius, deg(-60.0));
    let pieces = vec![
        line(pt(0.0, 0.0), pt(0.32, 0.0))?,
        line(pt(0.32, 0.0), pt(0.32, 0.08))?,
        line(pt(0.32, 0.08), pt(0.26, 0.08))?,
        line(pt(0.26, 0.08), pt(0.16, 1.20))?,
        line(pt(0.16, 1.20), pt(0.28, 1.20))?,
        line(pt(0.28, 1.20), pt(0.28, 1.26))?,
        line(pt(0.28, 1.26), pt(0.13, 1.26))?,
        bezier(&[[0.13, 1.26], [0.10, 1.36], [0.10, 1.46], [0.13, 1.56]])?,
        line(pt(0.13, 1.56), pt(0.20, 1.56))?,
        line(pt(0.20, 1.56), finial_start)?,
        arc(finial_center, finial_radius, deg(-60.0), deg(90.0))?,
    ];
    Ok(Profile::new("lightmill", pieces)?)
}

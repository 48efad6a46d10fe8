//! A body's profile at a scene time: its built-in model, profile file, torus or M_t frame
//! (`docs/scenes.md`).

use super::model::{Body, Shape};
use revdist::models::morph::Morph;
use revdist::profile::Profile;

/// The profile of a body at scene time `time` (M_t frames for a morph).
pub fn shape_profile(body: &Body, time: f64) -> Result<Profile, String> {
    match &body.shape {
        Shape::Model(m) => revdist::models::model(m).map_err(|e| e.to_string()),
        Shape::ProfileFile(p) => revdist::profile_file::load_path(p).map_err(|e| e.to_string()),
        Shape::Torus { major, minor } => torus_profile(*major, *minor),
        Shape::Morph { period } => {
            let t = (time / period).rem_euclid(1.0);
            Morph::shared()
                .and_then(|m| m.frame(t))
                .map_err(|e| e.to_string())
        }
    }
}

/// A torus profile: the full circle of radius `minor` about `(rho, z) = (major, 0)`, an exact
/// rational quadratic NURBS from its lowest point, counter-clockwise (as the built-in `ring`).
pub fn torus_profile(major: f64, minor: f64) -> Result<Profile, String> {
    use revdist::models::primitives::{arc, deg};
    let circle = arc([major, 0.0], minor, deg(-90.0), deg(270.0)).map_err(|e| e.to_string())?;
    Profile::new("torus", vec![circle]).map_err(|e| e.to_string())
}

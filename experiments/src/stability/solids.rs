//! The fixed solids of the solid level (sphere, cylinder, cone, ring, two balls), built once
//! at the run's eps.

use super::Error;
use revdist::models::primitives::{arc, deg, line, pt};
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::sync::Arc;

pub(super) fn ball(r: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("ball {r}"),
        vec![arc([0.0, r], r, deg(-90.0), deg(90.0))?],
    )?)
}

pub(super) fn cylinder(radius: f64, height: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("cylinder {radius}x{height}"),
        vec![
            line(pt(0.0, 0.0), pt(radius, 0.0))?,
            line(pt(radius, 0.0), pt(radius, height))?,
            line(pt(radius, height), pt(0.0, height))?,
        ],
    )?)
}

pub(super) fn ring(big_r: f64, r: f64, zc: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("ring {big_r}/{r}"),
        vec![arc([big_r, zc], r, deg(-90.0), deg(270.0))?],
    )?)
}

/// The fixed solids of the solid level, built once at the run's eps.
pub struct Shapes {
    pub(super) eps: f64,
    /// Built-in `sphere`: radius 0.75, centre (0, 0, 0.75).
    pub(super) sphere: Solid,
    /// Built-in `cylinder`: radius 0.5, z in [0, 1.5].
    pub(super) cylinder: Solid,
    /// Built-in `cone`: base radius 0.6 at z = 0, apex (0, 0, 1.5).
    pub(super) cone: Solid,
    /// Built-in `ring`: tube circle radius 0.9 at z = 0.6, tube radius 0.6.
    pub(super) ring: Solid,
    /// Balls of radius 0.5 and 0.4 resting on z = 0.
    pub(super) ball_05: Solid,
    pub(super) ball_04: Solid,
}

impl Shapes {
    pub fn new(eps: f64) -> Result<Shapes, Error> {
        let built = |p: Profile| Solid::from_profile(Arc::new(p), eps);
        let model =
            |name: &str| -> Result<Solid, Error> { Ok(built(revdist::models::model(name)?)?) };
        Ok(Shapes {
            eps,
            sphere: model("sphere")?,
            cylinder: model("cylinder")?,
            cone: model("cone")?,
            ring: model("ring")?,
            ball_05: built(ball(0.5)?)?,
            ball_04: built(ball(0.4)?)?,
        })
    }

    pub(super) fn build(&self, p: Profile) -> Result<Solid, Error> {
        Ok(Solid::from_profile(Arc::new(p), self.eps)?)
    }
}

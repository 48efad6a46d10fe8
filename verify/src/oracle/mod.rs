//! An independent oracle for certified distance queries between solids of revolution.
//!
//! It shares no code with `revdist::query`: it reads a profile's raw NURBS data and a solid's
//! pose, and does its own evaluation ([`profile_eval`]), planar distance and point-in-region
//! ([`planar`]), surface distance with lower and upper estimates ([`mod@surface_distance`]), and
//! checks a query's answer against it ([`checks`]).

pub mod checks;
pub mod planar;
pub mod profile_eval;
pub mod surface_distance;

pub use checks::{check, scene_slack, Check, CheckInput, Violation};
pub use planar::PlanarIndex;
pub use profile_eval::ProfileGeom;
pub use surface_distance::{refine_hint, surface_distance, OracleOptions, OracleResult};

use revdist::profile::Profile;

/// The oracle's view of a profile: own evaluation and a polyline hierarchy.
pub fn index(profile: &Profile) -> PlanarIndex {
    PlanarIndex::new(ProfileGeom::new(profile))
}

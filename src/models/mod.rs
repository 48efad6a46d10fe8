//! Built-in profiles, usable by name wherever a profile file is accepted.
//!
//! - The paper's five static solids (section 5, Figure 7): `pawn`, `cup`, `bottle`, `table`,
//!   `lightmill` ([`paper`]), and their freeform variants `pawn_ff`, `cup_ff`, `bottle_ff`,
//!   `table_ff`, `lightmill_ff`: the same silhouettes as clamped cubic B-splines with many
//!   control points, one per smooth run ([`freeform`]).
//! - Analytic solids: `ring` (torus), `sphere`, `capsule`, `cylinder`, `cone` ([`basic`]).
//! - The deformable model M_t of section 5 ([`mod@morph`]): by name as `morph@T` with T a number
//!   (wrapped into [0, 1)), e.g. `morph@0.25`.
//!
//! All profiles run counter-clockwise in the (rho, z) plane (the solid lies to the left of
//! the direction of travel); open profiles start at the bottom of the axis and end at its top.

pub mod basic;
mod fit;
pub mod freeform;
pub mod morph;
pub mod paper;
pub mod primitives;
pub mod sampling;
pub mod validate;

#[cfg(test)]
mod tests;

pub use freeform::{freeform_names, FreeformReport, FREEFORM_NAMES};
pub use morph::{morph, Morph, MorphFitReport};

use crate::nurbs::CurveError;
use crate::profile::{Profile, ProfileError};

/// Errors from building or looking up a built-in model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModelError {
    /// The name is not a built-in model.
    #[error("unknown model '{name}'; valid names: {valid}, or morph@T with T a number")]
    UnknownModel { name: String, valid: String },
    /// `morph@T` whose T does not parse as a number.
    #[error(
        "bad morph parameter in '{0}': expected morph@T with T a finite number, e.g. morph@0.25"
    )]
    BadMorphName(String),
    /// The morph parameter t is NaN or infinite.
    #[error("morph parameter t must be finite, got {0}")]
    NonFiniteMorphParameter(f64),
    /// Fitting the common representation of the morph keyframes failed.
    #[error("morph keyframe '{model}': {detail}")]
    MorphFit { model: String, detail: String },
    /// Fitting a freeform variant failed (a bug in the fitter or the model tables).
    #[error("freeform variant '{model}': {detail}")]
    FreeformFit { model: String, detail: String },
    /// A model piece was rejected by the NURBS constructor (a bug in the model tables).
    #[error("invalid model curve: {0}")]
    Curve(#[from] CurveError),
    /// A model was rejected by the profile validation (a bug in the model tables).
    #[error("invalid model profile: {0}")]
    Profile(#[from] ProfileError),
}

/// Names of the built-in static models, in display order: the paper's five, their freeform
/// variants ([`freeform_names`]), then the analytic solids.
pub fn model_names() -> &'static [&'static str] {
    &[
        "pawn",
        "cup",
        "bottle",
        "table",
        "lightmill",
        "pawn_ff",
        "cup_ff",
        "bottle_ff",
        "table_ff",
        "lightmill_ff",
        "ring",
        "sphere",
        "capsule",
        "cylinder",
        "cone",
    ]
}

/// Prefix of the deformable model's names: `morph@T`.
pub const MORPH_PREFIX: &str = "morph@";

/// The built-in model called `name` (see [`model_names`]), or a frame `morph@T` of the
/// deformable model M_t.
pub fn model(name: &str) -> Result<Profile, ModelError> {
    match name {
        "pawn" => paper::pawn(),
        "cup" => paper::cup(),
        "bottle" => paper::bottle(),
        "table" => paper::table(),
        "lightmill" => paper::lightmill(),
        "ring" => basic::ring(),
        "sphere" => basic::sphere(),
        "capsule" => basic::capsule(),
        "cylinder" => basic::cylinder(),
        "cone" => basic::cone(),
        _ => {
            if let Some(variant) = freeform::freeform(name) {
                return variant;
            }
            match name.strip_prefix(MORPH_PREFIX) {
                Some(t) => {
                    let t: f64 = t
                        .trim()
                        .parse()
                        .map_err(|_| ModelError::BadMorphName(name.to_string()))?;
                    if !t.is_finite() {
                        return Err(ModelError::BadMorphName(name.to_string()));
                    }
                    morph(t)
                }
                None => Err(ModelError::UnknownModel {
                    name: name.to_string(),
                    valid: model_names().join(", "),
                }),
            }
        }
    }
}

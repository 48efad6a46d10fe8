//! The scene file as written: serde types of the TOML format, read as given and checked
//! afterwards (`validate.rs`).

use serde::Deserialize;

/// A pose as written in a scene file.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseSpec {
    #[serde(default)]
    pub translation: Option<Vec<f64>>,
    /// Rotation axis (normalised when read) with `angle` in radians.
    #[serde(default)]
    pub axis: Option<Vec<f64>>,
    #[serde(default)]
    pub angle: Option<f64>,
    /// Unit quaternion `[w, x, y, z]` (a norm within 1e-3 of 1 is normalised; not with
    /// `axis`/`angle`).
    #[serde(default)]
    pub quaternion: Option<Vec<f64>>,
}

/// One keyframe of a kinematic body.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyframeSpec {
    pub time: f64,
    pub pose: PoseSpec,
}

/// A named smooth random motion about the body's pose.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomMotionSpec {
    pub seed: u64,
    /// Largest offset of the translation from the body's pose (length units).
    pub amplitude: f64,
    /// Largest rotation away from the body's orientation (radians).
    #[serde(default)]
    pub angle: f64,
    /// Slowest period of the motion (seconds).
    pub period: f64,
}

/// The deforming model M_t.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MorphSpec {
    /// Seconds per full morph: `t = (time / period) mod 1`.
    pub period: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodySpec {
    pub(super) name: String,
    #[serde(default)]
    pub(super) model: Option<String>,
    #[serde(default)]
    pub(super) profile: Option<String>,
    #[serde(default)]
    pub(super) morph: Option<MorphSpec>,
    pub(super) effect: String,
    #[serde(default)]
    pub(super) pose: PoseSpec,
    #[serde(default)]
    pub(super) keyframes: Option<Vec<KeyframeSpec>>,
    #[serde(default)]
    pub(super) interpolation: Option<String>,
    #[serde(default)]
    pub(super) random_motion: Option<RandomMotionSpec>,
    #[serde(default)]
    pub(super) torus: Option<TorusSpec>,
    #[serde(default)]
    pub(super) mass: Option<f64>,
    #[serde(default)]
    pub(super) density: Option<f64>,
    #[serde(default)]
    pub(super) velocity: Option<Vec<f64>>,
    #[serde(default)]
    pub(super) angular_velocity: Option<Vec<f64>>,
}

/// A thin torus: a circle of radius `minor` about `(rho, z) = (major, 0)`, revolved.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorusSpec {
    pub major: f64,
    pub minor: f64,
}

/// A generated mesh of interlocked rings (see the module docs).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RingMeshSpec {
    pub(super) name: String,
    pub(super) rows: usize,
    pub(super) cols: usize,
    pub(super) major: f64,
    pub(super) minor: f64,
    #[serde(default)]
    pub(super) spacing: Option<f64>,
    #[serde(default)]
    pub(super) center: Option<Vec<f64>>,
    #[serde(default)]
    pub(super) effect: Option<String>,
    #[serde(default)]
    pub(super) density: Option<f64>,
    #[serde(default)]
    pub(super) twist: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub(super) enum MeasureSpec {
    Keyword(String),
    Pairs(Vec<Vec<String>>),
}

#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub(super) enum ToleranceSpec {
    Keyword(String),
    Width(f64),
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SceneSpec {
    pub(super) duration: f64,
    pub(super) time_step: f64,
    pub(super) eps: f64,
    #[serde(default)]
    pub(super) tolerance: Option<ToleranceSpec>,
    #[serde(default)]
    pub(super) measure: Option<MeasureSpec>,
    #[serde(default)]
    pub(super) within: Option<f64>,
    #[serde(default)]
    pub(super) render: Option<RenderSpec>,
    #[serde(default)]
    pub(super) gravity: Option<Vec<f64>>,
    #[serde(default)]
    pub(super) substeps: Option<usize>,
    #[serde(default)]
    pub(super) contact_skin: Option<f64>,
    #[serde(default)]
    pub(super) friction: Option<f64>,
    #[serde(default)]
    pub(super) solver_iterations: Option<usize>,
    #[serde(default, rename = "body")]
    pub(super) bodies: Vec<BodySpec>,
    #[serde(default, rename = "ring_mesh")]
    pub(super) ring_meshes: Vec<RingMeshSpec>,
}

/// Rendered frames: every `every`-th frame as a PNG, seen from `eye` towards `target`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RenderSpec {
    #[serde(default)]
    pub(super) every: Option<usize>,
    #[serde(default)]
    pub(super) width: Option<usize>,
    #[serde(default)]
    pub(super) height: Option<usize>,
    pub(super) eye: Vec<f64>,
    pub(super) target: Vec<f64>,
    #[serde(default)]
    pub(super) fov: Option<f64>,
}

//! The TOML scene format (issue 14): bodies, their poses and effects, what to measure.
//!
//! ```toml
//! duration = 2.0          # seconds of scene time
//! time_step = 0.02        # seconds per frame (frames = duration / time_step + 1)
//! eps = 1e-3              # biarc tree bound of every body (length units)
//! tolerance = "trees"     # or a width in length units (see revdist::query::Tolerance)
//! measure = "all"         # or a list of pairs: [["cup", "pawn"], ["cup", "table"]]
//! within = 0.5            # optional: pairs whose bounding spheres are farther apart than
//!                         # this get the spheres' interval instead of a query
//!
//! [[body]]
//! name = "table"
//! model = "table"         # a built-in model (`revdist models`), or
//! # profile = "my.toml"   # a profile file, relative to the scene file, or
//! # morph = { period = 2.0 }  # the deforming model M_t, t = (time / period) mod 1
//! effect = "static"       # static | kinematic | deforming
//! pose = { translation = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0], angle = 0.0 }
//! # or pose = { translation = [...], quaternion = [w, x, y, z] }
//!
//! [[body]]
//! name = "pawn"
//! model = "pawn"
//! effect = "kinematic"
//! keyframes = [           # interpolated: translation piecewise cubic (Catmull-Rom,
//!   { time = 0.0, pose = { translation = [1, 0, 0] } },  # "smooth", the default) or
//!   { time = 2.0, pose = { translation = [0.5, 0, 0] } },  # linear; rotation slerp
//! ]
//! interpolation = "smooth"  # or "linear"
//! # or random_motion = { seed = 7, amplitude = 0.2, angle = 0.5, period = 2.0 }
//! ```
//!
//! Rendered frames are made only when asked for:
//!
//! ```toml
//! [render]
//! every = 5               # every 5th frame, as DIR/<scene>-frames/NNNNN.png
//! width = 640
//! height = 480
//! eye = [4.0, -4.0, 3.0]
//! target = [0.0, 0.0, 0.7]
//! fov = 0.7               # vertical field of view, radians
//! ```
//!
//! Every field is checked when the scene is loaded; an error names the field
//! (`body[2].keyframes[1].time: ...`) and the problem.

use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// A scene file that could not be used: the field and the problem.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file '{path}': {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("scene file '{path}': {message}")]
    Syntax { path: PathBuf, message: String },
    #[error("{field}: {problem}")]
    Field { field: String, problem: String },
}

fn field_error(field: impl Into<String>, problem: impl Into<String>) -> SceneError {
    SceneError::Field {
        field: field.into(),
        problem: problem.into(),
    }
}

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
    /// Unit quaternion `[w, x, y, z]` (normalised when read; not with `axis`/`angle`).
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
struct BodySpec {
    name: String,
    #[serde(default)]
    model: Option<String>,
    #[serde(default)]
    profile: Option<String>,
    #[serde(default)]
    morph: Option<MorphSpec>,
    effect: String,
    #[serde(default)]
    pose: PoseSpec,
    #[serde(default)]
    keyframes: Option<Vec<KeyframeSpec>>,
    #[serde(default)]
    interpolation: Option<String>,
    #[serde(default)]
    random_motion: Option<RandomMotionSpec>,
    #[serde(default)]
    torus: Option<TorusSpec>,
    #[serde(default)]
    mass: Option<f64>,
    #[serde(default)]
    density: Option<f64>,
    #[serde(default)]
    velocity: Option<Vec<f64>>,
    #[serde(default)]
    angular_velocity: Option<Vec<f64>>,
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
struct RingMeshSpec {
    name: String,
    rows: usize,
    cols: usize,
    major: f64,
    minor: f64,
    #[serde(default)]
    spacing: Option<f64>,
    #[serde(default)]
    center: Option<Vec<f64>>,
    #[serde(default)]
    effect: Option<String>,
    #[serde(default)]
    density: Option<f64>,
    #[serde(default)]
    twist: Option<f64>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
enum MeasureSpec {
    Keyword(String),
    Pairs(Vec<Vec<String>>),
}

#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
enum ToleranceSpec {
    Keyword(String),
    Width(f64),
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneSpec {
    duration: f64,
    time_step: f64,
    eps: f64,
    #[serde(default)]
    tolerance: Option<ToleranceSpec>,
    #[serde(default)]
    measure: Option<MeasureSpec>,
    #[serde(default)]
    within: Option<f64>,
    #[serde(default)]
    render: Option<RenderSpec>,
    #[serde(default)]
    gravity: Option<Vec<f64>>,
    #[serde(default)]
    substeps: Option<usize>,
    #[serde(default)]
    contact_skin: Option<f64>,
    #[serde(default)]
    friction: Option<f64>,
    #[serde(default)]
    solver_iterations: Option<usize>,
    #[serde(default, rename = "body")]
    bodies: Vec<BodySpec>,
    #[serde(default, rename = "ring_mesh")]
    ring_meshes: Vec<RingMeshSpec>,
}

/// Rendered frames: every `every`-th frame as a PNG, seen from `eye` towards `target`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RenderSpec {
    #[serde(default)]
    every: Option<usize>,
    #[serde(default)]
    width: Option<usize>,
    #[serde(default)]
    height: Option<usize>,
    eye: Vec<f64>,
    target: Vec<f64>,
    #[serde(default)]
    fov: Option<f64>,
}

/// Checked render settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Render {
    pub every: usize,
    pub width: usize,
    pub height: usize,
    pub eye: nalgebra::Point3<f64>,
    pub target: nalgebra::Point3<f64>,
    /// Vertical field of view (radians).
    pub fov: f64,
}

/// Where a body's shape comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Model(String),
    ProfileFile(PathBuf),
    Morph {
        period: f64,
    },
    /// A circle of radius `minor` about `(major, 0)` revolved about the z axis.
    Torus {
        major: f64,
        minor: f64,
    },
}

/// How a body's pose changes.
#[derive(Debug, Clone, PartialEq)]
pub enum Track {
    Keyframes {
        times: Vec<f64>,
        poses: Vec<Isometry3<f64>>,
        smooth: bool,
    },
    Random {
        seed: u64,
        amplitude: f64,
        angle: f64,
        period: f64,
    },
}

/// The effect a body takes part in.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    Static,
    Kinematic(Track),
    Deforming,
    /// A rigid body under gravity with contacts ([`crate::dynamics`]).
    Dynamic(DynamicBody),
}

/// How a dynamic body's mass is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MassSpec {
    /// Total mass; the density is uniform.
    Mass(f64),
    /// Uniform density (mass per unit volume).
    Density(f64),
}

/// A dynamic body's mass and initial velocities (world frame, velocity of the centre of
/// mass; angular velocity in radians per second).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicBody {
    pub mass: MassSpec,
    pub velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
}

/// Scene-level settings of the dynamics (used only when some body is dynamic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsSettings {
    /// Gravitational acceleration (length units per second squared).
    pub gravity: Vector3<f64>,
    /// Solver steps per frame.
    pub substeps: usize,
    /// Gap the contacts aim for; `None`: 8 times the query width.
    pub contact_skin: Option<f64>,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// Sequential-impulse sweeps per step.
    pub solver_iterations: usize,
}

impl Default for DynamicsSettings {
    fn default() -> Self {
        DynamicsSettings {
            gravity: Vector3::new(0.0, 0.0, -9.81),
            substeps: 10,
            contact_skin: None,
            friction: 0.5,
            solver_iterations: 10,
        }
    }
}

/// A checked body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    pub name: String,
    pub shape: Shape,
    pub effect: Effect,
    pub pose: Isometry3<f64>,
}

/// Which pairs a scene measures.
#[derive(Debug, Clone, PartialEq)]
pub enum Measure {
    All,
    Pairs(Vec<(usize, usize)>),
}

/// A checked scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub duration: f64,
    pub time_step: f64,
    pub eps: f64,
    /// `None`: the trees' accuracy; `Some(w)`: an absolute interval width.
    pub tolerance: Option<f64>,
    pub measure: Measure,
    pub within: Option<f64>,
    /// Rendered frames, when the scene asks for them.
    pub render: Option<Render>,
    /// Settings of the dynamics (defaults when the file gives none).
    pub dynamics: DynamicsSettings,
    pub bodies: Vec<Body>,
    /// Pairs of bodies that a generator built interlocked (ring meshes); their linking is
    /// checked at the start and the end of a run.
    pub links: Vec<(usize, usize)>,
}

impl Scene {
    /// Reads and checks a scene file; profile paths are resolved against its directory.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        Scene::parse(&text, base).map_err(|e| match e {
            SceneError::Syntax { message, .. } => SceneError::Syntax {
                path: path.to_path_buf(),
                message,
            },
            e => e,
        })
    }

    /// Parses and checks scene text; relative profile paths are resolved against `base`.
    pub fn parse(text: &str, base: &Path) -> Result<Scene, SceneError> {
        let spec: SceneSpec = toml::from_str(text).map_err(|e| SceneError::Syntax {
            path: PathBuf::from("<scene>"),
            message: e.to_string(),
        })?;
        check_scene(spec, base)
    }

    /// Number of frames: times `0, dt, 2 dt, ...` up to the duration.
    pub fn frames(&self) -> usize {
        (self.duration / self.time_step + 1e-9).floor() as usize + 1
    }

    /// Whether some body is dynamic (then the runner steps the dynamics).
    pub fn has_dynamics(&self) -> bool {
        self.bodies
            .iter()
            .any(|b| matches!(b.effect, Effect::Dynamic(_)))
    }

    /// The index of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The measured pairs, as body indices with the first below the second.
    pub fn measured_pairs(&self) -> Vec<(usize, usize)> {
        match &self.measure {
            Measure::All => (0..self.bodies.len())
                .flat_map(|i| (i + 1..self.bodies.len()).map(move |j| (i, j)))
                .collect(),
            Measure::Pairs(p) => p.clone(),
        }
    }
}

fn positive(field: &str, v: f64) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(field_error(
            field,
            format!("must be a positive number, got {v}"),
        ))
    }
}

fn vec3(field: &str, v: &[f64]) -> Result<Vector3<f64>, SceneError> {
    if v.len() != 3 {
        return Err(field_error(
            field,
            format!("expected 3 numbers, got {}", v.len()),
        ));
    }
    if !v.iter().all(|x| x.is_finite()) {
        return Err(field_error(field, "numbers must be finite"));
    }
    Ok(Vector3::new(v[0], v[1], v[2]))
}

/// A pose from its spec; `field` names it in errors.
pub fn pose_of(field: &str, p: &PoseSpec) -> Result<Isometry3<f64>, SceneError> {
    let t = match &p.translation {
        Some(v) => vec3(&format!("{field}.translation"), v)?,
        None => Vector3::zeros(),
    };
    let r = match (&p.quaternion, &p.axis, p.angle) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            return Err(field_error(
                field,
                "give either quaternion or axis and angle, not both",
            ))
        }
        (Some(q), None, None) => {
            if q.len() != 4 {
                return Err(field_error(
                    format!("{field}.quaternion"),
                    format!("expected 4 numbers [w, x, y, z], got {}", q.len()),
                ));
            }
            let quat = Quaternion::new(q[0], q[1], q[2], q[3]);
            let n = quat.norm();
            if !(n.is_finite() && n > 0.0) {
                return Err(field_error(
                    format!("{field}.quaternion"),
                    "must be finite and non-zero",
                ));
            }
            UnitQuaternion::from_quaternion(quat)
        }
        (None, Some(axis), angle) => {
            let a = vec3(&format!("{field}.axis"), axis)?;
            let angle = angle.unwrap_or(0.0);
            if !angle.is_finite() {
                return Err(field_error(format!("{field}.angle"), "must be finite"));
            }
            if a.norm() == 0.0 {
                return Err(field_error(format!("{field}.axis"), "must not be zero"));
            }
            UnitQuaternion::from_axis_angle(&Unit::new_normalize(a), angle)
        }
        (None, None, Some(_)) => {
            return Err(field_error(format!("{field}.angle"), "needs an axis"));
        }
        (None, None, None) => UnitQuaternion::identity(),
    };
    Ok(Isometry3::from_parts(Translation3::from(t), r))
}

fn check_body(i: usize, b: &BodySpec, base: &Path) -> Result<Body, SceneError> {
    let f = format!("body[{i}]");
    if b.name.trim().is_empty() {
        return Err(field_error(format!("{f}.name"), "must not be empty"));
    }
    let f = format!("body[{i}] ('{}')", b.name);
    let shape = match (&b.model, &b.profile, &b.morph, &b.torus) {
        (Some(m), None, None, None) => {
            revdist::models::model(m)
                .map_err(|e| field_error(format!("{f}.model"), e.to_string()))?;
            Shape::Model(m.clone())
        }
        (None, Some(p), None, None) => {
            let path = base.join(p);
            if !path.is_file() {
                return Err(field_error(
                    format!("{f}.profile"),
                    format!("no profile file '{}'", path.display()),
                ));
            }
            Shape::ProfileFile(path)
        }
        (None, None, Some(m), None) => Shape::Morph {
            period: positive(&format!("{f}.morph.period"), m.period)?,
        },
        (None, None, None, Some(t)) => torus_shape(&format!("{f}.torus"), t.major, t.minor)?,
        _ => {
            return Err(field_error(
                f,
                "give exactly one of model, profile, morph or torus",
            ))
        }
    };
    let pose = pose_of(&format!("{f}.pose"), &b.pose)?;
    let has_track = b.keyframes.is_some() || b.random_motion.is_some();
    let effect = match b.effect.as_str() {
        "static" | "deforming" if has_track => {
            return Err(field_error(
                format!("{f}.effect"),
                format!(
                    "'{}' bodies do not move: remove keyframes/random_motion or use 'kinematic'",
                    b.effect
                ),
            ))
        }
        "static" => {
            if matches!(shape, Shape::Morph { .. }) {
                return Err(field_error(
                    format!("{f}.effect"),
                    "a morph body deforms: use effect = 'deforming'",
                ));
            }
            Effect::Static
        }
        "deforming" => {
            if !matches!(shape, Shape::Morph { .. }) {
                return Err(field_error(
                    format!("{f}.effect"),
                    "only a morph body can deform (give morph = { period = ... })",
                ));
            }
            Effect::Deforming
        }
        "kinematic" => {
            if matches!(shape, Shape::Morph { .. }) {
                return Err(field_error(
                    format!("{f}.effect"),
                    "a morph body is 'deforming' (moving and deforming at once is not supported)",
                ));
            }
            Effect::Kinematic(check_track(&f, b, &pose)?)
        }
        "dynamic" => {
            if has_track {
                return Err(field_error(
                    format!("{f}.effect"),
                    "a dynamic body moves under gravity and contacts: remove keyframes/random_motion",
                ));
            }
            if matches!(shape, Shape::Morph { .. }) {
                return Err(field_error(
                    format!("{f}.effect"),
                    "a dynamic body must be rigid: a morph body can only be 'deforming'",
                ));
            }
            Effect::Dynamic(check_dynamic(&f, b)?)
        }
        other => {
            return Err(field_error(
                format!("{f}.effect"),
                format!("unknown effect '{other}' (static, kinematic, deforming or dynamic)"),
            ))
        }
    };
    if !matches!(effect, Effect::Dynamic(_)) {
        for (name, given) in [
            ("mass", b.mass.is_some()),
            ("density", b.density.is_some()),
            ("velocity", b.velocity.is_some()),
            ("angular_velocity", b.angular_velocity.is_some()),
        ] {
            if given {
                return Err(field_error(
                    format!("{f}.{name}"),
                    format!("only dynamic bodies take {name} (effect is '{}')", b.effect),
                ));
            }
        }
    }
    Ok(Body {
        name: b.name.clone(),
        shape,
        effect,
        pose,
    })
}

/// A pair of bodies built interlocked (body indices).
pub type Link = (usize, usize);

fn torus_shape(field: &str, major: f64, minor: f64) -> Result<Shape, SceneError> {
    let major = positive(&format!("{field}.major"), major)?;
    let minor = positive(&format!("{field}.minor"), minor)?;
    if minor >= major {
        return Err(field_error(
            format!("{field}.minor"),
            format!("must be below major ({major}) so that the torus has a hole, got {minor}"),
        ));
    }
    Ok(Shape::Torus { major, minor })
}

fn check_dynamic(f: &str, b: &BodySpec) -> Result<DynamicBody, SceneError> {
    let mass = match (b.mass, b.density) {
        (Some(_), Some(_)) => {
            return Err(field_error(
                format!("{f}.mass"),
                "give mass or density, not both",
            ))
        }
        (Some(m), None) => MassSpec::Mass(positive(&format!("{f}.mass"), m)?),
        (None, Some(d)) => MassSpec::Density(positive(&format!("{f}.density"), d)?),
        (None, None) => MassSpec::Density(1.0),
    };
    let velocity = match &b.velocity {
        Some(v) => vec3(&format!("{f}.velocity"), v)?,
        None => Vector3::zeros(),
    };
    let angular_velocity = match &b.angular_velocity {
        Some(v) => vec3(&format!("{f}.angular_velocity"), v)?,
        None => Vector3::zeros(),
    };
    Ok(DynamicBody {
        mass,
        velocity,
        angular_velocity,
    })
}

/// The bodies of a ring mesh: a `rows` x `cols` grid of horizontal rings (axis z) with centre
/// spacing `spacing`, and one vertical link ring between each pair of grid neighbours, centred
/// between them in the vertical plane through their centres, so that it passes through both
/// holes. Returns the bodies and the interlocked pairs (link, ring).
fn ring_mesh_bodies(
    k: usize,
    m: &RingMeshSpec,
    first_index: usize,
) -> Result<(Vec<Body>, Vec<Link>), SceneError> {
    let f = format!("ring_mesh[{k}] ('{}')", m.name);
    if m.name.trim().is_empty() {
        return Err(field_error(
            format!("ring_mesh[{k}].name"),
            "must not be empty",
        ));
    }
    if m.rows == 0 || m.cols == 0 || m.rows * m.cols > 400 {
        return Err(field_error(
            format!("{f}.rows"),
            format!(
                "rows and cols must be 1..400 rings in all, got {} x {}",
                m.rows, m.cols
            ),
        ));
    }
    let shape = torus_shape(&f, m.major, m.minor)?;
    let (major, minor) = (m.major, m.minor);
    // A link centred between two ring centres at distance D crosses each ring's plane at
    // o = D / 2 - major from that ring's centre. Its tube must clear the hole's rim:
    // o < major - 2 minor. Two links through the same ring cross at o along perpendicular
    // (or opposite) directions, o sqrt(2) apart at least, so o > sqrt(2) minor keeps their
    // tubes apart there (and the rings, 2 o apart, do not touch). Default o = 2 minor.
    let spacing = m.spacing.unwrap_or(2.0 * major + 4.0 * minor);
    let lo = 2.0 * major + 2.0 * std::f64::consts::SQRT_2 * minor;
    let hi = 2.0 * major + 2.0 * (major - 2.0 * minor);
    if !(spacing.is_finite() && spacing > lo && spacing < hi) {
        return Err(field_error(
            format!("{f}.spacing"),
            format!(
                "must lie in ({lo}, {hi}) so that neighbours do not touch and links pass through both holes, got {spacing}"
            ),
        ));
    }
    let centre = match &m.center {
        Some(c) => vec3(&format!("{f}.center"), c)?,
        None => Vector3::zeros(),
    };
    let twist = m.twist.unwrap_or(0.0);
    if !twist.is_finite() {
        return Err(field_error(format!("{f}.twist"), "must be finite"));
    }
    let effect_name = m.effect.clone().unwrap_or_else(|| "dynamic".into());
    let dynamic = match effect_name.as_str() {
        "dynamic" => true,
        "static" => false,
        o => {
            return Err(field_error(
                format!("{f}.effect"),
                format!("unknown effect '{o}' for a ring mesh (dynamic or static)"),
            ))
        }
    };
    if m.density.is_some() && !dynamic {
        return Err(field_error(
            format!("{f}.density"),
            "only dynamic bodies take density",
        ));
    }
    let effect = if dynamic {
        Effect::Dynamic(DynamicBody {
            mass: MassSpec::Density(match m.density {
                Some(d) => positive(&format!("{f}.density"), d)?,
                None => 1.0,
            }),
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        })
    } else {
        Effect::Static
    };
    // The whole mesh is turned by `twist` about the vertical through `center`.
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), twist);
    let x0 = -0.5 * spacing * (m.cols - 1) as f64;
    let y0 = -0.5 * spacing * (m.rows - 1) as f64;
    let at = |x: f64, y: f64| centre + turn * Vector3::new(x0 + x, y0 + y, 0.0);
    let mut bodies = Vec::new();
    let mut links = Vec::new();
    let ring_index = |r: usize, c: usize| first_index + r * m.cols + c;
    for r in 0..m.rows {
        for c in 0..m.cols {
            let p = at(c as f64 * spacing, r as f64 * spacing);
            bodies.push(Body {
                name: format!("{}_r{r}c{c}", m.name),
                shape: shape.clone(),
                effect: effect.clone(),
                pose: Isometry3::from_parts(Translation3::from(p), turn),
            });
        }
    }
    // Links along x (between (r, c) and (r, c + 1)), then along y. A link's axis is
    // horizontal and perpendicular to the line between the two centres.
    let mut add_link =
        |bodies: &mut Vec<Body>, a: usize, b: usize, p: Vector3<f64>, along_x: bool| {
            let to_vertical = if along_x {
                // local z -> world y: the link lies in the xz plane.
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
            } else {
                // local z -> world x: the link lies in the yz plane.
                UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2)
            };
            let index = first_index + bodies.len();
            bodies.push(Body {
                name: format!("{}_link_{}_{}", m.name, a - first_index, b - first_index),
                shape: shape.clone(),
                effect: effect.clone(),
                pose: Isometry3::from_parts(Translation3::from(p), turn * to_vertical),
            });
            links.push((index, a));
            links.push((index, b));
        };
    for r in 0..m.rows {
        for c in 0..m.cols {
            if c + 1 < m.cols {
                let p = at((c as f64 + 0.5) * spacing, r as f64 * spacing);
                add_link(&mut bodies, ring_index(r, c), ring_index(r, c + 1), p, true);
            }
            if r + 1 < m.rows {
                let p = at(c as f64 * spacing, (r as f64 + 0.5) * spacing);
                add_link(
                    &mut bodies,
                    ring_index(r, c),
                    ring_index(r + 1, c),
                    p,
                    false,
                );
            }
        }
    }
    Ok((bodies, links))
}

fn check_track(f: &str, b: &BodySpec, pose: &Isometry3<f64>) -> Result<Track, SceneError> {
    match (&b.keyframes, &b.random_motion) {
        (Some(keys), None) => {
            if keys.len() < 2 {
                return Err(field_error(
                    format!("{f}.keyframes"),
                    format!("need at least 2 keyframes, got {}", keys.len()),
                ));
            }
            let mut times = Vec::with_capacity(keys.len());
            let mut poses = Vec::with_capacity(keys.len());
            for (k, key) in keys.iter().enumerate() {
                let kf = format!("{f}.keyframes[{k}]");
                if !key.time.is_finite() || key.time < 0.0 {
                    return Err(field_error(
                        format!("{kf}.time"),
                        format!("must be a finite time >= 0, got {}", key.time),
                    ));
                }
                if times.last().is_some_and(|&t: &f64| key.time <= t) {
                    return Err(field_error(
                        format!("{kf}.time"),
                        "keyframe times must increase",
                    ));
                }
                times.push(key.time);
                poses.push(pose_of(&format!("{kf}.pose"), &key.pose)?);
            }
            let smooth = match b.interpolation.as_deref() {
                None | Some("smooth") => true,
                Some("linear") => false,
                Some(o) => {
                    return Err(field_error(
                        format!("{f}.interpolation"),
                        format!("unknown interpolation '{o}' (smooth or linear)"),
                    ))
                }
            };
            Ok(Track::Keyframes {
                times,
                poses,
                smooth,
            })
        }
        (None, Some(m)) => {
            if b.interpolation.is_some() {
                return Err(field_error(
                    format!("{f}.interpolation"),
                    "only keyframes are interpolated",
                ));
            }
            let rf = format!("{f}.random_motion");
            let amplitude = m.amplitude;
            if !(amplitude.is_finite() && amplitude >= 0.0) {
                return Err(field_error(
                    format!("{rf}.amplitude"),
                    "must be finite and >= 0",
                ));
            }
            if !(m.angle.is_finite() && m.angle >= 0.0) {
                return Err(field_error(
                    format!("{rf}.angle"),
                    "must be finite and >= 0",
                ));
            }
            let _ = pose;
            Ok(Track::Random {
                seed: m.seed,
                amplitude,
                angle: m.angle,
                period: positive(&format!("{rf}.period"), m.period)?,
            })
        }
        (Some(_), Some(_)) => Err(field_error(f, "give keyframes or random_motion, not both")),
        (None, None) => Err(field_error(
            f,
            "a kinematic body needs keyframes or random_motion",
        )),
    }
}

fn check_scene(spec: SceneSpec, base: &Path) -> Result<Scene, SceneError> {
    let duration = spec.duration;
    if !(duration.is_finite() && duration >= 0.0) {
        return Err(field_error(
            "duration",
            format!("must be finite and >= 0, got {duration}"),
        ));
    }
    let time_step = positive("time_step", spec.time_step)?;
    if duration / time_step > 1e7 {
        return Err(field_error("time_step", "more than 10 million frames"));
    }
    let eps = positive("eps", spec.eps)?;
    if eps > 0.1 {
        return Err(field_error("eps", format!("{eps} is coarser than 0.1")));
    }
    let tolerance = match spec.tolerance {
        None => None,
        Some(ToleranceSpec::Keyword(k)) if k == "trees" => None,
        Some(ToleranceSpec::Keyword(k)) => {
            return Err(field_error(
                "tolerance",
                format!("unknown tolerance '{k}' (\"trees\" or a width)"),
            ))
        }
        Some(ToleranceSpec::Width(w)) if w.is_finite() && w >= 0.0 => Some(w),
        Some(ToleranceSpec::Width(w)) => {
            return Err(field_error("tolerance", format!("must be >= 0, got {w}")))
        }
    };
    let within = match spec.within {
        None => None,
        Some(w) => Some(positive("within", w)?),
    };
    if spec.bodies.is_empty() && spec.ring_meshes.is_empty() {
        return Err(field_error(
            "body",
            "a scene needs at least one body (missing field `body`)",
        ));
    }
    let mut bodies: Vec<Body> = Vec::with_capacity(spec.bodies.len());
    for (i, b) in spec.bodies.iter().enumerate() {
        let body = check_body(i, b, base)?;
        if bodies.iter().any(|o| o.name == body.name) {
            return Err(field_error(
                format!("body[{i}].name"),
                format!("'{}' is used twice", body.name),
            ));
        }
        bodies.push(body);
    }
    let mut links = Vec::new();
    for (k, m) in spec.ring_meshes.iter().enumerate() {
        let (generated, l) = ring_mesh_bodies(k, m, bodies.len())?;
        for body in generated {
            if bodies.iter().any(|o| o.name == body.name) {
                return Err(field_error(
                    format!("ring_mesh[{k}].name"),
                    format!("body name '{}' is used twice", body.name),
                ));
            }
            bodies.push(body);
        }
        links.extend(l);
    }
    let dynamics = check_dynamics(
        &spec.gravity,
        spec.substeps,
        spec.contact_skin,
        spec.friction,
        spec.solver_iterations,
        &bodies,
    )?;
    let measure = match spec.measure {
        None => Measure::All,
        Some(MeasureSpec::Keyword(k)) if k == "all" => Measure::All,
        Some(MeasureSpec::Keyword(k)) => {
            return Err(field_error(
                "measure",
                format!("unknown keyword '{k}' (\"all\" or a list of pairs)"),
            ))
        }
        Some(MeasureSpec::Pairs(pairs)) => {
            let mut out = Vec::new();
            for (k, p) in pairs.iter().enumerate() {
                let field = format!("measure[{k}]");
                if p.len() != 2 {
                    return Err(field_error(
                        field,
                        format!("expected 2 body names, got {}", p.len()),
                    ));
                }
                let idx = |name: &str| {
                    bodies
                        .iter()
                        .position(|b| b.name == name)
                        .ok_or_else(|| field_error(&field, format!("no body called '{name}'")))
                };
                let (i, j) = (idx(&p[0])?, idx(&p[1])?);
                if i == j {
                    return Err(field_error(
                        field,
                        "a body cannot be measured against itself",
                    ));
                }
                let pair = (i.min(j), i.max(j));
                if out.contains(&pair) {
                    return Err(field_error(field, "pair listed twice"));
                }
                out.push(pair);
            }
            Measure::Pairs(out)
        }
    };
    let render = match spec.render {
        None => None,
        Some(r) => {
            let eye = vec3("render.eye", &r.eye)?;
            let target = vec3("render.target", &r.target)?;
            if (eye - target).norm() == 0.0 {
                return Err(field_error("render.target", "must differ from render.eye"));
            }
            let size = |field: &str, v: Option<usize>, default: usize| match v.unwrap_or(default) {
                n @ 16..=4096 => Ok(n),
                n => Err(field_error(
                    field,
                    format!("must be 16..4096 pixels, got {n}"),
                )),
            };
            let fov = r.fov.unwrap_or(0.7);
            if !(fov > 0.0 && fov < 3.0) {
                return Err(field_error(
                    "render.fov",
                    format!("must be in (0, 3) radians, got {fov}"),
                ));
            }
            Some(Render {
                every: match r.every.unwrap_or(1) {
                    0 => return Err(field_error("render.every", "must be at least 1")),
                    n => n,
                },
                width: size("render.width", r.width, 640)?,
                height: size("render.height", r.height, 480)?,
                eye: nalgebra::Point3::from(eye),
                target: nalgebra::Point3::from(target),
                fov,
            })
        }
    };
    Ok(Scene {
        duration,
        time_step,
        eps,
        tolerance,
        measure,
        within,
        render,
        dynamics,
        bodies,
        links,
    })
}

fn check_dynamics(
    gravity: &Option<Vec<f64>>,
    substeps: Option<usize>,
    contact_skin: Option<f64>,
    friction: Option<f64>,
    solver_iterations: Option<usize>,
    bodies: &[Body],
) -> Result<DynamicsSettings, SceneError> {
    let d = DynamicsSettings::default();
    let gravity = match gravity {
        Some(g) => vec3("gravity", g)?,
        None => d.gravity,
    };
    let substeps = match substeps {
        None => d.substeps,
        Some(n @ 1..=10_000) => n,
        Some(n) => {
            return Err(field_error(
                "substeps",
                format!("must be 1..10000 steps per frame, got {n}"),
            ))
        }
    };
    let contact_skin = match contact_skin {
        None => None,
        Some(s) => Some(positive("contact_skin", s)?),
    };
    let friction = match friction {
        None => d.friction,
        Some(mu) if mu.is_finite() && mu >= 0.0 => mu,
        Some(mu) => {
            return Err(field_error(
                "friction",
                format!("must be finite and >= 0, got {mu}"),
            ))
        }
    };
    let solver_iterations = match solver_iterations {
        None => d.solver_iterations,
        Some(n @ 1..=1000) => n,
        Some(n) => {
            return Err(field_error(
                "solver_iterations",
                format!("must be 1..1000, got {n}"),
            ))
        }
    };
    if bodies
        .iter()
        .any(|b| matches!(b.effect, Effect::Dynamic(_)))
    {
        // Contacts are only with bodies whose motion the solver bounds (static: none).
        for (i, b) in bodies.iter().enumerate() {
            if matches!(b.effect, Effect::Kinematic(_) | Effect::Deforming) {
                return Err(field_error(
                    format!("body[{i}] ('{}').effect", b.name),
                    "a scene with dynamic bodies can only have static and dynamic bodies \
                     (contacts with kinematic or deforming bodies are not supported)",
                ));
            }
        }
    }
    Ok(DynamicsSettings {
        gravity,
        substeps,
        contact_skin,
        friction,
        solver_iterations,
    })
}

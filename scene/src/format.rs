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
    #[serde(rename = "body")]
    bodies: Vec<BodySpec>,
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
    Morph { period: f64 },
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
    pub bodies: Vec<Body>,
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
    let shape = match (&b.model, &b.profile, &b.morph) {
        (Some(m), None, None) => {
            revdist::models::model(m)
                .map_err(|e| field_error(format!("{f}.model"), e.to_string()))?;
            Shape::Model(m.clone())
        }
        (None, Some(p), None) => {
            let path = base.join(p);
            if !path.is_file() {
                return Err(field_error(
                    format!("{f}.profile"),
                    format!("no profile file '{}'", path.display()),
                ));
            }
            Shape::ProfileFile(path)
        }
        (None, None, Some(m)) => Shape::Morph {
            period: positive(&format!("{f}.morph.period"), m.period)?,
        },
        _ => {
            return Err(field_error(
                f,
                "give exactly one of model, profile or morph",
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
            return Err(field_error(
                format!("{f}.effect"),
                "'dynamic' (rigid bodies under gravity) is not available in this build",
            ))
        }
        other => {
            return Err(field_error(
                format!("{f}.effect"),
                format!("unknown effect '{other}' (static, kinematic or deforming)"),
            ))
        }
    };
    Ok(Body {
        name: b.name.clone(),
        shape,
        effect,
        pose,
    })
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
    if spec.bodies.is_empty() {
        return Err(field_error("body", "a scene needs at least one body"));
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
        bodies,
    })
}

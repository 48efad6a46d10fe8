//! Checks of one `[[body]]` table: its shape, effect, track (keyframes or random motion) and
//! dynamic properties.

use super::error::{field_error, SceneError};
use super::model::{Body, DynamicBody, Effect, MassSpec, Shape, Track};
use super::spec::BodySpec;
use super::values::{pose_of, positive, positive_length, vec3};
use nalgebra::Vector3;
use revdist::limits::check_length;
use std::path::Path;

pub(super) fn check_body(i: usize, b: &BodySpec, base: &Path) -> Result<Body, SceneError> {
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
            Effect::Kinematic(check_track(&f, b)?)
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

pub(super) fn torus_shape(field: &str, major: f64, minor: f64) -> Result<Shape, SceneError> {
    let major = positive_length(&format!("{field}.major"), major)?;
    let minor = positive_length(&format!("{field}.minor"), minor)?;
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

fn check_track(f: &str, b: &BodySpec) -> Result<Track, SceneError> {
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
            let amplitude = check_length(&format!("{rf}.amplitude"), m.amplitude)?;
            if !(m.angle.is_finite() && m.angle >= 0.0) {
                return Err(field_error(
                    format!("{rf}.angle"),
                    "must be finite and >= 0",
                ));
            }
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

//! Checks of a whole scene: timing, eps and tolerance, the bodies (`validate_body.rs`) and
//! generated ones (`generators.rs`), measured pairs, rendering and dynamics settings.

use super::error::{field_error, SceneError};
use super::generators::ring_mesh_bodies;
use super::model::{Body, DynamicsSettings, Effect, Measure, Render, Scene};
use super::reach::check_reach;
use super::shape::shape_profile;
use super::spec::{MeasureSpec, SceneSpec, ToleranceSpec};
use super::validate_body::check_body;
use super::values::{count_in, positive, positive_length, translation, vec3};
use revdist::limits::{check_magnitude, MAX_EPS_REL, MAX_TRANSLATION};
use std::path::Path;

pub(super) fn check_scene(spec: SceneSpec, base: &Path) -> Result<Scene, SceneError> {
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
    let tolerance = match spec.tolerance {
        None => None,
        Some(ToleranceSpec::Keyword(k)) if k == "trees" => None,
        Some(ToleranceSpec::Keyword(k)) => {
            return Err(field_error(
                "tolerance",
                format!("unknown tolerance '{k}' (\"trees\" or a width)"),
            ))
        }
        Some(ToleranceSpec::Width(w)) if w.is_finite() && w >= 0.0 => {
            Some(check_magnitude("tolerance", w, MAX_TRANSLATION)?)
        }
        Some(ToleranceSpec::Width(w)) => {
            return Err(field_error("tolerance", format!("must be >= 0, got {w}")))
        }
    };
    let within = match spec.within {
        None => None,
        Some(w) => Some(positive_length("within", w)?),
    };
    if spec.bodies.is_empty() && spec.ring_meshes.is_empty() {
        return Err(field_error(
            "body",
            "a scene needs at least one body (missing field `body`)",
        ));
    }
    let mut bodies: Vec<Body> = Vec::with_capacity(spec.bodies.len());
    // Where each body was declared, for errors about its motion.
    let mut origins: Vec<String> = Vec::with_capacity(spec.bodies.len());
    for (i, b) in spec.bodies.iter().enumerate() {
        let body = check_body(i, b, base)?;
        if bodies.iter().any(|o| o.name == body.name) {
            return Err(field_error(
                format!("body[{i}].name"),
                format!("'{}' is used twice", body.name),
            ));
        }
        bodies.push(body);
        origins.push(format!("body[{i}] ('{}')", b.name));
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
            origins.push(format!("ring_mesh[{k}] ('{}')", m.name));
        }
        links.extend(l);
    }
    check_eps_against_sizes(eps, &bodies)?;
    let dynamics = check_dynamics(
        &spec.gravity,
        spec.substeps,
        spec.contact_skin,
        spec.friction,
        spec.solver_iterations,
        &bodies,
    )?;
    check_reach(&bodies, &origins, duration, &dynamics)?;
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
            let eye = translation("render.eye", &r.eye)?;
            let target = translation("render.target", &r.target)?;
            if (eye - target).norm() == 0.0 {
                return Err(field_error("render.target", "must differ from render.eye"));
            }
            let size = |field: &str, v: Option<usize>, default: usize| {
                count_in(field, v, default, 16..=4096, " pixels")
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
    let substeps = count_in(
        "substeps",
        substeps,
        d.substeps,
        1..=10_000,
        " steps per frame",
    )?;
    let contact_skin = match contact_skin {
        None => None,
        Some(s) => Some(positive_length("contact_skin", s)?),
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
    let solver_iterations = count_in(
        "solver_iterations",
        solver_iterations,
        d.solver_iterations,
        1..=1000,
        "",
    )?;
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

/// The scene's eps is at most [`MAX_EPS_REL`] of the largest body's size (its profile's
/// bounding-box diagonal; M_t's at time 0). Each body's own range (`MIN_EPS_REL` to
/// `MAX_EPS_REL` of its size) is enforced by the core's tree build when the runner builds it.
fn check_eps_against_sizes(eps: f64, bodies: &[Body]) -> Result<(), SceneError> {
    let largest = bodies
        .iter()
        .filter_map(|b| shape_profile(b, 0.0).ok())
        .map(|p| p.bounding_box().diagonal())
        .reduce(f64::max);
    match largest {
        Some(size) if eps > MAX_EPS_REL * size => Err(field_error(
            "eps",
            format!("{eps} is coarser than {MAX_EPS_REL} of the largest body's size ({size:e})"),
        )),
        _ => Ok(()),
    }
}

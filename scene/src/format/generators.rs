//! Bodies generated from one table: the `[[ring_mesh]]` of interlocked rings.

use super::error::{field_error, SceneError};
use super::model::{Body, DynamicBody, Effect, Link, MassSpec};
use super::spec::RingMeshSpec;
use super::validate_body::torus_shape;
use super::values::{positive, translation};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// The bodies of a ring mesh: a `rows` x `cols` grid of horizontal rings (axis z) with centre
/// spacing `spacing`, and one vertical link ring between each pair of grid neighbours, centred
/// between them in the vertical plane through their centres, so that it passes through both
/// holes. Returns the bodies and the interlocked pairs (link, ring).
pub(super) fn ring_mesh_bodies(
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
        Some(c) => translation(&format!("{f}.center"), c)?,
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

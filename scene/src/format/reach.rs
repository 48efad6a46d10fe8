//! How far a body's motion can carry it: an upper bound on the length of its translation over
//! the whole run, held to [`MAX_TRANSLATION`] before anything runs (the poses themselves are
//! checked where they are read), so that no frame meets a pose `revdist distance` would refuse.

use super::error::{field_error, SceneError};
use super::model::{Body, DynamicsSettings, Effect, Track};
use revdist::limits::MAX_TRANSLATION;

/// Bound on a smooth keyframe track's translation over its largest keyframe translation `P`:
/// the cubic Hermite basis adds at most 4/27 of each end tangent, and each tangent (a
/// difference of keyframes over at least the segment's duration) is at most `2 P`.
const SMOOTH_OVERSHOOT: f64 = 1.0 + 16.0 / 27.0;

/// An upper bound on a body's distance from the origin during a run of `duration` seconds,
/// the field (after the body's) that sets it and how it is bounded; `None` when the body stays
/// within its checked poses (static, deforming, linear keyframes).
fn reach(
    body: &Body,
    duration: f64,
    dynamics: &DynamicsSettings,
) -> Option<(f64, &'static str, &'static str)> {
    let base = body.pose.translation.vector.norm();
    match &body.effect {
        Effect::Static | Effect::Deforming => None,
        Effect::Kinematic(Track::Keyframes { poses, smooth, .. }) => {
            let largest = poses
                .iter()
                .map(|p| p.translation.vector.norm())
                .fold(0.0, f64::max);
            smooth.then_some((
                largest * SMOOTH_OVERSHOOT,
                ".keyframes",
                "smooth interpolation can overshoot the largest keyframe translation by 16/27 of it",
            ))
        }
        Effect::Kinematic(Track::Random { amplitude, .. }) => Some((
            base + 3f64.sqrt() * amplitude,
            ".random_motion.amplitude",
            "|pose| + sqrt(3) amplitude",
        )),
        Effect::Dynamic(d) => Some((
            base + d.velocity.norm() * duration
                + 0.5 * dynamics.gravity.norm() * duration * duration,
            "",
            "free flight: |pose| + |velocity| duration + |gravity| duration^2 / 2",
        )),
    }
}

/// Every body's motion stays within [`MAX_TRANSLATION`]; `origins[i]` names where body `i`
/// was declared (e.g. `body[2] ('pawn')` or `ring_mesh[0] ('mesh')`).
pub(super) fn check_reach(
    bodies: &[Body],
    origins: &[String],
    duration: f64,
    dynamics: &DynamicsSettings,
) -> Result<(), SceneError> {
    for (body, origin) in bodies.iter().zip(origins) {
        if let Some((bound, field, how)) = reach(body, duration, dynamics) {
            if bound.is_nan() || bound > MAX_TRANSLATION {
                return Err(field_error(
                    format!("{origin}{field}"),
                    format!(
                        "the motion can carry the body {bound:e} from the origin ({how}), \
                         outside the representable range (<= {MAX_TRANSLATION:e})"
                    ),
                ));
            }
        }
    }
    Ok(())
}

//! Scenes accept only the ranges `revdist distance` accepts (`revdist::limits`): every
//! translation, length and motion is checked when the scene is loaded, and the error names
//! the field, instead of a run that reports lower 0, value inf and witnesses at the origin.

use revdist_scene::runner::run;

mod common;
use common::{assert_errors_mention, error_of, parse};

const HEAD: &str = "duration = 1.0\ntime_step = 0.5\neps = 1e-3\n";

/// A static sphere with the given pose table.
fn sphere(name: &str, pose: &str) -> String {
    format!("[[body]]\nname = \"{name}\"\nmodel = \"sphere\"\neffect = \"static\"\npose = {pose}\n")
}

/// A kinematic sphere at `x` with a random motion of the given amplitude.
fn wobbly(x: f64, amplitude: f64) -> String {
    format!(
        "[[body]]\nname = \"wobbly\"\nmodel = \"sphere\"\neffect = \"kinematic\"\n\
         pose = {{ translation = [{x:e}, 0.0, 0.0] }}\n\
         random_motion = {{ seed = 3, amplitude = {amplitude:e}, period = 1.0 }}\n"
    )
}

/// A kinematic sphere through two keyframes at `x0` and `x1`.
fn keyed(x0: f64, x1: f64, interpolation: &str) -> String {
    format!(
        "[[body]]\nname = \"keyed\"\nmodel = \"sphere\"\neffect = \"kinematic\"\n\
         interpolation = \"{interpolation}\"\nkeyframes = [\n\
         {{ time = 0.0, pose = {{ translation = [{x0:e}, 0.0, 0.0] }} }},\n\
         {{ time = 1.0, pose = {{ translation = [{x1:e}, 0.0, 0.0] }} }},\n]\n"
    )
}

/// Reproducers of inputs that once ran out of range: a pose at 1e200 and a random-motion
/// amplitude of 1e300 ran and reported lower 0, value inf and witnesses at the origin; now
/// each is refused up front.
#[test]
fn out_of_range_poses_and_amplitudes_name_the_field() {
    let origin = sphere("a", "{ translation = [0.0, 0.0, 0.0] }");
    let e = error_of(&format!(
        "{HEAD}{origin}{}",
        sphere("far", "{ translation = [1e200, 0.0, 0.0] }")
    ));
    assert_eq!(
        e,
        "body[1] ('far').pose.translation = 1e200 is outside the representable range \
         (|body[1] ('far').pose.translation| <= 1e100)"
    );
    let e = error_of(&format!("{HEAD}{origin}{}", wobbly(0.0, 1e300)));
    assert!(
        e.starts_with("body[1] ('wobbly').random_motion.amplitude = 1e300 is outside"),
        "{e}"
    );
}

/// Every other place a translation or a length is given is checked the same way.
#[test]
fn every_translation_and_length_is_in_range() {
    let b = sphere("a", "{ translation = [0.0, 0.0, 0.0] }");
    let cases = [
        (
            format!("{HEAD}{b}{}", keyed(0.0, 1e200, "linear")),
            "body[1] ('keyed').keyframes[1].pose.translation = 1e200 is outside",
        ),
        (
            format!("{HEAD}{}", sphere("a", "{ translation = [0.0, inf, 0.0] }")),
            "body[0] ('a').pose.translation.y is inf, not a finite number",
        ),
        (
            format!("{HEAD}[[body]]\nname = \"t\"\ntorus = {{ major = 1e200, minor = 0.1 }}\neffect = \"static\"\n"),
            "body[0] ('t').torus.major = 1e200 is outside",
        ),
        (
            format!("{HEAD}[[ring_mesh]]\nname = \"m\"\nrows = 1\ncols = 2\nmajor = 0.1\nminor = 0.012\ncenter = [0.0, 1e200, 0.0]\n"),
            "ring_mesh[0] ('m').center = 1e200 is outside",
        ),
        (
            format!("{HEAD}contact_skin = 1e200\n{b}"),
            "contact_skin = 1e200 is outside",
        ),
        (format!("{HEAD}within = 1e200\n{b}"), "within = 1e200 is outside"),
        (format!("{HEAD}tolerance = 1e200\n{b}"), "tolerance = 1e200 is outside"),
        (
            format!("{HEAD}{b}[render]\neye = [1e200, 0.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n"),
            "render.eye = 1e200 is outside",
        ),
    ];
    assert_errors_mention(&cases);
}

/// A rotation axis needs an angle (it was read as angle 0), as an angle needs an axis.
#[test]
fn an_axis_needs_an_angle() {
    let e = error_of(&format!(
        "{HEAD}{}",
        sphere("a", "{ axis = [0.0, 0.0, 1.0] }")
    ));
    assert_eq!(e, "body[0] ('a').pose.angle: an axis needs an angle");
    let e = error_of(&format!("{HEAD}{}", sphere("a", "{ angle = 0.5 }")));
    assert_eq!(e, "body[0] ('a').pose.angle: needs an axis");
}

/// Poses within range whose motion would leave it during the run are refused up front: a
/// random motion about a pose near the limit, smooth keyframes that overshoot, a dynamic
/// body thrown fast enough.
#[test]
fn motions_that_would_leave_the_range_are_refused() {
    let b = sphere("a", "{ translation = [0.0, 0.0, 0.0] }");
    let cases = [
        (
            format!("{HEAD}{b}{}", wobbly(9e99, 1e99)),
            "body[1] ('wobbly').random_motion.amplitude: the motion can carry the body",
        ),
        (
            format!("{HEAD}{b}{}", keyed(-9e99, 9e99, "smooth")),
            "body[1] ('keyed').keyframes: the motion can carry the body",
        ),
        (
            "duration = 10.0\ntime_step = 0.5\neps = 1e-3\n\
             [[body]]\nname = \"thrown\"\ntorus = { major = 0.1, minor = 0.02 }\n\
             effect = \"dynamic\"\nvelocity = [2e99, 0.0, 0.0]\n"
                .to_string(),
            "body[0] ('thrown'): the motion can carry the body 2e100 from the origin (free flight",
        ),
    ];
    assert_errors_mention(&cases);
    // Linear keyframes stay between their poses: the same keys are accepted.
    parse(&format!("{HEAD}{b}{}", keyed(-9e99, 9e99, "linear"))).unwrap();
}

/// eps is held to `MAX_EPS_REL` (0.1) of the largest body's size, not to an absolute 0.1:
/// a coarse eps is fine for large bodies and refused for small ones.
#[test]
fn eps_is_relative_to_the_largest_body() {
    let big =
        "[[body]]\nname = \"big\"\ntorus = { major = 100.0, minor = 20.0 }\neffect = \"static\"\n";
    parse(&format!(
        "duration = 1.0\ntime_step = 0.5\neps = 1.0\n{big}"
    ))
    .unwrap();
    let e = error_of(&format!(
        "duration = 1.0\ntime_step = 0.5\neps = 1.0\n{}",
        sphere("a", "{}")
    ));
    assert!(
        e.starts_with("eps: 1 is coarser than 0.1 of the largest body's size"),
        "{e}"
    );
}

/// A valid scene with every kind of placement near (but within) the limits still loads and
/// runs, with finite certified answers.
#[test]
fn a_valid_scene_still_loads_and_runs() {
    let text = format!(
        "{HEAD}{}{}{}",
        sphere(
            "a",
            "{ translation = [0.0, 0.0, 0.0], axis = [0.0, 1.0, 0.0], angle = 0.3 }"
        ),
        sphere("b", "{ translation = [3.0, 0.0, 0.0] }"),
        wobbly(-3.0, 0.2)
    );
    let scene = parse(&text).unwrap();
    run(&scene, |f| {
        for s in &f.samples {
            assert!(s.lower.is_finite() && s.upper.is_finite() && s.lower > 0.0);
        }
        Ok(())
    })
    .unwrap();
}

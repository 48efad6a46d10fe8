//! The runner computes only what a scene asks for: counters checked on small scenes, and
//! every bad field of a scene file named in its error.

use revdist_scene::format::Scene;
use revdist_scene::runner::{run, Counters, Source};
use std::path::Path;

mod common;
use common::{assert_errors_mention, parse};

fn run_counting(scene: &Scene) -> (Counters, Vec<(usize, Source, f64, f64)>) {
    let mut seen = Vec::new();
    let c = run(scene, |f| {
        for s in &f.samples {
            seen.push((f.index, s.source, s.lower, s.upper));
        }
        Ok(())
    })
    .unwrap();
    (c, seen)
}

const HEAD: &str = "duration = 0.5\ntime_step = 0.1\neps = 1e-3\n";

fn body(name: &str, model: &str, effect: &str, x: f64) -> String {
    format!(
        "[[body]]\nname = \"{name}\"\nmodel = \"{model}\"\neffect = \"{effect}\"\npose = {{ translation = [{x}, 0.0, 0.0] }}\n"
    )
}

/// A static scene: one query per measured pair for the whole run, no rebuild, no pose
/// update; every later frame reuses the certified answer.
#[test]
fn static_scene_queries_each_pair_once() {
    let text = format!(
        "{HEAD}{}{}{}",
        body("a", "sphere", "static", 0.0),
        body("b", "cone", "static", 1.8),
        body("c", "capsule", "static", -1.8)
    );
    let scene = parse(&text).unwrap();
    let (c, seen) = run_counting(&scene);
    assert_eq!(c.frames, 6);
    assert_eq!(c.queries, vec![1, 1, 1]);
    assert_eq!(c.reused, vec![5, 5, 5]);
    assert_eq!(c.rebuilds, vec![0, 0, 0]);
    assert_eq!(c.pose_updates, vec![0, 0, 0]);
    assert_eq!(c.initial_builds, vec![1, 1, 1]);
    // Reused answers are the queried ones.
    for (frame, source, lower, upper) in &seen {
        assert_eq!(*source == Source::Query, *frame == 0);
        assert!(lower <= upper && *lower > 0.0);
    }
}

/// A kinematic scene rebuilds nothing and updates only the moving body's pose, once per
/// frame after the first; its pairs are queried every frame, static pairs once.
#[test]
fn kinematic_scene_rebuilds_nothing() {
    let text = format!(
        "{HEAD}{}{}[[body]]\nname = \"m\"\nmodel = \"cylinder\"\neffect = \"kinematic\"\nkeyframes = [{{ time = 0.0, pose = {{ translation = [0.0, 2.0, 0.0] }} }}, {{ time = 0.5, pose = {{ translation = [0.0, 1.6, 0.3] }} }}]\n",
        body("a", "sphere", "static", 0.0),
        body("b", "cone", "static", 1.8),
    );
    let scene = parse(&text).unwrap();
    let (c, _) = run_counting(&scene);
    assert_eq!(c.rebuilds, vec![0, 0, 0]);
    assert_eq!(c.pose_updates, vec![0, 0, 5]);
    // Pairs in order (a,b), (a,m), (b,m).
    assert_eq!(c.queries, vec![1, 6, 6]);
}

/// A deforming scene rebuilds only the deforming body, once per frame after the first;
/// an unmeasured pair is never queried.
#[test]
fn deforming_scene_rebuilds_only_the_morph() {
    let text = format!(
        "{HEAD}measure = [[\"morph\", \"a\"]]\n{}{}[[body]]\nname = \"morph\"\nmorph = {{ period = 1.0 }}\neffect = \"deforming\"\npose = {{ translation = [0.0, 1.8, 0.0] }}\n",
        body("a", "sphere", "static", 0.0),
        body("b", "cone", "static", 1.8),
    );
    let scene = parse(&text).unwrap();
    let (c, seen) = run_counting(&scene);
    assert_eq!(c.rebuilds, vec![0, 0, 5]);
    assert_eq!(c.pose_updates, vec![0, 0, 0]);
    assert_eq!(c.queries, vec![6]);
    assert_eq!(seen.len(), 6);
}

/// The broad phase answers far pairs from their bounding spheres without a query, with an
/// interval that still holds the true distance (checked against a query).
#[test]
fn broad_phase_skips_far_pairs() {
    let text = format!(
        "{HEAD}within = 0.5\n{}{}{}",
        body("a", "sphere", "static", 0.0),
        body("near", "cone", "static", 1.7),
        body("far", "capsule", "static", 9.0)
    );
    let scene = parse(&text).unwrap();
    let (c, seen) = run_counting(&scene);
    // Pairs (a,near), (a,far), (near,far).
    assert_eq!(c.queries, vec![1, 0, 0]);
    assert_eq!(c.broad_phase_skips, vec![0, 6, 6]);
    let queried = {
        let mut s = scene.clone();
        s.within = None;
        run_counting(&s).1
    };
    for ((_, src, lo, hi), (_, _, qlo, qhi)) in seen.iter().zip(&queried) {
        if *src == Source::BroadPhase {
            assert!(
                *lo <= *qhi && *qlo <= *hi,
                "sphere interval [{lo}, {hi}] vs [{qlo}, {qhi}]"
            );
        }
    }
}

/// Bad scene files: each error names the field and the problem.
#[test]
fn bad_scenes_name_the_field() {
    let b = body("a", "sphere", "static", 0.0);
    let cases = [
        (format!("duration = 1.0\ntime_step = -0.1\neps = 1e-3\n{b}"), "time_step"),
        (format!("duration = 1.0\ntime_step = 0.1\neps = nan\n{b}"), "eps"),
        (format!("{HEAD}{}", body("a", "teapot", "static", 0.0)), "body[0] ('a').model"),
        (format!("{HEAD}{}", body("a", "sphere", "wobbly", 0.0)), "unknown effect 'wobbly'"),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nmorph = {{ period = 1.0 }}\neffect = \"dynamic\"\n"),
            "body[0] ('a').effect: a dynamic body must be rigid",
        ),
        (format!("{HEAD}{b}{b}"), "'a' is used twice"),
        (format!("{HEAD}measure = [[\"a\", \"zz\"]]\n{b}"), "measure[0]: no body called 'zz'"),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nmodel = \"cone\"\neffect = \"static\"\npose = {{ translation = [1.0, 2.0] }}\n"),
            "pose.translation: expected 3 numbers, got 2",
        ),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nmodel = \"cone\"\neffect = \"static\"\npose = {{ quaternion = [0.0, 0.0, 0.0, 0.0] }}\n"),
            "pose.quaternion: rotation [0.0, 0.0, 0.0, 0.0] is not a unit quaternion [w, x, y, z] (norm 0, more than 1e-3 from 1)",
        ),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nmodel = \"cone\"\neffect = \"static\"\npose = {{ quaternion = [1.0, 0.0, 0.0, 1.0] }}\n"),
            "normalised it is [0.7071067811865475, 0.0, 0.0, 0.7071067811865475]",
        ),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nmodel = \"cone\"\neffect = \"kinematic\"\nkeyframes = [{{ time = 1.0, pose = {{}} }}, {{ time = 0.5, pose = {{}} }}]\n"),
            "keyframes[1].time: keyframe times must increase",
        ),
        (
            format!("{HEAD}[[body]]\nname = \"a\"\nprofile = \"no/such/file.toml\"\neffect = \"static\"\n"),
            "no profile file",
        ),
        (format!("{HEAD}colour = \"red\"\n{b}"), "unknown field `colour`"),
        (HEAD.to_string(), "missing field `body`"),
    ];
    assert_errors_mention(&cases);
}

/// A quaternion typed with 4 decimals (norm 0.99999) is normalised, as on the command line.
#[test]
fn typed_quaternions_are_normalised() {
    let text = format!(
        "{HEAD}[[body]]\nname = \"a\"\nmodel = \"cone\"\neffect = \"static\"\npose = {{ quaternion = [0.7071, 0.0, 0.7071, 0.0] }}\n"
    );
    let scene = parse(&text).unwrap();
    let q = scene.bodies[0].pose.rotation.into_inner();
    assert!((q.norm() - 1.0).abs() < 1e-15);
    assert_eq!(q.w, q.j);
}

/// Every example scene parses, plans and runs its first frames.
#[test]
fn example_scenes_run() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let mut scene =
                Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            scene.duration = 2.0 * scene.time_step;
            let (c, seen) = run_counting(&scene);
            assert_eq!(c.frames, 3, "{}", path.display());
            assert!(seen.iter().all(|s| s.2 <= s.3), "{}", path.display());
            n += 1;
        }
    }
    assert!(n >= 5, "{n} example scenes");
}

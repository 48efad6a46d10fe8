//! The `dynamic` effect: mass properties against closed forms, a ring dropped on the table,
//! an interlocked chain, the counters (no dynamics work unless asked for, static-static pairs
//! never queried) and the errors of bad dynamic fields.

use revdist_scene::format::torus_profile;
use revdist_scene::format::Scene;
use revdist_scene::mass::mass_properties;
use revdist_scene::runner::{run, Counters, Frame};
use std::f64::consts::PI;
use std::path::Path;

mod common;
use common::{assert_errors_mention, parse};

/// Runs a scene, keeping every frame.
fn run_frames(scene: &Scene) -> (Counters, Vec<Frame>) {
    let mut frames = Vec::new();
    let c = run(scene, |f| {
        frames.push(f.clone());
        Ok(())
    })
    .unwrap();
    (c, frames)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Solid torus (R, r): V = 2 pi^2 R r^2, I_z = m (R^2 + 3 r^2 / 4), I_xy = m (R^2 / 2 + 5 r^2
/// / 8); ball of radius a: V = 4 pi a^3 / 3, I = 2 m a^2 / 5, centre on the axis.
#[test]
fn mass_properties_match_closed_forms() {
    for (big, small) in [(1.0, 0.12), (0.1, 0.012), (0.9, 0.6)] {
        let p = torus_profile(big, small).unwrap();
        let mp = mass_properties(&p, Some(2.0), None).unwrap();
        let v = 2.0 * PI * PI * big * small * small;
        let m = 2.0 * v;
        assert!(
            rel(mp.volume, v) < 1e-4,
            "torus volume {} vs {v}",
            mp.volume
        );
        assert!(rel(mp.mass, m) < 1e-4);
        assert!(mp.com_z.abs() < 1e-9 * big, "com {}", mp.com_z);
        let iz = m * (big * big + 0.75 * small * small);
        let ixy = m * (0.5 * big * big + 0.625 * small * small);
        assert!(rel(mp.inertia_z, iz) < 2e-4, "I_z {} vs {iz}", mp.inertia_z);
        assert!(
            rel(mp.inertia_xy, ixy) < 2e-4,
            "I_xy {} vs {ixy}",
            mp.inertia_xy
        );
    }
    let ball = revdist::models::model("sphere").unwrap();
    let mp = mass_properties(&ball, None, Some(3.0)).unwrap();
    let a: f64 = 0.75;
    let v = 4.0 / 3.0 * PI * a.powi(3);
    assert!(rel(mp.volume, v) < 1e-4, "ball volume {} vs {v}", mp.volume);
    assert!(rel(mp.mass, 3.0) < 1e-12);
    assert!((mp.com_z - 0.75).abs() < 1e-6, "com {}", mp.com_z);
    let i = 0.4 * 3.0 * a * a;
    assert!(rel(mp.inertia_z, i) < 2e-4 && rel(mp.inertia_xy, i) < 2e-4);
}

/// Checks of every dynamic frame: no overlap, every certified lower bound positive, the
/// energy never increasing from one step to the next (beyond rounding). Returns the smallest
/// lower bound.
fn check_frames(frames: &[Frame]) -> f64 {
    let mut min_lower = f64::INFINITY;
    let mut prev = None;
    for f in frames {
        let d = f.dynamics.as_ref().expect("dynamic frame");
        let e = d.kinetic + d.potential;
        let tol = 1e-12 * (d.potential.abs() + d.kinetic) + 1e-15;
        assert_eq!(d.report.overlaps, 0, "frame {}", f.index);
        assert!(
            d.report.max_energy_increase <= tol,
            "frame {}: a step gained {:e}",
            f.index,
            d.report.max_energy_increase
        );
        if let Some(p) = prev {
            assert!(e <= p + tol, "frame {}: energy {e} after {p}", f.index);
        }
        prev = Some(e);
        min_lower = min_lower.min(d.report.min_lower);
        for s in &f.samples {
            assert!(!s.overlap && s.lower > 0.0, "frame {}: {:?}", f.index, s);
            min_lower = min_lower.min(s.lower);
        }
    }
    assert!(min_lower > 0.0);
    min_lower
}

/// A ring dropped on the table falls, lands and comes to rest on the top (z = 1.46): its gap
/// stays positive, its energy never grows, and it ends nearly at rest just above the top.
#[test]
fn ring_dropped_on_table_comes_to_rest() {
    let text = "duration = 1.0\ntime_step = 0.02\neps = 1e-4\nsubsteps = 10\n\
        [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n\
        [[body]]\nname = \"ring\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { translation = [0.1, 0.05, 1.62], axis = [1.0, 0.4, 0.0], angle = 0.25 }\n";
    let scene = parse(text).unwrap();
    let (c, frames) = run_frames(&scene);
    assert_eq!(c.frames, 51);
    assert_eq!(c.dynamics_steps, 500);
    assert_eq!(c.mass_computations, 1);
    let min_lower = check_frames(&frames);
    let first = frames[0].dynamics.as_ref().unwrap();
    let last = frames.last().unwrap();
    let d = last.dynamics.as_ref().unwrap();
    // It fell: about m g (1.62 - 1.472) of potential energy went.
    assert!(d.potential < first.potential * 0.95);
    // At rest: kinetic energy below 1e-3 of what the fall released.
    let released = first.potential - d.potential;
    assert!(
        d.kinetic < 1e-3 * released,
        "kinetic {} of {released}",
        d.kinetic
    );
    // On the top: the ring's centre just above 1.46 + minor radius, within a few skins.
    let z = last.poses[1].translation.vector.z;
    assert!((1.46 + 0.012..1.46 + 0.012 + 0.02).contains(&z), "z = {z}");
    // The gap to the table stays positive and ends within a few skins.
    let gap = last.samples[0].lower;
    assert!(gap > 0.0 && gap < 0.01, "gap {gap}, min {min_lower}");
}

/// Three interlocked rings (two horizontal rings and the link between them) fall onto the
/// table: no overlap in any step, the link intact in every frame, the energy never growing.
#[test]
fn interlocked_chain_stays_linked() {
    let text = "duration = 0.6\ntime_step = 0.02\neps = 1e-4\nsubsteps = 10\n\
        [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n\
        [[ring_mesh]]\nname = \"chain\"\nrows = 1\ncols = 2\nmajor = 0.1\nminor = 0.012\n\
        center = [0.0, 0.0, 1.7]\ntwist = 0.4\n";
    let scene = parse(text).unwrap();
    assert_eq!(scene.bodies.len(), 4);
    assert_eq!(scene.links.len(), 2);
    let (c, frames) = run_frames(&scene);
    check_frames(&frames);
    for f in &frames {
        assert_eq!(
            f.dynamics.as_ref().unwrap().links_intact,
            2,
            "frame {}",
            f.index
        );
    }
    // They fell onto the table: every ring ends below its start and above the top.
    let last = frames.last().unwrap();
    for i in 1..4 {
        let z = last.poses[i].translation.vector.z;
        assert!(z < 1.7 - 0.05 && z > 1.46, "ring {i} at z = {z}");
    }
    assert!(c.dynamics_queries[1] > 0 && c.dynamics_queries[0] > 0);
    assert_eq!(c.dynamics_static_static_queries, 0);
}

/// No dynamic body: no dynamics at all (no steps, no mass properties, no contact queries, no
/// dynamics in the frames), whatever dynamics settings the file gives.
#[test]
fn no_dynamics_without_dynamic_bodies() {
    let text = "duration = 0.2\ntime_step = 0.1\neps = 1e-3\ngravity = [0.0, 0.0, -1.0]\nsubsteps = 5\n\
        [[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"static\"\n\
        [[body]]\nname = \"b\"\ntorus = { major = 0.5, minor = 0.1 }\neffect = \"static\"\npose = { translation = [2.0, 0.0, 0.0] }\n";
    let scene = parse(text).unwrap();
    assert!(!scene.has_dynamics());
    let (c, frames) = run_frames(&scene);
    assert_eq!(c.dynamics_steps, 0);
    assert_eq!(c.mass_computations, 0);
    assert_eq!(c.dynamics_queries, [0, 0]);
    assert_eq!(c.dynamics_pair_checks, 0);
    assert_eq!(c.queries, vec![1]);
    assert!(frames.iter().all(|f| f.dynamics.is_none()));
    assert!(frames.iter().all(|f| f.cost.dynamics == 0.0));
}

/// Static-static pairs are never looked at by the solver, even when they touch-close; far
/// dynamic pairs are left to the broad phase.
#[test]
fn static_pairs_are_never_queried() {
    let text = "duration = 0.1\ntime_step = 0.02\neps = 1e-3\nsubsteps = 2\nmeasure = [[\"s1\", \"d\"]]\n\
        [[body]]\nname = \"s1\"\nmodel = \"cylinder\"\neffect = \"static\"\n\
        [[body]]\nname = \"s2\"\nmodel = \"cone\"\neffect = \"static\"\npose = { translation = [1.11, 0.0, 0.0] }\n\
        [[body]]\nname = \"d\"\nmodel = \"sphere\"\neffect = \"dynamic\"\npose = { translation = [0.0, 0.0, 1.6] }\n\
        [[body]]\nname = \"far\"\nmodel = \"sphere\"\neffect = \"dynamic\"\npose = { translation = [30.0, 0.0, 0.0] }\n";
    let scene = parse(text).unwrap();
    let (c, frames) = run_frames(&scene);
    check_frames(&frames);
    assert_eq!(c.dynamics_steps, 10);
    assert_eq!(c.dynamics_static_static_queries, 0);
    // 5 pairs with a dynamic body are checked per step (s1-d, s1-far, s2-d, s2-far, d-far);
    // s1-s2 never.
    assert_eq!(c.dynamics_pair_checks, 5 * 10);
    // Only the pairs near the falling sphere can be queried: s1-d and s2-d (spheres within
    // reach); the far sphere's pairs never are. Between queries the bound carried from the
    // last one (minus the motion since) is enough for a while.
    assert_eq!(c.dynamics_queries[1], 0);
    assert!(c.dynamics_queries[0] >= 1 && c.dynamics_carried_skips >= 1);
    assert!(c.dynamics_queries[0] + c.dynamics_carried_skips <= 2 * 10);
    assert_eq!(c.mass_computations, 2);
}

/// Bad dynamic fields: each error names the field and the problem.
#[test]
fn bad_dynamic_fields_name_the_field() {
    let head = "duration = 1.0\ntime_step = 0.1\neps = 1e-3\n";
    let body = "[[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"dynamic\"\n";
    let dynamic = |extra: &str| format!("{head}{body}{extra}\n");
    let cases = [
        (dynamic("velocity = [1.0, 2.0]"), "body[0] ('a').velocity: expected 3 numbers, got 2"),
        (
            dynamic("angular_velocity = [1.0, 2.0, 3.0, 4.0]"),
            "body[0] ('a').angular_velocity: expected 3 numbers, got 4",
        ),
        (dynamic("mass = -1.0"), "body[0] ('a').mass: must be a positive number"),
        (dynamic("density = 0.0"), "body[0] ('a').density: must be a positive number"),
        (dynamic("mass = 1.0\ndensity = 2.0"), "body[0] ('a').mass: give mass or density, not both"),
        (dynamic("keyframes = []"), "body[0] ('a').effect: a dynamic body moves under gravity"),
        (dynamic("spin = 1.0"), "unknown field `spin`"),
        (
            format!("{head}[[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"static\"\nvelocity = [0.0, 0.0, 1.0]\n"),
            "body[0] ('a').velocity: only dynamic bodies take velocity",
        ),
        (
            format!("{head}[[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"static\"\nmass = 2.0\n"),
            "body[0] ('a').mass: only dynamic bodies take mass",
        ),
        (format!("{head}gravity = [0.0, -9.81]\n{body}"), "gravity: expected 3 numbers, got 2"),
        (format!("{head}substeps = 0\n{body}"), "substeps: must be 1..10000"),
        (format!("{head}contact_skin = -0.1\n{body}"), "contact_skin: must be a positive number"),
        (format!("{head}friction = -0.5\n{body}"), "friction: must be finite and >= 0"),
        (format!("{head}solver_iterations = 0\n{body}"), "solver_iterations: must be 1..1000"),
        (
            format!("{head}[[body]]\nname = \"t\"\ntorus = {{ major = 0.1, minor = 0.2 }}\neffect = \"dynamic\"\n"),
            "body[0] ('t').torus.minor: must be below major",
        ),
        (
            format!("{head}[[body]]\nname = \"t\"\ntorus = {{ major = 0.1 }}\neffect = \"dynamic\"\n"),
            "missing field `minor`",
        ),
        (
            format!("{head}[[body]]\nname = \"k\"\nmodel = \"cone\"\neffect = \"kinematic\"\nrandom_motion = {{ seed = 1, amplitude = 0.1, period = 1.0 }}\n{}", body.replace("\"a\"", "\"d\"")),
            "body[0] ('k').effect: a scene with dynamic bodies can only have static and dynamic bodies",
        ),
        (
            format!("{head}[[ring_mesh]]\nname = \"m\"\nrows = 2\ncols = 2\nmajor = 0.1\nminor = 0.012\nspacing = 0.2\n"),
            "ring_mesh[0] ('m').spacing: must lie in",
        ),
        (
            format!("{head}[[ring_mesh]]\nname = \"m\"\nrows = 0\ncols = 2\nmajor = 0.1\nminor = 0.012\n"),
            "ring_mesh[0] ('m').rows",
        ),
        (
            format!("{head}[[ring_mesh]]\nname = \"m\"\nrows = 1\ncols = 2\nmajor = 0.1\nminor = 0.012\ncenter = [0.0, 1.0]\n"),
            "ring_mesh[0] ('m').center: expected 3 numbers, got 2",
        ),
    ];
    assert_errors_mention(&cases);
}

/// A contact skin too thin for the queries' certified width, or bodies starting inside the
/// clearance, are refused when the run starts.
#[test]
fn unsafe_starts_are_refused() {
    let thin = "duration = 0.1\ntime_step = 0.02\neps = 1e-3\ncontact_skin = 1e-3\n\
        [[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"dynamic\"\n";
    let scene = parse(thin).unwrap();
    let e = run(&scene, |_| Ok(())).unwrap_err().to_string();
    assert!(e.contains("contact_skin"), "{e}");
    let close = "duration = 0.1\ntime_step = 0.02\neps = 1e-3\n\
        [[body]]\nname = \"a\"\nmodel = \"sphere\"\neffect = \"static\"\n\
        [[body]]\nname = \"b\"\nmodel = \"sphere\"\neffect = \"dynamic\"\npose = { translation = [1.0, 0.0, 0.0] }\n";
    let scene = parse(close).unwrap();
    let e = run(&scene, |_| Ok(())).unwrap_err().to_string();
    assert!(e.contains("'a' and 'b' start overlapping"), "{e}");
}

/// A fast, fast-spinning ring thrown at the table and at a resting ring: the step bounds
/// (rotation included) keep every pair apart in every step; energy never grows.
#[test]
fn fast_spinning_ring_never_overlaps() {
    let text = "duration = 0.4\ntime_step = 0.02\neps = 1e-4\nsubsteps = 5\n\
        [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n\
        [[body]]\nname = \"resting\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { translation = [0.0, 0.0, 1.4735] }\n\
        [[body]]\nname = \"thrown\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { translation = [-0.3, 0.0, 1.75], axis = [0.0, 1.0, 0.0], angle = 1.2 }\n\
        velocity = [1.5, 0.0, -3.0]\nangular_velocity = [20.0, 35.0, -10.0]\n";
    let scene = parse(text).unwrap();
    let (c, frames) = run_frames(&scene);
    let min_lower = check_frames(&frames);
    assert!(min_lower > 0.0);
    assert_eq!(c.dynamics_static_static_queries, 0);
    // The thrown ring came down to the table top.
    let z = frames.last().unwrap().poses[2].translation.vector.z;
    assert!(z < 1.6, "z = {z}");
}

/// Free flight: without gravity a spinning ring (about a non-principal axis) keeps its
/// energy to rounding (the exact torque-free rotation); with gravity, semi-implicit Euler
/// loses exactly m g^2 h^2 / 2 per step.
#[test]
fn free_flight_energy() {
    let body = "[[body]]\nname = \"r\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { axis = [0.0, 1.0, 0.0], angle = 1.2 }\nvelocity = [1.0, 0.0, 2.0]\nangular_velocity = [20.0, 35.0, -10.0]\n";
    let still = parse(&format!(
        "duration = 1.0\ntime_step = 0.02\neps = 1e-4\ngravity = [0.0, 0.0, 0.0]\n{body}"
    ))
    .unwrap();
    let (_, frames) = run_frames(&still);
    let e = |f: &Frame| {
        let d = f.dynamics.as_ref().unwrap();
        d.kinetic + d.potential
    };
    let e0 = e(&frames[0]);
    for f in &frames {
        assert!(
            (e(f) - e0).abs() < 1e-12 * e0,
            "frame {}: {} vs {e0}",
            f.index,
            e(f)
        );
    }
    let falling = parse(&format!(
        "duration = 0.2\ntime_step = 0.02\neps = 1e-4\nsubsteps = 4\n{body}"
    ))
    .unwrap();
    let (c, frames) = run_frames(&falling);
    let m = mass_properties(&torus_profile(0.1, 0.012).unwrap(), None, None)
        .unwrap()
        .mass;
    let h = 0.02 / 4.0;
    let expected = e(&frames[0]) - c.dynamics_steps as f64 * 0.5 * m * 9.81 * 9.81 * h * h;
    let got = e(frames.last().unwrap());
    assert!(
        (got - expected).abs() < 1e-10 * got.abs(),
        "{got} vs {expected}"
    );
}

/// The example ring mesh: 25 rings and 40 links, every link through both of its rings'
/// holes at the start (linking number +-1 for all 80 pairs).
#[test]
fn ring_mesh_example_is_interlocked() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments/scenes/ring_mesh.toml");
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.bodies.len(), 66);
    assert_eq!(scene.links.len(), 80);
    let poses: Vec<_> = scene.bodies.iter().map(|b| b.pose).collect();
    assert_eq!(revdist_scene::runner::links_intact(&scene, &poses), 80);
}

/// Xorshift64 (Marsaglia 2003): the seeded generator of the random throws.
struct Xorshift64(u64);

impl Xorshift64 {
    /// Uniform in [-1, 1).
    fn signed_unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// Random throws: a few rings with random poses, velocities and spins dropped together on
/// the table; no step may let two solids overlap, and the energy never grows.
#[test]
fn random_throws_never_overlap() {
    let mut rng = Xorshift64(0x2545_f491_4f6c_dd1d);
    let mut rnd = || rng.signed_unit();
    for seed in 0..4 {
        let mut text = String::from(
            "duration = 0.3\ntime_step = 0.02\neps = 1e-4\nsubsteps = 5\n\
             [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n",
        );
        for k in 0..3 {
            text.push_str(&format!(
                "[[body]]\nname = \"r{k}\"\ntorus = {{ major = 0.1, minor = 0.02 }}\neffect = \"dynamic\"\n\
                 pose = {{ translation = [{}, {}, {}], axis = [{}, {}, 1.0], angle = {} }}\n\
                 velocity = [{}, {}, {}]\nangular_velocity = [{}, {}, {}]\n",
                0.15 * rnd(),
                0.15 * rnd() + 0.25 * (k as f64 - 1.0),
                1.6 + 0.06 * k as f64,
                rnd(),
                rnd(),
                2.0 * rnd(),
                rnd(),
                rnd(),
                -2.0 + rnd(),
                20.0 * rnd(),
                20.0 * rnd(),
                20.0 * rnd()
            ));
        }
        let scene = parse(&text).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        let (c, frames) = run_frames(&scene);
        check_frames(&frames);
        assert!(c.dynamics_queries[0] > 0, "seed {seed}");
    }
}

/// Longer stress run (`cargo test --release -p revdist-scene --test dynamics -- --ignored`):
/// piles of 12 thrown rings, `STRESS_SEEDS` seeds (default 10), one second each.
#[test]
#[ignore]
fn stress_random_piles() {
    let seeds: u64 = std::env::var("STRESS_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let mut worst = f64::INFINITY;
    for seed in 0..seeds {
        let mut rng =
            Xorshift64(0x9e37_79b9_7f4a_7c15u64 ^ (seed.wrapping_mul(0x2545_f491_4f6c_dd1d) | 1));
        let mut rnd = || rng.signed_unit();
        let mut text = String::from(
            "duration = 1.0\ntime_step = 0.02\neps = 1e-4\nsubsteps = 10\n\
             [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n",
        );
        for k in 0..12 {
            let (col, row, layer) = (k % 2, (k / 2) % 2, k / 4);
            text.push_str(&format!(
                "[[body]]\nname = \"r{k}\"\ntorus = {{ major = 0.1, minor = 0.015 }}\neffect = \"dynamic\"\n\
                 pose = {{ translation = [{}, {}, {}], axis = [{}, {}, 1.0], angle = {} }}\n\
                 velocity = [{}, {}, {}]\nangular_velocity = [{}, {}, {}]\n",
                0.25 * (col as f64 - 0.5) + 0.01 * rnd(),
                0.25 * (row as f64 - 0.5) + 0.01 * rnd(),
                1.62 + 0.25 * layer as f64,
                rnd(),
                rnd(),
                0.5 * rnd(),
                0.5 * rnd(),
                0.5 * rnd(),
                -1.0 + rnd(),
                10.0 * rnd(),
                10.0 * rnd(),
                10.0 * rnd()
            ));
        }
        let scene = parse(&text).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        let (_, frames) = run_frames(&scene);
        worst = worst.min(check_frames(&frames));
    }
    eprintln!("smallest certified lower bound over {seeds} piles: {worst:e}");
}

/// The outputs of a dynamic scene: one dynamics CSV row per frame, and a summary section
/// with the smallest certified gap, the energy, the links and the queries per step.
#[test]
fn dynamic_outputs_report_gap_energy_links_and_queries() {
    use revdist_scene::output::{dynamics_csv_row, DynamicsTally, DYNAMICS_CSV_HEADER};
    let text = "duration = 0.2\ntime_step = 0.02\neps = 1e-4\nsubsteps = 4\n\
        [[body]]\nname = \"table\"\nmodel = \"table\"\neffect = \"static\"\n\
        [[ring_mesh]]\nname = \"chain\"\nrows = 1\ncols = 2\nmajor = 0.1\nminor = 0.012\n\
        center = [0.0, 0.0, 1.62]\n";
    let scene = parse(text).unwrap();
    let mut csv = Vec::new();
    let mut tally = DynamicsTally::new();
    let counters = run(&scene, |f| {
        dynamics_csv_row(f, &mut csv)?;
        tally.add(f);
        Ok(())
    })
    .unwrap();
    let csv = String::from_utf8(csv).unwrap();
    assert_eq!(csv.lines().count(), counters.frames);
    let columns = DYNAMICS_CSV_HEADER.split(',').count();
    assert!(csv.lines().all(|l| l.split(',').count() == columns));
    let md = tally.markdown(&scene, &counters);
    for needle in [
        "smallest certified lower bound of a contact query",
        "energy (kinetic + potential) at the start / end",
        "largest energy increase of one step",
        "links intact at the start / end | 2 / 2 of 2",
        "contact queries per step",
        "static-static queries | 0",
        "dynamics per frame, median (ms)",
    ] {
        assert!(md.contains(needle), "summary lacks {needle:?}:\n{md}");
    }
    assert!(tally.min_lower > 0.0 && tally.steps == 40);
}

/// A chain hanging from a static ring: two dynamic links drop until they hang on the ring
/// and on each other (contacts in tension), then swing; the links never break or overlap.
#[test]
fn chain_hangs_from_a_static_ring() {
    use revdist_scene::links::{core_circle, linking_number};
    let text = "duration = 1.0\ntime_step = 0.02\neps = 1e-4\nsubsteps = 10\n\
        [[body]]\nname = \"hook\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"static\"\n\
        pose = { translation = [0.0, 0.0, 2.0] }\n\
        [[body]]\nname = \"b\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { translation = [0.12, 0.0, 2.0], axis = [1.0, 0.0, 0.0], angle = 1.5707963267948966 }\n\
        [[body]]\nname = \"c\"\ntorus = { major = 0.1, minor = 0.012 }\neffect = \"dynamic\"\n\
        pose = { translation = [0.12, 0.0, 1.86], axis = [0.0, 1.0, 0.0], angle = 1.5707963267948966 }\n\
        angular_velocity = [0.0, 0.0, 3.0]\n";
    let scene = parse(text).unwrap();
    let linked = |poses: &[nalgebra::Isometry3<f64>], a: usize, b: usize| {
        linking_number(&core_circle(&poses[a], 0.1), &core_circle(&poses[b], 0.1)).abs() == 1
    };
    let poses: Vec<_> = scene.bodies.iter().map(|b| b.pose).collect();
    assert!(linked(&poses, 0, 1) && linked(&poses, 1, 2) && !linked(&poses, 0, 2));
    let (_, frames) = run_frames(&scene);
    check_frames(&frames);
    for f in &frames {
        assert!(
            linked(&f.poses, 0, 1) && linked(&f.poses, 1, 2),
            "frame {}",
            f.index
        );
    }
    // Hanging, not fallen: the lower link stays within two ring diameters of the hook.
    let z = frames.last().unwrap().poses[2].translation.vector.z;
    let zb = frames.last().unwrap().poses[1].translation.vector.z;
    eprintln!("hanging chain: b at z = {zb}, c at z = {z}");
    assert!(z > 2.0 - 0.5 && z < 2.0, "z = {z}");
    // Both links dropped until they hang: b's top on the hook, c's top on b's bottom.
    assert!(zb < 2.0 - 0.05 && z < 1.86 - 0.05, "b at {zb}, c at {z}");
}

//! Mutation fuzzer of scene files: the example scenes mutated at the byte and the
//! TOML-value level (`tests/support/mutate.rs` of the core). Every input must be parsed and
//! checked without a panic and within a time limit, and refused with an error that names
//! the field (or line) that is wrong, or accepted as a scene with finite settings. The seed
//! is fixed so that a failure reproduces; set `REVDIST_FUZZ_SEED` to explore others.

#[path = "../../tests/support/mutate.rs"]
mod mutate;

use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use mutate::{mutate_bytes, mutate_toml};
use revdist::rng::SplitMix64;
use revdist_scene::format::Scene;

/// Mutated scene files per run.
const SCENE_INPUTS: usize = 3000;
/// Longest one input may take to be parsed and checked.
const PER_INPUT_LIMIT: Duration = Duration::from_secs(5);

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../experiments/scenes")
}

/// One mutated scene: refused naming its problem, or a scene with finite settings.
fn check_scene(text: &[u8]) -> Result<bool, String> {
    let Ok(text) = std::str::from_utf8(text) else {
        return Ok(false);
    };
    match Scene::parse(text, &scenes_dir()) {
        Err(e) => {
            let m = e.to_string();
            let named = m.contains('`')
                || m.contains("line")
                || m.contains('[')
                || m.contains('.')
                || m.split(':').next().is_some_and(|f| !f.trim().is_empty());
            if m.trim().is_empty() || m.len() > 2000 || !named {
                Err(format!("unclear error: {m}"))
            } else {
                Ok(false)
            }
        }
        Ok(scene) => {
            if scene.eps.is_finite() && scene.eps > 0.0 && scene.frames() < 20_000_000 {
                Ok(true)
            } else {
                Err(format!(
                    "accepted eps {} with {} frames",
                    scene.eps,
                    scene.frames()
                ))
            }
        }
    }
}

#[test]
fn mutated_scene_files_are_refused_clearly_or_accepted_sane() {
    let seed = std::env::var("REVDIST_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20261127u64);
    let mut seeds: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    seeds.sort();
    assert!(
        seeds.len() >= 4,
        "the example scenes are the fuzzer's seeds"
    );
    let mut rng = SplitMix64(seed ^ 0x5CE4E);
    let inputs: Vec<Vec<u8>> = (0..SCENE_INPUTS)
        .map(|i| {
            let base = rng.pick(&seeds).clone();
            if i % 3 == 0 {
                mutate_bytes(&mut rng, base.as_bytes())
            } else {
                mutate_toml(&mut rng, &base)
            }
        })
        .collect();
    let (tx, rx) = mpsc::channel();
    let worker_inputs = inputs.clone();
    std::thread::spawn(move || {
        for (i, text) in worker_inputs.iter().enumerate() {
            let r = std::panic::catch_unwind(AssertUnwindSafe(|| check_scene(text)))
                .unwrap_or_else(|_| Err("panicked".to_string()));
            if tx.send((i, r)).is_err() {
                return;
            }
        }
    });
    let started = Instant::now();
    let mut accepted = 0;
    for i in 0..inputs.len() {
        let (j, r) = rx.recv_timeout(PER_INPUT_LIMIT).unwrap_or_else(|_| {
            panic!(
                "scene input {i} hung:\n{}",
                String::from_utf8_lossy(&inputs[i])
            )
        });
        match r {
            Ok(ok) => accepted += usize::from(ok),
            Err(why) => panic!(
                "scene input {j}: {why}\n{}",
                String::from_utf8_lossy(&inputs[j])
            ),
        }
    }
    eprintln!(
        "{SCENE_INPUTS} mutated scenes ({accepted} accepted) in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(
        accepted >= SCENE_INPUTS / 50,
        "mutations must also reach valid scenes"
    );
}

//! Mutation fuzzer of revdist's inputs: valid profile files and batch lines mutated at the
//! byte and the TOML/JSON-value level (`support/mutate.rs`). Every input must be answered
//! without a panic, within a time limit, and either accepted (then its solid builds or is
//! refused clearly, and a query on it gives an ordered interval) or refused with an error
//! that names what is wrong. The seed is fixed so that a failure reproduces; set
//! `REVDIST_FUZZ_SEED` to explore others.

#[path = "support/mutate.rs"]
mod mutate;

use std::io::Write;
use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::sync::Arc;
use std::time::{Duration, Instant};

use mutate::{mutate_bytes, mutate_json, mutate_toml};
use nalgebra::Isometry3;
use revdist::models::model;
use revdist::profile_file::{from_toml_str, to_toml_string};
use revdist::query::{try_distance, Budget, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;

/// Mutated profile files checked in-process.
const PROFILE_INPUTS: usize = 8000;
/// Mutated batch lines, answered by one run of the binary.
const BATCH_LINES: usize = 3000;
/// Longest any one profile input may take (parse, build, one query); the loads that hung
/// before never finished.
const PER_INPUT_LIMIT: Duration = Duration::from_secs(5);
/// Longest the whole batch may take.
const BATCH_LIMIT: Duration = Duration::from_secs(120);

fn seed() -> u64 {
    std::env::var("REVDIST_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20261127)
}

/// Words of which an error must contain one: it says where (line, piece, point, field) or
/// what (eps, size, weights, knots, degree, range) is wrong.
const LOCATORS: [&str; 26] = [
    "line",
    "piece",
    "point",
    "profile",
    "eps",
    "size",
    "weight",
    "knot",
    "degree",
    "range",
    "field",
    "name",
    "missing",
    "unknown",
    "invalid",
    "expected",
    "tolerance",
    "pose",
    "rotation",
    "translation",
    "model",
    "request",
    "utf-8",
    "blank",
    "coordinate",
    "axis",
];

fn names_its_problem(message: &str) -> bool {
    let m = message.to_lowercase();
    !m.trim().is_empty() && m.len() < 1000 && LOCATORS.iter().any(|w| m.contains(w))
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz_inputs");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// How far a mutated profile got.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
enum Outcome {
    NotText,
    Refused,
    NoTree,
    Queried,
}

/// One mutated profile file: refused clearly, or built and queried with an ordered interval.
fn check_profile(text: &[u8]) -> Result<Outcome, String> {
    // Files are read as UTF-8 text; other bytes are an I/O error naming the file (the CLI
    // tests check its message).
    let Ok(text) = std::str::from_utf8(text) else {
        return Ok(Outcome::NotText);
    };
    let profile = match from_toml_str(text) {
        Err(e) if names_its_problem(&e.to_string()) => return Ok(Outcome::Refused),
        Err(e) => return Err(format!("unclear profile error: {e}")),
        Ok(p) => p,
    };
    let size = profile.bounding_box().diagonal();
    let solid = match Solid::from_profile(Arc::new(profile), 1e-3 * size) {
        Err(e) if names_its_problem(&e.to_string()) => return Ok(Outcome::NoTree),
        Err(e) => return Err(format!("unclear tree error: {e}")),
        Ok(s) => s,
    };
    let sphere = Solid::from_profile(Arc::new(model("sphere").unwrap()), 1e-3).unwrap();
    let opts = QueryOptions {
        budget: Budget {
            max_node_pairs: None,
            max_time: Some(Duration::from_millis(500)),
        },
        ..QueryOptions::default()
    };
    let b = sphere.with_pose(Isometry3::translation(1.5 * size + 1.0, 0.1, 0.2));
    match try_distance(&solid, &b, &opts) {
        Err(e) if names_its_problem(&e.to_string()) => Ok(Outcome::NoTree),
        Err(e) => Err(format!("unclear query error: {e}")),
        Ok(d)
            if d.lower >= 0.0 && d.lower <= d.upper && d.value >= d.lower && d.value <= d.upper =>
        {
            Ok(Outcome::Queried)
        }
        Ok(d) => Err(format!(
            "disordered interval [{}, {}] value {}",
            d.lower, d.upper, d.value
        )),
    }
}

/// Valid profile files to mutate: built-in models and a documented example.
fn profile_seeds() -> Vec<String> {
    let mut seeds: Vec<String> = ["sphere", "capsule", "cone", "cup", "pawn_ff", "ring"]
        .iter()
        .map(|n| to_toml_string(&model(n).unwrap()))
        .collect();
    seeds.push(
        "name = \"quarter-disk\"\n[[piece]]\ndegree = 2\nknots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]\npoints = [[0.0, -1.0], [1.0, -1.0], [1.0, 0.0]]\nweights = [1.0, 0.7071067811865476, 1.0]\n[[piece]]\ndegree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[1.0, 0.0], [0.0, 0.0]]\n"
            .to_string(),
    );
    seeds
}

#[test]
fn mutated_profile_files_are_refused_clearly_or_answered() {
    let seeds = profile_seeds();
    let mut rng = SplitMix64(seed());
    let inputs: Vec<Vec<u8>> = (0..PROFILE_INPUTS)
        .map(|i| {
            let base = rng.pick(&seeds).clone();
            // One to three mutations, byte-level for a third of the inputs.
            let mut text = base.into_bytes();
            let rounds = if rng.below(3) == 0 {
                1 + rng.below(3)
            } else {
                1
            };
            for _ in 0..rounds {
                text = if i % 3 == 0 {
                    mutate_bytes(&mut rng, &text)
                } else {
                    mutate_toml(&mut rng, &String::from_utf8_lossy(&text))
                };
            }
            text
        })
        .collect();
    // A worker answers the inputs in order; this thread enforces the per-input limit.
    let (done_tx, done_rx) = mpsc::channel();
    let worker_inputs = inputs.clone();
    std::thread::spawn(move || {
        for (i, text) in worker_inputs.iter().enumerate() {
            let r = std::panic::catch_unwind(AssertUnwindSafe(|| check_profile(text)))
                .unwrap_or_else(|_| Err("panicked".to_string()));
            if done_tx.send((i, r)).is_err() {
                return;
            }
        }
    });
    let started = Instant::now();
    let mut failures = Vec::new();
    let mut outcomes = std::collections::HashMap::new();
    for i in 0..inputs.len() {
        match done_rx.recv_timeout(PER_INPUT_LIMIT) {
            Ok((_, Ok(o))) => *outcomes.entry(o).or_insert(0) += 1,
            Ok((j, Err(why))) => failures.push((j, why)),
            Err(_) => failures.push((i, format!("no answer within {PER_INPUT_LIMIT:?}"))),
        }
        if failures.iter().any(|(_, w)| w.starts_with("no answer")) {
            break;
        }
    }
    if let Some((i, why)) = failures.first() {
        let path = scratch(&format!("profile-{}-{i}.toml", seed()));
        std::fs::write(&path, &inputs[*i]).unwrap();
        panic!(
            "{} of {} mutated profiles failed; first: input {i} ({}): {why}",
            failures.len(),
            inputs.len(),
            path.display()
        );
    }
    eprintln!(
        "{} mutated profiles in {:.1} s: {outcomes:?}",
        inputs.len(),
        started.elapsed().as_secs_f64()
    );
    // The mutations must reach the geometry, not only the parser (about 6% of the inputs
    // stay valid profiles: most mutations break a joint, a knot vector or the syntax).
    assert!(outcomes.get(&Outcome::Queried).copied().unwrap_or(0) >= inputs.len() / 25);
}

/// Valid batch lines to mutate.
const BATCH_SEEDS: [&str; 4] = [
    r#"{"a": "pawn", "b": "cup", "pose_b": {"translation": [1.5, 0.0, 0.2], "rotation": [1.0, 0.0, 0.0, 0.0]}, "eps": 0.001}"#,
    r#"{"a": "sphere", "b": "capsule", "pose_b": {"translation": [0.0, 2.5, 0.0]}, "tolerance": 0.0}"#,
    r#"{"a": "cone", "b": "morph@0.3", "pose_b": {"translation": [2.0, 0.0, 0.0], "rotation": [0.8, 0.6, 0.0, 0.0]}, "refine": true}"#,
    r#"{"a": "table_ff", "b": "ring", "eps": 0.01}"#,
];

#[test]
fn mutated_batch_lines_each_get_one_clear_answer() {
    let mut rng = SplitMix64(seed() ^ 0xB47C);
    let mut input = Vec::new();
    for i in 0..BATCH_LINES {
        let base = *rng.pick(&BATCH_SEEDS);
        let mut line = if i % 3 == 0 {
            mutate_bytes(&mut rng, base.as_bytes())
        } else {
            mutate_json(&mut rng, base)
        };
        // A mutation may add or remove line breaks: the batch answers the lines there are.
        line.retain(|&b| b != b'\n');
        input.extend_from_slice(&line);
        input.push(b'\n');
    }
    let path = scratch(&format!("batch-{}.jsonl", seed()));
    std::fs::write(&path, &input).unwrap();
    let started = Instant::now();
    let child = Command::new(env!("CARGO_BIN_EXE_revdist"))
        .args([
            "distance",
            "--batch",
            path.to_str().unwrap(),
            "--max-time-ms",
            "200",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let (stop_tx, stop_rx) = mpsc::channel::<()>();
    let watchdog = std::thread::spawn(move || {
        if stop_rx.recv_timeout(BATCH_LIMIT).is_err() {
            let _ = Command::new("kill").arg(pid.to_string()).status();
            return true;
        }
        false
    });
    let out = child.wait_with_output().unwrap();
    let _ = stop_tx.send(());
    assert!(
        !watchdog.join().unwrap(),
        "the batch {} hung",
        path.display()
    );
    let code = out.status.code();
    assert!(
        matches!(code, Some(0) | Some(1)),
        "exit {code:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("output is UTF-8");
    let answers: Vec<&str> = text.lines().collect();
    assert_eq!(
        answers.len(),
        BATCH_LINES,
        "one answer per line ({})",
        path.display()
    );
    let mut failed = 0;
    for (i, a) in answers.iter().enumerate() {
        let v: serde_json::Value = serde_json::from_str(a).expect("each answer is JSON");
        assert_eq!(v["line"], i + 1, "{a}");
        if let Some(e) = v.get("error") {
            failed += 1;
            let e = e.as_str().unwrap();
            assert!(names_its_problem(e), "line {}: unclear error '{e}'", i + 1);
        } else {
            let (lo, hi) = (v["lower"].as_f64().unwrap(), v["upper"].as_f64().unwrap());
            assert!(lo >= 0.0 && lo <= hi, "line {}: {a}", i + 1);
        }
    }
    assert_eq!(code == Some(1), failed > 0);
    eprintln!(
        "{BATCH_LINES} mutated batch lines ({failed} refused) in {:.1} s",
        started.elapsed().as_secs_f64()
    );
}

/// The fuzzer's own mutations are seeded: the same seed gives the same inputs.
#[test]
fn mutations_are_reproducible() {
    let base = BATCH_SEEDS[0];
    let run = |s| {
        let mut rng = SplitMix64(s);
        (0..50)
            .map(|_| mutate_json(&mut rng, base))
            .collect::<Vec<_>>()
    };
    assert_eq!(run(7), run(7));
    assert_ne!(run(7), run(8));
    let _ = std::io::stdout().flush();
}

/// Re-serialising a seed without mutating it gives the same profile: refusals come from the
/// mutations, not from the fuzzer's TOML writer.
#[test]
fn unmutated_seeds_round_trip() {
    for text in profile_seeds() {
        let table: toml::Table = text.parse().unwrap();
        let again = toml::to_string(&table).unwrap();
        let p = from_toml_str(&again).unwrap_or_else(|e| panic!("{e}\n{again}"));
        assert_eq!(p, from_toml_str(&text).unwrap());
    }
}

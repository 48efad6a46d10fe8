//! Every driver's command line: `--help` prints a description and exits 0 without writing
//! anything, and bad command lines (a flag without its value, a stray word, `--pairs` given a
//! count) exit 2 with an `error: ...` message, never a panic. No driver runs an experiment here.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Every driver, and a flag of it that takes a value.
const DRIVERS: [(&str, &str); 11] = [
    (env!("CARGO_BIN_EXE_accuracy_time"), "--out"),
    (env!("CARGO_BIN_EXE_bvh_tables"), "--out"),
    (env!("CARGO_BIN_EXE_convergence"), "--out"),
    (env!("CARGO_BIN_EXE_deforming"), "--eps"),
    (env!("CARGO_BIN_EXE_fcl_bench"), "--pairs"),
    (env!("CARGO_BIN_EXE_motion"), "--frames"),
    (env!("CARGO_BIN_EXE_pareto"), "--poses"),
    (env!("CARGO_BIN_EXE_patch_kernels"), "--patch-pairs"),
    (env!("CARGO_BIN_EXE_query_cost"), "--poses"),
    (env!("CARGO_BIN_EXE_stability"), "--seeds"),
    (env!("CARGO_BIN_EXE_tails"), "--poses"),
];

/// An empty folder to run in, so that anything a driver writes would show.
fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("experiments-cli-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(bin: &str, args: &[&str], dir: &Path) -> Output {
    Command::new(bin)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("driver starts")
}

fn name(bin: &str) -> &str {
    Path::new(bin).file_name().unwrap().to_str().unwrap()
}

/// Exit status 2 and a one-line `error: ...` first, without a panic.
fn assert_usage_error(bin: &str, args: &[&str], dir: &Path) {
    let out = run(bin, args, dir);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{} {args:?}: {stderr}",
        name(bin)
    );
    assert!(
        stderr.starts_with("error: "),
        "{} {args:?}: {stderr}",
        name(bin)
    );
    assert!(
        !stderr.contains("panicked"),
        "{} {args:?}: {stderr}",
        name(bin)
    );
}

#[test]
fn help_describes_the_driver_and_writes_nothing() {
    let dir = scratch("help");
    for (bin, _) in DRIVERS {
        let out = run(bin, &["--help"], &dir);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{} --help failed", name(bin));
        let description = text.lines().next().unwrap_or("");
        assert!(
            description.len() > 80,
            "{}: no description: {text}",
            name(bin)
        );
        assert!(text.contains("Usage:") && text.contains("--help"), "{text}");
        // `--help` is not an output folder, and nothing else was written either.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0, "{}", name(bin));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_command_lines_are_errors_not_panics() {
    let dir = scratch("bad");
    for (bin, flag) in DRIVERS {
        assert_usage_error(bin, &[flag], &dir);
        assert_usage_error(bin, &["figures"], &dir);
        assert_usage_error(bin, &["--no-such-flag"], &dir);
    }
    // `--pairs` always means model pairs: a count is rejected (patch_kernels has no --pairs).
    for bin in [
        env!("CARGO_BIN_EXE_fcl_bench"),
        env!("CARGO_BIN_EXE_patch_kernels"),
    ] {
        assert_usage_error(bin, &["--pairs", "20"], &dir);
    }
    assert_usage_error(env!("CARGO_BIN_EXE_pareto"), &["--eps", "1e-3,2"], &dir);
    assert_usage_error(env!("CARGO_BIN_EXE_motion"), &["--poses", "3"], &dir);
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

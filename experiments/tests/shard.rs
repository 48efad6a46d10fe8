//! `--shard I/N` and `--merge DIR...` of the long drivers (`verify::shard`): on a tiny
//! configuration, two shards merged give the unsharded run's table, the same work units in
//! the same order with the same non-timing columns (timings differ from run to run), and bad
//! `--shard` values are usage errors that say what is wrong.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn output(bin: &str, args: &[&str], extra: &[&str]) -> Output {
    Command::new(bin)
        .args(args)
        .args(extra)
        .output()
        .expect("driver runs")
}

fn run(bin: &str, args: &[&str], extra: &[&str]) {
    let out = output(bin, args, extra);
    assert!(
        out.status.success(),
        "{bin} {args:?} {extra:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The CSV's columns `names` (by header), one vector per data row.
fn columns(path: &Path, names: &[&str]) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let at: Vec<usize> = names
        .iter()
        .map(|n| {
            header
                .iter()
                .position(|h| h == n)
                .unwrap_or_else(|| panic!("no column {n} in {header:?}"))
        })
        .collect();
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            at.iter().map(|&k| cells[k].to_owned()).collect()
        })
        .collect()
}

fn temp(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!("revdist-shard-{tag}-{}", std::process::id()))
}

/// Runs `bin args` unsharded, as shards 0/2 and 1/2, and merged; `csv` of the merge must
/// hold the unsharded run's rows in `same` (work units and non-timing columns). A merge
/// with `--seed 12345` added (other settings than the shards') must be refused. Returns the
/// merge's directory.
fn merged_equals_unsharded(
    tag: &str,
    bin: &str,
    args: &[&str],
    csv: &str,
    same: &[&str],
) -> PathBuf {
    let mut other = args.to_vec();
    other.extend(["--seed", "12345"]);
    merged_equals_unsharded_unless(tag, bin, (args, &other), csv, same)
}

/// [`merged_equals_unsharded`] with the arguments of the refused merge given (`other`).
fn merged_equals_unsharded_unless(
    tag: &str,
    bin: &str,
    (args, other): (&[&str], &[&str]),
    csv: &str,
    same: &[&str],
) -> PathBuf {
    let dirs: Vec<PathBuf> = ["whole", "s0", "s1", "merged"]
        .iter()
        .map(|d| temp(&format!("{tag}-{d}")))
        .collect();
    let s = |p: &PathBuf| p.to_str().expect("utf-8 path").to_owned();
    run(bin, args, &["--out", &s(&dirs[0])]);
    run(bin, args, &["--out", &s(&dirs[1]), "--shard", "0/2"]);
    run(bin, args, &["--out", &s(&dirs[2]), "--shard", "1/2"]);
    assert!(
        !dirs[1].join(csv).exists(),
        "a shard writes raw rows, not the table"
    );
    let list = format!("{},{}", s(&dirs[2]), s(&dirs[1]));
    run(bin, args, &["--out", &s(&dirs[3]), "--merge", &list]);
    let whole = columns(&dirs[0].join(csv), same);
    let merged = columns(&dirs[3].join(csv), same);
    assert!(!whole.is_empty());
    assert_eq!(
        merged, whole,
        "{bin}: merged shards vs unsharded ({same:?})"
    );
    // A merge with other settings than the shards' is refused.
    let out = output(bin, other, &["--out", &s(&dirs[3]), "--merge", &list]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("run with other settings"), "{err}");
    for d in &dirs[..3] {
        std::fs::remove_dir_all(d).unwrap();
    }
    dirs[3].clone()
}

#[test]
fn bad_shard_values_are_usage_errors() {
    for (bad, says) in [
        ("3/2", "need 0 <= I < N"),
        ("0/0", "need 0 <= I < N"),
        ("a/b", "'a' is not a whole number"),
        ("2", "not of the form I/N"),
    ] {
        let out = output(env!("CARGO_BIN_EXE_fcl_bench"), &["--shard", bad], &[]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("--shard") && err.contains(says),
            "{bad}: {err}"
        );
    }
}

#[test]
fn fcl_bench_shards_merge() {
    let dir = merged_equals_unsharded(
        "fcl_bench",
        env!("CARGO_BIN_EXE_fcl_bench"),
        &[
            "--pairs",
            "torus-torus,pawn-cup",
            "--eps",
            "1e-3,1e-4",
            "--poses",
            "3",
            "--poses-1e-5",
            "3",
        ],
        "fcl_bench.csv",
        &[
            "pair",
            "eps",
            "poses",
            "tris_balanced",
            "tris_capped",
            "h_sum_balanced",
            "h_sum_capped",
            "rev_max_width",
            "rev_query_tree_bytes",
            "obbrss_bytes_balanced",
            "rss_bytes_capped",
            "violations",
        ],
    );
    assert!(dir.join("fcl_bench.md").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn motion_shards_merge() {
    let dir = merged_equals_unsharded(
        "motion",
        env!("CARGO_BIN_EXE_motion"),
        &[
            "--frames",
            "4",
            "--eps",
            "1e-3,1e-4",
            "--pairs",
            "pawn-cup,torus-torus,cup-bottle",
        ],
        "motion.csv",
        &[
            "pair",
            "eps",
            "frames",
            "mean_node_pairs",
            "mean_leaf_tests",
            "min_distance",
            "violations",
        ],
    );
    assert!(dir.join("motion_eps1e-4.svg").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn deforming_shards_merge() {
    let dir = merged_equals_unsharded(
        "deforming",
        env!("CARGO_BIN_EXE_deforming"),
        &["--frames", "3", "--eps", "1e-3,2e-3,1e-4"],
        "deforming.csv",
        &[
            "static_model",
            "eps",
            "frames",
            "mt_triangles_mean",
            "gap_mean",
            "violations",
        ],
    );
    assert!(dir.join("deforming.svg").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn pareto_shards_merge() {
    // Three pairs over two shards; the triangle cap leaves FCL's finer levels out of the
    // bigger pairs, and the merged report lists them as the unsharded one does.
    let dir = merged_equals_unsharded(
        "pareto",
        env!("CARGO_BIN_EXE_pareto"),
        &[
            "--poses",
            "3",
            "--pairs",
            "torus-torus,pawn-cup,cup-bottle",
            "--eps",
            "1e-2,1e-3",
            "--refine-eps",
            "1e-3",
            "--fcl-eps",
            "1e-2,1e-3",
            "--max-triangles",
            "20000",
        ],
        "pareto.csv",
        &[
            "method",
            "pair",
            "eps",
            "poses",
            "mean_node_pairs",
            "zero_lower",
            "checks",
            "violations",
        ],
    );
    let md = std::fs::read_to_string(dir.join("pareto.md")).unwrap();
    let skipped: Vec<&str> = md
        .lines()
        .filter(|l| l.contains("not run: predicted"))
        .collect();
    assert!(!skipped.is_empty(), "the cap skipped no level: {md}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn stability_shards_merge() {
    // Every column but the time: the errors are deterministic (seeded cases, exact references).
    let dir = merged_equals_unsharded_unless(
        "stability",
        env!("CARGO_BIN_EXE_stability"),
        (&["--seeds", "1"], &["--seeds", "2"]),
        "stability.csv",
        &[
            "level",
            "family",
            "delta",
            "cases",
            "max_abs_error",
            "median_abs_error",
            "max_rel_error",
            "median_rel_error",
            "bound",
            "max_error_over_bound",
            "max_certified_width",
            "certificate_violations",
            "bound_exceeded",
        ],
    );
    assert!(dir.join("stability.svg").exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn peers_shards_merge_both_tables() {
    // The mesh table through the shared helper, then the convex table of the same runs'
    // settings (its own raw rows, peers_convex.rows.csv, split alike).
    let args = [
        "--poses",
        "3",
        "--parry-poses",
        "1",
        "--eps",
        "1e-3",
        "--pairs",
        "pawn-cup,torus-torus,cup-bottle",
    ];
    let bin = env!("CARGO_BIN_EXE_peers");
    let dir = merged_equals_unsharded(
        "peers",
        bin,
        &args,
        "peers.csv",
        &[
            "pair",
            "eps",
            "poses",
            "parry_poses",
            "triangles",
            "h_sum",
            "rev_bytes",
            "fcl_obbrss_bytes",
            "parry_bytes",
            "rev_max_width",
            "violations",
            "coal_status",
        ],
    );
    let whole = temp("peers-convex-whole");
    run(bin, &args, &["--out", whole.to_str().unwrap()]);
    let convex = [
        "pair",
        "poses",
        "parry_max_excess",
        "rev_max_width",
        "violations",
    ];
    let rows = columns(&dir.join("peers_convex.csv"), &convex);
    assert_eq!(rows.len(), 10);
    assert_eq!(rows, columns(&whole.join("peers_convex.csv"), &convex));
    assert!(dir.join("peers.svg").exists());
    for d in [dir, whole] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

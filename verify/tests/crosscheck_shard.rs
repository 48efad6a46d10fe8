//! `verify crosscheck --shard I/N` and `--merge DIR,...` (`verify::shard`): two shards of a
//! small run, merged, give the unsharded run's report (every count and worst case; only the
//! timings differ), and a merge with other settings is refused.

use std::path::PathBuf;
use std::process::Command;

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .expect("verify runs")
}

fn temp(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "verify-crosscheck-shard-{tag}-{}",
        std::process::id()
    ))
}

/// The data lines of a report's CSV (the `#` provenance lines differ: time, shards).
fn data(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_to_string(dir.join("crosscheck.csv"))
        .expect("the report's CSV")
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(str::to_owned)
        .collect()
}

#[test]
fn two_shards_merge_to_the_unsharded_report() {
    let run = [
        "crosscheck",
        "--poses",
        "30",
        "--convex-poses",
        "3",
        "--occt-poses",
        "0",
    ];
    let dirs: Vec<PathBuf> = ["whole", "s0", "s1", "merged"]
        .iter()
        .map(|t| temp(t))
        .collect();
    let s: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
    let ok = |extra: &[&str]| {
        let out = verify(&[&run[..], extra].concat());
        assert!(
            out.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    ok(&["--out", &s[0]]);
    ok(&["--out", &s[1], "--shard", "0/2"]);
    ok(&["--out", &s[2], "--shard", "1/2"]);
    assert!(!dirs[1].join("crosscheck.csv").exists());
    let list = format!("{},{}", s[1], s[2]);
    ok(&["--out", &s[3], "--merge", &list]);
    let whole = data(&dirs[0]);
    assert!(whole.len() > 40, "{whole:?}");
    assert_eq!(data(&dirs[3]), whole);
    assert_eq!(
        std::fs::read_to_string(dirs[3].join("failures.jsonl")).unwrap(),
        std::fs::read_to_string(dirs[0].join("failures.jsonl")).unwrap()
    );
    // Other settings than the shards' (another seed), or a shard missing: refused.
    let out = verify(&[&run[..], &["--seed", "7", "--out", &s[3], "--merge", &list]].concat());
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("`seed` is '1' there, '7'"));
    let out = verify(&[&run[..], &["--out", &s[3], "--merge", &s[1]]].concat());
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("shards [1] of 2 are missing"));
    let out = verify(&[&run[..], &["--shard", "2/2"]].concat());
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("need 0 <= I < N"));
    for d in dirs {
        std::fs::remove_dir_all(d).unwrap();
    }
}

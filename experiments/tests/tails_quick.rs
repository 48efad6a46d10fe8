//! A quick slice of the tail benchmark: `tails --poses 40` runs end to end, writes
//! `tails.csv` with its columns (found by header name) and one row per query, and `tails.md`
//! with its statistics; every reproducer line parses as a `revdist distance` command line
//! with the row's models, eps, tolerance and a pose of a translation and a unit quaternion.
//! When the `revdist` binary sits beside the driver (a workspace build), every reproducer
//! also runs through it.

use std::path::Path;
use std::process::Command;

const COLUMNS: [&str; 16] = [
    "index",
    "model_a",
    "model_b",
    "eps",
    "tolerance",
    "kind",
    "family",
    "gap",
    "time_us",
    "node_pairs",
    "leaf_tests",
    "lower",
    "upper",
    "overlap",
    "budget_exhausted",
    "reproducer",
];

/// The fields of one CSV line (RFC 4180 quotes: `"..."`, `""` for a quote inside).
fn fields(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    assert!(!quoted, "unterminated quote in {line}");
    out.push(cur);
    out
}

/// Words of a shell command line: blanks separate, single quotes group.
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut cur: Option<String> = None;
    let mut quoted = false;
    for c in line.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                cur.get_or_insert_with(String::new);
            }
            ' ' if !quoted => words.extend(cur.take()),
            _ => cur.get_or_insert_with(String::new).push(c),
        }
    }
    assert!(!quoted, "unterminated quote in {line}");
    words.extend(cur);
    words
}

/// `[x, y, ...]` after `"key":` in the pose JSON.
fn numbers(json: &str, key: &str) -> Vec<f64> {
    let start = json
        .find(&format!("\"{key}\":["))
        .unwrap_or_else(|| panic!("no {key} in {json}"))
        + key.len()
        + 4;
    let end = start + json[start..].find(']').expect("closing bracket");
    json[start..end]
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .unwrap_or_else(|e| panic!("{x}: {e}"))
        })
        .collect()
}

/// Checks one reproducer against its row; returns its arguments after `revdist`.
fn check_reproducer(line: &str, row: &[String], col: &dyn Fn(&str) -> usize) -> Vec<String> {
    let w = shell_words(line);
    assert_eq!(&w[..2], ["revdist", "distance"], "{line}");
    assert_eq!(w[2], row[col("model_a")], "{line}");
    assert_eq!(w[3], row[col("model_b")], "{line}");
    for m in &w[2..4] {
        assert!(
            revdist::models::model(m).is_ok(),
            "unknown model {m}: {line}"
        );
    }
    assert_eq!(w[4], "--eps");
    let eps: f64 = w[5].parse().expect("eps");
    let row_eps: f64 = row[col("eps")].parse().expect("row eps");
    assert_eq!(eps, row_eps, "{line}");
    let mut rest = &w[6..];
    if row[col("tolerance")] == "0" {
        assert_eq!(&rest[..2], ["--tolerance", "0"], "{line}");
        rest = &rest[2..];
    } else {
        assert_eq!(row[col("tolerance")], "default");
    }
    assert_eq!(rest.len(), 3, "{line}");
    assert_eq!(&rest[..2], ["--json", "--pose-b"], "{line}");
    let json = &rest[2];
    assert!(json.starts_with('{') && json.ends_with('}'), "{json}");
    let t = numbers(json, "translation");
    let q = numbers(json, "rotation");
    assert_eq!((t.len(), q.len()), (3, 4), "{json}");
    assert!(t.iter().chain(&q).all(|x| x.is_finite()), "{json}");
    let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(
        (norm - 1.0).abs() < 1e-9,
        "rotation not a unit quaternion: {json}"
    );
    w[1..].to_vec()
}

#[test]
fn tails_slice_writes_its_tables_and_reproducers() {
    let bin = env!("CARGO_BIN_EXE_tails");
    let dir = std::env::temp_dir().join(format!("revdist-tails-{}", std::process::id()));
    let out = Command::new(bin)
        .args(["--poses", "40", "--out"])
        .arg(&dir)
        .output()
        .expect("driver runs");
    assert!(
        out.status.success(),
        "tails failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("tails.csv")).unwrap();
    assert!(csv.starts_with("# experiment: tails"));
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header = fields(lines.next().expect("header"));
    for c in COLUMNS {
        assert!(header.iter().any(|h| h == c), "no column {c} in {header:?}");
    }
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<Vec<String>> = lines.map(fields).collect();
    assert_eq!(rows.len(), 40);
    let mut kinds = std::collections::BTreeSet::new();
    let mut commands = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r.len(), header.len(), "row {i}: {r:?}");
        assert_eq!(r[col("index")], i.to_string());
        kinds.insert(r[col("kind")].clone());
        let time: f64 = r[col("time_us")].parse().unwrap();
        let (lower, upper): (f64, f64) = (
            r[col("lower")].parse().unwrap(),
            r[col("upper")].parse().unwrap(),
        );
        assert!(
            time > 0.0 && 0.0 <= lower && lower <= upper,
            "row {i}: {r:?}"
        );
        assert!(r[col("node_pairs")].parse::<usize>().is_ok());
        assert!(["true", "false"].contains(&r[col("budget_exhausted")].as_str()));
        commands.push(check_reproducer(&r[col("reproducer")], r, &col));
    }
    // Every tenth query is degenerate, the kinds in turn: 4 of them in 40 queries.
    assert!(kinds.contains("random") && kinds.len() >= 5, "{kinds:?}");

    let md = std::fs::read_to_string(dir.join("tails.md")).unwrap();
    for needle in [
        "p99 / median",
        "| all | 40 |",
        "family: degenerate",
        "eps 1e-7",
        "The ten slowest queries",
        "`revdist distance ",
        "Provenance",
    ] {
        assert!(md.contains(needle), "tails.md lacks {needle:?}");
    }
    assert_eq!(md.matches("`revdist distance ").count(), 10);

    // The real command-line parser, when a workspace build left `revdist` beside the driver.
    let revdist = Path::new(bin).with_file_name("revdist");
    if revdist.is_file() {
        for args in &commands {
            let out = Command::new(&revdist).args(args).output().unwrap();
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(
                out.status.success() && stdout.contains("\"lower\""),
                "revdist {args:?}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
    } else {
        eprintln!(
            "no {} built: reproducers parsed, not run",
            revdist.display()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

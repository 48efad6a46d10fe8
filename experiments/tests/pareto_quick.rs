//! A tiny slice of the `pareto` driver: it writes every output, revdist's
//! certified width at its default tolerance is at most eps_a + eps_b, the width does not grow
//! as eps shrinks, and no revdist answer contradicts an FCL answer. The checks are plain
//! functions, and `checks_reject_bad_rows` shows that each one fails on rows that break it.

use std::path::PathBuf;
use std::process::Command;

/// Rounding allowance on a certified width: revdist widens its interval by its rounding slack
/// (`revdist::query::distance::query_slack`, about 1e-10 at these models' scale) on both
/// sides, so a width may exceed the requested eps_a + eps_b by that much.
const WIDTH_SLACK: f64 = 1e-9;

/// The columns of `pareto.csv` the checks read.
#[derive(Debug, Clone)]
struct Row {
    method: String,
    pair: String,
    eps: f64,
    width_max: f64,
    checks: usize,
    violations: usize,
}

fn parse(csv: &str) -> Result<Vec<Row>, String> {
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().ok_or("no header")?.split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .ok_or(format!("no column {name}"))
    };
    let (m, p, e, w, c, v) = (
        col("method")?,
        col("pair")?,
        col("eps")?,
        col("width_max")?,
        col("checks")?,
        col("violations")?,
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f.get(i).and_then(|x| x.parse::<f64>().ok());
            let int = |i: usize| f.get(i).and_then(|x| x.parse::<usize>().ok());
            Ok(Row {
                method: f.get(m).ok_or("short row")?.to_string(),
                pair: f.get(p).ok_or("short row")?.to_string(),
                eps: num(e).ok_or(format!("bad eps in '{l}'"))?,
                width_max: num(w).ok_or(format!("bad width in '{l}'"))?,
                checks: int(c).ok_or(format!("bad checks in '{l}'"))?,
                violations: int(v).ok_or(format!("bad violations in '{l}'"))?,
            })
        })
        .collect()
}

/// The properties the quick slice must have, for every pair in `pairs`.
fn check(rows: &[Row], pairs: &[&str]) -> Result<(), String> {
    for pair in pairs {
        let mut rev: Vec<&Row> = rows
            .iter()
            .filter(|r| r.pair == *pair && r.method == "revdist")
            .collect();
        if rev.len() < 2 {
            return Err(format!("{pair}: fewer than two revdist rows"));
        }
        if !rows
            .iter()
            .any(|r| r.pair == *pair && r.method.starts_with("fcl_"))
        {
            return Err(format!("{pair}: no FCL row"));
        }
        rev.sort_by(|x, y| y.eps.total_cmp(&x.eps));
        for r in &rev {
            if r.width_max.is_nan() || r.width_max > 2.0 * r.eps + WIDTH_SLACK {
                return Err(format!(
                    "{pair} eps {:e}: width {:e} above eps_a + eps_b",
                    r.eps, r.width_max
                ));
            }
        }
        for w in rev.windows(2) {
            if w[1].width_max > w[0].width_max * 1.01 + WIDTH_SLACK {
                return Err(format!(
                    "{pair}: width grew from {:e} (eps {:e}) to {:e} (eps {:e})",
                    w[0].width_max, w[0].eps, w[1].width_max, w[1].eps
                ));
            }
        }
    }
    for r in rows.iter().filter(|r| r.method.starts_with("revdist")) {
        if r.checks == 0 {
            return Err(format!(
                "{} {} {:e}: not cross-checked",
                r.method, r.pair, r.eps
            ));
        }
        if r.violations != 0 {
            return Err(format!(
                "{} {} {:e}: {} cross-check violations",
                r.method, r.pair, r.eps, r.violations
            ));
        }
    }
    Ok(())
}

fn out_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("revdist-pareto-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn quick_slice_writes_outputs_and_keeps_its_promises() {
    let out = out_dir("quick");
    let pairs = ["torus-torus", "pawn-cup"];
    let status = Command::new(env!("CARGO_BIN_EXE_pareto"))
        .args(["--poses", "3", "--pairs", &pairs.join(",")])
        .args(["--eps", "1e-2,1e-3,1e-4,1e-5", "--refine-eps", "1e-3"])
        .args(["--fcl-eps", "1e-2,1e-3", "--out"])
        .arg(&out)
        .status()
        .expect("pareto runs");
    assert!(status.success(), "pareto failed: {status}");
    for f in [
        "pareto.csv",
        "pareto.md",
        "pareto_time.svg",
        "pareto_build.svg",
        "pareto_memory.svg",
    ] {
        let len = std::fs::metadata(out.join(f)).map_or(0, |m| m.len());
        assert!(len > 200, "{f} missing or empty");
    }
    let csv = std::fs::read_to_string(out.join("pareto.csv")).unwrap();
    assert!(
        csv.starts_with("# experiment: pareto"),
        "provenance preamble"
    );
    let rows = parse(&csv).unwrap();
    // 4 eps x (default, tolerance 0) + 1 refined, and 2 eps x (OBBRSS, RSS), per pair.
    assert_eq!(rows.len(), 2 * (4 * 2 + 1 + 2 * 2), "rows: {rows:?}");
    check(&rows, &pairs).unwrap();
    let svg = std::fs::read_to_string(out.join("pareto_time.svg")).unwrap();
    assert!(svg.contains("certified error bound") && svg.contains("FCL OBBRSS"));
    let md = std::fs::read_to_string(out.join("pareto.md")).unwrap();
    assert!(md.contains("## pawn-cup") && md.contains("Provenance"));
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn checks_reject_bad_rows() {
    let row = |method: &str, eps: f64, width_max: f64, violations: usize| Row {
        method: method.into(),
        pair: "a-b".into(),
        eps,
        width_max,
        checks: 10,
        violations,
    };
    let good = vec![
        row("revdist", 1e-2, 1.5e-2, 0),
        row("revdist", 1e-3, 1.9e-3, 0),
        row("revdist", 1e-4, 3e-10, 0),
        row("fcl_obbrss", 1e-2, 1.9e-2, 0),
    ];
    check(&good, &["a-b"]).unwrap();
    let mut wide = good.clone();
    wide[1].width_max = 2.1e-3;
    assert!(check(&wide, &["a-b"]).unwrap_err().contains("above"));
    let mut grows = good.clone();
    grows[2].width_max = 1.95e-4;
    grows[1].width_max = 1e-4;
    assert!(check(&grows, &["a-b"]).unwrap_err().contains("grew"));
    let mut bad = good.clone();
    bad[0].violations = 1;
    assert!(check(&bad, &["a-b"]).unwrap_err().contains("violations"));
    assert!(check(&good[..3], &["a-b"]).unwrap_err().contains("no FCL"));
    assert!(check(&good, &["a-c"]).is_err());
}

#[test]
fn bad_arguments_fail_with_a_message() {
    for (args, msg) in [
        (
            vec!["--poses", "0"],
            "'--poses <N>': needs a positive integer",
        ),
        (
            vec!["--pairs", "pawn"],
            "'pawn' for '--pairs <a-b,...>': needs a model pair",
        ),
        (vec!["--pairs", "pawn-teapot"], "teapot"),
        (
            vec!["--eps", "1e-3,2"],
            "'2' for '--eps <E,...>': needs a number in (0, 1)",
        ),
        (vec!["--frobnicate"], "unexpected argument '--frobnicate'"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_pareto"))
            .args(&args)
            .arg("--out")
            .arg(out_dir("bad"))
            .output()
            .expect("pareto runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("error: ") && err.contains(msg),
            "{args:?}: {err}"
        );
    }
}

//! Quick slices of the motion (Figure 12) and deforming (Figure 8) drivers: they run end to
//! end, write their outputs and find no cross-check violation (the drivers exit non-zero on
//! any violation).

use std::process::Command;

fn run(bin: &str, args: &[&str], dir: &std::path::Path) {
    let out = Command::new(bin)
        .args(args)
        .arg("--out")
        .arg(dir)
        .output()
        .expect("driver runs");
    assert!(
        out.status.success(),
        "{bin} {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn data_rows(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// Index of the column named `name` in the CSV's header (the line after the `#` preamble).
fn column(csv: &str, name: &str) -> usize {
    let header = csv
        .lines()
        .find(|l| !l.starts_with('#'))
        .expect("a header line");
    header
        .split(',')
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {header}"))
}

#[test]
fn motion_slice_writes_outputs_without_violations() {
    let dir = std::env::temp_dir().join(format!("revdist-motion-{}", std::process::id()));
    run(
        env!("CARGO_BIN_EXE_motion"),
        &[
            "--frames",
            "6",
            "--eps",
            "1e-3",
            "--pairs",
            "pawn-cup,table-lightmill",
        ],
        &dir,
    );
    let csv = std::fs::read_to_string(dir.join("motion.csv")).unwrap();
    assert!(csv.starts_with("# experiment: motion"));
    let rows = data_rows(&csv);
    assert_eq!(rows.len(), 2);
    let (violations, min_gap) = (column(&csv, "violations"), column(&csv, "min_distance"));
    for r in &rows {
        assert_eq!(r[violations], "0", "violations in {r:?}");
        let min_distance: f64 = r[min_gap].parse().unwrap();
        assert!(min_distance > 0.0, "the motion touched: {r:?}");
    }
    assert!(dir.join("motion_eps1e-3.svg").exists());
    assert!(dir.join("motion.md").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn deforming_slice_writes_outputs_without_violations() {
    let dir = std::env::temp_dir().join(format!("revdist-deforming-{}", std::process::id()));
    run(
        env!("CARGO_BIN_EXE_deforming"),
        &["--frames", "3", "--eps", "1e-3"],
        &dir,
    );
    let csv = std::fs::read_to_string(dir.join("deforming.csv")).unwrap();
    let rows = data_rows(&csv);
    assert_eq!(rows.len(), 5, "one row per static model");
    let violations = column(&csv, "violations");
    for r in &rows {
        assert_eq!(r[violations], "0", "violations in {r:?}");
        // Rebuild included: FCL's frame costs at least its tessellation and BVH build.
        let (rev, fcl): (f64, f64) = (r[5].parse().unwrap(), r[9].parse().unwrap());
        assert!(rev > 0.0 && fcl > 0.0);
    }
    assert!(dir.join("deforming.svg").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

//! A quick slice of the penetration experiment: `penetration` at a tiny scale runs end to end
//! (with coal in its own process when it is installed) and writes its CSV, Markdown table and
//! figure; coal's signed queries against depths worked out by hand.

use experiments::peers::coal::CoalPeer;
use experiments::peers::convex::primitive;
use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use std::process::Command;

#[test]
fn penetration_slice_runs_and_writes_its_outputs() {
    let dir = std::env::temp_dir().join(format!("revdist-penetration-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_penetration"))
        .args([
            "--poses",
            "1",
            "--coal-poses",
            "2",
            "--eps",
            "1e-3",
            "--out",
        ])
        .arg(&dir)
        .output()
        .expect("penetration runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "penetration failed: {stderr}");
    let csv = std::fs::read_to_string(dir.join("penetration.csv")).unwrap();
    assert!(csv.starts_with("# experiment: penetration"));
    let rows: Vec<&str> = csv
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .collect();
    // 15 paper pairs and 5 balls, 6 levels, 1 pose; then 10 convex pairs x 2 poses with coal.
    let models = 20 * 6;
    assert!(
        rows.len() == models || rows.len() == models + 20,
        "{}",
        rows.len()
    );
    for r in &rows {
        let f: Vec<&str> = r.split(',').collect();
        let (lower, upper): (f64, f64) = (f[6].parse().unwrap(), f[7].parse().unwrap());
        assert!(lower.is_nan() || (0.0 <= lower && lower <= upper), "{r}");
        // cover_cells, then the lower bound's certificate (empty when certified apart).
        let cells: usize = f[13].parse().unwrap();
        let kinds = ["none", "point", "ball_covering", "translation_covering"];
        if lower.is_nan() {
            assert!(f[14].is_empty() && cells == 0, "{r}");
        } else {
            assert!(kinds.contains(&f[14]), "{r}");
            assert_eq!(f[14] == "none", lower == 0.0, "{r}");
            assert!(f[14] != "translation_covering" || cells > 0, "{r}");
        }
    }
    if rows.len() > models {
        assert!(
            rows[models..]
                .iter()
                .all(|r| r.contains(",inside,")
                    || r.contains(",coal below a certified common point,"))
        );
    }
    let md = std::fs::read_to_string(dir.join("penetration.md")).unwrap();
    assert!(md.contains("width target met"));
    assert!(dir.join("penetration.svg").exists());
}

#[test]
fn zero_poses_fail_with_a_message() {
    let dir = std::env::temp_dir().join(format!("revdist-penetration-bad-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_penetration"))
        .args(["--poses", "0", "--out"])
        .arg(&dir)
        .output()
        .expect("penetration runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("'--poses <N>': needs a positive integer"),
        "{err}"
    );
}

/// B at translation `t` (A at the identity), no rotation.
fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
}

#[test]
fn coal_signed_depths_of_spheres_and_stacked_cylinders() {
    let Ok(mut coal) = CoalPeer::start() else {
        eprintln!("coal missing: skipped (scripts/deps.sh installs it)");
        return;
    };
    for name in ["sphere", "cylinder"] {
        coal.primitive(name, &primitive(name).unwrap()).unwrap();
    }
    // Two balls of radius 0.75 with centres 0.5 apart: depth 1.5 - 0.5 = 1, normal +x.
    // Apart by 0.2: signed distance +0.2.
    let got = coal
        .signed_query("sphere", "sphere", &[at(0.5, 0.0, 0.0), at(1.7, 0.0, 0.0)])
        .unwrap();
    assert!((got[0].distance + 1.0).abs() < 1e-12, "{got:?}");
    let n = got[0].normal.unwrap();
    assert!((n[0] - 1.0).abs() < 1e-12 && n[1].abs() < 1e-12 && n[2].abs() < 1e-12);
    assert!((got[1].distance - 0.2).abs() < 1e-12, "{got:?}");
    // Cylinders (radius 0.5, height 1.5) on one axis, B raised by 1.2: they share a height of
    // 0.3, the shortest way out is along the axis (sideways takes 1.0): depth 0.3 (EPA,
    // within its tolerance 1e-6).
    let got = coal
        .signed_query("cylinder", "cylinder", &[at(0.0, 0.0, 1.2)])
        .unwrap();
    assert!((got[0].distance + 0.3).abs() < 1e-6, "{got:?}");
}

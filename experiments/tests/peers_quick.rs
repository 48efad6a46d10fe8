//! A quick slice of the peers benchmark: `peers` at a tiny scale runs end to end with coal (in
//! its own process) and parry3d, writes its CSVs, Markdown table and figure, and its
//! cross-checks pass; without coal it still runs and says how to get it. The coal process on
//! its own: its exact primitives against distances worked out by hand, its OBBRSS mesh
//! distance against FCL's on the same mesh (two implementations of the same quantity).

use experiments::peers::coal::{CoalPeer, MISSING_HINT, PROGRAM_ENV};
use experiments::peers::convex::Primitive;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::path::{Path, PathBuf};
use std::process::Command;

fn out_dir(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!("revdist-peers-{tag}-{}", std::process::id()))
}

/// The rows of a CSV with `#` provenance lines: header, then the records.
fn csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        text.starts_with("# experiment: peers"),
        "{}",
        path.display()
    );
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let split = |l: &str| l.split(',').map(str::to_owned).collect::<Vec<_>>();
    let header = split(lines.next().expect("header"));
    (header, lines.map(split).collect())
}

fn run_peers(dir: &Path, env: Option<(&str, &str)>) -> std::process::Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_peers"));
    cmd.args([
        "--poses",
        "6",
        "--parry-poses",
        "2",
        "--eps",
        "1e-3",
        "--pairs",
        "torus-torus,pawn-cup",
        "--out",
    ])
    .arg(dir);
    if let Some((k, v)) = env {
        cmd.env(k, v);
    }
    cmd.output().expect("peers runs")
}

#[test]
fn peers_slice_runs_every_peer_and_passes_its_cross_checks() {
    let dir = out_dir("all");
    let out = run_peers(&dir, None);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "peers failed: {stderr}");
    let (header, rows) = csv(&dir.join("peers.csv"));
    let col = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"))
    };
    assert_eq!(rows.len(), 2);
    for r in &rows {
        assert_eq!(r[col("coal_status")], "ran", "coal did not run: {stderr}");
        for c in [
            "rev_median_us",
            "fcl_obbrss_median_us",
            "fcl_rss_median_us",
            "coal_obbrss_median_us",
            "parry_median_us",
            "ratio_fastest_peer_over_rev",
        ] {
            let v: f64 = r[col(c)].parse().unwrap();
            assert!(v > 0.0 && v.is_finite(), "{c} = {v}");
        }
        assert_eq!(r[col("parry_poses")], "2");
        assert_eq!(r[col("violations")], "0");
        assert_eq!(
            r[col("occt_median_us")],
            "",
            "OCCT is a hook, not measured here"
        );
    }
    let (header, rows) = csv(&dir.join("peers_convex.csv"));
    assert_eq!(rows.len(), 10, "every unordered pair of 4 convex solids");
    let coal = header
        .iter()
        .position(|h| h == "coal_gjk_median_us")
        .unwrap();
    assert!(rows.iter().all(|r| r[coal].parse::<f64>().unwrap() > 0.0));
    let md = std::fs::read_to_string(dir.join("peers.md")).unwrap();
    assert!(md.contains("one-sided") && md.contains("coal OBBRSS"));
    let svg = std::fs::read_to_string(dir.join("peers.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("parry3d"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn missing_coal_is_said_not_a_failure() {
    let dir = out_dir("nocoal");
    let out = run_peers(&dir, Some((PROGRAM_ENV, "/nonexistent/coal_peer")));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "peers without coal failed: {stderr}");
    assert!(stderr.contains(MISSING_HINT), "{stderr}");
    let md = std::fs::read_to_string(dir.join("peers.md")).unwrap();
    assert!(md.contains(MISSING_HINT), "{md}");
    let (header, rows) = csv(&dir.join("peers.csv"));
    let status = header.iter().position(|h| h == "coal_status").unwrap();
    assert!(rows.iter().all(|r| r[status].contains(MISSING_HINT)));
    let _ = std::fs::remove_dir_all(&dir);
}

fn at(x: f64, y: f64, z: f64) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::new(x, y, z), UnitQuaternion::identity())
}

#[test]
fn coal_process_matches_hand_values_and_fcl() {
    let mut coal = CoalPeer::start().expect("coal built (scripts/deps.sh installs it)");
    assert_eq!(coal.version, "3.0.3");
    let cyl = Primitive::Cylinder {
        r: 0.5,
        lz: 1.5,
        zc: 0.75,
    };
    let cone = Primitive::Cone {
        r: 0.6,
        lz: 1.5,
        zc: 0.75,
    };
    coal.primitive("cyl", &cyl).unwrap();
    coal.primitive("cone", &cone).unwrap();
    // Side by side: 1.2 - 0.5 - 0.6; the cone's base disk 0.5 above the cylinder's top disk
    // (z 1.5); the cone turned upside down below the cylinder.
    let flip = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, -0.3),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
    );
    let d = coal
        .query("cyl", "cone", &[at(1.2, 0.0, 0.0), at(0.0, 0.0, 2.0), flip])
        .unwrap();
    // Flipped about x and lowered by 0.3, the cone's apex (local z 1.5) lands at z -1.8 and
    // its base (local z 0) at z -0.3: 0.3 below the cylinder's bottom disk.
    let expect = [0.1, 0.5, 0.3];
    for (a, e) in d.iter().zip(expect) {
        assert!((a.distance - e).abs() < 1e-6, "{} vs {e}", a.distance);
    }
    // The same certified torus mesh in coal and FCL: the same OBBRSS distance.
    let p = experiments::shapes::profile("torus").unwrap();
    let (cm, _) = experiments::baseline_mesh::certified_mesh(&p, 1e-2, None).unwrap();
    let fcl = experiments::baseline_mesh::obbrss_of(&cm).unwrap();
    coal.mesh("torus", &cm).unwrap();
    let poses = [
        at(2.6, 0.1, 0.0),
        Isometry3::from_parts(
            Translation3::new(0.4, -0.2, 1.2),
            UnitQuaternion::from_euler_angles(0.3, 0.2, -0.4),
        ),
    ];
    let c = coal.query("torus", "torus", &poses).unwrap();
    for (pose, a) in poses.iter().zip(&c) {
        let f = fcl
            .distance(&fcl, &Isometry3::identity(), pose)
            .unwrap()
            .distance;
        assert!(f > 0.0);
        assert!(
            (a.distance - f).abs() < 1e-9 * (1.0 + f),
            "coal {} vs FCL {f}",
            a.distance
        );
    }
}

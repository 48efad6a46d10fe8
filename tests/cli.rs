//! Integration tests of the `revdist` command-line program.

use std::path::PathBuf;
use std::process::{Command, Output};

fn revdist(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_revdist"))
        .args(args)
        .output()
        .expect("the revdist binary runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn models_lists_every_builtin_with_kind_pieces_and_height() {
    let out = revdist(&["models"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for name in revdist::models::model_names() {
        let line = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(*name))
            .unwrap_or_else(|| panic!("{name} missing from:\n{text}"));
        let fields: Vec<&str> = line.split_whitespace().collect();
        let expected = revdist::models::model(name).unwrap();
        assert_eq!(fields[2], expected.pieces().len().to_string(), "{line}");
        let height: f64 = fields[3].parse().unwrap();
        assert!((1.0..=2.0).contains(&height), "{line}");
        let kind = if *name == "ring" {
            "closed"
        } else {
            "open-on-axis"
        };
        assert_eq!(fields[1], kind, "{line}");
    }
    assert!(text.contains("morph@"), "{text}");
}

#[test]
fn profile_draws_an_svg_with_the_control_polygon() {
    let dir = scratch("profile");
    let svg = dir.join("pawn.svg");
    let out = revdist(&["profile", "pawn", "--svg", svg.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"), "{text}");
    assert!(text.trim_end().ends_with("</svg>"));
    // Nine pieces: nine curve polylines plus nine dashed control polygons.
    assert_eq!(text.matches("<polyline").count(), 18);
    assert!(text.contains("stroke-dasharray=\"3 2\""));
    assert!(text.contains(">pawn</text>"));
    let out = revdist(&[
        "profile",
        "morph@0.5",
        "--svg",
        dir.join("m.svg").to_str().unwrap(),
        "--no-control-polygon",
        "--mirror",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn export_and_reread_round_trips() {
    let dir = scratch("export");
    for name in revdist::models::model_names() {
        let toml = dir.join(format!("{name}.toml"));
        let out = revdist(&["export", name, "--toml", toml.to_str().unwrap()]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        let text = std::fs::read_to_string(&toml).unwrap();
        let read = revdist::profile_file::from_toml_str(&text).unwrap();
        assert_eq!(read, revdist::models::model(name).unwrap(), "{name}");
        // A file path is accepted wherever a model name is, and re-exports identically.
        let again = dir.join(format!("{name}-again.toml"));
        let out = revdist(&[
            "export",
            toml.to_str().unwrap(),
            "--toml",
            again.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
        assert_eq!(std::fs::read_to_string(&again).unwrap(), text);
        let svg = dir.join(format!("{name}.svg"));
        let out = revdist(&[
            "profile",
            toml.to_str().unwrap(),
            "--svg",
            svg.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{name}: {}", stderr(&out));
    }
}

#[test]
fn unknown_model_is_a_clear_error() {
    let dir = scratch("unknown");
    let out = revdist(&[
        "profile",
        "knight",
        "--svg",
        dir.join("k.svg").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.starts_with("error: unknown model 'knight'"), "{err}");
    assert!(err.contains("pawn, cup, bottle, table, lightmill"), "{err}");
    assert!(err.contains("no profile file 'knight'"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!dir.join("k.svg").exists());
    let out = revdist(&[
        "export",
        "morph@later",
        "--toml",
        dir.join("m.toml").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("bad morph parameter"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn malformed_files_are_clear_errors() {
    let dir = scratch("malformed");
    let cases = [
        ("syntax.toml", "name = \"x\"\n[[piece]\n", "malformed profile file"),
        (
            "unknown-field.toml",
            "name = \"x\"\ncolour = 3\n[[piece]]\ndegree = 1\nknots = [0, 0, 1, 1]\npoints = [[0, 0], [1, 0]]\n",
            "malformed profile file",
        ),
        (
            "not-closed.toml",
            "name = \"x\"\n[[piece]]\ndegree = 1\nknots = [0.0, 0.0, 1.0, 1.0]\npoints = [[0.5, 0.0], [1.0, 1.0]]\n",
            "invalid profile",
        ),
    ];
    for (file, text, expected) in cases {
        let path = dir.join(file);
        std::fs::write(&path, text).unwrap();
        let out = revdist(&[
            "profile",
            path.to_str().unwrap(),
            "--svg",
            dir.join("o.svg").to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(2), "{file}");
        let err = stderr(&out);
        assert!(err.starts_with("error: profile file '"), "{file}: {err}");
        assert!(err.contains(expected), "{file}: {err}");
        assert!(!err.contains("panicked"), "{file}: {err}");
    }
}

#[test]
fn usage_errors_exit_with_code_2() {
    let out = revdist(&["profile", "pawn"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--svg"), "{}", stderr(&out));
    let out = revdist(&["frobnicate"]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn unwritable_output_is_a_clear_error() {
    let dir = scratch("unwritable");
    let blocker = dir.join("file");
    std::fs::write(&blocker, "x").unwrap();
    // A directory cannot be created below a regular file.
    let target = blocker.join("sub").join("p.svg");
    let out = revdist(&["profile", "cup", "--svg", target.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).starts_with("error: cannot create directory"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn figures_draws_every_model_and_the_morph() {
    let dir = scratch("figures");
    let out = revdist(&["figures", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    for name in revdist::models::model_names() {
        let svg =
            std::fs::read_to_string(dir.join("profiles").join(format!("{name}.svg"))).unwrap();
        assert!(svg.contains(&format!(">{name}</text>")), "{name}");
    }
    let overview = std::fs::read_to_string(dir.join("profiles.svg")).unwrap();
    assert_eq!(
        overview.matches("<g transform").count(),
        revdist::models::model_names().len()
    );
    let morph = std::fs::read_to_string(dir.join("morph.svg")).unwrap();
    assert_eq!(morph.matches("<g transform").count(), 10);
    assert!(morph.contains(">morph@0.5</text>"), "frame names carry t");
}

//! `revdist toi` from the command line: a head-on approach of two balls against its closed
//! form, the gradient in `distance --json`, and errors that name the problem.

use std::process::Command;

fn revdist(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_revdist"))
        .args(args)
        .output()
        .expect("revdist runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn number(json: &str, key: &str) -> f64 {
    let v: serde_json::Value = serde_json::from_str(json).expect("json");
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {json}"))
}

#[test]
fn head_on_balls_bracket_the_closed_form() {
    // Balls of radius 0.75; B's centre from x = 3 to x = 0: contact at distance D = 0.1
    // when 3 - 3t = 1.6.
    let (ok, out, err) = revdist(&[
        "toi",
        "sphere",
        "sphere",
        "--pose-b",
        r#"{"translation": [3, 0, 0]}"#,
        "--pose-b-end",
        r#"{"translation": [0, 0, 0]}"#,
        "--contact-distance",
        "0.1",
        "--json",
    ]);
    assert!(ok, "{err}");
    let exact = (3.0 - 1.6) / 3.0;
    assert!(out.contains(r#""outcome":"contact""#), "{out}");
    assert!(
        number(&out, "t_lower") <= exact && exact <= number(&out, "t_upper"),
        "{out}"
    );
    assert!(number(&out, "upper_at_upper") <= 0.1, "{out}");
}

#[test]
fn distance_json_has_the_gradient_when_apart() {
    let (ok, out, err) = revdist(&[
        "distance",
        "sphere",
        "sphere",
        "--pose-b",
        r#"{"translation": [3, 0, 0]}"#,
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let n = &v["gradient"]["translation"];
    // Centres on the x axis: the normal is +x.
    assert!((n[0].as_f64().unwrap() - 1.0).abs() < 1e-9, "{out}");
    let (ok, out, _) = revdist(&["distance", "sphere", "sphere", "--json"]);
    assert!(ok && !out.contains("gradient"), "{out}");
}

#[test]
fn bad_inputs_name_the_problem() {
    let (ok, _, err) = revdist(&[
        "toi",
        "sphere",
        "cup",
        "--pose-b",
        "{}",
        "--contact-distance=-1",
    ]);
    assert!(!ok && err.contains("contact distance"), "{err}");
    let (ok, _, err) = revdist(&[
        "toi",
        "sphere",
        "cup",
        "--pose-b",
        "{}",
        "--pose-b-end",
        r#"{"rotation": [2, 0, 0, 0]}"#,
    ]);
    assert!(!ok && err.contains("--pose-b-end"), "{err}");
    let (ok, _, err) = revdist(&["toi", "sphere", "nonesuch", "--pose-b", "{}"]);
    assert!(!ok && err.contains("nonesuch"), "{err}");
}

/// `toi --batch`: one line out per line in, in order, each with its line number; the
/// answers equal single `toi --json` runs (less the timing); bad lines get their own error
/// line and exit status 1.
#[test]
fn batch_answers_every_line_like_single_runs() {
    let dir = std::env::temp_dir().join(format!("revdist_toi_batch_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("motions.jsonl");
    let good = [
        (
            r#"{"translation": [3, 0, 0]}"#,
            r#"{"translation": [0, 0, 0]}"#,
            "0.1",
        ),
        (
            r#"{"translation": [3, 0, 2]}"#,
            r#"{"translation": [-3, 0, 2]}"#,
            "0",
        ),
        (
            r#"{"translation": [0, 3, 0.2]}"#,
            r#"{"translation": [0.1, 0, 0]}"#,
            "0",
        ),
    ];
    let mut text = String::new();
    for (p0, p1, d) in good {
        text += &format!(
            "{{\"a\": \"sphere\", \"b\": \"pawn\", \"pose_b\": {p0}, \"pose_b_end\": {p1}, \"eps\": 0.001, \"contact_distance\": {d}}}\n"
        );
    }
    text += "{\"a\": \"sphere\", \"b\": \"pawn\"}\n\n";
    std::fs::write(&path, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_revdist"))
        .args(["toi", "--batch", path.to_str().unwrap(), "--threads", "2"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 5);
    for (i, (p0, p1, d)) in good.iter().enumerate() {
        assert_eq!(lines[i]["line"], i + 1);
        assert!(lines[i].get("time_us").is_none());
        let (ok, single, err) = revdist(&[
            "toi",
            "sphere",
            "pawn",
            "--pose-b",
            p0,
            "--pose-b-end",
            p1,
            "--eps",
            "0.001",
            "--contact-distance",
            d,
            "--json",
        ]);
        assert!(ok, "{err}");
        let mut single: serde_json::Value = serde_json::from_str(&single).unwrap();
        let mut batch = lines[i].clone();
        single.as_object_mut().unwrap().remove("time_us");
        batch.as_object_mut().unwrap().remove("line");
        assert_eq!(batch, single);
    }
    assert!(lines[3]["error"].as_str().unwrap().contains("pose_b"));
    assert!(lines[4]["error"].as_str().unwrap().contains("blank line"));
    let _ = std::fs::remove_dir_all(&dir);
}

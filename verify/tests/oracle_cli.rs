//! `verify oracle` loads every shape by the name the campaigns print (the reproducer lines of
//! `verify queries --primitives` name the primitives), and refuses an unknown name with the
//! list of accepted ones.

use std::process::Command;

fn oracle(a: &str, b: &str) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["oracle", a, b, "--pose-b", r#"{"translation": [0, 0, 5]}"#])
        .output()
        .expect("verify runs")
}

#[test]
fn pool_names_load() {
    for (a, b) in [
        ("prim-ball-big", "prim-torus-thin"),
        ("rand-s5-3", "frozen-rand-s1-25"),
        ("straight-span", "morph@0.35"),
    ] {
        let out = oracle(a, b);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success() && stdout.contains("no violations"),
            "{a} {b}: {stdout}{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn unknown_name_lists_the_accepted_ones() {
    let out = oracle("prim-ball-huge", "sphere");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("unknown shape 'prim-ball-huge'"), "{err}");
    for name in [
        "sphere",
        "prim-ball-big",
        "frozen-rand-s1-25",
        "rand-s<SEED>-<K>",
        "morph@T",
    ] {
        assert!(err.contains(name), "{name} missing from: {err}");
    }
}

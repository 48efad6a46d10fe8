//! The fixed regression cases: the cases that failed before the certificates were made
//! rigorous (M_t against a sphere, an exactly straight span) and the failures the campaign
//! found against earlier cores, read from `verify/regressions/campaign-cases.txt` with the
//! random profiles frozen beside it (`<name>.toml`). `cases.jsonl` there replays the same
//! cases with `revdist distance --batch` (a test keeps it in step).

use super::cases::{Case, PoseKind, PoseSpec};
use super::pool::{Shape, FROZEN_PREFIX};
use revdist::profile::Profile;
use std::path::PathBuf;

/// The folder of the frozen data (`verify/regressions/`).
fn regressions_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("regressions")
}

/// The list of fixed cases.
const CASES_FILE: &str = "campaign-cases.txt";

/// One line of the case list: shape names, pose of B, eps and what went wrong.
#[derive(Debug, Clone)]
struct FrozenCase {
    a: String,
    b: String,
    pose: PoseSpec,
    eps: f64,
    note: String,
}

/// Whether a shape name is a random profile frozen as `<name>.toml`.
fn is_frozen_profile(name: &str) -> bool {
    name.starts_with("rand")
}

/// `n` numbers separated by blanks.
fn numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N], String> {
    let values: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().map_err(|e| format!("{what}: '{w}': {e}")))
        .collect::<Result<_, _>>()?;
    values
        .try_into()
        .map_err(|v: Vec<f64>| format!("{what}: expected {N} numbers, got {}", v.len()))
}

/// One case line: `A B | tx ty tz | w x y z | eps | note`.
fn parse_line(line: &str) -> Result<FrozenCase, String> {
    let fields: Vec<&str> = line.splitn(5, '|').collect();
    let [names, translation, rotation, eps, note] = fields[..] else {
        return Err(format!(
            "expected 5 fields separated by '|', got {}",
            fields.len()
        ));
    };
    let names: Vec<&str> = names.split_whitespace().collect();
    let [a, b] = names[..] else {
        return Err(format!("expected 2 shape names, got {}", names.len()));
    };
    let [eps] = numbers::<1>(eps, "eps")?;
    Ok(FrozenCase {
        a: a.to_string(),
        b: b.to_string(),
        pose: PoseSpec {
            translation: numbers(translation, "translation")?,
            rotation: numbers(rotation, "rotation")?,
        },
        eps,
        note: note.trim().to_string(),
    })
}

/// The case list, in order (`#` starts a comment line).
fn frozen_cases() -> Vec<FrozenCase> {
    let path = regressions_dir().join(CASES_FILE);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read '{}': {e}", path.display()));
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty() && !line.trim_start().starts_with('#'))
        .map(|(k, line)| {
            parse_line(line).unwrap_or_else(|e| panic!("{}:{}: {e}", path.display(), k + 1))
        })
        .collect()
}

/// The frozen random profiles the cases use, by name, in order of first use.
pub(super) fn frozen_profiles() -> Vec<(String, Profile)> {
    let mut names: Vec<String> = Vec::new();
    for c in frozen_cases() {
        for n in [c.a, c.b] {
            if is_frozen_profile(&n) && !names.contains(&n) {
                names.push(n);
            }
        }
    }
    names
        .into_iter()
        .map(|name| {
            let path = regressions_dir().join(format!("{name}.toml"));
            let text = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("cannot read '{}': {e}", path.display()));
            let p = revdist::profile_file::from_toml_str_allowing_self_contact(&text)
                .unwrap_or_else(|e| panic!("frozen profile '{}': {e}", path.display()));
            (name, p)
        })
        .collect()
}

/// The pool name of a case's shape (frozen random profiles are `frozen-<name>`).
fn pool_name(name: &str) -> String {
    if is_frozen_profile(name) {
        format!("{FROZEN_PREFIX}{name}")
    } else {
        name.to_string()
    }
}

impl FrozenCase {
    /// The case with label `R{k}` between pool shapes `a` and `b`.
    fn case(&self, k: usize, a: usize, b: usize) -> Case {
        Case {
            id: usize::MAX - k,
            kind: PoseKind::Regression,
            a,
            b,
            pose: self.pose,
            eps: self.eps,
            tolerance: Some(0.0),
            refine: false,
            note: self.note.clone(),
        }
    }
}

/// The fixed regression cases (labels `R0`, `R1`, ... in file order), on the pool's shapes.
pub fn regression_cases(shapes: &[Shape]) -> Vec<Case> {
    let find = |n: &str| {
        let n = pool_name(n);
        shapes.iter().position(|s| s.name == n).expect("in pool")
    };
    frozen_cases()
        .iter()
        .enumerate()
        .map(|(k, c)| c.case(k, find(&c.a), find(&c.b)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How `revdist distance` loads a shape from the workspace root (`None`: it cannot).
    fn replay_spec(name: &str) -> Option<String> {
        if is_frozen_profile(name) {
            Some(format!("verify/regressions/{name}.toml"))
        } else if revdist::models::model(name).is_ok() {
            Some(name.to_string())
        } else {
            None
        }
    }

    /// `cases.jsonl` holds one batch line per fixed case whose shapes `revdist distance`
    /// can load (all but the straight-span profile's), in the case list's order.
    #[test]
    fn replay_file_matches_the_case_list() {
        let mut expected = String::new();
        for (k, c) in frozen_cases().iter().enumerate() {
            if let (Some(a), Some(b)) = (replay_spec(&c.a), replay_spec(&c.b)) {
                expected.push_str(&c.case(k, 0, 0).batch_line(&a, &b));
                expected.push('\n');
            }
        }
        let path = regressions_dir().join("cases.jsonl");
        let found = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            found,
            expected,
            "{} should read:\n{expected}",
            path.display()
        );
    }

    #[test]
    fn case_lines_parse_and_name_their_problems() {
        let c = parse_line("ring sphere | 0 0 0.5 | 1 0 0 0 | 1e-4 | far (|t| ~ 1): note").unwrap();
        assert_eq!((c.a.as_str(), c.b.as_str()), ("ring", "sphere"));
        assert_eq!(c.pose.translation, [0.0, 0.0, 0.5]);
        assert_eq!(c.note, "far (|t| ~ 1): note");
        let e = parse_line("ring sphere | 0 0 | 1 0 0 0 | 1e-4 | x").unwrap_err();
        assert!(e.contains("translation: expected 3 numbers, got 2"), "{e}");
        assert!(parse_line("ring | 0 0 0 | 1 0 0 0 | 1e-4 | x").is_err());
        assert_eq!(frozen_cases().len(), 23);
        assert_eq!(frozen_profiles().len(), 22);
    }
}

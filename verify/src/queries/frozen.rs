//! The frozen data of the fixed regression cases (`verify/regressions/`): the case list
//! `campaign-cases.txt` (shape names, pose of B, eps and what went wrong) and the random
//! profiles frozen beside it (`<name>.toml`).

use super::pose_spec::PoseSpec;
use revdist::profile::Profile;
use std::path::PathBuf;

/// The folder of the frozen data (`verify/regressions/`).
pub(super) fn regressions_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("regressions")
}

/// The list of fixed cases.
const CASES_FILE: &str = "campaign-cases.txt";

/// One line of the case list: shape names, pose of B, eps and what went wrong.
#[derive(Debug, Clone)]
pub(super) struct FrozenCase {
    pub(super) a: String,
    pub(super) b: String,
    pub(super) pose: PoseSpec,
    pub(super) eps: f64,
    pub(super) note: String,
}

/// Whether a shape name is a random profile frozen as `<name>.toml`.
pub(super) fn is_frozen_profile(name: &str) -> bool {
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
pub(super) fn frozen_cases() -> Vec<FrozenCase> {
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

#[cfg(test)]
mod tests {
    use super::*;

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

//! The fixed regression cases: the cases that failed before the certificates were made
//! rigorous (M_t against a sphere, an exactly straight span) and the failures the campaign
//! found against earlier cores, as campaign cases on the pool's shapes. Their list
//! (`verify/regressions/campaign-cases.txt`) and the random profiles frozen beside it are
//! read by `frozen.rs`; `cases.jsonl` there replays the same cases with
//! `revdist distance --batch` (a test keeps it in step).

use super::cases::{Case, PoseKind};
use super::frozen::{frozen_cases, is_frozen_profile, FrozenCase};
use super::pool::{Shape, FROZEN_PREFIX};

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
    use super::super::frozen::regressions_dir;
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
}

//! The command-line flags the drivers share, each with one meaning in every driver. A driver
//! flattens [`Common`] (all six) or the pieces it uses (`#[command(flatten)]`); a flag a
//! driver has no use for is then rejected instead of ignored. Defaults that differ between
//! drivers (how many poses, which eps) are the driver's: the pieces hold what was given.

use crate::args::{accuracy, model_pair, positive_count, seed, ModelPair};
use clap::Args;
use std::path::PathBuf;

/// Id of the `--out` argument: [`crate::driver`] creates that folder before a driver runs.
pub const OUT_ID: &str = "out";

/// `--out DIR`: where the outputs go.
#[derive(Args, Debug, Clone)]
pub struct Out {
    /// Folder to write the outputs to (created if missing)
    #[arg(long = "out", id = OUT_ID, value_name = "DIR", default_value = "figures")]
    pub dir: PathBuf,
}

/// The values given, or `default` when none were.
pub fn given_or<T: Clone>(given: &[T], default: &[T]) -> Vec<T> {
    if given.is_empty() { default } else { given }.to_vec()
}

/// `--eps E[,E...]`: the accuracies to run at.
#[derive(Args, Debug, Clone)]
pub struct Eps {
    /// Accuracies in (0, 1), comma-separated or repeated [default: the driver's list]
    #[arg(long = "eps", id = "eps", value_name = "E,...", value_delimiter = ',',
          value_parser = accuracy)]
    pub list: Vec<f64>,
}

impl Eps {
    /// The accuracies given, or `default` when none were.
    pub fn or(&self, default: &[f64]) -> Vec<f64> {
        given_or(&self.list, default)
    }
}

/// `--pairs a-b[,c-d...]`: the model pairs to run.
#[derive(Args, Debug, Clone)]
pub struct Pairs {
    /// Model pairs a-b, comma-separated or repeated [default: the driver's list]
    #[arg(long = "pairs", id = "pairs", value_name = "a-b,...", value_delimiter = ',',
          value_parser = model_pair)]
    pub list: Vec<ModelPair>,
}

impl Pairs {
    /// The pairs given, or `default` when none were.
    pub fn or(&self, default: &[ModelPair]) -> Vec<ModelPair> {
        given_or(&self.list, default)
    }
}

/// `--poses N`: seeded poses per pair.
#[derive(Args, Debug, Clone)]
pub struct Poses {
    /// Seeded poses per pair (a positive integer) [default: the driver's]
    #[arg(long = "poses", id = "poses", value_name = "N", value_parser = positive_count)]
    pub count: Option<usize>,
}

impl Poses {
    /// The count given, or `default`.
    pub fn or(&self, default: usize) -> usize {
        self.count.unwrap_or(default)
    }
}

/// `--paper`: the paper's scale.
#[derive(Args, Debug, Clone)]
pub struct Paper {
    /// Run at the paper's scale (far more poses, frames or seeds; hours rather than minutes)
    #[arg(long = "paper", id = "paper")]
    pub on: bool,
}

impl Paper {
    /// `paper` at the paper's scale, else `default`.
    pub fn pick<T>(&self, default: T, paper: T) -> T {
        if self.on {
            paper
        } else {
            default
        }
    }
}

/// `--seed S`: the base seed of the random poses or cases.
#[derive(Args, Debug, Clone)]
pub struct Seed {
    /// Base seed of the random poses or cases, decimal or 0x hex [default: the driver's fixed seed]
    #[arg(long = "seed", id = "seed", value_name = "S", value_parser = seed)]
    pub value: Option<u64>,
}

impl Seed {
    /// The seed given, or `default`.
    pub fn or(&self, default: u64) -> u64 {
        self.value.unwrap_or(default)
    }
}

/// `--frames N` and `--frames-1e-5 N`: frames of a motion or deformation, at eps >= 5e-5 and
/// below (where the baselines are slowest, so fewer).
#[derive(Args, Debug, Clone)]
pub struct Frames {
    /// Frames per pair at eps >= 5e-5 [default: the driver's]
    #[arg(long = "frames", id = "frames", value_name = "N", value_parser = positive_count)]
    pub coarse: Option<usize>,
    /// Frames per pair at eps < 5e-5 [default: the driver's]
    #[arg(long = "frames-1e-5", id = "frames_fine", value_name = "N",
          value_parser = positive_count)]
    pub fine: Option<usize>,
}

impl Frames {
    /// The (coarse, fine) counts given, each falling back to its default.
    pub fn or(&self, (coarse, fine): (usize, usize)) -> (usize, usize) {
        (self.coarse.unwrap_or(coarse), self.fine.unwrap_or(fine))
    }
}

/// Below this eps a driver runs its fine count of poses or frames (`--frames-1e-5`,
/// `--poses-1e-5`).
pub const FINE_EPS: f64 = 5e-5;

/// The count of a (coarse, fine) pair that applies at `eps`.
pub fn count_at(eps: f64, (coarse, fine): (usize, usize)) -> usize {
    if eps < FINE_EPS {
        fine
    } else {
        coarse
    }
}

/// All six shared flags.
#[derive(Args, Debug, Clone)]
pub struct Common {
    #[command(flatten)]
    pub out: Out,
    #[command(flatten)]
    pub eps: Eps,
    #[command(flatten)]
    pub pairs: Pairs,
    #[command(flatten)]
    pub poses: Poses,
    #[command(flatten)]
    pub paper: Paper,
    #[command(flatten)]
    pub seed: Seed,
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::error::ErrorKind;
    use clap::Parser;

    #[derive(Parser, Debug)]
    struct Demo {
        #[command(flatten)]
        common: Common,
    }

    fn parse(args: &[&str]) -> Result<Demo, clap::Error> {
        Demo::try_parse_from(std::iter::once("demo").chain(args.iter().copied()))
    }

    #[test]
    fn defaults_and_values() {
        let d = parse(&[]).unwrap().common;
        assert_eq!(d.out.dir, PathBuf::from("figures"));
        assert_eq!(d.eps.or(&[1e-3]), vec![1e-3]);
        assert_eq!(d.poses.or(7), 7);
        assert_eq!(d.seed.or(9), 9);
        assert!(!d.paper.on);
        let d = parse(&[
            "--out",
            "x",
            "--eps",
            "1e-3,1e-4",
            "--eps",
            "1e-5",
            "--pairs",
            "pawn-cup",
            "--poses",
            "3",
            "--paper",
            "--seed",
            "0x10",
        ])
        .unwrap()
        .common;
        assert_eq!(d.out.dir, PathBuf::from("x"));
        assert_eq!(d.eps.list, vec![1e-3, 1e-4, 1e-5]);
        assert_eq!(d.pairs.list, vec![("pawn".into(), "cup".into())]);
        assert_eq!((d.poses.or(7), d.seed.or(9), d.paper.on), (3, 16, true));
        assert_eq!(d.paper.pick(1, 2), 2);
    }

    #[test]
    fn bad_values_are_errors() {
        for bad in [
            &["--eps", "2"][..],
            &["--eps", "1e-3,0"],
            &["--poses", "0"],
            &["--poses", "x"],
            &["--pairs", "pawn"],
            &["--seed", "0xzz"],
        ] {
            let e = parse(bad).unwrap_err();
            assert_eq!(e.kind(), ErrorKind::ValueValidation, "{bad:?}");
            assert!(e.to_string().contains(bad[0]), "{bad:?}: {e}");
        }
    }

    #[test]
    fn flag_without_value_is_an_error_not_a_panic() {
        for flag in ["--out", "--eps", "--pairs", "--poses", "--seed"] {
            let e = parse(&[flag]).unwrap_err();
            assert_eq!(e.kind(), ErrorKind::InvalidValue, "{flag}");
        }
    }

    #[test]
    fn help_is_help_not_a_folder() {
        let e = parse(&["--help"]).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::DisplayHelp);
        // A positional folder is gone: a stray word is an error, not the output folder.
        assert_eq!(
            parse(&["figures"]).unwrap_err().kind(),
            ErrorKind::UnknownArgument
        );
    }
}

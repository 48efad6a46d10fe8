//! The `main` of every driver: parse the command line, create the output folder (the value
//! of the shared `--out` flag, [`crate::cli::Out`], if the driver has it), run, and turn the
//! outcome into an exit status.
//!
//! Exit status: 0 on success and for `--help`; 1 when the run finished and wrote its outputs
//! but a check failed ([`CheckFailed`]); 2 on a usage error or any other error, printed as
//! `error: ...` on stderr.

use crate::cli::OUT_ID;
use clap::Parser;
use std::error::Error;
use std::fmt;
use std::path::PathBuf;

/// What a driver's body returns.
pub type DriverResult = Result<(), Box<dyn Error>>;

/// A run that completed and wrote its outputs, but whose results failed a check (e.g. a
/// cross-check violation): exit status 1.
#[derive(Debug)]
pub struct CheckFailed(pub String);

impl fmt::Display for CheckFailed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl Error for CheckFailed {}

/// `Ok` when a run's cross-checks found no violation, else a [`CheckFailed`] with their
/// count and `detail` (where to look).
pub fn check_violations(count: usize, detail: &str) -> DriverResult {
    match count {
        0 => Ok(()),
        n => Err(CheckFailed(format!("{n} cross-check violations {detail}")).into()),
    }
}

/// Parses the process's arguments into `A`, creates its output folder, runs `body` and exits
/// with the status described in the module documentation.
pub fn run<A: Parser>(body: impl FnOnce(A) -> DriverResult) -> ! {
    std::process::exit(run_with(std::env::args_os(), body))
}

/// [`run`] on the given command line (program name first), returning the exit status.
pub fn run_with<A: Parser>(
    argv: impl IntoIterator<Item = impl Into<std::ffi::OsString> + Clone>,
    body: impl FnOnce(A) -> DriverResult,
) -> i32 {
    let mut command = A::command();
    let parsed = command
        .try_get_matches_from_mut(argv)
        .and_then(|m| Ok((A::from_arg_matches(&m)?, out_dir(&m))))
        .map_err(|e| e.format(&mut command));
    let (args, out_dir) = match parsed {
        Ok(parsed) => parsed,
        Err(e) => {
            // clap prints help to stdout and errors (`error: ...`, with usage) to stderr.
            let _ = e.print();
            return e.exit_code();
        }
    };
    let outcome = match &out_dir {
        Some(dir) => std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()).into()),
        None => Ok(()),
    }
    .and_then(|()| body(args));
    status(outcome)
}

/// The `--out` folder, if the driver has the flag.
fn out_dir(matches: &clap::ArgMatches) -> Option<PathBuf> {
    matches
        .try_get_one::<PathBuf>(OUT_ID)
        .ok()
        .flatten()
        .cloned()
}

/// The exit status of an outcome, printing the error if any.
fn status(outcome: DriverResult) -> i32 {
    match outcome {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("error: {e}");
            if e.is::<CheckFailed>() {
                1
            } else {
                2
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::{Out, Poses};

    #[derive(Parser)]
    struct Demo {
        #[command(flatten)]
        out: Out,
    }

    /// A driver that only prints.
    #[derive(Parser)]
    struct Printer {
        #[command(flatten)]
        poses: Poses,
    }

    fn temp(tag: &str) -> PathBuf {
        std::env::temp_dir().join(format!("experiments-driver-{tag}-{}", std::process::id()))
    }

    #[test]
    fn creates_the_folder_and_runs() {
        let dir = temp("ok");
        let mut seen = None;
        let code = run_with(["demo", "--out", dir.to_str().unwrap()], |a: Demo| {
            seen = Some(a.out.dir.is_dir());
            Ok(())
        });
        assert_eq!((code, seen), (0, Some(true)));
        std::fs::remove_dir_all(&dir).unwrap();
        let code = run_with(["printer", "--poses", "3"], |p: Printer| {
            assert_eq!(p.poses.count, Some(3));
            Ok(())
        });
        assert_eq!(code, 0);
    }

    #[test]
    fn errors_become_exit_statuses() {
        let dir = temp("err");
        let d = dir.to_str().unwrap();
        assert_eq!(
            run_with(["demo", "--out", d], |_: Demo| Err("boom".into())),
            2
        );
        let failed = |_: Demo| check_violations(3, "(see above)");
        assert_eq!(run_with(["demo", "--out", d], failed), 1);
        assert_eq!(
            run_with(["demo", "--out", d], |_: Demo| check_violations(0, "")),
            0
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn usage_errors_and_help_do_not_run_the_body() {
        let never = |_: Demo| -> DriverResult { panic!("the body ran") };
        assert_eq!(run_with(["demo", "--out"], never), 2);
        assert_eq!(run_with(["demo", "stray"], never), 2);
        assert_eq!(run_with(["demo", "--help"], never), 0);
    }
}

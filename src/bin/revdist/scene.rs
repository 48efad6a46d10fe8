//! `revdist scene FILE [ARGS...]`: runs a scene through the `revdist-scene` executable of the
//! scene crate, found next to this one (a git-style external subcommand, so that the core
//! crate stays free of the scene crate's dependencies).

use crate::CmdResult;
use std::ffi::OsString;
use std::process::Command;

/// Arguments, forwarded unchanged to `revdist-scene` (see `revdist-scene --help`).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The scene file and the scene runner's options (e.g. `--out DIR`, `--duration S`).
    #[arg(trailing_var_arg = true, allow_hyphen_values = true, required = true)]
    args: Vec<OsString>,
}

pub fn run(args: Args) -> CmdResult {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate revdist: {e}"))?;
    let runner = exe.with_file_name(format!("revdist-scene{}", std::env::consts::EXE_SUFFIX));
    if !runner.is_file() {
        return Err(format!(
            "the scene runner '{}' is not built; build it with `cargo build --release -p revdist-scene`",
            runner.display()
        )
        .into());
    }
    let status = Command::new(&runner)
        .args(&args.args)
        .status()
        .map_err(|e| format!("cannot run '{}': {e}", runner.display()))?;
    if status.success() {
        Ok(())
    } else {
        // The runner printed its own error.
        std::process::exit(status.code().unwrap_or(2));
    }
}

//! `revdist export NAME --toml OUT`: write a profile as a TOML profile file.

use std::io::Write;
use std::path::PathBuf;

use revdist::profile_file::to_toml_string;

use crate::input::{load_profile, write_file};
use crate::CmdResult;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Built-in model name (see `revdist models`), or a profile file to re-write.
    profile: String,
    /// Output TOML file.
    #[arg(long)]
    toml: PathBuf,
}

pub fn run(args: Args) -> CmdResult {
    let profile = load_profile(&args.profile)?;
    write_file(&args.toml, &to_toml_string(&profile))?;
    writeln!(std::io::stdout(), "wrote {}", args.toml.display())?;
    Ok(())
}

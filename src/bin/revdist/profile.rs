//! `revdist profile NAME|FILE --svg OUT`: draw a profile and its control polygon.

use std::io::Write;
use std::path::PathBuf;

use revdist::svg::{profiles_svg, ProfileSvgOptions};

use crate::input::{load_profile, write_file};
use crate::CmdResult;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Built-in model name (see `revdist models`) or profile file.
    profile: String,
    /// Output SVG file.
    #[arg(long)]
    svg: PathBuf,
    /// Also draw the mirror image across the axis.
    #[arg(long)]
    mirror: bool,
    /// Leave out the control polygon.
    #[arg(long)]
    no_control_polygon: bool,
}

pub fn run(args: Args) -> CmdResult {
    let profile = load_profile(&args.profile)?;
    let options = ProfileSvgOptions {
        mirror: args.mirror,
        control_polygon: !args.no_control_polygon,
        ..ProfileSvgOptions::default()
    };
    write_file(&args.svg, &profiles_svg(&[&profile], &options))?;
    writeln!(std::io::stdout(), "wrote {}", args.svg.display())?;
    Ok(())
}

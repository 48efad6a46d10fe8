//! `revdist figures --out DIR`: draw every built-in model into `DIR/profiles/<name>.svg`,
//! an overview `DIR/profiles.svg`, and frames of the deformable model M_t `DIR/morph.svg`.

use std::io::Write;
use std::path::PathBuf;

use revdist::models::{self, model_names};
use revdist::profile::Profile;
use revdist::svg::{profile_grid_svg, profiles_svg, ProfileSvgOptions};

use crate::input::write_file;
use crate::CmdResult;

/// Frames of M_t drawn in `morph.svg`: t = k / MORPH_FRAMES.
const MORPH_FRAMES: usize = 10;
/// Polyline samples per knot span in the small overview drawings (a quarter-circle span of
/// 100 pixels radius deviates by about 0.1 pixel from its 16-segment polyline).
const CELL_SAMPLES_PER_SPAN: usize = 16;
/// Drawings per row of the overview figures.
const COLUMNS: usize = 5;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output directory (created if missing).
    #[arg(long, default_value = "figures")]
    out: PathBuf,
}

pub fn run(args: Args) -> CmdResult {
    let profiles = model_names()
        .iter()
        .map(|name| models::model(name))
        .collect::<Result<Vec<Profile>, _>>()?;
    let single = ProfileSvgOptions {
        mirror: true,
        ..ProfileSvgOptions::default()
    };
    for profile in &profiles {
        let path = args
            .out
            .join("profiles")
            .join(format!("{}.svg", profile.name()));
        write_file(&path, &profiles_svg(&[profile], &single))?;
    }
    let cell = ProfileSvgOptions {
        width: 240.0,
        height: 300.0,
        mirror: true,
        control_polygon: false,
        samples_per_span: CELL_SAMPLES_PER_SPAN,
        ..ProfileSvgOptions::default()
    };
    let refs: Vec<&Profile> = profiles.iter().collect();
    let overview = profile_grid_svg(&refs, COLUMNS, "revdist built-in profiles (rho, z)", &cell);
    write_file(&args.out.join("profiles.svg"), &overview)?;
    let frames = (0..MORPH_FRAMES)
        .map(|k| models::morph(k as f64 / MORPH_FRAMES as f64))
        .collect::<Result<Vec<Profile>, _>>()?;
    let refs: Vec<&Profile> = frames.iter().collect();
    let morph = profile_grid_svg(
        &refs,
        COLUMNS,
        "deformable model M_t, t = 0, 0.1, ..., 0.9",
        &cell,
    );
    write_file(&args.out.join("morph.svg"), &morph)?;
    writeln!(
        std::io::stdout(),
        "wrote {} profile drawings, profiles.svg and morph.svg to {}",
        profiles.len(),
        args.out.display()
    )?;
    Ok(())
}

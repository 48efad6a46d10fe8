//! `revdist`: command-line front end. A thin dispatcher: each subcommand lives in its own
//! file and returns a `Result`; errors are printed as `error: ...` with exit code 2 (1 for a
//! batch whose lines all ran, some with errors).

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod distance;
mod export;
mod figures;
mod input;
mod models;
mod profile;
mod scene;
mod tessellate;
mod toi;
mod tree;

/// Result of a subcommand.
pub type CmdResult = Result<(), Box<dyn std::error::Error>>;

/// Minimum distance between solids of revolution (Son, Yoon, Kim, Elber 2020).
#[derive(Debug, Parser)]
#[command(name = "revdist", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List the built-in models (name, kind, pieces, height).
    Models(models::Args),
    /// Draw a profile (built-in name or profile file) and its control polygon as SVG.
    Profile(profile::Args),
    /// Write a built-in model (or a re-read profile file) as a TOML profile file.
    Export(export::Args),
    /// Draw every built-in model and frames of the deformable model into a directory.
    Figures(figures::Args),
    /// Build the biarc tree of a profile: node counts, depth, bytes, build time; optional SVG.
    Tree(tree::Args),
    /// Minimum distance between two posed solids (one query, or JSON lines with --batch).
    Distance(distance::Args),
    /// Certified time of impact of two solids moving from start to end poses over [0, 1].
    Toi(toi::Args),
    /// Closed triangle mesh (OBJ or binary STL) within a certified Hausdorff distance eps.
    Tessellate(tessellate::Args),
    /// Run a scene file (bodies, motions, effects; see experiments/scenes/) with revdist-scene.
    Scene(scene::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Models(args) => models::run(args),
        Command::Profile(args) => profile::run(args),
        Command::Export(args) => export::run(args),
        Command::Figures(args) => figures::run(args),
        Command::Tree(args) => tree::run(args),
        Command::Distance(args) => distance::run(args),
        Command::Toi(args) => toi::run(args),
        Command::Tessellate(args) => tessellate::run(args),
        Command::Scene(args) => scene::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // A batch whose lines ran, some with errors (each on its own output line).
        Err(e) if e.is::<distance::batch::LinesFailed>() => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

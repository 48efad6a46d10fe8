//! `revdist models`: list the built-in models.

use std::io::Write;

use revdist::models::{self, model_names, MORPH_PREFIX};
use revdist::profile::ProfileKind;

use crate::CmdResult;

#[derive(Debug, clap::Args)]
pub struct Args {}

pub fn run(_args: Args) -> CmdResult {
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{:<12} {:<13} {:>6} {:>7}",
        "name", "kind", "pieces", "height"
    )?;
    for name in model_names() {
        let profile = models::model(name)?;
        let bbox = profile.bounding_box();
        let kind = match profile.kind() {
            ProfileKind::Closed => "closed",
            ProfileKind::OpenOnAxis => "open-on-axis",
        };
        writeln!(
            out,
            "{:<12} {:<13} {:>6} {:>7.3}",
            name,
            kind,
            profile.pieces().len(),
            bbox.max.y - bbox.min.y
        )?;
    }
    writeln!(
        out,
        "\nThe deformable model M_t of the paper's section 5 is available as {MORPH_PREFIX}T, T in [0, 1) (e.g. {MORPH_PREFIX}0.25)."
    )?;
    Ok(())
}

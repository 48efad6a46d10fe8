//! Inputs of the subcommands: a profile argument (a built-in model name, see `revdist
//! models`, else a profile file path; resolved by `revdist::request::spec`) and output files.

use std::path::Path;

pub use revdist::request::spec::load_profile;

/// Write `contents` to `path`, creating missing parent directories.
pub fn write_file(path: &Path, contents: &str) -> Result<(), Box<dyn std::error::Error>> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| format!("cannot create directory '{}': {e}", parent.display()))?;
    }
    std::fs::write(path, contents)
        .map_err(|e| format!("cannot write '{}': {e}", path.display()))?;
    Ok(())
}

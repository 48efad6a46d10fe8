//! Resolving a profile argument: a built-in model name (see `revdist models`), else a
//! profile file path. Shared by every subcommand that takes a profile.

use std::path::Path;

use revdist::models::{self, ModelError};
use revdist::profile::Profile;
use revdist::profile_file::{load_path, ProfileFileError};

/// The built-in model `spec`, or the profile file at path `spec` when it is not a built-in
/// name (built-in names win; write `./pawn` for a file called `pawn`).
pub fn load_profile(spec: &str) -> Result<Profile, Box<dyn std::error::Error>> {
    match models::model(spec) {
        Ok(profile) => Ok(profile),
        Err(ModelError::UnknownModel { .. }) if Path::new(spec).is_file() => {
            read_profile_file(spec)
        }
        Err(ModelError::UnknownModel { .. }) if Path::new(spec).is_dir() => {
            Err(format!("'{spec}' is a directory, not a profile file or a built-in model").into())
        }
        Err(e @ ModelError::UnknownModel { .. }) => {
            Err(format!("{e}; no profile file '{spec}' exists either").into())
        }
        Err(e) => Err(e.into()),
    }
}

/// Read and validate a TOML profile file.
pub fn read_profile_file(path: &str) -> Result<Profile, Box<dyn std::error::Error>> {
    load_path(Path::new(path)).map_err(|e| match e {
        ProfileFileError::Io { .. } => e.to_string().into(),
        _ => format!("profile file '{path}': {e}").into(),
    })
}

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

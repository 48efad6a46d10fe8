//! Resolving a profile argument: a built-in model name (`crate::models`), else a profile
//! file path (`crate::profile_file`). Shared by every subcommand of the command line that
//! takes a profile and by the Python package.

use std::path::Path;

use std::sync::Arc;

use crate::biarc::TreeError;
use crate::models::{self, ModelError};
use crate::profile::Profile;
use crate::profile_file::{load_path, ProfileFileError};
use crate::solid::Solid;

/// Why a profile argument names no profile.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpecError {
    /// A built-in name that does not build (e.g. `morph@x`).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Neither a built-in name nor an existing file.
    #[error("{model}; no profile file '{spec}' exists either")]
    NotFound { model: ModelError, spec: String },
    /// A directory where a file was expected.
    #[error("'{0}' is a directory, not a profile file or a built-in model")]
    Directory(String),
    /// The file exists but cannot be read.
    #[error("{0}")]
    Unreadable(ProfileFileError),
    /// The file was read but is not a valid profile.
    #[error("profile file '{path}': {source}")]
    File {
        path: String,
        #[source]
        source: ProfileFileError,
    },
    /// The profile's tree cannot be built at this eps (e.g. below what rounding certifies).
    #[error("'{spec}' at eps {eps}: {source}")]
    Tree {
        spec: String,
        eps: f64,
        #[source]
        source: TreeError,
    },
}

/// The built-in model `spec`, or the profile file at path `spec` when it is not a built-in
/// name (built-in names win; write `./pawn` for a file called `pawn`).
pub fn load_profile(spec: &str) -> Result<Profile, SpecError> {
    match models::model(spec) {
        Ok(profile) => Ok(profile),
        Err(ModelError::UnknownModel { .. }) if Path::new(spec).is_file() => {
            read_profile_file(spec)
        }
        Err(ModelError::UnknownModel { .. }) if Path::new(spec).is_dir() => {
            Err(SpecError::Directory(spec.to_string()))
        }
        Err(model @ ModelError::UnknownModel { .. }) => Err(SpecError::NotFound {
            model,
            spec: spec.to_string(),
        }),
        Err(e) => Err(e.into()),
    }
}

/// Read and validate a TOML profile file.
pub fn read_profile_file(path: &str) -> Result<Profile, SpecError> {
    load_path(Path::new(path)).map_err(|e| match e {
        ProfileFileError::Io { .. } => SpecError::Unreadable(e),
        _ => SpecError::File {
            path: path.to_string(),
            source: e,
        },
    })
}

/// The solid of `profile` (named `spec` in messages) with trees of bound `eps`, at the
/// identity pose.
pub fn build_solid(spec: &str, profile: Profile, eps: f64) -> Result<Solid, SpecError> {
    Solid::from_profile(Arc::new(profile), eps).map_err(|source| SpecError::Tree {
        spec: spec.to_string(),
        eps,
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_files_and_neither() {
        assert!(load_profile("pawn").is_ok());
        let e = load_profile("no-such-model-or-file").unwrap_err();
        assert!(matches!(e, SpecError::NotFound { .. }));
        let text = e.to_string();
        assert!(
            text.starts_with("unknown model 'no-such-model-or-file'"),
            "{text}"
        );
        assert!(
            text.ends_with("no profile file 'no-such-model-or-file' exists either"),
            "{text}"
        );
        assert!(matches!(load_profile("src"), Err(SpecError::Directory(_))));
        assert!(matches!(
            read_profile_file("no/such/file.toml"),
            Err(SpecError::Unreadable(_))
        ));
        assert!(matches!(
            read_profile_file("Cargo.toml"),
            Err(SpecError::File { .. })
        ));
    }
}

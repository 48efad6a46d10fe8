//! Why a scene file could not be used.

use revdist::limits::RangeError;
use std::path::PathBuf;

/// A scene file that could not be used: the field and the problem.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("cannot read scene file '{path}': {source}")]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("scene file '{path}': {message}")]
    Syntax { path: PathBuf, message: String },
    #[error("{field}: {problem}")]
    Field { field: String, problem: String },
    /// A number outside the range `revdist distance` accepts ([`revdist::limits`]); the
    /// message names the field.
    #[error(transparent)]
    Range(#[from] RangeError),
}

pub(super) fn field_error(field: impl Into<String>, problem: impl Into<String>) -> SceneError {
    SceneError::Field {
        field: field.into(),
        problem: problem.into(),
    }
}

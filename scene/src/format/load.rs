//! Reading a scene: its text, parsed as TOML into the spec (`spec.rs`) and checked into a
//! [`Scene`] (`validate.rs`).

use super::error::SceneError;
use super::model::Scene;
use super::spec::SceneSpec;
use super::validate::check_scene;
use std::path::{Path, PathBuf};

impl Scene {
    /// Reads and checks a scene file; profile paths are resolved against its directory.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        Scene::parse(&text, base).map_err(|e| match e {
            SceneError::Syntax { message, .. } => SceneError::Syntax {
                path: path.to_path_buf(),
                message,
            },
            e => e,
        })
    }

    /// Parses and checks scene text; relative profile paths are resolved against `base`.
    pub fn parse(text: &str, base: &Path) -> Result<Scene, SceneError> {
        let spec: SceneSpec = toml::from_str(text).map_err(|e| SceneError::Syntax {
            path: PathBuf::from("<scene>"),
            message: e.to_string(),
        })?;
        check_scene(spec, base)
    }
}

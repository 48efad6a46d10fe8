//! Helpers shared by the scene crate's integration tests.

use revdist_scene::format::{Scene, SceneError};
use std::path::Path;

/// Parses a scene text with paths relative to the working directory.
pub fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Path::new("."))
}

/// The error message of a scene text that must be rejected.
pub fn error_of(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

/// Every scene text is rejected with a message that contains its expected part (the field
/// and the problem).
pub fn assert_errors_mention(cases: &[(String, &str)]) {
    for (text, expected) in cases {
        let e = error_of(text);
        assert!(
            e.contains(expected),
            "error {e:?} should mention {expected:?}"
        );
    }
}

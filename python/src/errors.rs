//! Core errors as Python exceptions: `ValueError` with the core's message (the command
//! line's), `FileNotFoundError` for a profile file that does not exist.

use pyo3::exceptions::{PyFileNotFoundError, PyValueError};
use pyo3::PyErr;

/// A `ValueError` carrying `e`'s message.
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A `FileNotFoundError` carrying `message`.
pub fn not_found(message: impl std::fmt::Display) -> PyErr {
    PyFileNotFoundError::new_err(message.to_string())
}

/// `(2, 5)`, `(7,)`, `()` as Python writes shapes, for messages about arrays.
pub fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

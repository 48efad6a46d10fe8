//! Poses from numpy arrays, read in place (any strides, no copy of the array): `(N, 7)` rows
//! `[tx, ty, tz, qw, qx, qy, qz]`, `(N, 4, 4)` homogeneous matrices, or one pose as `(7,)`
//! or `(4, 4)`. Each row is checked by `revdist::request::pose` (the command line's check),
//! its error prefixed with where it was given (`poses[3]: ...`).

use nalgebra::Isometry3;
use numpy::ndarray::{Ix2, Ix3};
use numpy::PyReadonlyArrayDyn;
use pyo3::PyResult;
use revdist::request::{pose_from_matrix, pose_from_quaternion};

use crate::errors::{shape_text, value_error};

/// Poses read from an array, and whether it held a single pose (`(7,)` or `(4, 4)`).
pub struct Poses {
    pub poses: Vec<Isometry3<f64>>,
    pub single: bool,
}

/// The shapes an array of poses may have, for error messages.
const SHAPES: &str = "(N, 7) rows [tx, ty, tz, qw, qx, qy, qz], (N, 4, 4) homogeneous matrices, or one pose as (7,) or (4, 4)";

/// Reads the poses of `array`; `name` says where they were given (`poses`, `pose_a`).
pub fn read(name: &str, array: &PyReadonlyArrayDyn<'_, f64>) -> PyResult<Poses> {
    let view = array.as_array();
    match view.shape() {
        [7] => Ok(Poses {
            poses: vec![row7(name, view.iter(), None)?],
            single: true,
        }),
        [4, 4] => Ok(Poses {
            poses: vec![matrix(name, view.iter(), None)?],
            single: true,
        }),
        [_, 7] => {
            let rows = view
                .into_dimensionality::<Ix2>()
                .map_err(|e| value_error(format!("{name}: {e}")))?;
            let poses = rows
                .outer_iter()
                .enumerate()
                .map(|(i, row)| match row.as_slice() {
                    Some(r) => row7(name, r.iter(), Some(i)),
                    None => row7(name, row.iter(), Some(i)),
                })
                .collect::<PyResult<_>>()?;
            Ok(Poses {
                poses,
                single: false,
            })
        }
        [_, 4, 4] => {
            let ms = view
                .into_dimensionality::<Ix3>()
                .map_err(|e| value_error(format!("{name}: {e}")))?;
            let poses = ms
                .outer_iter()
                .enumerate()
                .map(|(i, m)| matrix(name, m.iter(), Some(i)))
                .collect::<PyResult<_>>()?;
            Ok(Poses {
                poses,
                single: false,
            })
        }
        shape => Err(value_error(format!(
            "{name} must have shape {SHAPES}; got shape {}",
            shape_text(shape)
        ))),
    }
}

fn place(name: &str, index: Option<usize>) -> String {
    match index {
        Some(i) => format!("{name}[{i}]"),
        None => name.to_string(),
    }
}

/// Copies the first `N` values of `values` (an array of exactly `N` elements).
fn fixed<'a, const N: usize>(values: impl Iterator<Item = &'a f64>) -> [f64; N] {
    let mut out = [0.0; N];
    for (o, v) in out.iter_mut().zip(values) {
        *o = *v;
    }
    out
}

fn row7<'a>(
    name: &str,
    row: impl Iterator<Item = &'a f64>,
    index: Option<usize>,
) -> PyResult<Isometry3<f64>> {
    let v: [f64; 7] = fixed(row);
    pose_from_quaternion([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]])
        .map_err(|e| value_error(format!("{}: {e}", place(name, index))))
}

fn matrix<'a>(
    name: &str,
    m: impl Iterator<Item = &'a f64>,
    index: Option<usize>,
) -> PyResult<Isometry3<f64>> {
    let flat: [f64; 16] = fixed(m);
    let mut rows = [[0.0; 4]; 4];
    for (k, v) in flat.iter().enumerate() {
        rows[k / 4][k % 4] = *v;
    }
    pose_from_matrix(&rows).map_err(|e| value_error(format!("{}: {e}", place(name, index))))
}

//! Profiles to and from numpy arrays: a polyline `(n, 2)` of `[rho, z]` points, or NURBS
//! pieces as dicts or sequences of arrays. Values are read through `numpy.asarray` (lists,
//! tuples and any real dtype), then checked by the core exactly as a profile file's pieces
//! are (`revdist::nurbs::NurbsCurve::new`, `revdist::profile::Profile::new`); every problem
//! is a `ValueError` naming the piece and the field.

use nalgebra::Point2;
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use revdist::nurbs::NurbsCurve;
use revdist::profile::ProfileError;

use crate::errors::{shape_text, value_error};

/// Largest integer that float64 holds exactly: integers beyond it would be rounded.
const EXACT_INT: f64 = 9_007_199_254_740_992.0;

/// The fields of a NURBS piece, in the order of its sequence form.
const FIELDS: [&str; 4] = ["degree", "knots", "points", "weights"];

/// A float array's shape and values (in logical order).
struct Floats {
    shape: Vec<usize>,
    values: Vec<f64>,
}

/// `value` as float64 through `numpy.asarray`: real dtypes only (integers up to 2**53, which
/// convert exactly); `what` names it in errors.
fn floats(what: &str, value: &Bound<'_, PyAny>) -> PyResult<Floats> {
    let np = value.py().import("numpy")?;
    let array = np
        .call_method1("asarray", (value,))
        .map_err(|e| value_error(format!("{what}: not an array of numbers ({e})")))?;
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "f" | "i" | "u") {
        return Err(value_error(format!(
            "{what} must be real numbers (float64), got dtype {}",
            dtype.str()?
        )));
    }
    let array = array.call_method1("astype", ("float64",))?;
    let array = array
        .cast::<PyArrayDyn<f64>>()
        .map_err(|e| value_error(format!("{what}: {e}")))?;
    let view = array.readonly();
    let values: Vec<f64> = view.as_array().iter().copied().collect();
    if kind != "f" && values.iter().any(|v| v.abs() > EXACT_INT) {
        return Err(value_error(format!(
            "{what}: integers beyond 2**53 do not convert exactly to float64"
        )));
    }
    Ok(Floats {
        shape: array.shape().to_vec(),
        values,
    })
}

/// The rows of an `(n, 2)` array as points `[rho, z]`.
fn points(what: &str, a: Floats) -> PyResult<Vec<Point2<f64>>> {
    match a.shape[..] {
        [_, 2] => Ok(a
            .values
            .chunks(2)
            .map(|p| Point2::new(p[0], p[1]))
            .collect()),
        _ => Err(value_error(format!(
            "{what} must have shape (n, 2), rows [rho, z]; got shape {}",
            shape_text(&a.shape)
        ))),
    }
}

/// A one-dimensional array's values.
fn vector(what: &str, a: Floats) -> PyResult<Vec<f64>> {
    match a.shape[..] {
        [_] => Ok(a.values),
        _ => Err(value_error(format!(
            "{what} must be one-dimensional; got shape {}",
            shape_text(&a.shape)
        ))),
    }
}

/// One line piece per segment of the polyline `rz` (piece `k` joins `rz[k]` to `rz[k+1]`).
pub fn polyline_pieces(rz: &Bound<'_, PyAny>) -> PyResult<Vec<NurbsCurve>> {
    let a = floats("rz", rz)?;
    let pts = points("rz", a)?;
    if pts.len() < 2 {
        return Err(value_error(format!(
            "rz: a polyline needs at least 2 points, got {}",
            pts.len()
        )));
    }
    if let Some(k) = pts
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(value_error(format!(
            "rz[{k}] = [{}, {}] is not a finite point",
            pts[k].x, pts[k].y
        )));
    }
    pts.windows(2)
        .enumerate()
        .map(|(k, w)| {
            NurbsCurve::line(w[0], w[1])
                .map_err(|e| value_error(format!("segment {k} (rz[{k}] to rz[{}]): {e}", k + 1)))
        })
        .collect()
}

/// A polyline's profile error, saying which segment a piece is and how to close a polyline.
pub fn polyline_error(e: &ProfileError) -> PyErr {
    let hint = match e {
        ProfileError::NotClosedNorOnAxis { .. } => {
            " (a closed polyline repeats its first point at the end)"
        }
        _ => " (piece k is the segment from rz[k] to rz[k + 1])",
    };
    value_error(format!("invalid profile: {e}{hint}"))
}

/// The field `name` of piece `k` given as a dict: `None` when absent (only `weights` may
/// be); unknown keys are refused, as in profile files.
fn dict_fields<'py>(k: usize, d: &Bound<'py, PyDict>) -> PyResult<[Option<Bound<'py, PyAny>>; 4]> {
    for key in d.keys() {
        let name: String = key.extract().map_err(|_| {
            value_error(format!("piece {k}: field names must be strings, got {key}"))
        })?;
        if !FIELDS.contains(&name.as_str()) {
            return Err(value_error(format!(
                "piece {k}: unknown field '{name}' (expected degree, knots, points and optional weights)"
            )));
        }
    }
    let mut out = [None, None, None, None];
    for (slot, name) in out.iter_mut().zip(FIELDS) {
        *slot = d.get_item(name)?;
    }
    Ok(out)
}

/// The fields of piece `k` given as a sequence `(degree, knots, points[, weights])`.
fn sequence_fields<'py>(
    k: usize,
    piece: &Bound<'py, PyAny>,
) -> PyResult<[Option<Bound<'py, PyAny>>; 4]> {
    let n =
        piece.len().map_err(|_| {
            value_error(format!(
            "piece {k}: expected a dict or a sequence (degree, knots, points[, weights]), got {}",
            piece.get_type().name().map(|n| n.to_string()).unwrap_or_default()
        ))
        })?;
    if !(3..=4).contains(&n) {
        return Err(value_error(format!(
            "piece {k}: a sequence (degree, knots, points[, weights]) has 3 or 4 items, got {n}"
        )));
    }
    let mut out = [None, None, None, None];
    for (i, slot) in out.iter_mut().enumerate().take(n) {
        *slot = Some(piece.get_item(i)?);
    }
    Ok(out)
}

/// NURBS pieces from Python: a list (or any iterable) of dicts or sequences.
pub fn nurbs_pieces(pieces: &Bound<'_, PyAny>) -> PyResult<Vec<NurbsCurve>> {
    if pieces.cast::<PyDict>().is_ok() {
        return Err(value_error(
            "pieces must be a list of pieces (dicts or sequences), got one dict",
        ));
    }
    let items = pieces
        .try_iter()
        .map_err(|_| value_error("pieces must be a list of pieces (dicts or sequences)"))?;
    let mut out = Vec::new();
    for (k, piece) in items.enumerate() {
        let piece = piece?;
        let fields = match piece.cast::<PyDict>() {
            Ok(d) => dict_fields(k, d)?,
            Err(_) => sequence_fields(k, &piece)?,
        };
        let [degree, knots, pts, weights] = fields;
        let missing = |name: &str| value_error(format!("piece {k}: missing field '{name}'"));
        let degree = degree.ok_or_else(|| missing("degree"))?;
        let degree: usize = degree.extract().map_err(|_| {
            value_error(format!(
                "piece {k}: degree must be a whole number >= 1, got {degree}"
            ))
        })?;
        let knots = knots.ok_or_else(|| missing("knots"))?;
        let knots = vector(
            &format!("piece {k}: knots"),
            floats(&format!("piece {k}: knots"), &knots)?,
        )?;
        let pts = pts.ok_or_else(|| missing("points"))?;
        let pts = points(
            &format!("piece {k}: points"),
            floats(&format!("piece {k}: points"), &pts)?,
        )?;
        let weights = match weights {
            Some(w) if !w.is_none() => {
                let what = format!("piece {k}: weights");
                Some(vector(&what, floats(&what, &w)?)?)
            }
            _ => None,
        };
        let curve = NurbsCurve::new(degree, knots, pts, weights)
            .map_err(|e| value_error(format!("piece {k}: {e}")))?;
        out.push(curve);
    }
    Ok(out)
}

/// Pieces as Python dicts of numpy arrays (what [`nurbs_pieces`] reads back bit for bit).
pub fn pieces_to_python<'py>(
    py: Python<'py>,
    pieces: &[NurbsCurve],
) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for c in pieces {
        let d = PyDict::new(py);
        d.set_item("degree", c.degree())?;
        d.set_item("knots", Array1::from(c.knots().to_vec()).into_pyarray(py))?;
        let flat: Vec<f64> = c.points().iter().flat_map(|p| [p.x, p.y]).collect();
        let pts = Array2::from_shape_vec((c.points().len(), 2), flat).map_err(value_error)?;
        d.set_item("points", pts.into_pyarray(py))?;
        match c.weights() {
            Some(w) => d.set_item("weights", Array1::from(w.to_vec()).into_pyarray(py))?,
            None => d.set_item("weights", py.None())?,
        }
        out.append(d)?;
    }
    Ok(out)
}

//! `revdist.Solid`: a solid of revolution with its biarc tree (paper 4.1), built from a
//! built-in model, a profile file, or either as the command line resolves it.

use std::path::Path;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use revdist::models::{model, model_names};
use revdist::request::{build_solid, check_eps, load_profile, read_profile_file};
use revdist::solid::Solid;
use revdist::tessellate::{tessellate, TessellateOptions, VertexPlacement};

use crate::errors::{not_found, value_error};

/// A mesh as numpy arrays: vertices (n, 3) and triangles (m, 3).
type Mesh<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// Default bound of the biarc trees, the command line's (`revdist distance --eps`).
pub const DEFAULT_EPS: f64 = 1e-4;

/// A solid of revolution: a profile in the (rho, z) half-plane revolved about the z axis,
/// held as a biarc tree of two-sided Hausdorff bound `eps` (Son et al. 2020, section 4.1).
/// Poses are given to `distance` and `Pair`, not stored here.
#[pyclass(name = "Solid", module = "revdist", frozen)]
pub struct PySolid {
    pub solid: Solid,
    spec: String,
    eps: f64,
}

impl PySolid {
    fn build(spec: &str, profile: revdist::profile::Profile, eps: f64) -> PyResult<Self> {
        let solid = build_solid(spec, profile, eps).map_err(value_error)?;
        Ok(PySolid {
            solid,
            spec: spec.to_string(),
            eps,
        })
    }
}

#[pymethods]
impl PySolid {
    /// The built-in model `name` (see `revdist.models()`; `"morph@0.25"` too) with trees of
    /// bound `eps`.
    #[staticmethod]
    #[pyo3(signature = (name, eps = DEFAULT_EPS))]
    fn model(py: Python<'_>, name: &str, eps: f64) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        let profile = model(name).map_err(value_error)?;
        py.detach(|| Self::build(name, profile, eps))
    }

    /// The profile file (TOML, `revdist export`'s format) at `path` with trees of bound
    /// `eps`. Raises `FileNotFoundError` when no such file exists.
    #[staticmethod]
    #[pyo3(signature = (path, eps = DEFAULT_EPS))]
    fn from_file(py: Python<'_>, path: std::path::PathBuf, eps: f64) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        let spec = path.to_string_lossy().into_owned();
        let profile = read_profile_file(&spec).map_err(|e| {
            if Path::new(&path).exists() {
                value_error(e)
            } else {
                not_found(e)
            }
        })?;
        py.detach(|| Self::build(&spec, profile, eps))
    }

    /// A built-in model name or else a profile file path, resolved exactly as the command
    /// line resolves its arguments (built-in names win).
    #[staticmethod]
    #[pyo3(signature = (spec, eps = DEFAULT_EPS))]
    fn load(py: Python<'_>, spec: &str, eps: f64) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        let profile = load_profile(spec).map_err(|e| match e {
            revdist::request::SpecError::NotFound { .. } => not_found(e),
            e => value_error(e),
        })?;
        py.detach(|| Self::build(spec, profile, eps))
    }

    /// The model name or file path the solid was built from.
    #[getter]
    fn spec(&self) -> &str {
        &self.spec
    }

    /// The bound the biarc tree was built with.
    #[getter]
    fn eps(&self) -> f64 {
        self.eps
    }

    /// Nodes of the query tree.
    #[getter]
    fn nodes(&self) -> usize {
        self.solid.tree.nodes.len()
    }

    /// A closed, outward-oriented triangle mesh `(V, F)` of the solid in its own frame (axis
    /// z) whose two-sided Hausdorff distance to the true surface is certified to be at most
    /// `eps` (`revdist tessellate`): `V` float64 `(n, 3)`, `F` int64 `(m, 3)`.
    /// `on_surface=True` puts every vertex on the biarc surface (more triangles).
    #[pyo3(signature = (eps, on_surface = false))]
    fn tessellate<'py>(&self, py: Python<'py>, eps: f64, on_surface: bool) -> PyResult<Mesh<'py>> {
        let profile = self
            .solid
            .profile
            .clone()
            .ok_or_else(|| value_error("this solid has no exact profile to tessellate"))?;
        let options = TessellateOptions {
            placement: if on_surface {
                VertexPlacement::OnSurface
            } else {
                VertexPlacement::Balanced
            },
            ..TessellateOptions::default()
        };
        let cm = py
            .detach(|| tessellate(&profile, eps, options))
            .map_err(value_error)?;
        let v: Vec<f64> = cm
            .mesh
            .vertices
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .collect();
        let f: Vec<i64> = cm
            .mesh
            .triangles
            .iter()
            .flat_map(|t| t.map(i64::from))
            .collect();
        let v = Array2::from_shape_vec((cm.mesh.vertices.len(), 3), v).map_err(value_error)?;
        let f = Array2::from_shape_vec((cm.mesh.triangles.len(), 3), f).map_err(value_error)?;
        Ok((v.into_pyarray(py), f.into_pyarray(py)))
    }

    fn __repr__(&self) -> String {
        format!(
            "revdist.Solid({:?}, eps={}, nodes={})",
            self.spec,
            self.eps,
            self.solid.tree.nodes.len()
        )
    }
}

/// The names of the built-in models (`morph@T`, T in [0, 1), names the frames of the
/// deformable model M_t too).
#[pyfunction]
pub fn models() -> Vec<&'static str> {
    model_names().to_vec()
}

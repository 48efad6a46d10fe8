//! `revdist.Solid`: a solid of revolution with its biarc tree (paper 4.1), built from a
//! built-in model, a profile file, either as the command line resolves it, or a profile given
//! as numpy arrays (a polyline or NURBS pieces, [`crate::arrays`]). A solid pickles by its
//! recipe (the built-in name, or the profile's pieces) and is rebuilt on load, which gives
//! the same tree and so the same bits on every answer (the build is deterministic).

use std::path::Path;
use std::sync::Arc;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use revdist::models::{model, model_names};
use revdist::profile::Profile;
use revdist::request::{build_solid, check_eps, load_profile, read_profile_file, DEFAULT_EPS};
use revdist::solid::Solid;
use revdist::tessellate::{tessellate, TessellateOptions, VertexPlacement};

use crate::arrays;
use crate::errors::{not_found, value_error};

/// A mesh as numpy arrays: vertices (n, 3) and triangles (m, 3).
type Mesh<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// Tags of a pickled solid's recipe: `(MODEL_RECIPE, spec, eps)` or
/// `(PIECES_RECIPE, spec, eps, profile name, pieces)`.
const MODEL_RECIPE: &str = "model";
const PIECES_RECIPE: &str = "pieces";

/// A solid of revolution: a profile in the (rho, z) half-plane revolved about the z axis,
/// held as a biarc tree of two-sided Hausdorff bound `eps` (Son et al. 2020, section 4.1).
/// Poses are given to `distance` and `Pair`, not stored here.
#[pyclass(name = "Solid", module = "revdist", frozen)]
pub struct PySolid {
    pub solid: Solid,
    spec: String,
    eps: f64,
    /// Built from a built-in model called `spec` (pickled by name), else from its pieces.
    builtin: bool,
}

impl PySolid {
    fn build(spec: &str, profile: Profile, eps: f64, builtin: bool) -> PyResult<Self> {
        let solid = build_solid(spec, profile, eps).map_err(value_error)?;
        Ok(PySolid {
            solid,
            spec: spec.to_string(),
            eps,
            builtin,
        })
    }

    /// The exact profile (every solid built here has one).
    fn exact_profile(&self) -> PyResult<&Arc<Profile>> {
        self.solid
            .profile
            .as_ref()
            .ok_or_else(|| value_error("this solid has no exact profile"))
    }
}

/// Rebuilds a pickled solid from its recipe (what `Solid.__reduce__` returns); not for
/// direct use.
#[pyfunction]
pub fn _solid_from_recipe(py: Python<'_>, recipe: &Bound<'_, PyTuple>) -> PyResult<PySolid> {
    let tag: String = recipe.get_item(0)?.extract()?;
    let spec: String = recipe.get_item(1)?.extract()?;
    let eps: f64 = recipe.get_item(2)?.extract()?;
    check_eps(eps).map_err(value_error)?;
    match tag.as_str() {
        MODEL_RECIPE => {
            let profile = model(&spec).map_err(value_error)?;
            py.detach(|| PySolid::build(&spec, profile, eps, true))
        }
        PIECES_RECIPE => {
            let name: String = recipe.get_item(3)?.extract()?;
            let pieces = arrays::nurbs_pieces(&recipe.get_item(4)?)?;
            let profile = Profile::new(name, pieces)
                .map_err(|e| value_error(format!("invalid profile: {e}")))?;
            py.detach(|| PySolid::build(&spec, profile, eps, false))
        }
        _ => Err(value_error(format!("unknown solid recipe '{tag}'"))),
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
        py.detach(|| Self::build(name, profile, eps, true))
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
        py.detach(|| Self::build(&spec, profile, eps, false))
    }

    /// A built-in model name or else a profile file path, resolved exactly as the command
    /// line resolves its arguments (built-in names win).
    #[staticmethod]
    #[pyo3(signature = (spec, eps = DEFAULT_EPS))]
    fn load(py: Python<'_>, spec: &str, eps: f64) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        // Built-in names win, as in `load_profile`, which gives the errors of neither.
        let (profile, builtin) = match model(spec) {
            Ok(profile) => (profile, true),
            Err(_) => {
                let profile = load_profile(spec).map_err(|e| match e {
                    revdist::request::SpecError::NotFound { .. } => not_found(e),
                    e => value_error(e),
                })?;
                (profile, false)
            }
        };
        py.detach(|| Self::build(spec, profile, eps, builtin))
    }

    /// The profile of the polyline `rz`, a float array `(n, 2)` of points `[rho, z]`, one
    /// line piece per segment (piece `k` joins `rz[k]` to `rz[k + 1]`; corners are allowed),
    /// with trees of bound `eps`. The polyline is open with both ends on the axis (`rho = 0`,
    /// the axis segment between them closes the region) or closed (its last point repeats
    /// the first, and it stays in `rho > 0`); it is checked as a profile file is (simple, in
    /// the half-plane, finite), and `ValueError` names the problem.
    #[staticmethod]
    #[pyo3(signature = (rz, eps = DEFAULT_EPS, name = "polyline"))]
    fn from_polyline(
        py: Python<'_>,
        rz: &Bound<'_, PyAny>,
        eps: f64,
        name: &str,
    ) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        let pieces = arrays::polyline_pieces(rz)?;
        let profile = Profile::new(name, pieces).map_err(|e| arrays::polyline_error(&e))?;
        py.detach(|| Self::build(name, profile, eps, false))
    }

    /// The profile of NURBS `pieces`, joined end to start, with trees of bound `eps`. Each
    /// piece is a dict `{"degree": int, "knots": (k,), "points": (n, 2) [rho, z],
    /// "weights": (n,) or None}` (weights optional: rational when given) or a sequence
    /// `(degree, knots, points[, weights])`, arrays or lists; what `Solid.profile()` returns.
    /// Checked as a profile file is; `ValueError` names the piece and the problem.
    #[staticmethod]
    #[pyo3(signature = (pieces, eps = DEFAULT_EPS, name = "nurbs"))]
    fn from_nurbs(
        py: Python<'_>,
        pieces: &Bound<'_, PyAny>,
        eps: f64,
        name: &str,
    ) -> PyResult<Self> {
        check_eps(eps).map_err(value_error)?;
        let pieces = arrays::nurbs_pieces(pieces)?;
        let profile =
            Profile::new(name, pieces).map_err(|e| value_error(format!("invalid profile: {e}")))?;
        py.detach(|| Self::build(name, profile, eps, false))
    }

    /// The exact profile's NURBS pieces, joined end to start: a list of dicts `{"degree",
    /// "knots" float64 (k,), "points" float64 (n, 2) [rho, z], "weights" float64 (n,) or
    /// None}`, which `Solid.from_nurbs` takes back.
    fn profile<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        arrays::pieces_to_python(py, self.exact_profile()?.pieces())
    }

    /// Whether the profile is `"closed"` (a loop in rho > 0) or `"open"` (both ends on the
    /// axis).
    #[getter]
    fn kind(&self) -> PyResult<&'static str> {
        Ok(match self.exact_profile()?.kind() {
            revdist::profile::ProfileKind::Closed => "closed",
            revdist::profile::ProfileKind::OpenOnAxis => "open",
        })
    }

    /// Pickling: the recipe, rebuilt by `_solid_from_recipe` on load (a built-in model by
    /// name, any other profile by its pieces, so that no file needs to be where the solid
    /// is unpickled).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let rebuild = py
            .import("revdist._revdist")?
            .getattr("_solid_from_recipe")?;
        let recipe = if self.builtin {
            (MODEL_RECIPE, &self.spec, self.eps).into_pyobject(py)?
        } else {
            let profile = self.exact_profile()?;
            let pieces = arrays::pieces_to_python(py, profile.pieces())?;
            (PIECES_RECIPE, &self.spec, self.eps, profile.name(), pieces).into_pyobject(py)?
        };
        (rebuild, (recipe,)).into_pyobject(py)
    }

    /// A solid is immutable: a copy is the solid itself.
    fn __copy__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    /// A solid is immutable: a deep copy is the solid itself.
    fn __deepcopy__(slf: Py<Self>, _memo: &Bound<'_, PyDict>) -> Py<Self> {
        slf
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
        let profile = Arc::clone(self.exact_profile()?);
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

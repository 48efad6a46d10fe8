//! `revdist._revdist`: the compiled half of the Python package `revdist` (the other half,
//! `revdist/__init__.py`, wraps its answers in a result class and normalises dtypes).
//!
//! Every input goes through the core's `revdist::request` (profiles, eps, tolerances,
//! budgets, poses) and every query through `revdist::query::try_distance` or
//! `try_distance_cached`, the functions the command line's batch uses: the same query gives
//! the same bits and the same error message as `revdist distance --batch`.

mod arrays;
mod errors;
mod poses;
mod query;
mod solid;
mod toi;

use pyo3::prelude::*;

#[pymodule]
fn _revdist(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<solid::PySolid>()?;
    m.add_class::<query::PyPair>()?;
    m.add_function(wrap_pyfunction!(solid::models, m)?)?;
    m.add_function(wrap_pyfunction!(solid::_solid_from_recipe, m)?)?;
    m.add("WIDTH_LIMITS", query::WIDTH_LIMIT_NAMES.to_vec())?;
    m.add("DEFAULT_EPS", revdist::request::DEFAULT_EPS)?;
    m.add_function(wrap_pyfunction!(toi::time_of_impact, m)?)?;
    m.add("TOI_OUTCOMES", toi::OUTCOME_NAMES.to_vec())?;
    Ok(())
}

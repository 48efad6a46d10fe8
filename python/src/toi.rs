//! `revdist.time_of_impact`: certified time of impact for numpy arrays of motions, through
//! `revdist::toi::times_of_impact` (the library's parallel batch; each search is exactly
//! `revdist toi`'s). The GIL is released while the searches run.
//!
//! Each motion moves B from `pose_b_start[i]` to `pose_b_end[i]` and A from
//! `pose_a_start[i]` (default the identity) to `pose_a_end[i]` (default its start) over
//! `t in [0, 1]`; a single pose (`(7,)` or `(4, 4)`) is used for every motion.

use nalgebra::Isometry3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use revdist::request::check_eps;
use revdist::solid::Solid;
use revdist::toi::{times_of_impact, Motion, TimeOfImpact, ToiOptions, ToiOutcome};

use crate::errors::value_error;
use crate::poses::{self, Poses};
use crate::solid::PySolid;

/// Names of `revdist::toi::ToiOutcome`, indexed by the codes of the `outcome_code` array.
pub const OUTCOME_NAMES: [&str; 3] = ["contact", "apart", "undecided"];

fn outcome_code(o: ToiOutcome) -> u8 {
    match o {
        ToiOutcome::Contact => 0,
        ToiOutcome::Apart => 1,
        ToiOutcome::Undecided => 2,
    }
}

/// The number of motions the pose arrays give: every array of more than one pose has the
/// same count `N`, single poses are repeated.
fn motion_count(arrays: &[(&str, &Poses)]) -> PyResult<usize> {
    let mut n: Option<(usize, &str)> = None;
    for (name, p) in arrays {
        if p.single {
            continue;
        }
        match n {
            Some((m, other)) if m != p.poses.len() => {
                return Err(value_error(format!(
                    "{name} holds {} poses but {other} holds {m}",
                    p.poses.len()
                )))
            }
            None => n = Some((p.poses.len(), name)),
            _ => {}
        }
    }
    Ok(n.map_or(1, |(m, _)| m))
}

fn pose_at(p: &Poses, i: usize) -> Isometry3<f64> {
    if p.single {
        p.poses[0]
    } else {
        p.poses[i]
    }
}

/// `solid` itself, or rebuilt from its profile with trees of bound `eps`.
fn at_eps(solid: &PySolid, eps: Option<f64>, name: &str) -> PyResult<Solid> {
    let Some(eps) = eps else {
        return Ok(solid.solid.clone());
    };
    check_eps(eps).map_err(value_error)?;
    let profile = solid.solid.profile.clone().ok_or_else(|| {
        value_error(format!(
            "{name}: this solid has no profile to rebuild at eps {eps}"
        ))
    })?;
    Solid::from_profile(profile, eps).map_err(|e| value_error(format!("{name}: {e}")))
}

/// Certified times of impact of `a` and `b` along N motions; a dict of numpy arrays (the
/// Python layer wraps it in `TimeOfImpactResult`).
#[pyfunction]
#[pyo3(signature = (a, b, pose_b_start, pose_b_end, pose_a_start = None, pose_a_end = None,
    *, eps = None, contact_distance = 0.0, threads = None))]
#[allow(clippy::too_many_arguments)]
pub fn time_of_impact<'py>(
    py: Python<'py>,
    a: &PySolid,
    b: &PySolid,
    pose_b_start: PyReadonlyArrayDyn<'py, f64>,
    pose_b_end: PyReadonlyArrayDyn<'py, f64>,
    pose_a_start: Option<PyReadonlyArrayDyn<'py, f64>>,
    pose_a_end: Option<PyReadonlyArrayDyn<'py, f64>>,
    eps: Option<f64>,
    contact_distance: f64,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let identity = Poses {
        poses: vec![Isometry3::identity()],
        single: true,
    };
    let b0 = poses::read("pose_b_start", &pose_b_start)?;
    let b1 = poses::read("pose_b_end", &pose_b_end)?;
    let a0 = match &pose_a_start {
        Some(p) => poses::read("pose_a_start", p)?,
        None => identity,
    };
    let a1 = match &pose_a_end {
        Some(p) => poses::read("pose_a_end", p)?,
        None => Poses {
            poses: a0.poses.clone(),
            single: a0.single,
        },
    };
    let n = motion_count(&[
        ("pose_b_start", &b0),
        ("pose_b_end", &b1),
        ("pose_a_start", &a0),
        ("pose_a_end", &a1),
    ])?;
    let motions = (0..n)
        .map(|i| {
            let ma = Motion::new(pose_at(&a0, i), pose_at(&a1, i))
                .map_err(|e| value_error(format!("motion {i} of a: {e}")))?;
            let mb = Motion::new(pose_at(&b0, i), pose_at(&b1, i))
                .map_err(|e| value_error(format!("motion {i} of b: {e}")))?;
            Ok((ma, mb))
        })
        .collect::<PyResult<Vec<_>>>()?;
    if threads == Some(0) {
        return Err(value_error("threads must be at least 1"));
    }
    let (sa, sb) = (at_eps(a, eps, "a")?, at_eps(b, eps, "b")?);
    let opts = ToiOptions {
        contact_distance,
        ..ToiOptions::default()
    };
    // Checked before the searches (each would report it).
    if !(contact_distance.is_finite() && contact_distance >= 0.0) {
        return Err(value_error(format!(
            "contact_distance must be a finite number >= 0, got {contact_distance}"
        )));
    }
    let answers = py
        .detach(|| times_of_impact(&sa, &sb, &motions, &opts, threads))
        .map_err(value_error)?;
    let answers = answers
        .into_iter()
        .enumerate()
        .map(|(i, r)| r.map_err(|e| value_error(format!("motion {i}: {e}"))))
        .collect::<PyResult<Vec<TimeOfImpact>>>()?;
    arrays(py, &answers)
}

/// The answers as numpy arrays (NaN where a contact field does not apply).
fn arrays<'py>(py: Python<'py>, answers: &[TimeOfImpact]) -> PyResult<Bound<'py, PyDict>> {
    let n = answers.len();
    let mut point_a = Array2::<f64>::from_elem((n, 3), f64::NAN);
    let mut point_b = Array2::<f64>::from_elem((n, 3), f64::NAN);
    for (i, r) in answers.iter().enumerate() {
        if let Some(c) = &r.contact {
            for k in 0..3 {
                point_a[[i, k]] = c.point_a[k];
                point_b[[i, k]] = c.point_b[k];
            }
        }
    }
    let col = |f: &dyn Fn(&TimeOfImpact) -> f64| answers.iter().map(f).collect::<Vec<f64>>();
    let count = |f: &dyn Fn(&TimeOfImpact) -> usize| {
        answers.iter().map(|r| f(r) as i64).collect::<Vec<i64>>()
    };
    let out = PyDict::new(py);
    out.set_item(
        "outcome_code",
        answers
            .iter()
            .map(|r| outcome_code(r.outcome))
            .collect::<Vec<u8>>()
            .into_pyarray(py),
    )?;
    out.set_item("t_lower", col(&|r| r.t_lower).into_pyarray(py))?;
    out.set_item(
        "t_upper",
        col(&|r| r.t_upper.unwrap_or(f64::NAN)).into_pyarray(py),
    )?;
    out.set_item(
        "upper_at_upper",
        col(&|r| r.contact.as_ref().map_or(f64::NAN, |c| c.upper)).into_pyarray(py),
    )?;
    out.set_item("point_a", point_a.into_pyarray(py))?;
    out.set_item("point_b", point_b.into_pyarray(py))?;
    out.set_item("queries", count(&|r| r.queries).into_pyarray(py))?;
    out.set_item("certificates", count(&|r| r.certificates).into_pyarray(py))?;
    out.set_item("speed_bound", col(&|r| r.speed_bound).into_pyarray(py))?;
    Ok(out)
}

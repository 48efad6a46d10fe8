//! Freeform variants of the paper's five static solids (section 5, Figure 7): `pawn_ff`,
//! `cup_ff`, `bottle_ff`, `table_ff`, `lightmill_ff`.
//!
//! The exact models of [`super::paper`] are built from lines, circular arcs and a few cubic
//! Bezier pieces, so their biarc trees are small (a line or an arc is one biarc). The profiles
//! of the paper's Figure 7 look drawn by a designer as freeform curves, and its Table 2 reports
//! 95 to 687 BVH nodes for them at eps 1e-3 to 1e-5. A freeform variant has the same silhouette
//! as its exact model, drawn the way a CAD designer would draw it: one clamped, non-rational
//! cubic B-spline per *smooth run* of the profile, with as many control points as the run
//! needs to stay within [`FREEFORM_FIT_TOLERANCE`] of the exact shape.
//!
//! **Construction.** The exact profile is parameterised by arc length and cut at its creases:
//! the joins between source pieces whose tangent turns by more than [`CREASE_ANGLE`](super::fit::CREASE_ANGLE)
//! (corners, rims). Each run between two creases (or a crease and an axis end) is fitted by
//! least squares with the shared fitter of `models::fit`:
//! - the piece interpolates the source at both run ends, so consecutive pieces meet exactly
//!   at the crease points and the profile's ends lie exactly on the axis (rho = 0);
//! - at both run ends the second (second-to-last) control point lies on the source's
//!   one-sided tangent: every corner keeps the exact model's angle, and at the axis ends the
//!   tangent is the source's, perpendicular to the axis, so the solid has no cone point there;
//! - inside a run the piece is one cubic with simple knots, hence C2: tangent-continuous
//!   wherever the exact model is (its smooth joins are inside runs);
//! - knots are placed adaptively, as a designer adds control points where the shape bends:
//!   starting from one Bezier span, the span with the largest deviation is halved (a knot
//!   inserted at its mid-parameter) and the run refitted until every span's deviation is at
//!   most [`FREEFORM_FIT_TOLERANCE`]. Straight runs are reproduced by one span with four
//!   collinear control points; curved runs get tens of control points.
//!
//! The fitted control points are checked to have rho >= 0, so by the convex-hull property
//! the whole curve stays in the half-plane. The deviation reported per run ([`RunFit`]) is
//! the distance between the fitted point and the exact point at equal arc-length parameter
//! over [`ERROR_SAMPLES_PER_SPAN`] samples per span, which bounds the two-sided Hausdorff
//! distance up to that sampling; the tests also measure the Hausdorff distance directly by
//! dense sampling of both profiles.
//!
//! Fitting takes 4 to 130 ms per model in a release build (dominated by the SVD solves of the
//! refinement); each variant is fitted once per process, on first use, and cached.
//!
//! Result (eps 1e-3 / 1e-4 / 1e-5, biarc-tree nodes): pawn_ff 73 / 85 / 121 (exact pawn
//! 19 / 31 / 59), cup_ff 39 / 49 / 69, bottle_ff 82 / 92 / 122, table_ff 41 / 61 / 97,
//! lightmill_ff 22 / 22 / 26, against 95 to 687 BVH nodes in the paper's Table 2. The
//! variants have 4 to 33 control points per piece (39 to 63 per model; the lightmill is
//! mostly straight runs, 48 in 11 pieces) and stay within 2.7e-5 to 4.4e-5 of their exact
//! models (sampled two-sided Hausdorff distance).

use std::ops::Range;
use std::sync::OnceLock;

use super::fit::{
    chain_tangents, fit_cubic, ArcLength, CubicFit, EndCondition, Join, Samples, FIT_DEGREE,
};
use super::{paper, ModelError};
use crate::nurbs::NurbsCurve;
use crate::profile::Profile;

/// Names of the freeform variants, in the paper's order (pawn, cup, bottle, table, lightmill).
pub const FREEFORM_NAMES: [&str; 5] =
    ["pawn_ff", "cup_ff", "bottle_ff", "table_ff", "lightmill_ff"];

/// The exact model each variant of [`FREEFORM_NAMES`] is fitted to, same order.
pub const FREEFORM_SOURCES: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];

/// Constructors of the exact models of [`FREEFORM_SOURCES`], same order.
const SOURCE_MODELS: [fn() -> Result<Profile, ModelError>; 5] = [
    paper::pawn,
    paper::cup,
    paper::bottle,
    paper::table,
    paper::lightmill,
];

/// Largest deviation (units) allowed between a run of the exact profile and its fitted piece,
/// at equal arc-length parameter. The models are 1.2 to 2 units tall; 5e-5 is half the
/// 1e-4 absolute silhouette accuracy asked of the variants, leaving the other half for what
/// the error sampling can miss between samples. It is also below the coarsest eps of the
/// paper's tables (1e-3) and far above rounding, so it decides how many control points a run
/// gets, not the accuracy of any later computation (the trees bound the error to the fitted
/// curve itself).
pub const FREEFORM_FIT_TOLERANCE: f64 = 5e-5;

/// Least-squares targets per knot span of a run (at the span's midpoints of equal parameter
/// steps): four times the four coefficients a cubic span adds, so every span is well
/// determined.
const FIT_SAMPLES_PER_SPAN: usize = 16;

/// Samples per knot span (ends included) at which a run's deviation is measured. A span
/// deviates smoothly, with a few oscillations (the error of a cubic least-squares fit), so 64
/// samples catch its maximum to about a percent (checked against dense two-sided sampling by
/// the tests).
pub const ERROR_SAMPLES_PER_SPAN: usize = 64;

/// Most knot spans a run may get before the fit is declared failed: far above what the
/// models need (at most 30 spans), it only stops a runaway refinement on a broken source.
const MAX_SPANS_PER_RUN: usize = 256;

/// Fit of one smooth run of the exact profile.
#[derive(Debug, Clone, PartialEq)]
pub struct RunFit {
    /// Indices of the exact model's pieces that make up the run.
    pub source_pieces: Range<usize>,
    /// Control points of the fitted cubic (knot spans + 3).
    pub control_points: usize,
    /// Largest deviation from the exact run at equal arc-length parameter.
    pub max_deviation: f64,
}

/// How a freeform variant was fitted.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeformReport {
    /// The variant's name (e.g. `pawn_ff`).
    pub model: &'static str,
    /// The exact model it was fitted to (e.g. `pawn`).
    pub source: &'static str,
    /// One entry per piece of the variant, in profile order.
    pub runs: Vec<RunFit>,
}

impl FreeformReport {
    /// Largest deviation over all runs.
    pub fn max_deviation(&self) -> f64 {
        self.runs
            .iter()
            .map(|r| r.max_deviation)
            .fold(0.0, f64::max)
    }

    /// Total number of control points (a joint shared by two pieces counts twice).
    pub fn control_points(&self) -> usize {
        self.runs.iter().map(|r| r.control_points).sum()
    }
}

/// A fitted variant.
#[derive(Debug, Clone)]
struct Freeform {
    profile: Profile,
    report: FreeformReport,
}

/// Names of the freeform variants (see [`FREEFORM_NAMES`]).
pub fn freeform_names() -> &'static [&'static str] {
    &FREEFORM_NAMES
}

/// The freeform variant called `name` (one of [`FREEFORM_NAMES`]), or None for other names.
pub fn freeform(name: &str) -> Option<Result<Profile, ModelError>> {
    Some(cached(name)?.map(|f| f.profile.clone()))
}

/// How the variant called `name` was fitted, or None for names not in [`FREEFORM_NAMES`].
pub fn fit_report(name: &str) -> Option<Result<&'static FreeformReport, ModelError>> {
    Some(cached(name)?.map(|f| &f.report))
}

/// The process-wide fit of the variant called `name` (fitted on first use).
fn cached(name: &str) -> Option<Result<&'static Freeform, ModelError>> {
    static CACHE: [OnceLock<Result<Freeform, ModelError>>; 5] = [
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
    ];
    let index = FREEFORM_NAMES.iter().position(|n| *n == name)?;
    let fitted = CACHE[index].get_or_init(|| fit_variant(index));
    Some(fitted.as_ref().map_err(Clone::clone))
}

/// Fits variant `index` of [`FREEFORM_NAMES`] to its exact model.
fn fit_variant(index: usize) -> Result<Freeform, ModelError> {
    let (name, source_name) = (FREEFORM_NAMES[index], FREEFORM_SOURCES[index]);
    let source = SOURCE_MODELS[index]()?;
    let fail = |detail: String| ModelError::FreeformFit {
        model: name.to_string(),
        detail,
    };
    let pieces = source.pieces();
    let table = ArcLength::new(pieces);
    let tangents = chain_tangents(pieces).map_err(fail)?;
    // Run boundaries: the profile's ends and every crease, with the one-sided tangents there.
    let mut bounds = vec![(0, 0.0, tangents.start, tangents.start)];
    for (i, join) in tangents.joins.iter().enumerate() {
        if let Join::Crease { before, after } = *join {
            bounds.push((i + 1, table.piece_ends()[i], before, after));
        }
    }
    bounds.push((pieces.len(), table.total(), tangents.end, tangents.end));
    let mut curves = Vec::with_capacity(bounds.len() - 1);
    let mut runs = Vec::with_capacity(bounds.len() - 1);
    for pair in bounds.windows(2) {
        let ((first, s0, _, start), (last, s1, end, _)) = (pair[0], pair[1]);
        let conditions = (EndCondition::Tangent(start), EndCondition::Tangent(end));
        let (knots, fit) = fit_run(&table, s0, s1, conditions).map_err(fail)?;
        if let Some((i, p)) = fit.points.iter().enumerate().find(|(_, p)| p.x < 0.0) {
            return Err(fail(format!(
                "run of pieces {first}..{last}: control point {i} has rho = {} < 0",
                p.x
            )));
        }
        runs.push(RunFit {
            source_pieces: first..last,
            control_points: fit.points.len(),
            max_deviation: fit.max_deviation(),
        });
        curves.push(NurbsCurve::new(FIT_DEGREE, knots, fit.points, None)?);
    }
    Ok(Freeform {
        profile: Profile::new(name, curves)?,
        report: FreeformReport {
            model: name,
            source: source_name,
            runs,
        },
    })
}

/// Fits the run between arc lengths s0 and s1 with adaptively placed knots (see the module
/// doc): returns the knot vector and the fit.
fn fit_run(
    table: &ArcLength,
    s0: f64,
    s1: f64,
    conditions: (EndCondition, EndCondition),
) -> Result<(Vec<f64>, CubicFit), String> {
    // Span boundaries in the piece's parameter, 0 and 1 included.
    let mut breaks = vec![0.0, 1.0];
    loop {
        let mut knots = vec![0.0; FIT_DEGREE];
        knots.extend_from_slice(&breaks);
        knots.extend([1.0; FIT_DEGREE]);
        let (mut fit_params, mut error_params) = (Vec::new(), Vec::new());
        for w in breaks.windows(2) {
            let at = |f: f64| w[0] + (w[1] - w[0]) * f;
            fit_params.extend(
                (0..FIT_SAMPLES_PER_SPAN)
                    .map(|i| at((i as f64 + 0.5) / FIT_SAMPLES_PER_SPAN as f64)),
            );
            error_params.extend(
                (0..=ERROR_SAMPLES_PER_SPAN).map(|i| at(i as f64 / ERROR_SAMPLES_PER_SPAN as f64)),
            );
        }
        let samples = Samples {
            fit: &fit_params,
            error: &error_params,
        };
        let fit = fit_cubic(table, s0, s1, conditions, &knots, &samples)?;
        let (worst, error) = fit
            .deviations
            .chunks(ERROR_SAMPLES_PER_SPAN + 1)
            .map(|span| span.iter().copied().fold(0.0, f64::max))
            .enumerate()
            .fold(
                (0, 0.0),
                |best, (i, e)| if e > best.1 { (i, e) } else { best },
            );
        if error <= FREEFORM_FIT_TOLERANCE {
            return Ok((knots, fit));
        }
        if breaks.len() > MAX_SPANS_PER_RUN {
            return Err(format!(
                "arc length [{s0}, {s1}]: deviation {error:e} after {MAX_SPANS_PER_RUN} spans"
            ));
        }
        breaks.insert(worst + 1, 0.5 * (breaks[worst] + breaks[worst + 1]));
    }
}

#[cfg(test)]
mod tests;

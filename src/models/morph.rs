//! The deformable model M_t of section 5 (Figure 10): a smooth cyclic interpolation through
//! the five static profiles pawn -> cup -> bottle -> table -> lightmill -> pawn.
//!
//! **Common representation.** Every keyframe is refitted, by least squares, as the same
//! chain of [`MORPH_BLOCKS`] pieces, each a clamped cubic B-spline with the same knot
//! vector ([`MORPH_SPANS_PER_BLOCK`] uniform spans). The profile is cut into three regions
//! with a fixed number of blocks each ([`REGION_BLOCKS`]): the bottom disk, the outer side,
//! and a closing region back to the axis ([`CLOSING_ANCHOR`]), so that the cup's cavity
//! blends into the tops of the other shapes instead of folding through their sides. Inside a
//! region, block boundaries are placed at every piece boundary of the source (creases stay
//! exact corners, straight pieces are reproduced exactly), then the block with the largest
//! fit error is halved in arc length until the region's budget is used. Each block is parameterised by arc
//! length and interpolates its end points; at a smooth block boundary (and at the two axis
//! ends) both neighbouring control points are constrained to the source tangent, so the
//! keyframe is G1 there. The fit error of each keyframe (maximum distance between the fitted
//! point and the source point at the same arc-length parameter, an upper bound of the
//! Hausdorff distance up to sampling) is in [`Morph::fit_reports`]: below 1e-4 for all
//! five (see the tests).
//!
//! **Blending.** Frame t lies between keyframes k = floor(5t) and k+1 (cyclically); its
//! control points are (1 - s) P_k + s P_{k+1} with s = 6u^5 - 15u^4 + 10u^3 and u = 5t - k
//! (smootherstep: C2 in t). The weights are non-negative and sum to one, so every frame's
//! control points are convex combinations of the keyframes': the ends stay exactly on the
//! axis, and rho > 0 away from the ends because every keyframe's interior control points
//! have rho > 0 (convex-hull property). Interpolating blends with non-negative weights must
//! have zero velocity at the keyframes, so M_t pauses briefly at each static shape.
//!
//! **Tangent continuity.** Blending two tangent-continuous joints whose tangents differ gives
//! a corner (up to 57 degrees here), so at every block boundary that is smooth in both
//! keyframes being blended, the two handles are turned onto the bisector of their directions
//! (lengths kept): the frame is G1 there, the keyframes are untouched, and the frame still
//! moves continuously with t. The frame has corners only where one of the two keyframes has
//! a crease. This step can move a handle off the convex hull of the blend, so frame validity
//! (rho >= 0, no self-intersection, clearance) is checked by the tests at 1000 frames.

use std::sync::OnceLock;

use nalgebra::{Point2, Vector2};

use super::fit::{
    chain_tangents, fit_cubic, grid_params, midpoint_params, uniform_knots, ArcLength,
    EndCondition, Join, Samples, FIT_DEGREE,
};
use super::paper;
use super::ModelError;
use crate::nurbs::NurbsCurve;
use crate::profile::Profile;

/// Number of pieces of every morph frame.
pub const MORPH_BLOCKS: usize = 16;
/// Uniform cubic spans per piece of a morph frame.
pub const MORPH_SPANS_PER_BLOCK: usize = 4;
/// Degree of the morph frames' pieces.
pub const MORPH_DEGREE: usize = FIT_DEGREE;
/// Control points per piece of a morph frame.
const POINTS_PER_BLOCK: usize = MORPH_SPANS_PER_BLOCK + MORPH_DEGREE;
/// Keyframes in cyclic order (section 5: counter-clockwise through Figure 7 from the pawn).
pub const KEYFRAME_NAMES: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];
/// Start of each keyframe's *closing region* (see [`REGION_BLOCKS`]) as (piece index,
/// fraction of that piece's arc length): the cup's rim with the cavity behind it, and the
/// parts of the others' tops that it blends into: the polar cap of the pawn's head, the
/// bottle's and the table's flat tops, the upper half of the lightmill's finial.
pub const CLOSING_ANCHOR: [(usize, f64); 5] = [(8, 0.8), (3, 0.0), (7, 0.0), (7, 0.0), (10, 0.5)];
/// Blocks per region of every keyframe: the bottom disk (first piece), the outer side, and
/// the closing region back to the axis. Aligning the regions makes corresponding blocks
/// play the same part in every keyframe (the cup's cavity blends into the others' tops), so
/// that the blends do not fold over themselves.
pub const REGION_BLOCKS: [usize; 3] = [1, 11, 4];

/// Tangent turn (radians) above which a join between two source pieces is a crease and the
/// fit leaves it a free corner (shared with the freeform variants).
pub use super::fit::CREASE_ANGLE;
/// Least-squares samples per cubic span of a block.
const FIT_SAMPLES_PER_SPAN: usize = 24;
/// Samples per cubic span at which the fit error is measured.
const ERROR_SAMPLES_PER_SPAN: usize = 64;

/// Fit quality of one keyframe's common representation.
#[derive(Debug, Clone, PartialEq)]
pub struct MorphFitReport {
    /// Source model name.
    pub model: &'static str,
    /// Maximum distance between fitted and source points at equal arc-length parameter.
    pub max_deviation: f64,
    /// Number of source creases kept as exact corners.
    pub creases: usize,
}

/// M_t: the five keyframes in common representation, ready to blend.
#[derive(Debug, Clone, PartialEq)]
pub struct Morph {
    /// Knot vector shared by every piece of every frame.
    knots: Vec<f64>,
    /// Control points per keyframe, blocks concatenated (neighbouring blocks share their
    /// boundary point): MORPH_BLOCKS * (POINTS_PER_BLOCK - 1) + 1 points.
    keyframes: Vec<Vec<Point2<f64>>>,
    /// Per keyframe, whether the boundary between block j and block j + 1 is smooth (G1).
    smooth_joints: Vec<Vec<bool>>,
    reports: Vec<MorphFitReport>,
}

/// Frame M_t of the deformable model (t wraps into [0, 1); non-finite t is an error).
pub fn morph(t: f64) -> Result<Profile, ModelError> {
    Morph::shared()?.frame(t)
}

impl Morph {
    /// The process-wide fitted model (fitted once, on first use).
    pub fn shared() -> Result<&'static Morph, ModelError> {
        static SHARED: OnceLock<Result<Morph, ModelError>> = OnceLock::new();
        SHARED
            .get_or_init(Morph::fit)
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Fit the five static profiles to the common representation.
    pub fn fit() -> Result<Morph, ModelError> {
        let sources = [
            paper::pawn()?,
            paper::cup()?,
            paper::bottle()?,
            paper::table()?,
            paper::lightmill()?,
        ];
        let mut keyframes = Vec::with_capacity(5);
        let mut smooth_joints = Vec::with_capacity(5);
        let mut reports = Vec::with_capacity(5);
        for ((name, source), closing) in KEYFRAME_NAMES.iter().zip(&sources).zip(CLOSING_ANCHOR) {
            let FittedKeyframe {
                points,
                smooth,
                report,
            } = fit_keyframe(name, source, closing).map_err(|detail| ModelError::MorphFit {
                model: name.to_string(),
                detail,
            })?;
            keyframes.push(points);
            smooth_joints.push(smooth);
            reports.push(report);
        }
        Ok(Morph {
            knots: block_knots(),
            keyframes,
            smooth_joints,
            reports,
        })
    }

    /// Fit quality of each keyframe, in [`KEYFRAME_NAMES`] order.
    pub fn fit_reports(&self) -> &[MorphFitReport] {
        &self.reports
    }

    /// The knot vector shared by every piece of every frame.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Control points of keyframe `index` (in [`KEYFRAME_NAMES`] order), blocks concatenated.
    pub fn keyframe_points(&self, index: usize) -> Option<&[Point2<f64>]> {
        self.keyframes.get(index).map(Vec::as_slice)
    }

    /// Control points of frame t, blocks concatenated (block b owns points
    /// `b * 6 ..= b * 6 + 6`), written into `out` (cleared first; reuses its allocation).
    pub fn control_points_into(
        &self,
        t: f64,
        out: &mut Vec<Point2<f64>>,
    ) -> Result<(), ModelError> {
        let (k, s) = blend_position(t)?;
        let next = (k + 1) % 5;
        let (a, b) = (&self.keyframes[k], &self.keyframes[next]);
        out.clear();
        out.extend(
            a.iter()
                .zip(b)
                .map(|(p, q)| Point2::from(p.coords * (1.0 - s) + q.coords * s)),
        );
        // Keyframes (s = 0) are returned exactly as fitted.
        if s > 0.0 {
            let joints = self.smooth_joints[k].iter().zip(&self.smooth_joints[next]);
            for (j, _) in joints.enumerate().filter(|(_, (&sa, &sb))| sa && sb) {
                align_handles(out, (j + 1) * (POINTS_PER_BLOCK - 1));
            }
        }
        Ok(())
    }

    /// Frame M_t as a profile of [`MORPH_BLOCKS`] cubic pieces (t wraps into [0, 1)).
    pub fn frame(&self, t: f64) -> Result<Profile, ModelError> {
        let mut points = Vec::new();
        self.control_points_into(t, &mut points)?;
        let pieces = points
            .windows(POINTS_PER_BLOCK)
            .step_by(POINTS_PER_BLOCK - 1)
            .map(|block| NurbsCurve::new(MORPH_DEGREE, self.knots.clone(), block.to_vec(), None))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Profile::new(format!("morph@{t}"), pieces)?)
    }
}

/// Make the two handles at the block joint `joint` (control point index) collinear: both
/// turn to the bisector of their directions, keeping their lengths. Identity when they are
/// collinear already (at the keyframes), continuous in the handles otherwise; handles that
/// vanish or point back onto each other are left alone.
fn align_handles(points: &mut [Point2<f64>], joint: usize) {
    let center = points[joint];
    let (before, after) = (center - points[joint - 1], points[joint + 1] - center);
    let (Some(u), Some(v)) = (
        before.try_normalize(f64::MIN_POSITIVE),
        after.try_normalize(f64::MIN_POSITIVE),
    ) else {
        return;
    };
    let Some(d) = (u + v).try_normalize(f64::MIN_POSITIVE) else {
        return;
    };
    points[joint - 1] = center - d * before.norm();
    points[joint + 1] = center + d * after.norm();
}

/// Keyframe index k and blend weight s of frame t (see the module doc).
fn blend_position(t: f64) -> Result<(usize, f64), ModelError> {
    if !t.is_finite() {
        return Err(ModelError::NonFiniteMorphParameter(t));
    }
    let x = t.rem_euclid(1.0) * 5.0;
    // rem_euclid can return 1.0 for tiny negative t; the modulo keeps k in 0..5.
    let k = (x.floor() as usize).min(4);
    let u = (x - k as f64).clamp(0.0, 1.0);
    let s = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
    Ok((k, s))
}

/// Clamped uniform cubic knot vector of one block on [0, 1].
fn block_knots() -> Vec<f64> {
    uniform_knots(MORPH_SPANS_PER_BLOCK)
}

/// One fitted block of a keyframe: arc-length interval, end conditions, control points and
/// maximum deviation from the source.
struct Block {
    s0: f64,
    s1: f64,
    start: EndCondition,
    end: EndCondition,
    points: Vec<Point2<f64>>,
    error: f64,
}

/// One keyframe in common representation.
struct FittedKeyframe {
    /// Control points, blocks concatenated.
    points: Vec<Point2<f64>>,
    /// Whether the boundary between block j and block j + 1 is smooth.
    smooth: Vec<bool>,
    report: MorphFitReport,
}

/// Fit one open-on-axis profile to the common representation.
fn fit_keyframe(
    name: &'static str,
    source: &Profile,
    closing: (usize, f64),
) -> Result<FittedKeyframe, String> {
    let pieces = source.pieces();
    let table = ArcLength::new(pieces);
    let tangent_or_err = |v: Option<Vector2<f64>>| v.ok_or("zero tangent at a block end");
    let tangents = chain_tangents(pieces)?;
    // Conditions at s = 0, every piece boundary, and the total length.
    let mut conditions = vec![EndCondition::Tangent(tangents.start)];
    let mut creases = 0;
    for join in &tangents.joins {
        conditions.push(match *join {
            Join::Smooth(tangent) => EndCondition::Tangent(tangent),
            Join::Crease { .. } => {
                creases += 1;
                EndCondition::Free
            }
        });
    }
    conditions.push(EndCondition::Tangent(tangents.end));
    let mut starts = vec![0.0];
    starts.extend_from_slice(table.piece_ends());
    let (piece, fraction) = closing;
    if piece >= pieces.len() || !(0.0..1.0).contains(&fraction) {
        return Err(format!(
            "closing anchor ({piece}, {fraction}) is not on the profile"
        ));
    }
    let closing_s = starts[piece] + fraction * (starts[piece + 1] - starts[piece]);
    let bounds = [0.0, starts[1], closing_s, table.total()];
    // Block boundary condition at arc length s: the piece join there, or the tangent.
    let condition_at = |s: f64| -> Result<EndCondition, String> {
        match starts.iter().position(|&b| b == s) {
            Some(i) => Ok(conditions[i]),
            None => Ok(EndCondition::Tangent(tangent_or_err(table.tangent(s))?)),
        }
    };
    let mut blocks = Vec::with_capacity(MORPH_BLOCKS);
    for (region, &budget) in REGION_BLOCKS.iter().enumerate() {
        let (s_a, s_b) = (bounds[region], bounds[region + 1]);
        let mut cuts = vec![s_a];
        cuts.extend(starts.iter().copied().filter(|&b| b > s_a && b < s_b));
        cuts.push(s_b);
        if s_b <= s_a || cuts.len() - 1 > budget {
            return Err(format!(
                "region {region} (arc length {s_a} to {s_b}) has {} pieces, budget {budget}",
                cuts.len() - 1
            ));
        }
        // One block per piece, then halve the block with the largest fit error until the
        // region's budget is used.
        let mut region_blocks = Vec::with_capacity(budget);
        for pair in cuts.windows(2) {
            let (c0, c1) = (condition_at(pair[0])?, condition_at(pair[1])?);
            region_blocks.push(fit_block(&table, pair[0], pair[1], c0, c1)?);
        }
        while region_blocks.len() < budget {
            let worst = (0..region_blocks.len())
                .max_by(|&a, &b| region_blocks[a].error.total_cmp(&region_blocks[b].error))
                .ok_or("empty region")?;
            let block = region_blocks.remove(worst);
            let mid = 0.5 * (block.s0 + block.s1);
            let at_mid = EndCondition::Tangent(tangent_or_err(table.tangent(mid))?);
            let second = fit_block(&table, mid, block.s1, at_mid, block.end)?;
            let first_half = fit_block(&table, block.s0, mid, block.start, at_mid)?;
            region_blocks.insert(worst, second);
            region_blocks.insert(worst, first_half);
        }
        blocks.extend(region_blocks);
    }
    let mut points = Vec::with_capacity(MORPH_BLOCKS * (POINTS_PER_BLOCK - 1) + 1);
    for (i, block) in blocks.iter().enumerate() {
        let skip = usize::from(i > 0);
        points.extend(block.points.iter().skip(skip));
    }
    let max_deviation = blocks.iter().map(|b| b.error).fold(0.0, f64::max);
    let smooth = blocks[1..]
        .iter()
        .map(|b| matches!(b.start, EndCondition::Tangent(_)))
        .collect();
    Ok(FittedKeyframe {
        points,
        smooth,
        report: MorphFitReport {
            model: name,
            max_deviation,
            creases,
        },
    })
}

/// Least-squares fit of the source between arc lengths s0 and s1 by a clamped cubic with
/// the common block knot vector, parameterised by arc length.
fn fit_block(
    table: &ArcLength,
    s0: f64,
    s1: f64,
    start: EndCondition,
    end: EndCondition,
) -> Result<Block, String> {
    let fit = midpoint_params(FIT_SAMPLES_PER_SPAN * MORPH_SPANS_PER_BLOCK);
    let error = grid_params(ERROR_SAMPLES_PER_SPAN * MORPH_SPANS_PER_BLOCK);
    let samples = Samples {
        fit: &fit,
        error: &error,
    };
    let fitted = fit_cubic(table, s0, s1, (start, end), &block_knots(), &samples)?;
    let error = fitted.max_deviation();
    Ok(Block {
        s0,
        s1,
        start,
        end,
        points: fitted.points,
        error,
    })
}

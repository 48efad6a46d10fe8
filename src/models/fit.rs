//! Least-squares fitting of clamped cubic B-splines to stretches of a profile, shared by the
//! deformable model M_t ([`mod@super::morph`]: every keyframe refitted to a common
//! representation) and the freeform variants of the paper's models ([`super::freeform`]).
//!
//! The source profile is parameterised by arc length ([`ArcLength`]). A stretch between arc
//! lengths s0 and s1 is fitted by one clamped cubic B-spline on the parameter domain [0, 1]
//! (parameter u stands for arc length s0 + u (s1 - s0)) with a caller-chosen knot vector:
//! - the curve interpolates the source at both ends (first and last control points fixed);
//! - an end with [`EndCondition::Tangent`] has its neighbouring control point constrained to
//!   the given tangent line (only the handle length is free), so the fit leaves that end with
//!   a known direction: G1 to a neighbour with the same tangent;
//! - all other control points are free; they minimise the sum of squared distances between
//!   the fitted point at u and the source point at arc length s0 + u (s1 - s0) over the
//!   caller's fit samples (a linear least-squares problem, solved by SVD).
//!
//! The fit's deviation is the distance between fitted and source points at equal parameter,
//! measured at the caller's error samples. Since every fitted point is that close to a source
//! point and every source point that close to a fitted point, its maximum bounds the two-sided
//! Hausdorff distance between the stretch and its fit (up to the sampling of u).

use nalgebra::{DMatrix, DVector, Point2, Vector2};

use crate::nurbs::{basis_functions, NurbsCurve};

/// Degree of every fitted piece.
pub const FIT_DEGREE: usize = 3;

/// Tangent turn (radians) above which a join between two source pieces is a crease (a G0
/// corner) rather than a smooth (G1) join. The built-in models' smooth joins agree to rounding
/// (about 1e-15); their creases turn by at least several degrees.
pub const CREASE_ANGLE: f64 = 1e-6;

/// Samples per knot span of the source pieces in the arc-length table. Only the
/// parameterisation depends on it (the fitted targets are exact curve points).
const ARC_TABLE_SAMPLES_PER_SPAN: usize = 256;

/// Relative singular value cut-off of the least-squares solve.
const LSQ_RCOND: f64 = 1e-12;

/// Arc-length table of an open chain of pieces: (piece, parameter, arc length) samples.
pub struct ArcLength<'a> {
    pieces: &'a [NurbsCurve],
    entries: Vec<(usize, f64, f64)>,
    /// Arc length at the end of each piece.
    piece_ends: Vec<f64>,
}

impl<'a> ArcLength<'a> {
    /// Tabulates the chain `pieces` (joined end to start).
    pub fn new(pieces: &'a [NurbsCurve]) -> Self {
        let mut entries = Vec::new();
        let mut piece_ends = Vec::with_capacity(pieces.len());
        let mut s = 0.0;
        for (i, piece) in pieces.iter().enumerate() {
            let mut prev = piece.start();
            entries.push((i, piece.domain().0, s));
            for (t0, t1) in piece.distinct_spans() {
                for k in 1..=ARC_TABLE_SAMPLES_PER_SPAN {
                    let t = t0 + (t1 - t0) * k as f64 / ARC_TABLE_SAMPLES_PER_SPAN as f64;
                    let p = piece.eval(t);
                    s += (p - prev).norm();
                    prev = p;
                    entries.push((i, t, s));
                }
            }
            piece_ends.push(s);
        }
        ArcLength {
            pieces,
            entries,
            piece_ends,
        }
    }

    /// Arc length of the whole chain.
    pub fn total(&self) -> f64 {
        self.piece_ends.last().copied().unwrap_or(0.0)
    }

    /// Arc length at the end of each piece.
    pub fn piece_ends(&self) -> &[f64] {
        &self.piece_ends
    }

    /// Piece and parameter at arc length s (linear interpolation in the table; the first
    /// piece containing s wins at piece boundaries).
    fn locate(&self, s: f64) -> (usize, f64) {
        let idx = self.entries.partition_point(|e| e.2 < s);
        if idx == 0 {
            return (self.entries[0].0, self.entries[0].1);
        }
        if idx >= self.entries.len() {
            let last = self.entries[self.entries.len() - 1];
            return (last.0, last.1);
        }
        let (a, b) = (self.entries[idx - 1], self.entries[idx]);
        if a.0 != b.0 || b.2 <= a.2 {
            return (b.0, b.1);
        }
        let f = (s - a.2) / (b.2 - a.2);
        (a.0, a.1 + f * (b.1 - a.1))
    }

    /// The source point at arc length s (an exact curve point).
    pub fn point(&self, s: f64) -> Point2<f64> {
        let (piece, t) = self.locate(s);
        self.pieces[piece].eval(t)
    }

    /// The unit tangent (direction of travel) at arc length s, if the derivative is not zero.
    pub fn tangent(&self, s: f64) -> Option<Vector2<f64>> {
        let (piece, t) = self.locate(s);
        unit_tangent(&self.pieces[piece], t)
    }
}

/// Unit tangent of `piece` at parameter `t`, if its derivative is not zero there.
pub fn unit_tangent(piece: &NurbsCurve, t: f64) -> Option<Vector2<f64>> {
    piece.derivatives(t)[1].try_normalize(f64::MIN_POSITIVE)
}

/// The join between two consecutive source pieces.
#[derive(Debug, Clone, Copy)]
pub enum Join {
    /// Tangent-continuous: the mean of the two unit tangents (direction of travel).
    Smooth(Vector2<f64>),
    /// A corner that turns by more than [`CREASE_ANGLE`]: the unit tangents on either side.
    Crease {
        before: Vector2<f64>,
        after: Vector2<f64>,
    },
}

/// Tangents of an open chain: at its start, at every join, at its end.
pub struct ChainTangents {
    pub start: Vector2<f64>,
    pub joins: Vec<Join>,
    pub end: Vector2<f64>,
}

/// Classifies every join of `pieces` as smooth or a crease and reads the end tangents.
pub fn chain_tangents(pieces: &[NurbsCurve]) -> Result<ChainTangents, String> {
    let first = pieces.first().ok_or("empty profile")?;
    let last = pieces.last().ok_or("empty profile")?;
    let tangent_or_err = |v: Option<Vector2<f64>>| v.ok_or("zero tangent at a block end");
    let start = tangent_or_err(unit_tangent(first, first.domain().0))?;
    let mut joins = Vec::with_capacity(pieces.len().saturating_sub(1));
    for pair in pieces.windows(2) {
        let before = tangent_or_err(unit_tangent(&pair[0], pair[0].domain().1))?;
        let after = tangent_or_err(unit_tangent(&pair[1], pair[1].domain().0))?;
        let turn = before.perp(&after).atan2(before.dot(&after));
        joins.push(if turn.abs() <= CREASE_ANGLE {
            Join::Smooth((before + after).normalize())
        } else {
            Join::Crease { before, after }
        });
    }
    let end = tangent_or_err(unit_tangent(last, last.domain().1))?;
    Ok(ChainTangents { start, joins, end })
}

/// How an end of a fitted stretch is joined to its neighbour.
#[derive(Debug, Clone, Copy)]
pub enum EndCondition {
    /// The neighbouring control point lies on this unit tangent (direction of travel).
    Tangent(Vector2<f64>),
    /// The neighbouring control point is free.
    Free,
}

/// Clamped cubic knot vector on [0, 1] with `spans` uniform spans.
pub fn uniform_knots(spans: usize) -> Vec<f64> {
    let mut knots = vec![0.0; FIT_DEGREE + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend([1.0; FIT_DEGREE + 1]);
    knots
}

/// `count` parameters at the midpoints of `count` equal steps of [0, 1].
pub fn midpoint_params(count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| (i as f64 + 0.5) / count as f64)
        .collect()
}

/// `steps + 1` parameters at equal steps of [0, 1], both ends included.
pub fn grid_params(steps: usize) -> Vec<f64> {
    (0..=steps).map(|i| i as f64 / steps as f64).collect()
}

/// Where the fit samples and measures a stretch, in the fitted piece's parameter u in [0, 1].
pub struct Samples<'a> {
    /// Parameters of the least-squares targets.
    pub fit: &'a [f64],
    /// Parameters at which the deviation is measured.
    pub error: &'a [f64],
}

/// One fitted stretch: the control points and the deviation at each error sample.
pub struct CubicFit {
    pub points: Vec<Point2<f64>>,
    /// Distance between fitted and source point at each of [`Samples::error`].
    pub deviations: Vec<f64>,
}

impl CubicFit {
    /// Largest deviation over the error samples.
    pub fn max_deviation(&self) -> f64 {
        self.deviations.iter().copied().fold(0.0, f64::max)
    }
}

/// Unknowns of one control point in the least-squares problem.
#[derive(Debug, Clone, Copy)]
enum Slot {
    /// Interpolated end point.
    Fixed(Point2<f64>),
    /// base + x * dir with the scalar x in column `col`.
    OnTangent {
        col: usize,
        base: Point2<f64>,
        dir: Vector2<f64>,
    },
    /// Free point with coordinates in columns `col`, `col + 1`.
    Free { col: usize },
}

/// Least-squares fit of the source between arc lengths s0 and s1 by a clamped cubic with
/// `knots` (on [0, 1], at least one span), parameterised by arc length (see the module doc).
/// Fails when the solve fails or a tangent handle comes out reversed.
pub fn fit_cubic(
    table: &ArcLength,
    s0: f64,
    s1: f64,
    (start, end): (EndCondition, EndCondition),
    knots: &[f64],
    samples: &Samples,
) -> Result<CubicFit, String> {
    let n = knots.len() - FIT_DEGREE - 1;
    if n < FIT_DEGREE + 1 {
        return Err(format!("knot vector of {} knots has no span", knots.len()));
    }
    let p0 = table.point(s0);
    // The end point is taken from the piece that ends there (not the next one).
    let p1 = table.point(s1);
    let mut slots = vec![Slot::Fixed(p0); n];
    slots[n - 1] = Slot::Fixed(p1);
    let mut cols = 0;
    match start {
        EndCondition::Tangent(dir) => {
            slots[1] = Slot::OnTangent {
                col: cols,
                base: p0,
                dir,
            };
            cols += 1;
        }
        EndCondition::Free => {
            slots[1] = Slot::Free { col: cols };
            cols += 2;
        }
    }
    for slot in slots.iter_mut().take(n - 2).skip(2) {
        *slot = Slot::Free { col: cols };
        cols += 2;
    }
    match end {
        EndCondition::Tangent(dir) => {
            slots[n - 2] = Slot::OnTangent {
                col: cols,
                base: p1,
                dir: -dir,
            };
            cols += 1;
        }
        EndCondition::Free => {
            slots[n - 2] = Slot::Free { col: cols };
            cols += 2;
        }
    }
    let rows = samples.fit.len();
    let mut a = DMatrix::<f64>::zeros(2 * rows, cols);
    let mut rhs = DVector::<f64>::zeros(2 * rows);
    for (i, &u) in samples.fit.iter().enumerate() {
        let target = table.point(s0 + u * (s1 - s0));
        let (rx, ry) = (2 * i, 2 * i + 1);
        rhs[rx] = target.x;
        rhs[ry] = target.y;
        let (span, values) = basis_functions(FIT_DEGREE, knots, u);
        for (k, v) in values.iter().enumerate() {
            match slots[span - FIT_DEGREE + k] {
                Slot::Fixed(p) => {
                    rhs[rx] -= v * p.x;
                    rhs[ry] -= v * p.y;
                }
                Slot::OnTangent { col, base, dir } => {
                    rhs[rx] -= v * base.x;
                    rhs[ry] -= v * base.y;
                    a[(rx, col)] += v * dir.x;
                    a[(ry, col)] += v * dir.y;
                }
                Slot::Free { col } => {
                    a[(rx, col)] += v;
                    a[(ry, col + 1)] += v;
                }
            }
        }
    }
    let x = a
        .svd(true, true)
        .solve(&rhs, LSQ_RCOND)
        .map_err(|e| format!("least-squares solve failed: {e}"))?;
    let mut points = Vec::with_capacity(n);
    for slot in &slots {
        points.push(match *slot {
            Slot::Fixed(p) => p,
            Slot::OnTangent { col, base, dir } => {
                if x[col] <= 0.0 {
                    return Err(format!(
                        "tangent handle reversed (length {}) on arc length [{s0}, {s1}]",
                        x[col]
                    ));
                }
                base + dir * x[col]
            }
            Slot::Free { col } => Point2::new(x[col], x[col + 1]),
        });
    }
    let deviations = samples
        .error
        .iter()
        .map(|&u| {
            let (span, values) = basis_functions(FIT_DEGREE, knots, u);
            let fitted = values
                .iter()
                .enumerate()
                .fold(Vector2::zeros(), |acc, (k, v)| {
                    acc + points[span - FIT_DEGREE + k].coords * *v
                });
            let target = table.point(s0 + u * (s1 - s0));
            (fitted - target.coords).norm()
        })
        .collect();
    Ok(CubicFit { points, deviations })
}

//! Profiles: chains of NURBS pieces that bound a region of the (rho, z) half-plane, rho >= 0.
//! Revolving the region about the z-axis gives the solid (paper section 4.1, Figure 2).
//!
//! A profile is either
//! - [`ProfileKind::Closed`]: the chain's end meets its start and the curve stays in rho > 0,
//!   so the region is the inside of the loop (a ring-like solid), or
//! - [`ProfileKind::OpenOnAxis`]: both ends lie on the axis rho = 0, and the region is closed
//!   by the axis segment between them.

mod simple;

pub use simple::SELF_TOUCH_REL;

use crate::limits::MIN_PROFILE_SIZE;
use crate::nurbs::{Aabb2, NurbsCurve};
use nalgebra::Point2;

/// Relative gap allowed between consecutive pieces, and between an end point and the axis,
/// as a fraction of the profile's size (control-box diagonal). 1e-9 absorbs the rounding of
/// coordinates written with fewer digits, while real gaps in models of size 1 are far larger.
pub const JOIN_TOLERANCE_REL: f64 = 1e-9;

/// Relative arc length below which a piece counts as zero-length (a point, not a curve).
pub const ZERO_LENGTH_REL: f64 = 1e-12;

/// Whether the profile bounds its region by itself or together with the axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProfileKind {
    /// The chain is a loop strictly inside rho > 0.
    Closed,
    /// Both ends lie on the axis; the axis segment between them closes the region.
    OpenOnAxis,
}

/// Why a chain of pieces is not a valid profile.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// No pieces at all.
    #[error("a profile needs at least one piece")]
    Empty,
    /// A control point left the half-plane rho >= 0.
    #[error("piece {piece}, control point {index}: rho = {rho:e} < 0 (profiles live in rho >= 0)")]
    NegativeRho {
        piece: usize,
        index: usize,
        rho: f64,
    },
    /// Consecutive pieces do not meet.
    #[error("gap of {gap:e} between the end of piece {piece} and the start of piece {next}")]
    Gap { piece: usize, next: usize, gap: f64 },
    /// A piece is a point at the profile's scale.
    #[error("piece {piece} has length {length:e}, below {ZERO_LENGTH_REL:e} of the profile's size {size:e}: a point, not a curve")]
    ZeroLength {
        piece: usize,
        length: f64,
        size: f64,
    },
    /// The whole profile is too small to be represented.
    #[error("the profile's size (bounding-box diagonal) {size:e} is below the smallest representable size {MIN_PROFILE_SIZE:e}")]
    TooSmall { size: f64 },
    /// The chain crosses, touches or folds back onto itself (or onto the axis segment that
    /// closes an open profile), within [`SELF_TOUCH_REL`] of its size.
    #[error("{first} and {second} meet at (rho, z) = ({rho:e}, {z:e}): a profile must not cross, touch or fold back onto itself (tolerance {tolerance:e}, 1e-9 of its size)")]
    SelfIntersection {
        first: String,
        second: String,
        rho: f64,
        z: f64,
        tolerance: f64,
    },
    /// A closed chain that reaches the axis would give a solid with a pinched, non-manifold
    /// point on the axis.
    #[error("closed profile touches the axis (min rho = {min_rho:e}); a closed profile must stay in rho > 0")]
    ClosedTouchesAxis { min_rho: f64 },
    /// Ends neither meet nor both lie on the axis.
    #[error("profile is neither closed (start {start:?} != end {end:?}) nor open with both ends on the axis rho = 0")]
    NotClosedNorOnAxis { start: [f64; 2], end: [f64; 2] },
}

/// A validated profile: the pieces, joined end to start, and what kind of region they bound.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    name: String,
    pieces: Vec<NurbsCurve>,
    kind: ProfileKind,
}

impl Profile {
    /// Validates `pieces` as a profile (see [`ProfileError`] for every rejected case).
    ///
    /// The end points of joined pieces are snapped together and ends within the join tolerance
    /// of the axis are not moved (callers write them exactly); the checks only decide validity.
    pub fn new(name: impl Into<String>, pieces: Vec<NurbsCurve>) -> Result<Self, ProfileError> {
        let profile = Self::allowing_self_contact(name, pieces)?;
        let scale = profile.bounding_box().diagonal();
        let closing_axis = profile.kind == ProfileKind::OpenOnAxis;
        if let Some(c) = simple::first_crossing(&profile.pieces, closing_axis, scale) {
            let name = |p: Option<usize>| {
                p.map_or("the axis segment closing the profile".to_string(), |k| {
                    format!("piece {k}")
                })
            };
            let (first, second) = if c.first == c.second {
                (name(c.first), "itself".to_string())
            } else {
                (name(c.first), name(c.second))
            };
            return Err(ProfileError::SelfIntersection {
                first,
                second,
                rho: c.point.x,
                z: c.point.y,
                tolerance: SELF_TOUCH_REL * scale,
            });
        }
        Ok(profile)
    }

    /// Every check of [`Profile::new`] but the last: the chain may touch, cross or fold back
    /// onto itself. Such a chain bounds no well-defined solid; this constructor exists for
    /// robustness tests of the trees and queries on degenerate chains (zero-width fins,
    /// retraces, near-cusps) drawn by property tests, which must not break the library.
    pub fn allowing_self_contact(
        name: impl Into<String>,
        pieces: Vec<NurbsCurve>,
    ) -> Result<Self, ProfileError> {
        if pieces.is_empty() {
            return Err(ProfileError::Empty);
        }
        for (piece, c) in pieces.iter().enumerate() {
            if let Some((index, q)) = c.points().iter().enumerate().find(|(_, q)| q.x < 0.0) {
                return Err(ProfileError::NegativeRho {
                    piece,
                    index,
                    rho: q.x,
                });
            }
        }
        let bbox = pieces
            .iter()
            .map(NurbsCurve::bounding_box)
            .reduce(Aabb2::union)
            .expect("non-empty");
        let scale = bbox.diagonal();
        if scale.is_nan() || scale < MIN_PROFILE_SIZE {
            return Err(ProfileError::TooSmall { size: scale });
        }
        let join_tol = JOIN_TOLERANCE_REL * scale;
        let zero_length = ZERO_LENGTH_REL * scale;
        for (piece, c) in pieces.iter().enumerate() {
            if let Some(length) = zero_length_of(c, zero_length) {
                return Err(ProfileError::ZeroLength {
                    piece,
                    length,
                    size: scale,
                });
            }
        }
        for piece in 0..pieces.len() - 1 {
            let gap = (pieces[piece].end() - pieces[piece + 1].start()).norm();
            if gap > join_tol {
                return Err(ProfileError::Gap {
                    piece,
                    next: piece + 1,
                    gap,
                });
            }
        }
        let start = pieces[0].start();
        let end = pieces[pieces.len() - 1].end();
        let kind = if start.x <= join_tol && end.x <= join_tol {
            ProfileKind::OpenOnAxis
        } else if (start - end).norm() <= join_tol {
            let min_rho = bbox.min.x;
            if min_rho <= join_tol {
                return Err(ProfileError::ClosedTouchesAxis { min_rho });
            }
            ProfileKind::Closed
        } else {
            return Err(ProfileError::NotClosedNorOnAxis {
                start: [start.x, start.y],
                end: [end.x, end.y],
            });
        };
        Ok(Profile {
            name: name.into(),
            pieces,
            kind,
        })
    }

    /// The profile's name (a model name or the file's `name`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The NURBS pieces, joined end to start.
    pub fn pieces(&self) -> &[NurbsCurve] {
        &self.pieces
    }

    /// Closed loop or open with both ends on the axis.
    pub fn kind(&self) -> ProfileKind {
        self.kind
    }

    /// A box that certainly contains the profile (union of the pieces' control boxes).
    pub fn bounding_box(&self) -> Aabb2 {
        self.pieces
            .iter()
            .map(NurbsCurve::bounding_box)
            .reduce(Aabb2::union)
            .expect("a profile has pieces")
    }

    /// Total arc length to within `tolerance`.
    pub fn arc_length(&self, tolerance: f64) -> f64 {
        let per_piece = tolerance / self.pieces.len() as f64;
        self.pieces.iter().map(|c| c.arc_length(per_piece)).sum()
    }

    /// `n` points per piece, evenly spaced in parameter (for drawing and sampling), end points
    /// included; consecutive pieces share their joint once.
    pub fn sample(&self, n_per_piece: usize) -> Vec<Point2<f64>> {
        let n = n_per_piece.max(2);
        let mut out = Vec::with_capacity(n * self.pieces.len());
        for (k, c) in self.pieces.iter().enumerate() {
            let (a, b) = c.domain();
            let first = if k == 0 { 0 } else { 1 };
            out.extend((first..n).map(|i| c.eval(a + (b - a) * i as f64 / (n - 1) as f64)));
        }
        out
    }
}

/// Number of chords of the cheap lower bound on a piece's length in [`has_zero_length`].
const LENGTH_PROBE_CHORDS: usize = 16;

/// The length of `curve` when it is no longer than `threshold`. An inscribed polyline is
/// never longer than the curve, so a probe polyline longer than `threshold` settles the
/// common case without quadrature; only near-degenerate pieces pay for the adaptive arc
/// length.
fn zero_length_of(curve: &NurbsCurve, threshold: f64) -> Option<f64> {
    let (a, b) = curve.domain();
    let probe: f64 = (0..LENGTH_PROBE_CHORDS)
        .map(|i| {
            let t0 = a + (b - a) * i as f64 / LENGTH_PROBE_CHORDS as f64;
            let t1 = a + (b - a) * (i + 1) as f64 / LENGTH_PROBE_CHORDS as f64;
            (curve.eval(t1) - curve.eval(t0)).norm()
        })
        .sum();
    if probe > threshold {
        return None;
    }
    let length = curve.arc_length(threshold);
    (length <= threshold).then_some(length)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point2<f64> {
        Point2::new(x, y)
    }

    fn line(a: Point2<f64>, b: Point2<f64>) -> NurbsCurve {
        NurbsCurve::line(a, b).unwrap()
    }

    #[test]
    fn cylinder_is_open_on_axis() {
        let (a, b, c, d) = (p(0., 0.), p(1., 0.), p(1., 2.), p(0., 2.));
        let prof = Profile::new("cyl", vec![line(a, b), line(b, c), line(c, d)]).unwrap();
        assert_eq!(prof.kind(), ProfileKind::OpenOnAxis);
        assert!((prof.arc_length(1e-12) - 4.0).abs() < 1e-12);
        assert_eq!(prof.sample(3).len(), 7);
    }

    #[test]
    fn square_ring_is_closed() {
        let (a, b, c, d) = (p(1., 0.), p(2., 0.), p(2., 1.), p(1., 1.));
        let prof = Profile::new(
            "box ring",
            vec![line(a, b), line(b, c), line(c, d), line(d, a)],
        )
        .unwrap();
        assert_eq!(prof.kind(), ProfileKind::Closed);
    }

    #[test]
    fn every_bad_chain_has_its_own_error() {
        use ProfileError::*;
        assert!(matches!(Profile::new("e", vec![]), Err(Empty)));
        assert!(matches!(
            Profile::new(
                "neg",
                vec![line(p(0., 0.), p(-1., 1.)), line(p(-1., 1.), p(0., 2.))]
            ),
            Err(NegativeRho {
                piece: 0,
                index: 1,
                ..
            })
        ));
        assert!(matches!(
            Profile::new(
                "gap",
                vec![line(p(0., 0.), p(1., 1.)), line(p(1., 1.1), p(0., 2.))]
            ),
            Err(Gap {
                piece: 0,
                next: 1,
                ..
            })
        ));
        assert!(matches!(
            Profile::new(
                "zero",
                vec![
                    line(p(0., 0.), p(1., 1.)),
                    line(p(1., 1.), p(1., 1.)),
                    line(p(1., 1.), p(0., 2.))
                ]
            ),
            Err(ZeroLength { piece: 1, .. })
        ));
        assert!(matches!(
            Profile::new("point", vec![line(p(0., 0.), p(0., 0.))]),
            Err(TooSmall { .. })
        ));
        assert!(matches!(
            Profile::new("open", vec![line(p(0., 0.), p(1., 1.))]),
            Err(NotClosedNorOnAxis { .. })
        ));
        let (a, b, c, d) = (p(1., 0.), p(2., 0.), p(2., 1.), p(0., 1.));
        assert!(matches!(
            Profile::new(
                "pinched",
                vec![line(a, b), line(b, c), line(c, d), line(d, a)]
            ),
            Err(ClosedTouchesAxis { .. })
        ));
    }
}

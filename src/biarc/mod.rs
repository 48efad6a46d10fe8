//! Biarc trees of profile curves (Son, Yoon, Kim, Elber 2020, section 4.1, Algorithm 1).
//!
//! A profile is split into *spirals* ([`spiral`]), each spiral is approximated by G1 biarcs
//! ([`fit`]) whose two-sided Hausdorff error is bounded by the bilens ([`bound`]), and the
//! recursive mid-parameter subdivision forms a flat bounding-volume hierarchy ([`tree`]).

pub mod arc;
pub mod arc_deviation;
pub mod bound;
pub mod disk;
pub mod fit;
pub mod oracle;
pub mod span;
pub mod spiral;
#[cfg(test)]
mod test_curves;
pub mod tree;

pub use arc::Arc;
pub use disk::Disk;
pub use fit::{fit_biarc, CurveSample, FittedBiarc, PlanarCurve};
pub use tree::{
    BiarcNode, BiarcTree, NodeId, SpiralBound, SpiralInfo, TreeError, TreeStats, UpperNode,
};

/// Errors of biarc fitting, spiral segmentation and tree building.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BiarcError {
    /// The curve's derivative vanishes (or is not finite) where a tangent is needed.
    #[error("zero or non-finite tangent at parameter {t}")]
    ZeroTangent {
        /// Parameter of the offending point.
        t: f64,
    },
    /// A piece with `t1 <= t0`.
    #[error("empty parameter interval [{t0}, {t1}]")]
    EmptyInterval {
        /// Start parameter.
        t0: f64,
        /// End parameter.
        t1: f64,
    },
    /// A piece whose end points coincide (a closed loop cannot be one spiral).
    #[error("piece [{t0}, {t1}] starts and ends at the same point")]
    ClosedPiece {
        /// Start parameter.
        t0: f64,
        /// End parameter.
        t1: f64,
    },
    /// No minor arc fits the data: the piece turns too far to be a short spiral.
    #[error("piece [{t0}, {t1}] is not a short spiral (no minor-arc biarc exists)")]
    NotASpiral {
        /// Start parameter.
        t0: f64,
        /// End parameter.
        t1: f64,
    },
}

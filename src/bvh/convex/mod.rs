//! Convex solids of revolution: a certificate that the solid is convex, decided on its
//! exact profile ([`convexity`]), and the support function of the convex hull of its
//! approximating surface ([`support`]), which the query's convex fast path
//! ([`crate::query::convex`]) runs GJK on, and the chain's pieces kept for its nearest-point
//! questions ([`nearest`]).
//!
//! **Error bound.** The hull of the tree's approximating surface `H` and the true solid `S`
//! are within [`ConvexHullData::error`] of each other (two-sided Hausdorff distance between
//! sets): the chain is within the tree's eps of the profile, so `S` lies in `H` grown by eps
//! (`S` is the hull of its boundary) and, when `S` is convex, `H` lies in `S` grown by eps
//! (the hull of a set within eps of a convex set). A section certified convex up to a dent
//! adds the dent; the hull's rounding adds [`support::HULL_ROUNDING_REL`] of the extent.

pub mod convexity;
pub mod exact;
pub mod nearest;
pub mod support;

use super::QueryTree;
use crate::profile::Profile;
pub use convexity::{certify_convex, ConvexProfile};
pub use nearest::MeridianPiece;
pub use support::SupportTable;

/// What the convex fast path needs of a solid certified convex.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexHullData {
    /// The convexity certificate of the exact profile.
    pub certificate: ConvexProfile,
    /// Support function of the hull of the approximating surface.
    pub support: SupportTable,
    /// Two-sided Hausdorff bound between the hull and the true solid (module doc): the
    /// tree's eps, the certificate's dent and the hull's rounding.
    pub error: f64,
    /// The tree's pieces (`tree.patches`, same order) for nearest points in the meridian
    /// plane ([`nearest`]).
    pub pieces: Vec<MeridianPiece>,
}

impl ConvexHullData {
    /// The data of a solid whose tree `tree` approximates `profile`, when the solid is
    /// certified convex; `None` otherwise (then the query takes the normal traversal).
    pub fn certify(profile: &Profile, tree: &QueryTree) -> Option<ConvexHullData> {
        let certificate = certify_convex(profile)?;
        let support = SupportTable::of_chain(&tree.chain)?;
        let error = tree.eps + certificate.dent + support::HULL_ROUNDING_REL * support.extent;
        error.is_finite().then_some(ConvexHullData {
            certificate,
            support,
            error,
            pieces: nearest::meridian_pieces(tree),
        })
    }
}

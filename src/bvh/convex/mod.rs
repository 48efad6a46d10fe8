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
use crate::num::cross2;
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
    /// The chain's creases (joints where the tangent turns, and ends on the axis that are
    /// not flat: a cone's apex): the meridian points that revolve into rim circles (or
    /// points), where the hull is curved along the rim only ([`crate::query::convex`]'s rim
    /// solver).
    pub creases: Vec<nalgebra::Point2<f64>>,
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
            creases: creases(&tree.chain),
        })
    }
}

/// Turn (radians, as the sine of the angle between unit tangents) above which a joint of the
/// chain is a crease: biarc joints are tangent up to rounding (1e-12 and below), the
/// profile's creases turn by whole angles.
const CREASE_TURN: f64 = 1e-6;

/// The chain's creases: every joint whose tangents differ, and each end whose tangent is
/// not orthogonal to the axis (a smooth pole or a flat disk's centre is no crease).
fn creases(chain: &[crate::bvh::ProfileArc]) -> Vec<nalgebra::Point2<f64>> {
    let mut out = Vec::new();
    if let (Some(first), Some(last)) = (chain.first(), chain.last()) {
        if first.tangent_at(0.0).y.abs() > CREASE_TURN {
            out.push(first.start());
        }
        for w in chain.windows(2) {
            let (t0, t1) = (w[0].tangent_at(1.0), w[1].tangent_at(0.0));
            let sine = cross2(t0, t1).abs();
            if sine > CREASE_TURN || t0.dot(&t1) < 0.0 {
                out.push(w[0].end());
            }
        }
        if last.tangent_at(1.0).y.abs() > CREASE_TURN {
            out.push(last.end());
        }
    }
    out
}

//! Distance from a point `(rho, z)` to a profile curve, and point-in-region with a sign.
//!
//! The dense polyline of [`ProfileGeom`](super::profile_eval::ProfileGeom) is put in a
//! bounding-box hierarchy over consecutive segments. Three queries:
//!
//! - [`PlanarIndex::poly_distance`]: distance to the polyline. Every curve point is within
//!   `sag` of the polyline and every polyline vertex is a curve point, so
//!   `dist(q, curve) >= poly_distance(q) - sag` (used for lower bounds).
//! - [`PlanarIndex::closest`]: the closest *curve* point. All segments whose polyline distance
//!   is within `2 sag` of the best one are candidates (the true closest point is within `sag`
//!   of a segment, whose distance is then at most `dist(q, curve) + sag <= best + 2 sag`);
//!   on each, the parameter is refined by safeguarded Newton on `(C(t) - q) . C'(t) = 0`
//!   over the segment and its two neighbours, also trying the bracket ends, and by a
//!   derivative-free golden-section search over the segment's own range (Newton stalls where
//!   the speed goes to zero; see [`golden_on_piece`]); the nearer point wins. The answer is
//!   an actual curve point, so its distance is `>=` the true distance up to round-off.
//! - [`PlanarIndex::inside_poly`]: crossing parity of a ray towards `+rho` against the
//!   polygon closed by the axis segment (open chains) or by itself (loops). The axis segment
//!   lies at `rho = 0 <= q.rho` and never crosses the ray, so it needs no edge of its own.
//!
//! [`PlanarIndex::signed`] combines them: the sign is the polygon's unless `q` is within
//! `2 sag` of the polyline, where the side of the tangent at the closest curve point decides
//! (the polygon and the curve bound regions that differ only within `sag` of the polyline).

mod closest;
mod hierarchy;
mod piece_search;
#[cfg(test)]
mod tests;

pub use closest::{CurvePoint, Signed};
pub use hierarchy::PlanarIndex;
pub use piece_search::{golden_on_piece, minimise_on_piece, GOLDEN_MAX_ITER, GOLDEN_TOL_ULPS};

//! Every slack and tolerance of the distance query, in one place, with where each number
//! comes from.
//!
//! A certified interval is only as good as its rounding budget: every snap and every
//! inclusive test of a kernel can move a candidate off the exact surfaces, and the query
//! widens its interval by the sum ([`crate::query::query_slack`]). The
//! two sums are [`POSE_SLACK_REL`] (terms that grow with the pose) and [`SIZE_SLACK_REL`]
//! (terms that grow with the pieces); the tests below check, at compile time, that each covers its terms.
//! The other constants are decision thresholds (when two axes count as one, when a fast path
//! may answer) and stopping rules of iterations; none of them widens the interval, each says
//! why it cannot make a bound wrong.
//!
//! This module sits below the solid's hierarchy ([`crate::bvh`]) because the patch snaps are
//! applied when the tree is built.

// ---------------------------------------------------------------------------------------
// The query's rounding budget.
// ---------------------------------------------------------------------------------------

/// Rounding slack of a query relative to the configuration scale `1 + |t| + extent_a +
/// extent_b` (`t` the relative translation, `extent` the radius of a tree's root bounding
/// disk about the origin), for the terms that grow with the pose:
/// * [`BOUND_SLACK`] (`1e-11`), the circle solver's guarantee with margin;
/// * [`AXIS_TOLERANCE`] (`1e-12`, twice: axis direction and offset), solids treated as
///   coaxial move by at most that fraction of the scale.
///
/// Sum `1.2e-11`, rounded up.
pub const POSE_SLACK_REL: f64 = 2e-11;

/// Rounding slack relative to the solids' size `extent_a + extent_b`, for the terms that grow
/// with the pieces: [`POINT_SNAP`] (`1e-12`, twice: parallels treated as points on the axis)
/// and [`ANGLE_SLACK`], [`SEGMENT_SLACK`] (`1e-12` each: a foot accepted that far outside an
/// arc's angle range or a segment's parameter range is off its patch by at most that
/// fraction of the piece's radius or length).
///
/// Sum `4e-12`, rounded up.
pub const SIZE_SLACK_REL: f64 = 5e-12;

/// Relative slack (of the configuration scale) subtracted from computed bounds: the circle
/// solver guarantees its minimum distance to `1e-12` of the scale
/// ([`crate::circle::TIE_REL_TOL`], checked against exact arithmetic by `verify circles`),
/// and composing the pose adds a few ulps; `1e-11` covers both with a 10x margin.
pub const BOUND_SLACK: f64 = 1e-11;

/// Relative tolerance for deciding that two axes are the same line (coaxial solids) or
/// parallel; relative to the size of the configuration. Round-off in composing a pose is
/// ~1e-15; 1e-12 leaves margin and is far below any eps used by trees.
pub const AXIS_TOLERANCE: f64 = 1e-12;

/// Relative size (to the configuration) below which a boundary parallel is a point.
pub const POINT_SNAP: f64 = 1e-12;

/// Angular slack (radians) for deciding that an arc angle lies in an arc's range. Contacts
/// exactly on a shared patch boundary must be kept by both neighbours (inclusive test); the
/// value is above round-off of `atan2` (1e-15) and far below any arc sweep of a tree leaf.
/// A foot accepted up to this far outside the range is off its patch by at most
/// `ANGLE_SLACK * radius`, which the query adds to its interval ([`SIZE_SLACK_REL`]); a foot
/// rejected near a range end loses nothing, since the boundary parallels' candidates cover
/// minima at the patch boundary.
pub const ANGLE_SLACK: f64 = 1e-12;

/// Relative slack on a segment parameter in [0, 1] (same role as [`ANGLE_SLACK`]).
pub const SEGMENT_SLACK: f64 = 1e-12;

// ---------------------------------------------------------------------------------------
// Snaps when the pieces are built (counted in the tree's eps, not in the budget above).
// ---------------------------------------------------------------------------------------

/// Relative distance (to the arc radius) below which an arc centre is put on the axis: a
/// major circle of radius 1e-16 would otherwise be a circle of pure round-off whose
/// meridian planes are meaningless. 1e-10 keeps the surface change far below any eps.
pub const AXIS_SNAP: f64 = 1e-10;

/// Relative rise (to the segment's length) below which a segment is made exactly flat
/// (equal heights) or exactly cylindrical (equal radii): a profile point at `z = -1.4e-18`
/// where its model meant 0 (an M_t frame's bottom) would otherwise make a cone 9e-18 rad from
/// flat, whose common-normal solves are ill-conditioned and fall back to subdivision on
/// every query that reaches it. Each end moves by half the rise, at most 5e-13 of the length.
pub const FLAT_SNAP: f64 = 1e-12;

/// Rounding per rotation step of a piece hull's chord points
/// ([`crate::bvh::hull::PieceHull::of_piece`]), relative to the arc's size (radius plus
/// centre distance): a rotation by a sine/cosine pair moves a unit vector off the unit
/// circle and off its angle by at most about 3 ulps, and placing the point adds one more of
/// the size; 8 ulps (1.8e-15) per step covers both. The hull grows by it, so the chords'
/// hull contains the arc exactly, not only up to rounding.
pub const ROTATION_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// Largest error with which a tree's chain is detected as the offset of a point, a segment of
/// the axis or a circle (a ball, capsule or solid torus, [`crate::bvh::offset_solid::detect`]),
/// relative to `1 + |centre| + r` (both centres for a capsule): arcs fitted to an exact
/// (rational) circle agree with it to rounding (~1e-15), and so do the fitted ends of an exact
/// side; anything farther is not treated as an offset (the traversal handles it). The detection error is added to the
/// closed form's interval.
pub const DETECT_REL: f64 = 1e-9;

/// Relative offset from the axis used to classify points on the axis in point-in-solid
/// tests (far above round-off, far below any feature of a profile).
pub const AXIS_NUDGE: f64 = 1e-10;

// ---------------------------------------------------------------------------------------
// Decision thresholds of the kernels (which case, which fast path).
// ---------------------------------------------------------------------------------------

/// A patch pair is settled by stage 1 when its realised upper bound exceeds its lower bound
/// by at most this fraction of the configuration scale: an exact solve could not narrow it
/// by more than the query's own rounding slack ([`POSE_SLACK_REL`] is `2e-11`; the lower
/// bound already carries [`BOUND_SLACK`]).
pub const SETTLE_REL: f64 = 1e-10;

/// Relative agreement (to the configuration scale) between a realised distance and the
/// torus bound for the boundary kernel's fast path (`parallel_torus_fast`) to accept it: the
/// circle module guarantees its minimum to [`crate::circle::TIE_REL_TOL`] (`1e-12`) of the
/// scale, and the query's slack ([`POSE_SLACK_REL`], `2e-11`) covers both with margin.
pub const FAST_PATH_REL: f64 = 1e-12;

/// A binormal shorter than this (relative to the configuration size) has no direction;
/// the major circles then intersect and the sampled kernel takes over. Round-off of the
/// feet is ~1e-15 of the size.
pub const MIN_BINORMAL_REL: f64 = 1e-12;

/// Outward widening of the Gauss-map restricted ranges: cosine values (dimensionless) and
/// the final angle arcs (radians). The inputs carry round-off of ~1e-16; `acos` near +-1
/// turns a cosine error `e` into an angle error `sqrt(2 e)`, so a 1e-12 cosine margin costs
/// at most 1.5e-6 rad of restriction and covers every round-off.
pub const GAUSS_SLACK: f64 = 1e-12;

/// Below this horizontal length of the other axis (axes nearly parallel) the longitude of
/// the normal is not restricted by the Gauss map: `alpha` would be ill-conditioned.
pub const MIN_AXIS_TILT: f64 = 1e-6;

/// Meridian angles closer than this (radians) are scanned once: the crossing scan's
/// samples along a meridian do not resolve finer angular differences.
pub const MERIDIAN_DEDUP: f64 = 1e-12;

/// Angular resolution of the roots of the meridian-line field (radians per unit of `s`:
/// `d theta / d s <= 4`): 1e-15 in `s` is at double precision; callers polish nothing
/// further.
pub const S_TOL: f64 = 1e-15;

/// Coefficient noise factor of the meridian-line field's polynomials: the coefficients are
/// sums of products of O(size) terms, each with a few ulps of error; 64 eps of the largest
/// product bounds the accumulated rounding (same reasoning as the circle module's degree-8
/// polynomial).
pub const COEFF_NOISE_FACTOR: f64 = 64.0 * f64::EPSILON;

// ---------------------------------------------------------------------------------------
// Stopping rules of iterations (a bound stopped early stays valid, only less tight).
// ---------------------------------------------------------------------------------------

/// The hull iteration stops when the bound is within this fraction of the upper estimate
/// `|v|`: below every tree eps relative to the distances where it matters (1e-6 of a 1e-2
/// gap is 1e-8), and the sagittas and tree eps subtracted afterwards are far larger.
pub const GAP_REL: f64 = 1e-6;

/// Convergence of the hulls' nearest points
/// ([`crate::bvh::hull::ParallelHull::nearest_points`]): they are wanted as the start of a
/// realised pair (projected onto the patches and polished), not as a bound; iterating them
/// to [`GAP_REL`] took up to 24 support points where the start needs a few.
pub const WITNESS_GAP_REL: f64 = 1e-3;

/// Refinement on the exact profiles stops when one round of alternating projections moves
/// the distance by less than this (relative to the size).
pub const REFINE_CONVERGENCE: f64 = 1e-15;

#[cfg(test)]
mod tests {
    use super::*;

    /// The pose-proportional slack covers its terms: the bounds' slack and the coaxial
    /// snap (axis direction and offset).
    #[test]
    fn pose_slack_covers_its_terms() {
        const { assert!(POSE_SLACK_REL >= BOUND_SLACK + 2.0 * AXIS_TOLERANCE) };
    }

    /// The size-proportional slack covers its terms: two parallels snapped to points, a
    /// foot off an arc's angle range and one off a segment's parameter range.
    #[test]
    fn size_slack_covers_its_terms() {
        const { assert!(SIZE_SLACK_REL >= 2.0 * POINT_SNAP + ANGLE_SLACK + SEGMENT_SLACK) };
    }

    /// A settled pair cannot hide more than the query's own slack: the settle threshold is
    /// above the pose slack it must not undercut, and the fast path's agreement is within it.
    #[test]
    fn thresholds_sit_inside_the_budget() {
        const { assert!(SETTLE_REL >= POSE_SLACK_REL) };
        const { assert!(FAST_PATH_REL + BOUND_SLACK <= POSE_SLACK_REL) };
    }
}

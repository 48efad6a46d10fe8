//! The distance query between two posed solids: the entry points and their checks, the
//! interval's rounding slack ([`query_slack`]: every snap and tolerance of the kernels), and
//! the choice of path: the closed form for balls and solid tori
//! ([`crate::query::closed_form`]), the convex path ([`crate::query::convex`]), else the
//! search over the boundary surfaces ([`crate::query::search`]) followed by solid semantics
//! (overlap and nesting give 0, [`crate::query::front::overlap`]), optional refinement on
//! the exact surfaces, and frame coherence through a [`QueryCache`].
//!
//! Certification: the search bounds the distance between the boundary surfaces; the
//! interval is widened by the query's rounding slack. Solids that do not overlap have the
//! surfaces' distance; overlapping or nested solids have distance 0. `overlap = true` (with
//! `lower = upper = 0`) only with a certificate: a point inside both true solids. When
//! overlap can be neither certified nor excluded at the trees' accuracy, `lower = 0`.

use super::overlap::{certify_overlap, inscribed_overlap, nesting, Verdict};
use super::refine::refine_on_profiles;
use crate::bvh::QueryTree;
use crate::query::bound::node_pair::BoundKind;
use crate::query::certified::{Certified, TraversalStats};
use crate::query::closed_form::offset_distance;
use crate::query::convex::convex_distance;
use crate::query::search::{traverse, Budget, TraversalOptions};
use crate::solid::Solid;
use crate::tolerances::{POSE_SLACK_REL, SIZE_SLACK_REL};
use nalgebra::{Isometry3, Point3};

/// How wide the certified interval `upper - lower` may be when the query stops.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Tolerance {
    /// The accuracy the trees were built for: `upper - lower <= eps_a + eps_b`, the
    /// trees' requested bounds ([`QueryTree::target_eps`]). Then `|value - distance| <= eps_a + eps_b`, the error bound a distance between
    /// two meshes of Hausdorff error `eps_a` and `eps_b` has.
    #[default]
    Trees,
    /// `upper - lower <= T` (absolute, length units); `0` runs until nothing can be
    /// narrowed further.
    Absolute(f64),
}

impl Tolerance {
    /// The absolute width for trees of bounds `eps_a`, `eps_b`.
    pub fn width(self, eps_a: f64, eps_b: f64) -> f64 {
        match self {
            Tolerance::Trees => eps_a + eps_b,
            Tolerance::Absolute(t) => t.max(0.0),
        }
    }
}

/// What the caller asks of a query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QueryOptions {
    /// When to stop ([`Tolerance`]). The trees' eps limit what is reachable: a leaf pair's
    /// own interval is `2 (e_a + e_b)` wide, `e` the leaves' eps, so a query stops at the
    /// requested width or at the narrowest interval its leaves allow, whichever is wider.
    pub tolerance: Tolerance,
    /// Anytime budget.
    pub budget: Budget,
    /// Node-pair bound used for inner nodes.
    pub bound: BoundKind,
    /// Refine the witness points on the exact NURBS surfaces (needs the profiles).
    pub refine: bool,
    /// Answer pairs of balls and solid tori in closed form ([`crate::query::closed_form`]),
    /// and overlapping solids whose inscribed balls or solid tori overlap
    /// ([`crate::bvh::inscribed`]); `false` runs the traversal for them too (to measure it,
    /// or to compare the two).
    pub closed_form: bool,
    /// Answer pairs of solids certified convex by GJK ([`crate::query::convex`]) when no
    /// refinement is asked for; `false` runs the traversal for them too.
    pub convex_path: bool,
}

impl Default for QueryOptions {
    fn default() -> Self {
        QueryOptions {
            tolerance: Tolerance::Trees,
            budget: Budget::default(),
            bound: BoundKind::default(),
            refine: false,
            closed_form: true,
            convex_path: true,
        }
    }
}

/// Result of a distance query: the [`Certified`] answer of whichever path took it, in the
/// world frame.
pub type Distance = Certified;

/// Frame coherence for sequences of queries on the same pair: the best leaf pair of the
/// last query gives the next query its first upper bound (a realised pair of that leaf
/// pair, instead of the one a dive along bounding spheres reaches).
#[derive(Debug, Clone, Default)]
pub struct QueryCache {
    last_pair: Option<(u32, u32)>,
}

/// Distance between two posed solids.
pub fn distance(a: &Solid, b: &Solid, opts: &QueryOptions) -> Distance {
    distance_cached(a, b, opts, &mut QueryCache::default())
}

/// Largest configuration scale a query accepts: squared lengths of up to `1e300` stay
/// finite. Beyond it [`distance`] returns the trivial certificate `[0, inf]` and
/// [`try_distance`] an error.
pub const MAX_SCALE: f64 = 1e150;

/// Why a query cannot be answered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QueryError {
    /// A pose has a NaN or infinite component.
    #[error("pose is not finite")]
    NonFinitePose,
    /// The solids are too far apart or too large for double precision.
    #[error("configuration scale {scale:e} (translation plus solid sizes) exceeds the representable range {MAX_SCALE:e}")]
    OutOfRange { scale: f64 },
    /// A solid has an empty tree.
    #[error("solid has no surface (empty tree)")]
    EmptySolid,
}

fn extent(t: &QueryTree) -> f64 {
    t.nodes
        .get(t.root as usize)
        .map_or(0.0, |n| n.bound.center.coords.norm() + n.bound.radius)
}

/// The absolute rounding slack of a query between `ta` and `tb` at `pos_ab`
/// ([`POSE_SLACK_REL`], [`SIZE_SLACK_REL`]).
pub fn query_slack(ta: &QueryTree, tb: &QueryTree, pos_ab: &Isometry3<f64>) -> f64 {
    let size = extent(ta) + extent(tb);
    POSE_SLACK_REL * (1.0 + pos_ab.translation.vector.norm() + size) + SIZE_SLACK_REL * size
}

/// Checks that a query between `a` and `b` is within the representable range.
pub fn check_query(a: &Solid, b: &Solid) -> Result<(), QueryError> {
    check_posed(a, b, &a.relative_pose(b))
}

/// [`check_query`] with B's pose in A's frame, `pos_ab`, already computed.
fn check_posed(a: &Solid, b: &Solid, pos_ab: &Isometry3<f64>) -> Result<(), QueryError> {
    let finite = |p: &Isometry3<f64>| {
        p.translation.vector.iter().all(|x| x.is_finite())
            && p.rotation.coords.iter().all(|x| x.is_finite())
    };
    if !finite(&a.pose) || !finite(&b.pose) {
        return Err(QueryError::NonFinitePose);
    }
    if a.tree.nodes.is_empty() || b.tree.nodes.is_empty() {
        return Err(QueryError::EmptySolid);
    }
    let tmax = pos_ab.translation.vector.amax();
    let scale = 1.0 + tmax + extent(&a.tree) + extent(&b.tree);
    // NaN fails `is_finite`; a finite scale must not exceed the range.
    if !scale.is_finite() || scale > MAX_SCALE {
        return Err(QueryError::OutOfRange { scale });
    }
    Ok(())
}

/// [`distance`], with an error for poses outside the representable range.
pub fn try_distance(a: &Solid, b: &Solid, opts: &QueryOptions) -> Result<Distance, QueryError> {
    try_distance_cached(a, b, opts, &mut QueryCache::default())
}

/// [`distance_cached`], with an error for poses outside the representable range.
pub fn try_distance_cached(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    cache: &mut QueryCache,
) -> Result<Distance, QueryError> {
    let pos_ab = a.relative_pose(b);
    check_posed(a, b, &pos_ab)?;
    Ok(checked_distance(a, b, &pos_ab, opts, cache))
}

/// [`distance`] with a warm start from `cache`, which is updated.
///
/// Solid semantics (`query/front/overlap.rs`): the search bounds the distance between the
/// boundary surfaces; overlap is reported only with a certificate (a point inside both true
/// solids); when overlap can be neither certified nor excluded, `lower = 0`.
pub fn distance_cached(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    cache: &mut QueryCache,
) -> Distance {
    // Outside the representable range the only certificate is the trivial one.
    try_distance_cached(a, b, opts, cache).unwrap_or(Certified {
        value: f64::INFINITY,
        lower: 0.0,
        upper: f64::INFINITY,
        point_a: Point3::origin(),
        point_b: Point3::origin(),
        overlap: false,
        stats: TraversalStats::default(),
    })
}

/// The query proper, for solids that passed [`check_query`].
fn checked_distance(
    a: &Solid,
    b: &Solid,
    pos_ab: &Isometry3<f64>,
    opts: &QueryOptions,
    cache: &mut QueryCache,
) -> Distance {
    let pos_ab = *pos_ab;
    let slack = query_slack(&a.tree, &b.tree, &pos_ab);
    if let (true, Some(oa), Some(ob)) = (opts.closed_form, &a.tree.offset, &b.tree.offset) {
        if let Some(answer) = offset_distance(oa, ob, &pos_ab, slack) {
            return answer.placed(&a.pose);
        }
    }
    if opts.convex_path && !opts.refine {
        let width = opts.tolerance.width(a.tree.target_eps, b.tree.target_eps);
        if let Some(r) = convex_distance(&a.tree, &b.tree, &pos_ab, slack, width) {
            return r.placed(&a.pose);
        }
    }
    // Nested, coincident and deeply overlapping solids: their inscribed balls or solid
    // tori overlap, a closed form certifies it without the traversal.
    if opts.closed_form {
        if let Some(x) = inscribed_overlap(&a.tree, &b.tree, &pos_ab, slack) {
            let stats = TraversalStats {
                closed_forms: 1,
                ..TraversalStats::default()
            };
            return Certified::overlap_at(x, stats).placed(&a.pose);
        }
    }
    search_path(a, b, &pos_ab, slack, opts, cache).placed(&a.pose)
}

/// The search's bounds on the boundary surfaces ([`traverse`]) made an answer for the
/// solids (A's frame): the overlap or nesting verdict, then refinement when asked.
fn search_path(
    a: &Solid,
    b: &Solid,
    pos_ab: &Isometry3<f64>,
    slack: f64,
    opts: &QueryOptions,
    cache: &mut QueryCache,
) -> Certified {
    // The answer is widened by the rounding slack on both sides: the traversal stops that
    // much narrower, so that `upper - lower` keeps within the requested width.
    let width = opts.tolerance.width(a.tree.target_eps, b.tree.target_eps);
    // A query whose interval may reach 0 within the requested width (the surfaces may touch
    // within it) keeps narrowing until its lower bound clears the slack (`lower_floor`):
    // certifying "no overlap" after it would search both solids for a point inside the
    // other. It used to be a second pass at tolerance 0 from the root; one pass does the
    // same without expanding the upper node pairs twice.
    let topts = TraversalOptions {
        tolerance: (width - 2.0 * slack).max(0.0),
        lower_floor: slack,
        budget: opts.budget,
        bound: opts.bound,
    };
    let s = traverse(&a.tree, &b.tree, pos_ab, &topts, cache.last_pair);
    cache.last_pair = s.best_pair.or(cache.last_pair);
    let eps_sum = a.tree.eps + b.tree.eps;
    let surface_lower = (s.lower - slack).max(0.0);
    let surface_upper = s.upper + slack;

    let may_meet = s.surfaces_meet || surface_lower <= 0.0;
    let verdict = if may_meet {
        // A verified interpenetration (deepest common normal with both ends inside the
        // other solid) first, then sampled points of either solid inside the other.
        let pen = s
            .penetration
            .filter(|&(_, _, m)| m > eps_sum + slack)
            .map(|(p, _, _)| p);
        let witness = Some((s.point_a, s.point_b));
        match pen.or_else(|| {
            certify_overlap(
                &a.tree,
                &b.tree,
                pos_ab,
                s.best_pair,
                witness,
                s.surfaces_meet,
                slack,
            )
        }) {
            Some(x) => Verdict::Overlap(x),
            None => Verdict::Undecided,
        }
    } else {
        nesting(&a.tree, &b.tree, pos_ab, &s.point_a, &s.point_b, slack)
    };
    let lower = match verdict {
        Verdict::Overlap(x) => return Certified::overlap_at(x, s.stats),
        Verdict::Apart => surface_lower,
        Verdict::Undecided => 0.0,
    };
    let mut upper = surface_upper;
    let (mut pa, mut pb) = (s.point_a, s.point_b);
    let mut value = s.approx;
    if opts.refine {
        if let Some(r) = refine_on_profiles(a, b, pos_ab, &pa, &pb) {
            // Two points on the exact boundaries: their distance is an upper bound. A value
            // below the certified lower bound would contradict it; it is never used to move
            // the lower bound, and such a refinement is discarded.
            if r.distance >= lower && r.distance <= upper {
                upper = r.distance;
                value = r.distance;
                pa = r.point_a;
                pb = r.point_b;
            }
        }
    }
    Certified {
        value: value.clamp(lower, upper),
        lower,
        upper,
        point_a: pa,
        point_b: pb,
        overlap: false,
        stats: s.stats,
    }
}

//! Translational penetration depth and signed distance of two posed solids, as a certified
//! interval, with the translation that achieves its upper bound.
//!
//! **Definition.** `PD(A, B) = inf { |t| : A and B + t have disjoint interiors }`, the
//! shortest translation of B that separates the solids; the *signed distance* is the
//! distance when the solids are apart and `-PD` when they overlap. Both are
//! 1-Lipschitz in B's translation.
//!
//! **Lower bound: two balls about one common point.** Let `x` be a point inside both
//! solids with clearances `c_A = d(x, dA) > 0` and `c_B = d(x, dB) > 0` (`dA` the boundary
//! surface). The open balls `U(x, c_A)` and `U(x, c_B)` lie in the interiors of A and B.
//! Translating B by `t` carries its ball to `U(x + t, c_B)`, inside the interior of
//! `B + t`. If `|t| < c_A + c_B`, some `lambda` lies in `(|t| - c_B, c_A)` and in
//! `[0, |t|]`, and the point `p = x + lambda t / |t|` (`p = x` when `t = 0`) is within
//! `lambda < c_A` of `x` and within `|t| - lambda < c_B` of `x + t`: it is interior to both A
//! and `B + t`, so `t` does not separate them. Hence `PD >= c_A + c_B` for every common
//! point, which is at least the bound `2 rho` of one ball of radius
//! `rho = min(c_A, c_B)` inside both (the special case `c_A = c_B = rho`, where the two
//! balls `U(x, rho)` and `U(x + t, rho)` meet while `|t| < 2 rho`). The sum is the better
//! certificate: for a ball of radius `r_2` nested in a ball of radius `r_1` it gives
//! `PD = r_1 + r_2 - |c_1 - c_2|` exactly at B's centre, where `2 rho = 2 r_2` falls short;
//! between two balls that cross, both give the exact depth at the lens's centre, and for a
//! shallow contact of two smooth surfaces (depth below both curvature radii) the lens's
//! thickness, which is PD to first order.
//!
//! **The same bound at any point: signed margins.** Let `s_A(x)` be A's signed margin,
//! `d(x, dA)` inside A and `-d(x, A)` outside, and `s_B` likewise; both are 1-Lipschitz. At
//! any point `x` with `s_A(x) + s_B(x) > 0`, `PD >= s_A(x) + s_B(x)`. One margin is
//! positive, say `s_A(x) = c_A > 0`, so `U(x, c_A)` lies in A's interior. For
//! `|t| < c_A + s_B(x)`, B's margin at `x` after the translation is
//! `s_B(x - t) >= s_B(x) - |t| > -c_A`: either `x` is interior to `B + t`, or `B + t` has a
//! point within `c_A` of `x`, inside `U(x, c_A)`, and being a solid (the closure of its
//! interior) it has interior points there too; either way the interiors meet. Inside both
//! solids this is the bound above; outside one it certifies a corner of A pressed into a
//! face of B from the points beyond the corner on the face's normal (`s_A = -|x - corner|`,
//! `s_B = depth + |x - corner|`), and a ball of radius `r` centred at `c` outside A from its
//! centre (`r - d(c, A)`, the exact depth where A is convex near the contact), two
//! certificates that need no ball inside both solids.
//!
//! For a solid of revolution `d(x, dA)` (and `d(x, A)` outside) is the planar distance from
//! `x`'s meridian point `(hypot(x, y), z)` to the profile, in the half-plane `rho >= 0` (the
//! distance to a point of the surface at revolution angle `theta'` is smallest at
//! `theta' = theta(x)`). The query knows the approximating chain, within the tree's bound `e`
//! of the true profile both ways, so a chain margin `m > e` (inside) gives a true clearance
//! of at least `m - e`, the classification of `x` being that of the true solid
//! ([`crate::bvh::containment`]), and any other point is within `|m| + e` of the true
//! surface, a true signed margin of at least `-(|m| + e)`
//! ([`deepest::certified_margin`], with the query's rounding budget `slack`,
//! [`crate::query::query_slack`], added to `e`: the same discipline as the overlap
//! certificate, `query/front/overlap.rs`). The certified bound is the sum of the two, when
//! positive. The search for the point ([`deepest`]) is local ascents, from the distance
//! query's overlap point and, when the interval is still wider than asked, from the upper
//! bound's last contact (B's point there lies inside A about as deep as the separating
//! translation is long, often in another overlap region): a point they find is a
//! certificate however it was found, and a missed better point only makes the bound
//! weaker.
//!
//! **Several contact regions: a covering of translations.** `PD >= L` as soon as every
//! translation `t` with `|t| < L` leaves the solids overlapping, and a point `x` whose
//! signed margins at the pose `B + t0` sum to `sigma > 0` certifies every `t` within
//! `sigma` of `t0` (B's margin at `x` is 1-Lipschitz in B's translation). The bound above is
//! the ball of radius `s_A + s_B` about `t0 = 0`. Where a bump sits in a groove, touching
//! both walls, each way out is blocked by another region and the depth exceeds any one
//! point's sum; [`translation_cover`] covers the ball of translations by such balls (cells
//! of directions times radii, each certified at its centre), which reaches it. It runs when
//! the interval is still not narrow after the point's and the upper bound's searches.
//!
//! **Upper bound: a certified separating translation.** Let the distance query certify
//! `d(A, B + t) >= L > 0` at a translation `t`. The distance is 1-Lipschitz in B's
//! translation, so `d(A, B + t - v) >= L - |v| > 0` for `|v| < L`: every such translation
//! separates, and taking `v` along `t` gives `PD <= |t| - L`. The translation actually
//! queried is the difference of two floating-point poses, measured after rounding, and the
//! bound adds the query's rounding slack. The search ([`separate`]) starts from the
//! deepest point's nearest surface points (the translation moving B's nearest point onto
//! A's, exact for two balls), and steps in contact space: at a separated translation with
//! witness normal `n` and gap `g`, the touching translation is about `t - g n`, and its
//! component along `n` (the nearest point of the contact's tangent plane in translation
//! space) is the next candidate. The fixed points are translations parallel to the contact
//! normal, where the minimal translation of a smooth contact is. When the covering of
//! translations stops short of its goal, the cell that stopped it is a translation no
//! point's margins held B in at (or, when its cells ran out, the first it had not
//! examined): a few more queries search along it, where the deepest point's directions
//! may all have missed a sideways way out. A ball's covering, capped
//! likewise, gives the search its first direction: the ball's way out.
//!
//! **What is certified and what is not.** `lower <= PD <= upper` always (an unanswered side
//! stays `0` or `inf`). Narrow intervals are reached for shallow contacts and for balls
//! against any solid; deep interlocked solids may leave a wide interval, whose ends remain
//! honest. `verify penetration` checks both ends against the oracle and exact ball depths.

pub mod ball_depth;
pub mod deepest;
pub mod separate;
pub mod signed;
mod stages;
pub mod translation_cover;

#[cfg(test)]
mod tests;

pub use signed::{
    penetration, signed_distance, LowerCertificate, Penetration, PenetrationStats, SignedDistance,
};

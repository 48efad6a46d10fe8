//! Distance between the boundary surfaces of two posed solids of revolution, with a realised
//! upper estimate, a lower estimate and an inside/outside census.
//!
//! # The reduction
//! For a point `y` of A's surface, the distance from `y` to B's surface of revolution equals
//! the planar distance from `y`'s `(rho, z)` in B's frame to B's profile curve (the closest
//! point of a surface of revolution lies in the meridian half-plane through `y`). So the
//! surface distance is `min over (t, theta) of f(t, theta)`, with
//! `f(t, theta) = dist_B(y_A(t, theta))`, `y_A` A's surface parametrised by the profile
//! parameter `t` and the revolution angle `theta`. The same is done with A and B swapped.
//!
//! # Lower estimate (branch and bound)
//! A *cell* is a parameter interval `[ta, tb]` of one piece of the source profile times an
//! angle interval `[th0, th1]`. Its surface patch lies within `r_cell` of the centre point
//! `c = y(tm, thm)`:
//! `|y(t, th) - c| <= |C(t) - C(tm)| + |R_th C(tm) - R_thm C(tm)| <= r_param + 2 rho(tm) sin((th1 - th0) / 4)`,
//! where `r_param` bounds the distance from `C(tm)` to the arc `C([ta, tb])` by the arc length
//! of each half, estimated by a two-chord inscribed polygon times [`ARC_SAFETY`] (cells start
//! with a turning angle below [`MAX_TURN`], where the two-chord polygon is within 0.3% of the
//! arc). `dist_B` is 1-Lipschitz in the 3-D point and
//! `dist_B >= poly_distance_B - sag_B` ([`super::planar`]), so every point of the cell is at
//! least `lb = poly_distance_B(c) - sag_B - r_cell` from B's surface. Cells are split (in
//! the dimension contributing more to `r_cell`) best-first by `lb` until the smallest `lb`
//! reaches `upper - tau`, or the budget runs out; the lower estimate is the smallest `lb`
//! left (clamped at 0). It is a lower bound up to the two stated estimates (sagitta and arc
//! length), both taken with a factor of safety. Both directions bound the same surface
//! distance, so the branch and bound runs in one of them only (the one with the smaller
//! initial grid); the other direction's grid still serves the inside census and seeds.
//! With a goal (`OracleOptions::goal`) the search stops as soon as the lower estimate is
//! known to be at least the goal, or cannot exceed it (the realised upper estimate is at or
//! below it): the estimate is then as tight as its user needs, and still a lower bound.
//!
//! # Upper estimate
//! From the best, mutually distant cells (and from any cell found later whose centre beats the
//! current upper by `tau / 2`), a local minimisation of `f` over `(t, theta)`: BFGS on scaled
//! variables with the gradient `n . dy/d(t, theta)` (`n` the unit vector from B's closest
//! point to `y`: envelope theorem), `t` clamped to its piece and hopping to the neighbouring
//! piece at a joint, then a few rounds of alternating projection between the two surfaces.
//! Every value is the distance of two actual surface points (own NURBS evaluation), so the
//! upper estimate is `>=` the true distance up to round-off.
//!
//! # Inside census
//! At every initial grid cell centre of both directions, and at every point a local
//! minimisation ends on, the sign of the planar distance in the other solid is taken
//! (polygon crossing parity, or the tangent side within `2 sag` of the polyline); a point
//! deeper than `poly_distance - sag > margin` (or a realised curve distance `> margin` on
//! the tangent branch) inside the other solid certifies that the solids overlap.
//! Solids overlap exactly when a point of one boundary lies inside the other solid (crossing
//! boundaries or nesting), so with both directions sampled, nesting is always seen; crossing
//! boundaries whose penetration falls between samples show up as `upper ~ 0`.

mod branch_bound;
mod cells;
mod direction;
mod driver;
mod local_min;
mod options;
mod result;

pub use driver::{refine_hint, surface_distance};
pub use options::OracleOptions;
pub use result::OracleResult;

/// Factor on the two-chord estimate of a half-cell's arc length.
pub const ARC_SAFETY: f64 = 1.02;
/// Largest turning angle (radians) between the two chords of an initial parameter interval.
pub const MAX_TURN: f64 = 0.35;
/// In quick mode with a goal, cells are not split below this radius (relative to the source
/// profile's size) to prove the surfaces apart; the local minimisations decide instead.
pub const QUICK_GOAL_MIN_CELL_REL: f64 = 1e-4;

/// Relative margin for the inside census: a sample must be deeper than this times the scene
/// scale (1 + |translation| + sizes) to count as inside; a few hundred ulps of the scene's
/// coordinates, far below any eps a query uses.
pub const INSIDE_MARGIN_REL: f64 = 1e-13;

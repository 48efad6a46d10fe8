//! Cross-check of revdist against FCL on certified meshes, against CGAL and libccd on
//! convex pairs, and against OpenCASCADE on the true curved surfaces ([`occt`], its own
//! criterion and poses) (`docs/verification.md`, section 4).
//!
//! # What is compared
//!
//! * **Mesh pairs** ([`runner`]): the 15 pairs (with repetition) of the paper models pawn, cup,
//!   bottle, table, lightmill, and the M_t frames [`shapes::MORPH_FRAMES`] against each of
//!   them, at every requested eps. Each model is a revdist solid (biarc tree of bound eps) and
//!   a certified mesh (`revdist::tessellate`, two-sided Hausdorff bound `h <= eps` to the true
//!   surface), the latter given to FCL as a `BVHModel<OBBRSS>`. Poses ([`poses`]): separated
//!   (gaps 0.1..1), near-touching (gaps 1e-4..1e-1), overlapping (pushed past contact), and B
//!   placed at random inside A's bounding ball (interlocked, nested or crossing, as the shapes
//!   allow).
//! * **Convex pairs** ([`convex`]): sphere, capsule, cone and cylinder, tessellated; the convex
//!   hulls of the posed mesh vertices go to CGAL's exact `Polytope_distance_d`, to FCL's
//!   libccd GJK distance and, when they overlap, to libccd's GJK+EPA penetration.
//!
//! # Agreement criterion ([`criterion`])
//!
//! Write `S_a, S_b` for the true surfaces, `K_a, K_b` for the true solids, `M_a, M_b` for the
//! meshes, with certified `d_H(M, S) <= h` (two-sided). revdist returns a certified interval
//! `[lower, upper]` for the **solids'** distance `D_K = dist(K_a, K_b)` (0 when they overlap
//! or nest). FCL returns the **meshes'** distance `d_f = dist(M_a, M_b)`, exactly for the meshes
//! up to rounding (0 when the triangle sets intersect; it has no signed mesh distance).
//!
//! 1. *Distance between sets is 1-Lipschitz in the Hausdorff distance of each set*: if
//!    `d_H(X, X') <= h` then `|dist(X, Y) - dist(X', Y)| <= h`. So the surfaces' distance
//!    `D_S = dist(S_a, S_b)` lies in `[max(0, d_f - h_a - h_b), d_f + h_a + h_b]`. When
//!    `d_f = 0` this reads `D_S <= h_a + h_b`.
//! 2. *Solids vs surfaces*: `D_K <= D_S` always, with equality unless the solids share a point
//!    while the surfaces are apart (one nested in the other or in its cavity).
//! 3. Hence, when the solids do not meet, both intervals contain `D_K = D_S` and must
//!    intersect: **passed** when `[lower, upper]` meets `[d_f - h_a - h_b, d_f + h_a + h_b]`
//!    widened by the rounding slack [`criterion::SLACK_REL`] times the scale `1 + |t| +
//!    size_a + size_b`.
//! 4. When the intervals are disjoint with revdist *below* FCL and revdist's lower bound is 0,
//!    the case is **explained** if the solids certainly share a point: FCL's nearest point on
//!    `M_b` lies inside solid A (revdist's point-in-solid test through A's tree) with a margin
//!    above `eps_a + h_b` (the tree's chain is within `eps_a` of `S_a`, the mesh point within
//!    `h_b` of a point of `S_b`, so that point of `S_b` is inside `K_a`), or symmetrically
//!    FCL's point on `M_a` inside B. A point of `S_b` inside `K_a` lies in both solids, so
//!    `D_K = 0` whatever `D_S` is. Every other disjoint case is **failed**: revdist above FCL
//!    can never be explained (`D_K <= D_S <= d_f + h_a + h_b`).
//!
//! The margin of a case is reported as `separation` (how far the intervals are apart, <= 0
//! when they meet) and `usage = |value - d_f| / (h_a + h_b + upper - lower)`.
//!
//! # Convex pairs
//!
//! Let `V` be the mesh vertices of a convex solid `K` with `d_H(M, S) <= h`, `S = boundary of
//! K`. Then `d_H(conv V, K) <= h`:
//! * `conv V ⊂ K ⊕ hB`: every vertex lies on `M`, so within `h` of `S ⊂ K`; the offset `K ⊕ hB`
//!   is convex, so it holds the hull. (Vertices may lie outside `K`, e.g. `Balanced`
//!   placement pushes ring vertices out; they are still within `h`.)
//! * every `x ∈ K` is within `h` of `conv V`: if `x ∉ conv V`, let `p` be the nearest point
//!   of `conv V`; the ray from `x` in direction `x - p` leaves the bounded convex `K` at a point
//!   `y ∈ S`, and the half-space `{z : (z - p)·(x - p) <= 0}` holds `conv V`, so
//!   `dist(y, conv V) >= |x - p|`; but `y` is within `h` of `M ⊂ conv V` (every triangle is in
//!   the hull). So `|x - p| <= h`.
//!
//! With (1), the hulls' distance `d_c` (CGAL, exact; 0 when the hulls meet) satisfies
//! `|d_c - D_K| <= h_a + h_b`, and `D_K` is revdist's solid distance (convex solids cannot
//! nest without meeting), so the same interval test applies with no "explained" class. FCL's
//! libccd GJK gets the extra slack [`convex::GJK_SLACK`] (its stopping rule does not bound the
//! error). The signed distance of convex sets is 1-Lipschitz in the Hausdorff distance too, so
//! a libccd EPA penetration depth `p` gives `D_K <= max(0, h_a + h_b - p)`: revdist's lower
//! bound must not exceed it ([`criterion::judge_penetration`]).

pub mod convex;
pub mod criterion;
pub mod occt;
pub mod occt_pairs;
pub mod occt_times;
pub mod options;
pub mod poses;
mod raw;
pub mod record;
pub mod report;
pub mod runner;
pub mod shapes;

pub use options::Options;
pub use report::Report;
pub use runner::run;

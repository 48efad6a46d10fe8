//! Rigid-body dynamics for the `dynamic` effect: gravity, contacts from
//! certified distance queries, and a step that provably never lets two solids overlap.
//!
//! # Why not rapier3d
//!
//! The step is driven by revdist's *certified lower bounds*: a body may move only as far as
//! the certified gaps to its neighbours allow (below). rapier's pipeline decides motion from
//! its own contact manifolds and penetration depths; plugging revdist in would take a parry
//! custom shape and query dispatcher returning contacts (no place for a lower bound to limit
//! the motion), glam/nalgebra conversions, and it would still allow the small penetrations
//! its solver is built to correct. The solver here is a few hundred lines, and its guarantee
//! is proved below instead of tuned.
//!
//! # State and integrator
//!
//! A dynamic body has mass `m`, centre of mass `x` (world), orientation `R`, velocity `v` and
//! angular momentum `L` (world); its angular velocity is `w = R I^-1 R^T L` with the body's
//! inertia tensor `I = diag(I_xy, I_xy, I_z)` about the centre of mass ([`crate::mass`]).
//! Static bodies do not move (infinite mass). One step of length `h`
//! (`h = time_step / substeps`):
//!
//! 1. `v += g h` (gravity; semi-implicit Euler).
//! 2. Broad phase and queries: a pair with at least one dynamic body is queried unless a
//!    certified lower bound `B_ij` of its distance is already `>= cap_i + cap_j + clearance`
//!    (`cap_i = 2 |motion_i| + skin`, the most the body will be allowed to move in this
//!    step). `B_ij` is the larger of the bounding spheres' gap and the bound carried from the
//!    pair's last query (its lower bound minus the pair's motion bounds `s_ij`, step 4, of
//!    every step since; so a pair resting apart is not asked again every step). A query
//!    gives a certified interval
//!    `[lower, upper]` and witness points `p_a`, `p_b`. Static-static pairs are never looked at.
//!    A pair whose lower bound falls below the clearance is asked
//!    again at the narrowest width the trees allow (`Tolerance::Absolute(0)`; exact circles,
//!    as a torus's, give an interval of rounding width), and the larger certified lower bound
//!    is kept. Otherwise a pair whose true gap is just above the clearance could get a lower
//!    bound just below it, and step 4 would stop it for good.
//! 3. Contacts (sequential impulses, restitution 0, Coulomb friction), plus a few witness
//!    pairs of earlier steps per pair as extra speculative contacts (a small manifold that
//!    only shapes the velocities). For each queried pair
//!    the normal `n = (p_b - p_a) / |p_b - p_a|` and the relative normal velocity `u_n` of the
//!    witness points. Speculative: `u_n >= -(lower - skin) / h` while `lower > skin` (the pair
//!    may close up to the skin in this step, no impulse before that), `u_n >= 0` in the skin,
//!    and a gentle push apart `u_n >= (skin / 2 - lower) / (4 h)` below half the skin.
//! 4. Motion bounds: every point of body `i` moves at most
//!    `s_i = |v_i| h + |w_i| rho_i h` in the step (`rho_i`: the largest distance from the centre
//!    of mass to the body's bounding sphere). The bound of a pair (relative translation) is
//!    `s_ij = |v_j - v_i| h + (|w_i| rho_i + |w_j| rho_j) h`. Each body is first held to its cap
//!    (`s_i <= cap_i`, scaling `v_i` and `L_i` down), then each queried pair to
//!    `s_ij <= max(0, lower_ij - clearance)` by scaling both bodies' `v` and `L` by the same
//!    factor (which scales `s_ij` by it); passes repeat until no pair is violated, and after
//!    20 passes the bodies of violating pairs are stopped (`v = L = 0`), which ends it.
//! 5. Energy guard: the energy after the move is known before it (translation changes the
//!    potential by `-m g . v h`; the rotation keeps `L` and, for an axially symmetric body,
//!    the rotational energy, see below); if it would exceed the energy at the start of the
//!    step, all velocities are scaled by the largest `c <= 1` that prevents it.
//! 6. Move: `x += v h`; the rotation is the exact torque-free motion of an axially
//!    symmetric body with angular momentum `L` (unchanged): `R = exp(h L / I_xy) R
//!    exp(h (1 / I_z - 1 / I_xy) (L . e_z) e_z)`, a precession of the axis `e_z = R z` about
//!    `L` composed with a spin about the body's own axis.
//!
//! # Theorem (no overlap)
//!
//! If at the start of a step every pair's solids are disjoint, then at every time of the step
//! they are disjoint, and the true distance of every queried pair stays `>= clearance`.
//!
//! **Proof.** During step 6 body `i` moves rigidly: its centre at constant velocity `v_i`,
//! its orientation along the torque-free motion `R_i(t)`, whose angular velocity
//! `w_i(t) = L_i / I_xy + (1 / I_z - 1 / I_xy) (L_i . e_z) e_z(t)` has constant length
//! `|w_i|` (`L_i` and `L_i . e_z` are constant). A point `p` of body `i` at offset `r(t)`
//! from the centre (`|r| <= rho_i`) has velocity `v_i + w_i(t) x r(t)`, of length at most
//! `|v_i| + |w_i| rho_i`. For two points `p` of `i` and `q` of `j`, the derivative of
//! `q - p` is `(v_j - v_i) + w_j x r_j - w_i x r_i`, so over the step `q - p` changes by at
//! most `s_ij` (step 4's bound). So the distance of every pair of points, and hence of the solids
//! (the infimum over points; solids, not surfaces, since every point of both solids is
//! covered), drops by at most `s_ij` during the step. Queried pair: the distance was at
//! least `lower_ij` (certified) and `s_ij <= lower_ij - clearance` (step 4), so it stays
//! `>= clearance > 0`; when `lower_ij < clearance`, step 4 stops both bodies (`s_ij = 0`).
//! Pair not queried: its distance was at least `B_ij >= cap_i + cap_j + clearance` (the
//! spheres' gap bounds it; so does the carried bound, by the same argument applied to each
//! step since its last query), and `s_ij <= s_i + s_j <= cap_i + cap_j` (the per-body caps of
//! step 4); so it stays `>= clearance`. Steps 4 and 5 only scale velocities down, which
//! never increases any `s_ij`, so the bounds hold for the final velocities. ∎
//!
//! Because the true distance stays `>= clearance` and a query's lower bound is at most its
//! interval's width `W` below the truth, every certified lower bound of the next step is
//! `>= clearance - W > 0`; the scene checks `clearance = skin / 4 > W` when it starts. So no
//! query ever reports overlap, and the run's minimum certified distance is positive.
//!
//! # Energy
//!
//! Restitution is 0 and every velocity scaling multiplies a body's kinetic energy by
//! `c^2 <= 1`. Semi-implicit Euler loses `m |g|^2 h^2 / 2` per step in free fall. The
//! rotation of step 6 keeps `L . e_z` (a rotation about `L` and a spin about `e_z`), hence
//! the rotational energy `(|L|^2 - (L . e_z)^2) / (2 I_xy) + (L . e_z)^2 / (2 I_z)` of an
//! axially symmetric body, exactly. (Rotating about the fixed axis `w` for the whole step,
//! the textbook update, does not: it gained 0.2% of the rotational energy per step on a
//! spinning ring, which is why the exact flow is used.) Sequential
//! impulses with accumulated clamping can in principle add energy (an impulse relaxed in a
//! later sweep), and the push apart below half the skin adds some; step 5 removes any such
//! gain, so the total energy (kinetic + gravitational) never increases from one step to the
//! next, up to rounding. The runner reports the largest increase it measured.
//!
//! Measured on `experiments/scenes/ring_mesh.toml` (65 rings, 4000 steps of 1 ms): no step
//! increased the energy beyond rounding (largest change 5.6e-17, 2e-16 of the total; the
//! guard acted in 2 steps), energy 0.3262 at the start and 0.2660 at the end, smallest
//! certified lower bound of a contact query 6.4e-4 (the clearance is 4e-4), no body stopped,
//! 80 of 80 links intact, 125 queries per step (`figures/scenes/ring_mesh.md`). Without
//! the exact rotation (fixed-axis update) a ring spinning at 40 rad/s gained 0.2% of its
//! rotational energy per step, which the guard would then have had to remove.

mod body;
mod contact;
mod report;
mod setup;
mod solver;
mod step;

pub use body::RigidBody;
pub use report::StepReport;

use crate::format::DynamicsSettings;
use contact::Stored;
use revdist::query::{QueryCache, QueryOptions};
use std::collections::HashMap;

/// The dynamics of a scene.
pub struct World {
    pub bodies: Vec<RigidBody>,
    settings: DynamicsSettings,
    /// Gap contacts aim for.
    pub skin: f64,
    /// Hard clearance of step 4 (`skin / 4`).
    pub clearance: f64,
    /// Widest certified interval a query returns at the scene's tolerance.
    pub width: f64,
    opts: QueryOptions,
    caches: HashMap<(usize, usize), QueryCache>,
    /// Certified lower bounds carried from a pair's last query: its lower bound minus the
    /// pair's motion bounds `s_ij` of every step since.
    carried: HashMap<(usize, usize), f64>,
    manifolds: HashMap<(usize, usize), Vec<Stored>>,
    /// Mass-property computations made (one per dynamic body).
    pub mass_computations: usize,
}

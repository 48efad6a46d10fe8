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

use crate::format::{DynamicsSettings, Effect, MassSpec, Scene};
use crate::mass::{mass_properties, MassProperties};
use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::query::{distance_cached, QueryCache, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::collections::HashMap;

/// Sweeps of the pairwise scaling in step 4 before the bodies of violating pairs are stopped.
const SCALING_PASSES: usize = 20;

/// A body as the solver sees it.
#[derive(Debug, Clone)]
pub struct RigidBody {
    pub dynamic: bool,
    /// Mass properties (dynamic bodies).
    pub mass: Option<MassProperties>,
    /// Centre of mass, world.
    pub x: Point3<f64>,
    pub rotation: UnitQuaternion<f64>,
    pub v: Vector3<f64>,
    /// Angular momentum about the centre of mass, world.
    pub l: Vector3<f64>,
    /// Largest distance from the centre of mass to a point of the body.
    pub rho: f64,
    /// Bounding sphere in the local frame (centre, radius).
    pub sphere: (Point3<f64>, f64),
}

impl RigidBody {
    fn inv_mass(&self) -> f64 {
        self.mass.map_or(0.0, |m| 1.0 / m.mass)
    }

    /// World inverse inertia tensor (zero for static bodies).
    fn inv_inertia(&self) -> Matrix3<f64> {
        match self.mass {
            None => Matrix3::zeros(),
            Some(m) => {
                let r = self.rotation.to_rotation_matrix();
                let d = Matrix3::from_diagonal(&Vector3::new(
                    1.0 / m.inertia_xy,
                    1.0 / m.inertia_xy,
                    1.0 / m.inertia_z,
                ));
                r.matrix() * d * r.matrix().transpose()
            }
        }
    }

    /// Angular velocity, world.
    pub fn omega(&self) -> Vector3<f64> {
        self.inv_inertia() * self.l
    }

    pub fn kinetic(&self) -> f64 {
        match self.mass {
            None => 0.0,
            Some(m) => 0.5 * m.mass * self.v.norm_squared() + 0.5 * self.l.dot(&self.omega()),
        }
    }

    pub fn potential(&self, g: &Vector3<f64>) -> f64 {
        self.mass.map_or(0.0, |m| -m.mass * g.dot(&self.x.coords))
    }

    /// Pose of the solid (local frame to world).
    pub fn pose(&self) -> Isometry3<f64> {
        let com = self.mass.map_or(Vector3::zeros(), |m| m.com().coords);
        Isometry3::from_parts(
            Translation3::from(self.x.coords - self.rotation * com),
            self.rotation,
        )
    }

    fn world_sphere(&self) -> (Point3<f64>, f64) {
        (self.pose() * self.sphere.0, self.sphere.1)
    }

    fn scale(&mut self, c: f64) {
        self.v *= c;
        self.l *= c;
    }

    /// Bound on how far any point moves in a step of length `h`.
    fn motion(&self, h: f64) -> f64 {
        if !self.dynamic {
            return 0.0;
        }
        (self.v.norm() + self.omega().norm() * self.rho) * h
    }
}

/// What one step (or a frame's steps) did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StepReport {
    pub steps: usize,
    /// Queries by kind: static-dynamic, dynamic-dynamic.
    pub queries: [usize; 2],
    /// Static-static queries (never made; counted to prove it).
    pub static_static_queries: usize,
    /// Pairs looked at by the broad phase.
    pub pair_checks: usize,
    /// Second queries at the narrowest width, for pairs near the clearance.
    pub tight_queries: usize,
    /// Pairs within reach by their bounding spheres but skipped thanks to a carried bound.
    pub carried_skips: usize,
    /// Smallest certified lower bound of the step's queries (infinity without queries).
    pub min_lower: f64,
    /// Smallest certified lower bound of a pair not queried (bounding-sphere gap or carried
    /// bound).
    pub min_unqueried: f64,
    /// Bodies whose velocity was scaled by the per-body caps or the pairwise bounds.
    pub scaled: usize,
    /// Bodies stopped because a pair stayed violated (or started inside the clearance).
    pub stopped: usize,
    /// Steps in which the energy guard scaled all velocities.
    pub energy_guard: usize,
    /// Largest energy increase of a step (negative: it decreased).
    pub max_energy_increase: f64,
    /// Queries that reported overlap (must stay 0).
    pub overlaps: usize,
}

impl StepReport {
    /// An empty report (infinite minima, no energy change seen).
    pub fn new() -> StepReport {
        StepReport {
            min_lower: f64::INFINITY,
            min_unqueried: f64::INFINITY,
            max_energy_increase: f64::NEG_INFINITY,
            ..StepReport::default()
        }
    }

    fn absorb(&mut self, o: &StepReport) {
        self.steps += o.steps;
        self.queries[0] += o.queries[0];
        self.queries[1] += o.queries[1];
        self.static_static_queries += o.static_static_queries;
        self.pair_checks += o.pair_checks;
        self.tight_queries += o.tight_queries;
        self.carried_skips += o.carried_skips;
        self.min_lower = self.min_lower.min(o.min_lower);
        self.min_unqueried = self.min_unqueried.min(o.min_unqueried);
        self.scaled += o.scaled;
        self.stopped += o.stopped;
        self.energy_guard += o.energy_guard;
        self.max_energy_increase = self.max_energy_increase.max(o.max_energy_increase);
        self.overlaps += o.overlaps;
    }
}

/// One contact of a step.
struct Contact {
    i: usize,
    j: usize,
    lower: f64,
    r_i: Vector3<f64>,
    r_j: Vector3<f64>,
    n: Vector3<f64>,
    t: [Vector3<f64>; 2],
    k_n: f64,
    k_t: [f64; 2],
    target: f64,
    lambda_n: f64,
    lambda_t: [f64; 2],
    /// The pair's certified contact (its `lower` drives step 4); `false` for the extra
    /// points of the pair's manifold, which only shape the velocities.
    certified: bool,
}

/// A witness pair remembered from an earlier step, in the bodies' local frames.
#[derive(Debug, Clone, Copy)]
struct Stored {
    a: Point3<f64>,
    b: Point3<f64>,
    /// Normal in body `i`'s frame.
    n: Vector3<f64>,
}

/// Most remembered witness pairs per body pair.
const MANIFOLD_POINTS: usize = 4;

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

impl World {
    /// The solver for `scene`'s bodies (`solids`: their built solids at the start). `width`
    /// is the widest certified interval a query may return.
    pub fn new(
        scene: &Scene,
        solids: &[Solid],
        opts: QueryOptions,
        width: f64,
    ) -> Result<World, String> {
        let skin = scene.dynamics.contact_skin.unwrap_or(8.0 * width);
        let clearance = skin / 4.0;
        if clearance <= width {
            return Err(format!(
                "contact_skin: {skin} is too thin for the queries' certified width {width}: it must exceed 4 x {width} so that the clearance skin / 4 keeps every lower bound positive"
            ));
        }
        let mut bodies = Vec::with_capacity(solids.len());
        let mut mass_computations = 0;
        for (body, solid) in scene.bodies.iter().zip(solids) {
            let root = &solid.tree.nodes[solid.tree.root as usize].bound;
            let sphere = (
                Point3::new(0.0, 0.0, root.center.y),
                root.center.x.abs() + root.radius,
            );
            let (mass, v, w) = match &body.effect {
                Effect::Dynamic(d) => {
                    let profile = solid
                        .profile
                        .as_deref()
                        .ok_or_else(|| format!("body '{}': no profile", body.name))?;
                    let (density, mass) = match d.mass {
                        MassSpec::Mass(m) => (None, Some(m)),
                        MassSpec::Density(rho) => (Some(rho), None),
                    };
                    let mp = mass_properties(profile, density, mass)
                        .map_err(|e| format!("body '{}': {e}", body.name))?;
                    mass_computations += 1;
                    (Some(mp), d.velocity, d.angular_velocity)
                }
                _ => (None, Vector3::zeros(), Vector3::zeros()),
            };
            let com_z = mass.map_or(0.0, |m| m.com_z);
            let pose = solid.pose;
            let rho = (sphere.0.z - com_z).abs() + sphere.1;
            let mut rb = RigidBody {
                dynamic: mass.is_some(),
                mass,
                x: pose * Point3::new(0.0, 0.0, com_z),
                rotation: pose.rotation,
                v,
                l: Vector3::zeros(),
                rho,
                sphere,
            };
            if let Some(m) = mass {
                // L = R I R^T w.
                let r = rb.rotation.to_rotation_matrix();
                let i = m.inertia();
                rb.l = r.matrix() * i * r.matrix().transpose() * w;
            }
            bodies.push(rb);
        }
        Ok(World {
            bodies,
            settings: scene.dynamics,
            skin,
            clearance,
            width,
            opts,
            caches: HashMap::new(),
            carried: HashMap::new(),
            manifolds: HashMap::new(),
            mass_computations,
        })
    }

    /// Checks that no pair with a dynamic body starts inside the clearance (such a pair could
    /// never move): queries every pair whose bounding spheres are that close.
    pub fn check_start(&mut self, scene: &Scene, solids: &[Solid]) -> Result<(), String> {
        let n = self.bodies.len();
        let spheres: Vec<(Point3<f64>, f64)> =
            self.bodies.iter().map(|b| b.world_sphere()).collect();
        for i in 0..n {
            for j in i + 1..n {
                if !(self.bodies[i].dynamic || self.bodies[j].dynamic) {
                    continue;
                }
                let gap = (spheres[i].0 - spheres[j].0).norm() - spheres[i].1 - spheres[j].1;
                if gap >= self.clearance {
                    continue;
                }
                let cache = self.caches.entry((i, j)).or_default();
                let d = distance_cached(&solids[i], &solids[j], &self.opts, cache);
                if d.lower < self.clearance {
                    return Err(format!(
                        "bodies '{}' and '{}' start {} (certified lower bound {:e}), closer than the contact clearance {:e} (contact_skin / 4)",
                        scene.bodies[i].name,
                        scene.bodies[j].name,
                        if d.overlap { "overlapping" } else { "too close" },
                        d.lower,
                        self.clearance
                    ));
                }
            }
        }
        Ok(())
    }

    /// Kinetic and potential energy of the dynamic bodies.
    pub fn energy(&self) -> (f64, f64) {
        let g = self.settings.gravity;
        self.bodies.iter().fold((0.0, 0.0), |(k, p), b| {
            (k + b.kinetic(), p + b.potential(&g))
        })
    }

    /// Advances by `dt` in `settings.substeps` steps; updates the solids' poses.
    pub fn advance(&mut self, dt: f64, solids: &mut [Solid]) -> StepReport {
        let mut report = StepReport::new();
        let h = dt / self.settings.substeps as f64;
        for _ in 0..self.settings.substeps {
            let r = self.step(h, solids);
            report.absorb(&r);
        }
        report
    }

    /// One step of length `h` (module docs, steps 1-6).
    pub fn step(&mut self, h: f64, solids: &mut [Solid]) -> StepReport {
        let mut rep = StepReport::new();
        rep.steps = 1;
        let g = self.settings.gravity;
        let (k0, p0) = self.energy();
        let n = self.bodies.len();
        // 1. Gravity.
        for b in self.bodies.iter_mut().filter(|b| b.dynamic) {
            b.v += g * h;
        }
        // 2. Broad phase and queries.
        let caps: Vec<f64> = self
            .bodies
            .iter()
            .map(|b| {
                if b.dynamic {
                    2.0 * b.motion(h) + self.skin
                } else {
                    0.0
                }
            })
            .collect();
        let spheres: Vec<(Point3<f64>, f64)> =
            self.bodies.iter().map(|b| b.world_sphere()).collect();
        let mut contacts = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let (di, dj) = (self.bodies[i].dynamic, self.bodies[j].dynamic);
                if !di && !dj {
                    continue;
                }
                rep.pair_checks += 1;
                let gap = (spheres[i].0 - spheres[j].0).norm() - spheres[i].1 - spheres[j].1;
                let carried = self
                    .carried
                    .get(&(i, j))
                    .copied()
                    .unwrap_or(f64::NEG_INFINITY);
                let reach = caps[i] + caps[j] + self.clearance;
                if gap.max(carried) >= reach {
                    rep.min_unqueried = rep.min_unqueried.min(gap.max(carried));
                    if gap < reach {
                        rep.carried_skips += 1;
                    }
                    continue;
                }
                let cache = self.caches.entry((i, j)).or_default();
                let mut d = distance_cached(&solids[i], &solids[j], &self.opts, cache);
                if !d.overlap && d.lower < self.clearance {
                    // Near the clearance: ask for the narrowest interval the trees allow, so
                    // that the lower bound is close to the true gap (which step 4 keeps
                    // >= clearance); both answers are certified, keep the better bound.
                    let tight = QueryOptions {
                        tolerance: Tolerance::Absolute(0.0),
                        ..self.opts
                    };
                    let t = distance_cached(&solids[i], &solids[j], &tight, cache);
                    rep.tight_queries += 1;
                    if t.overlap || t.lower > d.lower {
                        d = t;
                    }
                }
                if di && dj {
                    rep.queries[1] += 1;
                } else if di || dj {
                    rep.queries[0] += 1;
                } else {
                    rep.static_static_queries += 1;
                }
                rep.min_lower = rep.min_lower.min(d.lower);
                self.carried.insert((i, j), d.lower);
                if d.overlap {
                    rep.overlaps += 1;
                }
                let (bi, bj) = (&self.bodies[i], &self.bodies[j]);
                let diff = d.point_b - d.point_a;
                let n_dir = diff
                    .try_normalize(1e-300)
                    .or_else(|| (bj.x - bi.x).try_normalize(1e-300))
                    .unwrap_or(Vector3::z());
                let mut main = self.contact(i, j, d.lower, d.point_a, d.point_b, n_dir, h);
                main.certified = true;
                contacts.push(main);
                self.manifold_contacts(i, j, &d, n_dir, solids, h, &mut contacts);
            }
        }
        // 3. Contacts.
        self.solve(&mut contacts);
        // 4. Motion bounds: per-body caps, then pairwise.
        let mut scaled = vec![false; n];
        for (i, b) in self.bodies.iter_mut().enumerate() {
            let s = b.motion(h);
            if b.dynamic && s > caps[i] {
                b.scale(caps[i] / s);
                scaled[i] = true;
            }
        }
        let mut stopped = vec![false; n];
        let mut pass = 0;
        loop {
            let mut violated = false;
            for c in contacts.iter().filter(|c| c.certified) {
                let allowed = (c.lower - self.clearance).max(0.0);
                let s = self.pair_motion(c.i, c.j, h);
                if s <= allowed {
                    continue;
                }
                violated = true;
                let factor = if pass < SCALING_PASSES && s.is_finite() && s > 0.0 {
                    allowed / s
                } else {
                    0.0
                };
                for k in [c.i, c.j] {
                    if self.bodies[k].dynamic {
                        self.bodies[k].scale(factor);
                        scaled[k] = true;
                        if factor == 0.0 {
                            stopped[k] = true;
                        }
                    }
                }
            }
            if !violated {
                break;
            }
            pass += 1;
        }
        rep.scaled = scaled.iter().filter(|&&s| s).count();
        rep.stopped = stopped.iter().filter(|&&s| s).count();
        // 5. Energy guard: energy after the move, predicted exactly.
        let k2: f64 = self.bodies.iter().map(|b| b.kinetic()).sum();
        let w2: f64 = self
            .bodies
            .iter()
            .filter_map(|b| b.mass.map(|m| m.mass * g.dot(&b.v) * h))
            .sum();
        if k2 - w2 > k0 && k2 > 0.0 {
            let c = ((w2 + (w2 * w2 + 4.0 * k2 * k0).sqrt()) / (2.0 * k2)).min(1.0);
            for b in self.bodies.iter_mut().filter(|b| b.dynamic) {
                b.scale(c * (1.0 - 1e-12));
            }
            rep.energy_guard = 1;
        }
        // Carried bounds: the distance of a pair drops by at most s_ij in this step.
        let drops: Vec<((usize, usize), f64)> = self
            .carried
            .keys()
            .map(|&(i, j)| ((i, j), self.pair_motion(i, j, h)))
            .collect();
        for (key, s) in drops {
            if let Some(b) = self.carried.get_mut(&key) {
                *b -= s;
            }
        }
        // 6. Move.
        for (b, solid) in self.bodies.iter_mut().zip(solids.iter_mut()) {
            if !b.dynamic {
                continue;
            }
            b.x += b.v * h;
            // The exact torque-free motion of an axially symmetric body: the axis precesses
            // about L at rate |L| / I_xy while the body spins about its axis at rate
            // (1 / I_z - 1 / I_xy) (L . e_z).
            if let Some(m) = b.mass {
                let lz = b.l.dot(&(b.rotation * Vector3::z()));
                let precession = UnitQuaternion::from_scaled_axis(b.l * (h / m.inertia_xy));
                let spin = UnitQuaternion::from_axis_angle(
                    &Vector3::z_axis(),
                    (1.0 / m.inertia_z - 1.0 / m.inertia_xy) * lz * h,
                );
                b.rotation = precession * b.rotation * spin;
                b.rotation.renormalize();
            }
            solid.pose = b.pose();
        }
        let (k1, p1) = self.energy();
        rep.max_energy_increase = (k1 + p1) - (k0 + p0);
        rep
    }

    /// Pair motion bound `s_ij` of step 4.
    fn pair_motion(&self, i: usize, j: usize, h: f64) -> f64 {
        let (a, b) = (&self.bodies[i], &self.bodies[j]);
        let rot = |x: &RigidBody| {
            if x.dynamic {
                x.omega().norm() * x.rho
            } else {
                0.0
            }
        };
        ((b.v - a.v).norm() + rot(a) + rot(b)) * h
    }

    #[allow(clippy::too_many_arguments)]
    fn contact(
        &self,
        i: usize,
        j: usize,
        lower: f64,
        pa: Point3<f64>,
        pb: Point3<f64>,
        n: Vector3<f64>,
        h: f64,
    ) -> Contact {
        let (bi, bj) = (&self.bodies[i], &self.bodies[j]);
        let r_i = pa - bi.x;
        let r_j = pb - bj.x;
        let helper = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let t0 = n.cross(&helper).normalize();
        let t1 = n.cross(&t0);
        let (ii, ij) = (bi.inv_inertia(), bj.inv_inertia());
        let (mi, mj) = (bi.inv_mass(), bj.inv_mass());
        let k = |d: &Vector3<f64>| {
            let a = r_i.cross(d);
            let b = r_j.cross(d);
            mi + mj + a.dot(&(ii * a)) + b.dot(&(ij * b))
        };
        let skin = self.skin;
        let target = if lower > skin {
            -(lower - skin) / h
        } else if lower < 0.5 * skin {
            (0.5 * skin - lower) / (4.0 * h)
        } else {
            0.0
        };
        Contact {
            i,
            j,
            lower,
            r_i,
            r_j,
            n,
            t: [t0, t1],
            k_n: k(&n),
            k_t: [k(&t0), k(&t1)],
            target,
            lambda_n: 0.0,
            lambda_t: [0.0; 2],
            certified: false,
        }
    }

    /// The pair's small contact manifold: witness pairs of earlier steps (kept while their
    /// points stay within a few skins of each other and have not slid apart) become extra
    /// speculative contacts at their current estimated gap, and the new witness pair joins
    /// them unless an old one is close to it. These contacts only shape the velocities (a
    /// ring lying on the table is held at several points instead of rocking about one);
    /// the no-overlap guarantee rests on the certified contact alone (step 4).
    #[allow(clippy::too_many_arguments)]
    fn manifold_contacts(
        &mut self,
        i: usize,
        j: usize,
        d: &revdist::query::Distance,
        n: Vector3<f64>,
        solids: &[Solid],
        h: f64,
        out: &mut Vec<Contact>,
    ) {
        let (pose_i, pose_j) = (solids[i].pose, solids[j].pose);
        let reach = 3.0 * self.skin;
        let slack = d.upper - d.lower;
        let spread = 0.1 * self.bodies[i].sphere.1.min(self.bodies[j].sphere.1);
        let mut kept: Vec<Stored> = Vec::new();
        let stored = self.manifolds.remove(&(i, j)).unwrap_or_default();
        for st in stored {
            let (pa, pb) = (pose_i * st.a, pose_j * st.b);
            let nw = pose_i.rotation * st.n;
            let sep = pb - pa;
            let gap = sep.dot(&nw);
            let slide = (sep - nw * gap).norm();
            if gap > reach || slide > self.skin || (pa - d.point_a).norm() < spread {
                continue;
            }
            out.push(self.contact(i, j, (gap - slack).max(0.0), pa, pb, nw, h));
            kept.push(st);
        }
        if d.lower < reach {
            if kept.len() >= MANIFOLD_POINTS {
                kept.remove(0);
            }
            kept.push(Stored {
                a: pose_i.inverse_transform_point(&d.point_a),
                b: pose_j.inverse_transform_point(&d.point_b),
                n: pose_i.rotation.inverse_transform_vector(&n),
            });
        }
        if !kept.is_empty() {
            self.manifolds.insert((i, j), kept);
        }
    }

    /// Sequential impulses: normal (accumulated, >= 0) then friction (|t| <= mu n).
    fn solve(&mut self, contacts: &mut [Contact]) {
        let mu = self.settings.friction;
        // Angular velocities and inverse inertias are kept alongside during the sweeps.
        let inv_i: Vec<Matrix3<f64>> = self.bodies.iter().map(|b| b.inv_inertia()).collect();
        let mut w: Vec<Vector3<f64>> = self.bodies.iter().map(|b| b.omega()).collect();
        for _ in 0..self.settings.solver_iterations {
            for c in contacts.iter_mut() {
                if c.k_n <= 0.0 {
                    continue;
                }
                let rel = |bodies: &[RigidBody], w: &[Vector3<f64>]| {
                    (bodies[c.j].v + w[c.j].cross(&c.r_j)) - (bodies[c.i].v + w[c.i].cross(&c.r_i))
                };
                let u = rel(&self.bodies, &w);
                let un = u.dot(&c.n);
                let new = (c.lambda_n + (c.target - un) / c.k_n).max(0.0);
                let d = new - c.lambda_n;
                c.lambda_n = new;
                apply(&mut self.bodies, &mut w, &inv_i, c, c.n * d);
                if mu > 0.0 {
                    for k in 0..2 {
                        let u = rel(&self.bodies, &w);
                        let ut = u.dot(&c.t[k]);
                        let limit = mu * c.lambda_n;
                        let new = (c.lambda_t[k] - ut / c.k_t[k]).clamp(-limit, limit);
                        let d = new - c.lambda_t[k];
                        c.lambda_t[k] = new;
                        apply(&mut self.bodies, &mut w, &inv_i, c, c.t[k] * d);
                    }
                }
            }
        }
    }
}

/// Applies impulse `p` to body `j` at `r_j` and `-p` to body `i` at `r_i`.
fn apply(
    bodies: &mut [RigidBody],
    w: &mut [Vector3<f64>],
    inv_i: &[Matrix3<f64>],
    c: &Contact,
    p: Vector3<f64>,
) {
    if bodies[c.j].dynamic {
        let m = bodies[c.j].inv_mass();
        let dl = c.r_j.cross(&p);
        bodies[c.j].v += p * m;
        bodies[c.j].l += dl;
        w[c.j] += inv_i[c.j] * dl;
    }
    if bodies[c.i].dynamic {
        let m = bodies[c.i].inv_mass();
        let dl = c.r_i.cross(&p);
        bodies[c.i].v -= p * m;
        bodies[c.i].l -= dl;
        w[c.i] -= inv_i[c.i] * dl;
    }
}

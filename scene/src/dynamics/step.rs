//! The step of length `h` (module documentation of [`super`], steps 1-6): gravity, broad
//! phase and queries, contacts, motion bounds, energy guard and the exact torque-free move.

use super::body::RigidBody;
use super::report::StepReport;
use super::World;
use nalgebra::{Point3, UnitQuaternion, Vector3};
use revdist::query::{distance_cached, QueryOptions, Tolerance};
use revdist::solid::Solid;

/// Sweeps of the pairwise scaling in step 4 before the bodies of violating pairs are stopped.
const SCALING_PASSES: usize = 20;

impl World {
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
    pub(super) fn pair_motion(&self, i: usize, j: usize, h: f64) -> f64 {
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
}

//! Sequential impulses (module documentation of [`super`], step 3): normal impulses
//! accumulated and clamped at zero, then Coulomb friction.

use super::body::RigidBody;
use super::contact::Contact;
use super::World;
use nalgebra::{Matrix3, Vector3};

impl World {
    /// Sequential impulses: normal (accumulated, >= 0) then friction (|t| <= mu n).
    pub(super) fn solve(&mut self, contacts: &mut [Contact]) {
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

//! The solver's start: bodies with their mass properties and momenta from the scene, and the
//! check that no pair starts inside the clearance.

use super::body::RigidBody;
use super::World;
use crate::format::{Effect, MassSpec, Scene};
use crate::mass::mass_properties;
use nalgebra::{Point3, Vector3};
use revdist::query::{distance_cached, QueryOptions};
use revdist::solid::Solid;
use std::collections::HashMap;

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
}

//! A body as the solver sees it: mass properties, state, energy and the motion bound of
//! step 4 (module documentation of [`super`]).

use crate::mass::MassProperties;
use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};

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
    pub(super) fn inv_mass(&self) -> f64 {
        self.mass.map_or(0.0, |m| 1.0 / m.mass)
    }

    /// World inverse inertia tensor (zero for static bodies).
    pub(super) fn inv_inertia(&self) -> Matrix3<f64> {
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

    pub(super) fn world_sphere(&self) -> (Point3<f64>, f64) {
        (self.pose() * self.sphere.0, self.sphere.1)
    }

    pub(super) fn scale(&mut self, c: f64) {
        self.v *= c;
        self.l *= c;
    }

    /// Bound on how far any point moves in a step of length `h`.
    pub(super) fn motion(&self, h: f64) -> f64 {
        if !self.dynamic {
            return 0.0;
        }
        (self.v.norm() + self.omega().norm() * self.rho) * h
    }
}

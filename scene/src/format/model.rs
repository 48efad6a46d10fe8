//! A checked scene: bodies with their shapes, effects and poses, what to measure, rendering
//! and dynamics settings.

use nalgebra::{Isometry3, Vector3};
use std::path::PathBuf;

/// Checked render settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Render {
    pub every: usize,
    pub width: usize,
    pub height: usize,
    pub eye: nalgebra::Point3<f64>,
    pub target: nalgebra::Point3<f64>,
    /// Vertical field of view (radians).
    pub fov: f64,
}

/// Where a body's shape comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    Model(String),
    ProfileFile(PathBuf),
    Morph {
        period: f64,
    },
    /// A circle of radius `minor` about `(major, 0)` revolved about the z axis.
    Torus {
        major: f64,
        minor: f64,
    },
}

/// How a body's pose changes.
#[derive(Debug, Clone, PartialEq)]
pub enum Track {
    Keyframes {
        times: Vec<f64>,
        poses: Vec<Isometry3<f64>>,
        smooth: bool,
    },
    Random {
        seed: u64,
        amplitude: f64,
        angle: f64,
        period: f64,
    },
}

/// The effect a body takes part in.
#[derive(Debug, Clone, PartialEq)]
pub enum Effect {
    Static,
    Kinematic(Track),
    Deforming,
    /// A rigid body under gravity with contacts ([`crate::dynamics`]).
    Dynamic(DynamicBody),
}

/// How a dynamic body's mass is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MassSpec {
    /// Total mass; the density is uniform.
    Mass(f64),
    /// Uniform density (mass per unit volume).
    Density(f64),
}

/// A dynamic body's mass and initial velocities (world frame, velocity of the centre of
/// mass; angular velocity in radians per second).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicBody {
    pub mass: MassSpec,
    pub velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
}

/// Scene-level settings of the dynamics (used only when some body is dynamic).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsSettings {
    /// Gravitational acceleration (length units per second squared).
    pub gravity: Vector3<f64>,
    /// Solver steps per frame.
    pub substeps: usize,
    /// Gap the contacts aim for; `None`: 8 times the query width.
    pub contact_skin: Option<f64>,
    /// Coulomb friction coefficient.
    pub friction: f64,
    /// Sequential-impulse sweeps per step.
    pub solver_iterations: usize,
}

impl Default for DynamicsSettings {
    fn default() -> Self {
        DynamicsSettings {
            gravity: Vector3::new(0.0, 0.0, -9.81),
            substeps: 10,
            contact_skin: None,
            friction: 0.5,
            solver_iterations: 10,
        }
    }
}

/// A checked body.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    pub name: String,
    pub shape: Shape,
    pub effect: Effect,
    pub pose: Isometry3<f64>,
}

/// Which pairs a scene measures.
#[derive(Debug, Clone, PartialEq)]
pub enum Measure {
    All,
    Pairs(Vec<(usize, usize)>),
}

/// A checked scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub duration: f64,
    pub time_step: f64,
    pub eps: f64,
    /// `None`: the trees' accuracy; `Some(w)`: an absolute interval width.
    pub tolerance: Option<f64>,
    pub measure: Measure,
    pub within: Option<f64>,
    /// Rendered frames, when the scene asks for them.
    pub render: Option<Render>,
    /// Settings of the dynamics (defaults when the file gives none).
    pub dynamics: DynamicsSettings,
    pub bodies: Vec<Body>,
    /// Pairs of bodies that a generator built interlocked (ring meshes); their linking is
    /// checked at the start and the end of a run.
    pub links: Vec<(usize, usize)>,
}

impl Scene {
    /// Number of frames: times `0, dt, 2 dt, ...` up to the duration.
    pub fn frames(&self) -> usize {
        (self.duration / self.time_step + 1e-9).floor() as usize + 1
    }

    /// Whether some body is dynamic (then the runner steps the dynamics).
    pub fn has_dynamics(&self) -> bool {
        self.bodies
            .iter()
            .any(|b| matches!(b.effect, Effect::Dynamic(_)))
    }

    /// The index of the body called `name`.
    pub fn body_index(&self, name: &str) -> Option<usize> {
        self.bodies.iter().position(|b| b.name == name)
    }

    /// The measured pairs, as body indices with the first below the second.
    pub fn measured_pairs(&self) -> Vec<(usize, usize)> {
        match &self.measure {
            Measure::All => (0..self.bodies.len())
                .flat_map(|i| (i + 1..self.bodies.len()).map(move |j| (i, j)))
                .collect(),
            Measure::Pairs(p) => p.clone(),
        }
    }
}

/// A pair of bodies built interlocked (body indices).
pub type Link = (usize, usize);

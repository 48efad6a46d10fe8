//! Rigid-body dynamics for dynamic bodies of a scene (issue 14, item 3).
//!
//! Interface used by the scene runner. Implemented by the dynamics work.

use nalgebra::{Isometry3, Point3, Vector3};
use revdist::solid::Solid;

/// How a body takes part in the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// Never moves; infinite mass (e.g. the table).
    Fixed,
    /// Moved by the scene (pose set each step with [`RigidWorld::set_kinematic_pose`]); pushes
    /// dynamic bodies but is not pushed back.
    Kinematic,
    /// Integrated under gravity and contacts.
    Dynamic,
}

/// One body handed to the dynamics.
#[derive(Debug, Clone)]
pub struct BodySpec {
    /// The shape at its initial pose (`solid.pose`).
    pub solid: Solid,
    pub motion: Motion,
    /// Density (mass per unit volume) of a dynamic body.
    pub density: f64,
    pub linear_velocity: Vector3<f64>,
    pub angular_velocity: Vector3<f64>,
}

/// World parameters.
#[derive(Debug, Clone)]
pub struct DynamicsParams {
    pub gravity: Vector3<f64>,
    /// Coefficient of friction (Coulomb).
    pub friction: f64,
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Contacts are generated for pairs closer than this (speculative margin), length units.
    pub contact_margin: f64,
}

/// A contact found in a step: world points on the two bodies, normal from `a` to `b`.
#[derive(Debug, Clone)]
pub struct Contact {
    pub body_a: usize,
    pub body_b: usize,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    pub normal: Vector3<f64>,
    /// Certified lower bound of the distance at the start of the step.
    pub distance_lower: f64,
}

/// What one step computed (counters for the scene's cost report).
#[derive(Debug, Clone, Default)]
pub struct StepReport {
    /// Pairs considered by the broad phase.
    pub broad_pairs: usize,
    /// revdist distance queries run for contacts.
    pub distance_queries: usize,
    pub contacts: usize,
    /// Smallest certified lower bound of the distance over queried pairs at the end of the step
    /// (`f64::INFINITY` if no pair was queried).
    pub min_distance_lower: f64,
}

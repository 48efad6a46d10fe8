//! The scene runner: builds a plan from a [`Scene`] and computes only what
//! it asks for.
//!
//! * Trees are built once per body; only deforming bodies rebuild, once per frame.
//! * Only kinematic bodies get pose updates.
//! * Only measured pairs are queried, and a pair whose two bodies did not change since its
//!   last query is not queried again (its certified answer still holds): a static scene
//!   runs exactly one query per measured pair.
//! * With `within`, a measured pair whose bounding spheres are farther apart than that gets
//!   the spheres' certified interval and no query (the broad phase).
//!
//! * Only a scene with a dynamic body steps the dynamics ([`crate::dynamics`]): mass
//!   properties, broad phase and contact queries are computed for nothing else, and
//!   static-static pairs are never looked at.
//!
//! [`Counters`] record every piece of work, so tests can check that nothing unrequested was
//! done; [`FrameCost`] splits each frame's wall time by effect.

use crate::dynamics::{StepReport, World};
use crate::format::{shape_profile, Body, Effect, Scene, Shape};
use crate::links::{core_circle, linking_number};
use crate::motion::pose_at;
use nalgebra::{Isometry3, Point3};
use revdist::query::{distance_cached, QueryCache, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;

/// Why a scene could not run.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("body '{body}': {message}")]
    Body { body: String, message: String },
    #[error("dynamics: {0}")]
    Dynamics(String),
}

/// Pairs of [`Scene::links`] whose core circles are linked for the given poses.
pub fn links_intact(scene: &Scene, poses: &[Isometry3<f64>]) -> usize {
    scene
        .links
        .iter()
        .filter(|&&(a, b)| {
            let (Shape::Torus { major: ra, .. }, Shape::Torus { major: rb, .. }) =
                (&scene.bodies[a].shape, &scene.bodies[b].shape)
            else {
                return false;
            };
            linking_number(&core_circle(&poses[a], *ra), &core_circle(&poses[b], *rb)).abs() == 1
        })
        .count()
}

/// Work done, per body and per measured pair.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Counters {
    pub frames: usize,
    /// Tree builds before the first frame, per body (1 each).
    pub initial_builds: Vec<usize>,
    /// Tree rebuilds during the run, per body (only deforming bodies).
    pub rebuilds: Vec<usize>,
    /// Pose updates, per body (only kinematic bodies).
    pub pose_updates: Vec<usize>,
    /// Distance queries, per measured pair.
    pub queries: Vec<usize>,
    /// Frames a pair's previous answer was reused because neither body changed.
    pub reused: Vec<usize>,
    /// Frames the broad phase answered a pair from its bounding spheres.
    pub broad_phase_skips: Vec<usize>,
    /// Dynamics: steps taken (0 unless some body is dynamic).
    pub dynamics_steps: usize,
    /// Dynamics: contact queries, static-dynamic and dynamic-dynamic.
    pub dynamics_queries: [usize; 2],
    /// Dynamics: pairs within reach by their bounding spheres but not queried because the
    /// bound carried from their last query was enough.
    pub dynamics_carried_skips: usize,
    /// Dynamics: second queries at the narrowest width (pairs near the clearance).
    pub dynamics_tight_queries: usize,
    /// Dynamics: queries between two non-dynamic bodies (never made).
    pub dynamics_static_static_queries: usize,
    /// Dynamics: pairs looked at by the solver's broad phase.
    pub dynamics_pair_checks: usize,
    /// Dynamics: mass-property computations (one per dynamic body).
    pub mass_computations: usize,
}

/// Wall time of one frame, by effect (seconds).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct FrameCost {
    pub rebuild: f64,
    pub kinematics: f64,
    pub dynamics: f64,
    pub measure: f64,
}

/// The dynamics in one frame (scenes with dynamic bodies).
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsFrame {
    /// Kinetic and potential energy at the end of the frame.
    pub kinetic: f64,
    pub potential: f64,
    /// What the frame's steps did (empty in frame 0).
    pub report: StepReport,
    /// Interlocked pairs of the scene ([`Scene::links`]) still linked (linking number +-1).
    pub links_intact: usize,
}

/// How a pair's interval was obtained in a frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    Query,
    Reused,
    BroadPhase,
}

/// One measured pair in one frame (world frame).
#[derive(Debug, Clone, PartialEq)]
pub struct PairSample {
    pub pair: (usize, usize),
    pub lower: f64,
    pub upper: f64,
    pub value: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    pub overlap: bool,
    pub source: Source,
}

/// Everything computed in one frame.
#[derive(Debug, Clone)]
pub struct Frame {
    pub index: usize,
    pub time: f64,
    /// World pose of every body.
    pub poses: Vec<Isometry3<f64>>,
    pub samples: Vec<PairSample>,
    pub cost: FrameCost,
    /// `Some` when the scene has dynamic bodies.
    pub dynamics: Option<DynamicsFrame>,
}

/// A body during the run.
struct Live {
    solid: Solid,
    /// The frame in which the body last changed (pose or shape).
    changed: usize,
}

fn build(body: &Body, time: f64, eps: f64, pose: Isometry3<f64>) -> Result<Solid, RunError> {
    let err = |message: String| RunError::Body {
        body: body.name.clone(),
        message,
    };
    let profile = shape_profile(body, time).map_err(err)?;
    let solid = Solid::from_profile(Arc::new(profile), eps).map_err(|e| err(e.to_string()))?;
    Ok(solid.with_pose(pose))
}

/// The bounding sphere of a posed solid: its tree's root disk revolved (centre on the axis
/// at the disk's height, radius `|rho| + r`), in world coordinates.
fn bounding_sphere(s: &Solid) -> Option<(Point3<f64>, f64)> {
    let t = &s.tree;
    let root = t.nodes.get(t.root as usize)?;
    let d = root.bound;
    let centre = s.pose * Point3::new(0.0, 0.0, d.center.y);
    Some((centre, d.center.x.abs() + d.radius))
}

/// Runs a scene, handing each frame to `sink` as it is computed; returns the counters.
pub fn run(
    scene: &Scene,
    mut sink: impl FnMut(&Frame) -> Result<(), Box<dyn std::error::Error>>,
) -> Result<Counters, Box<dyn std::error::Error>> {
    let n = scene.bodies.len();
    let pairs = scene.measured_pairs();
    let mut counters = Counters {
        frames: 0,
        initial_builds: vec![0; n],
        rebuilds: vec![0; n],
        pose_updates: vec![0; n],
        queries: vec![0; pairs.len()],
        reused: vec![0; pairs.len()],
        broad_phase_skips: vec![0; pairs.len()],
        ..Counters::default()
    };
    let opts = QueryOptions {
        tolerance: scene
            .tolerance
            .map_or(Tolerance::Trees, Tolerance::Absolute),
        ..QueryOptions::default()
    };
    // Initial poses and trees.
    let mut live = Vec::with_capacity(n);
    for (i, body) in scene.bodies.iter().enumerate() {
        let pose = match &body.effect {
            Effect::Kinematic(track) => pose_at(track, &body.pose, 0.0),
            _ => body.pose,
        };
        live.push(Live {
            solid: build(body, 0.0, scene.eps, pose)?,
            changed: 0,
        });
        counters.initial_builds[i] += 1;
    }
    // Dynamics only when a body is dynamic.
    let mut world = if scene.has_dynamics() {
        let solids: Vec<Solid> = live.iter().map(|l| l.solid.clone()).collect();
        let eps_max = solids.iter().map(|s| s.tree.target_eps).fold(0.0, f64::max);
        // The widest interval a query returns: the requested width, or what the leaves
        // allow (2 (e_a + e_b) <= 4 eps), whichever is wider.
        let width = opts.tolerance.width(eps_max, eps_max).max(4.0 * eps_max);
        let mut w = World::new(scene, &solids, opts, width).map_err(RunError::Dynamics)?;
        w.check_start(scene, &solids).map_err(RunError::Dynamics)?;
        counters.mass_computations = w.mass_computations;
        let start = links_intact(scene, &solids.iter().map(|s| s.pose).collect::<Vec<_>>());
        if start != scene.links.len() {
            return Err(RunError::Dynamics(format!(
                "only {start} of the {} generated ring links are interlocked at the start",
                scene.links.len()
            ))
            .into());
        }
        Some(w)
    } else {
        None
    };
    let mut caches = vec![QueryCache::default(); pairs.len()];
    let mut last: Vec<Option<(usize, PairSample)>> = vec![None; pairs.len()];
    for index in 0..scene.frames() {
        let time = index as f64 * scene.time_step;
        let mut cost = FrameCost::default();
        if index > 0 {
            let clock = Instant::now();
            for (i, body) in scene.bodies.iter().enumerate() {
                if body.effect == Effect::Deforming {
                    let pose = live[i].solid.pose;
                    live[i].solid = build(body, time, scene.eps, pose)?;
                    live[i].changed = index;
                    counters.rebuilds[i] += 1;
                }
            }
            cost.rebuild = clock.elapsed().as_secs_f64();
            let clock = Instant::now();
            for (i, body) in scene.bodies.iter().enumerate() {
                if let Effect::Kinematic(track) = &body.effect {
                    live[i].solid.pose = pose_at(track, &body.pose, time);
                    live[i].changed = index;
                    counters.pose_updates[i] += 1;
                }
            }
            cost.kinematics = clock.elapsed().as_secs_f64();
        }
        let mut dyn_frame = None;
        if let Some(w) = world.as_mut() {
            let clock = Instant::now();
            let report = if index > 0 {
                let mut solids: Vec<Solid> = live.iter().map(|l| l.solid.clone()).collect();
                let r = w.advance(scene.time_step, &mut solids);
                for (i, body) in scene.bodies.iter().enumerate() {
                    if matches!(body.effect, Effect::Dynamic(_)) {
                        live[i].solid.pose = solids[i].pose;
                        live[i].changed = index;
                    }
                }
                counters.dynamics_steps += r.steps;
                counters.dynamics_queries[0] += r.queries[0];
                counters.dynamics_queries[1] += r.queries[1];
                counters.dynamics_static_static_queries += r.static_static_queries;
                counters.dynamics_pair_checks += r.pair_checks;
                counters.dynamics_tight_queries += r.tight_queries;
                counters.dynamics_carried_skips += r.carried_skips;
                if r.overlaps > 0 {
                    return Err(RunError::Dynamics(format!(
                        "frame {index}: a contact query reported overlap (a bug: the step bounds forbid it)"
                    ))
                    .into());
                }
                r
            } else {
                StepReport::new()
            };
            cost.dynamics = clock.elapsed().as_secs_f64();
            let (kinetic, potential) = w.energy();
            let poses: Vec<Isometry3<f64>> = live.iter().map(|l| l.solid.pose).collect();
            dyn_frame = Some(DynamicsFrame {
                kinetic,
                potential,
                report,
                links_intact: links_intact(scene, &poses),
            });
        }
        let clock = Instant::now();
        let mut samples = Vec::with_capacity(pairs.len());
        for (k, &(i, j)) in pairs.iter().enumerate() {
            let (a, b) = (&live[i], &live[j]);
            // Reuse: neither body changed since the pair's last answer.
            if let Some((at, prev)) = &last[k] {
                if a.changed <= *at && b.changed <= *at {
                    counters.reused[k] += 1;
                    samples.push(PairSample {
                        source: Source::Reused,
                        ..prev.clone()
                    });
                    continue;
                }
            }
            if let (Some(w), Some((ca, ra)), Some((cb, rb))) = (
                scene.within,
                bounding_sphere(&a.solid),
                bounding_sphere(&b.solid),
            ) {
                let lower = (ca - cb).norm() - ra - rb;
                if lower > w {
                    counters.broad_phase_skips[k] += 1;
                    let dir = (cb - ca) / (cb - ca).norm();
                    samples.push(PairSample {
                        pair: (i, j),
                        lower,
                        upper: (ca - cb).norm() + ra + rb,
                        value: lower,
                        point_a: ca + dir * ra,
                        point_b: cb - dir * rb,
                        overlap: false,
                        source: Source::BroadPhase,
                    });
                    continue;
                }
            }
            counters.queries[k] += 1;
            let d = distance_cached(&a.solid, &b.solid, &opts, &mut caches[k]);
            let sample = PairSample {
                pair: (i, j),
                lower: d.lower,
                upper: d.upper,
                value: d.value,
                point_a: d.point_a,
                point_b: d.point_b,
                overlap: d.overlap,
                source: Source::Query,
            };
            last[k] = Some((index, sample.clone()));
            samples.push(sample);
        }
        cost.measure = clock.elapsed().as_secs_f64();
        counters.frames += 1;
        sink(&Frame {
            index,
            time,
            poses: live.iter().map(|l| l.solid.pose).collect(),
            samples,
            cost,
            dynamics: dyn_frame,
        })?;
    }
    Ok(counters)
}

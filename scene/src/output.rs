//! Scene outputs: the per-frame CSV of measured pairs and the run summary (counters and
//! per-frame cost by effect) as Markdown.

use crate::format::Scene;
use crate::runner::{Counters, Frame, Source};
use std::fmt::Write as _;
use std::io::Write;

/// `# key: value` lines opening the CSV (read with `comment="#"`).
pub fn csv_preamble(scene_path: &str, scene: &Scene) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# experiment: revdist scene");
    let _ = writeln!(s, "# scene: {scene_path}");
    let _ = writeln!(s, "# revdist: {}", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "# frames: {}", scene.frames());
    let _ = writeln!(s, "# time_step: {}", scene.time_step);
    let _ = writeln!(s, "# eps: {}", scene.eps);
    let tol = scene
        .tolerance
        .map_or("trees (eps_a + eps_b)".to_string(), |t| t.to_string());
    let _ = writeln!(s, "# tolerance: {tol}");
    s.push_str(
        "frame,time,a,b,lower,upper,value,overlap,source,point_a_x,point_a_y,point_a_z,point_b_x,point_b_y,point_b_z\n",
    );
    s
}

/// The CSV rows of one frame.
pub fn csv_rows(scene: &Scene, frame: &Frame, out: &mut impl Write) -> std::io::Result<()> {
    for s in &frame.samples {
        let source = match s.source {
            Source::Query => "query",
            Source::Reused => "reused",
            Source::BroadPhase => "broad_phase",
        };
        writeln!(
            out,
            "{},{},{},{},{:e},{:e},{:e},{},{source},{},{},{},{},{},{}",
            frame.index,
            frame.time,
            scene.bodies[s.pair.0].name,
            scene.bodies[s.pair.1].name,
            s.lower,
            s.upper,
            s.value,
            s.overlap,
            s.point_a.x,
            s.point_a.y,
            s.point_a.z,
            s.point_b.x,
            s.point_b.y,
            s.point_b.z,
        )?;
    }
    Ok(())
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The Markdown summary: what was computed (counters) and what it cost.
pub fn summary(
    scene_path: &str,
    scene: &Scene,
    counters: &Counters,
    costs: &[crate::runner::FrameCost],
    min_lower: f64,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Scene `{scene_path}`\n");
    let _ = writeln!(
        s,
        "{} frames of {} s, eps {}, {} bodies, {} measured pairs; smallest certified lower bound over all pairs and frames: {:e}.\n",
        counters.frames,
        scene.time_step,
        scene.eps,
        scene.bodies.len(),
        counters.queries.len(),
        min_lower
    );
    let ms = |f: &dyn Fn(&crate::runner::FrameCost) -> f64| {
        1e3 * median(costs.iter().skip(1).map(f).collect())
    };
    let _ = writeln!(s, "Median cost per frame (ms, frames after the first):\n");
    let _ = writeln!(s, "| rebuild | kinematics | dynamics | measure | total |");
    let _ = writeln!(s, "| ---: | ---: | ---: | ---: | ---: |");
    let _ = writeln!(
        s,
        "| {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |\n",
        ms(&|c| c.rebuild),
        ms(&|c| c.kinematics),
        ms(&|c| c.dynamics),
        ms(&|c| c.measure),
        ms(&|c| c.rebuild + c.kinematics + c.dynamics + c.measure)
    );
    let _ = writeln!(s, "| body | effect | builds | rebuilds | pose updates |");
    let _ = writeln!(s, "| --- | --- | ---: | ---: | ---: |");
    for (i, b) in scene.bodies.iter().enumerate() {
        let effect = match b.effect {
            crate::format::Effect::Static => "static",
            crate::format::Effect::Kinematic(_) => "kinematic",
            crate::format::Effect::Deforming => "deforming",
            crate::format::Effect::Dynamic(_) => "dynamic",
        };
        let _ = writeln!(
            s,
            "| {} | {effect} | {} | {} | {} |",
            b.name, counters.initial_builds[i], counters.rebuilds[i], counters.pose_updates[i]
        );
    }
    let _ = writeln!(s, "\n| pair | queries | reused | broad phase |");
    let _ = writeln!(s, "| --- | ---: | ---: | ---: |");
    for (k, &(i, j)) in scene.measured_pairs().iter().enumerate() {
        let _ = writeln!(
            s,
            "| {}-{} | {} | {} | {} |",
            scene.bodies[i].name,
            scene.bodies[j].name,
            counters.queries[k],
            counters.reused[k],
            counters.broad_phase_skips[k]
        );
    }
    s
}

/// Header of the per-frame dynamics CSV (`<scene>-dynamics.csv`).
pub const DYNAMICS_CSV_HEADER: &str = "frame,time,kinetic,potential,energy,max_step_energy_increase,steps,queries_static_dynamic,queries_dynamic_dynamic,pair_checks,tight_queries,min_lower,min_lower_unqueried,carried_skips,bodies_scaled,bodies_stopped,energy_guard_steps,links_intact,dynamics_ms";

/// One row of the dynamics CSV (frames of a dynamic scene).
pub fn dynamics_csv_row(frame: &Frame, out: &mut impl Write) -> std::io::Result<()> {
    let Some(d) = &frame.dynamics else {
        return Ok(());
    };
    let r = &d.report;
    let fin = |x: f64| {
        if x.is_finite() {
            format!("{x:e}")
        } else {
            String::new()
        }
    };
    writeln!(
        out,
        "{},{},{:e},{:e},{:e},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.3}",
        frame.index,
        frame.time,
        d.kinetic,
        d.potential,
        d.kinetic + d.potential,
        fin(r.max_energy_increase),
        r.steps,
        r.queries[0],
        r.queries[1],
        r.pair_checks,
        r.tight_queries,
        fin(r.min_lower),
        fin(r.min_unqueried),
        r.carried_skips,
        r.scaled,
        r.stopped,
        r.energy_guard,
        d.links_intact,
        1e3 * frame.cost.dynamics
    )
}

/// Running totals of a dynamic scene for its summary.
#[derive(Debug, Clone, Default)]
pub struct DynamicsTally {
    pub frames: usize,
    pub energy_start: Option<f64>,
    pub energy_end: f64,
    /// Energy at the end of the frame before (for the per-frame change).
    pub max_step_increase: f64,
    pub max_frame_increase: f64,
    pub min_lower: f64,
    pub min_unqueried: f64,
    pub links_start: usize,
    pub links_end: usize,
    pub steps: usize,
    pub queries: usize,
    pub scaled: usize,
    pub stopped: usize,
    pub energy_guard: usize,
    pub overlaps: usize,
    last_energy: Option<f64>,
    pub dynamics_s: Vec<f64>,
}

impl DynamicsTally {
    pub fn new() -> DynamicsTally {
        DynamicsTally {
            min_lower: f64::INFINITY,
            min_unqueried: f64::INFINITY,
            max_step_increase: f64::NEG_INFINITY,
            max_frame_increase: f64::NEG_INFINITY,
            ..DynamicsTally::default()
        }
    }

    /// Adds a frame (does nothing for frames without dynamics).
    pub fn add(&mut self, frame: &Frame) {
        let Some(d) = &frame.dynamics else {
            return;
        };
        let e = d.kinetic + d.potential;
        if self.energy_start.is_none() {
            self.energy_start = Some(e);
            self.links_start = d.links_intact;
        }
        if let Some(prev) = self.last_energy {
            self.max_frame_increase = self.max_frame_increase.max(e - prev);
        }
        self.last_energy = Some(e);
        self.energy_end = e;
        self.links_end = d.links_intact;
        self.frames += 1;
        let r = &d.report;
        self.max_step_increase = self.max_step_increase.max(r.max_energy_increase);
        self.min_lower = self.min_lower.min(r.min_lower);
        self.min_unqueried = self.min_unqueried.min(r.min_unqueried);
        self.steps += r.steps;
        self.queries += r.queries[0] + r.queries[1];
        self.scaled += r.scaled;
        self.stopped += r.stopped;
        self.energy_guard += r.energy_guard;
        self.overlaps += r.overlaps;
        if frame.index > 0 {
            self.dynamics_s.push(frame.cost.dynamics);
        }
    }

    /// The dynamics section of the summary.
    pub fn markdown(&self, scene: &Scene, counters: &Counters) -> String {
        let mut s = String::new();
        let dynamic = scene
            .bodies
            .iter()
            .filter(|b| matches!(b.effect, crate::format::Effect::Dynamic(_)))
            .count();
        let _ = writeln!(s, "\n## Dynamics\n");
        let _ = writeln!(
            s,
            "{dynamic} dynamic bodies, gravity {:?}, {} steps per frame ({} steps in all), friction {}, {} solver sweeps.\n",
            scene.dynamics.gravity.as_slice(),
            scene.dynamics.substeps,
            self.steps,
            scene.dynamics.friction,
            scene.dynamics.solver_iterations,
        );
        let per_step = self.queries as f64 / self.steps.max(1) as f64;
        let e0 = self.energy_start.unwrap_or(0.0);
        let rows = [
            (
                "smallest certified lower bound of a contact query, all steps",
                format!("{:e}", self.min_lower),
            ),
            (
                "smallest certified lower bound of a pair not queried (spheres or carried)",
                format!("{:e}", self.min_unqueried),
            ),
            ("queries reporting overlap", self.overlaps.to_string()),
            (
                "energy (kinetic + potential) at the start / end",
                format!("{e0:.6e} / {:.6e}", self.energy_end),
            ),
            (
                "largest energy increase of one step",
                format!("{:e}", self.max_step_increase),
            ),
            (
                "largest energy increase from one frame to the next",
                format!("{:e}", self.max_frame_increase),
            ),
            (
                "links intact at the start / end",
                format!(
                    "{} / {} of {}",
                    self.links_start,
                    self.links_end,
                    scene.links.len()
                ),
            ),
            (
                "contact queries per step (static-dynamic + dynamic-dynamic)",
                format!(
                    "{per_step:.1} ({} + {})",
                    counters.dynamics_queries[0], counters.dynamics_queries[1]
                ),
            ),
            (
                "pairs within reach of their bounding spheres, skipped by a carried bound",
                counters.dynamics_carried_skips.to_string(),
            ),
            (
                "second queries at the narrowest width (pairs near the clearance)",
                counters.dynamics_tight_queries.to_string(),
            ),
            (
                "static-static queries",
                counters.dynamics_static_static_queries.to_string(),
            ),
            (
                "body-steps with velocities scaled by the motion bounds / stopped",
                format!("{} / {}", self.scaled, self.stopped),
            ),
            ("steps with the energy guard", self.energy_guard.to_string()),
            (
                "dynamics per frame, median (ms)",
                format!("{:.2}", 1e3 * median(self.dynamics_s.clone())),
            ),
        ];
        let _ = writeln!(s, "| quantity | value |");
        let _ = writeln!(s, "| --- | ---: |");
        for (k, v) in rows {
            let _ = writeln!(s, "| {k} | {v} |");
        }
        s
    }
}

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
    let _ = writeln!(s, "| rebuild | kinematics | measure | total |");
    let _ = writeln!(s, "| ---: | ---: | ---: | ---: |");
    let _ = writeln!(
        s,
        "| {:.3} | {:.3} | {:.3} | {:.3} |\n",
        ms(&|c| c.rebuild),
        ms(&|c| c.kinematics),
        ms(&|c| c.measure),
        ms(&|c| c.rebuild + c.kinematics + c.measure)
    );
    let _ = writeln!(s, "| body | effect | builds | rebuilds | pose updates |");
    let _ = writeln!(s, "| --- | --- | ---: | ---: | ---: |");
    for (i, b) in scene.bodies.iter().enumerate() {
        let effect = match b.effect {
            crate::format::Effect::Static => "static",
            crate::format::Effect::Kinematic(_) => "kinematic",
            crate::format::Effect::Deforming => "deforming",
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

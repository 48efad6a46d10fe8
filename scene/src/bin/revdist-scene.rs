//! `revdist-scene FILE [--out DIR]`: runs a scene (also reached as `revdist scene FILE`).
//! Writes `DIR/<scene>.csv` (every measured pair in every frame) and `DIR/<scene>.md` (what
//! was computed and what it cost); a scene with dynamic bodies also gets
//! `DIR/<scene>-dynamics.csv` (per frame: energy, contact queries, smallest certified gap,
//! velocity scalings, links intact, cost) and a dynamics section in the summary. Errors are
//! printed as `error: ...` with exit status 2.

use clap::Parser;
use revdist_scene::format::Scene;
use revdist_scene::output::{
    csv_preamble, csv_rows, dynamics_csv_row, summary, DynamicsTally, DYNAMICS_CSV_HEADER,
};
use revdist_scene::render::SceneRenderer;
use revdist_scene::runner::{run, FrameCost};
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Run a scene file: bodies, motions and effects (see scene/src/format.rs for the format).
#[derive(Debug, Parser)]
#[command(name = "revdist-scene", version, about)]
struct Args {
    /// The scene file (TOML).
    file: PathBuf,
    /// Output directory for the CSV and the summary.
    #[arg(long, default_value = "scene-out")]
    out: PathBuf,
    /// Run only this much scene time (seconds) instead of the scene's duration.
    #[arg(long)]
    duration: Option<f64>,
}

fn main() -> ExitCode {
    match go(Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn go(args: Args) -> Result<(), Box<dyn std::error::Error>> {
    let mut scene = Scene::load(&args.file)?;
    if let Some(d) = args.duration {
        if !(d.is_finite() && d >= 0.0) {
            return Err(format!("--duration must be finite and >= 0, got {d}").into());
        }
        scene.duration = d.min(scene.duration);
    }
    let stem = args
        .file
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("scene")
        .to_string();
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create '{}': {e}", args.out.display()))?;
    let csv_path = args.out.join(format!("{stem}.csv"));
    let file = std::fs::File::create(&csv_path)
        .map_err(|e| format!("cannot write '{}': {e}", csv_path.display()))?;
    let mut csv = BufWriter::new(file);
    let shown = args.file.display().to_string();
    csv.write_all(csv_preamble(&shown, &scene).as_bytes())?;
    let mut costs: Vec<FrameCost> = Vec::new();
    let mut min_lower = f64::INFINITY;
    let mut renderer = SceneRenderer::new(&scene);
    let frames_dir = args.out.join(format!("{stem}-frames"));
    let mut render_s = Vec::new();
    // Scenes with dynamic bodies also get DIR/<scene>-dynamics.csv, one row per frame.
    let dyn_path = args.out.join(format!("{stem}-dynamics.csv"));
    let mut dyn_csv = if scene.has_dynamics() {
        let file = std::fs::File::create(&dyn_path)
            .map_err(|e| format!("cannot write '{}': {e}", dyn_path.display()))?;
        let mut w = BufWriter::new(file);
        w.write_all(
            csv_preamble(&shown, &scene)
                .lines()
                .filter(|l| l.starts_with('#'))
                .map(|l| format!("{l}\n"))
                .collect::<String>()
                .as_bytes(),
        )?;
        writeln!(w, "{DYNAMICS_CSV_HEADER}")?;
        Some(w)
    } else {
        None
    };
    let mut tally = DynamicsTally::new();
    let wall = std::time::Instant::now();
    let counters = run(&scene, |frame| {
        csv_rows(&scene, frame, &mut csv)?;
        if let Some(w) = dyn_csv.as_mut() {
            dynamics_csv_row(frame, w)?;
            tally.add(frame);
        }
        costs.push(frame.cost);
        if let Some(r) = renderer.as_mut() {
            let clock = std::time::Instant::now();
            r.frame(&scene, frame, &frames_dir)?;
            render_s.push(clock.elapsed().as_secs_f64());
        }
        for s in &frame.samples {
            min_lower = min_lower.min(s.lower);
        }
        Ok(())
    })?;
    csv.flush()?;
    let wall_s = wall.elapsed().as_secs_f64();
    if let Some(w) = dyn_csv.as_mut() {
        w.flush()?;
    }
    let mut md = summary(&shown, &scene, &counters, &costs, min_lower);
    if dyn_csv.is_some() {
        md.push_str(&tally.markdown(&scene, &counters));
        md.push_str(&format!(
            "\nWall time of the run: {wall_s:.1} s ({:.1} ms per frame, rendering included); per-frame rows in `{}`.\n",
            1e3 * wall_s / counters.frames.max(1) as f64,
            dyn_path.display()
        ));
    }
    if let (Some(r), Some(spec)) = (&renderer, &scene.render) {
        let total: f64 = render_s.iter().sum();
        let gif_path = args.out.join(format!("{stem}.gif"));
        let clock = std::time::Instant::now();
        r.write_gif(&gif_path, scene.time_step * spec.every as f64)?;
        md.push_str(&format!(
            "\nRendered {} frames into `{}` ({:.1} ms per rendered frame) and the animated summary `{}` ({:.0} ms).\n",
            r.rendered,
            frames_dir.display(),
            1e3 * total / r.rendered.max(1) as f64,
            gif_path.display(),
            1e3 * clock.elapsed().as_secs_f64()
        ));
    }
    let md_path = args.out.join(format!("{stem}.md"));
    std::fs::write(&md_path, &md)
        .map_err(|e| format!("cannot write '{}': {e}", md_path.display()))?;
    print!("{md}");
    println!("\nwrote {} and {}", csv_path.display(), md_path.display());
    Ok(())
}

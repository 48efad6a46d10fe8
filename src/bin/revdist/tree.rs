//! `revdist tree NAME|FILE --eps E [--json] [--svg OUT]`: build the biarc tree of a profile
//! (paper section 4.1) and report node counts, depth, bytes and build time; optionally draw the
//! profile, the leaf arcs and their error bands.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use revdist::biarc::{Arc, BiarcTree, SpiralBound};
use revdist::profile::Profile;

use crate::input::{load_profile, write_file};
use crate::CmdResult;

/// Timed rebuilds for the reported build time (median); the first build is not timed.
const TIMED_BUILDS: usize = 21;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Built-in model name (see `revdist models`) or profile file.
    profile: String,
    /// Leaf bound: two-sided Hausdorff distance between curve and biarcs.
    #[arg(long)]
    eps: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Draw the profile, its arcs and their error bands into this SVG file.
    #[arg(long)]
    svg: Option<PathBuf>,
}

pub fn run(args: Args) -> CmdResult {
    let profile = load_profile(&args.profile)?;
    let mut tree = BiarcTree::build(&profile, args.eps)?;
    let mut times = Vec::with_capacity(TIMED_BUILDS);
    for _ in 0..TIMED_BUILDS {
        let start = Instant::now();
        tree.rebuild(&profile, args.eps)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let build_ms = times[times.len() / 2];
    let st = tree.stats();
    let max_eps = tree
        .nodes()
        .iter()
        .filter(|n| n.is_leaf())
        .map(|n| n.eps())
        .fold(0.0, f64::max);
    // How each spiral's node bounds are certified (see `SpiralBound`).
    let count = |kind: SpiralBound| tree.spirals().iter().filter(|s| s.bound() == kind).count();
    let (bilens, arc_deviation, control_polygon) = (
        count(SpiralBound::Bilens),
        count(SpiralBound::ArcDeviation),
        count(SpiralBound::ControlPolygon),
    );
    if args.json {
        let v = serde_json::json!({
            "profile": profile.name(),
            "eps": args.eps,
            "spirals": st.spirals,
            "spirals_bilens": bilens,
            "spirals_arc_deviation": arc_deviation,
            "spirals_control_polygon": control_polygon,
            "nodes": st.nodes,
            "leaves": st.leaves,
            "arcs": 2 * st.leaves,
            "upper_nodes": st.upper_nodes,
            "depth": st.depth,
            "bytes": st.bytes,
            "build_ms_median": build_ms,
            "max_leaf_bound": max_eps,
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!("profile      {}", profile.name());
        println!("eps          {:e}", args.eps);
        println!(
            "spirals      {} (bounds: {bilens} bilens, {arc_deviation} arc deviation, \
             {control_polygon} control polygon)",
            st.spirals
        );
        println!(
            "nodes        {} ({} leaves, {} arcs)",
            st.nodes,
            st.leaves,
            2 * st.leaves
        );
        println!("upper nodes  {}", st.upper_nodes);
        println!("depth        {}", st.depth);
        println!("bytes        {}", st.bytes);
        println!("build time   {build_ms:.4} ms (median of {TIMED_BUILDS})");
        println!("max leaf eps {max_eps:e}");
    }
    if let Some(path) = &args.svg {
        write_file(path, &tree_svg(&profile, &tree))?;
        if !args.json {
            println!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// SVG path command drawing `arc` (points mapped by `map`), without the initial move.
fn arc_path(arc: &Arc, map: &impl Fn(nalgebra::Point2<f64>) -> (f64, f64)) -> String {
    let (x, y) = map(arc.end);
    if arc.is_segment() {
        return format!("L {x:.6} {y:.6}");
    }
    let r = arc.radius() * map_scale(map);
    let large = u8::from(arc.sweep.abs() > std::f64::consts::PI);
    // The map flips z, so a counter-clockwise arc in (rho, z) (sweep > 0) needs SVG's
    // sweep-flag 0 (checked by drawing the pawn's arcs over its sampled profile).
    let sweep = u8::from(arc.sweep < 0.0);
    format!("A {r:.6} {r:.6} 0 {large} {sweep} {x:.6} {y:.6}")
}

fn map_scale(map: &impl Fn(nalgebra::Point2<f64>) -> (f64, f64)) -> f64 {
    let (a, _) = map(nalgebra::Point2::new(0.0, 0.0));
    let (b, _) = map(nalgebra::Point2::new(1.0, 0.0));
    b - a
}

/// The profile (thin black polyline), each leaf arc (alternating colours) and its error band
/// (a translucent stroke of width 2 eps_node around the arc, to scale).
fn tree_svg(profile: &Profile, tree: &BiarcTree) -> String {
    const WIDTH: f64 = 800.0;
    let bb = profile.bounding_box();
    let size = (bb.max - bb.min).amax().max(1e-12);
    let margin = 0.05 * size;
    let scale = WIDTH / (size + 2.0 * margin);
    let (w, h) = (
        (bb.max.x - bb.min.x + 2.0 * margin) * scale,
        (bb.max.y - bb.min.y + 2.0 * margin) * scale,
    );
    let map = |p: nalgebra::Point2<f64>| {
        (
            (p.x - bb.min.x + margin) * scale,
            (bb.max.y + margin - p.y) * scale,
        )
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.3} {h:.3}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        "<!-- {}: eps {:e}, {} spirals, {} leaves; bands are 2 eps_node wide, to scale -->",
        profile.name(),
        tree.eps(),
        tree.spirals().len(),
        tree.stats().leaves
    );
    for (i, leaf) in tree.leaves().enumerate() {
        let color = if i % 2 == 0 { "#1f77b4" } else { "#d62728" };
        let (x0, y0) = map(leaf.arcs()[0].start);
        let mut d = format!("M {x0:.6} {y0:.6} ");
        for a in leaf.arcs() {
            d.push_str(&arc_path(a, &map));
            d.push(' ');
        }
        let band = (2.0 * leaf.eps() * scale).max(0.0);
        let _ = writeln!(
            s,
            r#"<path d="{d}" fill="none" stroke="{color}" stroke-opacity="0.25" stroke-width="{band:.6}"/>"#
        );
        let _ = writeln!(
            s,
            r#"<path d="{d}" fill="none" stroke="{color}" stroke-width="1.5"/>"#
        );
        let (xj, yj) = map(leaf.arcs()[0].end);
        let _ = writeln!(
            s,
            r#"<circle cx="{xj:.6}" cy="{yj:.6}" r="1.5" fill="{color}"/>"#
        );
    }
    let pts: Vec<String> = profile
        .sample(200)
        .into_iter()
        .map(|p| {
            let (x, y) = map(p);
            format!("{x:.4},{y:.4}")
        })
        .collect();
    let _ = writeln!(
        s,
        r#"<polyline points="{}" fill="none" stroke="black" stroke-width="0.5"/>"#,
        pts.join(" ")
    );
    s.push_str("</svg>\n");
    s
}

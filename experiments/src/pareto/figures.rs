//! The figures `pareto_{time,build,memory}.svg`: cost against the certified error bound.

use super::method::METHODS;
use super::row::Row;
use super::Settings;
use crate::plot::{log_log_panels, Curve, Panel};
use std::path::Path;

/// Writes the three figures, one panel per pair and one curve per method.
pub(super) fn figures(
    out: &Path,
    rows: &[Row],
    args: &Settings,
) -> Result<(), Box<dyn std::error::Error>> {
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let panels = |y: &dyn Fn(&Row) -> f64| -> Vec<Panel> {
        pairs
            .iter()
            .map(|pair| Panel {
                title: pair.clone(),
                curves: METHODS
                    .iter()
                    .enumerate()
                    .map(|(k, &m)| Curve {
                        name: m.label().to_string(),
                        style: k,
                        dashed: m.is_fcl(),
                        points: rows
                            .iter()
                            .filter(|r| r.method == m && &r.pair == pair)
                            .map(|r| (r.width_max, y(r)))
                            .collect(),
                    })
                    .collect(),
            })
            .collect()
    };
    let x_desc = "certified error bound: interval width (model length units)";
    let size = (430, 430);
    log_log_panels(
        &out.join("pareto_time.svg"),
        &format!("What accuracy costs: median query time over {} poses near contact (lower left is better)", args.poses),
        &panels(&|r| r.median_us),
        x_desc,
        "median query time (us)",
        size,
    )?;
    log_log_panels(
        &out.join("pareto_build.svg"),
        "What accuracy costs: build time (revdist trees; FCL tessellation + BVH)",
        &panels(&|r| r.build_ms),
        x_desc,
        "build time (ms)",
        size,
    )?;
    log_log_panels(
        &out.join("pareto_memory.svg"),
        "What accuracy costs: memory (revdist query trees; FCL BVH, triangles, vertices)",
        &panels(&|r| r.bytes as f64),
        x_desc,
        "memory (bytes)",
        size,
    )?;
    Ok(())
}

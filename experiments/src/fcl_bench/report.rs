//! `fcl_bench.md`: the cold, warm/blocked and layout tables and the text around them.

use super::row::{Row, BV_NAMES};
use super::GAPS;
use crate::baseline_mesh::LAYOUT_NAMES;
use crate::stats::human_bytes;
use crate::table::Table;
use std::fmt::Write as _;
use std::time::Duration;

/// The `pair` and `eps` columns that open every Markdown table.
fn pair_and_eps() -> Table<'static, Row> {
    Table::new()
        .markdown("pair", |r: &Row| r.pair.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
}

/// The main Markdown table: cold medians, the faster layout per FCL column.
fn cold_table() -> Table<'static, Row> {
    pair_and_eps()
        .markdown("poses", |r| r.poses.to_string())
        .right()
        .markdown("triangles A+B", |r| r.tris[r.best_obbrss].to_string())
        .right()
        .markdown("revdist median / p90 us", |r| {
            format!("{:.1} / {:.1}", r.rev_trees.0, r.rev_trees.1)
        })
        .right()
        .markdown("revdist tol 0, traversal, median us", |r| {
            format!("{:.1}", r.rev_exact.0)
        })
        .right()
        .markdown("FCL OBBRSS median us", |r| {
            format!(
                "{:.1} ({})",
                r.best_obbrss_us(),
                LAYOUT_NAMES[r.best_obbrss]
            )
        })
        .right()
        .markdown("FCL RSS median us", |r| {
            format!("{:.1} ({})", r.best_rss_us(), LAYOUT_NAMES[r.best_rss])
        })
        .right()
        .markdown("faster FCL BV", |r| BV_NAMES[r.faster().0].into())
        .markdown("ratio vs faster FCL BV", |r| format!("{:.2}", r.ratio()))
        .right()
        .markdown("build revdist / mesh+OBBRSS ms", |r| {
            let o = r.best_obbrss;
            let fcl = r.mesh_ms[o] + r.obbrss_build_ms[o];
            format!("{:.2} / {fcl:.1}", r.rev_build_ms)
        })
        .right()
        .markdown("memory revdist / OBBRSS / RSS", |r| {
            let rev = human_bytes(r.rev_bytes as f64);
            let obbrss = human_bytes(r.obbrss_bytes[r.best_obbrss] as f64);
            format!(
                "{rev} / {obbrss} / {}",
                human_bytes(r.rss_bytes[r.best_rss] as f64)
            )
        })
        .right()
        .markdown("max width / h_a+h_b", |r| {
            format!("{:.2e} / {:.2e}", r.max_width, r.h_sum[r.best_obbrss])
        })
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

/// Blocked and warm medians, FCL's faster BV in each mode (each BV in its faster cold layout).
fn blocked_warm_table() -> Table<'static, Row> {
    let us = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.1}", f(r));
    let ratio = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.2}", f(r));
    let fcl = |f: fn(&Row) -> (usize, f64)| {
        move |r: &Row| {
            let (bv, t) = f(r);
            format!("{t:.1} ({})", BV_NAMES[bv])
        }
    };
    pair_and_eps()
        .markdown("revdist blocked", us(|r| r.rev_trees_blocked))
        .right()
        .markdown("FCL blocked (faster BV)", fcl(Row::faster_blocked))
        .right()
        .markdown("ratio blocked vs faster FCL BV", ratio(Row::blocked_ratio))
        .right()
        .markdown("revdist warm", us(|r| r.rev_trees_warm))
        .right()
        .markdown("FCL warm (faster BV)", fcl(Row::faster_warm))
        .right()
        .markdown("ratio warm vs faster FCL BV", ratio(Row::warm_ratio))
        .right()
        .markdown(
            "cold / blocked revdist",
            ratio(|r| r.rev_trees.0 / r.rev_trees_blocked),
        )
        .right()
        .markdown(
            "cold / blocked FCL",
            ratio(|r| r.faster().1 / r.faster_blocked().1),
        )
        .right()
}

/// FCL's medians in every layout.
fn layouts_table() -> Table<'static, Row> {
    let layout = |l: usize| move |r: &Row| format!("{:.1} / {:.1}", r.fcl[l].0, r.fcl[l].1);
    pair_and_eps()
        .markdown("balanced OBBRSS / RSS", layout(0))
        .right()
        .markdown("tris", |r| r.tris[0].to_string())
        .right()
        .markdown("capped OBBRSS / RSS", layout(1))
        .right()
        .markdown("tris", |r| r.tris[1].to_string())
        .right()
}

/// The CPU and its cores, as the report's header names the machine.
fn machine() -> String {
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{}, {cores} cores", crate::provenance::cpu_model())
}

/// `poses`: per pair at eps >= 5e-5 and below.
pub(super) fn markdown(rows: &[Row], poses: (usize, usize), wall: Duration) -> String {
    let mut s = String::from("# revdist vs FCL 0.7 at equal accuracy\n\n");
    let _ = writeln!(
        s,
        "Machine: {}. Commit: {}. Poses per pair: {} (eps >= 5e-5), {} (eps < 5e-5; the first \
         poses of the same sequence; the default list's freeform and M_t pairs: half as many, \
         at eps 1e-3 and 1e-4 only, unless --paper; the `poses` column tells), gaps \
         log-uniform in [{:e}, {:e}], seeded; wall time {:.0} s.\n",
        machine(),
        crate::provenance::git_commit(),
        poses.0,
        poses.1,
        GAPS.0,
        GAPS.1,
        wall.as_secs_f64()
    );
    s.push_str(
        "Single thread, one query at a time, methods interleaved per pose. revdist: default \
         tolerance (certified interval width <= eps_a + eps_b; balls and solid tori in closed form) \
         and tolerance 0 with the traversal only (no closed form). FCL: \
         `BVHModel<OBBRSS>` / `<RSS>` on certified meshes (two-sided Hausdorff bound <= eps), \
         the faster of two layouts per column (balanced; meridian edges capped at 1/64 of the \
         profile diagonal). Ratio = median of the faster FCL BV (OBBRSS or RSS, each in its \
         faster layout; named in the column before) / revdist median (default tolerance). \
         Memory: revdist query-tree arrays vs FCL's node, triangle and vertex arrays (both \
         shapes; one when A = B). Build: revdist trees vs tessellation + OBBRSS build (layout \
         of the OBBRSS column). Violations: cases where revdist's interval misses FCL's \
         `d ± (h_a + h_b)`. All times are *cold*: each query runs after the other methods' \
         queries (FCL's meshes take megabytes), so its trees and code come from memory. The \
         second table runs each method *blocked* (alone over all poses in a row, the usual \
         benchmark loop) and *warm* (each query repeated at once on the same pose).\n\n",
    );
    s.push_str(&cold_table().markdown_text(rows));
    s.push_str(
        "\nBlocked (each method alone over all poses in a row) and warm (each query repeated at \
         once on the same pose); FCL: the faster BV in that mode, each BV in its layout of the \
         first table; medians, us:\n\n",
    );
    s.push_str(&blocked_warm_table().markdown_text(rows));
    s.push_str("\nAll layouts (FCL medians, us; triangles):\n\n");
    s.push_str(&layouts_table().markdown_text(rows));
    s
}

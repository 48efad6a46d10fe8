//! The columns of `fcl_bench.csv`.

use super::row::{Row, BV_NAMES};
use crate::baseline_mesh::LAYOUT_NAMES;
use crate::table::Table;

/// The columns of `fcl_bench.csv` (index 0 of a per-layout field: balanced, 1: capped).
pub(super) fn csv_table() -> Table<'static, Row> {
    let fixed = |digits: usize, f: fn(&Row) -> f64| move |r: &Row| format!("{:.*}", digits, f(r));
    let sci4 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.4e}", f(r));
    let count = |f: fn(&Row) -> usize| move |r: &Row| f(r).to_string();
    Table::new()
        .csv("pair", |r: &Row| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .csv("poses", count(|r| r.poses))
        .csv("rev_trees_median_us", fixed(2, |r| r.rev_trees.0))
        .csv("rev_trees_p90_us", fixed(2, |r| r.rev_trees.1))
        .csv("rev_tol0_median_us", fixed(2, |r| r.rev_exact.0))
        .csv("rev_tol0_p90_us", fixed(2, |r| r.rev_exact.1))
        .csv("fcl_obbrss_balanced_us", fixed(2, |r| r.fcl[0].0))
        .csv("fcl_rss_balanced_us", fixed(2, |r| r.fcl[0].1))
        .csv("fcl_obbrss_capped_us", fixed(2, |r| r.fcl[1].0))
        .csv("fcl_rss_capped_us", fixed(2, |r| r.fcl[1].1))
        .csv("best_obbrss_layout", |r| LAYOUT_NAMES[r.best_obbrss].into())
        .csv("best_rss_layout", |r| LAYOUT_NAMES[r.best_rss].into())
        // The headline: the faster FCL BV (cold, each BV in its faster layout) over revdist.
        .csv("faster_fcl_bv", |r| BV_NAMES[r.faster().0].into())
        .csv("faster_fcl_bv_layout", |r| {
            LAYOUT_NAMES[r.faster_layout()].into()
        })
        .csv("faster_fcl_bv_us", fixed(2, |r| r.faster().1))
        .csv("ratio_vs_faster_fcl_bv", fixed(3, Row::ratio))
        .csv(
            "ratio_vs_faster_fcl_bv_tol0",
            fixed(3, |r| r.faster().1 / r.rev_exact.0),
        )
        .csv(
            "ratio_obbrss_over_rev",
            fixed(3, |r| r.best_obbrss_us() / r.rev_trees.0),
        )
        .csv(
            "ratio_rss_over_rev",
            fixed(3, |r| r.best_rss_us() / r.rev_trees.0),
        )
        .csv("tris_balanced", count(|r| r.tris[0]))
        .csv("tris_capped", count(|r| r.tris[1]))
        .csv("h_sum_balanced", sci4(|r| r.h_sum[0]))
        .csv("h_sum_capped", sci4(|r| r.h_sum[1]))
        .csv("rev_max_width", sci4(|r| r.max_width))
        .csv("rev_build_ms", fixed(3, |r| r.rev_build_ms))
        .csv("mesh_ms_balanced", fixed(3, |r| r.mesh_ms[0]))
        .csv(
            "obbrss_build_ms_balanced",
            fixed(3, |r| r.obbrss_build_ms[0]),
        )
        .csv("rss_build_ms_balanced", fixed(3, |r| r.rss_build_ms[0]))
        .csv("mesh_ms_capped", fixed(3, |r| r.mesh_ms[1]))
        .csv("obbrss_build_ms_capped", fixed(3, |r| r.obbrss_build_ms[1]))
        .csv("rss_build_ms_capped", fixed(3, |r| r.rss_build_ms[1]))
        .csv("rev_query_tree_bytes", count(|r| r.rev_bytes))
        .csv("rev_biarc_tree_bytes", count(|r| r.rev_tree_bytes))
        .csv("obbrss_bytes_balanced", count(|r| r.obbrss_bytes[0]))
        .csv("rss_bytes_balanced", count(|r| r.rss_bytes[0]))
        .csv("obbrss_bytes_capped", count(|r| r.obbrss_bytes[1]))
        .csv("rss_bytes_capped", count(|r| r.rss_bytes[1]))
        .csv("violations", count(|r| r.violations))
        // Warm and blocked columns come last (readers find columns by their header).
        .csv("rev_trees_warm_median_us", fixed(2, |r| r.rev_trees_warm))
        .csv(
            "fcl_obbrss_balanced_warm_us",
            fixed(2, |r| r.fcl_obbrss_warm[0]),
        )
        .csv(
            "fcl_obbrss_capped_warm_us",
            fixed(2, |r| r.fcl_obbrss_warm[1]),
        )
        .csv("fcl_rss_balanced_warm_us", fixed(2, |r| r.fcl_rss_warm[0]))
        .csv("fcl_rss_capped_warm_us", fixed(2, |r| r.fcl_rss_warm[1]))
        .csv("faster_fcl_bv_warm", |r| BV_NAMES[r.faster_warm().0].into())
        .csv("ratio_vs_faster_fcl_bv_warm", fixed(3, Row::warm_ratio))
        .csv(
            "rev_trees_blocked_median_us",
            fixed(2, |r| r.rev_trees_blocked),
        )
        .csv(
            "fcl_obbrss_balanced_blocked_us",
            fixed(2, |r| r.fcl_obbrss_blocked[0]),
        )
        .csv(
            "fcl_obbrss_capped_blocked_us",
            fixed(2, |r| r.fcl_obbrss_blocked[1]),
        )
        .csv(
            "fcl_rss_best_layout_blocked_us",
            fixed(2, |r| r.fcl_rss_blocked),
        )
        .csv("faster_fcl_bv_blocked", |r| {
            BV_NAMES[r.faster_blocked().0].into()
        })
        .csv(
            "ratio_vs_faster_fcl_bv_blocked",
            fixed(3, Row::blocked_ratio),
        )
}

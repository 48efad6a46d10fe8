//! The outputs' text: the columns of `pareto.csv` and of the per-pair tables, and `pareto.md`.

use super::row::Row;
use super::summary::summary;
use super::Settings;
use crate::poses::CLOSE_GAPS;
use crate::provenance::Provenance;
use crate::stats::human_bytes;
use crate::table::Table;
use std::fmt::Write as _;

/// The columns of `pareto.csv` and of the per-pair tables in `pareto.md`.
pub(super) fn cost_table() -> Table<'static, Row> {
    let or_dash = |v: Option<String>| v.unwrap_or_else(|| "-".into());
    Table::new()
        .csv("method", |r: &Row| r.method.key().to_owned())
        .with_markdown("method", |r| r.method.label().to_owned())
        .csv("pair", |r| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("poses", |r| r.poses.to_string())
        .csv("width_max", |r| format!("{:.4e}", r.width_max))
        .csv("width_median", |r| format!("{:.4e}", r.width_median))
        .markdown("certified error: max / median", |r| {
            format!("{:.2e} / {:.2e}", r.width_max, r.width_median)
        })
        .right()
        .csv("query_median_us", |r| format!("{:.2}", r.median_us))
        .csv("query_p90_us", |r| format!("{:.2}", r.p90_us))
        .markdown("query median / p90 (us)", |r| {
            format!("{:.1} / {:.1}", r.median_us, r.p90_us)
        })
        .right()
        .markdown("node pairs / query", move |r| {
            or_dash(r.node_pairs.map(|n| format!("{n:.0}")))
        })
        .right()
        .markdown("lower = 0", move |r| {
            or_dash(r.zero_lower.map(|n| n.to_string()))
        })
        .right()
        .csv("build_ms", |r| format!("{:.4}", r.build_ms))
        .with_markdown("build (ms)", |r| format!("{:.3}", r.build_ms))
        .right()
        .csv("bytes", |r| r.bytes.to_string())
        .with_markdown("memory", |r| human_bytes(r.bytes as f64))
        .right()
        .csv("mean_node_pairs", |r| {
            r.node_pairs.map_or(String::new(), |n| format!("{n:.1}"))
        })
        .csv("zero_lower", |r| {
            r.zero_lower.map_or(String::new(), |n| n.to_string())
        })
        .csv("triangles", |r| {
            r.triangles.map_or(String::new(), |t| t.to_string())
        })
        .markdown("triangles (layout)", move |r| {
            or_dash(
                r.triangles
                    .map(|t| format!("{t} ({})", r.layout.unwrap_or(""))),
            )
        })
        .right()
        .csv("layout", |r| r.layout.unwrap_or("").to_owned())
        .csv("checks", |r| r.checks.to_string())
        .csv("violations", |r| r.violations.to_string())
        .markdown("violations / checks", |r| {
            format!("{} / {}", r.violations, r.checks)
        })
        .right()
}

/// `run`: wall time (s) and the load averages at start / end.
pub(super) fn markdown(
    rows: &[Row],
    skipped: &[String],
    args: &Settings,
    prov: &Provenance,
    (wall, load): (f64, &str),
) -> String {
    let mut s =
        String::from("# What accuracy costs: revdist and FCL on the accuracy/cost plane\n\n");
    let _ = writeln!(
        s,
        "Per model pair, {} seeded poses near contact (gaps log-uniform in [{:e}, {:e}], the \
         poses of `fcl_bench`), the same poses for every method and accuracy, timed one query \
         at a time on one thread with the methods interleaved per pose (wall time {wall:.0} s; \
         1-minute load average at start / end {load} on {} cores: above ~1, other processes \
         shared the cores and absolute times are noisier, ratios less so).\n",
        args.poses,
        CLOSE_GAPS.0,
        CLOSE_GAPS.1,
        prov.get("threads_available").unwrap_or("?")
    );
    s.push_str(
        "**Certified error bound** (x axis of the figures, model length units): for revdist the \
         width `upper - lower` of the certified interval it returns (worst over the poses in the \
         figures; median beside it here); for FCL `h_a + h_b`, the meshes' certified Hausdorff \
         bounds, since the truth lies in `d_FCL ± (h_a + h_b)`. revdist at its default \
         tolerance stops once the width is at most `eps_a + eps_b`; at tolerance 0 it narrows \
         as far as its trees allow; refined polishes the witnesses on the exact surfaces, which \
         lowers the upper bound. FCL runs `BVHModel<OBBRSS>` and `<RSS>` on certified meshes \
         (the faster of two layouts per row). Build: revdist's trees (median of a few builds) \
         against tessellation + BVH build (one build). Memory: revdist's query-tree arrays \
         against FCL's node, triangle and vertex arrays. One structure when A = B. \
         Violations: revdist answers whose interval misses an FCL interval of the same pose \
         (each revdist answer against every FCL answer).\n\n",
    );
    s.push_str(
        "![query time](pareto_time.svg)\n\n![build time](pareto_build.svg)\n\n\
         ![memory](pareto_memory.svg)\n\n\
         Points stacked at the left edge (a few 1e-10) sit at the rounding floor of revdist's \
         bounds: where every leaf pair is resolved exactly (the torus is one exact circle, the \
         table and lightmill are mostly exact lines and arcs), a finer eps buys no more \
         accuracy and only costs time. revdist's three modes share one tree per eps, so in the \
         build and memory figures they differ only in x.\n\n",
    );
    s.push_str("## What the curves show\n\n");
    s.push_str(&summary(rows, args));
    if !skipped.is_empty() {
        s.push_str("\nNot run (triangle count ~ eps^-1):\n\n");
        for k in skipped {
            let _ = writeln!(s, "- {k}");
        }
    }
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let table = cost_table();
    for pair in &pairs {
        let _ = writeln!(s, "\n## {pair}\n");
        s.push_str(&table.markdown_text(rows.iter().filter(|r| &r.pair == pair)));
    }
    s.push_str(&prov.markdown_footer());
    s
}

//! The outputs' text: the columns of `peers.csv` and `peers_convex.csv`, and `peers.md`.

use super::rows::{ConvexRow, Row, Timed};
use super::{COAL_GJK_TOLERANCE, CONVEX_EPS, PARRY_GROSS_EXCESS};
use crate::poses::CLOSE_GAPS;
use crate::stats::human_bytes;
use crate::table::Table;

fn opt_us(v: Option<f64>) -> String {
    v.map_or_else(String::new, |t| format!("{t:.2}"))
}

/// The columns of `peers.csv` (coal's are empty when it did not run; `coal_status` says why).
pub(super) fn mesh_csv() -> Table<'static, Row> {
    let f2 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.2}", f(r));
    let f3 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.3}", f(r));
    let n = |f: fn(&Row) -> usize| move |r: &Row| f(r).to_string();
    let coal = |f: fn(&Timed) -> String| move |r: &Row| r.coal.as_ref().map_or(String::new(), f);
    Table::new()
        .csv("pair", |r: &Row| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .csv("poses", n(|r| r.poses))
        .csv("parry_poses", n(|r| r.parry_poses))
        .csv("triangles", n(|r| r.tris))
        .csv("h_sum", |r| format!("{:.4e}", r.h_sum))
        .csv("rev_median_us", f2(|r| r.rev.us))
        .csv("fcl_obbrss_median_us", f2(|r| r.fcl_obbrss.us))
        .csv("fcl_rss_median_us", f2(|r| r.fcl_rss.us))
        .csv("coal_obbrss_median_us", coal(|t| format!("{:.2}", t.us)))
        .csv("parry_median_us", f2(|r| r.parry.us))
        .csv("occt_median_us", |r| opt_us(r.occt_us))
        .csv("fastest_peer", |r| r.fastest().0.into())
        .csv("ratio_fastest_peer_over_rev", f3(Row::ratio))
        .csv("rev_build_ms", f3(|r| r.rev.build_ms))
        .csv("fcl_obbrss_build_ms", f3(|r| r.fcl_obbrss.build_ms))
        .csv("fcl_rss_build_ms", f3(|r| r.fcl_rss.build_ms))
        .csv(
            "coal_obbrss_build_ms",
            coal(|t| format!("{:.3}", t.build_ms)),
        )
        .csv("parry_build_ms", f3(|r| r.parry.build_ms))
        .csv("rev_bytes", n(|r| r.rev.bytes))
        .csv("fcl_obbrss_bytes", n(|r| r.fcl_obbrss.bytes))
        .csv("fcl_rss_bytes", n(|r| r.fcl_rss.bytes))
        .csv("coal_obbrss_bytes", coal(|t| t.bytes.to_string()))
        .csv("parry_bytes", n(|r| r.parry.bytes))
        .csv("rev_max_width", |r| format!("{:.4e}", r.max_width))
        .csv("violations", n(|r| r.violations))
        .csv("coal_status", |r| match &r.coal {
            Ok(_) => "ran".into(),
            Err(e) => e.replace(',', ";"),
        })
}

pub(super) fn convex_csv() -> Table<'static, ConvexRow> {
    Table::new()
        .csv("pair", |r: &ConvexRow| r.pair.clone())
        .csv("poses", |r| r.poses.to_string())
        .csv("rev_median_us", |r| format!("{:.3}", r.rev_us))
        .csv("rev_convex_path_median_us", |r| opt_us(r.rev_convex_us))
        .csv("coal_gjk_median_us", |r| {
            r.coal.as_ref().map_or(String::new(), |t| format!("{t:.3}"))
        })
        .csv("parry_median_us", |r| format!("{:.3}", r.parry_us))
        .csv("fastest_peer", |r| r.fastest().0.into())
        .csv("ratio_fastest_peer_over_rev", |r| {
            format!("{:.3}", r.fastest().1 / r.rev_us)
        })
        .csv("ratio_fastest_peer_over_rev_convex_path", |r| {
            r.rev_convex_us
                .map_or_else(String::new, |c| format!("{:.3}", r.fastest().1 / c))
        })
        .csv("parry_max_excess", |r| format!("{:.3e}", r.parry_excess))
        .csv("rev_max_width", |r| format!("{:.4e}", r.max_width))
        .csv("violations", |r| r.violations.to_string())
}

fn mesh_md(coal_note: &str) -> Table<'static, Row> {
    let note = coal_note.to_owned();
    let time_build_mem = |t: &Timed| {
        format!(
            "{:.1} / {:.1} / {}",
            t.us,
            t.build_ms,
            human_bytes(t.bytes as f64)
        )
    };
    Table::new()
        .markdown("pair", |r: &Row| r.pair.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
        .markdown("poses (parry3d)", |r| {
            format!("{} ({})", r.poses, r.parry_poses)
        })
        .right()
        .markdown("triangles A+B", |r| r.tris.to_string())
        .right()
        .markdown("revdist", move |r| time_build_mem(&r.rev))
        .right()
        .markdown("FCL OBBRSS", move |r| time_build_mem(&r.fcl_obbrss))
        .right()
        .markdown("FCL RSS", move |r| time_build_mem(&r.fcl_rss))
        .right()
        .markdown("coal OBBRSS", move |r| {
            r.coal
                .as_ref()
                .map_or_else(|_| note.clone(), time_build_mem)
        })
        .right()
        .markdown("parry3d (one-sided)", move |r| time_build_mem(&r.parry))
        .right()
        .markdown("OCCT", |r| {
            r.occt_us.map_or_else(|| "-".into(), |t| format!("{t:.0}"))
        })
        .right()
        .markdown("fastest peer", |r| r.fastest().0.into())
        .markdown("ratio", |r| format!("{:.2}", r.ratio()))
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

fn convex_md(coal_note: &str) -> Table<'static, ConvexRow> {
    let note = coal_note.to_owned();
    Table::new()
        .markdown("pair", |r: &ConvexRow| r.pair.clone())
        .markdown("poses", |r| r.poses.to_string())
        .right()
        .markdown("revdist default", |r| format!("{:.2}", r.rev_us))
        .right()
        .markdown("revdist convex path", |r| {
            r.rev_convex_us
                .map_or_else(|| "-".into(), |t| format!("{t:.2}"))
        })
        .right()
        .markdown("coal GJK", move |r| {
            r.coal
                .as_ref()
                .map_or_else(|_| note.clone(), |t| format!("{t:.2}"))
        })
        .right()
        .markdown("parry3d", |r| format!("{:.2}", r.parry_us))
        .right()
        .markdown("fastest peer", |r| r.fastest().0.into())
        .markdown("ratio default / convex path", |r| {
            let f = r.fastest().1;
            match r.rev_convex_us {
                Some(c) => format!("{:.2} / {:.2}", f / r.rev_us, f / c),
                None => format!("{:.2} / -", f / r.rev_us),
            }
        })
        .right()
        .markdown("parry3d max excess", |r| format!("{:.1e}", r.parry_excess))
        .right()
        .markdown("revdist max width", |r| format!("{:.1e}", r.max_width))
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

pub(super) fn markdown(
    rows: &[Row],
    convex: &[ConvexRow],
    (parry_poses, parry_budget): (usize, Option<f64>),
    coal: &str,
) -> String {
    let note = match rows.first().map(|r| &r.coal) {
        Some(Err(e)) => e.clone(),
        _ => "coal missing: run scripts/deps.sh".into(),
    };
    let mut s = String::from("# revdist beside its peers: FCL 0.7, coal 3, parry3d 0.31\n\n");
    s.push_str(&format!(
        "coal: {coal}. Single thread, one query at a time, each method *blocked* (alone over \
         the poses of a row; coal times its queries in its own process). Poses near contact \
         (gaps log-uniform in [{:e}, {:e}], seeded as in fcl_bench). Each cell: median query \
         us / build ms (tessellation included for the mesh peers) / memory (both shapes; one \
         when A = B). Mesh peers get the same certified mesh (balanced layout, two-sided \
         Hausdorff bound <= eps). parry3d's TriMesh-TriMesh distance is one-sided (best-first \
         over mesh 1's BVH against mesh 2's whole AABB, then one BVH query into mesh 2 per \
         leaf triangle) and runs on the first {parry_poses} poses of each row only{}. Ratio = \
         fastest peer's median / revdist's (> 1: revdist faster). OCCT: hook for the \
         OpenCASCADE cross-check's time per query (not measured here). Violations: a peer's \
         distance outside revdist's certified interval widened by h_a + h_b.\n\n",
        CLOSE_GAPS.0,
        CLOSE_GAPS.1,
        parry_budget.map_or(String::new(), |b| format!(
            ", stopping after the pose that exceeds {b} s of its queries (the count in brackets)"
        ))
    ));
    s.push_str(&mesh_md(&note).markdown_text(rows));
    s.push_str(&format!(
        "\nConvex solids of revolution (revdist eps {CONVEX_EPS:e}; peers: exact primitives, \
         GJK), median us per query. Violations: coal's distance outside revdist's interval \
         widened by coal's GJK error bound tol (1 + d + swept radii), tol = \
         {COAL_GJK_TOLERANCE:e} (its default convergence test), or parry3d's off by more than \
         {PARRY_GROSS_EXCESS:e}; parry3d states no tolerance, its largest excess over \
         revdist's interval is listed. revdist convex path: `QueryOptions {{ convex_path: true, \
         .. }}` (GJK on the biarc solids; coal is checked against its intervals too). Ratio: \
         fastest peer's median / revdist's (default / convex path; > 1: revdist faster).\n\n"
    ));
    s.push_str(&convex_md(&note).markdown_text(convex));
    s
}

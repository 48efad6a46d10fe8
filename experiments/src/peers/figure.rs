//! The figure `peers.svg`: median query time per mesh row, one bar per method.

use super::rows::Row;
use super::Res;
use crate::plot::{grouped_bars, BarSeries};

/// Median query time per row, one bar per method (log scale).
pub(super) fn figure(path: &std::path::Path, rows: &[Row]) -> Res<()> {
    let categories: Vec<String> = rows
        .iter()
        .map(|r| format!("{} {:.0e}", r.pair, r.eps))
        .collect();
    let series = |name: &str, f: &dyn Fn(&Row) -> f64| BarSeries {
        name: name.into(),
        values: rows.iter().map(f).collect(),
    };
    let s = vec![
        series("revdist", &|r| r.rev.us),
        series("FCL OBBRSS", &|r| r.fcl_obbrss.us),
        series("FCL RSS", &|r| r.fcl_rss.us),
        series("coal OBBRSS", &|r| {
            r.coal.as_ref().map_or(f64::NAN, |t| t.us)
        }),
        series("parry3d (one-sided)", &|r| r.parry.us),
    ];
    let width = (160 + 90 * rows.len()).max(800) as u32;
    grouped_bars(
        path,
        "Median query time near contact, us (blocked)",
        &categories,
        &s,
        "us per query",
        true,
        None,
        (width, 520),
    )?;
    Ok(())
}

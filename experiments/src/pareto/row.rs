//! One row of the table (one method at one eps on one pair), its raw form for `--shard`,
//! and look-ups over rows.

use super::method::Method;
use crate::shard::{Cells, Field, Record};

/// One row of the table: one method at one eps on one pair.
pub(super) struct Row {
    pub(super) method: Method,
    pub(super) pair: String,
    pub(super) eps: f64,
    pub(super) poses: usize,
    /// Certified error bound: revdist's interval width (max / median over the poses), FCL's
    /// h_a + h_b (the same for every pose).
    pub(super) width_max: f64,
    pub(super) width_median: f64,
    pub(super) median_us: f64,
    pub(super) p90_us: f64,
    pub(super) build_ms: f64,
    pub(super) bytes: usize,
    /// revdist only: node pairs popped per query (mean).
    pub(super) node_pairs: Option<f64>,
    /// revdist only: answers whose certified lower bound is 0 (separation not certified).
    pub(super) zero_lower: Option<usize>,
    /// FCL only: triangles of the distinct meshes, and the layout kept.
    pub(super) triangles: Option<usize>,
    pub(super) layout: Option<&'static str>,
    /// Cross-checks of this row's answers and how many failed.
    pub(super) checks: usize,
    pub(super) violations: usize,
}

crate::shard_record!(Row {
    method,
    pair,
    eps,
    poses,
    width_max,
    width_median,
    median_us,
    p90_us,
    build_ms,
    bytes,
    node_pairs,
    zero_lower,
    triangles,
    layout,
    checks,
    violations,
});

/// A raw row of `--shard`: a row of the table, and on its pair's first row the FCL levels the
/// triangle cap left out.
pub(super) struct RawRow {
    pub(super) row: Row,
    pub(super) skipped: Vec<String>,
}

impl Record for RawRow {
    fn columns() -> Vec<&'static str> {
        let mut c = Row::columns();
        c.push("skipped");
        c
    }
    fn cells(&self) -> Vec<String> {
        let mut c = self.row.cells();
        c.push(self.skipped.text());
        c
    }
    fn from_cells(line: &Cells) -> Result<Self, String> {
        Ok(RawRow {
            row: Row::from_cells(line)?,
            skipped: line.get("skipped")?,
        })
    }
}

/// The row of `method` on `pair` at `eps`.
pub(super) fn find<'a>(rows: &'a [Row], method: Method, pair: &str, eps: f64) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.method == method && r.pair == pair && r.eps == eps)
}

/// Cross-checks of revdist answers against FCL answers, and how many failed, over all rows.
pub(super) fn cross_checks(rows: &[Row]) -> (usize, usize) {
    rows.iter()
        .filter(|r| !r.method.is_fcl())
        .fold((0, 0), |(c, v), r| (c + r.checks, v + r.violations))
}

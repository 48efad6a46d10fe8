//! The campaign's summary: failures, reproducers (random profiles as TOML, batch lines in
//! `failures.jsonl`) and the report text (by pose kind, shape class and check, timing, the
//! slowest queries and the failures in full).

use super::cases::{Case, PoseKind};
use super::checked_query::CaseResult;
use super::pool::Shape;
use crate::oracle::Check;
use crate::random_profiles::to_toml;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

/// Campaign summary.
pub struct Summary {
    pub results: Vec<CaseResult>,
    pub shapes: Arc<Vec<Shape>>,
    pub wall: Duration,
    pub out: PathBuf,
}

impl Summary {
    /// Cases with a violation or a tree-build error.
    pub fn failures(&self) -> impl Iterator<Item = &CaseResult> {
        self.results.iter().filter(|r| r.failed())
    }

    /// Cases whose oracle lower estimate stopped on its cell budget before its goal.
    pub fn budget_stops(&self) -> usize {
        self.results
            .iter()
            .filter(|r| r.oracle.as_ref().is_some_and(|o| o.budget_hit))
            .count()
    }

    /// Cases of one pose kind.
    pub fn count_of(&self, kind: PoseKind) -> usize {
        self.results.iter().filter(|r| r.case.kind == kind).count()
    }

    /// Number of violations (all checks) plus build errors.
    pub fn violation_count(&self) -> usize {
        self.results
            .iter()
            .map(|r| {
                r.violations.len() + r.build_error.is_some() as usize + r.panic.is_some() as usize
            })
            .sum()
    }

    /// The reproducer spec of a shape: built-in name or file path in the output directory.
    fn shape_spec(&self, k: usize) -> String {
        let s = &self.shapes[k];
        if s.random {
            self.out
                .join(format!("{}.toml", s.name))
                .display()
                .to_string()
        } else {
            s.name.clone()
        }
    }

    /// Kind and orientation of a shape, e.g. `closed ccw`.
    fn shape_tag(&self, k: usize) -> String {
        let g = &self.shapes[k].index.geom;
        format!(
            "{} {}",
            match g.kind {
                revdist::profile::ProfileKind::Closed => "closed",
                revdist::profile::ProfileKind::OpenOnAxis => "open",
            },
            if g.orientation > 0.0 { "ccw" } else { "cw" }
        )
    }

    /// Failing cases per shape class (built-in, built-in freeform variant, M_t frame, random
    /// closed, random open):
    /// a case counts for every class among its two shapes.
    fn classes(&self) -> String {
        let mut counts: std::collections::BTreeMap<&str, (usize, usize)> = Default::default();
        for r in &self.results {
            let mut seen = Vec::new();
            for k in [r.case.a, r.case.b] {
                let sh = &self.shapes[k];
                let c = if !sh.random {
                    if sh.name.starts_with("morph@") {
                        "M_t frames"
                    } else if revdist::models::FREEFORM_NAMES.contains(&sh.name.as_str()) {
                        "built-in freeform"
                    } else {
                        "built-in"
                    }
                } else if sh.index.geom.kind == revdist::profile::ProfileKind::Closed {
                    "random closed"
                } else {
                    "random open"
                };
                if !seen.contains(&c) {
                    seen.push(c);
                    let e = counts.entry(c).or_default();
                    e.0 += 1;
                    e.1 += r.failed() as usize;
                }
            }
        }
        counts
            .iter()
            .map(|(c, (n, f))| format!(" {c} {n}/{f};"))
            .collect()
    }

    /// Batch JSON line for `revdist distance --batch`.
    pub fn batch_line(&self, c: &Case) -> String {
        c.batch_line(&self.shape_spec(c.a), &self.shape_spec(c.b))
    }

    /// Command line for one case.
    pub fn command_line(&self, c: &Case) -> String {
        let mut extra = String::new();
        if let Some(t) = c.tolerance {
            write!(extra, " --tolerance {t:?}").unwrap();
        }
        if c.refine {
            extra.push_str(" --refine");
        }
        format!(
            "revdist distance {} {} --eps {:?}{extra} --pose-b '{}' --json",
            self.shape_spec(c.a),
            self.shape_spec(c.b),
            c.eps,
            c.pose.json()
        )
    }

    /// Writes every random profile of the pool (so that any case line of the report can be
    /// replayed) and `failures.jsonl` (one batch line per failing case) to the output
    /// directory.
    pub fn write_reproducers(&self) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.out)?;
        for sh in self.shapes.iter().filter(|sh| sh.random) {
            std::fs::write(
                self.out.join(format!("{}.toml", sh.name)),
                to_toml(&sh.profile),
            )?;
        }
        let mut lines = String::new();
        for r in self.failures() {
            lines.push_str(&self.batch_line(&r.case));
            lines.push('\n');
        }
        std::fs::write(self.out.join("failures.jsonl"), lines)
    }

    /// Writes `summary.json` to the output directory: the counts a merge of shards adds up
    /// ([`super::merge`]), with the settings that must agree between shards and one batch
    /// line per failing case.
    pub fn write_summary(
        &self,
        seed: u64,
        count: usize,
        shard: Option<(usize, usize)>,
    ) -> std::io::Result<()> {
        std::fs::create_dir_all(&self.out)?;
        let by_check: serde_json::Map<String, serde_json::Value> = Check::ALL
            .iter()
            .map(|&ch| {
                let n = self
                    .results
                    .iter()
                    .flat_map(|r| &r.violations)
                    .filter(|v| v.check == ch)
                    .count();
                (ch.name().to_string(), n.into())
            })
            .collect();
        let (index, of) = shard.unwrap_or((0, 1));
        let summary = serde_json::json!({
            "seed": seed,
            "count": count,
            "shard": [index, of],
            "cases": self.results.len(),
            "failing": self.failures().count(),
            "violations": self.violation_count(),
            "by_check": by_check,
            "failures": self.failures().map(|r| self.batch_line(&r.case)).collect::<Vec<_>>(),
            "wall_s": self.wall.as_secs_f64(),
        });
        std::fs::write(
            self.out.join("summary.json"),
            serde_json::to_string_pretty(&summary)? + "\n",
        )
    }

    /// Human-readable report.
    pub fn report(&self, print_failures: usize) -> String {
        let mut s = String::new();
        let n = self.results.len();
        let fails: Vec<&CaseResult> = self.failures().collect();
        writeln!(
            s,
            "queries: {n} cases, {} failing ({} violations), wall {:.1} s",
            fails.len(),
            self.violation_count(),
            self.wall.as_secs_f64()
        )
        .unwrap();
        // Per kind.
        let mut kinds: HashMap<PoseKind, (usize, usize)> = HashMap::new();
        for r in &self.results {
            let e = kinds.entry(r.case.kind).or_default();
            e.0 += 1;
            e.1 += r.failed() as usize;
        }
        let mut kv: Vec<_> = kinds.into_iter().collect();
        kv.sort();
        write!(s, "by pose kind (cases/failing):").unwrap();
        for (k, (c, f)) in kv {
            write!(s, " {} {c}/{f};", k.name()).unwrap();
        }
        writeln!(s).unwrap();
        writeln!(s, "by shape class (cases/failing):{}", self.classes()).unwrap();
        // Per check: count and worst.
        writeln!(s, "by check (cases, worst excess, worst case):").unwrap();
        for ch in Check::ALL {
            let mut count = 0;
            let mut worst: Option<(f64, &CaseResult, &str)> = None;
            for r in &self.results {
                for v in r.violations.iter().filter(|v| v.check == ch) {
                    count += 1;
                    if worst.is_none_or_less(v.excess) {
                        worst = Some((v.excess, r, &v.detail));
                    }
                }
            }
            match worst {
                Some((e, r, detail)) => writeln!(
                    s,
                    "  {:<24} {count:>6}  worst {e:.3e}  case {} ({}): {detail}",
                    ch.name(),
                    case_label(&r.case),
                    r.case.kind.name()
                )
                .unwrap(),
                None => writeln!(s, "  {:<24} {count:>6}", ch.name()).unwrap(),
            }
        }
        let builds = self
            .results
            .iter()
            .filter(|r| r.build_error.is_some())
            .count();
        writeln!(s, "  {:<24} {builds:>6}", "tree build errors").unwrap();
        let panics: Vec<&CaseResult> = self.results.iter().filter(|r| r.panic.is_some()).collect();
        match panics.first() {
            Some(r) => writeln!(
                s,
                "  {:<24} {:>6}  first: case {}: {}",
                "panics",
                panics.len(),
                case_label(&r.case),
                r.panic.as_deref().unwrap_or("")
            )
            .unwrap(),
            None => writeln!(s, "  {:<24} {:>6}", "panics", 0).unwrap(),
        }
        // Timing.
        let mut qt: Vec<f64> = self
            .results
            .iter()
            .filter(|r| r.answer.is_some())
            .map(|r| r.query_time.as_secs_f64() * 1e3)
            .collect();
        let mut ot: Vec<f64> = self
            .results
            .iter()
            .filter(|r| r.oracle.is_some())
            .map(|r| r.oracle_time.as_secs_f64() * 1e3)
            .collect();
        let stats = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            if v.is_empty() {
                (0.0, 0.0, 0.0)
            } else {
                (v[v.len() / 2], v[(v.len() * 95) / 100], v[v.len() - 1])
            }
        };
        let mut pt: Vec<f64> = self
            .results
            .iter()
            .map(|r| r.place_time.as_secs_f64() * 1e3)
            .collect();
        let (qm, q95, qx) = stats(&mut qt);
        let (om, o95, ox) = stats(&mut ot);
        let (pm, p95, px) = stats(&mut pt);
        writeln!(
            s,
            "timing (ms): query median {qm:.3} p95 {q95:.3} max {qx:.1}; oracle median {om:.1} p95 {o95:.1} max {ox:.1}; pose placement median {pm:.1} p95 {p95:.1} max {px:.1}"
        )
        .unwrap();
        let sum = |v: &[f64]| v.iter().sum::<f64>() / 1e3;
        writeln!(
            s,
            "cpu time (s): queries {:.1}, oracle {:.1}, placement {:.1}",
            sum(&qt),
            sum(&ot),
            sum(&pt)
        )
        .unwrap();
        let hints = self
            .results
            .iter()
            .filter(|r| r.hint_improved.is_some())
            .count();
        let budget = self.budget_stops();
        let share = 100.0 * budget as f64 / self.results.len().max(1) as f64;
        writeln!(
            s,
            "oracle: {hints} cases tightened by the query's witnesses, {budget} lower estimates stopped on the cell budget ({share:.2}%)"
        )
        .unwrap();
        let mut stops: std::collections::BTreeMap<&str, usize> = Default::default();
        for r in &self.results {
            if r.oracle.as_ref().is_some_and(|o| o.budget_hit) {
                *stops.entry(r.case.kind.name()).or_default() += 1;
            }
        }
        if !stops.is_empty() {
            let list: Vec<String> = stops.iter().map(|(k, n)| format!("{k} {n}")).collect();
            writeln!(s, "budget stops by pose kind: {}", list.join("; ")).unwrap();
        }
        let mut slow: Vec<&CaseResult> =
            self.results.iter().filter(|r| r.answer.is_some()).collect();
        slow.sort_by_key(|r| std::cmp::Reverse(r.query_time));
        for r in slow.iter().take(3) {
            writeln!(
                s,
                "slow query: {:.0} ms, case {} [{}] {} vs {}: {}",
                r.query_time.as_secs_f64() * 1e3,
                case_label(&r.case),
                r.case.kind.name(),
                self.shapes[r.case.a].name,
                self.shapes[r.case.b].name,
                self.batch_line(&r.case)
            )
            .unwrap();
        }
        if !fails.is_empty() {
            writeln!(
                s,
                "failures (first {}; all in {}/failures.jsonl):",
                print_failures.min(fails.len()),
                self.out.display()
            )
            .unwrap();
        }
        for r in fails.iter().take(print_failures) {
            writeln!(
                s,
                "- case {} [{}; {}] {} ({}) vs {} ({}) eps {:e}{}{}",
                case_label(&r.case),
                r.case.kind.name(),
                r.case.note,
                self.shapes[r.case.a].name,
                self.shape_tag(r.case.a),
                self.shapes[r.case.b].name,
                self.shape_tag(r.case.b),
                r.case.eps,
                match r.case.tolerance {
                    Some(t) => format!(" tolerance {t:e}"),
                    None => String::new(),
                },
                if r.case.refine { " refine" } else { "" }
            )
            .unwrap();
            if let Some(e) = &r.build_error {
                writeln!(s, "    build error: {e}").unwrap();
            }
            if let Some(e) = &r.panic {
                writeln!(s, "    PANIC: {e}").unwrap();
            }
            if let (Some(d), Some(o)) = (&r.answer, &r.oracle) {
                writeln!(
                    s,
                    "    query: value {:.9e} [{:.9e}, {:.9e}] overlap {}; oracle: [{:.9e}, {:.9e}] overlap {} min_signed {:.3e}",
                    d.value, d.lower, d.upper, d.overlap, o.lower, o.upper, o.overlap(), o.min_signed
                )
                .unwrap();
            }
            for v in &r.violations {
                writeln!(s, "    {}: {}", v.check.name(), v.detail).unwrap();
            }
            writeln!(s, "    {}", self.command_line(&r.case)).unwrap();
            writeln!(s, "    {}", self.batch_line(&r.case)).unwrap();
        }
        s
    }
}

fn case_label(c: &Case) -> String {
    if c.kind == PoseKind::Regression {
        format!("R{}", usize::MAX - c.id)
    } else {
        c.id.to_string()
    }
}

trait NoneOrLess {
    fn is_none_or_less(&self, e: f64) -> bool;
}

impl NoneOrLess for Option<(f64, &CaseResult, &str)> {
    fn is_none_or_less(&self, e: f64) -> bool {
        match self {
            None => true,
            Some((w, _, _)) => e > *w,
        }
    }
}

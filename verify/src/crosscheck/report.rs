//! Per-group summaries of the case records ([`super::record`]) and the Markdown/CSV report
//! with reproducer lines for `revdist distance --batch`.

use super::criterion::Verdict;
use super::options::Options;
use super::poses::PoseKind;
use super::record::{CaseRecord, Check};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

/// Reproducer lines listed per verdict class in the Markdown report.
const MAX_LISTED: usize = 30;

/// Counts and extremes of a group of records.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    pub cases: usize,
    pub passed: usize,
    pub explained: usize,
    pub failed: usize,
    /// Largest separation of the intervals (> 0 only for explained or failed cases).
    pub worst_separation: f64,
    /// Index into [`Report::records`] of the case with the largest separation.
    pub worst_separated: Option<usize>,
    /// Largest share of the tolerance used by a passed case.
    pub max_usage: f64,
    /// Index of the passed case with the largest usage.
    pub max_usage_case: Option<usize>,
}

impl Tally {
    fn add(&mut self, i: usize, r: &CaseRecord) {
        self.cases += 1;
        match r.judgement.verdict {
            Verdict::Passed => {
                self.passed += 1;
                if self.max_usage_case.is_none() || r.judgement.usage > self.max_usage {
                    self.max_usage = r.judgement.usage;
                    self.max_usage_case = Some(i);
                }
            }
            Verdict::Explained => self.explained += 1,
            Verdict::Failed => self.failed += 1,
        }
        if self.worst_separated.is_none() || r.judgement.separation > self.worst_separation {
            self.worst_separation = r.judgement.separation;
            self.worst_separated = Some(i);
        }
    }

    /// The worst case: the most separated one when some intervals are disjoint, else the
    /// passed case that used the largest share of its tolerance.
    pub fn worst(&self) -> Option<usize> {
        if self.worst_separation > 0.0 {
            self.worst_separated
        } else {
            self.max_usage_case.or(self.worst_separated)
        }
    }
}

/// Result of a run.
#[derive(Debug, Clone)]
pub struct Report {
    pub records: Vec<CaseRecord>,
    pub options: Options,
    pub threads: usize,
    pub prepare_time: Duration,
    pub wall: Duration,
}

type GroupKey = (Check, String, String, u64);

impl Report {
    /// The report of `records` (in any order: they are sorted by check, pair, eps and pose
    /// number), run with `options` on `threads` threads; `(prepare, wall)` times.
    pub fn new(
        mut records: Vec<CaseRecord>,
        options: Options,
        threads: usize,
        (prepare_time, wall): (Duration, Duration),
    ) -> Report {
        records.sort_by(|x, y| {
            (x.check, &x.a, &x.b, x.eps.to_bits(), x.index).cmp(&(
                y.check,
                &y.a,
                &y.b,
                y.eps.to_bits(),
                y.index,
            ))
        });
        Report {
            records,
            options,
            threads,
            prepare_time,
            wall,
        }
    }

    /// Tallies per (check, pair, eps), in a stable order.
    pub fn groups(&self) -> BTreeMap<GroupKey, Tally> {
        let mut g: BTreeMap<GroupKey, Tally> = BTreeMap::new();
        for (i, r) in self.records.iter().enumerate() {
            g.entry((r.check, r.a.clone(), r.b.clone(), r.eps.to_bits()))
                .or_default()
                .add(i, r);
        }
        g
    }

    /// Tally of all records of one check (all checks for `None`).
    pub fn total(&self, check: Option<Check>) -> Tally {
        let mut t = Tally::default();
        for (i, r) in self.records.iter().enumerate() {
            if check.is_none_or(|c| c == r.check) {
                t.add(i, r);
            }
        }
        t
    }

    /// Tally per check and pose kind.
    pub fn by_kind(&self) -> BTreeMap<(Check, PoseKind), Tally> {
        let mut g: BTreeMap<(Check, PoseKind), Tally> = BTreeMap::new();
        for (i, r) in self.records.iter().enumerate() {
            g.entry((r.check, r.kind)).or_default().add(i, r);
        }
        g
    }

    pub fn failures(&self) -> usize {
        self.total(None).failed
    }

    /// The summary CSV: one row per (check, pair, eps).
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "check,a,b,eps,cases,passed,explained,failed,worst_separation,max_usage_passed,worst_reproducer\n",
        );
        for ((check, a, b, eps), t) in self.groups() {
            let rep = t
                .worst()
                .map(|i| self.records[i].reproducer().replace('"', "\"\""))
                .unwrap_or_default();
            let _ = writeln!(
                s,
                "{},{a},{b},{:e},{},{},{},{},{:.6e},{:.4},\"{rep}\"",
                check.name(),
                f64::from_bits(eps),
                t.cases,
                t.passed,
                t.explained,
                t.failed,
                t.worst_separation,
                t.max_usage
            );
        }
        s
    }

    /// The Markdown report.
    pub fn markdown(&self) -> String {
        let o = &self.options;
        let mut s =
            String::from("# revdist cross-check against FCL, CGAL, libccd and OpenCASCADE\n\n");
        let _ = writeln!(
            s,
            "Poses per mesh pair and eps: {}; per convex pair and eps: {}; eps: {:?}; OCCT \
             sweep: {} poses per pair, revdist at eps {:?}; seed {}; {} threads; shapes \
             prepared in {:.1} s; wall time {:.1} s.\n",
            o.poses,
            o.convex_poses,
            o.eps,
            o.occt_poses,
            o.occt_eps,
            o.seed,
            self.threads,
            self.prepare_time.as_secs_f64(),
            self.wall.as_secs_f64()
        );
        s.push_str(
            "Criterion (verify/src/crosscheck/mod.rs): revdist's certified interval for the \
             solids must meet the baseline's `[d - h_a - h_b, d + h_a + h_b]` (clipped at 0, \
             plus a rounding slack of 1e-12 of the scale), `h` the meshes' certified Hausdorff \
             bounds. *Explained*: revdist 0 below the baseline's interval with a certified \
             point of one surface inside the other solid (nesting). `separation` > 0 means the \
             intervals are disjoint by that much; `usage` = |value - d| / (h_a + h_b + width). \
             OCCT (`occt-brep`, verify/src/crosscheck/occt.rs): the same test with OCCT's \
             tolerance 1e-7 in place of h_a + h_b; a failed case's note says which side the \
             evidence blames, and `occt-missed-minimum` (explained) means revdist's witnesses, \
             on the true surfaces by the oracle's evaluation, are closer than OCCT's minimum.\n\n",
        );
        s.push_str("## Totals\n\n| check | cases | passed | explained | failed | worst separation | max usage (passed) |\n| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for c in [
            Check::Fcl,
            Check::Cgal,
            Check::Gjk,
            Check::Penetration,
            Check::Occt,
        ] {
            let t = self.total(Some(c));
            if t.cases > 0 {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {:.3e} | {:.3} |",
                    c.name(),
                    t.cases,
                    t.passed,
                    t.explained,
                    t.failed,
                    t.worst_separation,
                    t.max_usage
                );
            }
        }
        s.push_str("\n## By pose kind\n\n| check | pose | cases | passed | explained | failed | worst separation |\n| --- | --- | ---: | ---: | ---: | ---: | ---: |\n");
        for ((c, k), t) in self.by_kind() {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {:.3e} |",
                c.name(),
                k.name(),
                t.cases,
                t.passed,
                t.explained,
                t.failed,
                t.worst_separation
            );
        }
        s.push_str("\n## Per pair and eps\n\n| check | A | B | eps | cases | passed | explained | failed | worst separation | max usage |\n| --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
        for ((c, a, b, eps), t) in self.groups() {
            let _ = writeln!(
                s,
                "| {} | {a} | {b} | {:.0e} | {} | {} | {} | {} | {:.3e} | {:.3} |",
                c.name(),
                f64::from_bits(eps),
                t.cases,
                t.passed,
                t.explained,
                t.failed,
                t.worst_separation,
                t.max_usage
            );
        }
        s.push_str(&super::occt_times::markdown(&self.records));
        let all = self.total(None);
        s.push_str("\n## Reproducers\n\nEach line runs with `revdist distance --batch FILE`.\n\n");
        if let Some(i) = all.worst() {
            let r = &self.records[i];
            let _ = writeln!(
                s,
                "Worst case overall ({}, {}, separation {:.3e}, usage {:.3}, revdist [{:.9e}, {:.9e}], baseline {:.9e}, h_a + h_b {:.3e}):\n\n```\n{}\n```\n",
                r.check.name(),
                r.judgement.verdict.name(),
                r.judgement.separation,
                r.judgement.usage,
                r.lower,
                r.upper,
                r.baseline,
                r.mesh_bounds,
                r.reproducer()
            );
        }
        for v in [Verdict::Failed, Verdict::Explained] {
            let list: Vec<&CaseRecord> = self
                .records
                .iter()
                .filter(|r| r.judgement.verdict == v)
                .collect();
            let _ = writeln!(s, "### {} ({})\n", v.name(), list.len());
            if list.is_empty() {
                continue;
            }
            s.push_str("```\n");
            for r in list.iter().take(MAX_LISTED) {
                let _ = writeln!(
                    s,
                    "{}  # {} {} sep {:.3e} revdist [{:.6e}, {:.6e}] overlap {} baseline {:.6e} {}",
                    r.reproducer(),
                    r.check.name(),
                    r.kind.name(),
                    r.judgement.separation,
                    r.lower,
                    r.upper,
                    r.overlap,
                    r.baseline,
                    r.note
                );
            }
            if list.len() > MAX_LISTED {
                let _ = writeln!(s, "# ... {} more", list.len() - MAX_LISTED);
            }
            s.push_str("```\n\n");
        }
        s
    }

    /// Writes `crosscheck.md`, `crosscheck.csv` and `failures.jsonl` (reproducers of failed
    /// cases) into `dir`, creating it.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        std::fs::create_dir_all(dir)?;
        let o = &self.options;
        let prov = crate::provenance::Provenance::collect(
            "verify crosscheck",
            &[
                ("poses", o.poses.to_string()),
                ("convex_poses", o.convex_poses.to_string()),
                ("occt_poses", o.occt_poses.to_string()),
                ("occt_eps", format!("{:?}", o.occt_eps)),
                ("eps", format!("{:?}", o.eps)),
                ("seed", o.seed.to_string()),
                ("threads", self.threads.to_string()),
            ],
        );
        std::fs::write(
            dir.join("crosscheck.md"),
            self.markdown() + &prov.markdown_footer(),
        )?;
        std::fs::write(
            dir.join("crosscheck.csv"),
            prov.csv_preamble() + &self.csv(),
        )?;
        let failed: String = self
            .records
            .iter()
            .filter(|r| r.judgement.verdict == Verdict::Failed)
            .map(|r| r.reproducer() + "\n")
            .collect();
        let occt = super::occt_times::csv(&self.records);
        if !occt.is_empty() {
            std::fs::write(dir.join("occt_times.csv"), prov.csv_preamble() + &occt)?;
        }
        std::fs::write(dir.join("failures.jsonl"), failed)
    }

    /// A short text summary for the terminal.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        for c in [
            Check::Fcl,
            Check::Cgal,
            Check::Gjk,
            Check::Penetration,
            Check::Occt,
        ] {
            let t = self.total(Some(c));
            if t.cases > 0 {
                let _ = writeln!(
                    s,
                    "{:<11} cases {:>6}  passed {:>6}  explained {:>5}  failed {:>4}  worst separation {:.3e}  max usage {:.3}",
                    c.name(),
                    t.cases,
                    t.passed,
                    t.explained,
                    t.failed,
                    t.worst_separation,
                    t.max_usage
                );
            }
        }
        let _ = writeln!(s, "wall time {:.1} s", self.wall.as_secs_f64());
        s
    }
}

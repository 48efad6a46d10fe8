//! Pass/fail tallies of a `verify circles` run and their printed summary.

use super::cases::Case;
use super::check::Outcome;
use super::{CLUSTER_GAP, REL_TOL};
use revdist::circle::Circle3;

/// Pass/fail tallies of a run.
#[derive(Debug, Default, Clone)]
pub struct Summary {
    pub per_family: Vec<(&'static str, usize, usize)>,
    pub worst: Option<(f64, String, f64, f64)>,
    pub count_checked: usize,
    pub count_mismatch: usize,
    pub count_mismatch_example: Option<String>,
    pub companion_worst: f64,
    pub companion_over_tol: usize,
    /// Case label of the worst companion-matrix error.
    pub companion_worst_label: Option<String>,
    /// Companion-matrix cases above tolerance, per family.
    pub companion_over_tol_per_family: Vec<(&'static str, usize)>,
    pub failures: Vec<String>,
    pub count_mismatch_random: usize,
    /// Mismatches whose exact roots include a pair closer than [`CLUSTER_GAP`].
    pub count_mismatch_clustered: usize,
    /// Mismatches in the random family among well-separated roots (genuine misses).
    pub count_mismatch_random_resolvable: usize,
}

impl Summary {
    pub fn total(&self) -> (usize, usize) {
        self.per_family
            .iter()
            .fold((0, 0), |(p, f), &(_, pp, ff)| (p + pp, f + ff))
    }

    pub(super) fn record(&mut self, case: &Case, o: &Outcome) {
        let ok = o.rel_err <= REL_TOL;
        let entry = match self.per_family.iter_mut().find(|e| e.0 == case.family) {
            Some(e) => e,
            None => {
                self.per_family.push((case.family, 0, 0));
                self.per_family.last_mut().unwrap()
            }
        };
        if ok {
            entry.1 += 1;
        } else {
            entry.2 += 1;
            if self.failures.len() < 40 {
                self.failures.push(format!(
                    "{}: rel err {:.3e} (exact {:.17e}, float {:.17e})",
                    case.label, o.rel_err, o.exact, o.float
                ));
                if std::env::var_os("VERIFY_SOURCE").is_some() {
                    eprintln!(
                        "// {}: exact {:e}\n({}, {}, {:e}),",
                        case.label,
                        o.exact,
                        circle_source(&o.inputs.0),
                        circle_source(&o.inputs.1),
                        o.exact
                    );
                }
            }
        }
        if self
            .worst
            .as_ref()
            .is_none_or(|w| o.rel_err > w.0 || o.rel_err.is_nan())
        {
            self.worst = Some((o.rel_err, case.label.clone(), o.exact, o.float));
        }
        if let Some(ce) = o.count_exact {
            self.count_checked += 1;
            if ce != o.count_float {
                self.count_mismatch += 1;
                let clustered = o.min_root_gap < CLUSTER_GAP;
                if clustered {
                    self.count_mismatch_clustered += 1;
                }
                if case.family == "random" {
                    self.count_mismatch_random += 1;
                    if !clustered {
                        self.count_mismatch_random_resolvable += 1;
                    }
                }
                if std::env::var_os("VERIFY_COUNTS").is_some() {
                    eprintln!(
                        "// count {}: exact {ce}, float {}, distance {:e}, root gap {:e}\n({}, {}),",
                        case.label,
                        o.count_float,
                        o.exact,
                        o.min_root_gap,
                        circle_source(&o.inputs.0),
                        circle_source(&o.inputs.1)
                    );
                }
                if self.count_mismatch_example.is_none() {
                    self.count_mismatch_example = Some(format!(
                        "{} (exact {ce}, float {})",
                        case.label, o.count_float
                    ));
                }
            }
        }
        if let Some(c) = o.companion_rel_err {
            if c > self.companion_worst {
                self.companion_worst = c;
                self.companion_worst_label = Some(case.label.clone());
            }
            if c > REL_TOL {
                self.companion_over_tol += 1;
                match self
                    .companion_over_tol_per_family
                    .iter_mut()
                    .find(|e| e.0 == case.family)
                {
                    Some(e) => e.1 += 1,
                    None => self.companion_over_tol_per_family.push((case.family, 1)),
                }
            }
        }
    }
}

impl std::fmt::Display for Summary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (fam, p, fl) in &self.per_family {
            writeln!(f, "{fam:>14}: {p} pass, {fl} fail")?;
        }
        let (p, fl) = self.total();
        writeln!(
            f,
            "{:>14}: {p} pass, {fl} fail (relative tolerance {REL_TOL:e})",
            "total"
        )?;
        if let Some((e, label, exact, float)) = &self.worst {
            writeln!(
                f,
                "worst: rel err {e:.3e} in {label} (exact {exact:.17e}, float {float:.17e})"
            )?;
        }
        for fail in &self.failures {
            writeln!(f, "FAIL {fail}")?;
        }
        writeln!(
            f,
            "binormal counts (distinct theta on B vs exact Sturm count): {} compared, {} mismatches ({} with exact roots closer than {CLUSTER_GAP:e} rad; {} in the random family, {} of them resolvable){}",
            self.count_checked,
            self.count_mismatch,
            self.count_mismatch_clustered,
            self.count_mismatch_random,
            self.count_mismatch_random_resolvable,
            self.count_mismatch_example
                .as_ref()
                .map(|e| format!(", first: {e}"))
                .unwrap_or_default()
        )?;
        write!(
            f,
            "companion-matrix reference (faer, informational): worst rel err {:.3e}{}, {} cases above tolerance{}",
            self.companion_worst,
            self.companion_worst_label
                .as_ref()
                .map(|l| format!(" in {l}"))
                .unwrap_or_default(),
            self.companion_over_tol,
            self.companion_over_tol_per_family
                .iter()
                .map(|(fam, n)| format!(" {fam} {n}"))
                .collect::<Vec<_>>()
                .join(",")
        )
    }
}

/// Rust source of a circle, exact to the last bit (`f64::from_bits`).
fn circle_source(c: &Circle3) -> String {
    let v = |x: [f64; 3]| {
        format!(
            "[{}]",
            x.map(|e| format!("f64::from_bits({:#x})", e.to_bits()))
                .join(", ")
        )
    };
    format!(
        "circle_u({}, {}, {}, f64::from_bits({:#x}))",
        v(c.center.coords.into()),
        v(c.normal.into_inner().into()),
        v(c.u_axis.into_inner().into()),
        c.radius.to_bits()
    )
}

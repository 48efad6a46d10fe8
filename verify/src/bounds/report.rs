//! Tallies of the bound checks and the report printed by `verify bounds`.

use super::Bound;
use std::fmt::Write;

/// Violations kept in full per bound.
const EXAMPLES: usize = 5;

/// What one bound's checks found.
#[derive(Debug, Clone, Default)]
pub struct Tally {
    /// Configurations in which the bound was evaluated at least once.
    pub configs: usize,
    /// Evaluations (a configuration has one per piece pair for the piece bounds).
    pub checks: usize,
    /// Evaluations that claimed something (a finite bound above `-inf`).
    pub finite: usize,
    /// Evaluations with a positive bound (a separation claimed).
    pub positive: usize,
    /// Bounds above the realised distance but within the bound's declared allowance.
    pub used_allowance: usize,
    /// Bounds above the realised distance plus the allowance: wrong.
    pub violations: usize,
    /// Largest `(bound - reference) / scale` met (negative: every bound below).
    pub worst: f64,
    /// Reproducers of the first violations.
    pub examples: Vec<String>,
}

impl Tally {
    /// One evaluation: `bound` against the MPFR `reference` (a realised distance) with the
    /// bound's own `allowance`, at configuration `scale`.
    pub fn record(
        &mut self,
        bound: f64,
        reference: f64,
        allowance: f64,
        scale: f64,
        describe: impl FnOnce() -> String,
    ) {
        self.checks += 1;
        if bound.is_nan() {
            self.violations += 1;
            self.push(format!("NaN bound; {}", describe()));
            return;
        }
        if bound == f64::NEG_INFINITY {
            return;
        }
        self.finite += 1;
        if bound > 0.0 {
            self.positive += 1;
        }
        let excess = (bound - reference) / scale;
        if self.finite == 1 || excess > self.worst {
            self.worst = excess;
        }
        if bound > reference + allowance {
            self.violations += 1;
            self.push(format!(
                "bound {bound:e} > realised {reference:e} + allowance {allowance:e} (excess {:e}); {}",
                bound - reference - allowance,
                describe()
            ));
        } else if bound > reference {
            self.used_allowance += 1;
        }
    }

    fn push(&mut self, s: String) {
        if self.examples.len() < EXAMPLES {
            self.examples.push(s);
        }
    }

    pub fn merge(&mut self, o: &Tally) {
        if o.finite > 0 && (self.finite == 0 || o.worst > self.worst) {
            self.worst = o.worst;
        }
        self.configs += o.configs;
        self.checks += o.checks;
        self.finite += o.finite;
        self.positive += o.positive;
        self.used_allowance += o.used_allowance;
        self.violations += o.violations;
        for e in &o.examples {
            self.push(e.clone());
        }
    }
}

/// How close the search's realised pairs come to the minimum: the MPFR reference against
/// the exact kernel's value on the piece pairs the kernel solved without sampling.
#[derive(Debug, Clone, Default)]
pub struct Power {
    pub compared: usize,
    /// `(reference - kernel) / scale` within 1e-12, 1e-9, 1e-6.
    pub within: [usize; 3],
    pub worst: f64,
    /// Constructed contacts (gap >= 0) and how many references met the gap to 1e-12 of
    /// the scale.
    pub contacts: usize,
    pub contacts_met: usize,
}

impl Power {
    pub fn kernel(&mut self, reference: f64, kernel: f64, scale: f64) {
        let r = (reference - kernel) / scale;
        self.compared += 1;
        for (k, lim) in [1e-12, 1e-9, 1e-6].iter().enumerate() {
            if r <= *lim {
                self.within[k] += 1;
            }
        }
        self.worst = self.worst.max(r);
    }

    pub fn merge(&mut self, o: &Power) {
        self.compared += o.compared;
        for k in 0..3 {
            self.within[k] += o.within[k];
        }
        self.worst = self.worst.max(o.worst);
        self.contacts += o.contacts;
        self.contacts_met += o.contacts_met;
    }
}

/// The whole campaign.
#[derive(Debug, Clone, Default)]
pub struct Report {
    pub seed: u64,
    pub tallies: Vec<(Bound, Tally)>,
    pub power: Power,
    pub seconds: f64,
}

impl Report {
    pub fn violations(&self) -> usize {
        self.tallies.iter().map(|(_, t)| t.violations).sum()
    }

    pub fn tally(&self, b: Bound) -> Option<&Tally> {
        self.tallies.iter().find(|(x, _)| *x == b).map(|(_, t)| t)
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut s = String::new();
        writeln!(
            s,
            "verify bounds, seed {}, {:.1} s",
            self.seed, self.seconds
        )
        .ok();
        writeln!(
            s,
            "| bound | configs | evaluations | finite | positive | within allowance | violations | worst (bound - realised) / scale |"
        )
        .ok();
        writeln!(s, "| --- | --- | --- | --- | --- | --- | --- | --- |").ok();
        for (b, t) in &self.tallies {
            writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {:.2e} |",
                b.name(),
                t.configs,
                t.checks,
                t.finite,
                t.positive,
                t.used_allowance,
                t.violations,
                t.worst
            )
            .ok();
        }
        let p = &self.power;
        writeln!(
            s,
            "search power: {} piece pairs solved by the kernel without sampling; reference within 1e-12 / 1e-9 / 1e-6 of the scale above the kernel's value in {} / {} / {}; largest gap {:.2e} of the scale",
            p.compared, p.within[0], p.within[1], p.within[2], p.worst
        )
        .ok();
        writeln!(
            s,
            "constructed contacts (gap >= 0): {}, reference within 1e-12 of the scale of the gap in {}",
            p.contacts, p.contacts_met
        )
        .ok();
        for (b, t) in &self.tallies {
            for e in &t.examples {
                writeln!(s, "VIOLATION {}: {e}", b.name()).ok();
            }
        }
        f.write_str(&s)
    }
}

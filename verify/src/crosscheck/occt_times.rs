//! OCCT's time per query in the cross-check report: the median per pair and per family
//! (exact, freeform, M_t frames), beside revdist's median at each eps of the sweep.

use super::occt_pairs::family;
use super::record::{CaseRecord, Check};
use std::collections::BTreeMap;
use std::fmt::Write as _;

fn median_ms(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Times of one group: OCCT's (one per pose) and revdist's per eps.
#[derive(Default)]
struct Times {
    occt: Vec<f64>,
    revdist: BTreeMap<u64, Vec<f64>>,
}

impl Times {
    fn add(&mut self, r: &CaseRecord, first_eps: u64) {
        if r.eps.to_bits() == first_eps {
            if let Some(t) = r.baseline_time {
                self.occt.push(t.as_secs_f64() * 1e3);
            }
        }
        self.revdist
            .entry(r.eps.to_bits())
            .or_default()
            .push(r.query_time.as_secs_f64() * 1e3);
    }
}

/// Times grouped by pair and by family, and the sweep's eps (as bits, descending).
type Grouped = (
    BTreeMap<(String, String), Times>,
    BTreeMap<&'static str, Times>,
    Vec<u64>,
);

/// The OCCT records' times, grouped; `None` without any.
fn collect(records: &[CaseRecord]) -> Option<Grouped> {
    let occt: Vec<&CaseRecord> = records.iter().filter(|r| r.check == Check::Occt).collect();
    let first = occt.first()?.eps.to_bits();
    let mut eps: Vec<u64> = occt.iter().map(|r| r.eps.to_bits()).collect();
    eps.sort_by(|x, y| f64::from_bits(*y).total_cmp(&f64::from_bits(*x)));
    eps.dedup();
    let mut pairs: BTreeMap<(String, String), Times> = BTreeMap::new();
    let mut families: BTreeMap<&'static str, Times> = BTreeMap::new();
    for r in occt {
        pairs
            .entry((r.a.clone(), r.b.clone()))
            .or_default()
            .add(r, first);
        families
            .entry(family(&r.a, &r.b))
            .or_default()
            .add(r, first);
    }
    Some((pairs, families, eps))
}

/// The Markdown section (empty without OCCT records).
pub fn markdown(records: &[CaseRecord]) -> String {
    let Some((pairs, families, eps)) = collect(records) else {
        return String::new();
    };
    let mut s = String::from(
        "\n## OCCT time per query\n\nMedian CPU time of the calling thread \
         (`CLOCK_THREAD_CPUTIME_ID`, so other processes on the cores do not inflate it) of one \
         `BRepExtrema_DistShapeShape` query, and revdist's median at each eps of the sweep on \
         the same poses, measured the same way (one query per thread, all cores busy).\n\n",
    );
    let head = |s: &mut String, first: &str| {
        let _ = write!(s, "| {first} | poses | OCCT median (ms) |");
        for e in &eps {
            let _ = write!(s, " revdist eps {:.0e} (ms) |", f64::from_bits(*e));
        }
        let _ = write!(s, "\n| --- | ---: | ---: |");
        for _ in &eps {
            s.push_str(" ---: |");
        }
        s.push('\n');
    };
    let row = |s: &mut String, name: &str, t: &Times| {
        let _ = write!(
            s,
            "| {name} | {} | {:.2} |",
            t.occt.len(),
            median_ms(t.occt.clone())
        );
        for e in &eps {
            let v = t.revdist.get(e).cloned().unwrap_or_default();
            let _ = write!(s, " {:.3} |", median_ms(v));
        }
        s.push('\n');
    };
    head(&mut s, "family");
    for (f, t) in &families {
        row(&mut s, f, t);
    }
    s.push('\n');
    head(&mut s, "pair");
    for ((a, b), t) in &pairs {
        row(&mut s, &format!("{a} / {b}"), t);
    }
    s
}

/// `a,b,family,poses,occt_median_ms,revdist_median_ms_eps...` (empty without OCCT records).
pub fn csv(records: &[CaseRecord]) -> String {
    let Some((pairs, _, eps)) = collect(records) else {
        return String::new();
    };
    let mut s = String::from("a,b,family,poses,occt_median_ms");
    for e in &eps {
        let _ = write!(s, ",revdist_median_ms_eps_{:e}", f64::from_bits(*e));
    }
    s.push('\n');
    for ((a, b), t) in &pairs {
        let _ = write!(
            s,
            "{a},{b},{},{},{:.4}",
            family(a, b),
            t.occt.len(),
            median_ms(t.occt.clone())
        );
        for e in &eps {
            let v = t.revdist.get(e).cloned().unwrap_or_default();
            let _ = write!(s, ",{:.4}", median_ms(v));
        }
        s.push('\n');
    }
    s
}

//! The outputs' text: the columns of `tails.csv` and `tails.md` (quantiles per group, the
//! targets, the ten slowest queries).

use super::nesting::Nest;
use super::query::Row;
use super::{MORPH_FRAME, TARGET_MAX_US, TARGET_P99_OVER_MEDIAN};
use crate::stats::{median, quantile};
use crate::table::Table;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// A CSV field, quoted when it holds a comma or a quote (RFC 4180).
pub(super) fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_owned()
    }
}

/// The columns of `tails.csv` (the reproducer last; it is quoted: its JSON has commas).
pub(super) fn csv_table() -> Table<'static, Row> {
    Table::new()
        .csv("index", |r: &Row| r.q.spec.index.to_string())
        .csv("model_a", |r| r.q.a.clone())
        .csv("model_b", |r| r.q.b.clone())
        .csv("eps", |r| format!("{:e}", r.q.spec.eps))
        .csv("tolerance", |r| {
            if r.q.spec.tol0 { "0" } else { "default" }.into()
        })
        .csv("kind", |r| r.q.spec.kind.name().into())
        .csv("family", |r| r.q.family().into())
        .csv("gap", |r| format!("{:.6e}", r.q.gap))
        .csv("time_us", |r| format!("{:.2}", r.time_us))
        .csv("node_pairs", |r| r.node_pairs.to_string())
        .csv("leaf_tests", |r| r.leaf_tests.to_string())
        .csv("lower", |r| format!("{:.9e}", r.lower))
        .csv("upper", |r| format!("{:.9e}", r.upper))
        .csv("overlap", |r| r.overlap.to_string())
        .csv("budget_exhausted", |r| r.budget_exhausted.to_string())
        .csv("reproducer", |r| csv_field(&r.q.reproducer()))
}

/// Statistics of a group of queries.
struct Group {
    label: String,
    times: Vec<f64>,
}

impl Group {
    fn q(&self, p: f64) -> f64 {
        quantile(&self.times, p)
    }
    fn max(&self) -> f64 {
        self.times.iter().copied().fold(f64::NAN, f64::max)
    }
    fn tail_ratio(&self) -> f64 {
        self.q(0.99) / median(&self.times)
    }
}

fn stats_table() -> Table<'static, Group> {
    let t = |p: f64| move |g: &Group| format!("{:.1}", g.q(p));
    Table::new()
        .markdown("queries", |g: &Group| g.label.clone())
        .markdown("n", |g| g.times.len().to_string())
        .right()
        .markdown("median us", |g| format!("{:.1}", median(&g.times)))
        .right()
        .markdown("p90 us", t(0.9))
        .right()
        .markdown("p99 us", t(0.99))
        .right()
        .markdown("p99.9 us", t(0.999))
        .right()
        .markdown("max us", |g| format!("{:.1}", g.max()))
        .right()
        .markdown("p99 / median", |g| format!("{:.1}", g.tail_ratio()))
        .right()
}

/// Groups of `rows` by `key`, in key order.
fn groups<K: Ord>(
    rows: &[Row],
    key: impl Fn(&Row) -> K,
    label: impl Fn(&K) -> String,
) -> Vec<Group> {
    let mut m: BTreeMap<K, Vec<f64>> = BTreeMap::new();
    for r in rows {
        m.entry(key(r)).or_default().push(r.time_us);
    }
    m.into_iter()
        .map(|(k, times)| Group {
            label: label(&k),
            times,
        })
        .collect()
}

pub(super) fn markdown(rows: &[Row], nests: &[Nest], secs: f64) -> String {
    let all = Group {
        label: "all".into(),
        times: rows.iter().map(|r| r.time_us).collect(),
    };
    let mut s = String::from("# Tail of revdist's query times\n\n");
    let _ = writeln!(
        s,
        "{} seeded queries as a new user would try them: the 16 built-in models (exact, freeform \
         `*_ff`, the M_t frame `{MORPH_FRAME}`), gaps log-uniform in [1e-7, 1], eps drawn from \
         the set, tolerance 0 on about a tenth, every tenth query degenerate (coaxial and \
         flipped stacks, identical solids offset by 1e-9..1e-2, solids resting in the cup, \
         concentric nesting: {} nesting model pairs). Trees built once per (model, eps) before \
         any timing. Each query is timed **cold**: run once, alone, on one thread, with no \
         untimed warm-up run of the same query (other queries ran in between, so its trees \
         come from memory), as a user's single query runs. Wall time {secs:.0} s.\n",
        rows.len(),
        nests.len()
    );
    let (p99, med, max) = (all.q(0.99), median(&all.times), all.max());
    let _ = writeln!(
        s,
        "- median {med:.1} us, p90 {:.1} us, p99 {p99:.1} us, p99.9 {:.1} us, max {max:.1} us; \
         p99 / median = {:.1}.",
        all.q(0.9),
        all.q(0.999),
        all.tail_ratio()
    );
    let verdict = |ok: bool| if ok { "met" } else { "**not met**" };
    let _ = writeln!(
        s,
        "- Targets of the issue: p99 <= {TARGET_P99_OVER_MEDIAN}x the median: {} ({:.1}x); \
         max <= {} ms on one thread: {} ({:.2} ms).\n",
        verdict(all.tail_ratio() <= TARGET_P99_OVER_MEDIAN),
        all.tail_ratio(),
        TARGET_MAX_US / 1e3,
        verdict(max <= TARGET_MAX_US),
        max / 1e3
    );
    let mut table = vec![all];
    table.extend(groups(rows, |r| r.q.family(), |f| format!("family: {f}")));
    table.extend(groups(
        rows,
        |r| r.q.spec.kind,
        |k| format!("kind: {}", k.name()),
    ));
    table.extend(groups(
        rows,
        |r| std::cmp::Reverse(r.q.spec.eps.to_bits()),
        |e| format!("eps {:.0e}", f64::from_bits(e.0)),
    ));
    table.extend(groups(
        rows,
        |r| r.q.spec.tol0,
        |&t| format!("tolerance {}", if t { "0" } else { "default" }),
    ));
    s.push_str(&stats_table().markdown_text(&table));
    let nest_names: Vec<String> = nests
        .iter()
        .map(|n| {
            format!(
                "{} in {}{} (clearance {:.3})",
                n.inner,
                n.outer,
                if n.flipped { " upside down" } else { "" },
                n.clearance
            )
        })
        .collect();
    let _ = write!(
        s,
        "\nNesting pairs (the `nested` kind draws from them): {}.\n",
        if nest_names.is_empty() {
            "none".to_string()
        } else {
            nest_names.join(", ")
        }
    );
    s.push_str(
        "\nFamilies: *degenerate* is every query of a degenerate kind; the others are the random \
         queries, *M_t* when either model is the M_t frame, else *freeform* when either is a \
         `*_ff` model, else *exact*. Quantiles are nearest-rank.\n\n## The ten slowest queries\n\n",
    );
    let mut slow: Vec<&Row> = rows.iter().collect();
    slow.sort_by(|x, y| y.time_us.total_cmp(&x.time_us));
    for r in slow.iter().take(10) {
        let _ = writeln!(
            s,
            "- #{} {:.1} us: {}-{} eps {:.0e}, tolerance {}, {} (gap {:.2e}), {} node pairs, {} \
             exact leaves, [{:.3e}, {:.3e}]{}\n\n  `{}`",
            r.q.spec.index,
            r.time_us,
            r.q.a,
            r.q.b,
            r.q.spec.eps,
            if r.q.spec.tol0 { "0" } else { "default" },
            r.q.spec.kind.name(),
            r.q.gap,
            r.node_pairs,
            r.leaf_tests,
            r.lower,
            r.upper,
            if r.overlap { ", overlap" } else { "" },
            r.q.reproducer()
        );
    }
    s
}

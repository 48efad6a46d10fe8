//! The sentences of `pareto.md` on what the data show, computed from the rows.

use super::method::Method;
use super::row::{cross_checks, find, Row};
use super::Settings;
use crate::stats::log_log_slope;
use std::fmt::Write as _;

/// Sentences on what the data show, computed from the rows (so they stay true when rerun).
pub(super) fn summary(rows: &[Row], args: &Settings) -> String {
    let mut s = String::new();
    let (checks, violations) = cross_checks(rows);
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let of = |m: Method, pair: &str| -> Vec<&Row> {
        rows.iter()
            .filter(|r| r.method == m && r.pair == pair)
            .collect()
    };

    // Query time at equal eps: FCL OBBRSS median / revdist median (default tolerance).
    let (mut ahead, mut behind, mut trend) = (Vec::new(), Vec::new(), Vec::new());
    for pair in &pairs {
        let ratios: Vec<(f64, f64)> = of(Method::FclObbrss, pair)
            .iter()
            .filter_map(|f| {
                find(rows, Method::Rev, pair, f.eps).map(|r| (f.eps, f.median_us / r.median_us))
            })
            .collect();
        for &(eps, ratio) in &ratios {
            let txt = format!("{pair} at eps {eps:.0e} ({ratio:.2}x)");
            if ratio < 1.0 {
                behind.push(txt);
            } else {
                ahead.push(txt);
            }
        }
        if let (Some(first), Some(last)) = (ratios.first(), ratios.last()) {
            if ratios.len() > 1 {
                trend.push(format!(
                    "{pair} {:.2}x at {:.0e} to {:.2}x at {:.0e}",
                    first.1, first.0, last.1, last.0
                ));
            }
        }
    }
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    let _ = writeln!(
        s,
        "- **Query time at equal eps** (FCL OBBRSS median / revdist median at its default \
         tolerance, the same poses): revdist is faster on {}; **revdist is behind** on {}. \
         From the coarsest to the finest eps FCL ran at, the ratio goes {}: FCL's time grows with \
         its mesh, revdist's slowly with eps.",
        list(&ahead),
        list(&behind),
        list(&trend)
    );

    // Coarse eps: the default tolerance slower than tolerance 0.
    let mut slow = Vec::new();
    for pair in &pairs {
        for r in of(Method::Rev, pair) {
            if let Some(t0) = find(rows, Method::RevTol0, pair, r.eps) {
                if r.median_us > 1.5 * t0.median_us && r.zero_lower.unwrap_or(0) > 0 {
                    slow.push(format!(
                        "{pair} at eps {:.0e}: {:.0} us against {:.0} us, lower bound 0 in {} of \
                         {} answers",
                        r.eps,
                        r.median_us,
                        t0.median_us,
                        r.zero_lower.unwrap_or(0),
                        r.poses
                    ));
                }
            }
        }
    }
    if !slow.is_empty() {
        let _ = writeln!(
            s,
            "- **Coarse trees are slow at the default tolerance**: {}. An interval up to \
             eps_a + eps_b wide reaches 0 for the closest poses, and the query then spends its \
             time on deciding whether the solids overlap (fewer node pairs than at tolerance 0, \
             yet slower); tolerance 0 narrows the interval first and is faster there.",
            slow.join("; ")
        );
    }

    // Structure cost against accuracy: fitted exponents over the three finest eps of each
    // method (where the leaves, not the pieces of the profile, set the size).
    let exponent = |m: Method, pair: &str, y: &dyn Fn(&Row) -> f64| -> String {
        let mut pts: Vec<(f64, f64)> = of(m, pair).iter().map(|r| (r.eps, y(r))).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts.truncate(3);
        // An exponent that rounds to 0 is shown as 0.00, not -0.00.
        log_log_slope(&pts).map_or("-".to_string(), |e| {
            format!("{:.2}", if e.abs() < 0.005 { 0.0 } else { -e })
        })
    };
    let fits: Vec<String> = pairs
        .iter()
        .map(|p| {
            let bytes = |r: &Row| r.bytes as f64;
            let build = |r: &Row| r.build_ms;
            format!(
                "{p} {} / {} (memory), {} / {} (build)",
                exponent(Method::FclObbrss, p, &bytes),
                exponent(Method::Rev, p, &bytes),
                exponent(Method::FclObbrss, p, &build),
                exponent(Method::Rev, p, &build)
            )
        })
        .collect();
    let finest = |f: &dyn Fn(&Row) -> bool| {
        rows.iter()
            .filter(|r| f(r))
            .map(|r| r.width_max)
            .fold(f64::MAX, f64::min)
    };
    let _ = writeln!(
        s,
        "- **Structure cost**: memory and build time grow as eps^-k, k fitted over each \
         method's three finest eps (FCL OBBRSS / revdist): {}. A mesh of error eps needs \
         ~eps^-1 triangles, a biarc tree ~eps^-1/3 leaves (cubic convergence), and none more \
         where the profile is exact lines and arcs (the torus is one circle). revdist's \
         certified width reaches {:.1e} (the rounding floor of its bounds), FCL's mesh bound \
         {:.1e}, where the next mesh would exceed the triangle cap.",
        fits.join("; "),
        finest(&|r| !r.method.is_fcl()),
        finest(&|r| r.method.is_fcl()),
    );

    // Refinement: its cost and what it narrows.
    let mut refine = Vec::new();
    for pair in &pairs {
        for r in of(Method::RevRefined, pair) {
            if let Some(d) = find(rows, Method::Rev, pair, r.eps) {
                refine.push(format!(
                    "{pair} at {:.0e}: +{:.0} us, width max {:.1e} to {:.1e}, median {:.1e} to \
                     {:.1e}",
                    r.eps,
                    r.median_us - d.median_us,
                    d.width_max,
                    r.width_max,
                    d.width_median,
                    r.width_median
                ));
            }
        }
    }
    if !refine.is_empty() {
        let _ = writeln!(
            s,
            "- **Refined** answers move the upper bound onto the exact surfaces (the lower bound \
             stays the trees'), against the default tolerance: {}.",
            refine.join("; ")
        );
    }
    let _ = writeln!(
        s,
        "- **Cross-check**: every revdist answer against every FCL answer of its pose: \
         {violations} violations in {checks} checks."
    );
    s
}

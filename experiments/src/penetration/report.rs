//! The outputs' text: `penetration.csv` and the summary lines and tables of `penetration.md`.

use super::row::{Class, CoalVerdict, Row};
use super::COAL_EPA_TOLERANCE;
use crate::stats::{median, quantile};
use revdist::query::penetration::separate::MAX_QUERIES;
use std::fmt::Write as _;

pub(super) fn csv(rows: &[Row], preamble: String) -> String {
    let mut s = preamble;
    s += "pair,class,eps,level,push,size,lower,upper,width,target,met,distance_queries,probes,cover_cells,certificate,signed_us,distance_us,coal_depth,coal_us,coal_verdict,tx,ty,tz,qw,qx,qy,qz\n";
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.17e}"));
    for r in rows {
        let (t, q) = (r.pose.translation.vector, r.pose.rotation.quaternion());
        let _ = writeln!(
            s,
            "{},{},{:e},{:e},{:.17e},{:.6e},{:.17e},{:.17e},{:.6e},{:.6e},{},{},{},{},{},{:.1},{:.1},{},{},{},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
            r.pair,
            r.class.name(),
            r.eps,
            r.level,
            r.push,
            r.size,
            r.lower,
            r.upper,
            r.width(),
            r.target(),
            r.met(),
            r.queries,
            r.probes,
            r.cover_cells,
            r.certificate_name(),
            r.signed_us,
            r.distance_us,
            opt(r.coal_depth),
            opt(r.coal_us),
            match r.coal_verdict {
                None => "",
                Some(CoalVerdict::Inside) => "inside",
                Some(CoalVerdict::BelowCommonPoint(_)) => "coal below a certified common point",
                Some(CoalVerdict::AboveSeparation) => "coal above a confirmed separation",
                Some(CoalVerdict::Unexplained) => "unexplained",
            },
            t.x,
            t.y,
            t.z,
            q.w,
            q.i,
            q.j,
            q.k
        );
    }
    s
}

/// The summary's line of one class at one eps.
pub(super) fn summary_line(class: Class, eps: f64, rows: &[&Row]) -> String {
    let answered: Vec<&&Row> = rows.iter().filter(|r| r.answered()).collect();
    let met = answered.iter().filter(|r| r.met()).count();
    let w_eps: Vec<f64> = answered.iter().map(|r| r.width() / r.eps).collect();
    let w_rel: Vec<f64> = answered
        .iter()
        .filter(|r| r.lower > 0.0)
        .map(|r| r.width() / r.lower)
        .collect();
    let signed: Vec<f64> = answered.iter().map(|r| r.signed_us).collect();
    let dist: Vec<f64> = answered.iter().map(|r| r.distance_us).collect();
    let ratio: Vec<f64> = answered
        .iter()
        .map(|r| r.signed_us / r.distance_us)
        .collect();
    let target = if class.targeted() {
        format!(
            "{met} / {} ({:.1} %)",
            answered.len(),
            100.0 * met as f64 / answered.len().max(1) as f64
        )
    } else {
        format!("({met} / {})", answered.len())
    };
    format!(
        "| {} | {eps:.0e} | {} | {} | {target} | {:.3} | {:.3} | {:.4} | {:.0} | {:.0} | {:.2} | {:.2} |\n",
        class.name(),
        rows.len(),
        answered.len(),
        median(&w_eps),
        quantile(&w_eps, 0.9),
        median(&w_rel),
        median(&signed),
        median(&dist),
        median(&ratio),
        quantile(&ratio, 0.9),
    )
}

/// Where the width of the targeted cases that miss it goes.
pub(super) fn misses(rows: &[Row]) -> String {
    let missed: Vec<&Row> = rows
        .iter()
        .filter(|r| r.class.targeted() && r.answered() && !r.met())
        .collect();
    if missed.is_empty() {
        return "Every ball and shallow case met the width target.\n".into();
    }
    let spent = missed.iter().filter(|r| r.queries > MAX_QUERIES).count();
    let untouched = missed.iter().filter(|r| r.lower <= 0.0).count();
    let mut s = format!(
        "{} ball or shallow cases missed the width target: {spent} with the upper bound's \
         search out of distance queries ({MAX_QUERIES}), {} with queries left (no shorter \
         separating translation along its directions); {untouched} with no certified lower \
         bound (lower 0: touching within the trees' accuracy). The worst by width / target:\n\n\
         | pair | class | eps | push / size | lower | upper | width / target | queries | lower by |\n\
         |---|---|---|---|---|---|---|---|---|\n",
        missed.len(),
        missed.len() - spent,
    );
    let mut worst = missed.clone();
    worst.sort_by(|x, y| (y.width() / y.target()).total_cmp(&(x.width() / x.target())));
    for r in worst.iter().take(8) {
        let _ = writeln!(
            s,
            "| {} | {} | {:.0e} | {:.0e} | {:.6e} | {:.6e} | {:.2} | {} | {} |",
            r.pair,
            r.class.name(),
            r.eps,
            r.level,
            r.lower,
            r.upper,
            r.width() / r.target(),
            r.queries,
            r.certificate_name()
        );
    }
    s
}

pub(super) fn coal_table(rows: &[Row], coal_version: &str) -> String {
    let convex: Vec<&Row> = rows.iter().filter(|r| r.coal_depth.is_some()).collect();
    if convex.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\n## coal {coal_version} EPA depths against the interval\n\n\
         coal's signed distance (default request: EPA, closed forms for sphere and capsule \
         pairs) on its exact primitives at the same poses; inside means `lower - tol <= coal \
         <= upper + tol`, `tol = {COAL_EPA_TOLERANCE:e} + 1e-9 scene` (coal's EPA tolerance). \
         A depth outside is judged by `verify`'s oracle on the exact profiles: *coal error* \
         when it is below a point's certified bound `c_A + c_B` (signed clearances; or above a translation \
         the oracle confirms separating); *unexplained* (a violation) otherwise.\n\n\
         | pair | eps | cases | inside | coal error | unexplained | max excess | largest coal shortfall below c_A + c_B | median (coal - lower) / width | median coal us | median revdist signed us |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    let mut keys: Vec<(String, u64)> = Vec::new();
    for r in &convex {
        let k = (r.pair.clone(), r.eps.to_bits());
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    for (pair, eps) in keys {
        let g: Vec<&&Row> = convex
            .iter()
            .filter(|r| r.pair == pair && r.eps.to_bits() == eps && r.answered())
            .collect();
        let inside = g
            .iter()
            .filter(|r| r.coal_verdict == Some(CoalVerdict::Inside))
            .count();
        let unexplained = g.iter().filter(|r| r.coal_violates()).count();
        let shortfall = g
            .iter()
            .filter_map(|r| match r.coal_verdict {
                Some(CoalVerdict::BelowCommonPoint(lo)) => Some(lo - r.coal_depth?),
                _ => None,
            })
            .fold(0.0, f64::max);
        let excess = g.iter().filter_map(|r| r.coal_excess()).fold(0.0, f64::max);
        let pos: Vec<f64> = g
            .iter()
            .map(|r| {
                (r.coal_depth.unwrap_or(f64::NAN) - r.lower) / r.width().max(f64::MIN_POSITIVE)
            })
            .collect();
        let cu: Vec<f64> = g.iter().filter_map(|r| r.coal_us).collect();
        let su: Vec<f64> = g.iter().map(|r| r.signed_us).collect();
        let _ = writeln!(
            s,
            "| {pair} | {:.0e} | {} | {inside} | {} | {unexplained} | {excess:.2e} | {shortfall:.2e} | {:.3} | {:.2} | {:.0} |",
            f64::from_bits(eps),
            g.len(),
            g.len() - inside - unexplained,
            median(&pos),
            median(&cu),
            median(&su),
        );
    }
    s
}

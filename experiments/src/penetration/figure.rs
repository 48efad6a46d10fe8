//! The figure `penetration.svg`: interval width against depth, per eps.

use super::row::{Class, Row};
use super::{LEVELS, TARGET_REL};
use crate::driver::DriverResult;
use crate::plot::{log_log_panels, Curve, Panel};
use crate::stats::{median, quantile};

/// Width against depth, one panel per eps: medians and 90th percentiles per depth level of
/// the ball cases and the model pairs, and the target.
pub(super) fn draw(path: &std::path::Path, rows: &[Row], eps_list: &[f64]) -> DriverResult {
    let mut panels = Vec::new();
    for &eps in eps_list {
        let mut curves = Vec::new();
        for (k, (name, balls)) in [("ball vs model", true), ("model pairs", false)]
            .into_iter()
            .enumerate()
        {
            let mut med = Vec::new();
            let mut p90 = Vec::new();
            for &level in &LEVELS {
                let g: Vec<&Row> = rows
                    .iter()
                    .filter(|r| {
                        r.eps == eps
                            && r.level == level
                            && r.answered()
                            && r.lower > 0.0
                            && (r.class == Class::Ball) == balls
                            && r.class != Class::Convex
                    })
                    .collect();
                if g.is_empty() {
                    continue;
                }
                let depth = median(
                    &g.iter()
                        .map(|r| 0.5 * (r.lower + r.upper))
                        .collect::<Vec<_>>(),
                );
                let w: Vec<f64> = g.iter().map(|r| r.width()).collect();
                med.push((depth, median(&w)));
                p90.push((depth, quantile(&w, 0.9)));
            }
            curves.push(Curve {
                name: format!("{name}: median width"),
                style: 2 * k,
                dashed: false,
                points: med,
            });
            curves.push(Curve {
                name: format!("{name}: 90th percentile"),
                style: 2 * k + 1,
                dashed: true,
                points: p90,
            });
        }
        let depths: Vec<f64> = rows
            .iter()
            .filter(|r| r.eps == eps && r.answered() && r.lower > 0.0)
            .map(|r| 0.5 * (r.lower + r.upper))
            .collect();
        let (lo, hi) = (quantile(&depths, 0.0), quantile(&depths, 1.0));
        let target: Vec<(f64, f64)> = (0..=24)
            .map(|k| {
                let x = lo * (hi / lo).powf(k as f64 / 24.0);
                (x, (4.0 * eps).max(TARGET_REL * x))
            })
            .collect();
        curves.push(Curve {
            name: "target max(2 (eps_a + eps_b), 5 % PD)".into(),
            style: 4,
            dashed: true,
            points: target,
        });
        panels.push(Panel {
            title: format!("eps = {eps:.0e}"),
            curves,
        });
    }
    log_log_panels(
        path,
        "Penetration depth: certified interval width vs depth (paper's models)",
        &panels,
        "depth (interval midpoint)",
        "upper - lower",
        (520, 440),
    )?;
    Ok(())
}

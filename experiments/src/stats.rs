//! Summary statistics of timing samples.

use std::time::Duration;

/// The `q`-quantile (nearest rank) of `v`; NaN for an empty slice.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s[((s.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize]
}

/// Median (nearest rank, the upper of the two middle values for even lengths).
pub fn median(v: &[f64]) -> f64 {
    quantile(v, 0.5)
}

/// Arithmetic mean; NaN for an empty slice.
pub fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.iter().sum::<f64>() / v.len() as f64
}

/// Microseconds in a duration.
pub fn us(d: Duration) -> f64 {
    d.as_secs_f64() * 1e6
}

/// Wall-clock time of `f` on each item in turn, microseconds, one sample per item: the
/// *blocked* protocol (one method alone over all items in a row). Producing an item (the
/// iterator's `next`) is not timed, so setup such as posing a solid stays outside.
pub fn time_each<T, E>(
    items: impl IntoIterator<Item = T>,
    mut f: impl FnMut(T) -> Result<(), E>,
) -> Result<Vec<f64>, E> {
    let mut times = Vec::new();
    for item in items {
        let t = std::time::Instant::now();
        f(item)?;
        times.push(us(t.elapsed()));
    }
    Ok(times)
}

/// A byte count for tables: `6.2 KB`, `30.8 MB`, `1.05 GB` (decimal units).
pub fn human_bytes(b: f64) -> String {
    if b >= 1e9 {
        format!("{:.2} GB", b / 1e9)
    } else if b >= 1e6 {
        format!("{:.1} MB", b / 1e6)
    } else {
        format!("{:.1} KB", b / 1e3)
    }
}

/// Least-squares slope of log(y) against log(x) over the pairs with both positive.
pub fn log_log_slope(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let (mx, my) = (
        logs.iter().map(|p| p.0).sum::<f64>() / n,
        logs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_and_slope() {
        let v = [5.0, 1.0, 3.0, 2.0, 4.0];
        assert_eq!(median(&v), 3.0);
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 5.0);
        assert!(median(&[]).is_nan());
        assert_eq!(mean(&v), 3.0);
        let cubic: Vec<(f64, f64)> = (1..6).map(|k| (k as f64, (k as f64).powi(-3))).collect();
        assert!((log_log_slope(&cubic).unwrap() + 3.0).abs() < 1e-12);
        assert!(log_log_slope(&[(1.0, 1.0)]).is_none());
        assert_eq!(human_bytes(6176.0), "6.2 KB");
        assert_eq!(human_bytes(30_835_732.0), "30.8 MB");
        assert_eq!(human_bytes(1.05e9), "1.05 GB");
        let mut seen = Vec::new();
        let times = time_each([1, 2, 3], |k| {
            seen.push(k);
            Ok::<(), ()>(())
        });
        assert_eq!((times.map(|t| t.len()), seen), (Ok(3), vec![1, 2, 3]));
        assert_eq!(
            time_each([1, 2], |k| if k == 2 { Err(k) } else { Ok(()) }),
            Err(2)
        );
    }
}

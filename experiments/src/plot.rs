//! The figures' common style and the chart kinds plotters lacks (grouped bars with a legend
//! outside the plot). SVG only: text is written as `<text>` and needs no font files (see
//! `../shared/notes/style_ecosystem.md` section 4).

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Font family of every figure.
pub const FONT: &str = "sans-serif";
/// Caption size (px).
pub const CAPTION: u32 = 20;
/// Axis-description and legend size (px).
pub const LABEL: u32 = 15;
/// Tick-label size (px).
pub const TICK: u32 = 13;

/// Error type of the drawing helpers.
pub type PlotResult = Result<(), Box<dyn std::error::Error>>;

/// Colour `k` of a qualitative palette readable on white (Okabe-Ito, colour-blind safe).
pub fn colour(k: usize) -> RGBColor {
    const OKABE_ITO: [RGBColor; 8] = [
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(0, 0, 0),
        RGBColor(120, 120, 120),
    ];
    if k < OKABE_ITO.len() {
        OKABE_ITO[k]
    } else {
        let (r, g, b) = Palette99::pick(k).to_rgba().rgb();
        RGBColor(r, g, b)
    }
}

/// Tick label of a log axis: `1e-3`, `10`, `1e4`.
pub fn log_tick(v: &f64) -> String {
    let e = v.log10();
    if (e - e.round()).abs() < 1e-9 && (-2.0..=3.0).contains(&e.round()) {
        let s = format!("{v}");
        s.trim_end_matches(".0").to_string()
    } else {
        format!("{v:.0e}")
    }
}

/// One series of a grouped bar chart: a name and one value per category (NaN: no bar).
pub struct BarSeries {
    pub name: String,
    pub values: Vec<f64>,
}

/// A grouped bar chart: one group per category, one bar per series, log y axis when `log`
/// (bars then start at the axis minimum), legend to the right of the plot, optional text
/// above each group (e.g. a speed-up ratio).
#[allow(clippy::too_many_arguments)]
pub fn grouped_bars(
    path: &Path,
    caption: &str,
    categories: &[String],
    series: &[BarSeries],
    y_desc: &str,
    log: bool,
    group_notes: Option<&[String]>,
    size: (u32, u32),
) -> PlotResult {
    let colours: Vec<RGBColor> = (0..series.len()).map(colour).collect();
    grouped_bars_coloured(
        path,
        caption,
        categories,
        series,
        &colours,
        y_desc,
        log,
        group_notes,
        size,
    )
}

/// Shades of one hue, light to dark, for `n` bars of one method (e.g. one per eps).
pub fn shades(base: RGBColor, n: usize) -> Vec<RGBColor> {
    (0..n)
        .map(|k| {
            // Mix towards white: the first is lightest, the last is `base`.
            let w = if n > 1 {
                0.6 * (n - 1 - k) as f64 / (n - 1) as f64
            } else {
                0.0
            };
            let mix = |c: u8| (c as f64 + (255.0 - c as f64) * w).round() as u8;
            RGBColor(mix(base.0), mix(base.1), mix(base.2))
        })
        .collect()
}

/// [`grouped_bars`] with one colour per series (e.g. [`shades`] of one hue per method).
#[allow(clippy::too_many_arguments)]
pub fn grouped_bars_coloured(
    path: &Path,
    caption: &str,
    categories: &[String],
    series: &[BarSeries],
    colours: &[RGBColor],
    y_desc: &str,
    log: bool,
    group_notes: Option<&[String]>,
    size: (u32, u32),
) -> PlotResult {
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let legend_w = 170;
    let (plot_area, legend_area) = root.split_horizontally(size.0 - legend_w);
    let finite: Vec<f64> = series
        .iter()
        .flat_map(|s| s.values.iter().copied())
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .collect();
    let hi = finite.iter().copied().fold(f64::MIN, f64::max).max(1e-300);
    let lo = finite.iter().copied().fold(f64::MAX, f64::min);
    let n_cat = categories.len().max(1);
    let n_ser = series.len().max(1);
    let x_range = 0.0..n_cat as f64;
    let draw = |y_lo: f64, y_hi: f64, is_log: bool| -> PlotResult {
        let mut builder = ChartBuilder::on(&plot_area);
        builder
            .caption(caption, (FONT, CAPTION))
            .margin(14)
            .x_label_area_size(if categories.iter().any(|c| c.len() > 8) {
                70
            } else {
                40
            })
            .y_label_area_size(70);
        let bar = |k: usize, j: usize| -> (f64, f64) {
            let w = 0.8 / n_ser as f64;
            let x0 = k as f64 + 0.1 + w * j as f64;
            (x0, x0 + w * 0.92)
        };
        macro_rules! body {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .disable_x_mesh()
                    .x_labels(0)
                    .y_label_formatter(&|v: &f64| log_tick(v))
                    .y_desc(y_desc)
                    .label_style((FONT, TICK))
                    .axis_desc_style((FONT, LABEL))
                    .draw()?;
                for (j, s) in series.iter().enumerate() {
                    let c = colours.get(j).copied().unwrap_or_else(|| colour(j));
                    chart.draw_series(s.values.iter().enumerate().filter_map(|(k, &v)| {
                        (v.is_finite() && (!is_log || v > 0.0)).then(|| {
                            let (x0, x1) = bar(k, j);
                            Rectangle::new([(x0, y_lo), (x1, v)], c.filled())
                        })
                    }))?;
                }
                if let Some(notes) = group_notes {
                    for (k, note) in notes.iter().enumerate() {
                        let top = series
                            .iter()
                            .filter_map(|s| s.values.get(k).copied())
                            .filter(|v| v.is_finite())
                            .fold(y_lo, f64::max);
                        let y = if is_log {
                            top * 1.25
                        } else {
                            top + 0.03 * (y_hi - y_lo)
                        };
                        chart.draw_series(std::iter::once(Text::new(
                            note.clone(),
                            (k as f64 + 0.2, y),
                            (FONT, TICK),
                        )))?;
                    }
                }
                // Category labels under each group, in the root area's pixels.
                for (k, name) in categories.iter().enumerate() {
                    let (px, py) = chart.backend_coord(&(k as f64 + 0.5, y_lo));
                    let style = TextStyle::from((FONT, TICK).into_font())
                        .pos(Pos::new(HPos::Center, VPos::Top));
                    plot_area.draw(&Text::new(name.clone(), (px, py + 6), style))?;
                }
                Ok(())
            }};
        }
        if is_log {
            let chart = builder.build_cartesian_2d(x_range.clone(), (y_lo..y_hi).log_scale())?;
            body!(chart)
        } else {
            let chart = builder.build_cartesian_2d(x_range.clone(), y_lo..y_hi)?;
            body!(chart)
        }
    };
    if log {
        draw(lo / 2.0, hi * 3.0, true)?;
    } else {
        draw(0.0, hi * 1.15, false)?;
    }
    for (j, s) in series.iter().enumerate() {
        let y = 50 + 24 * j as i32;
        legend_area.draw(&Rectangle::new(
            [(6, y - 6), (24, y + 6)],
            colours
                .get(j)
                .copied()
                .unwrap_or_else(|| colour(j))
                .filled(),
        ))?;
        legend_area.draw(&Text::new(s.name.clone(), (30, y - 7), (FONT, LABEL)))?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_read_well() {
        assert_eq!(log_tick(&10.0), "10");
        assert_eq!(log_tick(&0.01), "0.01");
        assert_eq!(log_tick(&1e-5), "1e-5");
        assert_eq!(log_tick(&1e4), "1e4");
    }

    #[test]
    fn grouped_bars_write_an_svg() {
        let dir = std::env::temp_dir().join(format!("revdist-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("bars.svg");
        let cats = vec!["pawn".to_string(), "cup".to_string()];
        let series = vec![
            BarSeries {
                name: "revdist".into(),
                values: vec![10.0, 20.0],
            },
            BarSeries {
                name: "FCL".into(),
                values: vec![100.0, f64::NAN],
            },
        ];
        let notes = vec!["10x".to_string(), String::new()];
        grouped_bars(
            &path,
            "t",
            &cats,
            &series,
            "us",
            true,
            Some(&notes),
            (700, 400),
        )
        .unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("revdist") && svg.contains("pawn") && svg.contains("10x"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

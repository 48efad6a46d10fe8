//! The figures' common style and the chart kinds plotters lacks (grouped bars with a legend
//! outside the plot). SVG only: text is written as `<text>` and needs no font files (see
//! `docs/protocols.md`, "Figures").

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

/// Tick label of a log axis: plain numbers in [0.01, 1e4) (`0.05`, `10`, `900`), powers
/// of ten in exponent form outside it (`1e-5`, `1e4`).
pub fn log_tick(v: &f64) -> String {
    let v = *v;
    if (0.01..1e4).contains(&v) {
        let digits = if v >= 1.0 { 0 } else { 2 };
        let s = format!("{v:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
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
            // Category names are drawn by hand just under the axis.
            .x_label_area_size(30)
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
        // Whole decades, so that the log axis labels at least two powers of ten.
        let floor = 10f64.powf((lo / 1.5).log10().floor());
        let ceil = 10f64.powf((hi * 2.0).log10().ceil());
        draw(floor, ceil, true)?;
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

/// One curve of a log-log chart: a method's points (drawn in order), in colour and marker
/// `style` ([`colour`]; markers cycle circle, square, triangle, diamond, cross), dashed or solid.
pub struct Curve {
    pub name: String,
    pub style: usize,
    pub dashed: bool,
    pub points: Vec<(f64, f64)>,
}

/// One panel of [`log_log_panels`]: a title and its curves.
pub struct Panel {
    pub title: String,
    pub curves: Vec<Curve>,
}

/// Decade-aligned range holding every positive value of `v` (`(0.1, 10)` when there is none).
fn decades(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    if lo > hi {
        return (0.1, 10.0);
    }
    let (l, h) = (lo.log10().floor(), hi.log10().ceil());
    (10f64.powf(l), 10f64.powf(if h > l { h } else { l + 1.0 }))
}

/// Draws marker `style` of colour `c` at the points (a plotters series per marker shape).
fn draw_markers<DB: DrawingBackend, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    points: &[(f64, f64)],
    style: usize,
    c: RGBColor,
) -> PlotResult
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
    DB::ErrorType: 'static,
{
    let fill = c.filled();
    let pts = points.iter().copied();
    match style % 5 {
        0 => chart.draw_series(pts.map(|p| Circle::new(p, 4, fill)))?,
        1 => chart.draw_series(
            pts.map(|p| EmptyElement::at(p) + Rectangle::new([(-4, -4), (4, 4)], fill)),
        )?,
        2 => chart.draw_series(pts.map(|p| TriangleMarker::new(p, 6, fill)))?,
        3 => chart.draw_series(pts.map(|p| {
            EmptyElement::at(p) + Polygon::new(vec![(0, -6), (6, 0), (0, 6), (-6, 0)], fill)
        }))?,
        _ => chart.draw_series(pts.map(|p| Cross::new(p, 5, c.stroke_width(2))))?,
    };
    Ok(())
}

/// Panels of log-log curves side by side, sharing decade-aligned axis ranges (so the panels
/// compare at a glance), under one caption, with one legend of every distinct curve name to
/// the right, in the order of the first panel's curves. Earlier curves are drawn on top of
/// later ones. Non-positive or non-finite points are left out. `panel` is one panel's size.
pub fn log_log_panels(
    path: &Path,
    caption: &str,
    panels: &[Panel],
    x_desc: &str,
    y_desc: &str,
    panel: (u32, u32),
) -> PlotResult {
    let legend_w = 230;
    let size = (
        panel.0 * panels.len().max(1) as u32 + legend_w,
        panel.1 + 40,
    );
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let body = root.titled(caption, (FONT, CAPTION))?;
    let (plots, legend_area) = body.split_horizontally(size.0 - legend_w);
    let all = || {
        panels
            .iter()
            .flat_map(|p| p.curves.iter())
            .flat_map(|c| c.points.iter().copied())
            .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
    };
    let (x_lo, x_hi) = decades(all().map(|p| p.0));
    let (y_lo, y_hi) = decades(all().map(|p| p.1));
    for (area, p) in plots
        .split_evenly((1, panels.len().max(1)))
        .iter()
        .zip(panels)
    {
        let mut chart = ChartBuilder::on(area)
            .caption(&p.title, (FONT, LABEL + 2))
            .margin(10)
            .margin_right(18)
            .x_label_area_size(52)
            .y_label_area_size(70)
            .build_cartesian_2d((x_lo..x_hi).log_scale(), (y_lo..y_hi).log_scale())?;
        chart
            .configure_mesh()
            .x_label_formatter(&|v: &f64| log_tick(v))
            .y_label_formatter(&|v: &f64| log_tick(v))
            .x_desc(x_desc)
            .y_desc(y_desc)
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, LABEL))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(200, 200, 200))
            .draw()?;
        // Reverse order: the first curves end up on top where curves coincide.
        for c in p.curves.iter().rev() {
            let pts: Vec<(f64, f64)> = c
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
                .collect();
            let col = colour(c.style);
            let line = col.stroke_width(2);
            if c.dashed {
                chart.draw_series(DashedLineSeries::new(pts.clone(), 7, 4, line))?;
            } else {
                chart.draw_series(LineSeries::new(pts.clone(), line))?;
            }
            draw_markers(&mut chart, &pts, c.style, col)?;
        }
    }
    let mut seen: Vec<(&str, usize, bool)> = Vec::new();
    for c in panels.iter().flat_map(|p| p.curves.iter()) {
        if !seen.iter().any(|s| s.0 == c.name) {
            seen.push((&c.name, c.style, c.dashed));
        }
    }
    for (k, (name, style, dashed)) in seen.into_iter().enumerate() {
        let y = 60 + 26 * k as i32;
        let col = colour(style);
        let (x0, x1) = (8, 44);
        let step = if dashed { 11 } else { x1 - x0 };
        for x in (x0..x1).step_by(step as usize) {
            let seg = [(x, y), ((x + if dashed { 7 } else { step }).min(x1), y)];
            legend_area.draw(&PathElement::new(seg, col.stroke_width(2)))?;
        }
        let m = ((x0 + x1) / 2, y);
        let fill = col.filled();
        match style % 5 {
            0 => legend_area.draw(&Circle::new(m, 4, fill))?,
            1 => legend_area.draw(&Rectangle::new(
                [(m.0 - 4, m.1 - 4), (m.0 + 4, m.1 + 4)],
                fill,
            ))?,
            2 => legend_area.draw(&TriangleMarker::new(m, 6, fill))?,
            3 => legend_area.draw(&Polygon::new(
                vec![
                    (m.0, m.1 - 6),
                    (m.0 + 6, m.1),
                    (m.0, m.1 + 6),
                    (m.0 - 6, m.1),
                ],
                fill,
            ))?,
            _ => legend_area.draw(&Cross::new(m, 5, col.stroke_width(2)))?,
        }
        let style =
            TextStyle::from((FONT, LABEL).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
        legend_area.draw(&Text::new(name.to_string(), (52, y), style))?;
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
        assert_eq!(log_tick(&900.0), "900");
        assert_eq!(log_tick(&0.05), "0.05");
        assert_eq!(log_tick(&0.5), "0.5");
    }

    #[test]
    fn log_log_panels_write_an_svg() {
        let dir = std::env::temp_dir().join(format!("revdist-panels-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("panels.svg");
        let curve = |name: &str, style: usize, dashed: bool| Curve {
            name: name.into(),
            style,
            dashed,
            points: vec![(1e-3, 10.0), (1e-5, 100.0), (0.0, 5.0)],
        };
        let panels = vec![
            Panel {
                title: "left".into(),
                curves: vec![curve("a", 0, false), curve("b", 3, true)],
            },
            Panel {
                title: "right".into(),
                curves: vec![curve("a", 0, false)],
            },
        ];
        log_log_panels(&path, "cap", &panels, "x (m)", "y (us)", (300, 300)).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("left") && svg.contains("right") && svg.contains("x (m)"));
        // One legend entry per distinct name.
        assert_eq!(svg.lines().filter(|l| l.trim() == "a").count(), 1);
        assert_eq!(decades([2e-4, 0.3].into_iter()), (1e-4, 1.0));
        std::fs::remove_dir_all(&dir).unwrap();
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

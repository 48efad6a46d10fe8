//! SVG drawings of profiles in the (rho, z) half-plane, as pure functions returning the SVG
//! text (no file I/O). [`SvgCanvas`] is a small reusable builder: a world-to-screen
//! transform (z up, equal scale on both axes) plus polylines, lines, dots, circle arcs and
//! text; [`SvgDocument`] places canvases side by side for grid figures.

use std::fmt::Write as _;

use nalgebra::Point2;

use crate::models::sampling::sample_piece;
use crate::profile::Profile;

/// Stroke and fill of a drawn element.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// Stroke colour (any SVG colour), or "none".
    pub stroke: String,
    /// Stroke width in pixels.
    pub stroke_width: f64,
    /// Fill colour, or "none".
    pub fill: String,
    /// SVG dash pattern in pixels, e.g. "4 3".
    pub dash: Option<String>,
    /// Opacity in [0, 1].
    pub opacity: f64,
}

impl Style {
    /// Solid stroke of the given colour and width, no fill.
    pub fn stroke(color: &str, width: f64) -> Self {
        Style {
            stroke: color.to_string(),
            stroke_width: width,
            fill: "none".to_string(),
            dash: None,
            opacity: 1.0,
        }
    }

    /// Filled shape without a stroke.
    pub fn fill(color: &str) -> Self {
        Style {
            stroke: "none".to_string(),
            stroke_width: 0.0,
            fill: color.to_string(),
            dash: None,
            opacity: 1.0,
        }
    }

    /// The same style with a dash pattern.
    pub fn dashed(mut self, pattern: &str) -> Self {
        self.dash = Some(pattern.to_string());
        self
    }

    /// The same style with an opacity.
    pub fn with_opacity(mut self, opacity: f64) -> Self {
        self.opacity = opacity;
        self
    }

    fn attributes(&self) -> String {
        let mut s = format!(
            r#"stroke="{}" stroke-width="{}" fill="{}""#,
            escape(&self.stroke),
            num(self.stroke_width),
            escape(&self.fill)
        );
        if let Some(dash) = &self.dash {
            let _ = write!(s, r#" stroke-dasharray="{}""#, escape(dash));
        }
        if self.opacity < 1.0 {
            let _ = write!(s, r#" opacity="{}""#, num(self.opacity));
        }
        s
    }
}

/// Horizontal text alignment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

impl Anchor {
    fn as_str(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// A drawing area of `width` x `height` pixels showing a world box with equal scale on both
/// axes, rho to the right and z up, centred, with a margin in pixels.
#[derive(Debug, Clone)]
pub struct SvgCanvas {
    width: f64,
    height: f64,
    scale: f64,
    /// Screen position of the world origin.
    origin_x: f64,
    origin_y: f64,
    body: String,
}

impl SvgCanvas {
    /// Canvas fitting the world box `[min, max]` into `width` x `height` pixels, leaving
    /// `margin` pixels on each side (and `top` extra pixels at the top for a title).
    pub fn new(
        min: Point2<f64>,
        max: Point2<f64>,
        width: f64,
        height: f64,
        margin: f64,
        top: f64,
    ) -> Self {
        let span_x = (max.x - min.x).max(f64::EPSILON);
        let span_y = (max.y - min.y).max(f64::EPSILON);
        let avail_x = (width - 2.0 * margin).max(1.0);
        let avail_y = (height - 2.0 * margin - top).max(1.0);
        let scale = (avail_x / span_x).min(avail_y / span_y);
        let cx = 0.5 * (min.x + max.x);
        let cy = 0.5 * (min.y + max.y);
        SvgCanvas {
            width,
            height,
            scale,
            origin_x: 0.5 * width - cx * scale,
            origin_y: top + margin + 0.5 * avail_y + cy * scale,
            body: String::new(),
        }
    }

    /// Pixels per world unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Width and height in pixels.
    pub fn size(&self) -> (f64, f64) {
        (self.width, self.height)
    }

    /// Screen coordinates (pixels, y down) of a world point (rho, z).
    pub fn to_screen(&self, p: Point2<f64>) -> (f64, f64) {
        (
            self.origin_x + p.x * self.scale,
            self.origin_y - p.y * self.scale,
        )
    }

    /// Open polyline through world points.
    pub fn polyline(&mut self, points: &[Point2<f64>], style: &Style) {
        if points.is_empty() {
            return;
        }
        let _ = writeln!(
            self.body,
            r#"<polyline points="{}" {} stroke-linejoin="round"/>"#,
            self.screen_coords(points),
            style.attributes()
        );
    }

    /// Closed polygon through world points (e.g. a filled error band).
    pub fn polygon(&mut self, points: &[Point2<f64>], style: &Style) {
        if points.is_empty() {
            return;
        }
        let _ = writeln!(
            self.body,
            r#"<polygon points="{}" {} stroke-linejoin="round"/>"#,
            self.screen_coords(points),
            style.attributes()
        );
    }

    /// Any SVG element text in screen coordinates, added as is (for what the helpers above
    /// do not cover).
    pub fn raw(&mut self, element: &str) {
        self.body.push_str(element);
        if !element.ends_with('\n') {
            self.body.push('\n');
        }
    }

    fn screen_coords(&self, points: &[Point2<f64>]) -> String {
        let mut coords = String::with_capacity(points.len() * 16);
        for p in points {
            let (x, y) = self.to_screen(*p);
            let _ = write!(coords, "{},{} ", num(x), num(y));
        }
        coords.truncate(coords.trim_end().len());
        coords
    }

    /// Straight segment between world points.
    pub fn line(&mut self, a: Point2<f64>, b: Point2<f64>, style: &Style) {
        let ((x1, y1), (x2, y2)) = (self.to_screen(a), self.to_screen(b));
        let _ = writeln!(
            self.body,
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" {}/>"#,
            num(x1),
            num(y1),
            num(x2),
            num(y2),
            style.attributes()
        );
    }

    /// Dot of `radius_px` pixels at a world point.
    pub fn dot(&mut self, center: Point2<f64>, radius_px: f64, style: &Style) {
        let (x, y) = self.to_screen(center);
        let _ = writeln!(
            self.body,
            r#"<circle cx="{}" cy="{}" r="{}" {}/>"#,
            num(x),
            num(y),
            num(radius_px),
            style.attributes()
        );
    }

    /// Circular arc of world radius `radius` about `center` from angle `phi0` to `phi1`
    /// (radians from +rho towards +z; phi1 < phi0 runs clockwise), as an exact SVG arc path.
    pub fn arc(&mut self, center: Point2<f64>, radius: f64, phi0: f64, phi1: f64, style: &Style) {
        let point =
            |phi: f64| Point2::new(center.x + radius * phi.cos(), center.y + radius * phi.sin());
        let sweep = phi1 - phi0;
        // A single SVG arc cannot draw a full turn: split into pieces of at most a half turn.
        let pieces = ((sweep.abs() / std::f64::consts::PI).ceil() as usize).max(1);
        let (sx, sy) = self.to_screen(point(phi0));
        let r = num(radius * self.scale);
        // World counter-clockwise is screen anticlockwise, i.e. SVG sweep-flag 0 (y is down).
        let flag = if sweep >= 0.0 { 0 } else { 1 };
        let mut d = format!("M{},{}", num(sx), num(sy));
        for i in 1..=pieces {
            let (x, y) = self.to_screen(point(phi0 + sweep * i as f64 / pieces as f64));
            let _ = write!(d, " A{r},{r} 0 0 {flag} {},{}", num(x), num(y));
        }
        let _ = writeln!(self.body, r#"<path d="{d}" {}/>"#, style.attributes());
    }

    /// Text at a world point.
    pub fn text(&mut self, at: Point2<f64>, text: &str, size_px: f64, anchor: Anchor) {
        let (x, y) = self.to_screen(at);
        self.text_px(x, y, text, size_px, anchor);
    }

    /// Text at a screen position in pixels.
    pub fn text_px(&mut self, x: f64, y: f64, text: &str, size_px: f64, anchor: Anchor) {
        self.body
            .push_str(&text_element(x, y, text, size_px, anchor));
    }

    /// The canvas as a standalone SVG document.
    pub fn finish(self) -> String {
        let mut doc = SvgDocument::new(self.width, self.height);
        doc.place(0.0, 0.0, self);
        doc.finish()
    }
}

/// An SVG document holding canvases at pixel offsets (for grid figures).
#[derive(Debug, Clone)]
pub struct SvgDocument {
    width: f64,
    height: f64,
    body: String,
}

impl SvgDocument {
    /// Empty white document of `width` x `height` pixels.
    pub fn new(width: f64, height: f64) -> Self {
        SvgDocument {
            width,
            height,
            body: String::new(),
        }
    }

    /// Place a canvas with its top-left corner at (x, y) pixels.
    pub fn place(&mut self, x: f64, y: f64, canvas: SvgCanvas) {
        let _ = write!(
            self.body,
            "<g transform=\"translate({},{})\">\n{}</g>\n",
            num(x),
            num(y),
            canvas.body
        );
    }

    /// Text at a pixel position of the document.
    pub fn text_px(&mut self, x: f64, y: f64, text: &str, size_px: f64, anchor: Anchor) {
        self.body
            .push_str(&text_element(x, y, text, size_px, anchor));
    }

    /// The SVG text.
    pub fn finish(self) -> String {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{}</svg>\n",
            self.body,
            w = num(self.width),
            h = num(self.height),
        )
    }
}

/// What [`profiles_svg`] and [`profile_grid_svg`] draw.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSvgOptions {
    /// Size of one drawing in pixels.
    pub width: f64,
    pub height: f64,
    /// Also draw the mirror image across the axis (the solid's silhouette).
    pub mirror: bool,
    /// Draw the control polygons and control points.
    pub control_polygon: bool,
    /// Draw the axis of revolution rho = 0.
    pub axis: bool,
    /// Mark the piece boundaries with dots.
    pub piece_ends: bool,
    /// Title above the drawing (None: the profiles' names).
    pub title: Option<String>,
    /// Polyline samples per knot span of every piece.
    pub samples_per_span: usize,
}

impl Default for ProfileSvgOptions {
    fn default() -> Self {
        ProfileSvgOptions {
            width: 480.0,
            height: 560.0,
            mirror: false,
            control_polygon: true,
            axis: true,
            piece_ends: true,
            title: None,
            samples_per_span: 64,
        }
    }
}

/// Colours of successive profiles in one drawing.
const PALETTE: [&str; 6] = [
    "#1f4e9c", "#c0392b", "#1e8449", "#8e44ad", "#d35400", "#17202a",
];
/// Margin around a drawing, pixels.
const MARGIN_PX: f64 = 16.0;
/// Space for the title, pixels.
const TITLE_PX: f64 = 28.0;

/// One drawing of several profiles over a common world box.
pub fn profiles_svg(profiles: &[&Profile], options: &ProfileSvgOptions) -> String {
    profiles_canvas(profiles, options).finish()
}

/// A grid of drawings, one profile each, `columns` wide, every cell `options.width` x
/// `options.height` pixels, with an overall title. Each cell has its own scale.
pub fn profile_grid_svg(
    profiles: &[&Profile],
    columns: usize,
    title: &str,
    options: &ProfileSvgOptions,
) -> String {
    let columns = columns.max(1);
    let rows = profiles.len().div_ceil(columns).max(1);
    let width = options.width * columns as f64;
    let height = options.height * rows as f64 + TITLE_PX;
    let mut doc = SvgDocument::new(width, height);
    doc.text_px(0.5 * width, 0.75 * TITLE_PX, title, 18.0, Anchor::Middle);
    for (i, profile) in profiles.iter().enumerate() {
        let cell = ProfileSvgOptions {
            title: Some(profile.name().to_string()),
            ..options.clone()
        };
        let x = (i % columns) as f64 * options.width;
        let y = TITLE_PX + (i / columns) as f64 * options.height;
        doc.place(x, y, profiles_canvas(&[profile], &cell));
    }
    doc.finish()
}

fn profiles_canvas(profiles: &[&Profile], options: &ProfileSvgOptions) -> SvgCanvas {
    let curves: Vec<Vec<Vec<Point2<f64>>>> = profiles
        .iter()
        .map(|p| {
            p.pieces()
                .iter()
                .map(|piece| sample_piece(piece, options.samples_per_span))
                .collect()
        })
        .collect();
    let (mut min, mut max) = (
        Point2::new(0.0, f64::INFINITY),
        Point2::new(0.0, f64::NEG_INFINITY),
    );
    let mut include = |p: &Point2<f64>| {
        min = min.inf(p);
        max = max.sup(p);
        if options.mirror {
            min.x = min.x.min(-p.x);
        }
    };
    curves.iter().flatten().flatten().for_each(&mut include);
    if options.control_polygon {
        profiles
            .iter()
            .flat_map(|p| p.pieces())
            .flat_map(|piece| piece.points())
            .for_each(&mut include);
    }
    if !min.y.is_finite() {
        (min.y, max.y) = (0.0, 1.0);
    }
    let mut canvas = SvgCanvas::new(min, max, options.width, options.height, MARGIN_PX, TITLE_PX);
    if options.axis {
        let pad = 0.04 * (max.y - min.y).max(1e-9);
        canvas.line(
            Point2::new(0.0, min.y - pad),
            Point2::new(0.0, max.y + pad),
            &Style::stroke("#888888", 1.0).dashed("8 3 2 3"),
        );
    }
    for (i, (profile, pieces)) in profiles.iter().zip(&curves).enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        if options.control_polygon {
            for piece in profile.pieces() {
                canvas.polyline(piece.points(), &Style::stroke("#999999", 0.8).dashed("3 2"));
                for p in piece.points() {
                    canvas.dot(*p, 1.8, &Style::fill("#777777"));
                }
            }
        }
        for samples in pieces {
            canvas.polyline(samples, &Style::stroke(color, 1.8));
            if options.mirror {
                let mirrored: Vec<_> = samples.iter().map(|p| Point2::new(-p.x, p.y)).collect();
                canvas.polyline(&mirrored, &Style::stroke(color, 1.8).with_opacity(0.45));
            }
        }
        if options.piece_ends {
            for samples in pieces {
                if let Some(p) = samples.first() {
                    canvas.dot(*p, 2.6, &Style::fill(color));
                }
            }
            if let Some(p) = pieces.last().and_then(|s| s.last()) {
                canvas.dot(*p, 2.6, &Style::fill(color));
            }
        }
    }
    let title = options.title.clone().unwrap_or_else(|| {
        profiles
            .iter()
            .map(|p| p.name())
            .collect::<Vec<_>>()
            .join(", ")
    });
    canvas.text_px(
        0.5 * options.width,
        0.7 * TITLE_PX,
        &title,
        15.0,
        Anchor::Middle,
    );
    canvas
}

/// An SVG text element at a pixel position, with its line break.
fn text_element(x: f64, y: f64, text: &str, size_px: f64, anchor: Anchor) -> String {
    format!(
        "<text x=\"{}\" y=\"{}\" font-family=\"sans-serif\" font-size=\"{}\" text-anchor=\"{}\">{}</text>\n",
        num(x),
        num(y),
        num(size_px),
        anchor.as_str(),
        escape(text)
    )
}

/// Number formatting for SVG attributes: at most 3 decimals, no trailing zeros.
fn num(x: f64) -> String {
    let s = format!("{x:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// XML escaping of text and attribute values.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            _ => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_to_screen_flips_z_and_keeps_aspect() {
        let canvas = SvgCanvas::new(
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 2.0),
            100.0,
            200.0,
            0.0,
            0.0,
        );
        assert_eq!(canvas.scale(), 100.0);
        assert_eq!(canvas.to_screen(Point2::new(0.0, 0.0)), (0.0, 200.0));
        assert_eq!(canvas.to_screen(Point2::new(1.0, 2.0)), (100.0, 0.0));
    }

    #[test]
    fn arc_path_uses_half_turn_pieces_and_screen_orientation() {
        let mut canvas = SvgCanvas::new(
            Point2::new(-1.0, -1.0),
            Point2::new(1.0, 1.0),
            100.0,
            100.0,
            0.0,
            0.0,
        );
        canvas.arc(
            Point2::origin(),
            1.0,
            0.0,
            2.0 * std::f64::consts::PI,
            &Style::stroke("black", 1.0),
        );
        let svg = canvas.finish();
        // A full turn needs two arc commands, counter-clockwise in the world = sweep flag 0.
        assert_eq!(svg.matches(" A50,50 0 0 0 ").count(), 2, "{svg}");
        assert!(svg.contains("M100,50"), "{svg}");
    }

    #[test]
    fn polygons_close_and_fill() {
        let mut canvas = SvgCanvas::new(
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 1.0),
            10.0,
            10.0,
            0.0,
            0.0,
        );
        let square = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
        ];
        canvas.polygon(&square, &Style::fill("red").with_opacity(0.5));
        canvas.raw("<desc>x</desc>");
        let svg = canvas.finish();
        assert!(
            svg.contains(r#"<polygon points="0,10 10,10 10,0" stroke="none" stroke-width="0" fill="red" opacity="0.5""#),
            "{svg}"
        );
        assert!(svg.contains("<desc>x</desc>\n"));
    }

    #[test]
    fn text_is_escaped() {
        let mut doc = SvgDocument::new(10.0, 10.0);
        doc.text_px(0.0, 0.0, "a<b & \"c\"", 10.0, Anchor::Start);
        let svg = doc.finish();
        assert!(svg.contains("a&lt;b &amp; &quot;c&quot;"));
        assert!(!svg.contains("a<b"));
    }

    #[test]
    fn numbers_are_compact() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(1.23456), "1.235");
    }
}

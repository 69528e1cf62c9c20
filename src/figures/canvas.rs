//! A figure as a list of classed shapes, and its two back-ends: SVG (written directly, every
//! shape keeps its class, so tests and users can find "the obstacles" or "the path") and PNG
//! (rasterised with plotters' bitmap back-end and the bundled DejaVu Sans font).
//!
//! Figures are drawings, not results: coordinates are `f64` pixels here by design.

use std::fmt::Write as _;
use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::{FontStyle, RGBColor};

/// An RGB colour.
pub type Rgb = (u8, u8, u8);

/// One drawn element. `class` names what it shows (`obstacle`, `move`, `path`, ...).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A disc.
    Circle {
        /// What it shows.
        class: &'static str,
        /// Centre, pixels.
        c: (f64, f64),
        /// Radius, pixels.
        r: f64,
        /// Fill colour and opacity.
        fill: Option<(Rgb, f64)>,
        /// Stroke colour and width.
        stroke: Option<(Rgb, f64)>,
    },
    /// A segment.
    Line {
        /// What it shows.
        class: &'static str,
        /// From.
        a: (f64, f64),
        /// To.
        b: (f64, f64),
        /// Colour.
        color: Rgb,
        /// Width, pixels.
        width: f64,
    },
    /// An open polyline.
    Polyline {
        /// What it shows.
        class: &'static str,
        /// Vertices.
        points: Vec<(f64, f64)>,
        /// Colour.
        color: Rgb,
        /// Width, pixels.
        width: f64,
    },
    /// A filled polygon.
    Polygon {
        /// What it shows.
        class: &'static str,
        /// Vertices.
        points: Vec<(f64, f64)>,
        /// Fill colour.
        fill: Rgb,
    },
    /// An axis-aligned filled rectangle.
    Rect {
        /// What it shows.
        class: &'static str,
        /// Top-left corner.
        a: (f64, f64),
        /// Bottom-right corner.
        b: (f64, f64),
        /// Fill colour.
        fill: Rgb,
    },
    /// Text anchored at its left baseline (or centred when `centre`).
    Text {
        /// What it shows.
        class: &'static str,
        /// Anchor.
        at: (f64, f64),
        /// The text.
        text: String,
        /// Font size, pixels.
        size: f64,
        /// Centre horizontally on the anchor.
        centre: bool,
    },
}

impl Shape {
    /// The shape's class.
    pub fn class(&self) -> &'static str {
        match self {
            Shape::Circle { class, .. }
            | Shape::Line { class, .. }
            | Shape::Polyline { class, .. }
            | Shape::Polygon { class, .. }
            | Shape::Rect { class, .. }
            | Shape::Text { class, .. } => class,
        }
    }
}

/// A figure: a white canvas of `width × height` pixels and its shapes in drawing order.
#[derive(Clone, Debug, PartialEq)]
pub struct Canvas {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Shapes, painted in order.
    pub shapes: Vec<Shape>,
}

/// Why a figure could not be written.
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// The output's extension is neither `.svg` nor `.png`.
    #[error("cannot tell the figure format of '{0}': the file name must end in .svg or .png")]
    Format(String),
    /// Writing failed.
    #[error("cannot write figure {path}: {message}")]
    Write {
        /// The path.
        path: String,
        /// The cause.
        message: String,
    },
    /// The requested size is unusable.
    #[error("figure size {0}x{1} is out of range (each side 100 to 8000 pixels)")]
    Size(u32, u32),
}

impl Canvas {
    /// An empty canvas; sides must be within 100..=8000 pixels.
    pub fn new(width: u32, height: u32) -> Result<Self, FigureError> {
        if !(100..=8000).contains(&width) || !(100..=8000).contains(&height) {
            return Err(FigureError::Size(width, height));
        }
        Ok(Canvas {
            width,
            height,
            shapes: Vec::new(),
        })
    }

    /// The shapes of one class.
    pub fn of_class<'a>(&'a self, class: &'a str) -> impl Iterator<Item = &'a Shape> + 'a {
        self.shapes.iter().filter(move |s| s.class() == class)
    }

    /// Writes the figure as SVG or PNG, chosen by the file's extension, whole
    /// ([`crate::atomic`]: a failed write leaves any earlier file in place).
    pub fn save(&self, path: &Path) -> Result<(), FigureError> {
        let name = path.display().to_string();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let write_err = |message: String| FigureError::Write {
            path: name.clone(),
            message,
        };
        match ext.as_deref() {
            Some("svg") => crate::atomic::replace_with(path, |tmp| {
                std::fs::write(tmp, self.to_svg()).map_err(|e| e.to_string())
            })
            .map_err(write_err),
            Some("png") => {
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                    if !dir.is_dir() {
                        return Err(write_err(format!("no directory {}", dir.display())));
                    }
                }
                crate::atomic::replace_with(path, |tmp| self.draw_png(tmp)).map_err(write_err)
            }
            _ => Err(FigureError::Format(name)),
        }
    }

    /// The figure as an SVG document.
    pub fn to_svg(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, sans-serif">"#,
            w = self.width,
            h = self.height
        );
        let _ = writeln!(
            s,
            r#"<rect class="background" x="0" y="0" width="{}" height="{}" fill="white"/>"#,
            self.width, self.height
        );
        for shape in &self.shapes {
            match shape {
                Shape::Circle {
                    class,
                    c,
                    r,
                    fill,
                    stroke,
                } => {
                    let fill = fill.map_or("fill=\"none\"".to_string(), |(c, o)| {
                        format!("fill=\"{}\" fill-opacity=\"{o:.3}\"", hex(c))
                    });
                    let stroke = stroke.map_or(String::new(), |(c, w)| {
                        format!(" stroke=\"{}\" stroke-width=\"{w:.2}\"", hex(c))
                    });
                    let _ = writeln!(
                        s,
                        r#"<circle class="{class}" cx="{:.2}" cy="{:.2}" r="{r:.2}" {fill}{stroke}/>"#,
                        c.0, c.1
                    );
                }
                Shape::Line {
                    class,
                    a,
                    b,
                    color,
                    width,
                } => {
                    let _ = writeln!(
                        s,
                        r#"<line class="{class}" x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{}" stroke-width="{width:.2}" stroke-linecap="round"/>"#,
                        a.0,
                        a.1,
                        b.0,
                        b.1,
                        hex(*color)
                    );
                }
                Shape::Polyline {
                    class,
                    points,
                    color,
                    width,
                } => {
                    let _ = writeln!(
                        s,
                        r#"<polyline class="{class}" points="{}" fill="none" stroke="{}" stroke-width="{width:.2}" stroke-linejoin="round"/>"#,
                        points_attr(points),
                        hex(*color)
                    );
                }
                Shape::Polygon {
                    class,
                    points,
                    fill,
                } => {
                    let _ = writeln!(
                        s,
                        r#"<polygon class="{class}" points="{}" fill="{}"/>"#,
                        points_attr(points),
                        hex(*fill)
                    );
                }
                Shape::Rect { class, a, b, fill } => {
                    let _ = writeln!(
                        s,
                        r#"<rect class="{class}" x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}"/>"#,
                        a.0,
                        a.1,
                        b.0 - a.0,
                        b.1 - a.1,
                        hex(*fill)
                    );
                }
                Shape::Text {
                    class,
                    at,
                    text,
                    size,
                    centre,
                } => {
                    let anchor = if *centre { "middle" } else { "start" };
                    let _ = writeln!(
                        s,
                        r#"<text class="{class}" x="{:.2}" y="{:.2}" font-size="{size:.1}" text-anchor="{anchor}">{}</text>"#,
                        at.0,
                        at.1,
                        escape(text)
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }

    fn draw_png(&self, path: &Path) -> Result<(), String> {
        register_font();
        let root = BitMapBackend::new(path, (self.width, self.height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let px = |p: (f64, f64)| (p.0.round() as i32, p.1.round() as i32);
        let rgb = |c: Rgb| RGBColor(c.0, c.1, c.2);
        for shape in &self.shapes {
            let r = match shape {
                Shape::Circle {
                    c, r, fill, stroke, ..
                } => {
                    let mut result = Ok(());
                    if let Some((col, o)) = fill {
                        result = root.draw(&Circle::new(
                            px(*c),
                            r.round() as i32,
                            rgb(*col).mix(*o).filled(),
                        ));
                    }
                    if let Some((col, w)) = stroke {
                        result = result.and(root.draw(&Circle::new(
                            px(*c),
                            r.round() as i32,
                            rgb(*col).stroke_width(w.round().max(1.0) as u32),
                        )));
                    }
                    result
                }
                Shape::Line {
                    a, b, color, width, ..
                } => root.draw(&PathElement::new(
                    vec![px(*a), px(*b)],
                    rgb(*color).stroke_width(width.round().max(1.0) as u32),
                )),
                Shape::Polyline {
                    points,
                    color,
                    width,
                    ..
                } => root.draw(&PathElement::new(
                    points.iter().map(|&p| px(p)).collect::<Vec<_>>(),
                    rgb(*color).stroke_width(width.round().max(1.0) as u32),
                )),
                Shape::Polygon { points, fill, .. } => root.draw(&plotters::element::Polygon::new(
                    points.iter().map(|&p| px(p)).collect::<Vec<_>>(),
                    rgb(*fill).filled(),
                )),
                Shape::Rect { a, b, fill, .. } => {
                    root.draw(&Rectangle::new([px(*a), px(*b)], rgb(*fill).filled()))
                }
                Shape::Text {
                    at,
                    text,
                    size,
                    centre,
                    ..
                } => {
                    let style = ("sans-serif", *size).into_font().color(&BLACK);
                    let style = if *centre {
                        style.pos(plotters::style::text_anchor::Pos::new(
                            plotters::style::text_anchor::HPos::Center,
                            plotters::style::text_anchor::VPos::Bottom,
                        ))
                    } else {
                        style.pos(plotters::style::text_anchor::Pos::new(
                            plotters::style::text_anchor::HPos::Left,
                            plotters::style::text_anchor::VPos::Bottom,
                        ))
                    };
                    root.draw(&plotters::element::Text::new(text.clone(), px(*at), style))
                }
            };
            r.map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())
    }
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/DejaVuSans.ttf");
        // The bundled font is a valid TrueType file; if registration ever failed, text would
        // be missing from PNGs but nothing else would change.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, bytes);
    });
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

fn points_attr(points: &[(f64, f64)]) -> String {
    points
        .iter()
        .map(|p| format!("{:.2},{:.2}", p.0, p.1))
        .collect::<Vec<_>>()
        .join(" ")
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A perceptually ordered colour map (viridis anchors, linear in between); `t ∈ [0, 1]`.
///
/// ```
/// use truecost::figures::canvas::viridis;
/// assert_eq!(viridis(0.0), (68, 1, 84));
/// assert_eq!(viridis(1.0), (253, 231, 37));
/// ```
pub fn viridis(t: f64) -> Rgb {
    const ANCHORS: [Rgb; 5] = [
        (68, 1, 84),
        (59, 82, 139),
        (33, 145, 140),
        (94, 201, 98),
        (253, 231, 37),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let x = t * (ANCHORS.len() - 1) as f64;
    let i = (x.floor() as usize).min(ANCHORS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    let mix = |p: u8, q: u8| (p as f64 + (q as f64 - p as f64) * f).round() as u8;
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

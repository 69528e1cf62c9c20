//! Line charts for the experiment plots: series of points against a numeric axis,
//! with axis labels, ticks, a legend, and a caption naming the model and seed.

use super::canvas::{Canvas, FigureError, Rgb, Shape};
use super::wrap;

/// One named series.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend entry.
    pub name: String,
    /// Points `(x, y)`; non-finite `y` values are skipped (e.g. "never reached").
    pub points: Vec<(f64, f64)>,
}

/// A line chart.
#[derive(Clone, Debug, PartialEq)]
pub struct LineChart {
    /// Title.
    pub title: String,
    /// Caption: model, seed, samples — where the numbers come from.
    pub caption: String,
    /// X-axis label.
    pub x_label: String,
    /// Y-axis label.
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
    /// Named x positions: when not empty, x value `k` stands for `x_categories[k]` and the x
    /// axis is labelled with these names instead of numbers (e.g. ρ = 0.99, 1/n^0.8).
    pub x_categories: Vec<String>,
    /// A fixed y range (e.g. `[0, 1]` for rates); `None`: from the data, with 0 included.
    pub y_range: Option<(f64, f64)>,
}

/// Colours for up to ten series (then repeated).
const PALETTE: [Rgb; 10] = [
    (31, 119, 180),
    (255, 127, 14),
    (44, 160, 44),
    (214, 39, 40),
    (148, 103, 189),
    (140, 86, 75),
    (227, 119, 194),
    (127, 127, 127),
    (188, 189, 34),
    (23, 190, 207),
];

const LEFT: f64 = 80.0;
const RIGHT: f64 = 190.0;
const TOP: f64 = 65.0;
const BOTTOM: f64 = 105.0;

impl LineChart {
    /// Lays the chart out on a `width × height` canvas. Each series becomes one polyline of
    /// class `series` and one point marker of class `marker` per finite point.
    ///
    /// ```
    /// use truecost::figures::chart::{LineChart, Series};
    /// let chart = LineChart { title: "t".into(), caption: "c".into(), x_label: "ε".into(),
    ///     y_label: "y".into(), series: vec![Series { name: "a".into(),
    ///     points: vec![(0.0, 1.0), (0.5, 2.0), (1.0, f64::NAN)] }], x_categories: vec![], y_range: None };
    /// let canvas = chart.draw(600, 400).unwrap();
    /// assert_eq!(canvas.of_class("series").count(), 1);
    /// assert_eq!(canvas.of_class("marker").count(), 2);
    /// ```
    pub fn draw(&self, width: u32, height: u32) -> Result<Canvas, FigureError> {
        let mut canvas = Canvas::new(width, height)?;
        let (w, h) = (f64::from(width), f64::from(height));
        let finite: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().copied())
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        let (x0, x1) = if self.x_categories.is_empty() {
            span(finite.iter().map(|p| p.0))
        } else {
            (-0.5, self.x_categories.len() as f64 - 0.5)
        };
        let (y0, y1) = self
            .y_range
            .unwrap_or_else(|| span(finite.iter().map(|p| p.1).chain([0.0])));
        // The caption is wrapped at '; ' boundaries into lines of about 130 characters, below
        // the x-axis label.
        let lines = wrap(&self.caption, 130);
        let bottom = BOTTOM + 15.0 * lines.len().saturating_sub(2) as f64;
        let (px0, px1, py0, py1) = (LEFT, w - RIGHT, h - bottom, TOP);
        let to_px = |(x, y): (f64, f64)| {
            (
                px0 + (x - x0) / (x1 - x0) * (px1 - px0),
                py0 + (y - y0) / (y1 - y0) * (py1 - py0),
            )
        };
        let shapes = &mut canvas.shapes;
        for (class, a, b) in [
            ("axis", (px0, py0), (px1, py0)),
            ("axis", (px0, py0), (px0, py1)),
        ] {
            shapes.push(Shape::Line {
                class,
                a,
                b,
                color: (0, 0, 0),
                width: 1.0,
            });
        }
        let x_ticks: Vec<(f64, String)> = if self.x_categories.is_empty() {
            ticks(x0, x1)
                .into_iter()
                .map(|t| (t, tick_text(t)))
                .collect()
        } else {
            (0..self.x_categories.len())
                .map(|k| (k as f64, self.x_categories[k].clone()))
                .collect()
        };
        for ((t, text), is_x) in x_ticks.into_iter().map(|t| (t, true)).chain(
            ticks(y0, y1)
                .into_iter()
                .map(|t| ((t, tick_text(t)), false)),
        ) {
            let (at, a, b) = if is_x {
                let p = to_px((t, y0));
                ((p.0, py0 + 20.0), p, (p.0, py0 + 5.0))
            } else {
                let p = to_px((x0, t));
                ((px0 - 10.0, p.1 + 4.0), p, (px0 - 5.0, p.1))
            };
            shapes.push(Shape::Line {
                class: "tick",
                a,
                b,
                color: (0, 0, 0),
                width: 1.0,
            });
            shapes.push(Shape::Text {
                class: "tick-label",
                at: if is_x { at } else { (at.0 - 30.0, at.1) },
                text,
                size: 11.0,
                centre: is_x,
            });
        }
        shapes.push(Shape::Text {
            class: "x-label",
            at: ((px0 + px1) / 2.0, py0 + 45.0),
            text: self.x_label.clone(),
            size: 13.0,
            centre: true,
        });
        shapes.push(Shape::Text {
            class: "y-label",
            at: (10.0, TOP - 14.0),
            text: self.y_label.clone(),
            size: 13.0,
            centre: false,
        });
        for (i, s) in self.series.iter().enumerate() {
            let color = PALETTE[i % PALETTE.len()];
            let points: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .map(to_px)
                .collect();
            for &c in &points {
                shapes.push(Shape::Circle {
                    class: "marker",
                    c,
                    r: 3.0,
                    fill: Some((color, 1.0)),
                    stroke: None,
                });
            }
            shapes.push(Shape::Polyline {
                class: "series",
                points,
                color,
                width: 2.0,
            });
            let y = TOP + 10.0 + 18.0 * i as f64;
            shapes.push(Shape::Line {
                class: "legend",
                a: (w - RIGHT + 15.0, y),
                b: (w - RIGHT + 35.0, y),
                color,
                width: 2.0,
            });
            shapes.push(Shape::Text {
                class: "legend-label",
                at: (w - RIGHT + 40.0, y + 4.0),
                text: s.name.clone(),
                size: 11.0,
                centre: false,
            });
        }
        shapes.push(Shape::Text {
            class: "title",
            at: (LEFT, 30.0),
            text: self.title.clone(),
            size: 16.0,
            centre: false,
        });
        for (k, line) in lines.iter().enumerate() {
            shapes.push(Shape::Text {
                class: "caption",
                at: (10.0, h - 12.0 - 15.0 * (lines.len() - 1 - k) as f64),
                text: line.clone(),
                size: 11.0,
                centre: false,
            });
        }
        Ok(canvas)
    }
}

/// The range of the values, widened when empty or degenerate.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    if !lo.is_finite() {
        (0.0, 1.0)
    } else if hi - lo < 1e-12 {
        (lo - 0.5, hi + 0.5)
    } else {
        (lo, hi)
    }
}

/// About five round tick values within `[lo, hi]`.
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let raw = (hi - lo) / 5.0;
    let magnitude = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * magnitude)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * magnitude);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

fn tick_text(t: f64) -> String {
    if t == 0.0 {
        "0".into()
    } else if t.abs() >= 1e5 || t.abs() < 1e-3 {
        format!("{t:.1e}")
    } else if t.fract().abs() < 1e-9 {
        format!("{t:.0}")
    } else {
        let s = format!("{t:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        assert_eq!(
            ticks(0.0, 1.0),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        let t = ticks(3.0, 97.0);
        assert!(t.iter().all(|&x| (3.0..=97.0).contains(&x)));
        assert_eq!(t, vec![20.0, 40.0, 60.0, 80.0]);
    }

    #[test]
    fn legend_has_one_entry_per_series() {
        let chart = LineChart {
            title: "t".into(),
            caption: "model: exact; seed 1".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: (0..3)
                .map(|i| Series {
                    name: format!("s{i}"),
                    points: vec![(0.0, i as f64), (1.0, 2.0 * i as f64)],
                })
                .collect(),
            x_categories: vec![],
            y_range: None,
        };
        let c = chart.draw(700, 500).unwrap();
        assert_eq!(c.of_class("legend").count(), 3);
        assert_eq!(c.of_class("legend-label").count(), 3);
        assert_eq!(c.of_class("marker").count(), 6);
        assert!(c.to_svg().contains("seed 1"));
        assert_eq!(wrap("aa; bb; cc", 6), vec!["aa; bb", "cc"]);
    }

    #[test]
    fn categories_label_the_x_axis() {
        let chart = LineChart {
            title: "t".into(),
            caption: "c".into(),
            x_label: "ρ".into(),
            y_label: "y".into(),
            series: vec![Series {
                name: "a".into(),
                points: vec![(0.0, 1.0), (1.0, 2.0)],
            }],
            x_categories: vec!["0.99".into(), "1/n^0.8".into()],
            y_range: Some((0.0, 1.0)),
        };
        let c = chart.draw(700, 500).unwrap();
        let svg = c.to_svg();
        assert!(svg.contains(">0.99<") && svg.contains(">1/n^0.8<"), "{svg}");
        // Two x ticks (the categories) plus the numeric y ticks.
        let x_labels = c
            .of_class("tick-label")
            .filter(
                |s| matches!(s, Shape::Text { text, .. } if text == "0.99" || text == "1/n^0.8"),
            )
            .count();
        assert_eq!(x_labels, 2);
    }
}

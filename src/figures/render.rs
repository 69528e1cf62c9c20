//! The paper's problem figure: obstacle discs, allowed moves, start and goal, with an optional
//! overlay (optimal path, cost-to-go heat map with colour bar, policy arrows, every optimal
//! action with ties and moves into walls and a legend, visit counts).

use super::canvas::{viridis, Canvas, FigureError, Rgb, Shape};
use crate::problems::geometry::Disc;

/// What a problem figure shows, in world coordinates (y grows upwards, as in the paper's plots).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// First caption line (problem and mode).
    pub title: String,
    /// Second caption line (model, planner, seed: where the numbers come from).
    pub caption: String,
    /// World position of every state.
    pub positions: Vec<(f64, f64)>,
    /// The world's extent: `[0, w] × [0, h]`.
    pub extent: (f64, f64),
    /// Disc obstacles.
    pub obstacles: Vec<Disc>,
    /// Allowed moves, each unordered pair once.
    pub moves: Vec<(usize, usize)>,
    /// `x1` (`None`: no single initial state to mark, e.g. a Taxi slice).
    pub initial: Option<usize>,
    /// Goals.
    pub goals: Vec<usize>,
    /// Wall segments in world coordinates (a map's walls; drawn thick and dark).
    pub walls: Vec<((f64, f64), (f64, f64))>,
    /// Text marks in world coordinates (depot letters, pick-up and drop-off marks).
    pub marks: Vec<Mark>,
}

/// A text mark on a figure: its SVG class, world position and text.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// The SVG class (`depot`, `passenger`, `pickup`, `dropoff`, …).
    pub class: &'static str,
    /// Where, in world coordinates (the text is centred there).
    pub at: (f64, f64),
    /// The text.
    pub text: String,
    /// Font size in pixels.
    pub size: f64,
}

/// An overlay and its data.
#[derive(Clone, Debug, PartialEq)]
pub enum Overlay {
    /// The bare problem.
    None,
    /// A path from `x1` (state ids).
    Path(Vec<usize>),
    /// A value per state (`None`: unknown or `+∞`), with a label for the colour bar and the
    /// exact extreme values as text.
    Values {
        /// Values to colour by.
        values: Vec<Option<f64>>,
        /// What they are (e.g. "G* (exact)").
        label: String,
    },
    /// The successor chosen at every state (`None`: no action; a goal names itself).
    Policy(Vec<Option<usize>>),
    /// Every optimal action at every state, with a legend of what the glyphs mean: several
    /// glyphs at one state are tied optimal actions.
    Actions {
        /// Per state, one glyph per optimal action (empty: nothing drawn — a goal, an ended
        /// episode, a state where the objective prescribes nothing).
        actions: Vec<Vec<ActionGlyph>>,
        /// The legend, drawn under the map in this order.
        legend: Vec<LegendEntry>,
    },
    /// Visit counts per unordered move.
    Visits(Vec<((usize, usize), u64)>),
}

/// How one optimal action is drawn at its state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ActionGlyph {
    /// The action's intended move leads to this state: an arrow towards it.
    Move(usize),
    /// The action's intended move runs into a wall or the border, the agent stays in place:
    /// a short stroke from the state towards the obstacle, ending in a bar across it.
    Blocked {
        /// The direction pushed, one grid step in world coordinates (`(1, 0)` east, `(0, 1)`
        /// north; y grows upwards).
        toward: (i8, i8),
    },
}

/// What a legend line shows next to its text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LegendKey {
    /// One arrow.
    Arrow,
    /// Two arrows from one point (tied optimal actions).
    Tie,
    /// A stroke ending in a bar ([`ActionGlyph::Blocked`]).
    Blocked,
}

/// One legend line: a key drawn as the figure draws it, and what it means.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LegendEntry {
    /// The key.
    pub key: LegendKey,
    /// The meaning, one line.
    pub text: String,
}

const LEFT: f64 = 30.0;
const RIGHT: f64 = 110.0;
const TOP: f64 = 50.0;
const BOTTOM: f64 = 60.0;
const GREY: Rgb = (170, 170, 170);
const DARK: Rgb = (40, 40, 40);

/// Lays out the figure on a `width × height` canvas.
///
/// ```
/// use truecost::figures::render::{draw, Overlay, Scene};
/// let scene = Scene { title: "t".into(), caption: "c".into(),
///     positions: vec![(0.0, 0.0), (1.0, 0.0)], extent: (1.0, 1.0), obstacles: vec![],
///     moves: vec![(0, 1)], initial: Some(0), goals: vec![1], walls: vec![], marks: vec![] };
/// let canvas = draw(&scene, &Overlay::Path(vec![0, 1]), 400, 400).unwrap();
/// assert_eq!(canvas.of_class("move").count(), 1);
/// assert_eq!(canvas.of_class("path").count(), 1);
/// ```
pub fn draw(
    scene: &Scene,
    overlay: &Overlay,
    width: u32,
    height: u32,
) -> Result<Canvas, FigureError> {
    let mut canvas = Canvas::new(width, height)?;
    let (w, h) = (f64::from(width), f64::from(height));
    // The caption is wrapped at "; " boundaries to the canvas width (about 6.5 px a character).
    let lines = super::wrap(&scene.caption, ((w - 2.0 * LEFT) / 6.5).max(20.0) as usize);
    let legend: &[LegendEntry] = match overlay {
        Overlay::Actions { legend, .. } => legend,
        _ => &[],
    };
    // Under the map: the legend, one line per entry, above the caption.
    let legend_top =
        h - BOTTOM.max(14.0 * lines.len() as f64 + 20.0) - LEGEND_LINE * legend.len() as f64;
    let scale =
        ((w - LEFT - RIGHT) / scene.extent.0).min((legend_top - TOP).max(10.0) / scene.extent.1);
    let to_px = |(x, y): (f64, f64)| (LEFT + x * scale, TOP + (scene.extent.1 - y) * scale);
    let node = |v: usize| to_px(scene.positions[v]);
    let shapes = &mut canvas.shapes;

    shapes.push(Shape::Rect {
        class: "world",
        a: to_px((0.0, scene.extent.1)),
        b: to_px((scene.extent.0, 0.0)),
        fill: (250, 250, 250),
    });
    if let Overlay::Values { values, label } = overlay {
        value_cells(shapes, scene, values, label, &to_px, scale, w);
    }
    for d in &scene.obstacles {
        shapes.push(Shape::Circle {
            class: "obstacle",
            c: to_px((d.cx as f64, d.cy as f64)),
            r: d.r as f64 * scale,
            fill: Some(((120, 120, 120), 0.35)),
            stroke: Some(((80, 80, 80), 1.0)),
        });
    }
    let visits = match overlay {
        Overlay::Visits(v) => Some(v),
        _ => None,
    };
    for &(a, b) in &scene.moves {
        shapes.push(Shape::Line {
            class: "move",
            a: node(a),
            b: node(b),
            color: if visits.is_some() {
                (225, 225, 225)
            } else {
                GREY
            },
            width: 1.0,
        });
    }
    if let Some(visits) = visits {
        let max = visits.iter().map(|&(_, c)| c).max().unwrap_or(0).max(1) as f64;
        for &((a, b), count) in visits.iter().filter(|&&(_, c)| c > 0) {
            let t = (count as f64).ln_1p() / max.ln_1p();
            shapes.push(Shape::Line {
                class: "visits",
                a: node(a),
                b: node(b),
                color: viridis(t),
                width: 1.0 + 4.0 * t,
            });
        }
        colour_bar(
            shapes,
            w,
            "visits (log scale)",
            "0",
            &format!("{}", max as u64),
        );
    }
    for &(a, b) in &scene.walls {
        shapes.push(Shape::Line {
            class: "wall",
            a: to_px(a),
            b: to_px(b),
            color: DARK,
            width: 5.0,
        });
    }
    for v in 0..scene.positions.len() {
        shapes.push(Shape::Circle {
            class: "node",
            c: node(v),
            r: 1.5,
            fill: Some((DARK, 0.6)),
            stroke: None,
        });
    }
    match overlay {
        Overlay::Path(path) if !path.is_empty() => shapes.push(Shape::Polyline {
            class: "path",
            points: path.iter().map(|&v| node(v)).collect(),
            color: (215, 48, 39),
            width: 3.0,
        }),
        Overlay::Policy(policy) => {
            for (x, next) in policy.iter().enumerate() {
                if let Some(y) = next.filter(|&y| y != x) {
                    arrow(shapes, node(x), node(y), POLICY_CLASSES);
                }
            }
        }
        Overlay::Actions { actions, .. } => {
            let step = min_spacing(&scene.positions) * scale;
            for (x, glyphs) in actions.iter().enumerate() {
                for glyph in glyphs {
                    match *glyph {
                        ActionGlyph::Move(y) if y != x => {
                            arrow(shapes, node(x), node(y), POLICY_CLASSES)
                        }
                        ActionGlyph::Move(_) => {}
                        ActionGlyph::Blocked { toward } => {
                            blocked(shapes, node(x), toward, step, BLOCKED_CLASSES)
                        }
                    }
                }
            }
        }
        _ => {}
    }
    for (k, entry) in legend.iter().enumerate() {
        let y = legend_top + LEGEND_LINE * (k as f64 + 0.5);
        let key = (LEFT + 4.0, y);
        match entry.key {
            LegendKey::Arrow => arrow(shapes, key, (key.0 + 40.0, y), LEGEND_CLASSES),
            LegendKey::Tie => {
                arrow(
                    shapes,
                    (key.0, y + 4.0),
                    (key.0 + 40.0, y + 4.0),
                    LEGEND_CLASSES,
                );
                arrow(
                    shapes,
                    (key.0, y + 4.0),
                    (key.0 + 36.0, y - 14.0),
                    LEGEND_CLASSES,
                );
            }
            LegendKey::Blocked => blocked(shapes, key, (1, 0), 56.0, LEGEND_CLASSES),
        }
        shapes.push(Shape::Text {
            class: "legend",
            at: (LEFT + 44.0, y + 4.0),
            text: entry.text.clone(),
            size: 12.0,
            centre: false,
        });
    }
    for m in &scene.marks {
        shapes.push(Shape::Text {
            class: m.class,
            at: to_px(m.at),
            text: m.text.clone(),
            size: m.size,
            centre: true,
        });
    }
    for (v, class, color, label) in scene
        .initial
        .map(|x| (x, "start", (26, 152, 80), "x1"))
        .into_iter()
        .chain(
            scene
                .goals
                .iter()
                .map(|&g| (g, "goal", (215, 48, 39), "goal")),
        )
    {
        let c = node(v);
        shapes.push(Shape::Circle {
            class,
            c,
            r: 6.0,
            fill: Some((color, 1.0)),
            stroke: Some(((255, 255, 255), 1.5)),
        });
        shapes.push(Shape::Text {
            class: "label",
            at: (c.0 + 8.0, c.1 - 6.0),
            text: label.to_string(),
            size: 13.0,
            centre: false,
        });
    }
    shapes.push(Shape::Text {
        class: "title",
        at: (LEFT, 30.0),
        text: scene.title.clone(),
        size: 18.0,
        centre: false,
    });
    for (k, line) in lines.iter().enumerate() {
        shapes.push(Shape::Text {
            class: "caption",
            at: (LEFT, h - 10.0 - 14.0 * (lines.len() - 1 - k) as f64),
            text: line.clone(),
            size: 12.0,
            centre: false,
        });
    }
    Ok(canvas)
}

/// Height of one legend line, pixels.
const LEGEND_LINE: f64 = 20.0;
/// The classes of a drawn arrow (shaft, head) and of a blocked move (stroke, bar).
const POLICY_CLASSES: (&str, &str) = ("policy", "arrowhead");
const BLOCKED_CLASSES: (&str, &str) = ("blocked", "blocked-bar");
const LEGEND_CLASSES: (&str, &str) = ("legend-key", "legend-key");
const ARROW: Rgb = (33, 102, 172);

/// An arrow from `a` reaching past the middle towards `b` (so that arrows of neighbouring
/// states in opposite directions do not overlap).
fn arrow(
    shapes: &mut Vec<Shape>,
    a: (f64, f64),
    b: (f64, f64),
    classes: (&'static str, &'static str),
) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = (dx * dx + dy * dy).sqrt().max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let tip = (a.0 + dx * 0.55, a.1 + dy * 0.55);
    let head = (len * 0.18).clamp(3.0, 8.0);
    shapes.push(Shape::Line {
        class: classes.0,
        a,
        b: tip,
        color: ARROW,
        width: 1.5,
    });
    shapes.push(Shape::Polygon {
        class: classes.1,
        points: vec![
            (tip.0 + ux * head, tip.1 + uy * head),
            (tip.0 - uy * head * 0.6, tip.1 + ux * head * 0.6),
            (tip.0 + uy * head * 0.6, tip.1 - ux * head * 0.6),
        ],
        fill: ARROW,
    });
}

/// A move into a wall or the border from the state at `a` (pixels), `step` pixels between
/// neighbouring states: a stroke towards the obstacle stopping short of the cell's edge, and a
/// bar across its end (the agent stays in place).
fn blocked(
    shapes: &mut Vec<Shape>,
    a: (f64, f64),
    toward: (i8, i8),
    step: f64,
    classes: (&'static str, &'static str),
) {
    let (dx, dy) = (f64::from(toward.0), -f64::from(toward.1));
    let len = (dx * dx + dy * dy).sqrt().max(1e-9);
    let (ux, uy) = (dx / len, dy / len);
    let reach = (step * 0.38).max(4.0);
    let half = (step * 0.14).clamp(2.5, 8.0);
    let end = (a.0 + ux * reach, a.1 + uy * reach);
    shapes.push(Shape::Line {
        class: classes.0,
        a,
        b: end,
        color: ARROW,
        width: 1.5,
    });
    shapes.push(Shape::Line {
        class: classes.1,
        a: (end.0 - uy * half, end.1 + ux * half),
        b: (end.0 + uy * half, end.1 - ux * half),
        color: ARROW,
        width: 2.5,
    });
}

fn value_cells(
    shapes: &mut Vec<Shape>,
    scene: &Scene,
    values: &[Option<f64>],
    label: &str,
    to_px: &dyn Fn((f64, f64)) -> (f64, f64),
    scale: f64,
    w: f64,
) {
    let finite: Vec<f64> = values
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let lo = finite.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // Cell size: the smallest distance between two states (a grid step), at most 40 px.
    let half = (min_spacing(&scene.positions) * scale / 2.0).clamp(2.0, 20.0);
    for (v, value) in values.iter().enumerate() {
        let c = to_px(scene.positions[v]);
        let fill = match value {
            Some(x) if x.is_finite() => {
                let t = if hi > lo { (x - lo) / (hi - lo) } else { 0.0 };
                viridis(t)
            }
            _ => (235, 235, 235),
        };
        let class = if value.is_some_and(|x| x.is_finite()) {
            "value"
        } else {
            "value-none"
        };
        shapes.push(Shape::Rect {
            class,
            a: (c.0 - half, c.1 - half),
            b: (c.0 + half, c.1 + half),
            fill,
        });
    }
    let (lo_text, hi_text) = if finite.is_empty() {
        ("none".to_string(), "none".to_string())
    } else {
        (short(lo), short(hi))
    };
    colour_bar(shapes, w, label, &lo_text, &hi_text);
}

fn colour_bar(shapes: &mut Vec<Shape>, w: f64, label: &str, lo: &str, hi: &str) {
    let (x, top, bottom) = (w - RIGHT + 30.0, TOP + 30.0, TOP + 330.0);
    let steps = 64;
    for i in 0..steps {
        let t = i as f64 / (steps - 1) as f64;
        let y1 = bottom - (bottom - top) * (i as f64 + 1.0) / steps as f64;
        let y0 = bottom - (bottom - top) * i as f64 / steps as f64;
        shapes.push(Shape::Rect {
            class: "colorbar",
            a: (x, y1),
            b: (x + 18.0, y0),
            fill: viridis(t),
        });
    }
    for (text, y) in [(hi, top + 4.0), (lo, bottom + 4.0)] {
        shapes.push(Shape::Text {
            class: "colorbar-label",
            at: (x + 22.0, y),
            text: text.to_string(),
            size: 11.0,
            centre: false,
        });
    }
    shapes.push(Shape::Text {
        class: "colorbar-label",
        at: (x - 6.0, top - 12.0),
        text: label.to_string(),
        size: 11.0,
        centre: false,
    });
}

fn min_spacing(points: &[(f64, f64)]) -> f64 {
    let mut best = f64::INFINITY;
    // Grids are small (≤ a few hundred states): the quadratic scan is fine for a drawing.
    for (i, a) in points.iter().enumerate() {
        for b in &points[i + 1..] {
            let d = ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
            if d > 0.0 && d < best {
                best = d;
            }
        }
    }
    if best.is_finite() {
        best
    } else {
        1.0
    }
}

fn short(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{x:.0}")
    } else {
        format!("{x:.4}")
    }
}

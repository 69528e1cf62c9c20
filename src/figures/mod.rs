//! Figures: the paper's problem figure with overlays, drawn as classed shapes and
//! written as SVG or PNG. Pure Rust; the PNG text uses the bundled DejaVu Sans font
//! (`assets/`, Bitstream Vera licence). [`envs`] draws the Gymnasium benchmarks' maps with
//! their exact policies and values.

pub mod canvas;
pub mod chart;
pub mod envs;
pub mod plots;
pub mod policy;
pub mod render;

use crate::model::Problem;
use crate::planning::Mode;
use crate::problems::{reference_coordinates, GridLayout, SIDE};
use crate::stochastic::StochasticProblem;
use render::Scene;

/// The scene of a paper grid problem: exact grid points `(800·col/19, 800·row/19)` in exact
/// mode, the reference code's `f64` coordinates in reference mode.
///
/// ```
/// use truecost::figures::grid_scene;
/// use truecost::planning::Mode;
/// use truecost::problems::GridLayout;
/// let s = grid_scene(&GridLayout::exact(0).unwrap(), Mode::Exact);
/// assert_eq!(s.obstacles.len(), 0);
/// assert_eq!(s.moves.len(), 760);
/// ```
pub fn grid_scene(layout: &GridLayout, mode: Mode) -> Scene {
    let reference = reference_coordinates();
    let coordinate = |k: usize| match mode {
        Mode::Exact => 800.0 * k as f64 / 19.0,
        Mode::Reference => reference[k],
    };
    let positions = (0..layout.neighbours.len())
        .map(|i| (coordinate(i % SIDE), coordinate(i / SIDE)))
        .collect();
    let moves = undirected_pairs(
        layout
            .neighbours
            .iter()
            .enumerate()
            .flat_map(|(i, list)| list.iter().map(move |&j| (i, j))),
    );
    Scene {
        title: String::new(),
        caption: String::new(),
        positions,
        extent: (800.0, 800.0),
        obstacles: layout.scenario.obstacles.clone(),
        moves,
        initial: Some(layout.initial),
        goals: vec![layout.goal],
        walls: Vec::new(),
        marks: Vec::new(),
    }
}

/// The scene of a user problem (no geometry): states on a circle, in index order.
pub fn file_scene(problem: &Problem) -> Scene {
    circle_scene(
        problem.states(),
        problem.initial(),
        problem.goals(),
        (0..problem.states()).flat_map(|x| problem.moves(x).iter().map(move |m| (x, m.successor))),
    )
}

/// The scene of a stochastic user problem: states on a circle, a segment between a state and
/// every possible outcome of its actions.
///
/// ```
/// use truecost::figures::stochastic_file_scene;
/// use truecost::stochastic::{file, NoiseModel, Predictability, StochasticProblem};
/// let line = file::read(concat!(env!("CARGO_MANIFEST_DIR"), "/problems/line.json").as_ref()).unwrap();
/// let file::ProblemFile::Deterministic(p) = line else { panic!() };
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// assert_eq!(stochastic_file_scene(&s).positions.len(), 4);
/// ```
pub fn stochastic_file_scene(problem: &StochasticProblem) -> Scene {
    circle_scene(
        problem.states(),
        problem.initial(),
        problem.goals(),
        (0..problem.action_total()).flat_map(|a| {
            let x = problem.state_of(a);
            problem.outcomes(a).iter().map(move |o| (x, o.successor))
        }),
    )
}

/// `n` states on a circle, in index order, with a segment per unordered pair of `edges`.
fn circle_scene(
    n: usize,
    initial: usize,
    goals: &[usize],
    edges: impl Iterator<Item = (usize, usize)>,
) -> Scene {
    let positions = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            (50.0 + 40.0 * a.cos(), 50.0 + 40.0 * a.sin())
        })
        .collect();
    Scene {
        title: String::new(),
        caption: String::new(),
        positions,
        extent: (100.0, 100.0),
        obstacles: Vec::new(),
        moves: undirected_pairs(edges),
        initial: Some(initial),
        goals: goals.to_vec(),
        walls: Vec::new(),
        marks: Vec::new(),
    }
}

/// Each unordered pair `{a, b}` with `a ≠ b` once, in first-seen order.
fn undirected_pairs(edges: impl Iterator<Item = (usize, usize)>) -> Vec<(usize, usize)> {
    let mut seen = std::collections::HashSet::new();
    edges
        .filter(|&(a, b)| a != b)
        .map(|(a, b)| (a.min(b), a.max(b)))
        .filter(|p| seen.insert(*p))
        .collect()
}

/// Splits text at "; " into lines of at most about `width` characters.
pub(crate) fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for part in text.split("; ") {
        match lines.last_mut() {
            Some(line) if line.chars().count() + part.chars().count() + 2 <= width => {
                line.push_str("; ");
                line.push_str(part);
            }
            _ => lines.push(part.to_string()),
        }
    }
    lines
}

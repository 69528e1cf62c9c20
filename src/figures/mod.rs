//! Figures (issue 6): the paper's problem figure with overlays, drawn as classed shapes and
//! written as SVG or PNG. Pure Rust; the PNG text uses the bundled DejaVu Sans font
//! (`assets/`, Bitstream Vera licence).

pub mod canvas;
pub mod chart;
pub mod plots;
pub mod render;

use crate::model::Problem;
use crate::planning::Mode;
use crate::problems::{reference_coordinates, GridLayout, SIDE};
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
        initial: layout.initial,
        goals: vec![layout.goal],
    }
}

/// The scene of a user problem (no geometry): states on a circle, in index order.
pub fn file_scene(problem: &Problem) -> Scene {
    let n = problem.states();
    let positions = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            (50.0 + 40.0 * a.cos(), 50.0 + 40.0 * a.sin())
        })
        .collect();
    let moves = undirected_pairs(
        (0..n).flat_map(|x| problem.moves(x).iter().map(move |m| (x, m.successor))),
    );
    Scene {
        title: String::new(),
        caption: String::new(),
        positions,
        extent: (100.0, 100.0),
        obstacles: Vec::new(),
        moves,
        initial: problem.initial(),
        goals: problem.goals().to_vec(),
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

//! The paper's 19 grid problems (docs/spec.md §5), built exactly, and their reference-mode twins
//! (docs/spec.md §7).
//!
//! Data: `data/problem_circles.txt`, three lines per problem (obstacle discs, initial point,
//! goal point) in an 800×800 world. Grid: 20×20 points, node `i = 20·row + col` at
//! `(800·col/19, 800·row/19)`; 4-neighbour moves in both directions where the segment is safe
//! ([`geometry`]). Initial and goal nodes are the nodes nearest the given points (lowest index
//! on ties). On problems 3, 13, 14, 16 the pocket behind the goal is removed.

pub mod geometry;

use std::collections::VecDeque;

use num_bigint::BigInt;

use crate::model::{Graph, Move, Problem};
use crate::value::Rational;
use geometry::{segment_safe, segment_safe_f64, Disc};

/// The paper's data file, compiled in.
pub const CIRCLES: &str = include_str!("../../data/problem_circles.txt");
/// Grid points per side.
pub const SIDE: usize = 20;
/// Grid nodes.
pub const GRID_NODES: usize = SIDE * SIDE;
/// The problems used by the paper's figures and tables.
pub const PAPER_PROBLEMS: [usize; 16] = [0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];
/// The problems whose pocket behind the goal is removed.
pub const PRUNED: [usize; 4] = [3, 13, 14, 16];

/// One problem of the data file.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Scenario {
    /// Disc obstacles.
    pub obstacles: Vec<Disc>,
    /// The initial point.
    pub start: (i64, i64),
    /// The goal point.
    pub goal: (i64, i64),
}

/// Errors in building a paper problem.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ProblemError {
    /// The data file is malformed.
    #[error("problem data line {line}: {message}")]
    Malformed {
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// No such problem.
    #[error("unknown problem {id}: the paper's problems are numbered 0 to {last}")]
    Unknown {
        /// The id asked for.
        id: usize,
        /// The last valid id.
        last: usize,
    },
}

/// The stage cost of a grid move in the exact model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum StepCost {
    /// 1 per move (the paper's text).
    #[default]
    Unit,
    /// The exact segment length, 800/19 per move.
    Euclidean,
}

/// A compass direction on the grid; `Up` decreases the row (towards `y = 0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// `col − 1`.
    Left,
    /// `row − 1`.
    Up,
    /// `row + 1`.
    Down,
    /// `col + 1`.
    Right,
}

/// The action order of every node: left, up, down, right (the reference code's order, used in
/// both modes so that they can be compared move by move).
pub const ORDER: [Direction; 4] = [
    Direction::Left,
    Direction::Up,
    Direction::Down,
    Direction::Right,
];
/// The reference code's order on the pruned problems: up, left, down, right.
pub const ORDER_PRUNED_REFERENCE: [Direction; 4] = [
    Direction::Up,
    Direction::Left,
    Direction::Down,
    Direction::Right,
];

/// The grid neighbour of node `i` in direction `d`, if inside the grid.
pub fn neighbour(i: usize, d: Direction) -> Option<usize> {
    let (row, col) = (i / SIDE, i % SIDE);
    match d {
        Direction::Left => (col > 0).then(|| i - 1),
        Direction::Right => (col + 1 < SIDE).then(|| i + 1),
        Direction::Up => (row > 0).then(|| i - SIDE),
        Direction::Down => (row + 1 < SIDE).then(|| i + SIDE),
    }
}

/// Parses the data file format (three lines per problem).
///
/// ```
/// let s = truecost::problems::parse_circles("[[397, 389, 240]]\n(73, 392)\n(733, 387)\n").unwrap();
/// assert_eq!(s[0].obstacles[0].r, 240);
/// assert_eq!(s[0].goal, (733, 387));
/// ```
pub fn parse_circles(text: &str) -> Result<Vec<Scenario>, ProblemError> {
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty())
        .collect();
    if lines.is_empty() || !lines.len().is_multiple_of(3) {
        return Err(ProblemError::Malformed {
            line: lines.last().map_or(1, |l| l.0),
            message: format!(
                "expected three lines per problem, found {} non-empty lines",
                lines.len()
            ),
        });
    }
    lines
        .chunks(3)
        .map(|chunk| {
            let (l0, discs) = chunk[0];
            let obstacles = parse_int_groups(discs, '[', ']', l0)?
                .into_iter()
                .map(|g| match g.as_slice() {
                    [cx, cy, r] if *r >= 0 => Ok(Disc {
                        cx: *cx,
                        cy: *cy,
                        r: *r,
                    }),
                    _ => Err(ProblemError::Malformed {
                        line: l0,
                        message: "a disc is [cx, cy, r] with r >= 0".into(),
                    }),
                })
                .collect::<Result<_, _>>()?;
            let point = |(l, t): (usize, &str)| -> Result<(i64, i64), ProblemError> {
                match parse_int_groups(t, '(', ')', l)?.as_slice() {
                    [g] if g.len() == 2 => Ok((g[0], g[1])),
                    _ => Err(ProblemError::Malformed {
                        line: l,
                        message: "a point is (x, y)".into(),
                    }),
                }
            };
            Ok(Scenario {
                obstacles,
                start: point(chunk[1])?,
                goal: point(chunk[2])?,
            })
        })
        .collect()
}

/// Parses groups such as `[1, 2, 3], [4, 5, 6]` (inside optional outer brackets) or `(1, 2)`.
fn parse_int_groups(
    text: &str,
    open: char,
    close: char,
    line: usize,
) -> Result<Vec<Vec<i64>>, ProblemError> {
    let bad = |m: &str| ProblemError::Malformed {
        line,
        message: m.to_string(),
    };
    let mut body = text.trim();
    if open == '[' {
        body = body
            .strip_prefix('[')
            .and_then(|b| b.strip_suffix(']'))
            .ok_or_else(|| bad("expected a list of discs such as [[cx, cy, r], ...]"))?
            .trim();
    }
    let mut groups = Vec::new();
    let mut rest = body;
    while !rest.is_empty() {
        let start = rest
            .strip_prefix(open)
            .ok_or_else(|| bad(&format!("expected '{open}'")))?;
        let end = start
            .find(close)
            .ok_or_else(|| bad(&format!("missing '{close}'")))?;
        let numbers = start[..end]
            .split(',')
            .map(|t| {
                t.trim()
                    .parse::<i64>()
                    .ok()
                    .filter(|v| v.abs() <= 1_000_000_000)
                    .ok_or_else(|| bad(&format!("'{}' is not an integer coordinate", t.trim())))
            })
            .collect::<Result<Vec<_>, _>>()?;
        groups.push(numbers);
        rest = start[end + 1..].trim_start();
        if let Some(r) = rest.strip_prefix(',') {
            rest = r.trim_start();
            if rest.is_empty() {
                return Err(bad("trailing ','"));
            }
        } else if !rest.is_empty() {
            return Err(bad("expected ',' between groups"));
        }
    }
    Ok(groups)
}

/// The paper's 19 scenarios.
pub fn paper_scenarios() -> Vec<Scenario> {
    parse_circles(CIRCLES).expect("the bundled data file parses")
}

/// One scenario by id.
pub fn scenario(id: usize) -> Result<Scenario, ProblemError> {
    let all = paper_scenarios();
    let last = all.len() - 1;
    all.into_iter()
        .nth(id)
        .ok_or(ProblemError::Unknown { id, last })
}

/// A grid problem before costs are attached: which moves exist, in order, and `x1`, goal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GridLayout {
    /// The problem id.
    pub id: usize,
    /// The scenario it was built from.
    pub scenario: Scenario,
    /// Ordered neighbours of every grid node (after pruning).
    pub neighbours: Vec<Vec<usize>>,
    /// `x1`.
    pub initial: usize,
    /// The goal node.
    pub goal: usize,
}

impl GridLayout {
    /// The exact layout of docs/spec.md §5 (integer geometry, order left, up, down, right).
    pub fn exact(id: usize) -> Result<Self, ProblemError> {
        let scenario = scenario(id)?;
        let point = |i: usize| ((800 * (i % SIDE)) as i128, (800 * (i / SIDE)) as i128);
        let discs: Vec<((i128, i128), i128)> = scenario
            .obstacles
            .iter()
            .map(|d| ((19 * d.cx as i128, 19 * d.cy as i128), 19 * d.r as i128))
            .collect();
        let safe = |a: usize, b: usize| {
            discs
                .iter()
                .all(|&(c, r)| segment_safe(point(a), point(b), c, r))
        };
        let nearest = |(x, y): (i64, i64)| {
            (0..GRID_NODES)
                .min_by_key(|&i| {
                    let (px, py) = point(i);
                    let (dx, dy) = (px - 19 * x as i128, py - 19 * y as i128);
                    (dx * dx + dy * dy, i)
                })
                .expect("grid is non-empty")
        };
        let (initial, goal) = (nearest(scenario.start), nearest(scenario.goal));
        Ok(Self::assemble(id, scenario, &ORDER, safe, initial, goal))
    }

    /// The reference code's layout (docs/spec.md §7): `f64` coordinates by repeated addition, `f64`
    /// obstacle and nearest-node tests, its action orders.
    pub fn reference(id: usize) -> Result<Self, ProblemError> {
        let scenario = scenario(id)?;
        let coords = reference_coordinates();
        let point = |i: usize| (coords[i % SIDE], coords[i / SIDE]);
        let safe = |a: usize, b: usize| {
            scenario
                .obstacles
                .iter()
                .all(|d| segment_safe_f64(point(a), point(b), d))
        };
        let nearest = |(x, y): (i64, i64)| {
            let mut best = (f64::INFINITY, 0);
            for i in 0..GRID_NODES {
                let (px, py) = point(i);
                let d = ((px - x as f64).powi(2) + (py - y as f64).powi(2)).sqrt();
                if d < best.0 {
                    best = (d, i);
                }
            }
            best.1
        };
        let (initial, goal) = (nearest(scenario.start), nearest(scenario.goal));
        let order = if PRUNED.contains(&id) {
            ORDER_PRUNED_REFERENCE
        } else {
            ORDER
        };
        Ok(Self::assemble(
            id,
            scenario.clone(),
            &order,
            safe,
            initial,
            goal,
        ))
    }

    /// The layout from a geometry: every node's neighbours in `order` joined by a safe
    /// segment, then the pocket behind the goal pruned for the problems of docs/spec.md §5 that do so.
    fn assemble(
        id: usize,
        scenario: Scenario,
        order: &[Direction],
        safe: impl Fn(usize, usize) -> bool,
        initial: usize,
        goal: usize,
    ) -> Self {
        let neighbours = (0..GRID_NODES)
            .map(|i| {
                order
                    .iter()
                    .filter_map(|&d| neighbour(i, d))
                    .filter(|&j| safe(i, j))
                    .collect()
            })
            .collect();
        let mut layout = GridLayout {
            id,
            scenario,
            neighbours,
            initial,
            goal,
        };
        if PRUNED.contains(&id) {
            layout.prune_behind_goal();
        }
        layout
    }

    /// Removes the nodes of x1's component that can only be reached through the goal (the
    /// pocket behind it), keeping the goal itself (docs/spec.md §5).
    fn prune_behind_goal(&mut self) {
        let n = self.neighbours.len();
        let mut keep = vec![false; n];
        keep[self.initial] = true;
        let mut queue = VecDeque::from([self.initial]);
        while let Some(v) = queue.pop_front() {
            if v == self.goal {
                continue; // do not pass through the goal
            }
            for &w in &self.neighbours[v] {
                if !keep[w] {
                    keep[w] = true;
                    queue.push_back(w);
                }
            }
        }
        let component = self.component_of_initial();
        for v in 0..n {
            if component[v] && !keep[v] {
                self.neighbours[v].clear();
            }
        }
        for v in 0..n {
            self.neighbours[v].retain(|&w| !component[w] || keep[w]);
        }
    }

    /// Membership of x1's component (moves are symmetric, so reachability suffices).
    pub fn component_of_initial(&self) -> Vec<bool> {
        let mut seen = vec![false; self.neighbours.len()];
        seen[self.initial] = true;
        let mut queue = VecDeque::from([self.initial]);
        while let Some(v) = queue.pop_front() {
            for &w in &self.neighbours[v] {
                if !seen[w] {
                    seen[w] = true;
                    queue.push_back(w);
                }
            }
        }
        seen
    }

    /// The exact planning problem with the chosen step cost.
    pub fn to_problem(&self, step: StepCost) -> Problem {
        let cost = match step {
            StepCost::Unit => Rational::from_integer(BigInt::from(1)),
            StepCost::Euclidean => Rational::new(BigInt::from(800), BigInt::from(19)),
        };
        let moves = self
            .neighbours
            .iter()
            .map(|list| {
                list.iter()
                    .map(|&j| Move {
                        successor: j,
                        cost: cost.clone(),
                    })
                    .collect()
            })
            .collect();
        Problem::new(moves, self.initial, vec![self.goal]).expect("grid problems are well formed")
    }

    /// The reference-mode graph: `f64` Euclidean step costs on the reference coordinates.
    pub fn to_reference_graph(&self) -> Graph<f64> {
        let coords = reference_coordinates();
        let point = |i: usize| (coords[i % SIDE], coords[i / SIDE]);
        let adjacency = self
            .neighbours
            .iter()
            .enumerate()
            .map(|(i, list)| {
                list.iter()
                    .map(|&j| {
                        let (a, b) = (point(i), point(j));
                        (j, ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt())
                    })
                    .collect()
            })
            .collect();
        Graph::from_adjacency(
            adjacency,
            self.initial,
            &[self.goal],
            (0..GRID_NODES).collect(),
            Rational::from_integer(BigInt::from(1)),
        )
    }
}

/// The reference code's grid coordinates: `0`, then repeated `f64` addition of `40 + 40/19`.
pub fn reference_coordinates() -> [f64; SIDE] {
    let step = 40.0 + 40.0 / 19.0;
    let mut c = [0.0; SIDE];
    for k in 1..SIDE {
        c[k] = c[k - 1] + step;
    }
    c
}

/// The summary facts of a problem (the `problems` listing).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Facts {
    /// Problem id.
    pub id: usize,
    /// Grid nodes (400).
    pub grid_nodes: usize,
    /// States in x1's component.
    pub states: usize,
    /// Undirected edges in x1's component.
    pub edges: usize,
    /// `x1`.
    pub initial: usize,
    /// The goal node.
    pub goal: usize,
    /// Moves on an optimal path, `None` if the goal is unreachable.
    pub optimal_moves: Option<u64>,
    /// Whether the paper's figures and tables use it.
    pub in_paper: bool,
}

impl GridLayout {
    /// The facts of this layout (unit costs; moves by breadth-first search).
    pub fn facts(&self) -> Facts {
        let component = self.component_of_initial();
        let states = component.iter().filter(|&&c| c).count();
        let directed: usize = (0..self.neighbours.len())
            .filter(|&v| component[v])
            .map(|v| self.neighbours[v].len())
            .sum();
        let mut dist = vec![u64::MAX; self.neighbours.len()];
        dist[self.initial] = 0;
        let mut queue = VecDeque::from([self.initial]);
        while let Some(v) = queue.pop_front() {
            for &w in &self.neighbours[v] {
                if dist[w] == u64::MAX {
                    dist[w] = dist[v] + 1;
                    queue.push_back(w);
                }
            }
        }
        Facts {
            id: self.id,
            grid_nodes: self.neighbours.len(),
            states,
            edges: directed / 2,
            initial: self.initial,
            goal: self.goal,
            optimal_moves: (dist[self.goal] != u64::MAX).then_some(dist[self.goal]),
            in_paper: PAPER_PROBLEMS.contains(&self.id),
        }
    }
}

//! Figures of the benchmarks: the map as a [`Scene`] — cells as states, FrozenLake's holes
//! and CliffWalking's cliff as discs, the start and the goal — with a policy or a value overlay
//! drawn by [`crate::figures::render::draw`].
//!
//! The policy overlays ([`policy_overlay`], [`taxi_actions_overlay`]) draw *every* optimal
//! action of a state ([`crate::objectives::actions::optimal_actions`]: the actions whose exact `Q`-value equals the optimal
//! value, compared as rationals, and that some optimal stationary policy uses): an arrow to the
//! cell its move aims at, several arrows at a state where actions tie; an action whose move
//! aims into a wall or the border (the agent stays in place) is a short stroke ending in a bar.
//! The legend under the map says what arrows, several arrows and bars mean.
//!
//! Taxi's 500 states are 25 taxi cells × 5 passenger places × 4 destinations: one figure draws
//! the 5×5 map (its walls, the depots R, G, Y, B) and one *slice* ([`TaxiSlice`]: the
//! passenger's place and the destination fixed, the 25 taxi cells varying), the destination
//! marked as the goal; the policy overlay marks pick-up and drop-off actions in their cells
//! ([`taxi_scene`], [`taxi_actions_overlay`], [`taxi_value_overlay`]).

use num_traits::Signed;

use super::policy::legend;
use super::render::{ActionGlyph, Mark, Overlay, Scene};
use crate::envs::{cliffwalking, taxi, Environment, Layout};
use crate::objectives::actions::optimal_actions;
use crate::objectives::{Model, Solution};
use crate::problems::geometry::Disc;

/// Cell side in world units.
const CELL: i64 = 10;

/// Why an environment cannot be drawn.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("taxi's 500 states do not fit one 5x5 map: draw one slice of 25 with --passenger R|G|Y|B|taxi and --destination R|G|Y|B")]
pub struct NotDrawable;

/// The depot names of Taxi's four locations, in Gymnasium's numbering.
pub const DEPOTS: [&str; 4] = ["R", "G", "Y", "B"];

/// One slice of Taxi's states: the passenger's place (0..=3 at depot R, G, Y, B; 4 in the
/// taxi) and the destination (0..=3) fixed, the 25 taxi cells varying.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TaxiSlice {
    /// 0..=3: waiting at a depot; 4: in the taxi.
    pub passenger: usize,
    /// 0..=3: a depot.
    pub destination: usize,
}

impl TaxiSlice {
    /// The slice, refused (one line) when the passenger is already at the destination: those
    /// 25 states are where the episode has ended (Taxi's goals), there is no policy to draw.
    ///
    /// ```
    /// use truecost::figures::envs::TaxiSlice;
    /// let s = TaxiSlice::new(4, 1).unwrap();
    /// assert_eq!(s.state(0, 4), ((0 * 5 + 4) * 5 + 4) * 4 + 1); // Gymnasium's encode(0, 4, 4, 1) = 97
    /// assert!(TaxiSlice::new(2, 2).unwrap_err().contains("ended"));
    /// ```
    pub fn new(passenger: usize, destination: usize) -> Result<TaxiSlice, String> {
        if passenger > 4 || destination > 3 {
            return Err(format!(
                "taxi slice: passenger {passenger} (0..=4) or destination {destination} (0..=3) out of range"
            ));
        }
        if passenger == destination {
            return Err(format!(
                "taxi slice: the passenger is at the destination {}: those 25 states are where the episode has ended (Taxi's goals); choose another --passenger or --destination",
                DEPOTS[destination]
            ));
        }
        Ok(TaxiSlice {
            passenger,
            destination,
        })
    }

    /// The Taxi state of the taxi at `(row, col)` in this slice (Gymnasium's `encode`).
    pub fn state(&self, row: usize, col: usize) -> usize {
        taxi::encode(row, col, self.passenger, self.destination)
    }

    /// The 25 states of the slice, cell by cell (row-major from the top).
    pub fn states(&self) -> Vec<usize> {
        (0..25).map(|c| self.state(c / 5, c % 5)).collect()
    }

    /// What the slice is, in words.
    pub fn describe(&self) -> String {
        let passenger = match self.passenger {
            4 => "in the taxi".to_string(),
            p => format!("waiting at {}", DEPOTS[p]),
        };
        format!(
            "passenger {passenger}, destination {}",
            DEPOTS[self.destination]
        )
    }
}

/// The world centre of the cell `(row, col)` of an `nrow`-row map (row 0 on top).
fn cell_centre(nrow: usize, row: usize, col: usize) -> (f64, f64) {
    (
        (CELL * col as i64 + CELL / 2) as f64,
        (CELL * (nrow - 1 - row) as i64 + CELL / 2) as f64,
    )
}

/// The scene of Taxi's 5×5 map: 25 cells (the taxi's position, scene state
/// `row·5 + col`), a grey segment between neighbouring cells not separated by a wall, the six
/// walls of Gymnasium's `MAP`, the depots R, G, Y, B; with a slice, the destination as the
/// goal and a `passenger` mark at the passenger's depot (if waiting). No `x1` is marked: the
/// initial state is drawn uniformly from 300 states.
///
/// ```
/// use truecost::{envs::EnvSpec, figures::envs::{taxi_scene, TaxiSlice}};
/// let env = EnvSpec::parse("taxi").unwrap().build().unwrap();
/// let s = taxi_scene(&env, Some(&TaxiSlice::new(0, 1).unwrap()));
/// assert_eq!((s.positions.len(), s.walls.len(), s.moves.len(), s.goals.clone()), (25, 6, 34, vec![4]));
/// assert_eq!(s.marks.iter().filter(|m| m.class == "depot").count(), 4);
/// ```
pub fn taxi_scene(env: &Environment, slice: Option<&TaxiSlice>) -> Scene {
    let n = 5;
    let positions = (0..n * n).map(|s| cell_centre(n, s / n, s % n)).collect();
    let mut moves = Vec::new();
    let mut walls = Vec::new();
    for r in 0..n {
        for c in 0..n {
            let s = r * n + c;
            if c + 1 < n {
                if taxi::open_east(r, c) {
                    moves.push((s, s + 1));
                } else {
                    let x = (CELL * (c as i64 + 1)) as f64;
                    let y0 = (CELL * (n - 1 - r) as i64) as f64;
                    walls.push(((x, y0), (x, y0 + CELL as f64)));
                }
            }
            if r + 1 < n {
                moves.push((s, s + n));
            }
        }
    }
    let offset = CELL as f64 * 0.3;
    let mut marks: Vec<Mark> = taxi::LOCATIONS
        .iter()
        .zip(DEPOTS)
        .map(|(&(r, c), name)| {
            let (x, y) = cell_centre(n, r, c);
            Mark {
                class: "depot",
                at: (x - offset, y + offset),
                text: name.to_string(),
                size: 18.0,
            }
        })
        .collect();
    let mut goals = Vec::new();
    let caption = match slice {
        Some(slice) => {
            let (r, c) = taxi::LOCATIONS[slice.destination];
            goals.push(r * n + c);
            if slice.passenger < 4 {
                let (r, c) = taxi::LOCATIONS[slice.passenger];
                let (x, y) = cell_centre(n, r, c);
                marks.push(Mark {
                    class: "passenger",
                    at: (x, y - offset),
                    text: "passenger".into(),
                    size: 11.0,
                });
            }
            format!(
                "5x5 map, walls thick, depots R G Y B; slice: {} (25 of the 500 states, one per taxi cell)",
                slice.describe()
            )
        }
        None => "5x5 map, walls thick, depots R G Y B".to_string(),
    };
    Scene {
        title: format!("{} ({})", env.spec, env.gymnasium_id),
        caption,
        positions,
        extent: ((CELL * n as i64) as f64, (CELL * n as i64) as f64),
        obstacles: Vec::new(),
        moves,
        initial: None,
        goals,
        walls,
        marks,
    }
}

/// The cell a Taxi move (Gymnasium action 0 south, 1 north, 2 east, 3 west) aims at from
/// `(row, col)`: the cell itself where a wall or the border is in the way, or for pick-up and
/// drop-off (4, 5).
fn taxi_target(row: usize, col: usize, action: usize) -> (usize, usize) {
    match action {
        0 => ((row + 1).min(4), col),
        1 => (row.saturating_sub(1), col),
        2 if taxi::open_east(row, col) => (row, (col + 1).min(4)),
        3 if taxi::open_west(row, col) => (row, col.saturating_sub(1)),
        _ => (row, col),
    }
}

/// The pick-up (`action` 4) or drop-off (5) mark in the cell `(row, col)`.
fn taxi_mark(row: usize, col: usize, action: usize) -> Mark {
    let (px, py) = cell_centre(5, row, col);
    Mark {
        class: if action == 4 { "pickup" } else { "dropoff" },
        at: (px, py + CELL as f64 * 0.25),
        text: if action == 4 { "pick up" } else { "drop off" }.into(),
        size: 12.0,
    }
}

/// The reported policy of a Taxi slice, one action per cell: an arrow from each cell to the
/// cell its move aims at (none for a move into a wall or the border), and a `pickup` /
/// `dropoff` mark in the cells where the policy picks up or drops off (returned as marks to
/// add to the scene). [`taxi_actions_overlay`] draws every optimal action instead.
///
/// ```
/// use truecost::{envs::EnvSpec, figures::envs::{taxi_policy_overlay, TaxiSlice}};
/// use truecost::figures::render::Overlay;
/// use truecost::objectives::{Model, Objective};
/// let env = EnvSpec::parse("taxi").unwrap().build().unwrap();
/// let m = Model::from_environment(&env).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// // Passenger in the taxi, destination G (0, 4): drop off at G only.
/// let (Overlay::Policy(next), marks) = taxi_policy_overlay(&m, &s, &TaxiSlice::new(4, 1).unwrap()) else { panic!() };
/// assert_eq!(marks.iter().map(|m| m.class).collect::<Vec<_>>(), vec!["dropoff"]);
/// assert_eq!(next.iter().filter(|n| n.is_some()).count(), 24); // every other cell moves
/// ```
pub fn taxi_policy_overlay(model: &Model, s: &Solution, slice: &TaxiSlice) -> (Overlay, Vec<Mark>) {
    let n = 5;
    let mut next = Vec::with_capacity(n * n);
    let mut marks = Vec::new();
    for cell in 0..n * n {
        let (r, c) = (cell / n, cell % n);
        let x = slice.state(r, c);
        let Some(a) = s.policy[x].map(|a| a - model.problem.actions(x).start) else {
            next.push(None);
            continue;
        };
        if a >= 4 {
            marks.push(taxi_mark(r, c, a));
        }
        let (nr, nc) = taxi_target(r, c, a);
        let target = nr * n + nc;
        next.push((target != cell).then_some(target));
    }
    (Overlay::Policy(next), marks)
}

/// Every optimal action of a Taxi slice ([`optimal_actions`]): per cell an arrow to the cell
/// each optimal move aims at — several arrows where moves tie —, a bar for an optimal move into
/// a wall or the border, and a `pickup` / `dropoff` mark (returned as marks to add to the
/// scene) where picking up or dropping off is optimal; with the legend.
///
/// ```
/// use truecost::{envs::EnvSpec, figures::envs::{taxi_actions_overlay, TaxiSlice}};
/// use truecost::figures::render::{ActionGlyph, Overlay};
/// use truecost::objectives::{Model, Objective};
/// let env = EnvSpec::parse("taxi").unwrap().build().unwrap();
/// let m = Model::from_environment(&env).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// // Passenger in the taxi, destination R (0, 0): from (1, 1) north to (0, 1) or west to
/// // (1, 0) are both two moves from the drop-off.
/// let (Overlay::Actions { actions, .. }, marks) = taxi_actions_overlay(&m, &s, &TaxiSlice::new(4, 0).unwrap()) else { panic!() };
/// assert_eq!(actions[6], vec![ActionGlyph::Move(1), ActionGlyph::Move(5)]);
/// assert_eq!(marks.iter().map(|m| m.class).collect::<Vec<_>>(), vec!["dropoff"]);
/// ```
pub fn taxi_actions_overlay(
    model: &Model,
    s: &Solution,
    slice: &TaxiSlice,
) -> (Overlay, Vec<Mark>) {
    let optimal = optimal_actions(model, s);
    let n = 5;
    let mut actions = Vec::with_capacity(n * n);
    let mut tied = false;
    let mut marks = Vec::new();
    for cell in 0..n * n {
        let (r, c) = (cell / n, cell % n);
        let x = slice.state(r, c);
        let first = model.problem.actions(x).start;
        tied |= optimal[x].len() > 1;
        let mut glyphs = Vec::new();
        for a in optimal[x].iter().map(|a| a - first) {
            if a >= 4 {
                marks.push(taxi_mark(r, c, a));
                continue;
            }
            let (nr, nc) = taxi_target(r, c, a);
            glyphs.push(if (nr, nc) == (r, c) {
                let toward = [(0, -1), (0, 1), (1, 0), (-1, 0)][a];
                ActionGlyph::Blocked { toward }
            } else {
                ActionGlyph::Move(nr * n + nc)
            });
        }
        actions.push(glyphs);
    }
    let legend = legend(&actions, tied, "cell", "a wall or the border", false);
    (Overlay::Actions { actions, legend }, marks)
}

/// The value overlay of a Taxi slice: the objective's exact values at its 25 states (coloured
/// as `f64`), labelled with the objective.
pub fn taxi_value_overlay(s: &Solution, slice: &TaxiSlice) -> Overlay {
    Overlay::Values {
        values: slice
            .states()
            .iter()
            .map(|&x| s.values[x].finite().map(|_| s.values[x].to_f64()))
            .collect(),
        label: format!("{} (exact)", s.objective.name()),
    }
}

/// The scene of a FrozenLake or CliffWalking map (Taxi: [`taxi_scene`] of a slice).
///
/// ```
/// use truecost::{envs::EnvSpec, figures::envs::scene};
/// let env = EnvSpec::parse("frozenlake").unwrap().build().unwrap();
/// let s = scene(&env).unwrap();
/// assert_eq!((s.positions.len(), s.obstacles.len(), s.moves.len(), s.initial, s.goals.clone()), (16, 4, 24, Some(0), vec![15]));
/// ```
pub fn scene(env: &Environment) -> Result<Scene, NotDrawable> {
    let (nrow, ncol) = env.shape;
    let blocked: Vec<usize> = match &env.layout {
        Layout::FrozenLake { .. } => env.traps.clone(),
        Layout::CliffWalking => (0..nrow * ncol)
            .filter(|&s| cliffwalking::is_cliff(s / ncol, s % ncol))
            .collect(),
        Layout::Taxi => return Err(NotDrawable),
    };
    let centre = |s: usize| {
        let (r, c) = ((s / ncol) as i64, (s % ncol) as i64);
        (CELL * c + CELL / 2, CELL * (nrow as i64 - 1 - r) + CELL / 2)
    };
    let positions = (0..nrow * ncol)
        .map(|s| {
            let (x, y) = centre(s);
            (x as f64, y as f64)
        })
        .collect();
    let obstacles = blocked
        .iter()
        .map(|&s| {
            let (cx, cy) = centre(s);
            Disc { cx, cy, r: 4 }
        })
        .collect();
    let mut moves = Vec::new();
    for s in 0..nrow * ncol {
        if s % ncol + 1 < ncol {
            moves.push((s, s + 1));
        }
        if s + ncol < nrow * ncol {
            moves.push((s, s + ncol));
        }
    }
    let kind = match env.layout {
        Layout::FrozenLake { .. } => "holes as discs",
        _ => "the cliff as discs",
    };
    Ok(Scene {
        title: format!("{} ({})", env.spec, env.gymnasium_id),
        caption: format!("{nrow}x{ncol} cells, {kind}"),
        positions,
        extent: ((CELL * ncol as i64) as f64, (CELL * nrow as i64) as f64),
        obstacles,
        moves,
        initial: Some(env.initial[0].0),
        goals: env.goals.clone(),
        walls: Vec::new(),
        marks: Vec::new(),
    })
}

/// The `(row, col)` step of Gymnasium action `a` of a grid benchmark.
fn step(env: &Environment, a: usize) -> (i64, i64) {
    match (&env.layout, a) {
        (Layout::FrozenLake { .. }, 0) | (Layout::CliffWalking, 3) => (0, -1),
        (Layout::FrozenLake { .. }, 1) | (Layout::CliffWalking, 2) => (1, 0),
        (Layout::FrozenLake { .. }, 2) | (Layout::CliffWalking, 1) => (0, 1),
        _ => (-1, 0),
    }
}

/// The cell Gymnasium action `a` aims at from `x` (the move without slipping, before a fall).
pub fn intended_cell(env: &Environment, x: usize, a: usize) -> usize {
    let (nrow, ncol) = env.shape;
    let (r, c) = (x / ncol, x % ncol);
    let (dr, dc) = step(env, a);
    let nr = (r as i64 + dr).clamp(0, nrow as i64 - 1) as usize;
    let nc = (c as i64 + dc).clamp(0, ncol as i64 - 1) as usize;
    nr * ncol + nc
}

/// Whether some action of the environment has more than one outcome (slippery FrozenLake,
/// slippery CliffWalking).
fn slippery(env: &Environment) -> bool {
    env.table.iter().flatten().any(|outcomes| {
        outcomes
            .iter()
            .filter(|t| t.probability.is_positive())
            .count()
            > 1
    })
}

/// The policy overlay of a FrozenLake or CliffWalking map: every optimal action of every state
/// ([`optimal_actions`]) — an arrow to the cell its move aims at (before slipping), several
/// arrows where actions tie, a bar for a move into the border (the agent stays in place) —
/// with the legend; nothing at goals, holes and states from which no policy reaches a goal.
///
/// ```
/// use truecost::{envs::EnvSpec, figures::envs::policy_overlay};
/// use truecost::figures::render::{ActionGlyph, Overlay};
/// use truecost::objectives::{Model, Objective};
/// let env = EnvSpec::parse("cliffwalking").unwrap().build().unwrap();
/// let m = Model::from_environment(&env).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// let Overlay::Actions { actions, .. } = policy_overlay(&env, &m, &s) else { panic!() };
/// assert_eq!(actions[36], vec![ActionGlyph::Move(24)]); // up, round the cliff
/// assert!(actions[47].is_empty()); // the goal
/// ```
pub fn policy_overlay(env: &Environment, model: &Model, s: &Solution) -> Overlay {
    let optimal = optimal_actions(model, s);
    let actions: Vec<Vec<ActionGlyph>> = optimal
        .iter()
        .enumerate()
        .map(|(x, list)| {
            let first = model.problem.actions(x).start;
            list.iter()
                .map(|a| {
                    let a = a - first;
                    match intended_cell(env, x, a) {
                        y if y == x => {
                            let (dr, dc) = step(env, a);
                            ActionGlyph::Blocked {
                                toward: (dc as i8, -dr as i8),
                            }
                        }
                        y => ActionGlyph::Move(y),
                    }
                })
                .collect()
        })
        .collect();
    let tied = optimal.iter().any(|list| list.len() > 1);
    let legend = legend(&actions, tied, "cell", "the border", slippery(env));
    Overlay::Actions { actions, legend }
}

/// The value overlay (`+∞` uncoloured), labelled with the objective and the exact initial value.
pub fn value_overlay(s: &Solution) -> Overlay {
    Overlay::Values {
        values: s
            .values
            .iter()
            .map(|v| v.finite().map(|_| v.to_f64()))
            .collect(),
        label: format!("{} (exact)", s.objective.name()),
    }
}

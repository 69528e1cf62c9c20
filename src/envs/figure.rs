//! Figures of the benchmarks (issue 11, item 5): the map as a [`Scene`] — cells as states,
//! FrozenLake's holes and CliffWalking's cliff as discs, the start and the goal — with a
//! policy (the intended cell of each chosen action) or a value overlay drawn by
//! [`crate::figures::render::draw`].

use super::{cliffwalking, Environment, Layout};
use crate::figures::render::{Overlay, Scene};
use crate::objectives::{Model, Solution};
use crate::problems::geometry::Disc;

/// Cell side in world units.
const CELL: i64 = 10;

/// Why an environment cannot be drawn.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("render --env draws frozenlake and cliffwalking; taxi's 500 states (taxi, passenger, destination) do not fit one 5x5 map")]
pub struct NotDrawable;

/// The scene of a FrozenLake or CliffWalking map.
///
/// ```
/// use truecost::envs::{figure::scene, EnvSpec};
/// let env = EnvSpec::parse("frozenlake").unwrap().build().unwrap();
/// let s = scene(&env).unwrap();
/// assert_eq!((s.positions.len(), s.obstacles.len(), s.moves.len(), s.initial, s.goals.clone()), (16, 4, 24, 0, vec![15]));
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
        initial: env.initial[0].0,
        goals: env.goals.clone(),
    })
}

/// The cell Gymnasium action `a` aims at from `x` (the move without slipping, before a fall).
pub fn intended_cell(env: &Environment, x: usize, a: usize) -> usize {
    let (nrow, ncol) = env.shape;
    let (r, c) = (x / ncol, x % ncol);
    // (row, col) deltas in each benchmark's action numbering.
    let (dr, dc): (i64, i64) = match (&env.layout, a) {
        (Layout::FrozenLake { .. }, 0) | (Layout::CliffWalking, 3) => (0, -1),
        (Layout::FrozenLake { .. }, 1) | (Layout::CliffWalking, 2) => (1, 0),
        (Layout::FrozenLake { .. }, 2) | (Layout::CliffWalking, 1) => (0, 1),
        _ => (-1, 0),
    };
    let nr = (r as i64 + dr).clamp(0, nrow as i64 - 1) as usize;
    let nc = (c as i64 + dc).clamp(0, ncol as i64 - 1) as usize;
    nr * ncol + nc
}

/// The policy overlay: at each state the intended cell of the solution's action (a goal
/// names itself; no arrow where the policy prescribes nothing).
pub fn policy_overlay(env: &Environment, model: &Model, s: &Solution) -> Overlay {
    Overlay::Policy(
        (0..env.states())
            .map(|x| {
                if env.goals.contains(&x) {
                    Some(x)
                } else {
                    s.policy[x].map(|a| intended_cell(env, x, a - model.problem.actions(x).start))
                }
            })
            .collect(),
    )
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

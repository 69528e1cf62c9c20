//! CliffWalking-v1 and CliffWalkingSlippery-v1 (Gymnasium 1.x `toy_text/cliffwalking.py`),
//! exact.
//!
//! A 4 × 12 grid, states `row·12 + col`; actions 0 UP, 1 RIGHT, 2 DOWN, 3 LEFT; a move off the
//! grid stays. The start is 36 (row 3, col 0), the goal 47, the cliff 37..=46. Every move
//! rewards −1 and terminates when it lands on the goal; a move into the cliff rewards −100 and
//! returns to the start (not terminated). Slippery: action `a` lists the moves
//! `(a−1) mod 4`, `a`, `(a+1) mod 4` in that order, 1/3 each. Gymnasium computes the rows of
//! the cliff and goal cells like any other (they are never used in an episode); so do we.

use super::{ratio, Environment, Layout, Transition};

/// Rows and columns.
pub const SHAPE: (usize, usize) = (4, 12);
/// The start state.
pub const START: usize = 36;
/// The goal state.
pub const GOAL: usize = 47;
/// Action names in Gymnasium's numbering.
pub const ACTIONS: [&str; 4] = ["up", "right", "down", "left"];

/// Whether a cell is on the cliff.
pub fn is_cliff(row: usize, col: usize) -> bool {
    row == 3 && (1..=10).contains(&col)
}

/// Builds CliffWalking.
pub fn build(slippery: bool) -> Environment {
    let (nrow, ncol) = SHAPE;
    let delta = |a: usize| -> (i64, i64) {
        match a {
            0 => (-1, 0),
            1 => (0, 1),
            2 => (1, 0),
            _ => (0, -1),
        }
    };
    let mut table = Vec::with_capacity(nrow * ncol);
    for s in 0..nrow * ncol {
        let (r, c) = ((s / ncol) as i64, (s % ncol) as i64);
        let actions = (0..4)
            .map(|a| {
                let moves: Vec<usize> = if slippery {
                    vec![(a + 3) % 4, a, (a + 1) % 4]
                } else {
                    vec![a]
                };
                let p = ratio(1, moves.len() as i64);
                moves
                    .into_iter()
                    .map(|b| {
                        let (dr, dc) = delta(b);
                        let nr = (r + dr).clamp(0, nrow as i64 - 1) as usize;
                        let nc = (c + dc).clamp(0, ncol as i64 - 1) as usize;
                        let next = nr * ncol + nc;
                        if is_cliff(nr, nc) {
                            Transition {
                                probability: p.clone(),
                                next: START,
                                reward: -100,
                                terminated: false,
                            }
                        } else {
                            Transition {
                                probability: p.clone(),
                                next,
                                reward: -1,
                                terminated: next == GOAL,
                            }
                        }
                    })
                    .collect()
            })
            .collect();
        table.push(actions);
    }
    Environment {
        spec: format!("cliffwalking:slippery={slippery}"),
        gymnasium_id: if slippery {
            "CliffWalkingSlippery-v1"
        } else {
            "CliffWalking-v1"
        },
        layout: Layout::CliffWalking,
        shape: SHAPE,
        action_names: &ACTIONS,
        table,
        initial: vec![(START, ratio(1, 1))],
        goals: vec![GOAL],
        traps: Vec::new(),
    }
}

//! Taxi-v4 (Gymnasium 1.x `toy_text/taxi.py`, not rainy, no fickle passenger), exact.
//!
//! State `((row·5 + col)·5 + passenger)·4 + destination`: passenger 0..=3 at a location
//! (R (0,0), G (0,4), Y (4,0), B (4,3)), 4 in the taxi. Actions 0 south, 1 north, 2 east,
//! 3 west, 4 pick-up, 5 drop-off; every outcome has probability 1. Reward −1 per action; −10
//! for a pick-up where the passenger is not, or a drop-off without passenger or off the four
//! locations; a drop-off at the destination with the passenger aboard rewards +20 and
//! terminates (the passenger is then at the destination); a drop-off at another location
//! leaves the passenger there (−1). Walls (the `|` of the map) block east/west moves. The
//! initial distribution is uniform over the 300 states with the passenger at a location that
//! is not the destination. The goal states are the 100 with passenger = destination: they
//! are entered only by a delivery.

use super::{ratio, Environment, Layout, Transition};

/// Gymnasium's `MAP`.
pub const MAP: [&str; 7] = [
    "+---------+",
    "|R: | : :G|",
    "| : | : : |",
    "| : : : : |",
    "| | : | : |",
    "|Y| : |B: |",
    "+---------+",
];
/// The four locations R, G, Y, B as (row, col).
pub const LOCATIONS: [(usize, usize); 4] = [(0, 0), (0, 4), (4, 0), (4, 3)];
/// Action names in Gymnasium's numbering.
pub const ACTIONS: [&str; 6] = ["south", "north", "east", "west", "pickup", "dropoff"];

/// Gymnasium's `encode`.
pub fn encode(row: usize, col: usize, passenger: usize, destination: usize) -> usize {
    ((row * 5 + col) * 5 + passenger) * 4 + destination
}

/// Gymnasium's `decode`: (row, col, passenger, destination).
pub fn decode(state: usize) -> (usize, usize, usize, usize) {
    (state / 100, (state / 20) % 5, (state / 4) % 5, state % 4)
}

/// Whether the map has no wall east of (row, col) (Gymnasium: `desc[1+row][2*col+2] == ':'`).
pub fn open_east(row: usize, col: usize) -> bool {
    MAP[1 + row].as_bytes()[2 * col + 2] == b':'
}

/// Whether the map has no wall west of (row, col).
pub fn open_west(row: usize, col: usize) -> bool {
    MAP[1 + row].as_bytes()[2 * col] == b':'
}

/// Builds Taxi-v4.
pub fn build() -> Environment {
    let mut table = vec![Vec::new(); 500];
    let mut initial = Vec::new();
    let mut goals = Vec::new();
    for (s, row) in table.iter_mut().enumerate() {
        let (r, c, pass, dest) = decode(s);
        if pass < 4 && pass != dest {
            initial.push(s);
        }
        if pass == dest {
            goals.push(s);
        }
        for a in 0..6 {
            let (mut nr, mut nc, mut np) = (r, c, pass);
            let (mut reward, mut terminated) = (-1, false);
            match a {
                0 => nr = (r + 1).min(4),
                1 => nr = r.saturating_sub(1),
                2 if open_east(r, c) => nc = (c + 1).min(4),
                3 if open_west(r, c) => nc = c.saturating_sub(1),
                4 => {
                    if pass < 4 && (r, c) == LOCATIONS[pass] {
                        np = 4;
                    } else {
                        reward = -10;
                    }
                }
                5 => {
                    if pass == 4 && (r, c) == LOCATIONS[dest] {
                        np = dest;
                        terminated = true;
                        reward = 20;
                    } else if let (4, Some(i)) = (pass, LOCATIONS.iter().position(|&l| l == (r, c)))
                    {
                        np = i;
                    } else {
                        reward = -10;
                    }
                }
                _ => {}
            }
            row.push(vec![Transition {
                probability: ratio(1, 1),
                next: encode(nr, nc, np, dest),
                reward,
                terminated,
            }]);
        }
    }
    let share = ratio(1, initial.len() as i64);
    Environment {
        spec: "taxi".into(),
        gymnasium_id: "Taxi-v4",
        layout: Layout::Taxi,
        shape: (5, 5),
        action_names: &ACTIONS,
        table,
        initial: initial.into_iter().map(|s| (s, share.clone())).collect(),
        goals,
        traps: Vec::new(),
    }
}

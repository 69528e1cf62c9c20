//! FrozenLake-v1 (Gymnasium 1.x `toy_text/frozen_lake.py`), exact.
//!
//! States `row·ncol + col`; actions 0 LEFT, 1 DOWN, 2 RIGHT, 3 UP; a move off the map stays.
//! Slippery: action `a` lists the moves `(a−1) mod 4`, `a`, `(a+1) mod 4` in that order with
//! probabilities `(1−p)/2`, `p`, `(1−p)/2` (`p = success_rate`, default 1/3); not slippery: the
//! move itself with probability 1. Reward 1 on entering `G`, else 0; entering `G` or `H`
//! terminates. At `G` and `H` every action lists `(1, s, 0, terminated)`. The initial
//! distribution is uniform over the `S` cells.

use num_traits::{One, Zero};

use super::{EnvError, Environment, Layout, MapChoice, Transition};
use crate::value::Rational;

/// Gymnasium's `MAPS["4x4"]`.
pub const MAP_4X4: [&str; 4] = ["SFFF", "FHFH", "FFFH", "HFFG"];
/// Gymnasium's `MAPS["8x8"]`.
pub const MAP_8X8: [&str; 8] = [
    "SFFFFFFF", "FFFFFFFF", "FFFHFFFF", "FFFFFHFF", "FFFHFFFF", "FHHFFFHF", "FHFFHFHF", "FFFHFFFG",
];
/// Action names in Gymnasium's numbering.
pub const ACTIONS: [&str; 4] = ["left", "down", "right", "up"];

/// The most cells of a map file: 100 × 100, whose exact model every command builds and
/// solves in seconds (a map of 10⁶ cells passed the reader but no command could build it).
pub const MAX_MAP_CELLS: usize = 10_000;

/// The largest map file read, in bytes: a map of [`MAX_MAP_CELLS`] cells with its line ends
/// and generous surrounding blanks fits well below it.
pub const MAX_MAP_BYTES: u64 = 1 << 20;

/// Reads a map file (at most [`MAX_MAP_BYTES`]): one row per non-empty line, letters
/// `S F H G` only, all rows equally long, at least one `S` and one `G`.
fn read_map(path: &std::path::Path) -> Result<Vec<String>, EnvError> {
    let bad = |reason: String| EnvError::Map {
        path: path.display().to_string(),
        reason,
    };
    use crate::bounded::BoundedError;
    let text =
        crate::bounded::read_text(path, MAX_MAP_BYTES, "map files").map_err(|e| match e {
            BoundedError::Io { source, .. } => bad(source.to_string()),
            BoundedError::TooLarge { limit, what, .. } => {
                bad(format!("larger than {limit} bytes, the limit for {what}"))
            }
            BoundedError::NotText { .. } => bad("not UTF-8 text".to_string()),
        })?;
    let rows: Vec<String> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(str::to_string)
        .collect();
    check_map(&rows).map_err(bad)?;
    Ok(rows)
}

/// The checks of `read_map` on rows already read.
pub fn check_map(rows: &[String]) -> Result<(), String> {
    let width = rows.first().map(|r| r.len()).unwrap_or(0);
    if width == 0 {
        return Err("empty map".into());
    }
    if rows.len().saturating_mul(width) > MAX_MAP_CELLS {
        return Err(format!(
            "{} x {width} cells: a map has at most {MAX_MAP_CELLS} cells (100 x 100)",
            rows.len()
        ));
    }
    for (i, r) in rows.iter().enumerate() {
        if let Some(c) = r.chars().find(|c| !"SFHG".contains(*c)) {
            return Err(format!("row {i}: letter '{c}' (use S, F, H, G)"));
        }
        if r.len() != width {
            return Err(format!("row {i} has {} cells, row 0 has {width}", r.len()));
        }
    }
    for letter in ['S', 'G'] {
        if !rows.iter().any(|r| r.contains(letter)) {
            return Err(format!("no '{letter}' cell"));
        }
    }
    Ok(())
}

/// Builds FrozenLake on the chosen map.
pub fn build(
    map: &MapChoice,
    slippery: bool,
    success_rate: &Rational,
    spec: String,
) -> Result<Environment, EnvError> {
    let desc: Vec<String> = match map {
        MapChoice::FourByFour => MAP_4X4.iter().map(|s| s.to_string()).collect(),
        MapChoice::EightByEight => MAP_8X8.iter().map(|s| s.to_string()).collect(),
        MapChoice::File(path) => read_map(path)?,
    };
    Ok(from_desc(desc, slippery, success_rate, spec))
}

/// Builds FrozenLake from Gymnasium's `desc` (rows already checked by [`check_map`]).
pub fn from_desc(
    desc: Vec<String>,
    slippery: bool,
    success_rate: &Rational,
    spec: String,
) -> Environment {
    let grid: Vec<Vec<u8>> = desc.iter().map(|r| r.as_bytes().to_vec()).collect();
    let (nrow, ncol) = (grid.len(), grid[0].len());
    let fail = (Rational::one() - success_rate) / Rational::from_integer(2.into());
    let to_s = |r: usize, c: usize| r * ncol + c;
    let step = |r: usize, c: usize, a: usize| -> (usize, usize) {
        match a {
            0 => (r, c.saturating_sub(1)),
            1 => ((r + 1).min(nrow - 1), c),
            2 => (r, (c + 1).min(ncol - 1)),
            _ => (r.saturating_sub(1), c),
        }
    };
    let outcome = |r: usize, c: usize, b: usize, p: Rational| {
        let (nr, nc) = step(r, c, b);
        let letter = grid[nr][nc];
        Transition {
            probability: p,
            next: to_s(nr, nc),
            reward: i64::from(letter == b'G'),
            terminated: letter == b'G' || letter == b'H',
        }
    };
    let mut table = Vec::with_capacity(nrow * ncol);
    let (mut goals, mut traps, mut starts) = (Vec::new(), Vec::new(), Vec::new());
    for (r, row) in grid.iter().enumerate() {
        for (c, &letter) in row.iter().enumerate() {
            let s = to_s(r, c);
            match letter {
                b'G' => goals.push(s),
                b'H' => traps.push(s),
                b'S' => starts.push(s),
                _ => {}
            }
            let actions = (0..4)
                .map(|a| {
                    if letter == b'G' || letter == b'H' {
                        vec![Transition {
                            probability: Rational::one(),
                            next: s,
                            reward: 0,
                            terminated: true,
                        }]
                    } else if slippery {
                        [(a + 3) % 4, a, (a + 1) % 4]
                            .into_iter()
                            .map(|b| {
                                let p = if b == a {
                                    success_rate.clone()
                                } else {
                                    fail.clone()
                                };
                                outcome(r, c, b, p)
                            })
                            .collect()
                    } else {
                        vec![outcome(r, c, a, Rational::one())]
                    }
                })
                .collect();
            table.push(actions);
        }
    }
    let share = Rational::new(1.into(), starts.len().into());
    debug_assert!(!share.is_zero());
    Environment {
        spec,
        gymnasium_id: "FrozenLake-v1",
        layout: Layout::FrozenLake { desc },
        shape: (nrow, ncol),
        action_names: &ACTIONS,
        table,
        initial: starts.into_iter().map(|s| (s, share.clone())).collect(),
        goals,
        traps,
    }
}

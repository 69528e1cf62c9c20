//! The benchmark grid files of issue 12, item 3 ("large models"): an `R × C` 4-neighbour grid
//! whose every move has a stage cost drawn from `{1, 2, 3, 4}`, deterministic from a seed.
//!
//! Layout: state `i = C·row + col`; the moves of a state, in this order, go up, left, right,
//! down (only those inside the grid); the initial state is the top-left corner `0`, the goal
//! the bottom-right corner `R·C − 1`. Each move's cost is `1 + (k mod 4)` for the next
//! `k = next_u32()` ([`rand::Rng`]) of [`ChaCha8Rng::seed_from_u64`]`(seed)`, moves drawn in state order then
//! move order. The file is a deterministic problem (`truecost-problem/1`); `--gamma` turns it
//! into the stochastic model, e.g. `truecost solve --file grid.json --gamma 0.99 --algorithm
//! exact`.

use rand::Rng;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::model::{Move, Problem};
use crate::value::Rational;

/// The largest side accepted by [`cost_grid`] (10⁶ states at most).
pub const MAX_SIDE: usize = 1000;

/// The most states of a grid written as a problem file by `export --grid`: its file (about 250
/// bytes a state) must stay below the 32 MiB that every reader of problem files accepts
/// ([`crate::model::file::MAX_FILE_BYTES`]).
pub const MAX_EXPORT_STATES: usize = 100_000;

/// Refuses, before any work, a grid whose problem file no reader would accept.
///
/// ```
/// use truecost::stochastic::benchmark::exportable_size;
/// assert!(exportable_size(316, 316).is_ok());
/// assert!(exportable_size(1000, 1000).unwrap_err().to_string().contains("at most 100000 states"));
/// ```
pub fn exportable_size(rows: usize, cols: usize) -> Result<(), BenchmarkGridError> {
    if rows.saturating_mul(cols) > MAX_EXPORT_STATES {
        return Err(BenchmarkGridError::TooLargeToExport(rows, cols));
    }
    Ok(())
}

/// Why a benchmark grid could not be built.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BenchmarkGridError {
    /// A side outside `1..=MAX_SIDE` or a single-state grid.
    #[error(
        "grid size must be ROWSxCOLS with 1 <= ROWS, COLS <= 1000 and at least 2 states, got {0}"
    )]
    Size(String),
    /// A grid too large for a problem file that can be read back.
    #[error("a {0}x{1} grid cannot be exported: a problem file holds at most 100000 states (readers accept 32 MiB)")]
    TooLargeToExport(usize, usize),
}

/// Parses a grid size `ROWSxCOLS` (or a single side `N` for `N×N`).
///
/// ```
/// use truecost::stochastic::benchmark::parse_size;
/// assert_eq!(parse_size("100x100").unwrap(), (100, 100));
/// assert_eq!(parse_size("25").unwrap(), (25, 25));
/// assert!(parse_size("0x5").is_err());
/// ```
pub fn parse_size(text: &str) -> Result<(usize, usize), BenchmarkGridError> {
    let bad = || BenchmarkGridError::Size(crate::echo::echo(text));
    let (r, c) = match text.split_once(['x', 'X', '×']) {
        Some((r, c)) => (r, c),
        None => (text, text),
    };
    let side = |s: &str| -> Result<usize, BenchmarkGridError> {
        let v: usize = s.trim().parse().map_err(|_| bad())?;
        if (1..=MAX_SIDE).contains(&v) {
            Ok(v)
        } else {
            Err(bad())
        }
    };
    let (r, c) = (side(r)?, side(c)?);
    if r * c < 2 {
        return Err(bad());
    }
    Ok((r, c))
}

/// The benchmark grid (module docs): `rows × cols` states, costs 1–4 from `seed`.
///
/// ```
/// use truecost::stochastic::benchmark::cost_grid;
/// let p = cost_grid(3, 4, 7).unwrap();
/// assert_eq!((p.states(), p.initial(), p.goals()), (12, 0, &[11][..]));
/// assert_eq!(p.moves(0).len(), 2); // a corner: right, down
/// assert_eq!(p.moves(5).len(), 4); // an inner state
/// assert_eq!(cost_grid(3, 4, 7).unwrap(), p); // deterministic from the seed
/// ```
pub fn cost_grid(rows: usize, cols: usize, seed: u64) -> Result<Problem, BenchmarkGridError> {
    if !(1..=MAX_SIDE).contains(&rows) || !(1..=MAX_SIDE).contains(&cols) || rows * cols < 2 {
        return Err(BenchmarkGridError::Size(format!("{rows}x{cols}")));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let costs: Vec<Rational> = (1..=4).map(|c| Rational::from_integer(c.into())).collect();
    let mut moves = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in 0..cols {
            let mut list = Vec::with_capacity(4);
            let mut push = |successor: usize| {
                let k = (rng.next_u32() % 4) as usize;
                list.push(Move {
                    successor,
                    cost: costs[k].clone(),
                });
            };
            if r > 0 {
                push((r - 1) * cols + c);
            }
            if c > 0 {
                push(r * cols + c - 1);
            }
            if c + 1 < cols {
                push(r * cols + c + 1);
            }
            if r + 1 < rows {
                push((r + 1) * cols + c);
            }
            moves.push(list);
        }
    }
    Ok(Problem::new(moves, 0, vec![rows * cols - 1]).expect("a well-formed grid"))
}

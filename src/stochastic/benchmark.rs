//! The benchmark grid files of the large-model benchmarks: an `R × C` 4-neighbour grid
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
    /// An unknown cost pattern.
    #[error("unknown grid pattern '{0}': the patterns are random, unit, ties, walls, goals")]
    Pattern(String),
    /// A cost range that is not `LO-HI` with `1 <= LO <= HI <= 1000000`.
    #[error("grid costs must be LO-HI with integers 1 <= LO <= HI <= 1000000, got '{0}'")]
    Costs(String),
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

/// The benchmark grid (module docs): `rows × cols` states, costs 1–4 from `seed` (the
/// [`GridPattern::Random`] grid with costs `1-4`).
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
    pattern_grid(rows, cols, GridPattern::Random, CostRange::DEFAULT, seed)
}

/// The cost patterns of `export --grid --pattern` (a family for tests and benchmarks, so the
/// exact optimum is measured on grids with many exact ties, not one friendly instance).
///
/// Every pattern is a 4-neighbour grid laid out as in the module docs (moves up, left, right,
/// down among the free cells; initial state the top-left cell; goals keep their moves).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GridPattern {
    /// Every move costs a random integer of the [`CostRange`] (default `1-4`), from the seed:
    /// `lo + (k mod (hi − lo + 1))` for the next `k = next_u32()`, in state then move order.
    Random,
    /// Every move costs 1.
    Unit,
    /// A regular pattern with many exact ties: a move costs `1 + ((row + col) mod 4)`, `(row,
    /// col)` the cell it leaves.
    Ties,
    /// Unit costs and walls: every column `c` with `c mod 4 = 3` (except the last column) is
    /// a wall with a single gap, in the bottom row for `⌊c/4⌋` even and in the top row
    /// otherwise (a serpentine). Wall cells are not states; the free cells are numbered row by
    /// row. The goal is the bottom-right cell.
    Walls,
    /// The [`GridPattern::Ties`] costs with several goals: the top-right, bottom-left,
    /// bottom-right and centre `(⌊R/2⌋, ⌊C/2⌋)` cells (those that are not the initial cell).
    Goals,
}

impl GridPattern {
    /// Every pattern, in the order of [`GridPattern::NAMES`].
    pub const ALL: [GridPattern; 5] = [
        GridPattern::Random,
        GridPattern::Unit,
        GridPattern::Ties,
        GridPattern::Walls,
        GridPattern::Goals,
    ];

    /// The names accepted by [`GridPattern::parse`].
    pub const NAMES: [&'static str; 5] = ["random", "unit", "ties", "walls", "goals"];

    /// The pattern's name.
    pub fn name(self) -> &'static str {
        Self::NAMES[Self::ALL.iter().position(|&p| p == self).expect("listed")]
    }

    /// Parses a pattern name.
    ///
    /// ```
    /// use truecost::stochastic::benchmark::GridPattern;
    /// assert_eq!(GridPattern::parse("ties").unwrap(), GridPattern::Ties);
    /// assert!(GridPattern::parse("maze").unwrap_err().to_string().contains("random, unit, ties, walls, goals"));
    /// ```
    pub fn parse(text: &str) -> Result<Self, BenchmarkGridError> {
        Self::NAMES
            .iter()
            .position(|&n| n == text)
            .map(|i| Self::ALL[i])
            .ok_or_else(|| BenchmarkGridError::Pattern(crate::echo::echo(text)))
    }
}

/// The integer cost range `lo-hi` of [`GridPattern::Random`] (`1 ≤ lo ≤ hi ≤ 10⁶`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CostRange {
    /// The least cost.
    pub lo: u32,
    /// The largest cost.
    pub hi: u32,
}

impl CostRange {
    /// `1-4`, the benchmark grid's costs.
    pub const DEFAULT: CostRange = CostRange { lo: 1, hi: 4 };

    /// The largest cost accepted.
    pub const MAX: u32 = 1_000_000;

    /// Parses `LO-HI` (or a single cost `N` for `N-N`).
    ///
    /// ```
    /// use truecost::stochastic::benchmark::CostRange;
    /// assert_eq!(CostRange::parse("2-9").unwrap(), CostRange { lo: 2, hi: 9 });
    /// assert!(CostRange::parse("5-2").is_err());
    /// assert!(CostRange::parse("0-3").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, BenchmarkGridError> {
        let bad = || BenchmarkGridError::Costs(crate::echo::echo(text));
        let (lo, hi) = text.split_once('-').unwrap_or((text, text));
        let int = |s: &str| s.trim().parse::<u32>().map_err(|_| bad());
        let (lo, hi) = (int(lo)?, int(hi)?);
        if lo == 0 || lo > hi || hi > Self::MAX {
            return Err(bad());
        }
        Ok(CostRange { lo, hi })
    }
}

/// A grid of the pattern family ([`GridPattern`]): `rows × cols` cells, costs from `range`
/// and `seed` for [`GridPattern::Random`] (the other patterns ignore both).
///
/// ```
/// use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
/// let walls = pattern_grid(3, 5, GridPattern::Walls, CostRange::DEFAULT, 0).unwrap();
/// assert_eq!(walls.states(), 13); // column 3 is a wall but for its bottom cell
/// assert_eq!(walls.goals(), &[12]);
/// let goals = pattern_grid(3, 3, GridPattern::Goals, CostRange::DEFAULT, 0).unwrap();
/// assert_eq!(goals.goals(), &[2, 4, 6, 8]);
/// let ties = pattern_grid(2, 2, GridPattern::Ties, CostRange::DEFAULT, 0).unwrap();
/// assert_eq!(ties.moves(3)[0].cost.to_string(), "3"); // leaves (1, 1): 1 + 2
/// ```
pub fn pattern_grid(
    rows: usize,
    cols: usize,
    pattern: GridPattern,
    range: CostRange,
    seed: u64,
) -> Result<Problem, BenchmarkGridError> {
    if !(1..=MAX_SIDE).contains(&rows) || !(1..=MAX_SIDE).contains(&cols) || rows * cols < 2 {
        return Err(BenchmarkGridError::Size(format!("{rows}x{cols}")));
    }
    let wall = |r: usize, c: usize| {
        pattern == GridPattern::Walls
            && c % 4 == 3
            && c + 1 < cols
            && r != if (c / 4).is_multiple_of(2) {
                rows - 1
            } else {
                0
            }
    };
    let mut index = vec![None; rows * cols];
    let mut cells = Vec::with_capacity(rows * cols);
    for r in 0..rows {
        for c in 0..cols {
            if !wall(r, c) {
                index[r * cols + c] = Some(cells.len());
                cells.push((r, c));
            }
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let span = range.hi - range.lo + 1;
    let costs: Vec<Rational> = (0..=3)
        .map(|c| Rational::from_integer((1 + c).into()))
        .collect();
    let mut moves = Vec::with_capacity(cells.len());
    for &(r, c) in &cells {
        let mut list = Vec::with_capacity(4);
        let neighbours = [
            (r > 0).then(|| (r - 1, c)),
            (c > 0).then(|| (r, c - 1)),
            (c + 1 < cols).then(|| (r, c + 1)),
            (r + 1 < rows).then(|| (r + 1, c)),
        ];
        for (nr, nc) in neighbours.into_iter().flatten() {
            let Some(successor) = index[nr * cols + nc] else {
                continue;
            };
            let cost = match pattern {
                GridPattern::Random => {
                    Rational::from_integer((range.lo + rng.next_u32() % span).into())
                }
                GridPattern::Unit | GridPattern::Walls => costs[0].clone(),
                GridPattern::Ties | GridPattern::Goals => costs[(r + c) % 4].clone(),
            };
            list.push(Move { successor, cost });
        }
        moves.push(list);
    }
    let at = |r: usize, c: usize| index[r * cols + c].expect("goal cells are free");
    let goals = if pattern == GridPattern::Goals {
        let mut g: Vec<usize> = [
            (0, cols - 1),
            (rows - 1, 0),
            (rows / 2, cols / 2),
            (rows - 1, cols - 1),
        ]
        .iter()
        .map(|&(r, c)| at(r, c))
        .filter(|&x| x != 0)
        .collect();
        g.sort_unstable();
        g.dedup();
        g
    } else {
        vec![at(rows - 1, cols - 1)]
    };
    Ok(Problem::new(moves, 0, goals).expect("a well-formed grid"))
}

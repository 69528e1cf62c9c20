//! The JSON problem-file format for user-defined deterministic problems.
//!
//! ```json
//! {
//!   "format": "truecost-problem/1",
//!   "name": "a line of three states",
//!   "states": 3,
//!   "initial": 0,
//!   "goals": [2],
//!   "actions": [
//!     [ { "to": 1, "cost": "1" } ],
//!     [ { "to": 0, "cost": "1" }, { "to": 2, "cost": "5/2" } ],
//!     []
//!   ]
//! }
//! ```
//!
//! * `actions[x]` is the ordered action list `U(x)` of state `x` (order matters: greedy ties and
//!   exploration follow it). A goal's list may be empty (goals always have the termination
//!   action); a non-goal state's list may not ("empty action set": give it a move, e.g. a
//!   self-loop, if it is a trap).
//! * Costs are **strings** holding exact non-negative numbers: `"1"`, `"0.25"`, `"800/19"`,
//!   `"1e-3"`. JSON numbers are refused: they would pass through `f64`.
//! * `format`, `name` and `states` are optional; `states`, if given, must equal the number of
//!   action lists. Unknown fields are refused. The format tag may also be
//!   `truecost-stochastic/1` (the stochastic format, [`crate::stochastic::file`], of which a
//!   file without `outcomes` is a deterministic problem); an action listing `outcomes` is
//!   refused here with a message naming it (only the stochastic solvers read those).
//!
//! Limits, each refusal naming its bound: a file of at most [`MAX_FILE_BYTES`]
//! bytes, read **once** (so `/dev/stdin`, pipes and FIFOs work); each number as in
//! [`crate::value::parse_rational`] (at most 4096 bytes, exponents within ±10000); the exact
//! numbers of one file at most [`MAX_NUMBER_BITS`] bits in all.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{ModelError, Move, Problem};
use crate::echo::echo;
use crate::value::{parse_rational, Extended, ParseRationalError, Rational};

/// The format tag written by [`to_json`].
pub const FORMAT: &str = "truecost-problem/1";

/// The format tag of stochastic files ([`crate::stochastic::file::FORMAT`]).
pub const STOCHASTIC_FORMAT: &str = "truecost-stochastic/1";

/// The largest problem file read, in bytes (32 MiB: a 100×100 stochastic grid with every
/// outcome listed takes about 6 MiB).
pub const MAX_FILE_BYTES: u64 = 32 << 20;

/// The most bits all exact numbers (costs, probabilities) of one file may take together
/// (numerators and denominators), so that a small file of huge exponents cannot fill memory.
pub const MAX_NUMBER_BITS: u64 = 1 << 28;

/// Why a problem file was refused. Every message fits on one line.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file could not be read.
    #[error("cannot read problem file {}: {source}", echo(.path))]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is larger than [`MAX_FILE_BYTES`].
    #[error("problem file {} is larger than {} bytes (32 MiB), the limit of this reader", echo(.path), MAX_FILE_BYTES)]
    TooLarge {
        /// The path.
        path: String,
    },
    /// The exact numbers of the file exceed [`MAX_NUMBER_BITS`].
    #[error("state {state}, action {action}: the exact numbers of this file take more than 2^28 bits in all, the limit of this reader")]
    NumbersTooLarge {
        /// The state where the budget ran out.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// A deterministic action without its successor.
    #[error("state {state}, action {action}: missing field `to` (the successor of a deterministic move)")]
    MissingSuccessor {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// An action listing outcomes where a deterministic problem is needed.
    #[error("state {state}, action {action} lists outcomes (a stochastic action): this command needs a deterministic problem (stochastic files are solved by `solve --algorithm exact|vi|async-vi` and drawn by `render`)")]
    Stochastic {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// Not valid JSON of the expected shape.
    #[error("problem file is not valid: {0}")]
    Json(String),
    /// A format tag this version does not read.
    #[error("unsupported format '{}' (this truecost reads '{FORMAT}' and '{STOCHASTIC_FORMAT}')", echo(.0))]
    Format(String),
    /// `states` disagrees with the action lists.
    #[error("'states' is {states} but {lists} action lists are given")]
    StatesMismatch {
        /// `states`.
        states: usize,
        /// Number of lists.
        lists: usize,
    },
    /// A cost that is not an exact number.
    #[error("state {state}, action {action}: {source}")]
    Cost {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
        /// The cause.
        source: ParseRationalError,
    },
    /// A non-goal state without actions.
    #[error("state {0} has an empty action set (only goals may have none; model a trap with a self-loop)")]
    EmptyActions(usize),
    /// The problem itself is ill formed.
    #[error("{0}")]
    Model(#[from] ModelError),
}

/// The JSON shape of a problem file, shared with the stochastic format; `A` is an action entry.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FileProblem<A> {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) format: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) states: Option<usize>,
    pub(crate) initial: usize,
    pub(crate) goals: Vec<usize>,
    pub(crate) actions: Vec<Vec<A>>,
}

impl<A: serde::de::DeserializeOwned> FileProblem<A> {
    /// Parses the JSON text; a serde error becomes one line.
    pub(crate) fn parse(text: &str) -> Result<Self, FileError> {
        serde_json::from_str(text).map_err(|e| FileError::Json(one_line(&e.to_string())))
    }
}

impl<A> FileProblem<A> {
    /// Checks the optional format tag: one of the two formats this version reads.
    pub(crate) fn check_format(&self) -> Result<(), FileError> {
        match &self.format {
            Some(f) if f != FORMAT && f != STOCHASTIC_FORMAT => Err(FileError::Format(f.clone())),
            _ => Ok(()),
        }
    }

    /// Checks the optional `states` against the number of action lists.
    pub(crate) fn check_states(&self) -> Result<(), FileError> {
        match self.states {
            Some(states) if states != self.actions.len() => Err(FileError::StatesMismatch {
                states,
                lists: self.actions.len(),
            }),
            _ => Ok(()),
        }
    }
}

/// Parses the exact cost text of action `action` of `state`.
pub(crate) fn parse_cost(
    state: usize,
    action: usize,
    text: &str,
) -> Result<crate::value::Rational, FileError> {
    parse_rational(text).map_err(|source| FileError::Cost {
        state,
        action,
        source,
    })
}

/// An action entry of either format: a deterministic move `{to, cost}` or a stochastic action
/// `{cost, outcomes}` (only the stochastic reader accepts the latter).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FileAction {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) to: Option<usize>,
    pub(crate) cost: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) outcomes: Option<Vec<FileOutcome>>,
}

/// One listed outcome `{to, p}` of a stochastic action.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FileOutcome {
    pub(crate) to: usize,
    pub(crate) p: String,
}

/// The running total of the bits of a file's exact numbers (checked against
/// [`MAX_NUMBER_BITS`] as the numbers are parsed).
#[derive(Default)]
pub(crate) struct NumberBudget(u64);

impl NumberBudget {
    /// Counts `r` (parsed at `state`, `action`); refuses once the total passes the bound.
    pub(crate) fn take(
        &mut self,
        r: &Rational,
        state: usize,
        action: usize,
    ) -> Result<(), FileError> {
        self.0 += r.numer().bits() + r.denom().bits();
        if self.0 > MAX_NUMBER_BITS {
            return Err(FileError::NumbersTooLarge { state, action });
        }
        Ok(())
    }
}

/// Parses a problem file's text (a deterministic problem: no action may list outcomes).
///
/// ```
/// let text = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "800/19"}], []]}"#;
/// let p = truecost::model::file::from_json(text).unwrap();
/// assert_eq!(p.states(), 2);
/// assert!(truecost::model::file::from_json(r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": 1.5}], []]}"#).is_err());
/// // The stochastic tag is accepted when no action lists outcomes.
/// let tagged = text.replace("{\"initial\"", "{\"format\": \"truecost-stochastic/1\", \"initial\"");
/// assert_eq!(truecost::model::file::from_json(&tagged).unwrap(), p);
/// ```
pub fn from_json(text: &str) -> Result<Problem, FileError> {
    from_file(FileProblem::<FileAction>::parse(text)?)
}

/// Builds the deterministic problem of a parsed file (shared with the stochastic reader).
pub(crate) fn from_file(file: FileProblem<FileAction>) -> Result<Problem, FileError> {
    file.check_format()?;
    file.check_states()?;
    let mut budget = NumberBudget::default();
    let mut moves = Vec::with_capacity(file.actions.len());
    for (x, list) in file.actions.iter().enumerate() {
        let mut row = Vec::with_capacity(list.len());
        for (a, action) in list.iter().enumerate() {
            if action.outcomes.is_some() {
                return Err(FileError::Stochastic {
                    state: x,
                    action: a,
                });
            }
            let successor = action.to.ok_or(FileError::MissingSuccessor {
                state: x,
                action: a,
            })?;
            let cost = parse_cost(x, a, &action.cost)?;
            budget.take(&cost, x, a)?;
            row.push(Move { successor, cost });
        }
        moves.push(row);
    }
    let problem = Problem::new(moves, file.initial, file.goals)?;
    if let Some(x) =
        (0..problem.states()).find(|&x| problem.moves(x).is_empty() && !problem.is_goal(x))
    {
        return Err(FileError::EmptyActions(x));
    }
    Ok(problem)
}

/// Reads a problem file's text **once**, at most [`MAX_FILE_BYTES`] bytes (so standard input,
/// pipes and FIFOs work, and `/dev/zero` is refused rather than read for ever).
///
/// ```
/// use truecost::model::file::{read_text, FileError};
/// let err = read_text(std::path::Path::new("/no/such/file.json")).unwrap_err();
/// assert!(matches!(err, FileError::Io { .. }));
/// ```
pub fn read_text(path: &Path) -> Result<String, FileError> {
    use crate::bounded::BoundedError;
    let path_text = || path.display().to_string();
    crate::bounded::read_text(path, MAX_FILE_BYTES, "problem files").map_err(|e| match e {
        BoundedError::Io { source, .. } => FileError::Io {
            path: path_text(),
            source,
        },
        BoundedError::TooLarge { .. } => FileError::TooLarge { path: path_text() },
        BoundedError::NotText { .. } => FileError::Io {
            path: path_text(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "stream did not contain valid UTF-8",
            ),
        },
    })
}

/// Reads and parses a deterministic problem file (read once, see [`read_text`]).
pub fn read(path: &Path) -> Result<Problem, FileError> {
    from_json(&read_text(path)?)
}

/// Writes a problem in the file format (costs as exact strings); `from_json` reads it back.
///
/// ```
/// use truecost::model::{file, Move, Problem};
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: truecost::value::parse_rational("0.5").unwrap() }], vec![]], 0, vec![1]).unwrap();
/// let text = file::to_json(&p, Some("half"));
/// assert!(text.contains("\"1/2\""));
/// assert_eq!(file::from_json(&text).unwrap(), p);
/// ```
pub fn to_json(problem: &Problem, name: Option<&str>) -> String {
    let file = FileProblem {
        format: Some(FORMAT.to_string()),
        name: name.map(str::to_string),
        states: Some(problem.states()),
        initial: problem.initial(),
        goals: problem.goals().to_vec(),
        actions: (0..problem.states())
            .map(|x| {
                problem
                    .moves(x)
                    .iter()
                    .map(|m| FileAction {
                        to: Some(m.successor),
                        cost: Extended::Finite(m.cost.clone()).to_string(),
                        outcomes: None,
                    })
                    .collect()
            })
            .collect(),
    };
    serde_json::to_string_pretty(&file).expect("serialisable")
}

/// A serde message as one short line (it may quote a key or value of the file).
fn one_line(s: &str) -> String {
    crate::echo::escape(&s.split_whitespace().collect::<Vec<_>>().join(" "), 200)
}

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
//!   action lists. Unknown fields are refused.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{ModelError, Move, Problem};
use crate::value::{parse_rational, Extended, ParseRationalError};

/// The format tag written by [`to_json`].
pub const FORMAT: &str = "truecost-problem/1";

/// Why a problem file was refused. Every message fits on one line.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file could not be read.
    #[error("cannot read problem file {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// Not valid JSON of the expected shape.
    #[error("problem file is not valid: {0}")]
    Json(String),
    /// A format tag this version does not read.
    #[error("unsupported format '{0}' (this truecost reads '{FORMAT}')")]
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

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileAction {
    to: usize,
    cost: String,
}

/// Parses a problem file's text.
///
/// ```
/// let text = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "800/19"}], []]}"#;
/// let p = truecost::model::file::from_json(text).unwrap();
/// assert_eq!(p.states(), 2);
/// assert!(truecost::model::file::from_json(r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": 1.5}], []]}"#).is_err());
/// ```
pub fn from_json(text: &str) -> Result<Problem, FileError> {
    let file = FileProblem::<FileAction>::parse(text)?;
    if let Some(f) = &file.format {
        if f != FORMAT {
            return Err(FileError::Format(f.clone()));
        }
    }
    file.check_states()?;
    let mut moves = Vec::with_capacity(file.actions.len());
    for (x, list) in file.actions.iter().enumerate() {
        let mut row = Vec::with_capacity(list.len());
        for (a, action) in list.iter().enumerate() {
            row.push(Move {
                successor: action.to,
                cost: parse_cost(x, a, &action.cost)?,
            });
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

/// Reads and parses a problem file.
pub fn read(path: &Path) -> Result<Problem, FileError> {
    let text = std::fs::read_to_string(path).map_err(|source| FileError::Io {
        path: path.display().to_string(),
        source,
    })?;
    from_json(&text)
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
                        to: m.successor,
                        cost: Extended::Finite(m.cost.clone()).to_string(),
                    })
                    .collect()
            })
            .collect(),
    };
    serde_json::to_string_pretty(&file).expect("serialisable")
}

fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

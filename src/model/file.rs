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
//! * `initial` is the initial state `x1` (a state number), or an initial **distribution**: a
//!   list `[{"state": x, "p": "q"}, ...]` of distinct states with probabilities that are
//!   **strings** holding exact numbers in `(0, 1]` (JSON numbers are refused, as for costs) and
//!   sum to exactly 1; each violation is refused naming the entry (numbered from 0). A list of
//!   one entry (probability 1) is the same as the number. The problem read keeps the first
//!   listed state as its initial state; the distribution itself is returned in a
//!   [`FileObjective`] by [`from_json_with_objective`] and
//!   [`crate::stochastic::file::from_json_with_objective`], for the objectives' model, whose
//!   values at the initial state are expectations over it. [`from_json`] and [`read`] refuse a
//!   distribution of two or more states ([`FileError::InitialDistribution`]): what they return
//!   has a single initial state, and their callers use it.
//! * Optional, for the discounted objective (what a reinforcement-learning agent maximises):
//!   a `"reward": "r"` on an action, an exact number as a string like costs (it may be
//!   negative; JSON numbers are refused), is the action's expected reward, received whatever
//!   the outcome; either every action of the file has one or none has (the first action without
//!   one is named). Without rewards the discounted objective rewards the negated stage costs.
//!   A top-level `"terminal": [x, ...]` lists non-goal states where the episode ends (no reward
//!   any more, like Gymnasium's holes); each must be a state, not a goal, listed once, and every
//!   action it has must be a zero-cost self-loop (with reward 0 when rewards are given). Goals,
//!   and states without actions, always end the episode. The readers that need them return both
//!   in a [`FileObjective`] ([`crate::stochastic::file::from_json_with_objective`]); every other
//!   command checks and ignores them.
//! * `format`, `name` and `states` are optional; `states`, if given, must equal the number of
//!   action lists. Unknown fields are refused. The format tag may also be
//!   `truecost-stochastic/1` (the stochastic format, [`crate::stochastic::file`], of which a
//!   file without `outcomes` is a deterministic problem); an action listing `outcomes` is
//!   refused here with a message naming it (only the stochastic solvers read those).
//!
//! Limits, each refusal naming its bound: a file of at most [`MAX_FILE_BYTES`]
//! bytes, read **once** (so `/dev/stdin`, pipes and FIFOs work); each number as in
//! [`crate::value::parse_rational`] (at most 4096 bytes, exponents within ±10000); the exact
//! numbers of one file (costs, rewards, probabilities, the initial distribution's included) at
//! most [`MAX_NUMBER_BITS`] bits in all, counted in lowest terms as they are read and, before
//! any is read, from their digit counts and exponents (a lower bound, so that a file of huge
//! exponents is refused without reducing a number); the lcm of the stage costs' denominators
//! at most [`MAX_COST_DENOMINATOR_BITS`] bits.

use std::path::Path;

use num_traits::{One, Zero};
use serde::{Deserialize, Serialize};

use super::{ModelError, Move, Problem, StateId};
use crate::echo::echo;
use crate::value::{parse_rational, Extended, ParseRationalError, Rational};

/// The format tag written by [`to_json`].
pub const FORMAT: &str = "truecost-problem/1";

/// The format tag of stochastic files ([`crate::stochastic::file::FORMAT`]).
pub const STOCHASTIC_FORMAT: &str = "truecost-stochastic/1";

/// The largest problem file read, in bytes (32 MiB: a 100×100 stochastic grid with every
/// outcome listed takes about 6 MiB).
pub const MAX_FILE_BYTES: u64 = 32 << 20;

/// The most bits of the lcm of a deterministic file's stage-cost denominators, checked as they
/// are read: every sum of stage costs (a path's cost, as the planners add them up) has a
/// denominator dividing it, so the planners' exact sums stay small. The stochastic model takes
/// the same bound ([`crate::stochastic::problem::MAX_SCALED_COST_BITS`]); 200 costs
/// `1/(k·10^10000)` made an lcm of millions of bits, and the planners' sums ran for minutes.
pub const MAX_COST_DENOMINATOR_BITS: u64 = 1024;

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
    #[error("state {state}, action {action}: the exact numbers of this file take {bits} bits up to here, more than 2^28 = {MAX_NUMBER_BITS} bits in all, the limit of this reader")]
    NumbersTooLarge {
        /// The state where the budget ran out.
        state: usize,
        /// The action index.
        action: usize,
        /// The bits counted up to and including this number.
        bits: u64,
    },
    /// The exact numbers of the file must exceed [`MAX_NUMBER_BITS`], counted from their digits
    /// and exponents before any is read (`FileProblem::check_number_bits`).
    #[error("{at}: the exact numbers of this file take at least {bits} bits up to here (counted from their digits and exponents before reading them), more than 2^28 = {MAX_NUMBER_BITS} bits in all, the limit of this reader")]
    NumbersAtLeast {
        /// Where the count passed the bound: `state s, action a` or `initial entry e`.
        at: String,
        /// The lower bound counted up to and including this number.
        bits: u64,
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
    /// A reward that is not an exact number.
    #[error("state {state}, action {action}: reward {source}")]
    Reward {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
        /// The cause.
        source: ParseRationalError,
    },
    /// Some actions have a reward, this one has none.
    #[error("state {state}, action {action} has no \"reward\" while other actions of this file have one: give every action a reward, or none (the discounted objective then rewards the negated stage costs)")]
    MissingReward {
        /// The state of the first action without a reward.
        state: usize,
        /// Its index.
        action: usize,
    },
    /// A `terminal` entry that is not a state.
    #[error("terminal state {state} is not a state of this problem (states 0 to {last})")]
    TerminalOutOfRange {
        /// The entry.
        state: usize,
        /// The last state.
        last: usize,
    },
    /// A `terminal` entry that is a goal.
    #[error("terminal state {0} is a goal: goals always end the episode, list only non-goal states in \"terminal\"")]
    TerminalGoal(usize),
    /// A `terminal` entry listed twice.
    #[error("terminal state {0} is listed twice")]
    TerminalDuplicate(usize),
    /// An action of a terminal state that is not a zero-cost self-loop.
    #[error("terminal state {state}, action {action}: the actions of a terminal state must be zero-cost self-loops (the episode is over there)")]
    TerminalAction {
        /// The terminal state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// An action of a terminal state with a nonzero reward.
    #[error("terminal state {state}, action {action}: reward {reward}, but the actions of a terminal state must have reward 0 (the episode is over there)")]
    TerminalReward {
        /// The terminal state.
        state: usize,
        /// The action index.
        action: usize,
        /// The reward, shortened.
        reward: String,
    },
    /// The lcm of a deterministic file's stage-cost denominators exceeds
    /// [`MAX_COST_DENOMINATOR_BITS`].
    #[error("state {state}, action {action}: the lcm of the stage costs' denominators up to here takes {bits} bits; the exact solvers take at most {MAX_COST_DENOMINATOR_BITS} (refused before any work)")]
    CostDenominators {
        /// The state where the lcm passed the bound.
        state: usize,
        /// The action index.
        action: usize,
        /// The lcm's bits.
        bits: u64,
    },
    /// The exact numbers of the file exceed [`MAX_NUMBER_BITS`] in the initial distribution.
    #[error("initial entry {entry}: the exact numbers of this file take {bits} bits up to here, more than 2^28 = {MAX_NUMBER_BITS} bits in all, the limit of this reader")]
    InitialNumbersTooLarge {
        /// The entry of the `initial` list where the budget ran out.
        entry: usize,
        /// The bits counted up to and including this number.
        bits: u64,
    },
    /// An empty `initial` list.
    #[error("\"initial\" is an empty list: give a state number or at least one {{\"state\": x, \"p\": \"q\"}} entry")]
    InitialEmpty,
    /// An `initial` entry whose state is not a state of the problem.
    #[error(
        "initial entry {entry}: state {state} is not a state of this problem (states 0 to {last})"
    )]
    InitialOutOfRange {
        /// The entry (numbered from 0).
        entry: usize,
        /// Its state.
        state: usize,
        /// The last state.
        last: usize,
    },
    /// An `initial` entry whose state an earlier entry lists.
    #[error("initial entry {entry}: state {state} is listed twice (first in entry {first})")]
    InitialDuplicate {
        /// The entry (numbered from 0).
        entry: usize,
        /// Its state.
        state: usize,
        /// The earlier entry listing it.
        first: usize,
    },
    /// An `initial` probability that is not a string.
    #[error("initial entry {entry} (state {state}): probability {found} is not a string: write it as an exact number in a string (\"1/3\", \"0.25\"), a JSON number would pass through f64")]
    InitialNotText {
        /// The entry (numbered from 0).
        entry: usize,
        /// Its state.
        state: usize,
        /// The JSON value found, shortened.
        found: String,
    },
    /// An `initial` probability that is not an exact number.
    #[error("initial entry {entry} (state {state}): probability {source}")]
    InitialProbability {
        /// The entry (numbered from 0).
        entry: usize,
        /// Its state.
        state: usize,
        /// The cause.
        source: ParseRationalError,
    },
    /// An `initial` probability outside `(0, 1]`.
    #[error("initial entry {entry} (state {state}): probability {probability} is not in (0, 1]")]
    InitialRange {
        /// The entry (numbered from 0).
        entry: usize,
        /// Its state.
        state: usize,
        /// The probability, shortened.
        probability: String,
    },
    /// `initial` probabilities that do not sum to 1.
    #[error("the initial probabilities sum to {sum}, not 1")]
    InitialSum {
        /// The sum, shortened.
        sum: String,
    },
    /// A file that draws its initial state from several states, read by a command that needs a
    /// single initial state ([`FileObjective::single_initial`]; [`from_json`] and [`read`]
    /// refuse it for any command).
    #[error("this file draws its initial state from {states} states; {command} needs a single initial state (solve --objective, compare and discount take the distribution)")]
    InitialDistribution {
        /// The number of states of the distribution.
        states: usize,
        /// The command, or "this command".
        command: String,
    },
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
    pub(crate) initial: FileInitial,
    pub(crate) goals: Vec<usize>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub(crate) terminal: Option<Vec<usize>>,
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
}

impl FileProblem<FileAction> {
    /// Checks the optional `states` against the number of action lists, then the exact
    /// numbers' size before any is read (`FileProblem::check_number_bits`).
    pub(crate) fn check_states(&self) -> Result<(), FileError> {
        match self.states {
            Some(states) if states != self.actions.len() => Err(FileError::StatesMismatch {
                states,
                lists: self.actions.len(),
            }),
            _ => self.check_number_bits(),
        }
    }

    /// Refuses, before any number is read, a file whose exact numbers must take more than
    /// [`MAX_NUMBER_BITS`] bits: the lower bounds of [`crate::value::bits_lower_bound`] (from
    /// the digit counts and exponents) added up in the order the readers read the numbers
    /// (per action its cost, reward and probabilities; then the initial distribution). The
    /// readers' own count, of the numbers in lowest terms, is at least this sum, so no file
    /// they accept is refused here; a file of huge exponents is refused without reducing any
    /// of its numbers.
    pub(crate) fn check_number_bits(&self) -> Result<(), FileError> {
        use crate::value::bits_lower_bound;
        let mut bits = 0u64;
        let mut over = |text: &str| {
            bits = bits.saturating_add(bits_lower_bound(text));
            bits > MAX_NUMBER_BITS
        };
        for (state, list) in self.actions.iter().enumerate() {
            for (action, a) in list.iter().enumerate() {
                let texts = std::iter::once(&a.cost)
                    .chain(a.reward.iter())
                    .chain(a.outcomes.iter().flatten().map(|o| &o.p));
                for text in texts {
                    if over(text) {
                        return Err(FileError::NumbersAtLeast {
                            at: format!("state {state}, action {action}"),
                            bits,
                        });
                    }
                }
            }
        }
        if let FileInitial::Distribution(list) = &self.initial {
            for (entry, e) in list.iter().enumerate() {
                if let serde_json::Value::String(text) = &e.p {
                    if over(text) {
                        return Err(FileError::NumbersAtLeast {
                            at: format!("initial entry {entry}"),
                            bits,
                        });
                    }
                }
            }
        }
        Ok(())
    }
}

/// A file's `initial`: a state number, or a list of `{"state": x, "p": "q"}` entries (module
/// docs; checked by [`read_initial`]).
#[derive(Serialize)]
#[serde(untagged)]
pub(crate) enum FileInitial {
    /// `"initial": x`.
    State(usize),
    /// `"initial": [{"state": x, "p": "q"}, ...]`.
    Distribution(Vec<FileInitialEntry>),
}

/// One entry `{"state": x, "p": "q"}` of an initial distribution. The probability is kept as
/// the JSON value given, so that a JSON number is refused naming its entry.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FileInitialEntry {
    pub(crate) state: usize,
    pub(crate) p: serde_json::Value,
}

impl<'de> Deserialize<'de> for FileInitial {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Initial;
        impl<'de> serde::de::Visitor<'de> for Initial {
            type Value = FileInitial;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(r#"a state number or a list of {"state": x, "p": "q"} entries"#)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<FileInitial, E> {
                usize::try_from(v)
                    .map(FileInitial::State)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Unsigned(v), &self))
            }
            fn visit_seq<S: serde::de::SeqAccess<'de>>(
                self,
                mut seq: S,
            ) -> Result<FileInitial, S::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = seq.next_element()? {
                    entries.push(entry);
                }
                Ok(FileInitial::Distribution(entries))
            }
        }
        deserializer.deserialize_any(Initial)
    }
}

/// An initial distribution: `(state, probability)` in the file's order.
type Distribution = Vec<(StateId, Rational)>;

/// A file's initial state as [`Problem::new`] takes it (the first listed state of a
/// distribution) and, for a distribution of two or more states, the distribution in the
/// file's order. `states` is the number of action lists; a state number is checked by the
/// problem itself, each entry of a list here (module docs), its probabilities counted in
/// `budget`.
pub(crate) fn read_initial(
    initial: &FileInitial,
    states: usize,
    budget: &mut NumberBudget,
) -> Result<(StateId, Option<Distribution>), FileError> {
    let list = match initial {
        FileInitial::State(x) => return Ok((*x, None)),
        FileInitial::Distribution(list) => list,
    };
    if states == 0 {
        return Err(ModelError::NoStates.into());
    }
    let Some(first) = list.first() else {
        return Err(FileError::InitialEmpty);
    };
    let mut listed_in: Vec<Option<usize>> = vec![None; states];
    let mut distribution = Vec::with_capacity(list.len());
    let mut sum = Rational::zero();
    for (entry, e) in list.iter().enumerate() {
        let state = e.state;
        if state >= states {
            return Err(FileError::InitialOutOfRange {
                entry,
                state,
                last: states - 1,
            });
        }
        if let Some(first) = listed_in[state] {
            return Err(FileError::InitialDuplicate {
                entry,
                state,
                first,
            });
        }
        listed_in[state] = Some(entry);
        let serde_json::Value::String(text) = &e.p else {
            return Err(FileError::InitialNotText {
                entry,
                state,
                found: echo(&e.p.to_string()),
            });
        };
        let p = parse_rational(text).map_err(|source| FileError::InitialProbability {
            entry,
            state,
            source,
        })?;
        if budget.over(&p) {
            return Err(FileError::InitialNumbersTooLarge {
                entry,
                bits: budget.0,
            });
        }
        if !crate::value::in_unit_interval_open_closed(&p) {
            return Err(FileError::InitialRange {
                entry,
                state,
                probability: echo(&Extended::Finite(p).to_string()),
            });
        }
        sum += &p;
        distribution.push((state, p));
    }
    if !sum.is_one() {
        return Err(FileError::InitialSum {
            sum: echo(&Extended::Finite(sum).to_string()),
        });
    }
    Ok((
        first.state,
        (distribution.len() > 1).then_some(distribution),
    ))
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
    pub(crate) reward: Option<String>,
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
        if self.over(r) {
            return Err(FileError::NumbersTooLarge {
                state,
                action,
                bits: self.0,
            });
        }
        Ok(())
    }

    /// Counts `r`; whether the total has passed the bound.
    pub(crate) fn over(&mut self, r: &Rational) -> bool {
        self.0 += r.numer().bits() + r.denom().bits();
        self.0 > MAX_NUMBER_BITS
    }
}

/// What a problem file says besides its problem, for the objectives' model (module docs): the
/// actions' rewards, if the file gives them, the non-goal states it lists as terminal, and
/// its initial distribution, if it draws the initial state from two or more states. The
/// default (no rewards, no terminal state, a single initial state) is a file without these.
///
/// ```
/// use truecost::stochastic::file::from_json_with_objective;
/// let text = r#"{"initial": [{"state": 2, "p": "1/4"}, {"state": 0, "p": "3/4"}], "goals": [1],
///     "terminal": [2], "actions": [
///     [{"to": 1, "cost": "1", "reward": "1"}, {"to": 2, "cost": "1", "reward": "-1/2"}],
///     [],
///     [{"to": 2, "cost": "0", "reward": "0"}]]}"#;
/// let (_, extra) = from_json_with_objective(text).unwrap();
/// let rewards: Vec<String> = extra.rewards.unwrap().iter().map(|r| r.to_string()).collect();
/// assert_eq!(rewards, ["1", "-1/2", "0"]);
/// assert_eq!(extra.terminal, [2]);
/// let initial: Vec<(usize, String)> =
///     extra.initial.unwrap().iter().map(|(x, p)| (*x, p.to_string())).collect();
/// assert_eq!(initial, [(2, "1/4".to_string()), (0, "3/4".to_string())]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileObjective {
    /// The expected reward of every action in the problem's global action order (state by
    /// state, each state's actions in the file's order), or `None` if the file gives no
    /// reward (the discounted objective then rewards the negated stage costs).
    pub rewards: Option<Vec<Rational>>,
    /// The non-goal states the file lists as terminal, in increasing order.
    pub terminal: Vec<StateId>,
    /// The initial distribution in the file's order (distinct states, probabilities in
    /// `(0, 1]` summing to 1), if the file draws the initial state from two or more states;
    /// the problem read with it has the first listed state as its initial state. `None`: the
    /// problem's own initial state, with probability 1.
    pub initial: Option<Vec<(StateId, Rational)>>,
}

impl FileObjective {
    /// Refuses a file that draws its initial state from two or more states, for `command`,
    /// which needs a single initial state (one line naming it; module docs).
    ///
    /// ```
    /// use truecost::stochastic::file::from_json_with_objective;
    /// let text = r#"{"initial": [{"state": 0, "p": "1/2"}, {"state": 1, "p": "1/2"}],
    ///     "goals": [2], "actions": [[{"to": 2, "cost": "1"}], [{"to": 2, "cost": "1"}], []]}"#;
    /// let (_, extra) = from_json_with_objective(text).unwrap();
    /// let e = extra.single_initial("render").unwrap_err().to_string();
    /// assert!(e.starts_with("this file draws its initial state from 2 states; render needs a single initial state"), "{e}");
    /// ```
    pub fn single_initial(&self, command: &str) -> Result<(), FileError> {
        match &self.initial {
            Some(d) => Err(FileError::InitialDistribution {
                states: d.len(),
                command: command.to_string(),
            }),
            None => Ok(()),
        }
    }
}

/// Collects the optional rewards of a file's actions as they are parsed (all or none).
#[derive(Default)]
pub(crate) struct RewardReader {
    given: Vec<Rational>,
    first_missing: Option<(usize, usize)>,
}

impl RewardReader {
    /// Reads the reward of action `action` of `state`, if it has one.
    pub(crate) fn take(
        &mut self,
        entry: &FileAction,
        state: usize,
        action: usize,
        budget: &mut NumberBudget,
    ) -> Result<(), FileError> {
        match &entry.reward {
            Some(text) => {
                let r = parse_rational(text).map_err(|source| FileError::Reward {
                    state,
                    action,
                    source,
                })?;
                budget.take(&r, state, action)?;
                self.given.push(r);
            }
            None => {
                self.first_missing.get_or_insert((state, action));
            }
        }
        match self.first_missing {
            // The first action without a reward, once some action has one.
            Some((state, action)) if !self.given.is_empty() => {
                Err(FileError::MissingReward { state, action })
            }
            _ => Ok(()),
        }
    }

    /// The rewards of every action, or `None` if no action has one.
    pub(crate) fn finish(self) -> Option<Vec<Rational>> {
        (!self.given.is_empty()).then_some(self.given)
    }
}

/// Checks a file's `terminal` list against its problem (module docs) and returns it sorted:
/// `actions(x)` is the range of global ids of the actions of `x`, `zero_self_loop(x, a)`
/// whether action `a` of `x` is a zero-cost self-loop.
pub(crate) fn check_terminal(
    listed: Option<&[usize]>,
    states: usize,
    is_goal: impl Fn(usize) -> bool,
    actions: impl Fn(usize) -> std::ops::Range<usize>,
    zero_self_loop: impl Fn(usize, usize) -> bool,
    rewards: Option<&[Rational]>,
) -> Result<Vec<StateId>, FileError> {
    let mut seen = vec![false; states];
    for &x in listed.unwrap_or_default() {
        if x >= states {
            return Err(FileError::TerminalOutOfRange {
                state: x,
                last: states - 1,
            });
        }
        if is_goal(x) {
            return Err(FileError::TerminalGoal(x));
        }
        if seen[x] {
            return Err(FileError::TerminalDuplicate(x));
        }
        seen[x] = true;
        let range = actions(x);
        let first = range.start;
        for a in range {
            if !zero_self_loop(x, a) {
                return Err(FileError::TerminalAction {
                    state: x,
                    action: a - first,
                });
            }
            if let Some(r) = rewards.and_then(|r| r.get(a)).filter(|r| !r.is_zero()) {
                return Err(FileError::TerminalReward {
                    state: x,
                    action: a - first,
                    reward: crate::echo::echo(&Extended::Finite(r.clone()).to_string()),
                });
            }
        }
    }
    Ok((0..states).filter(|&x| seen[x]).collect())
}

/// Parses a problem file's text (a deterministic problem: no action may list outcomes, and
/// the initial state is a single state: a distribution of two or more states is refused,
/// [`FileError::InitialDistribution`]).
///
/// ```
/// let text = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "800/19"}], []]}"#;
/// let p = truecost::model::file::from_json(text).unwrap();
/// assert_eq!(p.states(), 2);
/// assert!(truecost::model::file::from_json(r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": 1.5}], []]}"#).is_err());
/// // The stochastic tag is accepted when no action lists outcomes.
/// let tagged = text.replace("{\"initial\"", "{\"format\": \"truecost-stochastic/1\", \"initial\"");
/// assert_eq!(truecost::model::file::from_json(&tagged).unwrap(), p);
/// // A one-entry distribution is the state itself.
/// let listed = text.replace("\"initial\": 0", r#""initial": [{"state": 0, "p": "1"}]"#);
/// assert_eq!(truecost::model::file::from_json(&listed).unwrap(), p);
/// ```
pub fn from_json(text: &str) -> Result<Problem, FileError> {
    let (problem, extra) = from_json_with_objective(text)?;
    extra.single_initial("this command")?;
    Ok(problem)
}

/// Parses a deterministic problem file's text with what it says besides the problem
/// ([`FileObjective`]: rewards, terminal states, initial distribution); the problem's
/// initial state is the first listed state of a distribution.
///
/// ```
/// use truecost::model::file::from_json_with_objective;
/// let text = r#"{"initial": [{"state": 1, "p": "1/3"}, {"state": 0, "p": "2/3"}], "goals": [2],
///     "actions": [[{"to": 2, "cost": "1"}], [{"to": 0, "cost": "1"}], []]}"#;
/// let (p, extra) = from_json_with_objective(text).unwrap();
/// assert_eq!(p.initial(), 1);
/// assert_eq!(extra.initial.unwrap().len(), 2);
/// let short = text.replace(r#""2/3""#, r#""1/3""#);
/// let e = from_json_with_objective(&short).unwrap_err().to_string();
/// assert_eq!(e, "the initial probabilities sum to 2/3, not 1");
/// ```
pub fn from_json_with_objective(text: &str) -> Result<(Problem, FileObjective), FileError> {
    from_file(FileProblem::<FileAction>::parse(text)?)
}

/// A number's text as a message shows it: whole up to 40 characters, otherwise its first 20
/// characters, "…" and its length (a cost of `-1e10000` has 10 002 characters).
///
/// ```text
/// short_number("-3/4") == "-3/4"
/// short_number(&format!("-1{}", "0".repeat(10_000))) == "-1000000000000000000… (10002 characters)"
/// ```
fn short_number(text: &str) -> String {
    if text.chars().count() <= 40 {
        return text.to_string();
    }
    let head: String = text.chars().take(20).collect();
    format!("{head}… ({} characters)", text.chars().count())
}

/// Builds the deterministic problem of a parsed file, with its rewards, terminal states and
/// initial distribution (shared with the stochastic reader).
pub(crate) fn from_file(
    file: FileProblem<FileAction>,
) -> Result<(Problem, FileObjective), FileError> {
    file.check_format()?;
    file.check_states()?;
    let mut budget = NumberBudget::default();
    let mut rewards = RewardReader::default();
    let mut moves = Vec::with_capacity(file.actions.len());
    let mut lcm = num_bigint::BigInt::one();
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
            lcm = num_integer::Integer::lcm(&lcm, cost.denom());
            if lcm.bits() > MAX_COST_DENOMINATOR_BITS {
                return Err(FileError::CostDenominators {
                    state: x,
                    action: a,
                    bits: lcm.bits(),
                });
            }
            rewards.take(action, x, a, &mut budget)?;
            row.push(Move { successor, cost });
        }
        moves.push(row);
    }
    let (x1, initial) = read_initial(&file.initial, file.actions.len(), &mut budget)?;
    let problem = Problem::new(moves, x1, file.goals).map_err(|e| match e {
        ModelError::NegativeCost {
            state,
            action,
            cost,
        } => ModelError::NegativeCost {
            state,
            action,
            cost: short_number(&cost),
        },
        e => e,
    })?;
    if let Some(x) =
        (0..problem.states()).find(|&x| problem.moves(x).is_empty() && !problem.is_goal(x))
    {
        return Err(FileError::EmptyActions(x));
    }
    let rewards = rewards.finish();
    let mut first = Vec::with_capacity(problem.states() + 1);
    first.push(0);
    for x in 0..problem.states() {
        first.push(first[x] + problem.moves(x).len());
    }
    let terminal = check_terminal(
        file.terminal.as_deref(),
        problem.states(),
        |x| problem.is_goal(x),
        |x| first[x]..first[x + 1],
        |x, a| {
            let m = &problem.moves(x)[a - first[x]];
            m.successor == x && m.cost.is_zero()
        },
        rewards.as_deref(),
    )?;
    Ok((
        problem,
        FileObjective {
            rewards,
            terminal,
            initial,
        },
    ))
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

/// Reads and parses a deterministic problem file (read once, see [`read_text`]); a
/// distribution of two or more initial states is refused, as by [`from_json`].
pub fn read(path: &Path) -> Result<Problem, FileError> {
    from_json(&read_text(path)?)
}

/// Reads and parses a deterministic problem file with what it says besides the problem
/// ([`from_json_with_objective`]; read once, see [`read_text`]).
pub fn read_with_objective(path: &Path) -> Result<(Problem, FileObjective), FileError> {
    from_json_with_objective(&read_text(path)?)
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
        initial: FileInitial::State(problem.initial()),
        goals: problem.goals().to_vec(),
        terminal: None,
        actions: (0..problem.states())
            .map(|x| {
                problem
                    .moves(x)
                    .iter()
                    .map(|m| FileAction {
                        to: Some(m.successor),
                        cost: Extended::Finite(m.cost.clone()).to_string(),
                        reward: None,
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

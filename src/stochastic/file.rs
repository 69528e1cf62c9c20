//! Stochastic extensions of the JSON problem file ([`crate::model::file`]).
//!
//! An action may list its outcomes instead of a single successor:
//!
//! ```json
//! {
//!   "format": "truecost-stochastic/1",
//!   "name": "a slippery corridor",
//!   "initial": 0,
//!   "goals": [2],
//!   "actions": [
//!     [ { "cost": "1", "outcomes": [ { "to": 1, "p": "0.9" }, { "to": 0, "p": "0.1" } ] } ],
//!     [ { "cost": "1", "outcomes": [ { "to": 2, "p": "3/4" }, { "to": 0, "p": "1/4" } ] },
//!       { "to": 0, "cost": "1/2" } ],
//!     []
//!   ]
//! }
//! ```
//!
//! * An action is either deterministic, `{ "to": y, "cost": c }` (outcome `y` with probability
//!   1), or stochastic, `{ "cost": c, "outcomes": [ { "to": y, "p": q }, ... ] }`; not both.
//! * Probabilities are **strings** holding exact numbers in `(0, 1]` (`"0.9"`, `"1/3"`); the
//!   probabilities of an action must sum to exactly 1. JSON numbers are refused (they would pass
//!   through `f64`). Outcomes are kept in the order given (a sampler draws them in that order).
//! * The cost is paid whatever the outcome. Costs, goals, `initial`, `states`, `name` and the
//!   "only goals may have an empty action list" rule are as in the deterministic format.
//! * `initial` is a state number or an initial distribution
//!   `[{"state": x, "p": "q"}, ...]`, as in the deterministic format: distinct states,
//!   probabilities strings holding exact numbers in `(0, 1]` summing to exactly 1, a one-entry
//!   list the same as the number. The problem read has the first listed state as its initial
//!   state; [`from_json_with_objective`] returns the distribution (for the objectives' model),
//!   while [`from_json`] and [`read`] refuse a distribution of two or more states.
//! * `format` is optional; if given it is `truecost-stochastic/1` or `truecost-problem/1`, and a
//!   file tagged `truecost-problem/1` may not list outcomes.
//! * The discounted objective's optional fields are as in the deterministic format: a
//!   `"reward": "r"` on every action or on none (the action's expected reward, received
//!   whatever the outcome, like the cost), and `"terminal": [x, ...]`, non-goal states where the
//!   episode ends, whose actions must all be zero-cost self-loops (every outcome back to the
//!   state) with reward 0. [`from_json_with_objective`] returns them in a [`FileObjective`].
//! * The limits of [`crate::model::file`] apply (file size, number sizes); the file is read once.
//!
//! A file without any `outcomes` is a deterministic problem ([`ProblemFile::Deterministic`]), to
//! which a noise model and `γ` may be applied; a file with outcomes is a stochastic problem as
//! it stands ([`ProblemFile::Stochastic`]).

use std::path::Path;

use num_traits::Zero;

use super::problem::{StochasticAction, StochasticProblem};
use super::{Outcome, OutcomeKind, StochasticError};
pub use crate::model::file::FileObjective;
use crate::model::file::{
    self as det_file, FileAction, FileError, FileInitial, FileInitialEntry, FileOutcome,
    NumberBudget, RewardReader,
};
use crate::model::Problem;
use crate::value::{parse_rational, Extended, ParseRationalError};

/// The format tag written by [`to_json`].
pub const FORMAT: &str = "truecost-stochastic/1";

/// A problem file: deterministic (noise may be applied) or stochastic as given.
#[derive(Clone, Debug)]
pub enum ProblemFile {
    /// No action lists outcomes.
    Deterministic(Problem),
    /// Some action lists outcomes.
    Stochastic(Box<StochasticProblem>),
}

/// Why a stochastic problem file was refused. Every message fits on one line.
#[derive(Debug, thiserror::Error)]
pub enum StochasticFileError {
    /// As for deterministic files (I/O, JSON, costs, indices, empty action sets...).
    #[error("{0}")]
    File(#[from] FileError),
    /// An outcome probability that is not an exact number.
    #[error("state {state}, action {action}, outcome {outcome}: probability {source}")]
    Probability {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
        /// The outcome index.
        outcome: usize,
        /// The cause.
        source: ParseRationalError,
    },
    /// An action with both or neither of `to` and `outcomes`.
    #[error("state {state}, action {action}: give either \"to\" (a deterministic move) or \"outcomes\" (a stochastic action), exactly one of them")]
    Shape {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// A file tagged deterministic that lists outcomes.
    #[error("state {state}, action {action} lists outcomes, but the file is tagged 'truecost-problem/1' (deterministic): tag it 'truecost-stochastic/1'")]
    TaggedDeterministic {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// Probabilities out of range or not summing to 1, and similar.
    #[error("{0}")]
    Stochastic(#[from] StochasticError),
}

/// Checks a stochastic problem's `terminal` list (module docs of [`crate::model::file`]) and
/// returns it sorted: a terminal state's actions are zero-cost self-loops. Shared by the JSON
/// and DRN readers.
pub(crate) fn check_terminal(
    problem: &StochasticProblem,
    listed: Option<&[usize]>,
    rewards: Option<&[crate::value::Rational]>,
) -> Result<Vec<crate::model::StateId>, FileError> {
    det_file::check_terminal(
        listed,
        problem.states(),
        |x| problem.is_goal(x),
        |x| problem.actions(x),
        |x, a| problem.cost(a).is_zero() && problem.outcomes(a).iter().all(|o| o.successor == x),
        rewards,
    )
}

/// A stochastic problem file: the deterministic file's shape (its actions may list outcomes).
type FileProblem = det_file::FileProblem<FileAction>;

/// Parses a problem file's text (either format); a distribution of two or more initial
/// states is refused ([`FileError::InitialDistribution`]: the problem returned has a single
/// initial state, and callers use it).
///
/// ```
/// use truecost::stochastic::file::{from_json, ProblemFile};
/// let text = r#"{"initial": 0, "goals": [1], "actions": [
///     [{"cost": "1", "outcomes": [{"to": 1, "p": "0.9"}, {"to": 0, "p": "0.1"}]}], []]}"#;
/// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { panic!() };
/// assert_eq!(p.outcomes(0).len(), 2);
/// let bad = text.replace("0.1", "0.2");
/// assert!(from_json(&bad).unwrap_err().to_string().contains("sum to 11/10, not 1"));
/// let det = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1"}], []]}"#;
/// assert!(matches!(from_json(det).unwrap(), ProblemFile::Deterministic(_)));
/// ```
pub fn from_json(text: &str) -> Result<ProblemFile, StochasticFileError> {
    let (problem, extra) = from_json_with_objective(text)?;
    extra.single_initial("this command")?;
    Ok(problem)
}

/// [`from_json`] with what the file says besides the problem, for the objectives' model: the
/// actions' rewards (in the global action order of the problem returned), the terminal
/// states and the initial distribution (the problem returned has its first listed state as
/// initial state).
///
/// ```
/// use truecost::stochastic::file::{from_json, from_json_with_objective, ProblemFile};
/// let text = r#"{"initial": 0, "goals": [1], "terminal": [2], "actions": [
///     [{"cost": "1", "reward": "1/2", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 2, "p": "1/2"}]}],
///     [],
///     [{"cost": "0", "reward": "0", "outcomes": [{"to": 2, "p": "1"}]}]]}"#;
/// let (ProblemFile::Stochastic(_), extra) = from_json_with_objective(text).unwrap() else { panic!() };
/// assert_eq!(extra.rewards.unwrap()[0].to_string(), "1/2");
/// assert_eq!(extra.terminal, [2]);
/// assert_eq!(extra.initial, None);
/// // All or none: the second action has no reward.
/// let mixed = text.replace(r#""cost": "0", "reward": "0""#, r#""cost": "0""#);
/// let e = from_json_with_objective(&mixed).unwrap_err().to_string();
/// assert!(e.starts_with("state 2, action 0 has no \"reward\""), "{e}");
/// // A terminal state's actions are zero-cost self-loops.
/// let leaky = text.replace(r#"[{"to": 2, "p": "1"}]"#, r#"[{"to": 0, "p": "1"}]"#);
/// assert!(from_json_with_objective(&leaky).unwrap_err().to_string().contains("zero-cost self-loops"));
/// // An initial distribution: read here, refused by `from_json`.
/// let drawn = text.replace(r#""initial": 0"#, r#""initial": [{"state": 0, "p": "0.9"}, {"state": 2, "p": "0.1"}]"#);
/// let (ProblemFile::Stochastic(p), extra) = from_json_with_objective(&drawn).unwrap() else { panic!() };
/// assert_eq!((p.initial(), extra.initial.unwrap()[1].1.to_string()), (0, "1/10".to_string()));
/// assert!(from_json(&drawn).unwrap_err().to_string().contains("from 2 states; this command needs a single initial state"));
/// ```
pub fn from_json_with_objective(
    text: &str,
) -> Result<(ProblemFile, FileObjective), StochasticFileError> {
    let file = FileProblem::parse(text)?;
    file.check_format()?;
    let first_listing = file.actions.iter().enumerate().find_map(|(x, list)| {
        list.iter()
            .position(|a| a.outcomes.is_some())
            .map(|a| (x, a))
    });
    let Some((state, action)) = first_listing else {
        // No outcomes: a deterministic problem, whichever of the two tags it carries.
        let (problem, extra) = det_file::from_file(file)?;
        return Ok((ProblemFile::Deterministic(problem), extra));
    };
    if file.format.as_deref() == Some(det_file::FORMAT) {
        return Err(StochasticFileError::TaggedDeterministic { state, action });
    }
    file.check_states()?;
    let mut budget = NumberBudget::default();
    let mut rewards = RewardReader::default();
    let mut actions = Vec::with_capacity(file.actions.len());
    for (x, list) in file.actions.iter().enumerate() {
        let mut row = Vec::with_capacity(list.len());
        for (a, action) in list.iter().enumerate() {
            let cost = det_file::parse_cost(x, a, &action.cost)?;
            budget.take(&cost, x, a)?;
            rewards.take(action, x, a, &mut budget)?;
            let outcomes = match (&action.to, &action.outcomes) {
                (Some(to), None) => vec![Outcome {
                    successor: *to,
                    probability: crate::value::Rational::from_integer(1.into()),
                    kind: OutcomeKind::Listed,
                }],
                (None, Some(list)) => {
                    let mut outcomes = Vec::with_capacity(list.len());
                    for (i, o) in list.iter().enumerate() {
                        let probability = parse_rational(&o.p).map_err(|source| {
                            StochasticFileError::Probability {
                                state: x,
                                action: a,
                                outcome: i,
                                source,
                            }
                        })?;
                        budget.take(&probability, x, a)?;
                        outcomes.push(Outcome {
                            successor: o.to,
                            probability,
                            kind: OutcomeKind::Listed,
                        });
                    }
                    outcomes
                }
                _ => {
                    return Err(StochasticFileError::Shape {
                        state: x,
                        action: a,
                    })
                }
            };
            row.push(StochasticAction { cost, outcomes });
        }
        actions.push(row);
    }
    let (x1, initial) = det_file::read_initial(&file.initial, file.actions.len(), &mut budget)?;
    let problem = StochasticProblem::new(actions, x1, file.goals)?;
    if let Some(x) =
        (0..problem.states()).find(|&x| problem.actions(x).is_empty() && !problem.is_goal(x))
    {
        return Err(FileError::EmptyActions(x).into());
    }
    let rewards = rewards.finish();
    let terminal = check_terminal(&problem, file.terminal.as_deref(), rewards.as_deref())?;
    Ok((
        ProblemFile::Stochastic(Box::new(problem)),
        FileObjective {
            rewards,
            terminal,
            initial,
        },
    ))
}

/// Reads and parses a problem file (either format); a distribution of two or more initial
/// states is refused, as by [`from_json`].
///
/// The file is read once ([`det_file::read_text`]): standard input and pipes work.
pub fn read(path: &Path) -> Result<ProblemFile, StochasticFileError> {
    from_json(&det_file::read_text(path)?)
}

/// Reads and parses a problem file (either format) with its rewards, terminal states and
/// initial distribution ([`from_json_with_objective`]); read once, as [`read`].
pub fn read_with_objective(
    path: &Path,
) -> Result<(ProblemFile, FileObjective), StochasticFileError> {
    from_json_with_objective(&det_file::read_text(path)?)
}

/// Whether a file's text lists outcomes anywhere (it needs the stochastic solvers), without
/// validating the rest. Unreadable or malformed text gives `false`.
pub fn lists_outcomes(text: &str) -> bool {
    serde_json::from_str::<FileProblem>(text)
        .map(|f| f.actions.iter().flatten().any(|a| a.outcomes.is_some()))
        .unwrap_or(false)
}

/// Writes a stochastic problem in the file format (every action with its outcomes, exact
/// strings); [`from_json`] reads it back to the same transitions (provided every non-goal
/// state has an action: files refuse empty non-goal action lists, as deterministic files do).
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{file, NoiseModel, Predictability, StochasticProblem};
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: truecost::value::parse_rational("1").unwrap() }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.75").unwrap()).unwrap();
/// let text = file::to_json(&s, Some("one step"));
/// assert!(text.contains("\"3/4\""));
/// let file::ProblemFile::Stochastic(back) = file::from_json(&text).unwrap() else { panic!() };
/// assert_eq!(back.outcomes(0)[1].probability.to_string(), "1/4");
/// ```
pub fn to_json(problem: &StochasticProblem, name: Option<&str>) -> String {
    to_json_with_objective(problem, name, &FileObjective::default())
}

/// [`to_json`] with what the objectives' model reads besides the problem: every action's
/// `reward` (if `extra.rewards` is given), the `terminal` list (if not empty) and the initial
/// distribution as the `initial` list (if `extra.initial` is given; its first state should be
/// the problem's initial state, which [`from_json_with_objective`] gives the problem it reads
/// back); [`from_json_with_objective`] reads them back.
///
/// # Panics
///
/// If `extra.rewards` does not hold one reward per action of `problem`.
///
/// ```
/// use truecost::stochastic::file::{from_json_with_objective, to_json_with_objective, FileObjective};
/// use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
/// let q = |n: i64| truecost::value::Rational::from_integer(n.into());
/// let one = |to| vec![Outcome { successor: to, probability: q(1), kind: OutcomeKind::Listed }];
/// let act = |cost, to| StochasticAction { cost: q(cost), outcomes: one(to) };
/// let p = StochasticProblem::new(vec![vec![act(1, 1), act(1, 2)], vec![], vec![act(0, 2)]], 0, vec![1]).unwrap();
/// let half = truecost::value::Rational::new(1.into(), 2.into());
/// let extra = FileObjective {
///     rewards: Some(vec![q(1), q(-1), q(0)]),
///     terminal: vec![2],
///     initial: Some(vec![(0, half.clone()), (2, half)]),
/// };
/// let text = to_json_with_objective(&p, None, &extra);
/// assert!(text.contains(r#""reward": "-1""#));
/// assert!(text.contains(r#""p": "1/2""#));
/// assert_eq!(from_json_with_objective(&text).unwrap().1, extra);
/// ```
pub fn to_json_with_objective(
    problem: &StochasticProblem,
    name: Option<&str>,
    extra: &FileObjective,
) -> String {
    if let Some(r) = &extra.rewards {
        assert_eq!(r.len(), problem.action_total(), "one reward per action");
    }
    let initial = match &extra.initial {
        Some(d) => FileInitial::Distribution(
            d.iter()
                .map(|(x, p)| FileInitialEntry {
                    state: *x,
                    p: serde_json::Value::String(Extended::Finite(p.clone()).to_string()),
                })
                .collect(),
        ),
        None => FileInitial::State(problem.initial()),
    };
    let file = FileProblem {
        format: Some(FORMAT.to_string()),
        name: name.map(str::to_string),
        states: Some(problem.states()),
        initial,
        goals: problem.goals().to_vec(),
        terminal: (!extra.terminal.is_empty()).then(|| extra.terminal.clone()),
        actions: (0..problem.states())
            .map(|x| {
                problem
                    .actions(x)
                    .map(|a| FileAction {
                        to: None,
                        cost: Extended::Finite(problem.cost(a).clone()).to_string(),
                        reward: extra
                            .rewards
                            .as_ref()
                            .map(|r| Extended::Finite(r[a].clone()).to_string()),
                        outcomes: Some(
                            problem
                                .outcomes(a)
                                .iter()
                                .map(|o| FileOutcome {
                                    to: o.successor,
                                    p: Extended::Finite(o.probability.clone()).to_string(),
                                })
                                .collect(),
                        ),
                    })
                    .collect()
            })
            .collect(),
    };
    serde_json::to_string_pretty(&file).expect("serialisable")
}

//! The formats of the field, as adapters at the edge: a problem in Storm's explicit DRN format
//! ([`drn`], written and read) and in the PRISM language ([`prism`], written; PRISM-language
//! input is recognised and refused), read into the one model type
//! ([`StochasticProblem`] with its [`FileObjective`]). Nothing inside the solvers knows which
//! file a problem came from.
//!
//! [`read_with_objective`] is what `--file` reads: the text is read once and its format told by
//! its content ([`detect`]), not by its name.

pub mod drn;
pub mod prism;

use std::path::Path;

use num_traits::{One, Zero};

use crate::model::file::{self as det_file, FileError};
use crate::model::StateId;
use crate::stochastic::file::{self as json_file, FileObjective, ProblemFile, StochasticFileError};
use crate::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use crate::value::Rational;

/// The format of a problem file's text, told by its content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// truecost's JSON problem files (and anything that is none of the others: the JSON
    /// reader names what is wrong).
    Json,
    /// Storm's explicit format: its first line that is neither empty nor a `//` comment starts
    /// with `@`.
    Drn,
    /// The PRISM language: its first word (after `//` comments) is a PRISM model type or
    /// top-level keyword.
    Prism,
}

/// The first words a PRISM-language model may start with (model types and top-level
/// declarations).
const PRISM_OPENERS: &[&str] = &[
    "mdp",
    "dtmc",
    "ctmc",
    "pta",
    "pomdp",
    "popta",
    "smg",
    "probabilistic",
    "nondeterministic",
    "stochastic",
    "module",
    "const",
    "global",
    "formula",
    "label",
    "rewards",
    "system",
    "init",
];

/// The format of `text`, from its first line that is neither blank nor a `//` comment.
///
/// ```
/// use truecost::formats::{detect, Kind};
/// assert_eq!(detect("// a model\n@type: MDP\n"), Kind::Drn);
/// assert_eq!(detect("  {\"initial\": 0}"), Kind::Json);
/// assert_eq!(detect("// coin\nmdp\nmodule m endmodule"), Kind::Prism);
/// assert_eq!(detect("nonsense"), Kind::Json);
/// ```
pub fn detect(text: &str) -> Kind {
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with("//"))
        .unwrap_or("");
    if first.starts_with('@') {
        return Kind::Drn;
    }
    let word: String = first
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    if PRISM_OPENERS.contains(&word.as_str()) {
        return Kind::Prism;
    }
    Kind::Json
}

/// Why a problem file was refused. Every message fits on one line.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// A truecost JSON file's refusal.
    #[error("{0}")]
    Json(#[from] StochasticFileError),
    /// A DRN file's refusal.
    #[error("{0}")]
    Drn(#[from] drn::DrnError),
    /// PRISM-language input.
    #[error("{}", prism::INPUT_REFUSED)]
    Prism,
    /// A goal label or cost reward model named for a file that is not DRN.
    #[error("--goal-label and --cost-reward name a DRN file's label and reward model; this problem file is truecost's JSON, which gives its goals and costs itself")]
    NamesNotDrn,
}

impl From<FileError> for ReadError {
    fn from(e: FileError) -> Self {
        ReadError::Json(e.into())
    }
}

/// Parses a problem file's text in any supported format ([`detect`]) with what it says besides
/// the problem (rewards, terminal states, initial distribution): truecost's JSON
/// ([`json_file::from_json_with_objective`]) or Storm's DRN ([`drn::from_drn`], always a
/// stochastic problem). PRISM-language text is refused in one line ([`prism::INPUT_REFUSED`]).
///
/// ```
/// use truecost::formats::from_text_with_objective;
/// use truecost::stochastic::file::ProblemFile;
/// let drn = "@type: MDP\n@reward_models\ncost\n@nr_states\n2\n@nr_choices\n2\n@model\n\
///            state 0 init\n\taction 0 [1]\n\t\t1 : 1/2\n\t\t0 : 1/2\n\
///            state 1 goal\n\taction 0 [0]\n\t\t1 : 1\n";
/// let (ProblemFile::Stochastic(p), _) = from_text_with_objective(drn).unwrap() else { panic!() };
/// assert_eq!(p.outcomes(0)[1].probability.to_string(), "1/2");
/// let prism = from_text_with_objective("mdp\nmodule m\nendmodule\n").unwrap_err();
/// assert!(prism.to_string().starts_with("PRISM-language input is not read"));
/// ```
pub fn from_text_with_objective(text: &str) -> Result<(ProblemFile, FileObjective), ReadError> {
    from_text_with_names(text, &drn::DrnNames::default())
}

/// [`from_text_with_objective`], a DRN file's goals and costs read from the label and reward
/// model `names` gives ([`drn::from_drn_with`]); names other than the defaults are refused for
/// JSON problem files ([`ReadError::NamesNotDrn`]).
///
/// ```
/// use truecost::formats::{drn::DrnNames, from_text_with_names};
/// let drn = "@type: MDP\n@reward_models\ntime\n@nr_states\n2\n@nr_choices\n2\n@model\n\
///            state 0 init\n\taction 0 [2]\n\t\t1 : 1\nstate 1 elected\n\taction 0 [0]\n\t\t1 : 1\n";
/// let names = DrnNames { goal_label: Some("elected".into()), cost_reward: None };
/// assert!(from_text_with_names(drn, &names).is_ok());
/// let json = r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1"}], []]}"#;
/// assert!(from_text_with_names(json, &Default::default()).is_ok());
/// assert!(from_text_with_names(json, &names).unwrap_err().to_string().starts_with("--goal-label"));
/// ```
pub fn from_text_with_names(
    text: &str,
    names: &drn::DrnNames,
) -> Result<(ProblemFile, FileObjective), ReadError> {
    match detect(text) {
        Kind::Drn => {
            let (problem, extra) = drn::from_drn_with(text, names)?;
            Ok((ProblemFile::Stochastic(Box::new(problem)), extra))
        }
        Kind::Prism => Err(ReadError::Prism),
        Kind::Json if !names.is_default() => Err(ReadError::NamesNotDrn),
        Kind::Json => Ok(json_file::from_json_with_objective(text)?),
    }
}

/// Reads a problem file once ([`det_file::read_text`]: at most 32 MiB, standard input and pipes
/// work) and parses it in whichever format it is ([`from_text_with_objective`]).
pub fn read_with_objective(path: &Path) -> Result<(ProblemFile, FileObjective), ReadError> {
    read_with_names(path, &drn::DrnNames::default())
}

/// [`read_with_objective`] with a DRN file's goal label and cost reward model
/// ([`from_text_with_names`]).
pub fn read_with_names(
    path: &Path,
    names: &drn::DrnNames,
) -> Result<(ProblemFile, FileObjective), ReadError> {
    from_text_with_names(&det_file::read_text(path)?, names)
}

/// The initial states a DRN or PRISM file can state: the problem's initial state, or every
/// state of a **uniform** initial distribution (in increasing order). `None` for a
/// distribution that is not uniform (neither format has probabilities on initial states).
pub fn initial_states(problem: &StochasticProblem, extra: &FileObjective) -> Option<Vec<StateId>> {
    let Some(d) = &extra.initial else {
        return Some(vec![problem.initial()]);
    };
    let uniform = Rational::new(1.into(), d.len().into());
    if d.iter().any(|(_, p)| *p != uniform) {
        return None;
    }
    let mut states: Vec<StateId> = d.iter().map(|(x, _)| *x).collect();
    states.sort_unstable();
    Some(states)
}

/// A zero-cost self-loop stands in for the actions of a goal without actions: both formats need
/// a choice in every state (dead ends are made traps first, [`dead_ends_as_traps`]).
///
/// What the writers write for state `x`: `Some(range)` of its global action ids, or `None`
/// for the stand-in self-loop.
fn written_actions(problem: &StochasticProblem, x: StateId) -> Option<std::ops::Range<usize>> {
    let range = problem.actions(x);
    (!range.is_empty()).then_some(range)
}

/// The problem as every file format can hold it: each non-goal state without actions (a dead
/// end, `G* = +∞`, where the episode ends) gets one zero-cost self-loop with reward 0 and is
/// listed terminal (a trap: the same value under every objective), since problem files give
/// every non-goal state an action and Storm every state a choice. Anything else is unchanged.
///
/// ```
/// use truecost::formats::dead_ends_as_traps;
/// use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
/// let one = truecost::value::Rational::from_integer(1.into());
/// let to = |y| StochasticAction { cost: one.clone(), outcomes: vec![Outcome { successor: y, probability: one.clone(), kind: OutcomeKind::Listed }] };
/// let p = StochasticProblem::new(vec![vec![to(1), to(2)], vec![], vec![]], 0, vec![2]).unwrap();
/// let (q, extra) = dead_ends_as_traps(&p, &Default::default());
/// assert_eq!((q.actions(1).len(), q.outcomes(2)[0].successor, q.cost(2).to_string()), (1, 1, "0".to_string()));
/// assert_eq!(extra.terminal, [1]);
/// ```
pub fn dead_ends_as_traps(
    problem: &StochasticProblem,
    extra: &FileObjective,
) -> (StochasticProblem, FileObjective) {
    let dead = |x: StateId| !problem.is_goal(x) && problem.actions(x).is_empty();
    if !(0..problem.states()).any(dead) {
        return (problem.clone(), extra.clone());
    }
    let mut lists = problem.action_lists();
    let mut rewards = extra.rewards.as_ref().map(|_| Vec::new());
    let mut terminal = extra.terminal.clone();
    for (x, list) in lists.iter_mut().enumerate() {
        if let (Some(out), Some(given)) = (rewards.as_mut(), extra.rewards.as_ref()) {
            out.extend(problem.actions(x).map(|a| given[a].clone()));
        }
        if dead(x) {
            list.push(StochasticAction {
                cost: Rational::zero(),
                outcomes: vec![Outcome {
                    successor: x,
                    probability: Rational::one(),
                    kind: OutcomeKind::Listed,
                }],
            });
            if let Some(out) = rewards.as_mut() {
                out.push(Rational::zero());
            }
            terminal.push(x);
        }
    }
    terminal.sort_unstable();
    terminal.dedup();
    let traps = StochasticProblem::new(lists, problem.initial(), problem.goals().to_vec())
        .expect("the same problem with self-loops added");
    let extra = FileObjective {
        rewards,
        terminal,
        initial: extra.initial.clone(),
    };
    (traps, extra)
}

/// The first line of a written file: `name` in a `//` comment (both formats' comment), escaped to
/// one printable line; nothing without a name.
fn name_comment(name: Option<&str>) -> String {
    name.map(|n| format!("// {} (written by truecost)\n", crate::echo::printable(n)))
        .unwrap_or_default()
}

/// An exact number as both formats write it: an integer or `p/q`, with a leading `-` if
/// negative.
fn exact_text(r: &Rational) -> String {
    crate::value::Extended::Finite(r.clone()).to_string()
}

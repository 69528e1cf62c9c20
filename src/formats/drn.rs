//! Storm's explicit DRN format (its `DirectEncodingParser`): written by [`to_drn`], read by
//! [`from_drn`].
//!
//! ```text
//! // paper problem 0 (written by truecost)
//! @type: MDP
//! @value_type: rational
//! @parameters
//!
//! @reward_models
//! cost
//! @nr_states
//! 3
//! @nr_choices
//! 4
//! @model
//! state 0 init
//!     action 0 [1]
//!         1 : 9/10
//!         0 : 1/10
//! ...
//! state 2 goal
//!     action 0 [0]
//!         2 : 1
//! ```
//!
//! (Storm indents with tabs; shown here with spaces.)
//!
//! What truecost writes: an `MDP` with exact rational numbers (`@value_type: rational`); the
//! action reward model `cost` (the stage cost) and, when the problem carries rewards of the
//! discounted objective, a second one, `reward`; state labels `init` (the initial state, or
//! every state of a uniform initial distribution), `goal` and `terminal` (the non-goal states
//! where the episode ends). A state without actions (a goal, a dead end) gets one zero-cost
//! self-loop: Storm needs a choice in every state.
//!
//! What truecost reads, as Storm's parser does (header lines in any order, `//` comments and
//! blank lines skipped; state ids in order without gaps; `@nr_states` and `@nr_choices` must
//! match what follows):
//! * `@type: MDP` or `DTMC` (a DTMC is an MDP with one action per state); other types, a
//!   non-empty `@parameters` line and interval or parametric `@value_type`s are refused;
//! * numbers as exact decimals or fractions (`0.1` is `1/10`); `@placeholders` are refused;
//! * the cost of an action: its reward in the model named `cost` (or in the only reward model
//!   if none is so named) plus its state's reward in that model (an equal expectation of the
//!   total until the goal); a model named `reward` gives the discounted objective's rewards;
//!   other reward models are ignored;
//! * labels `goal` (at least one state), `init` (at least one state; several are a uniform
//!   initial distribution) and `terminal`; other labels are ignored. A goal whose only action is
//!   a zero-cost self-loop reads back without actions.
//!
//! A file written elsewhere names its target and its costs as its model does (Storm's export of
//! a PRISM model keeps the model's labels and reward structures: `"done"`, `"coinflips"`):
//! [`from_drn_with`] reads the goals from another label and the costs from another reward model
//! ([`DrnNames`]; the command line's `--goal-label` and `--cost-reward`), without editing the
//! file.
//!
//! Limits: those of truecost's problem files (the file's size, each number's text, all exact
//! numbers together), and a declared state or choice count larger than the file could hold is
//! refused before anything else is read.

use std::fmt::Write as _;

use num_traits::Zero;

use super::{exact_text, initial_states, written_actions};
use crate::echo::echo;
use crate::model::file::{FileError, FileObjective, NumberBudget};
use crate::model::StateId;
use crate::stochastic::{
    Outcome, OutcomeKind, StochasticAction, StochasticError, StochasticProblem,
};
use crate::value::{parse_rational, Rational};

/// The reward model holding the stage costs.
pub const COST_MODEL: &str = "cost";
/// The reward model holding the discounted objective's rewards.
pub const REWARD_MODEL: &str = "reward";

/// The label of the goal states when [`DrnNames`] names none.
pub const GOAL_LABEL: &str = "goal";

/// Which label marks the goal states and which reward model holds the stage costs, for a file
/// that names them otherwise than truecost writes them (module docs). `None`: the defaults,
/// label `goal` and reward model `cost` (or the only reward model).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DrnNames {
    /// The label of the goal states (`--goal-label`).
    pub goal_label: Option<String>,
    /// The reward model of the stage costs (`--cost-reward`).
    pub cost_reward: Option<String>,
}

impl DrnNames {
    /// Whether both names are the defaults.
    pub fn is_default(&self) -> bool {
        self.goal_label.is_none() && self.cost_reward.is_none()
    }

    fn goal(&self) -> &str {
        self.goal_label.as_deref().unwrap_or(GOAL_LABEL)
    }
}

/// The fewest bytes a state takes in a DRN file (`state 0` and a line break), which bounds a
/// declared count by the file's size.
const MIN_STATE_BYTES: usize = 8;

/// Why a DRN file was refused, or a problem could not be written as one. Every message fits
/// on one line.
#[derive(Debug, thiserror::Error)]
pub enum DrnError {
    /// A line that does not parse.
    #[error("DRN line {line}: {message}")]
    Syntax {
        /// The line number (from 1).
        line: usize,
        /// What is wrong (user text escaped).
        message: String,
    },
    /// A file-level rule (counts, labels, reward models).
    #[error("DRN file: {0}")]
    File(String),
    /// Refused by the rules every problem file obeys (number sizes, terminal states).
    #[error("DRN file: {0}")]
    Problem(#[from] FileError),
    /// Refused by the stochastic model's checks (probabilities, costs).
    #[error("DRN file: {0}")]
    Stochastic(#[from] StochasticError),
    /// An initial distribution the format cannot state.
    #[error("the initial distribution is not uniform: Storm's DRN and PRISM formats give initial states without probabilities (a uniform distribution is written as several initial states)")]
    NotUniform,
}

fn syntax(line: usize, message: impl Into<String>) -> DrnError {
    DrnError::Syntax {
        line,
        message: message.into(),
    }
}

/// Writes `problem` in Storm's DRN format (module docs), with the rewards, terminal states and
/// uniform initial distribution of `extra`; `name` goes into a comment. [`from_drn`] reads it
/// back to the same problem.
///
/// ```
/// use truecost::formats::drn::{from_drn, to_drn};
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// let one = truecost::value::parse_rational("1").unwrap();
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// let text = to_drn(&s, &Default::default(), Some("one step")).unwrap();
/// assert!(text.contains("state 0 init\n\taction 0 [1]\n\t\t1 : 9/10\n\t\t0 : 1/10\n"));
/// assert!(text.contains("state 1 goal\n\taction 0 [0]\n\t\t1 : 1\n"));
/// let (back, _) = from_drn(&text).unwrap();
/// let moves = |p: &StochasticProblem| (0..p.action_total())
///     .map(|a| (p.state_of(a), p.cost(a).clone(),
///               p.outcomes(a).iter().map(|o| (o.successor, o.probability.clone())).collect::<Vec<_>>()))
///     .collect::<Vec<_>>();
/// assert_eq!(moves(&back), moves(&s));
/// ```
pub fn to_drn(
    problem: &StochasticProblem,
    extra: &FileObjective,
    name: Option<&str>,
) -> Result<String, DrnError> {
    let init = initial_states(problem, extra).ok_or(DrnError::NotUniform)?;
    let n = problem.states();
    let mut labels = vec![Vec::new(); n];
    for &x in &init {
        labels[x].push("init");
    }
    for &g in problem.goals() {
        labels[g].push("goal");
    }
    for &x in &extra.terminal {
        labels[x].push("terminal");
    }
    let rewards = extra.rewards.as_deref();
    let choices: usize = (0..n)
        .map(|x| written_actions(problem, x).map_or(1, |r| r.len()))
        .sum();
    let mut out = super::name_comment(name);
    let models = if rewards.is_some() {
        format!("{COST_MODEL} {REWARD_MODEL}")
    } else {
        COST_MODEL.to_string()
    };
    let _ = write!(
        out,
        "@type: MDP\n@value_type: rational\n@parameters\n\n@reward_models\n{models}\n\
         @nr_states\n{n}\n@nr_choices\n{choices}\n@model\n"
    );
    for (x, state_labels) in labels.iter().enumerate() {
        let _ = write!(out, "state {x}");
        for l in state_labels {
            let _ = write!(out, " {l}");
        }
        out.push('\n');
        let Some(range) = written_actions(problem, x) else {
            let zero = if rewards.is_some() { "[0, 0]" } else { "[0]" };
            let _ = write!(out, "\taction 0 {zero}\n\t\t{x} : 1\n");
            continue;
        };
        let first = range.start;
        for a in range {
            let _ = write!(
                out,
                "\taction {} [{}",
                a - first,
                exact_text(problem.cost(a))
            );
            if let Some(r) = rewards {
                let _ = write!(out, ", {}", exact_text(&r[a]));
            }
            out.push_str("]\n");
            for o in problem.outcomes(a) {
                let _ = writeln!(out, "\t\t{} : {}", o.successor, exact_text(&o.probability));
            }
        }
    }
    Ok(out)
}

/// The header of a DRN file (up to `@model`).
#[derive(Default)]
struct Header {
    kind: Option<String>,
    reward_models: Vec<String>,
    states: Option<usize>,
    choices: Option<usize>,
}

/// One action as read: its rewards per reward model (as many as its bracket lists) and its
/// transitions (target, probability, line).
#[derive(Default)]
struct ReadAction {
    rewards: Vec<Rational>,
    outcomes: Vec<(usize, Rational, usize)>,
}

/// One state as read.
#[derive(Default)]
struct ReadState {
    rewards: Vec<Rational>,
    labels: Vec<String>,
    actions: Vec<ReadAction>,
}

/// Reads a DRN file (module docs) into a problem and what it says besides (the `reward`
/// model's rewards, the `terminal` states, a uniform initial distribution over several `init`
/// states, in increasing order).
///
/// ```
/// use truecost::formats::drn::from_drn;
/// let text = "@type: MDP\n@reward_models\ncost\n@nr_states\n2\n@nr_choices\n2\n@model\n\
///             state 0 init\n\taction a [1/3]\n\t\t1 : 0.25\n\t\t0 : 0.75\n\
///             state 1 goal\n\taction b [0]\n\t\t1 : 1\n";
/// let (p, extra) = from_drn(text).unwrap();
/// assert_eq!((p.states(), p.cost(0).to_string(), p.goals()), (2, "1/3".to_string(), &[1][..]));
/// assert!(p.actions(1).is_empty()); // the goal's stand-in self-loop
/// assert_eq!(extra, Default::default());
/// let bad = text.replace("0.75", "0.5");
/// assert!(from_drn(&bad).unwrap_err().to_string().contains("sum to 3/4, not 1"));
/// let huge = text.replace("@nr_states\n2", "@nr_states\n99999999999");
/// assert!(from_drn(&huge).unwrap_err().to_string().contains("more than a file of"));
/// ```
pub fn from_drn(text: &str) -> Result<(StochasticProblem, FileObjective), DrnError> {
    from_drn_with(text, &DrnNames::default())
}

/// [`from_drn`] with the goals read from the label `names.goal_label` and the stage costs from
/// the reward model `names.cost_reward` (module docs); a name the file does not have is refused
/// in one line.
///
/// ```
/// use truecost::formats::drn::{from_drn_with, DrnNames};
/// let text = "@type: MDP\n@reward_models\nsteps coins\n@nr_states\n2\n@nr_choices\n2\n@model\n\
///             state 0 init\n\taction 0 [1, 5]\n\t\t1 : 1\n\
///             state 1 done\n\taction 0 [0, 0]\n\t\t1 : 1\n";
/// let names = DrnNames { goal_label: Some("done".into()), cost_reward: Some("coins".into()) };
/// let (p, _) = from_drn_with(text, &names).unwrap();
/// assert_eq!((p.goals(), p.cost(0).to_string()), (&[1][..], "5".to_string()));
/// let steps = DrnNames { cost_reward: Some("steps".into()), ..names.clone() };
/// assert_eq!(from_drn_with(text, &steps).unwrap().0.cost(0).to_string(), "1");
/// let wrong = DrnNames { goal_label: Some("finished".into()), ..names.clone() };
/// assert!(from_drn_with(text, &wrong).unwrap_err().to_string().contains("no state is labelled 'finished'"));
/// let missing = DrnNames { cost_reward: Some("time".into()), ..names };
/// assert!(from_drn_with(text, &missing).unwrap_err().to_string().contains("no reward model named 'time'"));
/// ```
pub fn from_drn_with(
    text: &str,
    names: &DrnNames,
) -> Result<(StochasticProblem, FileObjective), DrnError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let header = read_header(&mut lines, text.len())?;
    let mut budget = NumberBudget::default();
    let nondeterministic = header.kind.as_deref() == Some("MDP");
    let declared = header.states.expect("checked before @model");
    let mut states: Vec<ReadState> = Vec::new();
    let mut choices = 0usize;
    for (number, raw) in lines {
        if raw.starts_with("//") || raw.is_empty() {
            continue;
        }
        let line = raw.trim_start();
        if let Some(rest) = line.strip_prefix("state ") {
            let (id, rest) = split_word(rest);
            let id = parse_count(id).ok_or_else(|| {
                syntax(number, format!("state id '{}' is not a number", echo(id)))
            })?;
            if id != states.len() {
                return Err(syntax(
                    number,
                    format!(
                        "state ids must be in order without gaps: expected {} but got {id}",
                        states.len()
                    ),
                ));
            }
            if id >= declared {
                return Err(syntax(number, "more states than declared in @nr_states"));
            }
            let mut state = ReadState::default();
            let mut rest = rest.trim_start();
            if rest.starts_with('[') {
                let (values, after) = bracket(rest, number)?;
                state.rewards = values
                    .iter()
                    .map(|v| value(v, number, &mut budget, id, 0))
                    .collect::<Result<_, _>>()?;
                rest = after;
            }
            state.labels = labels(rest, number)?;
            states.push(state);
        } else if let Some(rest) = line.strip_prefix("action ") {
            let s = states.len().saturating_sub(1);
            let Some(state) = states.last_mut() else {
                return Err(syntax(number, "an action before the first state"));
            };
            if !nondeterministic && !state.actions.is_empty() {
                return Err(syntax(number, "a second action in a DTMC"));
            }
            choices += 1;
            if header.choices.is_some_and(|c| choices > c) {
                return Err(syntax(number, "more actions than declared in @nr_choices"));
            }
            let (_, rest) = split_word(rest);
            let mut action = ReadAction::default();
            let rest = rest.trim_start();
            if rest.starts_with('[') {
                let (values, after) = bracket(rest, number)?;
                if !after.trim().is_empty() {
                    return Err(syntax(
                        number,
                        format!(
                            "unexpected text '{}' after the action's rewards",
                            echo(after.trim())
                        ),
                    ));
                }
                let a = state.actions.len();
                action.rewards = values
                    .iter()
                    .map(|v| value(v, number, &mut budget, s, a))
                    .collect::<Result<_, _>>()?;
            } else if !rest.trim().is_empty() {
                return Err(syntax(
                    number,
                    format!(
                        "unexpected text '{}' after the action's name",
                        echo(rest.trim())
                    ),
                ));
            }
            state.actions.push(action);
        } else {
            let Some((target, probability)) = line.split_once(':') else {
                return Err(syntax(
                    number,
                    format!(
                        "':' not found in '{}' (a transition is 'TARGET : PROBABILITY')",
                        echo(line)
                    ),
                ));
            };
            let s = states.len().saturating_sub(1);
            let Some(state) = states.last_mut() else {
                return Err(syntax(number, "a transition before the first state"));
            };
            if state.actions.is_empty() {
                if nondeterministic {
                    return Err(syntax(
                        number,
                        "a transition before the state's first action",
                    ));
                }
                choices += 1;
                state.actions.push(ReadAction::default());
            }
            let target = target.trim();
            let target = parse_count(target).ok_or_else(|| {
                syntax(
                    number,
                    format!("target state '{}' is not a number", echo(target)),
                )
            })?;
            let a = state.actions.len() - 1;
            let p = value(probability.trim(), number, &mut budget, s, a)?;
            state.actions[a].outcomes.push((target, p, number));
        }
    }
    build(header, states, choices, names)
}

/// Reads the header lines up to `@model`; `bytes` is the file's size, which bounds the counts.
fn read_header<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    bytes: usize,
) -> Result<Header, DrnError> {
    let mut h = Header::default();
    let mut parameters_seen = false;
    let count = |text: &str, what: &str, at: usize| -> Result<usize, DrnError> {
        let n = parse_count(text.trim())
            .ok_or_else(|| syntax(at + 1, format!("{what} '{}' is not a number", echo(text))))?;
        if n > bytes / MIN_STATE_BYTES {
            return Err(syntax(
                at + 1,
                format!("{what} declares {n}, more than a file of {bytes} bytes can hold"),
            ));
        }
        Ok(n)
    };
    while let Some((number, line)) = lines.next() {
        if line.is_empty() || line.starts_with("//") {
            continue;
        }
        if let Some(kind) = line.strip_prefix("@type: ") {
            if h.kind.is_some() {
                return Err(syntax(number, "@type declared twice"));
            }
            if kind != "MDP" && kind != "DTMC" {
                return Err(syntax(
                    number,
                    format!(
                        "model type '{}' is not read (truecost reads MDP and DTMC)",
                        echo(kind)
                    ),
                ));
            }
            h.kind = Some(kind.to_string());
        } else if let Some(v) = line.strip_prefix("@value_type: ") {
            if v != "rational" && v != "double" {
                return Err(syntax(number, format!("value type '{}' is not read (truecost reads rational and double, as exact numbers)", echo(v))));
            }
        } else if line == "@parameters" {
            if parameters_seen {
                return Err(syntax(number, "@parameters declared twice"));
            }
            parameters_seen = true;
            if !follow(lines, "@parameters", number)?.trim().is_empty() {
                return Err(syntax(number + 1, "parametric models are not read"));
            }
        } else if line == "@placeholders" {
            // Storm reads `$name : value` lines until the next line starting with '@'.
            return Err(syntax(
                number,
                "placeholders are not read (write the numbers in place)",
            ));
        } else if line == "@reward_models" {
            if !h.reward_models.is_empty() {
                return Err(syntax(number, "@reward_models declared twice"));
            }
            let names = follow(lines, "@reward_models", number)?;
            h.reward_models = names.split([' ', '\t']).map(str::to_string).collect();
        } else if line == "@nr_states" {
            if h.states.is_some() {
                return Err(syntax(number, "@nr_states declared twice"));
            }
            h.states = Some(count(
                follow(lines, "@nr_states", number)?,
                "@nr_states",
                number,
            )?);
        } else if line == "@nr_choices" {
            if h.choices.is_some() {
                return Err(syntax(number, "@nr_choices declared twice"));
            }
            h.choices = Some(count(
                follow(lines, "@nr_choices", number)?,
                "@nr_choices",
                number,
            )?);
        } else if line == "@model" {
            if h.kind.is_none() {
                return Err(syntax(number, "@type must be declared before @model"));
            }
            if h.states.is_none_or(|n| n == 0) {
                return Err(syntax(
                    number,
                    "@nr_states must be declared (and positive) before @model",
                ));
            }
            return Ok(h);
        } else {
            return Err(syntax(
                number,
                format!("could not parse header line '{}'", echo(line)),
            ));
        }
    }
    Err(DrnError::File("the file ends before @model".into()))
}

/// The line after a header keyword (`what`, on line `at`).
fn follow<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    what: &str,
    at: usize,
) -> Result<&'a str, DrnError> {
    lines
        .next()
        .map(|(_, l)| l)
        .ok_or_else(|| syntax(at, format!("{what} is not followed by a line")))
}

/// A count or state id: decimal digits only.
fn parse_count(text: &str) -> Option<usize> {
    if text.is_empty() || !text.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    text.parse().ok()
}

/// The first space-separated word of `text` and the rest.
fn split_word(text: &str) -> (&str, &str) {
    match text.find(' ') {
        Some(i) => (&text[..i], &text[i + 1..]),
        None => (text, ""),
    }
}

/// The comma-separated entries of a `[...]` at the start of `text`, and what follows it.
fn bracket(text: &str, line: usize) -> Result<(Vec<&str>, &str), DrnError> {
    let end = text.find(']').ok_or_else(|| syntax(line, "']' missing"))?;
    let values = text[1..end].split(',').map(str::trim).collect();
    Ok((values, &text[end + 1..]))
}

/// A state's labels: words separated by white space, or `"quoted text"`.
fn labels(text: &str, line: usize) -> Result<Vec<String>, DrnError> {
    let mut out = Vec::new();
    let mut rest = text.trim_start();
    while !rest.is_empty() {
        if let Some(quoted) = rest.strip_prefix('"') {
            let end = quoted
                .find('"')
                .ok_or_else(|| syntax(line, "a label's closing '\"' is missing"))?;
            out.push(quoted[..end].to_string());
            rest = quoted[end + 1..].trim_start();
        } else {
            let end = rest.find(char::is_whitespace).unwrap_or(rest.len());
            out.push(rest[..end].to_string());
            rest = rest[end..].trim_start();
        }
    }
    Ok(out)
}

/// An exact number of the model (a probability or a reward), counted in `budget`.
fn value(
    text: &str,
    line: usize,
    budget: &mut NumberBudget,
    state: usize,
    action: usize,
) -> Result<Rational, DrnError> {
    let r = parse_rational(text).map_err(|e| syntax(line, format!("{e}")))?;
    budget.take(&r, state, action)?;
    Ok(r)
}

/// The problem of the states read (module docs: costs, goals, initial states, terminal
/// states, rewards).
fn build(
    header: Header,
    states: Vec<ReadState>,
    choices: usize,
    chosen: &DrnNames,
) -> Result<(StochasticProblem, FileObjective), DrnError> {
    let declared = header.states.expect("checked before @model");
    if states.len() != declared {
        return Err(DrnError::File(format!(
            "{} states given, {declared} declared in @nr_states",
            states.len()
        )));
    }
    if let Some(c) = header.choices.filter(|&c| c != choices) {
        return Err(DrnError::File(format!(
            "{choices} actions given, {c} declared in @nr_choices"
        )));
    }
    let width = states
        .iter()
        .map(|s| s.rewards.len())
        .chain(
            states
                .iter()
                .flat_map(|s| s.actions.iter().map(|a| a.rewards.len())),
        )
        .max()
        .unwrap_or(0);
    // Storm names reward model i after the i-th word of @reward_models, `rew<i>` without one.
    let names: Vec<String> = (0..width)
        .map(|i| match header.reward_models.get(i) {
            Some(n) if !n.is_empty() => n.clone(),
            _ => format!("rew{i}"),
        })
        .collect();
    let cost_model = match (
        names.iter().position(|n| n == COST_MODEL),
        &chosen.cost_reward,
    ) {
        (_, Some(wanted)) => names.iter().position(|n| n == wanted).ok_or_else(|| {
            DrnError::File(format!(
                "no reward model named '{}' (--cost-reward) among {} reward models ({})",
                echo(wanted),
                width,
                echo(&names.join(", "))
            ))
        })?,
        (Some(i), None) => i,
        (None, None) if width == 1 => 0,
        (None, None) => {
            return Err(DrnError::File(format!(
            "no reward model named '{COST_MODEL}' (the stage costs) among {} reward models ({})",
            width,
            echo(&names.join(", "))
        )))
        }
    };
    let reward_model = names.iter().position(|n| n == REWARD_MODEL);
    let entry = |v: &[Rational], i: usize| v.get(i).cloned().unwrap_or_else(Rational::zero);
    let mut goals = Vec::new();
    let mut init = Vec::new();
    let mut terminal = Vec::new();
    let mut actions = Vec::with_capacity(states.len());
    let mut rewards = Vec::new();
    for (x, s) in states.into_iter().enumerate() {
        let goal = s.labels.iter().any(|l| l == chosen.goal());
        if goal {
            goals.push(x);
        }
        if s.labels.iter().any(|l| l == "init") {
            init.push(x);
        }
        if s.labels.iter().any(|l| l == "terminal") {
            terminal.push(x);
        }
        let mut row = Vec::with_capacity(s.actions.len());
        let mut row_rewards = Vec::with_capacity(s.actions.len());
        for (a, action) in s.actions.into_iter().enumerate() {
            if action.outcomes.is_empty() {
                return Err(StochasticError::NoOutcomes {
                    state: x,
                    action: a,
                }
                .into());
            }
            let cost = entry(&s.rewards, cost_model) + entry(&action.rewards, cost_model);
            row_rewards
                .push(reward_model.map(|i| entry(&s.rewards, i) + entry(&action.rewards, i)));
            let outcomes = action
                .outcomes
                .into_iter()
                .map(|(to, p, line)| {
                    if to >= declared {
                        return Err(syntax(
                            line,
                            format!("target state {to} is not below @nr_states = {declared}"),
                        ));
                    }
                    Ok(Outcome {
                        successor: to,
                        probability: p,
                        kind: OutcomeKind::Listed,
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            row.push(StochasticAction { cost, outcomes });
        }
        // The stand-in of a goal without actions reads back as none.
        if goal
            && row.len() == 1
            && row[0].cost.is_zero()
            && row[0].outcomes.iter().all(|o| o.successor == x)
            && row_rewards[0].as_ref().is_none_or(Zero::is_zero)
        {
            row.clear();
            row_rewards.clear();
        }
        if row.is_empty() && !goal {
            return Err(FileError::EmptyActions(x).into());
        }
        actions.push(row);
        rewards.extend(row_rewards);
    }
    if goals.is_empty() {
        return Err(DrnError::File(format!(
            "no state is labelled '{}'",
            echo(chosen.goal())
        )));
    }
    let Some(&first) = init.first() else {
        return Err(DrnError::File("no state is labelled 'init'".into()));
    };
    let problem = StochasticProblem::new(actions, first, goals)?;
    let rewards: Option<Vec<Rational>> =
        reward_model.map(|_| rewards.into_iter().flatten().collect());
    let terminal =
        crate::stochastic::file::check_terminal(&problem, Some(&terminal), rewards.as_deref())?;
    let initial = (init.len() > 1).then(|| {
        let p = Rational::new(1.into(), init.len().into());
        init.iter()
            .map(|&x| (x, p.clone()))
            .collect::<Vec<(StateId, Rational)>>()
    });
    Ok((
        problem,
        FileObjective {
            rewards,
            terminal,
            initial,
        },
    ))
}

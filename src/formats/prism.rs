//! The PRISM language, written by [`to_prism`]: an `mdp` with one module and one state
//! variable.
//!
//! ```text
//! // paper problem 0 (written by truecost)
//! mdp
//!
//! module truecost
//!   s : [0..2] init 0;
//!   [a0] s=0 -> 9/10 : (s'=1) + 1/10 : (s'=0);
//!   ...
//!   [a0] s=2 -> 1 : (s'=2);
//! endmodule
//!
//! label "goal" = s=2;
//!
//! rewards "cost"
//!   [a0] s=0 : 1;
//!   ...
//! endrewards
//! ```
//!
//! State `x` is `s=x`; the actions of a state are the commands labelled `a0`, `a1`, … in their
//! order (a label per position, so that a transition reward names exactly one action); every
//! probability and cost is an exact `p/q` expression (PRISM's `/` is real division, and Storm
//! reads it exactly in its exact mode); the reward structure `cost` holds the stage costs, a
//! second one, `reward`, the discounted objective's rewards when the problem has them; the
//! labels `goal` and `terminal` are formulas over `s`; the initial state is the variable's
//! `init` value, a uniform initial distribution an `init … endinit` block. A state without
//! actions gets one zero-cost self-loop (a state without a command would be a deadlock).
//! Integers are written as decimal literals of at most 63 bits (what Storm's expression parser
//! reads); a number beyond that is refused.
//!
//! PRISM-language **input** is not read: a parser of the whole language is what reading it
//! takes, and a parser of only what [`to_prism`] writes would refuse most models people have.
//! Storm converts any PRISM model to DRN, which truecost reads ([`INPUT_REFUSED`]).

use std::fmt::Write as _;

use num_bigint::BigInt;

use super::{exact_text, initial_states, written_actions};
use crate::model::file::FileObjective;
use crate::stochastic::StochasticProblem;
use crate::value::Rational;

/// The one-line refusal of PRISM-language input.
pub const INPUT_REFUSED: &str = "PRISM-language input is not read: convert it to Storm's explicit DRN format, which truecost reads (storm --prism MODEL.prism --buildfull --exportbuild MODEL.drn, with the labels 'init' and 'goal' and a reward structure 'cost', or name yours with --goal-label and --cost-reward)";

/// Why a problem could not be written in the PRISM language. One line.
#[derive(Debug, thiserror::Error)]
pub enum PrismError {
    /// An initial distribution that is not uniform.
    #[error("the initial distribution is not uniform: Storm's DRN and PRISM formats give initial states without probabilities (a uniform distribution is written as several initial states)")]
    NotUniform,
    /// A number whose numerator or denominator needs more than 63 bits.
    #[error("{what} has a numerator or denominator beyond 2^63 - 1, which PRISM's integer literals cannot state")]
    TooLarge {
        /// Which number.
        what: String,
    },
}

/// A number as a PRISM expression, if its parts fit 63 bits.
fn literal(r: &Rational, what: impl FnOnce() -> String) -> Result<String, PrismError> {
    let limit = BigInt::from(i64::MAX);
    if r.numer().magnitude() > limit.magnitude() || r.denom() > &limit {
        return Err(PrismError::TooLarge { what: what() });
    }
    Ok(exact_text(r))
}

/// `s=x1 | s=x2 | …`, or `false` for no state.
fn formula(states: &[usize]) -> String {
    if states.is_empty() {
        return "false".into();
    }
    states
        .iter()
        .map(|x| format!("s={x}"))
        .collect::<Vec<_>>()
        .join(" | ")
}

/// Writes `problem` in the PRISM language (module docs), with the rewards, terminal states and
/// uniform initial distribution of `extra`; `name` goes into a comment.
///
/// ```
/// use truecost::formats::prism::to_prism;
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// let one = truecost::value::parse_rational("800/19").unwrap();
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// let text = to_prism(&s, &Default::default(), None).unwrap();
/// assert!(text.contains("  s : [0..1] init 0;\n  [a0] s=0 -> 9/10 : (s'=1) + 1/10 : (s'=0);\n"));
/// assert!(text.contains("label \"goal\" = s=1;"));
/// assert!(text.contains("rewards \"cost\"\n  [a0] s=0 : 800/19;\nendrewards"));
/// ```
pub fn to_prism(
    problem: &StochasticProblem,
    extra: &FileObjective,
    name: Option<&str>,
) -> Result<String, PrismError> {
    let init = initial_states(problem, extra).ok_or(PrismError::NotUniform)?;
    let n = problem.states();
    let mut out = super::name_comment(name);
    out.push_str("mdp\n\nmodule truecost\n");
    let _ = write!(out, "  s : [0..{}]", n - 1);
    if init.len() == 1 {
        let _ = write!(out, " init {}", init[0]);
    }
    out.push_str(";\n");
    let mut costs = String::new();
    let mut rewards = String::new();
    for x in 0..n {
        let Some(range) = written_actions(problem, x) else {
            let _ = writeln!(out, "  [a0] s={x} -> 1 : (s'={x});");
            continue;
        };
        let first = range.start;
        for a in range {
            let label = format!("a{}", a - first);
            let outcomes = problem
                .outcomes(a)
                .iter()
                .enumerate()
                .map(|(i, o)| {
                    let p = literal(&o.probability, || {
                        format!(
                            "state {x}, action {}, outcome {i}: the probability",
                            a - first
                        )
                    })?;
                    Ok(format!("{p} : (s'={})", o.successor))
                })
                .collect::<Result<Vec<_>, PrismError>>()?;
            let _ = writeln!(out, "  [{label}] s={x} -> {};", outcomes.join(" + "));
            let cost = problem.cost(a);
            if !num_traits::Zero::is_zero(cost) {
                let c = literal(cost, || {
                    format!("state {x}, action {}: the cost", a - first)
                })?;
                let _ = writeln!(costs, "  [{label}] s={x} : {c};");
            }
            if let Some(r) = extra.rewards.as_ref().map(|r| &r[a]) {
                if !num_traits::Zero::is_zero(r) {
                    let r = literal(r, || format!("state {x}, action {}: the reward", a - first))?;
                    let _ = writeln!(rewards, "  [{label}] s={x} : {r};");
                }
            }
        }
    }
    out.push_str("endmodule\n\n");
    if init.len() > 1 {
        let _ = writeln!(out, "init {} endinit\n", formula(&init));
    }
    let _ = writeln!(out, "label \"goal\" = {};", formula(problem.goals()));
    if !extra.terminal.is_empty() {
        let _ = writeln!(out, "label \"terminal\" = {};", formula(&extra.terminal));
    }
    let _ = write!(out, "\nrewards \"cost\"\n{costs}endrewards\n");
    if extra.rewards.is_some() {
        let _ = write!(out, "\nrewards \"reward\"\n{rewards}endrewards\n");
    }
    Ok(out)
}

//! The certificate of an exact optimum ([`super::policy_iteration::optimum`]), as
//! `solve --algorithm exact --certificate` writes it ([`crate::certificate`] checks it): every
//! state's `G*` over the optimum's common denominator, the optimal policy's action per state,
//! and the record of the problem.

use num_traits::Zero;
use rayon::prelude::*;

use super::policy_iteration::Optimum;
use super::StochasticProblem;
use crate::certificate::{self, CertifiedObjective, Mdp, MdpAction, ProblemRecord};
use crate::model::Decision;
use crate::value::integer_text;

/// The certificate's text for `opt`, the exact optimum of `problem`.
pub fn optimum_certificate(
    problem: &StochasticProblem,
    opt: &Optimum,
    objective: &CertifiedObjective,
    record: &ProblemRecord,
) -> String {
    let policy: Vec<Option<usize>> = opt
        .policy()
        .iter()
        .map(|d| match d {
            Some(Decision::Move(i)) => Some(*i),
            _ => None,
        })
        .collect();
    certificate::write(
        objective,
        record,
        unreduced_texts(opt, problem.states()),
        &policy,
    )
}

/// Every state's `G*` over the optimum's common denominator, not reduced (`"n/d"`, `"n"` when
/// `d = 1` or `n = 0`, `"inf"`): exact, and no gcd per state (reducing is most of the cost of
/// printing every value of a large stochastic model).
fn unreduced_texts(opt: &Optimum, n: usize) -> Vec<String> {
    let d = (0..n)
        .find_map(|x| opt.unreduced(x).map(|(_, d)| integer_text(d)))
        .unwrap_or_default();
    let text = |x: usize| match opt.unreduced(x) {
        Some((num, _)) if d == "1" || num.is_zero() => integer_text(num),
        Some((num, _)) => format!("{}/{d}", integer_text(num)),
        None => "inf".into(),
    };
    // In parallel only when the numbers are long (a thread pool costs more than short texts).
    if d.len() > 64 {
        (0..n).into_par_iter().map(text).collect()
    } else {
        (0..n).map(text).collect()
    }
}

/// `problem` as the certificate checker reads it ([`crate::certificate::Mdp`]): its stage
/// costs, their negations as rewards, its outcomes; goals and action-less states terminal.
pub fn problem_mdp(problem: &StochasticProblem) -> Mdp {
    let n = problem.states();
    Mdp {
        goal: (0..n).map(|x| problem.is_goal(x)).collect(),
        terminal: (0..n)
            .map(|x| problem.is_goal(x) || problem.actions(x).is_empty())
            .collect(),
        actions: (0..n)
            .map(|x| {
                problem
                    .actions(x)
                    .map(|a| MdpAction {
                        cost: problem.cost(a).clone(),
                        reward: -problem.cost(a).clone(),
                        outcomes: problem
                            .outcomes(a)
                            .iter()
                            .map(|o| (o.successor, o.probability.clone()))
                            .collect(),
                    })
                    .collect()
            })
            .collect(),
    }
}

//! The certificate of an exact optimum ([`super::policy_iteration::optimum`]), as
//! `solve --algorithm exact --certificate` writes it ([`crate::certificate`] checks it): every
//! state's `G*` over the optimum's common denominator (not reduced: no gcd per state, and the
//! denominator printed once), the optimal policy's action per state, and the record of the
//! problem.

use num_bigint::BigInt;
use num_traits::One;

use super::policy_iteration::Optimum;
use super::StochasticProblem;
use crate::certificate::{self, CertifiedObjective, Mdp, MdpAction, ProblemRecord};
use crate::model::Decision;

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
    let numerators: Vec<Option<&BigInt>> = (0..problem.states())
        .map(|x| opt.unreduced(x).map(|(k, _)| k))
        .collect();
    let one = BigInt::one();
    let denominator = (0..problem.states())
        .find_map(|x| opt.unreduced(x).map(|(_, d)| d))
        .unwrap_or(&one);
    certificate::write_over(objective, record, &numerators, denominator, &policy)
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

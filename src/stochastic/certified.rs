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

/// The certificate's text for `opt`, the exact optimum of `problem`
/// ([`write_optimum_certificate`] into one buffer).
pub fn optimum_certificate(
    problem: &StochasticProblem,
    opt: &Optimum,
    objective: &CertifiedObjective,
    record: &ProblemRecord,
) -> String {
    let certified = Certified::new(problem, opt);
    let mut out = Vec::with_capacity(certified.capacity());
    certified
        .write(&mut out, objective, record)
        .expect("writing into memory never fails");
    String::from_utf8(out).expect("JSON text is UTF-8")
}

/// Writes the certificate of `opt`, the exact optimum of `problem`, into `out`: the values
/// over the optimum's common denominator ([`certificate::write_over_to`], a batch at a time),
/// the policy, `record`.
pub fn write_optimum_certificate(
    out: &mut dyn std::io::Write,
    problem: &StochasticProblem,
    opt: &Optimum,
    objective: &CertifiedObjective,
    record: &ProblemRecord,
) -> std::io::Result<()> {
    Certified::new(problem, opt).write(out, objective, record)
}

/// What a certificate of an optimum holds: the numerators over the common denominator, the
/// policy's action indices.
struct Certified<'a> {
    numerators: Vec<Option<&'a BigInt>>,
    denominator: &'a BigInt,
    policy: Vec<Option<usize>>,
}

impl<'a> Certified<'a> {
    fn new(problem: &StochasticProblem, opt: &'a Optimum) -> Self {
        static ONE: std::sync::OnceLock<BigInt> = std::sync::OnceLock::new();
        let policy = opt
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
        let denominator = (0..problem.states())
            .find_map(|x| opt.unreduced(x).map(|(_, d)| d))
            .unwrap_or_else(|| ONE.get_or_init(BigInt::one));
        Certified {
            numerators,
            denominator,
            policy,
        }
    }

    /// A buffer size that holds the certificate's text.
    fn capacity(&self) -> usize {
        certificate::over_capacity(&self.numerators, self.denominator, &self.policy)
    }

    fn write(
        &self,
        out: &mut dyn std::io::Write,
        objective: &CertifiedObjective,
        record: &ProblemRecord,
    ) -> std::io::Result<()> {
        certificate::write_over_to(
            out,
            objective,
            record,
            &self.numerators,
            self.denominator,
            &self.policy,
        )
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

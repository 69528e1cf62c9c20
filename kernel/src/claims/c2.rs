//! Claim C2 (SPEC §6): cost–reward equivalence — the per-problem check over the
//! policy-enumeration oracle ([`crate::claims::oracle`]): for a cost functional linear in the
//! sequence of stage costs, a policy minimises the cost iff it maximises the reward obtained by
//! negating every stage cost. The rewards are evaluated afresh from the negated stage sequence,
//! never by negating the cost. The claim runner (scopes, the parallel enumeration, the report)
//! is `truecost::claims::c2`.

use super::exact::{FracExt, Q};
use super::oracle::{evaluate_fast, policies, trajectory, Functional};
use super::tiny::Tiny;

/// The functionals checked.
pub fn functionals() -> Vec<Functional> {
    vec![
        Functional::Total,
        Functional::Discounted(Q::new(1, 2)),
        Functional::Discounted(Q::new(9, 10)),
        Functional::Average,
        Functional::HorizonTotal(3),
        Functional::HorizonDiscounted(3, Q::new(1, 2)),
        Functional::HorizonAverage(4),
    ]
}

/// Checks one problem from the start states `0..starts`; `None` if the equivalence holds for
/// each of them and every functional, else a description of the failure. Also returns the
/// number of comparisons made.
pub fn check_problem(t: &Tiny, fs: &[Functional], starts: usize) -> (Option<String>, u64) {
    let ps = policies(t, true);
    assert!(ps.len() <= 128);
    let mut comparisons = 0;
    let mut costs = [FracExt::NegInf; 128];
    let mut rewards = [FracExt::NegInf; 128];
    for start in 0..starts.min(t.states()) {
        let trs: Vec<_> = ps.iter().map(|p| trajectory(t, p, start)).collect();
        for &f in fs {
            for (i, tr) in trs.iter().enumerate() {
                costs[i] = evaluate_fast(tr, f, 1);
                rewards[i] = evaluate_fast(tr, f, -1);
            }
            let (costs, rewards) = (&costs[..trs.len()], &rewards[..trs.len()]);
            let min = *costs.iter().min().expect("a policy");
            let max = *rewards.iter().max().expect("a policy");
            let argmin: u128 = costs
                .iter()
                .enumerate()
                .filter(|(_, c)| **c == min)
                .fold(0, |m, (i, _)| m | 1 << i);
            let argmax: u128 = rewards
                .iter()
                .enumerate()
                .filter(|(_, r)| **r == max)
                .fold(0, |m, (i, _)| m | 1 << i);
            comparisons += 1;
            if argmin != argmax {
                return (
                    Some(format!(
                        "from state {start}, {}: cost minimisers {argmin:#b} differ from reward maximisers {argmax:#b}",
                        f.name()
                    )),
                    comparisons,
                );
            }
        }
    }
    (None, comparisons)
}

//! Claim C2 (docs/spec.md §6): cost–reward equivalence — the per-problem check over the
//! policy-enumeration oracle ([`crate::claims::oracle`]): for a cost functional linear in the
//! sequence of stage costs, a policy minimises the cost iff it maximises the reward obtained by
//! negating every stage cost. The rewards are evaluated afresh from the negated stage sequence,
//! never by negating the cost. The claim runner (scopes, the parallel enumeration, the report)
//! is `truecost::claims::c2`.

use std::fmt;

use super::exact::{ExactInt, FracExt, Q};
use super::oracle::{evaluate_fast, policies, trajectory, Functional, Trajectory};
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

/// The policies (indices into `trs`, one trajectory per policy) minimising the cost and those
/// maximising the reward (every stage cost negated, evaluated afresh) under `f`, as bit masks.
pub fn optimisers<I: ExactInt>(trs: &[Trajectory], f: Functional<I>) -> (u128, u128) {
    assert!(!trs.is_empty() && trs.len() <= 128);
    let mut costs = [FracExt::<I>::NegInf; 128];
    let mut rewards = [FracExt::<I>::NegInf; 128];
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
    (argmin, argmax)
}

/// A failure of C2 on one problem: from `start`, under `functional`, the cost minimisers
/// (`argmin`, a bit mask over the policies) differ from the reward maximisers (`argmax`).
/// Formatted only when printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Failure<I: ExactInt = i128> {
    /// The start state.
    pub start: usize,
    /// The functional.
    pub functional: Functional<I>,
    /// The cost-minimising policies.
    pub argmin: u128,
    /// The reward-maximising policies.
    pub argmax: u128,
}

impl<I: ExactInt> fmt::Display for Failure<I> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "from state {}, {}: cost minimisers {:#b} differ from reward maximisers {:#b}",
            self.start, self.functional, self.argmin, self.argmax
        )
    }
}

/// Checks one problem from the start states `0..starts` (C2: for each functional, the
/// policies minimising the cost are those maximising the reward): the first [`Failure`], or
/// `None` if the equivalence holds for each start and every functional. Also returns the number
/// of comparisons made.
pub fn first_failure<I: ExactInt>(
    t: &Tiny,
    fs: &[Functional<I>],
    starts: usize,
) -> (Option<Failure<I>>, u64) {
    let ps = policies(t, true);
    assert!(ps.len() <= 128);
    let mut comparisons = 0;
    for start in 0..starts.min(t.states()) {
        let trs: Vec<_> = ps.iter().map(|p| trajectory(t, p, start)).collect();
        for &f in fs {
            let (argmin, argmax) = optimisers(&trs, f);
            comparisons += 1;
            if argmin != argmax {
                let failure = Failure {
                    start,
                    functional: f,
                    argmin,
                    argmax,
                };
                return (Some(failure), comparisons);
            }
        }
    }
    (None, comparisons)
}

/// [`first_failure`] with the failure described in one line.
pub fn check_problem<I: ExactInt>(
    t: &Tiny,
    fs: &[Functional<I>],
    starts: usize,
) -> (Option<String>, u64) {
    let (failure, comparisons) = first_failure(t, fs, starts);
    (failure.map(|f| f.to_string()), comparisons)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cost minimisers and reward maximisers at 16 bits (32 for 9/10) are the product's
    /// (`i128`) on every 4-state problem with one move per non-goal state and costs 0 or 255
    /// (the extremes of the harness's `u8` costs).
    #[test]
    fn narrow_optimisers_agree_with_i128() {
        let mut compared = 0;
        for code in 0..(4u32 * 2).pow(3) {
            let lists: Vec<Vec<(u8, u8)>> = (0..3)
                .map(|x| {
                    let c = code >> (3 * x) & 7;
                    vec![((c % 4) as u8, if c / 4 == 1 { 255 } else { 0 })]
                })
                .chain([vec![]])
                .collect();
            let t = Tiny::from_lists(&lists);
            let trs: Vec<_> = policies(&t, true)
                .iter()
                .map(|p| trajectory(&t, p, 0))
                .collect();
            let half = Q::<i16>::ratio(1, 2);
            let narrow = [
                Functional::Total,
                Functional::Discounted(half),
                Functional::Average,
                Functional::HorizonTotal(3),
                Functional::HorizonDiscounted(3, half),
                Functional::HorizonAverage(4),
            ];
            let fs = functionals();
            let wide: Vec<_> = fs
                .iter()
                .filter(|f| **f != Functional::Discounted(Q::new(9, 10)))
                .collect();
            for (n, w) in narrow.iter().zip(&wide) {
                assert_eq!(optimisers(&trs, *n), optimisers(&trs, **w));
                compared += 1;
            }
            assert_eq!(
                optimisers(&trs, Functional::Discounted(Q::<i32>::ratio(9, 10))),
                optimisers(&trs, Functional::Discounted(Q::new(9, 10)))
            );
            assert_eq!(check_problem(&t, &narrow, 1), (None, 6));
        }
        assert_eq!(compared, 6 * 512);
    }
}

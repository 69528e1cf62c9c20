//! What the optimal policies of a piece achieve (module docs of [`super`], step 4) on a
//! deterministic model whose stage costs are non-negative, by search on the graph of the
//! allowed actions instead of exact solves:
//!
//! * **success** `max`: 1 where a goal is reachable through allowed actions, else 0;
//!   `min`: 0 on the greatest set of non-goal states where some allowed action stays in the
//!   set or none is allowed (a policy avoids the goals forever from there), else 1 — outside
//!   that set every allowed path reaches a goal (an infinite path avoiding the goals would
//!   lie in the set);
//! * **least truecost**: the cheapest allowed path to a goal (Dijkstra from the goals, exact,
//!   costs `≥ 0`), `+∞` where none exists;
//! * **greatest truecost**: `+∞` when some allowed policy fails with positive probability;
//!   otherwise the allowed graph reachable from the initial states has no cycle (a cycle
//!   would lie in the avoiding set), and the dearest path to a goal is found over it.
//!
//! The values at the initial distribution are those of [`super::achievement`]'s exact solves
//! (checked on random problems in the tests below).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use num_traits::{One, Signed, Zero};

use super::{successor, Achievement};
use crate::model::StateId;
use crate::objectives::{Bounds, Model};
use crate::value::{Extended, Rational};

/// Whether every stage cost where the episode runs is non-negative (the condition of
/// [`achievement`]).
pub fn costs_non_negative(model: &Model) -> bool {
    let p = &model.problem;
    (0..p.states())
        .filter(|&x| !model.terminal[x])
        .all(|x| p.actions(x).all(|a| !p.cost(a).is_negative()))
}

/// The achievement of the allowed actions (module docs) on a deterministic model with
/// non-negative stage costs.
pub fn achievement(model: &Model, allowed: &[bool]) -> Achievement {
    let p = &model.problem;
    let n = p.states();
    let acts = |x: StateId| p.actions(x).filter(move |&a| allowed[a]);
    let mut predecessors: Vec<Vec<(StateId, usize)>> = vec![Vec::new(); n];
    for x in (0..n).filter(|&x| !p.is_goal(x)) {
        for a in acts(x) {
            predecessors[successor(model, a)].push((x, a));
        }
    }
    // Least truecost by Dijkstra from the goals; `reaches` is where it is finite.
    let mut least: Vec<Option<Rational>> = vec![None; n];
    let mut done = vec![false; n];
    let mut heap: BinaryHeap<Reverse<(Rational, StateId)>> = BinaryHeap::new();
    for &g in p.goals() {
        least[g] = Some(Rational::zero());
        heap.push(Reverse((Rational::zero(), g)));
    }
    while let Some(Reverse((d, y))) = heap.pop() {
        if done[y] {
            continue;
        }
        done[y] = true;
        for &(x, a) in &predecessors[y] {
            let through = &d + p.cost(a);
            if !done[x] && least[x].as_ref().is_none_or(|l| through < *l) {
                least[x] = Some(through.clone());
                heap.push(Reverse((through, x)));
            }
        }
    }
    // The states every allowed path leads to a goal from (the complement of the avoiding
    // set): a least fixpoint, counting each state's allowed actions not yet leading there.
    let mut open: Vec<usize> = (0..n).map(|x| acts(x).count()).collect();
    let mut sure: Vec<bool> = (0..n).map(|x| p.is_goal(x)).collect();
    let mut stack: Vec<StateId> = p.goals().to_vec();
    while let Some(y) = stack.pop() {
        for &(x, _) in &predecessors[y] {
            open[x] -= 1;
            if open[x] == 0 && !sure[x] {
                sure[x] = true;
                stack.push(x);
            }
        }
    }
    let indicator = |b: bool| if b { Rational::one() } else { Rational::zero() };
    let success = Bounds {
        min: model.at_initial_rational(&sure.iter().map(|&s| indicator(s)).collect::<Vec<_>>()),
        max: model.at_initial_rational(
            &least
                .iter()
                .map(|l| indicator(l.is_some()))
                .collect::<Vec<_>>(),
        ),
    };
    let truecost_min = model.at_initial(
        &least
            .iter()
            .map(|l| l.clone().map_or(Extended::Infinite, Extended::Finite))
            .collect::<Vec<_>>(),
    );
    let truecost_max = if success.min < Rational::one() {
        Extended::Infinite
    } else {
        // Every initial state is sure and every allowed path from it stays among sure states
        // without a cycle: the dearest path, in reverse topological order.
        let mut most: Vec<Option<Rational>> = vec![None; n];
        for &g in p.goals() {
            most[g] = Some(Rational::zero());
        }
        for (x0, _) in model.initial.iter().filter(|(_, q)| q.is_positive()) {
            let x0 = *x0;
            let mut stack = vec![(x0, false)];
            while let Some((x, expanded)) = stack.pop() {
                if most[x].is_some() {
                    continue;
                }
                if expanded {
                    let best = acts(x)
                        .map(|a| p.cost(a) + most[successor(model, a)].as_ref().expect("a DAG"))
                        .max()
                        .expect("a sure state has an allowed action");
                    most[x] = Some(best);
                } else {
                    stack.push((x, true));
                    stack.extend(acts(x).map(|a| (successor(model, a), false)));
                }
            }
        }
        model.at_initial(
            &most
                .into_iter()
                .map(|m| m.map_or(Extended::Infinite, Extended::Finite))
                .collect::<Vec<_>>(),
        )
    };
    Achievement {
        success,
        truecost_min,
        truecost_max,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};

    /// A small generator (64-bit LCG).
    struct Lcg(u64);

    impl Lcg {
        fn below(&mut self, n: u64) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 33) % n
        }
    }

    /// Random deterministic problems (some states without a way to the goal, cycles, zero
    /// costs) and random allowed sets: the graph search equals the exact solves.
    #[test]
    fn graph_search_equals_the_exact_solves() {
        let mut g = Lcg(7);
        for case in 0..300 {
            let n = 2 + g.below(9) as usize;
            let actions: Vec<Vec<StochasticAction>> = (0..n)
                .map(|x| {
                    if x == n - 1 {
                        return Vec::new();
                    }
                    (0..1 + g.below(3))
                        .map(|_| StochasticAction {
                            cost: Rational::from_integer(g.below(4).into()),
                            outcomes: vec![Outcome {
                                successor: g.below(n as u64) as usize,
                                probability: Rational::one(),
                                kind: OutcomeKind::Listed,
                            }],
                        })
                        .collect()
                })
                .collect();
            let initial = g.below(n as u64 - 1) as usize;
            let m = Model::from_problem(
                StochasticProblem::new(actions, initial, vec![n - 1]).unwrap(),
                format!("random {case}"),
            );
            assert!(costs_non_negative(&m));
            for _ in 0..4 {
                let allowed: Vec<bool> = (0..m.problem.action_total())
                    .map(|_| g.below(3) > 0)
                    .collect();
                let exact = super::super::achievement(&m, &allowed).unwrap();
                assert_eq!(achievement(&m, &allowed), exact, "case {case}");
            }
        }
    }
}

//! Which states have a finite optimal expected cost, which actions are safe, and proper
//! policies (docs/spec.md §3 with the conventions of [`super`]).
//!
//! A policy is *proper at `x`* if from `x` it reaches a goal with probability 1. `G*(x) < ∞`
//! exactly when some policy is proper at `x` (costs are finite and a trajectory that misses the
//! goals costs `+∞`). These states are computed by the classical almost-sure reachability
//! fixpoint: start from all states; repeatedly call an action *safe* if all its outcomes stay
//! in the current set, keep only the states from which a goal can be reached with positive
//! probability using safe actions, until nothing changes. On the final set `F`:
//! * every action of a state in `F` that is not safe has `Q* = +∞`;
//! * the *attractor policy* (at each state of `F`, the first safe action with an outcome closer
//!   to the goals, in the order of the last backward search) is proper on all of `F`: every
//!   step stays in `F` and has a positive probability of moving closer.

use std::collections::VecDeque;

use super::StochasticProblem;

/// The qualitative analysis of a stochastic problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Properness {
    /// `G*(x) < ∞`: some policy reaches a goal from `x` with probability 1 (goals included).
    pub finite: Vec<bool>,
    /// Per action (global id): all its outcomes have finite `G*`.
    pub safe: Vec<bool>,
    /// A proper policy on `finite` (action id per non-goal finite state, `None` elsewhere).
    pub attractor: Vec<Option<usize>>,
}

/// Runs the almost-sure reachability fixpoint.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{properness::analyse, NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// // 0 -> 1 (goal), 0 -> 2 (trap with a self-loop): any noise at 0 may fall into the trap.
/// let p = Problem::new(vec![
///     vec![Move { successor: 1, cost: one.clone() }, Move { successor: 2, cost: one.clone() }],
///     vec![],
///     vec![Move { successor: 2, cost: one.clone() }],
/// ], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// assert_eq!(analyse(&s).finite, vec![false, true, false]);
/// let d = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::one()).unwrap();
/// assert_eq!(analyse(&d).finite, vec![true, true, false]);
/// ```
pub fn analyse(problem: &StochasticProblem) -> Properness {
    let n = problem.states();
    // Reverse outcome lists: for each state, the actions with an outcome there.
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for a in 0..problem.action_total() {
        for o in problem.outcomes(a) {
            if into[o.successor].last() != Some(&a) {
                into[o.successor].push(a);
            }
        }
    }
    let mut inside = vec![true; n];
    loop {
        let safe: Vec<bool> = (0..problem.action_total())
            .map(|a| {
                inside[problem.state_of(a)]
                    && problem.outcomes(a).iter().all(|o| inside[o.successor])
            })
            .collect();
        let (reached, attractor) = attract(problem, &into, &safe, &inside);
        if reached == inside {
            return Properness {
                finite: inside,
                safe,
                attractor,
            };
        }
        inside = reached;
    }
}

/// States of `inside` from which a goal is reached with positive probability using safe
/// actions, with the action that first reached each.
fn attract(
    problem: &StochasticProblem,
    into: &[Vec<usize>],
    safe: &[bool],
    inside: &[bool],
) -> (Vec<bool>, Vec<Option<usize>>) {
    let n = problem.states();
    let mut reached = vec![false; n];
    let mut policy = vec![None; n];
    let mut queue = VecDeque::new();
    for &g in problem.goals() {
        reached[g] = true;
        queue.push_back(g);
    }
    while let Some(y) = queue.pop_front() {
        for &a in &into[y] {
            let x = problem.state_of(a);
            if !reached[x] && inside[x] && safe[a] {
                reached[x] = true;
                policy[x] = Some(a);
                queue.push_back(x);
            }
        }
    }
    (reached, policy)
}

/// Whether `policy` (an action id for every non-goal state with `finite[x]`) is proper on
/// `finite`: it uses only actions of the right state whose outcomes stay in `finite`, and
/// every such state reaches a goal in the policy's transition graph (for a finite chain this
/// is "reaches a goal with probability 1").
pub fn is_proper(problem: &StochasticProblem, finite: &[bool], policy: &[Option<usize>]) -> bool {
    let n = problem.states();
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for x in 0..n {
        if !finite[x] || problem.is_goal(x) {
            continue;
        }
        let Some(a) = policy[x] else { return false };
        if !problem.actions(x).contains(&a) {
            return false;
        }
        for o in problem.outcomes(a) {
            if !finite[o.successor] {
                return false;
            }
            into[o.successor].push(x);
        }
    }
    let mut reached = vec![false; n];
    let mut queue: VecDeque<usize> = problem.goals().iter().copied().collect();
    for &g in problem.goals() {
        reached[g] = true;
    }
    while let Some(y) = queue.pop_front() {
        for &x in &into[y] {
            if !reached[x] {
                reached[x] = true;
                queue.push_back(x);
            }
        }
    }
    (0..n).all(|x| !finite[x] || reached[x])
}

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
    almost_sure(problem, &|_| true)
}

/// [`analyse`] over the policies that use only the actions with `allowed(a)`: `finite` is then
/// the set of states from which such a policy reaches a goal with probability 1 (the
/// `Prob1E` set of probabilistic model checking: maximal reach probability 1), `safe` holds
/// only allowed actions, and the attractor policy uses only allowed actions.
///
/// ```
/// use truecost::stochastic::properness::almost_sure;
/// use truecost::stochastic::file::{from_json, ProblemFile};
/// // 0: action 0 reaches the goal 2 surely, action 1 risks the trap 1.
/// let text = r#"{"initial":0,"goals":[2],"actions":[[{"to":2,"cost":"1"},
///     {"cost":"1","outcomes":[{"to":1,"p":"1/2"},{"to":2,"p":"1/2"}]}],[{"to":1,"cost":"0"}],[]]}"#;
/// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { unreachable!() };
/// assert_eq!(almost_sure(&p, &|_| true).finite, [true, false, true]);
/// assert_eq!(almost_sure(&p, &|a| a != 0).finite, [false, false, true]);
/// ```
pub fn almost_sure(problem: &StochasticProblem, allowed: &dyn Fn(usize) -> bool) -> Properness {
    let n = problem.states();
    let into = reverse_actions(problem);
    let mut inside = vec![true; n];
    loop {
        let safe: Vec<bool> = (0..problem.action_total())
            .map(|a| {
                allowed(a)
                    && inside[problem.state_of(a)]
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

/// For each state, the actions with an outcome there (each action once per state).
fn reverse_actions(problem: &StochasticProblem) -> Vec<Vec<usize>> {
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); problem.states()];
    for a in 0..problem.action_total() {
        for o in problem.outcomes(a) {
            if into[o.successor].last() != Some(&a) {
                into[o.successor].push(a);
            }
        }
    }
    into
}

/// The states from which `targets` are reached with positive probability by some policy
/// using only the actions with `allowed(a)`, passing only through states with
/// `through(x)` (the targets included): a backward search. With the goals as targets, its
/// complement is the set where the maximal reach probability is 0 (`Prob0A` of probabilistic
/// model checking).
///
/// ```
/// use truecost::stochastic::properness::reaches;
/// use truecost::stochastic::file::{from_json, ProblemFile};
/// // 0 -> 1 -> 2 (goal); 3 only loops.
/// let text = r#"{"initial":0,"goals":[2],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"1"}]}],[{"to":2,"cost":"1"}],[],[{"to":3,"cost":"1"}]]}"#;
/// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { unreachable!() };
/// let goal = [false, false, true, false];
/// assert_eq!(reaches(&p, &|_| true, &goal, &|_| true), [true, true, true, false]);
/// assert_eq!(reaches(&p, &|a| a != 1, &goal, &|_| true), [false, false, true, false]);
/// assert_eq!(reaches(&p, &|_| true, &goal, &|x| x != 1), [false, false, true, false]);
/// ```
pub fn reaches(
    problem: &StochasticProblem,
    allowed: &dyn Fn(usize) -> bool,
    targets: &[bool],
    through: &dyn Fn(usize) -> bool,
) -> Vec<bool> {
    let into = reverse_actions(problem);
    let mut reached = targets.to_vec();
    let mut stack: Vec<usize> = (0..problem.states()).filter(|&x| targets[x]).collect();
    while let Some(y) = stack.pop() {
        for &a in &into[y] {
            let x = problem.state_of(a);
            if !reached[x] && through(x) && allowed(a) {
                reached[x] = true;
                stack.push(x);
            }
        }
    }
    reached
}

/// The states from which some policy using only the actions with `allowed(a)` avoids the
/// goals forever (a state without an allowed action stays where it is): the greatest set `S`
/// of non-goal states where every state has no allowed action or an allowed action with all
/// its outcomes in `S`. Where the minimal reach probability is 0 (`Prob0E`).
///
/// ```
/// use truecost::stochastic::properness::avoids;
/// use truecost::stochastic::file::{from_json, ProblemFile};
/// // 0 may loop or go to the goal 1; 2 must go to 0.
/// let text = r#"{"initial":0,"goals":[1],"actions":[[{"to":0,"cost":"1"},{"cost":"1","outcomes":[{"to":1,"p":"1"}]}],[],[{"to":0,"cost":"1"}]]}"#;
/// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { unreachable!() };
/// assert_eq!(avoids(&p, &|_| true), [true, false, true]);
/// assert_eq!(avoids(&p, &|a| a != 0), [false, false, false]);
/// ```
pub fn avoids(problem: &StochasticProblem, allowed: &dyn Fn(usize) -> bool) -> Vec<bool> {
    let n = problem.states();
    let into = reverse_actions(problem);
    let mut avoid: Vec<bool> = (0..n).map(|x| !problem.is_goal(x)).collect();
    // Per state: its allowed actions with every outcome still in the set.
    let mut staying: Vec<usize> = vec![0; n];
    let mut left: Vec<usize> = Vec::new();
    let mut inside_action: Vec<bool> = vec![false; problem.action_total()];
    for x in 0..n {
        if !avoid[x] {
            continue;
        }
        let own: Vec<usize> = problem.actions(x).filter(|&a| allowed(a)).collect();
        if own.is_empty() {
            staying[x] = usize::MAX; // ends here: never leaves the set
            continue;
        }
        for a in own {
            if problem.outcomes(a).iter().all(|o| avoid[o.successor]) {
                inside_action[a] = true;
                staying[x] += 1;
            }
        }
        if staying[x] == 0 {
            left.push(x);
        }
    }
    for &x in &left {
        avoid[x] = false;
    }
    while let Some(y) = left.pop() {
        for &a in &into[y] {
            if !inside_action[a] {
                continue;
            }
            inside_action[a] = false;
            let x = problem.state_of(a);
            if avoid[x] && staying[x] != usize::MAX {
                staying[x] -= 1;
                if staying[x] == 0 {
                    avoid[x] = false;
                    left.push(x);
                }
            }
        }
    }
    avoid
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

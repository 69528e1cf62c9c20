//! The exactly optimal actions of a solved objective: each action's exact `Q`-value by one
//! Bellman backup of the optimal values, and the actions that attain the optimum and that some
//! optimal stationary policy uses (what a policy figure draws where actions tie).

use num_traits::{Signed, Zero};

use super::{Model, Objective, Solution};
use crate::value::{Extended, Rational};

/// The exact `Q`-value of action `a` (a global id of [`Model::problem`]) under the solution's
/// objective: one Bellman backup of its exact optimal values. Truecost
/// `Q(x, a) = l(x, a) + Σ p·G*(y)` (`+∞` if an outcome has `G* = +∞`); reach `Σ p·V(y)`;
/// discounted `r(x, a) + α·Σ p·V_α(y)` (an ended episode has `V_α = 0`).
///
/// ```
/// use truecost::{envs::EnvSpec, objectives::actions::q_value};
/// use truecost::objectives::{Model, Objective};
/// let env = EnvSpec::parse("frozenlake:slippery=false").unwrap().build().unwrap();
/// let m = Model::from_environment(&env).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// // LEFT at the start hits the border: one step spent, still six to go.
/// assert_eq!(q_value(&m, &s, m.problem.actions(0).start).to_string(), "7");
/// ```
pub fn q_value(model: &Model, s: &Solution, a: usize) -> Extended {
    let p = &model.problem;
    let mut expected = Rational::zero();
    for o in p.outcomes(a) {
        match &s.values[o.successor] {
            Extended::Finite(v) => expected += &o.probability * v,
            Extended::Infinite if o.probability.is_zero() => {}
            Extended::Infinite => return Extended::Infinite,
        }
    }
    Extended::Finite(match &s.objective {
        Objective::Truecost => p.cost(a) + expected,
        Objective::Reach => expected,
        Objective::Discounted(alpha) => &model.reward[a] + alpha * expected,
    })
}

/// The exactly optimal actions of every state (global ids of [`Model::problem`], ascending):
/// the actions whose exact [`q_value`] equals the state's optimal value (rational equality, no
/// tolerance) and that some optimal stationary policy uses. Empty where the solution
/// prescribes nothing (`policy[x]` is `None`: goals, ended episodes, states from which no
/// policy reaches a goal).
///
/// Under truecost and reach an action can attain the optimal value without being usable: a
/// move into the border that keeps the agent in place attains the reach probability of its
/// own state, and a zero-cost loop attains `G*`; a policy choosing it never gets anywhere. So
/// where actions tie, an action is kept only if, with the state committed to it and every
/// other state free to choose among its value-attaining actions, a state where the solution
/// prescribes nothing is still reachable with positive probability from the state (then a
/// stationary policy with that choice reaches one with probability 1, and attains the optimal
/// values everywhere). Under discounting every policy ends (probability `1 − α` a step), so
/// every value-attaining action is optimal.
///
/// ```
/// use truecost::{envs::EnvSpec, objectives::actions::optimal_actions};
/// use truecost::objectives::{Model, Objective};
/// let env = EnvSpec::parse("cliffwalking").unwrap().build().unwrap();
/// let m = Model::from_environment(&env).unwrap();
/// let s = m.solve(&Objective::Truecost).unwrap();
/// let up = m.problem.actions(36).start; // Gymnasium's UP from the start, only way round the cliff
/// assert_eq!(optimal_actions(&m, &s)[36], vec![up]);
/// ```
pub fn optimal_actions(model: &Model, s: &Solution) -> Vec<Vec<usize>> {
    let p = &model.problem;
    let n = p.states();
    let mut optimal: Vec<Vec<usize>> = (0..n)
        .map(|x| match s.policy[x] {
            None => Vec::new(),
            Some(_) => p
                .actions(x)
                .filter(|&a| q_value(model, s, a) == s.values[x])
                .collect(),
        })
        .collect();
    if matches!(s.objective, Objective::Discounted(_)) {
        return optimal;
    }
    // Who steps where with positive probability, through value-attaining actions only.
    let mut predecessors: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (x, list) in optimal.iter().enumerate() {
        for &a in list {
            for o in p.outcomes(a).iter().filter(|o| o.probability.is_positive()) {
                predecessors[o.successor].push(x);
            }
        }
    }
    let ended: Vec<usize> = (0..n).filter(|&x| s.policy[x].is_none()).collect();
    for (x, list) in optimal.iter_mut().enumerate() {
        if list.len() < 2 {
            continue;
        }
        // The states that reach an ended state with positive probability without x.
        let mut reaches = vec![false; n];
        let mut queue = ended.clone();
        for &e in &ended {
            reaches[e] = true;
        }
        while let Some(y) = queue.pop() {
            for &z in &predecessors[y] {
                if z != x && !reaches[z] {
                    reaches[z] = true;
                    queue.push(z);
                }
            }
        }
        list.retain(|&a| {
            p.outcomes(a)
                .iter()
                .any(|o| o.probability.is_positive() && reaches[o.successor])
        });
    }
    optimal
}

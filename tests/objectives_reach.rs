//! The reach probabilities (`max_reach`, `min_reach`, the reach objective) against a brute-force
//! solver written here: on small random MDPs (traps, zero-cost cycles, dead ends, states that
//! reach a goal with a probability strictly between 0 and 1), every deterministic stationary
//! policy is evaluated as a Markov chain by exact Gaussian elimination, and the greatest and
//! least reach probabilities per state are the maximum and minimum over them (finite MDPs
//! have optimal deterministic stationary policies for both). Also the reach objective's policy
//! attains the greatest probability, and its expected truecost and number of steps are those
//! of its own chain.

use num_traits::{One, Zero};
use truecost::objectives::{max_reach, min_reach, Model, Objective, PolicyCost, Solution};
use truecost::problems::StepCost;
use truecost::stochastic::grid::exact_grid;
use truecost::stochastic::{
    NoiseModel, Outcome, OutcomeKind, Predictability, StochasticAction, StochasticProblem,
};
use truecost::value::{Extended, Rational};

/// A small deterministic generator (xorshift), so every run sees the same MDPs.
struct Rng(u64);

impl Rng {
    fn below(&mut self, n: u64) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0 % n
    }
}

fn q(n: i64, d: i64) -> Rational {
    Rational::new(n.into(), d.into())
}

/// A random MDP on 2–6 states: one or two goals, 0–3 actions a non-goal state (a dead end
/// now and then), 1–3 outcomes an action with weights 1–3, costs 0–2.
fn random_mdp(rng: &mut Rng) -> StochasticProblem {
    let n = 2 + rng.below(5) as usize;
    let mut goals = vec![n - 1];
    if n > 3 && rng.below(3) == 0 {
        goals.push(n - 2);
    }
    let actions = (0..n)
        .map(|x| {
            if goals.contains(&x) {
                return Vec::new();
            }
            let count = rng.below(4) as usize;
            (0..count)
                .map(|_| {
                    let k = 1 + rng.below(3.min(n as u64)) as usize;
                    let mut targets: Vec<usize> = Vec::new();
                    while targets.len() < k {
                        let y = rng.below(n as u64) as usize;
                        if !targets.contains(&y) {
                            targets.push(y);
                        }
                    }
                    let weights: Vec<i64> =
                        targets.iter().map(|_| 1 + rng.below(3) as i64).collect();
                    let total: i64 = weights.iter().sum();
                    StochasticAction {
                        cost: q(rng.below(3) as i64, 1),
                        outcomes: targets
                            .iter()
                            .zip(&weights)
                            .map(|(&y, &w)| Outcome {
                                successor: y,
                                probability: q(w, total),
                                kind: OutcomeKind::Listed,
                            })
                            .collect(),
                    }
                })
                .collect()
        })
        .collect();
    StochasticProblem::new(actions, 0, goals).unwrap()
}

/// Solves `A·v = b` exactly (Gaussian elimination; `A` nonsingular).
fn gauss(mut a: Vec<Vec<Rational>>, mut b: Vec<Rational>) -> Vec<Rational> {
    let m = b.len();
    for c in 0..m {
        let pivot = (c..m).find(|&r| !a[r][c].is_zero()).expect("nonsingular");
        a.swap(c, pivot);
        b.swap(c, pivot);
        let pivot_row = a[c].clone();
        for r in 0..m {
            if r != c && !a[r][c].is_zero() {
                let f = &a[r][c] / &pivot_row[c];
                for (v, w) in a[r].iter_mut().zip(&pivot_row).skip(c) {
                    *v -= &f * w;
                }
                let t = &f * &b[c];
                b[r] -= t;
            }
        }
    }
    (0..m).map(|r| &b[r] / &a[r][r]).collect()
}

/// The Markov chain of a policy (`policy[x]`: a global action id or none): per state the
/// probability of reaching a goal, and the expected total of `cost(a)` where that probability
/// is 1 (`None` elsewhere).
fn chain(
    p: &StochasticProblem,
    policy: &[Option<usize>],
    cost: impl Fn(usize) -> Rational,
) -> (Vec<Rational>, Vec<Option<Rational>>) {
    let n = p.states();
    let step = |x: usize| -> &[Outcome] {
        match policy[x] {
            Some(a) if !p.is_goal(x) => p.outcomes(a),
            _ => &[],
        }
    };
    // States that reach a goal in the chain's graph (a fixpoint, small n).
    let mut reach: Vec<bool> = (0..n).map(|x| p.is_goal(x)).collect();
    loop {
        let before = reach.clone();
        for x in 0..n {
            if step(x).iter().any(|o| reach[o.successor]) {
                reach[x] = true;
            }
        }
        if reach == before {
            break;
        }
    }
    // Probability: v = P v on the reaching non-goal states, goals 1, others 0.
    let unknowns: Vec<usize> = (0..n).filter(|&x| reach[x] && !p.is_goal(x)).collect();
    let system =
        |set: &[usize], rhs: &dyn Fn(usize) -> Rational, known: &dyn Fn(usize) -> Rational| {
            let pos = |y: usize| set.iter().position(|&z| z == y);
            let mut a = vec![vec![Rational::zero(); set.len()]; set.len()];
            let mut b = vec![Rational::zero(); set.len()];
            for (i, &x) in set.iter().enumerate() {
                a[i][i] += Rational::one();
                b[i] = rhs(x);
                for o in step(x) {
                    match pos(o.successor) {
                        Some(j) => a[i][j] -= &o.probability,
                        None => b[i] += &o.probability * known(o.successor),
                    }
                }
            }
            gauss(a, b)
        };
    let solved = system(&unknowns, &|_| Rational::zero(), &|y| {
        if p.is_goal(y) {
            Rational::one()
        } else {
            Rational::zero()
        }
    });
    let mut prob: Vec<Rational> = (0..n)
        .map(|x| {
            if p.is_goal(x) {
                Rational::one()
            } else {
                Rational::zero()
            }
        })
        .collect();
    for (&x, v) in unknowns.iter().zip(solved) {
        prob[x] = v;
    }
    // Expected cost where the probability is 1 (a closed set of the chain).
    let sure: Vec<usize> = (0..n)
        .filter(|&x| prob[x].is_one() && !p.is_goal(x))
        .collect();
    let totals = system(&sure, &|x| cost(policy[x].unwrap()), &|_| Rational::zero());
    let mut expected: Vec<Option<Rational>> =
        (0..n).map(|x| p.is_goal(x).then(Rational::zero)).collect();
    for (&x, v) in sure.iter().zip(totals) {
        expected[x] = Some(v);
    }
    (prob, expected)
}

/// Every deterministic stationary policy over the allowed actions (`None` where a state has
/// none).
fn policies(p: &StochasticProblem, allowed: &dyn Fn(usize) -> bool) -> Vec<Vec<Option<usize>>> {
    let mut all = vec![Vec::new()];
    for x in 0..p.states() {
        let own: Vec<usize> = p.actions(x).filter(|&a| allowed(a)).collect();
        let choices: Vec<Option<usize>> = if own.is_empty() || p.is_goal(x) {
            vec![None]
        } else {
            own.into_iter().map(Some).collect()
        };
        all = all
            .into_iter()
            .flat_map(|prefix: Vec<Option<usize>>| {
                choices.iter().map(move |&c| {
                    let mut next = prefix.clone();
                    next.push(c);
                    next
                })
            })
            .collect();
    }
    all
}

/// Per state, the least and greatest reach probability over all policies.
fn brute_force(
    p: &StochasticProblem,
    allowed: &dyn Fn(usize) -> bool,
) -> (Vec<Rational>, Vec<Rational>) {
    let n = p.states();
    let mut min = vec![Rational::one(); n];
    let mut max = vec![Rational::zero(); n];
    for policy in policies(p, allowed) {
        let (prob, _) = chain(p, &policy, |_| Rational::zero());
        for x in 0..n {
            if prob[x] < min[x] {
                min[x] = prob[x].clone();
            }
            if prob[x] > max[x] {
                max[x] = prob[x].clone();
            }
        }
    }
    (min, max)
}

#[test]
fn reach_probabilities_equal_the_brute_force_optimum_over_all_policies() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut strictly_between = 0;
    for case in 0..300 {
        let p = random_mdp(&mut rng);
        // Every action, then a random half of them.
        let mask: Vec<bool> = (0..p.action_total()).map(|_| rng.below(2) == 0).collect();
        for allowed in [&(|_: usize| true) as &dyn Fn(usize) -> bool, &|a: usize| {
            mask[a]
        }] {
            let (min, max) = brute_force(&p, allowed);
            let (greatest, policy) = max_reach(&p, allowed).unwrap();
            assert_eq!(
                greatest,
                max,
                "case {case}: max reach, {:?}",
                p.action_lists()
            );
            assert_eq!(
                min_reach(&p, allowed).unwrap(),
                min,
                "case {case}: min reach"
            );
            // The policy attains the greatest probability everywhere, with allowed actions.
            assert!(policy.iter().flatten().all(|&a| allowed(a)));
            assert_eq!(
                chain(&p, &policy, |_| Rational::zero()).0,
                max,
                "case {case}: policy"
            );
            strictly_between += max.iter().filter(|v| !v.is_zero() && !v.is_one()).count();
        }
    }
    assert!(
        strictly_between > 50,
        "maybe-states are exercised: {strictly_between}"
    );
}

#[test]
fn the_reach_objective_reports_a_reach_optimal_policy_and_its_own_cost_and_steps() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (mut finite, mut infinite) = (0, 0);
    for case in 0..200 {
        let p = random_mdp(&mut rng);
        let model = Model::from_problem(p.clone(), format!("random {case}"));
        let (_, max) = brute_force(&p, &|_| true);
        let r = model.solve(&Objective::Reach).unwrap();
        assert_eq!(probabilities(&r), max, "case {case}");
        let (prob, cost) = chain(&p, &r.policy, |a| p.cost(a).clone());
        assert_eq!(
            prob, max,
            "case {case}: the reported policy attains the maximum"
        );
        assert_eq!(r.policy_success, max[0], "case {case}");
        assert_eq!(
            (r.success.min.clone(), r.success.max.clone()),
            (max[0].clone(), max[0].clone())
        );
        let (_, steps) = chain(&p, &r.policy, |_| Rational::one());
        match &cost[0] {
            Some(c) => {
                finite += 1;
                assert_eq!(r.truecost, Extended::Finite(c.clone()), "case {case}");
                assert_eq!(
                    r.steps,
                    Extended::Finite(steps[0].clone().unwrap()),
                    "case {case}"
                );
                // On S1 the policy is truecost-optimal: its cost is G*(x1).
                let t = model.solve(&Objective::Truecost).unwrap();
                assert_eq!(r.truecost, t.value_initial, "case {case}");
            }
            None => {
                infinite += 1;
                assert_eq!(
                    (&r.truecost, &r.steps),
                    (&Extended::Infinite, &Extended::Infinite)
                );
            }
        }
    }
    assert!(
        finite > 20 && infinite > 20,
        "{finite} finite, {infinite} infinite"
    );
}

#[test]
fn paper_problems_reach_a_goal_surely_exactly_where_g_star_is_finite() {
    for (id, gamma) in [(3, "0.9"), (10, "0.999"), (16, "0.5"), (10, "1")] {
        let gamma = Predictability::parse(gamma).unwrap();
        let p = exact_grid(id, StepCost::Unit, NoiseModel::Paper, &gamma).unwrap();
        let model = Model::from_problem(p.clone(), format!("problem {id}"));
        let r = model.solve(&Objective::Reach).unwrap();
        let t = model.solve(&Objective::Truecost).unwrap();
        // Probability 1 exactly where some policy reaches a goal with probability 1.
        for x in 0..p.states() {
            let one = r.values[x] == Extended::Finite(Rational::one());
            assert_eq!(
                one,
                t.values[x].finite().is_some(),
                "problem {id}, state {x}"
            );
        }
        assert_eq!(r.truecost, t.value_initial, "problem {id}");
        assert_eq!(r.steps, t.steps, "problem {id}: the same policy's steps");
    }
}

#[test]
fn the_reach_objective_without_its_cost_attains_the_greatest_probability_by_graph_analysis() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut skipped, mut infinite) = (0, 0);
    for case in 0..200 {
        let p = random_mdp(&mut rng);
        let model = Model::from_problem(p.clone(), format!("random {case}"));
        let (_, max) = brute_force(&p, &|_| true);
        let r = model
            .solve_with(&Objective::Reach, PolicyCost::IfInfinite)
            .unwrap();
        assert_eq!(probabilities(&r), max, "case {case}");
        let (prob, cost) = chain(&p, &r.policy, |a| p.cost(a).clone());
        assert_eq!(prob, max, "case {case}: the policy attains the maximum");
        assert_eq!(r.policy_success, max[0], "case {case}");
        if max[0].is_one() {
            // The attractor policy reaches a goal surely: its cost is finite, not computed.
            skipped += 1;
            assert!(cost[0].is_some(), "case {case}");
            assert!(!r.costs_computed, "case {case}");
        } else {
            infinite += 1;
            assert!(cost[0].is_none(), "case {case}");
            assert!(r.costs_computed, "case {case}");
            assert_eq!(
                (&r.truecost, &r.steps),
                (&Extended::Infinite, &Extended::Infinite),
                "case {case}"
            );
        }
    }
    assert!(
        skipped > 20 && infinite > 20,
        "{skipped} not computed, {infinite} infinite"
    );
}

/// The reach objective's values, each a finite probability.
fn probabilities(r: &Solution) -> Vec<Rational> {
    r.values
        .iter()
        .map(|v| v.finite().unwrap().clone())
        .collect()
}

//! The stochastic model (docs/spec.md §3, §7): hand-derived optima, the exact Bellman equation, γ = 1
//! against Dijkstra, exact scaling with the step cost, optimality against an exhaustive
//! brute-force oracle and random perturbations (proptest), the published reference counts, and
//! bad input. Expected values come from hand derivations, independent oracles or the published
//! table (`shared/reference/problem10.md`), never from the code under test.

mod common;
use common::stochastic_file;

use num_bigint::BigInt;
use num_traits::{One, Zero};
use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use truecost::model::{ExactGraph, Move, Problem};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::dijkstra;
use truecost::stochastic::file;
use truecost::stochastic::grid::{exact_grid, exact_twin, reference_grid};
use truecost::stochastic::policy_iteration::{evaluate, optimum};
use truecost::stochastic::value_iteration::{
    value_iteration_exact, value_iteration_f64, FloatModel, Schedule, ViOptions,
};
use truecost::stochastic::{
    NoiseModel, Outcome, OutcomeKind, Predictability, StochasticAction, StochasticError,
    StochasticProblem,
};
use truecost::value::{parse_rational, ExactValue, Extended, Rational};

fn q(text: &str) -> Rational {
    parse_rational(text).unwrap()
}

fn gamma(text: &str) -> Predictability {
    Predictability::parse(text).unwrap()
}

fn moves(list: &[&[usize]]) -> Vec<Vec<Move>> {
    list.iter()
        .map(|succ| {
            succ.iter()
                .map(|&y| Move {
                    successor: y,
                    cost: q("1"),
                })
                .collect()
        })
        .collect()
}

/// Moves `(successor, cost)` per state.
fn weighted(list: &[&[(usize, &str)]]) -> Vec<Vec<Move>> {
    list.iter()
        .map(|succ| {
            succ.iter()
                .map(|&(y, c)| Move {
                    successor: y,
                    cost: q(c),
                })
                .collect()
        })
        .collect()
}

fn strings(values: &[Extended]) -> Vec<String> {
    values.iter().map(|v| v.to_string()).collect()
}

// ---------------------------------------------------------------------------------------------
// Hand-derived optima.

/// Line 0 – 1 – 2 (goal), unit costs. Both models coincide here (k ≤ 2). With γ:
/// G(0) = 1 + γ G(1) + (1−γ) G(0) ⇒ G(0) = 1/γ + G(1);
/// G(1) = 1 + (1−γ)/2 G(0) + (1−γ)/2 G(1) ⇒ G(1) = (1+γ)/(2γ²).
/// γ = 1/2: G = (5, 3, 0). γ = 9/10: G(1) = (19/10)/(162/100) = 95/81, G(0) = 10/9 + 95/81 = 185/81.
#[test]
fn line_of_three_by_hand() {
    let p = Problem::new(moves(&[&[1], &[0, 2], &[]]), 0, vec![2]).unwrap();
    for model in [NoiseModel::Paper, NoiseModel::Reference] {
        for (g, expected) in [("0.5", ["5", "3", "0"]), ("0.9", ["185/81", "95/81", "0"])] {
            let s = StochasticProblem::from_deterministic(&p, model, &gamma(g)).unwrap();
            let o = optimum(&s).unwrap();
            assert_eq!(strings(o.cost_to_go_all()), expected, "{model:?} γ = {g}");
            // The optimal action at 1 is the move to the goal (index 1).
            assert_eq!(o.policy()[1], Some(truecost::model::Decision::Move(1)));
        }
    }
}

/// A star: centre 0 with moves to 1 (goal), 2, 3; states 2 and 3 only move back to 0.
/// G(2) = G(3) = 1/γ + G(0) in both models. At 0, commanding the goal:
/// paper: G(0) = 1 + (1−γ)/3 (2 G(2) + G(0)) ⇒ G(0) = (γ+2)/(3γ²);
/// reference: stay (1−γ)/2, others (1−γ)/4 ⇒ G(0) = (1+γ)/(2γ²).
/// γ = 1/2: paper (10/3, 0, 16/3, 16/3); reference (3, 0, 5, 5).
#[test]
fn star_distinguishes_the_noise_models() {
    let p = Problem::new(moves(&[&[1, 2, 3], &[], &[0], &[0]]), 0, vec![1]).unwrap();
    let paper =
        StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma("1/2")).unwrap();
    assert_eq!(
        strings(optimum(&paper).unwrap().cost_to_go_all()),
        ["10/3", "0", "16/3", "16/3"]
    );
    let reference =
        StochasticProblem::from_deterministic(&p, NoiseModel::Reference, &gamma("1/2")).unwrap();
    assert_eq!(
        strings(optimum(&reference).unwrap().cost_to_go_all()),
        ["3", "0", "5", "5"]
    );
    // The outcome lists (commanded, other moves in order, stay) with exact probabilities.
    let a = paper.actions(0).start; // command the goal
    let listed: Vec<(usize, String, OutcomeKind)> = paper
        .outcomes(a)
        .iter()
        .map(|o| (o.successor, o.probability.to_string(), o.kind))
        .collect();
    assert_eq!(
        listed,
        vec![
            (1, "1/2".into(), OutcomeKind::Commanded),
            (2, "1/6".into(), OutcomeKind::Other(1)),
            (3, "1/6".into(), OutcomeKind::Other(2)),
            (0, "1/6".into(), OutcomeKind::Stay),
        ]
    );
    let listed: Vec<String> = reference
        .outcomes(a)
        .iter()
        .map(|o| o.probability.to_string())
        .collect();
    assert_eq!(listed, ["1/2", "1/8", "1/8", "1/4"]);
}

/// `split_f64` (the reference-mode float model, docs/spec.md §7) is `split` computed in `f64`: each of
/// its three probabilities is within a few units in the last place of the exact one, for both
/// noise models and every number of moves the grids have (1 to 8).
#[test]
fn the_f64_split_is_the_exact_split_in_f64() {
    let f = |r: &Rational| num_traits::ToPrimitive::to_f64(r).unwrap();
    for text in ["0.5", "0.8", "0.9", "0.99", "0.999999", "1"] {
        let g = gamma(text);
        for model in [NoiseModel::Paper, NoiseModel::Reference] {
            for k in 1..=8 {
                let (c, o, st) = model.split(&g, k);
                let (cf, of, sf) = model.split_f64(f(g.value()), k);
                for (exact, float) in [(f(&c), cf), (f(&o), of), (f(&st), sf)] {
                    assert!(
                        (exact - float).abs() <= 1e-15,
                        "{} γ={text} k={k}: {exact} against {float}",
                        model.name()
                    );
                }
            }
        }
    }
}

/// Paper problem 16 is a corridor 226 – 227 – … – 231 (goal), x1 = 227. With γ = 1/2 both
/// models agree (every state has k ≤ 2 moves). Commanding "right": an interior state gives
/// ¾·G(i) = 1 + ½·G(i+1) + ¼·G(i−1), the end 226 gives G(226) = 2 + G(227). Solving by hand
/// from the goal: G = 129/8, 113/8, 89/8, 61/8, 31/8, 0.
#[test]
fn paper_problem_16_corridor_by_hand() {
    for model in [NoiseModel::Paper, NoiseModel::Reference] {
        let s = exact_grid(16, StepCost::Unit, model, &gamma("0.5")).unwrap();
        let o = optimum(&s).unwrap();
        let g: Vec<String> = (226..=231).map(|x| o.cost_to_go(x).to_string()).collect();
        assert_eq!(
            g,
            ["129/8", "113/8", "89/8", "61/8", "31/8", "0"],
            "{model:?}"
        );
        assert_eq!(s.initial(), 227);
    }
}

/// A trap: from 0 the goal 1 is one move away but noise may push into the absorbing state 2.
/// With γ < 1 no policy reaches the goal with probability 1 from 0: G*(0) = +∞. With γ = 1
/// it is 1. A state without any action is a dead end (+∞).
#[test]
fn traps_and_dead_ends_are_infinite() {
    let p = Problem::new(moves(&[&[1, 2], &[], &[2], &[]]), 0, vec![1]).unwrap();
    let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma("0.999")).unwrap();
    assert_eq!(
        strings(optimum(&s).unwrap().cost_to_go_all()),
        ["inf", "0", "inf", "inf"]
    );
    let d = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::one())
        .unwrap();
    assert_eq!(
        strings(optimum(&d).unwrap().cost_to_go_all()),
        ["1", "0", "inf", "inf"]
    );
}

/// Zero-cost cycle: 0 ⇄ 1 at cost 0, 1 → 2 (goal) at cost 0, 0 → 2 at cost 5. The policy
/// that circles forever costs 0 per step but never reaches the goal: it is not proper, its true
/// cost is +∞. G*(0) = G*(1) = 0 via the free move to the goal, reached with probability 1.
#[test]
fn zero_cost_cycles_do_not_fool_policy_iteration() {
    let actions = vec![
        vec![
            StochasticAction {
                cost: q("0"),
                outcomes: vec![out(1, "1")],
            },
            StochasticAction {
                cost: q("5"),
                outcomes: vec![out(2, "1")],
            },
        ],
        vec![
            StochasticAction {
                cost: q("0"),
                outcomes: vec![out(0, "1")],
            },
            StochasticAction {
                cost: q("0"),
                outcomes: vec![out(2, "1/2"), out(1, "1/2")],
            },
        ],
        vec![],
    ];
    let s = StochasticProblem::new(actions, 0, vec![2]).unwrap();
    let o = optimum(&s).unwrap();
    assert_eq!(strings(o.cost_to_go_all()), ["0", "0", "0"]);
    // The reported policy is proper: its exact evaluation is finite everywhere.
    let g = evaluate(&s, o.policy_actions()).unwrap();
    assert_eq!(strings(&g), ["0", "0", "0"]);
    // Circling 0 → 1 → 0 is improper: +∞.
    let circling = evaluate(&s, &[Some(0), Some(2), None]).unwrap();
    assert_eq!(strings(&circling), ["inf", "inf", "0"]);
}

fn out(to: usize, p: &str) -> Outcome {
    Outcome {
        successor: to,
        probability: q(p),
        kind: OutcomeKind::Listed,
    }
}

// ---------------------------------------------------------------------------------------------
// One small problem with a trap, solved by hand, against what the module reports beside `G*`:
// the optimum's accessors, value iteration's work counts (checked against a count made here
// from the problem's own lists) and the sampler's end points (the mutants
// `unreduced → Some((0, 0))`, `q_value`'s `d·s_x` → `d/s_x`, `suboptimal_states` without its
// goal filter, `sweeps * per_sweep_terms` → `/`, `usable`'s `==` → `!=` and
// `cumulative.len() - 1` → `+ 1` survived the value tests).

fn action(cost: &str, outcomes: Vec<Outcome>) -> StochasticAction {
    StochasticAction {
        cost: q(cost),
        outcomes,
    }
}

/// State 0 has a safe action (to the goal 1 or back to 0) and an unsafe one (to the trap 2 with
/// probability 1/2); state 3 reaches the goal through 0 with three outcomes. The trap 2 only
/// loops, so `G*(2) = +∞` and the unsafe action must be neither backed up nor counted.
fn with_an_unsafe_action() -> StochasticProblem {
    StochasticProblem::new(
        vec![
            vec![
                action("1", vec![out(1, "3/4"), out(0, "1/4")]),
                action("1", vec![out(2, "1/2"), out(1, "1/2")]),
            ],
            vec![],
            vec![action("1", vec![out(2, "1")])],
            vec![action(
                "2",
                vec![out(0, "1/2"), out(3, "1/4"), out(1, "1/4")],
            )],
        ],
        3,
        vec![1],
    )
    .unwrap()
}

/// By hand: `G*(0) = 1 + G*(0)/4 = 4/3`; `G*(3) = 2 + G*(0)/2 + G*(3)/4`, so
/// `G*(3) = (4/3)·(8/3) = 32/9`; `G*(1) = 0`; `G*(2) = +∞`. `Q*(0, to the trap) = +∞`.
#[test]
fn the_optimum_s_accessors_by_hand() {
    let s = with_an_unsafe_action();
    let o = optimum(&s).unwrap();
    let want = [Some(q("4/3")), Some(q("0")), None, Some(q("32/9"))];
    for (x, want) in want.iter().enumerate() {
        let got = o
            .unreduced(x)
            .map(|(n, d)| Rational::new(n.clone(), d.clone()));
        assert_eq!(&got, want, "state {x}");
        let shown = want.clone().map_or(Extended::Infinite, Extended::Finite);
        assert_eq!(o.cost_to_go_all()[x], shown, "state {x}");
    }
    let (safe, unsafe_, trap, only) = (0, 1, s.actions(2).start, s.actions(3).start);
    assert_eq!(o.q_value(&s, safe), Extended::Finite(q("4/3")));
    assert_eq!(o.q_value(&s, unsafe_), Extended::Infinite);
    assert_eq!(o.q_value(&s, trap), Extended::Infinite);
    assert_eq!(o.q_value(&s, only), Extended::Finite(q("32/9")));
    assert!(o.is_optimal_action(&s, safe) && o.is_optimal_action(&s, only));
    assert!(!o.is_optimal_action(&s, unsafe_));
    // Goals are never counted; states with G* = +∞ neither; a finite state without an action is.
    let all = vec![Some(safe), None, Some(trap), Some(only)];
    assert_eq!(o.suboptimal_states(&s, &all), Vec::<usize>::new());
    let bad = vec![Some(unsafe_), Some(0), None, Some(only)];
    assert_eq!(o.suboptimal_states(&s, &bad), [0]);
    let missing = vec![Some(safe), None, None, None];
    assert_eq!(o.suboptimal_states(&s, &missing), [3]);
}

#[test]
fn backups_and_outcome_terms_are_sweeps_times_the_safe_actions_of_the_finite_states() {
    let s = with_an_unsafe_action();
    let star = optimum(&s).unwrap();
    let g = star.cost_to_go_all();
    assert_eq!(g[2], Extended::Infinite);
    // The count, by hand from the lists: swept = finite non-goal states; an action is safe when
    // every outcome has finite G*.
    let (mut backups, mut terms) = (0u64, 0u64);
    for x in 0..s.states() {
        if s.is_goal(x) || g[x] == Extended::Infinite {
            continue;
        }
        for a in s.actions(x) {
            let outcomes = s.outcomes(a);
            if outcomes
                .iter()
                .all(|o| g[o.successor] != Extended::Infinite)
            {
                backups += 1;
                terms += outcomes.len() as u64;
            }
        }
    }
    assert_eq!((backups, terms), (2, 5), "the hand count itself");
    for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
        let options = ViOptions::from_below(schedule, q("1/1000"), 10_000).unwrap();
        let exact = value_iteration_exact(&s, &options);
        assert!(exact.converged && exact.sweeps > 1, "{schedule:?}");
        assert_eq!(exact.backups, exact.sweeps * backups, "{schedule:?}");
        assert_eq!(exact.outcome_terms, exact.sweeps * terms, "{schedule:?}");
        assert_eq!(exact.cost_to_go[2], Extended::Infinite);
        let float = value_iteration_f64(&s, &FloatModel::nearest(&s), &options);
        assert!(float.sweeps > 1, "{schedule:?}");
        assert_eq!(float.backups, float.sweeps * backups, "{schedule:?}");
        assert_eq!(float.outcome_terms, float.sweeps * terms, "{schedule:?}");
    }
}

#[test]
fn sampling_at_and_beyond_one_gives_the_last_outcome() {
    let s = with_an_unsafe_action();
    // Action 3 (state 3's only action): outcomes 0, 3, 1 with probabilities 1/2, 1/4, 1/4.
    let a = s.actions(3).start;
    for (u, successor) in [
        (0.0, 0),
        (0.49, 0),
        (0.5, 3),
        (0.74, 3),
        (0.75, 1),
        (0.999, 1),
        (1.0, 1),
        (1.5, 1),
    ] {
        assert_eq!(s.sample(a, u), successor, "u = {u}");
    }
}

// ---------------------------------------------------------------------------------------------
// The exact Bellman equation, checked with plain big-rational arithmetic (an oracle that shares
// nothing with the solver but the problem).

fn assert_bellman(s: &StochasticProblem, g: &[Extended], label: &str) {
    for x in 0..s.states() {
        if s.is_goal(x) {
            assert_eq!(
                g[x],
                Extended::Finite(Rational::zero()),
                "{label}: goal {x}"
            );
            continue;
        }
        let best = s
            .actions(x)
            .map(|a| {
                let mut sum = Extended::Finite(s.cost(a).clone());
                for o in s.outcomes(a) {
                    sum = match (&sum, &g[o.successor]) {
                        (Extended::Finite(t), Extended::Finite(v)) => {
                            Extended::Finite(t + &o.probability * v)
                        }
                        _ => Extended::Infinite,
                    };
                }
                sum
            })
            .min()
            .unwrap_or(Extended::Infinite);
        match &g[x] {
            Extended::Finite(_) => assert_eq!(best, g[x], "{label}: state {x}"),
            // +∞ states: every action may reach a +∞ state (checked), and by the properness
            // analysis no policy reaches a goal surely (checked in the brute-force proptest).
            Extended::Infinite => assert_eq!(best, Extended::Infinite, "{label}: state {x}"),
        }
    }
}

#[test]
fn exact_optimum_satisfies_the_bellman_equation_exactly_on_paper_problems() {
    // Sized for the test profile: values with a few hundred digits.
    for (id, g) in [
        (10, "0.5"),
        (10, "0.7"),
        (3, "0.9"),
        (8, "0.99"),
        (16, "0.999"),
        (6, "0.9"),
    ] {
        for model in [NoiseModel::Paper, NoiseModel::Reference] {
            let s = exact_grid(id, StepCost::Unit, model, &gamma(g)).unwrap();
            let o = optimum(&s).unwrap();
            assert_bellman(
                &s,
                o.cost_to_go_all(),
                &format!("problem {id}, {model:?}, γ = {g}"),
            );
            // The reported policy attains G*: its own exact evaluation equals G*.
            assert_eq!(
                evaluate(&s, o.policy_actions()).unwrap(),
                o.cost_to_go_all()
            );
        }
    }
}

#[test]
fn gamma_one_equals_the_deterministic_optimum_of_dijkstra() {
    for id in 0..19 {
        for step in [StepCost::Unit, StepCost::Euclidean] {
            let problem = GridLayout::exact(id).unwrap().to_problem(step);
            let ExactGraph::Units(graph) = ExactGraph::new(&problem) else {
                panic!("grids fit in units")
            };
            let d = dijkstra::to_goals(&graph);
            let expected: Vec<Extended> = d
                .cost_to_go
                .iter()
                .map(|v| v.to_extended(graph.unit()).unwrap())
                .collect();
            for model in [NoiseModel::Paper, NoiseModel::Reference] {
                let s =
                    StochasticProblem::from_deterministic(&problem, model, &Predictability::one())
                        .unwrap();
                let o = optimum(&s).unwrap();
                assert_eq!(
                    o.cost_to_go_all(),
                    expected.as_slice(),
                    "problem {id} {step:?}"
                );
            }
        }
    }
}

/// G* is linear in the stage costs: Euclidean (800/19 per move) = 800/19 × unit, exactly, at
/// every state. Compared on the unreduced fractions by cross-multiplication.
#[test]
fn values_scale_exactly_with_the_step_cost() {
    for (id, g) in [(10, "0.9"), (0, "0.99"), (3, "0.5"), (13, "0.7")] {
        for model in [NoiseModel::Paper, NoiseModel::Reference] {
            let unit = optimum(&exact_grid(id, StepCost::Unit, model, &gamma(g)).unwrap()).unwrap();
            let euclid =
                optimum(&exact_grid(id, StepCost::Euclidean, model, &gamma(g)).unwrap()).unwrap();
            for x in 0..400 {
                match (unit.unreduced(x), euclid.unreduced(x)) {
                    (Some((nu, du)), Some((ne, de))) => assert_eq!(
                        ne * du * BigInt::from(19),
                        nu * de * BigInt::from(800),
                        "problem {id}, state {x}"
                    ),
                    (None, None) => {}
                    _ => panic!("problem {id}, state {x}: finite in one, infinite in the other"),
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Optimality: exhaustive brute force on small random problems, perturbations on grids.

/// A dense exact Gaussian elimination (the oracle's own solver).
fn solve_dense(mut a: Vec<Vec<Rational>>, mut b: Vec<Rational>) -> Vec<Rational> {
    let n = b.len();
    for k in 0..n {
        let pivot = (k..n).find(|&i| !a[i][k].is_zero()).expect("non-singular");
        a.swap(k, pivot);
        b.swap(k, pivot);
        for i in 0..n {
            if i != k && !a[i][k].is_zero() {
                let f = &a[i][k] / &a[k][k];
                let pivot_row = a[k].clone();
                for (aij, akj) in a[i].iter_mut().zip(&pivot_row).skip(k) {
                    *aij -= &f * akj;
                }
                let t = &f * &b[k];
                b[i] -= t;
            }
        }
    }
    (0..n).map(|i| &b[i] / &a[i][i]).collect()
}

/// The exact cost of a stationary policy by the oracle: a state is proper if every state it
/// can reach under the policy can reach a goal; proper states solve `G = l + P G` densely.
fn oracle_evaluate(s: &StochasticProblem, policy: &[Option<usize>]) -> Vec<Extended> {
    let n = s.states();
    let succ = |x: usize| -> Vec<usize> {
        if s.is_goal(x) {
            return vec![];
        }
        policy[x].map_or(vec![], |a| {
            s.outcomes(a).iter().map(|o| o.successor).collect()
        })
    };
    let reach = |x: usize| {
        let mut seen = vec![false; n];
        let mut stack = vec![x];
        seen[x] = true;
        while let Some(v) = stack.pop() {
            for w in succ(v) {
                if !seen[w] {
                    seen[w] = true;
                    stack.push(w);
                }
            }
        }
        seen
    };
    let reaches_goal: Vec<bool> = (0..n)
        .map(|x| reach(x).iter().enumerate().any(|(v, &r)| r && s.is_goal(v)))
        .collect();
    let proper: Vec<bool> = (0..n)
        .map(|x| {
            s.is_goal(x)
                || (policy[x].is_some()
                    && reach(x)
                        .iter()
                        .enumerate()
                        .all(|(v, &r)| !r || reaches_goal[v]))
        })
        .collect();
    let unknowns: Vec<usize> = (0..n).filter(|&x| proper[x] && !s.is_goal(x)).collect();
    let pos = |x: usize| unknowns.iter().position(|&u| u == x);
    let m = unknowns.len();
    let mut a = vec![vec![Rational::zero(); m]; m];
    let mut b = vec![Rational::zero(); m];
    for (i, &x) in unknowns.iter().enumerate() {
        let act = policy[x].unwrap();
        a[i][i] += Rational::one();
        b[i] = s.cost(act).clone();
        for o in s.outcomes(act) {
            if let Some(j) = pos(o.successor) {
                a[i][j] -= &o.probability;
            }
        }
    }
    let z = solve_dense(a, b);
    (0..n)
        .map(|x| {
            if s.is_goal(x) {
                Extended::Finite(Rational::zero())
            } else {
                pos(x).map_or(Extended::Infinite, |i| Extended::Finite(z[i].clone()))
            }
        })
        .collect()
}

/// All stationary deterministic policies (each non-goal state picks one of its actions).
fn all_policies(s: &StochasticProblem) -> Vec<Vec<Option<usize>>> {
    let mut out = vec![vec![None; s.states()]];
    for x in 0..s.states() {
        if s.is_goal(x) || s.actions(x).is_empty() {
            continue;
        }
        out = out
            .into_iter()
            .flat_map(|p| {
                s.actions(x).map(move |a| {
                    let mut q = p.clone();
                    q[x] = Some(a);
                    q
                })
            })
            .collect();
    }
    out
}

/// Random small stochastic problems: costs in {0, 1/2, 1, 2} (zero-cost cycles included),
/// 1–3 outcomes with random weights, dead ends and traps allowed.
fn small_problem() -> impl Strategy<Value = StochasticProblem> {
    (2usize..=5).prop_flat_map(|n| {
        let action = (
            0usize..4,
            proptest::collection::vec((0..n, 1u32..=4), 1..=3),
        );
        let state = proptest::collection::vec(action, 0..=3);
        (Just(n), proptest::collection::vec(state, n), 0..n, 0..n).prop_map(
            |(n, states, initial, goal)| {
                let costs = ["0", "1/2", "1", "2"];
                let actions = states
                    .into_iter()
                    .map(|list| {
                        list.into_iter()
                            .map(|(c, outs)| {
                                let total: u32 = outs.iter().map(|o| o.1).sum();
                                StochasticAction {
                                    cost: q(costs[c]),
                                    outcomes: outs
                                        .iter()
                                        .map(|&(to, w)| out(to, &format!("{w}/{total}")))
                                        .collect(),
                                }
                            })
                            .collect()
                    })
                    .collect();
                let _ = n;
                StochasticProblem::new(actions, initial, vec![goal]).unwrap()
            },
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    /// G*(x) = min over every stationary policy proper at x of its exact cost (exhaustive), and
    /// the reported policy attains it at every state; the library's `evaluate` of every policy
    /// equals the oracle's (fractional costs included).
    #[test]
    fn optimum_equals_exhaustive_brute_force(s in small_problem()) {
        let o = optimum(&s).unwrap();
        let mut best = vec![Extended::Infinite; s.states()];
        for p in all_policies(&s) {
            let oracle = oracle_evaluate(&s, &p);
            prop_assert_eq!(&evaluate(&s, &p).unwrap(), &oracle, "policy {:?}", p);
            for (x, v) in oracle.into_iter().enumerate() {
                if v < best[x] {
                    best[x] = v;
                }
            }
        }
        prop_assert_eq!(o.cost_to_go_all(), best.as_slice());
        prop_assert_eq!(oracle_evaluate(&s, o.policy_actions()), best);
        assert_bellman(&s, o.cost_to_go_all(), "random problem");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Randomly perturbing the optimal policy of a paper problem never lowers any state's
    /// exact expected cost (evaluations by the library, each re-verified by the oracle's
    /// plug-in check of the policy equation).
    #[test]
    fn perturbing_the_optimal_policy_never_helps(
        seed in any::<u64>(),
        id in prop::sample::select(vec![3usize, 8, 16]),
        model in prop::sample::select(vec![NoiseModel::Paper, NoiseModel::Reference]),
        g in prop::sample::select(vec!["0.5", "0.9"]),
    ) {
        let s = exact_grid(id, StepCost::Unit, model, &gamma(g)).unwrap();
        let o = optimum(&s).unwrap();
        let star = o.cost_to_go_all();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut policy = o.policy_actions().to_vec();
        let candidates: Vec<usize> = (0..s.states()).filter(|&x| policy[x].is_some()).collect();
        for _ in 0..1 + rng.random_range(0..5usize) {
            let x = candidates[rng.random_range(0..candidates.len())];
            let r = s.actions(x);
            policy[x] = Some(r.start + rng.random_range(0..r.len()));
        }
        let g = evaluate(&s, &policy).unwrap();
        for x in 0..s.states() {
            prop_assert!(g[x] >= star[x], "state {}: {} < {}", x, g[x], star[x]);
            // Oracle check of the policy equation where finite.
            if let (Extended::Finite(v), Some(a)) = (&g[x], policy[x]) {
                let mut sum = s.cost(a).clone();
                for o in s.outcomes(a) {
                    let Extended::Finite(w) = &g[o.successor] else { panic!("finite state reaches +inf") };
                    sum += &o.probability * w;
                }
                prop_assert_eq!(&sum, v);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Value iteration.

/// The published counts (`shared/reference/problem10.md`): reference noise, reference mode.
#[test]
fn problem_10_reference_stochastic_vi_counts_match_the_published_table() {
    let published = [
        ("0.999", Schedule::Asynchronous, 58, 178292),
        ("0.999", Schedule::Synchronous, 94, 288956),
        ("0.99", Schedule::Asynchronous, 69, 212106),
        ("0.99", Schedule::Synchronous, 112, 344288),
    ];
    for (g, schedule, sweeps, counted) in published {
        let grid = reference_grid(10, NoiseModel::Reference, &gamma(g)).unwrap();
        let run = value_iteration_f64(&grid.problem, &grid.float, &ViOptions::reference(schedule));
        assert_eq!(
            (run.sweeps, run.reference_counted),
            (sweeps, counted),
            "γ = {g} {schedule:?}"
        );
        assert!(run.converged);
        // The stopped values are close to the exact optimum of the exact twin, not equal.
        let twin = exact_twin(10, NoiseModel::Reference, &gamma(g))
            .unwrap()
            .unwrap();
        let o = optimum(&twin).unwrap();
        let d = o.distance(twin.initial(), |x| Rational::from_float(run.cost_to_go[x]));
        assert!(d.max_abs < q("0.01"), "γ = {g}: {}", d.max_abs);
        assert!(!d.max_abs.is_zero());
    }
}

#[test]
fn exact_value_iteration_from_below_is_a_lower_bound_that_converges() {
    let s = exact_grid(3, StepCost::Unit, NoiseModel::Paper, &gamma("0.9")).unwrap();
    let o = optimum(&s).unwrap();
    let star = o.cost_to_go_all();
    for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
        let mut previous_sweeps = 0;
        for tol in ["1", "0.1", "0.001"] {
            let opts = ViOptions::from_below(schedule, q(tol), 10_000).unwrap();
            let run = value_iteration_exact(&s, &opts);
            assert!(run.converged);
            assert!(run.sweeps >= previous_sweeps);
            previous_sweeps = run.sweeps;
            for (x, bound) in star.iter().enumerate() {
                assert!(
                    &run.cost_to_go[x] <= bound,
                    "{schedule:?} tol {tol} state {x}"
                );
            }
            // f64 value iteration takes the same number of sweeps here.
            let f = value_iteration_f64(&s, &FloatModel::nearest(&s), &opts);
            assert_eq!(f.sweeps, run.sweeps);
        }
    }
}

#[test]
fn exact_reference_rules_give_the_published_sweeps_too() {
    // The exact counterpart (exact geometry, 800/19, exact γ and 10^30) of the reference VI.
    let twin = exact_twin(10, NoiseModel::Reference, &gamma("0.999"))
        .unwrap()
        .unwrap();
    let run = value_iteration_exact(&twin, &ViOptions::reference(Schedule::Asynchronous));
    assert_eq!((run.sweeps, run.reference_counted), (58, 178292));
}

// ---------------------------------------------------------------------------------------------
// Sampling interface for learners.

#[test]
fn sampling_follows_the_exact_probabilities() {
    let s = exact_grid(10, StepCost::Unit, NoiseModel::Reference, &gamma("0.7")).unwrap();
    let x = 41;
    let a = s.actions(x).start;
    let probs: Vec<f64> = s.outcomes(a).iter().map(|o| o.probability_f64()).collect();
    assert_eq!(*s.cumulative(a).last().unwrap(), 1.0);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let draws = 200_000;
    let mut counts = vec![0usize; s.outcomes(a).len()];
    for _ in 0..draws {
        let u: f64 = rng.random();
        let y = s.sample(a, u);
        let i = s.outcomes(a).iter().position(|o| o.successor == y).unwrap();
        counts[i] += 1;
    }
    for (c, p) in counts.iter().zip(&probs) {
        let f = *c as f64 / draws as f64;
        assert!((f - p).abs() < 0.005, "frequency {f} vs probability {p}");
    }
}

trait ProbabilityF64 {
    fn probability_f64(&self) -> f64;
}
impl ProbabilityF64 for Outcome {
    fn probability_f64(&self) -> f64 {
        num_traits::ToPrimitive::to_f64(&self.probability).unwrap()
    }
}

// ---------------------------------------------------------------------------------------------
// Files and bad input.

#[test]
fn stochastic_files_round_trip_and_keep_their_optimum() {
    // A grid has isolated non-goal nodes (no action), which files refuse; give them a self-loop.
    let mut p = GridLayout::exact(16).unwrap();
    for (v, list) in p.neighbours.iter_mut().enumerate() {
        if list.is_empty() && v != p.goal {
            list.push(v);
        }
    }
    let det = p.to_problem(StepCost::Euclidean);
    let s = StochasticProblem::from_deterministic(&det, NoiseModel::Paper, &gamma("0.8")).unwrap();
    let text = file::to_json(&s, Some("problem 16"));
    let back = stochastic_file(&text);
    for a in 0..s.action_total() {
        let o1: Vec<_> = s
            .outcomes(a)
            .iter()
            .map(|o| (o.successor, o.probability.clone()))
            .collect();
        let o2: Vec<_> = back
            .outcomes(a)
            .iter()
            .map(|o| (o.successor, o.probability.clone()))
            .collect();
        assert_eq!(o1, o2);
        assert_eq!(s.cost(a), back.cost(a));
    }
    let (direct, read) = (optimum(&s).unwrap(), optimum(&back).unwrap());
    assert_eq!(direct.cost_to_go_all(), read.cost_to_go_all());
    // Policy iteration starts from the deterministic optimum over each action's intended move:
    // the commanded move when the problem has one (a noise model's), else its most likely
    // outcome (a file lists outcomes only) — here the same move.
    assert_eq!(s.commanded(0), Some(p.neighbours[0][0]));
    assert_eq!(back.commanded(0), None);
    assert_eq!(direct.stats.initial_policy, "deterministic-optimum");
    assert_eq!(read.stats.initial_policy, "deterministic-optimum");
}

#[test]
fn bad_gamma_is_rejected_clearly() {
    for text in ["0", "-0.1", "1.0001", "2", "abc", "", "0.5.1", "1/0"] {
        let e = Predictability::parse(text).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("gamma"), "{text}: {msg}");
        assert_eq!(msg.lines().count(), 1);
    }
    assert!(matches!(
        Predictability::parse("1.5"),
        Err(StochasticError::GammaRange(_))
    ));
    assert!(Predictability::parse("1").unwrap().is_deterministic());
    assert!(Predictability::parse("1e-3").is_ok());
}

/// γ reads back as its exact value, only γ = 1 is the deterministic model, and each noise
/// model's one-line description (in `solve` and `reproduce` reports) names it and its rule.
#[test]
fn predictability_and_noise_models_as_reported() {
    let g = Predictability::parse("0.999").unwrap();
    assert_eq!(g.to_string(), "999/1000");
    assert_eq!(Predictability::parse("1.0").unwrap().to_string(), "1");
    assert!(!g.is_deterministic());
    assert!(!Predictability::parse("1e-3").unwrap().is_deterministic());
    let paper = NoiseModel::Paper.describe();
    let reference = NoiseModel::Reference.describe();
    assert!(paper.starts_with("paper (text: "), "{paper}");
    assert!(
        reference.starts_with("reference (code: stay (1-gamma)/2"),
        "{reference}"
    );
}

#[test]
fn bad_stochastic_files_are_rejected_clearly() {
    let cases = [
        (
            r#"[{"to":1,"p":"0.5"},{"to":0,"p":"0.4"}]"#,
            "sum to 9/10, not 1",
        ),
        (
            r#"[{"to":1,"p":"0.5"},{"to":0,"p":"0.6"}]"#,
            "sum to 11/10, not 1",
        ),
        (r#"[{"to":1,"p":"1"},{"to":0,"p":"0"}]"#, "not in (0, 1]"),
        (
            r#"[{"to":1,"p":"1.5"},{"to":0,"p":"-0.5"}]"#,
            "not in (0, 1]",
        ),
        (r#"[{"to":1,"p":0.5},{"to":0,"p":"0.5"}]"#, "not valid"),
        (r#"[{"to":1,"p":"half"}]"#, "not an exact number"),
        (r#"[{"to":9,"p":"1"}]"#, "does not exist"),
        (r#"[]"#, "no outcomes"),
    ];
    for (outcomes, expect) in cases {
        let text = format!(
            r#"{{"initial":0,"goals":[1],"actions":[[{{"cost":"1","outcomes":{outcomes}}}],[]]}}"#
        );
        let msg = file::from_json(&text).unwrap_err().to_string();
        assert!(msg.contains(expect), "{outcomes}: {msg}");
        assert_eq!(msg.lines().count(), 1);
    }
    let both = r#"{"initial":0,"goals":[1],"actions":[[{"to":1,"cost":"1","outcomes":[{"to":1,"p":"1"}]}],[]]}"#;
    assert!(file::from_json(both)
        .unwrap_err()
        .to_string()
        .contains("exactly one of them"));
    let negative =
        r#"{"initial":0,"goals":[1],"actions":[[{"cost":"-1","outcomes":[{"to":1,"p":"1"}]}],[]]}"#;
    assert!(file::from_json(negative)
        .unwrap_err()
        .to_string()
        .contains("negative"));
    let empty = r#"{"initial":0,"goals":[2],"actions":[[{"cost":"1","outcomes":[{"to":2,"p":"1"}]}],[],[]]}"#;
    assert!(file::from_json(empty)
        .unwrap_err()
        .to_string()
        .contains("empty action set"));
    let tag = r#"{"format":"x/9","initial":0,"goals":[1],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"1"}]}],[]]}"#;
    assert!(file::from_json(tag)
        .unwrap_err()
        .to_string()
        .contains("unsupported format"));
}

#[test]
fn bad_tolerance_is_rejected() {
    assert!(matches!(
        ViOptions::from_below(Schedule::Synchronous, q("-1"), 10),
        Err(StochasticError::Tolerance(_))
    ));
}

#[test]
fn huge_probability_denominators_are_refused_not_wrapped() {
    let p = Problem::new(moves(&[&[1], &[]]), 0, vec![1]).unwrap();
    let g = gamma("0.99999999999999999999"); // 20 decimals: denominator 10^20 > 2^62
    let e = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &g).unwrap_err();
    assert!(e.to_string().contains("exceeds 2^62"), "{e}");
}

#[test]
fn costs_beyond_the_exact_solvers_limits_are_refused_clearly() {
    let text = r#"{"initial":0,"goals":[1],"actions":[[{"cost":"1e40","outcomes":[{"to":1,"p":"1/2"},{"to":0,"p":"1/2"}]}],[]]}"#;
    let s = stochastic_file(text);
    let e = optimum(&s).unwrap_err().to_string();
    assert!(e.contains("exceed 2^100"), "{e}");
    // Just inside the limit the optimum is exact: G = c + G/2 ⇒ G = 2c.
    let text = text.replace("1e40", "1e25");
    let s = stochastic_file(&text);
    assert_eq!(
        optimum(&s).unwrap().cost_to_go(0).to_string(),
        format!("2{}", "0".repeat(25))
    );
}

/// `Optimum::distance` names the lowest-index state among those attaining the largest
/// `|V − G*|` (its documentation), whatever the signs: on `0 → 1 (goal)` at cost 1 with
/// γ = 1/2 (`G*(0) = 2`, `G*(1) = 0`), `V = (7/4, 1/4)` deviates by −1/4 and +1/4, and
/// `V = G*` by 0 and 0: state 0 both times; `V = (2, 1/4)` makes state 1 the worst.
#[test]
fn distance_names_the_lowest_worst_state_on_ties() {
    let p = Problem::new(moves(&[&[1], &[]]), 0, vec![1]).unwrap();
    let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma("0.5")).unwrap();
    let o = optimum(&s).unwrap();
    let at = |v0: &str, v1: &str| {
        let (v0, v1) = (q(v0), q(v1));
        o.distance(0, move |x| {
            Some(if x == 0 { v0.clone() } else { v1.clone() })
        })
    };
    let d = at("1.75", "0.25");
    assert_eq!(
        (d.worst_state, d.max_abs.clone(), d.compared),
        (Some(0), q("0.25"), 2)
    );
    assert_eq!(d.initial, Some(q("-0.25")));
    let d = at("2", "0");
    assert_eq!((d.worst_state, d.max_abs.clone()), (Some(0), q("0")));
    let d = at("2", "0.25");
    assert_eq!((d.worst_state, d.max_abs), (Some(1), q("0.25")));
}

/// `Optimum::distance` counts the states with finite `G*` whose `V` is not finite, apart
/// from the compared ones: on `0 → 1 → 2 (goal)` at cost 1 with γ = 1 (`G* = 2, 1, 0`),
/// `V = (+∞, 1, 0)` compares 2 states (1 and the goal) and counts 1 not finite; the initial
/// state's difference is then unknown.
#[test]
fn distance_counts_the_values_that_are_not_finite() {
    let p = Problem::new(moves(&[&[1], &[2], &[]]), 0, vec![2]).unwrap();
    let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma("1")).unwrap();
    let o = optimum(&s).unwrap();
    let d = o.distance(0, |x| (x > 0).then(|| q(["0", "1", "0"][x])));
    assert_eq!((d.compared, d.not_finite, d.initial), (2, 1, None));
    assert_eq!((d.worst_state, d.max_abs), (Some(1), q("0")));
    let d = o.distance(0, |x| (x != 1).then(|| q(["2", "", "0"][x])));
    assert_eq!((d.compared, d.not_finite, d.initial), (2, 1, Some(q("0"))));
}

/// The reported policy is canonical (module docs of `policy_iteration`): at each state the
/// first action whose exact `Q*` equals `G*`. State 0 has three actions to the goal 1: cost
/// 3 surely (`Q = 3`), cost 2 surely (`Q = 2`), and cost 1 reaching the goal with
/// probability 1/2, else staying (`Q = 1 + Q/2 = 2`). The last two tie; the first of them is
/// reported in either order.
#[test]
fn the_reported_policy_is_the_first_optimal_action() {
    let (three, two) = (
        r#"{"cost":"3","outcomes":[{"to":1,"p":"1"}]}"#,
        r#"{"cost":"2","outcomes":[{"to":1,"p":"1"}]}"#,
    );
    let halves = r#"{"cost":"1","outcomes":[{"to":1,"p":"1/2"},{"to":0,"p":"1/2"}]}"#;
    for (order, first) in [([three, two, halves], 1), ([three, halves, two], 1)] {
        let text = format!(
            r#"{{"initial":0,"goals":[1],"actions":[[{}],[]]}}"#,
            order.join(",")
        );
        let o = optimum(&stochastic_file(&text)).unwrap();
        assert_eq!(o.cost_to_go(0).to_string(), "2", "{text}");
        assert_eq!(o.policy_actions(), [Some(first), None], "{text}");
    }
    // A different first optimal action when the sure one leads: order (2, 3, halves).
    let text = format!(r#"{{"initial":0,"goals":[1],"actions":[[{two},{three},{halves}],[]]}}"#);
    let o = optimum(&stochastic_file(&text)).unwrap();
    assert_eq!(o.policy_actions(), [Some(0), None]);
}

/// Policy iteration's initial policy is the deterministic optimum over the intended moves:
/// where that optimum is not the attractor's choice, it saves the improvement rounds the
/// attractor's policy would need. `0 → goal` costs 10, `0 → 1 → goal` costs 1 + 1; the
/// attractor (reaching a goal in the fewest moves) would take the costly direct move. Fully
/// predictable (γ = 1) and at γ = 0.9 the cheap detour is optimal from the start: no
/// improvement round, from the noise model and from the same problem read back from a file
/// (whose intended moves are the most likely outcomes, the commanded moves).
#[test]
fn the_deterministic_optimum_start_needs_no_improvement_from_either_source() {
    let p = Problem::new(
        weighted(&[&[(2, "10"), (1, "1")], &[(2, "1")], &[]]),
        0,
        vec![2],
    )
    .unwrap();
    for g in ["1", "0.9"] {
        let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma(g)).unwrap();
        let o = optimum(&s).unwrap();
        assert_eq!(o.stats.initial_policy, "deterministic-optimum");
        assert_eq!(o.stats.float_iterations, 0, "gamma {g}");
        let back = stochastic_file(&file::to_json(&s, None));
        let r = optimum(&back).unwrap();
        assert_eq!(r.stats.initial_policy, "deterministic-optimum");
        assert_eq!(r.stats.float_iterations, 0, "gamma {g}");
        assert_eq!(o.cost_to_go_all(), r.cost_to_go_all());
        // Value iteration's greedy policies (exact, and f64 on the nearest f64 model) take
        // the cheap detour too: the first minimising action; the goal terminates.
        use truecost::model::Decision;
        let options = ViOptions::from_below(Schedule::Synchronous, q("1/1000"), 10_000).unwrap();
        let greedy = [
            Some(Decision::Move(1)),
            Some(Decision::Move(0)),
            Some(Decision::Terminate),
        ];
        let exact = value_iteration_exact(&s, &options);
        assert!(exact.converged);
        assert_eq!(exact.policy, greedy, "gamma {g}");
        let float = value_iteration_f64(&s, &FloatModel::nearest(&s), &options);
        assert!(float.converged);
        assert_eq!(float.policy, greedy, "gamma {g}");
    }
}

/// The `f64` warm start does the improving, so that the exact phase evaluates once: read
/// from a file (outcomes only), `0 → goal` at cost 5 against a detour at cost 1 that stays
/// at 0 or moves to 1 with probability 1/2 each (its intended move, the first of the equally
/// likely outcomes, is the self-loop), and `1 → goal` at cost 0. The deterministic optimum
/// over the intended moves takes the direct move (`G = 5`); the warm start's first round sees
/// `Q(detour) = 1 + G(0)/2 + G(1)/2 = 7/2 < 5` and switches, its second changes nothing
/// (the detour's value `G = 1 + G/2` is 2), and one exact evaluation confirms `G*(0) = 2`.
#[test]
fn the_warm_start_finds_the_improvement_before_the_exact_phase() {
    let text = r#"{"initial":0,"goals":[2],"actions":[
        [{"cost":"5","outcomes":[{"to":2,"p":"1"}]},{"cost":"1","outcomes":[{"to":0,"p":"1/2"},{"to":1,"p":"1/2"}]}],
        [{"cost":"0","outcomes":[{"to":2,"p":"1"}]}],
        []]}"#;
    let o = optimum(&stochastic_file(text)).unwrap();
    assert_eq!(o.stats.initial_policy, "deterministic-optimum");
    assert_eq!((o.stats.float_iterations, o.stats.exact_iterations), (1, 1));
    assert_eq!(strings(o.cost_to_go_all()), ["2", "0", "0"]);
    assert_eq!(o.policy_actions(), [Some(1), Some(2), None]);
}

/// The warm start switches only on an improvement larger than 10⁻⁹ of the value (module
/// docs of `policy_iteration`): against a direct move at cost 10⁶, a detour whose intended
/// move is a self-loop (it stays at 0 or moves to 2 with probability 1/2 each; `2 → goal`
/// costs 0), so that the deterministic optimum over intended moves starts from the direct
/// move. The detour's value is twice its cost: cost 499999.999995 gives 999999.99999, cheaper
/// by 10⁻⁵ (relatively 10⁻¹¹), left to the mixed-precision stage, which certifies it and
/// switches (one round), so one exact evaluation confirms; cost 499999.5 gives 999999, cheaper
/// by 1 (relatively 10⁻⁶), and the warm start takes it.
#[test]
fn the_warm_start_ignores_improvements_below_its_relative_margin() {
    for (cost, detour, float, refined, exact) in [
        ("499999.999995", "999999.99999", 0, 1, 1),
        ("499999.5", "999999", 1, 0, 1),
    ] {
        let text = format!(
            r#"{{"initial":0,"goals":[1],"actions":[
            [{{"cost":"1000000","outcomes":[{{"to":1,"p":"1"}}]}},{{"cost":"{cost}","outcomes":[{{"to":0,"p":"1/2"}},{{"to":2,"p":"1/2"}}]}}],
            [],
            [{{"cost":"0","outcomes":[{{"to":1,"p":"1"}}]}}]]}}"#
        );
        let o = optimum(&stochastic_file(&text)).unwrap();
        assert_eq!(o.stats.initial_policy, "deterministic-optimum");
        assert_eq!(
            (
                o.stats.float_iterations,
                o.stats.refinement_rounds,
                o.stats.exact_iterations
            ),
            (float, refined, exact),
            "{detour}"
        );
        assert_eq!(o.cost_to_go(0), Extended::Finite(q(detour)));
        assert_eq!(o.policy_actions()[0], Some(1));
    }
}

/// Exact value iteration by hand on `0 → 1 (goal)` at cost 1 with γ = 1/2 (`G = 1 + G/2`:
/// 1, 3/2, 7/4, 15/8, …, changes 1, 1/2, 1/4, 1/8), plus a state 2 with only a self-loop
/// (`G* = +∞`). The stopping test `max change ≤ tolerance` is exact: with tolerance 3/8 the
/// run stops after sweep 3 (change 1/4), with 1/4 also after sweep 3 (equality stops), with
/// 1/5 after sweep 4; the reported last change is that sweep's change exactly. Only the
/// finite non-goal states are swept: one backup a sweep, and state 2 stays `+∞`.
#[test]
fn exact_value_iteration_stops_by_its_tolerance_exactly() {
    let p = Problem::new(moves(&[&[1], &[], &[2]]), 0, vec![1]).unwrap();
    let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &gamma("0.5")).unwrap();
    for (tol, sweeps, value, change) in [
        ("3/8", 3, "7/4", "1/4"),
        ("1/4", 3, "7/4", "1/4"),
        ("1/5", 4, "15/8", "1/8"),
        ("1/8", 4, "15/8", "1/8"),
    ] {
        let o = ViOptions::from_below(Schedule::Synchronous, q(tol), 100).unwrap();
        let r = value_iteration_exact(&s, &o);
        assert!(r.converged, "tolerance {tol}");
        assert_eq!(r.sweeps, sweeps, "tolerance {tol}");
        assert_eq!(
            r.cost_to_go[0],
            Extended::Finite(q(value)),
            "tolerance {tol}"
        );
        assert_eq!(
            r.last_change,
            Extended::Finite(q(change)),
            "tolerance {tol}"
        );
        assert_eq!(r.cost_to_go[2], Extended::Infinite);
        assert_eq!(r.backups, sweeps, "tolerance {tol}");
    }
    // A goal with an action (files allow it) is not swept either: `0 → 1 (goal)` at cost 1
    // with probability 1/2 (else stay), and the goal's move back to 0. G(0) = 1 + G(0)/2 as
    // above; one backup a sweep, the goal stays 0.
    let text = r#"{"initial": 0, "goals": [1], "actions": [
        [ { "cost": "1", "outcomes": [ { "to": 1, "p": "1/2" }, { "to": 0, "p": "1/2" } ] } ],
        [ { "to": 0, "cost": "1" } ] ]}"#;
    let s = stochastic_file(text);
    let o = ViOptions::from_below(Schedule::Synchronous, q("1/4"), 100).unwrap();
    let r = value_iteration_exact(&s, &o);
    assert_eq!((r.sweeps, r.backups), (3, 3));
    assert_eq!(
        r.cost_to_go,
        [Extended::Finite(q("7/4")), Extended::Finite(q("0"))]
    );
    // The f64 run sweeps the same states: one backup a sweep, 7/4 exactly in binary.
    let r = value_iteration_f64(&s, &FloatModel::nearest(&s), &o);
    assert_eq!((r.sweeps, r.backups, r.cost_to_go), (3, 3, vec![1.75, 0.0]));
}

/// Exact value iteration from a constant: `0 → 1 → 2 (goal)` at cost 1/2 a move (so values
/// are kept over the cost denominator 2), every state starting at 10, one synchronous sweep
/// with assignment: `G₁(0) = 1/2 + 10`, `G₁(1) = 1/2 + 0`, the largest change `10 − 1/2`.
#[test]
fn exact_value_iteration_starts_from_the_given_constant() {
    use truecost::stochastic::value_iteration::{Initial, SweepSet, UpdateRule};
    let text = r#"{"initial": 0, "goals": [2], "actions": [
        [ { "cost": "1/2", "outcomes": [ { "to": 1, "p": "1" } ] } ],
        [ { "cost": "1/2", "outcomes": [ { "to": 2, "p": "1" } ] } ], [] ]}"#;
    let s = stochastic_file(text);
    let o = ViOptions {
        schedule: Schedule::Synchronous,
        initial: Initial::Constant(BigInt::from(10)),
        rule: UpdateRule::Assign,
        sweep: SweepSet::All,
        tolerance: q("0"),
        max_sweeps: 1,
    };
    let r = value_iteration_exact(&s, &o);
    assert_eq!((r.sweeps, r.converged), (1, false));
    assert_eq!(strings(&r.cost_to_go), ["21/2", "1/2", "0"]);
    assert_eq!(r.last_change, Extended::Finite(q("19/2")));
}

/// Both value iterations' greedy policies take the first of tied minimising actions (their
/// documentation): state 0's actions to the goal cost 3, 1 and 1.
#[test]
fn value_iteration_s_greedy_policy_takes_the_first_of_tied_actions() {
    use truecost::model::Decision;
    let text = r#"{"initial": 0, "goals": [1], "actions": [
        [ { "cost": "3", "outcomes": [ { "to": 1, "p": "1" } ] },
          { "cost": "1", "outcomes": [ { "to": 1, "p": "1" } ] },
          { "cost": "1", "outcomes": [ { "to": 1, "p": "1" } ] } ], [] ]}"#;
    let s = stochastic_file(text);
    let o = ViOptions::from_below(Schedule::Synchronous, q("0"), 10).unwrap();
    let greedy = [Some(Decision::Move(1)), Some(Decision::Terminate)];
    let exact = value_iteration_exact(&s, &o);
    assert!(exact.converged);
    assert_eq!(exact.policy, greedy);
    let float = value_iteration_f64(&s, &FloatModel::nearest(&s), &o);
    assert!(float.converged);
    assert_eq!(float.policy, greedy);
}

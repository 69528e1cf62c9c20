//! Stochastic Q-learning (`learning::stochastic_q`) and its runner (`experiments::stochastic`):
//! invariants against independent oracles — the deterministic engine (γ = 1, ρ = 1), the exact
//! probabilities (binomial bounds), exact directed rounding, the published reference VI counts,
//! thread-count independence, and one-line refusals of bad input.

mod common;
use common::stochastic_file;

use num_traits::ToPrimitive;
use proptest::prelude::*;
use rand::RngExt;
use truecost::experiments::stochastic::{self, EpsilonSpec, RateSpec, Settings};
use truecost::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
use truecost::learning::q_learning::{QLearner, QLearningConfig};
use truecost::learning::stochastic_q::{
    f64_at_least, f64_at_most, outcome_index, LearningRate, RateError, StochasticQConfig,
    StochasticQLearner, Target, Tolerance,
};
use truecost::model::Graph;
use truecost::problems::{GridLayout, StepCost};
use truecost::stochastic::grid::exact_grid;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::{parse_rational, Extended, Rational};

fn gamma(t: &str) -> Predictability {
    Predictability::parse(t).unwrap()
}

/// With γ = 1 every action has one outcome and no uniform draw is made, so with ρ = 1 the
/// stochastic learner must reproduce the deterministic engine bit for bit: same generator
/// consumption, same Q̂, same counts.
#[test]
fn gamma_one_rho_one_equals_the_deterministic_engine() {
    for id in [16, 3] {
        let problem = GridLayout::exact(id).unwrap().to_problem(StepCost::Unit);
        let n = problem.states();
        let adjacency: Vec<Vec<(usize, f64)>> = (0..n)
            .map(|x| {
                problem
                    .moves(x)
                    .iter()
                    .map(|m| (m.successor, 1.0))
                    .collect()
            })
            .collect();
        let graph = Graph::from_adjacency(
            adjacency,
            problem.initial(),
            problem.goals(),
            (0..n).collect(),
            Rational::from_integer(1.into()),
        );
        let stochastic = StochasticProblem::from_deterministic(
            &problem,
            NoiseModel::Paper,
            &Predictability::one(),
        )
        .unwrap();
        assert!((0..stochastic.action_total()).all(|a| stochastic.outcomes(a).len() == 1));
        // Targets nobody reaches, so that neither engine stops early.
        let never = vec![-1.0; n];
        let far = vec![Extended::Finite(parse_rational("1000000").unwrap()); n];
        let target = Target::from_values(&stochastic, &far, Tolerance::Relative);
        for eps in ["0", "0.5", "1"] {
            let epsilon = EpsilonSchedule::Constant(
                Probability::new("ε", &parse_rational(eps).unwrap()).unwrap(),
            );
            let det_config = QLearningConfig {
                episodes: 40,
                max_steps: 300,
                ..QLearningConfig::paper(epsilon.clone())
            };
            let mut det = QLearner::new(
                &graph,
                &never,
                0.0,
                &det_config,
                sample_rng(5, 9),
                Plan::Random,
            )
            .unwrap();
            let det_outcome = det.run();
            let config = StochasticQConfig {
                episodes: 40,
                max_steps: 300,
                rate: LearningRate::Constant(1.0),
                epsilon,
                initial_value: 0.0,
            };
            let costs = vec![1.0; stochastic.action_total()];
            let mut learner = StochasticQLearner::new(
                &stochastic,
                &costs,
                &target,
                &config,
                sample_rng(5, 9),
                Plan::Random,
            )
            .unwrap();
            let outcome = learner.run();
            assert!(!det_outcome.converged && !outcome.converged);
            assert_eq!(
                outcome.actions, det_outcome.actions,
                "problem {id}, ε {eps}"
            );
            assert_eq!(outcome.goal_discovered_at, det_outcome.goal_discovered_at);
            for x in 0..n {
                if problem.goals().contains(&x) {
                    continue;
                }
                let d = &det.q_values()[det.actions_of(x)];
                let s = &learner.q_values()[stochastic.actions(x)];
                assert_eq!(d, s, "problem {id}, ε {eps}, state {x}");
            }
        }
    }
}

/// The learner's sampler and `StochasticProblem::sample` agree on every draw, and the drawn
/// frequencies match the exact probabilities within 5 binomial standard deviations.
#[test]
fn sampled_frequencies_match_the_exact_probabilities() {
    for (noise, g) in [(NoiseModel::Paper, "0.7"), (NoiseModel::Reference, "0.9")] {
        let p = exact_grid(10, StepCost::Unit, noise, &gamma(g)).unwrap();
        // A state with four actions (five outcomes per action).
        let x = (0..p.states()).find(|&x| p.actions(x).len() == 4).unwrap();
        let a = p.actions(x).start + 2;
        let outcomes = p.outcomes(a);
        let mut counts = vec![0u64; outcomes.len()];
        let mut rng = sample_rng(11, 3);
        let draws = 200_000u64;
        for _ in 0..draws {
            let u: f64 = rng.random();
            let i = outcome_index(p.cumulative(a), u);
            assert_eq!(outcomes[i].successor, p.sample(a, u));
            counts[i] += 1;
        }
        for (o, &c) in outcomes.iter().zip(&counts) {
            let q = o.probability.to_f64().unwrap();
            let mean = draws as f64 * q;
            let sd = (draws as f64 * q * (1.0 - q)).sqrt();
            assert!(
                (c as f64 - mean).abs() <= 5.0 * sd,
                "{noise:?}: outcome {:?} drawn {c} times, expected {mean} ± {sd}",
                o.kind
            );
        }
    }
}

proptest! {
    /// Directed rounding is exact: the result bounds r and its neighbour does not.
    #[test]
    fn directed_rounding_brackets_the_rational(n in -10_000_000i64..10_000_000, d in 1i64..100_000_000) {
        let r = Rational::new(n.into(), d.into());
        let up = f64_at_least(&r);
        let down = f64_at_most(&r);
        prop_assert!(Rational::from_float(up).unwrap() >= r);
        prop_assert!(Rational::from_float(down).unwrap() <= r);
        prop_assert!(down <= up);
        // No f64 strictly between them other than r itself: up and down are adjacent or equal.
        if up != down {
            prop_assert!(Rational::from_float(up).unwrap() > r && Rational::from_float(down).unwrap() < r);
            let mid = f64::from_bits(if down >= 0.0 { down.to_bits() + 1 } else { down.to_bits() - 1 });
            prop_assert_eq!(mid, up);
        }
    }
}

/// The target's interval test is the exact comparison with G*·(1 ± 1/10).
#[test]
fn target_interval_is_exact_at_its_ends() {
    let p = exact_grid(16, StepCost::Unit, NoiseModel::Paper, &gamma("0.9")).unwrap();
    let g: Vec<Extended> = (0..p.states())
        .map(|_| Extended::Finite(parse_rational("10/3").unwrap()))
        .collect();
    let t = Target::from_values(&p, &g, Tolerance::Relative);
    let x = (0..p.states()).find(|&x| t.is_tracked(x)).unwrap();
    // 10/3 · 0.9 = 3 and 10/3 · 1.1 = 11/3 (not an f64).
    assert!(t.within(x, 3.0));
    assert!(!t.within(x, f64::from_bits(3.0f64.to_bits() - 1)));
    let hi = 11.0 / 3.0; // the nearest f64 of 11/3
    let exact_hi = parse_rational("11/3").unwrap();
    assert_eq!(
        t.within(x, hi),
        Rational::from_float(hi).unwrap() <= exact_hi
    );
    let r = Target::from_values(&p, &g, Tolerance::Reference);
    assert!(r.within(x, 8.0) && !r.within(x, 8.4) && r.within(x, -1.6) && !r.within(x, -1.7));
}

/// `outcome_index` selects the first outcome whose cumulative threshold exceeds `u`, and the
/// last one when none does (`u` at or above the last threshold): never an index past the end.
#[test]
fn outcome_index_stays_within_the_outcomes() {
    for (cumulative, u, expected) in [
        (&[1.0][..], 0.0, 0),
        (&[1.0][..], 1.0, 0),
        (&[0.5, 1.0][..], 0.25, 0),
        (&[0.5, 1.0][..], 0.5, 1),
        (&[0.5, 1.0][..], 1.0, 1),
        (&[0.5, 1.0][..], 7.0, 1),
        (&[0.25, 0.5, 0.75][..], 0.75, 2),
        (&[0.25, 0.5, 0.75][..], 0.9, 2),
    ] {
        assert_eq!(
            outcome_index(cumulative, u),
            expected,
            "{cumulative:?} at {u}"
        );
    }
}

/// Directed rounding at the ends of the `f64` range: the largest finite `f64` is its own
/// rounding in both directions (a first step up would leave the range), and a value above it
/// rounds up to `+∞`.
#[test]
fn directed_rounding_at_the_largest_finite_f64() {
    let max = Rational::from_float(f64::MAX).unwrap();
    assert_eq!(f64_at_least(&max), f64::MAX);
    assert_eq!(f64_at_most(&max), f64::MAX);
    assert_eq!(f64_at_least(&-max.clone()), -f64::MAX);
    assert_eq!(f64_at_most(&-max.clone()), -f64::MAX);
    let above = &max * Rational::from_integer(2.into());
    assert_eq!(f64_at_least(&above), f64::INFINITY);
    assert_eq!(f64_at_most(&above), f64::MAX);
}

/// The states a target tracks are those reachable from `x1`, not goals, with an action and a
/// finite `G*` — checked state by state on a hand-made file: 0 (initial) reaches 1 (goal) and 3;
/// 2 has an action but nothing reaches it; 4 is reachable but has no finite value.
#[test]
fn a_target_tracks_reachable_non_goal_states_with_actions() {
    let text = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [1], "actions": [
        [{"cost": "1", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 3, "p": "1/4"}, {"to": 4, "p": "1/4"}]}],
        [],
        [{"cost": "1", "outcomes": [{"to": 1, "p": "1"}]}],
        [{"cost": "1", "outcomes": [{"to": 1, "p": "1"}]}],
        [{"cost": "1", "outcomes": [{"to": 4, "p": "1"}]}]]}"#;
    let p = stochastic_file(text);
    let one = Extended::Finite(Rational::from_integer(1.into()));
    let g = vec![
        one.clone(),
        Extended::Finite(Rational::from_integer(0.into())),
        one.clone(),
        one,
        Extended::Infinite,
    ];
    for tolerance in [Tolerance::Relative, Tolerance::Reference] {
        let t = Target::from_values(&p, &g, tolerance);
        let tracked: Vec<bool> = (0..5).map(|x| t.is_tracked(x)).collect();
        assert_eq!(tracked, [true, false, false, true, false]);
        assert_eq!(t.tracked_count(), 2);
        assert_eq!(t.tolerance(), tolerance);
        // Where G* = +∞ nothing is within tolerance, not even +∞.
        assert!(!t.within(4, f64::INFINITY) && !t.within(4, 1.0));
    }
}

/// Learning rates are checked on their exact value first (the error names the exact range),
/// then on the `f64` the learner uses (the error says it rounds out of range); the ends of
/// both ranges one by one.
#[test]
fn learning_rates_are_checked_exactly_then_in_f64() {
    let q = |t: &str| parse_rational(t).unwrap();
    let just_above_one = "1.000000000000000000000000000001"; // rounds to 1.0
    assert_eq!(
        LearningRate::constant(&q("1")),
        Ok(LearningRate::Constant(1.0))
    );
    assert_eq!(
        LearningRate::constant(&q("1/4")),
        Ok(LearningRate::Constant(0.25))
    );
    for refused in ["0", "-1", "2", just_above_one] {
        assert!(
            matches!(LearningRate::constant(&q(refused)), Err(RateError::Rho(_))),
            "rho = {refused}"
        );
    }
    assert!(matches!(
        LearningRate::constant(&q("1e-400")),
        Err(RateError::Rounded { .. })
    ));
    assert_eq!(LearningRate::decay(&q("1")), Ok(LearningRate::Decay(1.0)));
    assert_eq!(
        LearningRate::decay(&q("3/4")),
        Ok(LearningRate::Decay(0.75))
    );
    for refused in ["1/2", "0", "2", just_above_one] {
        assert!(
            matches!(LearningRate::decay(&q(refused)), Err(RateError::Omega(_))),
            "omega = {refused}"
        );
    }
    assert!(matches!(
        LearningRate::decay(&q("0.50000000000000001")),
        Err(RateError::Rounded { .. })
    ));
}

fn small(threads: Option<usize>, seed: u64) -> Settings {
    Settings {
        problems: vec![16, 3],
        gammas: vec![gamma("0.9")],
        rhos: vec![
            RateSpec::parse("0.5").unwrap(),
            RateSpec::parse("1/n^0.8").unwrap(),
        ],
        epsilons: vec![EpsilonSpec::parse("0.9").unwrap()],
        samples: 3,
        seed,
        episodes: 60,
        max_steps: 500,
        threads,
        ..Settings::default()
    }
}

fn without_times(report: &stochastic::Report) -> Vec<serde_json::Value> {
    report
        .rows
        .iter()
        .map(|r| {
            let mut v = serde_json::to_value(r).unwrap();
            v.as_object_mut()
                .unwrap()
                .retain(|k, _| !k.ends_with("_s") && k != "mean_ns_per_action");
            v
        })
        .collect()
}

#[test]
fn same_rows_with_one_or_two_threads_and_the_seed_matters() {
    let one = stochastic::run(&small(Some(1), 7), &|_| {}).unwrap();
    let two = stochastic::run(&small(Some(2), 7), &|_| {}).unwrap();
    assert_eq!(without_times(&one), without_times(&two));
    let other = stochastic::run(&small(Some(2), 8), &|_| {}).unwrap();
    assert_ne!(without_times(&one), without_times(&other));
    // Rows: per problem and γ, 2 learning rows then the two VIs; every row names its model.
    let names: Vec<&str> = one.rows.iter().map(|r| r.algorithm).collect();
    assert_eq!(
        names,
        [
            "q-learning",
            "q-learning",
            "stochastic-async-vi",
            "stochastic-vi"
        ]
        .repeat(2)
    );
    assert!(one.rows.iter().all(|r| r.noise == NoiseModel::Paper
        && r.tolerance == Tolerance::Relative
        && r.seed == 7));
}

/// The VI rows under the reference tolerance run the reference code's grid and reproduce its
/// published counts (reference/problem10.md): γ = 0.999, reference noise: asynchronous 58 sweeps
/// / 178292 counted actions, synchronous 94 / 288956.
#[test]
fn reference_vi_rows_reproduce_the_published_counts_of_problem_10() {
    let settings = Settings {
        problems: vec![10],
        gammas: vec![gamma("0.999")],
        rhos: vec![RateSpec::parse("0.99").unwrap()],
        epsilons: vec![EpsilonSpec::parse("0.9").unwrap()],
        samples: 1,
        episodes: 1,
        max_steps: 10,
        noise: NoiseModel::Reference,
        tolerance: Tolerance::Reference,
        ..Settings::default()
    };
    let report = stochastic::run(&settings, &|_| {}).unwrap();
    let vi: Vec<(f64, f64)> = report.rows[1..]
        .iter()
        .map(|r| (r.mean_iterations.unwrap(), r.mean_actions.unwrap()))
        .collect();
    assert_eq!(vi, vec![(58.0, 178292.0), (94.0, 288956.0)]);
    // The stopped values are within ±5 of the exact optimum everywhere.
    assert!(report.rows[1..]
        .iter()
        .all(|r| r.convergence_rate == Some(1.0)));
}

#[test]
fn bad_parameters_are_refused_in_one_line() {
    let errors = [
        RateSpec::parse("0").unwrap_err().to_string(),
        RateSpec::parse("1.01").unwrap_err().to_string(),
        RateSpec::parse("1/n^0.5").unwrap_err().to_string(),
        RateSpec::parse("1/n^1.5").unwrap_err().to_string(),
        RateSpec::parse("fast").unwrap_err().to_string(),
        EpsilonSpec::parse("-0.1").unwrap_err().to_string(),
        EpsilonSpec::parse("1.5").unwrap_err().to_string(),
        Predictability::parse("0").unwrap_err().to_string(),
        Predictability::parse("1.2").unwrap_err().to_string(),
        stochastic::run(
            &Settings {
                samples: 0,
                ..small(None, 0)
            },
            &|_| {},
        )
        .unwrap_err()
        .to_string(),
        stochastic::run(
            &Settings {
                problems: vec![99],
                ..small(None, 0)
            },
            &|_| {},
        )
        .unwrap_err()
        .to_string(),
        stochastic::run(
            &Settings {
                episodes: 0,
                ..small(None, 0)
            },
            &|_| {},
        )
        .unwrap_err()
        .to_string(),
    ];
    for e in &errors {
        assert!(!e.is_empty() && !e.contains('\n'), "{e:?}");
    }
    assert!(
        errors[2].contains("omega") && errors[0].contains("rho"),
        "{errors:?}"
    );
    // The learner itself refuses out-of-range rates given directly.
    let p = exact_grid(16, StepCost::Unit, NoiseModel::Paper, &gamma("0.9")).unwrap();
    let t = Target::from_values(
        &p,
        &vec![Extended::Infinite; p.states()],
        Tolerance::Relative,
    );
    for rate in [
        LearningRate::Constant(0.0),
        LearningRate::Constant(1.5),
        LearningRate::Decay(0.5),
    ] {
        let config = StochasticQConfig {
            episodes: 1,
            max_steps: 1,
            rate,
            epsilon: EpsilonSchedule::Constant(Probability::ONE),
            initial_value: 0.0,
        };
        let costs = vec![1.0; p.action_total()];
        assert!(
            StochasticQLearner::new(&p, &costs, &t, &config, sample_rng(0, 0), Plan::Random)
                .is_err()
        );
    }
}

/// On a tiny chain the decaying rate learns G* within 10% and the greedy policy is optimal;
/// G* is derived by hand: 0 → 1 → 2 (goal), γ = 0.9 paper noise. State 1 (two moves, to 0 and
/// to 2): commanded 0.9, other 0.05, stay 0.05. State 0 (one move to 1): 0.9 to 1, 0.1 stay.
#[test]
fn decaying_rate_learns_a_hand_solved_chain() {
    use truecost::model::{Move, Problem};
    let one = parse_rational("1").unwrap();
    let problem = Problem::new(
        vec![
            vec![Move {
                successor: 1,
                cost: one.clone(),
            }],
            vec![
                Move {
                    successor: 0,
                    cost: one.clone(),
                },
                Move {
                    successor: 2,
                    cost: one,
                },
            ],
            vec![],
        ],
        0,
        vec![2],
    )
    .unwrap();
    let s =
        StochasticProblem::from_deterministic(&problem, NoiseModel::Paper, &gamma("0.9")).unwrap();
    // By hand: G0 = (1 + 0.9 G1)/0.9 and G1 = 1 + 0.05 G0 + 0.05 G1
    // → 0.95 G1 = 1 + (1 + 0.9 G1)/18 → (0.95 − 0.05) G1 = 1 + 1/18 → G1 = 19/16.2 = 95/81,
    //   G0 = 10/9 + 95/81 = 185/81.
    let g = vec![
        Extended::Finite(parse_rational("185/81").unwrap()),
        Extended::Finite(parse_rational("95/81").unwrap()),
        Extended::Finite(parse_rational("0").unwrap()),
    ];
    let exact = truecost::stochastic::policy_iteration::optimum(&s).unwrap();
    assert_eq!(exact.cost_to_go_all(), &g[..]);
    let target = Target::from_values(&s, &g, Tolerance::Relative);
    let config = StochasticQConfig {
        episodes: 3000,
        max_steps: 50,
        rate: LearningRate::Decay(0.8),
        epsilon: EpsilonSchedule::Constant(
            Probability::new("ε", &parse_rational("0.5").unwrap()).unwrap(),
        ),
        initial_value: 0.0,
    };
    let costs = vec![1.0; s.action_total()];
    let mut learner =
        StochasticQLearner::new(&s, &costs, &target, &config, sample_rng(3, 1), Plan::Random)
            .unwrap();
    let outcome = learner.run();
    assert!(outcome.converged);
    let v = learner.cost_to_go();
    assert!(target.within(0, v[0]) && target.within(1, v[1]), "{v:?}");
    let flags = truecost::learning::stochastic_q::optimal_action_flags(&s, &exact);
    let sim = learner.simulate_greedy(Some(&flags));
    assert!(sim.reached_goal && sim.optimal_actions && sim.states >= 3);
}

/// The chain 0 → 1 → 2 (goal) with unit costs, one outcome per action (γ = 1), and its
/// target `G* = (2, 1, 0)` within 10 %.
fn unit_chain() -> (StochasticProblem, Target) {
    use truecost::model::{Move, Problem};
    let one = parse_rational("1").unwrap();
    let step = |to| {
        vec![Move {
            successor: to,
            cost: one.clone(),
        }]
    };
    let problem = Problem::new(vec![step(1), step(2), vec![]], 0, vec![2]).unwrap();
    let s =
        StochasticProblem::from_deterministic(&problem, NoiseModel::Paper, &Predictability::one())
            .unwrap();
    let g = ["2", "1", "0"].map(|t| Extended::Finite(parse_rational(t).unwrap()));
    let target = Target::from_values(&s, &g, Tolerance::Relative);
    (s, target)
}

/// `ρ = 1/n^ω` with `ω = 1` (the rate's own branch, `1/n`): `Q̂` is the running mean of the
/// targets. On the chain 0 → 1 → 2 (goal), one outcome per action (γ = 1), greedy, `Q₀ = 0`,
/// by hand: episode 1 sets `Q̂(0) = 1 + V(1) = 1` and `Q̂(1) = 1`; episode 2 sees the target
/// `1 + V(1) = 2` at state 0 on its second visit, so `Q̂(0) = (1 − 1/2)·1 + (1/2)·2 = 3/2`
/// (`ω = 0.8` gives the blend with `ρ = 2^−0.8` instead), and `Q̂(1)` stays 1.
#[test]
fn a_rate_of_one_over_n_averages_the_targets() {
    let (s, target) = unit_chain();
    let rho = 2f64.powf(-0.8);
    for (omega, expected) in [(1.0, 1.5), (0.8, (1.0 - rho) * 1.0 + rho * 2.0)] {
        let config = StochasticQConfig {
            episodes: 2,
            max_steps: 10,
            rate: LearningRate::Decay(omega),
            epsilon: EpsilonSchedule::Constant(Probability::ZERO),
            initial_value: 0.0,
        };
        let costs = vec![1.0; s.action_total()];
        let mut learner =
            StochasticQLearner::new(&s, &costs, &target, &config, sample_rng(0, 0), Plan::Random)
                .unwrap();
        let outcome = learner.run();
        assert!(!outcome.converged, "V(0) = 3/2 is not within 10 % of 2");
        assert_eq!(learner.q_values(), [expected, 1.0], "omega = {omega}");
        assert_eq!(learner.cost_to_go()[..2], [expected, 1.0]);
    }
}

/// Each milestone is reported by `advance` at the action that reached it, worked out by hand on
/// the chain 0 → 1 → 2 (goal), γ = 1, ρ = 1, greedy, `Q₀ = 0`, `G* = (2, 1, 0)`: action 2
/// enters the goal (and makes `V(1) = 1` exact); action 3, the first of episode 2, makes
/// `V(0) = 1 + V(1) = 2`, which is `G*(x1)` and completes the tracked states at once; the run
/// then finishes that episode (action 4).
#[test]
fn milestones_are_reported_at_the_action_that_reached_them() {
    use truecost::learning::q_learning::{Event, Milestone};
    let (s, target) = unit_chain();
    let config = StochasticQConfig {
        episodes: 10,
        max_steps: 10,
        rate: LearningRate::Constant(1.0),
        epsilon: EpsilonSchedule::Constant(Probability::ZERO),
        initial_value: 0.0,
    };
    let costs = vec![1.0; s.action_total()];
    let mut learner =
        StochasticQLearner::new(&s, &costs, &target, &config, sample_rng(0, 0), Plan::Random)
            .unwrap();
    let mut events = Vec::new();
    loop {
        let event = learner.advance();
        events.push((event, learner.outcome().actions));
        if event == Event::Finished {
            break;
        }
    }
    assert_eq!(
        events,
        [
            (Event::Milestone(Milestone::GoalDiscovered), 2),
            (Event::Milestone(Milestone::InitialOptimal), 3),
            (Event::Milestone(Milestone::Converged), 3),
            (Event::Finished, 4),
        ]
    );
    let outcome = learner.outcome();
    assert_eq!(
        (
            outcome.goal_discovered_at,
            outcome.initial_within_at,
            outcome.converged_at
        ),
        (Some(2), Some(3), Some(3))
    );
    assert_eq!(
        (outcome.initial_within_episode, outcome.episodes_run),
        (Some(2), 2)
    );
    assert!(outcome.converged);
}

/// The greedy simulation draws a uniform number for an action with several outcomes and none
/// for an action with one (as learning does): replayed by the test with its own generator and
/// `StochasticProblem::sample` on a loop 0 → {1, 0}, 1 → 2 (one outcome), 2 → {3 (goal), 0},
/// from a learner that has not run (`Q̂ = Q₀`, so the greedy action is each state's only one).
#[test]
fn the_greedy_simulation_draws_only_for_random_outcomes() {
    let text = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [3], "actions": [
        [{"cost": "1", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 0, "p": "1/2"}]}],
        [{"cost": "1", "outcomes": [{"to": 2, "p": "1"}]}],
        [{"cost": "1", "outcomes": [{"to": 3, "p": "1/2"}, {"to": 0, "p": "1/2"}]}],
        []]}"#;
    let p = stochastic_file(text);
    let g = ["4", "3", "2", "0"].map(|t| Extended::Finite(parse_rational(t).unwrap()));
    let target = Target::from_values(&p, &g, Tolerance::Relative);
    let config = StochasticQConfig {
        episodes: 1,
        max_steps: 1,
        rate: LearningRate::Constant(1.0),
        epsilon: EpsilonSchedule::Constant(Probability::ZERO),
        initial_value: 0.0,
    };
    let costs = vec![1.0; p.action_total()];
    let mut lengths = Vec::new();
    for seed in 0..16 {
        let mut learner = StochasticQLearner::new(
            &p,
            &costs,
            &target,
            &config,
            sample_rng(seed, 0),
            Plan::Random,
        )
        .unwrap();
        let sim = learner.simulate_greedy(None);
        let mut rng = sample_rng(seed, 0);
        let (mut x, mut states) = (0, 1u64);
        while x != 3 {
            let a = p.actions(x).start;
            x = if p.outcomes(a).len() == 1 {
                p.outcomes(a)[0].successor
            } else {
                p.sample(a, rng.random())
            };
            states += 1;
        }
        assert!(sim.reached_goal && !sim.optimal_actions);
        assert_eq!(sim.states, states, "seed {seed}");
        lengths.push(states);
    }
    // The replay is not trivial: the walks differ in length.
    lengths.sort();
    lengths.dedup();
    assert!(lengths.len() >= 3, "{lengths:?}");
}

/// Problem 6 has no path: the learning rows are not run, the VI rows say why, nothing claims
/// convergence; the progress callback counts exactly `total_runs` runs.
#[test]
fn unreachable_goal_is_reported_and_progress_counts_every_run() {
    use std::sync::atomic::{AtomicU64, Ordering};
    let settings = Settings {
        problems: vec![6, 16],
        ..small(Some(2), 1)
    };
    let done = AtomicU64::new(0);
    let report = stochastic::run(&settings, &|k| {
        done.fetch_add(k, Ordering::Relaxed);
    })
    .unwrap();
    assert_eq!(
        done.load(Ordering::Relaxed),
        stochastic::total_runs(&settings)
    );
    assert_eq!(stochastic::total_runs(&settings), 2 * (2 * 3 + 2));
    for row in report.rows.iter().filter(|r| r.problem == 6) {
        assert_eq!(row.optimum_initial, "inf");
        assert!(
            row.note.as_deref().unwrap().contains("unreachable"),
            "{row:?}"
        );
        assert_eq!(row.convergence_rate, None);
    }
    // Nothing is within tolerance of an infinite G*.
    let p = exact_grid(6, StepCost::Unit, NoiseModel::Paper, &gamma("0.9")).unwrap();
    let t = Target::from_values(
        &p,
        &vec![Extended::Infinite; p.states()],
        Tolerance::Relative,
    );
    assert!((0..p.states()).all(|x| !t.within(x, 0.0) && !t.within(x, f64::INFINITY)));
}

//! One small stochastic problem with a trap, solved by hand, against what the stochastic
//! module reports beside `G*`: the optimum's accessors (`unreduced`, `q_value`,
//! `is_optimal_action`, `suboptimal_states`), value iteration's work counts (`backups`,
//! `outcome_terms`, checked against a count made here from the problem's own lists) and the
//! sampler's end points (issue 14: the mutants `unreduced → Some((0, 0))`, `q_value`'s
//! `d·s_x` → `d/s_x`, `suboptimal_states` without its goal filter, `sweeps * per_sweep_terms` →
//! `/`, `usable`'s `==` → `!=` and `cumulative.len() - 1` → `+ 1` survived the value tests).

use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::value_iteration::{
    value_iteration_exact, value_iteration_f64, FloatModel, Schedule, ViOptions,
};
use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use truecost::value::{parse_rational, Extended, Rational};

fn q(text: &str) -> Rational {
    parse_rational(text).unwrap()
}

fn out(to: usize, p: &str) -> Outcome {
    Outcome {
        successor: to,
        probability: q(p),
        kind: OutcomeKind::Listed,
    }
}

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

/// The benchmark grid's size limits: sides `1..=MAX_SIDE` and at least two states, both in the
/// generator and in the `ROWSxCOLS` parser (`rows · cols < 2`, not `rows + cols < 2`).
#[test]
fn benchmark_grid_sizes_at_the_edges() {
    use truecost::stochastic::benchmark::{cost_grid, parse_size, MAX_SIDE};
    for (rows, cols) in [(1, 1), (0, 5), (5, 0), (MAX_SIDE + 1, 1), (1, MAX_SIDE + 1)] {
        assert!(cost_grid(rows, cols, 0).is_err(), "{rows}x{cols}");
        assert!(
            parse_size(&format!("{rows}x{cols}")).is_err(),
            "{rows}x{cols}"
        );
    }
    for (rows, cols) in [(1, 2), (2, 1), (1, MAX_SIDE), (3, 3)] {
        let p = cost_grid(rows, cols, 0).unwrap();
        assert_eq!(p.states(), rows * cols);
        assert_eq!(parse_size(&format!("{rows}x{cols}")).unwrap(), (rows, cols));
    }
    assert!(parse_size("1").is_err());
    assert_eq!(parse_size("2").unwrap(), (2, 2));
    // Memory sizes (`--max-memory`): a fraction longer than the integer part, and no integer
    // part at all (refused, as `1.` is).
    use truecost::stochastic::scale::parse_size as memory;
    assert_eq!(memory("0.25G").unwrap(), 1 << 28);
    assert_eq!(memory("1.125G").unwrap(), 9 << 27);
    assert!(memory(".5G").is_err());
}

/// `memory_estimate` (`--max-memory`) against what `optimum` then does on the same problem: the
/// same number of unknowns (every non-goal state of a cost grid has an action and a finite
/// `G*`), and its lifting steps an upper estimate of each exact evaluation's.
#[test]
fn the_memory_estimate_bounds_what_the_optimum_then_does() {
    use truecost::stochastic::benchmark::cost_grid;
    use truecost::stochastic::policy_iteration::memory_estimate;
    use truecost::stochastic::{NoiseModel, Predictability};
    for (side, seed, gamma) in [(3, 0, "0.9"), (5, 1, "0.99"), (8, 2, "0.999")] {
        let grid = cost_grid(side, side, seed).unwrap();
        let gamma = Predictability::parse(gamma).unwrap();
        let s = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &gamma).unwrap();
        let e = memory_estimate(&s, false);
        let o = optimum(&s).unwrap();
        assert_eq!(e.unknowns, side * side - 1);
        assert_eq!(o.stats.unknowns, e.unknowns, "{side}");
        assert_eq!(o.stats.finite_states, side * side, "{side}");
        assert!(o.stats.exact_iterations >= 1);
        assert!(
            o.stats.lifting_steps <= e.lifting_steps * o.stats.exact_iterations,
            "{side}: {:?} against {e:?}",
            o.stats
        );
        assert!(memory_estimate(&s, true).bytes > e.bytes);
    }
}

//! The exact optimum of a problem read from an explicit stochastic file (every action a list of
//! outcomes, no commanded move) against the same problem built from a grid and `γ`: the same
//! exact values, and at most two exact evaluations from either source (the initial policy is
//! the deterministic optimum over each action's intended move, its most likely outcome when
//! the file names no commanded one). The values are checked against the Bellman equation in
//! exact rational arithmetic here (positive costs: its only solution is `G*`).

mod common;

use common::cli::json;
use num_traits::Zero;
use truecost::model::Problem;
use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
use truecost::stochastic::file::{from_json, to_json, ProblemFile};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::{Extended, Rational};

/// The grid in the stochastic model with paper noise and `γ`, and the same problem written as
/// an explicit stochastic file and read back.
fn both_sources(grid: &Problem, gamma: &str) -> (StochasticProblem, StochasticProblem) {
    let gamma = Predictability::parse(gamma).unwrap();
    let built = StochasticProblem::from_deterministic(grid, NoiseModel::Paper, &gamma).unwrap();
    let ProblemFile::Stochastic(read) = from_json(&to_json(&built, None)).unwrap() else {
        panic!("a file listing outcomes is read as a stochastic problem")
    };
    assert!(
        (0..read.action_total()).all(|a| read.commanded(a).is_none()),
        "the file names no commanded move"
    );
    (built, *read)
}

/// Asserts `g(x) = min_a (l(x, a) + Σ p·g(y))` at every non-goal state and `g = 0` at goals, in
/// exact rational arithmetic (every value finite: every state of these grids reaches the goal).
fn assert_bellman(p: &StochasticProblem, g: &[Extended]) {
    let value = |y: usize| -> Rational {
        g[y].finite()
            .cloned()
            .unwrap_or_else(|| panic!("G*({y}) is finite on these grids"))
    };
    for x in 0..p.states() {
        if p.is_goal(x) {
            assert!(value(x).is_zero(), "goal {x}");
            continue;
        }
        let best = p
            .actions(x)
            .map(|a| {
                p.outcomes(a).iter().fold(p.cost(a).clone(), |acc, o| {
                    acc + &o.probability * value(o.successor)
                })
            })
            .min()
            .expect("every grid state has a move");
        assert_eq!(best, value(x), "Bellman equation at state {x}");
    }
}

#[test]
fn an_explicit_file_needs_at_most_two_exact_evaluations_like_its_grid() {
    for (side, pattern, gamma) in [
        (20, GridPattern::Random, "0.999"),
        (20, GridPattern::Random, "0.99"),
        (12, GridPattern::Ties, "0.999"),
        (12, GridPattern::Walls, "0.999"),
        (12, GridPattern::Goals, "0.999"),
    ] {
        let grid = pattern_grid(side, side, pattern, CostRange::DEFAULT, 0).unwrap();
        let (built, read) = both_sources(&grid, gamma);
        let from_grid = optimum(&built).unwrap();
        let from_file = optimum(&read).unwrap();
        let case = format!("{side}x{side} {} γ = {gamma}", pattern.name());
        for (source, o) in [("grid", &from_grid), ("file", &from_file)] {
            assert!(
                o.stats.exact_iterations <= 2,
                "{case} from the {source}: {:?}",
                o.stats
            );
        }
        assert_eq!(
            from_file.cost_to_go_all(),
            from_grid.cost_to_go_all(),
            "{case}"
        );
        assert_bellman(&read, from_file.cost_to_go_all());
    }
}

#[test]
fn a_file_without_a_dominant_outcome_starts_from_its_first_most_likely_one() {
    // 0 → 1 → 2 (goal). At 0 the first action's outcomes are 1 and 2 at 1/2 each (intended: 1),
    // the second's 0 at 3/4 (intended: a self-loop). The deterministic optimum over intended
    // moves takes the first action at 0 and the only one at 1; it is optimal, so one exact
    // evaluation confirms it.
    let text = r#"{"initial": 0, "goals": [2], "actions": [
        [{"cost": "2", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 2, "p": "1/2"}]},
         {"cost": "1", "outcomes": [{"to": 0, "p": "3/4"}, {"to": 2, "p": "1/4"}]}],
        [{"cost": "1", "outcomes": [{"to": 2, "p": "1"}]}],
        []]}"#;
    let ProblemFile::Stochastic(p) = from_json(text).unwrap() else {
        panic!("outcomes listed")
    };
    assert_eq!((p.intended(0), p.intended(1), p.intended(2)), (1, 0, 2));
    let o = optimum(&p).unwrap();
    // First action: 2 + 1/2·1 = 5/2; second: G = 1 + 3/4·G, G = 4.
    assert_eq!(o.cost_to_go(0).to_string(), "5/2");
    assert_eq!(o.stats.initial_policy, "deterministic-optimum");
    assert_eq!(o.stats.exact_iterations, 1);
}

#[test]
fn solve_reports_the_same_values_and_at_most_two_exact_evaluations_from_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let grid = pattern_grid(20, 20, GridPattern::Random, CostRange::DEFAULT, 0).unwrap();
    let (built, _) = both_sources(&grid, "0.999");
    let grid_file = dir.path().join("grid.json");
    let explicit_file = dir.path().join("explicit.json");
    std::fs::write(&grid_file, truecost::model::file::to_json(&grid, None)).unwrap();
    std::fs::write(&explicit_file, to_json(&built, None)).unwrap();
    let solve = |file: &std::path::Path, gamma: &[&str]| {
        let mut args = vec!["solve", "--file", file.to_str().unwrap()];
        args.extend_from_slice(gamma);
        args.extend_from_slice(&["--algorithm", "exact", "--format", "json", "--quiet"]);
        json(&args)
    };
    let from_grid = solve(&grid_file, &["--gamma", "0.999"]);
    let from_file = solve(&explicit_file, &[]);
    for v in [&from_grid, &from_file] {
        let exact = v["optimum"]["exact_iterations"].as_u64().unwrap();
        assert!((1..=2).contains(&exact), "{}", v["optimum"]);
    }
    assert_eq!(from_grid["cost_to_go"], from_file["cost_to_go"]);
    assert_eq!(from_file["cost_to_go"].as_array().unwrap().len(), 400);
}

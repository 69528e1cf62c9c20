//! The grid pattern family of `export --grid --pattern` and the exact optimum on it: on every
//! pattern, both noise models and γ ∈ {0.99, 0.999}, [`optimum`] (f64 warm start,
//! mixed-precision stage, exact policy iteration) agrees with a plain exact policy iteration
//! written here (exact evaluations from the first action everywhere, strict improvement, no
//! float stage), and needs a single exact evaluation.

mod common;

use common::cli::{fails_one_line, stdout};
use truecost::model::Problem;
use truecost::stochastic::benchmark::{cost_grid, pattern_grid, CostRange, GridPattern};
use truecost::stochastic::policy_iteration::{evaluate, optimum};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::{Extended, Rational};

/// Plain exact policy iteration: evaluate exactly, switch to the first action with the least
/// exact `Q` where it is strictly below the current value; until no switch.
fn plain_policy_iteration(p: &StochasticProblem) -> Vec<Extended> {
    let mut policy: Vec<Option<usize>> = (0..p.states())
        .map(|x| (!p.is_goal(x)).then(|| p.actions(x).start))
        .collect();
    loop {
        let g = evaluate(p, &policy).unwrap();
        assert!(
            g.iter().all(|v| matches!(v, Extended::Finite(_))),
            "every policy is proper on these grids"
        );
        let value = |y: usize| match &g[y] {
            Extended::Finite(r) => r.clone(),
            Extended::Infinite => unreachable!(),
        };
        let mut changed = false;
        for x in (0..p.states()).filter(|&x| !p.is_goal(x)) {
            let q = |a: usize| -> Rational {
                p.outcomes(a).iter().fold(p.cost(a).clone(), |acc, o| {
                    acc + &o.probability * value(o.successor)
                })
            };
            let (best, qa) = p
                .actions(x)
                .map(|a| (a, q(a)))
                .reduce(|b, c| if c.1 < b.1 { c } else { b })
                .unwrap();
            if qa < value(x) {
                policy[x] = Some(best);
                changed = true;
            }
        }
        if !changed {
            return g;
        }
    }
}

fn stochastic(grid: &Problem, noise: NoiseModel, gamma: &str) -> StochasticProblem {
    StochasticProblem::from_deterministic(grid, noise, &Predictability::parse(gamma).unwrap())
        .unwrap()
}

/// Small instances of every pattern (sizes where ties propagate over several states).
fn instances() -> Vec<(GridPattern, Problem)> {
    let mut out = Vec::new();
    for pattern in GridPattern::ALL {
        for (r, c) in [(4, 5), (5, 5)] {
            let range = CostRange::DEFAULT;
            out.push((pattern, pattern_grid(r, c, pattern, range, 3).unwrap()));
        }
    }
    out.push((
        GridPattern::Random,
        pattern_grid(5, 4, GridPattern::Random, CostRange { lo: 2, hi: 3 }, 9).unwrap(),
    ));
    out
}

#[test]
fn the_fast_path_finds_the_plain_exact_optimum_on_every_pattern() {
    for (pattern, grid) in instances() {
        for noise in [NoiseModel::Paper, NoiseModel::Reference] {
            for gamma in ["0.99", "0.999"] {
                let p = stochastic(&grid, noise, gamma);
                let what = format!(
                    "{} {} {gamma} ({} states)",
                    pattern.name(),
                    noise.name(),
                    p.states()
                );
                let plain = plain_policy_iteration(&p);
                let o = optimum(&p).unwrap();
                assert_eq!(o.cost_to_go_all(), &plain[..], "{what}");
                // The texts printed in parallel, each denominator once, are the values' own.
                let texts: Vec<String> = plain.iter().map(|v| v.to_string()).collect();
                assert_eq!(o.cost_to_go_texts(), texts, "{what}");
                // The reported policy attains G* everywhere.
                assert!(
                    o.suboptimal_states(&p, o.policy_actions()).is_empty(),
                    "{what}"
                );
                assert_eq!(o.stats.exact_iterations, 1, "{what}: {:?}", o.stats);
            }
        }
    }
}

/// A unit-cost grid large enough for gaps far below `f64` resolution (exact policy iteration
/// started from the `f64` policy needs 8 exact evaluations here): one exact evaluation.
#[test]
fn ties_below_f64_resolution_need_one_exact_evaluation() {
    for pattern in [GridPattern::Unit, GridPattern::Ties] {
        let grid = pattern_grid(12, 12, pattern, CostRange::DEFAULT, 0).unwrap();
        let p = stochastic(&grid, NoiseModel::Paper, "0.99");
        let o = optimum(&p).unwrap();
        assert_eq!(o.stats.exact_iterations, 1, "{:?}", o.stats);
        assert!(o.stats.refinement_rounds > 0, "{:?}", o.stats);
        assert!(o.suboptimal_states(&p, o.policy_actions()).is_empty());
    }
}

#[test]
fn patterns_have_their_shapes() {
    // Random with the default range is the benchmark grid.
    assert_eq!(
        pattern_grid(6, 7, GridPattern::Random, CostRange::DEFAULT, 5).unwrap(),
        cost_grid(6, 7, 5).unwrap()
    );
    let costs = |p: &Problem| -> Vec<String> {
        (0..p.states())
            .flat_map(|x| p.moves(x).iter().map(|m| m.cost.to_string()))
            .collect()
    };
    let r = pattern_grid(8, 8, GridPattern::Random, CostRange { lo: 5, hi: 7 }, 1).unwrap();
    let c = costs(&r);
    assert!(c.iter().all(|v| ["5", "6", "7"].contains(&v.as_str())));
    assert!(["5", "6", "7"].iter().all(|v| c.contains(&v.to_string())));
    assert!(
        costs(&pattern_grid(4, 4, GridPattern::Unit, CostRange::DEFAULT, 0).unwrap())
            .iter()
            .all(|v| v == "1")
    );
    // Ties: the cost of a move is 1 + (row + col) mod 4 of the cell left; cell (2, 3) of a
    // 4x4 grid is state 11, its moves cost 1 + 5 mod 4 = 2.
    let t = pattern_grid(4, 4, GridPattern::Ties, CostRange::DEFAULT, 0).unwrap();
    assert!(t.moves(11).iter().all(|m| m.cost.to_string() == "2"));
    // Walls: 8 columns, column 3 a wall but for its bottom cell, column 7 the last column.
    let w = pattern_grid(5, 8, GridPattern::Walls, CostRange::DEFAULT, 0).unwrap();
    assert_eq!(w.states(), 40 - 4);
    assert_eq!(w.goals(), &[35]);
    // Every state reaches the goal (the serpentine keeps the grid connected).
    let s = stochastic(&w, NoiseModel::Paper, "1");
    assert!(optimum(&s)
        .unwrap()
        .cost_to_go_all()
        .iter()
        .all(|v| matches!(v, Extended::Finite(_))));
    // Goals: the other three corners and the centre.
    let g = pattern_grid(5, 6, GridPattern::Goals, CostRange::DEFAULT, 0).unwrap();
    assert_eq!(g.goals(), &[5, 15, 24, 29]);
    assert_eq!(g.initial(), 0);
}

#[test]
fn export_writes_every_pattern_and_refuses_bad_options_before_work() {
    let dir = tempfile::tempdir().unwrap();
    for pattern in GridPattern::NAMES {
        let out = dir.path().join(format!("{pattern}.json"));
        let out = out.to_str().unwrap();
        let text = stdout(&[
            "export",
            "--grid",
            "6x6",
            "--pattern",
            pattern,
            "--out",
            out,
        ]);
        assert!(text.starts_with("wrote "), "{text}");
        let json = std::fs::read_to_string(out).unwrap();
        assert!(json.contains(&format!("pattern {pattern}")) || pattern == "random");
    }
    let out = dir.path().join("refused.json");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (&["--pattern", "maze"], "unknown grid pattern 'maze'"),
        (&["--costs", "4-2"], "LO-HI"),
        (&["--costs", "0-3"], "LO-HI"),
        (&["--costs", "1-x"], "LO-HI"),
        (
            &["--pattern", "ties", "--costs", "1-9"],
            "--costs applies to --pattern random only",
        ),
    ];
    for (extra, message) in cases {
        let mut args = vec!["export", "--grid", "6x6", "--out", out];
        args.extend_from_slice(extra);
        let err = fails_one_line(&args);
        assert!(err.contains(message), "{extra:?}: {err}");
        assert!(
            !std::path::Path::new(out).exists(),
            "{extra:?}: nothing written"
        );
    }
}

/// The parallel parts (batched reduction, improvement tests, refinement residuals) give the
/// same optimum, policy and statistics on one thread as on several.
#[test]
fn one_thread_and_several_agree() {
    let run = |threads: usize, p: &StochasticProblem| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let o = optimum(p).unwrap();
                // The texts first: printed from values reduced for them, not from the cache.
                let texts = o.cost_to_go_texts();
                (
                    o.cost_to_go_all().to_vec(),
                    texts,
                    o.policy_actions().to_vec(),
                    o.stats.clone(),
                )
            })
    };
    for pattern in [GridPattern::Random, GridPattern::Ties, GridPattern::Walls] {
        let grid = pattern_grid(9, 9, pattern, CostRange::DEFAULT, 5).unwrap();
        for noise in [NoiseModel::Paper, NoiseModel::Reference] {
            let p = stochastic(&grid, noise, "0.999");
            let one = run(1, &p);
            assert_eq!(one, run(3, &p), "{} {}", pattern.name(), noise.name());
            // The texts are the reduced values' own.
            let texts: Vec<String> = one.0.iter().map(|v| v.to_string()).collect();
            assert_eq!(one.1, texts);
        }
    }
}

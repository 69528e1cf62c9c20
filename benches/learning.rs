//! Benchmarks of Q-learning on Problem 10 of the paper: `ρ = 1`, `Q₀ = 0`, the paper's
//! 1000 episodes × 3000 steps, ε = 0 (greedy) and ε = 0.9 over the random plan.
//!
//! * `q_learning/<ε>/reference` — the reference mode of docs/spec.md §7 (`f64` Euclidean costs, checks
//!   every 1000 actions): the same work as the paper's Python code, which takes about 0.9 s
//!   (ε = 0) and 2.0 s (ε = 0.9) per run; the target is ≥ 100× faster (≤ 9 ms, ≤ 20 ms).
//! * `q_learning/<ε>/exact` — unit step costs in exact `Units`, metrics after every action.
//!
//! One iteration builds the Q-table and runs to the end (the run stops early when it converges,
//! as the paper's does); compiling the problem and its optimum happen once, outside the timing.
//! Run with `cargo bench --bench learning`. As in `benches/planners.rs`,
//! `TRUECOST_BENCH_ITERATIONS=N` runs every row `N` times without criterion and exits
//! (`TRUECOST_BENCH_ONLY=eps_0.9/reference` runs one row): the instructions of one run are the
//! difference of two callgrind totals at two values of `N` (`docs/speed.md`). With
//! `TRUECOST_BENCH_REPORT=1` as well, each run is timed on its own and the median, the minimum
//! and the time per action are printed: the Rust half of the side-by-side rounds.

use std::time::Duration;

mod support;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
use truecost::learning::q_learning::{LearningValue, QLearner, QLearningConfig, Rules};
use truecost::model::{ExactGraph, Graph};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::dijkstra;
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::value::{parse_rational, Units};

const PROBLEM: usize = 10;

fn exact_graph() -> Graph<Units> {
    let problem = GridLayout::exact(PROBLEM)
        .expect("problem 10 exists")
        .to_problem(StepCost::Unit);
    match ExactGraph::new(&problem) {
        ExactGraph::Units(g) => g,
        ExactGraph::Big(_) => panic!("grid problems compile to Units"),
    }
}

fn run<V: LearningValue>(g: &Graph<V>, optimum: &[V], config: &QLearningConfig) -> u64 {
    let mut learner = QLearner::new(
        g,
        optimum,
        V::zero(),
        config,
        sample_rng(0, 0),
        Plan::Random,
    )
    .expect("valid configuration");
    learner.run().actions
}

fn q_learning(c: &mut Criterion) {
    let reference = GridLayout::reference(PROBLEM)
        .expect("problem 10 exists")
        .to_reference_graph();
    let reference_optimum =
        value_iteration(&reference, Schedule::Asynchronous, Some(1000)).cost_to_go;
    let exact = exact_graph();
    let exact_optimum = dijkstra::to_goals(&exact).cost_to_go;
    let rows = [("eps_0", "0"), ("eps_0.9", "0.9")].map(|(name, epsilon)| {
        let epsilon = EpsilonSchedule::Constant(
            Probability::new("ε", &parse_rational(epsilon).unwrap()).unwrap(),
        );
        let exact_config = QLearningConfig::paper(epsilon);
        let reference_config = QLearningConfig {
            rules: Rules::Reference,
            ..exact_config.clone()
        };
        (name, exact_config, reference_config)
    });
    if let Some(iterations) = support::fixed_iterations() {
        for (name, exact_config, reference_config) in &rows {
            let runs: [(&str, &dyn Fn() -> u64); 2] = [
                ("reference", &|| {
                    run(black_box(&reference), &reference_optimum, reference_config)
                }),
                ("exact", &|| {
                    run(black_box(&exact), &exact_optimum, exact_config)
                }),
            ];
            for (mode, run) in runs {
                let row = format!("{name}/{mode}");
                if !support::wanted(&row) {
                    continue;
                }
                if let (Some(actions), Some((median, min))) = support::timed_calls(iterations, run)
                {
                    let median = median.as_secs_f64();
                    println!(
                        "q_learning/{row}: median {:.3} ms, min {:.3} ms over {iterations} runs, {actions} actions, {:.1} ns per action",
                        median * 1e3,
                        min.as_secs_f64() * 1e3,
                        median * 1e9 / actions as f64,
                    );
                }
            }
        }
        std::process::exit(0);
    }
    let mut group = c.benchmark_group("q_learning");
    group
        .sample_size(30)
        .measurement_time(Duration::from_secs(5));
    for (name, exact_config, reference_config) in &rows {
        group.bench_function(format!("{name}/reference"), |b| {
            b.iter(|| run(black_box(&reference), &reference_optimum, reference_config))
        });
        group.bench_function(format!("{name}/exact"), |b| {
            b.iter(|| run(black_box(&exact), &exact_optimum, exact_config))
        });
    }
    group.finish();
}

criterion_group!(benches, q_learning);
criterion_main!(benches);

//! Benchmarks of stochastic Q-learning on Problem 10 of the paper: γ = 0.999,
//! ρ = 0.99, ε = 0.9 over the random plan, 3000 episodes × 3000 steps, `Q₀ = 0`. The paper's
//! Python code takes about 2 s per run on this machine; the target is ≥ 100× faster (≤ 20 ms).
//!
//! * `stochastic_q_learning/relative` — paper noise, unit step costs, judged within 10% of the
//!   exact `G*` (the run stops at the end of the episode in which every tracked state is within
//!   tolerance, as the paper's does);
//! * `stochastic_q_learning/reference` — reference noise, Euclidean step costs, ±5 units;
//! * `stochastic_q_learning/full_9M_steps` — the same learner with a target nobody reaches, so
//!   every one of the 3000 episodes runs to its end or the goal: raw throughput.
//!
//! One iteration builds the learner and runs to the end; the grid, its exact optimum and the
//! targets are computed once, outside the timing. Run with
//! `cargo bench --bench stochastic_learning`.

use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
use truecost::learning::stochastic_q::{
    LearningRate, StochasticQConfig, StochasticQLearner, Target, Tolerance,
};
use truecost::problems::StepCost;
use truecost::stochastic::grid::exact_grid;
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::value_iteration::FloatModel;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::{parse_rational, Extended};

fn config() -> StochasticQConfig {
    StochasticQConfig {
        episodes: 3000,
        max_steps: 3000,
        rate: LearningRate::Constant(0.99),
        epsilon: EpsilonSchedule::Constant(
            Probability::new("ε", &parse_rational("0.9").unwrap()).unwrap(),
        ),
        initial_value: 0.0,
    }
}

fn run(p: &StochasticProblem, cost: &[f64], target: &Target, seed: u64) -> u64 {
    let mut learner = StochasticQLearner::new(
        p,
        cost,
        target,
        &config(),
        sample_rng(seed, 0),
        Plan::Random,
    )
    .expect("valid configuration");
    learner.run().actions
}

fn stochastic_q_learning(c: &mut Criterion) {
    let gamma = Predictability::parse("0.999").unwrap();
    let mut group = c.benchmark_group("stochastic_q_learning");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(5));
    for (name, noise, step, tolerance) in [
        (
            "relative",
            NoiseModel::Paper,
            StepCost::Unit,
            Tolerance::Relative,
        ),
        (
            "reference",
            NoiseModel::Reference,
            StepCost::Euclidean,
            Tolerance::Reference,
        ),
    ] {
        let p = exact_grid(10, step, noise, &gamma).unwrap();
        let target = Target::new(&p, &optimum(&p).unwrap(), tolerance);
        let cost = FloatModel::nearest(&p).cost;
        eprintln!(
            "{name}: {} actions in the seed-0 run",
            run(&p, &cost, &target, 0)
        );
        group.bench_function(name, |b| b.iter(|| run(&p, &cost, black_box(&target), 0)));
    }
    let p = exact_grid(10, StepCost::Unit, NoiseModel::Paper, &gamma).unwrap();
    let far = vec![Extended::Finite(parse_rational("1000000").unwrap()); p.states()];
    let never = Target::from_values(&p, &far, Tolerance::Relative);
    let cost = FloatModel::nearest(&p).cost;
    eprintln!(
        "full_9M_steps: {} actions in the seed-0 run",
        run(&p, &cost, &never, 0)
    );
    group.sample_size(10);
    group.bench_function("full_9M_steps", |b| {
        b.iter(|| run(&p, &cost, black_box(&never), 0))
    });
    group.finish();
}

criterion_group!(benches, stochastic_q_learning);
criterion_main!(benches);

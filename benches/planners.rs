//! Benchmarks of the model-free planners on Problem 10 of the paper.
//!
//! Every benchmark times the whole model-free pipeline of SPEC §2: the depth-first exploration
//! from `x1` followed by one planner on the discovered graph. Compiling the problem into a graph
//! happens once, outside the timed loop.
//!
//! * `model_free/<planner>/exact` — unit step costs, exact `Units` values; Dijkstra backwards
//!   from the goals, value iteration to its fixed point.
//! * `model_free/<planner>/exact_euclidean` — the same with the exact step cost 800/19.
//! * `model_free/<planner>/reference` — the reference mode of SPEC §7 (`f64`): forward
//!   Dijkstra from `x1`, value iteration capped at 1000 sweeps.
//!
//! Issue targets: Dijkstra ≤ 100 µs, asynchronous VI ≤ 1.5 ms, synchronous VI ≤ 1.25 ms.
//!
//! Run with `cargo bench --bench planners`.

use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::model::{ExactGraph, Graph};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::solvers::{dijkstra, exploration::explore};
use truecost::value::{CostValue, Units};

/// The problem every benchmark runs on.
const PROBLEM: usize = 10;

/// Problem 10 compiled exactly; the grid problems always fit the `Units` representation.
fn exact_graph(step: StepCost) -> Graph<Units> {
    let layout = GridLayout::exact(PROBLEM).expect("problem 10 exists");
    match ExactGraph::new(&layout.to_problem(step)) {
        ExactGraph::Units(graph) => graph,
        ExactGraph::Big(_) => panic!("problem 10 should compile to the Units representation"),
    }
}

/// Problem 10 in the reference mode (`f64` Euclidean costs, the reference code's layout).
fn reference_graph() -> Graph<f64> {
    GridLayout::reference(PROBLEM)
        .expect("problem 10 exists")
        .to_reference_graph()
}

/// Explore, then Dijkstra backwards from the goals (exact mode).
fn explore_then_dijkstra_to_goals<V: CostValue>(graph: &Graph<V>) -> u64 {
    let exploration = explore(graph);
    let solution = dijkstra::to_goals(&exploration.graph);
    black_box(&solution.cost_to_go);
    exploration.actions + solution.actions
}

/// Explore, then forward Dijkstra from `x1` (reference mode).
fn explore_then_dijkstra_from_initial<V: CostValue>(graph: &Graph<V>) -> u64 {
    let exploration = explore(graph);
    let search = dijkstra::from_initial(&exploration.graph);
    black_box(&search.path);
    exploration.actions + search.counts.relaxations
}

/// Explore, then value iteration with the given schedule and sweep cap.
fn explore_then_vi<V: CostValue>(
    graph: &Graph<V>,
    schedule: Schedule,
    max_sweeps: Option<u64>,
) -> u64 {
    let exploration = explore(graph);
    let solution = value_iteration(&exploration.graph, schedule, max_sweeps);
    black_box(&solution.cost_to_go);
    exploration.actions + solution.actions
}

/// The three model-free pipelines of one mode.
fn bench_mode<V: CostValue>(
    c: &mut Criterion,
    mode: &str,
    graph: &Graph<V>,
    dijkstra_pipeline: fn(&Graph<V>) -> u64,
    max_sweeps: Option<u64>,
) {
    let mut group = c.benchmark_group("model_free");
    group.bench_function(format!("dijkstra/{mode}"), |b| {
        b.iter(|| dijkstra_pipeline(black_box(graph)))
    });
    group.bench_function(format!("async_vi/{mode}"), |b| {
        b.iter(|| explore_then_vi(black_box(graph), Schedule::Asynchronous, max_sweeps))
    });
    group.bench_function(format!("sync_vi/{mode}"), |b| {
        b.iter(|| explore_then_vi(black_box(graph), Schedule::Synchronous, max_sweeps))
    });
    group.finish();
}

fn model_free(c: &mut Criterion) {
    bench_mode(
        c,
        "exact",
        &exact_graph(StepCost::Unit),
        explore_then_dijkstra_to_goals,
        None,
    );
    bench_mode(
        c,
        "exact_euclidean",
        &exact_graph(StepCost::Euclidean),
        explore_then_dijkstra_to_goals,
        None,
    );
    bench_mode(
        c,
        "reference",
        &reference_graph(),
        explore_then_dijkstra_from_initial,
        Some(1000),
    );
}

criterion_group! {
    name = benches;
    // Short runs: CI machines have two cores and only build the benches.
    config = Criterion::default()
        .sample_size(50)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = model_free
}
criterion_main!(benches);

//! Benchmarks of the model-free planners on Problem 10 of the paper.
//!
//! Every benchmark times exactly the timed region of the experiments' model-free rows,
//! [`model_free_counts`] (docs/spec.md §2, the model-free variants): the depth-first
//! exploration from `x1`, one planner on the discovered graph, and its path. Compiling the
//! problem into a graph happens once, outside the timed loop.
//!
//! * `model_free/<planner>/exact` — unit step costs, exact `Units` values; Dijkstra backwards
//!   from the goals, value iteration to its fixed point.
//! * `model_free/<planner>/exact_euclidean` — the same with the exact step cost 800/19.
//! * `model_free/<planner>/reference` — the reference mode of docs/spec.md §7 (`f64`): forward
//!   Dijkstra from `x1`, value iteration capped at 1000 sweeps.
//!
//! The targets are ≥ 150× the paper's Python code measured on the same machine
//! (`docs/speed.md`): model-free Dijkstra ≤ 15 µs, asynchronous VI ≤ 200 µs, synchronous VI
//! ≤ 200 µs.
//!
//! Run with `cargo bench --bench planners`. For instruction counts, which the load of other
//! processes does not change, set `TRUECOST_BENCH_ITERATIONS=N`: the binary then runs every
//! pipeline `N` times without criterion and exits (`TRUECOST_BENCH_ONLY=dijkstra/reference`
//! runs one of them), so that
//! `valgrind --tool=callgrind target/release/deps/planners-… --bench` at two values of `N` gives
//! the instructions of one run as a difference (`docs/speed.md`). With
//! `TRUECOST_BENCH_REPORT=1` as well, each call is timed on its own and the median and minimum
//! per row are printed: the Rust half of the side-by-side rounds of `docs/speed.md`.

use std::time::Duration;

mod support;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::model::{ExactGraph, Graph};
use truecost::planning::{model_free_counts, Algorithm, Mode, PlanCounts};
use truecost::problems::{GridLayout, StepCost};
use truecost::value::{CostValue, Units};

/// The problem every benchmark runs on.
const PROBLEM: usize = 10;

/// The planners, with their benchmark names.
const PLANNERS: [(&str, Algorithm); 3] = [
    ("dijkstra", Algorithm::Dijkstra),
    ("async_vi", Algorithm::AsyncVi),
    ("sync_vi", Algorithm::Vi),
];

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

/// The three model-free pipelines of one mode.
fn bench_mode<V: CostValue>(c: &mut Criterion, name: &str, graph: &Graph<V>, mode: Mode) {
    let mut group = c.benchmark_group("model_free");
    for (planner, algorithm) in PLANNERS {
        group.bench_function(format!("{planner}/{name}"), |b| {
            b.iter(|| model_free_counts(black_box(graph), algorithm, mode))
        });
    }
    group.finish();
}

fn model_free(c: &mut Criterion) {
    let unit = exact_graph(StepCost::Unit);
    let euclidean = exact_graph(StepCost::Euclidean);
    let reference = reference_graph();
    if let Some(iterations) = support::fixed_iterations() {
        // Instruction counting (callgrind): a fixed amount of work, no criterion.
        let graphs: [(&str, &dyn Fn(Algorithm) -> PlanCounts); 3] = [
            ("exact", &|a| {
                model_free_counts(black_box(&unit), a, Mode::Exact)
            }),
            ("exact_euclidean", &|a| {
                model_free_counts(black_box(&euclidean), a, Mode::Exact)
            }),
            ("reference", &|a| {
                model_free_counts(black_box(&reference), a, Mode::Reference)
            }),
        ];
        for (planner, algorithm) in PLANNERS {
            for (name, run) in graphs {
                if !support::wanted(&format!("{planner}/{name}")) {
                    continue;
                }
                if let (_, Some((median, min))) =
                    support::timed_calls(iterations, || run(algorithm))
                {
                    println!(
                        "model_free/{planner}/{name}: median {:.2} µs, min {:.2} µs over {iterations} calls",
                        median.as_secs_f64() * 1e6,
                        min.as_secs_f64() * 1e6,
                    );
                }
            }
        }
        std::process::exit(0);
    }
    bench_mode(c, "exact", &unit, Mode::Exact);
    bench_mode(c, "exact_euclidean", &euclidean, Mode::Exact);
    bench_mode(c, "reference", &reference, Mode::Reference);
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

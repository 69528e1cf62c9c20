//! Benchmarks of the stochastic solvers (value iteration and the exact optimum).
//!
//! * `exact_optimum/p10/<noise>/<γ>` — the exact optimum of Problem 10 (unit step costs) by
//!   policy iteration with exact rational solves. Target: ≤ 5 s at γ = 0.999.
//! * `exact_optimum_table/<noise>` — all 16 paper problems × γ ∈ {0.999, 0.99, 0.9, 0.7, 0.5}
//!   for one noise model. Target: both noise models together ≤ 5 minutes.
//! * `exact_optimum_grid/<side>x<side>` — the exact optimum of a seeded benchmark grid
//!   (`truecost export --grid`, costs 1–4, paper noise, γ = 0.99), mid-size (30×30, 900
//!   states); the 100×100 case is timed with the CLI (README, "Large models").
//! * `exact_evaluation/grid_100x100` — one exact solve (`algebra::linear::solve_exact`: Dixon
//!   lifting, reconstruction, exact check) of a 10⁴-unknown system shaped like policy
//!   evaluation on a 100×100 grid: `1000·z_i − Σ w_ij·z_j = c_i` over the four neighbours, seeded
//!   weights `w_ij ∈ 1..=249`, costs `c_i ∈ 1..=4`.
//! * `stochastic_vi/f64_grid/<schedule>` — `f64` VI on the 100×100 benchmark grid to the
//!   tolerance 1e-9 (no exact `G*`: that is `--exact-error`'s job).
//! * `stochastic_vi/reference/<schedule>/<γ>` — the reference code's stochastic VI on Problem 10
//!   (reference noise, `f64`, full graph, to the 0.1 tolerance).
//! * `stochastic_vi/exact/<schedule>/<γ>` — exact stochastic VI from below on Problem 10 (paper
//!   noise, unit costs, tolerance 0.1).
//! * `exact_values_10k/reduced_all` and `exact_values_10k/decimal` — the two steps after the
//!   exact optimum of a 10⁴-state grid when every value is printed: 10⁴ numerators of about
//!   119,000 bits (planted powers of 3 shared with the denominator, as in a policy
//!   evaluation's values) over one common denominator `2⁴·3³⁸·R` of the same size, reduced to
//!   lowest terms together ([`truecost::algebra::lowest_terms::reduced_all`]); then the
//!   reduced numerators printed in decimal in parallel ([`truecost::value::integer_text`]).
//!
//! Problems are built outside the timed loop. Run with `cargo bench --bench stochastic`.

use std::time::Duration;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::problems::{StepCost, PAPER_PROBLEMS};
use truecost::stochastic::benchmark::cost_grid;
use truecost::stochastic::grid::{exact_grid, reference_grid};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::value_iteration::{
    value_iteration_exact, value_iteration_f64, FloatModel, Schedule, ViOptions,
};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::parse_rational;

const GAMMAS: [&str; 5] = ["0.999", "0.99", "0.9", "0.7", "0.5"];

fn gamma(text: &str) -> Predictability {
    Predictability::parse(text).expect("a valid gamma")
}

fn exact_optimum(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact_optimum");
    group.sample_size(10);
    for noise in [NoiseModel::Paper, NoiseModel::Reference] {
        for g in ["0.999", "0.9", "0.5"] {
            let problem = exact_grid(10, StepCost::Unit, noise, &gamma(g)).expect("problem 10");
            group.bench_function(format!("p10/{}/{g}", noise.name()), |b| {
                b.iter(|| optimum(black_box(&problem)).expect("solvable"))
            });
        }
    }
    group.finish();
}

fn exact_optimum_table(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact_optimum_table");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(30));
    for noise in [NoiseModel::Paper, NoiseModel::Reference] {
        let problems: Vec<StochasticProblem> = PAPER_PROBLEMS
            .iter()
            .flat_map(|&id| {
                GAMMAS.iter().map(move |g| {
                    exact_grid(id, StepCost::Unit, noise, &gamma(g)).expect("paper problem")
                })
            })
            .collect();
        group.bench_function(noise.name(), |b| {
            b.iter(|| {
                for p in &problems {
                    black_box(optimum(p).expect("solvable"));
                }
            })
        });
    }
    group.finish();
}

fn exact_optimum_grid(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact_optimum_grid");
    group.sample_size(10);
    let side = 30;
    let grid = cost_grid(side, side, 0).expect("a valid size");
    let problem = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &gamma("0.99"))
        .expect("a valid gamma");
    group.bench_function(format!("{side}x{side}"), |b| {
        b.iter(|| optimum(black_box(&problem)).expect("solvable"))
    });
    group.finish();
}

fn exact_evaluation(c: &mut Criterion) {
    use truecost::algebra::linear::{solve_exact, SparseSystem};
    let mut group = c.benchmark_group("exact_evaluation");
    group.sample_size(10);
    let side = 100usize;
    // A fixed linear congruential sequence for the weights (the bench needs no randomness
    // source, only a system that is the same every run).
    let mut state = 12_345u64;
    let mut next = |range: u64| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        1 + (state >> 33) % range
    };
    let mut system = SparseSystem::new();
    for i in 0..side * side {
        let (r, c) = (i / side, i % side);
        let mut row = vec![(i, 1000i64)];
        let neighbours = [
            (r > 0).then(|| i - side),
            (r + 1 < side).then(|| i + side),
            (c > 0).then(|| i - 1),
            (c + 1 < side).then(|| i + 1),
        ];
        for j in neighbours.into_iter().flatten() {
            row.push((j, -(next(249) as i64)));
        }
        system
            .push_row(&row, next(4) as i128)
            .expect("small entries");
    }
    group.bench_function(format!("grid_{side}x{side}"), |b| {
        b.iter(|| solve_exact(black_box(&system)).expect("non-singular"))
    });
    group.finish();
}

fn f64_vi_grid(c: &mut Criterion) {
    let mut group = c.benchmark_group("stochastic_vi");
    group.sample_size(10);
    let grid = cost_grid(100, 100, 0).expect("a valid size");
    let problem = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &gamma("0.99"))
        .expect("a valid gamma");
    let float = FloatModel::nearest(&problem);
    for (name, schedule) in [
        ("async", Schedule::Asynchronous),
        ("sync", Schedule::Synchronous),
    ] {
        let options = ViOptions::from_below(schedule, parse_rational("1e-9").expect("1e-9"), 5000)
            .expect("valid options");
        group.bench_function(format!("f64_grid/{name}"), |b| {
            b.iter(|| value_iteration_f64(black_box(&problem), &float, &options))
        });
    }
    group.finish();
}

fn stochastic_vi(c: &mut Criterion) {
    let mut group = c.benchmark_group("stochastic_vi");
    group.sample_size(10);
    for g in ["0.999", "0.99"] {
        let grid = reference_grid(10, NoiseModel::Reference, &gamma(g)).expect("problem 10");
        let exact =
            exact_grid(10, StepCost::Unit, NoiseModel::Paper, &gamma(g)).expect("problem 10");
        for (name, schedule) in [
            ("async", Schedule::Asynchronous),
            ("sync", Schedule::Synchronous),
        ] {
            let reference = ViOptions::reference(schedule);
            group.bench_function(format!("reference/{name}/{g}"), |b| {
                b.iter(|| value_iteration_f64(black_box(&grid.problem), &grid.float, &reference))
            });
            let below = ViOptions::from_below(schedule, parse_rational("0.1").expect("0.1"), 1000)
                .expect("valid options");
            group.bench_function(format!("exact/{name}/{g}"), |b| {
                b.iter(|| value_iteration_exact(black_box(&exact), &below))
            });
        }
    }
    group.finish();
}

/// `bits` random bits (the top one set), from a seeded generator.
fn random_integer(rng: &mut rand_chacha::ChaCha8Rng, bits: usize) -> num_bigint::BigInt {
    use rand::Rng;
    let bytes: Vec<u8> = (0..bits.div_ceil(8))
        .map(|_| rng.next_u32() as u8)
        .collect();
    let x = num_bigint::BigInt::from_bytes_le(num_bigint::Sign::Plus, &bytes);
    (x >> (8 * bytes.len() - bits)) | (num_bigint::BigInt::from(1) << (bits - 1))
}

fn exact_values_10k(c: &mut Criterion) {
    use rand::SeedableRng;
    use rayon::prelude::*;
    use truecost::algebra::lowest_terms::reduced_all;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(52);
    let three = num_bigint::BigInt::from(3);
    let d = random_integer(&mut rng, 119_000) * three.pow(38) * 16 + 1;
    let d = d * three.pow(38) * 16;
    let numerators: Vec<num_bigint::BigInt> = (0..10_000)
        .map(|i| random_integer(&mut rng, 119_100) * three.pow(i % 5))
        .collect();
    let refs: Vec<&num_bigint::BigInt> = numerators.iter().collect();
    let mut group = c.benchmark_group("exact_values_10k");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(120));
    group.bench_function("reduced_all", |b| {
        b.iter(|| reduced_all(black_box(&refs), black_box(&d)))
    });
    let values = reduced_all(&refs, &d);
    group.bench_function("decimal", |b| {
        b.iter(|| {
            values
                .par_iter()
                .map(|v| truecost::value::integer_text(v.numer()).len())
                .sum::<usize>()
        })
    });
    group.finish();
}

criterion_group!(
    benches,
    exact_optimum,
    exact_optimum_table,
    exact_optimum_grid,
    exact_evaluation,
    f64_vi_grid,
    stochastic_vi,
    exact_values_10k
);
criterion_main!(benches);

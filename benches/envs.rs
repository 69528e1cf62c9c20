//! Benchmarks of the three objectives on the Gymnasium benchmarks.
//!
//! `objectives/<env>/<objective>` — one exact solve ([`Model::solve`]: the optimum and the
//! success-probability bounds, truecost and steps of the reported policy) per objective on
//! every environment. Target: each ≤ 1 s. Models are built outside the timed loop.
//! `discount/<env>` — the exact discount breakpoints (`truecost discount --env`). Target for
//! FrozenLake 8x8: ≤ 30 s on 2 cores. `discount/grid-NxN` — the same on the deterministic
//! benchmark grids of `truecost export --grid NxN --pattern random --costs 1-9 --seed 0`
//! (the successor-chain path, about one probe per running state).
//! Run with `cargo bench --bench envs -- --warm-up-time 1 --measurement-time 3`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::envs::EnvSpec;
use truecost::objectives::parametric::discount_breakpoints;
use truecost::objectives::{Model, Objective};
use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
use truecost::value::parse_rational;

const ENVS: [&str; 6] = [
    "frozenlake",
    "frozenlake:map=8x8",
    "frozenlake:map=8x8,slippery=false",
    "cliffwalking",
    "cliffwalking:slippery=true",
    "taxi",
];

fn objectives(c: &mut Criterion) {
    let mut group = c.benchmark_group("objectives");
    group.sample_size(10);
    for spec in ENVS {
        let env = EnvSpec::parse(spec)
            .and_then(|s| s.build())
            .expect("a valid spec");
        let model = Model::from_environment(&env).expect("a valid environment");
        for objective in [
            Objective::Truecost,
            Objective::Reach,
            Objective::Discounted(parse_rational("0.99").expect("0.99")),
        ] {
            group.bench_function(format!("{spec}/{}", objective.name()), |b| {
                b.iter(|| model.solve(black_box(&objective)).expect("solvable"))
            });
        }
    }
    group.finish();
}

/// `discount/<env>`: the exact breakpoints of the discount-optimal policies (target: FrozenLake
/// 8x8 ≤ 30 s on 2 cores).
fn discount(c: &mut Criterion) {
    let mut group = c.benchmark_group("discount");
    group.sample_size(10);
    for spec in ["frozenlake", "frozenlake:map=8x8"] {
        let env = EnvSpec::parse(spec)
            .and_then(|s| s.build())
            .expect("a valid spec");
        let model = Model::from_environment(&env).expect("a valid environment");
        group.bench_function(spec, |b| {
            b.iter(|| discount_breakpoints(black_box(&model)).expect("within the bounds"))
        });
    }
    for n in [10, 15, 20, 30] {
        let range = CostRange { lo: 1, hi: 9 };
        let grid = pattern_grid(n, n, GridPattern::Random, range, 0).expect("a valid grid");
        let model = Model::from_deterministic(&grid, format!("grid {n}x{n}")).expect("a model");
        group.bench_function(format!("grid-{n}x{n}"), |b| {
            b.iter(|| discount_breakpoints(black_box(&model)).expect("within the bounds"))
        });
    }
    group.finish();
}

criterion_group!(benches, objectives, discount);
criterion_main!(benches);

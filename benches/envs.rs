//! Benchmarks of the three objectives on the Gymnasium benchmarks (issue 11, item 7).
//!
//! `objectives/<env>/<objective>` — one exact solve ([`Model::solve`]: the optimum and the
//! success-probability bounds, truecost and steps of the reported policy) per objective on
//! every environment. Target: each ≤ 1 s. Models are built outside the timed loop.
//! Run with `cargo bench --bench envs -- --warm-up-time 1 --measurement-time 3`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::envs::EnvSpec;
use truecost::objectives::{Model, Objective};
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

criterion_group!(benches, objectives);
criterion_main!(benches);

//! The two largest inputs the exact discount analysis is built for, each a whole
//! `truecost discount` analysis (target: each ≤ 60 s on 2 idle cores):
//!
//! * `grid-50x50`: the deterministic benchmark grid of `truecost export --grid 50x50 --pattern
//!   random --costs 1-9 --seed 0` (2499 running states, 2533 breakpoints; the successor-chain
//!   path with the probes' memory);
//! * `frozenlake-16x16`: a slippery FrozenLake-style 16×16 map (195 running states, 46
//!   breakpoints): 80 % frozen cells drawn by Python's `random.Random(0)`, start top-left,
//!   goal bottom-right, redrawn until the goal is reachable.
//!
//! Ten runs each (criterion's least): several minutes per input. Run with
//! `cargo bench --bench discount_targets -- --warm-up-time 1 --measurement-time 1`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::envs::EnvSpec;
use truecost::objectives::parametric::discount_breakpoints;
use truecost::objectives::Model;
use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};

/// The 16×16 map (module docs).
const MAP: &str = "SFFFFFFFFFHFFFFF
HHHHFFHFFFFFHHFH
FHFFFFHFFFHFFHFF
FHHFFFFHFFFFHFHF
FFFFFFFFFFFFFHHH
HHFFFFHHHFHFFFHH
FFFFFHFFFFFFHFFF
FFHFFFFFFFFHFFHF
FFHHFFFFFFFFFFFH
FFFHHFFHFFHFFFFF
FFFFFFHFFFFFFFFH
FFFHFFFFFFFFFFFF
HFFFFFFFFFFFFFFH
FFFHHHFHFFFHFFFF
FFHFFFFHFHFHFFFF
FHFFFFHFFFFFHHHG";

fn targets(c: &mut Criterion) {
    let mut group = c.benchmark_group("discount");
    group.sample_size(10);
    let range = CostRange { lo: 1, hi: 9 };
    let grid = pattern_grid(50, 50, GridPattern::Random, range, 0).expect("a valid grid");
    let model = Model::from_deterministic(&grid, "grid 50x50".into()).expect("a model");
    group.bench_function("grid-50x50", |b| {
        b.iter(|| discount_breakpoints(black_box(&model)).expect("within the bounds"))
    });
    let path = std::env::temp_dir().join(format!("truecost-bench-{}.txt", std::process::id()));
    std::fs::write(&path, MAP).expect("a writable temporary directory");
    let env = EnvSpec::parse(&format!("frozenlake:map={}", path.display()))
        .and_then(|s| s.build())
        .expect("a valid map");
    let model = Model::from_environment(&env).expect("a valid environment");
    group.bench_function("frozenlake-16x16", |b| {
        b.iter(|| discount_breakpoints(black_box(&model)).expect("within the bounds"))
    });
    let _ = std::fs::remove_file(&path);
    group.finish();
}

criterion_group!(benches, targets);
criterion_main!(benches);

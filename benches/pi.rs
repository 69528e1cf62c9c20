//! Digits of π in base 4 (the target: the first 10^7 digits in ≤ 5 s on 2 cores). Times the
//! exact computation without the caches.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use truecost::learning::pi::compute;

fn pi_digits(c: &mut Criterion) {
    let mut group = c.benchmark_group("pi_base4");
    group.sample_size(10);
    for n in [100_000usize, 1_000_000, 10_000_000] {
        group.bench_function(format!("compute/{n}"), |b| b.iter(|| compute(black_box(n))));
    }
    group.finish();
}

criterion_group!(benches, pi_digits);
criterion_main!(benches);

//! Throughput of the claims engines: the smoke scope of each engine-1 check,
//! and the exact isolation of alpha*. `truecost verify` also prints cases per second.

use criterion::{criterion_group, criterion_main, Criterion};
use truecost::claims::{alpha, c1, c2, c3, c4, Scope};

fn engines(c: &mut Criterion) {
    let mut g = c.benchmark_group("claims_smoke");
    g.sample_size(10);
    g.bench_function("c1", |b| b.iter(|| c1::check(Scope::Smoke)));
    g.bench_function("c2", |b| b.iter(|| c2::check(Scope::Smoke)));
    g.bench_function("c3", |b| b.iter(|| c3::check(Scope::Smoke)));
    g.bench_function("c4", |b| b.iter(|| c4::check(Scope::Smoke)));
    g.bench_function("alpha_star", |b| b.iter(alpha::alpha_star));
    g.finish();
}

criterion_group!(benches, engines);
criterion_main!(benches);

//! Benchmarks of certificates (`solve --certificate`, `truecost check`) on a seeded benchmark
//! grid (`truecost export --grid`, costs 1–4 drawn by ChaCha8, not built for certificates):
//!
//! * `certificate/<grid>/solve` — the exact optimum alone (policy iteration, exact solves).
//! * `certificate/<grid>/solve_and_write` — the optimum, then the certificate's text: every
//!   value printed over the common denominator, the policy, the SHA-256 of the model's
//!   canonical export.
//! * `certificate/<grid>/check` — reading the certificate and checking every condition in exact
//!   arithmetic against the model.
//!
//! Grids: 50×50 deterministic (γ = 1, the size of the budget "writing costs at most 10 % of
//! the solve") and 20×20 under the paper's noise with γ = 0.99 (values of many digits).
//! Problems are built outside the timed loop. The grid is in memory, so the certificate hashes
//! the model's canonical export (as for `--problem` and `--env`; `--file` hashes the file's
//! bytes instead, which is cheaper). Run with `cargo bench --bench certificate`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::certificate::{self, CertifiedObjective, Identity, ProblemRecord};
use truecost::stochastic::benchmark::cost_grid;
use truecost::stochastic::certified::{optimum_certificate, problem_mdp};
use truecost::stochastic::policy_iteration::{optimum, Optimum};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

fn write(p: &StochasticProblem, opt: &Optimum, objective: &CertifiedObjective) -> String {
    let record = ProblemRecord {
        source: "problem".into(),
        name: "benchmark grid".into(),
        gamma: None,
        noise: None,
        step_cost: None,
        sha256: certificate::sha256_hex(problem_mdp(p).canonical_text().as_bytes()),
        sha256_of: certificate::CANONICAL_FORMAT.into(),
    };
    optimum_certificate(p, opt, objective, &record)
}

fn grids(c: &mut Criterion) {
    let cases = [
        (50, "1", CertifiedObjective::Deterministic),
        (20, "0.99", CertifiedObjective::Truecost),
    ];
    for (side, gamma_text, objective) in cases {
        let grid = cost_grid(side, side, 0).expect("a benchmark grid");
        let gamma = Predictability::parse(gamma_text).expect("a valid gamma");
        let p = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &gamma)
            .expect("a stochastic grid");
        let mut group = c.benchmark_group(format!("certificate/{side}x{side}_gamma_{gamma_text}"));
        group.sample_size(10);
        group.bench_function("solve", |b| {
            b.iter(|| optimum(black_box(&p)).expect("solvable"))
        });
        group.bench_function("solve_and_write", |b| {
            b.iter(|| {
                let opt = optimum(black_box(&p)).expect("solvable");
                write(&p, &opt, &objective)
            })
        });
        let text = write(&p, &optimum(&p).expect("solvable"), &objective);
        let mdp = problem_mdp(&p);
        group.bench_function("check", |b| {
            b.iter(|| {
                let cert = certificate::parse(black_box(&text)).expect("a certificate");
                certificate::check(&mdp, Identity::Canonical, &cert).expect("accepted")
            })
        });
        group.finish();
    }
}

criterion_group!(benches, grids);
criterion_main!(benches);

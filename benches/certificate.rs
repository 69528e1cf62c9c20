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
//! Grids, in group `certificate`: 50×50 deterministic (γ = 1) and 20×20 under the paper's
//! noise with γ = 0.99 (values of many digits); in group `certificate_large`, the 10⁴-state
//! grid 100×100 deterministic and under the paper's noise with γ = 0.99 (values of about
//! 86,000 bits, a certificate of 429 MB; about 10 s per solve, so this group takes minutes:
//! `cargo bench --bench certificate -- certificate/` runs the small group alone).
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
        goal_label: None,
        cost_reward: None,
    };
    optimum_certificate(p, opt, objective, &record)
}

/// The three benchmarks of one grid, in group `group`.
fn grid(c: &mut Criterion, group: &str, side: usize, gamma_text: &str) {
    let objective = match gamma_text {
        "1" => CertifiedObjective::Deterministic,
        _ => CertifiedObjective::Truecost,
    };
    let grid = cost_grid(side, side, 0).expect("a benchmark grid");
    let gamma = Predictability::parse(gamma_text).expect("a valid gamma");
    let p = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &gamma)
        .expect("a stochastic grid");
    let mut group = c.benchmark_group(format!("{group}/{side}x{side}_gamma_{gamma_text}"));
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

fn grids(c: &mut Criterion) {
    grid(c, "certificate", 50, "1");
    grid(c, "certificate", 20, "0.99");
}

fn large(c: &mut Criterion) {
    grid(c, "certificate_large", 100, "1");
    grid(c, "certificate_large", 100, "0.99");
}

criterion_group!(benches, grids, large);
criterion_main!(benches);

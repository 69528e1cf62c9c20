//! Benchmarks of certificates (`solve --certificate`, `truecost check`) on a seeded benchmark
//! grid (`truecost export --grid`, costs 1–4 drawn by ChaCha8, not built for certificates):
//!
//! * `certificate/<grid>/solve` — the exact optimum alone (policy iteration, exact solves).
//! * `certificate/<grid>/solve_and_write` — the optimum, then the certificate's text as
//!   `solve --certificate` streams it (into a sink here, a batch at a time): every value printed
//!   over the common denominator, the policy, the SHA-256 of the model's canonical export.
//! * `certificate/<grid>/check` — reading the certificate and checking every condition in exact
//!   arithmetic against the model.
//!
//! Grids, the rows of the speed table of `docs/guide/certificates.md`: in group `certificate`,
//! 50×50 deterministic (γ = 1) and under the paper's noise with γ = 0.99 and 0.999 (values of
//! thousands of digits), and 20×20 with γ = 0.99; in group `certificate_large`, the 10⁴-state
//! grid 100×100 deterministic and with γ = 0.99 and 0.999 (values of about 86,000 and 119,000
//! bits, certificates of 429 and 595 MB; 10 to 15 s per solve, so this group takes many
//! minutes: `cargo bench --bench certificate -- certificate/` runs the small group alone).
//! Problems are built outside the timed loop. The grid is in memory, so the certificate hashes
//! the model's canonical export (as for `--problem` and `--env`; `--file` hashes the file's
//! bytes instead, which is cheaper). Run with `cargo bench --bench certificate`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use truecost::certificate::{self, CertifiedObjective, Identity, ProblemRecord};
use truecost::stochastic::benchmark::cost_grid;
use truecost::stochastic::certified::{
    optimum_certificate, problem_mdp, write_optimum_certificate,
};
use truecost::stochastic::policy_iteration::{optimum, Optimum};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

fn record(p: &StochasticProblem) -> ProblemRecord {
    ProblemRecord {
        source: "problem".into(),
        name: "benchmark grid".into(),
        gamma: None,
        noise: None,
        step_cost: None,
        sha256: certificate::sha256_hex(problem_mdp(p).canonical_text().as_bytes()),
        sha256_of: certificate::CANONICAL_FORMAT.into(),
        goal_label: None,
        cost_reward: None,
    }
}

/// The certificate as `solve --certificate` streams it, into a sink.
fn write(p: &StochasticProblem, opt: &Optimum, objective: &CertifiedObjective) {
    write_optimum_certificate(&mut std::io::sink(), p, opt, objective, &record(p))
        .expect("a sink takes everything");
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
    let text = optimum_certificate(&p, &optimum(&p).expect("solvable"), &objective, &record(&p));
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
    grid(c, "certificate", 50, "0.99");
    grid(c, "certificate", 50, "0.999");
    grid(c, "certificate", 20, "0.99");
}

fn large(c: &mut Criterion) {
    grid(c, "certificate_large", 100, "1");
    grid(c, "certificate_large", 100, "0.99");
    grid(c, "certificate_large", 100, "0.999");
}

criterion_group!(benches, grids, large);
criterion_main!(benches);

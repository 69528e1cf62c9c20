//! The exact optimum over the grid pattern family (`truecost export --grid --pattern`):
//! every pattern × {2,500, 10⁴} states × γ ∈ {0.99, 0.999} × both noise models, each solved
//! once, one table row each: wall time, exact evaluations, lifting steps, mixed-precision
//! rounds and bits. Targets (release, 2 idle cores): 2,500 states ≤ 5 s and 10⁴ states ≤ 60 s
//! for every pattern; a row over its target is marked `OVER`.
//!
//! `cargo bench --bench stochastic_patterns` runs every row (about 20 minutes);
//! `cargo bench --bench stochastic_patterns -- 50` only the 50×50 rows, `-- ties` only one
//! pattern (a row runs when its label contains every argument given).

use std::time::Instant;

use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

fn main() {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    println!(
        "{:<40} {:>9} {:>6} {:>8} {:>7} {:>7}  target",
        "case", "seconds", "exact", "lifting", "rounds", "bits"
    );
    for (side, target) in [(50usize, 5.0f64), (100, 60.0)] {
        for pattern in GridPattern::ALL {
            for gamma in ["0.99", "0.999"] {
                for noise in [NoiseModel::Paper, NoiseModel::Reference] {
                    let label =
                        format!("{side}x{side}/{}/{gamma}/{}", pattern.name(), noise.name());
                    if !filters.iter().all(|f| label.contains(f.as_str())) {
                        continue;
                    }
                    let grid = pattern_grid(side, side, pattern, CostRange::DEFAULT, 0)
                        .expect("a valid grid");
                    let gamma = Predictability::parse(gamma).expect("a valid gamma");
                    let problem = StochasticProblem::from_deterministic(&grid, noise, &gamma)
                        .expect("a valid model");
                    let start = Instant::now();
                    let o = optimum(&problem).expect("solvable");
                    let seconds = start.elapsed().as_secs_f64();
                    let s = &o.stats;
                    println!(
                        "{label:<40} {seconds:>9.2} {:>6} {:>8} {:>7} {:>7}  {}",
                        s.exact_iterations,
                        s.lifting_steps,
                        s.refinement_rounds,
                        s.refinement_bits,
                        if seconds <= target { "ok" } else { "OVER" }
                    );
                }
            }
        }
    }
}

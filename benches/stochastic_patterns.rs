//! The exact optimum over the grid pattern family (`truecost export --grid --pattern`):
//! every pattern × {2,500, 10⁴} states × γ ∈ {0.99, 0.999} × both noise models, each solved
//! once, one table row each: wall time, exact evaluations, lifting steps, mixed-precision
//! rounds and bits. Targets (release, 2 idle cores): 2,500 states ≤ 5 s and 10⁴ states ≤ 60 s
//! for every pattern; a row over its target is marked `OVER`.
//!
//! Each case runs from three sources: `grid` (the problem built from the grid and `γ`),
//! `file` (the same problem written as an explicit stochastic file and read back: no
//! commanded moves, the same number of exact evaluations is expected) and `reach` (the reach
//! objective on the file's problem: the probability by graph analysis, then the reported
//! policy's expected truecost and steps; its target is twice the optimum's). `pmax` times the
//! greatest reach probability alone (no target beyond the optimum's). `truecost` times the
//! truecost objective on the file's problem (`solve --objective truecost`: the optimum, the
//! success probabilities over its optimal actions and the reported policy's steps; target twice
//! the optimum's), and `texts` the optimum with every state's exact value printed (what `solve
//! --format json` writes; target twice the optimum's). `reduce` times only the reduction of
//! every state's value to lowest terms (`Optimum::cost_to_go_all`, after an untimed solve;
//! target a tenth of the optimum's), and prints beside it, in the `bits` column's place, the
//! seconds of reducing each value alone by one gcd with the common denominator.
//!
//! `cargo bench --bench stochastic_patterns` runs every row (about an hour);
//! `cargo bench --bench stochastic_patterns -- 50` only the 50×50 rows, `-- ties` only one
//! pattern, `-- /file` only the explicit files (a row runs when its label contains every
//! argument given).

use std::time::Instant;

use truecost::objectives::{max_reach, Model, Objective};
use truecost::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
use truecost::stochastic::file::{from_json, to_json, ProblemFile};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

fn main() {
    let filters: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    println!(
        "{:<46} {:>9} {:>6} {:>8} {:>7} {:>7}  target",
        "case", "seconds", "exact", "lifting", "rounds", "bits"
    );
    for (side, target) in [(50usize, 5.0f64), (100, 60.0)] {
        for pattern in GridPattern::ALL {
            for gamma in ["0.99", "0.999"] {
                for noise in [NoiseModel::Paper, NoiseModel::Reference] {
                    for source in [
                        "grid", "file", "reach", "pmax", "truecost", "texts", "reduce",
                    ] {
                        let label = format!(
                            "{side}x{side}/{}/{gamma}/{}/{source}",
                            pattern.name(),
                            noise.name()
                        );
                        if filters.iter().all(|f| label.contains(f.as_str())) {
                            row(&label, side, pattern, gamma, noise, target);
                        }
                    }
                }
            }
        }
    }
}

/// Builds one case, times its source (module docs) and prints its row.
fn row(
    label: &str,
    side: usize,
    pattern: GridPattern,
    gamma: &str,
    noise: NoiseModel,
    target: f64,
) {
    let grid = pattern_grid(side, side, pattern, CostRange::DEFAULT, 0).expect("a valid grid");
    let gamma = Predictability::parse(gamma).expect("a valid gamma");
    let built = StochasticProblem::from_deterministic(&grid, noise, &gamma).expect("a valid model");
    let problem = if label.ends_with("/grid") {
        built
    } else {
        match from_json(&to_json(&built, None)).expect("a written file reads back") {
            ProblemFile::Stochastic(p) => *p,
            ProblemFile::Deterministic(_) => unreachable!("the file lists outcomes"),
        }
    };
    if label.ends_with("/reduce") {
        return reduce_row(label, &problem, target / 10.0);
    }
    let start = Instant::now();
    let (stats, target) = if label.ends_with("/reach") {
        let model = Model::from_problem(problem, label.to_string());
        model.solve(&Objective::Reach).expect("solvable");
        (None, 2.0 * target)
    } else if label.ends_with("/pmax") {
        max_reach(&problem, &|_| true).expect("solvable");
        (None, target)
    } else if label.ends_with("/truecost") {
        let model = Model::from_problem(problem, label.to_string());
        model.solve(&Objective::Truecost).expect("solvable");
        (None, 2.0 * target)
    } else if label.ends_with("/texts") {
        let opt = optimum(&problem).expect("solvable");
        std::hint::black_box(opt.cost_to_go_texts());
        (Some(opt.stats), 2.0 * target)
    } else {
        (Some(optimum(&problem).expect("solvable").stats), target)
    };
    let seconds = start.elapsed().as_secs_f64();
    let verdict = if seconds <= target { "ok" } else { "OVER" };
    match stats {
        Some(s) => println!(
            "{label:<46} {seconds:>9.2} {:>6} {:>8} {:>7} {:>7}  {verdict}",
            s.exact_iterations, s.lifting_steps, s.refinement_rounds, s.refinement_bits,
        ),
        None => println!(
            "{label:<46} {seconds:>9.2} {:>6} {:>8} {:>7} {:>7}  {verdict}",
            "-", "-", "-", "-"
        ),
    }
}

/// The `reduce` row: the batched reduction of every state's value against reducing each value
/// alone (module docs); both must give the same values.
fn reduce_row(label: &str, problem: &StochasticProblem, target: f64) {
    let opt = optimum(problem).expect("solvable");
    let start = Instant::now();
    let batched = opt.cost_to_go_all();
    let seconds = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let alone: Vec<_> = (0..batched.len()).map(|x| opt.cost_to_go(x)).collect();
    let alone_seconds = start.elapsed().as_secs_f64();
    assert!(
        batched == alone.as_slice(),
        "{label}: the reductions differ"
    );
    let verdict = if seconds <= target { "ok" } else { "OVER" };
    println!(
        "{label:<46} {seconds:>9.2} {:>6} {:>8} {:>7} {alone_seconds:>7.2}  {verdict}",
        opt.stats.exact_iterations, opt.stats.lifting_steps, opt.stats.refinement_rounds,
    );
}

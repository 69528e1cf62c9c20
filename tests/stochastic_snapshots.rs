//! Pinned stochastic results (insta; files in the top-level `snapshots/`).
//!
//! * `stochastic_exact_optima` — the exact `G*(x1)` of every paper problem (0–5, 7–16), unit
//!   step costs, `γ ∈ {0.999, 0.99, 0.9, 0.7, 0.5}`, both noise models. The exact values are
//!   reduced fractions of up to ~1500 digits, so each is pinned by its numerator and
//!   denominator digit counts, the SHA-256 of its exact text `"numerator/denominator"` (what
//!   Python's `str(fractions.Fraction)` prints, so anyone can check it independently) and its
//!   decimal expansion to 30 significant digits.
//! * `stochastic_reference_vi` — the reference code's stochastic value iteration (reference
//!   noise, reference mode) on all 19 problems, `γ ∈ {0.999, 0.99}`, both schedules: sweeps and
//!   counted actions (Problem 10's are published; the others are pinned here), `V(x1)`, and the
//!   exact distance of the stopped values from the exact optimum of the exact twin.

use serde_json::json;
use sha2::{Digest, Sha256};

use truecost::problems::{StepCost, PAPER_PROBLEMS};
use truecost::stochastic::grid::{exact_grid, exact_twin, reference_grid};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::value_iteration::{value_iteration_f64, Schedule, ViOptions};
use truecost::stochastic::{decimal, NoiseModel, Predictability};
use truecost::value::{Extended, Rational};

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

const GAMMAS: [&str; 5] = ["0.999", "0.99", "0.9", "0.7", "0.5"];

fn fingerprint(v: &Extended) -> serde_json::Value {
    match v {
        Extended::Infinite => json!("inf"),
        Extended::Finite(r) => {
            let text = v.to_string();
            let hash: String = Sha256::digest(text.as_bytes())
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect();
            json!({
                "decimal": decimal(v, 30),
                "numerator_digits": r.numer().to_string().len(),
                "denominator_digits": r.denom().to_string().len(),
                "sha256": hash,
            })
        }
    }
}

#[test]
fn exact_optima_of_the_paper_problems() {
    let mut rows = Vec::new();
    for noise in [NoiseModel::Paper, NoiseModel::Reference] {
        for &id in &PAPER_PROBLEMS {
            for g in GAMMAS {
                let gamma = Predictability::parse(g).unwrap();
                let s = exact_grid(id, StepCost::Unit, noise, &gamma).unwrap();
                let o = optimum(&s).unwrap();
                let v = o.cost_to_go(s.initial());
                rows.push(json!({
                    "noise": noise.name(),
                    "problem": id,
                    "gamma": g,
                    "cost_to_go_initial": fingerprint(&v),
                }));
            }
        }
    }
    settings().bind(|| insta::assert_json_snapshot!("stochastic_exact_optima", rows));
}

#[test]
fn reference_stochastic_vi_on_all_problems() {
    let mut rows = Vec::new();
    for id in 0..19 {
        for g in ["0.999", "0.99"] {
            let gamma = Predictability::parse(g).unwrap();
            let grid = reference_grid(id, NoiseModel::Reference, &gamma).unwrap();
            let twin = exact_twin(id, NoiseModel::Reference, &gamma).unwrap();
            let opt = twin.as_ref().map(|t| optimum(t).unwrap());
            for schedule in [Schedule::Asynchronous, Schedule::Synchronous] {
                let run = value_iteration_f64(
                    &grid.problem,
                    &grid.float,
                    &ViOptions::reference(schedule),
                );
                let distance = opt.as_ref().map(|o| {
                    let d = o.distance(grid.problem.initial(), |x| {
                        let v = run.cost_to_go[x];
                        v.is_finite().then(|| Rational::from_float(v)).flatten()
                    });
                    json!({
                        "error_initial": d.initial.map(|e| decimal(&Extended::Finite(e), 6)),
                        "max_error": decimal(&Extended::Finite(d.max_abs), 6),
                        "states_compared": d.compared,
                    })
                });
                rows.push(json!({
                    "problem": id,
                    "gamma": g,
                    "schedule": if schedule == Schedule::Synchronous { "sync" } else { "async" },
                    "sweeps": run.sweeps,
                    "counted_actions": run.reference_counted,
                    "converged": run.converged,
                    "cost_to_go_initial": format!("{:?}", run.cost_to_go[grid.problem.initial()]),
                    "distance_from_exact_optimum": distance,
                }));
            }
        }
    }
    settings().bind(|| insta::assert_json_snapshot!("stochastic_reference_vi", rows));
}

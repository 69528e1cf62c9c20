//! Pinned outputs of `truecost reproduce deterministic` (insta; files in the top-level
//! `snapshots/`): every paper problem, every row, 3 seeded samples, the paper's 1000 episodes ×
//! 3000 steps, in exact and in reference mode — everything but the times. A change to any
//! count fails CI until reviewed with `cargo insta review`; CI never accepts snapshots itself.
//!
//! In reference mode the greedy (ε = 0), π and model-free rows are the published numbers (see
//! `learning_conformance.rs`); the π rows' samples here are the first three π runs of each
//! problem in a process that runs the paper's problems in order.

use assert_cmd::Command;
use serde_json::Value;

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

/// The JSON rows of a run, one compact line per row, with the times removed.
fn rows_without_times(mode: &str) -> String {
    let out = Command::cargo_bin("truecost")
        .unwrap()
        .args([
            "reproduce",
            "deterministic",
            "--samples",
            "3",
            "--seed",
            "2024",
            "--mode",
            mode,
            "--format",
            "json",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let rows: Value = serde_json::from_slice(&out).unwrap();
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 16 * 11);
    rows.iter()
        .map(|row| {
            let mut row = row.as_object().unwrap().clone();
            row.retain(|k, _| !k.ends_with("_s") && k != "mean_ns_per_action");
            serde_json::to_string(&row).unwrap()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn deterministic_experiment_exact_mode() {
    let rows = rows_without_times("exact");
    settings().bind(|| insta::assert_snapshot!("reproduce_deterministic_exact", rows));
}

#[test]
fn deterministic_experiment_reference_mode() {
    let rows = rows_without_times("reference");
    // The published greedy row of Problem 10 is in the pinned output.
    assert!(rows.contains(r#""algorithm":"q-learning","convergence_rate":0.0,"epsilon":0.0"#));
    settings().bind(|| insta::assert_snapshot!("reproduce_deterministic_reference", rows));
}

//! `check --coq` on real certificates: the exact truecost optimum of every paper problem (0 to
//! 18) under both noise models with `γ ∈ {0.9, 0.99}`, and FrozenLake 8x8, CliffWalking and
//! Taxi (truecost, and FrozenLake 8x8 discounted), each accepted by both checkers with
//! `"coq_checked": true` — the verified checker extracted to OCaml, built once for the run.

mod common;

use std::path::Path;
use std::sync::OnceLock;

use common::cli::{json, stdout};
use truecost::certificate::coq;

/// The extracted checker, built (or found in the cache) once, before any `check --coq` runs.
fn checker_ready() {
    static BUILT: OnceLock<Result<std::path::PathBuf, String>> = OnceLock::new();
    let built = BUILT.get_or_init(coq::extracted_checker);
    assert!(built.is_ok(), "{built:?}");
}

/// `solve <source> --algorithm exact <extra> --certificate` then `check <source> --coq`: both
/// checkers accept, and the report says the Coq checker ran.
fn certified_and_coq_checked(dir: &Path, source: &[&str], extra: &[&str], objective: &str) {
    let cert = dir.join(format!(
        "{}.cert.json",
        source.join("-").replace([':', '/', '='], "_")
    ));
    let c = cert.display().to_string();
    let mut args = vec!["solve"];
    args.extend_from_slice(source);
    args.extend_from_slice(&["--algorithm", "exact"]);
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--certificate", &c]);
    stdout(&args);
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    args.extend_from_slice(&[&c, "--coq", "--format", "json"]);
    let v = json(&args);
    assert_eq!(v["accepted"], true, "{source:?} {extra:?}: {v}");
    assert_eq!(v["coq_checked"], true, "{source:?} {extra:?}: {v}");
    assert_eq!(v["objective"], objective, "{source:?} {extra:?}: {v}");
    let _ = std::fs::remove_file(&cert);
}

fn paper_problems(noise: &str, gamma: &str) {
    checker_ready();
    let dir = tempfile::tempdir().unwrap();
    for id in 0..19 {
        let n = id.to_string();
        certified_and_coq_checked(
            dir.path(),
            &["--problem", &n],
            &["--gamma", gamma, "--noise", noise],
            "truecost",
        );
    }
}

#[test]
fn paper_problems_paper_noise_gamma_0_9() {
    paper_problems("paper", "0.9");
}

#[test]
fn paper_problems_paper_noise_gamma_0_99() {
    paper_problems("paper", "0.99");
}

#[test]
fn paper_problems_reference_noise_gamma_0_9() {
    paper_problems("reference", "0.9");
}

#[test]
fn paper_problems_reference_noise_gamma_0_99() {
    paper_problems("reference", "0.99");
}

#[test]
fn environments() {
    checker_ready();
    let dir = tempfile::tempdir().unwrap();
    for env in ["frozenlake:map=8x8", "cliffwalking", "taxi"] {
        certified_and_coq_checked(dir.path(), &["--env", env], &[], "truecost");
    }
    certified_and_coq_checked(
        dir.path(),
        &["--env", "frozenlake:map=8x8"],
        &["--objective", "discounted", "--alpha", "99/100"],
        "discounted",
    );
}

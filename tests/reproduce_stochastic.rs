//! `truecost reproduce stochastic`: formats and files naming noise, tolerance and seed; one-line
//! errors for bad arguments; and the pinned CI-sized seeded tables (insta, top-level
//! `snapshots/`), everything but the times.

use assert_cmd::Command;
use serde_json::Value;

fn truecost() -> Command {
    Command::cargo_bin("truecost").unwrap()
}

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

/// A small configuration: two tiny problems, two γ, both rate kinds, constant ε and ε-decay.
const SMALL: [&str; 18] = [
    "reproduce",
    "stochastic",
    "--problems",
    "16,3",
    "--gammas",
    "0.99,0.9",
    "--rhos",
    "0.99,1/n^0.8",
    "--epsilons",
    "0.9,decay",
    "--samples",
    "3",
    "--episodes",
    "200",
    "--max-steps",
    "1000",
    "--seed",
    "2024",
];

fn run(extra: &[&str]) -> Vec<u8> {
    let out = truecost()
        .args(SMALL)
        .args(extra)
        .assert()
        .success()
        .get_output()
        .clone();
    assert!(out.stderr.is_empty(), "no progress bar when not a terminal");
    out.stdout
}

/// The JSON rows, one compact line per row, times removed.
fn rows_without_times(stdout: &[u8]) -> String {
    let v: Value = serde_json::from_slice(stdout).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|row| {
            let mut row = row.as_object().unwrap().clone();
            row.retain(|k, _| !k.ends_with("_s") && k != "mean_ns_per_action");
            serde_json::to_string(&row).unwrap()
        })
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn ci_sized_table_paper_noise_relative_tolerance() {
    let out = run(&["--format", "json"]);
    let rows: Value = serde_json::from_slice(&out).unwrap();
    // 2 problems × 2 γ × (4 learning rows + 2 VIs).
    assert_eq!(rows.as_array().unwrap().len(), 2 * 2 * 6);
    for row in rows.as_array().unwrap() {
        assert_eq!(row["noise"], "paper");
        assert_eq!(row["tolerance"], "relative");
        assert_eq!(row["seed"], 2024);
    }
    let pinned = rows_without_times(&out);
    settings().bind(|| insta::assert_snapshot!("reproduce_stochastic_paper_relative", pinned));
}

#[test]
fn ci_sized_table_reference_noise_reference_tolerance() {
    let out = truecost()
        .args([
            "reproduce",
            "stochastic",
            "--problems",
            "16,10",
            "--gammas",
            "0.999",
            "--rhos",
            "0.99",
            "--epsilons",
            "0.9",
            "--samples",
            "2",
            "--noise",
            "reference",
            "--tolerance",
            "reference",
            "--seed",
            "5",
            "--format",
            "json",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let rows: Value = serde_json::from_slice(&out).unwrap();
    let rows_list = rows.as_array().unwrap();
    assert_eq!(rows_list.len(), 2 * 3);
    // Problem 10's VI rows are the published reference counts (reference/problem10.md).
    assert_eq!(rows_list[4]["mean_iterations"], 58.0);
    assert_eq!(rows_list[4]["mean_actions"], 178292.0);
    assert_eq!(rows_list[5]["mean_iterations"], 94.0);
    assert_eq!(rows_list[5]["mean_actions"], 288956.0);
    let pinned = rows_without_times(&out);
    settings().bind(|| insta::assert_snapshot!("reproduce_stochastic_reference", pinned));
}

#[test]
fn text_csv_markdown_and_files_name_noise_tolerance_and_seed() {
    let small = [
        "reproduce",
        "stochastic",
        "--problems",
        "16",
        "--gammas",
        "0.9",
        "--rhos",
        "0.5",
        "--epsilons",
        "1",
        "--samples",
        "2",
        "--episodes",
        "50",
        "--max-steps",
        "300",
        "--noise",
        "reference",
        "--seed",
        "3",
    ];
    let dir = tempfile::tempdir().unwrap();
    let out = truecost()
        .args(small)
        .args(["--out", dir.path().to_str().unwrap()])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with(
        "truecost reproduce stochastic — noise reference; tolerance relative; seed 3;"
    ));
    assert!(text.contains("Problem 16, γ = 0.9 (G*(x1) = "));
    let md = std::fs::read_to_string(dir.path().join("stochastic.md")).unwrap();
    assert!(md.starts_with(
        "# truecost reproduce stochastic — noise reference; tolerance relative; seed 3;"
    ));
    assert!(md.contains("| Q-learning (ρ=0.5, ε=1) |"));
    let csv = std::fs::read_to_string(dir.path().join("stochastic.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let noise = header.iter().position(|&c| c == "noise").unwrap();
    let tolerance = header.iter().position(|&c| c == "tolerance").unwrap();
    let seed = header.iter().position(|&c| c == "seed").unwrap();
    let data: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(data.len(), 3);
    for row in &data {
        assert_eq!(row.len(), header.len());
        assert_eq!(
            (row[noise], row[tolerance], row[seed]),
            ("reference", "relative", "3")
        );
    }
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("stochastic.json")).unwrap())
            .unwrap();
    assert_eq!(json.as_array().unwrap().len(), 3);
}

/// Runs a command that must fail with exactly one line on stderr.
fn fails_one_line(args: &[&str]) -> String {
    let out = truecost().args(args).assert().code(1).get_output().clone();
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(out.stdout.is_empty(), "{args:?}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    err
}

#[test]
fn bad_arguments_give_one_line_errors() {
    let cases: [(&[&str], &str); 10] = [
        (&["--gammas", "1.5"], "gamma"),
        (&["--gammas", "0"], "gamma"),
        (&["--rhos", "0"], "rho"),
        (&["--rhos", "1.2"], "rho"),
        (&["--rhos", "1/n^0.5"], "omega"),
        (&["--epsilons", "1.1"], "ε"),
        (&["--samples", "0"], "samples"),
        (&["--problems", "19"], "unknown problem 19"),
        (&["--problems", "16,16"], "listed twice"),
        (&["--episodes", "0"], "episodes"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["reproduce", "stochastic", "--problems", "16"];
        if extra[0] == "--problems" {
            args.truncate(2);
        }
        args.extend_from_slice(extra);
        let err = fails_one_line(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    truecost()
        .args(["reproduce", "stochastic", "--noise", "loud"])
        .assert()
        .code(2);
}

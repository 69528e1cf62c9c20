//! `truecost reproduce deterministic`: formats, files, reproducibility across thread counts,
//! and one-line errors for every bad argument.

use assert_cmd::Command;
use serde_json::Value;

fn truecost() -> Command {
    Command::cargo_bin("truecost").unwrap()
}

/// A small, fast configuration: the two tiny problems and Problem 0, short runs (so that the π
/// rows need few digits).
const SMALL: [&str; 10] = [
    "reproduce",
    "deterministic",
    "--problems",
    "16,8,0",
    "--samples",
    "3",
    "--episodes",
    "150",
    "--max-steps",
    "200",
];

fn run(extra: &[&str]) -> Vec<u8> {
    let out = truecost()
        .args(SMALL)
        .args(extra)
        .assert()
        .success()
        .get_output()
        .clone();
    assert!(
        out.stderr.is_empty(),
        "no progress bar when stderr is not a terminal"
    );
    out.stdout
}

/// The rows of a JSON output with every time field removed (times are the only numbers that
/// are not a pure function of the settings).
fn without_times(stdout: &[u8]) -> Vec<Value> {
    let v: Value = serde_json::from_slice(stdout).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|row| {
            let mut row = row.as_object().unwrap().clone();
            row.retain(|k, _| !k.ends_with("_s") && k != "mean_ns_per_action");
            Value::Object(row)
        })
        .collect()
}

#[test]
fn json_rows_have_the_required_fields_and_state_mode_and_seed() {
    let rows = without_times(&run(&["--format", "json", "--seed", "7"]));
    assert_eq!(rows.len(), 3 * 11);
    let full: Value = serde_json::from_slice(&run(&["--format", "json", "--seed", "7"])).unwrap();
    for row in full.as_array().unwrap() {
        for key in [
            "problem",
            "algorithm",
            "epsilon",
            "samples",
            "mean_time_s",
            "std_time_s",
            "convergence_rate",
            "mean_actions",
            "mean_iterations",
            "shortest_path",
            "longest_path",
            "mean_actions_initial_optimal",
            "mean_actions_goal_discovered",
            "mean_ns_per_action",
        ] {
            assert!(row.get(key).is_some(), "{key} missing");
        }
        assert_eq!(row["mode"], "exact");
        assert_eq!(row["seed"], 7);
        assert_eq!(row["samples"], 3);
        if row["algorithm"].as_str().unwrap().starts_with("model-free") {
            assert_eq!(row["epsilon"], Value::Null);
        } else {
            assert!(row["epsilon"].is_number());
        }
    }
    // Problem order is the order given; rows in the paper's order.
    let order: Vec<(u64, String)> = rows
        .iter()
        .map(|r| {
            (
                r["problem"].as_u64().unwrap(),
                r["algorithm"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(order[0], (16, "q-learning".to_string()));
    assert_eq!(order[6], (16, "q-learning-pi".to_string()));
    assert_eq!(order[7], (16, "q-learning-epsilon-decay".to_string()));
    assert_eq!(order[10], (16, "model-free-vi".to_string()));
    assert_eq!(order[11].0, 8);
    assert_eq!(order[22].0, 0);
}

#[test]
fn same_seed_same_output_with_one_or_two_threads_and_the_seed_matters() {
    let one = without_times(&run(&["--format", "json", "--threads", "1"]));
    let two = without_times(&run(&["--format", "json", "--threads", "2"]));
    assert_eq!(one, two);
    let again = without_times(&run(&["--format", "json", "--threads", "2"]));
    assert_eq!(two, again);
    // A different seed changes the random rows (ε = 0.5 on Problem 0) but not the greedy row.
    let other = without_times(&run(&["--format", "json", "--threads", "2", "--seed", "1"]));
    let find = |rows: &[Value], alg: &str, eps: f64| {
        rows.iter()
            .find(|r| r["problem"] == 0 && r["algorithm"] == alg && r["epsilon"] == eps)
            .unwrap()
            .clone()
    };
    assert_ne!(
        find(&one, "q-learning", 0.5)["mean_actions"],
        find(&other, "q-learning", 0.5)["mean_actions"]
    );
    let mut greedy = find(&other, "q-learning", 0.0);
    assert_eq!(greedy["seed"], 1);
    greedy["seed"] = 0.into();
    assert_eq!(find(&one, "q-learning", 0.0), greedy);
}

#[test]
fn reference_mode_reports_the_published_greedy_counts_of_problem_10() {
    let out = truecost()
        .args([
            "reproduce",
            "deterministic",
            "--problems",
            "10",
            "--samples",
            "1",
            "--mode",
            "reference",
            "--episodes",
            "1000",
            "--format",
            "json",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let rows: Value = serde_json::from_slice(&out).unwrap();
    let greedy = &rows[0];
    assert_eq!(greedy["algorithm"], "q-learning");
    assert_eq!(greedy["epsilon"], 0.0);
    assert_eq!(greedy["mode"], "reference");
    assert_eq!(greedy["mean_iterations"], 999.0);
    assert_eq!(greedy["mean_actions"], 101214.0);
    assert_eq!(greedy["mean_actions_goal_discovered"], 2015.0);
    assert_eq!(greedy["mean_actions_initial_optimal"], 52000.0);
    assert_eq!(greedy["convergence_rate"], 0.0);
    assert_eq!(greedy["shortest_path"], 64);
    let dijkstra = &rows[8];
    assert_eq!(dijkstra["algorithm"], "model-free-dijkstra");
    assert_eq!(dijkstra["mean_actions"], 4423.0);
    assert_eq!(dijkstra["mean_iterations"], 331.0);
}

#[test]
fn text_csv_markdown_and_out_files() {
    let text = String::from_utf8(run(&[])).unwrap();
    assert!(text.starts_with("truecost reproduce deterministic — mode exact; seed 0; 3 samples"));
    assert!(text.contains("model: exact (paper text)"));
    assert!(text.contains("Problem 16"));
    assert!(text.contains("Q-learning, π plan (ε=1)"));
    assert!(text.contains("Model-free synchronous VI"));

    let csv = String::from_utf8(run(&["--format", "csv"])).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "problem");
    assert!(header.contains(&"mean_actions_initial_optimal"));
    assert!(header.contains(&"mode") && header.contains(&"seed"));
    assert_eq!(lines.count(), 33);

    let md = String::from_utf8(run(&["--format", "markdown"])).unwrap();
    assert!(md.starts_with("# truecost reproduce deterministic"));
    assert!(md.contains("## Problem 8"));
    assert!(md.contains("| Model-free Dijkstra |"));

    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("results");
    let stdout = run(&["--format", "json", "--out", out.to_str().unwrap()]);
    let json = std::fs::read(out.join("deterministic.json")).unwrap();
    assert_eq!(without_times(&json), without_times(&stdout));
    let md = std::fs::read_to_string(out.join("deterministic.md")).unwrap();
    assert!(md.contains("## Problem 0"));
    let csv = std::fs::read_to_string(out.join("deterministic.csv")).unwrap();
    assert_eq!(csv.lines().count(), 34);
}

#[test]
fn learning_rows_are_not_run_where_the_goal_is_unreachable() {
    let out = truecost()
        .args([
            "reproduce",
            "deterministic",
            "--problems",
            "6",
            "--samples",
            "2",
            "--format",
            "json",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let rows: Value = serde_json::from_slice(&out).unwrap();
    for row in rows.as_array().unwrap() {
        let learning = row["algorithm"].as_str().unwrap().starts_with("q-learning");
        if learning {
            assert_eq!(row["samples"], 0);
            assert!(row["note"].as_str().unwrap().contains("unreachable"));
            assert_eq!(row["mean_actions"], Value::Null);
        } else {
            assert_eq!(row["samples"], 2);
            // The planners' values equal G* (+inf everywhere): converged.
            assert_eq!(row["convergence_rate"], 1.0);
            assert_eq!(row["goal_reached_rate"], 0.0);
        }
    }
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
    let base = ["reproduce", "deterministic"];
    let with = |extra: &[&str]| -> Vec<String> {
        base.iter()
            .chain(extra)
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
    };
    let cases: [(&[&str], &str); 9] = [
        (&["--samples", "0"], "samples"),
        (&["--samples", "2000000"], "samples"),
        (&["--problems", "19"], "unknown problem 19"),
        (&["--problems", "1,1"], "listed twice"),
        (&["--episodes", "0"], "episodes"),
        (&["--max-steps", "0"], "steps"),
        (&["--threads", "0"], "thread"),
        (
            &["--episodes", "4000000", "--max-steps", "4000000"],
            "exceeds",
        ),
        (
            &["--mode", "reference", "--step-cost", "euclidean"],
            "--step-cost",
        ),
    ];
    for (extra, needle) in cases {
        let args = with(extra);
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let err = fails_one_line(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // An output directory that cannot be created (a file is in the way).
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("file");
    std::fs::write(&file, "x").unwrap();
    let err = fails_one_line(&[
        "reproduce",
        "deterministic",
        "--problems",
        "16",
        "--samples",
        "1",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(err.contains("cannot create output directory"), "{err}");
    // Usage errors are clap's (exit 2), e.g. a non-number.
    truecost()
        .args(["reproduce", "deterministic", "--samples", "many"])
        .assert()
        .code(2);
    truecost()
        .args(["reproduce", "deterministic", "--problems", "a,b"])
        .assert()
        .code(2);
}

//! `--env`, `--objective`, `compare`, `export` and `problems --env` on the command line.

mod common;

use common::cli::{fails, fails_one_line, json, stdout};

#[test]
fn solve_env_reports_each_objective_with_its_key() {
    let v = json(&[
        "solve",
        "--env",
        "frozenlake",
        "--algorithm",
        "exact",
        "--objective",
        "reach",
        "--format",
        "json",
    ]);
    assert_eq!(v["reach_probability_initial"], "14/17");
    assert_eq!(v["success_probability"], "14/17");
    assert_eq!(v["expected_truecost"], "inf");
    let v = json(&[
        "solve",
        "--env",
        "frozenlake",
        "--algorithm",
        "exact",
        "--objective",
        "truecost",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "inf");
    assert_eq!(v["success_probability"]["min"], "0");
    assert_eq!(v["success_probability"]["max"], "14/17");
    let v = json(&[
        "solve",
        "--env",
        "frozenlake:slippery=false",
        "--algorithm",
        "exact",
        "--objective",
        "discounted",
        "--alpha",
        "0.9",
        "--format",
        "json",
    ]);
    assert_eq!(v["discounted_value_initial"], "59049/100000");
    assert_eq!(v["policy"].as_array().unwrap().len(), 16);
    let v = json(&[
        "solve",
        "--env",
        "taxi",
        "--algorithm",
        "exact",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "1307/100");
    assert_eq!(v["terminal_bonus"], "-20");
    assert_eq!(v["initial_states"], 300);
    let text = stdout(&[
        "solve",
        "--env",
        "cliffwalking",
        "--algorithm",
        "exact",
        "--objective",
        "truecost",
    ]);
    assert!(text.contains("cost_to_go_initial        13 ~ 13"), "{text}");
}

#[test]
fn objectives_apply_to_paper_problems_too() {
    let v = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "exact",
        "--objective",
        "reach",
        "--format",
        "json",
    ]);
    assert_eq!(v["reach_probability_initial"], "1");
    let det = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "exact",
        "--format",
        "json",
        "--objective",
        "truecost",
    ]);
    let plain = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    assert_eq!(
        det["cost_to_go_initial"].as_str().unwrap(),
        plain["cost_to_go_initial"]
            .as_str()
            .unwrap_or(&plain["cost_to_go_initial"].to_string())
    );
}

#[test]
fn compare_prints_every_format() {
    let v = json(&[
        "compare",
        "--env",
        "frozenlake:map=8x8",
        "--alphas",
        "0.9",
        "--format",
        "json",
    ]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    assert_eq!(rows[0]["success_probability"], "1");
    assert_eq!(rows[2]["expected_truecost"], "inf");
    let md = stdout(&[
        "compare",
        "--env",
        "cliffwalking",
        "--alphas",
        "0.9",
        "--format",
        "markdown",
    ]);
    assert!(md.contains("| truecost | 13 | 1 | 13 | 13 |"), "{md}");
    let tex = stdout(&[
        "compare",
        "--env",
        "frozenlake",
        "--alphas",
        "0.5",
        "--format",
        "latex",
    ]);
    assert!(
        tex.contains("\\begin{tabular}") && tex.contains("$\\infty$"),
        "{tex}"
    );
    let text = stdout(&["compare", "--env", "frozenlake", "--alphas", "0.9"]);
    assert!(text.contains("0.823529"), "{text}");
}

#[test]
fn export_round_trips_through_a_problem_file() {
    let dir = tempfile::tempdir().unwrap();
    for (spec, expected) in [("taxi", "1307/100"), ("frozenlake:map=8x8", "")] {
        let out = dir.path().join("env.json");
        let out = out.to_str().unwrap();
        stdout(&["export", "--env", spec, "--out", out]);
        let via_file = json(&[
            "solve",
            "--file",
            out,
            "--algorithm",
            "exact",
            "--objective",
            "truecost",
            "--format",
            "json",
        ]);
        let direct = json(&[
            "solve",
            "--env",
            spec,
            "--algorithm",
            "exact",
            "--format",
            "json",
        ]);
        assert_eq!(
            via_file["cost_to_go_initial"], direct["cost_to_go_initial"],
            "{spec}"
        );
        if !expected.is_empty() {
            assert_eq!(direct["cost_to_go_initial"], expected);
        }
    }
}

#[test]
fn problems_env_lists_facts() {
    let v = json(&[
        "problems",
        "--env",
        "frozenlake:map=8x8",
        "--format",
        "json",
    ]);
    assert_eq!(
        (
            v["states"].as_u64(),
            v["goals"].as_u64(),
            v["traps"].as_u64()
        ),
        (Some(64), Some(1), Some(10))
    );
    assert_eq!(v["reach_probability_initial"], "1");
}

#[test]
fn bad_input_fails_cleanly() {
    for args in [
        vec!["solve", "--env", "lake", "--algorithm", "exact"],
        vec![
            "solve",
            "--env",
            "frozenlake",
            "--algorithm",
            "exact",
            "--objective",
            "discounted",
        ],
        vec![
            "solve",
            "--env",
            "frozenlake",
            "--algorithm",
            "exact",
            "--objective",
            "discounted",
            "--alpha",
            "1",
        ],
        vec!["solve", "--env", "frozenlake", "--algorithm", "vi"],
        vec![
            "solve",
            "--env",
            "frozenlake",
            "--algorithm",
            "exact",
            "--gamma",
            "0.9",
        ],
        vec![
            "solve",
            "--env",
            "frozenlake:map=/nonexistent/map.txt",
            "--algorithm",
            "exact",
        ],
        vec!["compare", "--env", "taxi", "--alphas", "0.9,x"],
        vec!["compare"],
        vec![
            "export",
            "--env",
            "taxi",
            "--out",
            "/nonexistent/dir/x.json",
        ],
    ] {
        let err = fails_one_line(&args);
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
    fails(
        &[
            "solve",
            "--env",
            "taxi",
            "--algorithm",
            "exact",
            "--objective",
            "cheapest",
        ],
        2,
    );
    fails(
        &[
            "solve",
            "--env",
            "taxi",
            "--problem",
            "3",
            "--algorithm",
            "exact",
        ],
        2,
    );
}

#[test]
fn render_env_writes_svg_and_png() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("fl.svg");
    let svg = svg.to_str().unwrap();
    stdout(&[
        "render",
        "--env",
        "frozenlake",
        "--overlay",
        "policy",
        "--objective",
        "reach",
        "--out",
        svg,
    ]);
    let text = std::fs::read_to_string(svg).unwrap();
    assert!(text.contains("success probability 0.823529"), "caption");
    let png = dir.path().join("cw.png");
    stdout(&[
        "render",
        "--env",
        "cliffwalking",
        "--overlay",
        "values",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // Taxi's policy needs a slice (tests/taxi_gaps.rs draws them).
    fails_one_line(&[
        "render",
        "--env",
        "taxi",
        "--overlay",
        "policy",
        "--out",
        svg,
    ]);
    fails_one_line(&[
        "render",
        "--env",
        "frozenlake",
        "--overlay",
        "visits",
        "--out",
        svg,
    ]);
}

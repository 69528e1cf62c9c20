//! The command line: outputs and every bad argument (one-line error, non-zero exit, no panic).

mod common;

use common::cli::{fails, fails_one_line, json, truecost};
use serde_json::Value;

#[test]
fn problems_json_lists_all_19_with_the_required_fields() {
    let v = json(&["problems", "--format", "json"]);
    let list = v.as_array().unwrap();
    assert_eq!(list.len(), 19);
    for (i, p) in list.iter().enumerate() {
        assert_eq!(p["id"], i);
        assert_eq!(p["grid_nodes"], 400);
        for key in ["states", "edges", "initial", "goal", "optimal_moves"] {
            assert!(p.get(key).is_some(), "{key}");
        }
    }
    assert_eq!(list[10]["states"], 339);
    assert_eq!(list[10]["edges"], 592);
    assert_eq!(list[10]["optimal_moves"], 63);
    assert_eq!(list[6]["optimal_moves"], Value::Null);
}

#[test]
fn problems_other_formats() {
    let csv = truecost()
        .args(["problems", "--format", "csv"])
        .assert()
        .success();
    let text = String::from_utf8(csv.get_output().stdout.clone()).unwrap();
    assert_eq!(text.lines().count(), 20);
    assert!(text.starts_with("id,grid_nodes,states,edges,initial,goal,optimal_moves"));
    assert!(text.contains("\n10,400,339,592,41,206,63,true\n"));
    let md = truecost()
        .args(["problems", "--format", "markdown"])
        .assert()
        .success();
    let text = String::from_utf8(md.get_output().stdout.clone()).unwrap();
    assert!(text.contains("| 3 | 400 | 135 | 167 | 38 | 398 | 90 | true |"));
    let plain = truecost().arg("problems").assert().success();
    let text = String::from_utf8(plain.get_output().stdout.clone()).unwrap();
    assert!(text.contains("exact (paper text)"));
    assert!(text.contains("unreachable"));
}

#[test]
fn solve_json_exact_and_reference() {
    let v = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    assert_eq!(v["reachable"], true);
    assert_eq!(v["cost_to_go_initial"], "63");
    assert_eq!(v["path"].as_array().unwrap().len(), 64);
    assert_eq!(v["path"][0], 41);
    assert_eq!(v["path"][63], 206);
    assert_eq!(v["mode"], "exact");

    let v = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "vi",
        "--step-cost",
        "euclidean",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "50400/19");

    let v = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "async-vi",
        "--model-free",
        "--mode",
        "reference",
        "--format",
        "json",
    ]);
    assert_eq!(v["mode"], "reference");
    assert_eq!(v["iterations"], 56);
    assert_eq!(v["actions"], 69570);
    let g = v["cost_to_go_initial"].as_f64().unwrap();
    assert!((g - 63.0 * 800.0 / 19.0).abs() < 1e-9);
}

#[test]
fn solve_unreachable_is_a_normal_answer() {
    let v = json(&[
        "solve",
        "--problem",
        "6",
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    assert_eq!(v["reachable"], false);
    assert_eq!(v["cost_to_go_initial"], "inf");
    assert_eq!(v["path"], Value::Array(vec![]));
    let text = truecost()
        .args(["solve", "--problem", "6", "--algorithm", "vi"])
        .assert()
        .success();
    let text = String::from_utf8(text.get_output().stdout.clone()).unwrap();
    assert!(text.contains("no goal is reachable"));
}

#[test]
fn solve_files_from_the_examples() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let v = json(&[
        "solve",
        "--file",
        &format!("{dir}/problems/line.json"),
        "--algorithm",
        "async-vi",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "5/2");
    assert_eq!(v["path"], serde_json::json!([0, 1, 2, 3]));
    let v = json(&[
        "solve",
        "--file",
        &format!("{dir}/problems/zero-cost-cycle.json"),
        "--algorithm",
        "vi",
        "--model-free",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "0");
    assert_eq!(v["path"], serde_json::json!([0, 1, 2]));
    let v = json(&[
        "solve",
        "--file",
        &format!("{dir}/problems/trap.json"),
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    assert_eq!(v["reachable"], false);
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        vec!["solve", "--algorithm", "dijkstra"],
        vec![
            "solve",
            "--problem",
            "1",
            "--file",
            "x.json",
            "--algorithm",
            "vi",
        ],
        vec!["solve", "--problem", "-1", "--algorithm", "vi"],
        vec!["solve", "--problem", "ten", "--algorithm", "vi"],
        vec!["solve", "--problem", "1", "--algorithm", "bfs"],
        vec!["solve", "--problem", "1"],
        vec![
            "solve",
            "--problem",
            "1",
            "--algorithm",
            "vi",
            "--mode",
            "python",
        ],
        vec![
            "solve",
            "--problem",
            "1",
            "--algorithm",
            "vi",
            "--step-cost",
            "manhattan",
        ],
        vec![
            "solve",
            "--problem",
            "1",
            "--algorithm",
            "vi",
            "--format",
            "xml",
        ],
        vec!["problems", "--format", "yaml"],
        vec!["frobnicate"],
    ] {
        let err = fails(&args, 2);
        assert!(err.contains("error"), "{args:?}: {err}");
    }
}

#[test]
fn bad_input_errors_exit_1_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, text: &str| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    };
    let err = fails_one_line(&["solve", "--problem", "19", "--algorithm", "vi"]);
    assert!(err.contains("unknown problem 19"), "{err}");
    let err = fails_one_line(&["solve", "--file", "/nonexistent.json", "--algorithm", "vi"]);
    assert!(err.contains("cannot read"), "{err}");
    let cases = [
        ("garbage.json", "{ not json", "not valid"),
        (
            "negative.json",
            r#"{"initial":0,"goals":[1],"actions":[[{"to":1,"cost":"-1"}],[]]}"#,
            "negative",
        ),
        (
            "float.json",
            r#"{"initial":0,"goals":[1],"actions":[[{"to":1,"cost":0.1}],[]]}"#,
            "not valid",
        ),
        (
            "empty.json",
            r#"{"initial":0,"goals":[2],"actions":[[{"to":2,"cost":"1"}],[],[]]}"#,
            "empty action set",
        ),
        (
            "nogoal.json",
            r#"{"initial":0,"goals":[],"actions":[[{"to":0,"cost":"1"}]]}"#,
            "no goal",
        ),
        (
            "range.json",
            r#"{"initial":0,"goals":[1],"actions":[[{"to":7,"cost":"1"}],[]]}"#,
            "does not exist",
        ),
        (
            "initial.json",
            r#"{"initial":5,"goals":[1],"actions":[[{"to":1,"cost":"1"}],[]]}"#,
            "initial state 5",
        ),
        (
            "cost.json",
            r#"{"initial":0,"goals":[1],"actions":[[{"to":1,"cost":"one"}],[]]}"#,
            "not an exact number",
        ),
    ];
    for (name, text, expect) in cases {
        let path = write(name, text);
        let err = fails_one_line(&["solve", "--file", &path, "--algorithm", "dijkstra"]);
        assert!(err.contains(expect), "{name}: {err}");
    }
    let ok = write(
        "ok.json",
        r#"{"initial":0,"goals":[1],"actions":[[{"to":1,"cost":"1"}],[]]}"#,
    );
    let err = fails_one_line(&[
        "solve",
        "--file",
        &ok,
        "--algorithm",
        "vi",
        "--mode",
        "reference",
    ]);
    assert!(err.contains("paper's problems"), "{err}");
    let err = fails_one_line(&[
        "solve",
        "--file",
        &ok,
        "--algorithm",
        "vi",
        "--step-cost",
        "unit",
    ]);
    assert!(err.contains("--step-cost"), "{err}");
    let err = fails_one_line(&[
        "solve",
        "--problem",
        "1",
        "--algorithm",
        "vi",
        "--mode",
        "reference",
        "--step-cost",
        "euclidean",
    ]);
    assert!(err.contains("--step-cost"), "{err}");
}

#[test]
fn help_is_available_everywhere() {
    for args in [
        vec!["--help"],
        vec!["solve", "--help"],
        vec!["problems", "--help"],
    ] {
        let out = truecost().args(&args).assert().success();
        let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
        assert!(text.contains("Usage"), "{args:?}");
    }
}

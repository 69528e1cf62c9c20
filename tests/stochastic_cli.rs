//! `truecost solve` in the stochastic model: outputs name the noise model, exact values are
//! exact strings, the published reference counts come out, and every bad combination of options
//! fails with one line and exit code 1 (usage errors 2).

mod common;

use common::cli::{fails, json, stdout as text};

#[test]
fn exact_optimum_of_a_file_problem_is_an_exact_string() {
    let dir = env!("CARGO_MANIFEST_DIR");
    // problems/line.json: 0 -1-> 1 -1/2-> 2 -1-> 3 (goal), back moves 0 <- 1 (cost 1), 1 <- 2
    // (cost 1/2), shortcut 0 -> 3 (7/2). At γ = 1 the deterministic optimum 5/2.
    let v = json(&[
        "solve",
        "--file",
        &format!("{dir}/problems/line.json"),
        "--algorithm",
        "exact",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "5/2");
    assert_eq!(v["gamma"], "1");
    assert_eq!(v["noise"], "paper");
    assert_eq!(v["algorithm"], "exact");
}

#[test]
fn the_readme_example_file_by_hand() {
    // G(0) = 1 + 0.9 G(1) + 0.1 G(0) ⇒ G(0) = 10/9 + G(1); at 1 the slippery move to the goal:
    // G(1) = 1 + G(0)/4 ⇒ G(1) = 46/27, G(0) = 76/27 (stepping back, 1/2 + G(0), is worse).
    let dir = env!("CARGO_MANIFEST_DIR");
    let v = json(&[
        "solve",
        "--file",
        &format!("{dir}/problems/slippery.json"),
        "--algorithm",
        "exact",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go"], serde_json::json!(["76/27", "46/27", "0"]));
    assert_eq!(v["policy_action"], serde_json::json!([0, 0, null]));
}

#[test]
fn hand_derived_star_through_a_stochastic_file() {
    // The star of tests/stochastic.rs written with explicit outcomes (paper model, γ = 1/2):
    // G*(0) = 10/3.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("star.json");
    std::fs::write(
        &path,
        r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [1], "actions": [
            [{"cost": "1", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 2, "p": "1/6"}, {"to": 3, "p": "1/6"}, {"to": 0, "p": "1/6"}]}],
            [],
            [{"cost": "1", "outcomes": [{"to": 0, "p": "0.5"}, {"to": 2, "p": "0.5"}]}],
            [{"cost": "1", "outcomes": [{"to": 0, "p": "0.5"}, {"to": 3, "p": "0.5"}]}]
        ]}"#,
    )
    .unwrap();
    let p = path.display().to_string();
    let v = json(&[
        "solve",
        "--file",
        &p,
        "--algorithm",
        "exact",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "10/3");
    assert_eq!(v["noise"], "explicit");
    assert_eq!(
        v["cost_to_go"],
        serde_json::json!(["10/3", "0", "16/3", "16/3"])
    );
    // Stochastic VI on the file (selected by the file's outcomes alone).
    let v = json(&[
        "solve",
        "--file",
        &p,
        "--algorithm",
        "vi",
        "--format",
        "json",
    ]);
    assert_eq!(v["value_iteration"]["converged"], true);
    assert!(v["value_iteration"]["error_initial"]
        .as_str()
        .unwrap()
        .starts_with('-'));
    // --gamma does not apply to a file with its own probabilities.
    let err = fails(
        &[
            "solve",
            "--file",
            &p,
            "--algorithm",
            "exact",
            "--gamma",
            "0.9",
        ],
        1,
    );
    assert!(err.contains("lists its own outcome probabilities"), "{err}");
}

#[test]
fn published_reference_counts_through_the_cli() {
    for (g, alg, sweeps, counted) in [
        ("0.999", "async-vi", 58, 178292),
        ("0.999", "vi", 94, 288956),
        ("0.99", "async-vi", 69, 212106),
        ("0.99", "vi", 112, 344288),
    ] {
        let v = json(&[
            "solve",
            "--problem",
            "10",
            "--gamma",
            g,
            "--noise",
            "reference",
            "--mode",
            "reference",
            "--algorithm",
            alg,
            "--format",
            "json",
        ]);
        assert_eq!(v["value_iteration"]["sweeps"], sweeps);
        assert_eq!(v["value_iteration"]["counted_actions"], counted);
        assert_eq!(v["noise"], "reference");
        assert_eq!(v["mode"], "reference");
        assert!(v["cost_to_go_initial"].is_f64());
        assert!(v["optimum"]["measured_on"]
            .as_str()
            .unwrap()
            .contains("exact twin"));
    }
}

#[test]
fn text_output_names_the_noise_model_and_gamma() {
    let t = text(&[
        "solve",
        "--problem",
        "10",
        "--gamma",
        "0.9",
        "--algorithm",
        "exact",
    ]);
    assert!(t.contains("noise paper"), "{t}");
    assert!(t.contains("gamma 9/10"), "{t}");
    assert!(t.contains("exact optimum: policy iteration"), "{t}");
    let t = text(&[
        "solve",
        "--problem",
        "10",
        "--gamma",
        "0.9",
        "--noise",
        "reference",
        "--algorithm",
        "async-vi",
    ]);
    assert!(t.contains("noise reference"), "{t}");
    assert!(t.contains("stopped after"), "{t}");
    assert!(t.contains("G*(x1)"), "{t}");
    let t = text(&[
        "solve",
        "--problem",
        "6",
        "--gamma",
        "0.9",
        "--algorithm",
        "exact",
    ]);
    assert!(
        t.contains("no policy reaches a goal with probability 1"),
        "{t}"
    );
}

#[test]
fn json_exact_value_is_a_reduced_fraction_whose_decimal_matches() {
    let v = json(&[
        "solve",
        "--problem",
        "8",
        "--gamma",
        "0.99",
        "--algorithm",
        "exact",
        "--format",
        "json",
    ]);
    let exact = v["cost_to_go_initial"].as_str().unwrap();
    let (n, d) = exact.split_once('/').unwrap();
    let decimal = v["cost_to_go_initial_decimal"].as_str().unwrap();
    // Long division by hand (independent of the code's decimal routine): the first 12 digits.
    let n: num_bigint::BigInt = n.parse().unwrap();
    let d: num_bigint::BigInt = d.parse().unwrap();
    let scaled = n * num_bigint::BigInt::from(10u64).pow(8) / d;
    let digits = scaled.to_string();
    let expected = format!(
        "{}.{}",
        &digits[..digits.len() - 8],
        &digits[digits.len() - 8..]
    );
    assert!(
        decimal.starts_with(&expected[..expected.len() - 1]),
        "{decimal} vs {expected}"
    );
    assert_eq!(
        v["optimum"]["numerator_digits"],
        exact.split_once('/').unwrap().0.len()
    );
}

#[test]
fn bad_stochastic_options_fail_with_one_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["--gamma", "0"], "(0, 1]"),
        (&["--gamma", "1.5"], "(0, 1]"),
        (&["--gamma", "-0.5"], "(0, 1]"),
        (&["--gamma", "zero"], "not an exact number"),
        (&["--noise", "reference"], "give --gamma too"),
        (&["--gamma", "0.9", "--model-free"], "--model-free"),
        (&["--gamma", "0.9", "--tolerance", "-1"], "tolerance"),
        (&["--gamma", "0.9", "--tolerance", "x"], "tolerance"),
        (&["--gamma", "0.9", "--max-sweeps", "0"], "at least 1"),
    ];
    for (extra, expect) in cases {
        let mut args = vec!["solve", "--problem", "10", "--algorithm", "vi"];
        args.extend_from_slice(extra);
        let err = fails(&args, 1);
        assert!(err.contains(expect), "{args:?}: {err}");
    }
    let err = fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "dijkstra",
            "--gamma",
            "0.9",
        ],
        1,
    );
    assert!(err.contains("deterministic model"), "{err}");
    let err = fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "exact",
            "--tolerance",
            "1",
        ],
        1,
    );
    assert!(err.contains("apply to --algorithm vi"), "{err}");
    let err = fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "exact",
            "--mode",
            "reference",
        ],
        1,
    );
    assert!(err.contains("exact counterpart"), "{err}");
    let err = fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "vi",
            "--gamma",
            "0.9",
            "--mode",
            "reference",
            "--arithmetic",
            "exact",
        ],
        1,
    );
    assert!(err.contains("f64"), "{err}");
    let err = fails(&["solve", "--problem", "19", "--algorithm", "exact"], 1);
    assert!(err.contains("unknown problem 19"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.json");
    std::fs::write(
        &bad,
        r#"{"initial":0,"goals":[1],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"0.6"},{"to":0,"p":"0.3"}]}],[]]}"#,
    )
    .unwrap();
    let err = fails(
        &[
            "solve",
            "--file",
            &bad.display().to_string(),
            "--algorithm",
            "exact",
        ],
        1,
    );
    assert!(err.contains("sum to 9/10, not 1"), "{err}");
    // A stochastic file without --gamma still goes to the stochastic solvers (and its error).
    let err = fails(
        &[
            "solve",
            "--file",
            &bad.display().to_string(),
            "--algorithm",
            "vi",
        ],
        1,
    );
    assert!(err.contains("sum to 9/10, not 1"), "{err}");
    // Usage errors.
    fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "exact",
            "--noise",
            "python",
        ],
        2,
    );
    fails(
        &[
            "solve",
            "--problem",
            "10",
            "--algorithm",
            "vi",
            "--arithmetic",
            "f32",
        ],
        2,
    );
}

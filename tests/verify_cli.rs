//! `truecost verify` and `truecost discount` on the command line.

mod common;

use common::cli::{fails, fails_one_line, stdout, truecost};
use serde_json::Value;

#[test]
fn verify_json_has_the_required_shape_and_exits_0_with_refuted_claims() {
    let text = stdout(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--format",
        "json",
        "--no-times",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    let claims = v["claims"].as_array().unwrap();
    assert_eq!(claims.len(), 7);
    for c in claims {
        for key in [
            "id",
            "statement",
            "verdict",
            "engine",
            "scope",
            "cases",
            "counterexample",
        ] {
            assert!(c.get(key).is_some(), "{key} in {c}");
        }
        assert!(["proved", "verified", "refuted", "inconclusive"]
            .contains(&c["verdict"].as_str().unwrap()));
    }
    assert!(claims.iter().any(|c| c["verdict"] == "refuted"));
    let lo = v["alpha_star"]["lo"].as_str().unwrap();
    let hi = v["alpha_star"]["hi"].as_str().unwrap();
    assert!(lo.contains('/') && hi.contains('/'));
    assert!(
        !text.contains("cases_per_second"),
        "no times with --no-times"
    );
    // The same run twice gives the same bytes.
    assert_eq!(
        text,
        stdout(&[
            "verify",
            "--no-coq",
            "--scope",
            "smoke",
            "--format",
            "json",
            "--no-times"
        ])
    );
}

#[test]
fn verify_prints_cases_per_second_unless_told_not_to() {
    let text = stdout(&["verify", "--no-coq", "--scope", "smoke", "--claim", "C2"]);
    assert!(text.contains("cases/s"), "{text}");
    assert!(text.contains("obligations/s"), "{text}");
    assert!(text.contains("smt solver: Z3 4."), "{text}");
    assert!(text.contains("C2  PROVED"));
    assert!(!text.contains("C1 "));
    // Without times: neither the rates nor the solver's version (a property of the machine).
    let quiet = stdout(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--claim",
        "C2",
        "--no-times",
    ]);
    assert!(quiet.contains("C2  PROVED") && quiet.contains("engine: smt (Z3) [proof]"));
    assert!(!quiet.contains("obligations/s") && !quiet.contains("smt solver"));
    // --no-smt leaves the enumeration's verdict.
    let no_smt = stdout(&[
        "verify", "--no-coq", "--scope", "smoke", "--claim", "C2", "--no-smt",
    ]);
    assert!(no_smt.contains("C2  VERIFIED") && !no_smt.contains("smt (Z3)"));
}

#[test]
fn verify_smt_out_refuses_a_non_empty_directory_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("x"), "x").unwrap();
    let e = fails_one_line(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--smt-out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(e.contains("not empty"), "{e}");
    let e = fails(&["verify", "--smt-out", "x", "--no-smt"], 2);
    assert!(e.contains("--no-smt"), "{e}");
}

#[test]
fn verify_latex_and_markdown() {
    let tex = stdout(&[
        "verify", "--no-coq", "--scope", "smoke", "--claim", "C4", "--format", "latex",
    ]);
    assert!(tex.contains("\\begin{tabular}") && tex.contains("\\bottomrule"));
    assert!(tex.contains("truecost 0.1.0") && tex.contains("commit"));
    assert!(tex.contains("C4 & refuted"));
    assert!(
        tex.contains("C4-corrected & proved & 24 & smt (Z3)"),
        "{tex}"
    );
    assert!(tex.contains("SMT solver Z3 4."), "{tex}");
    let md = stdout(&[
        "verify", "--no-coq", "--scope", "smoke", "--claim", "C3", "--format", "markdown",
    ]);
    assert!(md.contains("| claim | verdict | engine | cases | scope |"));
    assert!(md.contains("| C3 | proved | smt (Z3) |"), "{md}");
    assert!(md.contains("SMT solver: Z3 4."), "{md}");
    let quiet = stdout(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--claim",
        "C3",
        "--format",
        "markdown",
        "--no-times",
    ]);
    assert!(!quiet.contains("SMT solver"), "{quiet}");
}

#[test]
fn verify_writes_counterexamples_that_solve_replays() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    stdout(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--no-times",
        "--counterexamples",
        d,
    ]);
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["c1-as-printed.json", "c4-as-printed.json"]);
    for n in &names {
        let path = dir.path().join(n);
        stdout(&[
            "solve",
            "--file",
            path.to_str().unwrap(),
            "--algorithm",
            "dijkstra",
        ]);
        // The committed files are the same counterexamples.
        let committed = std::fs::read_to_string(format!("problems/counterexamples/{n}")).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), committed, "{n}");
    }
}

#[test]
fn verify_c4_bonus_set_of_a_file() {
    let text = stdout(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        "problems/counterexamples/c4-as-printed.json",
    ]);
    // By hand (tests/claims.rs): exact [-3, 0), printed [-1/3, 0).
    assert!(text.contains("exact (oracle):    [-3, 0)"), "{text}");
    assert!(
        text.contains("printed formula:   [-1/3, 0)  (DISAGREES)"),
        "{text}"
    );
    assert!(
        text.contains("corrected formula: [-3, 0)  (agrees)"),
        "{text}"
    );
    // Costs scaled by 1/2 halve the exact set (the file format takes fractions).
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("half.json");
    std::fs::write(&path, r#"{"initial": 0, "goals": [2], "actions": [[{"to": 1, "cost": "0"}, {"to": 2, "cost": "1/2"}], [{"to": 2, "cost": "0"}], []]}"#).unwrap();
    let text = stdout(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["bonus_sets"][0]["exact"], "[-3/2, 0)");
}

/// `--claim` selects a claim and its corrected form by the prefix, or one claim by its full id:
/// a corrected claim alone runs its check and reports it, and nothing else.
#[test]
fn verify_claim_selects_by_id_or_by_prefix() {
    let ids = |claim: &str| -> Vec<String> {
        let text = stdout(&[
            "verify",
            "--no-coq",
            "--scope",
            "smoke",
            "--claim",
            claim,
            "--format",
            "json",
            "--no-times",
            "--no-smt",
        ]);
        let v: Value = serde_json::from_str(&text).unwrap();
        v["claims"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["id"].as_str().unwrap().to_string())
            .collect()
    };
    assert_eq!(ids("C1"), ["C1", "C1-corrected"]);
    assert_eq!(ids("C1-corrected"), ["C1-corrected"]);
    assert_eq!(ids("C4"), ["C4", "C4-corrected"]);
    assert_eq!(ids("C4-corrected"), ["C4-corrected"]);
    assert_eq!(ids("C3-example"), ["C3-example"]);
}

#[test]
fn verify_bad_input() {
    let e = fails_one_line(&["verify", "--claim", "C9", "--scope", "smoke"]);
    assert!(e.contains("unknown claim"));
    fails_one_line(&["verify", "--claim", "C2", "--file", "problems/line.json"]);
    fails_one_line(&["verify", "--claim", "C4", "--file", "/nonexistent.json"]);
    truecost()
        .args(["verify", "--no-coq", "--scope", "huge"])
        .assert()
        .code(2);
}

#[test]
fn discount_command() {
    let text = stdout(&["discount", "--file", "problems/discount-example.json"]);
    // (0, alpha*]: open at 0, closed at the root of the worked example's polynomial.
    assert!(text.contains("(0, 0.9163"), "{text}");
    assert!(text.contains("5x^4 - x^3 - x^2 - x - 1"), "{text}");
    // Unit costs: never; no path (problem 6): always.
    assert!(stdout(&["discount", "--problem", "10"]).contains("\n  empty\n"));
    assert!(
        stdout(&["discount", "--problem", "6", "--format", "json"]).contains("\"set\": \"(0, 1)\"")
    );
    fails_one_line(&["discount", "--problem", "99"]);
    fails_one_line(&[
        "discount",
        "--file",
        "problems/line.json",
        "--step-cost",
        "unit",
    ]);
    truecost().args(["discount"]).assert().code(2);
}

#[test]
fn verify_does_not_depend_on_the_number_of_threads() {
    let run = |threads: &str| {
        let out = truecost()
            .env("RAYON_NUM_THREADS", threads)
            .args([
                "verify",
                "--no-coq",
                "--scope",
                "smoke",
                "--format",
                "json",
                "--no-times",
            ])
            .assert()
            .success()
            .get_output()
            .clone();
        out.stdout
    };
    assert_eq!(run("1"), run("3"));
}

/// `verify` re-checks the Coq development in the run (no `--no-coq`): each claim carried by a
/// Coq theorem gets the Coq level, or — for a refuted claim — keeps `refuted` with the Coq
/// engine named; the report names the Coq version and gives each theorem's statement as Coq
/// prints it (`coq_statement`), accepted only as pinned. Without `coqc` this test fails (the
/// install line is in the refusal of `tests/coq_proofs.rs`).
#[test]
fn verify_reaches_the_coq_level_when_coq_rechecks_the_development() {
    let text = stdout(&[
        "verify",
        "--scope",
        "smoke",
        "--format",
        "json",
        "--no-times",
    ]);
    let v: Value = serde_json::from_str(&text).unwrap();
    let verdict = |id: &str| -> (String, String) {
        let c = v["claims"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["id"] == id)
            .unwrap_or_else(|| panic!("{id} in {text}"));
        (
            c["verdict"].as_str().unwrap().to_string(),
            c["engine"].as_str().unwrap().to_string(),
        )
    };
    for id in ["C1-corrected", "C2", "C3", "C4-corrected"] {
        let (level, engine) = verdict(id);
        assert_eq!(level, "proved for every finite problem (Coq)", "{id}");
        assert!(engine.starts_with("coq (Coq 8."), "{id}: {engine}");
    }
    // The worked example is one fixed problem: its Coq theorems prove it for that problem.
    let (level, engine) = verdict("C3-example");
    assert_eq!(level, "proved in Coq for the paper's example");
    assert!(engine.starts_with("coq (Coq 8."), "{engine}");
    for id in ["C1", "C4"] {
        assert_eq!(verdict(id).0, "refuted", "{id}");
    }
    let c4 = v["claims"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["id"] == "C4")
        .unwrap();
    assert!(
        c4["notes"].as_array().unwrap().iter().any(|n| n
            .as_str()
            .unwrap()
            .contains("Truecost.C4.c4_as_printed_refuted")),
        "{c4}"
    );
    let theorems = v["coq"]["theorems"].as_array().unwrap();
    let pins = truecost::claims::coq::pins().unwrap();
    assert_eq!(theorems.len(), pins.len());
    for (t, pin) in theorems.iter().zip(&pins) {
        assert_eq!(t["theorem"], pin.name.as_str());
        assert_eq!(t["accepted"], true, "{t}");
        assert_eq!(t["coq_statement"], pin.statement.as_str(), "{t}");
    }
    // The report's own words, not the specification's section numbers.
    let text = stdout(&[
        "verify",
        "--no-coq",
        "--scope",
        "smoke",
        "--claim",
        "C2",
        "--no-smt",
        "--no-harnesses",
        "--no-times",
    ]);
    assert!(
        text.starts_with(
            "truecost 0.1.0 - the paper's four propositions (docs/spec.md), scope smoke\n"
        ),
        "{text}"
    );
    assert!(!text.contains("SPEC"), "{text}");
}

/// `--coq-timeout` takes whole seconds from 1 and goes with the re-check (not with `--no-coq`).
#[test]
fn verify_coq_timeout_is_checked() {
    for bad in ["0", "-1", "x"] {
        let e = fails(&["verify".to_string(), format!("--coq-timeout={bad}")], 2);
        assert!(e.contains("--coq-timeout"), "{e}");
    }
    let e = fails(&["verify", "--no-coq", "--coq-timeout", "5"], 2);
    assert!(e.contains("--no-coq"), "{e}");
}

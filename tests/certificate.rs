//! Certificates: `solve --certificate` then `truecost check` accepts on hand-made problems
//! (written here, not by truecost) and on the paper's problems, and every kind of tampering
//! is rejected naming the first failing state and condition. Reach certificates (the greatest
//! probability of reaching a goal): a hand-derived one, and those `solve --objective reach`
//! writes for environments and a perturbed paper problem, are accepted, and each tampering
//! rejected.
//! Expected values are derived by hand in the comments; the SHA-256 of hand-written
//! certificates comes from the `sha2` crate.

mod common;

use std::path::Path;

use common::cli::{fails_one_line, json, stdout, write};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

/// A stochastic problem (goal 3):
/// * 0: `a0` cost 1 → 1 or 3 with 1/2 each; `a1` cost 3 → 3.
/// * 1: `a0` cost 1 → 3; `a1` cost 0 → 2.
/// * 2: `a0` cost 0 → 1; `a1` cost 5 → 3.
/// * 4: a trap (cost-0 self-loop).
/// * 5: `a0` cost 1 → 3 or 4 (the trap) with 1/2 each; `a1` cost 1 → 5.
///
/// By hand: `V(1) = min(1, 0 + V(2))`, `V(2) = min(0 + V(1), 5)`: the zero-cost cycle 1 ↔ 2
/// never reaches the goal, so the proper choice is `π(1) = a0`, `V(1) = 1`, and
/// `V(2) = V(1) = 1` by `a0`. `V(0) = min(1 + V(1)/2, 3) = 3/2` by `a0`. From 4 and 5 every
/// policy misses the goal with positive probability (5's `a0` falls into the trap with
/// probability 1/2; `a1` loops forever): `inf`.
const HAND: &str = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [3], "actions": [
  [{"cost": "1", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 3, "p": "1/2"}]}, {"to": 3, "cost": "3"}],
  [{"to": 3, "cost": "1"}, {"to": 2, "cost": "0"}],
  [{"to": 1, "cost": "0"}, {"to": 3, "cost": "5"}],
  [],
  [{"to": 4, "cost": "0"}],
  [{"cost": "1", "outcomes": [{"to": 3, "p": "1/2"}, {"to": 4, "p": "1/2"}]}, {"to": 5, "cost": "1"}]
]}"#;

/// A deterministic problem (goal 2): 0 → 1 (cost 1), 0 → 2 (cost 5); 1 → 0 (1), 1 → 2 (1);
/// 3 → 3 (cost 1, a trap). By hand `G* = (2, 1, 0, inf)` with `π = (0, 1, -, -)`.
const LINE: &str = r#"{"format": "truecost-problem/1", "initial": 0, "goals": [2], "actions": [
  [{"to": 1, "cost": "1"}, {"to": 2, "cost": "5"}],
  [{"to": 0, "cost": "1"}, {"to": 2, "cost": "1"}],
  [],
  [{"to": 3, "cost": "1"}]
]}"#;

/// The discounted example (goal 1, rewards given): staying at 0 pays 0, entering the goal 1.
/// With `α = 1/2`: `V(0) = max(0 + V(0)/2, 1 + V(1)/2) = 1` (`V(1) = 0`, terminal), `π(0) = 1`.
const REWARDS: &str = r#"{"initial": 0, "goals": [1], "actions": [
  [{"to": 0, "cost": "1", "reward": "0"}, {"to": 1, "cost": "5", "reward": "1"}], []]}"#;

fn s(p: &Path) -> String {
    p.display().to_string()
}

/// `solve <source> --algorithm exact <extra> --certificate C` and the certificate read back.
fn certify(dir: &Path, source: &[&str], extra: &[&str]) -> Value {
    let cert = dir.join("solved.cert.json");
    let mut args = vec!["solve"];
    args.extend_from_slice(source);
    args.extend_from_slice(&["--algorithm", "exact"]);
    args.extend_from_slice(extra);
    let c = s(&cert);
    args.extend_from_slice(&["--certificate", &c]);
    stdout(&args);
    serde_json::from_str(&std::fs::read_to_string(&cert).unwrap()).unwrap()
}

/// `check <source> C --format json` on the certificate `cert`, which must be accepted.
fn accepted(dir: &Path, source: &[&str], cert: &Value) -> Value {
    let path = write(dir, "accept.cert.json", &cert.to_string());
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    let p = s(&path);
    args.extend_from_slice(&[&p, "--format", "json"]);
    let v = json(&args);
    assert_eq!(v["accepted"], true, "{v}");
    v
}

/// `check <source> C` on `cert`, which must be rejected: exit 1 and one line on stderr.
fn rejected(dir: &Path, source: &[&str], cert: &Value) -> String {
    let path = write(dir, "reject.cert.json", &cert.to_string());
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    let p = s(&path);
    args.push(&p);
    fails_one_line(&args)
}

/// The rejection's first failing state and condition, from its one line.
fn first_failure(line: &str) -> (Option<usize>, String) {
    let rest = line
        .strip_prefix("error: certificate rejected: ")
        .unwrap_or_else(|| panic!("not a rejection: {line}"));
    let (state, rest) = match rest.strip_prefix("state ") {
        Some(r) => {
            let (n, r) = r.split_once(": ").unwrap();
            (Some(n.parse().unwrap()), r)
        }
        None => (None, rest),
    };
    let condition = rest
        .strip_prefix("condition ")
        .unwrap()
        .split_once(':')
        .unwrap()
        .0;
    (state, condition.to_string())
}

/// The certificate's values equal `expected` as exact numbers (a certificate need not reduce
/// its fractions).
fn assert_values(cert: &Value, expected: &[&str]) {
    let exact = |t: &str| -> Option<num_rational::BigRational> {
        (t != "inf").then(|| t.parse().unwrap_or_else(|_| panic!("not exact: {t}")))
    };
    let got: Vec<_> = cert["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| exact(v.as_str().unwrap()))
        .collect();
    let want: Vec<_> = expected.iter().map(|t| exact(t)).collect();
    assert_eq!(got, want, "{}", cert["values"]);
}

/// The names of the conditions an accepted certificate's JSON report lists, in order.
fn condition_names(v: &Value) -> Vec<&str> {
    v["conditions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect()
}

fn tampered(cert: &Value, edit: impl FnOnce(&mut Value)) -> Value {
    let mut c = cert.clone();
    edit(&mut c);
    c
}

/// `3/2 ± 10⁻³⁰` as an exact fraction over `10³⁰`.
fn three_halves_off(plus: bool) -> String {
    let base = format!("15{}", "0".repeat(29));
    let numerator = if plus {
        format!("15{}1", "0".repeat(28))
    } else {
        format!("14{}", "9".repeat(29))
    };
    assert_eq!(base.len(), numerator.len());
    format!("{numerator}/1{}", "0".repeat(30))
}

#[test]
fn hand_problem_certificate_has_the_hand_values_and_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "hand.json", HAND);
    let source = ["--file", &s(&f)];
    let cert = certify(dir.path(), &source, &[]);
    assert_eq!(cert["format"], "truecost-certificate/1");
    assert_eq!(cert["objective"], "truecost");
    assert_values(&cert, &["3/2", "1", "1", "0", "inf", "inf"]);
    assert_eq!(cert["policy"], json!([0, 0, 0, null, null, null]));
    let sha = format!("{:x}", Sha256::digest(HAND.as_bytes()));
    assert_eq!(cert["problem"]["sha256"], sha.as_str());
    let v = accepted(dir.path(), &source, &cert);
    assert_eq!(v["states"], 6);
    assert_eq!(v["finite_states"], 4);
    assert_eq!(
        condition_names(&v),
        [
            "problem",
            "goal",
            "policy",
            "closed",
            "evaluation",
            "optimality",
            "proper",
            "infinite"
        ]
    );
}

#[test]
fn each_tampering_names_its_first_failing_state_and_condition() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "hand.json", HAND);
    let source = ["--file", &s(&f)];
    let cert = certify(dir.path(), &source, &[]);
    // No policy leads into state 0, so only its own equation sees its value.
    let cases: Vec<(&str, Value, Option<usize>, &str)> = vec![
        (
            "V(0) + 10^-30",
            tampered(&cert, |c| c["values"][0] = json!(three_halves_off(true))),
            Some(0),
            "evaluation",
        ),
        (
            "V(0) - 10^-30",
            tampered(&cert, |c| c["values"][0] = json!(three_halves_off(false))),
            Some(0),
            "evaluation",
        ),
        (
            "a non-optimal action at 0 (cost 3 straight to the goal)",
            tampered(&cert, |c| c["policy"][0] = json!(1)),
            Some(0),
            "evaluation",
        ),
        (
            "a non-optimal action with its own value V(0) = 3: a0 gives 3/2",
            tampered(&cert, |c| {
                c["policy"][0] = json!(1);
                c["values"][0] = json!("3");
            }),
            Some(0),
            "optimality",
        ),
        (
            "an improper policy: the zero-cost cycle 1 -> 2 -> 1 (values unchanged)",
            tampered(&cert, |c| c["policy"][1] = json!(1)),
            Some(1),
            "proper",
        ),
        (
            "an action index out of range",
            tampered(&cert, |c| c["policy"][0] = json!(7)),
            Some(0),
            "policy",
        ),
        (
            "a wrong SHA-256",
            tampered(&cert, |c| {
                c["problem"]["sha256"] = json!("0".repeat(64));
            }),
            None,
            "problem",
        ),
        (
            "a goal with value 1",
            tampered(&cert, |c| c["values"][3] = json!("1")),
            Some(3),
            "goal",
        ),
        (
            "state 2 claimed inf: it reaches the goal through 1",
            tampered(&cert, |c| {
                c["values"][2] = json!("inf");
                c["policy"][2] = json!(null);
            }),
            Some(2),
            "infinite",
        ),
        (
            "state 5 claimed finite through a0, which may fall into the trap",
            tampered(&cert, |c| {
                c["values"][5] = json!("1");
                c["policy"][5] = json!(0);
            }),
            Some(5),
            "closed",
        ),
    ];
    for (what, c, state, condition) in cases {
        let line = rejected(dir.path(), &source, &c);
        assert_eq!(
            first_failure(&line),
            (state, condition.to_string()),
            "{what}: {line}"
        );
    }
}

#[test]
fn malformed_certificates_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "hand.json", HAND);
    let source = ["--file", &s(&f)];
    let cert = certify(dir.path(), &source, &[]);
    let cases = [
        ("not JSON", Value::String("{".into()), "is not JSON"),
        (
            "a decimal value",
            tampered(&cert, |c| c["values"][1] = json!("1.0")),
            "value of state 1",
        ),
        (
            "a zero denominator",
            tampered(&cert, |c| c["values"][1] = json!("1/0")),
            "value of state 1",
        ),
        (
            "no policy",
            tampered(&cert, |c| {
                c.as_object_mut().unwrap().remove("policy");
            }),
            "no field \"policy\"",
        ),
        (
            "a negative action index",
            tampered(&cert, |c| c["policy"][0] = json!(-1)),
            "policy of state 0",
        ),
        (
            "another format",
            tampered(&cert, |c| c["format"] = json!("truecost-certificate/9")),
            "format",
        ),
        (
            "too few values",
            tampered(&cert, |c| {
                c["values"].as_array_mut().unwrap().pop();
            }),
            "5 values",
        ),
        (
            "an unknown field",
            tampered(&cert, |c| c["extra"] = json!(1)),
            "unknown field",
        ),
    ];
    for (what, c, says) in cases {
        let text = match &c {
            Value::String(raw) => raw.clone(),
            v => v.to_string(),
        };
        let path = write(dir.path(), "bad.cert.json", &text);
        let line = fails_one_line(&["check", "--file", &s(&f), &s(&path)]);
        assert!(
            line.starts_with("error: malformed certificate: "),
            "{what}: {line}"
        );
        assert!(line.contains(says), "{what}: {line}");
    }
    // The wrong source for the certificate.
    let path = write(dir.path(), "c.cert.json", &cert.to_string());
    let line = fails_one_line(&["check", "--problem", "10", &s(&path)]);
    assert!(line.contains("not from problem"), "{line}");
}

/// A certificate written here by hand (values, policy and SHA-256), for a problem written
/// here: the checker accepts it without any solver having run, and the solver agrees.
#[test]
fn a_hand_written_deterministic_certificate_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "line.json", LINE);
    let source = ["--file", &s(&f)];
    let hand = json!({
        "format": "truecost-certificate/1",
        "objective": "deterministic",
        "alpha": null,
        "problem": {"source": "file", "name": s(&f), "gamma": null, "noise": null,
                    "step_cost": null, "sha256": format!("{:x}", Sha256::digest(LINE.as_bytes())),
                    "sha256_of": "file bytes"},
        "states": 4,
        "values": ["2", "1", "0", "inf"],
        "policy": [0, 1, null, null],
    });
    let v = accepted(dir.path(), &source, &hand);
    assert_eq!(v["objective"], "deterministic");
    assert_eq!(v["finite_states"], 3);
    let solved = certify(dir.path(), &source, &[]);
    assert_eq!(solved["objective"], "deterministic");
    assert_values(&solved, &["2", "1", "0", "inf"]);
    assert_eq!(solved["policy"], hand["policy"]);
    // The shortcut 0 -> 2 (cost 5) as policy, with its value: optimality fails at 0.
    let c = tampered(&hand, |c| {
        c["policy"][0] = json!(1);
        c["values"][0] = json!("5");
    });
    let line = rejected(dir.path(), &source, &c);
    assert_eq!(
        first_failure(&line),
        (Some(0), "optimality".into()),
        "{line}"
    );
    // The trap claimed finite: the path of π from 3 never reaches the goal (cost 1 a step
    // makes V(3) = 1 + V(3) fail first).
    let c = tampered(&hand, |c| {
        c["values"][3] = json!("7");
        c["policy"][3] = json!(0);
    });
    let line = rejected(dir.path(), &source, &c);
    assert_eq!(
        first_failure(&line),
        (Some(3), "evaluation".into()),
        "{line}"
    );
}

#[test]
fn discounted_certificate_of_the_rewards_example() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "rewards.json", REWARDS);
    let source = ["--file", &s(&f)];
    let cert = certify(
        dir.path(),
        &source,
        &["--objective", "discounted", "--alpha", "1/2"],
    );
    assert_eq!(cert["objective"], "discounted");
    assert_eq!(cert["alpha"], "1/2");
    assert_values(&cert, &["1", "0"]);
    assert_eq!(cert["policy"], json!([1, null]));
    accepted(dir.path(), &source, &cert);
    // Staying at 0 is worth 0 + V(0)/2 = 1/2, not 1.
    let c = tampered(&cert, |c| c["policy"][0] = json!(0));
    let line = rejected(dir.path(), &source, &c);
    assert_eq!(
        first_failure(&line),
        (Some(0), "evaluation".into()),
        "{line}"
    );
    // V = 0 everywhere with π(0) = stay is self-consistent (0 = 0 + 0/2) but not optimal.
    let c = tampered(&cert, |c| {
        c["policy"][0] = json!(0);
        c["values"][0] = json!("0");
    });
    let line = rejected(dir.path(), &source, &c);
    assert_eq!(
        first_failure(&line),
        (Some(0), "optimality".into()),
        "{line}"
    );
    let c = tampered(&cert, |c| c["alpha"] = json!("1"));
    let line = rejected(dir.path(), &source, &c);
    assert_eq!(first_failure(&line), (None, "alpha".into()), "{line}");
}

#[test]
fn paper_problems_certificates_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    // Problem 6: the goal is unreachable from x1 (inf states); problem 10 as published.
    for (id, extra) in [
        ("0", vec![]),
        ("6", vec![]),
        ("10", vec![]),
        ("10", vec!["--step-cost", "euclidean"]),
        ("10", vec!["--gamma", "0.9"]),
        ("3", vec!["--gamma", "0.7", "--noise", "reference"]),
    ] {
        let source = ["--problem", id];
        let cert = certify(dir.path(), &source, &extra);
        let expected = if extra.contains(&"--gamma") {
            "truecost"
        } else {
            "deterministic"
        };
        assert_eq!(cert["objective"], expected, "problem {id} {extra:?}");
        assert_eq!(
            cert["problem"]["sha256_of"], "truecost-canonical-mdp/1",
            "problem {id}"
        );
        let v = accepted(dir.path(), &source, &cert);
        assert_eq!(v["states"], 400);
        // The same certificate does not certify another problem.
        let line = rejected(dir.path(), &["--problem", "11"], &cert);
        assert_eq!(first_failure(&line), (None, "problem".into()), "{line}");
    }
    // Problem 10, γ = 0.9: the first state with a value other than 0 and inf, raised by
    // 10^-30. Its own equation breaks, and so may those of states whose policy leads into
    // it: the first failing state is at most the tampered one.
    let source = ["--problem", "10"];
    let cert = certify(dir.path(), &source, &["--gamma", "0.9"]);
    let x = cert["values"]
        .as_array()
        .unwrap()
        .iter()
        .position(|v| v != "inf" && v != "0")
        .unwrap();
    let off = tampered(&cert, |c| {
        let v = c["values"][x].as_str().unwrap().to_string();
        let (n, d) = v.split_once('/').unwrap_or((&v, "1"));
        // n/d + 1/(d·10^30) = (n·10^30 + 1)/(d·10^30).
        c["values"][x] = json!(format!("{n}{}1/{d}{}", "0".repeat(29), "0".repeat(30)));
    });
    let line = rejected(dir.path(), &source, &off);
    let (state, condition) = first_failure(&line);
    assert!(state.unwrap() <= x, "{line}");
    assert!(
        condition == "evaluation" || condition == "optimality",
        "{line}"
    );
}

#[test]
fn environment_certificates_are_accepted() {
    let dir = tempfile::tempdir().unwrap();
    for (env, extra) in [
        ("frozenlake", vec![]),
        ("cliffwalking", vec![]),
        (
            "frozenlake:slippery=false",
            vec!["--objective", "discounted", "--alpha", "9/10"],
        ),
    ] {
        let source = ["--env", env];
        let cert = certify(dir.path(), &source, &extra);
        accepted(dir.path(), &source, &cert);
    }
    // A reach certificate (FrozenLake and problem 10 in the reach tests below).
    let source = ["--env", "cliffwalking:slippery=true"];
    let cert = certify(dir.path(), &source, &["--objective", "reach"]);
    assert_eq!(cert["objective"], "reach", "{cert}");
    let v = accepted(dir.path(), &source, &cert);
    assert_eq!(v["objective"], "reach", "{v}");
    let line = fails_one_line(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "dijkstra",
        "--certificate",
        &s(&dir.path().join("r.json")),
    ]);
    assert!(line.contains("--algorithm exact"), "{line}");
}

/// A stochastic problem (goal 3; costs play no part in reach):
/// * 0: `a0` → 1 with 3/4, → 4 (a trap) with 1/4; `a1` → 2.
/// * 1: `a0` → 3 or 0 with 1/2 each.
/// * 2: `a0` → 2 (a self-loop); `a1` → 3 with 1/3, → 4 with 2/3.
/// * 4: a trap (a self-loop).
///
/// By hand: `V(3) = 1`; 4 never reaches the goal: `V(4) = 0`. At 2 the self-loop gains
/// nothing, so `V(2) = 1/3` by `a1` (any value solves `V(2) = V(2)`: only a policy that leaves
/// the loop is proper). `V(1) = 1/2 + V(0)/2`; with `a0` at 0, `V(0) = 3/4 · V(1) = 3/8 +
/// 3/8 · V(0)`, so `V(0) = 3/5 > 1/3` (`a1`), and `V(1) = 4/5`.
const REACH: &str = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [3], "actions": [
  [{"cost": "1", "outcomes": [{"to": 1, "p": "3/4"}, {"to": 4, "p": "1/4"}]}, {"to": 2, "cost": "1"}],
  [{"cost": "1", "outcomes": [{"to": 3, "p": "1/2"}, {"to": 0, "p": "1/2"}]}],
  [{"to": 2, "cost": "1"}, {"cost": "1", "outcomes": [{"to": 3, "p": "1/3"}, {"to": 4, "p": "2/3"}]}],
  [],
  [{"to": 4, "cost": "1"}]
]}"#;

/// The hand certificate of [`REACH`] as the file `problem` records it.
fn reach_certificate(problem: &Path) -> Value {
    let sha = format!("{:x}", Sha256::digest(REACH.as_bytes()));
    json!({
        "format": "truecost-certificate/1",
        "objective": "reach",
        "alpha": null,
        "problem": {"source": "file", "name": s(problem), "gamma": null, "noise": null,
                    "step_cost": null, "sha256": sha, "sha256_of": "file bytes"},
        "states": 5,
        "values": ["3/5", "4/5", "1/3", "1", "0"],
        "policy": [0, 0, 1, null, null],
    })
}

#[test]
fn the_hand_reach_certificate_is_accepted_with_every_condition_listed() {
    let dir = tempfile::tempdir().unwrap();
    let problem = write(dir.path(), "reach.json", REACH);
    let source = ["--file", &s(&problem)];
    let v = accepted(dir.path(), &source, &reach_certificate(&problem));
    assert_eq!(v["objective"], "reach");
    assert_eq!(
        condition_names(&v),
        [
            "problem",
            "range",
            "goal",
            "policy",
            "evaluation",
            "optimality",
            "proper"
        ]
    );
    // Evaluation and properness at the three states of positive value (0, 1, 2); optimality
    // at every action of the four non-goals (2 + 1 + 2 + 1).
    let instances = |name: &str| {
        v["conditions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"] == name)
            .unwrap()["instances"]
            .clone()
    };
    assert_eq!(instances("evaluation"), 3);
    assert_eq!(instances("proper"), 3);
    assert_eq!(instances("optimality"), 6);
    // Unreduced fractions are the same numbers.
    let scaled = tampered(&reach_certificate(&problem), |c| {
        c["values"] = json!(["6/10", "12/15", "2/6", "7/7", "0/3"]);
    });
    accepted(dir.path(), &source, &scaled);
}

#[test]
fn each_reach_tampering_names_its_first_failing_state_and_condition() {
    let dir = tempfile::tempdir().unwrap();
    let problem = write(dir.path(), "reach.json", REACH);
    let source = ["--file", &s(&problem)];
    let cert = reach_certificate(&problem);
    let fails = |edit: &dyn Fn(&mut Value)| {
        first_failure(&rejected(
            dir.path(),
            &source,
            &tampered(&cert, |c| edit(c)),
        ))
    };
    let at = |x: usize, condition: &str| (Some(x), condition.to_string());
    // V(1) raised by 10^-30: 0's equation V(0) = 3/4 V(1) is the first to break.
    // 4/5 + 10^-30 = (8·10^29 + 1)/10^30.
    let off = format!("8{}1/1{}", "0".repeat(28), "0".repeat(30));
    assert_eq!(fails(&|c| c["values"][1] = json!(off)), at(0, "evaluation"));
    // V(0) lowered by 10^-30: its own equation breaks.
    // 3/5 - 10^-30 = (6·10^29 - 1)/10^30.
    let low = format!("5{}/1{}", "9".repeat(29), "0".repeat(30));
    assert_eq!(fails(&|c| c["values"][0] = json!(low)), at(0, "evaluation"));
    // A non-optimal action at 0 (a1, into 2) with its own exact values: V(0) = 1/3 and
    // V(1) = 1/2 + 1/6 = 2/3 satisfy every equation of the policy, but a0 gives
    // 3/4 · 2/3 = 1/2 > 1/3.
    assert_eq!(
        fails(&|c| {
            c["values"][0] = json!("1/3");
            c["values"][1] = json!("2/3");
            c["policy"][0] = json!(1);
        }),
        at(0, "optimality")
    );
    // An improper policy: the self-loop at 2 claimed to keep probability 1. V = (1, 1, 1)
    // on 0, 1, 2 satisfies every equation of the policy (0 → 2 → 2 ...) and every action's
    // upper bound, but from 0 and 2 the policy never reaches the goal nor a value-0 state.
    assert_eq!(
        fails(&|c| {
            c["values"] = json!(["1", "1", "1", "1", "0"]);
            c["policy"] = json!([1, 0, 0, null, null]);
        }),
        at(0, "proper")
    );
    // An index out of range, a missing action, an action where V = 0.
    assert_eq!(fails(&|c| c["policy"][1] = json!(5)), at(1, "policy"));
    assert_eq!(fails(&|c| c["policy"][2] = Value::Null), at(2, "policy"));
    assert_eq!(fails(&|c| c["policy"][4] = json!(0)), at(4, "policy"));
    // The trap claimed to reach the goal, with no action chosen.
    assert_eq!(fails(&|c| c["values"][4] = json!("1/2")), at(4, "policy"));
    // Values outside [0, 1] or infinite.
    assert_eq!(fails(&|c| c["values"][4] = json!("-1/2")), at(4, "range"));
    assert_eq!(fails(&|c| c["values"][2] = json!("4/3")), at(2, "range"));
    assert_eq!(fails(&|c| c["values"][4] = json!("inf")), at(4, "range"));
    // The goal's value must be 1.
    assert_eq!(fails(&|c| c["values"][3] = json!("1/2")), at(3, "goal"));
    assert_eq!(fails(&|c| c["policy"][3] = json!(0)), at(3, "goal"));
    // A trap claimed at 1/2 with its self-loop: its own equation holds (V = V) and its
    // upper bound too, but 0's equation now reads 3/5 against 3/4 · 4/5 + 1/4 · 1/2.
    assert_eq!(
        fails(&|c| {
            c["values"][4] = json!("1/2");
            c["policy"][4] = json!(0);
        }),
        at(0, "evaluation")
    );
    // Another problem (a byte changed): the SHA-256 differs.
    let other = write(
        dir.path(),
        "other.json",
        &REACH.replace("1/3", "1/4").replace("2/3", "3/4"),
    );
    assert_eq!(
        first_failure(&rejected(dir.path(), &["--file", &s(&other)], &cert)),
        (None, "problem".to_string())
    );
    // "alpha" is refused on a reach certificate.
    let line = {
        let path = write(
            dir.path(),
            "alpha.cert.json",
            &tampered(&cert, |c| c["alpha"] = json!("1/2")).to_string(),
        );
        fails_one_line(&["check", "--file", &s(&problem), &s(&path)])
    };
    assert!(line.contains("not discounted"), "{line}");
}

#[test]
fn reach_optima_are_accepted_and_their_tampering_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let reach = ["--objective", "reach"];
    let cert = certify(dir.path(), &["--env", "frozenlake"], &reach);
    let v = accepted(dir.path(), &["--env", "frozenlake"], &cert);
    assert_eq!(v["states"], 16);
    // The holes and the goal: 5 holes of value 0, the goal 15 of value 1.
    let values = cert["values"].as_array().unwrap();
    assert_eq!(values[15], "1");
    for hole in [5, 7, 11, 12] {
        assert_eq!(values[hole], "0", "hole {hole}");
    }
    // Problem 10 under the paper's noise model, γ = 0.9.
    let source = ["--problem", "10", "--gamma", "0.9"];
    let cert = certify(dir.path(), &source, &reach);
    accepted(dir.path(), &["--problem", "10"], &cert);
    // Lower the value of the first state where the policy acts by 10^-30: rejected at that
    // state or before (a state whose policy leads into it), by an equation of the policy.
    let x = cert["policy"]
        .as_array()
        .unwrap()
        .iter()
        .position(|a| !a.is_null())
        .expect("a state where the policy acts");
    let off = tampered(&cert, |c| {
        let v = c["values"][x].as_str().unwrap().to_string();
        let (n, d) = v.split_once('/').unwrap_or((&v, "1"));
        // n/d - 1/(d·10^30) = (n·10^30 - 1)/(d·10^30).
        let n: num_bigint::BigInt = n.parse().unwrap();
        let scale: num_bigint::BigInt = format!("1{}", "0".repeat(30)).parse().unwrap();
        c["values"][x] = json!(format!("{}/{d}{}", n * scale - 1, "0".repeat(30)));
    });
    let (state, condition) = first_failure(&rejected(dir.path(), &["--problem", "10"], &off));
    assert!(state.unwrap() <= x);
    assert_eq!(condition, "evaluation");
}

/// `check --coq`: the verified checker (Truecost.CertificateCheck.check, run by coqc) accepts
/// the certificate of the exact optimum of a small environment, and says so in the JSON and
/// the text.
#[test]
fn check_coq_runs_the_verified_checker() {
    let dir = tempfile::tempdir().unwrap();
    let source = ["--env", "frozenlake:slippery=false"];
    let cert = certify(dir.path(), &source, &[]);
    let path = write(dir.path(), "coq.cert.json", &cert.to_string());
    let p = s(&path);
    let v = json(&[
        "check", source[0], source[1], &p, "--coq", "--format", "json",
    ]);
    assert_eq!(v["accepted"], true, "{v}");
    assert_eq!(v["coq_checked"], true, "{v}");
    // The program that ran: the cached extracted checker, an executable file.
    let program = v["coq_checker"].as_str().expect("the checker's path");
    assert_eq!(
        program,
        truecost::certificate::coq::extracted_checker()
            .unwrap()
            .display()
            .to_string()
    );
    {
        use std::os::unix::fs::PermissionsExt;
        let meta = std::fs::metadata(program).unwrap();
        assert!(
            meta.is_file() && meta.permissions().mode() & 0o100 != 0,
            "{program}"
        );
    }
    let text = stdout(&["check", source[0], source[1], &p, "--coq"]);
    assert!(
        text.contains("accepted by the verified checker Truecost.CertificateCheck.check"),
        "{text}"
    );
    let v = json(&["check", source[0], source[1], &p, "--format", "json"]);
    assert_eq!(v["coq_checked"], false, "{v}");
    assert!(v["coq_checker"].is_null(), "{v}");
}

/// An exact value of a certificate as `num`'s `BigRational` (reduced): `"inf"` is `None`, each
/// integer decimal or `0x` hexadecimal (read here by `num-bigint`, not by the checker's reader).
fn certificate_value(text: &str) -> Option<num_rational::BigRational> {
    use num_bigint::BigInt;
    let integer = |t: &str| -> BigInt {
        let (negative, magnitude) = match t.strip_prefix('-') {
            Some(m) => (true, m),
            None => (false, t),
        };
        let n = match magnitude.strip_prefix("0x") {
            Some(hex) => BigInt::parse_bytes(hex.as_bytes(), 16).unwrap(),
            None => magnitude.parse().unwrap(),
        };
        if negative {
            -n
        } else {
            n
        }
    };
    (text != "inf").then(|| match text.split_once('/') {
        Some((n, d)) => num_rational::BigRational::new(integer(n), integer(d)),
        None => num_rational::BigRational::from_integer(integer(text)),
    })
}

/// A 12×12 benchmark grid under the paper's noise with `γ = 0.99`, exported with its outcome
/// probabilities: the exact values have more than 1024 bits, so the certificate writes them
/// in hexadecimal (`0x…`). `check` accepts it, and its values, read here independently, are the
/// optimum: with every stage cost at least 1 (costs 1–4), the solution of the Bellman equation
/// `V(x) = min_a [l(x, a) + Σ_y p(y | x, a) V(y)]` (`V = 0` at the goal) is unique and is the
/// optimal truecost, and the policy attains the minimum. Checked in `BigRational` arithmetic.
#[test]
fn long_values_are_written_in_hexadecimal_and_are_the_optimum() {
    use num_rational::BigRational;
    let dir = tempfile::tempdir().unwrap();
    let problem = dir.path().join("grid.json");
    stdout(&[
        "export",
        "--grid",
        "12x12",
        "--gamma",
        "0.99",
        "--out",
        &s(&problem),
    ]);
    let model: Value = serde_json::from_str(&std::fs::read_to_string(&problem).unwrap()).unwrap();
    let cert = certify(dir.path(), &["--file", &s(&problem)], &[]);
    accepted(dir.path(), &["--file", &s(&problem)], &cert);
    let texts: Vec<&str> = cert["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(texts.len(), 144);
    assert!(texts.iter().any(|t| t.contains("/0x")), "{}", texts[0]);
    let v: Vec<BigRational> = texts
        .iter()
        .map(|t| certificate_value(t).expect("every state of the grid reaches the goal"))
        .collect();
    let ratio = |t: &Value| -> BigRational { t.as_str().unwrap().parse().unwrap() };
    let goals: Vec<u64> = model["goals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g.as_u64().unwrap())
        .collect();
    for (x, actions) in model["actions"].as_array().unwrap().iter().enumerate() {
        if goals.contains(&(x as u64)) {
            assert_eq!(v[x], BigRational::from_integer(0.into()), "goal {x}");
            assert!(cert["policy"][x].is_null());
            continue;
        }
        let q: Vec<BigRational> = actions
            .as_array()
            .unwrap()
            .iter()
            .map(|a| {
                let mut q = ratio(&a["cost"]);
                assert!(q >= BigRational::from_integer(1.into()));
                match a.get("outcomes") {
                    Some(outcomes) => {
                        for o in outcomes.as_array().unwrap() {
                            q += ratio(&o["p"]) * &v[o["to"].as_u64().unwrap() as usize];
                        }
                    }
                    None => q += &v[a["to"].as_u64().unwrap() as usize],
                }
                q
            })
            .collect();
        let chosen = cert["policy"][x].as_u64().unwrap() as usize;
        assert_eq!(q[chosen], v[x], "evaluation at {x}");
        assert_eq!(q.iter().min().unwrap(), &v[x], "optimality at {x}");
    }
}

/// A DRN file read with `--goal-label done --cost-reward coins` (two reward models, a goal label
/// of its own): the certificate records both names, `check` reads the file with them without
/// being told (and accepts them repeated), refuses options that contradict them, and a record
/// whose names are edited is checked against the other reading (and rejected there). Values by
/// hand: from state 0, `coins` costs 5 to reach `done` directly, or 1 to state 2 and 1 from
/// there (2 in all); `steps` costs 1 either way.
#[test]
fn a_drn_file_s_goal_label_and_cost_reward_are_recorded_and_reused() {
    let dir = tempfile::tempdir().unwrap();
    let drn = write(
        dir.path(),
        "m.drn",
        "@type: MDP\n@reward_models\nsteps coins\n@nr_states\n3\n@nr_choices\n4\n@model\n\
         state 0 init\n\taction 0 [1, 5]\n\t\t1 : 1\n\taction 1 [1, 1]\n\t\t2 : 1\n\
         state 1 done\n\taction 0 [0, 0]\n\t\t1 : 1\n\
         state 2\n\taction 0 [1, 1]\n\t\t1 : 1\n",
    );
    let path = s(&drn);
    let source = ["--file", path.as_str()];
    let names = ["--goal-label", "done", "--cost-reward", "coins"];
    let cert = certify(dir.path(), &source, &names);
    assert_eq!(cert["problem"]["goal_label"], "done", "{cert}");
    assert_eq!(cert["problem"]["cost_reward"], "coins", "{cert}");
    assert_values(&cert, &["2", "0", "1"]);
    accepted(dir.path(), &source, &cert);
    let mut repeated = source.to_vec();
    repeated.extend_from_slice(&names);
    accepted(dir.path(), &repeated, &cert);
    for (option, value, says) in [
        ("--goal-label", "goal", "--goal-label 'goal' contradicts the certificate, written for the goal label 'done'"),
        ("--cost-reward", "steps", "--cost-reward 'steps' contradicts the certificate, written for the cost reward model 'coins'"),
    ] {
        let line = rejected(dir.path(), &[&source[..], &[option, value]].concat(), &cert);
        assert!(line.contains(says), "{line}");
    }
    // The record names the reading: with `steps` as the costs, the values are not optimal.
    let steps = tampered(&cert, |c| c["problem"]["cost_reward"] = json!("steps"));
    let line = rejected(dir.path(), &source, &steps);
    assert!(line.contains("state 0"), "{line}");
    // Without the names, the defaults: no reward model `cost`, so the file is not read.
    let plain = tampered(&cert, |c| {
        let problem = c["problem"].as_object_mut().unwrap();
        problem.remove("goal_label");
        problem.remove("cost_reward");
    });
    let line = rejected(dir.path(), &source, &plain);
    assert!(line.contains("no reward model named 'cost'"), "{line}");
}

/// A certificate that cannot be written is refused before any work: the refusal names the
/// certificate's path, not the problem file that does not exist either (which the work would
/// read first), for `solve` (files and environments) and `discount`.
#[test]
fn an_unwritable_certificate_is_refused_before_the_problem_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let missing_problem = s(&dir.path().join("no-such-problem.json"));
    let cert = s(&dir.path().join("no-such-dir").join("c.json"));
    let command = |source: [&str; 3], target: &str| -> Vec<String> {
        let mut args: Vec<String> = source.iter().map(|a| a.to_string()).collect();
        args.extend(["--certificate".to_string(), target.to_string()]);
        if source[0] == "solve" {
            args.extend(["--algorithm".to_string(), "exact".to_string()]);
        }
        args
    };
    let solve_file = ["solve", "--file", missing_problem.as_str()];
    for source in [
        solve_file,
        ["solve", "--env", "no-such-env"],
        ["discount", "--file", missing_problem.as_str()],
    ] {
        let args = command(source, &cert);
        let err = fails_one_line(&args);
        assert!(
            err.contains("cannot write") && err.contains("no-such-dir"),
            "{args:?}: {err}"
        );
        assert!(
            !err.contains("no-such-problem") && !err.contains("no-such-env"),
            "{err}"
        );
    }
    let err = fails_one_line(&command(solve_file, &s(dir.path())));
    assert!(err.contains("is a directory"), "{err}");
}

//! Reach certificates (the greatest probability of reaching a goal): `truecost check` accepts
//! a hand-derived certificate of a hand-written problem and the library's exact reach optima
//! of an environment and a perturbed paper problem, and rejects each kind of tampering naming
//! the first failing state and condition. Expected values are derived by hand in the comments;
//! the SHA-256 of hand-written certificates comes from the `sha2` crate.

mod common;

use std::path::{Path, PathBuf};

use common::cli::{fails_one_line, json, stdout};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

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
const HAND: &str = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [3], "actions": [
  [{"cost": "1", "outcomes": [{"to": 1, "p": "3/4"}, {"to": 4, "p": "1/4"}]}, {"to": 2, "cost": "1"}],
  [{"cost": "1", "outcomes": [{"to": 3, "p": "1/2"}, {"to": 0, "p": "1/2"}]}],
  [{"to": 2, "cost": "1"}, {"cost": "1", "outcomes": [{"to": 3, "p": "1/3"}, {"to": 4, "p": "2/3"}]}],
  [],
  [{"to": 4, "cost": "1"}]
]}"#;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn s(p: &Path) -> String {
    p.display().to_string()
}

/// The hand certificate of [`HAND`] as the file `problem` records it.
fn hand_certificate(problem: &Path) -> Value {
    let sha = format!("{:x}", Sha256::digest(HAND.as_bytes()));
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

/// `check <source> C --format json` on `cert`, which must be accepted.
fn accepted(dir: &Path, source: &[&str], cert: &Value) -> Value {
    let path = write(dir, "accept.cert.json", &cert.to_string());
    let p = s(&path);
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    args.extend_from_slice(&[&p, "--format", "json"]);
    let v = json(&args);
    assert_eq!(v["accepted"], true, "{v}");
    assert_eq!(v["objective"], "reach", "{v}");
    v
}

/// The first failing `(state, condition)` of `check <source> C` on `cert`, which must be
/// rejected in one line.
fn first_failure(dir: &Path, source: &[&str], cert: &Value) -> (Option<usize>, String) {
    let path = write(dir, "reject.cert.json", &cert.to_string());
    let p = s(&path);
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    args.push(&p);
    let line = fails_one_line(&args);
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
    let condition = rest.strip_prefix("condition ").unwrap().split_once(':');
    (state, condition.unwrap().0.to_string())
}

fn tampered(cert: &Value, edit: impl FnOnce(&mut Value)) -> Value {
    let mut c = cert.clone();
    edit(&mut c);
    c
}

#[test]
fn the_hand_reach_certificate_is_accepted_with_every_condition_listed() {
    let dir = tempfile::tempdir().unwrap();
    let problem = write(dir.path(), "hand.json", HAND);
    let source = ["--file", &s(&problem)];
    let v = accepted(dir.path(), &source, &hand_certificate(&problem));
    let names: Vec<&str> = v["conditions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
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
    let scaled = tampered(&hand_certificate(&problem), |c| {
        c["values"] = json!(["6/10", "12/15", "2/6", "7/7", "0/3"]);
    });
    accepted(dir.path(), &source, &scaled);
}

#[test]
fn each_reach_tampering_names_its_first_failing_state_and_condition() {
    let dir = tempfile::tempdir().unwrap();
    let problem = write(dir.path(), "hand.json", HAND);
    let source = ["--file", &s(&problem)];
    let cert = hand_certificate(&problem);
    let fails = |edit: &dyn Fn(&mut Value)| {
        first_failure(dir.path(), &source, &tampered(&cert, |c| edit(c)))
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
        &HAND.replace("1/3", "1/4").replace("2/3", "3/4"),
    );
    assert_eq!(
        first_failure(dir.path(), &["--file", &s(&other)], &cert),
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

/// The library's exact reach optimum (`objectives::Model::solve` with `Objective::Reach`) as a
/// certificate: the problem record is that of the truecost certificate `solve --certificate`
/// writes for the same source (the same model, hence the same canonical SHA-256).
fn library_reach_certificate(
    dir: &Path,
    source: &[&str],
    model: truecost::objectives::Model,
) -> Value {
    let path = dir.join("truecost.cert.json");
    let mut args = vec!["solve"];
    args.extend_from_slice(source);
    let p = s(&path);
    args.extend_from_slice(&["--algorithm", "exact", "--certificate", &p]);
    stdout(&args);
    let record = truecost::certificate::parse(&std::fs::read_to_string(&path).unwrap())
        .unwrap()
        .problem;
    let solution = model
        .solve(&truecost::objectives::Objective::Reach)
        .unwrap();
    let p = &model.problem;
    let policy: Vec<Option<usize>> = solution
        .policy
        .iter()
        .enumerate()
        .map(|(x, a)| a.map(|a| a - p.actions(x).start))
        .collect();
    let values = solution.values.iter().map(|v| v.to_string()).collect();
    let text = truecost::certificate::write(
        &truecost::certificate::CertifiedObjective::Reach,
        &record,
        values,
        &policy,
    );
    serde_json::from_str(&text).unwrap()
}

#[test]
fn library_reach_optima_are_accepted_and_their_tampering_rejected() {
    use truecost::objectives::Source;
    use truecost::stochastic::{NoiseModel, Predictability};
    let dir = tempfile::tempdir().unwrap();
    let lake = Source::Env("frozenlake".into()).load().unwrap();
    let cert = library_reach_certificate(dir.path(), &["--env", "frozenlake"], lake);
    let v = accepted(dir.path(), &["--env", "frozenlake"], &cert);
    assert_eq!(v["states"], 16);
    // The holes and the goal: 5 holes of value 0, the goal 15 of value 1.
    let values = cert["values"].as_array().unwrap();
    assert_eq!(values[15], "1");
    for hole in [5, 7, 11, 12] {
        assert_eq!(values[hole], "0", "hole {hole}");
    }
    // Problem 10 under the paper's noise model, γ = 0.9.
    let gamma = Predictability::parse("0.9").unwrap();
    let paper = Source::Paper {
        id: 10,
        step: truecost::problems::StepCost::default(),
        noise: NoiseModel::default(),
        gamma,
    }
    .load()
    .unwrap();
    let source = ["--problem", "10", "--gamma", "0.9"];
    let cert = library_reach_certificate(dir.path(), &source, paper);
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
    let (state, condition) = first_failure(dir.path(), &["--problem", "10"], &off);
    assert!(state.unwrap() <= x);
    assert_eq!(condition, "evaluation");
}

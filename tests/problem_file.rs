//! The JSON problem-file format (`truecost::model::file`): round trips, and a one-line error
//! naming the problem for every bad input.

mod common;

use common::*;
use proptest::prelude::*;
use truecost::model::file::{from_json, read, to_json, FORMAT};
use truecost::model::Problem;

/// The example of the format's documentation.
const DOC_EXAMPLE: &str = r#"{
  "format": "truecost-problem/1",
  "name": "a line of three states",
  "states": 3,
  "initial": 0,
  "goals": [2],
  "actions": [
    [ { "to": 1, "cost": "1" } ],
    [ { "to": 0, "cost": "1" }, { "to": 2, "cost": "5/2" } ],
    []
  ]
}"#;

fn doc_problem() -> Problem {
    Problem::new(
        vec![
            vec![mv(1, int(1))],
            vec![mv(0, int(1)), mv(2, frac(5, 2))],
            vec![],
        ],
        0,
        vec![2],
    )
    .unwrap()
}

/// Parses `text`, expects an error, and checks its message is one line containing every
/// `needle`.
fn refused(text: &str, needles: &[&str]) -> String {
    let result = from_json(text);
    let msg = match result {
        Ok(p) => panic!("accepted {text}\nas {p:?}"),
        Err(e) => e.to_string(),
    };
    assert!(!msg.is_empty());
    assert!(
        !msg.contains('\n') && !msg.contains('\r'),
        "multi-line message: {msg:?}"
    );
    for n in needles {
        assert!(msg.contains(n), "message {msg:?} does not mention {n:?}");
    }
    msg
}

/// A valid minimal file with one field replaced (as raw JSON text).
fn with(field: &str, value: &str) -> String {
    let mut fields = vec![
        ("initial", "0".to_string()),
        ("goals", "[1]".to_string()),
        (
            "actions",
            r#"[[{"to": 1, "cost": "800/19"}, {"to": 0, "cost": "0"}], []]"#.to_string(),
        ),
    ];
    match fields.iter_mut().find(|(k, _)| *k == field) {
        Some(slot) => slot.1 = value.to_string(),
        None => fields.push((field, value.to_string())),
    }
    let body: Vec<String> = fields
        .iter()
        .map(|(k, v)| format!("\"{k}\": {v}"))
        .collect();
    format!("{{{}}}", body.join(", "))
}

fn without(field: &str) -> String {
    let full = with("format", &format!("\"{FORMAT}\""));
    let v: serde_json::Value = serde_json::from_str(&full).unwrap();
    let mut map = v.as_object().unwrap().clone();
    map.remove(field);
    serde_json::Value::Object(map).to_string()
}

#[test]
fn documented_example_parses() {
    assert_eq!(from_json(DOC_EXAMPLE).unwrap(), doc_problem());
    assert_eq!(FORMAT, "truecost-problem/1");
    // Minimal: `format`, `name`, `states` are optional.
    let p = from_json(&with("initial", "0")).unwrap();
    assert_eq!(p.states(), 2);
    assert_eq!(p.moves(0)[0].cost, frac(800, 19));
    assert_eq!(p.moves(0)[1].successor, 0);
    assert_eq!(p.goals(), &[1]);
    // Costs in every exact notation.
    let text = r#"{"initial": 0, "goals": [1], "actions": [[
        {"to": 1, "cost": "0.25"}, {"to": 1, "cost": "1e-3"}, {"to": 1, "cost": "7"}], []]}"#;
    let p = from_json(text).unwrap();
    let costs: Vec<Q> = p.moves(0).iter().map(|m| m.cost.clone()).collect();
    assert_eq!(costs, vec![frac(1, 4), frac(1, 1000), int(7)]);
}

#[test]
fn valid_file_round_trips() {
    let p = doc_problem();
    let text = to_json(&p, Some("a line"));
    assert!(text.contains("\"truecost-problem/1\""));
    assert!(text.contains("\"a line\""));
    assert!(text.contains("\"5/2\""));
    assert_eq!(from_json(&text).unwrap(), p);
    // Stable: writing what was read gives the same text.
    assert_eq!(to_json(&from_json(&text).unwrap(), Some("a line")), text);
    // Without a name.
    let text = to_json(&p, None);
    assert!(!text.contains("\"name\""));
    assert_eq!(from_json(&text).unwrap(), p);
}

#[test]
fn read_from_disk() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("line.json");
    std::fs::write(&path, DOC_EXAMPLE).unwrap();
    assert_eq!(read(&path).unwrap(), doc_problem());

    let missing = dir.path().join("does-not-exist.json");
    let err = read(&missing).unwrap_err().to_string();
    assert!(!err.contains('\n'), "{err}");
    assert!(err.contains("does-not-exist.json"), "{err}");
    assert!(err.contains("cannot read"), "{err}");

    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, "{").unwrap();
    let err = read(&bad).unwrap_err().to_string();
    assert!(!err.contains('\n'), "{err}");
    assert!(err.contains("not valid"), "{err}");
}

#[test]
fn malformed_json() {
    refused("", &["not valid"]);
    refused("{", &["not valid"]);
    refused("[1, 2", &["not valid"]);
    refused("not json at all", &["not valid"]);
    refused(&(with("initial", "0") + " trailing"), &["not valid"]);
    // Valid JSON of the wrong shape.
    refused("[]", &["not valid"]);
    refused(&with("goals", "2"), &["not valid"]);
    refused(&with("initial", "-1"), &["not valid"]);
    refused(&with("initial", "\"0\""), &["not valid"]);
    refused(
        &with("actions", r#"[[{"to": -1, "cost": "1"}], []]"#),
        &["not valid"],
    );
}

#[test]
fn missing_fields() {
    for field in ["initial", "goals", "actions"] {
        refused(&without(field), &["missing field", field]);
    }
    refused(
        &with("actions", r#"[[{"to": 1}], []]"#),
        &["missing field", "cost"],
    );
    refused(
        &with("actions", r#"[[{"cost": "1"}], []]"#),
        &["missing field", "to"],
    );
    // The optional fields may be left out.
    for field in ["format", "name", "states"] {
        assert!(from_json(&without(field)).is_ok(), "{field} is optional");
    }
}

#[test]
fn unknown_fields() {
    refused(&with("comment", "\"hi\""), &["unknown field", "comment"]);
    refused(
        &with(
            "actions",
            r#"[[{"to": 1, "cost": "1", "weight": "2"}], []]"#,
        ),
        &["unknown field", "weight"],
    );
}

#[test]
fn costs_must_be_exact_non_negative_strings() {
    // JSON numbers would pass through f64.
    refused(
        &with("actions", r#"[[{"to": 1, "cost": 1.5}], []]"#),
        &["invalid type"],
    );
    refused(
        &with("actions", r#"[[{"to": 1, "cost": 1}], []]"#),
        &["invalid type"],
    );
    refused(
        &with(
            "actions",
            r#"[[{"to": 1, "cost": "1"}, {"to": 1, "cost": "abc"}], []]"#,
        ),
        &["state 0", "action 1", "'abc'"],
    );
    refused(
        &with("actions", r#"[[{"to": 1, "cost": "1/0"}], []]"#),
        &["state 0", "'1/0'"],
    );
    refused(
        &with("actions", r#"[[{"to": 1, "cost": ""}], []]"#),
        &["state 0", "action 0"],
    );
    refused(
        &with("actions", r#"[[{"to": 1, "cost": "-1"}], []]"#),
        &["state 0", "action 0", "negative", "-1"],
    );
    refused(
        &with("actions", r#"[[{"to": 1, "cost": "-1/2"}], []]"#),
        &["negative", "-1/2"],
    );
    // "-0" is zero, not negative.
    let p = from_json(&with("actions", r#"[[{"to": 1, "cost": "-0"}], []]"#)).unwrap();
    assert_eq!(p.moves(0)[0].cost, int(0));
}

#[test]
fn indices_must_exist() {
    refused(
        &with(
            "actions",
            r#"[[{"to": 1, "cost": "1"}, {"to": 5, "cost": "1"}], []]"#,
        ),
        &["state 0", "action 1", "successor 5", "does not exist"],
    );
    refused(
        &with("initial", "2"),
        &["initial state 2", "does not exist"],
    );
    refused(
        &with("goals", "[1, 7]"),
        &["goal state 7", "does not exist"],
    );
    refused(&with("goals", "[]"), &["no goal"]);
    refused(
        r#"{"initial": 0, "goals": [0], "actions": []}"#,
        &["no states"],
    );
    refused(
        r#"{"states": 0, "initial": 0, "goals": [0], "actions": []}"#,
        &["no states"],
    );
}

#[test]
fn non_goal_states_need_actions() {
    refused(
        r#"{"initial": 0, "goals": [2], "actions": [[{"to": 2, "cost": "1"}], [], []]}"#,
        &["state 1", "empty action set"],
    );
    // A goal may have none; a trap is modelled by a self-loop.
    let p = from_json(
        r#"{"initial": 0, "goals": [2], "actions": [[{"to": 2, "cost": "1"}], [{"to": 1, "cost": "0"}], []]}"#,
    )
    .unwrap();
    assert_eq!(p.states(), 3);
}

#[test]
fn states_must_match_and_format_must_be_known() {
    refused(&with("states", "3"), &["'states' is 3", "2 action lists"]);
    refused(&with("states", "1"), &["'states' is 1"]);
    assert!(from_json(&with("states", "2")).is_ok());
    refused(
        &with("format", "\"truecost-problem/2\""),
        &["unsupported format", "truecost-problem/2"],
    );
    refused(&with("format", "\"\""), &["unsupported format"]);
    refused(&with("format", "1"), &["not valid"]);
}

#[test]
fn example_problem_files_parse() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("problems");
    let entries = std::fs::read_dir(&dir).expect("the problems/ directory ships with the repo");
    let mut deterministic = 0;
    for entry in entries {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if truecost::stochastic::file::lists_outcomes(&text) {
            // Stochastic files have their own reader (tests/stochastic*.rs).
            truecost::stochastic::file::from_json(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            continue;
        }
        deterministic += 1;
        let p = read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        // And it round-trips through the writer.
        assert_eq!(
            from_json(&to_json(&p, None)).unwrap(),
            p,
            "{}",
            path.display()
        );
    }
    assert!(deterministic >= 4, "the four deterministic examples");
}

proptest! {
    /// Every generated problem round-trips through the format, except that a non-goal state
    /// without moves is refused, naming the first such state.
    #[test]
    fn generated_problems_round_trip(p in small_problem(), name in "[a-z ]{0,12}") {
        let text = to_json(&p, Some(&name));
        let dead = (0..p.states()).find(|&x| !p.is_goal(x) && p.moves(x).is_empty());
        match dead {
            None => {
                let back = from_json(&text);
                prop_assert!(back.is_ok(), "{:?}", back.err().map(|e| e.to_string()));
                let back = back.unwrap();
                prop_assert_eq!(&back, &p);
                prop_assert_eq!(to_json(&back, Some(&name)), text);
            }
            Some(x) => {
                let err = from_json(&text);
                prop_assert!(err.is_err());
                let msg = err.unwrap_err().to_string();
                let needle = format!("state {x} has an empty action set");
                prop_assert!(msg.contains(&needle), "{}", msg);
            }
        }
    }

    /// Huge costs survive exactly.
    #[test]
    fn huge_costs_round_trip(p in huge_problem()) {
        let dead = (0..p.states()).any(|x| !p.is_goal(x) && p.moves(x).is_empty());
        let back = from_json(&to_json(&p, None));
        if dead {
            prop_assert!(back.is_err());
        } else {
            prop_assert_eq!(back.unwrap(), p);
        }
    }
}

/// A cost whose exponent is `i64::MIN` must be refused like any other bad cost; it currently
/// panics inside `parse_rational` ("attempt to negate with overflow"), so a problem file can
/// crash the program (see `values::parse_rejects_exponent_i64_min_without_panicking`).
#[test]
fn cost_with_i64_min_exponent_is_refused_without_panicking() {
    let text = with(
        "actions",
        r#"[[{"to": 1, "cost": "1e-9223372036854775808"}], []]"#,
    );
    let result = std::panic::catch_unwind(|| from_json(&text).map_err(|e| e.to_string()));
    match result {
        Ok(Err(msg)) => {
            assert!(!msg.contains('\n'), "{msg}");
            assert!(msg.contains("state 0"), "{msg}");
        }
        Ok(Ok(p)) => panic!("accepted as {p:?}"),
        Err(_) => panic!("from_json panicked instead of returning Err"),
    }
}

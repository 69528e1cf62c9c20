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

/// A file's text written to a fresh temporary directory (kept alive by the returned guard).
fn on_disk(text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("problem.json");
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap().to_string();
    (dir, path)
}

/// Every command that reads a problem file refuses `text` in one line (exit 1) mentioning
/// each needle.
fn every_command_refuses(text: &str, needles: &[&str]) {
    let (_dir, path) = on_disk(text);
    let path = path.as_str();
    let exact = [
        "solve",
        "--file",
        path,
        "--algorithm",
        "exact",
        "--objective",
    ];
    for command in [
        vec!["compare", "--file", path],
        vec!["discount", "--file", path],
        vec!["solve", "--file", path, "--algorithm", "dijkstra"],
        [&exact[..], &["truecost"]].concat(),
        [&exact[..], &["discounted", "--alpha", "1/2"]].concat(),
    ] {
        let err = cli::fails(&command, 1);
        assert_eq!(err.lines().count(), 1, "{command:?}: {err}");
        for n in needles {
            assert!(
                err.contains(n),
                "{command:?}: {err:?} does not mention {n:?}"
            );
        }
    }
}

/// The two-route file of the reward tests: from 0, move to 1 and then into the goal 3 (reward
/// 0, then +1 on entering the goal), or step into the trap 2 (reward 1/2), where the episode
/// ends; every move costs 1, the trap's self-loop 0. `actions` and `terminal` may be replaced.
fn two_routes(actions: &str, terminal: &str) -> String {
    format!(
        r#"{{"format": "truecost-problem/1", "initial": 0, "goals": [3], "terminal": {terminal},
  "actions": {actions}}}"#
    )
}

const TWO_ROUTES_ACTIONS: &str = r#"[
    [{"to": 1, "cost": "1", "reward": "0"}, {"to": 2, "cost": "1", "reward": "1/2"}],
    [{"to": 3, "cost": "1", "reward": "1"}],
    [{"to": 2, "cost": "0", "reward": "0"}],
    []]"#;

#[test]
fn rewards_and_terminal_states_are_read_in_the_global_action_order() {
    use truecost::stochastic::file::{from_json_with_objective, FileObjective, ProblemFile};
    let (problem, extra) =
        from_json_with_objective(&two_routes(TWO_ROUTES_ACTIONS, "[2]")).unwrap();
    assert!(matches!(problem, ProblemFile::Deterministic(_)));
    assert_eq!(
        extra,
        FileObjective {
            rewards: Some(vec![int(0), frac(1, 2), int(1), int(0)]),
            terminal: vec![2],
            initial: None,
        }
    );
    // The deterministic reader (learn, verify) checks and ignores them.
    assert_eq!(
        from_json(&two_routes(TWO_ROUTES_ACTIONS, "[2]"))
            .unwrap()
            .states(),
        4
    );
    // Without the fields: no rewards, no terminal state.
    let plain = from_json_with_objective(&with("format", &format!("\"{FORMAT}\""))).unwrap();
    assert_eq!(plain.1, FileObjective::default());
    // A stochastic file: negative rewards and fractions, read exactly; terminal sorted.
    let text = r#"{"initial": 0, "goals": [3], "terminal": [2, 1], "actions": [
        [{"cost": "1", "reward": "-0.25", "outcomes": [{"to": 3, "p": "1/3"}, {"to": 1, "p": "2/3"}]},
         {"to": 2, "cost": "2", "reward": "-1e-3"}],
        [{"cost": "0", "reward": "0", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 1, "p": "1/2"}]}],
        [{"to": 2, "cost": "0", "reward": "-0"}],
        []]}"#;
    let (ProblemFile::Stochastic(_), extra) = from_json_with_objective(text).unwrap() else {
        panic!("a stochastic file")
    };
    assert_eq!(
        extra.rewards.unwrap(),
        vec![frac(-1, 4), frac(-1, 1000), int(0), int(0)]
    );
    assert_eq!(extra.terminal, vec![1, 2]);
}

#[test]
fn bad_rewards_and_terminal_states_are_refused_in_one_line() {
    let mixed = r#"[
        [{"to": 1, "cost": "1"}, {"to": 2, "cost": "1", "reward": "1/2"}],
        [{"to": 3, "cost": "1", "reward": "1"}],
        [{"to": 2, "cost": "0"}],
        []]"#;
    let number = TWO_ROUTES_ACTIONS.replace(r#""reward": "1/2""#, r#""reward": 0.5"#);
    let text = TWO_ROUTES_ACTIONS.replace(r#""reward": "1/2""#, r#""reward": "half""#);
    let leaky = TWO_ROUTES_ACTIONS.replace(
        r#"[{"to": 2, "cost": "0", "reward": "0"}]"#,
        r#"[{"to": 2, "cost": "0", "reward": "0"}, {"to": 0, "cost": "0", "reward": "0"}]"#,
    );
    let costly = TWO_ROUTES_ACTIONS.replace(
        r#"{"to": 2, "cost": "0", "reward": "0"}"#,
        r#"{"to": 2, "cost": "1/4", "reward": "0"}"#,
    );
    let rewarding = TWO_ROUTES_ACTIONS.replace(
        r#"{"to": 2, "cost": "0", "reward": "0"}"#,
        r#"{"to": 2, "cost": "0", "reward": "-1"}"#,
    );
    let cases: Vec<(String, Vec<&str>)> = vec![
        // Some actions with a reward, some without: the first without one is named (state 0,
        // action 0, before the first reward of the file).
        (
            two_routes(mixed, "[2]"),
            vec!["state 0, action 0 has no \"reward\"", "every action"],
        ),
        // A JSON number would pass through f64, as for costs.
        (
            two_routes(&number, "[2]"),
            vec!["invalid type", "expected a string"],
        ),
        (
            two_routes(&text, "[2]"),
            vec!["state 0, action 1: reward 'half'", "not an exact number"],
        ),
        (
            two_routes(TWO_ROUTES_ACTIONS, "[3]"),
            vec!["terminal state 3 is a goal"],
        ),
        (
            two_routes(TWO_ROUTES_ACTIONS, "[2, 4]"),
            vec!["terminal state 4 is not a state", "0 to 3"],
        ),
        (
            two_routes(TWO_ROUTES_ACTIONS, "[2, 2]"),
            vec!["terminal state 2 is listed twice"],
        ),
        (
            two_routes(&leaky, "[2]"),
            vec!["terminal state 2, action 1", "zero-cost self-loops"],
        ),
        (
            two_routes(&costly, "[2]"),
            vec!["terminal state 2, action 0", "zero-cost self-loops"],
        ),
        (
            two_routes(&rewarding, "[2]"),
            vec!["terminal state 2, action 0: reward -1", "reward 0"],
        ),
        // A state with real moves is no trap.
        (
            two_routes(TWO_ROUTES_ACTIONS, "[1]"),
            vec!["terminal state 1, action 0", "zero-cost self-loops"],
        ),
        (
            two_routes(TWO_ROUTES_ACTIONS, "[-1]"),
            vec!["not valid", "invalid value: integer `-1`"],
        ),
    ];
    for (text, needles) in cases {
        // The library readers (the deterministic one of learn and verify too) and every command
        // that reads a file refuse it, in one line.
        refused(&text, &needles);
        every_command_refuses(&text, &needles);
    }
}

#[test]
fn a_tiny_file_with_rewards_has_its_hand_computed_discounted_values() {
    // Stochastic: from 0, "try" (reward 1/2: +1 on entering the goal 1, which it does with
    // probability 1/2; else it stays) or "quit" into the trap 2 (reward 1/4, then the episode
    // is over). At alpha = 1/2: try forever gives V = 1/2 + alpha (1/2 V) = 1/2 + V/4, so
    // V = 2/3 > 1/4 (quit): V(0) = 2/3, action 0. With the negated stage costs (both cost 1)
    // instead: try gives V = -1 + V/4 = -4/3, quit -1: quitting is optimal.
    let text = r#"{"initial": 0, "goals": [1], "terminal": [2], "actions": [
        [{"cost": "1", "reward": "1/2", "outcomes": [{"to": 1, "p": "1/2"}, {"to": 0, "p": "1/2"}]},
         {"to": 2, "cost": "1", "reward": "1/4"}],
        [],
        [{"to": 2, "cost": "0", "reward": "0"}]]}"#;
    let discounted =
        |path: &str| cli::solve_json(&["--file", path, "--alpha", "1/2"], "discounted");
    let (_dir, path) = on_disk(text);
    let v = discounted(&path);
    assert_eq!(v["rewards"], "the file's rewards");
    assert_eq!(v["discounted_value_initial"], "2/3");
    assert_eq!(v["values"], serde_json::json!(["2/3", "0", "0"]));
    // Nothing is prescribed where the episode is over (the goal and the terminal trap).
    assert_eq!(v["policy"], serde_json::json!([0, null, null]));
    let costs = text
        .replace(r#", "reward": "1/2""#, "")
        .replace(r#", "reward": "1/4""#, "")
        .replace(r#", "reward": "0""#, "");
    let (_dir2, path2) = on_disk(&costs);
    let c = discounted(&path2);
    assert_eq!(c["rewards"], "negated stage costs");
    assert_eq!(c["discounted_value_initial"], "-1");
    assert_eq!(c["policy"][0], 1);
}

#[test]
fn discount_file_uses_a_deterministic_files_rewards() {
    // The two routes: the goal route returns 0 + alpha * 1 = alpha, the trap 1/2, so a
    // discount-optimal policy fails to reach the goal exactly for alpha <= 1/2 (at 1/2 both
    // routes are optimal). With the negated costs the goal route returns -1 - alpha and the
    // trap -1 (the episode ends there): it fails for every alpha.
    let (_dir, path) = on_disk(&two_routes(TWO_ROUTES_ACTIONS, "[2]"));
    let d = cli::json(&["discount", "--file", &path, "--format", "json"]);
    assert_eq!(d["rewards"], "the file's rewards");
    assert_eq!(d["set"], "(0, 1/2]");
    let costs = two_routes(TWO_ROUTES_ACTIONS, "[2]")
        .replace(r#", "reward": "0""#, "")
        .replace(r#", "reward": "1/2""#, "")
        .replace(r#", "reward": "1""#, "");
    let (_dir2, path2) = on_disk(&costs);
    let c = cli::json(&["discount", "--file", &path2, "--format", "json"]);
    assert_eq!(c["rewards"], "negated stage costs");
    assert_eq!(c["set"], "(0, 1)");
}

#[test]
fn noise_keeps_each_actions_reward() {
    // `--gamma 1/2` (paper noise: the commanded successor 1/2, the rest spread over the state's
    // other moves and staying) on the two routes, at alpha = 1/2. V(3) = 0 (goal), V(2) = 0
    // (terminal). State 1 (one move): V1 = 1 + alpha (V1/2), so V1 = 4/3. State 0 (two moves:
    // the commanded one 1/2, the other 1/4, stay 1/4): towards 1, 0 + alpha (V1/2 + V0/4) =
    // 1/3 + V0/8; towards the trap, 1/2 + alpha (V1/4 + V0/4) = 2/3 + V0/8, the better one, so
    // V0 = 2/3 + V0/8: V0 = 16/21.
    let (_dir, path) = on_disk(&two_routes(TWO_ROUTES_ACTIONS, "[2]"));
    let v = cli::json(&[
        "solve",
        "--file",
        &path,
        "--gamma",
        "1/2",
        "--algorithm",
        "exact",
        "--objective",
        "discounted",
        "--alpha",
        "1/2",
        "--format",
        "json",
    ]);
    assert_eq!(v["discounted_value_initial"], "16/21");
    assert_eq!(v["values"], serde_json::json!(["16/21", "4/3", "0", "0"]));
    assert_eq!(v["policy"], serde_json::json!([1, 0, null, null]));
}

/// The initial-distribution file of the tests below: 1/3 on state 0, two from the goal 3 at
/// cost 2, and 2/3 on state 1, which goes on to state 2 (cost 3) or straight into the goal
/// (cost 6); state 2 enters the goal (cost 2) or stays (cost 1). `initial` may be replaced.
fn drawn(initial: &str) -> String {
    format!(
        r#"{{"format": "truecost-problem/1", "initial": {initial}, "goals": [3], "actions": [
    [{{"to": 3, "cost": "2"}}],
    [{{"to": 2, "cost": "3"}}, {{"to": 3, "cost": "6"}}],
    [{{"to": 3, "cost": "2"}}, {{"to": 2, "cost": "1"}}],
    []]}}"#
    )
}

const ONE_THIRD_TWO_THIRDS: &str = r#"[{"state": 0, "p": "1/3"}, {"state": 1, "p": "2/3"}]"#;

#[test]
fn an_initial_distribution_is_read_exactly_and_a_single_entry_is_the_state() {
    use truecost::model::file::from_json_with_objective;
    use truecost::stochastic::file::{self as sfile, ProblemFile};
    let text = drawn(ONE_THIRD_TWO_THIRDS);
    let (problem, extra) = from_json_with_objective(&text).unwrap();
    // The problem keeps the first listed state; the distribution is returned beside it.
    assert_eq!(problem.initial(), 0);
    assert_eq!(extra.initial, Some(vec![(0, frac(1, 3)), (1, frac(2, 3))]));
    // Listed in another order, with other spellings of the same numbers: the first listed
    // state is the problem's.
    let (problem, extra) = from_json_with_objective(&drawn(
        r#"[{"p": "4/6", "state": 1}, {"state": 0, "p": "0.25e0"}, {"state": 2, "p": "1/12"}]"#,
    ))
    .unwrap();
    assert_eq!(
        extra.initial,
        Some(vec![(1, frac(2, 3)), (0, frac(1, 4)), (2, frac(1, 12))])
    );
    assert_eq!(problem.initial(), 1);
    // A decimal close to 1/3 is not 1/3: 2/3 + 3333333333/10^10 = 29999999999/(3 * 10^10).
    let close = drawn(r#"[{"state": 1, "p": "4/6"}, {"state": 0, "p": "0.3333333333"}]"#);
    let e = from_json_with_objective(&close).unwrap_err().to_string();
    assert_eq!(
        e,
        "the initial probabilities sum to 29999999999/30000000000, not 1"
    );
    // The stochastic reader gives the same.
    let (ProblemFile::Deterministic(_), s_extra) = sfile::from_json_with_objective(&text).unwrap()
    else {
        panic!("no outcomes: a deterministic file")
    };
    assert_eq!(
        s_extra.initial,
        Some(vec![(0, frac(1, 3)), (1, frac(2, 3))])
    );
    // One entry of probability 1 is the state number.
    let single = from_json_with_objective(&drawn(r#"[{"state": 2, "p": "1"}]"#)).unwrap();
    assert_eq!(single.0, from_json(&drawn("2")).unwrap());
    assert_eq!(single.1.initial, None);
    // The readers that return a single initial state refuse the distribution.
    refused(
        &text,
        &[
            "draws its initial state from 2 states",
            "this command needs a single initial state",
        ],
    );
    let e = sfile::from_json(&text).unwrap_err().to_string();
    assert!(
        e.contains("from 2 states; this command needs a single"),
        "{e}"
    );
}

#[test]
fn bad_initial_distributions_are_refused_in_one_line() {
    let cases: Vec<(&str, Vec<&str>)> = vec![
        (
            r#"[{"state": 0, "p": "1/3"}, {"state": 1, "p": "1/3"}]"#,
            vec!["the initial probabilities sum to 2/3, not 1"],
        ),
        (
            r#"[{"state": 0, "p": "1/2"}, {"state": 1, "p": "1/2"}, {"state": 2, "p": "1/2"}]"#,
            vec!["the initial probabilities sum to 3/2, not 1"],
        ),
        (
            r#"[{"state": 1, "p": "1/2"}, {"state": 1, "p": "1/2"}]"#,
            vec!["initial entry 1: state 1 is listed twice (first in entry 0)"],
        ),
        (
            r#"[{"state": 0, "p": "1/2"}, {"state": 4, "p": "1/2"}]"#,
            vec!["initial entry 1: state 4 is not a state of this problem (states 0 to 3)"],
        ),
        (
            r#"[{"state": 0, "p": "0"}, {"state": 1, "p": "1"}]"#,
            vec!["initial entry 0 (state 0): probability 0 is not in (0, 1]"],
        ),
        (
            r#"[{"state": 0, "p": "3/2"}, {"state": 1, "p": "-1/2"}]"#,
            vec!["initial entry 0 (state 0): probability 3/2 is not in (0, 1]"],
        ),
        (
            r#"[{"state": 0, "p": "1/2"}, {"state": 1, "p": 0.5}]"#,
            vec!["initial entry 1 (state 1): probability 0.5 is not a string"],
        ),
        (
            r#"[{"state": 0, "p": "half"}, {"state": 1, "p": "1/2"}]"#,
            vec![
                "initial entry 0 (state 0): probability 'half'",
                "not an exact number",
            ],
        ),
        ("[]", vec![r#""initial" is an empty list"#]),
        (r#"[{"state": 0}]"#, vec!["not valid", "missing field `p`"]),
        (
            r#""0""#,
            vec!["not valid", "expected a state number or a list"],
        ),
    ];
    for (initial, needles) in cases {
        let text = drawn(initial);
        // The library readers, with the distribution and without, refuse it in one line...
        refused(&text, &needles);
        let e = truecost::model::file::from_json_with_objective(&text)
            .unwrap_err()
            .to_string();
        let s = truecost::stochastic::file::from_json_with_objective(&text)
            .unwrap_err()
            .to_string();
        assert_eq!(e, s, "{initial}");
        // ...and so does every command that reads the file, with exit 1.
        every_command_refuses(&text, &needles);
    }
}

#[test]
fn the_objectives_take_the_initial_distribution_by_hand() {
    // G*(0) = 2; G*(1) = min(3 + G*(2), 6) = 5 with G*(2) = 2 (staying at 2 never ends): at
    // the distribution, 1/3 * 2 + 2/3 * 5 = 4, in 1/3 * 1 + 2/3 * 2 = 5/3 expected steps.
    let (_dir, path) = on_disk(&drawn(ONE_THIRD_TWO_THIRDS));
    let solve = |objective: &str, alpha: Option<&str>| {
        let mut source = vec!["--file", path.as_str()];
        if let Some(a) = alpha {
            source.extend_from_slice(&["--alpha", a]);
        }
        cli::solve_json(&source, objective)
    };
    let t = solve("truecost", None);
    assert_eq!(t["cost_to_go_initial"], "4");
    let text = cli::stdout(&[
        "solve",
        "--file",
        &path,
        "--algorithm",
        "exact",
        "--objective",
        "truecost",
    ]);
    assert!(
        text.contains("drawn from 2 states (values are expectations)"),
        "not uniform: {text}"
    );
    assert_eq!(t["values"], serde_json::json!(["2", "5", "2", "0"]));
    assert_eq!(t["expected_steps"], "5/3");
    assert_eq!(t["initial_states"], 2);
    // Every policy that moves on reaches the goal: reach 1.
    let r = solve("reach", None);
    assert_eq!(r["reach_probability_initial"], "1");
    // Discounted, the negated costs: staying at 2 returns -1/(1 - a), entering the goal -2.
    // At a = 1/4: V(2) = max(-2, -4/3) = -4/3 (stay: the goal is never reached from 1),
    // V(1) = max(-3 + V(2)/4, -6) = -10/3, V(0) = -2; at the distribution
    // 1/3 * (-2) + 2/3 * (-10/3) = -26/9, and the policy reaches the goal with probability 1/3.
    let d = solve("discounted", Some("1/4"));
    assert_eq!(d["discounted_value_initial"], "-26/9");
    assert_eq!(d["values"], serde_json::json!(["-2", "-10/3", "-4/3", "0"]));
    assert_eq!(d["success_probability"], "1/3");
    // At a = 9/10: V(2) = max(-2, -10) = -2, V(1) = -3 - 9/10 * 2 = -24/5: at the distribution
    // 1/3 * (-2) + 2/3 * (-24/5) = -58/15, every policy optimal there reaching the goal.
    let d = solve("discounted", Some("9/10"));
    assert_eq!(d["discounted_value_initial"], "-58/15");
    assert_eq!(d["success_probability"], "1");
    // `discount`: staying at 2 is optimal iff 1/(1 - a) <= 2, i.e. a <= 1/2 (at 1/2 both
    // are). Only an episode started at 1 passes through 2, so a discount-optimal policy fails
    // from the distribution for a in (0, 1/2], and from state 0 alone never.
    let set = |initial: &str| {
        let (_dir, path) = on_disk(&drawn(initial));
        cli::json(&["discount", "--file", &path, "--format", "json"])["set"].clone()
    };
    assert_eq!(set(ONE_THIRD_TWO_THIRDS), "(0, 1/2]");
    assert_eq!(set("0"), "empty");
    assert_eq!(set("1"), "(0, 1/2]");
    let text = cli::stdout(&["discount", "--file", &path]);
    assert!(
        text.contains("fails to reach the goal from some of the 2 initial states:\n  (0, 1/2]"),
        "{text}"
    );
    // `compare` values every objective at the distribution too.
    let c = cli::json(&[
        "compare", "--file", &path, "--alphas", "1/4", "--format", "json",
    ]);
    assert_eq!(c["initial_states"], 2);
    assert_eq!(c["rows"][0]["value_initial"], "4");
    assert_eq!(c["rows"][2]["value_initial"], "-26/9");
}

#[test]
fn commands_of_a_single_initial_state_refuse_a_distribution_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let (_d, path) = on_disk(&drawn(ONE_THIRD_TWO_THIRDS));
    let figure = dir.path().join("figure.svg");
    let figure_text = figure.to_str().unwrap();
    for (command, name) in [
        (
            vec!["solve", "--file", &path, "--algorithm", "dijkstra"],
            "solve without --objective",
        ),
        (
            vec!["solve", "--file", &path, "--algorithm", "exact"],
            "solve without --objective",
        ),
        (
            vec![
                "solve",
                "--file",
                &path,
                "--gamma",
                "0.9",
                "--algorithm",
                "vi",
            ],
            "solve without --objective",
        ),
        (
            vec!["render", "--file", &path, "--out", figure_text],
            "render",
        ),
        (
            vec![
                "render",
                "--file",
                &path,
                "--overlay",
                "values",
                "--out",
                figure_text,
            ],
            "render",
        ),
        (
            vec!["verify", "--claim", "C4", "--file", &path],
            "this command",
        ),
    ] {
        let err = cli::fails(&command, 1);
        assert_eq!(
            err.trim_end(),
            format!(
                "error: this file draws its initial state from 2 states; {name} needs a single initial state (solve --objective, compare and discount take the distribution)"
            ),
            "{command:?}"
        );
    }
    assert!(!figure.exists(), "no figure drawn");
    // The same file with a single initial state is accepted by each of them.
    let (_d1, single) = on_disk(&drawn("1"));
    cli::stdout(&["solve", "--file", &single, "--algorithm", "dijkstra"]);
    cli::stdout(&["render", "--file", &single, "--out", figure_text]);
    assert!(figure.exists());
    cli::stdout(&["verify", "--claim", "C4", "--file", &single]);
    // `learn` updates every state-action pair against Q*, whatever the initial state: it reads
    // the distribution and replays exactly as from a single initial state.
    let learn = |file: &str| {
        cli::stdout(&[
            "learn", "--file", file, "--q0", "0", "--order", "cyclic", "--rounds", "6",
        ])
    };
    let replay = learn(&path);
    assert_eq!(replay, learn(&single));
    // Q*(1, ->2) = 3 + G*(2) = 5, Q*(2, ->2) = 1 + G*(2) = 3.
    assert!(
        replay.contains("Q(1->2)=5") && replay.contains("Q(2->2)=3"),
        "{replay}"
    );
}

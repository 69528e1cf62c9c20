//! Gymnasium environments imported by `python3 -m truecost_gym export` give, read with `--file`,
//! the exact answers of the built-in `--env` benchmarks (docs/guide/gymnasium.md).
//!
//! The fixtures in `tests/data/gym_import/` were written by the importer from Gymnasium 1.4.0's
//! own tables (`python/tests/test_guide_and_fixtures.py` regenerates and compares them when
//! Gymnasium is installed); this file needs no Python. The files carry Gymnasium's expected
//! rewards (`reward` on every action), the holes as `terminal` states and Taxi's initial
//! distribution as the `initial` list, so every objective of `--file` is that of `--env`.
//! `mud_corridor.json` is the guide's environment, whose optimum and discount breakpoint are
//! derived by hand below.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::cli::{json, solve_json as solve};
use serde_json::Value;

/// (fixture, `--env` SPEC): the importer's file and the built-in benchmark it must match.
const PAIRS: [(&str, &str); 5] = [
    ("frozenlake_4x4_slippery.json", "frozenlake"),
    ("frozenlake_4x4.json", "frozenlake:slippery=false"),
    ("cliffwalking.json", "cliffwalking"),
    ("cliffwalking_slippery.json", "cliffwalking:slippery=true"),
    ("taxi.json", "taxi"),
];

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gym_import")
        .join(name)
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `truecost export --env SPEC` into `dir`, parsed.
fn exported(spec: &str, dir: &Path) -> Value {
    let out = dir.join("export.json");
    json_free(&["export", "--env", spec, "--out", out.to_str().unwrap()]);
    read_json(&out)
}

/// Runs a command that must succeed (its stdout is not JSON).
fn json_free(args: &[&str]) {
    common::cli::stdout(args);
}

/// The file's initial states: its `initial` state, or the states its `initial` list draws.
fn initial_states(file: &Value) -> Vec<usize> {
    match &file["initial"] {
        Value::Array(list) => list
            .iter()
            .map(|e| e["state"].as_u64().unwrap() as usize)
            .collect(),
        x => vec![x.as_u64().unwrap() as usize],
    }
}

/// The states where an episode of the file's problem runs: reachable from the initial states
/// along outcomes, not expanding goals (computed from the file's JSON alone).
fn running_states(file: &Value) -> BTreeSet<usize> {
    let goals: BTreeSet<usize> = file["goals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g.as_u64().unwrap() as usize)
        .collect();
    let mut seen = BTreeSet::new();
    let mut stack = initial_states(file);
    while let Some(x) = stack.pop() {
        if goals.contains(&x) || !seen.insert(x) {
            continue;
        }
        for action in file["actions"][x].as_array().unwrap() {
            for o in action["outcomes"].as_array().unwrap() {
                stack.push(o["to"].as_u64().unwrap() as usize);
            }
        }
    }
    seen
}

fn without(mut v: Value, keys: &[&str]) -> Value {
    for k in keys {
        v.as_object_mut().unwrap().remove(*k);
    }
    v
}

#[test]
fn imported_files_hold_the_problems_that_export_env_writes() {
    let dir = tempfile::tempdir().unwrap();
    for (name, spec) in PAIRS {
        let ours = without(read_json(&fixture(name)), &["name"]);
        let theirs = without(exported(spec, dir.path()), &["name"]);
        if spec != "taxi" {
            assert_eq!(ours, theirs, "{name} against export --env {spec}");
            continue;
        }
        // Taxi: the same 500 states, the same initial distribution (uniform over the 300
        // states with the passenger waiting at a depot other than the destination), the same
        // actions wherever an episode runs. Gymnasium's table enters only the 4 delivered states
        // with the taxi at the destination (terminated=True); the other 96 "passenger at the
        // destination" states, which `--env` also makes goals, no episode reaches, and the
        // importer keeps Gymnasium's actions there.
        for key in ["format", "states", "initial"] {
            assert_eq!(ours[key], theirs[key], "taxi: {key}");
        }
        assert_eq!(ours["states"], 500, "no state beyond Gymnasium's");
        // 25 taxi cells x 4 waiting places x 3 other destinations, 1/300 each.
        let initial = ours["initial"].as_array().unwrap();
        assert_eq!(initial.len(), 25 * 4 * 3);
        assert!(initial.iter().all(|e| e["p"] == "1/300"), "uniform");
        let running = running_states(&ours);
        assert_eq!(
            running,
            running_states(&theirs),
            "taxi: the same running states"
        );
        // The initial states and the 100 states with the passenger in the taxi.
        assert_eq!(running.len(), 400, "taxi: 400 running states");
        for &x in &running {
            assert_eq!(ours["actions"][x], theirs["actions"][x], "taxi: state {x}");
        }
        let goals = |v: &Value| -> BTreeSet<u64> {
            v["goals"]
                .as_array()
                .unwrap()
                .iter()
                .map(|g| g.as_u64().unwrap())
                .collect()
        };
        let (our_goals, their_goals) = (goals(&ours), goals(&theirs));
        assert_eq!(
            our_goals.len(),
            4,
            "taxi: the delivered states an episode enters"
        );
        assert!(our_goals.is_subset(&their_goals), "{our_goals:?}");
    }
}

#[test]
fn solve_file_gives_the_exact_answers_of_solve_env() {
    for (name, spec) in PAIRS {
        let path = fixture(name);
        let file = read_json(&path);
        let running = running_states(&file);
        for (objective, key) in [
            ("truecost", "cost_to_go_initial"),
            ("reach", "reach_probability_initial"),
        ] {
            let env = solve(&["--env", spec], objective);
            let ours = solve(&["--file", path.to_str().unwrap()], objective);
            let what = format!("{name} against --env {spec}, {objective}");
            assert_eq!(ours[key], env[key], "{what}");
            for k in [
                "initial_states",
                "success_probability",
                "policy_success_probability",
                "expected_truecost",
                "expected_steps",
            ] {
                assert_eq!(ours[k], env[k], "{what}: {k}");
            }
            for &x in &running {
                assert_eq!(ours["values"][x], env["values"][x], "{what}: value of {x}");
                assert_eq!(ours["policy"][x], env["policy"][x], "{what}: policy at {x}");
            }
        }
    }
}

/// `discount --format json` on a source.
fn discount_full(source: &[&str]) -> Value {
    let mut args = vec!["discount"];
    args.extend_from_slice(source);
    args.extend_from_slice(&["--format", "json"]);
    json(&args)
}

/// `discount --format json` on a source, without the keys that name the source.
fn discount(source: &[&str]) -> Value {
    without(discount_full(source), &["source", "rewards"])
}

#[test]
fn discount_file_of_an_import_equals_discount_env() {
    // The files carry Gymnasium's rewards (FrozenLake: 0 per step, +1 on entering the goal;
    // CliffWalking: -1 per step, -100 per fall) and FrozenLake's holes as terminal states, so
    // the whole analysis must coincide with `--env`'s (breakpoints, brackets, polynomials, optimal
    // actions, achievements, method and its counts of running states). Deterministic CliffWalking
    // has no breakpoint (every discount factor walks the shortest path along the cliff); on the
    // slippery one the discount-optimal path changes with alpha. Taxi's file draws the initial
    // state from Gymnasium's 300 as `--env` does, and its actions have one outcome each, so the
    // analysis takes the deterministic path of `--env taxi`: no breakpoint (every discount
    // factor delivers). The exported Taxi, which has `--env`'s states, goals and actions, is
    // compared whole. The imported one differs from it only at the 96 states no episode reaches
    // (see above): their optimal actions and policy are left out of the comparison, and the
    // method counts them among the states where the episode runs (496 = 400 + 96: it counts
    // every state that is not a goal, and they are goals only in `--env`).
    let dir = tempfile::tempdir().unwrap();
    let exported_taxi = dir.path().join("taxi.json");
    json_free(&[
        "export",
        "--env",
        "taxi",
        "--out",
        exported_taxi.to_str().unwrap(),
    ]);
    assert_eq!(
        discount(&["--file", exported_taxi.to_str().unwrap()]),
        discount(&["--env", "taxi"]),
        "exported taxi"
    );
    for (name, spec, has_breakpoints) in [
        ("frozenlake_4x4_slippery.json", "frozenlake", true),
        ("frozenlake_4x4.json", "frozenlake:slippery=false", false),
        ("cliffwalking.json", "cliffwalking", false),
        (
            "cliffwalking_slippery.json",
            "cliffwalking:slippery=true",
            true,
        ),
        ("taxi.json", "taxi", false),
    ] {
        let path = fixture(name);
        let full = discount_full(&["--file", path.to_str().unwrap()]);
        assert_eq!(full["rewards"], "the file's rewards", "{name}");
        let mut ours = without(full, &["source", "rewards"]);
        let mut env = discount(&["--env", spec]);
        if spec == "taxi" {
            let running = running_states(&read_json(&path));
            assert_eq!(ours["intervals"].as_array().unwrap().len(), 1, "{ours}");
            for v in [&mut ours, &mut env] {
                for key in ["optimal_actions", "policy"] {
                    let per_state = v["intervals"][0][key].as_array_mut().unwrap();
                    assert_eq!(per_state.len(), 500, "{key}");
                    for (x, a) in per_state.iter_mut().enumerate() {
                        if !running.contains(&x) {
                            *a = Value::Null;
                        }
                    }
                }
            }
            let count = |n: usize| format!(", {n} states where the episode runs,");
            let method = env["method"].as_str().unwrap().to_string();
            assert!(method.contains(&count(400)), "{method}");
            env["method"] = Value::from(method.replace(&count(400), &count(496)));
            assert_eq!(ours["initial_states"], 300);
        }
        assert_eq!(ours, env, "{name} against --env {spec}");
        assert_eq!(
            !ours["breakpoints"].as_array().unwrap().is_empty(),
            has_breakpoints,
            "{name}"
        );
    }
}

/// The fixture's JSON with every `reward` removed (the importer's `--rewards costs`).
fn without_rewards(name: &str, dir: &Path) -> PathBuf {
    let mut file = read_json(&fixture(name));
    for list in file["actions"].as_array_mut().unwrap() {
        for action in list.as_array_mut().unwrap() {
            action.as_object_mut().unwrap().remove("reward").unwrap();
        }
    }
    let out = dir.join(name);
    std::fs::write(&out, file.to_string()).unwrap();
    out
}

#[test]
fn discount_file_without_rewards_discounts_the_negated_costs() {
    // Without `reward` (the importer's `--rewards costs`) the discounted objective rewards the
    // negated stage costs: on FrozenLake -1 per step until the episode ends, another objective
    // than Gymnasium's (0 per step, +1 on entering the goal). Every value is then negative
    // (each step from a running state costs 1), where Gymnasium's are positive (some policy
    // reaches the goal with positive probability, and no reward is negative).
    let dir = tempfile::tempdir().unwrap();
    let path = without_rewards("frozenlake_4x4_slippery.json", dir.path());
    let file = path.to_str().unwrap();
    let full = discount_full(&["--file", file]);
    assert_eq!(full["rewards"], "negated stage costs");
    assert_ne!(
        without(full, &["source", "rewards"]),
        discount(&["--env", "frozenlake"])
    );
    let value = |v: Value| -> num_rational::BigRational {
        v["discounted_value_initial"]
            .as_str()
            .unwrap()
            .parse()
            .unwrap()
    };
    let zero = num_rational::BigRational::from_integer(0.into());
    assert!(value(solve_discounted(&["--file", file], "9/10")) < zero);
    assert!(value(solve_discounted(&["--env", "frozenlake"], "9/10")) > zero);
}

/// `solve --objective discounted --alpha A --format json` on a source.
fn solve_discounted(source: &[&str], alpha: &str) -> Value {
    let mut with_alpha = source.to_vec();
    with_alpha.extend_from_slice(&["--alpha", alpha]);
    solve(&with_alpha, "discounted")
}

#[test]
fn solve_file_discounted_gives_the_values_of_solve_env() {
    for (name, spec) in [
        ("frozenlake_4x4_slippery.json", "frozenlake"),
        ("frozenlake_4x4.json", "frozenlake:slippery=false"),
    ] {
        let path = fixture(name);
        for alpha in ["1/2", "9/10"] {
            let ours = solve_discounted(&["--file", path.to_str().unwrap()], alpha);
            let env = solve_discounted(&["--env", spec], alpha);
            assert_eq!(ours["rewards"], "the file's rewards");
            for k in [
                "discounted_value_initial",
                "values",
                "policy",
                "success_probability",
                "policy_success_probability",
                "expected_truecost",
                "expected_steps",
            ] {
                assert_eq!(ours[k], env[k], "{name} at alpha {alpha}: {k}");
            }
        }
    }
    // By hand: without slipping the goal is 6 steps from the start and only the step into it is
    // rewarded (+1), so V(0) = alpha^5: 1/32 at 1/2, 59049/100000 at 9/10.
    let path = fixture("frozenlake_4x4.json");
    for (alpha, value) in [("1/2", "1/32"), ("9/10", "59049/100000")] {
        let ours = solve_discounted(&["--file", path.to_str().unwrap()], alpha);
        assert_eq!(ours["discounted_value_initial"], value, "alpha {alpha}");
    }
}

#[test]
fn taxi_file_discounted_values_are_those_of_the_env() {
    // The file draws the initial state from Gymnasium's 300 as `--env taxi` does, so at every
    // state where an episode runs the discounted values and optimal actions are the
    // environment's, and so is everything at the initial distribution (its value, the
    // success probabilities, the expected truecost and steps).
    let path = fixture("taxi.json");
    let running = running_states(&read_json(&path));
    for alpha in ["1/2", "99/100"] {
        let ours = solve_discounted(&["--file", path.to_str().unwrap()], alpha);
        let env = solve_discounted(&["--env", "taxi"], alpha);
        assert_eq!(ours["rewards"], "the file's rewards");
        for &x in &running {
            assert_eq!(
                ours["values"][x], env["values"][x],
                "alpha {alpha}: value of {x}"
            );
            assert_eq!(
                ours["policy"][x], env["policy"][x],
                "alpha {alpha}: policy at {x}"
            );
        }
        for k in [
            "discounted_value_initial",
            "initial_states",
            "success_probability",
            "policy_success_probability",
            "expected_truecost",
            "expected_steps",
        ] {
            assert_eq!(ours[k], env[k], "alpha {alpha}: {k}");
        }
        // The value at the initial distribution is the mean of the initial states' values.
        let q = |v: &Value| -> num_rational::BigRational { v.as_str().unwrap().parse().unwrap() };
        let initial = initial_states(&read_json(&path));
        let mean = initial
            .iter()
            .map(|&x| q(&ours["values"][x]))
            .sum::<num_rational::BigRational>()
            / num_rational::BigRational::from_integer(initial.len().into());
        assert_eq!(q(&ours["discounted_value_initial"]), mean, "alpha {alpha}");
    }
}

#[test]
fn a_deterministic_table_imported_as_moves_is_a_deterministic_problem() {
    // `--deterministic-moves`: FrozenLake without slipping as a file of moves `{to, cost}`, so
    // the commands on deterministic problems read it and agree with `--env`.
    let path = fixture("frozenlake_4x4_moves.json");
    let file = path.to_str().unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(!text.contains("outcomes"), "moves only");
    let env = solve(&["--env", "frozenlake:slippery=false"], "truecost");
    let ours = solve(&["--file", file], "truecost");
    for k in ["cost_to_go_initial", "values", "policy", "expected_steps"] {
        assert_eq!(ours[k], env[k], "{k}");
    }
    let dijkstra = json(&[
        "solve",
        "--file",
        file,
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    assert_eq!(dijkstra["cost_to_go_initial"], env["cost_to_go_initial"]);
    let c4 = |source: &[&str]| {
        let mut args = vec!["verify", "--claim", "C4"];
        args.extend_from_slice(source);
        args.extend_from_slice(&["--format", "json"]);
        json(&args)
    };
    assert_eq!(
        c4(&["--file", file]),
        c4(&["--env", "frozenlake:slippery=false"])
    );
}

#[test]
fn discount_file_of_moves_discounts_gymnasiums_rewards() {
    // The deterministic file gives `discount` its failure set. With Gymnasium's rewards (0 per
    // step, +1 on entering the goal) a policy that reaches the goal in k steps returns
    // alpha^(k-1) > 0 and one that does not returns 0, so no discount factor makes an optimal
    // policy fail: the set is empty. With the negated costs (the file without rewards) the
    // hole at state 5, two steps away, returns -1 - alpha, more than the goal six steps away
    // (-(1 + alpha + ... + alpha^5)): every discount factor fails.
    let path = fixture("frozenlake_4x4_moves.json");
    let ours = discount_full(&["--file", path.to_str().unwrap()]);
    assert_eq!(ours["rewards"], "the file's rewards");
    assert_eq!(ours["set"], "empty", "{ours}");
    let dir = tempfile::tempdir().unwrap();
    let costs = without_rewards("frozenlake_4x4_moves.json", dir.path());
    let theirs = discount_full(&["--file", costs.to_str().unwrap()]);
    assert_eq!(theirs["rewards"], "negated stage costs");
    assert_eq!(theirs["set"], "(0, 1)", "{theirs}");
}

/// The guide's MudCorridor under the always-right policy, discounted by `a`, from cell `from`
/// (cells 1-3 cost 3, cell 0 costs 1, a move right succeeds with probability 9/10, else the
/// agent stays): `V(i) = (-toll(i) + 9a/10 V(i+1)) / (1 - a/10)`, `V(4) = 0`.
fn mud_go_right(a: f64, from: usize) -> f64 {
    let mut v = 0.0;
    for cell in (from..4).rev() {
        let toll = if cell == 0 { 1.0 } else { 3.0 };
        v = (-toll + 0.9 * a * v) / (1.0 - 0.1 * a);
    }
    v
}

#[test]
fn the_guides_mud_corridor_has_its_hand_computed_optimum_and_breakpoints() {
    let path = fixture("mud_corridor.json");
    let file = path.to_str().unwrap();
    // Truecost: always right; leaving a cell takes 10/9 expected tries, so
    // G*(0) = 10/9 * (1 + 3 + 3 + 3) = 100/9 in 4 * 10/9 = 40/9 expected steps.
    let t = solve(&["--file", file], "truecost");
    assert_eq!(t["cost_to_go_initial"], "100/9");
    assert_eq!(t["expected_steps"], "40/9");
    assert_eq!(
        t["policy"],
        serde_json::json!([1, 1, 1, 1, null]),
        "always right"
    );
    // Discounted (the negated costs are the environment's own rewards): staying on the meadow
    // forever returns -1/(1 - a); the breakpoints are where a state is indifferent between
    // heading for the goal and heading back to the meadow.
    let d = discount(&["--file", file]);
    let alphas: Vec<f64> = d["breakpoints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["alpha_decimal"].as_str().unwrap().parse().unwrap())
        .collect();
    assert_eq!(alphas.len(), 2, "{d}");
    let loiter = |a: f64| -1.0 / (1.0 - a);
    // Cell 1: back to the meadow (-3, then loitering) against onwards.
    let back_from_1 = |a: f64| -3.0 + a * loiter(a);
    assert!((back_from_1(alphas[0]) - mud_go_right(alphas[0], 1)).abs() < 1e-9);
    // Cell 0: loitering against going (every cell onwards going right).
    assert!((loiter(alphas[1]) - mud_go_right(alphas[1], 0)).abs() < 1e-9);
    for (a, goes) in [(alphas[1] - 1e-3, false), (alphas[1] + 1e-3, true)] {
        assert_eq!(mud_go_right(a, 0) > loiter(a), goes, "a = {a}");
    }
    let intervals = d["intervals"].as_array().unwrap();
    assert_eq!(intervals.first().unwrap()["success_probability"], "0");
    assert_eq!(intervals.last().unwrap()["success_probability"], "1");
    assert_eq!(intervals.last().unwrap()["truecost"], "100/9");
}

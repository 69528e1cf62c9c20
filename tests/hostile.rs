//! Hostile input: one regression test for each way hostile input once broke a command, and
//! the contract everywhere — one escaped line on stderr (≤ 300 characters after `error: `),
//! exit 1 for bad input and 2 for usage, no panic, no hang, bounded work.

mod common;

use common::cli::{assert_contract, fails, fails_one_line, json, stdout, truecost, write};
use serde_json::Value;

/// A 4-neighbour `n × n` grid file (goal in the far corner), costs 1-4 or 1.
fn grid_file(n: usize, varied: bool, format: Option<&str>) -> String {
    let mut lists = Vec::new();
    for x in 0..n * n {
        let (r, c) = (x / n, x % n);
        let mut moves = Vec::new();
        if x != n * n - 1 {
            for (dr, dc) in [(0i64, -1i64), (-1, 0), (1, 0), (0, 1)] {
                let (rr, cc) = (r as i64 + dr, c as i64 + dc);
                if (0..n as i64).contains(&rr) && (0..n as i64).contains(&cc) {
                    let y = rr as usize * n + cc as usize;
                    let cost = if varied { 1 + (x * 7 + y * 3) % 4 } else { 1 };
                    moves.push(format!(r#"{{"to": {y}, "cost": "{cost}"}}"#));
                }
            }
        }
        lists.push(format!("[{}]", moves.join(", ")));
    }
    let tag = format
        .map(|f| format!(r#""format": "{f}", "#))
        .unwrap_or_default();
    format!(
        r#"{{{tag}"initial": 0, "goals": [{}], "actions": [{}]}}"#,
        n * n - 1,
        lists.join(",\n")
    )
}

const LINE: &str = include_str!("../problems/line.json");

// `verify --claim C4` on a grid is beyond the enumeration oracle's bound (refused before any
// simple path is listed): the violated-cycle search answers, naming the oracle's refusal. On
// unit-cost grids every cycle costs at least 1 per stage and the cheapest path is the one with
// fewest states, so every bonus M < 0 keeps pi* average-cost optimal: (-inf, 0).
#[test]
fn c4_bonus_set_of_a_grid_beyond_the_oracle_comes_from_the_cycle_search() {
    let dir = tempfile::tempdir().unwrap();
    let grid = write(dir.path(), "grid7.json", &grid_file(7, false, None));
    for source in [
        ["--problem", "10"],
        ["--problem", "0"],
        ["--file", grid.to_str().unwrap()],
    ] {
        let mut args = vec!["verify", "--claim", "C4", "--format", "json"];
        args.extend_from_slice(&source);
        let v = json(&args);
        let method = v["method"].as_str().expect("a method");
        assert!(method.contains("violated-cycle search"), "{method}");
        assert!(
            method.contains("stationary policies from x1 (the bound"),
            "{method}"
        );
        let sets = v["bonus_sets"].as_array().expect("bonus sets");
        assert_eq!(sets.len(), 1, "{v}");
        assert_eq!(sets[0]["exact"], "(-inf, 0)", "{source:?}");
        assert_eq!(sets[0]["printed"], Value::Null, "{v}");
    }
    let err = fails_one_line(&["verify", "--claim", "C4", "--problem", "6"]);
    assert!(err.contains("no goal is reachable"), "{err}");
    // A small file is analysed by the oracle, with both formulas.
    let v = json(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        "problems/line.json",
        "--format",
        "json",
    ]);
    assert!(
        v["bonus_sets"].as_array().is_some_and(|a| !a.is_empty()),
        "{v}"
    );
    assert_eq!(v["bonus_sets"][0]["corrected_agrees"], true, "{v}");
}

/// A chain of `states` states (goal last) whose first `branching` states have a second,
/// costlier move to the next state: exactly `2^branching` stationary policies.
fn branching_chain(states: usize, branching: usize) -> String {
    let rows: Vec<String> = (0..states)
        .map(|x| {
            if x + 1 == states {
                "[]".to_string()
            } else if x < branching {
                format!(
                    r#"[{{"to":{},"cost":"1"}},{{"to":{},"cost":"2"}}]"#,
                    x + 1,
                    x + 1
                )
            } else {
                format!(r#"[{{"to":{},"cost":"1"}}]"#, x + 1)
            }
        })
        .collect();
    format!(
        r#"{{"format":"truecost-problem/1","states":{states},"initial":0,"goals":[{}],"actions":[{}]}}"#,
        states - 1,
        rows.join(",")
    )
}

// The policy bound of the exact bonus analysis counts states too: on 1,021 states 2^22 policies
// took minutes, so a large problem gets a smaller bound (policies x states <= 2^30), checked
// at once; beyond it the violated-cycle search answers, naming the bound. On a branching chain
// every goal path passes every state once and costs at least L* = states - 1 (each move 1 or
// 2), so every bonus M < 0 is in the set: (-inf, 0).
#[test]
fn c4_policy_bound_shrinks_with_the_number_of_states() {
    let dir = tempfile::tempdir().unwrap();
    for (states, branching, bound) in [(1021, 21, "1048576"), (300, 22, "2097152")] {
        let file = write(
            dir.path(),
            &format!("chain{states}.json"),
            &branching_chain(states, branching),
        );
        let started = std::time::Instant::now();
        let v = json(&[
            "verify",
            "--claim",
            "C4",
            "--file",
            file.to_str().unwrap(),
            "--format",
            "json",
        ]);
        assert!(started.elapsed() < std::time::Duration::from_secs(30));
        let method = v["method"].as_str().expect("a method");
        assert!(
            method.contains(&format!("more than {bound} stationary policies")),
            "{method}"
        );
        assert_eq!(v["bonus_sets"][0]["exact"], "(-inf, 0)", "{v}");
        assert_eq!(
            v["bonus_sets"][0]["optimal_cost"],
            (states - 1).to_string(),
            "{v}"
        );
    }
    // A long chain with 2^16 policies is analysed (the cross-check's cycle enumeration enters
    // only nodes on a cycle: it was exponential in the branching on such chains).
    let long = write(dir.path(), "long.json", &branching_chain(1021, 16));
    let v = json(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        long.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let sets = v["bonus_sets"].as_array().expect("bonus sets");
    assert_eq!(sets.len(), 1, "{v}");
    assert_eq!(sets[0]["least_mean_cycle"], Value::Null, "{v}");
    assert_eq!(sets[0]["corrected_agrees"], true, "{v}");
    // A small chain with a few choices is analysed.
    let small = write(dir.path(), "small.json", &branching_chain(20, 4));
    let v = json(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        small.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(
        v["bonus_sets"].as_array().is_some_and(|a| !a.is_empty()),
        "{v}"
    );
}

// `discount` on a stochastic file: the work of one exact probe grows with the size of the
// numbers (the lcm of the probability denominators), not only with the number of states; a
// problem whose single probe would pass the bound is refused before any work.
#[test]
fn discount_bounds_the_work_by_the_numbers_size() {
    // 30 states; state x moves on with probability 1/p_x (p_x the x-th prime above 1000) and
    // otherwise stays: the lcm of the denominators has about 30 x 10 bits.
    let primes: Vec<u64> = (1001u64..)
        .filter(|n| (2..*n).take_while(|d| d * d <= *n).all(|d| n % d != 0))
        .take(30)
        .collect();
    let rows: Vec<String> = primes
        .iter()
        .enumerate()
        .map(|(x, p)| {
            format!(
                r#"[{{"cost":"1","outcomes":[{{"to":{},"p":"1/{p}"}},{{"to":{x},"p":"{}/{p}"}}]}}]"#,
                x + 1,
                p - 1
            )
        })
        .chain(std::iter::once("[]".to_string()))
        .collect();
    let text = format!(
        r#"{{"format":"truecost-stochastic/1","states":31,"initial":0,"goals":[30],"actions":[{}]}}"#,
        rows.join(",")
    );
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "primes.json", &text);
    let started = std::time::Instant::now();
    let err = fails_one_line(&["discount", "--file", file.to_str().unwrap()]);
    assert_contract(&err);
    assert!(
        err.contains("one exact probe of this problem is estimated"),
        "{err}"
    );
    assert!(err.contains("30 running states"), "{err}");
    assert!(started.elapsed() < std::time::Duration::from_secs(10));
    // The same chain with denominators 2 is analysed.
    let halves: Vec<String> = (0..30)
        .map(|x| {
            format!(
                r#"[{{"cost":"1","outcomes":[{{"to":{},"p":"1/2"}},{{"to":{x},"p":"1/2"}}]}}]"#,
                x + 1
            )
        })
        .chain(std::iter::once("[]".to_string()))
        .collect();
    let text = format!(
        r#"{{"format":"truecost-stochastic/1","states":31,"initial":0,"goals":[30],"actions":[{}]}}"#,
        halves.join(",")
    );
    let file = write(dir.path(), "halves.json", &text);
    let v = json(&[
        "discount",
        "--file",
        file.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(v.is_object(), "{v}");
}

// `--file /dev/stdin` and a FIFO are read once (a second read would be refused or hang).
#[test]
fn problem_files_are_read_once_from_pipes() {
    let out = truecost()
        .args([
            "solve",
            "--file",
            "/dev/stdin",
            "--algorithm",
            "dijkstra",
            "--format",
            "json",
        ])
        .write_stdin(LINE)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let v: Value = serde_json::from_slice(&out).unwrap();
    assert_eq!(v["cost_to_go_initial"], "5/2");
    let slippery = std::fs::read_to_string("problems/slippery.json").unwrap();
    truecost()
        .args(["solve", "--file", "/dev/stdin", "--algorithm", "exact"])
        .write_stdin(slippery)
        .assert()
        .success();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("line.svg");
    truecost()
        .args([
            "render",
            "--file",
            "/dev/stdin",
            "--overlay",
            "path",
            "--out",
        ])
        .arg(&out)
        .write_stdin(LINE)
        .assert()
        .success();
    assert!(std::fs::read_to_string(&out).unwrap().contains("<svg"));
}

#[cfg(unix)]
#[test]
fn a_fifo_is_read_once() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("problem.fifo");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        // No mkfifo on this system: the pipe test above covers reading once.
        return;
    }
    let writer = {
        let fifo = fifo.clone();
        // Opening a FIFO for writing blocks until the reader opens it: exactly one reader.
        std::thread::spawn(move || std::fs::write(fifo, LINE).unwrap())
    };
    let text = stdout(&[
        "solve",
        "--file",
        fifo.to_str().unwrap(),
        "--algorithm",
        "vi",
    ]);
    assert!(text.contains("G*(x1)       5/2"), "{text}");
    writer.join().unwrap();
}

// Learning rates are checked as the learner uses them: exactly, and again once rounded to f64.
#[test]
fn learning_rates_are_checked_as_the_learner_uses_them() {
    let base = [
        "reproduce",
        "stochastic",
        "--problems",
        "10",
        "--gammas",
        "0.9",
        "--epsilons",
        "0.9",
        "--samples",
        "1",
        "--episodes",
        "1",
        "--max-steps",
        "1",
        "--format",
        "json",
        "--rhos",
    ];
    fn with<'a>(base: &[&'a str], rho: &'a str) -> Vec<&'a str> {
        [base, &[rho]].concat()
    }
    let run = |rho: &'static str| with(&base, rho);
    let err = fails_one_line(&run("1/n^0.50000000000000001"));
    assert!(err.contains("rounds to 0.5 in f64"), "{err}");
    assert!(err.contains("outside (0.5, 1]"), "{err}");
    let err = fails_one_line(&run("1e-400"));
    assert!(err.contains("rounds to 0.0 in f64"), "{err}");
    assert_contract(&err);
    // A rate beyond f64 precision runs, and the output names the rate that ran.
    let v = json(&run("0.5000000000000000000000001"));
    let rows = v.as_array().unwrap();
    let learning: Vec<&Value> = rows.iter().filter(|r| !r["rho"].is_null()).collect();
    assert!(!learning.is_empty(), "{v}");
    for row in learning {
        assert_eq!(row["rho"], "0.5", "{row}");
    }
}

// `--threads 100000` is refused instead of spawning threads until the system gives out.
#[test]
fn thread_count_is_bounded() {
    for experiment in ["deterministic", "stochastic"] {
        let err = fails_one_line(&[
            "reproduce",
            experiment,
            "--problems",
            "10",
            "--samples",
            "1",
            "--threads",
            "100000",
        ]);
        assert!(err.contains("at most 256 worker threads"), "{err}");
    }
}

// `--plots FILE` is checked before the run, not after it.
#[test]
fn plot_directory_is_checked_before_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "not-a-dir", "x");
    let out = dir.path().join("out");
    // The default run takes minutes: failing at once shows the check comes first.
    let err = fails_one_line(&[
        "reproduce",
        "deterministic",
        "--plots",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(err.contains("cannot create plot directory"), "{err}");
    assert!(!out.join("deterministic.json").exists());
}

// `discount` on a grid over the deterministic state bound is refused with its bound at once.
#[test]
fn discount_of_a_large_grid_is_refused_with_its_bound() {
    let dir = tempfile::tempdir().unwrap();
    // 51 x 51: 2601 states, 2600 where the episode runs, over the deterministic analysis'
    // bound of 2500: refused before any work.
    let grid = write(dir.path(), "grid51.json", &grid_file(51, true, None));
    let started = std::time::Instant::now();
    let err = fails_one_line(&["discount", "--file", grid.to_str().unwrap()]);
    assert_contract(&err);
    assert!(err.contains("2600 states where the episode runs"), "{err}");
    assert!(err.contains("takes at most 2500"), "{err}");
    assert!(started.elapsed() < std::time::Duration::from_secs(10));
    // A 3 x 3 grid with costs 1-4 (refused by the enumeration of goal paths and lassos: 696
    // pairs of degree 17 took five minutes) is answered by the parametric analysis.
    let small = write(dir.path(), "grid3.json", &grid_file(3, true, None));
    let v = json(&[
        "discount",
        "--file",
        small.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(v["set"].is_string(), "{v}");
    assert!(
        v["method"].as_str().unwrap().contains("deterministic"),
        "{v}"
    );
    // The unit-cost grid: one probe, no breakpoint, never a lasso.
    let unit = write(dir.path(), "unit32.json", &grid_file(32, false, None));
    let v = json(&[
        "discount",
        "--file",
        unit.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(v["set"], "empty");
}

/// A file with one move `0 → 1` of cost `cost` (raw JSON string content).
fn one_move(cost: &str) -> String {
    format!(r#"{{"initial": 0, "goals": [1], "actions": [[{{"to": 1, "cost": "{cost}"}}], []]}}"#)
}

// A long cost is refused with its documented length limit named, and echoed shortened.
#[test]
fn number_limits_are_named_and_echoes_are_short() {
    let dir = tempfile::tempdir().unwrap();
    let long = write(dir.path(), "long.json", &one_move(&"7".repeat(5000)));
    let err = fails_one_line(&[
        "solve",
        "--file",
        long.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
    ]);
    assert_contract(&err);
    assert!(
        err.contains("too long for an exact number (5000 bytes; the limit is 4096)"),
        "{err}"
    );
    let huge = write(dir.path(), "huge.json", &one_move(&"7".repeat(1_000_000)));
    let err = fails_one_line(&[
        "solve",
        "--file",
        huge.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
    ]);
    assert_contract(&err);
    assert!(err.len() < 400, "{} bytes", err.len());
    let big = write(dir.path(), "big.json", &one_move("1e10001"));
    let err = fails_one_line(&[
        "solve",
        "--file",
        big.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
    ]);
    assert!(
        err.contains("exponent outside the supported range -10000..=10000"),
        "{err}"
    );
    let edge = write(dir.path(), "edge.json", &one_move("1e10000"));
    let v = json(&[
        "solve",
        "--file",
        edge.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
        "--format",
        "json",
    ]);
    let expected = format!("1{}", "0".repeat(10_000));
    assert_eq!(v["cost_to_go_initial"], expected);
}

// The format tag and the outcomes agree in every command: a stochastic-tagged file without
// outcomes is accepted, a deterministic-tagged file with outcomes is refused.
#[test]
fn format_tags_and_outcomes_agree_in_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let tagged = write(
        dir.path(),
        "tagged.json",
        &LINE.replace("truecost-problem/1", "truecost-stochastic/1"),
    );
    let t = tagged.to_str().unwrap();
    for algorithm in ["dijkstra", "vi", "async-vi", "exact"] {
        let v = json(&[
            "solve",
            "--file",
            t,
            "--algorithm",
            algorithm,
            "--format",
            "json",
        ]);
        assert_eq!(v["cost_to_go_initial"], "5/2", "{algorithm}: {v}");
    }
    let svg = dir.path().join("t.svg");
    truecost()
        .args(["render", "--file", t, "--out"])
        .arg(&svg)
        .assert()
        .success();
    json(&["discount", "--file", t, "--format", "json"]);
    json(&["verify", "--claim", "C4", "--file", t, "--format", "json"]);

    let slippery = std::fs::read_to_string("problems/slippery.json").unwrap();
    let mislabelled = write(
        dir.path(),
        "mislabelled.json",
        &slippery.replace("truecost-stochastic/1", "truecost-problem/1"),
    );
    assert!(slippery.contains("truecost-stochastic/1"));
    let m = mislabelled.to_str().unwrap();
    let out = dir.path().join("m.svg");
    for args in [
        vec!["solve", "--file", m, "--algorithm", "exact"],
        vec!["solve", "--file", m, "--algorithm", "dijkstra"],
        vec!["render", "--file", m, "--out", out.to_str().unwrap()],
    ] {
        let err = fails_one_line(&args);
        assert!(
            err.contains("tagged 'truecost-problem/1'"),
            "{args:?}: {err}"
        );
    }
    // C4 is stated for the deterministic model: it names the outcomes it cannot take.
    let s = "problems/slippery.json";
    let err = fails_one_line(&["verify", "--claim", "C4", "--file", s]);
    assert!(err.contains("lists outcomes"), "{err}");
    // `discount` takes stochastic files (parametric policy analysis);
    // its answers are checked against brute force in tests/discount_stochastic.rs.
    let v = json(&["discount", "--file", s, "--format", "json"]);
    assert!(v.is_object(), "{v}");
}

// Newlines and ANSI escapes in costs, tags and paths are escaped before they reach the terminal.
#[test]
fn echoed_input_is_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let cost = write(dir.path(), "cost.json", &one_move("1\\n\\u001b[31mred"));
    let err = fails_one_line(&[
        "solve",
        "--file",
        cost.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
    ]);
    assert_contract(&err);
    assert!(err.contains("\\n\\x1b[31mred"), "{err}");
    let tag = write(
        dir.path(),
        "tag.json",
        &LINE.replace("truecost-problem/1", "x\\u001b[2J\\ny"),
    );
    let err = fails_one_line(&[
        "solve",
        "--file",
        tag.to_str().unwrap(),
        "--algorithm",
        "dijkstra",
    ]);
    assert_contract(&err);
    assert!(err.contains("x\\x1b[2J\\ny"), "{err}");
    let path = dir.path().join("no\nsuch\u{1b}[31m.json");
    let err = fails(
        &[
            "solve".as_ref(),
            "--file".as_ref(),
            path.as_os_str(),
            "--algorithm".as_ref(),
            "dijkstra".as_ref(),
        ],
        1,
    );
    assert_contract(&err);
    assert!(err.contains("no\\nsuch\\x1b[31m.json"), "{err}");
    // Usage errors (exit 2) are one escaped line too.
    let err = fails(&["solve", "--algorithm", "\u{1b}[31m"], 2);
    assert_contract(&err);
}

// A γ with a huge denominator is refused naming γ, not a state.
#[test]
fn gamma_denominator_limit_names_gamma() {
    let gamma = format!("0.{}1", "9".repeat(30));
    let err = fails_one_line(&[
        "solve",
        "--problem",
        "10",
        "--gamma",
        &gamma,
        "--algorithm",
        "exact",
    ]);
    assert_contract(&err);
    assert!(err.contains("gamma = "), "{err}");
    assert!(err.contains("too large a denominator"), "{err}");
    assert!(err.contains("2^62"), "{err}");
}

// Negative numbers after flags reach the range checks (not clap's "unexpected argument '-0'").
#[test]
fn negative_numbers_reach_the_range_checks() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("v.svg");
    let svg = svg.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "render",
                "--problem",
                "10",
                "--overlay",
                "visits",
                "--epsilon",
                "-0.1",
                "--out",
                svg,
            ],
            "outside",
        ),
        (
            vec![
                "reproduce",
                "stochastic",
                "--problems",
                "10",
                "--samples",
                "1",
                "--gammas",
                "-1",
            ],
            "(0, 1]",
        ),
        (
            vec![
                "reproduce",
                "stochastic",
                "--problems",
                "10",
                "--samples",
                "1",
                "--rhos",
                "-0.5",
            ],
            "outside (0, 1]",
        ),
        (
            vec![
                "reproduce",
                "stochastic",
                "--problems",
                "10",
                "--samples",
                "1",
                "--epsilons",
                "-0.1",
            ],
            "-1/10",
        ),
        (
            vec![
                "solve",
                "--problem",
                "10",
                "--gamma",
                "-1",
                "--algorithm",
                "exact",
            ],
            "(0, 1]",
        ),
    ];
    for (args, needle) in cases {
        let err = fails_one_line(&args);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
}

// `render --overlay path --epsilon 0.5 --seed 5` is refused: the visits options need
// `--overlay visits`.
#[test]
fn visits_options_need_the_visits_overlay() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("p.svg");
    let err = fails_one_line(&[
        "render",
        "--problem",
        "10",
        "--overlay",
        "path",
        "--epsilon",
        "0.5",
        "--seed",
        "5",
        "--out",
        svg.to_str().unwrap(),
    ]);
    assert!(err.contains("--overlay visits"), "{err}");
    assert!(!svg.exists());
}

// Problem 6's planner rows (G* = +inf everywhere) report converged: pinned in
// tests/reproduce.rs.

// Reference-mode JSON gives a number, or null where no goal is reachable, never `"inf"`.
#[test]
fn reference_json_value_is_a_number_or_null() {
    let v = json(&[
        "solve",
        "--problem",
        "6",
        "--algorithm",
        "dijkstra",
        "--mode",
        "reference",
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], Value::Null);
    assert_eq!(v["reachable"], false);
    let v = json(&[
        "solve",
        "--problem",
        "10",
        "--algorithm",
        "dijkstra",
        "--mode",
        "reference",
        "--format",
        "json",
    ]);
    assert!(
        v["cost_to_go_initial"].as_f64().is_some_and(|g| g > 0.0),
        "{v}"
    );
}

// The contract beyond the listed failures: oversized input, output checked before work.
#[test]
fn oversized_files_and_bad_outputs_are_refused_first() {
    let err = fails_one_line(&["solve", "--file", "/dev/zero", "--algorithm", "dijkstra"]);
    assert!(err.contains("larger than 33554432 bytes"), "{err}");
    let err = fails_one_line(&["render", "--problem", "10", "--out", "figure.gif"]);
    assert!(err.contains(".svg or .png"), "{err}");
    let err = fails_one_line(&[
        "render",
        "--problem",
        "10",
        "--width",
        "100000",
        "--out",
        "f.svg",
    ]);
    assert!(err.contains("out of range"), "{err}");
    let err = fails_one_line(&["render", "--problem", "10", "--out", "/no/such/dir/f.svg"]);
    assert!(err.contains("no directory"), "{err}");
}

/// Output files are written whole: `export` onto a path whose directory is missing leaves no
/// temporary file behind and an existing file untouched when it fails; onto `/dev/stdout` (a
/// pipe, which a rename cannot replace) it writes directly.
#[test]
fn exports_replace_files_whole_and_write_to_pipes_directly() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("grid.json");
    std::fs::write(&out, "a good earlier file\n").unwrap();
    let o = truecost()
        .args([
            "export",
            "--grid",
            "3x3",
            "--out",
            &out.display().to_string(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with('{') && text.ends_with("}\n"), "{text}");
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    assert_eq!(
        names,
        vec!["grid.json".to_string()],
        "no temporary file left"
    );
    let piped = truecost()
        .args(["export", "--grid", "3x3", "--out", "/dev/stdout"])
        .output()
        .unwrap();
    assert!(
        piped.status.success(),
        "{}",
        String::from_utf8_lossy(&piped.stderr)
    );
    let printed = String::from_utf8(piped.stdout).unwrap();
    assert!(printed.starts_with("{"), "{printed}");
    assert!(
        printed.contains(&text.trim_end()[..40]),
        "the same file on stdout"
    );
    // A reader that closes the pipe early (`| head -c 1`) is not an error.
    let script = format!(
        "{} export --grid 60x60 --out /dev/stdout | head -c 1 >/dev/null; exit ${{PIPESTATUS[0]}}",
        env!("CARGO_BIN_EXE_truecost")
    );
    let o = std::process::Command::new("bash")
        .args(["-c", &script])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// An absurd `RAYON_NUM_THREADS` is refused before any work, in one line (exit 2), instead of
/// rayon trying to start that many threads.
#[test]
fn an_absurd_thread_variable_is_refused_first() {
    for value in ["100000", "lots"] {
        let o = truecost()
            .env("RAYON_NUM_THREADS", value)
            .args(["solve", "--problem", "10", "--algorithm", "dijkstra"])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{value}");
        let err = String::from_utf8(o.stderr).unwrap();
        assert_contract(&err);
        assert!(err.contains("RAYON_NUM_THREADS"), "{err}");
    }
    let o = truecost()
        .env("RAYON_NUM_THREADS", "2")
        .args(["solve", "--problem", "10", "--algorithm", "dijkstra"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A crafted file or map name reaches stdout escaped: no raw ESC byte for the terminal, no
/// newline that would end a LaTeX comment and inject the rest as LaTeX.
#[test]
fn crafted_names_reach_reports_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m\n\\input{evil}\x1b[2J");
    std::fs::write(&map, "SFF\nFHF\nFFG\n").unwrap();
    let spec = format!("frozenlake:map={},slippery=false", map.display());
    for format in ["text", "latex", "markdown"] {
        let o = truecost()
            .args(["discount", "--env", &spec, "--format", format])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8(o.stdout).unwrap();
        assert!(!out.contains('\x1b'), "{format}: raw ESC in {out:?}");
        assert!(out.contains("m\\n\\input{evil}\\x1b[2J"), "{format}: {out}");
        if format == "latex" {
            for line in out.lines().filter(|l| l.contains("evil")) {
                assert!(line.starts_with('%'), "only inside a comment: {line}");
            }
        }
    }
    let file = dir.path().join("p\x1b]0;title\x07.json");
    std::fs::write(
        &file,
        r#"{"initial":0,"goals":[1],"actions":[[{"to":0,"cost":"1"},{"to":1,"cost":"3"}],[]]}"#,
    )
    .unwrap();
    let o = truecost()
        .args(["discount", "--file", &file.display().to_string()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8(o.stdout).unwrap();
    assert!(!out.chars().any(|c| c == '\x1b' || c == '\x07'), "{out:?}");
    assert!(out.contains("p\\x1b]0;title\\x07.json"), "{out}");
}

/// Usage errors keep what they name: a missing required option is listed, and a negative
/// discount factor is read as a value and refused as one (not taken for a flag `-0`).
#[test]
fn usage_errors_name_what_is_missing_or_wrong() {
    let o = truecost()
        .args(["solve", "--problem", "3"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8(o.stderr).unwrap();
    assert_contract(&err);
    assert!(err.contains("--algorithm"), "{err}");
    assert!(err.contains("see 'truecost solve --help'"), "{err}");
    let o = truecost()
        .args(["compare", "--env", "frozenlake", "--alphas", "-0.5"])
        .output()
        .unwrap();
    assert_ne!(o.status.code(), Some(0));
    let err = String::from_utf8(o.stderr).unwrap();
    assert_contract(&err);
    assert!(!err.contains("unexpected argument"), "{err}");
    assert!(err.contains("-0.5"), "{err}");
}

/// Long input echoed in a refusal is shortened, so the one-line cut keeps the reason: env
/// specs (names, options, values) and probabilities such as --epsilon.
#[test]
fn long_echoes_keep_the_reason() {
    let long = "9".repeat(400);
    let cases = [
        (
            vec![
                "solve".to_string(),
                "--algorithm".into(),
                "exact".into(),
                "--env".into(),
                format!("lake{long}"),
            ],
            "known: frozenlake",
        ),
        (
            vec![
                "solve".to_string(),
                "--algorithm".into(),
                "exact".into(),
                "--env".into(),
                format!("frozenlake:x{long}=1"),
            ],
            "options:",
        ),
        (
            vec![
                "solve".to_string(),
                "--algorithm".into(),
                "exact".into(),
                "--env".into(),
                format!("frozenlake:slippery={long}"),
            ],
            "true or false",
        ),
        (
            vec![
                "solve".to_string(),
                "--algorithm".into(),
                "exact".into(),
                "--env".into(),
                format!("frozenlake:y{long}"),
            ],
            "KEY=VALUE",
        ),
        (
            vec![
                "render".to_string(),
                "--problem".into(),
                "3".into(),
                "--overlay".into(),
                "visits".into(),
                "--epsilon".into(),
                format!("1{long}"),
                "--out".into(),
                "/tmp/never-written.png".into(),
            ],
            "outside [0, 1]",
        ),
    ];
    for (args, reason) in cases {
        let o = truecost().args(&args).output().unwrap();
        assert_ne!(o.status.code(), Some(0), "{args:?}");
        let err = String::from_utf8(o.stderr).unwrap();
        assert_contract(&err);
        assert!(err.contains(reason), "{reason:?} lost in {err}");
    }
}

/// A γ listed twice is refused like a problem listed twice (the same rows would run twice),
/// also when written two ways.
#[test]
fn a_gamma_listed_twice_is_refused() {
    for gammas in ["0.9,0.9", "0.9,9/10"] {
        let o = truecost()
            .args([
                "reproduce",
                "stochastic",
                "--problems",
                "3",
                "--gammas",
                gammas,
            ])
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{gammas}");
        let err = String::from_utf8(o.stderr).unwrap();
        assert_contract(&err);
        assert!(
            err.contains("gamma") && err.contains("listed twice"),
            "{err}"
        );
    }
}

/// Output paths are checked before the work: `export` into a missing directory, `reproduce
/// --out DIR` whose report file is a directory, and `render` onto a file system that refuses
/// new files are refused at once, with nothing computed.
#[test]
fn output_paths_are_checked_before_the_work() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing/dir/x.json");
    let started = std::time::Instant::now();
    let o = truecost()
        .args([
            "export",
            "--grid",
            "300x300",
            "--out",
            &missing.display().to_string(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8(o.stderr).unwrap();
    assert_contract(&err);
    assert!(err.contains("cannot write"), "{err}");
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("deterministic.json")).unwrap();
    let o = truecost()
        .args([
            "reproduce",
            "deterministic",
            "--problems",
            "3",
            "--samples",
            "1",
        ])
        .args(["--out", &out.display().to_string(), "--quiet"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8(o.stderr).unwrap();
    assert_contract(&err);
    assert!(
        err.contains("deterministic.json") && err.contains("is a directory"),
        "{err}"
    );
    // /sys refuses new files even to root: a figure there is refused before it is drawn.
    let o = truecost()
        .args(["render", "--problem", "3", "--out", "/sys/truecost-fig.png"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8(o.stderr).unwrap();
    assert_contract(&err);
    assert!(err.contains("cannot write"), "{err}");
    assert!(started.elapsed().as_secs() < 30, "refused before the work");
}

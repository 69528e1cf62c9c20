//! The number-size bound of the exact solvers (`solve --algorithm exact`, `compare`, and every
//! command that builds the stochastic model): the lcm `C` of the stage costs' denominators and
//! every stage cost scaled to an integer by it take at most 1024 bits, checked as the model is
//! built, before any work. Each edge is tested (accepted at the bound, refused one bit past
//! it, naming the state, the action, the bits and the bound), and so are the hostile inputs
//! that ran for minutes: a 200-state chain of 33,000-bit costs. `compare` solves its
//! discounted rows first, so the exact solver's `2^100` limit on the killed-process
//! construction's stage costs refuses before the truecost and reach objectives' solves.

mod common;

use std::time::{Duration, Instant};

use common::cli::{assert_contract, fails_one_line, json, write};
use num_bigint::BigInt;
use truecost::stochastic::problem::MAX_SCALED_COST_BITS;
use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use truecost::value::Rational;

/// A refusal's time budget in this (debug) test build on a loaded machine; in release each
/// comes within 0.1 s.
const REFUSAL_SECONDS: u64 = 5;

fn pow2(k: u64) -> BigInt {
    BigInt::from(1) << k
}

/// Two states: from 0, the goal 1 at stage cost 0, or a self-loop at stage cost `stay` (never
/// part of a proper policy, so the exact solver never writes an equation for it).
fn two_states(stay: &str) -> String {
    format!(
        r#"{{"states": 2, "initial": 0, "goals": [1], "actions": [[{{"to": 1, "cost": "0"}}, {{"to": 0, "cost": "{stay}"}}], []]}}"#
    )
}

/// The problem of [`two_states`] built directly.
fn built(stay: Rational) -> Result<StochasticProblem, String> {
    let to = |x: usize| Outcome {
        successor: x,
        probability: Rational::from_integer(1.into()),
        kind: OutcomeKind::Listed,
    };
    let actions = vec![
        vec![
            StochasticAction {
                cost: Rational::from_integer(0.into()),
                outcomes: vec![to(1)],
            },
            StochasticAction {
                cost: stay,
                outcomes: vec![to(0)],
            },
        ],
        Vec::new(),
    ];
    StochasticProblem::new(actions, 0, vec![1]).map_err(|e| e.to_string())
}

/// The bound's edges, built directly: an lcm of 1024 bits (`2^1023`) and a scaled cost of
/// 1024 bits (`2^1024 − 1`) pass, one bit more is refused naming the state, the action, the
/// bits and the bound.
#[test]
fn the_scaled_cost_bound_is_exact() {
    assert_eq!(MAX_SCALED_COST_BITS, 1024);
    let over = |k: u64| Rational::new(1.into(), pow2(k));
    assert!(built(over(1023)).is_ok());
    let e = built(over(1024)).unwrap_err();
    for w in [
        "state 0, action 1",
        "the lcm of the stage costs' denominators up to here takes 1025 bits",
        "at most 1024",
        "before any work",
    ] {
        assert!(e.contains(w), "{w:?} missing from {e}");
    }
    assert!(built(Rational::from_integer(pow2(1024) - 1)).is_ok());
    let e = built(Rational::from_integer(pow2(1024))).unwrap_err();
    for w in [
        "state 0, action 1",
        "the stage cost ≈1.79769313486231",
        "1025 bits",
        "at most 1024",
    ] {
        assert!(e.contains(w), "{w:?} missing from {e}");
    }
    // Scaling counts: 3 / 2^1022 scales to 3 under an lcm of 2^1023 set by another action.
    let mixed = vec![
        vec![StochasticAction {
            cost: Rational::new(3.into(), pow2(1022)),
            outcomes: vec![Outcome {
                successor: 1,
                probability: Rational::from_integer(1.into()),
                kind: OutcomeKind::Listed,
            }],
        }],
        vec![StochasticAction {
            cost: Rational::new(1.into(), pow2(1023)),
            outcomes: vec![Outcome {
                successor: 2,
                probability: Rational::from_integer(1.into()),
                kind: OutcomeKind::Listed,
            }],
        }],
        Vec::new(),
    ];
    assert!(StochasticProblem::new(mixed, 0, vec![2]).is_ok());
}

/// At the edge the exact solve answers (the loop is never evaluated); past it `solve
/// --algorithm exact` and `compare` refuse at once.
#[test]
fn solve_and_compare_answer_at_the_edge_and_refuse_past_it() {
    let dir = tempfile::tempdir().unwrap();
    let edge = write(
        dir.path(),
        "edge.json",
        &two_states(&format!("1/{}", pow2(1023))),
    );
    let v = json(&[
        "solve",
        "--algorithm",
        "exact",
        "--file",
        edge.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(v["cost_to_go_initial"], "0", "{v}");
    let past = write(
        dir.path(),
        "past.json",
        &two_states(&format!("1/{}", pow2(1024))),
    );
    refused_by_both(past.to_str().unwrap(), &["1025 bits", "at most 1024"]);
}

/// `solve --algorithm exact` and `compare` on `file` both refuse within [`REFUSAL_SECONDS`], in
/// one line containing every one of `words`.
fn refused_by_both(file: &str, words: &[&str]) {
    for args in [
        vec!["solve", "--algorithm", "exact", "--file", file],
        vec!["compare", "--file", file],
    ] {
        let start = Instant::now();
        let err = fails_one_line(&args);
        assert!(
            start.elapsed() < Duration::from_secs(REFUSAL_SECONDS),
            "{args:?}: {err}"
        );
        assert_contract(&err);
        for w in words {
            assert!(err.contains(w), "{w:?} missing from {err}");
        }
    }
}

/// A chain of 200 states, state `i` moving on at stage cost `cost(i)` or to the goal at
/// `cost(i + 1000)`.
fn chain(cost: impl Fn(usize) -> String) -> String {
    let n = 200;
    let actions: Vec<String> = (0..n - 1)
        .map(|i| {
            format!(
                r#"[{{"to": {}, "cost": "{}"}}, {{"to": {}, "cost": "{}"}}]"#,
                i + 1,
                cost(i),
                n - 1,
                cost(i + 1000)
            )
        })
        .chain(["[]".to_string()])
        .collect();
    format!(
        r#"{{"states": {n}, "initial": 0, "goals": [{}], "actions": [{}]}}"#,
        n - 1,
        actions.join(",")
    )
}

/// 200-state chains of 33,000-bit costs: integers `k·10^10000` (2 s before the exact solver
/// refused them) and fractions `1/(k·10^10000)` with distinct `k`, whose lcm grew without
/// bound (past 60 s), are refused at once by `solve --algorithm exact` and `compare`.
#[test]
fn chains_of_huge_costs_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let files = [
        (
            write(
                dir.path(),
                "int.json",
                &chain(|i| format!("{}e10000", i + 1)),
            ),
            "scaled to an integer by the lcm of the stage costs' denominators takes 33220 bits",
        ),
        (
            write(
                dir.path(),
                "frac.json",
                &chain(|i| format!("1/{}e10000", 2 * i + 1)),
            ),
            "the lcm of the stage costs' denominators up to here takes 33220 bits",
        ),
    ];
    for (file, words) in &files {
        refused_by_both(
            file.to_str().unwrap(),
            &["state 0, action 0", words, "at most 1024"],
        );
    }
}

/// `compare` refuses a discounted row the exact solver cannot take (the killed-process
/// construction charges the largest reward, `10^40`, minus a state's, per step: over `2^100`
/// with `α`'s denominator) before the truecost and reach solves of a 200-state chain whose
/// stage costs have 16 distinct 60-bit denominators (an lcm of about 960 bits, which the
/// truecost objective's exact solve refuses in turn).
#[test]
fn compare_refuses_a_discounted_row_before_the_other_objectives() {
    let dir = tempfile::tempdir().unwrap();
    let n = 200;
    // Distinct odd 60-bit denominators with small numerators: an lcm of about 1000 bits after
    // 17 states, so the costs repeat their denominators beyond.
    let denominator = |i: usize| (BigInt::from(1) << 59) + 2 * (i % 16) + 1;
    let actions: Vec<String> = (0..n - 1)
        .map(|i| {
            format!(
                r#"[{{"to": {}, "cost": "{}/{}", "reward": "1"}}, {{"to": {}, "cost": "1", "reward": "1e40"}}]"#,
                i + 1,
                i + 1,
                denominator(i),
                n - 1
            )
        })
        .chain(["[]".to_string()])
        .collect();
    let text = format!(
        r#"{{"states": {n}, "initial": 0, "goals": [{}], "actions": [{}]}}"#,
        n - 1,
        actions.join(",")
    );
    let file = write(dir.path(), "rewards.json", &text);
    let start = Instant::now();
    let err = fails_one_line(&[
        "compare",
        "--file",
        file.to_str().unwrap(),
        "--alphas",
        "0.9",
    ]);
    assert!(
        start.elapsed() < Duration::from_secs(REFUSAL_SECONDS),
        "{err}"
    );
    assert_contract(&err);
    for w in [
        "the discounted objective (killed-process construction) charges the model's largest reward, ≈1e40",
        "alpha's denominator 10",
        "2^100",
    ] {
        assert!(err.contains(w), "{w:?} missing from {err}");
    }
    // The truecost objective's own refusal (its stage costs scaled by their 960-bit lcm pass
    // the exact solver's 2^100) would have come first in the order of the rows.
    assert!(!err.contains("stage costs times"), "{err}");
    let err = fails_one_line(&[
        "solve",
        "--algorithm",
        "exact",
        "--file",
        file.to_str().unwrap(),
    ]);
    assert!(
        err.contains("stage costs times the probabilities' denominators exceed 2^100"),
        "{err}"
    );
}

//! Fuzz target for the problem-file readers, run by `cargo test` (and so by
//! CI) for a fixed budget of seeded cases: `cargo fuzz` needs a nightly toolchain, so this is a
//! proptest byte-level target instead.
//!
//! * Arbitrary bytes, and the files of the committed corpus `tests/fuzz_corpus/` mutated at the
//!   byte level (flips, deletions, insertions of hostile tokens, splices), go through every
//!   reader: `model::file::from_json`, `stochastic::file::from_json` and `parse_rational`.
//!   None may panic; a refusal is one line without raw control characters.
//! * Every **accepted** tiny file (≤ 5 states, ≤ 3 actions a state) must agree with a
//!   brute-force oracle written here: deterministic files — enumeration of simple paths
//!   (`common::simple_paths`) against Dijkstra; stochastic files — enumeration of every
//!   deterministic stationary policy, its proper states and its exact cost by Gaussian
//!   elimination, against the exact optimum (policy iteration).
//! * Generated tiny problems in both formats (whitespace, tags and number spellings varied)
//!   make sure accepted files are frequent, not only the corpus.
//!
//! Budget: `FUZZ_CASES` cases per property (default 600, ~3 s in the test profile). Add a file
//! to the corpus to fuzz around it.

mod common;

use num_traits::{One, Zero};
use proptest::prelude::*;
use proptest::test_runner::Config;

use common::{exact_all, simple_paths, Ext, Q};
use truecost::model::{file, ExactGraph};
use truecost::solvers::dijkstra;
use truecost::stochastic::file::{self as sfile, ProblemFile};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::StochasticProblem;
use truecost::value::parse_rational;

/// The committed corpus (each file embedded, so the target needs no working directory).
const CORPUS: &[&str] = &[
    include_str!("fuzz_corpus/big-numbers.json"),
    include_str!("fuzz_corpus/counterexample.json"),
    include_str!("fuzz_corpus/discount-example.json"),
    include_str!("fuzz_corpus/fractions-and-stay.json"),
    include_str!("fuzz_corpus/line.json"),
    include_str!("fuzz_corpus/slippery.json"),
    include_str!("fuzz_corpus/stochastic-tag-deterministic.json"),
    include_str!("fuzz_corpus/trap.json"),
    include_str!("fuzz_corpus/zero-cost-cycle.json"),
];

/// Tokens a hostile user would type into a problem file.
const TOKENS: &[&str] = &[
    "-1",
    "0",
    "1e10000",
    "1e10001",
    "1e-9223372036854775808",
    "1/0",
    "0.5",
    "\"1/3\"",
    "\"\"",
    "\\u001b[31m",
    "\\n",
    "null",
    "[]",
    "{}",
    "\"outcomes\": []",
    "\"to\": 99",
    "\"p\": \"2\"",
    "\"format\": \"truecost-problem/1\"",
    "\"format\": \"truecost-stochastic/1\"",
    "18446744073709551616",
    "\"states\": 0",
    "\"goals\": []",
    ",",
    "\"",
    "]",
    "}",
    "\u{202e}",
    "\u{0}",
];

fn cases() -> u32 {
    std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(600)
}

fn config() -> Config {
    Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    }
}

/// One byte-level mutation.
#[derive(Clone, Debug)]
enum Mutation {
    Flip(usize, u8),
    Delete(usize, usize),
    Insert(usize, usize),
    Splice(usize, usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Flip(i, b)),
        (any::<usize>(), 1usize..16).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (any::<usize>(), 0..TOKENS.len()).prop_map(|(i, t)| Mutation::Insert(i, t)),
        (any::<usize>(), any::<usize>(), 1usize..40)
            .prop_map(|(i, j, n)| Mutation::Splice(i, j, n)),
    ]
}

fn mutate(mut bytes: Vec<u8>, m: &Mutation) -> Vec<u8> {
    let len = bytes.len().max(1);
    match *m {
        Mutation::Flip(i, b) => {
            if !bytes.is_empty() {
                bytes[i % len] ^= b;
            }
        }
        Mutation::Delete(i, n) => {
            let start = i % len;
            let end = (start + n).min(bytes.len());
            if start < end {
                bytes.drain(start..end);
            }
        }
        Mutation::Insert(i, t) => {
            let at = i % (bytes.len() + 1);
            bytes.splice(at..at, TOKENS[t].bytes());
        }
        Mutation::Splice(i, j, n) => {
            // Copy a slice of the file elsewhere in it (duplicated keys, nested lists...).
            let from = i % len;
            let piece: Vec<u8> = bytes.iter().skip(from).take(n).copied().collect();
            let at = j % (bytes.len() + 1);
            bytes.splice(at..at, piece);
        }
    }
    bytes
}

/// Runs every reader on `text`; checks refusals are one clean line and accepted tiny files
/// agree with the oracles.
fn read_everything(text: &str) -> Result<(), TestCaseError> {
    for piece in text.split(['"', ',', ':']).take(64) {
        if piece.len() < 64 {
            let _ = parse_rational(piece);
        }
    }
    match file::from_json(text) {
        Ok(p) => {
            if small(p.states(), (0..p.states()).map(|x| p.moves(x).len())) {
                check_deterministic(&p)?;
            }
        }
        Err(e) => clean(&e.to_string())?,
    }
    match sfile::from_json(text) {
        Ok(ProblemFile::Deterministic(p)) => {
            // The two readers agree on a deterministic file.
            let direct = file::from_json(text).ok();
            prop_assert_eq!(Some(&p), direct.as_ref());
        }
        Ok(ProblemFile::Stochastic(s)) => {
            if small(s.states(), (0..s.states()).map(|x| s.actions(x).len())) {
                check_stochastic(&s)?;
            }
        }
        Err(e) => clean(&e.to_string())?,
    }
    Ok(())
}

fn small(states: usize, actions: impl Iterator<Item = usize>) -> bool {
    states <= 5 && actions.into_iter().all(|k| k <= 3)
}

fn clean(message: &str) -> Result<(), TestCaseError> {
    prop_assert!(
        !message.chars().any(char::is_control),
        "raw control character: {:?}",
        message
    );
    prop_assert!(
        message.chars().count() <= 600,
        "{} characters",
        message.len()
    );
    Ok(())
}

/// Dijkstra's `G*` against the enumeration of simple paths.
fn check_deterministic(p: &truecost::model::Problem) -> Result<(), TestCaseError> {
    let oracle = simple_paths(p);
    let eg = ExactGraph::new(p);
    let got: Vec<Ext> = match &eg {
        ExactGraph::Units(g) => exact_all(g, &dijkstra::to_goals(g).cost_to_go),
        ExactGraph::Big(g) => exact_all(g, &dijkstra::to_goals(g).cost_to_go),
    };
    prop_assert_eq!(
        got,
        oracle,
        "dijkstra disagrees with simple-path enumeration"
    );
    Ok(())
}

/// `G*` by brute force: the least cost, over every deterministic stationary policy proper at
/// `x` (it reaches a goal with probability 1 from `x`), of that policy at `x`.
fn brute_force_optimum(s: &StochasticProblem) -> Vec<Ext> {
    let n = s.states();
    let free: Vec<usize> = (0..n).filter(|&x| !s.is_goal(x)).collect();
    let mut best: Vec<Ext> = (0..n).map(|x| s.is_goal(x).then(Q::zero)).collect();
    let mut choice = vec![0usize; n];
    loop {
        let action = |x: usize| s.actions(x).nth(choice[x]);
        // Successor support of the policy; a state without an action is a dead end.
        let succ = |x: usize| -> Vec<usize> {
            if s.is_goal(x) {
                return Vec::new();
            }
            action(x)
                .map(|a| s.outcomes(a).iter().map(|o| o.successor).collect())
                .unwrap_or_default()
        };
        // can[x]: a goal is reachable from x under the policy.
        let mut can: Vec<bool> = (0..n).map(|x| s.is_goal(x)).collect();
        loop {
            let mut changed = false;
            for x in 0..n {
                if !can[x] && succ(x).iter().any(|&y| can[y]) {
                    can[x] = true;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        // proper[x]: every state reachable from x can reach a goal (and has an action).
        let proper: Vec<bool> = (0..n)
            .map(|x| {
                let mut seen = vec![false; n];
                let mut stack = vec![x];
                seen[x] = true;
                while let Some(y) = stack.pop() {
                    if !can[y] || (!s.is_goal(y) && action(y).is_none()) {
                        return false;
                    }
                    for z in succ(y) {
                        if !seen[z] {
                            seen[z] = true;
                            stack.push(z);
                        }
                    }
                }
                true
            })
            .collect();
        // Solve V = c + P V on the proper non-goal states (closed under successors).
        let idx: Vec<usize> = (0..n).filter(|&x| proper[x] && !s.is_goal(x)).collect();
        let m = idx.len();
        let pos = |x: usize| idx.iter().position(|&y| y == x);
        let mut a = vec![vec![Q::zero(); m + 1]; m];
        for (i, &x) in idx.iter().enumerate() {
            let act = action(x).expect("proper states act");
            a[i][i] += Q::one();
            for o in s.outcomes(act) {
                if let Some(j) = pos(o.successor) {
                    a[i][j] -= &o.probability;
                }
            }
            a[i][m] = s.cost(act).clone();
        }
        for col in 0..m {
            let pivot = (col..m)
                .find(|&r| !a[r][col].is_zero())
                .expect("a proper policy's system is regular");
            a.swap(col, pivot);
            let inv = Q::one() / &a[col][col];
            let row: Vec<Q> = a[col].iter().map(|v| v * &inv).collect();
            for (r, other) in a.iter_mut().enumerate() {
                if r != col && !other[col].is_zero() {
                    let f = other[col].clone();
                    for (o, p) in other.iter_mut().zip(&row).skip(col) {
                        *o -= p * &f;
                    }
                }
            }
            a[col] = row;
        }
        for (i, &x) in idx.iter().enumerate() {
            let v = a[i][m].clone();
            if best[x].as_ref().is_none_or(|b| &v < b) {
                best[x] = Some(v);
            }
        }
        // Next policy.
        let mut k = 0;
        loop {
            if k == free.len() {
                return best;
            }
            let x = free[k];
            choice[x] += 1;
            if choice[x] < s.actions(x).len() {
                break;
            }
            choice[x] = 0;
            k += 1;
        }
    }
}

/// The exact optimum (policy iteration) against the brute-force oracle.
fn check_stochastic(s: &StochasticProblem) -> Result<(), TestCaseError> {
    let oracle = brute_force_optimum(s);
    match optimum(s) {
        Ok(opt) => {
            let got: Vec<Ext> = opt
                .cost_to_go_all()
                .iter()
                .map(|v| v.finite().cloned())
                .collect();
            prop_assert_eq!(
                got,
                oracle,
                "policy iteration disagrees with policy enumeration"
            );
        }
        Err(e) => clean(&e.to_string())?,
    }
    Ok(())
}

/// A tiny problem as file text: per state a list of actions, each `(cost, outcomes)` with
/// outcomes `(successor, weight)` (weights normalised to probabilities), rendered in one of
/// several spellings.
fn tiny_file() -> impl Strategy<Value = String> {
    (1usize..=4)
        .prop_flat_map(|n| {
            let outcome = (0..n, 1u32..4);
            let action = (0u32..5, proptest::collection::vec(outcome, 1..3));
            (
                Just(n),
                proptest::collection::vec(proptest::collection::vec(action, 0..3), n),
                proptest::collection::vec(0..n, 1..3),
                0..n,
                0u8..6,
            )
        })
        .prop_map(|(n, lists, goals, initial, style)| {
            let lists: Vec<String> = lists
                .iter()
                .map(|list| {
                    let actions: Vec<String> = list
                        .iter()
                        .map(|(cost, outs)| {
                            let cost = match style % 3 {
                                0 => format!("{cost}"),
                                1 => format!("{cost}/2"),
                                _ => format!("{cost}e-1"),
                            };
                            if outs.len() == 1 || style >= 4 {
                                format!(r#"{{"to": {}, "cost": "{cost}"}}"#, outs[0].0)
                            } else {
                                let total: u32 = outs.iter().map(|o| o.1).sum();
                                let outs: Vec<String> = outs
                                    .iter()
                                    .map(|(to, w)| format!(r#"{{"to":{to},"p":"{w}/{total}"}}"#))
                                    .collect();
                                format!(r#"{{"cost":"{cost}","outcomes":[{}]}}"#, outs.join(","))
                            }
                        })
                        .collect();
                    format!("[{}]", actions.join(", "))
                })
                .collect();
            let tag = match style {
                0 | 4 => r#""format": "truecost-stochastic/1","#,
                1 => r#""format": "truecost-problem/1","#,
                _ => "",
            };
            let goals: Vec<String> = goals.iter().map(|g| g.to_string()).collect();
            format!(
                "{{{tag} \"states\": {n}, \"initial\": {initial}, \"goals\": [{}],\n \"actions\": [{}]}}",
                goals.join(","),
                lists.join(",\n  ")
            )
        })
}

proptest! {
    #![proptest_config(config())]

    /// Arbitrary bytes: no reader panics; refusals are clean lines.
    #[test]
    fn arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        read_everything(&String::from_utf8_lossy(&bytes))?;
    }

    /// The corpus, mutated at the byte level.
    #[test]
    fn mutated_corpus(file in 0..CORPUS.len(), mutations in proptest::collection::vec(mutation(), 1..5)) {
        let bytes = mutations.iter().fold(CORPUS[file].as_bytes().to_vec(), mutate);
        read_everything(&String::from_utf8_lossy(&bytes))?;
    }

}

/// Generated tiny files, valid or nearly so: accepted ones agree with the oracles, and many
/// are accepted in both models (so the oracle comparison really runs).
#[test]
fn generated_tiny_files() {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let (deterministic, stochastic) = (AtomicU32::new(0), AtomicU32::new(0));
    let mut runner = proptest::test_runner::TestRunner::new(config());
    runner
        .run(
            &(tiny_file(), proptest::option::weighted(0.3, mutation())),
            |(text, m)| {
                let text = match m {
                    Some(m) => String::from_utf8_lossy(&mutate(text.into_bytes(), &m)).into_owned(),
                    None => text,
                };
                match sfile::from_json(&text) {
                    Ok(ProblemFile::Deterministic(_)) => deterministic.fetch_add(1, Relaxed),
                    Ok(ProblemFile::Stochastic(_)) => stochastic.fetch_add(1, Relaxed),
                    Err(_) => 0,
                };
                read_everything(&text)
            },
        )
        .unwrap();
    let (d, s) = (deterministic.into_inner(), stochastic.into_inner());
    assert!(d * 10 >= cases(), "only {d} deterministic files accepted");
    assert!(s * 10 >= cases(), "only {s} stochastic files accepted");
}

/// The corpus itself is read without mutation, and its valid files are accepted (so the
/// mutations start from real files).
#[test]
fn corpus_files_are_read() {
    let mut accepted = 0;
    for text in CORPUS {
        read_everything(text).unwrap();
        if sfile::from_json(text).is_ok() {
            accepted += 1;
        }
    }
    assert_eq!(
        accepted,
        CORPUS.len(),
        "every corpus file is a valid problem"
    );
}

/// A case `generated_tiny_files` found (a token inserted into a probability): the stochastic
/// reader's error echoed `11e10000/2` in full, 10 049 characters. Numbers in errors are now
/// shortened (`≈5.5e10000`); so are a negative cost and a probability sum.
#[test]
fn huge_numbers_in_reader_errors_are_shortened() {
    let probability = r#"{"format": "truecost-stochastic/1", "states": 1, "initial": 0, "goals": [0],
 "actions": [[{"to": 0, "cost": "0"}, {"cost":"0","outcomes":[{"to":0,"p":"11e10000/2"},{"to":0,"p":"1/2"}]}]]}"#;
    let cost = r#"{"initial":0,"goals":[1],"actions":[[{"cost":"-1e5000","outcomes":[{"to":1,"p":"1"}]}],[]]}"#;
    let sum = r#"{"initial":0,"goals":[1],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"1e-5000"},{"to":0,"p":"1/2"}]}],[]]}"#;
    for text in [probability, cost, sum] {
        let Err(e) = sfile::from_json(text) else {
            panic!("refused: {text}")
        };
        let message = e.to_string();
        assert!(message.chars().count() <= 200, "{message}");
        assert!(message.contains('≈'), "{message}");
        read_everything(text).unwrap();
    }
}

/// Guards the stochastic oracle itself on a hand-solved file: from 0, the action costs 1 and
/// reaches the goal with probability 1/2 (else stays): `G = 1 + G/2`, so `G = 2`.
#[test]
fn brute_force_oracle_by_hand() {
    let text = r#"{"initial":0,"goals":[1],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"1/2"},{"to":0,"p":"1/2"}]},{"to":0,"cost":"0"}],[]]}"#;
    let ProblemFile::Stochastic(s) = sfile::from_json(text).unwrap() else {
        panic!("a stochastic file")
    };
    let two = Q::from_integer(2.into());
    assert_eq!(brute_force_optimum(&s), vec![Some(two), Some(Q::zero())]);
}

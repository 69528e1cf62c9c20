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
//!   elimination, against the exact optimum (policy iteration); both — the discounted values
//!   at `α = 1/2` of the file's rewards (or negated costs) and terminal states, by enumeration
//!   of every stationary policy, against the objective's exact solve, and its value at the
//!   initial distribution against the probability-weighted oracle values (for a file with an
//!   initial distribution, the truecost value there too). The readers that return a single
//!   initial state accept exactly the files the others accept without a distribution, and
//!   refuse the others with the same message.
//! * Generated tiny problems in both formats (whitespace, tags and number spellings varied,
//!   with or without rewards, a terminal state, an initial distribution or a mix of actions
//!   with and without a reward) make sure accepted files are frequent, not only the corpus.
//!
//! Budget: `FUZZ_CASES` cases per property (default 600, ~3 s in the test profile). Add a file
//! to the corpus to fuzz around it.

mod common;

use num_traits::{One, Zero};
use proptest::prelude::*;
use proptest::test_runner::Config;

use common::tiny::gauss_jordan;
use common::{exact_all, simple_paths, Ext, Q};
use truecost::model::{file, ExactGraph};
use truecost::objectives::{Model, Objective};
use truecost::solvers::dijkstra;
use truecost::stochastic::file::{self as sfile, FileObjective, ProblemFile};
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::parse_rational;

/// The committed corpus (each file embedded, so the target needs no working directory).
const CORPUS: &[&str] = &[
    include_str!("fuzz_corpus/big-numbers.json"),
    include_str!("fuzz_corpus/counterexample.json"),
    include_str!("fuzz_corpus/discount-example.json"),
    include_str!("fuzz_corpus/fractions-and-stay.json"),
    include_str!("fuzz_corpus/initial-distribution.json"),
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
    "\"reward\": \"-1/2\",",
    "\"terminal\": [0],",
    "[{\"state\": 0, \"p\": \"1/2\"}, {\"state\": 1, \"p\": \"1/2\"}]",
    "{\"state\": 1, \"p\": \"1\"}",
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
    let with_objective = sfile::from_json_with_objective(text);
    // The reader of a single initial state: the same file, unless it draws the initial state
    // from two or more states; the same refusal otherwise.
    match (&with_objective, sfile::from_json(text)) {
        (Ok((_, extra)), Ok(_)) => prop_assert!(extra.initial.is_none()),
        (Ok((_, extra)), Err(e)) => {
            prop_assert!(extra.initial.is_some(), "refused: {}", e);
            prop_assert!(
                e.to_string().contains("needs a single initial state"),
                "{}",
                e
            );
        }
        (Err(e), Ok(_)) => prop_assert!(false, "accepted, while refused with: {}", e),
        (Err(e), Err(f)) => prop_assert_eq!(e.to_string(), f.to_string()),
    }
    match with_objective {
        Ok((problem, extra)) => {
            let p = match problem {
                // A deterministic problem is a stochastic one, unless its numbers are past the
                // exact solvers' size limit (the planners take any size the reader does).
                ProblemFile::Deterministic(d) => match StochasticProblem::from_deterministic(
                    &d,
                    NoiseModel::Paper,
                    &Predictability::one(),
                ) {
                    Ok(p) => p,
                    Err(e) => {
                        let text = e.to_string();
                        prop_assert!(text.contains("at most 1024"), "{}", text);
                        return clean(&text);
                    }
                },
                ProblemFile::Stochastic(s) => *s,
            };
            if small(p.states(), (0..p.states()).map(|x| p.actions(x).len())) {
                if extra.initial.is_some() {
                    check_truecost_at_initial(&p, &extra)?;
                }
                check_discounted(p, &extra)?;
            }
        }
        Err(e) => clean(&e.to_string())?,
    }
    Ok(())
}

/// The initial distribution the objectives' model takes from a file: its list, or its single
/// initial state with probability 1.
fn initial_of(s: &StochasticProblem, extra: &FileObjective) -> Vec<(usize, Q)> {
    extra
        .initial
        .clone()
        .unwrap_or_else(|| vec![(s.initial(), Q::one())])
}

/// The expected truecost optimum at the file's initial distribution (`--file` with
/// `--objective truecost`) against the probability-weighted [`brute_force_optimum`] (`+∞` if
/// a state of the distribution has `+∞`).
fn check_truecost_at_initial(
    s: &StochasticProblem,
    extra: &FileObjective,
) -> Result<(), TestCaseError> {
    let oracle = brute_force_optimum(s);
    let mut expected = Some(Q::zero());
    for (x, p) in initial_of(s, extra) {
        expected = match (expected, &oracle[x]) {
            (Some(sum), Some(g)) => Some(sum + g * p),
            _ => None,
        };
    }
    let m = Model::from_problem(s.clone(), "fuzz".into()).with_file_objective(extra);
    match m.solve(&Objective::Truecost) {
        Ok(solution) => prop_assert_eq!(
            solution.value_initial.finite().cloned(),
            expected,
            "truecost at the initial distribution disagrees with policy enumeration"
        ),
        Err(e) => clean(&e.to_string())?,
    }
    Ok(())
}

/// The discounted values at `α` by brute force: the greatest value, per state, over every
/// deterministic stationary policy (`V = r + α P V` on the states where the episode runs, by
/// Gaussian elimination; `0` where it is over: goals, states without actions and the file's
/// terminal states), with the file's rewards, or the negated costs where it gives none.
fn brute_force_discounted(s: &StochasticProblem, extra: &FileObjective, alpha: &Q) -> Vec<Q> {
    let n = s.states();
    let ended: Vec<bool> = (0..n)
        .map(|x| s.is_goal(x) || s.actions(x).is_empty() || extra.terminal.contains(&x))
        .collect();
    let reward = |a: usize| match &extra.rewards {
        Some(r) => r[a].clone(),
        None => -s.cost(a).clone(),
    };
    let running: Vec<usize> = (0..n).filter(|&x| !ended[x]).collect();
    let mut best: Vec<Option<Q>> = (0..n).map(|x| ended[x].then(Q::zero)).collect();
    let mut choice = vec![0usize; n];
    loop {
        let k = running.len();
        let mut a = vec![vec![Q::zero(); k + 1]; k];
        for (i, &x) in running.iter().enumerate() {
            let act = s.actions(x).nth(choice[x]).expect("a running state acts");
            a[i][i] += Q::one();
            for o in s.outcomes(act) {
                if let Some(j) = running.iter().position(|&y| y == o.successor) {
                    a[i][j] -= &o.probability * alpha;
                }
            }
            a[i][k] = reward(act);
        }
        gauss_jordan(&mut a, "I - alpha P is regular");
        for (i, &x) in running.iter().enumerate() {
            if best[x].as_ref().is_none_or(|b| a[i][k] > *b) {
                best[x] = Some(a[i][k].clone());
            }
        }
        // Next policy.
        let mut i = 0;
        loop {
            if i == running.len() {
                return best
                    .into_iter()
                    .map(|v| v.expect("every state valued"))
                    .collect();
            }
            let x = running[i];
            choice[x] += 1;
            if choice[x] < s.actions(x).len() {
                break;
            }
            choice[x] = 0;
            i += 1;
        }
    }
}

/// The exact discounted solve at `α = 1/2` of the model that `--file` builds (the problem with
/// the file's rewards and terminal states) against [`brute_force_discounted`].
fn check_discounted(s: StochasticProblem, extra: &FileObjective) -> Result<(), TestCaseError> {
    let half = Q::new(1.into(), 2.into());
    let oracle = brute_force_discounted(&s, extra, &half);
    let at_initial = initial_of(&s, extra)
        .iter()
        .map(|(x, p)| &oracle[*x] * p)
        .fold(Q::zero(), |a, b| a + b);
    let m = Model::from_problem(s, "fuzz".into()).with_file_objective(extra);
    match m.solve(&Objective::Discounted(half)) {
        Ok(solution) => {
            let got: Vec<Option<Q>> = solution
                .values
                .iter()
                .map(|v| v.finite().cloned())
                .collect();
            let oracle: Vec<Option<Q>> = oracle.into_iter().map(Some).collect();
            prop_assert_eq!(
                got,
                oracle,
                "discounted solve disagrees with policy enumeration"
            );
            prop_assert_eq!(
                solution.value_initial.finite(),
                Some(&at_initial),
                "discounted value at the initial distribution"
            );
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
        gauss_jordan(&mut a, "a proper policy's system is regular");
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

/// A tiny problem as file text: per state a list of actions, each `(cost, outcomes, reward)`
/// with outcomes `(successor, weight)` (weights normalised to probabilities), rendered in one
/// of several spellings; `rewards` 0 to 6 write no reward, 7 to 14 a reward on every action,
/// 15 on every action but the last (refused); `terminal` lists one state (`true`: its actions
/// replaced by a zero-cost self-loop and, unless it is the only goal, removed from the goals,
/// so that it is accepted); `drawn`, if given, replaces `initial` by a distribution over its
/// states (an entry whose state an earlier one lists is dropped; weights normalised to
/// probabilities, so that a single entry has probability 1).
fn tiny_file() -> impl Strategy<Value = String> {
    (1usize..=4)
        .prop_flat_map(|n| {
            let outcome = (0..n, 1u32..4);
            let action = (0u32..5, proptest::collection::vec(outcome, 1..3), -2i32..3);
            (
                Just(n),
                proptest::collection::vec(proptest::collection::vec(action, 0..3), n),
                proptest::collection::vec(0..n, 1..3),
                0..n,
                0u8..6,
                0u8..16,
                proptest::option::weighted(0.2, (0..n, proptest::bool::weighted(0.9))),
                proptest::option::weighted(
                    0.5,
                    proptest::collection::vec((0..n, 1u32..4), 1..4),
                ),
            )
        })
        .prop_map(|(n, mut lists, mut goals, initial, style, rewards, terminal, drawn)| {
            if let Some((x, true)) = terminal {
                lists[x] = vec![(0, vec![(x, 1)], 0)];
                if goals.iter().any(|&g| g != x) {
                    goals.retain(|&g| g != x);
                }
            }
            let last = lists.iter().flatten().count();
            let mut index = 0;
            let lists: Vec<String> = lists
                .iter()
                .map(|list| {
                    let actions: Vec<String> = list
                        .iter()
                        .map(|(cost, outs, reward)| {
                            index += 1;
                            let cost = match style % 3 {
                                0 => format!("{cost}"),
                                1 => format!("{cost}/2"),
                                _ => format!("{cost}e-1"),
                            };
                            let reward = match rewards {
                                7..=13 => format!(r#", "reward": "{reward}""#),
                                14 => format!(r#", "reward": "{reward}/3""#),
                                15 if index < last => format!(r#", "reward": "{reward}""#),
                                _ => String::new(),
                            };
                            if outs.len() == 1 || style >= 4 {
                                format!(r#"{{"to": {}, "cost": "{cost}"{reward}}}"#, outs[0].0)
                            } else {
                                let total: u32 = outs.iter().map(|o| o.1).sum();
                                let outs: Vec<String> = outs
                                    .iter()
                                    .map(|(to, w)| format!(r#"{{"to":{to},"p":"{w}/{total}"}}"#))
                                    .collect();
                                format!(
                                    r#"{{"cost":"{cost}"{reward},"outcomes":[{}]}}"#,
                                    outs.join(",")
                                )
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
            let terminal = match terminal {
                Some((x, _)) => format!(r#""terminal": [{x}], "#),
                None => String::new(),
            };
            let goals: Vec<String> = goals.iter().map(|g| g.to_string()).collect();
            let initial = match drawn {
                Some(mut entries) => {
                    let mut seen = Vec::new();
                    entries.retain(|(x, _)| {
                        let first = !seen.contains(x);
                        seen.push(*x);
                        first
                    });
                    let total: u32 = entries.iter().map(|e| e.1).sum();
                    let entries: Vec<String> = entries
                        .iter()
                        .map(|(x, w)| format!(r#"{{"state": {x}, "p": "{w}/{total}"}}"#))
                        .collect();
                    format!("[{}]", entries.join(", "))
                }
                None => initial.to_string(),
            };
            format!(
                "{{{tag} \"states\": {n}, \"initial\": {initial}, \"goals\": [{}], {terminal}\n \"actions\": [{}]}}",
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
    let (rewarded, terminal) = (AtomicU32::new(0), AtomicU32::new(0));
    let drawn = AtomicU32::new(0);
    let mut runner = proptest::test_runner::TestRunner::new(config());
    runner
        .run(
            &(tiny_file(), proptest::option::weighted(0.3, mutation())),
            |(text, m)| {
                let text = match m {
                    Some(m) => String::from_utf8_lossy(&mutate(text.into_bytes(), &m)).into_owned(),
                    None => text,
                };
                if let Ok((problem, extra)) = sfile::from_json_with_objective(&text) {
                    match problem {
                        ProblemFile::Deterministic(_) => deterministic.fetch_add(1, Relaxed),
                        ProblemFile::Stochastic(_) => stochastic.fetch_add(1, Relaxed),
                    };
                    if extra.rewards.is_some() {
                        rewarded.fetch_add(1, Relaxed);
                    }
                    if !extra.terminal.is_empty() {
                        terminal.fetch_add(1, Relaxed);
                    }
                    if extra.initial.is_some() {
                        drawn.fetch_add(1, Relaxed);
                    }
                }
                read_everything(&text)
            },
        )
        .unwrap();
    let (d, s) = (deterministic.into_inner(), stochastic.into_inner());
    assert!(d * 10 >= cases(), "only {d} deterministic files accepted");
    assert!(s * 10 >= cases(), "only {s} stochastic files accepted");
    let (r, t) = (rewarded.into_inner(), terminal.into_inner());
    assert!(r * 10 >= cases(), "only {r} files with rewards accepted");
    assert!(
        t * 100 >= cases(),
        "only {t} files with a terminal state accepted"
    );
    let i = drawn.into_inner();
    assert!(
        i * 100 >= cases(),
        "only {i} files with an initial distribution accepted"
    );
}

/// The corpus itself is read without mutation, and its valid files are accepted (so the
/// mutations start from real files).
#[test]
fn corpus_files_are_read() {
    let mut accepted = 0;
    for text in CORPUS {
        read_everything(text).unwrap();
        if sfile::from_json_with_objective(text).is_ok() {
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

/// Guards the discounted oracle on a hand-solved file with rewards: from 0, "try" has reward
/// 1/2 and reaches the goal with probability 1/2 (else stays), "quit" enters the terminal
/// trap 2 with reward 1/4. At alpha = 1/2 trying forever gives V = 1/2 + V/4, V = 2/3 > 1/4.
#[test]
fn discounted_oracle_by_hand() {
    let text = r#"{"initial":0,"goals":[1],"terminal":[2],"actions":[
        [{"cost":"1","reward":"1/2","outcomes":[{"to":1,"p":"1/2"},{"to":0,"p":"1/2"}]},
         {"to":2,"cost":"1","reward":"1/4"}],
        [],
        [{"to":2,"cost":"0","reward":"0"}]]}"#;
    let (ProblemFile::Stochastic(s), extra) = sfile::from_json_with_objective(text).unwrap() else {
        panic!("a stochastic file")
    };
    let half = Q::new(1.into(), 2.into());
    assert_eq!(
        brute_force_discounted(&s, &extra, &half),
        vec![Q::new(2.into(), 3.into()), Q::zero(), Q::zero()]
    );
    check_discounted(*s, &extra).unwrap();
}

/// A case `mutated_corpus` found (a splice of `big-numbers.json`): the deterministic reader
/// refused a cost of `-1e10000` echoing all 10 002 characters of it. The number is shortened to
/// its first 20 characters and its length; the same file through the stochastic reader says
/// the same.
#[test]
fn a_huge_negative_cost_of_a_deterministic_file_is_shortened() {
    let text = r#"{"initial":1,"goals":[0,0],"actions":[[],[{"to":0,"cost":"0000"},{"to":1,"cost":"-1e10000"},{"to":1,"cost":"-0"}]]}"#;
    let e = file::from_json(text).unwrap_err().to_string();
    let head = format!("-1{}", "0".repeat(18));
    assert_eq!(
        e,
        format!(
            "state 1, action 1: negative stage cost {head}… (10002 characters) (costs must be >= 0)"
        )
    );
    assert_eq!(sfile::from_json(text).unwrap_err().to_string(), e);
    read_everything(text).unwrap();
    // A short negative cost is shown whole.
    let short = text.replace("-1e10000", "-3/4");
    assert!(file::from_json(&short)
        .unwrap_err()
        .to_string()
        .contains("negative stage cost -3/4 (costs"));
}

//! Claim C2 (docs/spec.md §6): cost–reward equivalence. For a cost functional that is linear in the
//! sequence of stage costs (total, discounted, average and their finite-horizon versions), a
//! policy minimises the cost iff it maximises the reward obtained by negating every stage cost.
//!
//! Oracle: every deterministic stationary policy is enumerated; for every start state and
//! every functional, the set of cost minimisers is computed from the stage costs and the set
//! of reward maximisers from the *negated stage sequence* (evaluated afresh, not by negating
//! the cost), and the two sets are compared.

use super::oracle::Functional;
use super::tiny::{minimality_key, FamilySpec, Tiny};
pub use truecost_kernel::claims::c2::{check_problem, functionals};

use super::{enumerate, keep_min, min_of, ClaimResult, Counterexample, EngineRun, Scope, Verdict};

/// The statement of C2 as printed.
pub const STATEMENT: &str = "C2 (as printed): for any cost functional linear in the sequence of stage costs (total, \
discounted, average, and their finite-horizon versions), a policy minimises the cost iff it maximises the reward \
obtained by negating every stage cost (r = -l).";

type Key = (usize, usize, u64, u64, u64);

#[derive(Default, serde::Serialize, serde::Deserialize)]
struct Acc {
    cases: u64,
    comparisons: u64,
    failures: u64,
    min: Option<(Key, (Tiny, String))>,
}

fn merge(a: Acc, b: Acc) -> Acc {
    Acc {
        cases: a.cases + b.cases,
        comparisons: a.comparisons + b.comparisons,
        failures: a.failures + b.failures,
        min: min_of(a.min, b.min),
    }
}

fn specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, degree, goal_degree, costs: &[u8]| FamilySpec {
        states,
        initial_fixed: true,
        degree,
        goal_degree,
        costs: costs.to_vec(),
        distinct_successors: false,
    };
    match scope {
        Scope::Smoke => vec![
            spec(2, (1, 2), (0, 1), &[0, 1, 2]),
            spec(3, (1, 1), (0, 1), &[0, 1, 2]),
        ],
        Scope::Quick => vec![
            spec(2, (1, 2), (0, 1), &[0, 1, 2, 3]),
            spec(3, (1, 2), (0, 1), &[0, 1, 2, 3]),
            spec(4, (1, 2), (0, 0), &[0, 1, 2, 3]),
        ],
        Scope::Full => vec![
            spec(2, (1, 2), (0, 2), &[0, 1, 2, 3]),
            spec(3, (1, 2), (0, 2), &[0, 1, 2, 3]),
            spec(4, (1, 2), (0, 0), &[0, 1, 2, 3]),
        ],
    }
}

/// Checks C2 in `scope`.
pub fn check(scope: Scope) -> ClaimResult {
    check_with(scope, check_problem)
}

/// [`check`] around a given per-problem comparison (`check_problem` in production): the
/// enumeration, the tally of cases, comparisons and failures, the least failing problem and
/// the verdict. C2 holds, so only a planted failure (the unit test below) reaches the failure
/// path.
fn check_with(
    scope: Scope,
    check_problem: impl Fn(&Tiny, &[Functional], usize) -> (Option<String>, u64) + Sync + Send,
) -> ClaimResult {
    let fs = functionals();
    let starts = if scope == Scope::Full { usize::MAX } else { 1 };
    let started = std::time::Instant::now();
    let mut acc = Acc::default();
    let mut parts = Vec::new();
    for spec in specs(scope) {
        let (a, _) = enumerate(
            &spec,
            Acc::default,
            |acc, t, i| {
                acc.cases += 1;
                let (bad, c) = check_problem(t, &fs, starts);
                acc.comparisons += c;
                if let Some(what) = bad {
                    acc.failures += 1;
                    keep_min(&mut acc.min, minimality_key(t, 0, i), || (*t, what));
                }
            },
            merge,
        );
        acc = merge(acc, a);
        parts.push(spec.describe());
    }
    let names: Vec<String> = fs.iter().map(Functional::name).collect();
    let scope_line = format!(
        "{} problems up to relabelling ({}; x1 = 0, one goal with termination); every deterministic stationary \
policy, {}; functionals: {}",
        acc.cases,
        parts.join(" | "),
        if starts == 1 { "from x1" } else { "from every start state" },
        names.join(", ")
    );
    ClaimResult {
        id: "C2".into(),
        statement: STATEMENT.into(),
        verdict: if acc.failures > 0 {
            Verdict::Refuted
        } else {
            Verdict::Verified
        },
        engine: "exhaustive enumeration".into(),
        scope: scope_line.clone(),
        cases: acc.cases,
        counterexample: acc.min.as_ref().map(|(_, (t, what))| {
            Counterexample::new(t, format!("C2 counterexample: {what}"), vec![], "c2")
        }),
        engines: vec![EngineRun {
            engine: "exhaustive enumeration".into(),
            mode: "exhaustive".into(),
            scope: scope_line,
            cases: acc.cases,
            failures: acc.failures,
            seconds: started.elapsed().as_secs_f64(),
        }],
        notes: vec![format!(
            "{} (problem, start state, functional) comparisons of argmin-cost and argmax-reward policy sets",
            acc.comparisons
        )],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// The bookkeeping around the comparison, against a planted failure on every problem with
    /// an odd number of moves: the verdict, the case, failure and comparison counts and the
    /// reported problem are recomputed here from what the comparison saw.
    #[test]
    fn a_planted_failure_is_counted_and_its_least_problem_reported() {
        let seen = Mutex::new(Vec::new());
        let r = check_with(Scope::Smoke, |t, fs, starts| {
            let (bad, comparisons) = check_problem(t, fs, starts);
            assert_eq!(bad, None, "C2 holds on every problem");
            let key = (t.states(), t.move_count(), t.cost_sum());
            let fails = t.move_count() % 2 == 1;
            seen.lock().unwrap().push((fails, key, comparisons));
            (fails.then(|| format!("planted {key:?}")), comparisons)
        });
        let seen = seen.into_inner().unwrap();
        let failures = seen.iter().filter(|s| s.0).count() as u64;
        assert!(failures > 1 && failures < seen.len() as u64, "{failures}");
        assert_eq!(r.verdict, Verdict::Refuted);
        assert_eq!(r.cases, seen.len() as u64);
        assert_eq!(
            (r.engines[0].cases, r.engines[0].failures),
            (r.cases, failures)
        );
        let comparisons: u64 = seen.iter().map(|s| s.2).sum();
        assert!(
            r.notes[0].starts_with(&format!("{comparisons} (problem, start state")),
            "{}",
            r.notes[0]
        );
        let least = seen.iter().filter(|s| s.0).map(|s| s.1).min().unwrap();
        assert_eq!(
            r.counterexample.unwrap().summary,
            format!("C2 counterexample: planted {least:?}")
        );
        // Without the planted failure: verified, no counterexample, the same counts.
        let r = check(Scope::Smoke);
        assert_eq!(r.verdict, Verdict::Verified);
        assert!(r.counterexample.is_none());
        assert_eq!((r.cases, r.engines[0].failures), (seen.len() as u64, 0));
    }
}

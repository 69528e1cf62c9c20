//! Claim C2 (SPEC §6): cost–reward equivalence. For a cost functional that is linear in the
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

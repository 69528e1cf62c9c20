//! Engine 2: proptest properties on larger random problems than engine 1 enumerates, with
//! shrinking to a minimal counterexample. The runs are deterministic (a fixed
//! ChaCha seed), so `truecost verify` reports the same cases and counterexamples every time.

use std::sync::atomic::{AtomicU64, Ordering};

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::{
    Config, FileFailurePersistence, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner,
};

use super::c3::{certificate, optimal_policy_avoids_goal};
use super::c4::{bonus_sets, witness, Instance};
use super::caught::{self, ENGINE_FAILED};
use super::exact::Q;
use super::oracle::Functional;
use super::qlearning::{run, Order, QProblem, Run, Terminal, Values, MAX_PAIRS};
use super::tiny::Tiny;
use super::{EngineRun, Scope};

/// A random tiny problem: `n` states (goal last), each with 1..=`deg` moves (the goal with
/// 0..=`goal_deg`), costs `0..=max_cost`.
pub fn tiny_strategy(
    max_states: usize,
    deg: usize,
    goal_deg: usize,
    max_cost: u8,
) -> impl Strategy<Value = Tiny> {
    (1..=max_states).prop_flat_map(move |n| {
        let non_goal = vec(vec((0..n as u8, 0..=max_cost), 1..=deg), n - 1);
        let goal = vec((0..n as u8, 0..=max_cost), 0..=goal_deg);
        (non_goal, goal).prop_map(|(mut lists, g)| {
            lists.push(g);
            Tiny::from_lists(&lists)
        })
    })
}

/// The outcome of one property.
#[derive(Clone, Debug, PartialEq)]
pub struct PropertyRun {
    /// The claim.
    pub claim: &'static str,
    /// Cases generated.
    pub cases: u64,
    /// Cases satisfying the claim's hypotheses.
    pub relevant: u64,
    /// The shrunk counterexample, if the property failed.
    pub counterexample: Option<(Tiny, String)>,
    /// What was generated.
    pub scope: String,
}

impl PropertyRun {
    /// As an [`EngineRun`].
    pub fn engine_run(&self, seconds: f64) -> EngineRun {
        EngineRun {
            engine: "proptest".into(),
            mode: "sampled".into(),
            scope: self.scope.clone(),
            cases: self.relevant,
            failures: u64::from(self.counterexample.is_some()),
            seconds,
        }
    }
}

fn runner(cases: u32, persistence: Option<&'static str>) -> TestRunner {
    let config = Config {
        cases,
        max_shrink_iters: 4096,
        failure_persistence: persistence
            .map(|p| Box::new(FileFailurePersistence::Direct(p)) as Box<_>),
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::deterministic_rng(RngAlgorithm::ChaCha))
}

/// Runs a property with `runner`: a panic in the code it checks fails the case with the
/// panic's description behind [`ENGINE_FAILED`], so that proptest shrinks it like any failure
/// and [`finish`] reports it as a failure of the engine, not as a counterexample to the claim.
fn run_guarded<S: Strategy>(
    mut runner: TestRunner,
    strategy: &S,
    test: impl Fn(S::Value) -> Result<(), TestCaseError>,
) -> Result<(), TestError<S::Value>> {
    runner.run(strategy, |v| match caught::caught(|| test(v)) {
        Ok(r) => r,
        Err(failure) => Err(TestCaseError::fail(format!("{ENGINE_FAILED}{failure}"))),
    })
}

/// The property's outcome; a case that panicked (see [`run_guarded`]) is raised again as the
/// failure of the engine ([`caught::raise`]), with the input proptest shrank it to.
fn finish(
    claim: &'static str,
    scope: String,
    result: Result<(), TestError<(Tiny, Vec<i64>)>>,
    cases: &AtomicU64,
    relevant: &AtomicU64,
) -> PropertyRun {
    let counterexample = match result {
        Ok(()) => None,
        Err(TestError::Fail(reason, (t, v))) => {
            if let Some(failure) = reason.message().strip_prefix(ENGINE_FAILED) {
                let values = if v.is_empty() {
                    String::new()
                } else {
                    format!(", Q0 = {v:?}")
                };
                caught::raise(format!(
                    "{failure}; on the input proptest shrank it to: {}{values}",
                    t.describe()
                ));
            }
            Some((t, reason.message().to_string()))
        }
        Err(TestError::Abort(reason)) => {
            Some((Tiny::empty(1), format!("aborted: {}", reason.message())))
        }
    };
    PropertyRun {
        claim,
        cases: cases.load(Ordering::Relaxed),
        relevant: relevant.load(Ordering::Relaxed),
        counterexample,
        scope,
    }
}

fn with_values(
    max_states: usize,
    deg: usize,
    goal_deg: usize,
) -> impl Strategy<Value = (Tiny, Vec<i64>)> {
    (
        tiny_strategy(max_states, deg, goal_deg, 4),
        vec(-2i64..=6, MAX_PAIRS),
    )
}

fn values_of(v: &[i64]) -> Values {
    let mut out = [0i64; MAX_PAIRS];
    out.copy_from_slice(&v[..MAX_PAIRS]);
    out
}

/// C1 as printed: converges under the cyclic order (with the termination pair updated).
pub fn c1_printed(cases: u32, persistence: Option<&'static str>) -> PropertyRun {
    let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
    let result = run_guarded(
        runner(cases, persistence),
        &with_values(6, 3, 2),
        |(t, v)| {
            n.fetch_add(1, Ordering::Relaxed);
            r.fetch_add(1, Ordering::Relaxed);
            let q = QProblem::new(&t, Terminal::Updated);
            let q0 = values_of(&v);
            if !q.all_finite() {
                return Err(TestCaseError::fail("a pair has Q* = inf; Q stays finite"));
            }
            match run(&q, &q0, Order::Cyclic, 64) {
                Run::Converged(_) => Ok(()),
                other => Err(TestCaseError::fail(format!("cyclic order: {other:?}"))),
            }
        },
    );
    finish(
        "C1",
        format!("{cases} random problems, up to 6 states, 1-3 moves, costs 0-4, Q0 in -2..6"),
        result,
        &n,
        &r,
    )
}

/// C1-corrected: under H0–H2 every tested order converges within the bound.
pub fn c1_corrected(cases: u32, persistence: Option<&'static str>) -> PropertyRun {
    let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
    let result = run_guarded(
        runner(cases, persistence),
        &with_values(6, 3, 2),
        |(t, v)| {
            n.fetch_add(1, Ordering::Relaxed);
            let q = QProblem::new(&t, Terminal::HeldAtZero);
            let mut q0 = values_of(&v);
            for p in 0..q.len() {
                if q.pairs[p].terminal {
                    q0[p] = 0; // H0
                }
            }
            if !q.all_finite() {
                return Ok(());
            }
            let Some(bound) = q.round_bound(&q0) else {
                return Ok(());
            };
            r.fetch_add(1, Ordering::Relaxed);
            for o in [
                Order::Cyclic,
                Order::Reverse,
                Order::FarFirst,
                Order::Random(7),
            ] {
                let outcome = run(&q, &q0, o, 256);
                if !converged_within(&outcome, bound) {
                    return Err(TestCaseError::fail(format!(
                        "{o:?}: {outcome:?}, bound {bound}"
                    )));
                }
            }
            Ok(())
        },
    );
    finish(
        "C1-corrected",
        format!("{cases} random problems (those satisfying H0-H2 counted), up to 6 states, 1-3 moves, costs 0-4, Q0 in -2..6; four orders"),
        result,
        &n,
        &r,
    )
}

/// C1-corrected's test of one run: `Q̂ = Q*` after at most `bound` rounds (Proposition 1,
/// corrected). A cycle, or a run not converged within the limit, fails.
fn converged_within(outcome: &Run, bound: u64) -> bool {
    match outcome {
        Run::Converged(k) => *k <= bound,
        Run::Cycles(..) | Run::NotWithin(_) => false,
    }
}

/// C2 on random problems up to 6 states.
pub fn c2(cases: u32, persistence: Option<&'static str>) -> PropertyRun {
    let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
    let fs: Vec<Functional> = super::c2::functionals();
    let strategy = (tiny_strategy(6, 2, 1, 6), Just(Vec::<i64>::new()));
    let result = run_guarded(runner(cases, persistence), &strategy, |(t, _)| {
        n.fetch_add(1, Ordering::Relaxed);
        r.fetch_add(1, Ordering::Relaxed);
        match super::c2::check_problem(&t, &fs, usize::MAX).0 {
            None => Ok(()),
            Some(what) => Err(TestCaseError::fail(what)),
        }
    });
    finish(
        "C2",
        format!("{cases} random problems, up to 6 states, 1-2 moves, costs 0-6"),
        result,
        &n,
        &r,
    )
}

/// C3 on random structures up to 7 states.
pub fn c3(cases: u32, persistence: Option<&'static str>) -> PropertyRun {
    let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
    let strategy = (tiny_strategy(7, 2, 0, 0), Just(Vec::<i64>::new()));
    let result = run_guarded(runner(cases, persistence), &strategy, |(t, _)| {
        n.fetch_add(1, Ordering::Relaxed);
        if certificate(&t, Q::new(1, 2)).is_none() {
            return Ok(());
        }
        r.fetch_add(1, Ordering::Relaxed);
        for alpha in super::c3::alphas() {
            let ok = certificate(&t, alpha).is_some_and(|c| optimal_policy_avoids_goal(&c, alpha));
            if !ok {
                return Err(TestCaseError::fail(format!(
                    "no certificate for alpha = {alpha}"
                )));
            }
        }
        Ok(())
    });
    finish("C3", format!("{cases} random structures (those satisfying the hypotheses counted), up to 7 states, 1-2 moves"), result, &n, &r)
}

/// C4 (as printed when `printed`, else corrected) against the oracle.
pub fn c4(printed: bool, cases: u32, persistence: Option<&'static str>) -> PropertyRun {
    let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
    let strategy = (tiny_strategy(6, 3, 0, 5), Just(Vec::<i64>::new()));
    let result = run_guarded(runner(cases, persistence), &strategy, |(t, _)| {
        n.fetch_add(1, Ordering::Relaxed);
        let inst = Instance::from_tiny(&t);
        let sets = match bonus_sets(&inst, 1 << 16) {
            Ok(Some(s)) => s,
            Ok(None) => return Ok(()),
            Err(e) => return Err(TestCaseError::fail(format!("internal: {e}"))),
        };
        for s in sets {
            let formula = if printed {
                s.printed
            } else {
                Some(s.corrected)
            };
            let Some(f) = formula else { continue };
            r.fetch_add(1, Ordering::Relaxed);
            if let Some(m) = witness(&f, &s.exact) {
                return Err(TestCaseError::fail(format!(
                    "S* = {}: at M = {m} the formula's set {f} disagrees with the exact set {}",
                    s.optimal_states, s.exact
                )));
            }
        }
        Ok(())
    });
    finish(
        if printed { "C4" } else { "C4-corrected" },
        format!("{cases} random problems (those with a goal path counted), up to 6 states, 1-3 moves, costs 0-5"),
        result,
        &n,
        &r,
    )
}

/// Number of generated cases per property in a scope.
pub fn cases(scope: Scope) -> u32 {
    match scope {
        Scope::Smoke => 64,
        Scope::Quick => 2000,
        Scope::Full => 20000,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A property whose code panics fails the engine (raised to the [`caught::caught`] around
    /// it, with the input proptest shrank it to), not the claim: a failing assertion of the
    /// same property is a counterexample.
    #[test]
    fn a_panic_in_a_property_fails_the_engine_not_the_claim() {
        let property = |panics: bool| {
            let (n, r) = (AtomicU64::new(0), AtomicU64::new(0));
            let result = run_guarded(runner(32, None), &with_values(4, 2, 1), |(t, _)| {
                n.fetch_add(1, Ordering::Relaxed);
                r.fetch_add(1, Ordering::Relaxed);
                match t.states() >= 3 {
                    true if panics => panic!("planted at {} states", t.states()),
                    true => Err(TestCaseError::fail("three states or more")),
                    false => Ok(()),
                }
            });
            caught::caught(|| finish("C0", String::new(), result, &n, &r))
        };
        let failure = property(true).unwrap_err();
        assert!(
            failure.starts_with("planted at 3 states (at src/claims/sampled.rs:"),
            "{failure}"
        );
        assert!(failure.contains("; on the input proptest shrank it to: "));
        let counterexample = property(false).unwrap().counterexample.unwrap();
        assert_eq!(counterexample.0.states(), 3);
        assert_eq!(counterexample.1, "three states or more");
    }

    /// The bound is inclusive: converging in exactly `bound` rounds passes, one more fails, and
    /// a cycle or a run cut off at the limit fails whatever the bound.
    #[test]
    fn converged_within_its_bound_and_not_beyond() {
        assert!(converged_within(&Run::Converged(0), 0));
        assert!(converged_within(&Run::Converged(3), 3));
        assert!(converged_within(&Run::Converged(2), 3));
        assert!(!converged_within(&Run::Converged(4), 3));
        assert!(!converged_within(&Run::Cycles(1, 2), 256));
        assert!(!converged_within(&Run::NotWithin(256), 256));
    }
}

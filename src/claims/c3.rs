//! Claim C3 (SPEC §6), general form: if a goal-reaching policy exists and some policy reaches a
//! cycle avoiding the goal, then there are costs `l` and a discount factor `α` for which a
//! discount-optimal policy has infinite true cost.
//!
//! The claim is existential, so each structure is checked with a *certificate*: costs `l` and
//! `α`, verified by the exact oracle (every stationary policy evaluated exactly; one optimal
//! policy from `x1` never reaches the goal, and all its stage costs are positive, so its true
//! cost is `+∞` however non-terminating trajectories are valued). The certificate comes from
//! a construction (cost 1 on the moves of a goal-avoiding lasso from `x1`, cost
//! `K > 1/((1-α) α^{n-2})` elsewhere), but it is *checked*, never trusted. We check the stronger
//! statement "for each α in a set, some `l` works".

use super::exact::{Frac, FracExt, Q};
use super::oracle::{evaluate_fast, policies, trajectory, Functional};
use super::tiny::{minimality_key, FamilySpec, Tiny, MAX_STATES};
use super::{enumerate, keep_min, min_of, ClaimResult, Counterexample, EngineRun, Scope, Verdict};

/// The statement of C3 as printed.
pub const STATEMENT: &str = "C3 (as printed): if a goal-reaching policy exists and some policy reaches a cycle avoiding \
the goal, then there are stage costs l and a discount factor alpha for which a discount-optimal policy has infinite \
true cost.";

/// The discount factors for which a certificate is required.
pub fn alphas() -> [Q; 2] {
    [Q::new(1, 2), Q::new(9, 10)]
}

/// The discount factors checked in a scope (`full` adds 2/3 and 99/100).
pub fn scope_alphas(scope: Scope) -> Vec<Q> {
    let mut v = alphas().to_vec();
    if scope == Scope::Full {
        v.push(Q::new(2, 3));
        v.push(Q::new(99, 100));
    }
    v
}

/// States from which an infinite walk avoiding the goal exists (greatest fixed point).
pub fn goal_avoiding_core(t: &Tiny) -> [bool; MAX_STATES] {
    let n = t.states();
    let mut w = [false; MAX_STATES];
    for (x, wx) in w.iter_mut().enumerate().take(n) {
        *wx = !t.is_goal(x);
    }
    loop {
        let mut changed = false;
        for x in 0..n {
            if w[x] && !t.moves(x).iter().any(|m| w[m.to as usize]) {
                w[x] = false;
                changed = true;
            }
        }
        if !changed {
            return w;
        }
    }
}

/// Whether the goal is reachable from `x1 = 0`.
pub fn goal_reachable(t: &Tiny) -> bool {
    let mut seen = [false; MAX_STATES];
    let mut stack = vec![0usize];
    seen[0] = true;
    while let Some(x) = stack.pop() {
        if t.is_goal(x) {
            return true;
        }
        for m in t.moves(x) {
            if !seen[m.to as usize] {
                seen[m.to as usize] = true;
                stack.push(m.to as usize);
            }
        }
    }
    false
}

/// The certificate construction for `alpha` (see the module doc). `None` if the hypotheses
/// fail or a cost does not fit.
pub fn certificate(t: &Tiny, alpha: Q) -> Option<Tiny> {
    let w = goal_avoiding_core(t);
    if !w[0] || !goal_reachable(t) {
        return None;
    }
    let n = t.states() as u32;
    let bound = Q::ONE / ((Q::ONE - alpha) * alpha.pow(n.saturating_sub(2)));
    let k = bound.numer() / bound.denom() + 1;
    let k = u8::try_from(k).ok()?;
    let mut marked = [[false; 3]; MAX_STATES];
    let mut x = 0usize;
    let mut seen = [false; MAX_STATES];
    while !seen[x] {
        seen[x] = true;
        let i = t.moves(x).iter().position(|m| w[m.to as usize])?;
        marked[x][i] = true;
        x = t.moves(x)[i].to as usize;
    }
    let mut c = *t;
    for y in 0..t.states() {
        for i in 0..t.deg[y] as usize {
            c.moves[y][i].cost = if marked[y][i] { 1 } else { k };
        }
    }
    Some(c)
}

/// The oracle: whether some policy that is discount-optimal from `x1 = 0` at `alpha` never
/// reaches the goal and has only positive stage costs on its trajectory.
pub fn optimal_policy_avoids_goal(t: &Tiny, alpha: Q) -> bool {
    let ps = policies(t, false);
    let mut best: Option<Frac> = None;
    let mut avoid_at_best = false;
    for p in &ps {
        let tr = trajectory(t, p, 0);
        let FracExt::Fin(value) = evaluate_fast(&tr, Functional::Discounted(alpha), 1) else {
            unreachable!("discounted values are finite")
        };
        let avoids =
            !tr.visits_goal && !tr.terminates && tr.cycle[..tr.cycle_len].iter().all(|&c| c > 0);
        match best {
            Some(b) if value > b => {}
            Some(b) if value == b => avoid_at_best |= avoids,
            _ => {
                best = Some(value);
                avoid_at_best = avoids;
            }
        }
    }
    avoid_at_best
}

type Key = (usize, usize, u64, u64, u64);

#[derive(Default, serde::Serialize, serde::Deserialize)]
struct Acc {
    cases: u64,
    hypotheses_fail: u64,
    certificates: u64,
    failures: u64,
    min: Option<(Key, (Tiny, String))>,
}

fn merge(a: Acc, b: Acc) -> Acc {
    Acc {
        cases: a.cases + b.cases,
        hypotheses_fail: a.hypotheses_fail + b.hypotheses_fail,
        certificates: a.certificates + b.certificates,
        failures: a.failures + b.failures,
        min: min_of(a.min, b.min),
    }
}

fn specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, d| FamilySpec {
        states,
        initial_fixed: true,
        degree: (1, d),
        goal_degree: (0, 0),
        costs: vec![0],
        distinct_successors: true,
    };
    match scope {
        Scope::Smoke => vec![spec(2, 2), spec(3, 2), spec(4, 2)],
        Scope::Quick => vec![spec(2, 2), spec(3, 3), spec(4, 3), spec(5, 3), spec(6, 2)],
        Scope::Full => vec![spec(2, 2), spec(3, 3), spec(4, 3), spec(5, 3), spec(6, 2)],
    }
}

/// Checks C3 in `scope`.
pub fn check(scope: Scope) -> ClaimResult {
    let scope_alphas = scope_alphas(scope);
    let started = std::time::Instant::now();
    let mut acc = Acc::default();
    let mut parts = Vec::new();
    let mut structures = 0;
    for spec in specs(scope) {
        let (a, distinct) = enumerate(
            &spec,
            Acc::default,
            |acc, t, i| {
                if certificate(t, Q::new(1, 2)).is_none() {
                    acc.hypotheses_fail += 1;
                    return;
                }
                acc.cases += 1;
                for &alpha in &scope_alphas {
                    let ok = certificate(t, alpha)
                        .is_some_and(|c| optimal_policy_avoids_goal(&c, alpha));
                    acc.certificates += 1;
                    if !ok {
                        acc.failures += 1;
                        keep_min(&mut acc.min, minimality_key(t, 0, i), || {
                            (*t, format!("no certificate found for alpha = {alpha}"))
                        });
                    }
                }
            },
            merge,
        );
        acc = merge(acc, a);
        structures += distinct;
        parts.push(format!(
            "{} states, 1-{} successors",
            spec.states, spec.degree.1
        ));
    }
    let alphas: Vec<String> = scope_alphas.iter().map(|a| a.to_string()).collect();
    let scope_line = format!(
        "{} structures satisfying the hypotheses, of {} up to relabelling ({}; distinct successors per state; x1 = 0, \
one goal); a checked certificate (l, alpha) for each alpha in {{{}}}",
        acc.cases,
        structures,
        parts.join(" | "),
        alphas.join(", ")
    );
    ClaimResult {
        id: "C3".into(),
        statement: STATEMENT.into(),
        verdict: if acc.failures == 0 {
            Verdict::Verified
        } else {
            Verdict::Inconclusive
        },
        engine: "exhaustive enumeration".into(),
        scope: scope_line.clone(),
        cases: acc.cases,
        counterexample: acc.min.as_ref().map(|(_, (t, what))| {
            Counterexample::new(t, format!("C3: {what}"), vec![], "c3-no-certificate")
        }),
        engines: vec![EngineRun {
            engine: "exhaustive enumeration".into(),
            mode: "exhaustive".into(),
            scope: scope_line,
            cases: acc.cases,
            failures: acc.failures,
            seconds: started.elapsed().as_secs_f64(),
        }],
        notes: vec![
            format!(
                "{} certificates (costs 1 on a goal-avoiding lasso from x1, K elsewhere) checked by exact evaluation of \
every stationary policy; the discount-optimal policy found never reaches the goal and pays >= 1 per stage, so its \
true cost is +inf",
                acc.certificates
            ),
            format!("{} structures fail the hypotheses and are not cases", acc.hypotheses_fail),
        ],
    }
}

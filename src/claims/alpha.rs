//! The worked example of claim C3 (docs/spec.md §6) exactly: `X = {0..5}`, goal 5, `U = {-1, +1}`,
//! `f(x,u) = min(5, max(0, x+u))`, `l(x,u) = x + 1`. The paper says the discount-optimal
//! policy from 0 avoids the goal exactly when `1/(1-α) < Σ_{i=1..5} i α^{i-1}`.
//!
//! The threshold `α*` is the root in `(0,1)` of `P(α) = (1-α)·Σ_{i=1..5} i α^{i-1} − 1`
//! (the printed inequality multiplied by `1 − α > 0`), isolated by a Sturm sequence and
//! bracketed by two rationals less than `10^-30` apart. Both sides are checked by exact
//! discounted solves: every one of the example's stationary policies is evaluated exactly at
//! the bracket's ends, and the optimal ones avoid (below) or reach (above) the goal.

use num_bigint::BigInt;
use num_traits::{One, Zero};

use super::oracle::{policies, trajectory, Trajectory};
use super::tiny::Tiny;
use super::{ClaimResult, EngineRun, Verdict};
use crate::algebra::poly::{isolate_roots, Algebraic, Poly};
use crate::value::Rational;

/// The statement checked.
pub const STATEMENT: &str = "C3-example (as printed): in X = {0..5}, goal 5, U = {-1,+1}, f(x,u) = min(5, max(0, x+u)), \
l(x,u) = x+1, the discount-optimal policy from 0 avoids the goal exactly when 1/(1-alpha) < sum_{i=1..5} i alpha^(i-1); \
the threshold alpha* is isolated exactly and both sides are checked by exact discounted solves.";

/// The worked example as a tiny problem (goal 5 keeps its two moves besides termination).
pub fn worked_example() -> Tiny {
    let lists: Vec<Vec<(u8, u8)>> = (0..6u8)
        .map(|x| {
            let down = x.saturating_sub(1);
            let up = (x + 1).min(5);
            vec![(down, x + 1), (up, x + 1)]
        })
        .collect();
    Tiny::from_lists(&lists)
}

/// `P(α) = (1 − (1 − α) Σ_{i=1..5} i α^{i−1}) / α = 5α⁴ − α³ − α² − α − 1`, built from the
/// printed inequality (multiplied by `1 − α > 0`; the factor `α > 0` removed): on `(0, 1)` the
/// inequality holds exactly where `P(α) < 0`.
///
/// ```
/// assert_eq!(truecost::claims::alpha::printed_polynomial().to_string(), "5x^4 - x^3 - x^2 - x - 1");
/// ```
pub fn printed_polynomial() -> Poly {
    let sum = Poly::from_i64(&[1, 2, 3, 4, 5]);
    let p = Poly::from_i64(&[1, -1])
        .mul(&sum)
        .sub(&Poly::from_i64(&[1]));
    let (q, r) = p.div_rem(&Poly::monomial(1));
    assert!(r.is_zero(), "P(0) = 0");
    q.scale(&Rational::from_integer(BigInt::from(-1)))
}

/// `α*`: the unique root of [`printed_polynomial`] in `(0,1)`, bracketed to width
/// `≤ 2^-100 < 10^-30`. Returns an error if the root is not unique.
///
/// ```
/// let a = truecost::claims::alpha::alpha_star().unwrap();
/// assert!(a.decimal(6).starts_with("0.9"));
/// ```
pub fn alpha_star() -> Result<Algebraic, String> {
    let p = printed_polynomial();
    let roots = isolate_roots(&p, &Rational::zero(), &Rational::one());
    if roots.len() != 1 {
        return Err(format!("{} roots of {p} in (0,1), expected 1", roots.len()));
    }
    let mut a = roots[0].clone();
    a.refine_to(&Rational::new(BigInt::one(), BigInt::one() << 100usize));
    Ok(a)
}

/// The exact discounted cost `Σ α^{k-1} l_k` of a trajectory (big rationals).
pub fn discounted_value(tr: &Trajectory, alpha: &Rational) -> Rational {
    let mut value = Rational::zero();
    let mut power = Rational::one();
    for &c in &tr.prefix[..tr.prefix_len] {
        value += &power * Rational::from_integer(BigInt::from(c));
        power *= alpha;
    }
    let mut cycle = Rational::zero();
    let mut p = Rational::one();
    for &c in &tr.cycle[..tr.cycle_len] {
        cycle += &p * Rational::from_integer(BigInt::from(c));
        p *= alpha;
    }
    value + power * cycle / (Rational::one() - p)
}

/// By exact solve (every stationary policy evaluated exactly at `alpha`): whether every
/// discount-optimal policy from `x1 = 0` avoids the goal, and whether every one reaches it.
pub fn optimal_policies_from_initial(t: &Tiny, alpha: &Rational) -> (bool, bool) {
    let ps = policies(t, true);
    let trs: Vec<Trajectory> = ps.iter().map(|p| trajectory(t, p, 0)).collect();
    let values: Vec<Rational> = trs.iter().map(|tr| discounted_value(tr, alpha)).collect();
    let best = values.iter().min().expect("a policy").clone();
    let optimal: Vec<&Trajectory> = trs
        .iter()
        .zip(&values)
        .filter(|(_, v)| **v == best)
        .map(|(tr, _)| tr)
        .collect();
    (
        optimal.iter().all(|tr| !tr.visits_goal),
        optimal.iter().all(|tr| tr.visits_goal),
    )
}

/// The printed inequality `1/(1-α) < Σ_{i=1..5} i α^{i-1}`, evaluated directly.
pub fn printed_inequality(alpha: &Rational) -> bool {
    let lhs = Rational::one() / (Rational::one() - alpha);
    let mut rhs = Rational::zero();
    let mut p = Rational::one();
    for i in 1..=5 {
        rhs += &p * Rational::from_integer(BigInt::from(i));
        p *= alpha;
    }
    lhs < rhs
}

/// Checks the worked example: `α*` isolated; strictly below it the optimal policy avoids the
/// goal, strictly above it reaches it; and the printed equivalence at `α = k/100`.
pub fn check() -> (ClaimResult, Option<Algebraic>) {
    let started = std::time::Instant::now();
    let star = match alpha_star() {
        Ok(a) => a,
        Err(e) => {
            return (
                ClaimResult {
                    id: "C3-example".into(),
                    statement: STATEMENT.into(),
                    verdict: Verdict::Refuted,
                    engine: "exact solve".into(),
                    scope: e.clone(),
                    cases: 0,
                    counterexample: None,
                    engines: vec![],
                    notes: vec![e],
                },
                None,
            )
        }
    };
    let mut result = check_threshold(&worked_example(), &star, printed_inequality);
    // The run's time includes isolating α*.
    for run in &mut result.engines {
        run.seconds = started.elapsed().as_secs_f64();
    }
    (result, Some(star))
}

/// The exact-solve checks of [`check`] for a given bracket `star` of the threshold and a given
/// form `printed` of the inequality: strictly below the bracket an optimal policy from 0 must
/// avoid the goal, strictly above it reach it, and at `α = k/100`, `k = 1..99`, `printed(α)`
/// must hold exactly where the optimal policies avoid the goal. [`check`] passes `α*` and
/// [`printed_inequality`]; any failure makes the verdict `Refuted` with a note naming it.
///
/// ```
/// use truecost::claims::alpha::{check_threshold, printed_inequality, worked_example};
/// use truecost::algebra::poly::Algebraic;
/// use truecost::claims::Verdict;
/// use truecost::value::Rational;
/// // A bracket (1/2 − 2^-10, 1/2], below α* ≈ 0.92: at its upper end the optimal policy
/// // still avoids the goal.
/// let mut half = Algebraic::from_rational(Rational::new(1.into(), 2.into()));
/// half.refine_to(&Rational::new(1.into(), 1024.into()));
/// let r = check_threshold(&worked_example(), &half, printed_inequality);
/// assert_eq!((r.verdict, r.cases), (Verdict::Refuted, 101));
/// ```
pub fn check_threshold(
    t: &Tiny,
    star: &Algebraic,
    printed: impl Fn(&Rational) -> bool,
) -> ClaimResult {
    let started = std::time::Instant::now();
    let mut notes = Vec::new();
    let mut failures = 0u64;
    let mut cases = 0u64;
    // Both sides of α*.
    let (avoid_lo, _) = optimal_policies_from_initial(t, &star.lo);
    let (_, reach_hi) = optimal_policies_from_initial(t, &star.hi);
    cases += 2;
    if !avoid_lo {
        failures += 1;
        notes.push("at the lower end of the bracket an optimal policy reaches the goal".into());
    }
    if !reach_hi {
        failures += 1;
        notes.push("at the upper end of the bracket an optimal policy avoids the goal".into());
    }
    // The printed equivalence on a grid of rationals.
    let mut grid_fail = Vec::new();
    for k in 1..100 {
        let a = Rational::new(BigInt::from(k), BigInt::from(100));
        let (avoid, reach) = optimal_policies_from_initial(t, &a);
        cases += 1;
        let holds = printed(&a);
        if !(holds && avoid || !holds && reach) {
            failures += 1;
            grid_fail.push(k.to_string());
        }
    }
    notes.push(format!(
        "alpha* is the root of {} in (0,1) (Sturm sequence: exactly one root there); bracket width <= 2^-100",
        printed_polynomial().primitive()
    ));
    notes.push(
        "exact solves: all 96 stationary policies of the example evaluated exactly at both bracket ends and at \
alpha = k/100, k = 1..99; the printed inequality is evaluated directly at each alpha"
            .into(),
    );
    if !grid_fail.is_empty() {
        notes.push(format!(
            "the equivalence fails at alpha = k/100 for k in {}",
            grid_fail.join(",")
        ));
    }
    let verdict = if failures == 0 {
        Verdict::Verified
    } else {
        Verdict::Refuted
    };
    let scope = "the worked example: 2 bracket ends of alpha* and 99 rationals k/100".to_string();
    ClaimResult {
        id: "C3-example".into(),
        statement: STATEMENT.into(),
        verdict,
        engine: "exact solve".into(),
        scope: scope.clone(),
        cases,
        counterexample: None,
        engines: vec![EngineRun {
            engine: "exact solve".into(),
            mode: "exhaustive".into(),
            scope,
            cases,
            failures,
            seconds: started.elapsed().as_secs_f64(),
        }],
        notes,
    }
}

//! SMT encodings of claim C3 (docs/spec.md §6, the dangers of discounting): the
//! worked example for every real `α ∈ (0,1)` (`C3-example`), and each structure's certificate
//! for every real `α` in a stated interval (`C3`). Both are univariate nonlinear real
//! arithmetic (QF_NRA) in the one unknown `α`.
//!
//! **Independent formulation.** Every deterministic stationary policy is followed from `x1`
//! ([`super::c2::lassos`]); its discounted cost is that of its lasso,
//! `V = Σ_{k<p} α^k c_k + α^p (Σ_{j<q} α^j d_j) / (1 − α^q)` (prefix costs `c`, cycle costs `d`;
//! a terminating lasso has `V = Σ α^k c_k`), a rational function `N(α)/D(α)` with
//! `D(α) = 1 − α^q`. On `(0,1)`, `D > 0` (its own proof obligations, [`DENOMINATORS`]), so
//! `V_a ≤ V_b ⟺ N_a·D_b ≤ N_b·D_a`: every comparison is a polynomial inequality in `α` with the
//! denominators cleared by their known sign.

use super::c2::{lassos, parse_shape, poly_term, Lasso};
use super::term::{and, eq, ge, gt, le, lt, mul, not, or, real, real_int, sub};
use super::{Encoding, Logic, Model, Obligation, Replay, Role, Sort};
use crate::algebra::poly::Poly;
use crate::claims::alpha::{
    discounted_value, optimal_policies_from_initial, printed_inequality, worked_example,
};
use crate::claims::c3::certificate;
use crate::claims::exact::Q;
use crate::claims::oracle::{policies, trajectory};
use crate::claims::tiny::{Family, FamilySpec, Tiny};
use crate::claims::Scope;
use crate::value::Rational;

/// The lemma of the obligations that the denominators `1 − α^q` are positive on `(0,1)`.
pub const DENOMINATORS: &str = "1 - alpha^q > 0 on (0,1)";

const BELOW: &str = "threshold < 0: every discount-optimal policy from 0 avoids the goal";
const ABOVE: &str = "threshold > 0: every discount-optimal policy from 0 reaches the goal";
const AT: &str = "threshold = 0: optimal policies of both kinds (a tie)";
const PRINTED: &str = "printed 1/(1-alpha) < sum i alpha^(i-1) iff threshold < 0";

/// The threshold polynomial of the claim, `5α⁴ − α³ − α² − α − 1`, constant first.
pub const THRESHOLD: [i64; 5] = [-1, -1, -1, -1, 5];

/// `(N, D)` with `V = N(α)/D(α)`: the discounted value of a lasso whose stage costs are given
/// by `cost` (the termination stage costs 0).
///
/// ```
/// use truecost::algebra::poly::Poly;
/// use truecost::claims::smt::c2::Lasso;
/// use truecost::claims::smt::c3::lasso_fraction;
/// // prefix cost 2, then a cycle of cost 1: 2 + α/(1 − α) = (2 − α)/(1 − α).
/// let l = Lasso { prefix: vec![(0, 0)], cycle: vec![(1, 0)], terminates: false, visits_goal: false };
/// let (n, d) = lasso_fraction(&l, &|m| if m.0 == 0 { 2 } else { 1 });
/// assert_eq!((n, d), (Poly::from_i64(&[2, -1]), Poly::from_i64(&[1, -1])));
/// ```
pub fn lasso_fraction(l: &Lasso, cost: &dyn Fn((usize, usize)) -> i64) -> (Poly, Poly) {
    let series = |moves: &[(usize, usize)]| {
        Poly::from_i64(&moves.iter().map(|&m| cost(m)).collect::<Vec<_>>())
    };
    let prefix = series(&l.prefix);
    if l.terminates {
        return (prefix, Poly::from_i64(&[1]));
    }
    let d = Poly::from_i64(&[1]).sub(&Poly::monomial(l.cycle.len()));
    let n = d
        .mul(&prefix)
        .add(&Poly::monomial(l.prefix.len()).mul(&series(&l.cycle)));
    (n, d)
}

/// `V_a ≤ V_b` (or `<` when `strict`) with denominators cleared: `N_a·D_b ≤ N_b·D_a`.
fn compare(a: &(Poly, Poly), b: &(Poly, Poly), strict: bool, var: &str) -> String {
    let lhs = mul(&poly_term(&a.0, var), &poly_term(&b.1, var));
    let rhs = mul(&poly_term(&b.0, var), &poly_term(&a.1, var));
    if strict {
        lt(&lhs, &rhs)
    } else {
        le(&lhs, &rhs)
    }
}

/// `0 < α < 1`.
fn unit(a: &str) -> String {
    and(&[gt(a, &real_int(0)), lt(a, &real_int(1))])
}

/// The obligations `0 < α < 1 ∧ 1 − α^q ≤ 0` (unsat) for each cycle length `q`.
fn denominators(claim: &str, lengths: &[usize]) -> Vec<Obligation> {
    let mut qs = lengths.to_vec();
    qs.sort_unstable();
    qs.dedup();
    qs.into_iter()
        .map(|q| {
            let mut o = Obligation::new(
                claim,
                DENOMINATORS,
                &format!("q = {q}"),
                Role::Proof,
                Logic::QfNra,
            );
            let a = o.declare("a", Sort::Real);
            o.assert(unit(&a));
            let d = Poly::from_i64(&[1]).sub(&Poly::monomial(q));
            o.assert(le(&poly_term(&d, &a), &real_int(0)));
            o
        })
        .collect()
}

/// `Σ_k p_k α^k` with declared coefficient constants `p0, p1, …` fixed to `coefficients`, so
/// that a model carries the threshold it refutes (the replay reads it back).
fn threshold_term(o: &mut Obligation, coefficients: &[Rational], a: &str) -> String {
    let mut terms = Vec::new();
    for (k, c) in coefficients.iter().enumerate() {
        let p = o.declare(&format!("p{k}"), Sort::Real);
        o.assert(eq(&p, &real(c)));
        if k == 0 {
            terms.push(p);
        } else {
            let mut factors = vec![p];
            factors.extend(std::iter::repeat_n(a.to_string(), k));
            terms.push(super::term::app("*", &factors));
        }
    }
    super::term::sum(&terms)
}

/// The C3-example encoding with the claim's threshold [`THRESHOLD`] (see the module doc and
/// `docs/proofs/c3.md`); the same in every scope (one structure, every real `α`).
///
/// ```no_run
/// use truecost::claims::smt::{c3, run, SmtVerdict, TIMEOUT_MS};
/// use truecost::claims::Scope;
/// assert_eq!(run(c3::example_encoding(Scope::Quick), TIMEOUT_MS).verdict, SmtVerdict::Proved);
/// ```
pub fn example_encoding(_scope: Scope) -> Encoding {
    let r = |n: i64| Rational::from_integer(n.into());
    example_encoding_with(&THRESHOLD.iter().map(|&c| r(c)).collect::<Vec<_>>())
}

/// The C3-example encoding with `threshold` (coefficients, constant first) in place of the
/// claim's polynomial in the proof obligations (the mutation test plants a wrong one).
pub fn example_encoding_with(threshold: &[Rational]) -> Encoding {
    let t = worked_example();
    let cost = |(x, i): (usize, usize)| i64::from(t.moves(x)[i].cost);
    let ls = lassos(&t, true);
    let values: Vec<(Poly, Poly)> = ls.iter().map(|l| lasso_fraction(l, &cost)).collect();
    let structure = format!(
        "worked example ({} stationary policies, {} lassos from 0)",
        policies(&t, true).len(),
        ls.len()
    );
    // "Some optimal policy of this kind": ∨_{a of the kind} ∧_{every b} V_a ≤ V_b.
    let optimal_of_kind = |reaches: bool, a: &str| {
        or(&(0..ls.len())
            .filter(|&k| ls[k].visits_goal == reaches)
            .map(|k| {
                and(&(0..ls.len())
                    .map(|j| compare(&values[k], &values[j], false, a))
                    .collect::<Vec<_>>())
            })
            .collect::<Vec<_>>())
    };
    let family = |lemma: &str, role: Role, threshold: &[Rational], conclusion: bool| {
        let mut o = Obligation::new("C3-example", lemma, &structure, role, Logic::QfNra);
        let a = o.declare("a", Sort::Real);
        o.assert(unit(&a));
        let p = threshold_term(&mut o, threshold, &a);
        let zero = real_int(0);
        let (side, negated) = match lemma {
            BELOW => (lt(&p, &zero), optimal_of_kind(true, &a)),
            ABOVE => (gt(&p, &zero), optimal_of_kind(false, &a)),
            _ => (
                eq(&p, &zero),
                not(&and(&[
                    optimal_of_kind(false, &a),
                    optimal_of_kind(true, &a),
                ])),
            ),
        };
        o.assert(side);
        if conclusion {
            o.assert(negated);
        }
        o
    };
    let claimed: Vec<Rational> = THRESHOLD
        .iter()
        .map(|&c| Rational::from_integer(c.into()))
        .collect();
    let mut obligations = Vec::new();
    for lemma in [BELOW, ABOVE, AT] {
        obligations.push(family(lemma, Role::Proof, threshold, true));
    }
    // The printed inequality against the threshold: L = 1/(1−α) stated as L·(1−α) = 1.
    let mut o = Obligation::new("C3-example", PRINTED, "none", Role::Proof, Logic::QfNra);
    let a = o.declare("a", Sort::Real);
    let l = o.declare("L", Sort::Real);
    o.assert(unit(&a));
    o.assert(eq(&mul(&l, &sub(&real_int(1), &a)), &real_int(1)));
    let p = threshold_term(&mut o, threshold, &a);
    let printed = lt(&l, &poly_term(&Poly::from_i64(&[1, 2, 3, 4, 5]), &a));
    o.assert(not(&eq(&printed, &lt(&p, &real_int(0)))));
    obligations.push(o);
    let lengths: Vec<usize> = ls
        .iter()
        .filter(|l| !l.terminates)
        .map(|l| l.cycle.len())
        .collect();
    obligations.extend(denominators("C3-example", &lengths));
    // Trust checks: each side's hypotheses are satisfiable; a planted threshold too low
    // (10α − 9: α = 9/10 < α*) and one too high (20α − 19) find the failure.
    for lemma in [BELOW, ABOVE, AT] {
        obligations.push(family(lemma, Role::Hypotheses, &claimed, false));
    }
    let q = |n: i64, d: i64| Rational::new(n.into(), d.into());
    obligations.push(family(
        ABOVE,
        Role::Dropped("the exact threshold (planted: 10 alpha - 9)".into()),
        &[q(-9, 1), q(10, 1)],
        true,
    ));
    obligations.push(family(
        BELOW,
        Role::Dropped("the exact threshold (planted: 20 alpha - 19)".into()),
        &[q(-19, 1), q(20, 1)],
        true,
    ));
    Encoding {
        claim: "C3-example",
        scope: format!(
            "the worked example (X = {{0..5}}, goal 5 with termination and its two moves, l(x,u) = x+1): every \
real alpha in (0,1); all {} stationary policies, as the {} distinct lassos they follow from 0; 'avoids' = every \
discount-optimal policy from 0 avoids the goal (at the threshold's root both kinds are optimal)",
            policies(&t, true).len(),
            ls.len()
        ),
        obligations,
        replay: example_replay,
    }
}

/// The threshold polynomial a model carries (`p0, p1, …`).
fn model_threshold(m: &Model) -> Poly {
    let mut c = Vec::new();
    while let Some(v) = m.get(&format!("p{}", c.len())) {
        c.push(v.clone());
    }
    Poly::new(c)
}

/// Replays a C3-example model: `α` and the threshold read back exactly, the oracle
/// (`alpha::optimal_policies_from_initial`: every stationary policy solved exactly at `α`)
/// decides whether the optimal policies avoid or reach the goal.
pub fn example_replay(o: &Obligation, m: &Model) -> Replay {
    let Some(a) = m.get("a") else {
        return Replay::NotConfirmed("no alpha in the model".into());
    };
    let zero = Rational::from_integer(0.into());
    let one = Rational::from_integer(1.into());
    if !(*a > zero && *a < one) {
        return Replay::NotConfirmed(format!("alpha = {a} is not in (0,1)"));
    }
    let p = model_threshold(m).eval(a);
    let (all_avoid, all_reach) = optimal_policies_from_initial(&worked_example(), a);
    let confirmed = match o.lemma.as_str() {
        BELOW => (p < zero && !all_avoid).then(|| {
            format!("at alpha = {a} the threshold is {p} < 0 but a discount-optimal policy from 0 reaches the goal")
        }),
        ABOVE => (p > zero && !all_reach).then(|| {
            format!("at alpha = {a} the threshold is {p} > 0 but a discount-optimal policy from 0 avoids the goal")
        }),
        AT => (p == zero && (all_avoid || all_reach)).then(|| {
            format!("at alpha = {a} the threshold is 0 but the optimal policies are all of one kind")
        }),
        PRINTED => (printed_inequality(a) != (p < zero)).then(|| {
            format!("at alpha = {a} the printed inequality and the threshold's sign disagree")
        }),
        _ => None,
    };
    match confirmed {
        Some(what) => Replay::Confirmed(what, None),
        None => Replay::NotConfirmed(format!(
            "the exact solve at alpha = {a} does not confirm the failure of '{}'",
            o.lemma
        )),
    }
}

/// The largest structures that get the trust checks with a hypothesis dropped.
pub fn dropped_states(scope: Scope) -> usize {
    match scope {
        Scope::Smoke | Scope::Quick => 3,
        Scope::Full => 4,
    }
}

/// The interval of `α` for which every certificate is checked.
pub fn interval() -> (Q, Q) {
    (Q::new(1, 2), Q::new(9, 10))
}

/// The structures of the C3 scope (the C3 enumeration's families, smaller).
pub fn structure_specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, d| FamilySpec {
        states,
        initial_fixed: true,
        degree: (1, d),
        goal_degree: (0, 0),
        costs: vec![0],
        distinct_successors: true,
    };
    match scope {
        Scope::Smoke => vec![spec(2, 2), spec(3, 2)],
        Scope::Quick => vec![spec(2, 2), spec(3, 3), spec(4, 2)],
        Scope::Full => vec![spec(2, 2), spec(3, 3), spec(4, 3), spec(5, 2)],
    }
}

/// The certificate checked on `[lo, hi]`: `c3::certificate` at `lo` or at `hi`, whichever has
/// the larger cost `K` (the construction's bound `1/((1−α)α^{n−2})` is largest at an end).
pub fn interval_certificate(t: &Tiny, (lo, hi): (Q, Q)) -> Option<Tiny> {
    let a = certificate(t, lo)?;
    let b = certificate(t, hi)?;
    Some(if a.cost_sum() >= b.cost_sum() { a } else { b })
}

const CERTIFIED: &str = "every other policy is strictly worse than the goal-avoiding lasso";

/// One structure's C3 obligation on `[lo, hi]` for the costed problem `c`: `α ∈ [lo, hi]` and
/// some other lasso (goal-reaching or not) at most as costly as the certificate's goal-avoiding lasso (the
/// lasso of the moves of cost 1 from `x1`).
fn certificate_obligation(c: &Tiny, bounds: (Option<Q>, Option<Q>), role: Role) -> Obligation {
    let cost = |(x, i): (usize, usize)| i64::from(c.moves(x)[i].cost);
    let ls = lassos(c, false);
    let structure = c.describe();
    let mut o = Obligation::new("C3", CERTIFIED, &structure, role, Logic::QfNra);
    let a = o.declare("a", Sort::Real);
    o.assert(unit(&a));
    if let Some(lo) = bounds.0 {
        o.assert(ge(&a, &real(&lo.to_rational())));
    }
    if let Some(hi) = bounds.1 {
        o.assert(le(&a, &real(&hi.to_rational())));
    }
    let marked = ls
        .iter()
        .find(|l| !l.visits_goal && l.prefix.iter().chain(&l.cycle).all(|&m| cost(m) == 1));
    let failures: Vec<String> = match marked {
        None => vec!["true".into()],
        Some(m) => {
            let vm = lasso_fraction(m, &cost);
            ls.iter()
                .filter(|l| *l != m)
                .map(|l| compare(&lasso_fraction(l, &cost), &vm, false, &a))
                .collect()
        }
    };
    o.assert(or(&failures));
    o
}

/// The C3 encoding in `scope` on the interval [`interval`] (see `docs/proofs/c3.md`).
pub fn encoding(scope: Scope) -> Encoding {
    encoding_with(scope, interval())
}

/// The C3 encoding with the interval `[lo, hi]` (the mutation test plants a wrong one).
pub fn encoding_with(scope: Scope, (lo, hi): (Q, Q)) -> Encoding {
    let mut obligations = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let (mut shapes, mut hypotheses_fail, mut lengths) = (0u64, 0u64, Vec::new());
    let mut parts = Vec::new();
    for spec in structure_specs(scope) {
        parts.push(format!(
            "{} states, 1-{} successors",
            spec.states, spec.degree.1
        ));
        let family = Family::new(&spec);
        for t in family.canonical() {
            shapes += 1;
            let Some(c) = interval_certificate(&t, interval()) else {
                hypotheses_fail += 1;
                continue;
            };
            let proof = certificate_obligation(&c, (Some(lo), Some(hi)), Role::Proof);
            if !seen.insert(proof.asserts.join("\n")) {
                continue;
            }
            lengths.extend(lassos(&c, false).iter().map(|l| l.cycle.len()));
            let mut h = proof.with_role(Role::Hypotheses);
            h.asserts.pop();
            obligations.push(proof);
            obligations.push(h);
            if c.states() > dropped_states(scope) {
                continue;
            }
            obligations.push(certificate_obligation(
                &c,
                (Some(lo), None),
                Role::Dropped(format!("alpha <= {hi}")),
            ));
            let mut flat = c;
            for x in 0..flat.states() {
                for k in 0..flat.deg[x] as usize {
                    flat.moves[x][k].cost = 1;
                }
            }
            obligations.push(certificate_obligation(
                &flat,
                (Some(lo), Some(hi)),
                Role::Dropped("K > 1/((1-alpha) alpha^(n-2)) (costs perturbed: K = 1)".into()),
            ));
        }
    }
    lengths.retain(|&q| q > 0);
    obligations.extend(denominators("C3", &lengths));
    let proofs = obligations.iter().filter(|o| o.role == Role::Proof).count();
    Encoding {
        claim: "C3",
        scope: format!(
            "every real alpha in [{lo}, {hi}]; every structure with {} (distinct successors per state; x1 = 0, one goal \
without moves), up to relabelling, enumerated outside the solver: {shapes} structures, {hypotheses_fail} failing the \
hypotheses, {} distinct certificate obligations; certificate = c3::certificate at {} or {}, the larger K; every \
stationary policy from x1 (one lasso per class); trust checks with alpha <= hi dropped and with K = 1 on every \
structure with <= {} states",
            parts.join(" | "),
            proofs - obligations.iter().filter(|o| o.lemma == DENOMINATORS).count(),
            interval().0,
            interval().1,
            dropped_states(scope)
        ),
        obligations,
        replay,
    }
}

/// Replays a C3 model exactly: the costed structure read back, `α` from the model, every
/// stationary policy's discounted value from `x1` computed by the oracle
/// (`oracle::trajectory`, `alpha::discounted_value`); confirmed if some goal-reaching policy
/// costs at most `1/(1−α)`, the value of the goal-avoiding lasso of cost-1 moves.
pub fn replay(o: &Obligation, m: &Model) -> Replay {
    let Some(a) = m.get("a") else {
        return Replay::NotConfirmed("no alpha in the model".into());
    };
    let one = Rational::from_integer(1.into());
    if o.lemma == DENOMINATORS {
        return Replay::NotConfirmed(format!("1 - alpha^q <= 0 at alpha = {a}"));
    }
    let lists: Option<Vec<Vec<(u8, u8)>>> = parse_shape(&o.structure).and_then(|s| {
        s.into_iter()
            .map(|l| {
                l.into_iter()
                    .map(|(to, c)| c.parse().ok().map(|c| (to, c)))
                    .collect()
            })
            .collect()
    });
    let Some(lists) = lists else {
        return Replay::NotConfirmed(format!("cannot read the structure {}", o.structure));
    };
    let t = Tiny::from_lists(&lists);
    let avoiding = &one / (&one - a);
    let best_reaching = policies(&t, false)
        .iter()
        .map(|p| trajectory(&t, p, 0))
        .filter(|tr| tr.visits_goal)
        .map(|tr| discounted_value(&tr, a))
        .min();
    match best_reaching {
        Some(v) if v <= avoiding => Replay::Confirmed(
            format!(
                "at alpha = {a} a goal-reaching policy costs {v} <= 1/(1-alpha) = {avoiding} on {}",
                t.describe()
            ),
            None,
        ),
        _ => Replay::NotConfirmed(format!(
            "at alpha = {a} every goal-reaching policy costs more than 1/(1-alpha) on {}",
            t.describe()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::smt::{solve, Answer, TIMEOUT_MS};

    fn q(n: i64, d: i64) -> Rational {
        Rational::new(n.into(), d.into())
    }

    /// A model of `α` and the threshold's coefficients `p0, p1, …` (none: the zero polynomial).
    fn model(a: Rational, threshold: &[i64]) -> Model {
        let mut values = vec![("a".to_string(), a)];
        for (k, &c) in threshold.iter().enumerate() {
            values.push((format!("p{k}"), q(c, 1)));
        }
        Model { values }
    }

    fn confirmed(r: Replay) -> bool {
        matches!(r, Replay::Confirmed(_, None))
    }

    /// The C3-example replay confirms a lemma's failure only when both its sides fail at the
    /// model's `α`, worked out by hand on the worked example. At `α = 1/2` the goal-avoiding
    /// loop at 0 costs `1/(1 − α) = 2` and every goal-reaching policy at least the path to 5,
    /// `1 + 2α + 3α² + 4α³ + 5α⁴ = 57/16 > 2`: every optimal policy avoids the goal. At `α =
    /// 99/100` the loop costs 100, the 2-cycle `0 ↔ 1` `(1 + 2α)/(1 − α²) > 100` (every other
    /// avoiding lasso costs more per stage), the path to 5 then termination less than
    /// `1 + 2 + 3 + 4 + 5 = 15`: every optimal policy reaches it. The claim's threshold at
    /// `1/2` is `5/16 − 1/8 − 1/4 − 1/2 − 1 = −25/16`; the printed inequality `2 < 57/16`
    /// holds there. A model with no coefficients carries the threshold 0, which is neither
    /// `< 0` nor `> 0`.
    #[test]
    fn the_example_replay_confirms_only_a_failure_of_both_sides() {
        let claimed = THRESHOLD.to_vec();
        let at = |lemma: &str, a: Rational, threshold: &[i64]| {
            let o = Obligation::new("C3-example", lemma, "x", Role::Proof, Logic::QfNra);
            confirmed(example_replay(&o, &model(a, threshold)))
        };
        // Below: threshold < 0 and a goal-reaching policy optimal.
        assert!(!at(BELOW, q(99, 100), &[]), "threshold 0 is not < 0");
        assert!(
            at(BELOW, q(99, 100), &[-1]),
            "-1 < 0 and the goal is reached"
        );
        assert!(
            !at(BELOW, q(1, 2), &[-1]),
            "-1 < 0 but every optimal policy avoids"
        );
        // Above: threshold > 0 and a goal-avoiding policy optimal.
        assert!(!at(ABOVE, q(1, 2), &[]), "threshold 0 is not > 0");
        assert!(at(ABOVE, q(1, 2), &[1]), "1 > 0 and the goal is avoided");
        assert!(
            !at(ABOVE, q(99, 100), &[1]),
            "1 > 0 but every optimal policy reaches"
        );
        // At: threshold = 0 and the optimal policies all of one kind.
        assert!(!at(AT, q(1, 2), &claimed), "the threshold is -25/16, not 0");
        assert!(
            at(AT, q(1, 2), &[]),
            "threshold 0 and every optimal policy avoids"
        );
        // Printed: the printed inequality (true at 1/2) against "threshold < 0".
        assert!(!at(PRINTED, q(1, 2), &claimed), "-25/16 < 0: they agree");
        assert!(at(PRINTED, q(1, 2), &[]), "0 is not < 0: they disagree");
    }

    /// The trust checks plant the thresholds `10α − 9` (root 9/10, below `α* ≈ 0.916`) and
    /// `20α − 19` (root 19/20, above it), constant coefficient first: `p0 = −9, p1 = 10` and
    /// `p0 = −19, p1 = 20`.
    #[test]
    fn the_planted_thresholds_are_ten_alpha_minus_nine_and_twenty_alpha_minus_nineteen() {
        let enc = example_encoding(Scope::Smoke);
        let planted = |role: &str| {
            enc.obligations
                .iter()
                .find(|o| o.role == Role::Dropped(role.into()))
                .unwrap_or_else(|| panic!("no trust check '{role}'"))
                .asserts
                .clone()
        };
        let low = planted("the exact threshold (planted: 10 alpha - 9)");
        assert!(low.contains(&"(= p0 (- 9.0))".to_string()), "{low:?}");
        assert!(low.contains(&"(= p1 10.0)".to_string()), "{low:?}");
        let high = planted("the exact threshold (planted: 20 alpha - 19)");
        assert!(high.contains(&"(= p0 (- 19.0))".to_string()), "{high:?}");
        assert!(high.contains(&"(= p1 20.0)".to_string()), "{high:?}");
    }

    /// The certificate obligation compares every other lasso with the goal-*avoiding* lasso of
    /// cost-1 moves, even when a goal-reaching lasso of cost-1 moves comes first. On
    /// `0: ->1 (1), ->0 (1); 1 (goal)` (the lassos in order: to the goal, then the loop) the
    /// goal path costs 1 and the loop `1/(1 − α)`, so the goal path is at most as costly for
    /// every `α` in `[1/2, 9/10]`: sat, and the model replays (compared the other way round,
    /// `1/(1 − α) ≤ 1` would need `α ≤ 0`: unsat).
    #[test]
    fn the_certificate_obligation_marks_the_goal_avoiding_lasso() {
        let c = Tiny::from_lists(&[vec![(1, 1), (0, 1)], vec![]]);
        let (lo, hi) = interval();
        let o = certificate_obligation(&c, (Some(lo), Some(hi)), Role::Proof);
        match solve(&o, TIMEOUT_MS) {
            Answer::Sat(Some(m)) => assert!(confirmed(replay(&o, &m))),
            other => panic!("{other:?}"),
        }
    }

    /// The certificate replay confirms only a goal-reaching policy that costs at most the
    /// loop's `1/(1 − α)`: on `0: ->0 (1), ->1 (11); 1 (goal)` the goal path costs 11, the
    /// loop 2 at `α = 1/2` (not confirmed), 11 at `α = 10/11` (a tie: confirmed) and 20 at
    /// `α = 19/20` (confirmed).
    #[test]
    fn the_certificate_replay_compares_the_goal_path_with_the_loop() {
        let o = Obligation::new(
            "C3",
            CERTIFIED,
            "0: ->0 (1), ->1 (11); 1 (goal)",
            Role::Proof,
            Logic::QfNra,
        );
        assert!(!confirmed(replay(&o, &model(q(1, 2), &[]))));
        assert!(confirmed(replay(&o, &model(q(10, 11), &[]))));
        assert!(confirmed(replay(&o, &model(q(19, 20), &[]))));
    }
}

//! Claim C4 (docs/spec.md §6): episodic equivalence. The single-shot problem versus the
//! infinite-horizon average-cost problem in which reaching the goal resets to `x1` with bonus
//! `M < 0` (the reset is one stage costing `M`; a path with `S` states is a reset cycle of `S`
//! stages and cost `L + M`).
//!
//! **As printed**: `π*` (the optimal single-shot path, `S*` states, cost `L*`) is average-cost
//! optimal iff `a ≤ M ≤ min{b, S*·Lav(Ĉ) − L*}`, with
//! `A(u) = (1 − S(u)/S*)·(S(u)·L*/(S*·L(u)) − 1)`, `a = max A(u)` over `S(u) < S*`,
//! `b = min A(u)` over `S(u) > S*`, `Ĉ` the goal-avoiding cycle of least mean cost.
//! `A(u)` is dimensionless while `M` is a cost: scaling every cost by 2 moves the true
//! thresholds and not `a`, `b`. Refuted.
//!
//! **C4-corrected** (derived from `(L*+M)/S* ≤ (L+M)/S` and `(L*+M)/S* ≤ Lav(Ĉ)`): with
//! `T(u) = (S*·L(u) − S(u)·L*) / (S(u) − S*)`, `π*` is average-cost optimal iff
//! `max_{S(u)<S*} T(u) ≤ M ≤ min{ min_{S(u)>S*} T(u), S*·Lav(Ĉ) − L* }` (and `M < 0`),
//! over simple goal paths `u` from `x1` and cycles reachable from `x1` avoiding the goal
//! (walks are mediants of these and add nothing).
//!
//! Oracle: every stationary policy of the average-cost problem is enumerated; its average
//! from `x1` is `(c + r·M)/k` (`r = 1` for a reset cycle); the exact set of `M` is the
//! intersection of the half-lines where `π*`'s average is least. `Lav(Ĉ)` by Karp's algorithm,
//! cross-checked against the enumeration of simple cycles and of policies.

use num_bigint::BigInt;
use num_traits::ToPrimitive;

use super::exact::Q;
use super::tiny::{minimality_key, FamilySpec, Tiny};
pub use truecost_kernel::claims::c4::{
    bonus_analysis, bonus_sets, witness, BonusError, BonusSets, End, Instance, Interval,
    ToInstance, MAX_BONUS_STATES,
};

use super::{enumerate, keep_min, min_of, ClaimResult, Counterexample, EngineRun, Scope, Verdict};
use crate::model::Problem;
use crate::value::{to_common_scale, Rational};

/// The most stationary policies the exact bonus analysis enumerates for one problem.
pub const MAX_BONUS_POLICIES: u64 = 1 << 22;

/// The most policy-stage steps it may take: each enumerated policy walks its lasso from `x1`,
/// up to one step per state, and so does the goal-path search, so the work is about
/// policies × states. Measured (release, a loaded 2-core machine): 2^20 policies on a 1,021-state
/// chain of two-way choices take 16 s, 2^22 took two minutes; this bound keeps every accepted
/// problem to about half a minute.
pub const MAX_BONUS_WORK: u64 = 1 << 30;

/// The policy bound of [`bonus_analysis`] for a problem of `states` states: the largest power
/// of two with `limit × states ≤` [`MAX_BONUS_WORK`], at most [`MAX_BONUS_POLICIES`] (so
/// problems of up to 256 states keep the full 2^22).
///
/// ```
/// use truecost::claims::c4::{bonus_policy_limit, MAX_BONUS_POLICIES};
/// assert_eq!(bonus_policy_limit(4), MAX_BONUS_POLICIES);
/// assert_eq!(bonus_policy_limit(256), 1 << 22);
/// assert_eq!(bonus_policy_limit(257), 1 << 21);
/// assert_eq!(bonus_policy_limit(1021), 1 << 20);
/// assert_eq!(bonus_policy_limit(0), MAX_BONUS_POLICIES);
/// ```
pub fn bonus_policy_limit(states: usize) -> u64 {
    let per_state = MAX_BONUS_WORK / (states.max(1) as u64);
    let power = 1u64 << (63 - per_state.max(1).leading_zeros());
    power.min(MAX_BONUS_POLICIES)
}

/// Whether the bonus `m`, in the problem's own units, lies in `interval`, a set of bonuses
/// scaled by `scale` (as [`Instance::from_problem`] scales costs to integers): `m·scale ∈
/// interval`, decided on exact rationals, since `m` may lie beyond [`Q`]'s range.
///
/// ```
/// use truecost::claims::c4::{contains_unscaled, End, Interval};
/// use truecost::claims::exact::Q;
/// use truecost::value::parse_rational;
/// // Scaled set [-6, 0) with scale 3: unscaled [-2, 0).
/// let i = Interval { lo: End::Closed(Q::int(-6)), hi: End::Open(Q::int(0)), empty: false };
/// let three = num_bigint::BigInt::from(3);
/// let m = |t: &str| parse_rational(t).unwrap();
/// assert!(contains_unscaled(&i, &m("-2"), &three));
/// assert!(contains_unscaled(&i, &m("-1/1000"), &three));
/// assert!(!contains_unscaled(&i, &m("0"), &three));
/// assert!(!contains_unscaled(&i, &m("-2.001"), &three));
/// ```
pub fn contains_unscaled(interval: &Interval, m: &Rational, scale: &BigInt) -> bool {
    let scaled = m * Rational::from_integer(scale.clone());
    let end = |q: Q| q.to_rational();
    !interval.empty
        && match interval.lo {
            End::Unbounded => true,
            End::Closed(a) => scaled >= end(a),
            End::Open(a) => scaled > end(a),
        }
        && match interval.hi {
            End::Unbounded => true,
            End::Closed(b) => scaled <= end(b),
            End::Open(b) => scaled < end(b),
        }
}

/// The statement of C4 as printed.
pub const STATEMENT: &str = "C4 (as printed): with bonus M < 0 paid at the reset to x1 (one stage), pi* (the optimal \
single-shot path: S* states, cost L*) is average-cost optimal iff a <= M <= min{b, S*.Lav(C^) - L*}, where \
A(u) = (1 - S(u)/S*)(S(u).L*/(S*.L(u)) - 1), a = max A(u) over goal-reaching u with S(u) < S*, b = min A(u) over \
S(u) > S*, and C^ is the goal-avoiding cycle of least average cost per stage.";

/// The corrected statement.
pub const CORRECTED: &str = "C4-corrected: with T(u) = (S*.L(u) - S(u).L*) / (S(u) - S*) over simple goal paths u from \
x1, pi* is average-cost optimal iff max{T(u) : S(u) < S*} <= M <= min{ min{T(u) : S(u) > S*}, S*.Lav(C^) - L* } and \
M < 0 (C^ over cycles reachable from x1 avoiding the goal; an empty max is -inf, an empty min +inf).";

/// `Instance::from_problem` on the library's exact model.
impl ToInstance for Problem {
    type Scale = BigInt;
    /// A problem with exact rational costs as an instance with integer costs: every cost times
    /// `D`, the least common multiple of the denominators (averages and bonuses scale by `D`;
    /// the caller divides the thresholds back). Returns the instance and `D`.
    ///
    /// ```
    /// use truecost::claims::c4::Instance;
    /// use truecost::model::{Move, Problem};
    /// let half = truecost::value::Rational::new(1.into(), 2.into());
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: half }], vec![]], 0, vec![1]).unwrap();
    /// let (inst, d) = Instance::from_problem(&p).unwrap();
    /// assert_eq!((inst.moves[0].clone(), d), (vec![(1, 1)], 2.into()));
    /// ```
    fn to_instance(&self) -> Result<(Instance, BigInt), String> {
        let problem = self;
        let costs: Vec<Rational> = (0..problem.states())
            .flat_map(|x| problem.moves(x).iter().map(|m| m.cost.clone()))
            .collect();
        let (d, scaled) = to_common_scale(&costs);
        let mut scaled = scaled.into_iter();
        let mut moves = Vec::new();
        for x in 0..problem.states() {
            let mut list = Vec::new();
            for m in problem.moves(x) {
                let c = scaled.next().expect("one scaled cost per move");
                let c = c.to_i64().filter(|c| *c < 1 << 40).ok_or(
                    "costs too large for the exact bonus analysis (scaled costs must stay below 2^40)",
                )?;
                list.push((m.successor, c));
            }
            moves.push(list);
        }
        Ok((
            Instance {
                initial: problem.initial(),
                is_goal: (0..problem.states()).map(|x| problem.is_goal(x)).collect(),
                moves,
            },
            d,
        ))
    }
}

type Key = (usize, usize, u64, u64, u64);

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
struct Finding {
    t: Tiny,
    sets: BonusSets,
    m: Q,
}

#[derive(Default, serde::Serialize, serde::Deserialize)]
struct Acc {
    cases: u64,
    no_path: u64,
    printed_cases: u64,
    printed_undefined: u64,
    printed_failures: u64,
    corrected_failures: u64,
    printed_min: Option<(Key, Finding)>,
    printed_min_positive: Option<(Key, Finding)>,
    corrected_min: Option<(Key, Finding)>,
    karp_checks: u64,
    internal: Option<String>,
}

fn merge(a: Acc, b: Acc) -> Acc {
    Acc {
        cases: a.cases + b.cases,
        no_path: a.no_path + b.no_path,
        printed_cases: a.printed_cases + b.printed_cases,
        printed_undefined: a.printed_undefined + b.printed_undefined,
        printed_failures: a.printed_failures + b.printed_failures,
        corrected_failures: a.corrected_failures + b.corrected_failures,
        printed_min: min_of(a.printed_min, b.printed_min),
        printed_min_positive: min_of(a.printed_min_positive, b.printed_min_positive),
        corrected_min: min_of(a.corrected_min, b.corrected_min),
        karp_checks: a.karp_checks + b.karp_checks,
        internal: a.internal.or(b.internal),
    }
}

fn specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, degree, costs: &[u8]| FamilySpec {
        states,
        initial_fixed: true,
        degree,
        goal_degree: (0, 0),
        costs: costs.to_vec(),
        distinct_successors: false,
    };
    match scope {
        Scope::Smoke => vec![spec(2, (1, 2), &[0, 1, 2]), spec(3, (1, 2), &[0, 1, 2])],
        Scope::Quick => vec![
            spec(2, (1, 2), &[0, 1, 2, 3]),
            spec(3, (1, 2), &[0, 1, 2, 3]),
            spec(4, (1, 2), &[0, 1, 2, 3]),
        ],
        Scope::Full => vec![
            spec(2, (1, 2), &[0, 1, 2, 3]),
            spec(3, (1, 2), &[0, 1, 2, 3]),
            spec(4, (1, 2), &[0, 1, 2, 3]),
            spec(4, (1, 3), &[0, 1]),
            spec(5, (1, 2), &[0, 1]),
        ],
    }
}

fn counterexample(f: &Finding, printed: bool) -> Counterexample {
    let s = &f.sets;
    let which = if printed { "printed" } else { "corrected" };
    let set = if printed {
        s.printed.expect("defined")
    } else {
        s.corrected
    };
    Counterexample::new(
        &f.t,
        format!(
            "C4 counterexample: at M = {} the {which} formula says pi* is {} but the exact average-cost oracle says it is {}",
            f.m,
            if set.contains(f.m) { "optimal" } else { "not optimal" },
            if s.exact.contains(f.m) { "optimal" } else { "not optimal" },
        ),
        vec![
            ("L*".into(), s.optimal_cost.to_string()),
            ("S*".into(), s.optimal_states.to_string()),
            (
                "Lav(C^)".into(),
                s.least_mean_cycle.map_or("none (+inf)".into(), |q| q.to_string()),
            ),
            ("bonus M".into(), f.m.to_string()),
            ("exact set of M (oracle)".into(), s.exact.to_string()),
            (
                "printed formula's set".into(),
                s.printed.map_or("undefined (L(u) = 0)".into(), |i| i.to_string()),
            ),
            ("corrected formula's set".into(), s.corrected.to_string()),
        ],
        if printed { "c4-as-printed" } else { "c4-corrected" },
    )
    .with_replay(format!(
        "truecost verify --claim C4 --file problems/counterexamples/{}.json",
        if printed { "c4-as-printed" } else { "c4-corrected" }
    ))
}

/// Checks C4 as printed and C4-corrected in `scope`. Returns `(C4, C4-corrected)`.
pub fn check(scope: Scope) -> (ClaimResult, ClaimResult) {
    check_with(scope, |_, s| s.corrected)
}

/// [`check`] around the corrected formula's set of `M` for one (problem, `S*`) case (in
/// production: the kernel's [`BonusSets::corrected`]): the enumeration, the tallies, the least
/// counterexamples and the verdicts. The corrected formula agrees with the oracle everywhere,
/// so only a planted set (the unit test below) reaches C4-corrected's failure path.
fn check_with(
    scope: Scope,
    corrected: impl Fn(&Tiny, &BonusSets) -> Interval + Sync + Send,
) -> (ClaimResult, ClaimResult) {
    let started = std::time::Instant::now();
    let mut acc = Acc::default();
    let mut parts = Vec::new();
    let mut structures = 0;
    for spec in specs(scope) {
        let (a, distinct) = enumerate(
            &spec,
            Acc::default,
            |acc, t, i| {
                let inst = Instance::from_tiny(t);
                let sets = match bonus_sets(&inst, 1 << 20) {
                    Ok(Some(s)) => s,
                    Ok(None) => {
                        acc.no_path += 1;
                        return;
                    }
                    Err(e) => {
                        acc.internal.get_or_insert(e);
                        return;
                    }
                };
                acc.cases += 1;
                acc.karp_checks += 1;
                for (j, s) in sets.into_iter().enumerate() {
                    let key = minimality_key(t, j as u64, i);
                    match s.printed {
                        None => acc.printed_undefined += 1,
                        Some(p) => {
                            acc.printed_cases += 1;
                            if let Some(m) = witness(&p, &s.exact) {
                                acc.printed_failures += 1;
                                keep_min(&mut acc.printed_min, key, || Finding {
                                    t: *t,
                                    sets: s.clone(),
                                    m,
                                });
                                let positive = (0..t.states())
                                    .all(|x| t.moves(x).iter().all(|mv| mv.cost > 0));
                                if positive {
                                    keep_min(&mut acc.printed_min_positive, key, || Finding {
                                        t: *t,
                                        sets: s.clone(),
                                        m,
                                    });
                                }
                            }
                        }
                    }
                    let set = corrected(t, &s);
                    if let Some(m) = witness(&set, &s.exact) {
                        acc.corrected_failures += 1;
                        keep_min(&mut acc.corrected_min, key, || Finding {
                            t: *t,
                            sets: BonusSets {
                                corrected: set,
                                ..s.clone()
                            },
                            m,
                        });
                    }
                }
            },
            merge,
        );
        acc = merge(acc, a);
        structures += distinct;
        parts.push(spec.describe());
    }
    if let Some(e) = &acc.internal {
        panic!("C4 oracle cross-check failed: {e}");
    }
    let seconds = started.elapsed().as_secs_f64();
    let scope_line = format!(
        "{} problems up to relabelling with a goal reachable from x1 ({}; x1 = 0, one goal); every optimal single-shot \
path length S*; exact intervals of M < 0 compared",
        acc.cases,
        parts.join(" | ")
    );
    let printed = ClaimResult {
        id: "C4".into(),
        statement: STATEMENT.into(),
        verdict: if acc.printed_min.is_some() {
            Verdict::Refuted
        } else {
            Verdict::Verified
        },
        engine: "exhaustive enumeration".into(),
        scope: scope_line.clone(),
        cases: acc.printed_cases,
        counterexample: acc.printed_min.as_ref().map(|(_, f)| counterexample(f, true)),
        engines: vec![EngineRun {
            engine: "exhaustive enumeration".into(),
            mode: "exhaustive".into(),
            scope: scope_line.clone(),
            cases: acc.printed_cases,
            failures: acc.printed_failures,
            seconds: seconds / 2.0,
        }],
        notes: vec![
            format!(
                "the printed formula disagrees with the oracle on {} of {} (problem, S*) cases where it is defined; it is \
undefined (division by L(u) = 0) in {} more",
                acc.printed_failures, acc.printed_cases, acc.printed_undefined
            ),
            "A(u) is dimensionless while M is a cost: multiplying every stage cost by 2 doubles the true thresholds but \
leaves a and b unchanged"
                .into(),
            format!(
                "{} more problems (of {structures} up to relabelling) have no goal reachable from x1 and are not cases",
                acc.no_path
            ),
        ]
        .into_iter()
        .chain(acc.printed_min_positive.as_ref().map(|(_, f)| {
            format!(
                "smallest counterexample with every cost > 0: {}; S* = {}, L* = {}, M = {}: exact set {}, printed {}",
                f.t.describe(),
                f.sets.optimal_states,
                f.sets.optimal_cost,
                f.m,
                f.sets.exact,
                f.sets.printed.map_or("undefined".into(), |i| i.to_string())
            )
        }))
        .collect(),
    };
    let corrected = ClaimResult {
        id: "C4-corrected".into(),
        statement: CORRECTED.into(),
        verdict: if acc.corrected_min.is_some() {
            Verdict::Refuted
        } else {
            Verdict::Verified
        },
        engine: "exhaustive enumeration".into(),
        scope: scope_line.clone(),
        cases: acc.printed_cases + acc.printed_undefined,
        counterexample: acc.corrected_min.as_ref().map(|(_, f)| counterexample(f, false)),
        engines: vec![EngineRun {
            engine: "exhaustive enumeration".into(),
            mode: "exhaustive".into(),
            scope: scope_line,
            cases: acc.printed_cases + acc.printed_undefined,
            failures: acc.corrected_failures,
            seconds: seconds / 2.0,
        }],
        notes: vec![format!(
            "Lav(C^) by Karp's algorithm cross-checked against simple-cycle enumeration and against the policies' \
goal-avoiding cycles on all {} problems",
            acc.karp_checks
        )],
    };
    (printed, corrected)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// C4-corrected's bookkeeping against a planted corrected set on every problem with an
    /// odd number of moves: a set that differs from the oracle's at `M = −1000` by
    /// construction. The verdict, the cases (one per call: every (problem, `S*`) case), the
    /// failures and the reported problem and sets are recomputed here from the calls; C4 as
    /// printed is untouched by the plant, and the problems without a reachable goal add up
    /// with the cases to the problems enumerated.
    #[test]
    fn a_planted_corrected_set_is_counted_and_its_least_case_reported() {
        let far = Q::int(-1000);
        let seen = Mutex::new(Vec::new());
        let (printed, r) = check_with(Scope::Smoke, |t, s| {
            let fails = t.move_count() % 2 == 1;
            let set = match (fails, s.exact.contains(far)) {
                (false, _) => s.corrected,
                (true, true) => Interval {
                    lo: End::Open(Q::int(-1)),
                    hi: End::Open(Q::ZERO),
                    empty: false,
                },
                (true, false) => Interval::negative(),
            };
            let key = (t.states(), t.move_count(), t.cost_sum());
            seen.lock().unwrap().push((
                fails,
                key,
                t.describe(),
                s.exact.to_string(),
                set.to_string(),
            ));
            set
        });
        let seen = seen.into_inner().unwrap();
        let calls = seen.len() as u64;
        let failures = seen.iter().filter(|s| s.0).count() as u64;
        assert!(failures > 1 && failures < calls, "{failures} of {calls}");
        assert_eq!(r.verdict, Verdict::Refuted);
        assert_eq!(
            (r.cases, r.engines[0].cases, r.engines[0].failures),
            (calls, calls, failures)
        );
        let least = seen.iter().filter(|s| s.0).map(|s| s.1).min().unwrap();
        let cx = r.counterexample.unwrap();
        assert!(
            cx.summary.starts_with("C4 counterexample: at M = "),
            "{}",
            cx.summary
        );
        assert_eq!(cx.file, "problems/counterexamples/c4-corrected.json");
        let detail = |name: &str| {
            cx.details
                .iter()
                .find(|(k, _)| k == name)
                .map(|(_, v)| v.clone())
                .unwrap()
        };
        let (exact, set) = (
            detail("exact set of M (oracle)"),
            detail("corrected formula's set"),
        );
        assert!(
            seen.iter().any(|s| s.0
                && s.1 == least
                && s.2 == cx.problem
                && s.3 == exact
                && s.4 == set),
            "{} {exact} {set}",
            cx.problem
        );
        // Without the plant: C4-corrected verified over the same cases, C4 as printed the same.
        let (printed_real, real) = check(Scope::Smoke);
        assert_eq!(real.verdict, Verdict::Verified);
        assert!(real.counterexample.is_none());
        assert_eq!((real.cases, real.engines[0].failures), (calls, 0));
        assert_eq!(
            (printed.verdict, printed.cases, printed.engines[0].failures),
            (
                printed_real.verdict,
                printed_real.cases,
                printed_real.engines[0].failures
            )
        );
        assert_eq!(printed.notes, printed_real.notes);
        // "N more problems (of P up to relabelling) have no goal reachable …", the cases P − N.
        let note = printed
            .notes
            .iter()
            .find(|n| n.contains("no goal reachable"))
            .unwrap();
        let words: Vec<&str> = note.split(' ').collect();
        let no_path: u64 = words[0].parse().unwrap();
        let problems: u64 = words[4].parse().unwrap();
        let cases: u64 = printed.scope.split(' ').next().unwrap().parse().unwrap();
        assert!(no_path > 0, "{note}");
        assert_eq!(cases + no_path, problems, "{note}");
    }

    /// The accumulators of the parallel enumeration add their counts. Every count is checked
    /// with both sides non-zero: a claim that holds has no failures on either side, so a
    /// product instead of a sum would go unnoticed by the verdicts (`0 · 0 = 0 + 0`) until a
    /// refutation reported a wrong count.
    #[test]
    fn merging_accumulators_adds_every_count() {
        let acc = |k: u64| Acc {
            cases: 3 * k,
            no_path: 5 * k,
            printed_cases: 7 * k,
            printed_undefined: 11 * k,
            printed_failures: 13 * k,
            corrected_failures: 17 * k,
            karp_checks: 19 * k,
            internal: (k == 2).then(|| "second".to_string()),
            ..Acc::default()
        };
        let m = merge(acc(1), acc(2));
        assert_eq!(
            (
                m.cases,
                m.no_path,
                m.printed_cases,
                m.printed_undefined,
                m.printed_failures,
                m.corrected_failures,
                m.karp_checks
            ),
            (9, 15, 21, 33, 39, 51, 57)
        );
        assert_eq!(m.internal.as_deref(), Some("second"));
    }
}

//! Claim C1 (docs/spec.md §6): finite-time convergence of derandomized Q-learning (`ρ = 1`).
//!
//! **As printed**: costs `l ≥ 0`, *any* initial values; if every state–action pair is
//! updated infinitely often by `Q̂(x,u) ← l(x,u) + min_{u'} Q̂(f(x,u),u')`, then `Q̂ = Q*`
//! after finitely many steps. Refuted (three independent reasons, each a minimal
//! counterexample of the enumeration): the goal's termination pair is a zero-cost self-loop,
//! so any constant is a fixed point there; a state that cannot reach the goal has
//! `Q* = +∞`, never attained; a zero-cost cycle started below `Q*` is a fixed point below `Q*`.
//!
//! **C1-corrected** (proved below, then verified): assume (H0) `Q̂(xg, uT)` is held at 0,
//! (H1) every state can reach the goal, (H2) `Q̂₀ ≥ Q*` on every pair, or every move has cost
//! `≥ c > 0`. Cut any fair update sequence into *rounds* (consecutive segments in which every
//! pair is updated at least once). Then `Q̂ = Q*` from the end of round `R` on, with
//! `R₁ = 1 + max_{moves (x,u)} h(f(x,u))` (`h(y)` = fewest moves of an optimal path from `y`)
//! when `Q̂₀ ≥ Q*`, and `R = max(R₁, ⌈(max Q* − min(0, min Q̂₀)) / c⌉)` otherwise.
//!
//! Proof. The update is monotone and `Q*` is its fixed point (under H0, H1), so a run from
//! `Q̂₀` stays between the runs from `min(Q̂₀, Q*)` and `max(Q̂₀, Q*)` under the same order.
//! From above: values stay `≥ Q*`; by induction on `r`, after round `r` every pair with
//! `h(f(x,u)) ≤ r − 1` is exact (its successor's optimal move is exact from round `r − 1` on,
//! and every other value is `≥ Q*`), so all pairs are exact after `R₁` rounds. From below with
//! costs `≥ c`: after round `r` every value is `≥ min(Q*, m + r·c)` (`m` = the least initial
//! value, at most 0) and `≤ Q*`, so all are exact once `m + r·c ≥ max Q*`. ∎

use super::exact::Q;
use super::qlearning::{all_orders, run, AllOrders, Order, QProblem, Run, Terminal, Values};
use super::replay::ReplayOrder;
use super::tiny::{minimality_key, FamilySpec, Tiny};
use super::{enumerate, keep_min, min_of, ClaimResult, Counterexample, EngineRun, Scope, Verdict};

/// The statement of C1 as printed.
pub const STATEMENT: &str = "C1 (as printed): with stage costs l >= 0 and ANY initial values Q0, if every state-action \
pair (the goal's termination action uT included: f(xg,uT) = xg, l = 0) is updated infinitely often by the rho = 1 rule \
Q(x,u) <- l(x,u) + min_u' Q(f(x,u),u'), then Q = Q* after finitely many steps.";

/// C1-corrected's round bound `R`, in one place: the statement ([`corrected_statement`]), the
/// SMT encoding's round-count obligations (`smt::c1`: Part A's `R₁`, Part B's B4 with `R` the
/// integer ceiling) and the bound's exact value ([`RoundBound::rounds`]) are all made from it,
/// so that changing the statement changes what is proved and checked.
///
/// `R₁ = r1_offset + max h(f(x,u))` over the moves `(x,u)`; `R = R₁` when `Q₀ ≥ Q*`, else
/// `R = max(R₁, ⌈(max Q* − m)/c⌉ + ceil_offset)` with `m = min(0, min Q₀)`. The statement's
/// bound is [`ROUND_BOUND`] (offsets 1 and 0); other offsets are planted wrong bounds that the
/// engines must reject.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RoundBound {
    /// The constant added to `max h(f(x,u))` in `R₁` (the statement: 1).
    pub r1_offset: i64,
    /// The constant added to `⌈(max Q* − m)/c⌉` (the statement: 0).
    pub ceil_offset: i64,
}

/// The round bound of C1-corrected as stated.
pub const ROUND_BOUND: RoundBound = RoundBound {
    r1_offset: 1,
    ceil_offset: 0,
};

/// `term` with `offset` added, as text (`1 + t`, `t`, `t - 1`).
fn plus(offset: i64, term: &str, before: bool) -> String {
    match offset {
        0 => term.to_string(),
        k if k > 0 && before => format!("{k} + {term}"),
        k if k > 0 => format!("{term} + {k}"),
        k => format!("{term} - {}", k.unsigned_abs()),
    }
}

impl RoundBound {
    /// `R₁` as printed in the statement.
    ///
    /// ```
    /// use truecost::claims::c1::ROUND_BOUND;
    /// assert_eq!(ROUND_BOUND.r1_text(), "1 + max over moves (x,u) of h(f(x,u))");
    /// ```
    pub fn r1_text(&self) -> String {
        plus(self.r1_offset, "max over moves (x,u) of h(f(x,u))", true)
    }

    /// The ceiling term of `R` as printed in the statement.
    ///
    /// ```
    /// use truecost::claims::c1::{RoundBound, ROUND_BOUND};
    /// assert_eq!(ROUND_BOUND.ceil_text(), "ceil((max Q* - min(0, min Q0)) / c)");
    /// let planted = RoundBound { ceil_offset: -1, ..ROUND_BOUND };
    /// assert_eq!(planted.ceil_text(), "ceil((max Q* - min(0, min Q0)) / c) - 1");
    /// ```
    pub fn ceil_text(&self) -> String {
        plus(
            self.ceil_offset,
            "ceil((max Q* - min(0, min Q0)) / c)",
            false,
        )
    }

    /// The statement of C1-corrected with this bound (with [`ROUND_BOUND`]: the registry's).
    pub fn statement(&self) -> String {
        format!(
            "C1-corrected: assume (H0) the goal's termination value is held at Q(xg,uT) = 0, \
(H1) every state can reach the goal (Q* finite), (H2) Q0 >= Q* on every pair, or every move costs l(x,u) >= c > 0 \
(Q0 then arbitrary). Cut any fair update sequence into rounds (consecutive segments updating every pair at least \
once). Then Q = Q* from the end of round R on, where R1 = {} (h = fewest moves \
of an optimal path to the goal), R = R1 if Q0 >= Q*, else R = max(R1, {}).",
            self.r1_text(),
            self.ceil_text()
        )
    }

    /// The bound's value, exactly: `max_h` is `max h(f(x,u))` over the moves (`None`: no
    /// move), `above` whether `Q₀ ≥ Q*`, and `(max Q*, m, c)` the rest, `c > 0` (only read
    /// when `!above`). Never negative.
    ///
    /// ```
    /// use truecost::claims::c1::ROUND_BOUND;
    /// use truecost::value::Rational;
    /// let r = |n: i64| Rational::from_integer(n.into());
    /// // R1 = 1 + 1; ceil((5 - (-2)) / 2) = 4.
    /// assert_eq!(ROUND_BOUND.rounds(Some(1), false, &r(5), &r(-2), &r(2)), 4);
    /// assert_eq!(ROUND_BOUND.rounds(Some(1), true, &r(5), &r(-2), &r(2)), 2);
    /// ```
    pub fn rounds(
        &self,
        max_h: Option<u64>,
        above: bool,
        max_qstar: &crate::value::Rational,
        m: &crate::value::Rational,
        c: &crate::value::Rational,
    ) -> u64 {
        use num_traits::ToPrimitive;
        let r1 = max_h.map_or(0, |h| (h as i64).saturating_add(self.r1_offset).max(0));
        if above {
            return r1 as u64;
        }
        let ceil = ((max_qstar - m) / c)
            .ceil()
            .to_integer()
            .to_i64()
            .unwrap_or(i64::MAX)
            .saturating_add(self.ceil_offset);
        r1.max(ceil).max(0) as u64
    }
}

/// The statement of C1-corrected, made from [`ROUND_BOUND`].
///
/// ```
/// let s = truecost::claims::c1::corrected_statement();
/// assert!(s.ends_with("R = max(R1, ceil((max Q* - min(0, min Q0)) / c))."));
/// ```
pub fn corrected_statement() -> String {
    ROUND_BOUND.statement()
}

type Key = (usize, usize, u64, u64, u64, u64);

#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
struct Finding {
    t: Tiny,
    q0: Values,
    terminal_q0: i64,
    what: String,
    /// The order under which the failure shows (`None`: a pair with `Q* = +∞`).
    order: Option<Order>,
    /// Rounds after which the failure is visible under that order.
    rounds: u64,
}

#[derive(Default, serde::Serialize, serde::Deserialize)]
struct Acc {
    printed_cases: u64,
    printed_failures: u64,
    printed_undecided: u64,
    printed_min: Option<(Key, Finding)>,
    printed_cycle_min: Option<(Key, Finding)>,
    corrected_cases: u64,
    corrected_failures: u64,
    corrected_min: Option<(Key, Finding)>,
    max_rounds: u64,
    bound_attained: u64,
    drop_h1: Option<(Key, Finding)>,
    drop_h2: Option<(Key, Finding)>,
    exhaustive_cases: u64,
    exhaustive_failures: u64,
    exhaustive_too_large: u64,
    exhaustive_max_rounds: u64,
    exhaustive_attained: u64,
    exhaustive_min: Option<(Key, Finding)>,
}

fn merge(a: Acc, b: Acc) -> Acc {
    Acc {
        printed_cases: a.printed_cases + b.printed_cases,
        printed_failures: a.printed_failures + b.printed_failures,
        printed_undecided: a.printed_undecided + b.printed_undecided,
        printed_min: min_of(a.printed_min, b.printed_min),
        printed_cycle_min: min_of(a.printed_cycle_min, b.printed_cycle_min),
        corrected_cases: a.corrected_cases + b.corrected_cases,
        corrected_failures: a.corrected_failures + b.corrected_failures,
        corrected_min: min_of(a.corrected_min, b.corrected_min),
        max_rounds: a.max_rounds.max(b.max_rounds),
        bound_attained: a.bound_attained + b.bound_attained,
        drop_h1: min_of(a.drop_h1, b.drop_h1),
        drop_h2: min_of(a.drop_h2, b.drop_h2),
        exhaustive_cases: a.exhaustive_cases + b.exhaustive_cases,
        exhaustive_failures: a.exhaustive_failures + b.exhaustive_failures,
        exhaustive_too_large: a.exhaustive_too_large + b.exhaustive_too_large,
        exhaustive_max_rounds: a.exhaustive_max_rounds.max(b.exhaustive_max_rounds),
        exhaustive_attained: a.exhaustive_attained + b.exhaustive_attained,
        exhaustive_min: min_of(a.exhaustive_min, b.exhaustive_min),
    }
}

/// The initial values checked for C1 as printed (and the every-order exploration).
fn initial_values(scope: Scope) -> &'static [i64] {
    match scope {
        Scope::Smoke | Scope::Quick => &[0, 1, 3],
        Scope::Full => &[-1, 0, 1, 3],
    }
}

/// The initial values checked for C1-corrected (simulated orders).
fn corrected_values(scope: Scope) -> &'static [i64] {
    match scope {
        Scope::Smoke => &[0, 1, 3],
        // Quick includes a negative value, so the min(0, min Q0) term of R is checked in CI.
        Scope::Quick => &[-2, 0, 1, 2, 4],
        Scope::Full => &[-2, -1, 0, 1, 2, 4],
    }
}

fn specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, degree, goal_degree, costs: &[u8]| FamilySpec {
        states,
        initial_fixed: false,
        degree,
        goal_degree,
        costs: costs.to_vec(),
        distinct_successors: false,
    };
    match scope {
        Scope::Smoke => vec![
            spec(1, (1, 1), (0, 1), &[0, 1, 2]),
            spec(2, (1, 2), (0, 1), &[0, 1, 2]),
            spec(3, (1, 1), (0, 0), &[0, 1, 2]),
        ],
        Scope::Quick => (1..=3)
            .map(|n| spec(n, (1, 2), (0, 1), &[0, 1, 2]))
            .collect(),
        Scope::Full => {
            let mut v: Vec<FamilySpec> = (1..=3)
                .map(|n| spec(n, (1, 2), (0, 1), &[0, 1, 2]))
                .collect();
            v.push(spec(4, (1, 1), (0, 1), &[0, 1, 2]));
            v
        }
    }
}

fn exhaustive_specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states, degree| FamilySpec {
        states,
        initial_fixed: false,
        degree,
        goal_degree: (0, 0),
        costs: vec![0, 1, 2],
        distinct_successors: false,
    };
    match scope {
        Scope::Smoke => vec![spec(2, (1, 2)), spec(3, (1, 1))],
        Scope::Quick | Scope::Full => vec![spec(2, (1, 2)), spec(3, (1, 2))],
    }
}

/// Every initial-value vector on the move pairs over `domain`; identical moves of one state
/// get non-decreasing values (they are interchangeable).
fn initial_vectors(q: &QProblem, domain: &[i64]) -> Vec<Values> {
    let moves: Vec<usize> = (0..q.len()).filter(|&p| !q.pairs[p].terminal).collect();
    let mut out = Vec::new();
    let mut idx = vec![0usize; moves.len()];
    loop {
        let mut v = [0i64; super::qlearning::MAX_PAIRS];
        let mut ok = true;
        for (k, &p) in moves.iter().enumerate() {
            v[p] = domain[idx[k]];
            if k > 0 && moves[k - 1] + 1 == p && q.pairs[p - 1] == q.pairs[p] && idx[k] < idx[k - 1]
            {
                ok = false;
            }
        }
        if ok {
            out.push(v);
        }
        let mut k = 0;
        loop {
            if k == moves.len() {
                return out;
            }
            idx[k] += 1;
            if idx[k] < domain.len() {
                break;
            }
            idx[k] = 0;
            k += 1;
        }
    }
}

const ORDERS: usize = 4;
const MAX_ROUNDS: u64 = 64;

fn orders(seed: u64) -> [Order; ORDERS] {
    [
        Order::Cyclic,
        Order::Reverse,
        Order::FarFirst,
        Order::Random(seed),
    ]
}

fn order_name(o: Order) -> String {
    match o {
        Order::Cyclic => "cyclic order".into(),
        Order::Reverse => "reverse cyclic order".into(),
        Order::FarFirst => "far-from-goal-first order".into(),
        Order::Random(s) => format!("random order (seed {s})"),
    }
}

fn describe_run(r: Run) -> String {
    match r {
        Run::Converged(k) => format!("Q = Q* after {k} rounds"),
        Run::Cycles(k, p) => format!(
            "round-end values repeat (from round {k}, period {p}) without reaching Q*: never converges"
        ),
        Run::NotWithin(k) => format!("Q != Q* after {k} rounds"),
    }
}

fn values_text(q: &QProblem, v: &Values) -> String {
    (0..q.len())
        .map(|p| {
            let pair = q.pairs[p];
            if pair.terminal {
                format!("Q({},uT)={}", pair.state, v[p])
            } else {
                format!("Q({}->{})={}", pair.state, pair.to, v[p])
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn optimum_text(q: &QProblem) -> String {
    let mut v = [0i64; super::qlearning::MAX_PAIRS];
    let mut inf = Vec::new();
    for p in 0..q.len() {
        match q.optimum[p] {
            Some(x) => v[p] = x,
            None => inf.push(p),
        }
    }
    let mut s = values_text(q, &v);
    for p in inf {
        let pair = q.pairs[p];
        s = s.replace(
            &format!("Q({}->{})=0", pair.state, pair.to),
            &format!("Q({}->{})=inf", pair.state, pair.to),
        );
    }
    s
}

/// C1-corrected's round bound `R` of a problem prepared with the termination pair held, from
/// `Q₀`: [`QProblem::round_bound`] in every check. A unit test plants a smaller one to take the
/// failure path, which the theorem (C1-corrected holds) leaves untaken in every scope.
type BoundOracle = fn(&QProblem, &Values) -> Option<u64>;

fn check_structure(
    acc: &mut Acc,
    t: &Tiny,
    index: u64,
    domain: &[i64],
    corrected_domain: &[i64],
    round_bound: BoundOracle,
) {
    let printed = QProblem::new(t, Terminal::Updated);
    let held = QProblem::new(t, Terminal::HeldAtZero);
    let terminal_pair = (0..printed.len())
        .find(|&p| printed.pairs[p].terminal)
        .expect("goal");
    let vectors = initial_vectors(&printed, domain);
    let positive = t
        .moves
        .iter()
        .take(t.states())
        .enumerate()
        .all(|(x, ms)| ms[..t.deg[x] as usize].iter().all(|m| m.cost > 0));
    for (vi, base) in vectors.iter().enumerate() {
        let q0sum: i64 = base.iter().map(|x| x.abs()).sum();
        for terminal_q0 in [0i64, 1] {
            let mut q0 = *base;
            q0[terminal_pair] = terminal_q0;
            let key: Key = {
                let (a, b, c, _, _) = minimality_key(t, 0, 0);
                (
                    a,
                    b,
                    c,
                    (q0sum + terminal_q0) as u64,
                    index,
                    // Ties within one problem go to the first found, in (vector, terminal
                    // value) order: `keep_min` keeps the first of equal keys, and no other call
                    // sees this `index`.
                    0,
                )
            };
            let seed = index.wrapping_mul(1_000_003).wrapping_add(vi as u64);
            // As printed.
            acc.printed_cases += 1;
            let verdict = if !printed.all_finite() {
                Some((
                    "some pair has Q* = inf (its state cannot reach the goal) while Q stays finite forever".to_string(),
                    None,
                    1,
                ))
            } else {
                let mut bad = None;
                for o in orders(seed) {
                    let r = run(&printed, &q0, o, MAX_ROUNDS);
                    match r {
                        Run::Converged(_) => {}
                        Run::Cycles(from, period) => {
                            bad = Some((
                                format!("under the {}: {}", order_name(o), describe_run(r)),
                                Some(o),
                                from + period,
                            ));
                            break;
                        }
                        Run::NotWithin(_) => {
                            acc.printed_undecided += 1;
                        }
                    }
                }
                bad
            };
            if let Some((what, order, rounds)) = verdict {
                acc.printed_failures += 1;
                let finding = || Finding {
                    t: *t,
                    q0,
                    terminal_q0,
                    what: what.clone(),
                    order,
                    rounds,
                };
                // A failure with the termination pair at 0 and Q* finite is a zero-cost cycle
                // started below Q* (the headline counterexample).
                if terminal_q0 == 0 && printed.all_finite() {
                    keep_min(&mut acc.printed_cycle_min, key, finding);
                }
                keep_min(&mut acc.printed_min, key, finding);
            }
        }
    }
    for (vi, q0) in initial_vectors(&held, corrected_domain).iter().enumerate() {
        let q0 = *q0;
        let seed = index.wrapping_mul(1_000_003).wrapping_add(vi as u64);
        let terminal_q0 = 0;
        let key: Key = {
            let (a, b, c, _, _) = minimality_key(t, 0, 0);
            (
                a,
                b,
                c,
                q0.iter().map(|x| x.unsigned_abs()).sum(),
                index,
                vi as u64,
            )
        };
        {
            // Corrected: terminal held at 0.
            let h1 = held.all_finite();
            let above = (0..held.len())
                .filter(|&p| !held.pairs[p].terminal)
                .all(|p| held.optimum[p].is_some_and(|q| q0[p] >= q));
            let h2 = above || positive;
            if h1 && h2 {
                acc.corrected_cases += 1;
                let bound = round_bound(&held, &q0).expect("hypotheses hold");
                for o in orders(seed) {
                    let r = run(&held, &q0, o, MAX_ROUNDS);
                    match r {
                        Run::Converged(k) if k <= bound => {
                            acc.max_rounds = acc.max_rounds.max(k);
                            if k == bound && o == Order::FarFirst {
                                acc.bound_attained += 1;
                            }
                        }
                        _ => {
                            acc.corrected_failures += 1;
                            keep_min(&mut acc.corrected_min, key, || Finding {
                                t: *t,
                                q0,
                                terminal_q0,
                                what: format!(
                                    "under the {}: {} (bound R = {bound})",
                                    order_name(o),
                                    describe_run(r)
                                ),
                                order: Some(o),
                                rounds: MAX_ROUNDS.min(bound + 1),
                            });
                        }
                    }
                }
            } else if h1 && !h2 {
                let r = run(&held, &q0, Order::Cyclic, MAX_ROUNDS);
                if let Run::Cycles(from, period) = r {
                    keep_min(&mut acc.drop_h2, key, || Finding {
                        t: *t,
                        q0,
                        terminal_q0,
                        what: format!("under the cyclic order: {}", describe_run(r)),
                        order: Some(Order::Cyclic),
                        rounds: from + period,
                    });
                }
            } else if !h1 && positive {
                keep_min(&mut acc.drop_h1, key, || Finding {
                    t: *t,
                    q0,
                    terminal_q0,
                    what: "a state cannot reach the goal: Q* = inf there, Q stays finite".into(),
                    order: None,
                    rounds: 1,
                });
            }
        }
    }
}

/// The most states the every-order exploration of one case may visit (past it the case is
/// counted as too large, and C1-corrected is inconclusive).
const EXPLORATION_STATES: usize = 200_000;

fn check_all_orders(
    acc: &mut Acc,
    t: &Tiny,
    index: u64,
    domain: &[i64],
    round_bound: BoundOracle,
    states: usize,
) {
    let held = QProblem::new(t, Terminal::HeldAtZero);
    if !held.all_finite() {
        return;
    }
    let positive = (0..held.len())
        .filter(|&p| !held.pairs[p].terminal)
        .all(|p| held.pairs[p].cost > 0);
    for (vi, q0) in initial_vectors(&held, domain).iter().enumerate() {
        let above = (0..held.len())
            .filter(|&p| !held.pairs[p].terminal)
            .all(|p| held.optimum[p].is_some_and(|q| q0[p] >= q));
        if !(above || positive) {
            continue;
        }
        acc.exhaustive_cases += 1;
        let bound = round_bound(&held, q0).expect("hypotheses hold");
        let key: Key = {
            let (a, b, c, _, _) = minimality_key(t, 0, 0);
            (
                a,
                b,
                c,
                q0.iter().map(|x| x.unsigned_abs()).sum(),
                index,
                vi as u64,
            )
        };
        match all_orders(&held, q0, states) {
            AllOrders::Converges(k) if k <= bound => {
                acc.exhaustive_max_rounds = acc.exhaustive_max_rounds.max(k);
                if k == bound {
                    acc.exhaustive_attained += 1;
                }
            }
            AllOrders::TooLarge => acc.exhaustive_too_large += 1,
            other => {
                acc.exhaustive_failures += 1;
                keep_min(&mut acc.exhaustive_min, key, || Finding {
                    t: *t,
                    q0: *q0,
                    terminal_q0: 0,
                    what: format!("every-order exploration: {other:?} (bound R = {bound})"),
                    order: Some(Order::FarFirst),
                    rounds: MAX_ROUNDS.min(bound + 1),
                });
            }
        }
    }
}

fn counterexample(f: &Finding, terminal: Terminal, file: &str) -> Counterexample {
    let q = QProblem::new(&f.t, terminal);
    let mut q0 = f.q0;
    if let Some(p) = (0..q.len()).find(|&p| q.pairs[p].terminal) {
        q0[p] = if terminal == Terminal::Updated {
            f.terminal_q0
        } else {
            0
        };
    }
    let summary = format!(
        "C1 counterexample with initial values {}: {}",
        values_text(&q, &q0),
        f.what
    );
    let replay = replay_command(f, &q, &q0, terminal, file);
    Counterexample::new(
        &f.t,
        summary,
        vec![
            ("initial values Q0".into(), values_text(&q, &q0)),
            ("optimal Q*".into(), optimum_text(&q)),
            (
                "termination pair".into(),
                match terminal {
                    Terminal::Updated => "updated by the rho = 1 rule (as printed)".into(),
                    Terminal::HeldAtZero => "held at 0 (H0)".into(),
                },
            ),
            ("what happens".into(), f.what.clone()),
        ],
        file,
    )
    .with_replay(replay)
}

/// The `truecost learn` command that replays a finding on its problem file:
/// the same initial values (one per pair, in the file's pair order), order and treatment of the
/// termination pair, for enough rounds to show the failure.
fn replay_command(
    f: &Finding,
    q: &QProblem,
    q0: &Values,
    terminal: Terminal,
    file: &str,
) -> String {
    let values: Vec<String> = (0..q.len()).map(|p| q0[p].to_string()).collect();
    let order = match ReplayOrder::from(f.order.unwrap_or(Order::Cyclic)) {
        ReplayOrder::Random(seed) => format!("random --seed {seed}"),
        other => other.name().to_string(),
    };
    format!(
        "truecost learn --file problems/counterexamples/{file}.json --q0 {} --order {order} --terminal {} --rounds {}",
        values.join(","),
        match terminal {
            Terminal::Updated => "updated",
            Terminal::HeldAtZero => "held",
        },
        f.rounds.max(4)
    )
}

/// The note for C1's smallest failure when it is not the headline counterexample: the
/// headline is the smallest failure with the termination pair at 0 and every
/// `Q*` finite; a smaller one (the termination pair at 1, or a pair with `Q* = ∞`) is named
/// too. `None` when the two are the same finding.
fn termination_pair_note(headline: &Finding, smallest: &Finding) -> Option<String> {
    if headline.t == smallest.t
        && headline.q0 == smallest.q0
        && headline.terminal_q0 == smallest.terminal_q0
    {
        return None;
    }
    let q = QProblem::new(&smallest.t, Terminal::Updated);
    let mut q0 = smallest.q0;
    if let Some(p) = (0..q.len()).find(|&p| q.pairs[p].terminal) {
        q0[p] = smallest.terminal_q0;
    }
    Some(format!(
        "also refuted at the goal's termination pair (a zero-cost self-loop updated by the same rule): {} ({}; initial values {})",
        smallest.what,
        smallest.t.describe(),
        values_text(&q, &q0)
    ))
}

/// Checks C1 as printed and C1-corrected in `scope`. Returns `(C1, C1-corrected)`.
pub fn check(scope: Scope) -> (ClaimResult, ClaimResult) {
    let domain = initial_values(scope);
    let corrected = corrected_values(scope);
    let started = std::time::Instant::now();
    let mut acc = Acc::default();
    let mut structures = 0;
    let mut scope_text = Vec::new();
    for spec in specs(scope) {
        let (a, distinct) = enumerate(
            &spec,
            Acc::default,
            |acc, t, i| check_structure(acc, t, i, domain, corrected, QProblem::round_bound),
            merge,
        );
        acc = merge(acc, a);
        structures += distinct;
        scope_text.push(spec.describe());
    }
    let seconds1 = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let mut ex_scope = Vec::new();
    for spec in exhaustive_specs(scope) {
        let (a, _) = enumerate(
            &spec,
            Acc::default,
            |acc, t, i| {
                check_all_orders(acc, t, i, domain, QProblem::round_bound, EXPLORATION_STATES)
            },
            merge,
        );
        acc = merge(acc, a);
        ex_scope.push(spec.describe());
    }
    let seconds2 = started.elapsed().as_secs_f64();
    results(&Pass {
        acc,
        structures,
        scope_text,
        ex_scope,
        domain,
        corrected,
        seconds: (seconds1, seconds2),
    })
}

/// One enumeration pass of C1 and C1-corrected: what it found, its scope and its times.
struct Pass {
    acc: Acc,
    structures: u64,
    scope_text: Vec<String>,
    ex_scope: Vec<String>,
    domain: &'static [i64],
    corrected: &'static [i64],
    seconds: (f64, f64),
}

/// The two claims' results (verdicts, counts, counterexamples, notes) from a pass.
fn results(pass: &Pass) -> (ClaimResult, ClaimResult) {
    let Pass {
        acc,
        structures,
        scope_text,
        ex_scope,
        domain,
        corrected,
        seconds: (seconds1, seconds2),
    } = pass;
    let dom: Vec<String> = domain.iter().map(|d| d.to_string()).collect();
    let scope_line = format!(
        "{structures} problems up to relabelling ({}; one goal); initial values in {{{}}} on every move pair, \
termination pair 0 or 1; fair orders: cyclic, reverse, far-from-goal-first (adversarial), seeded random",
        scope_text.join(" | "),
        dom.join(",")
    );
    let printed = ClaimResult {
        id: "C1".into(),
        statement: STATEMENT.into(),
        verdict: if acc.printed_min.is_some() {
            Verdict::Refuted
        } else if acc.printed_undecided > 0 {
            Verdict::Inconclusive
        } else {
            Verdict::Verified
        },
        engine: "exhaustive enumeration".into(),
        scope: scope_line.clone(),
        cases: acc.printed_cases,
        counterexample: acc
            .printed_cycle_min
            .as_ref()
            .or(acc.printed_min.as_ref())
            .map(|(_, f)| counterexample(f, Terminal::Updated, "c1-as-printed")),
        engines: vec![EngineRun {
            engine: "exhaustive enumeration".into(),
            mode: "exhaustive".into(),
            scope: scope_line.clone(),
            cases: acc.printed_cases,
            failures: acc.printed_failures,
            seconds: seconds1 / 2.0,
        }],
        notes: vec![
            format!(
                "{} of {} instances fail (definitive certificates only: a pair with Q* = inf, or repeating round-end \
values under a periodic order)",
                acc.printed_failures, acc.printed_cases
            ),
            "C1 and C1-corrected share one enumeration pass; its time is split evenly between them in cases per second"
                .into(),
        ],
    };
    let mut printed = printed;
    if let (Some((_, headline)), Some((_, smallest))) = (&acc.printed_cycle_min, &acc.printed_min) {
        printed
            .notes
            .extend(termination_pair_note(headline, smallest));
    }
    let mut notes = vec![
        format!(
            "worst observed number of rounds: {} (simulated orders), {} (every fair order); the bound R is attained \
exactly by the far-from-goal-first order in {} instances and by the worst fair order in {}",
            acc.max_rounds, acc.exhaustive_max_rounds, acc.bound_attained, acc.exhaustive_attained
        ),
        format!(
            "every-order exploration (all fair update sequences, round by round): {} instances, {} failures, \
{} too large to explore; scope: {}",
            acc.exhaustive_cases,
            acc.exhaustive_failures,
            acc.exhaustive_too_large,
            ex_scope.join(" | ")
        ),
    ];
    if let Some((_, f)) = &acc.printed_min {
        notes.push(format!(
            "H0 is necessary: {} ({}; initial values {})",
            f.what,
            f.t.describe(),
            values_text(&QProblem::new(&f.t, Terminal::Updated), &{
                let mut v = f.q0;
                v[QProblem::new(&f.t, Terminal::Updated)
                    .pairs
                    .iter()
                    .position(|p| p.terminal)
                    .expect("goal")] = f.terminal_q0;
                v
            })
        ));
    }
    for (name, slot) in [("H1", &acc.drop_h1), ("H2", &acc.drop_h2)] {
        if let Some((_, f)) = slot {
            let q = QProblem::new(&f.t, Terminal::HeldAtZero);
            notes.push(format!(
                "{name} is necessary: {} ({}; initial values {}; Q* {})",
                f.what,
                f.t.describe(),
                values_text(&q, &f.q0),
                optimum_text(&q)
            ));
        }
    }
    let failures = acc.corrected_failures + acc.exhaustive_failures;
    let corrected_min = min_of(acc.corrected_min.clone(), acc.exhaustive_min.clone());
    let corrected = ClaimResult {
        id: "C1-corrected".into(),
        statement: corrected_statement(),
        verdict: if failures > 0 {
            Verdict::Refuted
        } else if acc.exhaustive_too_large > 0 {
            Verdict::Inconclusive
        } else {
            Verdict::Verified
        },
        engine: "exhaustive enumeration".into(),
        scope: format!(
            "{structures} problems up to relabelling ({}; one goal); initial values in {{{}}} on every move pair, \
termination pair held at 0; instances satisfying H0-H2 only; fair orders: cyclic, reverse, far-from-goal-first \
(adversarial), seeded random",
            scope_text.join(" | "),
            corrected.iter().map(|d| d.to_string()).collect::<Vec<_>>().join(",")
        ),
        cases: acc.corrected_cases,
        counterexample: corrected_min
            .as_ref()
            .map(|(_, f)| counterexample(f, Terminal::HeldAtZero, "c1-corrected")),
        engines: vec![
            EngineRun {
                engine: "exhaustive enumeration".into(),
                mode: "exhaustive".into(),
                scope: "instances satisfying H0-H2, four fair orders each".into(),
                cases: acc.corrected_cases,
                failures: acc.corrected_failures,
                seconds: seconds1 / 2.0,
            },
            EngineRun {
                engine: "exhaustive enumeration (every fair order)".into(),
                mode: "exhaustive".into(),
                scope: ex_scope.join(" | "),
                cases: acc.exhaustive_cases,
                failures: acc.exhaustive_failures,
                seconds: *seconds2,
            },
        ],
        notes,
    };
    let _ = Q::ZERO;
    (printed, corrected)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::qlearning::{QProblem, Terminal};
    use crate::claims::tiny::Tiny;

    /// `initial_vectors` against a brute force: every vector over the domain on the move pairs,
    /// less those where two identical moves of one state (interchangeable) have decreasing
    /// values. Two identical moves `0 → 1` keep 6 of 9 vectors, `v(0) ≤ v(1)`; two moves of
    /// different costs keep all 9; the goal's termination pair (index 2) stays 0.
    #[test]
    fn initial_vectors_keep_one_of_each_pair_of_interchangeable_moves() {
        let domain = [0, 1, 3];
        for (second_cost, interchangeable) in [(1, true), (2, false)] {
            let t = Tiny::from_lists(&[vec![(1, 1), (1, second_cost)], vec![]]);
            let q = QProblem::new(&t, Terminal::Updated);
            let mut brute = Vec::new();
            for a in domain {
                for b in domain {
                    if !interchangeable || a <= b {
                        brute.push((a, b));
                    }
                }
            }
            let got: Vec<(i64, i64)> = initial_vectors(&q, &domain)
                .iter()
                .inspect(|v| assert!(v[2..].iter().all(|&x| x == 0), "{v:?}"))
                .map(|v| (v[0], v[1]))
                .collect();
            let mut sorted = got.clone();
            sorted.sort();
            assert_eq!(sorted, brute, "moves of costs 1 and {second_cost}");
            assert_eq!(got.len(), if interchangeable { 6 } else { 9 });
        }
    }

    /// A cycling failure of C1 as printed states the rounds its replay needs: the first round
    /// of the repetition plus its period, the least number after which `truecost learn`
    /// (`claims::replay`, an implementation apart from the claims engine's) reports that the
    /// values never converge. On the chain 0 → … → 5 (goal) from `Q₀ = 0` with the termination
    /// pair at 1 (held there by the update, so `Q ≠ Q*` forever), the values settle a step a
    /// round: the repetition starts late enough that `from + period` differs from `from · period`
    /// and from the replay command's floor of 4.
    #[test]
    fn a_cycling_failure_states_the_rounds_its_replay_needs() {
        use crate::claims::replay::{replay, InitialValues, ReplayVerdict};
        use crate::value::Rational;
        let t = Tiny::from_lists(&[
            vec![(1, 1)],
            vec![(2, 1)],
            vec![(3, 1)],
            vec![(4, 1)],
            vec![(5, 1)],
            vec![],
        ]);
        let mut acc = Acc::default();
        check_structure(&mut acc, &t, 0, &[0], &[0], QProblem::round_bound);
        let (_, f) = acc
            .printed_min
            .expect("the termination pair at 1 never converges");
        assert_eq!(f.terminal_q0, 1);
        let order = ReplayOrder::from(f.order.expect("a cycling failure has an order"));
        let q = QProblem::new(&t, Terminal::Updated);
        let q0 = InitialValues::PerPair(
            (0..q.len())
                .map(|p| Rational::from_integer(f.q0[p].into()))
                .collect(),
        );
        let p: crate::model::Problem = t.to_problem();
        let verdict = |rounds| {
            replay(&p, &q0, order, Terminal::Updated, rounds)
                .unwrap()
                .verdict
        };
        assert!(f.rounds > 4, "{}", f.rounds);
        assert!(matches!(
            verdict(f.rounds),
            ReplayVerdict::NeverConverges { from, period } if from + period == f.rounds
        ));
        assert_eq!(
            verdict(f.rounds - 1),
            ReplayVerdict::NotConverged {
                rounds: f.rounds - 1
            }
        );
        // Its report states the termination pair's 1 (pairs: the five moves, then the goal's
        // termination pair) in the values and in the replay command.
        let c = counterexample(&f, Terminal::Updated, "chain");
        assert_eq!(
            c.replay.as_deref(),
            Some("truecost learn --file problems/counterexamples/chain.json --q0 0,0,0,0,0,1 --order cyclic --terminal updated --rounds 6")
        );
    }

    /// The statement made from [`ROUND_BOUND`] is the published one, word for word; a planted
    /// bound changes it.
    #[test]
    fn the_statement_is_made_from_the_round_bound() {
        assert_eq!(
            corrected_statement(),
            "C1-corrected: assume (H0) the goal's termination value is held at Q(xg,uT) = 0, \
(H1) every state can reach the goal (Q* finite), (H2) Q0 >= Q* on every pair, or every move costs l(x,u) >= c > 0 \
(Q0 then arbitrary). Cut any fair update sequence into rounds (consecutive segments updating every pair at least \
once). Then Q = Q* from the end of round R on, where R1 = 1 + max over moves (x,u) of h(f(x,u)) (h = fewest moves \
of an optimal path to the goal), R = R1 if Q0 >= Q*, else R = max(R1, ceil((max Q* - min(0, min Q0)) / c))."
        );
        let planted = RoundBound {
            r1_offset: 0,
            ceil_offset: -1,
        };
        let s = planted.statement();
        assert!(
            s.contains("R1 = max over moves (x,u) of h(f(x,u)) (h"),
            "{s}"
        );
        assert!(s.ends_with("R = max(R1, ceil((max Q* - min(0, min Q0)) / c) - 1)."));
    }

    /// [`RoundBound::rounds`] of the stated bound is the kernel oracle's
    /// [`QProblem::round_bound`] on every smoke-scope problem satisfying H1 and H2, from every
    /// initial vector over {-2, 0, 1, 3} (so both branches, and a negative `m`, are taken); a
    /// planted `ceil − 1` differs on some of them.
    #[test]
    fn the_round_bound_s_value_is_the_kernel_s() {
        use crate::value::Rational;
        let r = |n: i64| Rational::from_integer(n.into());
        let (mut compared, mut ceil_branch, mut planted_differs) = (0, 0, 0);
        for spec in specs(Scope::Smoke) {
            for t in crate::claims::tiny::Family::new(&spec).canonical() {
                let held = QProblem::new(&t, Terminal::HeldAtZero);
                if !held.all_finite() {
                    continue;
                }
                let moves: Vec<usize> = (0..held.len())
                    .filter(|&p| !held.pairs[p].terminal)
                    .collect();
                let h = held.optimal_steps();
                let max_h = moves
                    .iter()
                    .map(|&p| u64::from(h[held.pairs[p].to as usize].unwrap()))
                    .max();
                let c = moves.iter().map(|&p| held.pairs[p].cost).min();
                let top = moves
                    .iter()
                    .map(|&p| held.optimum[p].unwrap())
                    .max()
                    .unwrap_or(0);
                for q0 in initial_vectors(&held, &[-2, 0, 1, 3]) {
                    let above = moves.iter().all(|&p| q0[p] >= held.optimum[p].unwrap());
                    let positive = c.is_some_and(|c| c > 0);
                    if !(above || positive) {
                        assert_eq!(held.round_bound(&q0), None);
                        continue;
                    }
                    let m = moves.iter().map(|&p| q0[p]).min().unwrap_or(0).min(0);
                    let cc = r(c.unwrap_or(1));
                    let ours = ROUND_BOUND.rounds(max_h, above, &r(top), &r(m), &cc);
                    assert_eq!(Some(ours), held.round_bound(&q0), "{}", t.describe());
                    compared += 1;
                    ceil_branch += u64::from(!above);
                    let wrong = RoundBound {
                        ceil_offset: -1,
                        ..ROUND_BOUND
                    };
                    planted_differs +=
                        u64::from(wrong.rounds(max_h, above, &r(top), &r(m), &cc) != ours);
                }
            }
        }
        assert!(
            compared > 100 && ceil_branch > 10,
            "{compared} {ceil_branch}"
        );
        assert!(planted_differs > 0);
    }

    /// C1-corrected's failure path, which the theorem leaves untaken, reached with a planted
    /// bound one below the true `R`. Chain 0 → 1 → 2 (goal), costs 1, `Q₀ = 0`, termination
    /// pair held: `R = max(R₁, ⌈(max Q* − min(0, min Q₀))/c⌉) = max(2, 2) = 2`, by hand. The
    /// cyclic and far-first orders (pairs 0, 1) need 2 rounds, the reverse order 1, and the
    /// random order (seed 0: splitmix64's draw 0x…65F4 is even, so it swaps the two pairs) 1.
    /// With `R` the case passes and the far-first order attains the bound; with `R − 1 = 1` the
    /// cyclic and far-first runs fail (the cyclic one reported, first, with the rounds that show
    /// it, `R − 1 + 1`), and the every-order exploration (worst order: 2 rounds) fails once.
    /// An exploration allowed no state is counted as too large.
    #[test]
    fn a_planted_bound_below_r_is_counted_and_reported() {
        let t = Tiny::from_lists(&[vec![(1, 1)], vec![(2, 1)], vec![]]);
        let below: BoundOracle = |q, v| q.round_bound(v).map(|r| r - 1);
        let mut right = Acc::default();
        check_structure(&mut right, &t, 0, &[0], &[0], QProblem::round_bound);
        check_all_orders(
            &mut right,
            &t,
            0,
            &[0],
            QProblem::round_bound,
            EXPLORATION_STATES,
        );
        let mut planted = Acc::default();
        check_structure(&mut planted, &t, 0, &[0], &[0], below);
        check_all_orders(&mut planted, &t, 0, &[0], below, EXPLORATION_STATES);
        assert_eq!((right.corrected_cases, right.corrected_failures), (1, 0));
        assert_eq!((right.max_rounds, right.bound_attained), (2, 1));
        assert_eq!(
            (right.exhaustive_failures, right.exhaustive_attained),
            (0, 1)
        );
        assert!(right.corrected_min.is_none() && right.exhaustive_min.is_none());
        assert_eq!(
            (planted.corrected_cases, planted.corrected_failures),
            (1, 2)
        );
        assert_eq!((planted.max_rounds, planted.bound_attained), (1, 0));
        assert_eq!(
            (planted.exhaustive_cases, planted.exhaustive_failures),
            (1, 1)
        );
        let (_, f) = planted.corrected_min.expect("a failure");
        assert_eq!(
            f.what,
            "under the cyclic order: Q = Q* after 2 rounds (bound R = 1)"
        );
        assert_eq!((f.order, f.rounds), (Some(Order::Cyclic), 2));
        let (_, f) = planted.exhaustive_min.expect("a failure");
        assert_eq!(
            f.what,
            "every-order exploration: Converges(2) (bound R = 1)"
        );
        assert_eq!((f.order, f.rounds), (Some(Order::FarFirst), 2));
        // An exploration allowed no state is too large: counted, neither a pass nor a failure.
        let mut small = Acc::default();
        check_all_orders(&mut small, &t, 0, &[0], QProblem::round_bound, 0);
        assert_eq!((small.exhaustive_cases, small.exhaustive_too_large), (1, 1));
        assert_eq!(
            (small.exhaustive_failures, small.exhaustive_attained),
            (0, 0)
        );
        assert_eq!(right.exhaustive_too_large, 0);
    }

    /// The verdicts from a pass's counts (the scopes never reach most of these: C1 as printed
    /// is refuted in each, and C1-corrected holds): C1 is inconclusive when runs were undecided
    /// and none failed; C1-corrected is refuted by a failure of either engine, and inconclusive
    /// when some case was too large to explore and none failed.
    #[test]
    fn verdicts_from_the_counts_of_a_pass() {
        let verdicts = |acc: Acc| {
            let (printed, corrected) = results(&Pass {
                acc,
                structures: 1,
                scope_text: vec![],
                ex_scope: vec![],
                domain: &[0],
                corrected: &[0],
                seconds: (0.0, 0.0),
            });
            (printed.verdict, corrected.verdict)
        };
        use Verdict::{Inconclusive, Refuted, Verified};
        let base = || Acc {
            printed_cases: 4,
            corrected_cases: 4,
            exhaustive_cases: 4,
            ..Acc::default()
        };
        assert_eq!(verdicts(base()), (Verified, Verified));
        let undecided = Acc {
            printed_undecided: 1,
            ..base()
        };
        assert_eq!(verdicts(undecided), (Inconclusive, Verified));
        for (simulated, explored) in [(2, 0), (0, 1), (2, 1)] {
            let failing = Acc {
                corrected_failures: simulated,
                exhaustive_failures: explored,
                ..base()
            };
            assert_eq!(verdicts(failing).1, Refuted, "{simulated} {explored}");
            let failing_and_too_large = Acc {
                corrected_failures: simulated,
                exhaustive_failures: explored,
                exhaustive_too_large: 1,
                ..base()
            };
            assert_eq!(verdicts(failing_and_too_large).1, Refuted);
        }
        let too_large = Acc {
            exhaustive_too_large: 1,
            ..base()
        };
        assert_eq!(verdicts(too_large).1, Inconclusive);
    }

    /// `merge` (the parallel enumeration's reduction) adds every count and keeps the larger of
    /// the round maxima, field by field: two accumulators with different non-zero values (the
    /// smoke and quick scopes leave several counts at 0, where `+`, `−` and `·` agree).
    #[test]
    fn merge_adds_every_count_and_keeps_the_larger_maxima() {
        let a = Acc {
            printed_cases: 1,
            printed_failures: 2,
            printed_undecided: 3,
            corrected_cases: 4,
            corrected_failures: 5,
            max_rounds: 6,
            bound_attained: 7,
            exhaustive_cases: 8,
            exhaustive_failures: 9,
            exhaustive_too_large: 10,
            exhaustive_max_rounds: 11,
            exhaustive_attained: 12,
            ..Acc::default()
        };
        let b = Acc {
            printed_cases: 100,
            printed_failures: 200,
            printed_undecided: 300,
            corrected_cases: 400,
            corrected_failures: 500,
            max_rounds: 2,
            bound_attained: 700,
            exhaustive_cases: 800,
            exhaustive_failures: 900,
            exhaustive_too_large: 1000,
            exhaustive_max_rounds: 20,
            exhaustive_attained: 1200,
            ..Acc::default()
        };
        let m = merge(a, b);
        assert_eq!(
            (m.printed_cases, m.printed_failures, m.printed_undecided),
            (101, 202, 303)
        );
        assert_eq!((m.corrected_cases, m.corrected_failures), (404, 505));
        assert_eq!((m.max_rounds, m.bound_attained), (6, 707));
        assert_eq!(
            (
                m.exhaustive_cases,
                m.exhaustive_failures,
                m.exhaustive_too_large
            ),
            (808, 909, 1010)
        );
        assert_eq!((m.exhaustive_max_rounds, m.exhaustive_attained), (20, 1212));
    }

    /// The full scope checks every initial value the quick scope (CI's) checks, and more, for
    /// C1 and for C1-corrected (the smoke scope is a different small set).
    #[test]
    fn the_full_scope_keeps_every_initial_value_of_the_quick_one() {
        for values in [initial_values, corrected_values] {
            let (quick, full) = (values(Scope::Quick), values(Scope::Full));
            assert!(quick.iter().all(|v| full.contains(v)), "{quick:?} {full:?}");
            assert!(full.len() > quick.len());
            // Distinct values: a repeated one would check less than the scope says.
            for scope in [Scope::Smoke, Scope::Quick, Scope::Full] {
                let mut distinct = values(scope).to_vec();
                distinct.sort();
                distinct.dedup();
                assert_eq!(distinct.len(), values(scope).len(), "{:?}", values(scope));
            }
        }
    }

    /// The quick scope (CI) checks the `min(0, min Q₀)` term of `R`, which
    /// only a negative initial value exercises: on `0 → 0 (1), 0 → goal (1)` from `Q₀ = −2`,
    /// `R = max(R₁, ⌈(max Q* − (−2))/c⌉) = max(2, 4) = 4`, and the cyclic order needs all 4
    /// rounds (`Q(0→0)`: −1, 0, 1, 2 by hand), so a scope without negative values never sees
    /// the term decide the bound.
    #[test]
    fn quick_scope_has_negative_initial_values_and_they_set_the_bound() {
        assert!(corrected_values(Scope::Quick).iter().any(|&v| v < 0));
        assert!(corrected_values(Scope::Quick).contains(&0));
        let q = QProblem::new(
            &Tiny::from_lists(&[vec![(0, 1), (1, 1)], vec![]]),
            Terminal::HeldAtZero,
        );
        let mut q0 = [0i64; crate::claims::qlearning::MAX_PAIRS];
        q0[0] = -2;
        q0[1] = -2;
        assert_eq!(q.round_bound(&q0), Some(4));
        assert_eq!(
            crate::claims::qlearning::run(&q, &q0, Order::Cyclic, 10),
            Run::Converged(4)
        );
    }

    /// A failure's `rounds` is the first number of rounds after which it shows: for C1-corrected
    /// without H2 (a cyclic run whose round-end values repeat), a run of exactly that many
    /// rounds finds the repetition and one round fewer does not. On the smoke scope's
    /// families, whose smallest such failure repeats from round `from` with period `p`.
    #[test]
    fn a_dropped_h2_failure_shows_after_its_rounds_and_not_before() {
        let mut checked = 0;
        for spec in specs(Scope::Smoke) {
            let (acc, _) = enumerate(
                &spec,
                Acc::default,
                |acc, t, i| {
                    check_structure(
                        acc,
                        t,
                        i,
                        initial_values(Scope::Smoke),
                        corrected_values(Scope::Smoke),
                        QProblem::round_bound,
                    )
                },
                merge,
            );
            let Some((_, f)) = acc.drop_h2 else { continue };
            let held = QProblem::new(&f.t, Terminal::HeldAtZero);
            let Run::Cycles(from, period) = run(&held, &f.q0, Order::Cyclic, f.rounds) else {
                panic!(
                    "{}: no repetition within {} rounds",
                    f.t.describe(),
                    f.rounds
                )
            };
            assert_eq!(from + period, f.rounds);
            assert!(matches!(
                run(&held, &f.q0, Order::Cyclic, f.rounds - 1),
                Run::NotWithin(_)
            ));
            checked += 1;
        }
        assert!(checked > 0);
    }

    fn finding(t: &Tiny, q0: Values, terminal_q0: i64) -> Finding {
        Finding {
            t: *t,
            q0,
            terminal_q0,
            what: "a failure".into(),
            order: None,
            rounds: 1,
        }
    }

    /// The extra note names the smallest failure only when it is not the headline: the same
    /// finding gives none, a different problem, initial values or termination-pair value one.
    #[test]
    fn the_termination_pair_note_only_for_a_different_smallest_failure() {
        let a = Tiny::from_lists(&[vec![(0, 0), (1, 1)], vec![]]);
        let b = Tiny::from_lists(&[vec![(0, 0), (1, 2)], vec![]]);
        let zero = [0i64; crate::claims::qlearning::MAX_PAIRS];
        let mut one = zero;
        one[0] = 1;
        let headline = finding(&a, zero, 0);
        assert_eq!(termination_pair_note(&headline, &headline.clone()), None);
        for other in [
            finding(&b, zero, 0),
            finding(&a, one, 0),
            finding(&a, zero, 1),
        ] {
            let note = termination_pair_note(&headline, &other).expect("a different failure");
            assert!(
                note.starts_with("also refuted at the goal's termination pair")
                    && note.contains(&other.t.describe()),
                "{note}"
            );
        }
    }

    /// The smallest failure is the one with the smallest initial values (the sum of their
    /// absolute values, the termination pair's included), not the first enumerated: on
    /// `0 → 1 (1), 0 → goal (1), 1 → 1 (1)`, where state 1 never reaches the goal (so every
    /// initial vector fails C1 as printed), with values from {−1, 0, 1, 3}, the first vector
    /// enumerated is all −1 but the smallest is all 0 with the termination pair at 0.
    #[test]
    fn the_smallest_printed_failure_has_the_smallest_initial_values() {
        let t = Tiny::from_lists(&[vec![(1, 1), (2, 1)], vec![(1, 1)], vec![]]);
        let mut acc = Acc::default();
        check_structure(&mut acc, &t, 0, &[-1, 0, 1, 3], &[0], QProblem::round_bound);
        let moves = QProblem::new(&t, Terminal::Updated).len() - 1;
        let vectors = 4u64.pow(moves as u32);
        assert_eq!(acc.printed_cases, 2 * vectors);
        assert_eq!(acc.printed_failures, 2 * vectors);
        assert!(acc.printed_cycle_min.is_none());
        let (_, smallest) = acc.printed_min.expect("a failure");
        assert_eq!(smallest.q0, [0i64; crate::claims::qlearning::MAX_PAIRS]);
        assert_eq!(smallest.terminal_q0, 0);
    }

    /// A run that neither converges nor cycles within `MAX_ROUNDS` is counted as undecided,
    /// once per order, and is not a failure. No scope is known to reach it; an initial value
    /// of −1000 does: on `0 → 0 (1), 0 → goal (1)`, Q(0→0) = 1 + min(Q(0→0), Q(0→goal)) rises
    /// by exactly 1 a round from −1000 (every value it takes is new, so no cycle), and needs
    /// about a thousand rounds to reach its limit.
    #[test]
    fn a_run_still_moving_after_the_round_limit_is_undecided_under_each_order() {
        let t = Tiny::from_lists(&[vec![(0, 1), (1, 1)], vec![]]);
        let mut acc = Acc::default();
        check_structure(&mut acc, &t, 0, &[-1000], &[0], QProblem::round_bound);
        // One initial vector (every move at −1000), with the termination pair at 0 and at 1.
        assert_eq!(acc.printed_cases, 2);
        assert_eq!(acc.printed_undecided, 2 * ORDERS as u64);
        assert_eq!(acc.printed_failures, 0);
        assert!(acc.printed_min.is_none() && acc.printed_cycle_min.is_none());
    }
}

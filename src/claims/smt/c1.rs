//! SMT encodings of claim C1 (derandomized Q-learning converges in finite time; docs/spec.md §6,
//! the paper's Proposition 1) — the argument is written out in `docs/proofs/c1.md`.
//!
//! **C1-corrected** is proved for every number of rounds by induction (see [`super::super::c1`]
//! for the statement): an invariant that every single update preserves, and progress per
//! round. The obligations are of two kinds:
//!
//! * **Local lemmas** about one update `Q(x,u) ← l(x,u) + min Q(y,·)` (`y = f(x,u)`) that
//!   mention only the updated pair, its cost and the pairs of its successor `y` — so one
//!   obligation per out-degree `d` of `y` covers every graph whose states have at most `d`
//!   pairs (the goal's termination pair counted), whatever the number of states:
//!   A1 (`Q ≥ Q*` is preserved), A2 (an exact optimal successor pair makes the update exact),
//!   B1 (with costs `≥ c > 0`, `Q ≥ min(Q*, t)` on `y`'s pairs gives `≥ min(Q*, t + c)`),
//!   B2 (monotonicity), B3 (`Q ≤ Q*` is preserved), and the round-count arithmetic.
//! * **Whole-structure steps** for every structure of the scope (enumerated up to
//!   relabelling): with `G*` defined independently as the least cost over simple paths, `h` as
//!   the fewest moves of an optimal path, and the level `r` (an integer) and `t` (a real)
//!   symbolic, one update of any pair preserves the invariant `I_r` (Part A) / `J_t` (Part B),
//!   makes its pair exact when `h(f(x,u)) ≤ r` / brings it to `min(Q*, t + c)`, and the
//!   invariant at the last level means `Q = Q*`; the Bellman and descent facts that the local
//!   lemmas assume are checked against the path definitions.
//!
//! **C1 as printed** is satisfiable: a fixed point of every update that differs from `Q*`
//! (so no order ever converges), replayed exactly through the Q-learning oracle.

use num_traits::{ToPrimitive, Zero};

use super::term::{
    and, app, eq, ge, gt, implies, int, is_min, le, lt, min, ne, not, or, real_int, sub, sum,
};
use super::{Encoding, Logic, Model, Obligation, Replay, Role, Sort};
use crate::claims::c1::{self, RoundBound};
use crate::claims::qlearning::{run as run_q, Order, QProblem, Run, Terminal, MAX_PAIRS};
use crate::claims::tiny::{Family, FamilySpec, Tiny};
use crate::claims::{Counterexample, Scope};
use crate::value::{to_common_scale, Rational};

const CLAIM: &str = "C1-corrected";
const PRINTED: &str = "C1";

/// Largest out-degree (pairs of the successor, termination pair included) of the local
/// lemmas in each scope.
fn local_degree(scope: Scope) -> usize {
    match scope {
        Scope::Smoke => 3,
        Scope::Quick => 6,
        Scope::Full => 8,
    }
}

/// The structure families of the whole-structure obligations.
fn structure_specs(scope: Scope) -> Vec<FamilySpec> {
    let spec = |states| FamilySpec {
        states,
        initial_fixed: false,
        degree: (1, 2),
        goal_degree: (0, 2),
        costs: vec![0],
        distinct_successors: false,
    };
    match scope {
        Scope::Smoke => (1..=2).map(spec).collect(),
        Scope::Quick => (1..=3).map(spec).collect(),
        Scope::Full => (1..=4).map(spec).collect(),
    }
}

fn structure_scope_text(scope: Scope) -> usize {
    structure_specs(scope)
        .iter()
        .map(|s| s.states)
        .max()
        .unwrap_or(0)
}

/// The local lemma's unknowns for a successor with `d` pairs.
struct Local {
    o: Obligation,
    l: String,
    qy: Vec<String>,
    sy: Vec<String>,
    gy: String,
    v: String,
}

impl Local {
    /// Declares `l`, `Q(y,i)`, `Q*(y,i)`, `G*(y)` and `v = min Q(y,·)`, with the Bellman facts
    /// `G*(y) = min Q*(y,·)` and `Q* ≥ 0` (costs ≥ 0), and `l ≥ 0`.
    fn new(lemma: &str, d: usize, role: Role) -> Local {
        let mut o = Obligation::new(
            CLAIM,
            lemma,
            &format!("any graph; successor y with {d} pair(s)"),
            role,
            Logic::QfLra,
        );
        let l = o.declare("l", Sort::Real);
        let qy: Vec<String> = (0..d)
            .map(|i| o.declare(&format!("qy{i}"), Sort::Real))
            .collect();
        let sy: Vec<String> = (0..d)
            .map(|i| o.declare(&format!("sy{i}"), Sort::Real))
            .collect();
        let gy = o.declare("gy", Sort::Real);
        let v = o.declare("v", Sort::Real);
        o.assert(ge(&l, "0.0"));
        for s in &sy {
            o.assert(ge(s, "0.0"));
        }
        o.assert(is_min(&gy, &sy));
        o.assert(is_min(&v, &qy));
        Local {
            o,
            l,
            qy,
            sy,
            gy,
            v,
        }
    }

    /// `l + v`, the updated value.
    fn new_value(&self) -> String {
        sum(&[self.l.clone(), self.v.clone()])
    }

    /// `Q*(x,u) = l + G*(y)`.
    fn target(&self) -> String {
        sum(&[self.l.clone(), self.gy.clone()])
    }

    fn above(&self) -> Vec<String> {
        self.qy
            .iter()
            .zip(&self.sy)
            .map(|(q, s)| ge(q, s))
            .collect()
    }
}

/// Adds `proof` with its `Hypotheses` twin (the same assertions without `conclusion_negated`).
fn with_hypotheses(out: &mut Vec<Obligation>, mut proof: Obligation, conclusion_negated: String) {
    out.push(proof.with_role(Role::Hypotheses));
    proof.assert(conclusion_negated);
    out.push(proof);
}

fn local_lemmas(scope: Scope, bound: RoundBound) -> Vec<Obligation> {
    let mut out = Vec::new();
    for d in 1..=local_degree(scope) {
        // A1: Q >= Q* on y's pairs => l + min Q(y,.) >= Q*(x,u).
        let mut a = Local::new("A1: Q >= Q* is preserved by one update", d, Role::Proof);
        for h in a.above() {
            a.o.assert(h);
        }
        let neg = lt(&a.new_value(), &a.target());
        with_hypotheses(&mut out, a.o, neg);
        // A1 without H2 (values below Q* allowed): the failure exists.
        let mut a = Local::new(
            "A1: Q >= Q* is preserved by one update",
            d,
            Role::Dropped("H2 (Q0 >= Q*)".into()),
        );
        a.o.assert(lt(&a.new_value(), &a.target()));
        out.push(a.o);
        // A2: Q >= Q* and an exact optimal pair at y => the update is exact.
        let mut a = Local::new(
            "A2: an exact optimal successor pair makes the update exact",
            d,
            Role::Proof,
        );
        for h in a.above() {
            a.o.assert(h);
        }
        let exact: Vec<String> = (0..d)
            .map(|i| and(&[eq(&a.qy[i], &a.sy[i]), eq(&a.sy[i], &a.gy)]))
            .collect();
        a.o.assert(or(&exact));
        let neg = ne(&a.new_value(), &a.target());
        with_hypotheses(&mut out, a.o, neg);
        // B1: costs >= c > 0 and Q >= min(Q*, t) on y's pairs => l + v >= min(Q*(x,u), t + c).
        let b1 = |role: Role, positive: bool| {
            let mut b = Local::new(
                "B1: with costs >= c > 0, Q >= min(Q*, t) gives min(Q*, t + c) after one update",
                d,
                role,
            );
            let c = b.o.declare("c", Sort::Real);
            let t = b.o.declare("t", Sort::Real);
            if positive {
                b.o.assert(gt(&c, "0.0"));
                b.o.assert(ge(&b.l, &c));
            }
            for i in 0..d {
                b.o.assert(or(&[ge(&b.qy[i], &b.sy[i]), ge(&b.qy[i], &t)]));
            }
            let neg = and(&[
                lt(&b.new_value(), &b.target()),
                lt(&b.new_value(), &sum(&[t.clone(), c.clone()])),
            ]);
            (b.o, neg)
        };
        let (o, neg) = b1(Role::Proof, true);
        with_hypotheses(&mut out, o, neg);
        let (mut o, neg) = b1(Role::Dropped("costs >= c > 0".into()), false);
        o.assert(neg);
        out.push(o);
        // B2: monotonicity.
        let mut b = Local::new(
            "B2: the update is monotone (Q <= Q' on y's pairs => new Q <= new Q')",
            d,
            Role::Proof,
        );
        let qy2: Vec<String> = (0..d)
            .map(|i| b.o.declare(&format!("qz{i}"), Sort::Real))
            .collect();
        let v2 = b.o.declare("w", Sort::Real);
        b.o.assert(is_min(&v2, &qy2));
        for i in 0..d {
            b.o.assert(le(&b.qy[i], &qy2[i]));
        }
        let neg = gt(&b.new_value(), &sum(&[b.l.clone(), v2.clone()]));
        with_hypotheses(&mut out, b.o, neg);
        // B3: Q <= Q* is preserved.
        let mut b = Local::new("B3: Q <= Q* is preserved by one update", d, Role::Proof);
        for i in 0..d {
            b.o.assert(le(&b.qy[i], &b.sy[i]));
        }
        let neg = gt(&b.new_value(), &b.target());
        with_hypotheses(&mut out, b.o, neg);
    }
    // H0 is needed: a termination pair updated by the rule (a zero-cost self-loop) keeps a
    // value above Q* = 0 for ever when it starts there.
    let mut o = Obligation::new(
        CLAIM,
        "H0: the termination pair is held at 0",
        "any graph; the goal with its termination pair and one move",
        Role::Dropped("H0 (Q(xg,uT) held at 0)".into()),
        Logic::QfLra,
    );
    let qt = o.declare("qt", Sort::Real);
    let qm = o.declare("qm", Sort::Real);
    let sm = o.declare("sm", Sort::Real);
    let v = o.declare("v", Sort::Real);
    o.assert(ge(&sm, "0.0"));
    o.assert(ge(&qm, &sm));
    o.assert(ge(&qt, "0.0"));
    o.assert(is_min(&v, &[qt.clone(), qm.clone()]));
    // The rule's new value of uT is 0 + v; it stays above Q*(xg,uT) = 0.
    o.assert(eq(&v, &qt));
    o.assert(gt(&qt, "0.0"));
    out.push(o);
    out.extend(round_count(bound));
    out
}

/// The lemma name of B4 for `bound` (the formula is part of it, so that the index and the
/// files name the bound they prove).
fn b4_lemma(bound: RoundBound) -> String {
    format!(
        "B4: R = max(R1, {}) with R1 = {}: R rounds reach level max Q*",
        bound.ceil_text(),
        bound.r1_text()
    )
}

/// B4, Part B's round count, with `R` the integer the statement defines (QF_NIRA): reals
/// `c > 0`, `m ≤ 0` (`m = min(0, min Q₀)`), `top ≥ 0` (`max Q*`, costs ≥ 0); integers
/// `hmax ≥ 0` (`max h(f(x,u))`), `k = ⌈(top − m)/c⌉` (as `(k − 1)·c < top − m ≤ k·c`, which
/// only the ceiling satisfies), `R1` and `R` as [`RoundBound`] makes them; negated
/// conclusion `m + R·c < top` (the lower run's level after `R` rounds, `m + R·c`, is below
/// `max Q*`). Unsat proves that `R` rounds reach the level at which Part B's sandwich closes.
fn round_count(bound: RoundBound) -> Vec<Obligation> {
    let mut o = Obligation::new(
        CLAIM,
        &b4_lemma(bound),
        "arithmetic",
        Role::Proof,
        Logic::QfNira,
    );
    let c = o.declare("c", Sort::Real);
    let m = o.declare("m", Sort::Real);
    let top = o.declare("top", Sort::Real);
    let hmax = o.declare("hmax", Sort::Int);
    let k = o.declare("k", Sort::Int);
    let r1 = o.declare("R1", Sort::Int);
    let r = o.declare("R", Sort::Int);
    let times_c = |n: &str| app("*", &[app("to_real", &[n.to_string()]), c.clone()]);
    o.assert(gt(&c, "0.0"));
    o.assert(le(&m, "0.0"));
    o.assert(ge(&top, "0.0"));
    o.assert(ge(&hmax, "0"));
    let gap = sub(&top, &m);
    o.assert(ge(&times_c(&k), &gap));
    o.assert(lt(&times_c(&app("-", &[k.clone(), "1".into()])), &gap));
    o.assert(eq(&r1, &app("+", &[int(bound.r1_offset), hmax.clone()])));
    let ceil = app("+", &[k.clone(), int(bound.ceil_offset)]);
    o.assert(eq(&r, &super::term::ite(&ge(&r1, &ceil), &r1, &ceil)));
    let neg = lt(&sum(&[m.clone(), times_c(&r)]), &top);
    let mut out = Vec::new();
    with_hypotheses(&mut out, o, neg);
    out
}

/// Replays a satisfiable B4 in exact arithmetic: the model's `c > 0`, `m`, `top` give the
/// true number of rounds `⌈(top − m)/c⌉`, recomputed here; the model's `R` is confirmed as
/// too small when it is below that number and `m + R·c < top` holds exactly.
fn replay_round_count(m: &Model) -> Replay {
    use num_traits::Signed;
    let get = |n: &str| m.get(n).cloned();
    let (Some(c), Some(lo), Some(top), Some(r)) = (get("c"), get("m"), get("top"), get("R")) else {
        return Replay::NotConfirmed("the model lacks c, m, top or R".into());
    };
    if !c.is_positive() || !r.is_integer() {
        return Replay::NotConfirmed("the model's c is not positive or R not an integer".into());
    }
    let needed = ((&top - &lo) / &c).ceil();
    let level = &lo + &r * &c;
    if r < needed && level < top {
        Replay::Confirmed(
            format!(
                "R = {r} rounds leave the lower run at level m + R c = {level} < max Q* = {top}, while \
ceil((max Q* - m)/c) = {needed} (c = {c}, m = {lo}): the bound stops short"
            ),
            None,
        )
    } else {
        Replay::NotConfirmed(format!(
            "the model's R = {r} is not below ceil((max Q* - m)/c) = {needed}"
        ))
    }
}

/// The pairs of a structure in [`QProblem`]'s order: `(state, successor, terminal)`.
fn pairs_of(t: &Tiny) -> Vec<(usize, usize, bool)> {
    let mut v = Vec::new();
    for x in 0..t.states() {
        if t.is_goal(x) {
            v.push((x, x, true));
        }
        for m in t.moves(x) {
            v.push((x, m.to as usize, false));
        }
    }
    v
}

/// Every simple path from `x` to the goal, as the list of pair indices it uses.
fn simple_paths(t: &Tiny, pairs: &[(usize, usize, bool)], x: usize) -> Vec<Vec<usize>> {
    fn go(
        t: &Tiny,
        pairs: &[(usize, usize, bool)],
        x: usize,
        seen: &mut Vec<bool>,
        path: &mut Vec<usize>,
        out: &mut Vec<Vec<usize>>,
    ) {
        if t.is_goal(x) {
            out.push(path.clone());
            return;
        }
        for (p, &(s, to, terminal)) in pairs.iter().enumerate() {
            if s != x || terminal || seen[to] {
                continue;
            }
            seen[to] = true;
            path.push(p);
            go(t, pairs, to, seen, path, out);
            path.pop();
            seen[to] = false;
        }
    }
    let mut seen = vec![false; t.states()];
    seen[x] = true;
    let mut out = Vec::new();
    go(t, pairs, x, &mut seen, &mut Vec::new(), &mut out);
    out
}

/// The common part of a whole-structure obligation: costs, `G*` by simple paths, `Q*`, `h`,
/// the Bellman and descent facts as a disjunct of the negated conclusion.
struct Whole {
    o: Obligation,
    pairs: Vec<(usize, usize, bool)>,
    cost: Vec<String>,
    qstar: Vec<String>,
    h: Vec<String>,
    /// Negated facts (the Bellman equations and the descent of `h`).
    facts_negated: Vec<String>,
}

impl Whole {
    fn new(claim: &str, t: &Tiny, lemma: &str, role: Role) -> Option<Whole> {
        let pairs = pairs_of(t);
        let n = t.states();
        let paths: Vec<Vec<Vec<usize>>> = (0..n).map(|x| simple_paths(t, &pairs, x)).collect();
        if paths.iter().any(|p| p.is_empty()) {
            return None; // H1 fails: outside C1-corrected's scope.
        }
        let mut o = Obligation::new(claim, lemma, &t.describe(), role, Logic::QfLra);
        let cost: Vec<String> = pairs
            .iter()
            .enumerate()
            .map(|(p, &(_, _, terminal))| {
                if terminal {
                    "0.0".to_string()
                } else {
                    let c = o.declare(&format!("l{p}"), Sort::Real);
                    o.assert(ge(&c, "0.0"));
                    c
                }
            })
            .collect();
        let path_cost =
            |path: &[usize]| sum(&path.iter().map(|&p| cost[p].clone()).collect::<Vec<_>>());
        let g: Vec<String> = (0..n)
            .map(|x| {
                let gx = o.declare(&format!("g{x}"), Sort::Real);
                let all: Vec<String> = paths[x].iter().map(|p| path_cost(p)).collect();
                o.assert(eq(&gx, &min(&all)));
                gx
            })
            .collect();
        let qstar: Vec<String> = pairs
            .iter()
            .enumerate()
            .map(|(p, &(_, to, terminal))| {
                if terminal {
                    "0.0".to_string()
                } else {
                    sum(&[cost[p].clone(), g[to].clone()])
                }
            })
            .collect();
        // h(x): the fewest moves of an optimal simple path (optimal paths can be taken simple
        // since costs are >= 0).
        let h: Vec<String> = (0..n)
            .map(|x| {
                let hx = o.declare(&format!("h{x}"), Sort::Real);
                let mut expr = real_int(n as i64); // never used: some path is optimal
                for k in (0..n).rev() {
                    let within: Vec<String> = paths[x]
                        .iter()
                        .filter(|p| p.len() == k)
                        .map(|p| eq(&path_cost(p), &g[x]))
                        .collect();
                    if !within.is_empty() {
                        expr = super::term::ite(&or(&within), &real_int(k as i64), &expr);
                    }
                }
                o.assert(eq(&hx, &expr));
                hx
            })
            .collect();
        let mut facts_negated = Vec::new();
        for x in 0..n {
            let own: Vec<String> = (0..pairs.len())
                .filter(|&p| pairs[p].0 == x)
                .map(|p| qstar[p].clone())
                .collect();
            // Bellman: G*(x) = min over x's pairs of Q* (the goal's termination pair included).
            facts_negated.push(ne(&g[x], &min(&own)));
            if !t.is_goal(x) {
                // Descent: some optimal pair leads to a state one move nearer.
                let descent: Vec<String> = (0..pairs.len())
                    .filter(|&p| pairs[p].0 == x)
                    .map(|p| and(&[eq(&qstar[p], &g[x]), eq(&sub(&h[x], &h[pairs[p].1]), "1.0")]))
                    .collect();
                facts_negated.push(not(&or(&descent)));
            }
        }
        Some(Whole {
            o,
            pairs,
            cost,
            qstar,
            h,
            facts_negated,
        })
    }

    /// Declares `Q` values `prefix{p}` for the non-terminal pairs (the terminal pair is 0).
    fn values(&mut self, prefix: &str) -> Vec<String> {
        (0..self.pairs.len())
            .map(|p| {
                if self.pairs[p].2 {
                    "0.0".to_string()
                } else {
                    self.o.declare(&format!("{prefix}{p}"), Sort::Real)
                }
            })
            .collect()
    }

    /// The value of pair `p` after its update from `q`: `l + min Q(f(p), ·)`.
    fn updated(&self, q: &[String], p: usize) -> String {
        let y = self.pairs[p].1;
        let succ: Vec<String> = (0..self.pairs.len())
            .filter(|&r| self.pairs[r].0 == y)
            .map(|r| q[r].clone())
            .collect();
        sum(&[self.cost[p].clone(), min(&succ)])
    }

    fn updatable(&self) -> Vec<usize> {
        (0..self.pairs.len())
            .filter(|&p| !self.pairs[p].2)
            .collect()
    }
}

/// `I_r(q)`: `Q ≥ Q*` everywhere and exact on pairs with `h(f(p)) ≤ r − 1`.
fn invariant_a(w: &Whole, q: &[String], r: &str) -> String {
    and(&w
        .updatable()
        .into_iter()
        .flat_map(|p| {
            let hf = &w.h[w.pairs[p].1];
            [
                ge(&q[p], &w.qstar[p]),
                implies(&le(hf, &sub(r, "1.0")), &eq(&q[p], &w.qstar[p])),
            ]
        })
        .collect::<Vec<_>>())
}

/// `J_t(q)`: `Q ≥ min(Q*, t)` everywhere.
fn invariant_b(w: &Whole, q: &[String], t: &str) -> String {
    and(&w
        .updatable()
        .into_iter()
        .map(|p| or(&[ge(&q[p], &w.qstar[p]), ge(&q[p], t)]))
        .collect::<Vec<_>>())
}

fn replaced(q: &[String], p: usize, v: String) -> Vec<String> {
    let mut q = q.to_vec();
    q[p] = v;
    q
}

/// Part A on one structure: the facts, `I_r` preserved by every single update, progress to
/// `h(f(p)) ≤ r`, and `I_{R₁}` ⇒ `Q = Q*`.
fn whole_a(t: &Tiny, role: Role, r1_offset: i64) -> Option<(Obligation, String)> {
    let mut w = Whole::new(
        CLAIM,
        t,
        "A: Bellman/descent facts; I_r preserved by every update; progress; I_R1 => Q = Q*",
        role,
    )?;
    let q = w.values("q");
    let r = w.o.declare("r", Sort::Real);
    w.o.assert(ge(&r, "0.0"));
    w.o.assert(invariant_a(&w, &q, &r));
    let mut negated = w.facts_negated.clone();
    for p in w.updatable() {
        let new = w.updated(&q, p);
        negated.push(not(&invariant_a(&w, &replaced(&q, p, new.clone()), &r)));
        negated.push(and(&[le(&w.h[w.pairs[p].1], &r), ne(&new, &w.qstar[p])]));
    }
    // I_{R1} with R1 = 1 + max h(f(p)) means every pair is exact.
    let hs: Vec<String> = w
        .updatable()
        .iter()
        .map(|&p| w.h[w.pairs[p].1].clone())
        .collect();
    if !hs.is_empty() {
        let r1 = sum(&[real_int(r1_offset), super::term::max(&hs)]);
        let exact_all = and(&w
            .updatable()
            .into_iter()
            .map(|p| eq(&q[p], &w.qstar[p]))
            .collect::<Vec<_>>());
        negated.push(and(&[eq(&r, &r1), not(&exact_all)]));
    }
    Some((w.o, or(&negated)))
}

/// Part B on one structure: costs `≥ c > 0`; `J_t` preserved and lifted to `J_{t+c}` by
/// every update; monotonicity; `Q ≤ Q*` preserved; `J_t` with `t ≥ max Q*` and `Q ≤ Q*` ⇒
/// `Q = Q*`.
fn whole_b(t: &Tiny, role: Role, positive: bool) -> Option<(Obligation, String)> {
    let mut w = Whole::new(CLAIM, t, "B: J_t lifted to J_(t+c) by every update; monotone; Q <= Q* preserved; J_t with t >= max Q* and Q <= Q* => Q = Q*", role)?;
    let q = w.values("q");
    let q2 = w.values("z");
    let c = w.o.declare("c", Sort::Real);
    let tt = w.o.declare("t", Sort::Real);
    if positive {
        w.o.assert(gt(&c, "0.0"));
        for p in w.updatable() {
            w.o.assert(ge(&w.cost[p], &c));
        }
    }
    w.o.assert(invariant_b(&w, &q, &tt));
    let tc = sum(&[tt.clone(), c.clone()]);
    let mut negated = Vec::new();
    for p in w.updatable() {
        let new = w.updated(&q, p);
        negated.push(and(&[lt(&new, &w.qstar[p]), lt(&new, &tc)]));
        negated.push(not(&invariant_b(&w, &replaced(&q, p, new.clone()), &tt)));
        // Monotonicity against the second vector z.
        let below: Vec<String> = w.updatable().iter().map(|&r| le(&q[r], &q2[r])).collect();
        negated.push(and(&[and(&below), gt(&new, &w.updated(&q2, p))]));
        // Q <= Q* preserved.
        let under: Vec<String> = w
            .updatable()
            .iter()
            .map(|&r| le(&q[r], &w.qstar[r]))
            .collect();
        negated.push(and(&[and(&under), gt(&new, &w.qstar[p])]));
    }
    let ups = w.updatable();
    if !ups.is_empty() {
        let top: Vec<String> = ups.iter().map(|&p| w.qstar[p].clone()).collect();
        let under: Vec<String> = ups.iter().map(|&r| le(&q[r], &w.qstar[r])).collect();
        let exact: Vec<String> = ups.iter().map(|&r| eq(&q[r], &w.qstar[r])).collect();
        negated.push(and(&[
            ge(&tt, &super::term::max(&top)),
            and(&under),
            not(&and(&exact)),
        ]));
    }
    Some((w.o, or(&negated)))
}

fn structures(scope: Scope) -> Vec<Tiny> {
    let mut out = Vec::new();
    for spec in structure_specs(scope) {
        out.extend(Family::new(&spec).canonical());
    }
    out
}

fn whole_structure_obligations(scope: Scope, r1_offset: i64) -> Vec<Obligation> {
    let mut out = Vec::new();
    let mut first = true;
    for t in structures(scope) {
        let Some((o, neg)) = whole_a(&t, Role::Proof, r1_offset) else {
            continue;
        };
        with_hypotheses(&mut out, o, neg);
        let (o, neg) = whole_b(&t, Role::Proof, true).expect("H1 holds");
        with_hypotheses(&mut out, o, neg);
        if first && t.states() >= 2 {
            // Costs >= c > 0 are needed for Part B (a zero-cost move makes no progress).
            let (mut o, neg) =
                whole_b(&t, Role::Dropped("costs >= c > 0".into()), false).expect("H1 holds");
            o.assert(neg);
            out.push(o);
            first = false;
        }
    }
    out
}

/// C1-corrected: local lemmas for every graph of bounded out-degree, the round count, and
/// the whole-structure steps for every structure of the scope — for the statement's bound
/// [`c1::ROUND_BOUND`].
pub fn corrected(scope: Scope) -> Encoding {
    corrected_with(scope, c1::ROUND_BOUND)
}

/// [`corrected_with`] with `R₁ = offset + max h(f(x,u))` and the statement's ceiling term: a
/// smaller offset than 1 is a planted wrong threshold that the proof must reject.
pub fn corrected_with_round_bound(scope: Scope, offset: i64) -> Encoding {
    corrected_with(
        scope,
        RoundBound {
            r1_offset: offset,
            ..c1::ROUND_BOUND
        },
    )
}

/// The encoding of C1-corrected for the round bound `bound` ([`RoundBound`], the one
/// definition the statement is printed from): Part A's last level is `R₁` and B4's round
/// count is `R`, both as `bound` makes them. A planted bound (`R₁` one lower, or the ceiling
/// minus one) makes some proof obligation satisfiable.
pub fn corrected_with(scope: Scope, bound: RoundBound) -> Encoding {
    let mut obligations = local_lemmas(scope, bound);
    obligations.extend(whole_structure_obligations(scope, bound.r1_offset));
    Encoding {
        claim: CLAIM,
        scope: format!(
            "local lemmas A1, A2, B1-B3 for every graph whose states have <= {} pairs (any number of states); \
B4 (the round count R = max(R1, {}), R1 = {}, integers; costs and levels reals); \
whole-structure steps for every structure with <= {} states and <= 2 moves per state (goal: <= 2 moves), up to \
relabelling, in which every state reaches the goal; every number of rounds (induction on the level r / t, \
docs/proofs/c1.md); costs, initial values, c and t: all reals",
            local_degree(scope),
            bound.ceil_text(),
            bound.r1_text(),
            structure_scope_text(scope)
        ),
        obligations,
        replay: replay_corrected,
    }
}

/// Replays of the corrected claim's satisfiable checks: the dropped hypotheses' failures are
/// local arithmetic facts (no run to replay); a satisfiable *proof* obligation would be a bug
/// in the proof, never a counterexample.
fn replay_corrected(o: &Obligation, m: &Model) -> Replay {
    match o.role {
        Role::Dropped(_) | Role::Hypotheses => Replay::NotApplicable,
        Role::Proof if o.lemma.starts_with("B4: ") => replay_round_count(m),
        _ => Replay::NotConfirmed(
            "a proof obligation of C1-corrected is satisfiable: the lemma is wrong".into(),
        ),
    }
}

/// The structures of the printed claim's search: ≤ 2 states, every state reaching the goal.
fn printed_structures() -> Vec<Tiny> {
    let spec = |states| FamilySpec {
        states,
        initial_fixed: false,
        degree: (1, 2),
        goal_degree: (0, 1),
        costs: vec![0],
        distinct_successors: false,
    };
    let mut out = Vec::new();
    for s in [spec(1), spec(2)] {
        out.extend(Family::new(&s).canonical());
    }
    out
}

/// C1 as printed: on a structure where every state reaches the goal, costs ≥ 0 and initial
/// values `Q₀` (the termination pair's at its optimum 0) that every update leaves unchanged (the termination pair updated as an
/// ordinary zero-cost self-loop) while `Q₀ ≠ Q*`: no fair order ever converges.
pub fn printed() -> Encoding {
    let mut obligations = Vec::new();
    for t in printed_structures() {
        let Some(mut w) = Whole::new(
            PRINTED,
            &t,
            "a fixed point of every update that differs from Q*",
            Role::Printed,
        ) else {
            continue;
        };
        // As printed the termination pair is an ordinary pair: give it a value too.
        let q: Vec<String> = (0..w.pairs.len())
            .map(|p| w.o.declare(&format!("q{p}"), Sort::Real))
            .collect();
        let mut facts = Vec::new();
        for p in 0..w.pairs.len() {
            let y = w.pairs[p].1;
            let succ: Vec<String> = (0..w.pairs.len())
                .filter(|&r| w.pairs[r].0 == y)
                .map(|r| q[r].clone())
                .collect();
            facts.push(eq(&q[p], &sum(&[w.cost[p].clone(), min(&succ)])));
        }
        w.o.assert(and(&facts));
        let differs: Vec<String> = (0..w.pairs.len()).map(|p| ne(&q[p], &w.qstar[p])).collect();
        w.o.assert(or(&differs));
        // The termination pair starts at its optimum, 0: the failure is not (only) that a
        // zero-cost self-loop keeps any value, but a zero-cost cycle started below Q*.
        let terminal = (0..w.pairs.len()).find(|&p| w.pairs[p].2).expect("a goal");
        w.o.assert(eq(&q[terminal], "0.0"));
        obligations.push(w.o);
    }
    Encoding {
        claim: PRINTED,
        scope: "every structure with <= 2 states and <= 2 moves per state (goal: <= 1 move), up to relabelling, \
in which every state reaches the goal; costs >= 0 and initial values: all reals"
            .into(),
        obligations,
        replay: replay_printed,
    }
}

/// Reads the structure back from the obligation (its `structure` is `Tiny::describe`'s text)
/// and the costs and values from the model; scales them to integers; runs the exact
/// derandomized Q-learning oracle under the cyclic order.
fn replay_printed(o: &Obligation, m: &Model) -> Replay {
    let Some(t) = printed_structures()
        .into_iter()
        .find(|t| t.describe() == o.structure)
    else {
        return Replay::NotConfirmed("structure not found".into());
    };
    let pairs = pairs_of(&t);
    let cost_of = |p: usize| -> Option<Rational> {
        if pairs[p].2 {
            Some(Rational::zero())
        } else {
            m.get(&format!("l{p}")).cloned()
        }
    };
    let mut all: Vec<Rational> = Vec::new();
    for p in 0..pairs.len() {
        match (cost_of(p), m.get(&format!("q{p}"))) {
            (Some(c), Some(q)) => {
                all.push(c);
                all.push(q.clone());
            }
            _ => return Replay::NotConfirmed(format!("pair {p} has no value in the model")),
        }
    }
    // Costs (even positions) must fit the oracle's u8 costs, values its i64 range.
    let (scale, ints) = to_common_scale(&all);
    let scaled: Option<Vec<i64>> = ints
        .iter()
        .enumerate()
        .map(|(k, v)| {
            v.to_i64().filter(|v| {
                if k % 2 == 0 {
                    (0..=255).contains(v)
                } else {
                    v.abs() < 1 << 40
                }
            })
        })
        .collect();
    let Some(scaled) = scaled else {
        return Replay::NotConfirmed(VALUES_TOO_LARGE.into());
    };
    // Rebuild the structure with the scaled integer costs.
    let mut lists: Vec<Vec<(u8, u8)>> = vec![Vec::new(); t.states()];
    for (p, &(x, to, terminal)) in pairs.iter().enumerate() {
        if !terminal {
            lists[x].push((to as u8, scaled[2 * p] as u8));
        }
    }
    let concrete = Tiny::from_lists(&lists);
    let q = QProblem::new(&concrete, Terminal::Updated);
    if q.len() != pairs.len() || (0..pairs.len()).any(|p| q.pairs[p].to as usize != pairs[p].1) {
        return Replay::NotConfirmed("pair order differs from the oracle's".into());
    }
    let mut q0 = [0i64; MAX_PAIRS];
    for p in 0..pairs.len() {
        q0[p] = scaled[2 * p + 1];
    }
    match run_q(&q, &q0, Order::Cyclic, 64) {
        Run::Cycles(k, period) => {
            let values: Vec<String> = (0..pairs.len())
                .map(|p| {
                    let (x, to, terminal) = pairs[p];
                    if terminal {
                        format!("Q({x},uT)={}", q0[p])
                    } else {
                        format!("Q({x}->{to})={}", q0[p])
                    }
                })
                .collect();
            let what = format!(
                "Z3's model (scaled by {scale}) replayed: under the cyclic order the round-end values repeat from round {k} (period {period}) without reaching Q*"
            );
            let ce = Counterexample::new(
                &concrete,
                format!("C1 counterexample (smt): {what}"),
                vec![("initial values".into(), values.join(", "))],
                "c1-smt",
            )
            .with_replay(format!(
                "truecost learn --file problems/counterexamples/c1-smt.json --q0 {} --order cyclic --terminal updated --rounds {}",
                (0..pairs.len())
                    .map(|p| q0[p].to_string())
                    .collect::<Vec<_>>()
                    .join(","),
                (k + period + 2).max(4)
            ));
            Replay::Confirmed(what, Some(ce))
        }
        Run::Converged(k) => Replay::NotConfirmed(format!("the oracle converges after {k} rounds")),
        Run::NotWithin(k) => Replay::NotConfirmed(format!("undecided after {k} rounds")),
    }
}

/// Why a model is not replayed when a scaled cost does not fit the oracle's `u8` or a value
/// its `2^40` bound.
const VALUES_TOO_LARGE: &str = "the model's values are too large for the oracle";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_paths_of_a_two_state_problem() {
        // 0 -> 0 (loop), 0 -> 1 (goal): one simple path from 0, the empty one from 1.
        let t = Tiny::from_lists(&[vec![(0, 0), (1, 0)], vec![]]);
        let pairs = pairs_of(&t);
        assert_eq!(pairs.len(), 3);
        assert_eq!(simple_paths(&t, &pairs, 0).len(), 1);
        assert_eq!(simple_paths(&t, &pairs, 1), vec![Vec::<usize>::new()]);
    }

    /// The one-state structure whose goal has one zero-cost self-loop: pairs `(0, uT)` (pair
    /// 0, cost 0, not in the model) and `(0 -> 0)` (pair 1, cost `l1`), as printed_structures
    /// lists it; and a model of its costs and values, all integers (so the common scale is 1).
    fn goal_loop(l1: i64, q0: i64, q1: i64) -> (Obligation, Model) {
        let t = Tiny::from_lists(&[vec![(0, 0)]]);
        assert!(printed_structures()
            .iter()
            .any(|p| p.describe() == t.describe()));
        let o = Obligation::new(PRINTED, "test", &t.describe(), Role::Printed, Logic::QfLra);
        let r = |n: i64| Rational::from_integer(n.into());
        let m = Model {
            values: vec![
                ("l1".into(), r(l1)),
                ("q0".into(), r(q0)),
                ("q1".into(), r(q1)),
            ],
        };
        (o, m)
    }

    fn not_confirmed(l1: i64, q0: i64, q1: i64) -> String {
        let (o, m) = goal_loop(l1, q0, q1);
        match replay_printed(&o, &m) {
            Replay::NotConfirmed(why) => why,
            other => panic!("{other:?}"),
        }
    }

    /// The oracle's costs are `u8`: a scaled cost of 256 (or −1) is refused as too large for
    /// it, not wrapped to 0 (or 255), though a value of 256 is fine. At cost 255 the model
    /// reaches the oracle, which converges: `Q* = (0, 255 + G*(0)) = (0, 255)`; round 1 of
    /// the cyclic order, from `(0, 256)`, sets `Q(0,uT) = 0 + min(0, 256) = 0`, then
    /// `Q(0->0) = 255 + min(0, 256) = 255`: `Q*` after 1 round.
    #[test]
    fn a_cost_beyond_the_oracle_s_u8_is_refused() {
        assert_eq!(not_confirmed(256, 0, 0), VALUES_TOO_LARGE);
        assert_eq!(not_confirmed(-1, 0, 0), VALUES_TOO_LARGE);
        assert_eq!(
            not_confirmed(255, 0, 256),
            "the oracle converges after 1 rounds"
        );
    }

    /// The oracle's values must have magnitude below `2^40`: `2^40` itself (either sign) is
    /// refused, `2^40 − 1` reaches the oracle, which converges: with cost 0, `Q* = (0, 0)`;
    /// round 1 sets `Q(0,uT) = 0 + min(0, 2^40 − 1) = 0`, then `Q(0->0) = 0 + min(0, 2^40 −
    /// 1) = 0`: `Q*` after 1 round.
    #[test]
    fn a_value_of_2_to_the_40_is_refused() {
        assert_eq!(not_confirmed(0, 0, 1 << 40), VALUES_TOO_LARGE);
        assert_eq!(not_confirmed(0, 0, -(1 << 40)), VALUES_TOO_LARGE);
        assert_eq!(
            not_confirmed(0, 0, (1 << 40) - 1),
            "the oracle converges after 1 rounds"
        );
    }
}

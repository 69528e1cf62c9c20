//! SMT encodings of C4 (as printed) and C4-corrected (Proposition 4, episodic equivalence;
//! docs/spec.md §6 C4). The argument is written in `docs/proofs/c4.md`.
//!
//! The *structure* of a problem (which state has which moves) is enumerated outside the
//! solver with [`crate::claims::tiny::Family`] (one cost value, so it enumerates shapes up to
//! relabelling) and reduced to the part reachable from `x1` ([`Shape`]); every move's cost is
//! then a symbolic real `c_i ≥ 0` and the bonus a symbolic real `M < 0`.
//!
//! For one shape, the proof obligation says: some simple goal path `p` is an optimal
//! single-shot path (every tie is a case, so every `S*` is covered), and *π\* is average-cost
//! optimal* (the independent side: every stationary policy of the reset problem enumerated
//! explicitly, its average from `x1` a reset cycle `(L(u)+M)/S(u)` or a goal-avoiding cycle
//! `W(C)/|C|`, cross-multiplied by the positive constant lengths) differs from *M lies in the
//! corrected interval* (the statement's `T(u)`, `max`, `min`, `Lav(Ĉ)` as written, with its
//! empty-set conventions). `unsat` for every shape is the proof on the scope.
//!
//! Trust checks: the hypotheses are satisfiable (per shape); dropping the cycle term
//! `S*·Lav(Ĉ) − L*` is satisfiable on every shape with a reachable goal-avoiding cycle, and
//! its model replays as a failure; C4 as printed (claim `C4`, nonlinear: `A(u)` divides by
//! `L(u)`) is satisfiable and its model replays as the counterexample. Every model is replayed
//! through the exact oracle [`crate::claims::c4::bonus_sets`] after scaling its rationals to
//! integers (averages are homogeneous of degree 1 in the costs and `M`, so the exact set of
//! the scaled instance is the scaled exact set).

use std::collections::HashSet;

use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive, Zero};

use super::term::{self, and, app, eq, ge, le, lt, not, or, real, real_int, sum};
use super::{Encoding, Logic, Model, Obligation, Replay, Role, Sort};
use crate::claims::c4::{bonus_sets, Instance, Interval};
use crate::claims::exact::Q;
use crate::claims::tiny::{Family, FamilySpec};
use crate::claims::{Counterexample, Scope};
use crate::model::{Move, Problem};
use crate::value::Rational;

/// The claim id of the corrected statement.
pub const CORRECTED_ID: &str = "C4-corrected";
/// The claim id of the printed statement.
pub const PRINTED_ID: &str = "C4";

const LEMMA_CORRECTED: &str = "pi* average-cost optimal <=> M in the corrected interval";
const LEMMA_PRINTED: &str = "pi* average-cost optimal <=> M in the printed interval";
const LEMMA_PRINTED_POSITIVE: &str =
    "pi* average-cost optimal <=> M in the printed interval (every cost > 0)";
const LEMMA_PLANTED: &str =
    "pi* average-cost optimal <=> M in a planted wrong interval (moves for states in T(u))";
const CYCLE_TERM: &str = "the cycle term S*.Lav(C^) - L*";

/// The part of a structure reachable from `x1`, relabelled canonically: states `0..n`,
/// `x1 = 0`, the goal `n − 1` (no moves: reaching it resets to `x1`), every other state with
/// one or two moves. Move `i` is `edges[i]` and its cost is the real unknown `c{i}`.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Shape {
    /// Number of states.
    pub n: usize,
    /// The moves `(from, to)`, sorted.
    pub edges: Vec<(usize, usize)>,
}

/// A simple path from `x1` to the goal, or a simple goal-avoiding cycle: its moves and its
/// length (`S(u)` = number of states for a path, number of moves for a cycle).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Walk {
    /// Indices of the moves, in order.
    pub edges: Vec<usize>,
    /// `S(u)` for a goal path (states on it), `|C|` for a cycle (moves on it).
    pub len: usize,
}

/// The average-cost outcome of one stationary policy followed from `x1`.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Outcome {
    /// It reaches the goal along this simple path and resets: average `(L(u) + M)/S(u)`.
    Reset(Walk),
    /// It ends on this goal-avoiding cycle: average `W(C)/|C|`.
    Cycle(Walk),
}

impl Shape {
    /// The goal.
    pub fn goal(&self) -> usize {
        self.n - 1
    }

    fn out(&self, x: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.edges
            .iter()
            .enumerate()
            .filter(move |(_, &(a, _))| a == x)
            .map(|(i, &(_, b))| (i, b))
    }

    /// Every simple path from `x1` to the goal (`len` = number of states on it).
    ///
    /// ```
    /// use truecost::claims::smt::c4::Shape;
    /// let s = Shape { n: 3, edges: vec![(0, 1), (0, 2), (1, 2)] };
    /// let lens: Vec<usize> = s.goal_paths().iter().map(|p| p.len).collect();
    /// assert_eq!(lens, vec![3, 2]);
    /// ```
    pub fn goal_paths(&self) -> Vec<Walk> {
        fn dfs(
            s: &Shape,
            x: usize,
            on: &mut Vec<bool>,
            path: &mut Vec<usize>,
            out: &mut Vec<Walk>,
        ) {
            if x == s.goal() {
                out.push(Walk {
                    edges: path.clone(),
                    len: path.len() + 1,
                });
                return;
            }
            let next: Vec<(usize, usize)> = s.out(x).collect();
            for (i, y) in next {
                if !on[y] {
                    on[y] = true;
                    path.push(i);
                    dfs(s, y, on, path, out);
                    path.pop();
                    on[y] = false;
                }
            }
        }
        let mut out = Vec::new();
        let mut on = vec![false; self.n];
        on[0] = true;
        dfs(self, 0, &mut on, &mut Vec::new(), &mut out);
        out
    }

    /// Every simple goal-avoiding cycle (each once, started at its least state; parallel moves
    /// give distinct cycles). Every non-goal state of a shape is reachable from `x1`.
    pub fn cycles(&self) -> Vec<Walk> {
        fn dfs(
            s: &Shape,
            start: usize,
            x: usize,
            on: &mut Vec<bool>,
            path: &mut Vec<usize>,
            out: &mut Vec<Walk>,
        ) {
            let next: Vec<(usize, usize)> = s.out(x).collect();
            for (i, y) in next {
                if y == start {
                    path.push(i);
                    out.push(Walk {
                        edges: path.clone(),
                        len: path.len(),
                    });
                    path.pop();
                } else if y > start && y != s.goal() && !on[y] {
                    on[y] = true;
                    path.push(i);
                    dfs(s, start, y, on, path, out);
                    path.pop();
                    on[y] = false;
                }
            }
        }
        let mut out = Vec::new();
        for start in 0..self.goal() {
            let mut on = vec![false; self.n];
            on[start] = true;
            dfs(self, start, start, &mut on, &mut Vec::new(), &mut out);
        }
        out
    }

    /// The distinct outcomes of every stationary policy (one move chosen at each non-goal
    /// state), followed from `x1` until it resets at the goal or closes a cycle.
    pub fn policy_outcomes(&self) -> Vec<Outcome> {
        let choices: Vec<Vec<(usize, usize)>> =
            (0..self.goal()).map(|x| self.out(x).collect()).collect();
        let mut pick = vec![0usize; choices.len()];
        let mut seen = HashSet::new();
        let mut out = Vec::new();
        loop {
            let mut at = vec![usize::MAX; self.n];
            let mut moves = Vec::new();
            let mut x = 0;
            let outcome = loop {
                if x == self.goal() {
                    let len = moves.len() + 1;
                    break Outcome::Reset(Walk { edges: moves, len });
                }
                if at[x] != usize::MAX {
                    let cyc: Vec<usize> = moves[at[x]..].to_vec();
                    let len = cyc.len();
                    break Outcome::Cycle(Walk { edges: cyc, len });
                }
                at[x] = moves.len();
                let (i, y) = choices[x][pick[x]];
                moves.push(i);
                x = y;
            };
            if seen.insert(outcome.clone()) {
                out.push(outcome);
            }
            let mut k = 0;
            loop {
                if k == pick.len() {
                    return out;
                }
                pick[k] += 1;
                if pick[k] < choices[k].len() {
                    break;
                }
                pick[k] = 0;
                k += 1;
            }
        }
    }

    /// `x1 = 0, goal 2; moves: c0 0->1, c1 0->2, c2 1->2` (read back by [`Shape::parse`]).
    pub fn describe(&self) -> String {
        let moves: Vec<String> = self
            .edges
            .iter()
            .enumerate()
            .map(|(i, (a, b))| format!("c{i} {a}->{b}"))
            .collect();
        format!("x1 = 0, goal {}; moves: {}", self.goal(), moves.join(", "))
    }

    /// Reads a shape back from [`Shape::describe`].
    ///
    /// ```
    /// use truecost::claims::smt::c4::Shape;
    /// let s = Shape { n: 3, edges: vec![(0, 0), (0, 2)] };
    /// assert_eq!(Shape::parse(&s.describe()), Some(s));
    /// ```
    pub fn parse(text: &str) -> Option<Shape> {
        let rest = text.strip_prefix("x1 = 0, goal ")?;
        let (goal, moves) = rest.split_once("; moves: ")?;
        let n = goal.parse::<usize>().ok()? + 1;
        let mut edges = Vec::new();
        for (i, m) in moves.split(", ").enumerate() {
            let (name, arc) = m.split_once(' ')?;
            if name != format!("c{i}") {
                return None;
            }
            let (a, b) = arc.split_once("->")?;
            let (a, b) = (a.parse::<usize>().ok()?, b.parse::<usize>().ok()?);
            if a >= n - 1 || b >= n {
                return None;
            }
            edges.push((a, b));
        }
        Some(Shape { n, edges })
    }
}

/// The canonical reachable part of a structure (Proposition 4 concerns only what is reachable
/// from `x1`: structures up to relabelling), given as per-state successor lists (state 0 is
/// `x1`, the last state the goal): `None` when the goal is not reachable (no single-shot path,
/// so no `π*`: the claim says nothing). States other than `x1` and the goal are relabelled
/// to the lexicographically least adjacency.
pub fn reachable_shape(succ: &[Vec<usize>]) -> Option<Shape> {
    let n = succ.len();
    let goal = n - 1;
    let mut reach = vec![false; n];
    reach[0] = true;
    let mut stack = vec![0];
    while let Some(x) = stack.pop() {
        if x == goal {
            continue;
        }
        for &y in &succ[x] {
            if !reach[y] {
                reach[y] = true;
                stack.push(y);
            }
        }
    }
    if !reach[goal] || goal == 0 {
        return None;
    }
    let middle: Vec<usize> = (1..goal).filter(|&x| reach[x]).collect();
    let m = middle.len();
    let mut best: Option<Vec<(usize, usize)>> = None;
    for perm in permutations(m) {
        // label[old] = new
        let mut label = vec![usize::MAX; n];
        label[0] = 0;
        label[goal] = m + 1;
        for (k, &x) in middle.iter().enumerate() {
            label[x] = perm[k] + 1;
        }
        let mut edges: Vec<(usize, usize)> = Vec::new();
        for x in 0..goal {
            if reach[x] {
                for &y in &succ[x] {
                    edges.push((label[x], label[y]));
                }
            }
        }
        edges.sort_unstable();
        if best.as_ref().is_none_or(|b| edges < *b) {
            best = Some(edges);
        }
    }
    Some(Shape {
        n: m + 2,
        edges: best.expect("at least the identity"),
    })
}

fn permutations(m: usize) -> Vec<Vec<usize>> {
    if m == 0 {
        return vec![Vec::new()];
    }
    let mut out = Vec::new();
    for p in permutations(m - 1) {
        for pos in 0..=p.len() {
            let mut q = p.clone();
            q.insert(pos, m - 1);
            out.push(q);
        }
    }
    out
}

/// The scope of the C4 proofs: every distinct reachable shape of the
/// structures with `2..=max_states` states (x1 = 0,
/// goal last with no moves, 1–2 moves per other state, parallel moves and self-loops
/// allowed), enumerated up to relabelling by [`Family`] with one cost value; with the number
/// of canonical structures enumerated.
pub fn shapes(max_states: usize) -> (Vec<Shape>, u64) {
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    let mut structures = 0u64;
    for states in 2..=max_states {
        let spec = FamilySpec {
            states,
            initial_fixed: true,
            degree: (1, 2),
            goal_degree: (0, 0),
            costs: vec![0],
            distinct_successors: false,
        };
        let family = Family::new(&spec);
        for t in family.canonical() {
            structures += 1;
            let succ: Vec<Vec<usize>> = (0..t.states())
                .map(|x| t.moves(x).iter().map(|mv| mv.to as usize).collect())
                .collect();
            if let Some(s) = reachable_shape(&succ) {
                if seen.insert(s.clone()) {
                    out.push(s);
                }
            }
        }
    }
    (out, structures)
}

/// Which interval of `M` the encoding compares with the exact optimality of `π*`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formula {
    /// C4-corrected as stated ([`crate::claims::c4::CORRECTED`]).
    Corrected,
    /// C4-corrected without the cycle term `S*·Lav(Ĉ) − L*` (a trust check: must fail).
    WithoutCycleTerm,
    /// C4 as printed ([`crate::claims::c4::STATEMENT`]): `A(u)` thresholds (nonlinear).
    Printed,
    /// A planted wrong threshold for the mutation test: `T(u)` counted in moves instead of
    /// states, `((S*−1)·L(u) − (S(u)−1)·L*)/(S(u) − S*)` (the reset as a free stage).
    Planted,
}

fn var(i: usize) -> String {
    format!("c{i}")
}

fn cost_of(w: &Walk) -> String {
    sum(&w.edges.iter().map(|&i| var(i)).collect::<Vec<_>>())
}

fn coef(k: i64) -> String {
    real_int(k)
}

fn times(k: i64, t: &str) -> String {
    app("*", &[coef(k), t.to_string()])
}

fn times_q(q: &Rational, t: &str) -> String {
    app("*", &[real(q), t.to_string()])
}

fn ratio(a: i64, b: i64) -> Rational {
    Rational::new(BigInt::from(a), BigInt::from(b))
}

/// The shape's data for one obligation.
struct Parts {
    paths: Vec<Walk>,
    cycles: Vec<Walk>,
    outcomes: Vec<Outcome>,
}

impl Parts {
    fn of(s: &Shape) -> Parts {
        Parts {
            paths: s.goal_paths(),
            cycles: s.cycles(),
            outcomes: s.policy_outcomes(),
        }
    }

    /// The moves that appear in some goal path or cycle (no other move's cost enters any
    /// average from `x1`: a move on neither lies only on lasso prefixes).
    fn relevant(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .paths
            .iter()
            .chain(&self.cycles)
            .flat_map(|w| w.edges.iter().copied())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// The independent side for the case `π* = p`: every stationary policy's average from `x1`
/// is at least `(L* + M)/S*`, cross-multiplied by the positive lengths.
fn optimal(parts: &Parts, p: &Walk) -> String {
    let ls = cost_of(p);
    let sp = p.len as i64;
    let lhs = |k: i64| times(k, &sum(&[ls.clone(), "M".into()]));
    and(&parts
        .outcomes
        .iter()
        .map(|o| match o {
            Outcome::Reset(u) => le(
                &lhs(u.len as i64),
                &times(sp, &sum(&[cost_of(u), "M".into()])),
            ),
            Outcome::Cycle(c) => le(&lhs(c.len as i64), &times(sp, &cost_of(c))),
        })
        .collect::<Vec<_>>())
}

/// `T(u) = (S*·L(u) − S(u)·L*) / (S(u) − S*)` (or the planted variant).
fn t_of(u: &Walk, p: &Walk, planted: bool) -> String {
    let (su, sp) = (u.len as i64, p.len as i64);
    let (a, b) = if planted { (sp - 1, su - 1) } else { (sp, su) };
    let num = term::sub(&times(a, &cost_of(u)), &times(b, &cost_of(p)));
    times_q(&ratio(1, su - sp), &num)
}

/// `A(u) = (1 − S(u)/S*)·(S(u)·L*/(S*·L(u)) − 1)` as printed (divides by `L(u)`).
fn a_of(u: &Walk, p: &Walk) -> String {
    let (su, sp) = (u.len as i64, p.len as i64);
    let first = term::sub("1.0", &real(&ratio(su, sp)));
    let inner = app("/", &[times(su, &cost_of(p)), times(sp, &cost_of(u))]);
    app("*", &[first, term::sub(&inner, "1.0")])
}

/// The formula side for the case `π* = p`: `M` lies in the formula's interval.
fn in_interval(parts: &Parts, p: &Walk, f: Formula) -> String {
    let sp = p.len as i64;
    let threshold = |u: &Walk| match f {
        Formula::Printed => a_of(u, p),
        Formula::Planted => t_of(u, p, true),
        _ => t_of(u, p, false),
    };
    let shorter: Vec<String> = parts
        .paths
        .iter()
        .filter(|u| u.len < p.len)
        .map(threshold)
        .collect();
    let mut upper: Vec<String> = parts
        .paths
        .iter()
        .filter(|u| u.len > p.len)
        .map(threshold)
        .collect();
    if f != Formula::WithoutCycleTerm && !parts.cycles.is_empty() {
        let means: Vec<String> = parts
            .cycles
            .iter()
            .map(|c| times_q(&ratio(1, c.len as i64), &cost_of(c)))
            .collect();
        let lav = term::min(&means);
        upper.push(term::sub(&times(sp, &lav), &cost_of(p)));
    }
    let mut parts_ = vec![lt("M", "0.0")];
    if !shorter.is_empty() {
        parts_.push(le(&term::max(&shorter), "M"));
    }
    if !upper.is_empty() {
        parts_.push(le("M", &term::min(&upper)));
    }
    and(&parts_)
}

/// `p` is an optimal single-shot path: `L(p) ≤ L(u)` for every simple goal path `u`.
fn single_shot_optimal(parts: &Parts, p: &Walk) -> Vec<String> {
    parts
        .paths
        .iter()
        .filter(|u| *u != p)
        .map(|u| le(&cost_of(p), &cost_of(u)))
        .collect()
}

/// One shape's obligation for Proposition 4, comparing exact average-cost
/// optimality of `π*` with `f`'s interval, for every choice
/// of `π*` among the optimal single-shot paths (one disjunct per choice), or `None` when no
/// case can differ syntactically (for `Printed`: no two goal paths of different lengths).
///
/// `role` selects the assertion set: `Proof`, `Dropped`, `Printed` assert hypotheses ∧
/// ¬conclusion; `Hypotheses` asserts the hypotheses alone.
pub fn obligation(claim: &str, shape: &Shape, f: Formula, role: Role) -> Option<Obligation> {
    let parts = Parts::of(shape);
    if parts.paths.is_empty() {
        return None;
    }
    let (lemma, logic) = match f {
        Formula::Corrected | Formula::WithoutCycleTerm => (LEMMA_CORRECTED, Logic::QfLra),
        Formula::Planted => (LEMMA_PLANTED, Logic::QfLra),
        Formula::Printed => (LEMMA_PRINTED, Logic::QfNra),
    };
    let mut ob = Obligation::new(claim, lemma, &shape.describe(), role.clone(), logic);
    for i in parts.relevant() {
        let c = ob.declare(&var(i), Sort::Real);
        ob.assert(ge(&c, "0.0"));
    }
    let m = ob.declare("M", Sort::Real);
    ob.assert(lt(&m, "0.0"));
    let mut cases = Vec::new();
    for p in &parts.paths {
        let mut hyp = single_shot_optimal(&parts, p);
        if f == Formula::Printed {
            // The printed formula is defined only when L(u) > 0 wherever it divides.
            for u in parts.paths.iter().filter(|u| u.len != p.len) {
                hyp.push(app(">", &[cost_of(u), "0.0".into()]));
            }
        }
        if role == Role::Hypotheses {
            cases.push(and(&hyp));
        } else {
            let differ = not(&eq(&optimal(&parts, p), &in_interval(&parts, p, f)));
            hyp.push(differ);
            cases.push(and(&hyp));
        }
    }
    if f == Formula::Printed && !parts.paths.iter().any(|u| u.len != parts.paths[0].len) {
        return None;
    }
    if f == Formula::WithoutCycleTerm && parts.cycles.is_empty() {
        return None;
    }
    ob.assert(or(&cases));
    Some(ob)
}

/// The states bound of the scope: smoke 3, quick 5, full 5 (≤ 5 states takes ≈ 175 s of CPU:
/// the per-obligation cost, not the solving, dominates; see `docs/proofs/c4.md`).
fn max_states(scope: Scope) -> usize {
    match scope {
        Scope::Smoke => 3,
        Scope::Quick => 5,
        Scope::Full => 5,
    }
}

/// Removes obligations whose declarations and assertions are identical to an earlier one
/// (the first shape stands for them); returns how many were removed.
fn dedupe(obs: &mut Vec<Obligation>) -> usize {
    let before = obs.len();
    let mut seen = HashSet::new();
    obs.retain(|o| {
        let names: Vec<&str> = o.decls.iter().map(|(n, _)| n.as_str()).collect();
        seen.insert((o.role.name(), names.join(" "), o.asserts.clone()))
    });
    before - obs.len()
}

/// The obligations of one formula over `shapes` (proof, hypotheses and — for the corrected
/// formula — the dropped-cycle-term trust checks), deduplicated.
pub fn corrected_obligations(shapes: &[Shape], f: Formula) -> (Vec<Obligation>, usize) {
    let mut obs = Vec::new();
    for s in shapes {
        if let Some(o) = obligation(CORRECTED_ID, s, f, Role::Proof) {
            obs.push(o);
        }
        if let Some(o) = obligation(CORRECTED_ID, s, f, Role::Hypotheses) {
            obs.push(o);
        }
        if f == Formula::Corrected {
            if let Some(o) = obligation(
                CORRECTED_ID,
                s,
                Formula::WithoutCycleTerm,
                Role::Dropped(CYCLE_TERM.into()),
            ) {
                obs.push(o);
            }
        }
    }
    let removed = dedupe(&mut obs);
    (obs, removed)
}

/// The SMT encoding of **C4-corrected**: for every reachable shape of the
/// structures with ≤ 5 states (`Scope::Full` and `Scope::Quick`; smoke: ≤ 3), every real cost ≥ 0 and every real `M < 0`, and
/// every choice of `π*` among the optimal single-shot paths: `π*` is average-cost optimal ⟺
/// `M` lies in the corrected interval. With the trust checks (hypotheses satisfiable, the
/// cycle term dropped).
pub fn encoding(scope: Scope) -> Encoding {
    encoding_with(scope, Formula::Corrected)
}

/// [`encoding`] with another formula in place of the corrected one: `Formula::Planted` is
/// the mutation test (its proof obligations must become `sat` and replay).
pub fn encoding_with(scope: Scope, f: Formula) -> Encoding {
    let n = max_states(scope);
    let (shapes, structures) = shapes(n);
    let (obligations, removed) = corrected_obligations(&shapes, f);
    let proofs = obligations.iter().filter(|o| o.role == Role::Proof).count();
    let scope_text = format!(
        "every structure with <= {n} states and 1-2 moves per non-goal state (x1 = state 0, goal = last state with no \
moves, parallel moves and self-loops allowed), up to relabelling: {structures} structures enumerated outside the solver \
(claims::tiny, one cost value), reduced to the part reachable from x1 with the goal reachable: {} distinct shapes; \
every move's cost a real >= 0, bonus M a real < 0; every optimal single-shot path as pi* (ties: each one, so every S*); \
one obligation per shape ({proofs} proof obligations after removing {removed} identical obligations); costs and \
bonuses: all reals",
        shapes.len()
    );
    Encoding {
        claim: CORRECTED_ID,
        scope: scope_text,
        obligations,
        replay,
    }
}

/// The SMT encoding of **C4 as printed**: for every reachable shape with ≤ 3 states (smoke,
/// quick) or ≤ 4 (full) that has two goal paths of different lengths, the printed statement
/// is satisfiable-false (`Role::Printed`, nonlinear), plus the smallest such shape with every
/// cost > 0; each model replays as a counterexample.
pub fn encoding_printed(scope: Scope) -> Encoding {
    let n = match scope {
        Scope::Smoke | Scope::Quick => 3,
        Scope::Full => 4,
    };
    let (shapes, _) = shapes(n);
    let mut obligations: Vec<Obligation> = shapes
        .iter()
        .filter_map(|s| obligation(PRINTED_ID, s, Formula::Printed, Role::Printed))
        .collect();
    let count = obligations.len();
    if let Some(first) = obligations.first().cloned() {
        let mut o = first;
        o.lemma = LEMMA_PRINTED_POSITIVE.into();
        let vars: Vec<String> = o
            .decls
            .iter()
            .map(|(v, _)| v.clone())
            .filter(|v| v != "M")
            .collect();
        for v in vars {
            o.assert(app(">", &[v, "0.0".into()]));
        }
        obligations.push(o);
    }
    Encoding {
        claim: PRINTED_ID,
        scope: format!(
            "every structure with <= {n} states and 1-2 moves per non-goal state, up to relabelling, whose part \
reachable from x1 has two goal paths of different lengths ({count} shapes), plus the first with every cost > 0; costs \
real >= 0 (L(u) > 0 where A(u) divides by it), bonus M real < 0: each obligation must be sat and its model replay"
        ),
        obligations,
        replay,
    }
}

fn to_q(r: &Rational) -> Option<Q> {
    let n = r.numer().to_i128()?;
    let d = r.denom().to_i128()?;
    let bound = 1i128 << 40;
    (n.abs() < bound && d < bound).then(|| Q::new(n, d))
}

/// The formula's interval of `M` at exact costs, for the case `π* = p` (evaluated exactly,
/// to confirm a model of the encoding).
fn formula_interval(shape: &Shape, costs: &[Q], p: &Walk, f: Formula) -> Option<Interval> {
    let l = |w: &Walk| w.edges.iter().fold(Q::ZERO, |a, &i| a + costs[i]);
    let (ls, sp) = (l(p), p.len as i128);
    let mut iv = Interval::negative();
    for u in shape.goal_paths() {
        if u.len == p.len {
            continue;
        }
        let su = u.len as i128;
        let t = match f {
            Formula::Printed => {
                if l(&u).is_zero() {
                    return None;
                }
                (Q::ONE - Q::new(su, sp)) * (Q::int(su) * ls / (Q::int(sp) * l(&u)) - Q::ONE)
            }
            Formula::Planted => (Q::int(sp - 1) * l(&u) - Q::int(su - 1) * ls) / Q::int(su - sp),
            _ => (Q::int(sp) * l(&u) - Q::int(su) * ls) / Q::int(su - sp),
        };
        if u.len < p.len {
            iv.at_least(t);
        } else {
            iv.at_most(t);
        }
    }
    if f != Formula::WithoutCycleTerm {
        if let Some(lav) = shape
            .cycles()
            .iter()
            .map(|c| l(c) / Q::int(c.len as i128))
            .min()
        {
            iv.at_most(Q::int(sp) * lav - ls);
        }
    }
    Some(iv)
}

/// Replays a `sat` model (exact rationals) through the exact oracle
/// [`crate::claims::c4::bonus_sets`]: the costs and `M` are scaled by the least common
/// denominator to integers (the exact set of the scaled instance is the scaled exact set);
/// the model is confirmed when, for some optimal single-shot path, `π*`'s exact optimality at
/// `M` differs from membership of `M` in the encoded formula's interval (evaluated exactly at
/// the model's own costs: the printed `A(u)` is not homogeneous).
pub fn replay(ob: &Obligation, model: &Model) -> Replay {
    let f = match (&ob.role, ob.claim.as_str()) {
        (Role::Hypotheses, _) => return Replay::NotApplicable,
        (_, PRINTED_ID) => Formula::Printed,
        (Role::Dropped(_), _) => Formula::WithoutCycleTerm,
        _ if ob.lemma == LEMMA_PLANTED => Formula::Planted,
        _ => Formula::Corrected,
    };
    let Some(shape) = Shape::parse(&ob.structure) else {
        return Replay::NotConfirmed(format!("cannot read the structure {:?}", ob.structure));
    };
    let zero = Rational::zero();
    let costs: Vec<Rational> = (0..shape.edges.len())
        .map(|i| model.get(&var(i)).cloned().unwrap_or_else(|| zero.clone()))
        .collect();
    let Some(m) = model.get("M").cloned() else {
        return Replay::NotConfirmed("the model has no M".into());
    };
    if !m.is_negative() || costs.iter().any(|c| c.is_negative()) {
        return Replay::NotConfirmed(format!("{BREAKS_A_HYPOTHESIS} (M = {m})"));
    }
    // Scale to integers (costs, then M, on one scale d).
    let mut values = costs.clone();
    values.push(m.clone());
    let (d, ints) = crate::value::to_common_scale(&values);
    let int = |n: &BigInt| n.to_i64().filter(|v| v.abs() < 1 << 40);
    let scaled: Option<Vec<i64>> = ints[..costs.len()].iter().map(int).collect();
    let (Some(scaled), Some(m_scaled)) = (scaled, int(&ints[costs.len()])) else {
        return Replay::NotConfirmed(TOO_LARGE_TO_REPLAY.into());
    };
    let (Some(qcosts), Some(qm)) = (costs.iter().map(to_q).collect::<Option<Vec<Q>>>(), to_q(&m))
    else {
        return Replay::NotConfirmed(TOO_LARGE_TO_REPLAY.into());
    };
    let mut moves = vec![Vec::new(); shape.n];
    for (i, &(a, b)) in shape.edges.iter().enumerate() {
        moves[a].push((b, scaled[i]));
    }
    let inst = Instance {
        initial: 0,
        is_goal: (0..shape.n).map(|x| x == shape.goal()).collect(),
        moves,
    };
    let sets = match bonus_sets(&inst, 1 << 20) {
        Ok(Some(s)) => s,
        Ok(None) => return Replay::NotConfirmed("the oracle finds no goal path".into()),
        Err(e) => return Replay::NotConfirmed(format!("oracle cross-check failed: {e}")),
    };
    let d_q = match d.to_i128() {
        Some(v) => Q::int(v),
        None => return Replay::NotConfirmed("scale too large".into()),
    };
    let mq = Q::int(m_scaled as i128);
    let paths = shape.goal_paths();
    let lstar = paths
        .iter()
        .map(|p| p.edges.iter().fold(Q::ZERO, |a, &i| a + qcosts[i]))
        .min();
    for s in &sets {
        // The oracle's own corrected set must agree with this evaluation (scaled).
        let Some(p) = paths.iter().find(|p| {
            p.len as i64 == s.optimal_states
                && Some(p.edges.iter().fold(Q::ZERO, |a, &i| a + qcosts[i])) == lstar
        }) else {
            return Replay::NotConfirmed(format!("no optimal path with S* = {}", s.optimal_states));
        };
        let Some(mine) = formula_interval(&shape, &qcosts, p, f) else {
            continue; // printed formula undefined for this S*
        };
        if let Some(check) = formula_interval(&shape, &qcosts, p, Formula::Corrected) {
            if check.contains(qm) != s.corrected.contains(mq) {
                return Replay::NotConfirmed(
                    "the corrected formula evaluated here disagrees with the oracle module's"
                        .into(),
                );
            }
        }
        let exact = s.exact.contains(mq);
        let claimed = mine.contains(qm);
        if exact != claimed {
            let what = format!(
                "{}: at M = {m} with costs ({}) and S* = {}, the {} formula says pi* is {} but the exact average-cost \
oracle says it is {}",
                ob.claim,
                costs.iter().map(|c| c.to_string()).collect::<Vec<_>>().join(", "),
                s.optimal_states,
                match f {
                    Formula::Printed => "printed",
                    Formula::Corrected => "corrected",
                    Formula::WithoutCycleTerm => "cycle-term-free",
                    Formula::Planted => "planted",
                },
                if claimed { "optimal" } else { "not optimal" },
                if exact { "optimal" } else { "not optimal" },
            );
            let ce = match ob.role {
                Role::Dropped(_) => None,
                _ => Some(counterexample(&shape, &costs, &m, s, &d_q, &mine, &what, f)),
            };
            return Replay::Confirmed(what, ce);
        }
    }
    Replay::NotConfirmed("the oracle agrees with the formula at the model for every S*".into())
}

#[allow(clippy::too_many_arguments)]
fn counterexample(
    shape: &Shape,
    costs: &[Rational],
    m: &Rational,
    s: &crate::claims::c4::BonusSets,
    d: &Q,
    formula: &Interval,
    what: &str,
    f: Formula,
) -> Counterexample {
    let moves: Vec<Vec<Move>> = (0..shape.n)
        .map(|x| {
            shape
                .edges
                .iter()
                .enumerate()
                .filter(|(_, e)| e.0 == x)
                .map(|(i, e)| Move {
                    successor: e.1,
                    cost: costs[i].clone(),
                })
                .collect()
        })
        .collect();
    let problem =
        Problem::new(moves, 0, vec![shape.goal()]).expect("a shape is a well-formed problem");
    let describe = (0..shape.n)
        .map(|x| {
            let list: Vec<String> = shape
                .edges
                .iter()
                .enumerate()
                .filter(|(_, e)| e.0 == x)
                .map(|(i, e)| format!("->{} ({})", e.1, costs[i]))
                .collect();
            let tag = if x == shape.goal() { " (goal)" } else { "" };
            if list.is_empty() {
                format!("{x}{tag}")
            } else {
                format!("{x}{tag}: {}", list.join(", "))
            }
        })
        .collect::<Vec<_>>()
        .join("; ");
    let unscale = |iv: &Interval| {
        use crate::claims::c4::End;
        let e = |x: End| match x {
            End::Closed(q) => End::Closed(q / *d),
            End::Open(q) => End::Open(q / *d),
            End::Unbounded => End::Unbounded,
        };
        Interval {
            lo: e(iv.lo),
            hi: e(iv.hi),
            empty: iv.empty,
        }
    };
    let lstar = Q::new(s.optimal_cost as i128, 1) / *d;
    let name = if f == Formula::Printed {
        "c4-as-printed-smt"
    } else {
        "c4-corrected-smt"
    };
    Counterexample {
        summary: what.to_string(),
        problem: describe,
        details: vec![
            ("L*".into(), lstar.to_string()),
            ("S*".into(), s.optimal_states.to_string()),
            (
                "Lav(C^)".into(),
                s.least_mean_cycle
                    .map_or("none (+inf)".into(), |q| (q / *d).to_string()),
            ),
            ("bonus M".into(), m.to_string()),
            (
                "exact set of M (oracle, scaled back)".into(),
                unscale(&s.exact).to_string(),
            ),
            ("formula's set".into(), formula.to_string()),
            (
                "replay".into(),
                format!("costs and M scaled by {d} to integers for the oracle"),
            ),
        ],
        file: format!("problems/counterexamples/{name}.json"),
        problem_file: crate::model::file::to_json(&problem, Some(what)) + "\n",
        replay: Some(format!(
            "truecost verify --claim C4 --file problems/counterexamples/{name}.json"
        )),
    }
}

/// Why a model is not replayed when its values, scaled to integers, reach `2^40`.
const TOO_LARGE_TO_REPLAY: &str = "the model's values are too large to replay";
/// Why a model with `M >= 0` or a negative cost is not replayed (followed by its `M`).
const BREAKS_A_HYPOTHESIS: &str = "the model breaks a hypothesis";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_of_three_states_by_hand() {
        // Reachable parts with goal 1 (2 states): 0 has moves from {0->0, 0->1}, multisets of
        // size 1-2 reaching the goal: {01}, {00,01}, {01,01}: 3 shapes.
        let (two, _) = shapes(2);
        assert_eq!(two.len(), 3);
        let three = Shape {
            n: 3,
            edges: vec![(0, 1), (0, 2), (1, 2)],
        };
        assert_eq!(three.cycles().len(), 0);
        assert_eq!(three.policy_outcomes().len(), 2);
        let looped = Shape {
            n: 3,
            edges: vec![(0, 1), (1, 0), (1, 2)],
        };
        assert_eq!(
            looped.cycles(),
            vec![Walk {
                edges: vec![0, 1],
                len: 2
            }]
        );
    }

    #[test]
    fn relabelling_is_canonical() {
        // x1 -> a -> goal and x1 -> b with b a self-loop: both labellings give one shape.
        let a = reachable_shape(&[vec![1, 2], vec![3], vec![2], vec![]]).unwrap();
        let b = reachable_shape(&[vec![2, 1], vec![1], vec![3], vec![]]).unwrap();
        assert_eq!(a, b);
        // The lexicographically least of the two labellings, by hand: the self-loop state
        // labelled 1 gives (1,1) before the other labelling's (1,3).
        assert_eq!(a.edges, [(0, 1), (0, 2), (1, 1), (2, 3)]);
        assert!(reachable_shape(&[vec![0], vec![]]).is_none());
    }

    /// `f`'s interval at exact `costs` when π* is the goal path of `s_star` states.
    fn interval_for(shape: &Shape, costs: &[Q], s_star: usize, f: Formula) -> Option<Interval> {
        let paths = shape.goal_paths();
        let p = paths
            .iter()
            .find(|w| w.len == s_star)
            .expect("a path of S* states");
        formula_interval(shape, costs, p, f)
    }

    /// The formulas' intervals at exact costs, by hand, on `0 → 1 → 2` (c0, c2) and `0 → 2`
    /// (c1) with costs 1, 5, 1: π* = `c0 c2` (L* = 2, S* = 3), the shorter `u = c1` (L = 5,
    /// S = 2) bounds `M` from below, and there is no cycle.
    #[test]
    fn formula_intervals_at_exact_costs_by_hand() {
        let shape = Shape {
            n: 3,
            edges: vec![(0, 1), (0, 2), (1, 2)],
        };
        let costs = [Q::int(1), Q::int(5), Q::int(1)];
        let at = |f: Formula| interval_for(&shape, &costs, 3, f).expect("defined");
        // Planted: ((S* − 1) L(u) − (S(u) − 1) L*) / (S(u) − S*) = (2·5 − 1·2)/(−1) = −8.
        let planted = at(Formula::Planted);
        assert!(planted.contains(Q::int(-8)) && planted.contains(Q::new(-1, 2)));
        assert!(!planted.contains(Q::new(-17, 2)) && !planted.contains(Q::ZERO));
        // Corrected: (S* L(u) − S(u) L*) / (S(u) − S*) = (15 − 4)/(−1) = −11.
        let corrected = at(Formula::Corrected);
        assert!(corrected.contains(Q::int(-11)) && !corrected.contains(Q::new(-23, 2)));
        // Printed: (1 − 2/3)(2·2/(3·5) − 1) = (1/3)(−11/15) = −11/45.
        let printed = at(Formula::Printed);
        assert!(printed.contains(Q::new(-11, 45)) && !printed.contains(Q::new(-12, 45)));
        // A zero L(u) leaves the printed formula undefined.
        let zero = [Q::int(1), Q::ZERO, Q::int(1)];
        assert!(interval_for(&shape, &zero, 3, Formula::Printed).is_none());
    }

    /// A model's value is replayed only below 2^40 in numerator and denominator.
    #[test]
    fn model_values_fit_below_two_to_the_forty() {
        let big = BigInt::from(1i64 << 40);
        let one = BigInt::from(1);
        assert!(to_q(&Rational::new(big.clone(), one.clone())).is_none());
        assert!(to_q(&Rational::new(-big.clone(), one.clone())).is_none());
        assert!(to_q(&Rational::new(one.clone(), big.clone())).is_none());
        let below: BigInt = &big - 1;
        assert_eq!(
            to_q(&Rational::new(below.clone(), one.clone())),
            Some(Q::int((1i128 << 40) - 1))
        );
        assert_eq!(
            to_q(&Rational::new(one, below)),
            Some(Q::new(1, (1i128 << 40) - 1))
        );
    }

    /// `0 -> 1 -> 2 -> 3` (c0, c2, c3) and `0 -> 3` (c1): goal paths of 4 and 2 states, so
    /// `S(u) − S*` is ±2 and a division by it is not a multiplication by it.
    fn two_lengths() -> Shape {
        Shape {
            n: 4,
            edges: vec![(0, 1), (0, 3), (1, 2), (2, 3)],
        }
    }

    fn model(values: &[(&str, Rational)]) -> Model {
        Model {
            values: values
                .iter()
                .map(|(n, v)| (n.to_string(), v.clone()))
                .collect(),
        }
    }

    fn rat(n: i64, d: i64) -> Rational {
        Rational::new(n.into(), d.into())
    }

    /// The formulas' intervals by hand on [`two_lengths`] with costs 1, 10, 1, 1: π* = the
    /// long path (L* = 3, S* = 4), `u` = the direct move (L = 10, S = 2) bounds `M` from
    /// below. Corrected: (4·10 − 2·3)/(2 − 4) = −17. Planted: (3·10 − 1·3)/(−2) = −27/2.
    /// Printed: (1 − 2/4)(2·3/(4·10) − 1) = (1/2)(−17/20) = −17/40.
    #[test]
    fn formula_intervals_divide_by_a_length_difference_of_two() {
        let shape = two_lengths();
        let costs = [Q::int(1), Q::int(10), Q::int(1), Q::int(1)];
        let at = |f: Formula| interval_for(&shape, &costs, 4, f).expect("defined");
        let corrected = at(Formula::Corrected);
        assert!(corrected.contains(Q::int(-17)) && corrected.contains(Q::new(-1, 2)));
        assert!(!corrected.contains(Q::new(-35, 2)) && !corrected.contains(Q::ZERO));
        let planted = at(Formula::Planted);
        assert!(planted.contains(Q::new(-27, 2)) && !planted.contains(Q::int(-14)));
        let printed = at(Formula::Printed);
        assert!(printed.contains(Q::new(-17, 40)) && !printed.contains(Q::new(-18, 40)));
    }

    /// [`Shape::parse`] refuses a move out of the goal (the goal has no moves) and a move to a
    /// state past the goal, and reads a move into the goal from the state before it.
    #[test]
    fn parse_refuses_moves_out_of_the_goal_or_past_it() {
        assert_eq!(Shape::parse("x1 = 0, goal 2; moves: c0 2->0"), None);
        assert_eq!(Shape::parse("x1 = 0, goal 2; moves: c0 0->3"), None);
        assert_eq!(Shape::parse("x1 = 0, goal 2; moves: c0 3->2"), None);
        assert_eq!(
            Shape::parse("x1 = 0, goal 2; moves: c0 1->2, c1 0->1"),
            Some(Shape {
                n: 3,
                edges: vec![(1, 2), (0, 1)]
            })
        );
    }

    /// Which formula a model is replayed against follows the obligation, not the model. On
    /// [`two_lengths`] with costs 1, 10, 1, 1 and `M = −15`: π* (average (3 − 15)/4 = −3) beats
    /// the direct move ((10 − 15)/2 = −5/2), so π* is optimal, and the corrected interval
    /// `[−17, 0)` agrees; the planted one, `[−27/2, 0)`, does not. The corrected proof
    /// obligation's model is no failure, the planted one's is (reported under the corrected
    /// claim's counterexample name), and a hypotheses check is never replayed.
    #[test]
    fn a_model_replays_against_its_own_obligation_s_formula() {
        let shape = two_lengths();
        let m = model(&[
            ("c0", rat(1, 1)),
            ("c1", rat(10, 1)),
            ("c2", rat(1, 1)),
            ("c3", rat(1, 1)),
            ("M", rat(-15, 1)),
        ]);
        let corrected = obligation(CORRECTED_ID, &shape, Formula::Corrected, Role::Proof).unwrap();
        assert!(matches!(replay(&corrected, &m), Replay::NotConfirmed(_)));
        let planted = obligation(CORRECTED_ID, &shape, Formula::Planted, Role::Proof).unwrap();
        let Replay::Confirmed(what, Some(ce)) = replay(&planted, &m) else {
            panic!("the planted formula fails at M = -15");
        };
        assert!(what.contains("planted formula"), "{what}");
        assert_eq!(ce.file, "problems/counterexamples/c4-corrected-smt.json");
        let hyp = obligation(CORRECTED_ID, &shape, Formula::Corrected, Role::Hypotheses).unwrap();
        assert!(matches!(replay(&hyp, &m), Replay::NotApplicable));
    }

    /// A model outside the hypotheses (M ≥ 0, or a negative cost) is not replayed, and neither
    /// is one whose values, scaled to integers, reach 2^40: costs 1/2 and `M = −2^39` scale (by
    /// 2) to `M = −2^40`.
    #[test]
    fn a_model_outside_the_hypotheses_or_the_range_is_not_replayed() {
        let ob = obligation(
            CORRECTED_ID,
            &Shape {
                n: 2,
                edges: vec![(0, 0), (0, 1)],
            },
            Formula::WithoutCycleTerm,
            Role::Dropped(CYCLE_TERM.into()),
        )
        .unwrap();
        let refused = |m: &Model, why: &str| match replay(&ob, m) {
            Replay::NotConfirmed(text) => assert!(text.contains(why), "{text}"),
            _ => panic!("replayed: {m:?}"),
        };
        let zero_m = model(&[("c0", rat(0, 1)), ("c1", rat(1, 1)), ("M", rat(0, 1))]);
        refused(&zero_m, BREAKS_A_HYPOTHESIS);
        let negative_cost = model(&[("c0", rat(-1, 1)), ("c1", rat(1, 1)), ("M", rat(-1, 2))]);
        refused(&negative_cost, BREAKS_A_HYPOTHESIS);
        let far = model(&[
            ("c0", rat(1, 2)),
            ("c1", rat(1, 2)),
            ("M", rat(-(1 << 39), 1)),
        ]);
        refused(&far, TOO_LARGE_TO_REPLAY);
        // The same costs with `M = −2^38` (scaled: −2^39) pass the bound and reach the oracle.
        let near = model(&[
            ("c0", rat(1, 2)),
            ("c1", rat(1, 2)),
            ("M", rat(-(1 << 38), 1)),
        ]);
        assert!(!matches!(replay(&ob, &near), Replay::NotConfirmed(t) if t == TOO_LARGE_TO_REPLAY));
    }

    /// The printed formula's counterexample, by hand, on `0 -> 1 -> 2` (c0 = 1/2, c2 = 1/2)
    /// and `0 -> 2` (c1 = 3/4) at `M = −1/8`: π* is the direct move (L* = 3/4, S* = 2); the
    /// exact condition (3/4 + M)/2 <= (1 + M)/3 is M <= −1/4, while the printed bound is
    /// A(u) = (1 − 3/2)(3·(3/4)/(2·1) − 1) = −1/16. The report gives the problem with the
    /// model's own costs and the exact set in the problem's units (the oracle ran on costs
    /// scaled by 8).
    #[test]
    fn a_printed_failure_s_counterexample_is_the_model_in_its_own_units() {
        let shape = Shape {
            n: 3,
            edges: vec![(0, 1), (0, 2), (1, 2)],
        };
        let ob = obligation(PRINTED_ID, &shape, Formula::Printed, Role::Printed).unwrap();
        let m = model(&[
            ("c0", rat(1, 2)),
            ("c1", rat(3, 4)),
            ("c2", rat(1, 2)),
            ("M", rat(-1, 8)),
        ]);
        let Replay::Confirmed(what, Some(ce)) = replay(&ob, &m) else {
            panic!("the printed formula fails at M = -1/8");
        };
        assert!(
            what.contains("printed formula says pi* is optimal"),
            "{what}"
        );
        assert_eq!(ce.file, "problems/counterexamples/c4-as-printed-smt.json");
        assert_eq!(
            ce.problem,
            "0: ->1 (1/2), ->2 (3/4); 1: ->2 (1/2); 2 (goal)"
        );
        let detail = |k: &str| {
            ce.details
                .iter()
                .find(|(n, _)| n == k)
                .map(|(_, v)| v.clone())
                .unwrap_or_else(|| panic!("no {k}"))
        };
        assert_eq!(detail("L*"), "3/4");
        assert_eq!(detail("S*"), "2");
        assert_eq!(detail("bonus M"), "-1/8");
        assert_eq!(
            detail("exact set of M (oracle, scaled back)"),
            "(-inf, -1/4]"
        );
        assert_eq!(detail("formula's set"), "(-inf, -1/16]");
        let p = crate::model::file::from_json(&ce.problem_file).expect("parses");
        let moves = |x: usize| -> Vec<(usize, Rational)> {
            p.moves(x)
                .iter()
                .map(|mv| (mv.successor, mv.cost.clone()))
                .collect()
        };
        assert_eq!(moves(0), [(1, rat(1, 2)), (2, rat(3, 4))]);
        assert_eq!(moves(1), [(2, rat(1, 2))]);
        assert!(moves(2).is_empty());
        assert_eq!(p.goals(), &[2]);
    }
}

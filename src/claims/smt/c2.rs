//! SMT encoding of claim C2 (docs/spec.md §6, cost–reward equivalence), and the lasso
//! machinery that the C3 encodings share ([`lassos`], [`shape_text`], [`parse_shape`],
//! [`poly_term`]).
//!
//! **Independent formulation.** For a structure (graph shape, enumerated outside the solver up
//! to relabelling with [`crate::claims::tiny::Family`]) every deterministic stationary policy
//! is enumerated explicitly by following it from `x1` ([`lassos`]): its stage sequence from
//! `x1` is a *lasso* — a prefix of moves, then a cycle of moves repeated forever, or termination
//! at the goal (stage cost 0 forever, docs/spec.md §1). Policies with the same lasso have the same value
//! under every functional, so the argmin/argmax sets are unions of lasso classes and it is
//! enough to compare lassos. Every move's stage cost is its own real unknown `l ≥ 0`. Each
//! functional of [`crate::claims::c2::functionals`] is written from the lasso for the cost
//! sequence `l` and, separately, for the reward sequence `r = −l` (each stage negated, the
//! value evaluated afresh, never by negating the cost value); the total is extended-real (a
//! cycle of positive sum is `+∞`, of negative sum `−∞`). The proof obligation of a structure
//! asserts `l ≥ 0` and that for some functional some lasso is a cost minimiser and not a reward
//! maximiser or vice versa: `unsat` proves C2 on that structure for every real cost.

use std::collections::HashSet;

use super::term::{and, app, eq, ge, gt, le, lt, max, mul, not, or, real, real_int, sub, sum};
use super::{Encoding, Logic, Model, Obligation, Replay, Role, Sort};
use crate::algebra::poly::Poly;
use crate::claims::c2::functionals;
use crate::claims::exact::{FracExt, Q};
use crate::claims::oracle::{evaluate_fast, policies, trajectory, Functional, Trajectory};
use crate::claims::tiny::{Family, FamilySpec, Tiny, MAX_STATES};
use crate::claims::Scope;
use crate::value::Rational;

/// A move: `(state, index of the move in the state's list)`.
pub type MoveId = (usize, usize);

/// The stage sequence from `x1` of a class of stationary policies (those that agree on the
/// states the trajectory visits): `prefix`, then `cycle` repeated forever; a terminating lasso
/// has an empty `cycle` and stays at the goal with stage cost 0 (the termination action).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Lasso {
    /// The moves before the cycle.
    pub prefix: Vec<MoveId>,
    /// The moves of the cycle (empty when the lasso terminates).
    pub cycle: Vec<MoveId>,
    /// Whether it ends with the termination action at the goal.
    pub terminates: bool,
    /// Whether it visits the goal.
    pub visits_goal: bool,
}

impl Lasso {
    /// The stage at position `k` (0-based): a move, or `None` for the termination stage (cost 0).
    pub fn stage(&self, k: usize) -> Option<MoveId> {
        if k < self.prefix.len() {
            Some(self.prefix[k])
        } else if self.terminates {
            None
        } else {
            Some(self.cycle[(k - self.prefix.len()) % self.cycle.len()])
        }
    }
}

/// Every lasso from `x1 = 0` of `t`, one per class of stationary policies, found by following
/// the policy and choosing a move (or, at the goal, termination — and the goal's moves when
/// `goal_may_move`) at each state the first time it is reached (docs/spec.md §1). Deterministic order.
///
/// ```
/// use truecost::claims::smt::c2::lassos;
/// use truecost::claims::tiny::Tiny;
/// // x1 = 0 with a self-loop and a move to the goal 1; the goal terminates.
/// let t = Tiny::from_lists(&[vec![(0, 0), (1, 0)], vec![]]);
/// let ls = lassos(&t, true);
/// assert_eq!(ls.len(), 2);
/// assert!(ls[0].cycle == vec![(0, 0)] && !ls[0].visits_goal);
/// assert!(ls[1].terminates && ls[1].prefix == vec![(0, 1)]);
/// ```
pub fn lassos(t: &Tiny, goal_may_move: bool) -> Vec<Lasso> {
    struct Walk<'a> {
        t: &'a Tiny,
        goal_may_move: bool,
        path: Vec<MoveId>,
        position: [Option<usize>; MAX_STATES],
        out: Vec<Lasso>,
    }
    fn visit(w: &mut Walk, x: usize) {
        if let Some(k) = w.position[x] {
            let visits_goal = w.path.iter().any(|&(y, _)| w.t.is_goal(y));
            w.out.push(Lasso {
                prefix: w.path[..k].to_vec(),
                cycle: w.path[k..].to_vec(),
                terminates: false,
                visits_goal,
            });
            return;
        }
        w.position[x] = Some(w.path.len());
        if w.t.is_goal(x) {
            w.out.push(Lasso {
                prefix: w.path.clone(),
                cycle: Vec::new(),
                terminates: true,
                visits_goal: true,
            });
        }
        if !w.t.is_goal(x) || w.goal_may_move {
            for i in 0..w.t.moves(x).len() {
                w.path.push((x, i));
                visit(w, w.t.moves(x)[i].to as usize);
                w.path.pop();
            }
        }
        w.position[x] = None;
    }
    let mut w = Walk {
        t,
        goal_may_move,
        path: Vec::new(),
        position: [None; MAX_STATES],
        out: Vec::new(),
    };
    visit(&mut w, 0);
    w.out
}

/// A structure as one line, `0: ->0 (a), ->1 (b); 1 (goal)`, each move followed by its cost
/// label in parentheses (a number, or the name of the SMT constant that is its cost; `-` for a
/// move no policy from `x1` uses). [`parse_shape`] reads it back.
pub fn shape_text(t: &Tiny, label: impl Fn(MoveId) -> String) -> String {
    t.describe_with(label)
}

/// Reads a [`shape_text`] back: per state, its moves as `(successor, cost label)`.
///
/// ```
/// use truecost::claims::smt::c2::parse_shape;
/// let s = parse_shape("0: ->0 (l1), ->1 (3); 1 (goal)").unwrap();
/// assert_eq!(s, vec![vec![(0, "l1".to_string()), (1, "3".to_string())], vec![]]);
/// ```
pub fn parse_shape(text: &str) -> Option<Vec<Vec<(u8, String)>>> {
    let mut out = Vec::new();
    for (x, part) in text.split("; ").enumerate() {
        let (head, moves) = match part.split_once(": ") {
            Some((h, m)) => (h, Some(m)),
            None => (part, None),
        };
        let id = head.trim_end_matches(" (goal)");
        if id.parse::<usize>().ok()? != x {
            return None;
        }
        let mut list = Vec::new();
        for m in moves
            .map(|m| m.split(", ").collect::<Vec<_>>())
            .unwrap_or_default()
        {
            let m = m.strip_prefix("->")?;
            let (to, label) = m.split_once(" (")?;
            list.push((to.parse().ok()?, label.strip_suffix(')')?.to_string()));
        }
        out.push(list);
    }
    (!out.is_empty() && out.len() <= MAX_STATES).then_some(out)
}

/// A univariate polynomial with rational coefficients as an SMT-LIB term in `var`
/// (`(+ (- 1.0) (* 5.0 a a a a))`).
///
/// ```
/// use truecost::algebra::poly::Poly;
/// use truecost::claims::smt::c2::poly_term;
/// assert_eq!(poly_term(&Poly::from_i64(&[-1, 0, 2]), "a"), "(+ (- 1.0) (* 2.0 a a))");
/// ```
pub fn poly_term(p: &Poly, var: &str) -> String {
    let terms: Vec<String> = p
        .coefficients()
        .iter()
        .enumerate()
        .filter(|(_, c)| !num_traits::Zero::is_zero(*c))
        .map(|(k, c)| {
            if k == 0 {
                real(c)
            } else {
                let mut args = vec![real(c)];
                args.extend(std::iter::repeat_n(var.to_string(), k));
                app("*", &args)
            }
        })
        .collect();
    sum(&terms)
}

/// Integer stage costs scaled from exact rationals: every value times the least common
/// multiple of the denominators (a positive scale, which changes no argmin or argmax of a
/// positively homogeneous functional). `None` if a value is negative or does not fit a `u8`.
pub fn scale_to_u8(values: &[Rational]) -> Option<Vec<u8>> {
    let (_, ints) = crate::value::to_common_scale(values);
    ints.iter().map(|n| u8::try_from(n).ok()).collect()
}

/// The planted faults of the mutation tests and trust checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plant {
    /// The claim as stated: rewards `r = −l`, the registry's linear functionals.
    None,
    /// The reward sequence is the cost sequence itself (`r = l`, not negated).
    RewardNotNegated,
    /// One functional that is not linear: the supremum of the stage values.
    MaxOfStages,
}

impl Plant {
    fn lemma(self) -> &'static str {
        match self {
            Plant::None => LEMMA,
            Plant::RewardNotNegated => LEMMA_NOT_NEGATED,
            Plant::MaxOfStages => LEMMA_MAX,
        }
    }
}

const LEMMA: &str = "argmin cost = argmax reward (r = -l), every functional";
const LEMMA_NOT_NEGATED: &str = "argmin cost = argmax reward, planted: r = l (not negated)";
const LEMMA_MAX: &str = "argmin cost = argmax reward, planted: sup of stages (not linear)";

/// An extended-real value as terms: finite part, and the `+∞` / `−∞` conditions (total only).
struct Value {
    finite: String,
    infinite: Option<(String, String)>,
}

/// `a ≤ b` in the extended reals.
fn le_ext(a: &Value, b: &Value) -> String {
    match (&a.infinite, &b.infinite) {
        (Some((ap, an)), Some((bp, bn))) => or(&[
            an.clone(),
            bp.clone(),
            and(&[not(ap), not(an), not(bp), not(bn), le(&a.finite, &b.finite)]),
        ]),
        _ => le(&a.finite, &b.finite),
    }
}

/// The value of `f` on a lasso's stage sequence, each stage given by `stage` (a term; the
/// termination stage is `0.0`), as SMT terms; `None` is the planted supremum of the stages.
fn lasso_value(f: Option<Functional>, lasso: &Lasso, stage: &dyn Fn(MoveId) -> String) -> Value {
    let st = |k: usize| lasso.stage(k).map_or_else(|| real_int(0), stage);
    let q = |x: Q| real(&x.to_rational());
    let finite = |term: String| Value {
        finite: term,
        infinite: None,
    };
    let p = lasso.prefix.len();
    let cyc: Vec<String> = if lasso.terminates {
        vec![real_int(0)]
    } else {
        lasso.cycle.iter().map(|&m| stage(m)).collect()
    };
    let Some(f) = f else {
        // The planted non-linear functional: the supremum of the stage values (the maximum
        // over the prefix and the cycle).
        let mut all: Vec<String> = (0..p).map(st).collect();
        all.extend(cyc);
        return finite(max(&all));
    };
    match f {
        Functional::Total => {
            let s = sum(&cyc);
            Value {
                finite: sum(&(0..p).map(st).collect::<Vec<_>>()),
                infinite: Some((gt(&s, &real_int(0)), lt(&s, &real_int(0)))),
            }
        }
        Functional::Discounted(a) => {
            // Σ_{k<p} α^k s_k + α^p (Σ_{j<c} α^j c_j) / (1 − α^c), α rational.
            let c = cyc.len() as u32;
            let mut terms: Vec<String> = (0..p).map(|k| mul(&q(a.pow(k as u32)), &st(k))).collect();
            let factor = a.pow(p as u32) / (Q::ONE - a.pow(c));
            terms.extend(
                cyc.iter()
                    .enumerate()
                    .map(|(j, s)| mul(&q(factor * a.pow(j as u32)), s)),
            );
            finite(sum(&terms))
        }
        Functional::Average => {
            let c = cyc.len() as i128;
            finite(sum(&cyc
                .iter()
                .map(|s| mul(&q(Q::new(1, c)), s))
                .collect::<Vec<_>>()))
        }
        Functional::HorizonTotal(h) => finite(sum(&(0..h).map(st).collect::<Vec<_>>())),
        Functional::HorizonDiscounted(h, a) => finite(sum(&(0..h)
            .map(|k| mul(&q(a.pow(k as u32)), &st(k)))
            .collect::<Vec<_>>())),
        Functional::HorizonAverage(h) => finite(sum(&(0..h)
            .map(|k| mul(&q(Q::new(1, h as i128)), &st(k)))
            .collect::<Vec<_>>())),
    }
}

/// Binds every value to a name in an SMT-LIB `let` (standard; the solver shares the terms).
fn bind(name: &str, v: Value, bindings: &mut Vec<String>) -> Value {
    bindings.push(format!("({name} {})", v.finite));
    let infinite = v.infinite.map(|(pos, neg)| {
        bindings.push(format!("({name}_pinf {pos})"));
        bindings.push(format!("({name}_ninf {neg})"));
        (format!("{name}_pinf"), format!("{name}_ninf"))
    });
    Value {
        finite: name.to_string(),
        infinite,
    }
}

/// The largest structures that get the planted-reward trust check (every structure up to
/// this many states with at least two lassos).
pub fn dropped_states(scope: Scope) -> usize {
    match scope {
        Scope::Smoke | Scope::Quick => 2,
        Scope::Full => 3,
    }
}

/// The shapes of a scope (costs enumerated as the single value 0: shapes only).
pub fn shape_specs(scope: Scope) -> Vec<FamilySpec> {
    let max = match scope {
        Scope::Smoke => 2,
        Scope::Quick => 3,
        Scope::Full => 4,
    };
    (1..=max)
        .map(|states| FamilySpec {
            states,
            initial_fixed: true,
            degree: (1, 2),
            goal_degree: (0, 2),
            costs: vec![0],
            distinct_successors: false,
        })
        .collect()
}

/// One structure's C2 obligation (and the cost constants' names per move, `None` for moves
/// no lasso uses). Cost constants are named `l1, l2, …` in the order the lassos first use
/// them, so that shapes whose parts reachable from `x1` agree give the same text.
type Names = Vec<Vec<Option<String>>>;

/// The cost constants' names per move (`l1, l2, …` in the order the lassos first use them;
/// `None` for moves no lasso uses), the moves in that order, and the structure's text.
fn cost_names(t: &Tiny, ls: &[Lasso]) -> (Names, Vec<MoveId>, String) {
    let mut names: Names = (0..t.states())
        .map(|x| vec![None; t.moves(x).len()])
        .collect();
    let mut order = Vec::new();
    for l in ls {
        for &(x, i) in l.prefix.iter().chain(&l.cycle) {
            if names[x][i].is_none() {
                names[x][i] = Some(format!("l{}", order.len() + 1));
                order.push((x, i));
            }
        }
    }
    let structure = shape_text(t, |(x, i)| {
        names[x][i].clone().unwrap_or_else(|| "-".into())
    });
    (names, order, structure)
}

const LEMMA_ALPHA: &str = "argmin cost = argmax reward (r = -l), discounted, every alpha in (0,1)";

/// `α^k · s` as a term (`s` for `k = 0`).
fn times_power(s: &str, k: usize, a: &str) -> String {
    if k == 0 {
        return s.to_string();
    }
    let mut args = vec![s.to_string()];
    args.extend(std::iter::repeat_n(a.to_string(), k));
    app("*", &args)
}

/// One structure's obligation for the discounted functional with the discount a real unknown
/// `α ∈ (0,1)` (QF_NRA): each lasso's value is `N/D` with `D = 1 − α^q` (a terminating lasso:
/// `D = 1`), `N = D·Σ_{k<p} α^k s_k + α^p Σ_{j<q} α^j c_j`; `D > 0` on `(0,1)` (the C3
/// obligations `1 - alpha^q > 0`), so `V_a ≤ V_b ⟺ N_a·D_b ≤ N_b·D_a`.
fn symbolic_alpha_obligation(t: &Tiny, role: Role) -> Obligation {
    let ls = lassos(t, true);
    let (names, order, structure) = cost_names(t, &ls);
    let mut o = Obligation::new("C2", LEMMA_ALPHA, &structure, role, Logic::QfNra);
    for &(x, i) in &order {
        let n = o.declare(names[x][i].as_ref().expect("named"), Sort::Real);
        o.assert(ge(&n, &real_int(0)));
    }
    let a = o.declare("a", Sort::Real);
    o.assert(and(&[gt(&a, &real_int(0)), lt(&a, &real_int(1))]));
    let cost = |m: MoveId| names[m.0][m.1].clone().expect("named");
    let reward = |m: MoveId| app("-", &[cost(m)]);
    let mut bindings = Vec::new();
    let mut fraction = |name: &str, l: &Lasso, stage: &dyn Fn(MoveId) -> String| {
        let series = |moves: &[MoveId]| {
            sum(&moves
                .iter()
                .enumerate()
                .map(|(k, &m)| times_power(&stage(m), k, &a))
                .collect::<Vec<_>>())
        };
        let prefix = series(&l.prefix);
        let (n, d) = if l.terminates {
            (prefix, real_int(1))
        } else {
            let d = sub(&real_int(1), &times_power(&real_int(1), l.cycle.len(), &a));
            let cycle = times_power(&series(&l.cycle), l.prefix.len(), &a);
            (sum(&[mul(&d, &prefix), cycle]), d)
        };
        bindings.push(format!("({name}_n {n})"));
        bindings.push(format!("({name}_d {d})"));
        (format!("{name}_n"), format!("{name}_d"))
    };
    let c: Vec<(String, String)> = ls
        .iter()
        .enumerate()
        .map(|(p, l)| fraction(&format!("c{p}"), l, &cost))
        .collect();
    let r: Vec<(String, String)> = ls
        .iter()
        .enumerate()
        .map(|(p, l)| fraction(&format!("r{p}"), l, &reward))
        .collect();
    let le_frac =
        |x: &(String, String), y: &(String, String)| le(&mul(&x.0, &y.1), &mul(&y.0, &x.1));
    let mut failures = Vec::new();
    for p in 0..ls.len() {
        let minimises = and(&(0..ls.len())
            .map(|s| le_frac(&c[p], &c[s]))
            .collect::<Vec<_>>());
        let maximises = and(&(0..ls.len())
            .map(|s| le_frac(&r[s], &r[p]))
            .collect::<Vec<_>>());
        failures.push(not(&eq(&minimises, &maximises)));
    }
    o.assert(app(
        "let",
        &[format!("({})", bindings.join(" ")), or(&failures)],
    ));
    o
}

/// The largest structures whose discounted functional is proved for every real `α ∈ (0,1)`.
/// Two states in every scope: on 3-state structures Z3 4.8.12's nonlinear procedure ran past
/// the 60 s obligation limit (measured on `0: ->1, ->1; 1: ->2, ->2; 2 (goal): ->0, ->1`), which
/// would leave C2 inconclusive; larger structures are proved at the registry's fixed `α`.
pub fn symbolic_alpha_states(scope: Scope) -> usize {
    match scope {
        Scope::Smoke | Scope::Quick | Scope::Full => 2,
    }
}

fn structure_obligation(t: &Tiny, role: Role, plant: Plant) -> (Obligation, String) {
    let ls = lassos(t, true);
    let (names, order, structure) = cost_names(t, &ls);
    // A planted fault's failures are looked for among integer costs 0..=20 (a failure there is
    // a failure), so that the model fits the oracle's integer costs.
    let integer = plant != Plant::None;
    let logic = if integer { Logic::QfLira } else { Logic::QfLra };
    let mut o = Obligation::new("C2", plant.lemma(), &structure, role, logic);
    for (k, &(x, i)) in order.iter().enumerate() {
        let n = o.declare(names[x][i].as_ref().expect("named"), Sort::Real);
        o.assert(ge(&n, &real_int(0)));
        if integer {
            let z = o.declare(&format!("k{}", k + 1), Sort::Int);
            o.assert(eq(&n, &app("to_real", std::slice::from_ref(&z))));
            o.assert(le(&z, &super::term::int(20)));
        }
    }
    let fs: Vec<Option<Functional>> = match plant {
        Plant::MaxOfStages => vec![None],
        _ => functionals().into_iter().map(Some).collect(),
    };
    let cost = |m: MoveId| names[m.0][m.1].clone().expect("named");
    let reward = |m: MoveId| match plant {
        Plant::RewardNotNegated => cost(m),
        _ => app("-", &[cost(m)]),
    };
    let mut per_functional = Vec::new();
    for (fi, &f) in fs.iter().enumerate() {
        let mut bindings = Vec::new();
        let c: Vec<Value> = ls
            .iter()
            .enumerate()
            .map(|(p, l)| {
                bind(
                    &format!("c{fi}_{p}"),
                    lasso_value(f, l, &cost),
                    &mut bindings,
                )
            })
            .collect();
        let r: Vec<Value> = ls
            .iter()
            .enumerate()
            .map(|(p, l)| {
                bind(
                    &format!("r{fi}_{p}"),
                    lasso_value(f, l, &reward),
                    &mut bindings,
                )
            })
            .collect();
        let mut failures = Vec::new();
        for p in 0..ls.len() {
            let minimises = and(&(0..ls.len())
                .map(|s| le_ext(&c[p], &c[s]))
                .collect::<Vec<_>>());
            let maximises = and(&(0..ls.len())
                .map(|s| le_ext(&r[s], &r[p]))
                .collect::<Vec<_>>());
            failures.push(not(&eq(&minimises, &maximises)));
        }
        per_functional.push(app(
            "let",
            &[format!("({})", bindings.join(" ")), or(&failures)],
        ));
    }
    o.assert(or(&per_functional));
    (o, structure)
}

/// Every canonical shape of the scope with its obligation, duplicates (same text) removed;
/// also the number of shapes before removal.
fn structures(scope: Scope, role: Role, plant: Plant) -> (Vec<(Tiny, Obligation)>, u64) {
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    let mut shapes = 0;
    for spec in shape_specs(scope) {
        let family = Family::new(&spec);
        for t in family.canonical() {
            shapes += 1;
            let (o, _) = structure_obligation(&t, role.clone(), plant);
            let key = o.asserts.join("\n");
            if seen.insert(key) {
                out.push((t, o));
            }
        }
    }
    (out, shapes)
}

/// The C2 encoding in `scope` (see the module doc and `docs/proofs/c2.md`).
///
/// ```no_run
/// use truecost::claims::smt::{c2, run, SmtVerdict, TIMEOUT_MS};
/// use truecost::claims::Scope;
/// assert_eq!(run(c2::encoding(Scope::Smoke), TIMEOUT_MS).verdict, SmtVerdict::Proved);
/// ```
pub fn encoding(scope: Scope) -> Encoding {
    encoding_with(scope, Plant::None)
}

/// The C2 encoding with a planted fault in its proof obligations (for the mutation test; the
/// trust checks are the same as [`encoding`]'s).
pub fn encoding_with(scope: Scope, plant: Plant) -> Encoding {
    let (proofs, shapes) = structures(scope, Role::Proof, plant);
    let mut obligations = Vec::new();
    let mut symbolic = 0;
    for (t, o) in &proofs {
        obligations.push(o.clone());
        if plant == Plant::None && t.states() <= symbolic_alpha_states(scope) {
            let s = symbolic_alpha_obligation(t, Role::Proof);
            let mut h = s.with_role(Role::Hypotheses);
            h.asserts.pop();
            obligations.push(s);
            obligations.push(h);
            symbolic += 1;
        }
        // Hypotheses alone: the cost constants and value definitions, without the negated
        // conclusion (the last assertion).
        let mut h = o.with_role(Role::Hypotheses);
        h.lemma = LEMMA.into();
        h.asserts.pop();
        obligations.push(h);
        if t.states() <= dropped_states(scope) && lassos(t, true).len() >= 2 {
            let (d, _) = structure_obligation(
                t,
                Role::Dropped("r = -l (planted: r = l)".into()),
                Plant::RewardNotNegated,
            );
            obligations.push(d);
        }
    }
    // The non-linear functional on the hand-checked structure where it fails: x1 with a
    // self-loop and a move to the goal (costs a, b: sup a against sup(b, 0); the reward of the
    // terminating lasso is 0 ≥ −a, so it is always a reward maximiser, while it minimises the
    // cost only if b ≤ a).
    let t = Tiny::from_lists(&[vec![(0, 0), (1, 0)], vec![]]);
    let (d, _) = structure_obligation(
        &t,
        Role::Dropped("linearity (planted: sup of stages)".into()),
        Plant::MaxOfStages,
    );
    obligations.push(d);
    let checks = obligations
        .iter()
        .filter(|o| matches!(o.role, Role::Dropped(_)))
        .count();
    let names: Vec<String> = functionals().iter().map(Functional::name).collect();
    let max_states = shape_specs(scope).last().map_or(0, |s| s.states);
    let scope_text = format!(
        "every structure with 1-{max_states} states, 1-2 moves per non-goal state and 0-2 at the goal (besides \
termination), parallel moves allowed, x1 = 0, one goal, up to relabelling ({shapes} shapes, enumerated outside the \
solver; {} distinct obligations once shapes whose part reachable from x1 gives the same obligation are merged); every \
deterministic stationary policy from x1 (one lasso per class); functionals: {}; every move's stage cost a real >= 0; the discounted functional also for every real alpha in (0,1) on the {} \
distinct obligations with <= {} states (QF_NRA); trust checks: hypotheses of every structure satisfiable, the \
planted reward r = l fails on each of the {} structures with <= {} states and >= 2 lassos, the planted sup of stages \
fails on a hand-checked structure",
        proofs.len(),
        names.join(", "),
        symbolic,
        symbolic_alpha_states(scope),
        checks - 1,
        dropped_states(scope)
    );
    Encoding {
        claim: "C2",
        scope: scope_text,
        obligations,
        replay,
    }
}

/// The extended-real value of the supremum of a trajectory's stages times `sign`.
fn sup_of_stages(tr: &Trajectory, sign: i64) -> i64 {
    tr.prefix[..tr.prefix_len]
        .iter()
        .chain(&tr.cycle[..tr.cycle_len])
        .map(|&c| sign * c)
        .max()
        .expect("a stage")
}

/// Replays a C2 model through the exact oracle: the costs (scaled to integers) on the
/// structure, every policy's trajectory from `x1`, the cost functional and the (planted)
/// reward functional evaluated exactly; confirmed if the argmin and argmax sets differ.
pub fn replay(o: &Obligation, m: &Model) -> Replay {
    let Some(shape) = parse_shape(&o.structure) else {
        return Replay::NotConfirmed(format!("cannot read the structure {}", o.structure));
    };
    let mut labels = Vec::new();
    for list in &shape {
        for (_, label) in list {
            labels.push(match m.get(label) {
                Some(v) => v.clone(),
                None => Rational::from_integer(0.into()),
            });
        }
    }
    let Some(scaled) = scale_to_u8(&labels) else {
        return Replay::NotConfirmed(
            "the model's costs do not scale into the oracle's range".into(),
        );
    };
    let mut k = 0;
    let lists: Vec<Vec<(u8, u8)>> = shape
        .iter()
        .map(|list| {
            list.iter()
                .map(|(to, _)| {
                    k += 1;
                    (*to, scaled[k - 1])
                })
                .collect()
        })
        .collect();
    let t = Tiny::from_lists(&lists);
    let plant = if o.lemma == LEMMA_NOT_NEGATED {
        Plant::RewardNotNegated
    } else if o.lemma == LEMMA_MAX {
        Plant::MaxOfStages
    } else {
        Plant::None
    };
    if o.lemma == LEMMA_ALPHA {
        return replay_symbolic_alpha(&t, m);
    }
    if plant == Plant::None {
        return match crate::claims::c2::check_problem(&t, &functionals(), 1).0 {
            Some(what) => Replay::Confirmed(
                format!("C2 fails on {}: {what}", t.describe()),
                Some(crate::claims::Counterexample::new(
                    &t,
                    format!("C2 counterexample: {what}"),
                    vec![],
                    "c2-smt",
                )),
            ),
            None => Replay::NotConfirmed(format!(
                "the oracle finds argmin cost = argmax reward on {}",
                t.describe()
            )),
        };
    }
    let trs: Vec<Trajectory> = policies(&t, true)
        .iter()
        .map(|p| trajectory(&t, p, 0))
        .collect();
    let differ = |cost: Vec<FracExt>, reward: Vec<FracExt>| {
        let min = cost.iter().min().expect("a policy");
        let max = reward.iter().max().expect("a policy");
        (0..trs.len()).any(|i| (cost[i] == *min) != (reward[i] == *max))
    };
    let failing: Vec<String> = match plant {
        Plant::RewardNotNegated => functionals()
            .into_iter()
            .filter(|&f| {
                differ(
                    trs.iter().map(|tr| evaluate_fast(tr, f, 1)).collect(),
                    trs.iter().map(|tr| evaluate_fast(tr, f, 1)).collect(),
                )
            })
            .map(|f| f.name())
            .collect(),
        _ => {
            let as_ext = |v: i64| FracExt::Fin(crate::claims::exact::Frac { n: v as i128, d: 1 });
            let cost = trs.iter().map(|tr| as_ext(sup_of_stages(tr, 1))).collect();
            let reward = trs.iter().map(|tr| as_ext(sup_of_stages(tr, -1))).collect();
            if differ(cost, reward) {
                vec!["sup of stages".into()]
            } else {
                vec![]
            }
        }
    };
    if failing.is_empty() {
        Replay::NotConfirmed(format!(
            "the oracle finds argmin = argmax under the planted reward on {}",
            t.describe()
        ))
    } else {
        Replay::Confirmed(
            format!(
                "with the planted fault, argmin cost != argmax reward on {} ({})",
                t.describe(),
                failing.join(", ")
            ),
            None,
        )
    }
}

/// Replays a model of the every-α discounted obligation: α read back (as a small exact
/// rational), every policy's discounted cost and reward evaluated by the oracle.
fn replay_symbolic_alpha(t: &Tiny, m: &Model) -> Replay {
    let alpha = m.get("a").and_then(|a| {
        let n = i128::try_from(a.numer()).ok()?;
        let d = i128::try_from(a.denom()).ok()?;
        (n.abs() < 1 << 20 && d < 1 << 20).then(|| Q::new(n, d))
    });
    let Some(alpha) = alpha else {
        return Replay::NotConfirmed(ALPHA_DOES_NOT_FIT.into());
    };
    let f = Functional::Discounted(alpha);
    match crate::claims::c2::check_problem(t, &[f], 1).0 {
        Some(what) => Replay::Confirmed(format!("C2 fails on {}: {what}", t.describe()), None),
        None => Replay::NotConfirmed(format!(
            "the oracle finds argmin cost = argmax reward at alpha = {alpha} on {}",
            t.describe()
        )),
    }
}

/// Why an every-α model is not replayed when its `α` does not fit the oracle's bound.
const ALPHA_DOES_NOT_FIT: &str = "alpha does not fit the oracle";

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::smt::{solve, Answer, TIMEOUT_MS};

    /// Whether Z3 finds the closed formula `term` (no unknowns) true.
    fn holds(term: String) -> bool {
        let mut o = Obligation::new("C2", "test", "none", Role::Proof, Logic::QfLra);
        o.assert(term);
        match solve(&o, TIMEOUT_MS) {
            Answer::Sat(_) => true,
            Answer::Unsat => false,
            other => panic!("{other:?}"),
        }
    }

    /// `le_ext` is `≤` in the extended reals `[−∞, +∞]`: `a ≤ b` iff `a = −∞` or `b = +∞` or
    /// both are finite and `a ≤ b` as reals (so `+∞ ≤ +∞` and `−∞ ≤ −∞`). The finite part of
    /// an infinite value (a total's prefix sum) is chosen here so that comparing finite parts
    /// alone gives the other answer in every infinite case: `+∞` (finite part 0) is not `≤ 1`,
    /// `−∞` (finite part 5) is `≤ 1`, and so on.
    #[test]
    fn le_ext_is_the_order_of_the_extended_reals() {
        let v = |finite: i64, inf: Option<(bool, bool)>| Value {
            finite: real_int(finite),
            infinite: inf.map(|(p, n)| (p.to_string(), n.to_string())),
        };
        let fin = |x| v(x, Some((false, false)));
        let pinf = |x| v(x, Some((true, false)));
        let ninf = |x| v(x, Some((false, true)));
        for (a, b, expected, what) in [
            (pinf(0), fin(1), false, "+inf <= 1"),
            (fin(1), pinf(0), true, "1 <= +inf"),
            (ninf(5), fin(1), true, "-inf <= 1"),
            (fin(1), ninf(5), false, "1 <= -inf"),
            (pinf(2), pinf(1), true, "+inf <= +inf"),
            (ninf(2), ninf(1), true, "-inf <= -inf"),
            (pinf(0), ninf(1), false, "+inf <= -inf"),
            (ninf(1), pinf(0), true, "-inf <= +inf"),
            (fin(1), fin(2), true, "1 <= 2"),
            (fin(2), fin(1), false, "2 <= 1"),
            (v(1, None), v(2, None), true, "1 <= 2 (no infinities)"),
            (v(2, None), v(1, None), false, "2 <= 1 (no infinities)"),
        ] {
            assert_eq!(holds(le_ext(&a, &b)), expected, "{what}");
        }
    }

    /// The discounted value of a lasso by hand: a prefix of one stage of cost 3, then the cycle
    /// 6, 9 repeated, at `α = 1/2`. Stage by stage: `3 + (1/2)·6 + (1/4)·9 + (1/8)·6 + …` =
    /// `3 + 6·(1/2)/(1 − 1/4) + 9·(1/4)/(1 − 1/4)` = `3 + 4 + 3` = 10: the cycle's `j`-th stage
    /// has weight `α^p · α^j / (1 − α^q)` (2/3, then 1/3), the second weight being the first
    /// times `α`.
    #[test]
    fn discounted_value_of_a_lasso_by_hand() {
        let l = Lasso {
            prefix: vec![(0, 0)],
            cycle: vec![(1, 0), (2, 0)],
            terminates: false,
            visits_goal: false,
        };
        let stage = |m: MoveId| real_int([3, 6, 9][m.0]);
        let v = lasso_value(Some(Functional::Discounted(Q::new(1, 2))), &l, &stage);
        assert!(v.infinite.is_none());
        assert!(holds(eq(&v.finite, &real_int(10))), "{}", v.finite);
        assert!(!holds(not(&eq(&v.finite, &real_int(10)))), "{}", v.finite);
    }

    /// A structure has at most `MAX_STATES` (7) states: `parse_shape` reads a text of 7
    /// states (no moves) and refuses one of 8.
    #[test]
    fn parse_shape_refuses_more_states_than_a_structure_holds() {
        let text =
            |n: usize| (0..n).map(|x| x.to_string()).collect::<Vec<_>>().join("; ") + " (goal)";
        assert_eq!(MAX_STATES, 7);
        assert_eq!(parse_shape(&text(7)), Some(vec![vec![]; 7]));
        assert_eq!(parse_shape(&text(8)), None);
    }

    /// The planted encoding plants its fault in every proof obligation: the every-α
    /// obligations (the unplanted claim, `r = −l`) belong to the unplanted encoding only. In
    /// the smoke scope (1–2 states, all within `symbolic_alpha_states`) the unplanted encoding
    /// has them, the planted `r = l` one has none, and each of its proofs has the planted lemma.
    #[test]
    fn only_the_unplanted_encoding_has_the_every_alpha_obligations() {
        let proofs = |plant| {
            encoding_with(Scope::Smoke, plant)
                .obligations
                .into_iter()
                .filter(|o| o.role == Role::Proof)
                .map(|o| o.lemma)
                .collect::<Vec<_>>()
        };
        assert!(proofs(Plant::None).iter().any(|l| l == LEMMA_ALPHA));
        let planted = proofs(Plant::RewardNotNegated);
        assert!(!planted.is_empty());
        assert!(
            planted.iter().all(|l| l == LEMMA_NOT_NEGATED),
            "{planted:?}"
        );
    }

    /// The every-α replay hands the oracle only an `α` whose numerator and denominator are
    /// below 2^20 in absolute value: `2^20 / (2^20 − 1)` (the denominator fits, the numerator
    /// does not) is refused, as is `−2^20 / 3`.
    #[test]
    fn the_every_alpha_replay_refuses_a_numerator_of_two_to_the_twenty() {
        let t = Tiny::from_lists(&[vec![(0, 1), (1, 3)], vec![]]);
        let big = 1i64 << 20;
        for a in [
            Rational::new(big.into(), (big - 1).into()),
            Rational::new((-big).into(), 3.into()),
        ] {
            let m = Model {
                values: vec![("a".into(), a.clone())],
            };
            match replay_symbolic_alpha(&t, &m) {
                Replay::NotConfirmed(why) => assert_eq!(why, ALPHA_DOES_NOT_FIT),
                other => panic!("alpha = {a}: {other:?}"),
            }
        }
    }
}

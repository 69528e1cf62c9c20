//! Shared random-problem generators (proptest strategies) and independent oracles for the
//! integration tests. Each test binary uses a subset, hence `dead_code` is allowed.
//!
//! The oracles here never call the code under test: they work on `Problem`'s public data
//! (states, ordered moves, goals) with their own `Option<BigRational>` arithmetic (`None` = +∞).
#![allow(dead_code)]

pub mod certificate_oracle;
pub mod cli;
pub mod smt;
pub mod tiny;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use proptest::prelude::*;
use truecost::model::{Graph, Move, Problem};
use truecost::value::ExactValue;

/// Exact rational.
pub type Q = BigRational;

/// A portable seeded generator (64-bit LCG), independent of the code under test.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in `0..n`.
    pub fn below(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) % n
    }
}

/// The problem of a `truecost-stochastic/1` file's text (a test's own file: it must parse).
pub fn stochastic_file(text: &str) -> truecost::stochastic::StochasticProblem {
    use truecost::stochastic::file::{from_json, ProblemFile};
    let ProblemFile::Stochastic(p) = from_json(text).unwrap() else {
        panic!("a stochastic file")
    };
    *p
}

/// An extended non-negative value of the oracles: `None` is `+∞`.
pub type Ext = Option<Q>;

/// The integer `n` as a rational.
pub fn int(n: i64) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// `n/d`.
pub fn frac(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

/// `2^k`.
pub fn pow2(k: u32) -> Q {
    Q::from_integer(BigInt::one() << k)
}

/// A `u64` as a rational.
pub fn from_u64(n: u64) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// A move.
pub fn mv(successor: usize, cost: Q) -> Move {
    Move { successor, cost }
}

/// The small cost set of the ordinary generator (includes 0, non-integers).
pub fn small_costs() -> Vec<Q> {
    vec![int(0), int(1), int(2), frac(1, 2), frac(5, 3), int(7)]
}

/// A cost set with costs so large that `ExactGraph::new` must choose `Big` whenever one of
/// the costs `>= 2^62` is used: `2^63`, `2^63 + 1`, `2^70` scale to at least `2^63`, and
/// `5·2^62/3` scales (the unit divides 1/3) to at least `5·2^62 >= 2^63`; with at least one
/// state, `(states + 1) × 2^63 >= 2^64 > u64::MAX`.
pub fn huge_costs() -> Vec<Q> {
    vec![
        int(0),
        frac(1, 2),
        pow2(63),
        pow2(63) + int(1),
        pow2(62) * frac(5, 3),
        pow2(70),
    ]
}

/// The largest integer cost `M` with `(n + 1) × M < u64::MAX`, i.e. `(u64::MAX - 1) / (n + 1)`.
pub fn boundary_max(n: usize) -> u64 {
    (u64::MAX - 1) / (n as u64 + 1)
}

/// Integer costs up to the `Units` boundary for `n` states (the unit is 1, the largest scaled
/// cost is `boundary_max(n)`), so `Units` must be chosen and planners run at the edge of `u64`.
pub fn boundary_costs(n: usize) -> Vec<Q> {
    let m = boundary_max(n);
    vec![
        int(0),
        int(1),
        from_u64(m),
        from_u64(m - 1),
        from_u64(m / 2),
    ]
}

/// The number of states: mostly 1..=8, sometimes up to 12.
pub fn state_count() -> impl Strategy<Value = usize> {
    prop_oneof![4 => 1usize..=8, 1 => 9usize..=12]
}

/// Random problems with `n` states whose costs are drawn from `costs`: 0..=4 moves per state,
/// random successors with a bias towards self-loops, dead ends (no moves), 1–2 goals (maybe
/// equal), random initial state. States that cannot reach a goal arise naturally.
pub fn problem_with(n: usize, costs: Vec<Q>) -> impl Strategy<Value = Problem> {
    let k = costs.len();
    // `None` stands for a self-loop.
    let one_move = (prop::option::weighted(0.8, 0..n), 0..k);
    let moves = prop::collection::vec(prop::collection::vec(one_move, 0..=4), n);
    let goals = prop::collection::vec(0..n, 1..=2);
    (moves, 0..n, goals).prop_map(move |(raw, initial, goals)| {
        let moves = raw
            .into_iter()
            .enumerate()
            .map(|(x, list)| {
                list.into_iter()
                    .map(|(s, c)| mv(s.unwrap_or(x), costs[c].clone()))
                    .collect()
            })
            .collect();
        Problem::new(moves, initial, goals).expect("generated problems are valid")
    })
}

/// The ordinary generator: small exact costs (so `Units` is chosen).
pub fn small_problem() -> impl Strategy<Value = Problem> {
    state_count().prop_flat_map(|n| problem_with(n, small_costs()))
}

/// Problems with at least one cost `>= 2^62` from [`huge_costs`] (so `Big` is chosen).
pub fn huge_problem() -> impl Strategy<Value = Problem> {
    state_count()
        .prop_flat_map(|n| problem_with(n, huge_costs()))
        .prop_filter("needs a huge cost", |p| max_cost(p) >= pow2(62))
}

/// Problems with integer costs up to the `Units` boundary.
pub fn boundary_problem() -> impl Strategy<Value = Problem> {
    state_count().prop_flat_map(|n| problem_with(n, boundary_costs(n)))
}

/// The largest stage cost of a problem (0 if it has no moves).
pub fn max_cost(p: &Problem) -> Q {
    (0..p.states())
        .flat_map(|x| p.moves(x).iter().map(|m| m.cost.clone()))
        .max()
        .unwrap_or_else(Q::zero)
}

/// Runs `$body` with `$g` bound to the compiled graph, whichever arm of `ExactGraph` it is.
#[macro_export]
macro_rules! with_exact_graph {
    ($eg:expr, $g:ident => $body:expr) => {
        match $eg {
            truecost::model::ExactGraph::Units($g) => $body,
            truecost::model::ExactGraph::Big($g) => $body,
        }
    };
}

/// The exact value of `v` in graph `g` as an oracle value.
pub fn exact<V: ExactValue>(g: &Graph<V>, v: &V) -> Ext {
    v.to_extended(g.unit())
        .expect("exact value type")
        .finite()
        .cloned()
}

/// Exact values of a whole vector.
pub fn exact_all<V: ExactValue>(g: &Graph<V>, vs: &[V]) -> Vec<Ext> {
    vs.iter().map(|v| exact(g, v)).collect()
}

/// Extended addition of the oracles.
pub fn add(a: &Q, b: &Ext) -> Ext {
    b.as_ref().map(|b| a + b)
}

/// Extended minimum of the oracles.
pub fn min_ext(a: Ext, b: Ext) -> Ext {
    match (a, b) {
        (None, b) => b,
        (a, None) => a,
        (Some(a), Some(b)) => Some(if a <= b { a } else { b }),
    }
}

/// Whether `a < b` in the extended order.
pub fn lt_ext(a: &Ext, b: &Ext) -> bool {
    match (a, b) {
        (_, None) => a.is_some(),
        (None, Some(_)) => false,
        (Some(a), Some(b)) => a < b,
    }
}

/// The right-hand side of the Bellman equation at `x` for values `g`: 0 at a goal, otherwise
/// `min_u l(x,u) + g(f(x,u))` (`+∞` without moves).
pub fn bellman_rhs(p: &Problem, g: &[Ext], x: usize) -> Ext {
    if p.is_goal(x) {
        return Some(Q::zero());
    }
    p.moves(x)
        .iter()
        .fold(None, |best, m| min_ext(best, add(&m.cost, &g[m.successor])))
}

/// Result of the Bellman–Ford oracle.
pub struct Oracle {
    /// `G*` (`None` = +∞).
    pub cost_to_go: Vec<Ext>,
    /// The number of Jacobi sweeps until (and including) the first sweep that changes nothing,
    /// starting from goals 0 and +∞ elsewhere, a value replaced only when strictly smaller.
    pub jacobi_sweeps: u64,
}

/// Bellman–Ford from scratch: `d_0` = 0 at goals, +∞ elsewhere;
/// `d_k(x) = min(d_{k-1}(x), min_u l(x,u) + d_{k-1}(f(x,u)))`. `d_k(x)` is the least cost of
/// reaching a goal in at most `k` moves, so it is stationary after `|X| - 1` sweeps.
pub fn bellman_ford(p: &Problem) -> Oracle {
    let n = p.states();
    let mut d: Vec<Ext> = (0..n)
        .map(|x| if p.is_goal(x) { Some(Q::zero()) } else { None })
        .collect();
    let mut sweeps = 0u64;
    loop {
        sweeps += 1;
        assert!(
            sweeps <= n as u64 + 1,
            "Bellman–Ford must settle within |X| sweeps"
        );
        let next: Vec<Ext> = (0..n)
            .map(|x| {
                let cand = bellman_rhs(p, &d, x);
                if lt_ext(&cand, &d[x]) {
                    cand
                } else {
                    d[x].clone()
                }
            })
            .collect();
        if next == d {
            return Oracle {
                cost_to_go: d,
                jacobi_sweeps: sweeps,
            };
        }
        d = next;
    }
}

/// `G*` by enumerating every simple path (exponential; only for small problems). A cheapest
/// walk to a goal can always be shortened to a simple path (costs are non-negative).
pub fn simple_paths(p: &Problem) -> Vec<Ext> {
    fn go(p: &Problem, x: usize, acc: &Q, on: &mut [bool], best: &mut Ext) {
        if let Some(b) = best {
            if acc >= b {
                return; // costs are non-negative: this branch cannot improve
            }
        }
        if p.is_goal(x) {
            *best = Some(acc.clone());
            return;
        }
        on[x] = true;
        for m in p.moves(x) {
            if !on[m.successor] {
                go(p, m.successor, &(acc + &m.cost), on, best);
            }
        }
        on[x] = false;
    }
    (0..p.states())
        .map(|x| {
            let mut best = None;
            go(p, x, &Q::zero(), &mut vec![false; p.states()], &mut best);
            best
        })
        .collect()
}

/// States reachable from `x1` (including it), by depth-first search.
pub fn reachable(p: &Problem) -> Vec<bool> {
    let mut seen = vec![false; p.states()];
    let mut stack = vec![p.initial()];
    seen[p.initial()] = true;
    while let Some(x) = stack.pop() {
        for m in p.moves(x) {
            if !seen[m.successor] {
                seen[m.successor] = true;
                stack.push(m.successor);
            }
        }
    }
    seen
}

/// `Σ_x |U(x)|`.
pub fn move_count(p: &Problem) -> usize {
    (0..p.states()).map(|x| p.moves(x).len()).sum()
}

/// The number of moves into each state (self-loops included).
pub fn in_degrees(p: &Problem) -> Vec<usize> {
    let mut d = vec![0; p.states()];
    for x in 0..p.states() {
        for m in p.moves(x) {
            d[m.successor] += 1;
        }
    }
    d
}

/// The same problem with every cost multiplied by `k`.
pub fn scaled(p: &Problem, k: &Q) -> Problem {
    let moves = (0..p.states())
        .map(|x| {
            p.moves(x)
                .iter()
                .map(|m| mv(m.successor, &m.cost * k))
                .collect()
        })
        .collect();
    Problem::new(moves, p.initial(), p.goals().to_vec()).expect("scaling keeps validity")
}

/// A `u64` view of a small non-negative integer rational (for tests only).
pub fn to_u64(q: &Q) -> u64 {
    assert!(q.is_integer());
    q.to_integer().to_u64().expect("fits")
}

/// A `truecost-stochastic/1`-style problem file of `n` running states in lines of `length` (the
/// last line shorter) and the goal `n`: state `i`'s action list is `actions(i, next)` (JSON),
/// `next` being `i + 1`, or the goal for the last state of each line.
pub fn line_chains(
    n: usize,
    length: usize,
    mut actions: impl FnMut(usize, usize) -> String,
) -> String {
    let lists: Vec<String> = (0..n)
        .map(|i| {
            let next = if i % length == length - 1 || i == n - 1 {
                n
            } else {
                i + 1
            };
            actions(i, next)
        })
        .chain(["[]".to_string()])
        .collect();
    format!(
        r#"{{"states": {}, "initial": 0, "goals": [{n}], "actions": [{}]}}"#,
        n + 1,
        lists.join(",")
    )
}

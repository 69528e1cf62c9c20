//! Claim C4 (SPEC §6): episodic equivalence. The single-shot problem versus the
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

use std::fmt;

use num_bigint::BigInt;
use num_traits::ToPrimitive;

use super::exact::Q;
use super::oracle::{karp_minimum_mean_cycle, simple_cycles};
use super::tiny::{minimality_key, FamilySpec, Tiny};
use super::{enumerate, keep_min, min_of, ClaimResult, Counterexample, EngineRun, Scope, Verdict};
use crate::model::Problem;
use crate::value::{to_common_scale, Rational};

/// The statement of C4 as printed.
pub const STATEMENT: &str = "C4 (as printed): with bonus M < 0 paid at the reset to x1 (one stage), pi* (the optimal \
single-shot path: S* states, cost L*) is average-cost optimal iff a <= M <= min{b, S*.Lav(C^) - L*}, where \
A(u) = (1 - S(u)/S*)(S(u).L*/(S*.L(u)) - 1), a = max A(u) over goal-reaching u with S(u) < S*, b = min A(u) over \
S(u) > S*, and C^ is the goal-avoiding cycle of least average cost per stage.";

/// The corrected statement.
pub const CORRECTED: &str = "C4-corrected: with T(u) = (S*.L(u) - S(u).L*) / (S(u) - S*) over simple goal paths u from \
x1, pi* is average-cost optimal iff max{T(u) : S(u) < S*} <= M <= min{ min{T(u) : S(u) > S*}, S*.Lav(C^) - L* } and \
M < 0 (C^ over cycles reachable from x1 avoiding the goal; an empty max is -inf, an empty min +inf).";

/// One end of an interval of bonuses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum End {
    /// Unbounded (`-∞` below, `+∞` above).
    Unbounded,
    /// Included.
    Closed(Q),
    /// Excluded.
    Open(Q),
}

/// A convex set of rationals `{M : lo ≤/< M ≤/< hi}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Interval {
    /// Lower end.
    pub lo: End,
    /// Upper end.
    pub hi: End,
    /// Whether the set is empty.
    pub empty: bool,
}

impl Interval {
    /// `M < 0`.
    pub fn negative() -> Interval {
        Interval {
            lo: End::Unbounded,
            hi: End::Open(Q::ZERO),
            empty: false,
        }
    }

    /// Whether `m` belongs to the set.
    pub fn contains(&self, m: Q) -> bool {
        !self.empty
            && match self.lo {
                End::Unbounded => true,
                End::Closed(a) => m >= a,
                End::Open(a) => m > a,
            }
            && match self.hi {
                End::Unbounded => true,
                End::Closed(b) => m <= b,
                End::Open(b) => m < b,
            }
    }

    /// Intersects with `[lo, +∞)` (closed).
    pub fn at_least(&mut self, lo: Q) {
        self.lo = match self.lo {
            End::Closed(a) | End::Open(a) if a > lo => self.lo,
            End::Open(a) if a == lo => self.lo,
            _ => End::Closed(lo),
        };
        self.normalise();
    }

    /// Intersects with `(-∞, hi]` (closed).
    pub fn at_most(&mut self, hi: Q) {
        self.hi = match self.hi {
            End::Closed(b) | End::Open(b) if b < hi => self.hi,
            End::Open(b) if b == hi => self.hi,
            _ => End::Closed(hi),
        };
        self.normalise();
    }

    fn normalise(&mut self) {
        let (a, ac) = match self.lo {
            End::Unbounded => return,
            End::Closed(a) => (a, true),
            End::Open(a) => (a, false),
        };
        let (b, bc) = match self.hi {
            End::Unbounded => return,
            End::Closed(b) => (b, true),
            End::Open(b) => (b, false),
        };
        if a > b || (a == b && !(ac && bc)) {
            self.empty = true;
        }
    }

    /// Set equality.
    pub fn same_set(&self, o: &Interval) -> bool {
        (self.empty && o.empty) || (!self.empty && !o.empty && self.lo == o.lo && self.hi == o.hi)
    }

    /// The finite ends.
    fn ends(&self) -> Vec<Q> {
        let mut v = Vec::new();
        for e in [self.lo, self.hi] {
            if let End::Closed(q) | End::Open(q) = e {
                v.push(q);
            }
        }
        v
    }
}

impl fmt::Display for Interval {
    /// `[-3/2, -1)`, `(-inf, 0)`, `empty`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.empty {
            return write!(f, "empty");
        }
        match self.lo {
            End::Unbounded => write!(f, "(-inf, ")?,
            End::Closed(a) => write!(f, "[{a}, ")?,
            End::Open(a) => write!(f, "({a}, ")?,
        }
        match self.hi {
            End::Unbounded => write!(f, "+inf)"),
            End::Closed(b) => write!(f, "{b}]"),
            End::Open(b) => write!(f, "{b})"),
        }
    }
}

/// A small average-cost instance: states `0..n`, initial state, goals, integer move costs.
#[derive(Clone, Debug)]
pub struct Instance {
    /// The initial state `x1`.
    pub initial: usize,
    /// Goal flags.
    pub is_goal: Vec<bool>,
    /// Moves `(successor, cost)` of each state.
    pub moves: Vec<Vec<(usize, i64)>>,
}

impl Instance {
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
    pub fn from_problem(problem: &Problem) -> Result<(Instance, BigInt), String> {
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

    /// From a tiny problem.
    pub fn from_tiny(t: &Tiny) -> Instance {
        Instance {
            initial: 0,
            is_goal: (0..t.states()).map(|x| t.is_goal(x)).collect(),
            moves: (0..t.states())
                .map(|x| {
                    t.moves(x)
                        .iter()
                        .map(|m| (m.to as usize, m.cost as i64))
                        .collect()
                })
                .collect(),
        }
    }

    fn tiny_like(&self) -> (usize, Vec<(usize, usize, i64)>) {
        // Goal-avoiding arcs among states reachable from x1 without passing a goal.
        let n = self.moves.len();
        let mut seen = vec![false; n];
        if self.is_goal[self.initial] {
            return (n, Vec::new());
        }
        seen[self.initial] = true;
        let mut stack = vec![self.initial];
        while let Some(x) = stack.pop() {
            for &(y, _) in &self.moves[x] {
                if !self.is_goal[y] && !seen[y] {
                    seen[y] = true;
                    stack.push(y);
                }
            }
        }
        let mut arcs = Vec::new();
        for x in 0..n {
            if seen[x] {
                for &(y, c) in &self.moves[x] {
                    if seen[y] {
                        arcs.push((x, y, c));
                    }
                }
            }
        }
        (n, arcs)
    }

    /// Every simple path from `x1` to a goal as `(L, S)`, or `Err(BonusError::SearchTooLong)`
    /// once the depth-first search has taken more than `max_steps` steps (issue 12: the bound
    /// is checked while the search runs, so a grid refuses at once instead of listing its
    /// astronomically many paths).
    ///
    /// ```
    /// use truecost::claims::c4::{BonusError, Instance};
    /// // x1 = 0 -> 1 -> goal 2, and 0 -> goal 2 directly.
    /// let inst = Instance { initial: 0, is_goal: vec![false, false, true],
    ///     moves: vec![vec![(1, 1), (2, 5)], vec![(2, 1)], vec![]] };
    /// let mut paths = inst.goal_paths(100).unwrap();
    /// paths.sort();
    /// assert_eq!(paths, vec![(2, 3), (5, 2)]);
    /// assert_eq!(inst.goal_paths(2), Err(BonusError::SearchTooLong { steps: 2 }));
    /// ```
    pub fn goal_paths(&self, max_steps: u64) -> Result<Vec<(i64, i64)>, BonusError> {
        struct Search<'a> {
            inst: &'a Instance,
            on: Vec<bool>,
            out: Vec<(i64, i64)>,
            steps: u64,
            max_steps: u64,
        }
        fn dfs(s: &mut Search, x: usize, cost: i64, states: i64) -> Result<(), BonusError> {
            s.steps += 1;
            if s.steps > s.max_steps {
                return Err(BonusError::SearchTooLong { steps: s.max_steps });
            }
            if s.inst.is_goal[x] {
                s.out.push((cost, states));
                return Ok(());
            }
            for &(y, c) in &s.inst.moves[x] {
                if !s.on[y] {
                    s.on[y] = true;
                    dfs(s, y, cost + c, states + 1)?;
                    s.on[y] = false;
                }
            }
            Ok(())
        }
        let mut search = Search {
            inst: self,
            on: vec![false; self.moves.len()],
            out: Vec::new(),
            steps: 0,
            max_steps,
        };
        search.on[self.initial] = true;
        dfs(&mut search, self.initial, 0, 1)?;
        Ok(search.out)
    }

    /// The states reachable from `x1` without passing through a goal (goals reached included).
    fn reachable(&self) -> Vec<bool> {
        let n = self.moves.len();
        let mut reach = vec![false; n];
        reach[self.initial] = true;
        let mut stack = vec![self.initial];
        while let Some(x) = stack.pop() {
            if self.is_goal[x] {
                continue;
            }
            for &(y, _) in &self.moves[x] {
                if !reach[y] {
                    reach[y] = true;
                    stack.push(y);
                }
            }
        }
        reach
    }

    /// The number of stationary policies over the non-goal states reachable from `x1`
    /// (`Π |U(x)|`), or `None` as soon as it exceeds `limit` (computed without enumerating).
    ///
    /// ```
    /// use truecost::claims::c4::Instance;
    /// let inst = Instance { initial: 0, is_goal: vec![false, false, true],
    ///     moves: vec![vec![(1, 1), (2, 5)], vec![(2, 1), (0, 1)], vec![]] };
    /// assert_eq!(inst.policy_count(10), Some(4));
    /// assert_eq!(inst.policy_count(3), None);
    /// ```
    pub fn policy_count(&self, limit: u64) -> Option<u64> {
        let reach = self.reachable();
        let mut count: u64 = 1;
        for x in (0..self.moves.len()).filter(|&x| reach[x] && !self.is_goal[x]) {
            count = count.checked_mul(self.moves[x].len() as u64)?;
            if count > limit {
                return None;
            }
        }
        Some(count)
    }

    /// Every stationary policy's average cost from `x1` as `(c, r, k)`: `(c + r·M)/k`.
    /// `None` if there are more than `limit` policies.
    /// The bound is checked before anything is enumerated ([`Instance::policy_count`]).
    pub fn policy_averages(&self, limit: u64) -> Option<Vec<(i64, i64, i64)>> {
        let n = self.moves.len();
        // Only states reachable from x1 matter.
        let reach = self.reachable();
        let free: Vec<usize> = (0..n).filter(|&x| reach[x] && !self.is_goal[x]).collect();
        if free.iter().any(|&x| self.moves[x].is_empty()) {
            return Some(Vec::new());
        }
        let count = self.policy_count(limit)?;
        let mut choice = vec![0usize; n];
        let mut out = Vec::with_capacity(count as usize);
        loop {
            // Follow from x1.
            let mut seen_at = vec![usize::MAX; n];
            let mut costs = Vec::new();
            let mut x = self.initial;
            loop {
                if self.is_goal[x] {
                    let l: i64 = costs.iter().sum();
                    out.push((l, 1, costs.len() as i64 + 1));
                    break;
                }
                if seen_at[x] != usize::MAX {
                    let cyc = &costs[seen_at[x]..];
                    out.push((cyc.iter().sum(), 0, cyc.len() as i64));
                    break;
                }
                seen_at[x] = costs.len();
                let (y, c) = self.moves[x][choice[x]];
                costs.push(c);
                x = y;
            }
            let mut k = 0;
            loop {
                if k == free.len() {
                    return Some(out);
                }
                let x = free[k];
                choice[x] += 1;
                if choice[x] < self.moves[x].len() {
                    break;
                }
                choice[x] = 0;
                k += 1;
            }
        }
    }

    /// `Lav(Ĉ)` by Karp's algorithm, cross-checked against simple-cycle enumeration
    /// (`Err` on disagreement: an internal error).
    pub fn least_mean_cycle(&self) -> Result<Option<Q>, String> {
        let (n, arcs) = self.tiny_like();
        let karp = karp_minimum_mean_cycle(n, &arcs);
        let enumerated = simple_cycles(n, &arcs)
            .into_iter()
            .map(|(w, l)| Q::new(w as i128, l as i128))
            .min();
        if karp != enumerated {
            return Err(format!(
                "Karp {karp:?} disagrees with cycle enumeration {enumerated:?}"
            ));
        }
        Ok(karp)
    }
}

/// The three sets of bonuses for one choice of `π*` (one value of `S*`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct BonusSets {
    /// `L*`.
    pub optimal_cost: i64,
    /// `S*`.
    pub optimal_states: i64,
    /// `Lav(Ĉ)` (`None`: no goal-avoiding cycle reachable).
    pub least_mean_cycle: Option<Q>,
    /// The exact set, from the policy-enumeration oracle.
    pub exact: Interval,
    /// The printed formula's set (`None` when it divides by `L(u) = 0`).
    pub printed: Option<Interval>,
    /// The corrected formula's set.
    pub corrected: Interval,
}

/// The most states reachable from `x1` that [`bonus_analysis`] accepts: with integer costs
/// below 2^40 (as `verify --claim C4` scales them), every sum and product it forms then stays
/// below 2^63.
pub const MAX_BONUS_STATES: usize = 1024;

/// Why the exact bonus analysis of one problem refuses (issue 12: every search with a
/// combinatorial blow-up has an effort bound, named in the refusal).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BonusError {
    /// More stationary policies than the enumeration oracle's bound.
    #[error("more than {limit} stationary policies from x1 (the bound of the policy-enumeration oracle): too large for the exact bonus analysis")]
    TooManyPolicies {
        /// The bound.
        limit: u64,
    },
    /// The search for simple goal paths went past its step bound.
    #[error("the search for simple goal paths from x1 took more than {steps} steps (its bound): too large for the exact bonus analysis")]
    SearchTooLong {
        /// The bound.
        steps: u64,
    },
    /// Too many states for exact integer arithmetic.
    #[error("{states} states are reachable from x1; the exact bonus analysis takes at most {MAX_BONUS_STATES}")]
    TooManyStates {
        /// States reachable from `x1`.
        states: usize,
    },
    /// A cross-check failed (a truecost bug).
    #[error("internal error: {0}")]
    Internal(String),
}

/// Computes the bonus sets for every distinct `S*` of an optimal single-shot path. `Ok(None)`
/// if no goal is reachable or the effort bounds are exceeded (see [`bonus_analysis`]).
pub fn bonus_sets(inst: &Instance, limit: u64) -> Result<Option<Vec<BonusSets>>, String> {
    match bonus_analysis(inst, limit) {
        Ok(sets) => Ok(sets),
        Err(BonusError::Internal(e)) => Err(e),
        Err(_) => Ok(None),
    }
}

/// The bonus sets of C4 for every distinct `S*` of an optimal single-shot path (`Ok(None)`
/// if no goal is reachable from `x1`), refusing before or during the work when it would be
/// too large: more than [`MAX_BONUS_STATES`] reachable states, more than `limit` stationary
/// policies (counted before enumerating), or a goal-path search longer than
/// `limit × (states + 1)` steps (checked while it runs).
///
/// ```
/// use truecost::claims::c4::{bonus_analysis, BonusError, Instance};
/// // A 4 x 4 grid: 4^15 policies, refused at once.
/// let n = 16;
/// let moves = (0..n).map(|x: usize| {
///     let (r, c) = (x / 4, x % 4);
///     let mut m = Vec::new();
///     if c > 0 { m.push((x - 1, 1)); } if c < 3 { m.push((x + 1, 1)); }
///     if r > 0 { m.push((x - 4, 1)); } if r < 3 { m.push((x + 4, 1)); }
///     m
/// }).collect();
/// let mut is_goal = vec![false; n];
/// is_goal[15] = true;
/// let grid = Instance { initial: 0, is_goal, moves };
/// assert_eq!(bonus_analysis(&grid, 1 << 22), Err(BonusError::TooManyPolicies { limit: 1 << 22 }));
/// ```
pub fn bonus_analysis(inst: &Instance, limit: u64) -> Result<Option<Vec<BonusSets>>, BonusError> {
    let reach = inst.reachable();
    if !(0..inst.moves.len()).any(|x| reach[x] && inst.is_goal[x]) {
        return Ok(None);
    }
    let states = reach.iter().filter(|&&r| r).count();
    if states > MAX_BONUS_STATES {
        return Err(BonusError::TooManyStates { states });
    }
    if inst.policy_count(limit).is_none() {
        return Err(BonusError::TooManyPolicies { limit });
    }
    let paths = inst.goal_paths(limit.saturating_mul(states as u64 + 1))?;
    let Some(lstar) = paths.iter().map(|p| p.0).min() else {
        return Ok(None);
    };
    let Some(averages) = inst.policy_averages(limit) else {
        return Err(BonusError::TooManyPolicies { limit });
    };
    let lav = inst.least_mean_cycle().map_err(BonusError::Internal)?;
    // Cross-check Karp against the policies' goal-avoiding cycles.
    let from_policies = averages
        .iter()
        .filter(|a| a.1 == 0)
        .map(|a| Q::new(a.0 as i128, a.2 as i128))
        .min();
    if from_policies != lav {
        return Err(BonusError::Internal(format!(
            "Karp {lav:?} disagrees with the policies' cycles {from_policies:?}"
        )));
    }
    let mut sstars: Vec<i64> = paths.iter().filter(|p| p.0 == lstar).map(|p| p.1).collect();
    sstars.sort_unstable();
    sstars.dedup();
    let mut out = Vec::new();
    for &s in &sstars {
        // Exact: (L*+M)/S* <= (c + rM)/k for every policy, i.e. M(k − r S*) <= c S* − L* k.
        let mut exact = Interval::negative();
        for &(c, r, k) in &averages {
            let coef = k - r * s;
            let rhs = c * s - lstar * k;
            if coef > 0 {
                exact.at_most(Q::new(rhs as i128, coef as i128));
            } else if coef < 0 {
                exact.at_least(Q::new(rhs as i128, coef as i128));
            } else if rhs < 0 {
                exact.empty = true;
            }
        }
        let cycle_bound = lav.map(|l| Q::int(s as i128) * l - Q::int(lstar as i128));
        // Printed.
        let printed = if paths.iter().any(|p| p.1 != s && p.0 == 0) {
            None
        } else {
            let a_of = |l: i64, su: i64| {
                (Q::ONE - Q::new(su as i128, s as i128))
                    * (Q::new((su * lstar) as i128, (s * l) as i128) - Q::ONE)
            };
            let mut iv = Interval::negative();
            for &(l, su) in &paths {
                if su < s {
                    iv.at_least(a_of(l, su));
                } else if su > s {
                    iv.at_most(a_of(l, su));
                }
            }
            if let Some(cb) = cycle_bound {
                iv.at_most(cb);
            }
            Some(iv)
        };
        let mut corrected = Interval::negative();
        for &(l, su) in &paths {
            if su == s {
                continue;
            }
            let t = Q::new((s * l - su * lstar) as i128, (su - s) as i128);
            if su < s {
                corrected.at_least(t);
            } else {
                corrected.at_most(t);
            }
        }
        if let Some(cb) = cycle_bound {
            corrected.at_most(cb);
        }
        out.push(BonusSets {
            optimal_cost: lstar,
            optimal_states: s,
            least_mean_cycle: lav,
            exact,
            printed,
            corrected,
        });
    }
    Ok(Some(out))
}

/// A bonus in the symmetric difference of two sets (`None` if they are equal).
pub fn witness(a: &Interval, b: &Interval) -> Option<Q> {
    let mut pts: Vec<Q> = a
        .ends()
        .into_iter()
        .chain(b.ends())
        .filter(|q| *q < Q::ZERO)
        .collect();
    pts.sort();
    pts.dedup();
    let mut cands = pts.clone();
    for w in pts.windows(2) {
        cands.push((w[0] + w[1]) * Q::new(1, 2));
    }
    match (pts.first(), pts.last()) {
        (Some(&lo), Some(&hi)) => {
            cands.push(lo - Q::ONE);
            cands.push(hi * Q::new(1, 2));
        }
        _ => cands.push(-Q::ONE),
    }
    cands.sort();
    cands
        .into_iter()
        .find(|&m| m < Q::ZERO && a.contains(m) != b.contains(m))
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
    let started = std::time::Instant::now();
    let mut acc = Acc::default();
    let mut parts = Vec::new();
    for spec in specs(scope) {
        let (a, _) = enumerate(
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
                    if let Some(m) = witness(&s.corrected, &s.exact) {
                        acc.corrected_failures += 1;
                        keep_min(&mut acc.corrected_min, key, || Finding {
                            t: *t,
                            sets: s.clone(),
                            m,
                        });
                    }
                }
            },
            merge,
        );
        acc = merge(acc, a);
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

//! Claim C4 (docs/spec.md §6): episodic equivalence — the exact bonus analysis. The single-shot
//! problem versus the infinite-horizon average-cost problem in which reaching the goal resets
//! to `x1` with bonus `M < 0` (the reset is one stage costing `M`; a path with `S` states is a
//! reset cycle of `S` stages and cost `L + M`).
//!
//! For every distinct `S*` of an optimal single-shot path, [`bonus_analysis`] computes three
//! sets of bonuses: the exact one (policy-enumeration oracle: every stationary policy's average
//! from `x1` is `(c + r·M)/k`, `r = 1` for a reset cycle; the set is the intersection of the
//! half-lines where `π*`'s average is least), the printed formula's
//! (`a ≤ M ≤ min{b, S*·Lav(Ĉ) − L*}` with `A(u) = (1 − S(u)/S*)·(S(u)·L*/(S*·L(u)) − 1)`) and
//! the corrected one (`max_{S(u)<S*} T(u) ≤ M ≤ min{ min_{S(u)>S*} T(u), S*·Lav(Ĉ) − L* }`,
//! `T(u) = (S*·L(u) − S(u)·L*) / (S(u) − S*)`). `Lav(Ĉ)` by Karp's algorithm, cross-checked
//! against the enumeration of simple cycles and of policies. The statements and the claim
//! runner are `truecost::claims::c4`.

use std::fmt;

use super::exact::{ExactInt, Q};
use super::oracle::{
    karp_minimum_mean_cycle_in, simple_cycles, simple_paths, with_search_space, Step,
};
use super::tiny::Tiny;

/// A problem type that converts to an [`Instance`] with integer costs and its scale `D`
/// ([`Instance::from_problem`]); implemented by `truecost::model::Problem` with
/// `Scale = BigInt`.
pub trait ToInstance {
    /// The common scale `D` of the costs (a big integer in `truecost`).
    type Scale;
    /// The instance with every cost times `D`, and `D`; an error (one line) when a scaled cost
    /// does not fit the exact bonus analysis.
    fn to_instance(&self) -> Result<(Instance, Self::Scale), String>;
}

/// One end of an interval of bonuses (exact rationals over `I`, `i128` unless stated).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum End<I: ExactInt = i128> {
    /// Unbounded (`-∞` below, `+∞` above).
    Unbounded,
    /// Included.
    Closed(Q<I>),
    /// Excluded.
    Open(Q<I>),
}

/// A convex set of rationals `{M : lo ≤/< M ≤/< hi}`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Interval<I: ExactInt = i128> {
    /// Lower end.
    pub lo: End<I>,
    /// Upper end.
    pub hi: End<I>,
    /// Whether the set is empty.
    pub empty: bool,
}

impl<I: ExactInt> Interval<I> {
    /// `M < 0`.
    pub fn negative() -> Interval<I> {
        Interval {
            lo: End::Unbounded,
            hi: End::Open(Q::zero()),
            empty: false,
        }
    }

    /// Whether `m` belongs to the set.
    pub fn contains(&self, m: Q<I>) -> bool {
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
    pub fn at_least(&mut self, lo: Q<I>) {
        self.lo = match self.lo {
            End::Closed(a) | End::Open(a) if a > lo => self.lo,
            End::Open(a) if a == lo => self.lo,
            _ => End::Closed(lo),
        };
        self.normalise();
    }

    /// Intersects with `(-∞, hi]` (closed).
    pub fn at_most(&mut self, hi: Q<I>) {
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
    pub fn same_set(&self, o: &Interval<I>) -> bool {
        (self.empty && o.empty) || (!self.empty && !o.empty && self.lo == o.lo && self.hi == o.hi)
    }

    /// The finite ends.
    fn ends(&self) -> Vec<Q<I>> {
        let mut v = Vec::new();
        for e in [self.lo, self.hi] {
            if let End::Closed(q) | End::Open(q) = e {
                v.push(q);
            }
        }
        v
    }
}

impl<I: ExactInt> fmt::Display for Interval<I> {
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
    /// the caller divides the thresholds back). Returns the instance and `D`. Generic over the
    /// problem type (see [`ToInstance`]: `truecost::model::Problem`, whose `D` is a `BigInt`),
    /// so that this crate, which Kani verifies, depends on no big-integer crate.
    /// Errors are one line (the scaled costs must stay below 2^40).
    pub fn from_problem<P: ToInstance>(problem: &P) -> Result<(Instance, P::Scale), String> {
        problem.to_instance()
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
        // A stack of fixed capacity: every state enters it at most once.
        let mut stack = vec![0usize; n];
        stack[0] = self.initial;
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let x = stack[len];
            for &(y, _) in &self.moves[x] {
                if !self.is_goal[y] && !seen[y] {
                    seen[y] = true;
                    stack[len] = y;
                    len += 1;
                }
            }
        }
        // The arcs among them, counted and then written into a buffer of that length.
        let seen = &seen;
        let among = |x: usize| {
            self.moves[x]
                .iter()
                .filter(move |&&(y, _)| seen[x] && seen[y])
        };
        let count: usize = (0..n).map(|x| among(x).count()).sum();
        let mut arcs = vec![(0usize, 0usize, 0i64); count];
        let mut len = 0;
        for x in 0..n {
            for &(y, c) in among(x) {
                arcs[len] = (x, y, c);
                len += 1;
            }
        }
        (n, arcs)
    }

    /// Every simple path from `x1` to a goal as `(L, S)`, in depth-first order (moves in each
    /// state's order), or `Err(BonusError::SearchTooLong)` once the depth-first search has
    /// taken more than `max_steps` steps (one per node of its search tree; the bound is checked
    /// while the search runs, so a grid refuses at once instead of listing its astronomically
    /// many paths). The search is iterative, on a stack of fixed capacity.
    ///
    /// ```
    /// use truecost_kernel::claims::c4::{BonusError, Instance};
    /// // x1 = 0 -> 1 -> goal 2, and 0 -> goal 2 directly.
    /// let inst = Instance { initial: 0, is_goal: vec![false, false, true],
    ///     moves: vec![vec![(1, 1), (2, 5)], vec![(2, 1)], vec![]] };
    /// let mut paths = inst.goal_paths(100).unwrap();
    /// paths.sort();
    /// assert_eq!(paths, vec![(2, 3), (5, 2)]);
    /// assert_eq!(inst.goal_paths(2), Err(BonusError::SearchTooLong { steps: 2 }));
    /// ```
    pub fn goal_paths(&self, max_steps: u64) -> Result<Vec<(i64, i64)>, BonusError> {
        // One step per node of the search tree: x1, then every arc that ends or extends a path.
        let too_long = BonusError::SearchTooLong { steps: max_steps };
        let mut steps = 1u64;
        if steps > max_steps {
            return Err(too_long);
        }
        if self.is_goal[self.initial] {
            return Ok(vec![(0, 1)]);
        }
        // Two runs of one search: the first counts the paths (and stops past `max_steps`), the
        // second writes them into a buffer of that length.
        let mut count = 0;
        self.each_goal_path(
            || {
                steps += 1;
                if steps > max_steps {
                    return Err(too_long.clone());
                }
                Ok(())
            },
            |_, _| count += 1,
        )?;
        let mut out = vec![(0i64, 0i64); count];
        let mut len = 0;
        self.each_goal_path(
            || Ok(()),
            |cost, states| {
                out[len] = (cost, states);
                len += 1;
            },
        )?;
        Ok(out)
    }

    /// The depth-first search of [`Instance::goal_paths`] from a non-goal `x1`: `step()` is
    /// called at every arc that ends or extends a path (an error stops the search), then
    /// `found(L, S)` at every simple path to a goal.
    fn each_goal_path(
        &self,
        mut step: impl FnMut() -> Result<(), BonusError>,
        mut found: impl FnMut(i64, i64),
    ) -> Result<(), BonusError> {
        with_search_space(self.moves.len(), |frames, on| {
            simple_paths(
                frames,
                on,
                self.initial,
                |x, k| self.moves[x].get(k).copied(),
                |y, on| {
                    if on {
                        Step::Skip
                    } else if self.is_goal[y] {
                        Step::End
                    } else {
                        Step::Enter
                    }
                },
                |s, cost, moves| {
                    step()?;
                    if s == Step::End {
                        found(cost, moves as i64 + 1);
                    }
                    Ok(())
                },
            )
        })
    }

    /// The states reachable from `x1` without passing through a goal (goals reached included).
    fn reachable(&self) -> Vec<bool> {
        let n = self.moves.len();
        let mut reach = vec![false; n];
        reach[self.initial] = true;
        // A stack of fixed capacity: every state enters it at most once.
        let mut stack = vec![0usize; n];
        stack[0] = self.initial;
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let x = stack[len];
            if self.is_goal[x] {
                continue;
            }
            for &(y, _) in &self.moves[x] {
                if !reach[y] {
                    reach[y] = true;
                    stack[len] = y;
                    len += 1;
                }
            }
        }
        reach
    }

    /// The number of stationary policies over the non-goal states reachable from `x1`
    /// (`Π |U(x)|`), or `None` as soon as it exceeds `limit` (computed without enumerating).
    ///
    /// ```
    /// use truecost_kernel::claims::c4::Instance;
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
        // The non-goal states reachable from x1: the first `free_len` entries of `free`.
        let mut free = vec![0usize; n];
        let mut free_len = 0;
        for x in (0..n).filter(|&x| reach[x] && !self.is_goal[x]) {
            free[free_len] = x;
            free_len += 1;
        }
        let free = &free[..free_len];
        if free.iter().any(|&x| self.moves[x].is_empty()) {
            return Some(Vec::new());
        }
        let count = self.policy_count(limit)?;
        let mut choice = vec![0usize; n];
        // One average per policy, `count` in all, written in order.
        let mut out = vec![(0i64, 0i64, 0i64); count as usize];
        let mut len = 0;
        // The stage costs of the trajectory followed: at most one per state before a goal or
        // a repeated state, so `n` entries, the first `steps` of them in use.
        let mut costs = vec![0i64; n];
        loop {
            // Follow from x1.
            let mut seen_at = vec![usize::MAX; n];
            let mut steps = 0;
            let mut x = self.initial;
            loop {
                if self.is_goal[x] {
                    let l: i64 = costs[..steps].iter().sum();
                    out[len] = (l, 1, steps as i64 + 1);
                    len += 1;
                    break;
                }
                if seen_at[x] != usize::MAX {
                    let cyc = &costs[seen_at[x]..steps];
                    out[len] = (cyc.iter().sum(), 0, cyc.len() as i64);
                    len += 1;
                    break;
                }
                seen_at[x] = steps;
                let (y, c) = self.moves[x][choice[x]];
                costs[steps] = c;
                steps += 1;
                x = y;
            }
            let mut k = 0;
            loop {
                if k == free.len() {
                    debug_assert_eq!(len, out.len());
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
        self.least_mean_cycle_in().map_err(|e| e.to_string())
    }

    /// [`Instance::least_mean_cycle`] in exact rationals over `I`; a disagreement is returned
    /// with the two values, formatted only when printed.
    pub fn least_mean_cycle_in<I: ExactInt>(&self) -> Result<Option<Q<I>>, InternalError> {
        let (n, arcs) = self.tiny_like();
        let karp = karp_minimum_mean_cycle_in::<I>(n, &arcs);
        let enumerated = simple_cycles(n, &arcs)
            .into_iter()
            .map(|(w, l)| Q::from_i64s(w, l as i64))
            .min();
        if karp != enumerated {
            return Err(InternalError::KarpVersusCycles {
                karp: wide(karp),
                enumerated: wide(enumerated),
            });
        }
        Ok(karp)
    }
}

/// The three sets of bonuses for one choice of `π*` (one value of `S*`).
#[derive(Clone, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BonusSets<I: ExactInt = i128> {
    /// `L*`.
    pub optimal_cost: i64,
    /// `S*`.
    pub optimal_states: i64,
    /// `Lav(Ĉ)` (`None`: no goal-avoiding cycle reachable).
    pub least_mean_cycle: Option<Q<I>>,
    /// The exact set, from the policy-enumeration oracle.
    pub exact: Interval<I>,
    /// The printed formula's set (`None` when it divides by `L(u) = 0`, or when not asked
    /// for: [`bonus_analysis_in`]).
    pub printed: Option<Interval<I>>,
    /// The corrected formula's set.
    pub corrected: Interval<I>,
}

/// The most states reachable from `x1` that [`bonus_analysis`] accepts: with integer costs
/// below 2^40 (as `verify --claim C4` scales them), every sum and product it forms then stays
/// below 2^63.
pub const MAX_BONUS_STATES: usize = 1024;

/// Why the exact bonus analysis of one problem refuses (every search with a
/// combinatorial blow-up has an effort bound, named in the refusal).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BonusError {
    /// More stationary policies than the enumeration oracle's bound.
    TooManyPolicies {
        /// The bound.
        limit: u64,
    },
    /// The search for simple goal paths went past its step bound.
    SearchTooLong {
        /// The bound.
        steps: u64,
    },
    /// Too many states for exact integer arithmetic.
    TooManyStates {
        /// States reachable from `x1`.
        states: usize,
    },
    /// A cross-check failed (a truecost bug).
    Internal(InternalError),
}

/// A failed cross-check of the exact bonus analysis (a truecost bug), with the values that
/// disagree: exact rationals as `(numerator, denominator)` in `i128` (every width widens
/// exactly), formatted only when printed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum InternalError {
    /// Karp's least mean cycle differs from the least mean over the enumerated simple cycles.
    KarpVersusCycles {
        /// Karp's `Lav(Ĉ)` (`None`: no cycle).
        karp: Option<(i128, i128)>,
        /// The enumeration's.
        enumerated: Option<(i128, i128)>,
    },
    /// Karp's least mean cycle differs from the least average of the goal-avoiding policies.
    KarpVersusPolicies {
        /// Karp's `Lav(Ĉ)` (`None`: no cycle).
        karp: Option<(i128, i128)>,
        /// The policies'.
        policies: Option<(i128, i128)>,
    },
    /// Any other, as a message.
    Message(String),
}

/// `q`'s numerator and denominator in `i128`.
fn wide<I: ExactInt>(q: Option<Q<I>>) -> Option<(i128, i128)> {
    q.map(|q| (q.numer().to_i128(), q.denom().to_i128()))
}

/// Writes `q` as `{:?}` writes an `Option<Q>` (`Some(Q { n: 3, d: 2 })`, `None`).
fn write_rational(f: &mut fmt::Formatter<'_>, q: Option<(i128, i128)>) -> fmt::Result {
    match q {
        Some((n, d)) => write!(f, "Some(Q {{ n: {n}, d: {d} }})"),
        None => write!(f, "None"),
    }
}

impl fmt::Display for InternalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InternalError::KarpVersusCycles { karp, enumerated } => {
                write!(f, "Karp ")?;
                write_rational(f, *karp)?;
                write!(f, " disagrees with cycle enumeration ")?;
                write_rational(f, *enumerated)
            }
            InternalError::KarpVersusPolicies { karp, policies } => {
                write!(f, "Karp ")?;
                write_rational(f, *karp)?;
                write!(f, " disagrees with the policies' cycles ")?;
                write_rational(f, *policies)
            }
            InternalError::Message(m) => write!(f, "{m}"),
        }
    }
}

impl From<&str> for InternalError {
    fn from(m: &str) -> InternalError {
        InternalError::Message(m.to_string())
    }
}

impl From<String> for InternalError {
    fn from(m: String) -> InternalError {
        InternalError::Message(m)
    }
}

/// Computes the bonus sets for every distinct `S*` of an optimal single-shot path. `Ok(None)`
/// if no goal is reachable or the effort bounds are exceeded (see [`bonus_analysis`]).
pub fn bonus_sets(inst: &Instance, limit: u64) -> Result<Option<Vec<BonusSets>>, String> {
    match bonus_analysis(inst, limit) {
        Ok(sets) => Ok(sets),
        Err(BonusError::Internal(e)) => Err(e.to_string()),
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
/// use truecost_kernel::claims::c4::{bonus_analysis, BonusError, Instance};
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
    bonus_analysis_in(inst, limit, true)
}

/// [`bonus_analysis`] in exact rationals over `I` (checked: a value that does not fit `I`
/// panics); the printed formula's set is computed only if `printed` is true (otherwise every
/// `printed` is `None`).
pub fn bonus_analysis_in<I: ExactInt>(
    inst: &Instance,
    limit: u64,
    printed: bool,
) -> Result<Option<Vec<BonusSets<I>>>, BonusError> {
    let with_printed = printed;
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
    let lav = inst
        .least_mean_cycle_in::<I>()
        .map_err(BonusError::Internal)?;
    // Cross-check Karp against the policies' goal-avoiding cycles.
    let from_policies = averages
        .iter()
        .filter(|a| a.1 == 0)
        .map(|a| Q::from_i64s(a.0, a.2))
        .min();
    if from_policies != lav {
        return Err(BonusError::Internal(InternalError::KarpVersusPolicies {
            karp: wide(lav),
            policies: wide(from_policies),
        }));
    }
    // The distinct `S*` in increasing order: each the least `S` of an optimal path above the
    // previous one (a scan of the paths per value; nothing is sorted); at most one per path.
    let mut optimal_states = vec![0i64; paths.len()];
    let mut distinct = 0;
    let mut previous = None;
    while let Some(s) = paths
        .iter()
        .filter(|p| p.0 == lstar && previous.is_none_or(|q| p.1 > q))
        .map(|p| p.1)
        .min()
    {
        previous = Some(s);
        optimal_states[distinct] = s;
        distinct += 1;
    }
    let sets_for = |s: i64| {
        // Exact: (L*+M)/S* <= (c + rM)/k for every policy, i.e. M(k − r S*) <= c S* − L* k.
        let mut exact = Interval::negative();
        for &(c, r, k) in &averages {
            let coef = k - r * s;
            let rhs = c * s - lstar * k;
            if coef > 0 {
                exact.at_most(Q::from_i64s(rhs, coef));
            } else if coef < 0 {
                exact.at_least(Q::from_i64s(rhs, coef));
            } else if rhs < 0 {
                exact.empty = true;
            }
        }
        let cycle_bound =
            lav.map(|l| Q::integer(I::from_i64(s)) * l - Q::integer(I::from_i64(lstar)));
        // Printed.
        let printed = if !with_printed || paths.iter().any(|p| p.1 != s && p.0 == 0) {
            None
        } else {
            let a_of = |l: i64, su: i64| {
                (Q::one() - Q::from_i64s(su, s)) * (Q::from_i64s(su * lstar, s * l) - Q::one())
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
            let t = Q::from_i64s(s * l - su * lstar, su - s);
            if su < s {
                corrected.at_least(t);
            } else {
                corrected.at_most(t);
            }
        }
        if let Some(cb) = cycle_bound {
            corrected.at_most(cb);
        }
        BonusSets {
            optimal_cost: lstar,
            optimal_states: s,
            least_mean_cycle: lav,
            exact,
            printed,
            corrected,
        }
    };
    Ok(Some(
        optimal_states[..distinct]
            .iter()
            .map(|&s| sets_for(s))
            .collect(),
    ))
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

impl fmt::Display for BonusError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BonusError::TooManyPolicies { limit } => write!(f, "more than {limit} stationary policies from x1 (the bound of the policy-enumeration oracle): too large for the exact bonus analysis"),
            BonusError::SearchTooLong { steps } => write!(f, "the search for simple goal paths from x1 took more than {steps} steps (its bound): too large for the exact bonus analysis"),
            BonusError::TooManyStates { states } => write!(f, "{states} states are reachable from x1; the exact bonus analysis takes at most {MAX_BONUS_STATES}"),
            BonusError::Internal(e) => write!(f, "internal error: {e}"),
        }
    }
}

impl std::error::Error for BonusError {}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failed cross-check prints the values as `{:?}` prints them (`Some(Q { n: .., d: .. })`),
    /// in the message the CLI shows.
    #[test]
    fn internal_errors_print_the_values_that_disagree() {
        let (a, b) = (Some(Q::<i16>::ratio(-3, 2)), None::<Q<i16>>);
        let cycles = BonusError::Internal(InternalError::KarpVersusCycles {
            karp: super::wide(a),
            enumerated: super::wide(b),
        });
        assert_eq!(
            cycles.to_string(),
            format!("internal error: Karp {a:?} disagrees with cycle enumeration {b:?}")
        );
        let (a, b) = (Some(Q::new(7, 1)), Some(Q::new(5, 3)));
        let policies = InternalError::KarpVersusPolicies {
            karp: super::wide(a),
            policies: super::wide(b),
        };
        assert_eq!(
            policies.to_string(),
            format!("Karp {a:?} disagrees with the policies' cycles {b:?}")
        );
        assert_eq!(
            policies.to_string(),
            "Karp Some(Q { n: 7, d: 1 }) disagrees with the policies' cycles Some(Q { n: 5, d: 3 })"
        );
    }

    fn wide(q: Q<i16>) -> Q {
        Q::new(q.numer() as i128, q.denom() as i128)
    }

    fn wide_end(e: End<i16>) -> End {
        match e {
            End::Unbounded => End::Unbounded,
            End::Closed(q) => End::Closed(wide(q)),
            End::Open(q) => End::Open(wide(q)),
        }
    }

    fn wide_interval(i: Interval<i16>) -> Interval {
        Interval {
            lo: wide_end(i.lo),
            hi: wide_end(i.hi),
            empty: i.empty,
        }
    }

    /// The analysis at 16 bits gives the product's (`i128`) sets on every 3-state problem with
    /// 1–2 moves per non-goal state and costs 0, 1 or 7; without the printed formula when not
    /// asked for.
    #[test]
    fn sixteen_bit_analysis_agrees_with_i128() {
        let costs = [0u8, 1, 7];
        let mut checked = 0;
        for code in 0..(3u32 * 3 * 3).pow(2) * 4 {
            let mut c = code;
            let mut lists: Vec<Vec<(u8, u8)>> = vec![Vec::new(), Vec::new(), Vec::new()];
            for x in 0..2 {
                let deg = 1 + (c % 2) as usize;
                c /= 2;
                for _ in 0..deg {
                    let (to, cost) = ((c % 3) as u8, costs[(c / 3 % 3) as usize]);
                    c /= 9;
                    lists[x].push((to, cost));
                }
            }
            let t = Tiny::from_lists(&lists);
            let inst = Instance::from_tiny(&t);
            let full = bonus_analysis(&inst, 1 << 12).expect("within bounds");
            let narrow = bonus_analysis_in::<i16>(&inst, 1 << 12, true).expect("within bounds");
            let lean = bonus_analysis_in::<i16>(&inst, 1 << 12, false).expect("within bounds");
            assert_eq!(full.is_some(), narrow.is_some());
            let (Some(full), Some(narrow), Some(lean)) = (full, narrow, lean) else {
                continue;
            };
            for ((f, n), l) in full.iter().zip(&narrow).zip(&lean) {
                assert_eq!(f.exact, wide_interval(n.exact));
                assert_eq!(f.corrected, wide_interval(n.corrected));
                assert_eq!(f.printed, n.printed.map(wide_interval));
                assert_eq!(f.least_mean_cycle, n.least_mean_cycle.map(wide));
                assert_eq!(
                    (l.exact, l.corrected, l.printed),
                    (n.exact, n.corrected, None)
                );
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }
}

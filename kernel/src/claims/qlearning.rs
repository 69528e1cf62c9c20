//! A tiny, self-contained derandomized Q-learning (docs/spec.md §2, `ρ = 1`) for checking claim C1:
//! `Q̂(x,u) ← l(x,u) + min_{u'} Q̂(f(x,u), u')`, one state–action pair at a time, in an order
//! chosen by the caller (or by an adversary that explores every order).
//!
//! The pairs are every move of every state plus, at the goal, the termination action `uT`
//! (`f(xg, uT) = xg`, `l = 0`, docs/spec.md §1). Two treatments of `uT`:
//! * [`Terminal::Updated`] — as printed: `uT` is an ordinary pair, updated by the same rule
//!   (a zero-cost self-loop).
//! * [`Terminal::HeldAtZero`] — the episodic convention: `Q̂(xg, uT) = 0` always.

use std::collections::{HashMap, HashSet};

use super::oracle::optimal_cost_to_go;
use super::tiny::{Tiny, MAX_STATES};

/// Largest number of state–action pairs.
pub const MAX_PAIRS: usize = 24;

/// Values of all pairs.
pub type Values = [i64; MAX_PAIRS];

/// How the goal's termination pair is treated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Terminal {
    /// Updated by the `ρ = 1` rule like every pair (as printed).
    Updated,
    /// Held at 0 (the episodic convention).
    HeldAtZero,
}

/// One state–action pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pair {
    /// `x`.
    pub state: u8,
    /// `f(x, u)`.
    pub to: u8,
    /// `l(x, u)`.
    pub cost: i64,
    /// Whether this is the termination action of the goal.
    pub terminal: bool,
}

/// A problem prepared for derandomized Q-learning.
#[derive(Clone, Debug)]
pub struct QProblem {
    /// The pairs, grouped by state (the goal's termination pair first among its pairs).
    pub pairs: Vec<Pair>,
    /// Pairs of state `x` are `first[x]..first[x + 1]`.
    pub first: [usize; MAX_STATES + 1],
    /// Treatment of `uT`.
    pub terminal: Terminal,
    /// `Q*` of every pair (`None` = `+∞`), from the policy-enumeration oracle.
    pub optimum: Vec<Option<i64>>,
    /// `G*` of every state (`None` = `+∞`).
    pub cost_to_go: [Option<i64>; MAX_STATES],
    /// Number of states.
    pub states: usize,
}

impl QProblem {
    /// Prepares `t`, computing `Q*` by enumerating policies ([`optimal_cost_to_go`]).
    pub fn new(t: &Tiny, terminal: Terminal) -> QProblem {
        let mut pairs = Vec::new();
        let mut first = [0usize; MAX_STATES + 1];
        for x in 0..t.states() {
            first[x] = pairs.len();
            if t.is_goal(x) {
                pairs.push(Pair {
                    state: x as u8,
                    to: x as u8,
                    cost: 0,
                    terminal: true,
                });
            }
            for m in t.moves(x) {
                pairs.push(Pair {
                    state: x as u8,
                    to: m.to,
                    cost: m.cost as i64,
                    terminal: false,
                });
            }
        }
        for f in first.iter_mut().skip(t.states()) {
            *f = pairs.len();
        }
        assert!(pairs.len() <= MAX_PAIRS);
        let cost_to_go = optimal_cost_to_go(t);
        let optimum = pairs
            .iter()
            .map(|p| {
                if p.terminal {
                    Some(0)
                } else {
                    cost_to_go[p.to as usize].map(|g| p.cost + g)
                }
            })
            .collect();
        QProblem {
            pairs,
            first,
            terminal,
            optimum,
            cost_to_go,
            states: t.states(),
        }
    }

    /// Number of pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    /// Whether there are no pairs (never: every problem has a goal).
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Whether pair `p` is updated at all (false for a held termination pair).
    pub fn updatable(&self, p: usize) -> bool {
        !(self.pairs[p].terminal && self.terminal == Terminal::HeldAtZero)
    }

    /// The `ρ = 1` update of pair `p`, in place: `Q̂(x,u) ← l(x,u) + min_{u'} Q̂(f(x,u), u')`.
    ///
    /// Contract (proved by `proofs::contracts::update_is_the_rho_one_rule`): for a pair `p`
    /// whose successor has pairs and whose new value fits an `i64`, [`update_spec`] holds
    /// between the values before and after.
    ///
    /// ```
    /// use truecost_kernel::claims::qlearning::{QProblem, Terminal};
    /// use truecost_kernel::claims::tiny::Tiny;
    /// // 0 -> 1 (goal) with cost 2: pairs are (0, ->1) and (1, uT).
    /// let q = QProblem::new(&Tiny::from_lists(&[vec![(1, 2)], vec![]]), Terminal::HeldAtZero);
    /// let mut v = [0i64; 24];
    /// v[0] = 7;
    /// q.update(&mut v, 0);
    /// assert_eq!(v[0], 2);
    /// ```
    #[kani::requires(self.update_is_defined(v, p))]
    #[kani::modifies(&v[p])]
    #[kani::ensures(|_| update_spec(self, &old(*v), v[p], p))]
    #[inline]
    pub fn update(&self, v: &mut Values, p: usize) {
        if !self.updatable(p) {
            return;
        }
        let pair = self.pairs[p];
        let y = pair.to as usize;
        let mut best = i64::MAX;
        for &value in &v[self.first[y]..self.first[y + 1]] {
            best = best.min(value);
        }
        v[p] = pair.cost + best;
    }

    /// The precondition of [`QProblem::update`]: `p` is a pair, the pair ranges of its
    /// successor lie within the values, are non-empty, and `l(x,u) + min` fits an `i64`.
    pub fn update_is_defined(&self, v: &Values, p: usize) -> bool {
        let Some(pair) = self.pairs.get(p) else {
            return false;
        };
        if !self.updatable(p) {
            return true;
        }
        let y = pair.to as usize;
        let (Some(&from), Some(&to)) = (self.first.get(y), self.first.get(y + 1)) else {
            return false;
        };
        from < to && to <= MAX_PAIRS && (from..to).all(|q| pair.cost.checked_add(v[q]).is_some())
    }

    /// Whether `v` equals `Q*` on every pair (false if some `Q*` is `+∞`).
    pub fn is_optimal(&self, v: &Values) -> bool {
        self.optimum
            .iter()
            .enumerate()
            .all(|(p, q)| *q == Some(v[p]))
    }

    /// Whether every state can reach the goal (`Q*` finite everywhere).
    pub fn all_finite(&self) -> bool {
        self.optimum.iter().all(Option::is_some)
    }

    /// `h(x)`: the fewest moves to the goal along optimal moves (`None` if unreachable).
    pub fn optimal_steps(&self) -> [Option<u32>; MAX_STATES] {
        let mut h = [None; MAX_STATES];
        let states = self.states;
        for x in 0..states {
            if self.pairs[self.first[x]..self.first[x + 1]]
                .iter()
                .any(|p| p.terminal)
            {
                h[x] = Some(0);
            }
        }
        loop {
            let mut changed = false;
            for x in 0..states {
                let Some(g) = self.cost_to_go[x] else {
                    continue;
                };
                for p in &self.pairs[self.first[x]..self.first[x + 1]] {
                    if p.terminal {
                        continue;
                    }
                    let y = p.to as usize;
                    if let (Some(gy), Some(hy)) = (self.cost_to_go[y], h[y]) {
                        if p.cost + gy == g && h[x].is_none_or(|hx| hy + 1 < hx) {
                            h[x] = Some(hy + 1);
                            changed = true;
                        }
                    }
                }
            }
            if !changed {
                return h;
            }
        }
    }

    /// The bound of C1-corrected on the number of rounds (see `c1`): `R₁ = 1 + max h(f(x,u))`
    /// over move pairs when `Q₀ ≥ Q*`; otherwise, with every move cost `≥ c > 0`,
    /// `max(R₁, ⌈(max Q* − min(0, min Q₀)) / c⌉)`. `None` if neither hypothesis holds.
    pub fn round_bound(&self, q0: &Values) -> Option<u64> {
        let h = self.optimal_steps();
        let moves: Vec<usize> = (0..self.len())
            .filter(|&p| !self.pairs[p].terminal)
            .collect();
        let r1 = moves
            .iter()
            .map(|&p| h[self.pairs[p].to as usize].map(|k| k as u64 + 1))
            .try_fold(0u64, |acc, k| k.map(|k| acc.max(k)))?;
        let above = moves
            .iter()
            .all(|&p| self.optimum[p].is_some_and(|q| q0[p] >= q));
        if above {
            return Some(r1);
        }
        let c = moves.iter().map(|&p| self.pairs[p].cost).min()?;
        if c <= 0 {
            return None;
        }
        let qmax = moves
            .iter()
            .map(|&p| self.optimum[p])
            .try_fold(0i64, |a, q| q.map(|q| a.max(q)))?;
        let m = moves.iter().map(|&p| q0[p]).min().unwrap_or(0).min(0);
        let gap = qmax - m;
        let r2 = if gap <= 0 {
            0
        } else {
            ((gap + c - 1) / c) as u64
        };
        Some(r1.max(r2))
    }
}

/// The guarantee of [`QProblem::update`] on pair `p`, from the values `before` the update to
/// the pair's value `after` it (the `ρ = 1` rule, stated as a minimum rather than
/// computed): a held termination pair keeps its value; otherwise the new value is
/// `l(x,u) + Q̂(f(x,u), u')` for some pair `u'` of the successor and at most that for every one.
/// No other value changes: the contract's `modifies(&v[p])`, which Kani checks (the stand-in's
/// proof harness asserts it).
pub fn update_spec(q: &QProblem, before: &Values, after: i64, p: usize) -> bool {
    if !q.updatable(p) {
        return after == before[p];
    }
    let pair = q.pairs[p];
    let y = pair.to as usize;
    let successors = q.first[y]..q.first[y + 1];
    let candidate = |k: usize| pair.cost.checked_add(before[k]);
    successors
        .clone()
        .all(|k| candidate(k).is_some_and(|c| after <= c))
        && successors.clone().any(|k| candidate(k) == Some(after))
}

/// A fair update order made of rounds; in each round every updatable pair is updated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Order {
    /// Pairs in index order, every round.
    Cyclic,
    /// Pairs in reverse index order, every round.
    Reverse,
    /// The adversary: pairs whose successor is farthest from the goal (largest `h`, `+∞` first)
    /// first, so that information travels one step per round.
    FarFirst,
    /// A fresh pseudo-random permutation every round (seeded).
    Random(u64),
}

/// The result of running derandomized Q-learning under one order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Run {
    /// `Q̂ = Q*` at the end of this round (0 = initially) and from then on.
    Converged(u64),
    /// The round-end values repeat without being `Q*`: under this periodic order `Q̂ ≠ Q*`
    /// forever. `(first round of the repetition, period)`.
    Cycles(u64, u64),
    /// Not `Q*` after this many rounds (non-periodic orders only).
    NotWithin(u64),
}

/// Runs `q0` under `order` for at most `max_rounds` rounds.
pub fn run(q: &QProblem, q0: &Values, order: Order, max_rounds: u64) -> Run {
    let p = q.len();
    let mut sequence: Vec<usize> = (0..p).filter(|&i| q.updatable(i)).collect();
    match order {
        Order::Cyclic | Order::Random(_) => {}
        Order::Reverse => sequence.reverse(),
        Order::FarFirst => {
            let h = q.optimal_steps();
            sequence.sort_by_key(|&i| {
                let y = q.pairs[i].to as usize;
                (std::cmp::Reverse(h[y].map_or(u64::MAX, |k| k as u64)), i)
            });
        }
    }
    let mut rng_state = match order {
        Order::Random(seed) => seed ^ 0x9E37_79B9_7F4A_7C15,
        _ => 0,
    };
    let mut v = *q0;
    let mut history: Vec<Values> = vec![v];
    if q.is_optimal(&v) {
        return Run::Converged(0);
    }
    for round in 1..=max_rounds {
        if let Order::Random(_) = order {
            // Fisher–Yates with a splitmix64 stream: portable and reproducible.
            for i in (1..sequence.len()).rev() {
                rng_state = rng_state.wrapping_add(0x9E37_79B9_7F4A_7C15);
                let mut z = rng_state;
                z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
                z ^= z >> 31;
                sequence.swap(i, (z % (i as u64 + 1)) as usize);
            }
        }
        for &i in &sequence {
            q.update(&mut v, i);
        }
        if q.is_optimal(&v) {
            return Run::Converged(round);
        }
        if !matches!(order, Order::Random(_)) {
            if let Some(k) = history.iter().position(|h| *h == v) {
                return Run::Cycles(k as u64, round - k as u64);
            }
            history.push(v);
        }
    }
    Run::NotWithin(max_rounds)
}

/// The verdict of exploring **every** fair order (each round: a sequence of updates that ends
/// as soon as every updatable pair has occurred in it at least once).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AllOrders {
    /// Under every fair order `Q̂ = Q*` after at most this many rounds (and the bound is attained
    /// by some order).
    Converges(u64),
    /// Some fair order never reaches `Q*` (a reachable cycle of round-end values avoiding `Q*`).
    Diverges,
    /// The reachable round-end values exceeded the exploration limit.
    TooLarge,
}

fn key(v: &Values, p: usize) -> u128 {
    let mut k = 0u128;
    for &x in &v[..p] {
        assert!((-128..128).contains(&x), "value out of the packed range");
        k = (k << 8) | ((x + 128) as u128);
    }
    k
}

/// Explores every fair order from `q0` exhaustively.
///
/// The round-end values form a finite graph (each edge: one round, all its update sequences);
/// convergence under every fair order holds iff no cycle avoids `Q*`, and the longest path to
/// `Q*` is the worst-case number of rounds. At most 16 pairs (the key packs one byte a pair into a
/// `u128`); values must stay in `-128..128`.
pub fn all_orders(q: &QProblem, q0: &Values, limit: usize) -> AllOrders {
    let p = q.len();
    assert!(p <= 16);
    let full: u32 = (0..p)
        .filter(|&i| q.updatable(i))
        .fold(0, |m, i| m | 1 << i);
    let mut succ: HashMap<u128, Vec<u128>> = HashMap::new();
    let mut values: HashMap<u128, Values> = HashMap::new();
    let start = key(q0, p);
    values.insert(start, *q0);
    let mut queue = vec![start];
    while let Some(k) = queue.pop() {
        if succ.contains_key(&k) {
            continue;
        }
        let v = values[&k];
        if q.is_optimal(&v) {
            succ.insert(k, Vec::new());
            continue;
        }
        // All round-end values from v: search (values, updated-set) within the round.
        let mut ends: HashSet<u128> = HashSet::new();
        let mut seen: HashSet<(u128, u32)> = HashSet::new();
        let mut stack = vec![(v, 0u32)];
        seen.insert((k, 0));
        while let Some((w, done)) = stack.pop() {
            for i in 0..p {
                if full & (1 << i) == 0 {
                    continue;
                }
                let mut w2 = w;
                q.update(&mut w2, i);
                let d2 = done | 1 << i;
                let k2 = key(&w2, p);
                if d2 == full {
                    if ends.insert(k2) {
                        values.entry(k2).or_insert(w2);
                    }
                } else if seen.insert((k2, d2)) {
                    stack.push((w2, d2));
                }
            }
            if seen.len() > limit {
                return AllOrders::TooLarge;
            }
        }
        let list: Vec<u128> = ends.into_iter().collect();
        for &e in &list {
            if !succ.contains_key(&e) {
                queue.push(e);
            }
        }
        succ.insert(k, list);
        if succ.len() > limit {
            return AllOrders::TooLarge;
        }
    }
    // Longest path to a Q* vertex; a cycle among non-Q* vertices = divergence. Depth-first
    // with an explicit stack (no recursion): a vertex is on the stack (`None`) until every
    // successor has its depth.
    let mut depth: HashMap<u128, Option<u64>> = HashMap::new();
    let longest = |start: u128, depth: &mut HashMap<u128, Option<u64>>| -> Option<u64> {
        let mut stack: Vec<(u128, usize, u64)> = vec![(start, 0, 0)];
        depth.insert(start, None);
        while let Some(&mut (k, ref mut next, ref mut best)) = stack.last_mut() {
            let list = &succ[&k];
            if let Some(&e) = list.get(*next) {
                *next += 1;
                match depth.get(&e) {
                    Some(None) => return None, // on the stack: a cycle
                    Some(Some(d)) => *best = (*best).max(d + 1),
                    None => {
                        depth.insert(e, None);
                        stack.push((e, 0, 0));
                    }
                }
            } else {
                let d = *best;
                depth.insert(k, Some(d));
                stack.pop();
                if let Some(parent) = stack.last_mut() {
                    parent.2 = parent.2.max(d + 1);
                }
            }
        }
        depth[&start]
    };
    match longest(start, &mut depth) {
        Some(d) => AllOrders::Converges(d),
        None => AllOrders::Diverges,
    }
}

//! The exact bonus set of Claim C4 (docs/spec.md §6) for problems too large for the enumeration
//! oracle of [`super::c4`] (Taxi from one initial state: 100 running states, `6^100` stationary
//! policies): a search over *violated cycles* with exact Bellman–Ford, no formula of the
//! claim used.
//!
//! **Facts used.** In the average-cost problem with reset (reaching a goal is followed by one
//! stage costing `M` back to `x1`), the average cost from `x1` of a stationary deterministic
//! policy is the mean cost per stage of the cycle it ends in, and every simple cycle of the
//! reset graph reachable from `x1` is the cycle of some policy. So `π*` (the reset cycle of an
//! optimal single-shot path: `S*` stages, cost `L* + M`) is average-cost optimal iff no cycle
//! reachable from `x1` has mean `< ℓ(M) = (L* + M)/S*`. A cycle with `c` (move costs), `r`
//! resets and `k` stages has mean `(c + r·M)/k`, linear in `M`; a mean `< ℓ(M)` exists iff the
//! graph weighted `w − ℓ(M)` has a negative cycle reachable from `x1` (Bellman–Ford, exact
//! integers after scaling by `S*·q` for `M = p/q`). Hence the set `E` of such `M` is a closed
//! interval (where one line lies below the minimum of lines), intersected with `M < 0`.
//!
//! **Search.** Right end: from `M = 0`, while a violated cycle exists, it has slope
//! `r/k < 1/S*` (else it is violated at every smaller `M` too, and `E` is empty), and `E` lies
//! left of its crossing with `ℓ`: move there (Newton's method on the concave
//! `min_C mean − ℓ`; each step meets a new line, so it ends). Left end likewise from
//! `M = −B`, `B` beyond every crossing of two such lines (then no violation at `−B` means
//! `E` is unbounded below). Every step is bounded ([`MAX_STEPS`]), every product checked.

use crate::claims::c4::{End, Instance, Interval};
use crate::claims::exact::Q;

/// The most Newton steps (Bellman–Ford runs) per end of the interval.
pub const MAX_STEPS: usize = 10_000;

/// The most states reachable from `x1` (each Bellman–Ford run is `O(states · moves)`).
pub const MAX_STATES: usize = 2_000;

/// The exact bonus set of one optimal path length `S*`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CycleBonusSet {
    /// `L*` (scaled costs, as in the instance).
    pub optimal_cost: i64,
    /// `S*`: states on the optimal path (stages of its reset cycle).
    pub optimal_states: i64,
    /// The exact set of `M < 0` for which `π*` is average-cost optimal.
    pub exact: Interval,
    /// `Lav(Ĉ)`, the least mean cost per stage of a goal-avoiding cycle reachable from `x1`
    /// (`None`: there is none), by Lawler's search with the same Bellman–Ford.
    pub least_mean_cycle: Option<Q>,
    /// Bellman–Ford runs made for the two ends.
    pub steps: usize,
}

/// A cycle of the reset graph: move costs, resets, stages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Cycle {
    cost: i128,
    resets: i128,
    stages: i128,
}

/// The reset graph restricted to the states reachable from `x1`: edges `(from, to, cost,
/// reset)`.
struct Graph {
    states: usize,
    initial: usize,
    edges: Vec<(usize, usize, i64, bool)>,
}

fn overflow() -> String {
    "the exact bonus search overflowed its 64- and 128-bit integers (costs too large)".into()
}

impl Graph {
    /// A negative cycle reachable from `x1` under the weights (`None`: the edge is left out),
    /// by Bellman–Ford: after `|X|` rounds an edge still relaxing leads, `|X|` predecessor steps
    /// back, onto a cycle of the predecessor graph, which is negative.
    fn negative_cycle(&self, weights: &[Option<i128>]) -> Result<Option<Cycle>, String> {
        let n = self.states;
        let mut dist: Vec<Option<i128>> = vec![None; n];
        let mut pred: Vec<usize> = vec![usize::MAX; n];
        dist[self.initial] = Some(0);
        let mut last = None;
        for _ in 0..n {
            last = None;
            for (e, &(a, b, _, _)) in self.edges.iter().enumerate() {
                let (Some(da), Some(w)) = (dist[a], weights[e]) else {
                    continue;
                };
                let nd = da.checked_add(w).ok_or_else(overflow)?;
                if dist[b].is_none_or(|db| nd < db) {
                    dist[b] = Some(nd);
                    pred[b] = e;
                    last = Some(b);
                }
            }
            if last.is_none() {
                return Ok(None);
            }
        }
        let Some(mut v) = last else { return Ok(None) };
        for _ in 0..n {
            v = self.edges[pred[v]].0;
        }
        let start = v;
        let mut cycle = Cycle {
            cost: 0,
            resets: 0,
            stages: 0,
        };
        loop {
            let (a, _, c, reset) = self.edges[pred[v]];
            cycle.cost += i128::from(c);
            cycle.resets += i128::from(reset);
            cycle.stages += 1;
            v = a;
            if v == start {
                return Ok(Some(cycle));
            }
        }
    }

    /// A cycle reachable from `x1` with mean `< ℓ(p/q) = (L* + p/q)/S*`: weights
    /// `S*·q·cost + [reset] S*·p − (L*·q + p)`.
    fn violated(&self, lstar: i64, sstar: i64, m: Q) -> Result<Option<Cycle>, String> {
        let (p, q) = (m.numer(), m.denom());
        let (l, s) = (i128::from(lstar), i128::from(sstar));
        let shift = l
            .checked_mul(q)
            .and_then(|v| v.checked_add(p))
            .ok_or_else(overflow)?;
        let weights: Vec<Option<i128>> = self
            .edges
            .iter()
            .map(|&(_, _, c, reset)| {
                let mut w = s.checked_mul(q)?.checked_mul(i128::from(c))?;
                if reset {
                    w = w.checked_add(s.checked_mul(p)?)?;
                }
                w.checked_sub(shift)
            })
            .map(|w| w.map(Some))
            .collect::<Option<_>>()
            .ok_or_else(overflow)?;
        self.negative_cycle(&weights)
    }

    /// `Lav(Ĉ)`: the least mean cost per stage of a goal-avoiding cycle reachable from `x1`
    /// (`None`: there is none), by Lawler's search — from a mean above every cycle's, while a
    /// cycle of mean `< λ` exists (a negative cycle under `cost − λ`), `λ` becomes its mean.
    fn least_mean_cycle(&self) -> Result<Option<Q>, String> {
        let cmax = self
            .edges
            .iter()
            .map(|e| i128::from(e.2))
            .max()
            .unwrap_or(0);
        let mut lambda = Q::int(cmax + 1);
        let mut found = None;
        for _ in 0..MAX_STEPS {
            let (p, q) = (lambda.numer(), lambda.denom());
            let weights: Vec<Option<i128>> = self
                .edges
                .iter()
                .map(|&(_, _, c, reset)| {
                    if reset {
                        return Ok(None);
                    }
                    q.checked_mul(i128::from(c))
                        .and_then(|w| w.checked_sub(p))
                        .map(Some)
                        .ok_or_else(overflow)
                })
                .collect::<Result<_, String>>()?;
            match self.negative_cycle(&weights)? {
                None => return Ok(found),
                Some(c) => {
                    lambda = Q::new(c.cost, c.stages);
                    found = Some(lambda);
                }
            }
        }
        Err(format!(
            "the least-mean-cycle search took more than {MAX_STEPS} steps"
        ))
    }
}

/// The exact bonus sets of C4, one per distinct `S*` of an optimal single-shot path (`Ok(None)`
/// if no goal is reachable from `x1`), by the violated-cycle search (module docs). Refuses a
/// reachable dead end (a state without move that is not a goal: the average-cost problem has
/// no policy there), a zero-cost cycle among the optimal paths (infinitely many `S*`), and
/// sizes beyond [`MAX_STATES`] / [`MAX_STEPS`].
///
/// ```
/// use truecost::claims::c4::{End, Instance};
/// use truecost::claims::c4_cycles::bonus_sets_by_cycles;
/// use truecost::claims::exact::Q;
/// // x1 = 0: straight to the goal 2 at cost 3 (S* = 2 states), or via 1 at cost 1 + 1 (3 states).
/// let inst = Instance { initial: 0, is_goal: vec![false, false, true],
///     moves: vec![vec![(2, 3), (1, 1)], vec![(2, 1)], vec![]] };
/// let sets = bonus_sets_by_cycles(&inst).unwrap().unwrap();
/// // L* = 2 by the long path (S* = 3): optimal iff (2 + M)/3 <= (3 + M)/2, i.e. M >= -5.
/// assert_eq!((sets[0].optimal_cost, sets[0].optimal_states), (2, 3));
/// assert_eq!((sets[0].exact.lo, sets[0].exact.hi), (End::Closed(Q::int(-5)), End::Open(Q::ZERO)));
/// ```
pub fn bonus_sets_by_cycles(inst: &Instance) -> Result<Option<Vec<CycleBonusSet>>, String> {
    let n = inst.moves.len();
    // Reachable from x1 in the single-shot problem (goals end the episode).
    let mut reach = vec![false; n];
    let mut stack = vec![inst.initial];
    reach[inst.initial] = true;
    while let Some(x) = stack.pop() {
        if inst.is_goal[x] {
            continue;
        }
        for &(y, _) in &inst.moves[x] {
            if !reach[y] {
                reach[y] = true;
                stack.push(y);
            }
        }
    }
    let states: Vec<usize> = (0..n).filter(|&x| reach[x]).collect();
    if !states.iter().any(|&x| inst.is_goal[x]) {
        return Ok(None);
    }
    if states.len() > MAX_STATES {
        return Err(format!(
            "{} states are reachable from x1; the violated-cycle search takes at most {MAX_STATES}",
            states.len()
        ));
    }
    if let Some(&x) = states
        .iter()
        .find(|&&x| !inst.is_goal[x] && inst.moves[x].is_empty())
    {
        return Err(format!(
            "state {x} is reachable from x1, is not a goal and has no move: the average-cost problem has no policy there"
        ));
    }
    // Cost-to-go to the goals (Bellman–Ford on the reachable part; costs are >= 0).
    let mut g: Vec<Option<i64>> = (0..n).map(|x| inst.is_goal[x].then_some(0)).collect();
    for _ in 0..states.len() {
        let mut changed = false;
        for &x in states.iter().filter(|&&x| !inst.is_goal[x]) {
            for &(y, c) in &inst.moves[x] {
                if let Some(gy) = g[y] {
                    let v = gy.checked_add(c).ok_or_else(overflow)?;
                    if g[x].is_none_or(|gx| v < gx) {
                        g[x] = Some(v);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    let lstar = g[inst.initial].expect("a goal is reachable");
    // The numbers of states of the optimal paths: walks along tight moves (a DAG unless a
    // zero-cost cycle lies on them).
    let tight = |x: usize, y: usize, c: i64| g[y].is_some_and(|gy| g[x] == Some(gy + c));
    let mut lengths: Vec<Option<Vec<bool>>> = vec![None; n];
    let mut on_stack = vec![false; n];
    fn path_lengths(
        x: usize,
        inst: &Instance,
        tight: &dyn Fn(usize, usize, i64) -> bool,
        lengths: &mut Vec<Option<Vec<bool>>>,
        on_stack: &mut Vec<bool>,
    ) -> Result<(), String> {
        if lengths[x].is_some() {
            return Ok(());
        }
        let n = inst.moves.len();
        let mut set = vec![false; n + 1];
        if inst.is_goal[x] {
            set[1] = true;
        } else {
            on_stack[x] = true;
            for &(y, c) in &inst.moves[x] {
                if !tight(x, y, c) {
                    continue;
                }
                if on_stack[y] {
                    return Err("a zero-cost cycle lies on the optimal single-shot paths (infinitely many S*): beyond the violated-cycle search".into());
                }
                path_lengths(y, inst, tight, lengths, on_stack)?;
                let sub = lengths[y].as_ref().expect("computed");
                for k in 1..n {
                    set[k + 1] |= sub[k];
                }
            }
            on_stack[x] = false;
        }
        lengths[x] = Some(set);
        Ok(())
    }
    path_lengths(inst.initial, inst, &tight, &mut lengths, &mut on_stack)?;
    let sstars: Vec<i64> = lengths[inst.initial]
        .as_ref()
        .expect("computed")
        .iter()
        .enumerate()
        .filter(|(_, &b)| b)
        .map(|(k, _)| k as i64)
        .collect();
    // The reset graph on the reachable states.
    let mut index = vec![usize::MAX; n];
    for (i, &x) in states.iter().enumerate() {
        index[x] = i;
    }
    let mut edges = Vec::new();
    for &x in &states {
        if inst.is_goal[x] {
            edges.push((index[x], index[inst.initial], 0, true));
        } else {
            for &(y, c) in &inst.moves[x] {
                edges.push((index[x], index[y], c, false));
            }
        }
    }
    let graph = Graph {
        states: states.len(),
        initial: index[inst.initial],
        edges,
    };
    // B: beyond every crossing (k L* − S* c)/(S* r − k) of a simple cycle's line with ℓ.
    let cmax = inst
        .moves
        .iter()
        .flatten()
        .map(|&(_, c)| i128::from(c))
        .max()
        .unwrap_or(0);
    let size = states.len() as i128 + 1;
    let bound = size
        .checked_mul(i128::from(lstar) + size.checked_mul(cmax).ok_or_else(overflow)?)
        .and_then(|b| b.checked_add(1))
        .ok_or_else(overflow)?;
    let lav = graph.least_mean_cycle()?;
    let mut out = Vec::new();
    for &sstar in &sstars {
        let (s, l) = (i128::from(sstar), i128::from(lstar));
        let crossing = |c: Cycle| Q::new(c.stages * l - s * c.cost, s * c.resets - c.stages);
        let mut steps = 0;
        // Right end.
        let mut m = Q::ZERO;
        let hi = loop {
            steps += 1;
            if steps > MAX_STEPS {
                return Err(format!(
                    "the violated-cycle search took more than {MAX_STEPS} steps"
                ));
            }
            match graph.violated(lstar, sstar, m)? {
                None => {
                    break Some(if m.is_zero() {
                        End::Open(m)
                    } else {
                        End::Closed(m)
                    })
                }
                Some(c) if c.resets * s >= c.stages => break None,
                Some(c) => {
                    let next = crossing(c);
                    if next >= m {
                        return Err(
                            "internal error: the violated-cycle search did not move left".into(),
                        );
                    }
                    m = next;
                }
            }
        };
        let Some(hi) = hi else {
            out.push(CycleBonusSet {
                optimal_cost: lstar,
                optimal_states: sstar,
                exact: Interval {
                    lo: End::Unbounded,
                    hi: End::Open(Q::ZERO),
                    empty: true,
                },
                least_mean_cycle: lav,
                steps,
            });
            continue;
        };
        // Left end.
        let mut m = Q::int(-bound);
        let mut moved = false;
        let lo = loop {
            steps += 1;
            if steps > 2 * MAX_STEPS {
                return Err(format!(
                    "the violated-cycle search took more than {MAX_STEPS} steps"
                ));
            }
            match graph.violated(lstar, sstar, m)? {
                None if moved => break End::Closed(m),
                None => break End::Unbounded,
                Some(c) if c.resets * s <= c.stages => {
                    return Err("internal error: a cycle violated left of a point of the bonus set is violated there too".into())
                }
                Some(c) => {
                    let next = crossing(c);
                    if next <= m {
                        return Err("internal error: the violated-cycle search did not move right".into());
                    }
                    m = next;
                    moved = true;
                }
            }
        };
        // Built by intersection, so that an empty pair of ends (`[0, 0)`: L* = 0 and a
        // shorter zero-cost path beats π* at every M < 0) is the empty set.
        let mut exact = Interval::negative();
        if let End::Closed(b) = hi {
            exact.at_most(b);
        }
        if let End::Closed(a) = lo {
            exact.at_least(a);
        }
        out.push(CycleBonusSet {
            optimal_cost: lstar,
            optimal_states: sstar,
            exact,
            least_mean_cycle: lav,
            steps,
        });
    }
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A goal-avoiding cycle caps M: `x1 = 0`, goal 2 at cost 4 (S* = 2), and a loop at 1
    /// (reachable: 0 → 1 costs 1) of mean 1. Optimal iff (4 + M)/2 <= 1 and, against the
    /// path 0 → 1 → 2 (cost 1 + 5, 3 states), (4 + M)/2 <= (6 + M)/3, i.e. M <= 0: the set
    /// is M <= -2. Three Newton steps (Bellman–Ford runs): at M = 0 only the loop is violated
    /// (mean 1 < 4/2), its crossing (1·4 − 2·1)/(2·0 − 1) = −2 is the right end, where nothing
    /// is violated; at −B nothing is violated either, so the left end is unbounded.
    #[test]
    fn goal_avoiding_cycle_caps_the_bonus() {
        let inst = Instance {
            initial: 0,
            is_goal: vec![false, false, true],
            moves: vec![vec![(2, 4), (1, 1)], vec![(1, 1), (2, 5)], vec![]],
        };
        let sets = bonus_sets_by_cycles(&inst).unwrap().unwrap();
        assert_eq!(sets.len(), 1);
        assert_eq!(
            (sets[0].exact.lo, sets[0].exact.hi, sets[0].exact.empty),
            (End::Unbounded, End::Closed(Q::int(-2)), false)
        );
        assert_eq!(sets[0].steps, 3);
    }

    /// The size bound counts the states reachable from `x1`: a chain of [`MAX_STATES`] states
    /// (cost 1 a move, the last the goal) is searched, with unreachable states beyond it —
    /// one policy, no cycle, so `π*` (`S* = MAX_STATES`, `L* = MAX_STATES − 1`) is optimal for
    /// every `M < 0` — and a chain of one state more is refused, naming its size.
    #[test]
    fn the_size_bound_counts_reachable_states() {
        let chain = |reachable: usize, unreachable: usize| {
            let n = reachable + unreachable;
            Instance {
                initial: 0,
                is_goal: (0..n).map(|x| x == reachable - 1).collect(),
                moves: (0..n)
                    .map(|x| {
                        if x + 1 < reachable {
                            vec![(x + 1, 1)]
                        } else if x >= reachable {
                            vec![(0, 1)]
                        } else {
                            vec![]
                        }
                    })
                    .collect(),
            }
        };
        let sets = bonus_sets_by_cycles(&chain(MAX_STATES, 5))
            .unwrap()
            .unwrap();
        assert_eq!(sets.len(), 1);
        assert_eq!(
            (sets[0].optimal_states, sets[0].optimal_cost),
            (MAX_STATES as i64, MAX_STATES as i64 - 1)
        );
        assert!(
            sets[0].exact.same_set(&Interval::negative()),
            "{}",
            sets[0].exact
        );
        assert_eq!(
            bonus_sets_by_cycles(&chain(MAX_STATES + 1, 0)).unwrap_err(),
            format!(
                "{} states are reachable from x1; the violated-cycle search takes at most {MAX_STATES}",
                MAX_STATES + 1
            )
        );
    }

    /// Costs whose sums leave 64 bits are refused, naming the overflow, not wrapped: two moves
    /// of 2^62 make a goal path of 2^63.
    #[test]
    fn overflowing_costs_are_refused() {
        let inst = Instance {
            initial: 0,
            is_goal: vec![false, false, true],
            moves: vec![vec![(1, 1 << 62)], vec![(2, 1 << 62)], vec![]],
        };
        assert_eq!(
            bonus_sets_by_cycles(&inst).unwrap_err(),
            "the exact bonus search overflowed its 64- and 128-bit integers (costs too large)"
        );
    }

    #[test]
    fn unreachable_goal_and_dead_end() {
        let inst = Instance {
            initial: 0,
            is_goal: vec![false, true],
            moves: vec![vec![(0, 1)], vec![]],
        };
        assert_eq!(bonus_sets_by_cycles(&inst).unwrap(), None);
        let inst = Instance {
            initial: 0,
            is_goal: vec![false, false, true],
            moves: vec![vec![(1, 1), (2, 3)], vec![], vec![]],
        };
        assert!(bonus_sets_by_cycles(&inst).unwrap_err().contains("no move"));
    }

    /// Two zero-cost goal paths: `0 → 2` (S = 2) and `0 → 1 → 2` (S = 3), so L* = 0 and both
    /// lengths are optimal. With S* = 2, π*'s average M/2 is the least at every M < 0 (the
    /// longer path's is M/3 > M/2): the set is all of M < 0. With S* = 3, the shorter path's
    /// M/2 < M/3 at every M < 0: the set is empty (and says so, not `[0, 0)`).
    #[test]
    fn zero_cost_paths_of_two_lengths_leave_the_longer_an_empty_set() {
        let inst = Instance {
            initial: 0,
            is_goal: vec![false, false, true],
            moves: vec![vec![(2, 0), (1, 0)], vec![(2, 0)], vec![]],
        };
        let sets = bonus_sets_by_cycles(&inst).unwrap().unwrap();
        let got: Vec<(i64, i64, bool, String)> = sets
            .iter()
            .map(|s| {
                (
                    s.optimal_cost,
                    s.optimal_states,
                    s.exact.empty,
                    s.exact.to_string(),
                )
            })
            .collect();
        assert_eq!(
            got,
            [
                (0, 2, false, "(-inf, 0)".to_string()),
                (0, 3, true, "empty".to_string())
            ]
        );
        assert!(sets[1].exact.same_set(&Interval {
            lo: End::Unbounded,
            hi: End::Unbounded,
            empty: true
        }));
    }
}

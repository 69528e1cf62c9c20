//! Value iteration (docs/spec.md §2): the backup `G(x) ← min_u { l(x,u) + G(f(x,u)) }`.
//!
//! Values start at `+∞` except goals at 0 (their termination action costs 0). A backup replaces
//! a value only when the new one is strictly smaller; with non-negative costs and this start
//! the iterates decrease monotonically, so this equals the plain Bellman update. Every node is
//! backed up in every sweep, goals included (termination keeps them at 0), so a sweep performs
//! `Σ degree` backups. The run stops after the first sweep that changes nothing (that sweep is
//! counted). Starting from `+∞` the `k`-th iterate is the least cost over paths of at most `k`
//! moves, so at most `|X|` sweeps change anything: the loop always ends.
//!
//! * [`Schedule::Synchronous`] computes a sweep from the previous sweep's values.
//! * [`Schedule::Asynchronous`] (Gauss–Seidel) updates in place, node by node in graph order.

use std::cmp::Ordering;

use super::{greedy_policy, total_degree, Solution};
use crate::model::Graph;
use crate::value::CostValue;

/// The order in which a sweep applies its backups.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Schedule {
    /// Jacobi: every backup of a sweep reads the previous sweep's values.
    Synchronous,
    /// Gauss–Seidel: backups read the values already updated in this sweep.
    Asynchronous,
}

/// Runs value iteration to its fixed point. `max_sweeps` caps the sweeps (the paper's code
/// uses 1000); `None` runs to convergence, which always happens within `|X| + 1` sweeps.
///
/// ```
/// use truecost_kernel::model::Graph;
/// use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0)], vec![(2, 1.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// let s = value_iteration(&g, Schedule::Synchronous, None);
/// assert_eq!(s.cost_to_go, vec![2.0, 1.0, 0.0]);
/// assert_eq!(s.iterations, 3); // two sweeps that change values, one that confirms
/// assert_eq!(s.actions, 3 * 2);
/// ```
pub fn value_iteration<V: CostValue, U>(
    graph: &Graph<V, U>,
    schedule: Schedule,
    max_sweeps: Option<u64>,
) -> Solution<V> {
    let n = graph.nodes();
    let mut g: Vec<V> = (0..n)
        .map(|v| {
            if graph.is_goal(v) {
                V::zero()
            } else {
                V::infinity()
            }
        })
        .collect();
    let mut sweeps = 0u64;
    let limit = max_sweeps.unwrap_or(n as u64 + 1);
    let mut previous = g.clone();
    let (first, successor, cost) = graph.compressed_rows();
    loop {
        sweeps += 1;
        let mut changed = false;
        match schedule {
            Schedule::Asynchronous => {
                for (x, bounds) in first.windows(2).enumerate() {
                    let range = bounds[0] as usize..bounds[1] as usize;
                    if let Some(best) = best_backup(&successor[range.clone()], &cost[range], &g) {
                        let less = best.compare(&g[x]) == Ordering::Less;
                        if less {
                            g[x] = best;
                        }
                        changed |= less;
                    }
                }
            }
            Schedule::Synchronous => {
                previous.clone_from(&g);
                for (value, bounds) in g.iter_mut().zip(first.windows(2)) {
                    let range = bounds[0] as usize..bounds[1] as usize;
                    if let Some(best) =
                        best_backup(&successor[range.clone()], &cost[range], &previous)
                    {
                        let less = best.compare(value) == Ordering::Less;
                        if less {
                            *value = best;
                        }
                        changed |= less;
                    }
                }
            }
        }
        if !changed || sweeps >= limit {
            break;
        }
    }
    let policy = greedy_policy(graph, &g);
    Solution {
        cost_to_go: g,
        policy,
        iterations: sweeps,
        actions: sweeps * total_degree(graph),
    }
}

/// `min_u { l(x,u) + G(f(x,u)) }` over the moves `(succ[k], cost[k])` of one node (`None` if
/// it has none): the first least candidate in move order.
///
/// For `f64` (the reference mode: inexact, with an [`CostValue::order_key`]) the minimum is
/// compared by their keys and selected without a data-dependent branch per move: the same value
/// (the key preserves the order exactly, and the first strictly smaller key wins as in the
/// comparison loop). Exact types keep the
/// comparison loop (for `Units` it is as cheap, and the sum's overflow checks would run twice).
#[inline]
fn best_backup<V: CostValue>(succ: &[u32], cost: &[V], g: &[V]) -> Option<V> {
    let candidate = |k: usize| cost[k].plus(&g[succ[k] as usize]);
    if succ.is_empty() {
        return None;
    }
    if !V::EXACT && V::zero().order_key().is_some() {
        let key = |v: &V| v.order_key().unwrap_or(u64::MAX);
        let mut best = candidate(0);
        let mut best_key = key(&best);
        for k in 1..succ.len() {
            let next = candidate(k);
            let next_key = key(&next);
            let smaller = next_key < best_key;
            best_key = if smaller { next_key } else { best_key };
            best = if smaller { next } else { best };
        }
        return Some(best);
    }
    let mut best = candidate(0);
    for k in 1..succ.len() {
        let next = candidate(k);
        if next.compare(&best) == Ordering::Less {
            best = next;
        }
    }
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::test_draw::Draw;
    use crate::value::Units;

    /// The first least candidate `cost[k] + g[succ[k]]` by `f64::total_cmp`, written plainly.
    fn first_least(succ: &[u32], cost: &[f64], g: &[f64]) -> Option<f64> {
        let mut best: Option<f64> = None;
        for (&y, &c) in succ.iter().zip(cost) {
            let candidate = c + g[y as usize];
            if best.is_none_or(|b| candidate.total_cmp(&b).is_lt()) {
                best = Some(candidate);
            }
        }
        best
    }

    /// Goal 0, moves 1 → 0 and 2 → 1 (cost 1 each), so that the schedules differ: in graph
    /// order Gauss–Seidel settles both values in its first sweep and confirms in the second,
    /// Jacobi needs two sweeps that change values and a third that confirms.
    #[test]
    fn schedules_sweep_as_counted_by_hand() {
        let g = Graph::<f64>::from_adjacency(
            vec![vec![], vec![(0, 1.0)], vec![(1, 1.0)]],
            0,
            &[0],
            vec![0, 1, 2],
            (),
        );
        let a = value_iteration(&g, Schedule::Asynchronous, None);
        assert_eq!(
            (a.cost_to_go.clone(), a.iterations, a.actions),
            (vec![0.0, 1.0, 2.0], 2, 4)
        );
        let s = value_iteration(&g, Schedule::Synchronous, None);
        assert_eq!(
            (s.cost_to_go.clone(), s.iterations, s.actions),
            (vec![0.0, 1.0, 2.0], 3, 6)
        );
        // The cap stops Jacobi early, with the values of its first sweep.
        let capped = value_iteration(&g, Schedule::Synchronous, Some(1));
        assert_eq!(capped.cost_to_go, vec![0.0, 1.0, f64::INFINITY]);
        assert_eq!(capped.iterations, 1);
    }

    #[test]
    fn keyed_backup_is_the_first_least_candidate() {
        // Values drawn from a small set so that ties, zeros and +∞ are frequent.
        let values = [0.0, 0.5, 1.0, 1.5, 2.0, f64::INFINITY];
        let mut draw = Draw(0x0123_4567_89AB_CDEF);
        for case in 0..5000 {
            let n = 1 + draw.below(6) as usize;
            let g: Vec<f64> = (0..n).map(|_| values[draw.below(6) as usize]).collect();
            let degree = draw.below(7) as usize;
            let succ: Vec<u32> = (0..degree).map(|_| draw.below(n as u64) as u32).collect();
            let cost: Vec<f64> = (0..degree)
                .map(|_| values[draw.below(5) as usize])
                .collect();
            let got = best_backup(&succ, &cost, &g);
            let want = first_least(&succ, &cost, &g);
            assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits), "case {case}");
            // The comparison loop of the exact types agrees on the same numbers (in units).
            let units = |v: f64| {
                Units(if v.is_finite() {
                    (2.0 * v) as u64
                } else {
                    u64::MAX
                })
            };
            let gu: Vec<Units> = g.iter().map(|&v| units(v)).collect();
            let cu: Vec<Units> = cost.iter().map(|&v| units(v)).collect();
            assert_eq!(best_backup(&succ, &cu, &gu), want.map(units), "case {case}");
        }
    }
}

//! Value iteration (SPEC §2): the backup `G(x) ← min_u { l(x,u) + G(f(x,u)) }`.
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
    loop {
        sweeps += 1;
        let mut changed = false;
        match schedule {
            Schedule::Asynchronous => {
                for x in 0..n {
                    if let Some(best) = best_backup(graph, x, &g) {
                        if best.compare(&g[x]) == Ordering::Less {
                            g[x] = best;
                            changed = true;
                        }
                    }
                }
            }
            Schedule::Synchronous => {
                previous.clone_from(&g);
                for (x, value) in g.iter_mut().enumerate() {
                    if let Some(best) = best_backup(graph, x, &previous) {
                        if best.compare(value) == Ordering::Less {
                            *value = best;
                            changed = true;
                        }
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

/// `min_u { l(x,u) + G(f(x,u)) }` over the moves of `x` (`None` if it has none).
#[inline]
fn best_backup<V: CostValue, U>(graph: &Graph<V, U>, x: usize, g: &[V]) -> Option<V> {
    let (succ, cost) = graph.edge_slices(x);
    let mut best: Option<V> = None;
    for (&y, c) in succ.iter().zip(cost) {
        let candidate = c.plus(&g[y as usize]);
        match &best {
            Some(b) if candidate.compare(b) != Ordering::Less => {}
            _ => best = Some(candidate),
        }
    }
    best
}

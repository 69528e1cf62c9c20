//! The exact planners of docs/spec.md §2: Dijkstra, synchronous and asynchronous value iteration,
//! exact policy evaluation, and the model-free exploration that precedes them.
//!
//! Every planner is a function over a [`Graph`] generic in its [`CostValue`]; none reads a
//! clock. A planner returns a [`Solution`]: `G*` for every node, an optimal policy, and the
//! counts of work it did (its own output, like the number of sweeps).

pub mod dijkstra;
pub mod exploration;
pub mod policy_evaluation;
pub mod value_iteration;

/// A small deterministic generator (xorshift64*), enough to draw the solvers' test graphs.
#[cfg(test)]
pub(crate) mod test_draw {
    pub(crate) struct Draw(pub(crate) u64);
    impl Draw {
        pub(crate) fn below(&mut self, n: u64) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) % n
        }
    }
}

use std::cmp::Ordering;

use crate::model::{Decision, Graph, InEdges};
use crate::value::CostValue;

/// The answer of a planner on a graph (node numbering of that graph).
#[derive(Clone, Debug, PartialEq)]
pub struct Solution<V> {
    /// `G*(v)` for every node (`+∞` where no goal is reachable).
    pub cost_to_go: Vec<V>,
    /// An optimal policy: `None` where no goal is reachable.
    pub policy: Vec<Option<Decision>>,
    /// Sweeps (value iteration) or heap pops (Dijkstra).
    pub iterations: u64,
    /// Backups (value iteration) or relaxations (Dijkstra): the planner's counted actions.
    pub actions: u64,
}

/// The optimal policy read off an exact cost-to-go: at each node, the **first** move in the
/// node's action order that attains `G*(x) = l(x,u) + G*(f(x,u))` *and makes progress*, i.e.
/// `G*(f(x,u)) < G*(x)`, or equal with fewer moves left along optimal moves (`h`, the length of
/// the shortest path to a goal over optimal moves). With positive costs this is exactly "the
/// first minimiser in action order"; with zero-cost cycles the progress condition stops the
/// policy from circling, so following it from any node with finite `G*` reaches a goal with
/// total cost `G*` (docs/spec.md §1, `π*(x) ∈ argmin_u Q*(x,u)`). Goals terminate.
///
/// ```
/// use truecost_kernel::model::{Decision, Graph};
/// use truecost_kernel::solvers::greedy_policy;
/// // 0 -> 1 (cost 0), 1 -> 0 (cost 0), 1 -> 2 (cost 0), goal 2
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 0.0)], vec![(0, 0.0), (2, 0.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// let policy = greedy_policy(&g, &[0.0, 0.0, 0.0]);
/// assert_eq!(policy, vec![Some(Decision::Move(0)), Some(Decision::Move(1)), Some(Decision::Terminate)]);
/// ```
pub fn greedy_policy<V: CostValue, U>(
    graph: &Graph<V, U>,
    cost_to_go: &[V],
) -> Vec<Option<Decision>> {
    greedy_policy_over(graph, &graph.in_edges(), cost_to_go)
}

/// [`greedy_policy`] with the graph's moves into each node already built.
pub(crate) fn greedy_policy_over<V: CostValue, U>(
    graph: &Graph<V, U>,
    incoming: &InEdges<'_, V>,
    cost_to_go: &[V],
) -> Vec<Option<Decision>> {
    let n = graph.nodes();
    let tight = |x: usize, y: usize, c: &V| {
        cost_to_go[x].is_finite()
            && c.plus(&cost_to_go[y]).compare(&cost_to_go[x]) == Ordering::Equal
    };
    // h: shortest number of optimal moves to a goal (backward BFS over tight edges).
    // The queue is a buffer of fixed capacity `n` (every node enters at most once), filled up
    // to `len` and read from `head`.
    let mut h = vec![u32::MAX; n];
    let mut queue = vec![0usize; n];
    let mut len = 0;
    for (v, hv) in h.iter_mut().enumerate() {
        if graph.is_goal(v) {
            *hv = 0;
            queue[len] = v;
            len += 1;
        }
    }
    let mut head = 0;
    while head < len {
        let y = queue[head];
        head += 1;
        for (x, c) in incoming.of(y) {
            if h[x] == u32::MAX && tight(x, y, c) {
                h[x] = h[y] + 1;
                queue[len] = x;
                len += 1;
            }
        }
    }
    (0..n)
        .map(|x| {
            if graph.is_goal(x) {
                return Some(Decision::Terminate);
            }
            if h[x] == u32::MAX {
                return None;
            }
            graph
                .edges(x)
                .position(|(y, c)| {
                    tight(x, y, c)
                        && match cost_to_go[y].compare(&cost_to_go[x]) {
                            Ordering::Less => true,
                            Ordering::Equal => h[y] < h[x],
                            Ordering::Greater => false,
                        }
                })
                .map(Decision::Move)
        })
        .collect()
}

/// The nodes visited by following `policy` from `start` until a goal (inclusive). `None` if the
/// policy is undefined on the way or revisits a node (it never reaches a goal).
///
/// ```
/// use truecost_kernel::model::{Decision, Graph};
/// use truecost_kernel::solvers::follow_policy;
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0)], vec![]], 0, &[1], vec![0, 1],
///     ());
/// assert_eq!(follow_policy(&g, &[Some(Decision::Move(0)), Some(Decision::Terminate)], 0), Some(vec![0, 1]));
/// ```
pub fn follow_policy<V: CostValue, U>(
    graph: &Graph<V, U>,
    policy: &[Option<Decision>],
    start: usize,
) -> Option<Vec<usize>> {
    let mut path = vec![start];
    let mut seen = vec![false; graph.nodes()];
    let mut x = start;
    seen[x] = true;
    loop {
        match policy[x]? {
            Decision::Terminate => return Some(path),
            Decision::Move(i) => {
                let (y, _) = graph.edges(x).nth(i)?;
                if seen[y] {
                    return None;
                }
                seen[y] = true;
                path.push(y);
                x = y;
            }
        }
    }
}

/// Σ of out-degrees: the number of backups one value-iteration sweep performs.
pub(crate) fn total_degree<V: CostValue, U>(graph: &Graph<V, U>) -> u64 {
    graph.edge_count() as u64
}

//! Dijkstra's algorithm (SPEC §2, §7), in two directions over one private core:
//!
//! * [`to_goals`] — backwards from the goal set over reversed moves: `G*` for every node. This
//!   is the default planner.
//! * [`from_initial`] — forwards from `x1`, stopping when a goal is popped: the paper's code
//!   (SPEC §7). It gives `G*(x1)` and one optimal path.
//!
//! Both use a binary heap ordered by (distance, insertion counter). A popped entry whose node
//! is already settled (stale) still counts as a pop; every neighbour examined from a settled
//! node counts as a relaxation. Preconditions: costs `>= 0`.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::{greedy_policy, Solution};
use crate::model::Graph;
use crate::value::CostValue;

/// Work counted by a Dijkstra run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DijkstraCounts {
    /// Heap pops, stale ones included.
    pub pops: u64,
    /// Neighbours examined.
    pub relaxations: u64,
}

struct Entry<V> {
    dist: V,
    counter: u64,
    node: u32,
}

impl<V: CostValue> PartialEq for Entry<V> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}
impl<V: CostValue> Eq for Entry<V> {}
impl<V: CostValue> PartialOrd for Entry<V> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<V: CostValue> Ord for Entry<V> {
    /// Reversed: `BinaryHeap` is a max-heap and we pop the smallest (distance, counter).
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .dist
            .compare(&self.dist)
            .then_with(|| other.counter.cmp(&self.counter))
    }
}

/// Result of the core: distances, predecessor on the search tree, counts.
struct Search<V> {
    dist: Vec<V>,
    parent: Vec<u32>,
    reached_target: Option<usize>,
    counts: DijkstraCounts,
}

/// The core. `neighbours(v, visit)` calls `visit(w, cost)` for every neighbour in order.
fn run<V: CostValue>(
    n: usize,
    sources: &[usize],
    mut neighbours: impl FnMut(usize, &mut dyn FnMut(usize, &V)),
    is_target: impl Fn(usize) -> bool,
) -> Search<V> {
    let mut dist = vec![V::infinity(); n];
    let mut parent = vec![u32::MAX; n];
    let mut settled = vec![false; n];
    let mut heap = BinaryHeap::new();
    let mut counter = 0u64;
    let mut counts = DijkstraCounts::default();
    for &s in sources {
        dist[s] = V::zero();
        heap.push(Entry {
            dist: V::zero(),
            counter,
            node: s as u32,
        });
        counter += 1;
    }
    while let Some(Entry { dist: d, node, .. }) = heap.pop() {
        counts.pops += 1;
        let v = node as usize;
        if settled[v] {
            continue;
        }
        settled[v] = true;
        if is_target(v) {
            return Search {
                dist,
                parent,
                reached_target: Some(v),
                counts,
            };
        }
        neighbours(v, &mut |w, c| {
            counts.relaxations += 1;
            let nd = d.plus(c);
            if !settled[w] && nd.compare(&dist[w]) == Ordering::Less {
                dist[w] = nd.clone();
                parent[w] = v as u32;
                heap.push(Entry {
                    dist: nd,
                    counter,
                    node: w as u32,
                });
                counter += 1;
            }
        });
    }
    Search {
        dist,
        parent,
        reached_target: None,
        counts,
    }
}

/// `G*` for every node by Dijkstra backwards from the goals, with the policy of
/// [`greedy_policy`]. `iterations` = heap pops, `actions` = relaxations.
///
/// ```
/// use truecost_kernel::model::Graph;
/// use truecost_kernel::solvers::dijkstra;
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0), (2, 5.0)], vec![(2, 1.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// assert_eq!(dijkstra::to_goals(&g).cost_to_go, vec![2.0, 1.0, 0.0]);
/// ```
pub fn to_goals<V: CostValue, U>(graph: &Graph<V, U>) -> Solution<V> {
    let search = run(
        graph.nodes(),
        &graph.goals(),
        |v, visit| {
            for (x, c) in graph.in_edges(v) {
                visit(x, c);
            }
        },
        |_| false,
    );
    let policy = greedy_policy(graph, &search.dist);
    Solution {
        cost_to_go: search.dist,
        policy,
        iterations: search.counts.pops,
        actions: search.counts.relaxations,
    }
}

/// Forward Dijkstra from `x1` that stops when a goal is popped (the paper's code, SPEC §7).
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardSearch<V> {
    /// `G*(x1)`, `+∞` if no goal was reached.
    pub cost: V,
    /// The path found, from `x1` to the goal (empty if none).
    pub path: Vec<usize>,
    /// Work counted.
    pub counts: DijkstraCounts,
}

/// Runs [`ForwardSearch`].
///
/// ```
/// use truecost_kernel::model::Graph;
/// use truecost_kernel::solvers::dijkstra;
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0), (2, 5.0)], vec![(2, 1.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// let s = dijkstra::from_initial(&g);
/// assert_eq!((s.cost, s.path), (2.0, vec![0, 1, 2]));
/// ```
pub fn from_initial<V: CostValue, U>(graph: &Graph<V, U>) -> ForwardSearch<V> {
    let search = run(
        graph.nodes(),
        &[graph.initial()],
        |v, visit| {
            for (y, c) in graph.edges(v) {
                visit(y, c);
            }
        },
        |v| graph.is_goal(v),
    );
    match search.reached_target {
        None => ForwardSearch {
            cost: V::infinity(),
            path: Vec::new(),
            counts: search.counts,
        },
        Some(goal) => {
            let mut path = vec![goal];
            let mut v = goal;
            while search.parent[v] != u32::MAX {
                v = search.parent[v] as usize;
                path.push(v);
            }
            path.reverse();
            ForwardSearch {
                cost: search.dist[goal].clone(),
                path,
                counts: search.counts,
            }
        }
    }
}

//! Dijkstra's algorithm (docs/spec.md §2, §7), in two directions over one private core:
//!
//! * [`to_goals`] — backwards from the goal set over reversed moves: `G*` for every node. This
//!   is the default planner.
//! * [`from_initial`] — forwards from `x1`, stopping when a goal is popped: the paper's code
//!   (docs/spec.md §7). It gives `G*(x1)` and one optimal path.
//!
//! Both use a binary heap ordered by (distance, insertion counter); for value types with an
//! order key (`Units`, `f64`) each entry is one machine integer. A popped entry whose node
//! is already settled (stale) still counts as a pop; every neighbour examined from a settled
//! node counts as a relaxation. Preconditions: costs `>= 0`.

use std::cmp::Ordering;

use super::{greedy_policy_over, Solution};
use crate::model::{Decision, Graph};
use crate::value::CostValue;

/// Work counted by a Dijkstra run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DijkstraCounts {
    /// Heap pops, stale ones included.
    pub pops: u64,
    /// Neighbours examined.
    pub relaxations: u64,
}

/// The search frontier: a priority queue of entries (distance, insertion counter, node) that
/// pops the smallest (distance, counter). Counters are distinct, so the order is total and
/// every implementation pops the same sequence.
trait Frontier<V> {
    /// An empty frontier for a search over `n` nodes that inserts at most `max_pushes` entries.
    fn new(n: usize, max_pushes: usize) -> Self;
    /// Inserts an entry.
    fn insert(&mut self, dist: &V, counter: u64, node: u32);
    /// Removes the smallest entry and returns its node.
    fn pop(&mut self) -> Option<u32>;
}

/// A binary min-heap in a buffer of fixed capacity (every entry the search can insert), filled
/// up to `len`: no insertion grows it, so a model checker sees one allocation of a length
/// known before the search.
struct MinHeap<T> {
    heap: Vec<T>,
    len: usize,
}

impl<T: Ord> MinHeap<T> {
    /// A heap over `buffer`, whose length is its capacity (the entries are placeholders).
    fn over(buffer: Vec<T>) -> Self {
        MinHeap {
            heap: buffer,
            len: 0,
        }
    }

    /// Adds `entry` (the buffer has room: at most its capacity entries are ever inserted).
    fn insert(&mut self, entry: T) {
        self.heap[self.len] = entry;
        self.len += 1;
        let mut i = self.len - 1;
        while i > 0 {
            let parent = (i - 1) / 2;
            if self.heap[parent] <= self.heap[i] {
                break;
            }
            self.heap.swap(parent, i);
            i = parent;
        }
    }

    /// Removes the least entry; it is left in the slot just past the heap, `heap[len]`.
    fn remove_least(&mut self) -> Option<&T> {
        if self.len == 0 {
            return None;
        }
        self.len -= 1;
        self.heap.swap(0, self.len);
        let mut i = 0;
        loop {
            let (left, right) = (2 * i + 1, 2 * i + 2);
            let mut least = i;
            if left < self.len && self.heap[left] < self.heap[least] {
                least = left;
            }
            if right < self.len && self.heap[right] < self.heap[least] {
                least = right;
            }
            if least == i {
                break;
            }
            self.heap.swap(i, least);
            i = least;
        }
        Some(&self.heap[self.len])
    }
}

/// The frontier for any value type: a [`MinHeap`] of entries compared with
/// [`CostValue::compare`].
struct Compared<V>(MinHeap<Entry<V>>);

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
    /// (distance, counter) order.
    fn cmp(&self, other: &Self) -> Ordering {
        self.dist
            .compare(&other.dist)
            .then_with(|| self.counter.cmp(&other.counter))
    }
}

impl<V: CostValue> Frontier<V> for Compared<V> {
    fn new(_n: usize, max_pushes: usize) -> Self {
        let placeholder = || Entry {
            dist: V::infinity(),
            counter: 0,
            node: 0,
        };
        Compared(MinHeap::over(
            (0..max_pushes).map(|_| placeholder()).collect(),
        ))
    }
    #[inline]
    fn insert(&mut self, dist: &V, counter: u64, node: u32) {
        self.0.insert(Entry {
            dist: dist.clone(),
            counter,
            node,
        });
    }
    #[inline]
    fn pop(&mut self) -> Option<u32> {
        self.0.remove_least().map(|entry| entry.node)
    }
}

/// The most nodes for which [`Keyed`] packs an entry in a `u128`: nodes take 31 bits and
/// counters 33, since a graph has fewer than `2^32` moves (its rows are `u32`), so at most
/// `n + m < 2^31 + 2^32 < 2^33` entries are ever inserted.
const KEYED_NODES: usize = 1 << 31;

/// The frontier for value types with an [`CostValue::order_key`]: one `u128` per entry,
/// `key · 2^64 + counter · 2^31 + node`, so that integer order is (distance, counter) order
/// (the node never decides: counters are distinct). Needs nodes below `2^31` and counters
/// below `2^33` ([`KEYED_NODES`]). A [`MinHeap`] of these integers.
struct Keyed(MinHeap<u128>);

impl<V: CostValue> Frontier<V> for Keyed {
    fn new(_n: usize, max_pushes: usize) -> Self {
        Keyed(MinHeap::over(vec![0; max_pushes]))
    }
    #[inline]
    fn insert(&mut self, dist: &V, counter: u64, node: u32) {
        let key = dist
            .order_key()
            .expect("Keyed is used only with order keys");
        debug_assert!(counter < 1 << 33 && (node as usize) < KEYED_NODES);
        self.0
            .insert(u128::from(key) << 64 | u128::from(counter) << 31 | u128::from(node));
    }
    #[inline]
    fn pop(&mut self) -> Option<u32> {
        self.0
            .remove_least()
            .map(|&least| (least & ((1 << 31) - 1)) as u32)
    }
}

/// Result of the core: distances, predecessor on the search tree, counts.
struct Search<V> {
    dist: Vec<V>,
    parent: Vec<u32>,
    reached_target: Option<usize>,
    counts: DijkstraCounts,
}

/// The core. `neighbours(v)` lists `v`'s neighbours `(w, cost)` in order (the concrete
/// iterator type lets the compiler inline the relaxation loop); `max_pushes` bounds the
/// entries ever pushed (sources plus moves: an entry is pushed only when a move from a node
/// being settled strictly improves its head, once per move at most). Picks the [`Keyed`]
/// frontier when the value type has order keys and the graph has at most [`KEYED_NODES`]
/// nodes, [`Compared`] otherwise: both pop the same sequence. The choice depends on the value
/// type and the node count only, never on the moves (whose number a model checker may see as
/// symbolic: it then runs one search, not both).
fn run<'g, V: CostValue, I: Iterator<Item = (usize, &'g V)>>(
    n: usize,
    sources: &[usize],
    max_pushes: usize,
    neighbours: impl Fn(usize) -> I,
    is_target: impl Fn(usize) -> bool,
) -> Search<V> {
    if V::zero().order_key().is_some() && n <= KEYED_NODES {
        search::<V, Keyed, I>(n, sources, max_pushes, neighbours, is_target)
    } else {
        search::<V, Compared<V>, I>(n, sources, max_pushes, neighbours, is_target)
    }
}

/// Dijkstra over frontier `F`. When a node is popped for the first time its entry is the
/// smallest of its entries, whose distance is the node's current `dist` (entries are pushed
/// only when `dist` strictly decreases, and never after the node is settled); so the
/// frontier only needs to return the node.
fn search<'g, V: CostValue, F: Frontier<V>, I: Iterator<Item = (usize, &'g V)>>(
    n: usize,
    sources: &[usize],
    max_pushes: usize,
    neighbours: impl Fn(usize) -> I,
    is_target: impl Fn(usize) -> bool,
) -> Search<V> {
    let mut dist = vec![V::infinity(); n];
    let mut parent = vec![u32::MAX; n];
    let mut settled = vec![false; n];
    let mut heap = F::new(n, max_pushes);
    let mut counter = 0u64;
    let mut counts = DijkstraCounts::default();
    for &s in sources {
        dist[s] = V::zero();
        heap.insert(&V::zero(), counter, s as u32);
        counter += 1;
    }
    while let Some(node) = heap.pop() {
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
        let d = dist[v].clone();
        for (w, c) in neighbours(v) {
            counts.relaxations += 1;
            // A settled neighbour is examined (counted) but can never improve.
            if settled[w] {
                continue;
            }
            let nd = d.plus(c);
            if nd.compare(&dist[w]) == Ordering::Less {
                heap.insert(&nd, counter, w as u32);
                dist[w] = nd;
                parent[w] = v as u32;
                counter += 1;
            }
        }
    }
    Search {
        dist,
        parent,
        reached_target: None,
        counts,
    }
}

/// `G*` for every node by Dijkstra backwards from the goals, with the policy of
/// [`greedy_policy`](super::greedy_policy). `iterations` = heap pops, `actions` = relaxations.
///
/// ```
/// use truecost_kernel::model::Graph;
/// use truecost_kernel::solvers::dijkstra;
/// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0), (2, 5.0)], vec![(2, 1.0)], vec![]],
///     0, &[2], vec![0, 1, 2], ());
/// assert_eq!(dijkstra::to_goals(&g).cost_to_go, vec![2.0, 1.0, 0.0]);
/// ```
pub fn to_goals<V: CostValue, U>(graph: &Graph<V, U>) -> Solution<V> {
    let incoming = graph.in_edges();
    let search = run(
        graph.nodes(),
        &graph.goals(),
        graph.nodes() + graph.edge_count(),
        |v| incoming.of(v),
        |_| false,
    );
    let policy = if V::EXACT && all_costs_positive(graph) {
        first_tight_moves(graph, &search.dist)
    } else {
        greedy_policy_over(graph, &incoming, &search.dist)
    };
    Solution {
        cost_to_go: search.dist,
        policy,
        iterations: search.counts.pops,
        actions: search.counts.relaxations,
    }
}

/// Whether every move costs more than 0.
fn all_costs_positive<V: CostValue, U>(graph: &Graph<V, U>) -> bool {
    let zero = V::zero();
    graph
        .compressed_rows()
        .2
        .iter()
        .all(|c| c.compare(&zero) == Ordering::Greater)
}

/// [`greedy_policy`] for an **exact** cost-to-go `G*` that Dijkstra computed on a graph whose
/// moves all cost more than 0, in one pass: the first move `x → y` in order with
/// `l(x,u) + G*(y) = G*(x)`. The two agree: such a move has `G*(y) = G*(x) − l < G*(x)`, so
/// it makes progress; and every non-goal `x` with finite `G*(x)` has one (its Dijkstra
/// parent move, exact arithmetic), so following them strictly decreases `G*` and reaches a
/// goal, i.e. `greedy_policy`'s `h(x)` is finite exactly where `G*(x)` is.
fn first_tight_moves<V: CostValue, U>(graph: &Graph<V, U>, g: &[V]) -> Vec<Option<Decision>> {
    (0..graph.nodes())
        .map(|x| {
            if graph.is_goal(x) {
                return Some(Decision::Terminate);
            }
            if !g[x].is_finite() {
                return None;
            }
            let (succ, cost) = graph.edge_slices(x);
            succ.iter()
                .zip(cost)
                .position(|(&y, c)| c.plus(&g[y as usize]).compare(&g[x]) == Ordering::Equal)
                .map(Decision::Move)
        })
        .collect()
}

/// Forward Dijkstra from `x1` that stops when a goal is popped (the paper's code, docs/spec.md §7).
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
        1 + graph.edge_count(),
        |v| graph.edges(v),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The fixed-capacity heap pops its entries in increasing order (against a sorted copy),
    /// nodes up to `2^31 − 1` and counters up to `2^33 − 1` packed without loss.
    #[test]
    fn keyed_pops_in_distance_then_counter_order() {
        let mut draw = Draw(0x5DEE_CE66_D1CE_4E5B);
        for case in 0..500 {
            let pushes = 1 + draw.below(40) as usize;
            let mut heap = <Keyed as Frontier<Units>>::new(4, pushes);
            let mut entries = Vec::new();
            for i in 0..pushes {
                let key = draw.below(6);
                let counter = if i == 0 { (1 << 33) - 1 } else { i as u64 };
                let node = if i % 7 == 0 {
                    (1u32 << 31) - 1 - i as u32
                } else {
                    draw.below(1 << 31) as u32
                };
                Frontier::<Units>::insert(&mut heap, &Units(key), counter, node);
                entries.push((key, counter, node));
                // Interleaved pops: the least entry so far.
                if draw.below(3) == 0 {
                    entries.sort();
                    let least = entries.remove(0);
                    assert_eq!(Frontier::<Units>::pop(&mut heap), Some(least.2), "{case}");
                }
            }
            entries.sort();
            for (_, _, node) in entries {
                assert_eq!(Frontier::<Units>::pop(&mut heap), Some(node), "{case}");
            }
            assert_eq!(Frontier::<Units>::pop(&mut heap), None);
        }
    }
    /// The frontier for any value type pops the same sequence as the packed one, on random
    /// interleavings of insertions and pops (ties in distance broken by the counter).
    #[test]
    fn compared_pops_what_keyed_pops() {
        let mut draw = Draw(0x2545_F491_4F6C_DD1D);
        for case in 0..500 {
            let inserts = 1 + draw.below(40) as usize;
            let mut keyed = <Keyed as Frontier<Units>>::new(4, inserts);
            let mut compared = <Compared<Units> as Frontier<Units>>::new(4, inserts);
            let mut popped = 0;
            for i in 0..inserts {
                let (key, node) = (Units(draw.below(6)), draw.below(1 << 20) as u32);
                Frontier::<Units>::insert(&mut keyed, &key, i as u64, node);
                compared.insert(&key, i as u64, node);
                if draw.below(3) == 0 {
                    let k = Frontier::<Units>::pop(&mut keyed);
                    assert!(k.is_some());
                    assert_eq!(compared.pop(), k, "{case}");
                    popped += 1;
                }
            }
            for _ in popped..inserts {
                let k = Frontier::<Units>::pop(&mut keyed);
                assert!(k.is_some());
                assert_eq!(compared.pop(), k, "{case}");
            }
            assert_eq!(compared.pop(), None);
        }
    }
    use crate::value::Units;

    use crate::solvers::test_draw::Draw;

    #[test]
    fn the_one_pass_policy_is_greedy_policy_on_positive_exact_costs() {
        let mut draw = Draw(0x0123_4567_89AB_CDEF);
        for case in 0..3000 {
            let n = 1 + draw.below(10) as usize;
            let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(); n];
            for _ in 0..draw.below(4 * n as u64 + 1) {
                let x = draw.below(n as u64) as usize;
                let y = draw.below(n as u64) as usize;
                // Few distinct costs: many ties between optimal moves.
                adjacency[x].push((y, Units(1 + draw.below(3))));
            }
            let goals: Vec<usize> = (0..n).filter(|_| draw.below(4) == 0).collect();
            let g = Graph::from_adjacency(adjacency, 0, &goals, (0..n).collect(), ());
            assert!(all_costs_positive(&g));
            let s = to_goals(&g);
            assert_eq!(
                s.policy,
                crate::solvers::greedy_policy(&g, &s.cost_to_go),
                "case {case}"
            );
        }
    }
}

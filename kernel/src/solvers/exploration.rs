//! Model-free exploration (docs/spec.md §2, §7): the robot cannot jump; it walks the graph depth-first
//! over *edges* until every move reachable from `x1` has been tried once, and the planners then
//! run on the graph it discovered.
//!
//! An *edge* is a move together with its reverse move, when one exists (the `k`-th move
//! `x → y` of `x` is paired with the `k`-th move `y → x` of `y`; a self-loop is its own edge).
//! The walk: at the current node, scan its moves from the first; each move inspected counts one
//! action; the first move whose edge is untried is taken (even into an already visited node),
//! and the edge is recorded in both directions; when none is left, the robot steps back along
//! its own path (stepping back is not counted). The discovered graph numbers nodes in order of
//! first appearance and keeps, per node, its moves in the order they were discovered.
//!
//! Stepping back is physically possible only when moves are reversible, as on the paper's
//! grids; on a directed problem the walk still discovers every move reachable from `x1`, but the
//! steps back are an idealisation (they are free and uncounted, as in the paper's code).

use crate::model::{Graph, NO_PARTNER};
use crate::value::CostValue;

/// The outcome of exploring from `x1`.
#[derive(Clone, Debug)]
pub struct Exploration<V, U = ()> {
    /// The discovered graph; its node `v` is node `graph.origin(v)` of the explored graph's
    /// numbering mapped through to the original problem.
    pub graph: Graph<V, U>,
    /// Actions counted by the walk (moves inspected).
    pub actions: u64,
    /// For each node of the explored graph, its index in the discovered graph (if reached).
    pub index: Vec<Option<usize>>,
}

/// Explores `graph` from its initial node. Terminates: every move is tried at most once and
/// every step back pops the stack, so the walk takes at most `2·|moves|` steps.
///
/// ```
/// use truecost_kernel::model::Graph;
/// use truecost_kernel::solvers::exploration::explore;
/// // 0 <-> 1 <-> 2, goal 2, node 3 unreachable
/// let g = Graph::<f64>::from_adjacency(
///     vec![vec![(1, 1.0)], vec![(0, 1.0), (2, 1.0)], vec![(1, 1.0)], vec![]],
///     0, &[2], vec![0, 1, 2, 3], ());
/// let e = explore(&g);
/// assert_eq!(e.graph.nodes(), 3);
/// assert_eq!(e.index, vec![Some(0), Some(1), Some(2), None]);
/// ```
pub fn explore<V: CostValue, U: Clone>(graph: &Graph<V, U>) -> Exploration<V, U> {
    let mut walk = Walk::new(graph);
    let start = graph.initial();
    walk.appear(start);
    // The robot's path, in a buffer of fixed capacity: every step forward tries a move not
    // tried before, so at most `1 + |moves|` nodes are ever on it.
    let mut stack = vec![0u32; 1 + graph.edge_count()];
    stack[0] = start as u32;
    let mut len = 1;
    while len > 0 {
        match walk.step(stack[len - 1] as usize) {
            Some(y) => {
                stack[len] = y;
                len += 1;
            }
            None => len -= 1,
        }
    }
    walk.finish()
}

/// The discovered index of a node not discovered (yet).
const UNSEEN: u32 = u32::MAX;

/// What the walk keeps per node of the explored graph.
#[derive(Clone, Copy)]
struct Node {
    /// The node's discovered index, `UNSEEN` until it appears.
    index: u32,
    /// The first of its moves not yet seen tried (a flat edge index), once discovered. The
    /// moves before it are all tried (tried marks are never removed), so resuming the scan
    /// there, and counting from the node's first move, counts exactly what a scan from the
    /// first move would.
    cursor: u32,
    /// The next free slot of its discovered row, once discovered.
    fill: u32,
}

/// The state of the walk over the explored graph's compressed rows (`row`, `target`,
/// `weight`: see [`Graph::compressed_rows`]).
///
/// The discovered graph is written in place, in compressed rows too. Every move out of a
/// discovered node is eventually recorded at that node, exactly once (taken, or recorded as the
/// reverse partner of a move taken into it), and no other move is: so discovered node `i` has
/// exactly the degree of `order[i]`, and its row is reserved when it first appears.
struct Walk<'g, V, U> {
    graph: &'g Graph<V, U>,
    row: &'g [u32],
    target: &'g [u32],
    weight: &'g [V],
    /// Per move of the explored graph: tried yet?
    tried: Vec<bool>,
    /// Per node of the explored graph.
    nodes: Vec<Node>,
    /// Actions counted (moves inspected).
    actions: u64,
    /// Explored node of each discovered node, in order of first appearance: the first
    /// `discovered` entries of a buffer sized for every node of the explored graph.
    order: Vec<usize>,
    /// Nodes discovered so far.
    discovered: usize,
    /// Discovered row starts, the first `discovered + 1` entries of a buffer of `n + 1`: row
    /// `i` is `first[i]..first[i + 1]`.
    first: Vec<u32>,
    /// Per slot: the discovered index of the move's target (`0` until recorded). Sized for
    /// every move of the explored graph, truncated to the rows when the walk ends.
    successor: Vec<u32>,
    /// Per slot: the move's cost (`V::zero()` until recorded); sized like `successor`.
    cost: Vec<V>,
    /// Per slot: the slot of the move's reverse partner. Moves are paired as in the explored
    /// graph, and the pairs keep their relative order in both rows (the `k`-th pair of `x` and
    /// `y` is recorded before the `k + 1`-th: the scans of both rows are in order), so this is
    /// the discovered graph's own pairing ([`Graph::reverse_move`]).
    partner: Vec<u32>,
}

impl<'g, V: CostValue, U: Clone> Walk<'g, V, U> {
    fn new(graph: &'g Graph<V, U>) -> Self {
        let (row, target, weight) = graph.compressed_rows();
        let (n, m) = (graph.nodes(), target.len());
        let unseen = Node {
            index: UNSEEN,
            cursor: 0,
            fill: 0,
        };
        Walk {
            graph,
            row,
            target,
            weight,
            tried: vec![false; m],
            nodes: vec![unseen; n],
            actions: 0,
            order: vec![0; n],
            discovered: 0,
            first: vec![0; n + 1],
            successor: vec![0; m],
            cost: vec![V::zero(); m],
            partner: vec![NO_PARTNER; m],
        }
    }

    /// Numbers `v` (first appearance) and reserves its row: one slot per move of `v`.
    fn appear(&mut self, v: usize) {
        let i = self.discovered;
        let slots = self.first[i];
        let (lo, hi) = (self.row[v], self.row[v + 1]);
        self.nodes[v] = Node {
            index: i as u32,
            cursor: lo,
            fill: slots,
        };
        self.order[i] = v;
        self.first[i + 1] = slots + (hi - lo);
        self.discovered = i + 1;
    }

    /// One step of the walk at discovered node `x`: takes the first untried move and returns
    /// where it leads, or `None` when every move of `x` is tried (step back).
    #[inline]
    fn step(&mut self, x: usize) -> Option<u32> {
        let (lo, hi) = (self.row[x] as usize, self.row[x + 1] as usize);
        let mut e = self.nodes[x].cursor as usize;
        while e < hi && self.tried[e] {
            e += 1;
        }
        self.nodes[x].cursor = e as u32;
        if e == hi {
            self.actions += (hi - lo) as u64;
            return None;
        }
        self.actions += (e - lo + 1) as u64;
        self.tried[e] = true;
        let y = self.target[e] as usize;
        if self.nodes[y].index == UNSEEN {
            self.appear(y);
        }
        let forward = self.record(x, y, e);
        if let Some(r) = self.graph.reverse_move(e) {
            self.tried[r] = true;
            let backward = self.record(y, x, r);
            self.partner[forward] = backward as u32;
            self.partner[backward] = forward as u32;
        }
        Some(y as u32)
    }

    /// Records the explored graph's move `e`, from `x` to `y` (both discovered), in `x`'s
    /// discovered row; returns its slot.
    #[inline]
    fn record(&mut self, x: usize, y: usize, e: usize) -> usize {
        let s = self.nodes[x].fill as usize;
        self.nodes[x].fill += 1;
        self.successor[s] = self.nodes[y].index;
        self.cost[s] = self.weight[e].clone();
        s
    }

    /// The discovered graph and the counts.
    fn finish(self) -> Exploration<V, U> {
        let Walk {
            graph,
            actions,
            nodes,
            mut order,
            discovered,
            mut first,
            mut successor,
            mut cost,
            mut partner,
            ..
        } = self;
        order.truncate(discovered);
        first.truncate(discovered + 1);
        debug_assert!((0..order.len()).all(|i| nodes[order[i]].fill == first[i + 1]));
        let recorded = *first.last().expect("first is never empty") as usize;
        successor.truncate(recorded);
        cost.truncate(recorded);
        partner.truncate(recorded);
        let goals: Vec<usize> = (0..order.len())
            .filter(|&i| graph.is_goal(order[i]))
            .collect();
        let origin = order.iter().map(|&v| graph.origin(v)).collect();
        let index = nodes
            .iter()
            .map(|node| (node.index != UNSEEN).then_some(node.index as usize))
            .collect();
        Exploration {
            graph: Graph::from_csr_paired(
                first,
                successor,
                cost,
                partner,
                0,
                &goals,
                origin,
                graph.unit().clone(),
            ),
            actions,
            index,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Per-node move lists `(successor, cost)`.
    type Adjacency = Vec<Vec<(usize, f64)>>;

    /// The walk of docs/spec.md §7 written as literally as possible, as an oracle for [`explore`]:
    /// every scan starts at the first move, the reverse partner is searched for by its rank,
    /// and the discovered graph is grown as per-node lists.
    fn literal_walk(graph: &Graph<f64>) -> (u64, Vec<Option<usize>>, Adjacency) {
        let n = graph.nodes();
        let moves = |x: usize| graph.edges(x).map(|(y, c)| (y, *c)).collect::<Vec<_>>();
        let partner = |x: usize, k: usize| -> Option<usize> {
            let mx = moves(x);
            let y = mx[k].0;
            if y == x {
                return None;
            }
            let rank = mx[..k].iter().filter(|m| m.0 == y).count();
            moves(y)
                .iter()
                .enumerate()
                .filter(|(_, m)| m.0 == x)
                .nth(rank)
                .map(|(j, _)| j)
        };
        let mut tried: Vec<Vec<bool>> = (0..n).map(|x| vec![false; graph.degree(x)]).collect();
        let mut index = vec![None; n];
        let mut lists: Vec<Vec<(usize, f64)>> = vec![Vec::new()];
        let mut order = vec![graph.initial()];
        index[graph.initial()] = Some(0);
        let mut stack = vec![graph.initial()];
        let mut actions = 0u64;
        while let Some(&x) = stack.last() {
            let mut taken = None;
            for (k, &done) in tried[x].iter().enumerate() {
                actions += 1;
                if !done {
                    taken = Some(k);
                    break;
                }
            }
            let Some(k) = taken else {
                stack.pop();
                continue;
            };
            let (y, c) = moves(x)[k];
            tried[x][k] = true;
            if index[y].is_none() {
                index[y] = Some(order.len());
                order.push(y);
                lists.push(Vec::new());
            }
            let (ix, iy) = (index[x].unwrap(), index[y].unwrap());
            lists[ix].push((iy, c));
            if let Some(j) = partner(x, k) {
                tried[y][j] = true;
                lists[iy].push((ix, moves(y)[j].1));
            }
            stack.push(y);
        }
        (actions, index, lists)
    }

    use crate::solvers::test_draw::Draw;

    #[test]
    fn explore_matches_the_literal_walk_on_random_graphs() {
        let mut draw = Draw(0x9E37_79B9_7F4A_7C15);
        for case in 0..2000 {
            let n = 1 + draw.below(9) as usize;
            // Undirected (both directions of every edge), directed, or mixed; multi-edges and
            // self-loops included.
            let symmetric = draw.below(3);
            let mut adjacency: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
            for _ in 0..draw.below(3 * n as u64 + 1) {
                let x = draw.below(n as u64) as usize;
                let y = draw.below(n as u64) as usize;
                let c = draw.below(5) as f64;
                adjacency[x].push((y, c));
                if symmetric == 0 || (symmetric == 2 && draw.below(2) == 0) {
                    adjacency[y].push((x, c + 0.5));
                }
            }
            // Shuffle each node's move order.
            for list in &mut adjacency {
                for i in (1..list.len()).rev() {
                    list.swap(i, draw.below(i as u64 + 1) as usize);
                }
            }
            let initial = draw.below(n as u64) as usize;
            let goals: Vec<usize> = (0..n).filter(|_| draw.below(3) == 0).collect();
            let origin: Vec<usize> = (0..n).map(|v| 100 + v).collect();
            let g = Graph::from_adjacency(adjacency, initial, &goals, origin, ());
            let e = explore(&g);
            let (actions, index, lists) = literal_walk(&g);
            assert_eq!(e.actions, actions, "case {case}: actions");
            assert_eq!(e.index, index, "case {case}: index");
            assert_eq!(e.graph.nodes(), lists.len(), "case {case}: nodes");
            for (i, list) in lists.iter().enumerate() {
                let got: Vec<(usize, f64)> = e.graph.edges(i).map(|(y, c)| (y, *c)).collect();
                assert_eq!(&got, list, "case {case}: moves of discovered node {i}");
                let v = index.iter().position(|&j| j == Some(i)).unwrap();
                assert_eq!(e.graph.origin(i), 100 + v, "case {case}: origin");
                assert_eq!(e.graph.is_goal(i), goals.contains(&v), "case {case}: goal");
            }
            assert_eq!(e.graph.initial(), 0);
        }
    }
}

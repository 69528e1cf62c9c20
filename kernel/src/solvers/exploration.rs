//! Model-free exploration (SPEC §2, §7): the robot cannot jump; it walks the graph depth-first
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

use crate::model::Graph;
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
    let n = graph.nodes();
    let mut tried = vec![false; graph.edge_count()];
    let mut index: Vec<Option<usize>> = vec![None; n];
    let mut order: Vec<usize> = Vec::new();
    let mut discovered: Vec<Vec<(usize, V)>> = Vec::new();
    let mut actions = 0u64;

    let start = graph.initial();
    index[start] = Some(0);
    order.push(start);
    discovered.push(Vec::new());
    let mut stack = vec![start];
    // Per node: the offset of its first edge in the flat edge numbering.
    let mut offset = Vec::with_capacity(n + 1);
    offset.push(0usize);
    for v in 0..n {
        offset.push(offset[v] + graph.degree(v));
    }
    let partner = reverse_partners(graph, &offset);
    // The moves before `cursor[x]` are all tried (tried marks are never removed), so resuming
    // the scan there and counting `k + 1` inspections for the move at position `k` counts
    // exactly what a scan from the first move would.
    let mut cursor = vec![0usize; n];
    while let Some(&x) = stack.last() {
        let (succ, cost) = graph.edge_slices(x);
        let mut k = cursor[x];
        while k < succ.len() && tried[offset[x] + k] {
            k += 1;
        }
        cursor[x] = k;
        let taken = if k < succ.len() {
            actions += k as u64 + 1;
            let e = offset[x] + k;
            tried[e] = true;
            if let Some(r) = partner[e] {
                tried[r] = true;
            }
            Some((succ[k] as usize, cost[k].clone(), partner[e]))
        } else {
            actions += succ.len() as u64;
            None
        };
        match taken {
            Some((y, c, reverse)) => {
                let iy = *index[y].get_or_insert_with(|| {
                    order.push(y);
                    discovered.push(Vec::new());
                    order.len() - 1
                });
                let ix = index[x].expect("on the path");
                discovered[ix].push((iy, c));
                if let Some(r) = reverse {
                    discovered[iy].push((ix, cost_of(graph, &offset, y, r)));
                }
                stack.push(y);
            }
            None => {
                stack.pop();
            }
        }
    }
    let goals: Vec<usize> = order
        .iter()
        .enumerate()
        .filter(|(_, &v)| graph.is_goal(v))
        .map(|(i, _)| i)
        .collect();
    let origin = order.iter().map(|&v| graph.origin(v)).collect();
    Exploration {
        graph: Graph::from_adjacency(discovered, 0, &goals, origin, graph.unit().clone()),
        actions,
        index,
    }
}

/// The flat edge index of each move's reverse partner (`None` for self-loops and moves without a
/// reverse). The `k`-th move `x → y` among `x`'s moves to `y` pairs with the `k`-th move
/// `y → x` among `y`'s moves to `x`.
fn reverse_partners<V: CostValue, U>(graph: &Graph<V, U>, offset: &[usize]) -> Vec<Option<usize>> {
    let mut partner = vec![None; graph.edge_count()];
    for x in 0..graph.nodes() {
        let (succ_x, _) = graph.edge_slices(x);
        for (k, &y) in succ_x.iter().enumerate() {
            if y as usize == x {
                continue;
            }
            let rank = succ_x[..k].iter().filter(|&&z| z == y).count();
            let (succ_y, _) = graph.edge_slices(y as usize);
            partner[offset[x] + k] = succ_y
                .iter()
                .enumerate()
                .filter(|(_, &z)| z as usize == x)
                .nth(rank)
                .map(|(j, _)| offset[y as usize] + j);
        }
    }
    partner
}

fn cost_of<V: CostValue, U>(graph: &Graph<V, U>, offset: &[usize], y: usize, e: usize) -> V {
    graph.edge_slices(y).1[e - offset[y]].clone()
}

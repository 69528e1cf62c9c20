//! The deterministic planning model's compiled form (docs/spec.md §1, §2): states, the ordered move
//! lists the planners run on, and a policy's [`Decision`]s.
//!
//! The validated problem with exact rational costs (`truecost::model::Problem`) and the choice
//! of the exact representation (`truecost::model::ExactGraph`) need big rationals and live in
//! `truecost`; a [`Graph`] here carries the value of one unit of its value type as an opaque
//! parameter `U` (`truecost` uses its exact rational; the Kani harnesses use `()`), so this
//! crate stays free of dependencies (the Kani harnesses compile it and nothing else).

use crate::value::CostValue;

/// Index of a state.
pub type StateId = usize;

/// What a policy does at a state: apply the move with this index in `U(x)`'s order, or
/// terminate (goals only).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Decision {
    /// The move at this position in the state's ordered action list.
    Move(usize),
    /// The termination action `uT` of a goal.
    Terminate,
}

/// `Graph::partner` of a move without a reverse partner.
pub(crate) const NO_PARTNER: u32 = u32::MAX;

/// The reverse partner of every move ([`Graph::reverse_move`]) in `O(moves + nodes)`: the
/// moves into `x` from `y` are contiguous in `x`'s reverse rows, in `y`'s order, so the
/// `k`-th move `x → y` pairs with the `k`-th of them.
fn reverse_partners(first: &[u32], successor: &[u32]) -> Vec<u32> {
    let n = first.len() - 1;
    // The moves into each node, `(source, move)` in forward order (counting sort).
    let mut rfirst = vec![0u32; n + 1];
    for &y in successor {
        rfirst[y as usize + 1] += 1;
    }
    for i in 0..n {
        rfirst[i + 1] += rfirst[i];
    }
    let mut fill = rfirst[..n].to_vec();
    let mut incoming = vec![(0u32, 0u32); successor.len()];
    for (x, bounds) in first.windows(2).enumerate() {
        for e in bounds[0] as usize..bounds[1] as usize {
            let slot = &mut fill[successor[e] as usize];
            incoming[*slot as usize] = (x as u32, e as u32);
            *slot += 1;
        }
    }
    let mut partner = vec![NO_PARTNER; successor.len()];
    // Per source `y` while `x` is handled: where its moves into `x` start, how many are used.
    let mut group = vec![u32::MAX; n];
    let mut used = vec![0u32; n];
    for x in 0..n {
        let ins = &incoming[rfirst[x] as usize..rfirst[x + 1] as usize];
        for (i, &(y, _)) in ins.iter().enumerate().rev() {
            group[y as usize] = i as u32;
        }
        for e in first[x] as usize..first[x + 1] as usize {
            let y = successor[e] as usize;
            if y == x || group[y] == u32::MAX {
                continue;
            }
            let i = (group[y] + used[y]) as usize;
            used[y] += 1;
            if let Some(&(source, r)) = ins.get(i) {
                if source as usize == y {
                    partner[e] = r;
                }
            }
        }
        for &(y, _) in ins {
            group[y as usize] = u32::MAX;
            used[y as usize] = 0;
        }
    }
    partner
}

/// Whether `a` and `b` hold the same entries, compared one entry at a time. Not `a == b`: on
/// slices of integers that is a `memcmp`, which a bounded model checker (CBMC, under Kani)
/// unrolls once per *byte*, four times as often as this loop runs; the harnesses that explore
/// graphs reach this check through [`Graph::from_csr_paired`] with their unwind bound sized
/// for the moves, not their bytes.
fn same_entries(a: &[u32], b: &[u32]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut same = true;
    for i in 0..a.len() {
        same &= a[i] == b[i];
    }
    same
}

/// The moves into each node of a [`Graph`] (from [`Graph::in_edges`]).
#[derive(Clone, Debug)]
pub struct InEdges<'g, V> {
    rfirst: Vec<u32>,
    /// For each reverse entry: the source node of the forward edge it mirrors, and that
    /// edge's index.
    reverse: Vec<(u32, u32)>,
    cost: &'g [V],
}

impl<'g, V> InEdges<'g, V> {
    /// The moves into `v`: `(source, cost)`, sources in forward-edge order.
    #[inline]
    pub fn of(&self, v: usize) -> impl Iterator<Item = (usize, &'g V)> + '_ {
        let range = self.rfirst[v] as usize..self.rfirst[v + 1] as usize;
        let cost = self.cost;
        self.reverse[range]
            .iter()
            .map(move |&(x, e)| (x as usize, &cost[e as usize]))
    }
}

/// A planning graph in compressed sparse row form, generic over the value type `V` and the
/// type `U` of the exact value of one unit of `V` (`()` when nobody needs it).
///
/// Node `v` of the graph is state `origin[v]` of the problem it was built from (the identity for
/// `truecost::model::ExactGraph::new`; the first-appearance order for a graph discovered by
/// exploration).
#[derive(Clone, Debug)]
pub struct Graph<V, U = ()> {
    first: Vec<u32>,
    successor: Vec<u32>,
    cost: Vec<V>,
    /// Per move: the flat index of its reverse partner ([`Graph::reverse_move`]), or
    /// `NO_PARTNER`.
    partner: Vec<u32>,
    is_goal: Vec<bool>,
    initial: u32,
    origin: Vec<StateId>,
    unit: U,
}

impl<V: CostValue, U> Graph<V, U> {
    /// Builds a graph from ordered successor lists (docs/spec.md §1: `U(x)` in order, `f`, `l`).
    /// `origin[v]` names node `v` in the caller's numbering; `unit` is the exact value of one
    /// unit of `V` (1 unless `V` is scaled; `()` where it is not needed).
    ///
    /// Preconditions (checked by `truecost::model::Problem::new` for problems): `initial`,
    /// goals and successors are `< adjacency.len()`, costs are non-negative, fewer than
    /// `u32::MAX` nodes and edges.
    ///
    /// ```
    /// use truecost_kernel::model::Graph;
    /// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0)], vec![]], 0, &[1], vec![0, 1], ());
    /// assert_eq!(g.nodes(), 2);
    /// assert_eq!(g.edges(0).count(), 1);
    /// ```
    pub fn from_adjacency(
        adjacency: Vec<Vec<(usize, V)>>,
        initial: usize,
        goals: &[usize],
        origin: Vec<StateId>,
        unit: U,
    ) -> Self {
        let n = adjacency.len();
        // The rows are written into buffers of their final lengths, one entry at a time.
        let edges = adjacency.iter().map(Vec::len).sum();
        let mut first = vec![0u32; n + 1];
        let mut successor = vec![0u32; edges];
        let mut cost = vec![V::zero(); edges];
        let mut e = 0;
        for (x, list) in adjacency.into_iter().enumerate() {
            for (y, c) in list {
                assert!(y < n, "successor out of range");
                successor[e] = y as u32;
                cost[e] = c;
                e += 1;
            }
            first[x + 1] = u32::try_from(e).expect("too many edges");
        }
        Self::from_csr(first, successor, cost, initial, goals, origin, unit)
    }

    /// Builds a graph from its compressed sparse rows: the moves of node `v` are
    /// `successor[first[v]..first[v + 1]]` with costs `cost[first[v]..first[v + 1]]`, in order.
    /// Otherwise as [`Graph::from_adjacency`] (same preconditions; additionally `first` starts
    /// at 0, never decreases, ends at `successor.len() == cost.len()`).
    ///
    /// ```
    /// use truecost_kernel::model::Graph;
    /// // 0 -> 1 (cost 1), 1 -> 0 (cost 2)
    /// let g = Graph::<f64>::from_csr(vec![0, 1, 2], vec![1, 0], vec![1.0, 2.0], 0, &[1],
    ///     vec![0, 1], ());
    /// assert_eq!(g.edges(1).collect::<Vec<_>>(), vec![(0, &2.0)]);
    /// assert_eq!(g.in_edges().of(0).collect::<Vec<_>>(), vec![(1, &2.0)]);
    /// ```
    pub fn from_csr(
        first: Vec<u32>,
        successor: Vec<u32>,
        cost: Vec<V>,
        initial: usize,
        goals: &[usize],
        origin: Vec<StateId>,
        unit: U,
    ) -> Self {
        Self::check_rows(&first, &successor, &cost, initial, &origin);
        let partner = reverse_partners(&first, &successor);
        Self::assemble(
            first, successor, cost, partner, initial, goals, origin, unit,
        )
    }

    /// [`Graph::from_csr`] with the moves' reverse partners already known (exploration
    /// records them as it discovers the moves). Precondition: `partner` is what
    /// [`Graph::reverse_move`] defines for these rows (checked in debug builds).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn from_csr_paired(
        first: Vec<u32>,
        successor: Vec<u32>,
        cost: Vec<V>,
        partner: Vec<u32>,
        initial: usize,
        goals: &[usize],
        origin: Vec<StateId>,
        unit: U,
    ) -> Self {
        Self::check_rows(&first, &successor, &cost, initial, &origin);
        debug_assert!(same_entries(
            &partner,
            &reverse_partners(&first, &successor)
        ));
        Self::assemble(
            first, successor, cost, partner, initial, goals, origin, unit,
        )
    }

    /// The preconditions of [`Graph::from_csr`] (panics otherwise).
    fn check_rows(
        first: &[u32],
        successor: &[u32],
        cost: &[V],
        initial: usize,
        origin: &[StateId],
    ) {
        assert!(!first.is_empty(), "first has one entry per node plus one");
        let n = first.len() - 1;
        assert!(n < u32::MAX as usize && initial < n && origin.len() == n);
        // Branch-free folds (they vectorise): the checks cost little next to the graph.
        let rows_ordered = first.windows(2).fold(true, |ok, w| ok & (w[0] <= w[1]));
        assert!(
            first[0] == 0
                && rows_ordered
                && first[n] as usize == successor.len()
                && successor.len() == cost.len(),
            "malformed compressed rows"
        );
        let largest = successor.iter().fold(0, |m, &y| m.max(y));
        assert!(
            successor.is_empty() || (largest as usize) < n,
            "successor out of range"
        );
    }

    #[allow(clippy::too_many_arguments)]
    fn assemble(
        first: Vec<u32>,
        successor: Vec<u32>,
        cost: Vec<V>,
        partner: Vec<u32>,
        initial: usize,
        goals: &[usize],
        origin: Vec<StateId>,
        unit: U,
    ) -> Self {
        let n = first.len() - 1;
        let mut is_goal = vec![false; n];
        for &g in goals {
            is_goal[g] = true;
        }
        Graph {
            first,
            successor,
            cost,
            partner,
            is_goal,
            initial: initial as u32,
            origin,
            unit,
        }
    }

    /// Number of nodes.
    #[inline]
    pub fn nodes(&self) -> usize {
        self.is_goal.len()
    }

    /// Number of directed edges (moves).
    #[inline]
    pub fn edge_count(&self) -> usize {
        self.successor.len()
    }

    /// The initial node `x1`.
    #[inline]
    pub fn initial(&self) -> usize {
        self.initial as usize
    }

    /// Whether node `v` is a goal.
    #[inline]
    pub fn is_goal(&self, v: usize) -> bool {
        self.is_goal[v]
    }

    /// The goal nodes in increasing order.
    pub fn goals(&self) -> Vec<usize> {
        (0..self.nodes()).filter(|&v| self.is_goal[v]).collect()
    }

    /// Out-degree of `v` (termination not counted).
    #[inline]
    pub fn degree(&self, v: usize) -> usize {
        (self.first[v + 1] - self.first[v]) as usize
    }

    /// The moves of `v` in order: `(successor, cost)`.
    #[inline]
    pub fn edges(&self, v: usize) -> impl ExactSizeIterator<Item = (usize, &V)> + '_ {
        let range = self.first[v] as usize..self.first[v + 1] as usize;
        self.successor[range.clone()]
            .iter()
            .zip(&self.cost[range])
            .map(|(&y, c)| (y as usize, c))
    }

    /// The moves into every node (the reverse compressed rows), built now by a counting sort
    /// over the moves: build it once and query it for many nodes.
    ///
    /// ```
    /// use truecost_kernel::model::Graph;
    /// // 0 -> 1 (cost 1), 2 -> 1 (cost 3), 1 -> 0 (cost 2)
    /// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0)], vec![(0, 2.0)], vec![(1, 3.0)]],
    ///     0, &[1], vec![0, 1, 2], ());
    /// let incoming = g.in_edges();
    /// assert_eq!(incoming.of(1).collect::<Vec<_>>(), vec![(0, &1.0), (2, &3.0)]);
    /// assert_eq!(incoming.of(2).count(), 0);
    /// ```
    pub fn in_edges(&self) -> InEdges<'_, V> {
        let n = self.nodes();
        // Within a target, sources appear in forward-edge order.
        let mut rfirst = vec![0u32; n + 1];
        for &y in &self.successor {
            rfirst[y as usize + 1] += 1;
        }
        for i in 0..n {
            rfirst[i + 1] += rfirst[i];
        }
        let mut fill = rfirst[..n].to_vec();
        let mut reverse = vec![(0u32, 0u32); self.successor.len()];
        for (x, bounds) in self.first.windows(2).enumerate() {
            let (lo, hi) = (bounds[0] as usize, bounds[1] as usize);
            for (e, &y) in (lo..hi).zip(&self.successor[lo..hi]) {
                let slot = &mut fill[y as usize];
                reverse[*slot as usize] = (x as u32, e as u32);
                *slot += 1;
            }
        }
        InEdges {
            rfirst,
            reverse,
            cost: &self.cost,
        }
    }

    /// The flat indices of `v`'s moves: move `k` of `v` is edge `edge_range(v).start + k` of
    /// [`Graph::edge`]'s numbering (all moves of node 0 first, then node 1, ...).
    #[inline]
    pub fn edge_range(&self, v: usize) -> core::ops::Range<usize> {
        self.first[v] as usize..self.first[v + 1] as usize
    }

    /// The reverse partner of move `e` (flat numbering), if it has one: the `k`-th move
    /// `x → y` among `x`'s moves to `y` pairs with the `k`-th move `y → x` among `y`'s moves to
    /// `x`; a self-loop and a move with no such reverse have none. The pairing is symmetric.
    ///
    /// ```
    /// use truecost_kernel::model::Graph;
    /// // 0 -> 1 twice, 1 -> 0 once, 1 -> 1
    /// let g = Graph::<f64>::from_adjacency(vec![vec![(1, 1.0), (1, 2.0)], vec![(1, 0.0), (0, 1.0)]],
    ///     0, &[1], vec![0, 1], ());
    /// assert_eq!((g.reverse_move(0), g.reverse_move(3)), (Some(3), Some(0)));
    /// assert_eq!((g.reverse_move(1), g.reverse_move(2)), (None, None));
    /// ```
    #[inline]
    pub fn reverse_move(&self, e: usize) -> Option<usize> {
        let r = self.partner[e];
        (r != NO_PARTNER).then_some(r as usize)
    }

    /// Edge `e` in the flat numbering of [`Graph::edge_range`]: `(successor, cost)`.
    #[inline]
    pub fn edge(&self, e: usize) -> (usize, &V) {
        (self.successor[e] as usize, &self.cost[e])
    }

    /// The compressed sparse rows themselves: `(first, successor, cost)`, where the moves of
    /// `v` are `successor[first[v]..first[v + 1]]` with their costs (for tight loops over
    /// many nodes; [`Graph::edge`]'s numbering).
    #[inline]
    pub fn compressed_rows(&self) -> (&[u32], &[u32], &[V]) {
        (&self.first, &self.successor, &self.cost)
    }

    /// Raw successor slice and cost slice of `v` (for tight inner loops).
    #[inline]
    pub fn edge_slices(&self, v: usize) -> (&[u32], &[V]) {
        let range = self.first[v] as usize..self.first[v + 1] as usize;
        (&self.successor[range.clone()], &self.cost[range])
    }

    /// The problem state that node `v` stands for.
    #[inline]
    pub fn origin(&self, v: usize) -> StateId {
        self.origin[v]
    }

    /// The whole node → problem-state map.
    pub fn origins(&self) -> &[StateId] {
        &self.origin
    }

    /// The exact value of one unit of `V` in this graph.
    pub fn unit(&self) -> &U {
        &self.unit
    }
}

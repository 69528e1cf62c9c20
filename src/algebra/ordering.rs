//! Fill-reducing orderings of a symmetric sparsity pattern and the symbolic factorisation that
//! goes with them (George and Liu, *Computer Solution of Large Sparse Positive Definite
//! Systems*, 1981: automatic nested dissection; Liu, *The role of elimination trees in sparse
//! factorization*, 1990: elimination tree and row subtrees).
//!
//! The pattern is a graph only — no coordinates — so the orderings apply to any system, not just
//! to grids. Elimination without pivoting in an ordering fills `L` (and `U`, its transpose in
//! pattern) exactly along the row subtrees of the elimination tree; [`Symbolic`] counts and
//! lists those entries, once per pattern.

/// A symmetric sparsity pattern: `adjacency[i]` lists the `j ≠ i` with `A_ij ≠ 0` or
/// `A_ji ≠ 0`, sorted and without repeats.
#[derive(Clone, Debug)]
pub struct Graph {
    adjacency: Vec<Vec<u32>>,
}

impl Graph {
    /// The graph of `A + Aᵀ` from the off-diagonal entries `(i, j)` of `A` (`i, j < n`;
    /// repeats and diagonal entries are ignored).
    ///
    /// ```
    /// use truecost::algebra::ordering::Graph;
    /// let g = Graph::from_entries(3, [(0, 1), (1, 0), (2, 1), (2, 2)]);
    /// assert_eq!(g.neighbours(1), [0, 2]);
    /// assert_eq!(g.neighbours(2), [1]);
    /// ```
    pub fn from_entries(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut adjacency = vec![Vec::new(); n];
        for (i, j) in entries {
            if i != j {
                adjacency[i].push(j as u32);
                adjacency[j].push(i as u32);
            }
        }
        for list in &mut adjacency {
            list.sort_unstable();
            list.dedup();
        }
        Graph { adjacency }
    }

    /// The number of vertices.
    pub fn len(&self) -> usize {
        self.adjacency.len()
    }

    /// Whether the graph has no vertices.
    pub fn is_empty(&self) -> bool {
        self.adjacency.is_empty()
    }

    /// The neighbours of `v`, ascending.
    pub fn neighbours(&self, v: usize) -> &[u32] {
        &self.adjacency[v]
    }
}

/// Parts at most this large are not dissected further.
const LEAF: usize = 8;

/// Nested dissection by level structures (George and Liu §8.2): in each connected part, a
/// breadth-first search from a pseudo-peripheral vertex, and the vertices of the level at the
/// median that touch the next level as the separator, numbered after the two sides, which are
/// dissected in turn. Returns `order` with `order[new] = old`. Deterministic (ties go to the
/// lowest index).
///
/// ```
/// use truecost::algebra::ordering::{nested_dissection, Graph};
/// // A path 0 – 1 – 2 – … – 20: the middle vertex separates it, so it is eliminated last.
/// let path = Graph::from_entries(21, (0..20).map(|i| (i, i + 1)));
/// let order = nested_dissection(&path);
/// assert_eq!(order[20], 10);
/// let mut sorted = order.clone();
/// sorted.sort_unstable();
/// assert_eq!(sorted, (0..21).collect::<Vec<_>>());
/// ```
pub fn nested_dissection(graph: &Graph) -> Vec<usize> {
    let n = graph.len();
    let mut order = vec![usize::MAX; n];
    // `part[v]`: the label of the part `v` belongs to (`usize::MAX` once numbered).
    let mut part = vec![0usize; n];
    let mut labels = 1usize;
    let mut level = vec![u32::MAX; n];
    // Parts to dissect: (label, vertices, first position).
    let mut stack: Vec<(usize, Vec<usize>, usize)> = vec![(0, (0..n).collect(), 0)];
    while let Some((label, vertices, first)) = stack.pop() {
        if vertices.len() <= LEAF {
            for (k, &v) in vertices.iter().enumerate() {
                order[first + k] = v;
                part[v] = usize::MAX;
            }
            continue;
        }
        let bfs = |start: usize, level: &mut [u32]| -> Vec<usize> {
            let mut seq = vec![start];
            level[start] = 0;
            let mut head = 0;
            while head < seq.len() {
                let v = seq[head];
                head += 1;
                for &w in graph.neighbours(v) {
                    let w = w as usize;
                    if part[w] == label && level[w] == u32::MAX {
                        level[w] = level[v] + 1;
                        seq.push(w);
                    }
                }
            }
            seq
        };
        let clear = |seq: &[usize], level: &mut [u32]| {
            for &v in seq {
                level[v] = u32::MAX;
            }
        };
        let start = *vertices.iter().min().expect("non-empty part");
        let seq = bfs(start, &mut level);
        if seq.len() < vertices.len() {
            // Disconnected: each connected piece is a part of its own.
            clear(&seq, &mut level);
            let mut pieces = Vec::new();
            let mut seen = 0;
            for &v in &vertices {
                if level[v] != u32::MAX || part[v] != label {
                    continue;
                }
                let piece = bfs(v, &mut level);
                seen += piece.len();
                pieces.push(piece);
            }
            debug_assert_eq!(seen, vertices.len());
            for piece in &pieces {
                clear(piece, &mut level);
            }
            let mut at = first;
            for piece in pieces {
                for &v in &piece {
                    part[v] = labels;
                }
                let len = piece.len();
                stack.push((labels, piece, at));
                labels += 1;
                at += len;
            }
            continue;
        }
        // Pseudo-peripheral start: repeatedly the least-degree vertex of the last level.
        let mut seq = seq;
        let mut start = start;
        let mut depth = level[*seq.last().expect("non-empty")];
        for _ in 0..4 {
            let far = seq
                .iter()
                .copied()
                .filter(|&v| level[v] == depth)
                .min_by_key(|&v| (graph.neighbours(v).len(), v))
                .expect("non-empty level");
            if far == start {
                break;
            }
            clear(&seq, &mut level);
            let next = bfs(far, &mut level);
            let next_depth = level[*next.last().expect("non-empty")];
            if next_depth <= depth {
                clear(&next, &mut level);
                seq = bfs(start, &mut level);
                break;
            }
            (seq, start, depth) = (next, far, next_depth);
        }
        if depth < 2 {
            // Every vertex within one step of the start: no useful separator.
            clear(&seq, &mut level);
            for (k, &v) in seq.iter().enumerate() {
                order[first + k] = v;
                part[v] = usize::MAX;
            }
            continue;
        }
        // The level where half the vertices have been seen (`seq` is in level order), kept
        // strictly inside `1..depth` so both sides are non-empty.
        let median = level[seq[seq.len() / 2]].clamp(1, depth - 1);
        let (mut low, mut high, mut separator) = (Vec::new(), Vec::new(), Vec::new());
        for &v in &seq {
            let l = level[v];
            if l < median {
                low.push(v);
            } else if l > median {
                high.push(v);
            } else if graph
                .neighbours(v)
                .iter()
                .any(|&w| part[w as usize] == label && level[w as usize] == median + 1)
            {
                separator.push(v);
            } else {
                low.push(v);
            }
        }
        clear(&seq, &mut level);
        let top = first + vertices.len() - separator.len();
        for (k, &v) in separator.iter().enumerate() {
            order[top + k] = v;
            part[v] = usize::MAX;
        }
        let low_len = low.len();
        for (side, at) in [(low, first), (high, first + low_len)] {
            for &v in &side {
                part[v] = labels;
            }
            stack.push((labels, side, at));
            labels += 1;
        }
    }
    debug_assert!(order.iter().all(|&v| v < n));
    order
}

/// The symbolic factorisation of a symmetric pattern in a given order: the elimination tree
/// and, row by row, the columns of the strictly lower factor `L` (new numbering), which are the
/// vertices of the row subtree of each row.
#[derive(Clone, Debug)]
pub struct Symbolic {
    /// `order[new] = old`.
    pub order: Vec<usize>,
    /// `position[old] = new`.
    pub position: Vec<usize>,
    /// Row `i` of `L` has its columns at `lower_columns[lower_first[i]..lower_first[i + 1]]`,
    /// ascending.
    pub lower_first: Vec<usize>,
    /// The columns of `L`, row by row.
    pub lower_columns: Vec<u32>,
}

/// The elimination tree of `graph` numbered by `position` (`parent[new]`, `usize::MAX` at a
/// root), by Liu's algorithm with path compression.
fn elimination_tree(graph: &Graph, order: &[usize], position: &[usize]) -> Vec<usize> {
    let n = graph.len();
    let mut parent = vec![usize::MAX; n];
    let mut ancestor = vec![usize::MAX; n];
    for (i, &old) in order.iter().enumerate() {
        for &w in graph.neighbours(old) {
            let mut r = position[w as usize];
            if r >= i {
                continue;
            }
            while ancestor[r] != usize::MAX && ancestor[r] != i {
                let next = ancestor[r];
                ancestor[r] = i;
                r = next;
            }
            if ancestor[r] == usize::MAX {
                ancestor[r] = i;
                parent[r] = i;
            }
        }
    }
    parent
}

/// Calls `visit(i, k)` for every entry `L_ik` (`k < i`) of the factor of `graph` in `order`:
/// the vertices on the elimination-tree paths from each earlier neighbour of `i` up to `i`.
fn row_subtrees(
    graph: &Graph,
    order: &[usize],
    position: &[usize],
    parent: &[usize],
    mut visit: impl FnMut(usize, usize),
) {
    let n = graph.len();
    let mut mark = vec![usize::MAX; n];
    for (i, &old) in order.iter().enumerate() {
        mark[i] = i;
        for &w in graph.neighbours(old) {
            let mut r = position[w as usize];
            if r >= i {
                continue;
            }
            while mark[r] != i {
                mark[r] = i;
                visit(i, r);
                r = parent[r];
            }
        }
    }
}

/// `position[old] = new` from `order[new] = old`.
fn inverse(order: &[usize]) -> Vec<usize> {
    let mut position = vec![0; order.len()];
    for (new, &old) in order.iter().enumerate() {
        position[old] = new;
    }
    position
}

/// The number of entries strictly below the diagonal of the factor `L` of `graph`'s pattern
/// eliminated in `order` (`order[new] = old`), without storing them: `U` has as many above the
/// diagonal, so an `LU` holds `n + 2·count` entries.
///
/// ```
/// use truecost::algebra::ordering::{factor_entries, Graph};
/// // A star with its centre 0: eliminated first, it joins every leaf to every other (the
/// // star's 4 entries and 4·3/2 = 6 of fill below the diagonal); eliminated last, no fill.
/// let star = Graph::from_entries(5, (1..5).map(|j| (0, j)));
/// assert_eq!(factor_entries(&star, &[0, 1, 2, 3, 4]), 10);
/// assert_eq!(factor_entries(&star, &[1, 2, 3, 4, 0]), 4);
/// ```
pub fn factor_entries(graph: &Graph, order: &[usize]) -> usize {
    let position = inverse(order);
    let parent = elimination_tree(graph, order, &position);
    let mut count = 0;
    row_subtrees(graph, order, &position, &parent, |_, _| count += 1);
    count
}

impl Symbolic {
    /// The symbolic factorisation of `graph` in `order` (`order[new] = old`, a permutation).
    ///
    /// ```
    /// use truecost::algebra::ordering::{Graph, Symbolic};
    /// // The path 0 – 1 – 2 eliminated as 0, 2, 1: row 2 of L (vertex 1) has columns 0 and 1.
    /// let path = Graph::from_entries(3, [(0, 1), (1, 2)]);
    /// let s = Symbolic::new(&path, vec![0, 2, 1]);
    /// assert_eq!(s.lower_row(2), [0, 1]);
    /// assert!(s.lower_row(1).is_empty());
    /// ```
    pub fn new(graph: &Graph, order: Vec<usize>) -> Self {
        let n = graph.len();
        let position = inverse(&order);
        let parent = elimination_tree(graph, &order, &position);
        let mut counts = vec![0usize; n];
        row_subtrees(graph, &order, &position, &parent, |i, _| counts[i] += 1);
        let mut lower_first = Vec::with_capacity(n + 1);
        lower_first.push(0);
        for c in &counts {
            lower_first.push(lower_first.last().expect("non-empty") + c);
        }
        let mut lower_columns = vec![0u32; lower_first[n]];
        let mut fill = lower_first.clone();
        row_subtrees(graph, &order, &position, &parent, |i, k| {
            lower_columns[fill[i]] = k as u32;
            fill[i] += 1;
        });
        for i in 0..n {
            lower_columns[lower_first[i]..lower_first[i + 1]].sort_unstable();
        }
        Symbolic {
            order,
            position,
            lower_first,
            lower_columns,
        }
    }

    /// The columns of row `i` of `L` (new numbering), ascending.
    pub fn lower_row(&self, i: usize) -> &[u32] {
        &self.lower_columns[self.lower_first[i]..self.lower_first[i + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::uniform;

    /// Fill by brute force: eliminate the vertices in order on an explicit graph (each
    /// eliminated vertex joins its remaining neighbours pairwise) and list the entries `(i, k)`
    /// of `L` in the new numbering.
    fn fill_by_elimination(graph: &Graph, order: &[usize]) -> Vec<(usize, usize)> {
        let n = graph.len();
        let position = inverse(order);
        let mut adjacency: Vec<std::collections::BTreeSet<usize>> = (0..n)
            .map(|v| {
                graph
                    .neighbours(order[v])
                    .iter()
                    .map(|&w| position[w as usize])
                    .collect()
            })
            .collect();
        let mut entries = Vec::new();
        for k in 0..n {
            let later: Vec<usize> = adjacency[k].iter().copied().filter(|&i| i > k).collect();
            for &i in &later {
                entries.push((i, k));
                for &j in &later {
                    if i != j {
                        adjacency[i].insert(j);
                    }
                }
            }
        }
        entries.sort_unstable();
        entries
    }

    fn grid(w: usize, h: usize) -> Graph {
        let mut edges = Vec::new();
        for r in 0..h {
            for c in 0..w {
                let v = r * w + c;
                if c + 1 < w {
                    edges.push((v, v + 1));
                }
                if r + 1 < h {
                    edges.push((v, v + w));
                }
            }
        }
        Graph::from_entries(w * h, edges)
    }

    fn random_graph(n: usize, edges: usize, seed: u64) -> Graph {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        Graph::from_entries(
            n,
            (0..edges).map(|_| (uniform(&mut rng, 0, n), uniform(&mut rng, 0, n))),
        )
    }

    #[test]
    fn nested_dissection_is_a_permutation_on_every_shape() {
        let shapes = [
            grid(1, 1),
            grid(9, 1),
            grid(17, 13),
            Graph::from_entries(30, []),
            random_graph(200, 150, 1),
            random_graph(300, 900, 2),
        ];
        for g in &shapes {
            let mut order = nested_dissection(g);
            order.sort_unstable();
            assert_eq!(order, (0..g.len()).collect::<Vec<_>>());
        }
    }

    #[test]
    fn the_symbolic_factor_lists_exactly_the_entries_of_elimination() {
        for (g, order) in [
            (grid(7, 6), None),
            (random_graph(60, 90, 3), None),
            (
                random_graph(40, 200, 4),
                Some((0..40).rev().collect::<Vec<_>>()),
            ),
        ] {
            let order = order.unwrap_or_else(|| nested_dissection(&g));
            let s = Symbolic::new(&g, order.clone());
            let mut got = Vec::new();
            for i in 0..g.len() {
                let row = s.lower_row(i);
                assert!(row.windows(2).all(|w| w[0] < w[1]), "row {i} not ascending");
                got.extend(row.iter().map(|&k| (i, k as usize)));
            }
            let want = fill_by_elimination(&g, &order);
            assert_eq!(got, want);
            assert_eq!(factor_entries(&g, &order), want.len());
        }
    }

    /// On a 40×40 grid the dissection's factor is less than half the band of the
    /// row-by-row numbering (up to 40 entries per row below the diagonal: the profile fills),
    /// both counted by elimination on the explicit graph.
    #[test]
    fn nested_dissection_fills_a_grid_far_less_than_the_band() {
        let g = grid(40, 40);
        let rows: Vec<usize> = (0..1600).collect();
        let band = fill_by_elimination(&g, &rows).len();
        assert!((1560 * 39..=1600 * 40).contains(&band), "{band}");
        let dissected = fill_by_elimination(&g, &nested_dissection(&g)).len();
        assert!(2 * dissected < band, "{dissected} against {band}");
    }
}

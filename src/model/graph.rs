//! The compiled form of a problem that the planners run on: compressed sparse rows of moves
//! (forward and reverse), costs in a chosen [`CostValue`] type.
//!
//! [`ExactGraph::new`] picks the narrowest exact representation that is provably safe
//! (issue "exact must not mean slow"): all stage costs are scaled to integer multiples of
//! `1/D` (`D` = lcm of the cost denominators) and stored as [`Units`] when
//! `(states + 1) × max scaled cost < u64::MAX`; otherwise costs stay big rationals
//! ([`Extended`]).

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive};

use super::{Problem, StateId};
use crate::value::{CostValue, Extended, Rational, Units};

/// A planning graph in compressed sparse row form, generic over the value type.
///
/// Node `v` of the graph is state `origin[v]` of the problem it was built from (the identity for
/// [`ExactGraph::new`]; the first-appearance order for a graph discovered by exploration).
#[derive(Clone, Debug)]
pub struct Graph<V> {
    first: Vec<u32>,
    successor: Vec<u32>,
    cost: Vec<V>,
    rfirst: Vec<u32>,
    /// For each reverse entry: the index of the forward edge it mirrors.
    redge: Vec<u32>,
    /// For each reverse entry: the source node of that edge.
    rsource: Vec<u32>,
    is_goal: Vec<bool>,
    initial: u32,
    origin: Vec<StateId>,
    unit: Rational,
}

/// A problem compiled exactly, in the representation [`ExactGraph::new`] chose.
#[derive(Clone, Debug)]
pub enum ExactGraph {
    /// Integer multiples of a common unit `1/D` in `u64`.
    Units(Graph<Units>),
    /// Big rationals.
    Big(Graph<Extended>),
}

impl<V: CostValue> Graph<V> {
    /// Builds a graph from ordered successor lists. `origin[v]` names node `v` in the caller's
    /// numbering; `unit` is the exact value of one unit of `V` (1 unless `V` is scaled).
    ///
    /// Preconditions (checked by [`Problem::new`] for problems): `initial`, goals and successors
    /// are `< adjacency.len()`, costs are non-negative, fewer than `u32::MAX` nodes and edges.
    ///
    /// ```
    /// use truecost::model::Graph;
    /// let g = Graph::<f64>::from_adjacency(
    ///     vec![vec![(1, 1.0)], vec![]], 0, &[1], vec![0, 1], num_rational::BigRational::from_integer(1.into()));
    /// assert_eq!(g.nodes(), 2);
    /// assert_eq!(g.edges(0).count(), 1);
    /// ```
    pub fn from_adjacency(
        adjacency: Vec<Vec<(usize, V)>>,
        initial: usize,
        goals: &[usize],
        origin: Vec<StateId>,
        unit: Rational,
    ) -> Self {
        let n = adjacency.len();
        assert!(n < u32::MAX as usize && initial < n && origin.len() == n);
        let mut first = Vec::with_capacity(n + 1);
        let mut successor = Vec::new();
        let mut cost = Vec::new();
        first.push(0u32);
        for list in adjacency {
            for (y, c) in list {
                assert!(y < n, "successor out of range");
                successor.push(y as u32);
                cost.push(c);
            }
            first.push(u32::try_from(successor.len()).expect("too many edges"));
        }
        // Reverse CSR by counting sort; within a target, sources appear in forward-edge order.
        let mut indeg = vec![0u32; n + 1];
        for &y in &successor {
            indeg[y as usize + 1] += 1;
        }
        for i in 0..n {
            indeg[i + 1] += indeg[i];
        }
        let rfirst = indeg.clone();
        let mut fill = indeg;
        let mut redge = vec![0u32; successor.len()];
        let mut rsource = vec![0u32; successor.len()];
        for x in 0..n {
            for e in first[x] as usize..first[x + 1] as usize {
                let slot = &mut fill[successor[e] as usize];
                redge[*slot as usize] = e as u32;
                rsource[*slot as usize] = x as u32;
                *slot += 1;
            }
        }
        let mut is_goal = vec![false; n];
        for &g in goals {
            is_goal[g] = true;
        }
        Graph {
            first,
            successor,
            cost,
            rfirst,
            redge,
            rsource,
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

    /// The moves into `v`: `(source, cost)`, sources in forward-edge order.
    #[inline]
    pub fn in_edges(&self, v: usize) -> impl Iterator<Item = (usize, &V)> + '_ {
        let range = self.rfirst[v] as usize..self.rfirst[v + 1] as usize;
        self.redge[range.clone()]
            .iter()
            .zip(&self.rsource[range])
            .map(move |(&e, &x)| (x as usize, &self.cost[e as usize]))
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
    pub fn unit(&self) -> &Rational {
        &self.unit
    }

    /// Renders a value of this graph exactly (or as `f64` text in the reference mode).
    pub fn render(&self, v: &V) -> String {
        v.render(&self.unit)
    }
}

impl Graph<Extended> {
    fn from_problem_big(problem: &Problem) -> Self {
        let adjacency = (0..problem.states())
            .map(|x| {
                problem
                    .moves(x)
                    .iter()
                    .map(|m| (m.successor, Extended::Finite(m.cost.clone())))
                    .collect()
            })
            .collect();
        Graph::from_adjacency(
            adjacency,
            problem.initial(),
            problem.goals(),
            (0..problem.states()).collect(),
            Rational::one(),
        )
    }
}

impl Graph<Units> {
    /// Compiles with costs as multiples of `1/D`, if every value a planner can form fits.
    fn from_problem_units(problem: &Problem) -> Option<Self> {
        let mut d = BigInt::one();
        for x in 0..problem.states() {
            for m in problem.moves(x) {
                d = d.lcm(m.cost.denom());
            }
        }
        let dr = Rational::from_integer(d.clone());
        let mut max = BigInt::from(0);
        let mut adjacency = Vec::with_capacity(problem.states());
        for x in 0..problem.states() {
            let mut list = Vec::with_capacity(problem.moves(x).len());
            for m in problem.moves(x) {
                let scaled = (&m.cost * &dr).to_integer();
                if scaled > max {
                    max = scaled.clone();
                }
                list.push((m.successor, Units(scaled.to_u64()?)));
            }
            adjacency.push(list);
        }
        // Planners form sums of at most `states` stage costs (+ one candidate move).
        let bound = max * BigInt::from(problem.states() as u64 + 1);
        if bound >= BigInt::from(u64::MAX) {
            return None;
        }
        Some(Graph::from_adjacency(
            adjacency,
            problem.initial(),
            problem.goals(),
            (0..problem.states()).collect(),
            Rational::new(BigInt::one(), d),
        ))
    }
}

impl ExactGraph {
    /// Compiles a problem in the narrowest exact representation that cannot overflow.
    ///
    /// ```
    /// use truecost::model::{ExactGraph, Move, Problem};
    /// use truecost::value::parse_rational;
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: parse_rational("800/19").unwrap() }], vec![]], 0, vec![1]).unwrap();
    /// assert!(matches!(ExactGraph::new(&p), ExactGraph::Units(_)));
    /// ```
    pub fn new(problem: &Problem) -> Self {
        match Graph::from_problem_units(problem) {
            Some(g) => ExactGraph::Units(g),
            None => ExactGraph::Big(Graph::from_problem_big(problem)),
        }
    }

    /// The name of the representation chosen (`"units"` or `"big-rational"`).
    pub fn representation(&self) -> &'static str {
        match self {
            ExactGraph::Units(_) => "units",
            ExactGraph::Big(_) => "big-rational",
        }
    }
}

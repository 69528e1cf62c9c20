//! The compiled form of a problem that the planners run on: compressed sparse rows of moves
//! (forward and reverse), costs in a chosen [`CostValue`](crate::value::CostValue) type.
//!
//! [`ExactGraph::new`] picks the narrowest exact representation that is provably safe, so
//! that exact arithmetic costs little speed: all stage costs are scaled to integer multiples of
//! `1/D` (`D` = lcm of the cost denominators) and stored as [`Units`] when
//! `(states + 1) × max scaled cost < u64::MAX`; otherwise costs stay big rationals
//! ([`Extended`]).

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive};

use super::Problem;
use crate::value::{ExactValue, Extended, Rational, Units};

/// A planning graph in compressed sparse row form, generic over the value type, whose unit
/// (the exact value of one unit of `V`) is an exact rational: the kernel's graph
/// (`truecost_kernel::model::Graph`, where the solvers and the Kani harnesses run) with
/// `U = Rational`.
///
/// ```
/// use truecost::model::Graph;
/// let g = Graph::<f64>::from_adjacency(
///     vec![vec![(1, 1.0)], vec![]], 0, &[1], vec![0, 1], num_rational::BigRational::from_integer(1.into()));
/// assert_eq!(g.nodes(), 2);
/// assert_eq!(g.edges(0).count(), 1);
/// ```
pub type Graph<V> = truecost_kernel::model::Graph<V, Rational>;

/// Exact rendering of a graph's values (docs/spec.md §1): a value times the graph's unit.
pub trait RenderValue<V> {
    /// Renders a value of this graph exactly (or as `f64` text in the reference mode).
    fn render(&self, v: &V) -> String;
}

impl<V: ExactValue> RenderValue<V> for Graph<V> {
    fn render(&self, v: &V) -> String {
        v.render(self.unit())
    }
}

/// A problem compiled exactly, in the representation [`ExactGraph::new`] chose.
#[derive(Clone, Debug)]
pub enum ExactGraph {
    /// Integer multiples of a common unit `1/D` in `u64`.
    Units(Graph<Units>),
    /// Big rationals.
    Big(Graph<Extended>),
}

/// Compiles with big-rational costs (always possible).
fn from_problem_big(problem: &Problem) -> Graph<Extended> {
    {
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

/// Compiles with costs as multiples of `1/D`, if every value a planner can form fits.
fn from_problem_units(problem: &Problem) -> Option<Graph<Units>> {
    {
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
        match from_problem_units(problem) {
            Some(g) => ExactGraph::Units(g),
            None => ExactGraph::Big(from_problem_big(problem)),
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

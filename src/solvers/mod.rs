//! The exact planners of docs/spec.md §2: Dijkstra, synchronous and asynchronous value iteration,
//! exact policy evaluation, and the model-free exploration that precedes them.
//!
//! They live in the bignum-free kernel (`truecost_kernel::solvers`, verified by the Kani
//! harnesses in `proofs/`) and are re-exported here under their old paths:
//! `truecost::solvers::dijkstra::to_goals`, `truecost::solvers::value_iteration`, … Every
//! planner is a function over a [`crate::model::Graph`] generic in its
//! [`crate::value::CostValue`]; none reads a clock.
//!
//! ```
//! use truecost::model::Graph;
//! use truecost::solvers::dijkstra;
//! use truecost::value::Units;
//! let one = num_rational::BigRational::from_integer(1.into());
//! let g = Graph::from_adjacency(vec![vec![(1, Units(2))], vec![]], 0, &[1], vec![0, 1], one);
//! assert_eq!(dijkstra::to_goals(&g).cost_to_go, vec![Units(2), Units(0)]);
//! ```

pub use truecost_kernel::solvers::*;

//! The deterministic planning model `P = (X, U, f, x1, XG, l)` of docs/spec.md §1.
//!
//! States are `0..n`. Each state has an ordered list of [`Move`]s (its actions `U(x)` other than
//! termination); the order is significant (greedy tie-breaking, exploration order). Every goal
//! additionally has the termination action `uT` with `f(xg, uT) = xg`, `l(xg, uT) = 0`, which
//! freezes the state; it is not stored as a move (see [`Decision::Terminate`]).
//!
//! A state with no moves that is not a goal is a dead end: `f` is partial (docs/spec.md §1) and its
//! cost-to-go is `+∞`.

pub mod file;
pub mod graph;

use num_traits::Signed;

use crate::value::Rational;

pub use graph::{ExactGraph, Graph, RenderValue};
/// Index of a state, and a policy's decision (the bignum-free kernel's, re-exported).
pub use truecost_kernel::model::{Decision, StateId};

/// One non-terminating action `u ∈ U(x)`: its successor `f(x, u)` and stage cost `l(x, u) ≥ 0`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Move {
    /// `f(x, u)`.
    pub successor: StateId,
    /// `l(x, u)`, exact and non-negative.
    pub cost: Rational,
}

/// Why a problem is not well formed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ModelError {
    /// `X` is empty.
    #[error("the problem has no states")]
    NoStates,
    /// More states than the solvers index (`u32`).
    #[error("the problem has {0} states; at most 4294967294 are supported")]
    TooManyStates(usize),
    /// `x1 ∉ X`.
    #[error("initial state {initial} does not exist (states are 0..{states})")]
    InitialOutOfRange {
        /// The given initial state.
        initial: StateId,
        /// `|X|`.
        states: usize,
    },
    /// `XG` is empty.
    #[error("the problem has no goal state")]
    NoGoal,
    /// A goal outside `X`.
    #[error("goal state {goal} does not exist (states are 0..{states})")]
    GoalOutOfRange {
        /// The given goal.
        goal: StateId,
        /// `|X|`.
        states: usize,
    },
    /// A move to a state outside `X`.
    #[error("state {state}, action {action}: successor {successor} does not exist (states are 0..{states})")]
    SuccessorOutOfRange {
        /// The state.
        state: StateId,
        /// The action's index.
        action: usize,
        /// The bad successor.
        successor: StateId,
        /// `|X|`.
        states: usize,
    },
    /// `l(x, u) < 0`.
    #[error("state {state}, action {action}: negative stage cost {cost} (costs must be >= 0)")]
    NegativeCost {
        /// The state.
        state: StateId,
        /// The action's index.
        action: usize,
        /// The cost as text.
        cost: String,
    },
    /// Wrong number of action lists.
    #[error("{lists} action lists given for {states} states")]
    ActionListCount {
        /// Lists given.
        lists: usize,
        /// `|X|`.
        states: usize,
    },
}

/// A deterministic planning problem (docs/spec.md §1), validated on construction.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::value::parse_rational;
/// // 0 --1--> 1 --2--> 2 (goal)
/// let p = Problem::new(
///     vec![
///         vec![Move { successor: 1, cost: parse_rational("1").unwrap() }],
///         vec![Move { successor: 2, cost: parse_rational("2").unwrap() }],
///         vec![],
///     ],
///     0,
///     vec![2],
/// ).unwrap();
/// assert_eq!(p.states(), 3);
/// assert!(p.is_goal(2));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    moves: Vec<Vec<Move>>,
    initial: StateId,
    is_goal: Vec<bool>,
    goals: Vec<StateId>,
}

impl Problem {
    /// Builds and validates a problem: `moves[x]` is the ordered action list of state `x`.
    ///
    /// Preconditions checked: at least one state and one goal, every index in range, every
    /// cost `>= 0`. Duplicate goals are merged.
    pub fn new(
        moves: Vec<Vec<Move>>,
        initial: StateId,
        goals: Vec<StateId>,
    ) -> Result<Self, ModelError> {
        let n = moves.len();
        if n == 0 {
            return Err(ModelError::NoStates);
        }
        if n >= u32::MAX as usize {
            return Err(ModelError::TooManyStates(n));
        }
        if initial >= n {
            return Err(ModelError::InitialOutOfRange { initial, states: n });
        }
        if goals.is_empty() {
            return Err(ModelError::NoGoal);
        }
        let mut is_goal = vec![false; n];
        let mut unique = Vec::new();
        for &g in &goals {
            if g >= n {
                return Err(ModelError::GoalOutOfRange { goal: g, states: n });
            }
            if !is_goal[g] {
                is_goal[g] = true;
                unique.push(g);
            }
        }
        for (x, list) in moves.iter().enumerate() {
            for (a, m) in list.iter().enumerate() {
                if m.successor >= n {
                    return Err(ModelError::SuccessorOutOfRange {
                        state: x,
                        action: a,
                        successor: m.successor,
                        states: n,
                    });
                }
                if m.cost.is_negative() {
                    return Err(ModelError::NegativeCost {
                        state: x,
                        action: a,
                        cost: crate::value::Extended::Finite(m.cost.clone()).to_string(),
                    });
                }
            }
        }
        Ok(Problem {
            moves,
            initial,
            is_goal,
            goals: unique,
        })
    }

    /// `|X|`.
    pub fn states(&self) -> usize {
        self.moves.len()
    }

    /// `x1`.
    pub fn initial(&self) -> StateId {
        self.initial
    }

    /// `XG`, in the order given (duplicates removed).
    pub fn goals(&self) -> &[StateId] {
        &self.goals
    }

    /// Whether `x ∈ XG`.
    pub fn is_goal(&self, x: StateId) -> bool {
        self.is_goal[x]
    }

    /// The ordered moves of `x` (`U(x)` without termination).
    pub fn moves(&self, x: StateId) -> &[Move] {
        &self.moves[x]
    }

    /// Total number of moves (directed edges).
    pub fn move_count(&self) -> usize {
        self.moves.iter().map(Vec::len).sum()
    }

    /// The states reachable from `x1` (including it), by breadth-first search over moves.
    pub fn reachable_from_initial(&self) -> Vec<bool> {
        let mut seen = vec![false; self.states()];
        let mut queue = std::collections::VecDeque::from([self.initial]);
        seen[self.initial] = true;
        while let Some(x) = queue.pop_front() {
            for m in &self.moves[x] {
                if !seen[m.successor] {
                    seen[m.successor] = true;
                    queue.push_back(m.successor);
                }
            }
        }
        seen
    }
}

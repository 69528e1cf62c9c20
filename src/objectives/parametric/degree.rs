//! A degree the covering of `(0, 1)` is certain to meet on a deterministic model, found from
//! the chain structure before any probe (module docs of [`super`], step 1′ and "Effort").
//!
//! The covering always holds a region reaching `α = 1` and one reaching `α = 0`, and the
//! probe that found each evaluated its policy, optimal on the whole region. Two facts bound
//! the degree of those policies from below, whatever the signs of the rewards:
//!
//! * **Next to 1** ([`near_one`]). A state `x` from which every cycle of actions that can be
//!   reached has a negative total reward: a policy whose chain from `x` runs into a cycle
//!   has a value there that falls to `−∞` as `α → 1` (the cycle's discounted rewards over
//!   `1 − α^k`), while a policy ending the episode along a shortest path keeps a bounded one.
//!   Finitely many policies, so for `α` near 1 the optimal ones end the episode from `x`,
//!   along a path of at least `x`'s fewest moves `d` to an end: a value of degree `d − 1`.
//! * **Next to 0** ([`near_zero`]). Where one action has the greatest stage reward of its
//!   state, alone, it is the only optimal action for `α` near 0 (the rest of a value is at
//!   most `α R/(1 − α)` in magnitude, `R` the largest reward). Following these actions from a
//!   state fixes the start of its chain under the policies optimal near 0: a path of `L`
//!   moves to an end (degree `L − 1`), a lasso of `j` states before a cycle of `k` (degree
//!   `max(j + k − 1, k)`), or `m` forced states before a state with a tie (degree `≥ m`: the
//!   chain has at least `m + 1` states).
//!
//! A chain of `s` states before it ends has a numerator of `s` coefficients (module docs of
//! [`super`], step 1′, whatever the rewards), so these are degrees of values the analysis
//! builds, never more: a file refused by them needs more than the bound when run with the
//! bound lifted (tested against the engine on random files).

use std::collections::VecDeque;
use std::fmt;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

use super::successor;
use crate::model::StateId;
use crate::objectives::Model;
use crate::value::Rational;

/// Why the policies of one end of `(0, 1)` must have a value of a degree: the reason of a
/// [`Certain`] degree, printed in the refusal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Reason {
    /// [`near_one`]: the state is `moves` moves from any end and reaches no cycle of
    /// non-negative total reward.
    NearOne {
        /// The state's fewest moves to an end.
        moves: usize,
    },
    /// [`near_zero`]: the actions of greatest reward, each the only one of its state, fix
    /// the first `states` states of the state's chain (`ends`: and end the episode after
    /// them; `cycle`: the length of the cycle they close, if they do).
    NearZero {
        /// The states of the chain the greedy actions fix.
        states: usize,
        /// The chain ends the episode after them.
        ends: bool,
        /// The length of the cycle they run into, if any.
        cycle: Option<usize>,
    },
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const GREEDY: &str = "takes the only action of greatest reward";
        match self {
            Reason::NearOne { moves } => write!(
                f,
                "is {moves} moves from any end, reaching no cycle of rewards totalling 0 or more, so near alpha = 1 the optimal policies end the episode from it"
            ),
            Reason::NearZero {
                states,
                ends: true,
                ..
            } => write!(
                f,
                "{GREEDY} for {states} moves to an end, so near alpha = 0 the optimal policies take that path"
            ),
            Reason::NearZero {
                states,
                cycle: Some(k),
                ..
            } => write!(
                f,
                "{GREEDY} through {states} states into a cycle of {k}, so near alpha = 0 the optimal policies follow that chain"
            ),
            Reason::NearZero { states, .. } => write!(
                f,
                "{GREEDY} through {states} states, so near alpha = 0 the optimal policies' chain from it is longer"
            ),
        }
    }
}

/// A degree some value of the covering must have: the state, the degree and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Certain {
    /// The state whose value has the degree.
    pub state: StateId,
    /// The degree (at least).
    pub degree: usize,
    /// Why.
    pub reason: Reason,
}

/// The edges of the running states: per state, the successors of its actions with the
/// actions' rewards scaled to integers by the lcm of their denominators.
struct Graph {
    edges: Vec<Vec<(StateId, BigInt)>>,
}

impl Graph {
    fn new(model: &Model, running: &[StateId]) -> Graph {
        let p = &model.problem;
        let mut lcm = BigInt::one();
        for &x in running {
            for a in p.actions(x) {
                lcm = lcm.lcm(model.reward[a].denom());
            }
        }
        let scale = Rational::from_integer(lcm);
        let mut edges = vec![Vec::new(); p.states()];
        for &x in running {
            edges[x] = p
                .actions(x)
                .map(|a| {
                    (
                        successor(model, a),
                        (&model.reward[a] * &scale).to_integer(),
                    )
                })
                .collect();
        }
        Graph { edges }
    }
}

/// Fewest moves from each state to where the episode is over (`Some(0)` there, `None` where
/// no path ends it): breadth-first search backwards.
fn moves_to_end(model: &Model, graph: &Graph) -> Vec<Option<usize>> {
    let n = graph.edges.len();
    let mut before: Vec<Vec<StateId>> = vec![Vec::new(); n];
    for (x, edges) in graph.edges.iter().enumerate() {
        for (y, _) in edges {
            before[*y].push(x);
        }
    }
    let mut moves: Vec<Option<usize>> = vec![None; n];
    let mut queue = VecDeque::new();
    for x in (0..n).filter(|&x| model.terminal[x]) {
        moves[x] = Some(0);
        queue.push_back(x);
    }
    while let Some(y) = queue.pop_front() {
        let d = moves[y].expect("queued states have a distance") + 1;
        for &x in &before[y] {
            if moves[x].is_none() {
                moves[x] = Some(d);
                queue.push_back(x);
            }
        }
    }
    moves
}

/// The strongly connected components of the running states (iterative Tarjan): per state its
/// component's number (`usize::MAX` where the episode is over).
fn components(model: &Model, graph: &Graph) -> Vec<usize> {
    let n = graph.edges.len();
    let unset = usize::MAX;
    let (mut index, mut low) = (vec![unset; n], vec![0usize; n]);
    let mut component = vec![unset; n];
    let mut on_stack = vec![false; n];
    let (mut stack, mut next, mut count) = (Vec::new(), 0usize, 0usize);
    for root in (0..n).filter(|&x| !model.terminal[x]) {
        if index[root] != unset {
            continue;
        }
        // Frames: the state and the position of its next edge.
        let mut frames = vec![(root, 0usize)];
        index[root] = next;
        low[root] = next;
        next += 1;
        stack.push(root);
        on_stack[root] = true;
        while let Some(&mut (x, ref mut i)) = frames.last_mut() {
            if let Some((y, _)) = graph.edges[x].get(*i) {
                *i += 1;
                let y = *y;
                if model.terminal[y] {
                    continue;
                }
                if index[y] == unset {
                    index[y] = next;
                    low[y] = next;
                    next += 1;
                    stack.push(y);
                    on_stack[y] = true;
                    frames.push((y, 0));
                } else if on_stack[y] {
                    low[x] = low[x].min(index[y]);
                }
                continue;
            }
            frames.pop();
            if let Some(&(parent, _)) = frames.last() {
                low[parent] = low[parent].min(low[x]);
            }
            if low[x] == index[x] {
                while let Some(z) = stack.pop() {
                    on_stack[z] = false;
                    component[z] = count;
                    if z == x {
                        break;
                    }
                }
                count += 1;
            }
        }
    }
    component
}

/// The most edge relaxations spent deciding whether the components hold a cycle of
/// non-negative total reward; past it the components left are taken to hold one (the
/// bound before the probes is then weaker, never wrong).
const MAX_RELAXATIONS: usize = 1 << 22;

/// Per component: whether it may hold a cycle whose rewards total 0 or more. Exact within
/// [`MAX_RELAXATIONS`]: a component whose internal actions all have negative rewards holds
/// none; otherwise, with `s` states and integer rewards `R`, a cycle with `ΣR ≥ 0` exists iff
/// one with `Σ((s + 1)·R + 1) > 0` does (at most `s` actions: `ΣR > −1` means `ΣR ≥ 0`),
/// found by a longest-path Bellman–Ford (queue-based) that meets a path of `s` actions.
fn non_negative_cycles(graph: &Graph, component: &[usize]) -> Vec<bool> {
    let count = component
        .iter()
        .filter(|&&c| c != usize::MAX)
        .map(|&c| c + 1)
        .max()
        .unwrap_or(0);
    let mut members: Vec<Vec<StateId>> = vec![Vec::new(); count];
    for (x, &c) in component.iter().enumerate() {
        if c != usize::MAX {
            members[c].push(x);
        }
    }
    let mut budget = MAX_RELAXATIONS;
    let inside = |x: StateId| {
        graph.edges[x]
            .iter()
            .filter(move |(y, _)| component[*y] == component[x])
    };
    members
        .iter()
        .map(|states| {
            if !states
                .iter()
                .any(|&x| inside(x).any(|(_, r)| !r.is_negative()))
            {
                return false;
            }
            let s = BigInt::from(states.len() + 1);
            let mut dist: Vec<BigInt> = vec![BigInt::zero(); graph.edges.len()];
            let mut length = vec![0usize; graph.edges.len()];
            let mut queued = vec![false; graph.edges.len()];
            let mut queue: VecDeque<StateId> = states.iter().copied().collect();
            for &x in states {
                queued[x] = true;
            }
            while let Some(x) = queue.pop_front() {
                queued[x] = false;
                for (y, r) in inside(x) {
                    if budget == 0 {
                        return true;
                    }
                    budget -= 1;
                    let through = &dist[x] + &s * r + 1;
                    if through > dist[*y] {
                        dist[*y] = through;
                        length[*y] = length[x] + 1;
                        if length[*y] >= states.len() {
                            return true;
                        }
                        if !queued[*y] {
                            queued[*y] = true;
                            queue.push_back(*y);
                        }
                    }
                }
            }
            false
        })
        .collect()
}

/// The degree the policies optimal next to `α = 1` must reach ([module docs](self)): the
/// greatest `d − 1` over the states `d ≥ 1` moves from an end that reach no cycle of
/// non-negative total reward.
pub fn near_one(model: &Model, running: &[StateId]) -> Option<Certain> {
    let graph = Graph::new(model, running);
    let moves = moves_to_end(model, &graph);
    let component = components(model, &graph);
    let non_negative = non_negative_cycles(&graph, &component);
    // Backwards from the components that may hold such a cycle: the states reaching one.
    let n = graph.edges.len();
    let mut before: Vec<Vec<StateId>> = vec![Vec::new(); n];
    for (x, edges) in graph.edges.iter().enumerate() {
        for (y, _) in edges {
            before[*y].push(x);
        }
    }
    let mut reaches: Vec<bool> = (0..n)
        .map(|x| component[x] != usize::MAX && non_negative[component[x]])
        .collect();
    let mut stack: Vec<StateId> = (0..n).filter(|&x| reaches[x]).collect();
    while let Some(y) = stack.pop() {
        for &x in &before[y] {
            if !reaches[x] {
                reaches[x] = true;
                stack.push(x);
            }
        }
    }
    running
        .iter()
        .filter(|&&x| !reaches[x])
        .filter_map(|&x| moves[x].map(|d| (x, d)))
        .max_by_key(|&(x, d)| (d, std::cmp::Reverse(x)))
        .map(|(state, moves)| Certain {
            state,
            degree: moves - 1,
            reason: Reason::NearOne { moves },
        })
}

/// The degree the policies optimal next to `α = 0` must reach ([module docs](self)): over
/// the states, the chain the actions of greatest reward fix where each is the only one.
pub fn near_zero(model: &Model, running: &[StateId]) -> Option<Certain> {
    let p = &model.problem;
    let n = p.states();
    // The successor by the state's only action of greatest reward.
    let greedy: Vec<Option<StateId>> = (0..n)
        .map(|x| {
            if model.terminal[x] {
                return None;
            }
            let best = p.actions(x).map(|a| &model.reward[a]).max()?;
            let mut top = p.actions(x).filter(|&a| &model.reward[a] == best);
            match (top.next(), top.next()) {
                (Some(a), None) => Some(successor(model, a)),
                _ => None,
            }
        })
        .collect();
    // Per state: the start of the walk that met it last, and its position on that walk.
    let mut owner = vec![usize::MAX; n];
    let mut position = vec![0usize; n];
    let mut best: Option<Certain> = None;
    for &x in running {
        // Walk the greedy successors from x.
        let mut walk = 0usize;
        let mut y = x;
        let (degree, reason) = loop {
            if model.terminal[y] {
                // A path of `walk` moves to an end.
                break (
                    walk.saturating_sub(1),
                    Reason::NearZero {
                        states: walk,
                        ends: true,
                        cycle: None,
                    },
                );
            }
            if owner[y] == x {
                // A lasso: j states before the cycle, k on it.
                let j = position[y];
                let k = walk - j;
                break (
                    (j + k - 1).max(k),
                    Reason::NearZero {
                        states: walk,
                        ends: false,
                        cycle: Some(k),
                    },
                );
            }
            match greedy[y] {
                Some(z) => {
                    owner[y] = x;
                    position[y] = walk;
                    walk += 1;
                    y = z;
                }
                // `walk` forced states, then a tie: the chain has at least `walk + 1`.
                None => {
                    break (
                        walk,
                        Reason::NearZero {
                            states: walk,
                            ends: false,
                            cycle: None,
                        },
                    )
                }
            }
        };
        if best.as_ref().is_none_or(|b| degree > b.degree) {
            best = Some(Certain {
                state: x,
                degree,
                reason,
            });
        }
    }
    best
}

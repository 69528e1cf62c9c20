//! Symbolic small structures shared by the harnesses: `N` non-goal states with `D` moves each
//! (successor: any state, chosen symbolically), the goal `N` without moves, `u16` stage costs.
//! Their optimal values are computed here independently (Bellman–Ford over fixed arrays), never
//! by the code under test.

use truecost_kernel::claims::qlearning::{Pair, QProblem, Terminal, Values, MAX_PAIRS};
use truecost_kernel::claims::tiny::MAX_STATES;

/// Non-goal states `0..N`; the goal is state `N`.
pub const N: usize = 3;
/// Moves per non-goal state.
pub const D: usize = 2;
/// Move pairs `(x, u)`: pair `p` belongs to state `p / D`.
pub const MOVES: usize = N * D;
/// The goal's termination pair `(g, uT)` comes after the moves.
pub const TERMINAL: usize = MOVES;
/// States of the tiny problems of the C2, C3 and C4 harnesses ([`any_tiny`]; goal last).
pub const TINY_STATES: usize = 4;
/// Longest freely chosen part of a round (see [`any_round`]).
pub const ROUND: usize = 2 * MOVES;

/// A structure: successor and stage cost of every move pair.
#[derive(Clone, Copy, Debug)]
pub struct Structure {
    /// `f(x, u)` of pair `p` (a state in `0..=N`).
    pub to: [usize; MOVES],
    /// `l(x, u)` of pair `p`.
    pub cost: [i64; MOVES],
}

/// Any structure whose every cost is at least `min_cost`: successors `u8 % (N + 1)`, costs
/// `max(u16, min_cost)`. Domain: `2^(8·MOVES) · 2^(16·MOVES) = 2^144` choices.
pub fn any_structure(min_cost: u16) -> Structure {
    let mut to = [0usize; MOVES];
    let mut cost = [0i64; MOVES];
    for p in 0..MOVES {
        to[p] = (kani::any::<u8>() % (N as u8 + 1)) as usize;
        cost[p] = kani::any::<u16>().max(min_cost) as i64;
    }
    Structure { to, cost }
}

/// `G*` by Bellman–Ford from the goal (`None` = cannot reach the goal). At most `N` rounds of
/// relaxations suffice on `N + 1` states.
pub fn cost_to_go(s: &Structure) -> [Option<i64>; N + 1] {
    let mut g = [None; N + 1];
    g[N] = Some(0);
    for _ in 0..N {
        for p in 0..MOVES {
            if let Some(gy) = g[s.to[p]] {
                let cand = s.cost[p] + gy;
                let x = p / D;
                if g[x].is_none_or(|gx| cand < gx) {
                    g[x] = Some(cand);
                }
            }
        }
    }
    g
}

/// `h(y)`: fewest moves on an optimal path from `y` to the goal (`h(goal) = 0`).
pub fn optimal_steps(s: &Structure, g: &[Option<i64>; N + 1]) -> [Option<u32>; N + 1] {
    let mut h = [None; N + 1];
    h[N] = Some(0);
    for _ in 0..N {
        for p in 0..MOVES {
            let (x, y) = (p / D, s.to[p]);
            if let (Some(gx), Some(gy), Some(hy)) = (g[x], g[y], h[y]) {
                if s.cost[p] + gy == gx && h[x].is_none_or(|hx| hy + 1 < hx) {
                    h[x] = Some(hy + 1);
                }
            }
        }
    }
    h
}

/// `Q*` of every move pair (`Q*(x,u) = l(x,u) + G*(f(x,u))`), assuming every state reaches
/// the goal (H1).
pub fn optimum(s: &Structure, g: &[Option<i64>; N + 1]) -> [i64; MOVES] {
    let mut q = [0i64; MOVES];
    for p in 0..MOVES {
        q[p] = s.cost[p] + g[s.to[p]].expect("H1");
    }
    q
}

/// The structure as truecost's derandomized Q-learning problem (`claims::qlearning`), whose
/// `update` the harnesses run: pairs `0..MOVES` are the moves, pair [`TERMINAL`] is `(g, uT)`.
pub fn learner(s: &Structure, terminal: Terminal) -> QProblem {
    let mut pairs = Vec::with_capacity(MOVES + 1);
    for p in 0..MOVES {
        pairs.push(Pair {
            state: (p / D) as u8,
            to: s.to[p] as u8,
            cost: s.cost[p],
            terminal: false,
        });
    }
    pairs.push(Pair {
        state: N as u8,
        to: N as u8,
        cost: 0,
        terminal: true,
    });
    let mut first = [MOVES + 1; MAX_STATES + 1];
    for x in 0..=N {
        first[x] = x * D;
    }
    QProblem {
        pairs,
        first,
        terminal,
        optimum: vec![None; MOVES + 1],
        cost_to_go: [None; MAX_STATES],
        states: N + 1,
    }
}

/// Any round: a sequence of at most [`ROUND`] pair updates chosen freely (symbolic length and
/// order, repeats allowed), followed by an update of every move pair it missed (in index order),
/// so the round is fair. Every fair round of at most [`ROUND`] updates is one of these (nothing
/// is appended to it); the others are fair rounds of at most `ROUND + MOVES` updates. Returns
/// the sequence and its length. Domain `2^(8·(ROUND + 1)) = 2^104`.
pub fn any_round() -> ([usize; ROUND + MOVES], usize) {
    let len = (kani::any::<u8>() % (ROUND as u8 + 1)) as usize;
    let mut order = [0usize; ROUND + MOVES];
    let mut seen = [false; MOVES];
    for k in 0..ROUND {
        order[k] = (kani::any::<u8>() % MOVES as u8) as usize;
        if k < len {
            seen[order[k]] = true;
        }
    }
    let mut end = len;
    for p in 0..MOVES {
        if !seen[p] {
            order[end] = p;
            end += 1;
        }
    }
    (order, end)
}

/// Empty values (every pair 0; callers fill the move pairs).
pub fn values() -> Values {
    [0i64; MAX_PAIRS]
}

/// Any tiny problem (truecost's `claims::tiny::Tiny`, the oracles' input) with `states` states
/// (goal last, `x1 = 0`): every non-goal state has 1 or 2 moves (a `bool`), successors
/// `u8 % states`, costs any `u8` (the oracles' cost type); the goal has no moves. Domain for 4
/// states: `2^3 · 2^(6·8) · 2^(6·8) = 2^99` choices.
pub fn any_tiny(states: usize) -> truecost_kernel::claims::tiny::Tiny {
    use truecost_kernel::claims::tiny::{Tiny, TinyMove};
    let mut t = Tiny::empty(states);
    for x in 0..states - 1 {
        let deg = if kani::any::<bool>() { 2 } else { 1 };
        t.deg[x] = deg;
        for k in 0..2 {
            let to = kani::any::<u8>() % states as u8;
            let cost = kani::any::<u8>();
            if k < deg as usize {
                t.moves[x][k] = TinyMove { to, cost };
            }
        }
    }
    t
}

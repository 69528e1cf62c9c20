//! The solvers' core lemmas, on truecost's own planners (`truecost_kernel::solvers`), checked
//! against an oracle written here: Bellman–Ford over fixed arrays.
//!
//! Each problem is drawn twice over the same choices: as fixed arrays (a [`Problem`], what the
//! oracle reads) and as truecost's [`Graph`] (what the planners read). Values are compared
//! element by element, never with `==` on vectors or arrays of integers (CBMC turns that into
//! `memcmp`, one loop iteration per byte).
//!
//! Loops CBMC unrolls, bounded by `tests/unwind_bounds.rs` from [`STATES`] and [`SLOTS`]: on a
//! problem with `n` states and `m ≤ 2(n − 1)` moves, Dijkstra pushes at most `1 + m` heap entries
//! (the goal, then one per strict improvement, at most one per move) and pops each once;
//! a heap push or pop sifts at most `⌊log₂(1 + m)⌋` levels; a relaxation scans at most `m`
//! moves into a node; value iteration sweeps at most `n + 1` times; `vec![x; k]` fills `k ≤ m`
//! slots; the oracle relaxes `m` moves `n − 1` times.

use truecost_kernel::model::{Decision, Graph};
use truecost_kernel::solvers::dijkstra;
use truecost_kernel::solvers::exploration::explore;
use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
use truecost_kernel::value::{CostValue, Units};

use crate::Three;

/// States of the symbolic planning problems (goal last, without moves): 4 in the stand-in's
/// runs, 3 under Kani, where the symbolic heap and the 64-bit sums of 4 states are the
/// heaviest queries of the crate (6 move slots, 7 heap entries; with 3 states 4 slots and 5
/// entries). The unwinds are derived for 4 states and suffice for 3.
pub const STATES: usize = if cfg!(kani) { 3 } else { 4 };
/// Move slots: two per non-goal state (slot `2x + k` is move `k` of state `x`).
pub const SLOTS: usize = 2 * (STATES - 1);

/// A problem as fixed arrays, the oracle's input: slot `i` belongs to state `i / 2`; it is a
/// move if `present[i]` (slot `2x` always is), to `to[i]` at cost `cost[i]`. State `n − 1` is
/// the goal and has no moves.
#[derive(Clone, Copy, Debug)]
pub struct Problem<const S: usize> {
    /// Number of states in use (`n ≤ S`, goal `n − 1`).
    pub n: usize,
    /// Whether slot `i` is a move.
    pub present: [bool; S],
    /// Its successor.
    pub to: [usize; S],
    /// Its stage cost.
    pub cost: [u64; S],
}

impl<const S: usize> Problem<S> {
    /// The same problem as truecost's graph (moves in slot order; `x1 = 0`).
    pub fn graph(&self) -> Graph<Units> {
        let mut adjacency: Vec<Vec<(usize, Units)>> = Vec::with_capacity(self.n);
        for x in 0..self.n {
            let mut list = Vec::with_capacity(2);
            for k in 0..2 {
                let i = 2 * x + k;
                if x + 1 < self.n && self.present[i] {
                    list.push((self.to[i], Units(self.cost[i])));
                }
            }
            adjacency.push(list);
        }
        let mut origin = Vec::with_capacity(self.n);
        for x in 0..self.n {
            origin.push(x);
        }
        Graph::from_adjacency(adjacency, 0, &[self.n - 1], origin, ())
    }

    /// The oracle: the least cost of a path to the goal from every state (`None` = no path),
    /// by Bellman–Ford. A least-cost path never repeats a state (costs are `≥ 0`), so it has at
    /// most `n − 1` moves and `n − 1` rounds of relaxing every move find it.
    pub fn least_path_cost(&self) -> [Option<u64>; STATES] {
        let mut g = [None; STATES];
        g[self.n - 1] = Some(0);
        for _ in 0..self.n - 1 {
            for i in 0..2 * (self.n - 1) {
                if self.present[i] {
                    if let Some(gy) = g[self.to[i]] {
                        let cand = self.cost[i] + gy;
                        if g[i / 2].is_none_or(|gx| cand < gx) {
                            g[i / 2] = Some(cand);
                        }
                    }
                }
            }
        }
        g
    }
}

/// `Some(v)` for a finite `Units`, `None` for `+∞`.
fn finite(v: Units) -> Option<u64> {
    v.is_finite().then_some(v.0)
}

/// Any 4-state problem with `u32` stage costs: states 0..=2 have one move and optionally a
/// second (successor `u8 % 4`, cost any `u32`), the goal 3 has none. Domain `2^3 · 2^(6·8) ·
/// 2^(6·32) = 2^243` choices. `Units` holds the costs exactly: a least-cost path adds at most 3
/// of them (below `2^34`), far below `u64::MAX`; Kani checks every addition the planners make.
fn any_problem() -> Problem<SLOTS> {
    let mut p = Problem {
        n: STATES,
        present: [false; SLOTS],
        to: [0; SLOTS],
        cost: [0; SLOTS],
    };
    for x in 0..STATES - 1 {
        let second: bool = kani::any();
        for k in 0..2 {
            let i = 2 * x + k;
            p.to[i] = (kani::any::<u8>() % STATES as u8) as usize;
            p.cost[i] = kani::any::<u32>() as u64;
            p.present[i] = k == 0 || second;
        }
    }
    p
}

/// Checks truecost's Dijkstra (`solvers::dijkstra::to_goals`) on `p` against the oracle:
/// `G*(goal) = 0`; Bellman optimality at every state (`G*(x) = min_u l(x,u) + G*(f(x,u))`, `+∞`
/// when no move reaches the goal), evaluated on the fixed arrays; and least-ness: `G*` equals
/// the least path cost, `+∞` included. Bellman optimality alone does not pin `G*` down: a state
/// that cannot reach the goal but lies on a zero-cost cycle satisfies the equations with any
/// finite value too. Also checks the policy: following it from every state with finite `G*`
/// reaches the goal at total cost `G*` (and it is `None` exactly where `G*` is `+∞`).
/// Returns the oracle's values.
fn check_dijkstra<const S: usize>(p: &Problem<S>) -> [Option<u64>; STATES] {
    let n = p.n;
    let goal = n - 1;
    let sol = dijkstra::to_goals(&p.graph());
    let oracle = p.least_path_cost();
    let mut v = [None; STATES];
    for x in 0..n {
        v[x] = finite(sol.cost_to_go[x]);
    }
    kani::assert(v[goal] == Some(0), "G*(goal) = 0");
    for x in 0..goal {
        let mut best: Option<u64> = None;
        for k in 0..2 {
            let i = 2 * x + k;
            if p.present[i] {
                if let Some(gy) = v[p.to[i]] {
                    let cand = p.cost[i] + gy;
                    if best.is_none_or(|b| cand < b) {
                        best = Some(cand);
                    }
                }
            }
        }
        kani::assert(v[x] == best, "Bellman optimality");
    }
    for x in 0..n {
        kani::assert(
            v[x] == oracle[x],
            "G* is the least path cost (Bellman-Ford)",
        );
    }
    // The policy, followed for at most n - 1 moves.
    for start in 0..goal {
        let mut x = start;
        let mut spent = 0u64;
        for _ in 0..n - 1 {
            if x == goal {
                break;
            }
            match sol.policy[x] {
                Some(Decision::Move(k)) if k < 2 && p.present[2 * x + k] => {
                    spent += p.cost[2 * x + k];
                    x = p.to[2 * x + k];
                }
                Some(_) => kani::assert(false, "a move of the state"),
                None => break,
            }
        }
        match v[start] {
            Some(g) => kani::assert(
                x == goal && spent == g,
                "the policy reaches the goal at cost G*",
            ),
            None => kani::assert(sol.policy[start].is_none(), "no policy where G* = +inf"),
        }
    }
    oracle
}

/// Truecost's Dijkstra against the Bellman–Ford oracle (`check_dijkstra`: `G*(goal) = 0`,
/// Bellman optimality, and least-ness — `G*` is the least path cost, `+∞` where there is no
/// path — and the policy) on every problem of `any_problem`
/// (domain 2^243; sampled by the stand-in). Kani also checks that no `Units` addition
/// overflows and no index is out of bounds. Unwind 8: 7 heap pops (`1 + SLOTS`) is the longest
/// loop.
#[kani::proof]
#[kani::unwind(8)]
#[cfg_attr(not(kani), kani::samples(5000))]
pub fn dijkstra_cost_to_go_satisfies_bellman_optimality() {
    let p = any_problem();
    let g = check_dijkstra(&p);
    let mut unreachable = false;
    let mut zero_cycle_off_goal = false;
    let mut tie = false;
    let mut long = false;
    for x in 0..STATES - 1 {
        unreachable |= g[x].is_none();
        let (a, b) = (2 * x, 2 * x + 1);
        // A zero-cost self-loop off every path to the goal: Bellman's equations hold there with
        // any finite value, so only least-ness rules them out.
        zero_cycle_off_goal |= g[x].is_none() && p.to[a] == x && p.cost[a] == 0;
        if let (true, Some(gx), Some(ga), Some(gb)) = (p.present[b], g[x], g[p.to[a]], g[p.to[b]]) {
            tie |= p.to[a] != p.to[b] && p.cost[a] + ga == gx && p.cost[b] + gb == gx;
        }
        long |= g[x].is_some_and(|gx| gx > u32::MAX as u64);
    }
    kani::cover!(unreachable, "a state cannot reach the goal");
    kani::cover!(
        zero_cycle_off_goal,
        "a zero-cost cycle that avoids the goal"
    );
    kani::cover!(tie, "two optimal moves to different successors tie");
    kani::cover!(long, "G* exceeds u32::MAX (a sum of several u32 costs)");
}

/// An extra comparison between two of truecost's planners: Dijkstra's `G*` equals synchronous
/// and asynchronous value iteration's (`solvers::value_iteration`), element by element, on
/// every problem of `any_problem` (domain 2^243). The independent check is
/// [`dijkstra_cost_to_go_satisfies_bellman_optimality`]. Unwind 8: 7 heap pops; value iteration
/// sweeps at most `STATES + 1 = 5` times.
#[kani::proof]
#[kani::unwind(8)]
#[cfg_attr(not(kani), kani::samples(5000))]
pub fn dijkstra_equals_value_iteration() {
    let p = any_problem();
    let g = p.graph();
    let d = dijkstra::to_goals(&g).cost_to_go;
    let sync = value_iteration(&g, Schedule::Synchronous, None);
    let asynchronous = value_iteration(&g, Schedule::Asynchronous, None);
    let mut unreachable = false;
    for x in 0..STATES {
        kani::assert(sync.cost_to_go[x] == d[x], "Dijkstra = VI");
        kani::assert(asynchronous.cost_to_go[x] == d[x], "Dijkstra = async VI");
        unreachable |= !d[x].is_finite();
    }
    kani::cover!(unreachable, "a state cannot reach the goal");
    kani::cover!(
        sync.iterations > asynchronous.iterations,
        "Gauss-Seidel needs fewer sweeps than Jacobi"
    );
}

/// Small exhaustive variant (a deliberate second check, enumerated completely by the stand-in):
/// every 3-state problem whose non-goal states have one or two moves with successor and cost in
/// `0..=2` (8100 problems): Dijkstra against the Bellman–Ford oracle (`check_dijkstra`) and,
/// as an extra, against synchronous value iteration. Unwind 6: 5 heap pops (`1 + 4` moves).
#[kani::proof]
#[kani::unwind(6)]
pub fn dijkstra_equals_value_iteration_exhaustive_small() {
    let mut p = Problem {
        n: 3,
        present: [false; 4],
        to: [0; 4],
        cost: [0; 4],
    };
    for x in 0..2 {
        let first: (Three, Three) = kani::any();
        (p.present[2 * x], p.to[2 * x], p.cost[2 * x]) =
            (true, first.0.value(), first.1.value() as u64);
        let second: Option<(Three, Three)> = kani::any();
        if let Some((to, c)) = second {
            (p.present[2 * x + 1], p.to[2 * x + 1], p.cost[2 * x + 1]) =
                (true, to.value(), c.value() as u64);
        }
    }
    let g = check_dijkstra(&p);
    let d = dijkstra::to_goals(&p.graph()).cost_to_go;
    let vi = value_iteration(&p.graph(), Schedule::Synchronous, None).cost_to_go;
    let mut unreachable = false;
    let mut zero_cycle_off_goal = false;
    for x in 0..3 {
        kani::assert(vi[x] == d[x], "Dijkstra = VI");
        unreachable |= g[x].is_none();
        zero_cycle_off_goal |= x < 2 && g[x].is_none() && p.to[2 * x] == x && p.cost[2 * x] == 0;
    }
    kani::cover!(unreachable, "a state cannot reach the goal");
    kani::cover!(
        zero_cycle_off_goal,
        "a zero-cost cycle that avoids the goal"
    );
}

/// Small exhaustive variant (enumerated completely by the stand-in): truecost's model-free
/// exploration (`solvers::exploration::explore`) terminates, discovers exactly the states
/// reachable from `x1`, and counts at most `(2·|moves| + 1)·2` actions (2 = the largest degree),
/// on every 3-state problem whose states each have one or two unit-cost moves (successors
/// anywhere; 1728 problems). Unwind 14: the walk's loop runs at most `2·6 + 1 = 13` times (one
/// step forward per move taken, at most 6, and one step back per step forward plus the start).
#[kani::proof]
#[kani::unwind(14)]
pub fn exploration_discovers_the_reachable_states_exhaustive_small() {
    let mut to = [[0usize; 2]; 3];
    let mut degree = [0usize; 3];
    let mut adjacency: Vec<Vec<(usize, Units)>> = Vec::with_capacity(3);
    for x in 0..3 {
        let first: Three = kani::any();
        let mut list = Vec::with_capacity(2);
        list.push((first.value(), Units(1)));
        (to[x][0], degree[x]) = (first.value(), 1);
        let second: Option<Three> = kani::any();
        if let Some(y) = second {
            list.push((y.value(), Units(1)));
            (to[x][1], degree[x]) = (y.value(), 2);
        }
        adjacency.push(list);
    }
    let moves = degree[0] + degree[1] + degree[2];
    let mut reach = [true, false, false];
    for _ in 0..2 {
        for x in 0..3 {
            for k in 0..degree[x] {
                reach[to[x][k]] |= reach[x];
            }
        }
    }
    let g = Graph::from_adjacency(adjacency, 0, &[2], vec![0, 1, 2], ());
    let e = explore(&g);
    for x in 0..3 {
        kani::assert(
            e.index[x].is_some() == reach[x],
            "discovers exactly the reachable states",
        );
    }
    kani::assert(
        e.actions <= ((2 * moves + 1) * 2) as u64,
        "bounded number of actions",
    );
    kani::cover!(!reach[1] || !reach[2], "a state is unreachable");
    kani::cover!(reach[1] && reach[2], "every state is reached");
    kani::cover!(
        to[0][0] == 0 || (degree[0] == 2 && to[0][1] == 0),
        "a self-loop at x1"
    );
}

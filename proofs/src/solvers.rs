//! The solvers' core lemmas, on truecost's own planners (`truecost_kernel::solvers`).

use truecost_kernel::model::Graph;
use truecost_kernel::solvers::dijkstra;
use truecost_kernel::solvers::exploration::explore;
use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
use truecost_kernel::value::{CostValue, Units};

use crate::Three;

/// States of the symbolic planning problems (goal last, without moves).
pub const STATES: usize = 4;

/// Any 4-state problem with `u32` stage costs: states 0..=2 have one move and optionally a
/// second (successor `u8 % 4`, cost any `u32`), the goal 3 has none. Domain `2^3 · 2^(6·8) ·
/// 2^(6·32) = 2^243` choices. `Units` holds the costs exactly: a planner adds at most 4 of them,
/// far below `u64::MAX`.
fn any_problem() -> Graph<Units> {
    let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(); STATES];
    for list in adjacency.iter_mut().take(STATES - 1) {
        let second: bool = kani::any();
        for k in 0..2 {
            let to = (kani::any::<u8>() % STATES as u8) as usize;
            let cost = kani::any::<u32>() as u64;
            if k == 0 || second {
                list.push((to, Units(cost)));
            }
        }
    }
    Graph::from_adjacency(adjacency, 0, &[STATES - 1], (0..STATES).collect(), ())
}

/// Bellman optimality of truecost's Dijkstra (`solvers::dijkstra::to_goals`): `G*(goal) = 0`
/// and `G*(x) = min_u l(x,u) + G*(f(x,u))` (`+∞` when no move reaches a goal), on every problem
/// of [`any_problem`] (domain 2^243; sampled by the stand-in). Kani also checks that no `Units`
/// addition overflows.
#[kani::proof]
#[kani::unwind(10)]
#[cfg_attr(not(kani), kani::samples(5000))]
pub fn dijkstra_cost_to_go_satisfies_bellman_optimality() {
    let g = any_problem();
    let sol = dijkstra::to_goals(&g);
    let v = &sol.cost_to_go;
    kani::assert(v[STATES - 1] == Units(0), "G*(goal) = 0");
    for x in 0..STATES - 1 {
        let mut best = Units::infinity();
        for (y, c) in g.edges(x) {
            let cand = c.plus(&v[y]);
            if cand.0 < best.0 {
                best = cand;
            }
        }
        kani::assert(v[x] == best, "Bellman optimality");
    }
}

/// Dijkstra's `G*` equals synchronous and asynchronous value iteration's
/// (`solvers::value_iteration`) on every problem of [`any_problem`] (domain 2^243).
#[kani::proof]
#[kani::unwind(10)]
#[cfg_attr(not(kani), kani::samples(5000))]
pub fn dijkstra_equals_value_iteration() {
    let g = any_problem();
    let d = dijkstra::to_goals(&g).cost_to_go;
    kani::assert(
        value_iteration(&g, Schedule::Synchronous, None).cost_to_go == d,
        "Dijkstra = VI",
    );
    kani::assert(
        value_iteration(&g, Schedule::Asynchronous, None).cost_to_go == d,
        "Dijkstra = async VI",
    );
}

/// Small exhaustive variant (a deliberate second check, enumerated completely by the stand-in):
/// every 3-state problem whose non-goal states have one or two moves with successor and cost in
/// `0..=2` (8100 problems): Dijkstra = synchronous VI.
#[kani::proof]
#[kani::unwind(10)]
pub fn dijkstra_equals_value_iteration_exhaustive_small() {
    let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(), Vec::new(), Vec::new()];
    for list in adjacency.iter_mut().take(2) {
        let first: (Three, Three) = kani::any();
        list.push((first.0.value(), Units(first.1.value() as u64)));
        let second: Option<(Three, Three)> = kani::any();
        if let Some((to, c)) = second {
            list.push((to.value(), Units(c.value() as u64)));
        }
    }
    let g = Graph::from_adjacency(adjacency, 0, &[2], vec![0, 1, 2], ());
    let d = dijkstra::to_goals(&g).cost_to_go;
    kani::assert(
        value_iteration(&g, Schedule::Synchronous, None).cost_to_go == d,
        "Dijkstra = VI",
    );
}

/// Small exhaustive variant (enumerated completely by the stand-in): truecost's model-free
/// exploration (`solvers::exploration::explore`) terminates, discovers exactly the states
/// reachable from `x1`, and counts at most `(2·|moves| + 1)·2` actions (2 = the largest degree),
/// on every 3-state problem whose states each have one or two unit-cost moves (successors
/// anywhere; 1728 problems).
#[kani::proof]
#[kani::unwind(16)]
pub fn exploration_discovers_the_reachable_states_exhaustive_small() {
    let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(), Vec::new(), Vec::new()];
    for list in adjacency.iter_mut() {
        let first: Three = kani::any();
        list.push((first.value(), Units(1)));
        let second: Option<Three> = kani::any();
        if let Some(to) = second {
            list.push((to.value(), Units(1)));
        }
    }
    let moves: usize = adjacency.iter().map(Vec::len).sum();
    let mut reach = [true, false, false];
    for _ in 0..3 {
        for x in 0..3 {
            if reach[x] {
                for &(y, _) in &adjacency[x] {
                    reach[y] = true;
                }
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
}

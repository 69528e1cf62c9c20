//! The solvers' core lemmas, on truecost's own planners (`truecost::solvers`).

use num_bigint::BigInt;
use num_rational::BigRational;
use truecost::model::Graph;
use truecost::solvers::dijkstra;
use truecost::solvers::exploration::explore;
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::value::{CostValue, Units};

use crate::Three;

/// Every 3-state problem (goal 2 without moves): states 0 and 1 have a first move (successor
/// and cost in `0..=2`) and optionally a second.
fn any_problem() -> Graph<Units> {
    let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(), Vec::new(), Vec::new()];
    for list in adjacency.iter_mut().take(2) {
        let first: (Three, Three) = kani::any();
        list.push((first.0.value(), Units(first.1.value() as u64)));
        let second: Option<(Three, Three)> = kani::any();
        if let Some((to, c)) = second {
            list.push((to.value(), Units(c.value() as u64)));
        }
    }
    Graph::from_adjacency(
        adjacency,
        0,
        &[2],
        vec![0, 1, 2],
        BigRational::from_integer(BigInt::from(1)),
    )
}

/// Bellman optimality of the computed `G*`: `G*(goal) = 0` and
/// `G*(x) = min_u l(x,u) + G*(f(x,u))` (with `+∞` for no move reaching a goal) on every problem
/// of [`any_problem`].
#[kani::proof]
#[kani::unwind(10)]
pub fn dijkstra_cost_to_go_satisfies_bellman_optimality() {
    let g = any_problem();
    let sol = dijkstra::to_goals(&g);
    let v = &sol.cost_to_go;
    kani::assert(v[2] == Units(0), "G*(goal) = 0");
    for x in 0..2 {
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

/// Dijkstra's `G*` equals synchronous and asynchronous value iteration's.
#[kani::proof]
#[kani::unwind(10)]
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

/// The model-free exploration terminates, discovers exactly the states reachable from `x1`, and
/// counts at most `(2·|moves| + 1)·max degree` actions: every 3-state problem whose states each
/// have one or two unit-cost moves (successors anywhere).
#[kani::proof]
#[kani::unwind(16)]
pub fn exploration_terminates_and_discovers_every_reachable_move() {
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
    let g = Graph::from_adjacency(
        adjacency,
        0,
        &[2],
        vec![0, 1, 2],
        BigRational::from_integer(BigInt::from(1)),
    );
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

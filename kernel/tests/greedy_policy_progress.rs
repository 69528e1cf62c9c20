//! Pins the optimal policy read off `G*` (`kernel/src/solvers/mod.rs`, `greedy_policy`) and the
//! policies of the planners: on zero-cost moves a tight move counts as progress only when it
//! leads strictly closer (fewer optimal moves) to a goal, so following the policy from any node
//! with finite `G*` reaches a goal at total cost `G*`; with positive costs the policy is the
//! first minimiser in action order.
//!
//! Why: the mutation run of 1 Dec 2026 left `h[y] < h[x]` (`<` → `<=`, which lets two nodes
//! point at each other) untested by the kernel's own tests. Expected values: by hand, and on
//! random graphs Bellman–Ford's `G*` and a literal walk written here.

mod support;

use truecost_kernel::model::Decision;
use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
use truecost_kernel::solvers::{dijkstra, follow_policy, greedy_policy};
use truecost_kernel::value::{CostValue, Units};

use support::{Plain, SplitMix};

#[test]
fn equal_distance_neighbours_do_not_point_at_each_other() {
    // 0: [→1 (0), →2 (0)], 1: [→0 (0), →2 (0)], goal 2: G* = 0 everywhere, and both 0 and 1
    // are one move from the goal; each must take its move to 2, not the one to the other.
    let p = Plain {
        adjacency: vec![vec![(1, 0), (2, 0)], vec![(0, 0), (2, 0)], vec![]],
        initial: 0,
        goals: vec![2],
    };
    let expected = vec![
        Some(Decision::Move(1)),
        Some(Decision::Move(1)),
        Some(Decision::Terminate),
    ];
    let g = p.units();
    assert_eq!(greedy_policy(&g, &[Units(0); 3]), expected);
    assert_eq!(dijkstra::to_goals(&g).policy, expected);
    for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
        assert_eq!(value_iteration(&g, schedule, None).policy, expected);
    }
    assert_eq!(greedy_policy(&p.floats(), &[0.0; 3]), expected);
}

/// Checks that `policy` is optimal for `p`: defined exactly where `G*` is finite, and followed
/// from there it reaches a goal at total cost `G*` (the cost of the moves it takes).
fn reaches_goals_optimally(p: &Plain, policy: &[Option<Decision>], optimal: &[Option<u64>]) {
    let g = p.units();
    for x in 0..p.nodes() {
        match optimal[x] {
            None => assert_eq!(policy[x], None, "{p:?} at {x}"),
            Some(cost) => {
                let path = follow_policy(&g, policy, x)
                    .unwrap_or_else(|| panic!("{p:?} {policy:?}: no goal from {x}"));
                assert!(p.is_goal(*path.last().expect("non-empty")));
                let mut total = 0;
                for (k, w) in path.windows(2).enumerate() {
                    let Some(Decision::Move(i)) = policy[w[0]] else {
                        panic!("step {k} of {path:?} is not a move");
                    };
                    assert_eq!(p.adjacency[w[0]][i].0, w[1]);
                    total += p.adjacency[w[0]][i].1;
                }
                assert_eq!(total, cost, "{p:?} from {x}");
            }
        }
    }
}

#[test]
fn policies_reach_a_goal_at_cost_g_star_despite_zero_cost_cycles() {
    let mut draw = SplitMix(0x2E40);
    for _ in 0..2000 {
        let p = Plain::random(&mut draw, 9, 0, 2);
        let optimal = p.optimal_costs();
        let exact: Vec<Units> = optimal
            .iter()
            .map(|c| c.map_or(Units::infinity(), Units))
            .collect();
        let g = p.units();
        reaches_goals_optimally(&p, &greedy_policy(&g, &exact), &optimal);
        reaches_goals_optimally(&p, &dijkstra::to_goals(&g).policy, &optimal);
        let s = value_iteration(&g, Schedule::Asynchronous, None);
        reaches_goals_optimally(&p, &s.policy, &optimal);
    }
}

#[test]
fn with_positive_costs_the_policy_is_the_first_minimiser() {
    let mut draw = SplitMix(0x000F_1257);
    for _ in 0..1500 {
        let p = Plain::random(&mut draw, 9, 1, 3);
        let optimal = p.optimal_costs();
        let expected: Vec<Option<Decision>> = (0..p.nodes())
            .map(|x| {
                if p.is_goal(x) {
                    return Some(Decision::Terminate);
                }
                let gx = optimal[x]?;
                p.adjacency[x]
                    .iter()
                    .position(|&(y, c)| optimal[y].map(|gy| c + gy) == Some(gx))
                    .map(Decision::Move)
            })
            .collect();
        let g = p.units();
        assert_eq!(dijkstra::to_goals(&g).policy, expected, "{p:?}");
        let s = value_iteration(&g, Schedule::Synchronous, None);
        assert_eq!(s.policy, expected, "{p:?}");
        let floats = p.floats();
        assert_eq!(dijkstra::to_goals(&floats).policy, expected, "{p:?}");
        let exact: Vec<f64> = optimal
            .iter()
            .map(|c| c.map_or(f64::INFINITY, |c| c as f64))
            .collect();
        assert_eq!(greedy_policy(&floats, &exact), expected, "{p:?}");
    }
}

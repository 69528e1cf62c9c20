//! Pins exact policy evaluation (`kernel/src/solvers/policy_evaluation.rs`) on the policies the
//! planners never produce: termination at a node that is not a goal, and a move index at or past
//! the node's out-degree. Both mean the task is never accomplished: `+∞`, for that node and for
//! every node whose trajectory runs into it (never a panic, never 0).
//!
//! Why: the mutation run of 1 Dec 2026 left the two match guards of `evaluate_policy`
//! (`is_goal`, `i < degree`) untested. Expected values: by hand, and on random policies a
//! literal walk of at most `|X|` steps written here.

mod support;

use truecost_kernel::model::Decision;
use truecost_kernel::solvers::policy_evaluation::evaluate_policy;
use truecost_kernel::value::{CostValue, Units};

use support::{finite, Plain, SplitMix};

/// 0→1 (2), 1→2 (3), goal 2, and 3 a non-goal without moves.
fn line() -> Plain {
    Plain {
        adjacency: vec![vec![(1, 2)], vec![(2, 3)], vec![], vec![]],
        initial: 0,
        goals: vec![2],
    }
}

#[test]
fn terminating_outside_the_goals_costs_infinity() {
    let g = line().units();
    let inf = Units::infinity();
    let policy = [
        Some(Decision::Move(0)),
        Some(Decision::Terminate),
        Some(Decision::Terminate),
        Some(Decision::Terminate),
    ];
    assert_eq!(evaluate_policy(&g, &policy), vec![inf, inf, Units(0), inf]);
    let policy = [
        Some(Decision::Terminate),
        Some(Decision::Move(0)),
        Some(Decision::Terminate),
        None,
    ];
    assert_eq!(
        evaluate_policy(&g, &policy),
        vec![inf, Units(3), Units(0), inf]
    );
}

#[test]
fn a_move_index_past_the_degree_costs_infinity() {
    let g = line().units();
    let inf = Units::infinity();
    // Degree 1 at nodes 0 and 1: index 1 is the first invalid one.
    for bad in [1, 2, usize::MAX] {
        let policy = [
            Some(Decision::Move(0)),
            Some(Decision::Move(bad)),
            Some(Decision::Terminate),
            Some(Decision::Move(0)),
        ];
        assert_eq!(
            evaluate_policy(&g, &policy),
            vec![inf, inf, Units(0), inf],
            "index {bad}"
        );
    }
    let policy = [
        Some(Decision::Move(0)),
        Some(Decision::Move(0)),
        Some(Decision::Terminate),
        None,
    ];
    assert_eq!(
        evaluate_policy(&g, &policy),
        vec![Units(5), Units(3), Units(0), inf]
    );
}

/// The total cost of following `policy` from `start`: at most `|X|` moves (a longer walk
/// revisits a node and circles forever), ending with termination at a goal.
fn walk(p: &Plain, policy: &[Option<Decision>], start: usize) -> Option<u64> {
    let mut x = start;
    let mut total = 0;
    for _ in 0..=p.nodes() {
        match policy[x] {
            Some(Decision::Terminate) if p.is_goal(x) => return Some(total),
            Some(Decision::Move(i)) if i < p.adjacency[x].len() => {
                let (y, c) = p.adjacency[x][i];
                total += c;
                x = y;
            }
            _ => return None,
        }
    }
    None
}

#[test]
fn evaluation_is_the_literal_walk_on_random_policies() {
    let mut draw = SplitMix(0x0090_11C7);
    for _ in 0..3000 {
        let p = Plain::random(&mut draw, 8, 0, 3);
        let policy: Vec<Option<Decision>> = (0..p.nodes())
            .map(|x| match draw.below(6) {
                0 => None,
                1 => Some(Decision::Terminate),
                // Indices up to one past the degree: some invalid.
                _ => Some(Decision::Move(
                    draw.below(p.adjacency[x].len() as u64 + 2) as usize
                )),
            })
            .collect();
        let expected: Vec<Option<u64>> = (0..p.nodes()).map(|x| walk(&p, &policy, x)).collect();
        assert_eq!(
            finite(&evaluate_policy(&p.units(), &policy), |v| v.0),
            expected,
            "{p:?} {policy:?}"
        );
    }
}

//! Pins value iteration (`kernel/src/solvers/value_iteration.rs`): a backup takes the *least*
//! `l(x,u) + G(f(x,u))` over all moves (not the first or last), the Gauss–Seidel schedule
//! updates in place only on a strict decrease, and the sweep and backup counts are those of the
//! module's documentation (the confirming sweep counted, `Σ degree` backups per sweep).
//!
//! Why: the mutation run of 1 Dec 2026 left `best_backup`'s match guard and the asynchronous
//! update's comparison untested by the kernel's own tests. Expected values: chains computed by
//! hand, and on random graphs Bellman–Ford plus the iterates `V_k` (least cost over at most `k`
//! moves) and a Gauss–Seidel sweep written here from the documentation.

mod support;

use truecost_kernel::model::Graph;
use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
use truecost_kernel::value::{CostValue, Units};

use support::{finite, Plain, SplitMix};

/// `min` over the moves of `x` of `c + g[y]` (`None` if no move reaches a finite value).
fn backup(p: &Plain, x: usize, g: &[Option<u64>]) -> Option<u64> {
    p.adjacency[x]
        .iter()
        .filter_map(|&(y, c)| g[y].map(|gy| c + gy))
        .min()
}

fn improves(new: Option<u64>, old: Option<u64>) -> bool {
    matches!((new, old), (Some(a), Some(b)) if a < b) || (new.is_some() && old.is_none())
}

/// Jacobi sweeps from `G = 0` at goals, `+∞` elsewhere: `(values, sweeps)` after stopping at
/// the first sweep that changes nothing, or after `limit` sweeps.
fn synchronous(p: &Plain, limit: u64) -> (Vec<Option<u64>>, u64) {
    let mut g: Vec<Option<u64>> = (0..p.nodes()).map(|v| p.is_goal(v).then_some(0)).collect();
    let mut sweeps = 0;
    loop {
        sweeps += 1;
        let next: Vec<Option<u64>> = (0..p.nodes())
            .map(|x| {
                let b = backup(p, x, &g);
                if improves(b, g[x]) {
                    b
                } else {
                    g[x]
                }
            })
            .collect();
        let changed = next != g;
        g = next;
        if !changed || sweeps >= limit {
            return (g, sweeps);
        }
    }
}

/// Gauss–Seidel sweeps in node order, in place.
fn asynchronous(p: &Plain) -> (Vec<Option<u64>>, u64) {
    let mut g: Vec<Option<u64>> = (0..p.nodes()).map(|v| p.is_goal(v).then_some(0)).collect();
    let mut sweeps = 0;
    loop {
        sweeps += 1;
        let mut changed = false;
        for x in 0..p.nodes() {
            let b = backup(p, x, &g);
            if improves(b, g[x]) {
                g[x] = b;
                changed = true;
            }
        }
        if !changed {
            return (g, sweeps);
        }
    }
}

fn edges(p: &Plain) -> u64 {
    p.adjacency.iter().map(|l| l.len() as u64).sum()
}

#[test]
fn both_schedules_reach_the_least_costs_in_the_documented_sweeps() {
    let mut draw = SplitMix(0x0BAC_00B5);
    for _ in 0..1500 {
        let p = Plain::random(&mut draw, 9, 0, 6);
        let g = p.units();
        let optimal = p.optimal_costs();
        let (values, sweeps) = synchronous(&p, u64::MAX);
        assert_eq!(values, optimal, "{p:?}");
        let s = value_iteration(&g, Schedule::Synchronous, None);
        assert_eq!(finite(&s.cost_to_go, |v| v.0), optimal, "{p:?}");
        assert_eq!(
            (s.iterations, s.actions),
            (sweeps, sweeps * edges(&p)),
            "{p:?}"
        );
        let (values, sweeps) = asynchronous(&p);
        assert_eq!(values, optimal, "{p:?}");
        let a = value_iteration(&g, Schedule::Asynchronous, None);
        assert_eq!(finite(&a.cost_to_go, |v| v.0), optimal, "{p:?}");
        assert_eq!(
            (a.iterations, a.actions),
            (sweeps, sweeps * edges(&p)),
            "{p:?}"
        );
        assert!(a.iterations <= s.iterations);
    }
}

#[test]
fn a_sweep_cap_stops_at_the_capped_iterate() {
    let mut draw = SplitMix(0xCA9);
    for _ in 0..500 {
        let p = Plain::random(&mut draw, 8, 1, 4);
        for cap in 1..4 {
            let (values, sweeps) = synchronous(&p, cap);
            let s = value_iteration(&p.units(), Schedule::Synchronous, Some(cap));
            assert_eq!(finite(&s.cost_to_go, |v| v.0), values, "{p:?} cap {cap}");
            assert_eq!(s.iterations, sweeps);
        }
    }
}

/// 0→1→2→3 (cost 1 each), goal 3.
fn chain_to_last() -> Graph<Units> {
    Plain {
        adjacency: vec![vec![(1, 1)], vec![(2, 1)], vec![(3, 1)], vec![]],
        initial: 0,
        goals: vec![3],
    }
    .units()
}

/// 3→2→1→0 (cost 1 each), goal 0.
fn chain_to_first() -> Graph<Units> {
    Plain {
        adjacency: vec![vec![], vec![(0, 1)], vec![(1, 1)], vec![(2, 1)]],
        initial: 3,
        goals: vec![0],
    }
    .units()
}

#[test]
fn gauss_seidel_uses_values_updated_in_the_same_sweep() {
    let expected = |v: [u64; 4]| v.map(Units).to_vec();
    // Towards the last node: each sweep moves the value one node back, in either schedule:
    // three sweeps that change, one that confirms; 3 moves per sweep.
    for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
        let s = value_iteration(&chain_to_last(), schedule, None);
        assert_eq!(s.cost_to_go, expected([3, 2, 1, 0]));
        assert_eq!((s.iterations, s.actions), (4, 12), "{schedule:?}");
    }
    // Towards node 0, in node order: Gauss–Seidel settles all in the first sweep (2 sweeps),
    // Jacobi still needs 4.
    let s = value_iteration(&chain_to_first(), Schedule::Asynchronous, None);
    assert_eq!(s.cost_to_go, expected([0, 1, 2, 3]));
    assert_eq!((s.iterations, s.actions), (2, 6));
    let s = value_iteration(&chain_to_first(), Schedule::Synchronous, None);
    assert_eq!(s.cost_to_go, expected([0, 1, 2, 3]));
    assert_eq!((s.iterations, s.actions), (4, 12));
}

#[test]
fn a_backup_takes_the_least_of_all_moves() {
    // 0 has three moves to the goal 1 costing 5, 2, 7 (the least in the middle) and one to the
    // dead end 2; 1 has a move back to 0 (cost 1), which must not raise the goal's 0.
    let g = Plain {
        adjacency: vec![vec![(1, 5), (1, 2), (2, 1), (1, 7)], vec![(0, 1)], vec![]],
        initial: 0,
        goals: vec![1],
    }
    .units();
    for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
        let s = value_iteration(&g, schedule, None);
        assert_eq!(
            s.cost_to_go,
            vec![Units(2), Units(0), Units::infinity()],
            "{schedule:?}"
        );
        // Sweep 1 sets G(0) = 2, sweep 2 confirms; 5 moves per sweep.
        assert_eq!((s.iterations, s.actions), (2, 10), "{schedule:?}");
    }
}

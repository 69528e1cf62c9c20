//! Pins derandomized Q-learning (`kernel/src/claims/qlearning.rs`): the pairs a problem is
//! prepared into (termination pair of the goal first, `Q*` from `G*`), the `ρ = 1` update, which
//! pairs are updatable, `h(x)` (fewest optimal moves to the goal) and the rounds of `run` under
//! the cyclic, reverse and far-first orders, against a literal round-by-round simulation.
//!
//! Why: claim C1 is checked with these; the kernel's own tests pinned them by one doctest.
//! Expected values: by hand, Bellman–Ford, a breadth-first search over optimal moves and a
//! simulation of the rounds written here from the module documentation.

use truecost_kernel::claims::qlearning::{run, Order, Pair, QProblem, Run, Terminal, Values};
use truecost_kernel::claims::tiny::Tiny;

mod support;
use support::SplitMix;

/// 0 → 1 (2), 0 → 2 (1), 1 → 2 (3), goal 2 with a move 2 → 0 (1).
fn small() -> Tiny {
    Tiny::from_lists(&[vec![(1, 2), (2, 1)], vec![(2, 3)], vec![(0, 1)]])
}

#[test]
fn a_problem_becomes_its_state_action_pairs() {
    let pair = |state, to, cost, terminal| Pair {
        state,
        to,
        cost,
        terminal,
    };
    for terminal in [Terminal::Updated, Terminal::HeldAtZero] {
        let q = QProblem::new(&small(), terminal);
        assert_eq!(
            q.pairs,
            vec![
                pair(0, 1, 2, false),
                pair(0, 2, 1, false),
                pair(1, 2, 3, false),
                pair(2, 2, 0, true),
                pair(2, 0, 1, false),
            ]
        );
        assert_eq!(&q.first[..4], &[0, 2, 3, 5]);
        assert!(q.first[4..].iter().all(|&f| f == 5));
        assert_eq!((q.len(), q.is_empty(), q.states), (5, false, 3));
        // G* = (1, 3, 0); Q*(x, u) = l + G*(f(x, u)), 0 for the termination pair.
        assert_eq!(&q.cost_to_go[..3], &[Some(1), Some(3), Some(0)]);
        assert_eq!(q.optimum, vec![Some(5), Some(1), Some(3), Some(0), Some(2)]);
        assert!(q.all_finite());
        let held = terminal == Terminal::HeldAtZero;
        assert_eq!(
            (0..5).map(|p| q.updatable(p)).collect::<Vec<_>>(),
            vec![true, true, true, !held, true]
        );
        let mut optimal = [0i64; 24];
        optimal[..5].copy_from_slice(&[5, 1, 3, 0, 2]);
        assert!(q.is_optimal(&optimal));
        optimal[4] = 3;
        assert!(!q.is_optimal(&optimal));
        // h: 0 and 1 are one optimal move from the goal, the goal 0.
        assert_eq!(&q.optimal_steps()[..3], &[Some(1), Some(1), Some(0)]);
    }
    // A state that cannot reach the goal: Q* infinite there.
    let q = QProblem::new(
        &Tiny::from_lists(&[vec![(0, 1)], vec![]]),
        Terminal::HeldAtZero,
    );
    assert_eq!(q.optimum, vec![None, Some(0)]);
    assert!(!q.all_finite());
    let mut v = [0i64; 24];
    v[1] = 0;
    assert!(!q.is_optimal(&v));
    assert_eq!(&q.optimal_steps()[..2], &[None, Some(0)]);
}

#[test]
fn an_update_is_cost_plus_the_least_value_at_the_successor() {
    let q = QProblem::new(&small(), Terminal::Updated);
    let mut v: Values = [0; 24];
    v[..5].copy_from_slice(&[10, 20, 30, 40, 50]);
    q.update(&mut v, 0); // 0 → 1: 2 + min(v[2]) = 32
    assert_eq!(v[0], 32);
    q.update(&mut v, 1); // 0 → 2: 1 + min(40, 50) = 41
    assert_eq!(v[1], 41);
    q.update(&mut v, 3); // termination: 0 + min(40, 50) = 40 (updated, as printed)
    assert_eq!(v[3], 40);
    q.update(&mut v, 4); // 2 → 0: 1 + min(32, 41) = 33
    assert_eq!(v[4], 33);
    let held = QProblem::new(&small(), Terminal::HeldAtZero);
    v[3] = 7;
    held.update(&mut v, 3);
    assert_eq!(v[3], 7, "a held termination pair is not updated");
}

/// The rounds simulated literally: each round applies the update to every updatable pair in
/// `sequence`; `Converged(r)` at the first round end equal to `Q*`, `Cycles` when a round-end
/// value repeats.
fn simulate(q: &QProblem, q0: &Values, sequence: &[usize], max_rounds: u64) -> Run {
    let mut v = *q0;
    let optimal = |v: &Values| (0..q.len()).all(|p| q.optimum[p] == Some(v[p]));
    if optimal(&v) {
        return Run::Converged(0);
    }
    let mut history = vec![v];
    for round in 1..=max_rounds {
        for &p in sequence {
            if q.updatable(p) {
                let pair = q.pairs[p];
                let y = pair.to as usize;
                let best = (0..q.len())
                    .filter(|&r| q.pairs[r].state as usize == y)
                    .map(|r| v[r])
                    .min()
                    .expect("every state has a pair here");
                v[p] = pair.cost + best;
            }
        }
        if optimal(&v) {
            return Run::Converged(round);
        }
        if let Some(k) = history.iter().position(|h| *h == v) {
            return Run::Cycles(k as u64, round - k as u64);
        }
        history.push(v);
    }
    Run::NotWithin(max_rounds)
}

/// Fewest optimal moves to the goal, by breadth-first search backwards over tight moves.
fn steps(t: &Tiny, g: &[Option<i64>]) -> Vec<Option<u32>> {
    let n = t.states();
    let mut h: Vec<Option<u32>> = (0..n).map(|x| t.is_goal(x).then_some(0)).collect();
    for k in 0..n as u32 {
        for x in 0..n {
            if h[x].is_some() {
                continue;
            }
            let tight = t.moves(x).iter().any(|m| {
                let y = m.to as usize;
                h[y] == Some(k) && g[x].is_some() && g[y].map(|gy| gy + i64::from(m.cost)) == g[x]
            });
            if tight {
                h[x] = Some(k + 1);
            }
        }
    }
    h
}

#[test]
fn rounds_match_the_literal_simulation_under_each_order() {
    let mut draw = SplitMix(41);
    let mut converged = 0;
    for _ in 0..400 {
        let t = support::random_tiny(&mut draw);
        let n = t.states();
        for terminal in [Terminal::Updated, Terminal::HeldAtZero] {
            let q = QProblem::new(&t, terminal);
            assert_eq!(
                &q.optimal_steps()[..n],
                &steps(&t, &q.cost_to_go)[..],
                "{t:?}"
            );
            let mut q0: Values = [0; 24];
            for v in q0.iter_mut().take(q.len()) {
                *v = draw.below(6) as i64 - 1;
            }
            let cyclic: Vec<usize> = (0..q.len()).collect();
            let reverse: Vec<usize> = (0..q.len()).rev().collect();
            let h = q.optimal_steps();
            let mut far: Vec<usize> = (0..q.len()).collect();
            far.sort_by_key(|&p| {
                let y = q.pairs[p].to as usize;
                (std::cmp::Reverse(h[y].map_or(u64::MAX, u64::from)), p)
            });
            for (order, sequence) in [
                (Order::Cyclic, cyclic),
                (Order::Reverse, reverse),
                (Order::FarFirst, far),
            ] {
                let expected = simulate(&q, &q0, &sequence, 12);
                assert_eq!(run(&q, &q0, order, 12), expected, "{t:?} {order:?}");
                converged += usize::from(matches!(expected, Run::Converged(_)));
            }
            // A fresh permutation every round is not periodic: never reported as cycling.
            let random = run(&q, &q0, Order::Random(5), 12);
            assert!(!matches!(random, Run::Cycles(..)), "{t:?} {random:?}");
        }
    }
    assert!(converged > 100, "{converged}");
}

#[test]
fn the_round_bound_by_hand() {
    let q = QProblem::new(&small(), Terminal::HeldAtZero);
    // Move pairs 0, 1, 2, 4 lead to 1, 2, 2, 0 with h = 1, 0, 0, 1: R₁ = 1 + 1 = 2.
    let mut q0: Values = [0; 24];
    q0[..5].copy_from_slice(&[5, 1, 3, 0, 2]); // Q* itself: Q₀ ≥ Q*
    assert_eq!(q.round_bound(&q0), Some(2));
    q0[..5].copy_from_slice(&[9, 1, 7, 0, 2]);
    assert_eq!(q.round_bound(&q0), Some(2));
    // Below Q*: least move cost c = 1, max Q* over moves 5, min(0, min Q₀) = 0: ⌈5/1⌉ = 5.
    q0[..5].copy_from_slice(&[0, 0, 0, 0, 0]);
    assert_eq!(q.round_bound(&q0), Some(5));
    // min Q₀ = −3 (the termination pair is not a move and does not count): ⌈8/1⌉ = 8.
    q0[..5].copy_from_slice(&[4, -3, 3, -9, 2]);
    assert_eq!(q.round_bound(&q0), Some(8));
    // Costs 2 and 4, goal 1 (0 → 1 (2), 1 → 0 (4)): c = 2, Q* = (2, 6); from 0: ⌈6/2⌉ = 3 > R₁.
    let q = QProblem::new(
        &Tiny::from_lists(&[vec![(1, 2)], vec![(0, 4)]]),
        Terminal::HeldAtZero,
    );
    assert_eq!(q.optimum, vec![Some(2), Some(0), Some(6)]);
    assert_eq!(q.round_bound(&[0; 24]), Some(3));
    // ⌈7/2⌉ = 4 with min Q₀ = −1.
    let mut q0: Values = [0; 24];
    q0[2] = -1;
    assert_eq!(q.round_bound(&q0), Some(4));
    // A zero-cost move and Q₀ below Q*: neither hypothesis holds.
    let q = QProblem::new(
        &Tiny::from_lists(&[vec![(1, 0)], vec![]]),
        Terminal::HeldAtZero,
    );
    assert_eq!(q.round_bound(&[-1; 24]), None);
    assert_eq!(q.round_bound(&[0; 24]), Some(1));
    // A state that cannot reach the goal: no bound.
    let q = QProblem::new(
        &Tiny::from_lists(&[vec![(0, 1)], vec![]]),
        Terminal::HeldAtZero,
    );
    assert_eq!(q.round_bound(&[0; 24]), None);
}

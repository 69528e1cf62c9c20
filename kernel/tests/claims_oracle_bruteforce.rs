//! Pins the claims' policy-enumeration oracles (`kernel/src/claims/oracle.rs`) against brute
//! force written here: the policies enumerated, the lasso a policy traces (against the literal
//! walk), every functional's value (horizon sums and averages against the literal stage
//! sequence, the discounted value by its Bellman equation `V(x) = l + α V(f(x))`, the total and
//! the average by the stages after the lasso closes), `G*`, Karp's minimum mean cycle and the
//! simple cycles (against every closed walk of distinct nodes), the goal-avoiding part of the
//! graph and the simple goal paths.
//!
//! Why: the oracles are the independent side of every claim check (C2–C4); the kernel's
//! own tests pinned them by two hand examples.

// Index loops over states read better than iterator chains here (as in kernel/src/claims).
#![allow(clippy::needless_range_loop)]

use truecost_kernel::claims::exact::{Ext, FracExt, Q};
use truecost_kernel::claims::oracle::{
    evaluate, evaluate_fast, goal_avoiding_arcs, karp_minimum_mean_cycle, optimal_cost_to_go,
    policies, simple_cycles, simple_goal_paths, trajectory, Functional, Policy, Trajectory,
    TERMINATE,
};
use truecost_kernel::claims::tiny::{Tiny, MAX_STATES};

mod support;
use support::SplitMix;

/// A random tiny problem: 1 to `max_states` states, 0 to 3 moves each, costs 0 to 3.
fn random_tiny(draw: &mut SplitMix, max_states: u64) -> Tiny {
    let n = 1 + draw.below(max_states) as usize;
    let lists: Vec<Vec<(u8, u8)>> = (0..n)
        .map(|_| {
            (0..draw.below(4))
                .map(|_| (draw.below(n as u64) as u8, draw.below(4) as u8))
                .collect()
        })
        .collect();
    Tiny::from_lists(&lists)
}

/// The literal walk of `policy` from `start`: the states visited and the stage costs, for
/// `steps` steps or until termination (then `true`).
fn walk(t: &Tiny, policy: &Policy, start: usize, steps: usize) -> (Vec<usize>, Vec<i64>, bool) {
    let (mut states, mut stages) = (vec![start], Vec::new());
    let mut x = start;
    for _ in 0..steps {
        if policy[x] == TERMINATE {
            return (states, stages, true);
        }
        let m = t.moves(x)[policy[x] as usize];
        stages.push(i64::from(m.cost));
        x = m.to as usize;
        states.push(x);
    }
    (states, stages, false)
}

/// The literal stage sequence of `policy` from `start`, `len` stages long (zeros after
/// termination, as the frozen cycle of docs/spec.md §1).
fn stages(t: &Tiny, policy: &Policy, start: usize, len: usize) -> Vec<i64> {
    let (_, mut s, _) = walk(t, policy, start, len);
    s.resize(len, 0);
    s
}

fn as_q(v: FracExt) -> Ext {
    match v {
        FracExt::NegInf => Ext::NegInf,
        FracExt::PosInf => Ext::PosInf,
        FracExt::Fin(f) => Ext::Fin(Q::new(f.n, f.d)),
    }
}

fn sample_policies(t: &Tiny, draw: &mut SplitMix) -> Vec<Policy> {
    let mut all = policies(t, true);
    while all.len() > 12 {
        all.swap_remove(draw.below(all.len() as u64) as usize);
    }
    all
}

#[test]
fn policies_are_every_combination_of_choices() {
    // 0: two moves, 1: one move, goal 2: one move.
    let t = Tiny::from_lists(&[vec![(1, 0), (2, 1)], vec![(2, 0)], vec![(0, 0)]]);
    let p = |a: u8, b: u8, c: u8| {
        let mut q = [0u8; MAX_STATES];
        q[..3].copy_from_slice(&[a, b, c]);
        q
    };
    assert_eq!(
        policies(&t, false),
        vec![p(0, 0, TERMINATE), p(1, 0, TERMINATE)]
    );
    assert_eq!(
        policies(&t, true),
        vec![
            p(0, 0, TERMINATE),
            p(0, 0, 0),
            p(1, 0, TERMINATE),
            p(1, 0, 0)
        ]
    );
    // A non-goal state without moves: no policy at all.
    assert!(policies(&Tiny::from_lists(&[vec![], vec![]]), true).is_empty());
    let mut draw = SplitMix(7);
    for _ in 0..300 {
        let t = random_tiny(&mut draw, 5);
        let n = t.states();
        let count = |goal_may_move: bool| -> usize {
            (0..n)
                .map(|x| match (t.is_goal(x), goal_may_move) {
                    (true, true) => 1 + t.moves(x).len(),
                    (true, false) => 1,
                    (false, _) => t.moves(x).len(),
                })
                .product()
        };
        for goal_may_move in [false, true] {
            let ps = policies(&t, goal_may_move);
            assert_eq!(ps.len(), count(goal_may_move), "{t:?}");
            let mut distinct = ps.clone();
            distinct.sort();
            distinct.dedup();
            assert_eq!(distinct.len(), ps.len());
            for p in &ps {
                for x in 0..n {
                    if p[x] == TERMINATE {
                        assert!(t.is_goal(x));
                    } else {
                        assert!((p[x] as usize) < t.moves(x).len());
                        assert!(goal_may_move || !t.is_goal(x));
                    }
                }
            }
        }
    }
}

/// The lasso of the literal walk: `(prefix_len, cycle_len, terminates, visits_goal)`.
fn lasso(t: &Tiny, policy: &Policy, start: usize) -> (usize, usize, bool, bool) {
    let (states, _, terminated) = walk(t, policy, start, t.states() + 1);
    let visits_goal = states.iter().any(|&x| t.is_goal(x));
    if terminated {
        return (states.len() - 1, 1, true, visits_goal);
    }
    let j = (1..states.len())
        .find(|&j| states[..j].contains(&states[j]))
        .expect("a repeat within |X| + 1 states");
    let s = states[..j]
        .iter()
        .position(|&x| x == states[j])
        .expect("seen");
    let visits_goal = states[..j].iter().any(|&x| t.is_goal(x));
    (s, j - s, false, visits_goal)
}

fn stage_of(tr: &Trajectory, k: usize) -> i64 {
    if k < tr.prefix_len {
        tr.prefix[k]
    } else {
        tr.cycle[(k - tr.prefix_len) % tr.cycle_len]
    }
}

#[test]
fn a_trajectory_is_the_lasso_of_the_literal_walk() {
    let mut draw = SplitMix(11);
    for _ in 0..400 {
        let t = random_tiny(&mut draw, 6);
        for p in sample_policies(&t, &mut draw) {
            for start in 0..t.states() {
                let tr = trajectory(&t, &p, start);
                let (prefix_len, cycle_len, terminates, visits_goal) = lasso(&t, &p, start);
                assert_eq!(
                    (tr.prefix_len, tr.cycle_len, tr.terminates, tr.visits_goal),
                    (prefix_len, cycle_len, terminates, visits_goal),
                    "{t:?} {p:?} from {start}"
                );
                let literal = stages(&t, &p, start, 3 * MAX_STATES);
                for (k, &s) in literal.iter().enumerate() {
                    assert_eq!(stage_of(&tr, k), s, "stage {k}, {t:?} {p:?} from {start}");
                }
                if tr.terminates {
                    assert_eq!(tr.cycle[0], 0);
                }
            }
        }
    }
}

fn alphas() -> [Q; 3] {
    [Q::new(1, 2), Q::new(9, 10), Q::new(2, 3)]
}

fn q(v: i64) -> Q {
    Q::int(i128::from(v))
}

#[test]
fn functionals_agree_with_the_literal_stage_sequence() {
    let mut draw = SplitMix(13);
    for _ in 0..300 {
        let t = random_tiny(&mut draw, 5);
        for p in sample_policies(&t, &mut draw) {
            for start in 0..t.states() {
                let tr = trajectory(&t, &p, start);
                let literal = stages(&t, &p, start, 3 * MAX_STATES);
                for sign in [1i64, -1] {
                    let s = |k: usize| sign * literal[k];
                    let check = |f: Functional, expected: Ext| {
                        assert_eq!(evaluate(&tr, f, sign), expected, "{f:?} {t:?} {p:?}");
                        assert_eq!(as_q(evaluate_fast(&tr, f, sign)), expected, "fast {f:?}");
                    };
                    for h in 0..6 {
                        let total = (0..h).fold(Q::ZERO, |a, k| a + q(s(k)));
                        check(Functional::HorizonTotal(h), Ext::Fin(total));
                        if h > 0 {
                            check(
                                Functional::HorizonAverage(h),
                                Ext::Fin(total / Q::int(h as i128)),
                            );
                        }
                        for a in alphas() {
                            let value = (0..h).fold(Q::ZERO, |v, k| v + a.pow(k as u32) * q(s(k)));
                            check(Functional::HorizonDiscounted(h, a), Ext::Fin(value));
                        }
                    }
                    // After |X| stages the walk is on its cycle (or frozen at 0).
                    let n = t.states();
                    let tail: Vec<i64> = (n..n + MAX_STATES).map(s).collect();
                    let total = if tail.iter().all(|&v| v == 0) {
                        Ext::Fin((0..n).fold(Q::ZERO, |a, k| a + q(s(k))))
                    } else if sign > 0 {
                        Ext::PosInf
                    } else {
                        Ext::NegInf
                    };
                    check(Functional::Total, total);
                    // 420 = lcm(1..=7) stages of the cycle, from stage |X|.
                    let long = stages(&t, &p, start, n + 420);
                    let mean: i128 = (n..n + 420).map(|k| i128::from(sign * long[k])).sum();
                    check(Functional::Average, Ext::Fin(Q::new(mean, 420)));
                }
            }
        }
    }
}

#[test]
fn discounted_values_satisfy_the_bellman_equation() {
    let mut draw = SplitMix(17);
    for _ in 0..300 {
        let t = random_tiny(&mut draw, 6);
        for p in sample_policies(&t, &mut draw) {
            for a in alphas() {
                for sign in [1i64, -1] {
                    let value = |x: usize| {
                        let v = evaluate(&trajectory(&t, &p, x), Functional::Discounted(a), sign);
                        let fast =
                            evaluate_fast(&trajectory(&t, &p, x), Functional::Discounted(a), sign);
                        assert_eq!(as_q(fast), v);
                        match v {
                            Ext::Fin(v) => v,
                            other => panic!("discounted value {other:?}"),
                        }
                    };
                    for x in 0..t.states() {
                        let expected = if p[x] == TERMINATE {
                            Q::ZERO
                        } else {
                            let m = t.moves(x)[p[x] as usize];
                            q(sign * i64::from(m.cost)) + a * value(m.to as usize)
                        };
                        assert_eq!(value(x), expected, "{t:?} {p:?} at {x}");
                    }
                }
            }
        }
    }
}

#[test]
fn hand_values_of_a_lasso() {
    // 0 → 1 (cost 2), 1 → 1 (cost 4): stages 2, 4, 4, ...
    let t = Tiny::from_lists(&[vec![(1, 2)], vec![(1, 4), (2, 0)], vec![]]);
    let tr = trajectory(&t, &[0, 0, TERMINATE, 0, 0, 0, 0], 0);
    let half = Q::new(1, 2);
    // 2 + (1/2)·4/(1 − 1/2) = 6.
    assert_eq!(
        evaluate(&tr, Functional::Discounted(half), 1),
        Ext::Fin(Q::int(6))
    );
    assert_eq!(
        evaluate(&tr, Functional::Discounted(half), -1),
        Ext::Fin(Q::int(-6))
    );
    assert_eq!(evaluate(&tr, Functional::Total, 1), Ext::PosInf);
    assert_eq!(evaluate(&tr, Functional::Total, -1), Ext::NegInf);
    assert_eq!(evaluate(&tr, Functional::Average, 1), Ext::Fin(Q::int(4)));
    // 2 + 4·(1/2) + 4·(1/4) = 5; (2 + 4 + 4)/3.
    assert_eq!(
        evaluate(&tr, Functional::HorizonDiscounted(3, half), 1),
        Ext::Fin(Q::int(5))
    );
    assert_eq!(
        evaluate(&tr, Functional::HorizonAverage(3), 1),
        Ext::Fin(Q::new(10, 3))
    );
    // 0 → 1 (2), 1 → 2 (0), terminate at 2: total 2, frozen at 0 afterwards.
    let tr = trajectory(&t, &[0, 1, TERMINATE, 0, 0, 0, 0], 0);
    assert!(tr.terminates && tr.visits_goal);
    assert_eq!(evaluate(&tr, Functional::Total, 1), Ext::Fin(Q::int(2)));
    assert_eq!(evaluate(&tr, Functional::Average, 1), Ext::Fin(Q::ZERO));
    assert_eq!(
        evaluate(&tr, Functional::Discounted(half), 1),
        Ext::Fin(Q::int(2))
    );
    assert_eq!(Functional::Total.name(), "total");
    assert_eq!(Functional::Average.name(), "average");
    assert_eq!(Functional::Discounted(half).name(), "discounted(alpha=1/2)");
    assert_eq!(Functional::HorizonTotal(3).name(), "total over 3 stages");
    assert_eq!(
        Functional::HorizonDiscounted(3, half).name(),
        "discounted(alpha=1/2) over 3 stages"
    );
    assert_eq!(
        Functional::HorizonAverage(4).name(),
        "average over 4 stages"
    );
}

/// `G*` by Bellman–Ford on the tiny problem's moves (goal = last state, value 0).
fn bellman_ford(t: &Tiny) -> Vec<Option<i64>> {
    let n = t.states();
    let mut g: Vec<Option<i64>> = (0..n).map(|x| t.is_goal(x).then_some(0)).collect();
    for _ in 0..n {
        for x in 0..n {
            for m in t.moves(x) {
                if let Some(gy) = g[m.to as usize] {
                    let c = i64::from(m.cost) + gy;
                    if g[x].is_none_or(|gx| c < gx) {
                        g[x] = Some(c);
                    }
                }
            }
        }
    }
    g
}

#[test]
fn optimal_cost_to_go_is_the_least_cost_to_the_goal() {
    let mut draw = SplitMix(19);
    for _ in 0..600 {
        let t = random_tiny(&mut draw, 5);
        let g = optimal_cost_to_go(&t);
        let expected = bellman_ford(&t);
        // A state with a move-less non-goal elsewhere has no policy at all: then nothing is
        // evaluated and every value stays `None`.
        if policies(&t, false).is_empty() {
            assert!(g.iter().all(Option::is_none));
            continue;
        }
        assert_eq!(&g[..t.states()], &expected[..], "{t:?}");
        assert!(g[t.states()..].iter().all(Option::is_none));
    }
}

/// Every simple cycle as `(weight, length)`, by enumerating arc sequences: closed walks of
/// distinct nodes whose first node is their smallest.
fn cycles_by_walks(n: usize, arcs: &[(usize, usize, i64)]) -> Vec<(i64, usize)> {
    let mut out = Vec::new();
    let mut walks: Vec<Vec<usize>> = (0..arcs.len()).map(|i| vec![i]).collect();
    for _ in 0..n {
        let mut next = Vec::new();
        for w in walks {
            let nodes: Vec<usize> = w.iter().map(|&i| arcs[i].0).collect();
            let end = arcs[*w.last().expect("non-empty")].1;
            let root = nodes[0];
            let distinct = (0..nodes.len()).all(|i| !nodes[..i].contains(&nodes[i]));
            if !distinct || nodes.iter().any(|&v| v < root) {
                continue;
            }
            if end == root {
                out.push((w.iter().map(|&i| arcs[i].2).sum(), w.len()));
            }
            for (i, a) in arcs.iter().enumerate() {
                if a.0 == end && end != root {
                    let mut longer = w.clone();
                    longer.push(i);
                    next.push(longer);
                }
            }
        }
        walks = next;
    }
    out.sort();
    out
}

fn random_arcs(draw: &mut SplitMix) -> (usize, Vec<(usize, usize, i64)>) {
    let n = 1 + draw.below(4) as usize;
    let arcs = (0..draw.below(7))
        .map(|_| {
            (
                draw.below(n as u64) as usize,
                draw.below(n as u64) as usize,
                draw.below(7) as i64 - 2,
            )
        })
        .collect();
    (n, arcs)
}

#[test]
fn simple_cycles_and_karp_agree_with_every_closed_walk() {
    let mut draw = SplitMix(23);
    for _ in 0..3000 {
        let (n, arcs) = random_arcs(&mut draw);
        let expected = cycles_by_walks(n, &arcs);
        let mut cycles = simple_cycles(n, &arcs);
        cycles.sort();
        assert_eq!(cycles, expected, "{n} {arcs:?}");
        let least_mean = expected
            .iter()
            .map(|&(w, len)| Q::new(i128::from(w), len as i128))
            .min();
        assert_eq!(
            karp_minimum_mean_cycle(n, &arcs),
            least_mean,
            "{n} {arcs:?}"
        );
    }
    assert_eq!(karp_minimum_mean_cycle(0, &[]), None);
    assert_eq!(karp_minimum_mean_cycle(2, &[(0, 1, 5)]), None);
}

#[test]
fn the_goal_avoiding_part_is_what_x1_reaches_without_the_goal() {
    let mut draw = SplitMix(29);
    for _ in 0..1000 {
        let t = random_tiny(&mut draw, 6);
        let n = t.states();
        let mut seen = vec![false; n];
        if !t.is_goal(0) {
            seen[0] = true;
            for _ in 0..n {
                for x in 0..n {
                    if seen[x] {
                        for m in t.moves(x) {
                            if !t.is_goal(m.to as usize) {
                                seen[m.to as usize] = true;
                            }
                        }
                    }
                }
            }
        }
        let arcs: Vec<(usize, usize, i64)> = (0..n)
            .filter(|&x| seen[x])
            .flat_map(|x| {
                t.moves(x)
                    .iter()
                    .filter(|m| seen[m.to as usize])
                    .map(move |m| (x, m.to as usize, i64::from(m.cost)))
            })
            .collect();
        assert_eq!(goal_avoiding_arcs(&t), (seen, arcs), "{t:?}");
    }
}

#[test]
fn simple_goal_paths_are_every_walk_of_distinct_states_to_the_goal() {
    let mut draw = SplitMix(31);
    for _ in 0..1000 {
        let t = random_tiny(&mut draw, 5);
        let n = t.states();
        // Walks as state sequences from 0, extended one move at a time.
        let mut expected = Vec::new();
        let mut walks: Vec<(Vec<usize>, i64)> = vec![(vec![0], 0)];
        while let Some((w, cost)) = walks.pop() {
            let x = *w.last().expect("non-empty");
            if t.is_goal(x) {
                expected.push((cost, w.len()));
                continue;
            }
            for m in t.moves(x) {
                let y = m.to as usize;
                if !w.contains(&y) {
                    let mut longer = w.clone();
                    longer.push(y);
                    walks.push((longer, cost + i64::from(m.cost)));
                }
            }
        }
        expected.sort();
        let mut paths = simple_goal_paths(&t);
        paths.sort();
        assert_eq!(paths, expected, "{t:?}");
        assert!(paths.iter().all(|&(_, s)| s <= n));
    }
}

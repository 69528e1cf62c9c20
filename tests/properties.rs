//! Property tests of the exact planners (docs/spec.md §1, §2) over random deterministic problems, on
//! both value representations (`ExactGraph::Units` and `ExactGraph::Big`), against oracles
//! written from scratch in `common` (Bellman–Ford and simple-path enumeration over
//! `BigRational`).

mod common;

use std::collections::HashSet;

use common::*;
use num_traits::Zero;
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use truecost::model::{Decision, ExactGraph, Graph, Problem, RenderValue};
use truecost::solvers::dijkstra;
use truecost::solvers::exploration::explore;
use truecost::solvers::policy_evaluation::evaluate_policy;
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::solvers::{follow_policy, Solution};
use truecost::value::{ExactValue, Extended};

type TestResult = Result<(), TestCaseError>;

/// Checks a policy returned by a planner against the oracle's `G*`:
/// goals terminate, `+∞` states have no decision, and following the policy from every state
/// with finite `G*` reaches a goal along moves whose stage costs sum to exactly `G*(x)`.
fn check_policy<V: ExactValue>(
    p: &Problem,
    g: &Graph<V>,
    policy: &[Option<Decision>],
    oracle: &[Ext],
    who: &str,
) -> TestResult {
    prop_assert_eq!(policy.len(), p.states(), "{}: policy length", who);
    for x in 0..p.states() {
        match &oracle[x] {
            None => prop_assert_eq!(policy[x], None, "{}: +inf state {} has a decision", who, x),
            Some(gx) => {
                if p.is_goal(x) {
                    prop_assert_eq!(policy[x], Some(Decision::Terminate), "{}: goal {}", who, x);
                }
                let path = follow_policy(g, policy, x);
                prop_assert!(
                    path.is_some(),
                    "{}: policy from {} does not reach a goal",
                    who,
                    x
                );
                let path = path.unwrap();
                prop_assert_eq!(path[0], x);
                prop_assert!(
                    p.is_goal(*path.last().unwrap()),
                    "{}: path ends off goal",
                    who
                );
                let mut total = Q::zero();
                for w in path.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    prop_assert!(!p.is_goal(a), "{}: path continues past goal {}", who, a);
                    let i = match policy[a] {
                        Some(Decision::Move(i)) => i,
                        other => {
                            return Err(TestCaseError::fail(format!("{who}: {other:?} at {a}")))
                        }
                    };
                    let m = &p.moves(a)[i];
                    prop_assert_eq!(m.successor, b, "{}: path does not follow the move", who);
                    total += &m.cost;
                }
                prop_assert_eq!(&total, gx, "{}: path cost from {} is not G*", who, x);
            }
        }
    }
    // At a state whose moves all cost > 0, the greedy choice is the first minimiser in the
    // state's action order (docs/spec.md §7 / `greedy_policy` documentation).
    for x in 0..p.states() {
        if p.is_goal(x) || oracle[x].is_none() || p.moves(x).iter().any(|m| m.cost.is_zero()) {
            continue;
        }
        let first = p
            .moves(x)
            .iter()
            .position(|m| add(&m.cost, &oracle[m.successor]) == oracle[x]);
        prop_assert_eq!(
            policy[x],
            first.map(Decision::Move),
            "{}: not first minimiser at {}",
            who,
            x
        );
    }
    // Exact policy evaluation of the returned policy gives G* everywhere.
    let evaluated = exact_all(g, &evaluate_policy(g, policy));
    prop_assert_eq!(&evaluated, oracle, "{}: evaluate_policy != G*", who);
    Ok(())
}

/// All planners on one graph (node `v` = state `v` of `p`) against the oracles.
fn check_planners<V: ExactValue>(p: &Problem, g: &Graph<V>) -> TestResult {
    let n = p.states();
    let oracle = bellman_ford(p);
    if n <= 7 {
        // The two oracles must agree (guards the oracle itself).
        prop_assert_eq!(&simple_paths(p), &oracle.cost_to_go, "oracles disagree");
    }
    let dij = dijkstra::to_goals(g);
    let sync = value_iteration(g, Schedule::Synchronous, None);
    let asyn = value_iteration(g, Schedule::Asynchronous, None);

    // Exactly equal values in the representation itself.
    prop_assert_eq!(&dij.cost_to_go, &sync.cost_to_go, "dijkstra vs sync VI");
    prop_assert_eq!(&dij.cost_to_go, &asyn.cost_to_go, "dijkstra vs async VI");

    // Equal to the oracle.
    let gstar = exact_all(g, &dij.cost_to_go);
    prop_assert_eq!(&gstar, &oracle.cost_to_go, "G* != oracle");

    // Bellman equation, checked exactly with the oracle's arithmetic.
    for x in 0..n {
        prop_assert_eq!(
            &gstar[x],
            &bellman_rhs(p, &gstar, x),
            "Bellman fails at {}",
            x
        );
    }

    for (who, s) in [("dijkstra", &dij), ("sync", &sync), ("async", &asyn)] {
        check_policy(p, g, &s.policy, &oracle.cost_to_go, who)?;
    }

    // Counts. Synchronous VI performs exactly the Jacobi sweeps of the oracle (the last one
    // confirms); Gauss–Seidel values are never above Jacobi values after the same number of
    // sweeps, so it needs no more sweeps. A sweep backs up every move once.
    let m = move_count(p) as u64;
    prop_assert_eq!(sync.iterations, oracle.jacobi_sweeps, "sync sweeps");
    prop_assert!(
        asyn.iterations >= 1 && asyn.iterations <= sync.iterations,
        "async sweeps"
    );
    prop_assert_eq!(sync.actions, sync.iterations * m);
    prop_assert_eq!(asyn.actions, asyn.iterations * m);
    // Backward Dijkstra settles exactly the states with finite G* and examines every move into
    // each of them once; every push is a goal or an improving relaxation.
    let indeg = in_degrees(p);
    let relax: u64 = (0..n)
        .filter(|&x| oracle.cost_to_go[x].is_some())
        .map(|x| indeg[x] as u64)
        .sum();
    let finite = oracle.cost_to_go.iter().filter(|v| v.is_some()).count() as u64;
    prop_assert_eq!(dij.actions, relax, "dijkstra relaxations");
    prop_assert!(dij.iterations >= finite, "dijkstra pops < settled");
    prop_assert!(
        dij.iterations <= p.goals().len() as u64 + relax,
        "dijkstra pops too many"
    );

    // Forward Dijkstra from x1: G*(x1) and a path from x1 to a goal of that cost.
    let fwd = dijkstra::from_initial(g);
    let x1 = p.initial();
    prop_assert_eq!(&exact(g, &fwd.cost), &oracle.cost_to_go[x1], "forward cost");
    match &oracle.cost_to_go[x1] {
        None => prop_assert!(fwd.path.is_empty()),
        Some(c) => {
            prop_assert_eq!(fwd.path.first(), Some(&x1));
            prop_assert!(p.is_goal(*fwd.path.last().unwrap()));
            let mut total = Q::zero();
            for w in fwd.path.windows(2) {
                let cheapest = p
                    .moves(w[0])
                    .iter()
                    .filter(|m| m.successor == w[1])
                    .map(|m| &m.cost)
                    .min();
                prop_assert!(cheapest.is_some(), "forward path uses a missing move");
                total += cheapest.unwrap();
            }
            prop_assert_eq!(&total, c, "forward path cost");
        }
    }
    Ok(())
}

/// Model-free exploration: it discovers exactly the reachable part, every move out of it, and
/// the planners on the discovered graph agree with the full graph.
fn check_exploration<V: ExactValue>(p: &Problem, g: &Graph<V>) -> TestResult {
    let n = p.states();
    let reach = reachable(p);
    let e = explore(g);
    let d = &e.graph;
    prop_assert_eq!(e.index.len(), n);
    prop_assert_eq!(
        d.nodes(),
        reach.iter().filter(|&&r| r).count(),
        "discovered node count"
    );
    prop_assert_eq!(e.index[p.initial()], Some(0));
    prop_assert_eq!(d.initial(), 0);
    let mut origins = HashSet::new();
    for (v, &r) in reach.iter().enumerate() {
        prop_assert_eq!(e.index[v].is_some(), r, "index of {} vs reachability", v);
        if let Some(i) = e.index[v] {
            prop_assert_eq!(d.origin(i), v, "origin(index(v)) != v");
        }
    }
    for i in 0..d.nodes() {
        let v = d.origin(i);
        prop_assert!(reach[v], "discovered node {} is unreachable", v);
        prop_assert!(origins.insert(v), "state {} discovered twice", v);
        prop_assert_eq!(d.is_goal(i), p.is_goal(v), "goal flag of {}", v);
    }
    // The discovered moves, as a multiset of (from, to, cost) in problem numbering, are exactly
    // the moves out of reachable states.
    let mut want: Vec<(usize, usize, Q)> = (0..n)
        .filter(|&x| reach[x])
        .flat_map(|x| {
            p.moves(x)
                .iter()
                .map(move |m| (x, m.successor, m.cost.clone()))
        })
        .collect();
    let mut got: Vec<(usize, usize, Q)> = Vec::new();
    for i in 0..d.nodes() {
        for (j, c) in d.edges(i) {
            let c = exact(d, c);
            prop_assert!(c.is_some(), "infinite stage cost discovered");
            got.push((d.origin(i), d.origin(j), c.unwrap()));
        }
    }
    want.sort();
    got.sort();
    prop_assert_eq!(&got, &want, "discovered moves");

    // Action count. Every reachable state is stood on and left only after a scan that inspects
    // all its moves, so actions >= Σ degree over reachable states (>= discovered moves / 2).
    // Each scan ends in a step forward (F of them, each trying a new move, F <= moves) or a
    // step back (F + 1 of them), and inspects at most Δ moves: actions <= (2F + 1) Δ.
    let sum_deg: u64 = want.len() as u64;
    let max_deg = (0..n)
        .filter(|&x| reach[x])
        .map(|x| p.moves(x).len())
        .max()
        .unwrap_or(0) as u64;
    prop_assert!(
        e.actions >= sum_deg,
        "actions {} < Σ degree {}",
        e.actions,
        sum_deg
    );
    prop_assert!(
        e.actions <= (2 * sum_deg + 1) * max_deg,
        "actions {} too many",
        e.actions
    );

    // Planners on the discovered graph: the reachable set is closed under moves, so G* of every
    // discovered node equals G* of its state in the full problem.
    let oracle = bellman_ford(p).cost_to_go;
    for s in [
        dijkstra::to_goals(d),
        value_iteration(d, Schedule::Synchronous, None),
        value_iteration(d, Schedule::Asynchronous, None),
    ] {
        for i in 0..d.nodes() {
            prop_assert_eq!(
                &exact(d, &s.cost_to_go[i]),
                &oracle[d.origin(i)],
                "discovered G*"
            );
        }
        prop_assert_eq!(
            &exact(d, &s.cost_to_go[0]),
            &oracle[p.initial()],
            "G*(x1) discovered"
        );
        // The policy on the discovered graph reaches a goal from x1 when G*(x1) is finite.
        if let Some(c) = &oracle[p.initial()] {
            let path = follow_policy(d, &s.policy, 0);
            prop_assert!(path.is_some(), "discovered policy does not reach a goal");
            let path = path.unwrap();
            let mut total = Q::zero();
            for w in path.windows(2) {
                let i = match s.policy[w[0]] {
                    Some(Decision::Move(i)) => i,
                    _ => return Err(TestCaseError::fail("path without a move")),
                };
                let (to, cost) = d.edges(w[0]).nth(i).unwrap();
                prop_assert_eq!(to, w[1]);
                total += exact(d, cost).unwrap();
            }
            prop_assert_eq!(&total, c, "discovered policy cost");
        }
    }
    Ok(())
}

/// Runs a solver on a graph and returns its exact values.
fn exact_solution<V: ExactValue>(g: &Graph<V>, s: &Solution<V>) -> Vec<Ext> {
    exact_all(g, &s.cost_to_go)
}

/// The problem compiled as big rationals directly (the `Big` value type on any problem).
fn big_graph(p: &Problem) -> Graph<Extended> {
    let adjacency = (0..p.states())
        .map(|x| {
            p.moves(x)
                .iter()
                .map(|m| (m.successor, Extended::Finite(m.cost.clone())))
                .collect()
        })
        .collect();
    Graph::from_adjacency(
        adjacency,
        p.initial(),
        p.goals(),
        (0..p.states()).collect(),
        int(1),
    )
}

/// All three planners' exact values on a graph.
fn all_planners<V: ExactValue>(g: &Graph<V>) -> [Vec<Ext>; 3] {
    [
        exact_solution(g, &dijkstra::to_goals(g)),
        exact_solution(g, &value_iteration(g, Schedule::Synchronous, None)),
        exact_solution(g, &value_iteration(g, Schedule::Asynchronous, None)),
    ]
}

// Default proptest configuration: 256 cases (override with PROPTEST_CASES).
proptest! {
    /// Small costs: `Units` is chosen (every scaled cost is at most 7·6 = 42, far from the
    /// bound) and all planners agree with the oracles.
    #[test]
    fn planners_exact_on_units(p in small_problem()) {
        let eg = ExactGraph::new(&p);
        prop_assert_eq!(eg.representation(), "units");
        with_exact_graph!(&eg, g => check_planners(&p, g))?;
    }

    /// Huge costs: `Big` is chosen and all planners agree with the oracles.
    #[test]
    fn planners_exact_on_big(p in huge_problem()) {
        let eg = ExactGraph::new(&p);
        prop_assert_eq!(eg.representation(), "big-rational");
        with_exact_graph!(&eg, g => check_planners(&p, g))?;
    }

    /// Costs right below the `Units` bound: `Units` is chosen, no addition overflows (it would
    /// panic), and all planners agree with the oracles.
    #[test]
    fn planners_exact_at_units_boundary(p in boundary_problem()) {
        let eg = ExactGraph::new(&p);
        prop_assert_eq!(eg.representation(), "units");
        with_exact_graph!(&eg, g => check_planners(&p, g))?;
    }

    /// The same problem as `Units` and as big rationals gives identical exact values; scaling
    /// every cost by 2^64 (forcing `Big`) scales every G* by 2^64.
    #[test]
    fn units_and_big_agree(p in small_problem()) {
        let eg = ExactGraph::new(&p);
        let units = match &eg {
            ExactGraph::Units(g) => all_planners(g),
            ExactGraph::Big(_) => return Err(TestCaseError::fail("small costs must use Units")),
        };
        let big = all_planners(&big_graph(&p));
        prop_assert_eq!(&units, &big);
        check_planners(&p, &big_graph(&p))?;

        let k = pow2(64);
        let ps = scaled(&p, &k);
        let egs = ExactGraph::new(&ps);
        let has_positive_cost = max_cost(&p) > Q::zero();
        prop_assert_eq!(egs.representation(), if has_positive_cost { "big-rational" } else { "units" });
        let scaled_values = with_exact_graph!(&egs, g => all_planners(g));
        for (a, b) in units.iter().zip(&scaled_values) {
            let expect: Vec<Ext> = a.iter().map(|v| v.as_ref().map(|v| v * &k)).collect();
            prop_assert_eq!(&expect, b);
        }
    }

    #[test]
    fn exploration_units(p in small_problem()) {
        with_exact_graph!(&ExactGraph::new(&p), g => check_exploration(&p, g))?;
    }

    #[test]
    fn exploration_big(p in huge_problem()) {
        with_exact_graph!(&ExactGraph::new(&p), g => check_exploration(&p, g))?;
    }

    /// `evaluate_policy` of an arbitrary policy equals an independent walk: follow the policy,
    /// +∞ on an undefined decision, a terminate off a goal, a bad index, or a revisit.
    #[test]
    fn evaluate_arbitrary_policy(p in small_problem(), picks in prop::collection::vec(0usize..6, 12)) {
        let policy: Vec<Option<Decision>> = (0..p.states())
            .map(|x| match picks[x] {
                0 => None,
                1 => Some(Decision::Terminate),
                k => Some(Decision::Move(k - 2)), // may be out of range
            })
            .collect();
        let expect: Vec<Ext> = (0..p.states())
            .map(|start| {
                let mut seen = vec![false; p.states()];
                let mut x = start;
                let mut total = Q::zero();
                loop {
                    if seen[x] {
                        return None;
                    }
                    seen[x] = true;
                    match policy[x] {
                        Some(Decision::Terminate) if p.is_goal(x) => return Some(total),
                        Some(Decision::Move(i)) if i < p.moves(x).len() => {
                            total += &p.moves(x)[i].cost;
                            x = p.moves(x)[i].successor;
                        }
                        _ => return None,
                    }
                }
            })
            .collect();
        let got = with_exact_graph!(&ExactGraph::new(&p), g => exact_all(g, &evaluate_policy(g, &policy)));
        prop_assert_eq!(got, expect);
    }
}

/// A hand-solved problem: 0 -(1/2)-> 1 -(5/3)-> 3 (goal), 0 -(7)-> 3, 1 -(0)-> 2 (dead end),
/// 4 -(1)-> 4 (a trap that cannot reach the goal).
fn hand_problem() -> Problem {
    Problem::new(
        vec![
            vec![mv(1, frac(1, 2)), mv(3, int(7))],
            vec![mv(2, int(0)), mv(3, frac(5, 3))],
            vec![],
            vec![],
            vec![mv(4, int(1))],
        ],
        0,
        vec![3],
    )
    .unwrap()
}

#[test]
fn hand_solved_problem() {
    let p = hand_problem();
    let want = vec![
        Some(frac(13, 6)),
        Some(frac(5, 3)),
        None,
        Some(int(0)),
        None,
    ];
    let want_policy = vec![
        Some(Decision::Move(0)),
        Some(Decision::Move(1)),
        None,
        Some(Decision::Terminate),
        None,
    ];
    let eg = ExactGraph::new(&p);
    assert_eq!(eg.representation(), "units");
    with_exact_graph!(&eg, g => {
        assert_eq!(g.unit(), &frac(1, 6));
        for s in [
            dijkstra::to_goals(g),
            value_iteration(g, Schedule::Synchronous, None),
            value_iteration(g, Schedule::Asynchronous, None),
        ] {
            assert_eq!(exact_all(g, &s.cost_to_go), want);
            assert_eq!(s.policy, want_policy);
            assert_eq!(g.render(&s.cost_to_go[0]), "13/6");
            assert_eq!(g.render(&s.cost_to_go[2]), "inf");
        }
        // Sync VI: sweep 1 sets G(1) = 5/3, G(0) = 7; sweep 2 sets G(0) = 13/6; sweep 3 confirms.
        let s = value_iteration(g, Schedule::Synchronous, None);
        assert_eq!((s.iterations, s.actions), (3, 3 * 5));
        assert_eq!(follow_policy(g, &s.policy, 0), Some(vec![0, 1, 3]));
        assert_eq!(follow_policy(g, &s.policy, 2), None);
    });
    let big = big_graph(&p);
    assert_eq!(exact_all(&big, &dijkstra::to_goals(&big).cost_to_go), want);
}

/// The zero-cost cycle 0 -(0)-> 1 -(0)-> 0 with the exit 1 -(0)-> 2 (goal) listed second.
fn zero_cycle() -> Problem {
    Problem::new(
        vec![
            vec![mv(1, int(0))],
            vec![mv(0, int(0)), mv(2, int(0))],
            vec![],
        ],
        0,
        vec![2],
    )
    .unwrap()
}

#[test]
fn follow_policy_refuses_to_circle_on_zero_cost_cycle() {
    let p = zero_cycle();
    with_exact_graph!(&ExactGraph::new(&p), g => {
        // Every move is a minimiser (all G* = 0), yet a policy taking 1 -> 0 circles forever.
        let circle = [Some(Decision::Move(0)), Some(Decision::Move(0)), Some(Decision::Terminate)];
        assert_eq!(follow_policy(g, &circle, 0), None);
        assert_eq!(follow_policy(g, &circle, 1), None);
        assert_eq!(follow_policy(g, &circle, 2), Some(vec![2]));
        assert_eq!(
            exact_all(g, &evaluate_policy(g, &circle)),
            vec![None, None, Some(int(0))]
        );
        // Undefined and out-of-range decisions.
        assert_eq!(follow_policy(g, &[None, None, Some(Decision::Terminate)], 0), None);
        let bad = [Some(Decision::Move(5)), Some(Decision::Move(1)), Some(Decision::Terminate)];
        assert_eq!(follow_policy(g, &bad, 0), None);
        assert_eq!(follow_policy(g, &bad, 1), Some(vec![1, 2]));
        // The planners' policies take the exit instead of the first (circling) minimiser.
        for s in [
            dijkstra::to_goals(g),
            value_iteration(g, Schedule::Synchronous, None),
            value_iteration(g, Schedule::Asynchronous, None),
        ] {
            assert_eq!(exact_all(g, &s.cost_to_go), vec![Some(int(0)); 3]);
            assert_eq!(
                s.policy,
                vec![Some(Decision::Move(0)), Some(Decision::Move(1)), Some(Decision::Terminate)]
            );
            assert_eq!(follow_policy(g, &s.policy, 0), Some(vec![0, 1, 2]));
        }
    });
}

/// Hand-counted exploration walks.
#[test]
fn exploration_counts_by_hand() {
    // 0 <-> 1 <-> 2 (goal), 3 unreachable. At 0: take 0->1 (1). At 1: 1->0 tried with its
    // partner (2), take 1->2 (3). At 2: 2->1 tried (4), back. At 1: two tried (6), back.
    // At 0: one tried (7), back. Total 7.
    let p = Problem::new(
        vec![
            vec![mv(1, int(1))],
            vec![mv(0, int(1)), mv(2, int(1))],
            vec![mv(1, int(1))],
            vec![],
        ],
        0,
        vec![2],
    )
    .unwrap();
    with_exact_graph!(&ExactGraph::new(&p), g => {
        let e = explore(g);
        assert_eq!(e.actions, 7);
        assert_eq!(e.index, vec![Some(0), Some(1), Some(2), None]);
        assert_eq!(e.graph.origins(), &[0, 1, 2]);
        assert_eq!(e.graph.goals(), vec![2]);
    });

    // Directed: 0 -> 1, 0 -> 2, 1 -> 2, goal 2 without moves. At 0: take 0->1 (1). At 1: take
    // 1->2 (2). At 2: nothing, back. At 1: 1->2 tried (3), back. At 0: 0->1 tried (4), take
    // 0->2 (5). At 2: back. At 0: both tried (7), back. Total 7.
    let p = Problem::new(
        vec![
            vec![mv(1, int(1)), mv(2, int(5))],
            vec![mv(2, int(1))],
            vec![],
        ],
        0,
        vec![2],
    )
    .unwrap();
    with_exact_graph!(&ExactGraph::new(&p), g => {
        let e = explore(g);
        assert_eq!(e.actions, 7);
        assert_eq!(e.graph.origins(), &[0, 1, 2]);
        let edges0: Vec<usize> = e.graph.edges(0).map(|(y, _)| y).collect();
        assert_eq!(edges0, vec![1, 2]);
        let s = dijkstra::to_goals(&e.graph);
        assert_eq!(exact(&e.graph, &s.cost_to_go[0]), Some(int(2)));
    });
}

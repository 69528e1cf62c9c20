//! Pins Dijkstra's documented pop order and work counts (`kernel/src/solvers/dijkstra.rs`): the
//! frontier pops the smallest (distance, insertion counter), a stale pop counts as a pop, every
//! neighbour examined from a settled node counts as a relaxation, and the two frontiers
//! (`Keyed` for `Units`/`f64`, `Compared` for a value type without an order key) give the same
//! answer. Also pins `to_goals`' policy on zero-cost moves and on `f64` sums that absorb a cost.
//!
//! Why: these are published numbers (pops and relaxations of the paper's Problem 10), and the
//! mutation run of 1 Dec 2026 found the heap order (`Entry`, `Compared`, `Keyed::push`), the
//! counters (`+= → *=`) and the policy choice of `to_goals` untested by the kernel's own tests.
//! The expected values are computed by hand (small graphs) or by a linear-scan reference
//! Dijkstra and Bellman–Ford written here from the module's documentation.

mod support;

use truecost_kernel::model::{Decision, Graph};
use truecost_kernel::solvers::dijkstra::{self, DijkstraCounts};
use truecost_kernel::value::{CostValue, Units};

use support::{finite, NoKey, Plain, SplitMix};

/// What the reference search returns.
#[derive(Debug, PartialEq)]
struct Reference {
    dist: Vec<Option<u64>>,
    parent: Vec<Option<usize>>,
    target: Option<usize>,
    pops: u64,
    relaxations: u64,
}

/// Dijkstra as documented, over a frontier that is a plain list scanned for the smallest
/// (distance, insertion counter).
fn reference(
    n: usize,
    sources: &[usize],
    neighbours: impl Fn(usize) -> Vec<(usize, u64)>,
    is_target: impl Fn(usize) -> bool,
) -> Reference {
    let mut dist: Vec<Option<u64>> = vec![None; n];
    let mut parent = vec![None; n];
    let mut settled = vec![false; n];
    let mut frontier: Vec<(u64, u64, usize)> = Vec::new();
    let mut counter = 0;
    let (mut pops, mut relaxations) = (0, 0);
    for &s in sources {
        dist[s] = Some(0);
        frontier.push((0, counter, s));
        counter += 1;
    }
    while !frontier.is_empty() {
        let smallest = (0..frontier.len())
            .min_by_key(|&i| (frontier[i].0, frontier[i].1))
            .expect("non-empty");
        let (d, _, v) = frontier.remove(smallest);
        pops += 1;
        if settled[v] {
            continue;
        }
        settled[v] = true;
        if is_target(v) {
            return Reference {
                dist,
                parent,
                target: Some(v),
                pops,
                relaxations,
            };
        }
        for (w, c) in neighbours(v) {
            relaxations += 1;
            if settled[w] {
                continue;
            }
            if dist[w].is_none_or(|dw| d + c < dw) {
                dist[w] = Some(d + c);
                parent[w] = Some(v);
                frontier.push((d + c, counter, w));
                counter += 1;
            }
        }
    }
    Reference {
        dist,
        parent,
        target: None,
        pops,
        relaxations,
    }
}

/// The reference run backwards from the goals (over reversed moves, sources in forward order).
fn reference_to_goals(p: &Plain) -> Reference {
    let mut incoming = vec![Vec::new(); p.nodes()];
    for (x, list) in p.adjacency.iter().enumerate() {
        for &(y, c) in list {
            incoming[y].push((x, c));
        }
    }
    reference(p.nodes(), &p.goals, |v| incoming[v].clone(), |_| false)
}

/// The reference run forwards from the initial node, stopping at the first goal popped.
fn reference_from_initial(p: &Plain) -> Reference {
    reference(
        p.nodes(),
        &[p.initial],
        |v| p.adjacency[v].clone(),
        |v| p.is_goal(v),
    )
}

/// The path from the source to `target` along the reference's parents.
fn reference_path(r: &Reference) -> Vec<usize> {
    let Some(mut v) = r.target else {
        return Vec::new();
    };
    let mut path = vec![v];
    while let Some(u) = r.parent[v] {
        path.push(u);
        v = u;
    }
    path.reverse();
    path
}

/// Checks `to_goals` and `from_initial` of one value type against the reference.
fn agrees_with_reference<V: CostValue>(p: &Plain, g: &Graph<V>, raw: impl Fn(&V) -> u64 + Copy) {
    let back = dijkstra::to_goals(g);
    let expected = reference_to_goals(p);
    assert_eq!(finite(&back.cost_to_go, raw), expected.dist, "{p:?}");
    assert_eq!(finite(&back.cost_to_go, raw), p.optimal_costs(), "{p:?}");
    assert_eq!(
        (back.iterations, back.actions),
        (expected.pops, expected.relaxations),
        "to_goals counts, {p:?}"
    );
    let forward = dijkstra::from_initial(g);
    let expected = reference_from_initial(p);
    assert_eq!(
        forward.counts,
        DijkstraCounts {
            pops: expected.pops,
            relaxations: expected.relaxations
        },
        "from_initial counts, {p:?}"
    );
    assert_eq!(forward.path, reference_path(&expected), "{p:?}");
    match expected.target {
        Some(goal) => {
            assert_eq!(Some(raw(&forward.cost)), expected.dist[goal], "{p:?}");
            assert_eq!(Some(raw(&forward.cost)), p.optimal_costs()[p.initial]);
            assert_eq!(raw(&forward.cost), p.walk_cost(&forward.path));
        }
        None => {
            assert!(!forward.cost.is_finite(), "{p:?}");
            assert_eq!(p.optimal_costs()[p.initial], None);
        }
    }
}

#[test]
fn pops_follow_distance_then_insertion_order_on_random_graphs() {
    let mut draw = SplitMix(0x5EED_D1A5);
    for _ in 0..1500 {
        // Costs 0..=2: zero-cost moves and equal distances everywhere.
        let p = Plain::random(&mut draw, 9, 0, 2);
        agrees_with_reference(&p, &p.units(), |v| v.0);
        agrees_with_reference(&p, &p.floats(), |v| *v as u64);
        agrees_with_reference(&p, &p.no_key(), |v| v.0);
    }
}

/// 0→1 (1), 0→2 (4), 1→2 (1), 2→3 (1), 1→3 (5); goal 3. Backwards: pop 3 (relax 1 at 5, 2 at
/// 1), pop 2 (relax 0 at 5, 1 at 2), pop 1 (relax 0 at 3), pop 0, then the stale entries of 1
/// (at 5) and 0 (at 5): 6 pops, 5 relaxations.
fn diamond<V: CostValue>(value: impl Fn(u64) -> V) -> Graph<V> {
    Plain {
        adjacency: vec![
            vec![(1, 1), (2, 4)],
            vec![(2, 1), (3, 5)],
            vec![(3, 1)],
            vec![],
        ],
        initial: 0,
        goals: vec![3],
    }
    .graph(value)
}

fn stale_pops_are_counted<V: CostValue>(value: impl Fn(u64) -> V + Copy) {
    let s = dijkstra::to_goals(&diamond(value));
    let expected: Vec<V> = [3, 2, 1, 0].into_iter().map(value).collect();
    assert_eq!(s.cost_to_go, expected);
    assert_eq!((s.iterations, s.actions), (6, 5));
    assert_eq!(
        s.policy,
        vec![
            Some(Decision::Move(0)),
            Some(Decision::Move(0)),
            Some(Decision::Move(0)),
            Some(Decision::Terminate)
        ]
    );
    // Forwards from 0: pop 0 (relax 1 at 1, 2 at 4), pop 1 (relax 2 at 2, 3 at 6), pop 2
    // (relax 3 at 3), pop 3: a goal, stop. 4 pops, 5 relaxations.
    let f = dijkstra::from_initial(&diamond(value));
    assert_eq!((f.cost, f.path), (value(3), vec![0, 1, 2, 3]));
    assert_eq!(
        f.counts,
        DijkstraCounts {
            pops: 4,
            relaxations: 5
        }
    );
}

#[test]
fn stale_pops_and_examined_neighbours_are_counted() {
    stale_pops_are_counted(Units);
    stale_pops_are_counted(|c| c as f64);
    stale_pops_are_counted(NoKey);
}

/// Goals 2 and 5 (pushed in that order), 1→2 (0), 0→1 (3), 0→5 (1); nodes 3, 4 isolated.
/// Backwards: pop 2, relax 1 at 0 (pushed after 5). Pop 5 (its entry is older than 1's, though
/// 1 < 5), relax 0 at 1; pop 1, relax 0 at 3 (no improvement); pop 0: 4 pops, 3 relaxations.
/// Popping 1 before 5 would push 0 twice: 5 pops.
fn two_goals<V: CostValue>(value: impl Fn(u64) -> V) -> Graph<V> {
    Plain {
        adjacency: vec![
            vec![(1, 3), (5, 1)],
            vec![(2, 0)],
            vec![],
            vec![],
            vec![],
            vec![],
        ],
        initial: 0,
        goals: vec![2, 5],
    }
    .graph(value)
}

/// From 0: 0→3 (1) then 0→1 (1), goals 1 and 3: both at distance 1, 3 was pushed first, so the
/// search stops at 3 after 2 pops and 2 relaxations.
fn tied_goals<V: CostValue>(value: impl Fn(u64) -> V) -> Graph<V> {
    Plain {
        adjacency: vec![vec![(3, 1), (1, 1)], vec![], vec![], vec![]],
        initial: 0,
        goals: vec![1, 3],
    }
    .graph(value)
}

fn ties_pop_in_insertion_order<V: CostValue>(value: impl Fn(u64) -> V + Copy) {
    let s = dijkstra::to_goals(&two_goals(value));
    let inf = V::infinity();
    assert_eq!(
        s.cost_to_go,
        vec![value(1), value(0), value(0), inf.clone(), inf, value(0)]
    );
    assert_eq!((s.iterations, s.actions), (4, 3));
    let f = dijkstra::from_initial(&tied_goals(value));
    assert_eq!((f.cost, f.path), (value(1), vec![0, 3]));
    assert_eq!(
        f.counts,
        DijkstraCounts {
            pops: 2,
            relaxations: 2
        }
    );
}

#[test]
fn equal_distances_pop_in_insertion_order_not_node_order() {
    ties_pop_in_insertion_order(Units);
    ties_pop_in_insertion_order(|c| c as f64);
    ties_pop_in_insertion_order(NoKey);
}

#[test]
fn unreachable_goals_give_infinity_and_an_empty_path() {
    // 0→1 (2), 1→0 (2); goal 2 has no moves into it. Backwards: pop 2 only. Forwards: pop 0
    // (relax 1), pop 1 (relax 0, settled), frontier empty.
    let p = Plain {
        adjacency: vec![vec![(1, 2)], vec![(0, 2)], vec![]],
        initial: 0,
        goals: vec![2],
    };
    let s = dijkstra::to_goals(&p.no_key());
    assert_eq!(
        s.cost_to_go,
        vec![NoKey::infinity(), NoKey::infinity(), NoKey(0)]
    );
    assert_eq!(s.policy, vec![None, None, Some(Decision::Terminate)]);
    assert_eq!((s.iterations, s.actions), (1, 0));
    let f = dijkstra::from_initial(&p.units());
    assert_eq!((f.cost, f.path), (Units::infinity(), vec![]));
    assert_eq!(
        f.counts,
        DijkstraCounts {
            pops: 2,
            relaxations: 2
        }
    );
}

/// 0→1 (0), 1→0 (0), 1→2 (0), goal 2: every node has `G* = 0`, and at 1 the first move whose
/// cost is tight (back to 0) makes no progress; the policy must take 1→2.
fn zero_cycle<V: CostValue>(value: impl Fn(u64) -> V) -> Graph<V> {
    Plain {
        adjacency: vec![vec![(1, 0)], vec![(0, 0), (2, 0)], vec![]],
        initial: 0,
        goals: vec![2],
    }
    .graph(value)
}

#[test]
fn to_goals_policy_makes_progress_on_zero_cost_cycles() {
    let expected = vec![
        Some(Decision::Move(0)),
        Some(Decision::Move(1)),
        Some(Decision::Terminate),
    ];
    assert_eq!(dijkstra::to_goals(&zero_cycle(Units)).policy, expected);
    assert_eq!(dijkstra::to_goals(&zero_cycle(NoKey)).policy, expected);
    assert_eq!(
        dijkstra::to_goals(&zero_cycle(|c| c as f64)).policy,
        expected
    );
}

#[test]
fn to_goals_policy_makes_progress_when_f64_absorbs_a_cost() {
    // 0: [→1 (1), →2 (1)], 1: [→0 (1), →2 (1)], 2: [→3 (1e20)], goal 3. In f64,
    // 1 + 1e20 == 1e20, so G*(0) = G*(1) = G*(2) = 1e20 and the moves 0→1 and 1→0 look tight
    // although they make no progress: the policy must go to 2 from both (h(2) = 1 < h = 2).
    let g = Graph::<f64>::from_adjacency(
        vec![
            vec![(1, 1.0), (2, 1.0)],
            vec![(0, 1.0), (2, 1.0)],
            vec![(3, 1e20)],
            vec![],
        ],
        0,
        &[3],
        vec![0, 1, 2, 3],
        (),
    );
    assert_eq!(1.0 + 1e20, 1e20);
    let s = dijkstra::to_goals(&g);
    assert_eq!(s.cost_to_go, vec![1e20, 1e20, 1e20, 0.0]);
    assert_eq!(
        s.policy,
        vec![
            Some(Decision::Move(1)),
            Some(Decision::Move(1)),
            Some(Decision::Move(0)),
            Some(Decision::Terminate)
        ]
    );
}

//! Pins the tiny problems and their symmetry-reduced families (`kernel/src/claims/tiny.rs`):
//! the accessors and descriptions of a `Tiny`, the number of labelled problems of a scope, and
//! that `Family::canonical` yields exactly one problem per class under relabelling of the free
//! states — the least one, state by state, `(degree, sorted moves)`.
//!
//! Why: the claims' small-scope results are only as complete as this enumeration, and the
//! kernel's own tests pinned it by one orbit count.
//! Expected values: by hand, and by a brute force written here that applies every permutation
//! of the free states to every labelled problem and keeps the least image.

use std::collections::BTreeSet;

use truecost_kernel::claims::tiny::{
    minimality_key, Family, FamilySpec, Tiny, TinyMove, MAX_DEGREE, MAX_STATES,
};

#[test]
fn a_tiny_problem_reports_its_moves_and_costs() {
    let t = Tiny::from_lists(&[vec![(1, 2), (0, 5)], vec![(2, 1)], vec![(0, 3)]]);
    assert_eq!((t.states(), t.goal()), (3, 2));
    assert_eq!(
        (0..3).map(|x| t.is_goal(x)).collect::<Vec<_>>(),
        [false, false, true]
    );
    assert_eq!(
        t.moves(0),
        &[TinyMove { to: 1, cost: 2 }, TinyMove { to: 0, cost: 5 }]
    );
    assert_eq!(t.moves(1).len(), 1);
    assert_eq!(t.move_count(), 4);
    assert_eq!(t.cost_sum(), 2 + 5 + 1 + 3);
    assert_eq!(
        t.describe(),
        "0: ->1 (2), ->0 (5); 1: ->2 (1); 2 (goal): ->0 (3)"
    );
    let lonely = Tiny::from_lists(&[vec![], vec![]]);
    assert_eq!(lonely.describe(), "0; 1 (goal)");
    assert_eq!((lonely.move_count(), lonely.cost_sum()), (0, 0));
    assert_eq!(minimality_key(&t, 9, 4), (3, 4, 11, 9, 4));
    let e = Tiny::empty(MAX_STATES);
    assert_eq!((e.states(), e.move_count()), (MAX_STATES, 0));
}

#[test]
fn a_scope_describes_itself() {
    let spec = FamilySpec {
        states: 4,
        initial_fixed: true,
        degree: (1, 2),
        goal_degree: (0, 0),
        costs: vec![0, 1],
        distinct_successors: true,
    };
    assert_eq!(
        spec.describe(),
        "4 states, 1-2 moves per non-goal state, 0 at the goal, costs {0,1}, distinct successors"
    );
    let spec = FamilySpec {
        degree: (2, 2),
        goal_degree: (1, 3),
        distinct_successors: false,
        ..spec
    };
    assert_eq!(
        spec.describe(),
        "4 states, 2 moves per non-goal state, 1-3 at the goal, costs {0,1}"
    );
    assert!(Family::new(&spec).initial_fixed());
    assert!(!Family::new(&FamilySpec {
        initial_fixed: false,
        ..spec
    })
    .initial_fixed());
}

/// The move lists a state may have: sorted multisets of `(to, cost)` of a size in `lo..=hi`
/// (successors distinct if asked), by brute force over all sequences.
fn move_lists(n: usize, costs: &[u8], (lo, hi): (usize, usize), distinct: bool) -> usize {
    let alphabet: Vec<TinyMove> = (0..n as u8)
        .flat_map(|to| costs.iter().map(move |&cost| TinyMove { to, cost }))
        .collect();
    let mut lists = BTreeSet::new();
    let mut frontier: Vec<Vec<TinyMove>> = vec![Vec::new()];
    for len in 0..=hi {
        let mut next = Vec::new();
        for list in &frontier {
            if len >= lo {
                let mut sorted = list.clone();
                sorted.sort();
                lists.insert(sorted);
            }
            for &m in &alphabet {
                if !(distinct && list.iter().any(|o| o.to == m.to)) {
                    let mut longer = list.clone();
                    longer.push(m);
                    next.push(longer);
                }
            }
        }
        frontier = next;
    }
    lists.len()
}

/// A problem as the comparison key of the canonical order: per state `(degree, sorted moves)`.
fn key(t: &Tiny) -> Vec<(usize, Vec<TinyMove>)> {
    (0..t.states())
        .map(|x| {
            let mut moves = t.moves(x).to_vec();
            moves.sort();
            (moves.len(), moves)
        })
        .collect()
}

/// `t` relabelled by `map` (old state → new state).
fn relabel(t: &Tiny, map: &[usize]) -> Tiny {
    let n = t.states();
    let mut lists = vec![Vec::new(); n];
    for x in 0..n {
        lists[map[x]] = t
            .moves(x)
            .iter()
            .map(|m| (map[m.to as usize] as u8, m.cost))
            .collect();
    }
    Tiny::from_lists(&lists)
}

/// Every permutation of `items`.
fn permutations(items: &[usize]) -> Vec<Vec<usize>> {
    if items.len() <= 1 {
        return vec![items.to_vec()];
    }
    let mut out = Vec::new();
    for i in 0..items.len() {
        let mut rest = items.to_vec();
        let head = rest.remove(i);
        for mut p in permutations(&rest) {
            p.insert(0, head);
            out.push(p);
        }
    }
    out
}

fn scopes() -> Vec<FamilySpec> {
    let mut out = Vec::new();
    for states in 1..=4 {
        for initial_fixed in [false, true] {
            for (degree, goal_degree, costs, distinct_successors) in [
                ((1, 1), (0, 0), vec![0], false),
                ((0, 2), (0, 1), vec![0], true),
                ((1, 2), (0, 0), vec![1, 2], false),
                ((1, 1), (1, 1), vec![0, 3], false),
            ] {
                if states == 4 && degree == (1, 2) {
                    continue; // 85,184 labelled problems: enough at 3 states
                }
                out.push(FamilySpec {
                    states,
                    initial_fixed,
                    degree,
                    goal_degree,
                    costs,
                    distinct_successors,
                });
            }
        }
    }
    out
}

#[test]
fn a_scope_counts_every_labelled_problem_once() {
    for spec in scopes() {
        let f = Family::new(&spec);
        let n = spec.states;
        let options = move_lists(n, &spec.costs, spec.degree, spec.distinct_successors);
        let goal = move_lists(n, &spec.costs, spec.goal_degree, spec.distinct_successors);
        let expected = goal as u64 * (options as u64).pow(n as u32 - 1);
        assert_eq!(f.labelled_count(), expected, "{spec:?}");
        let all: BTreeSet<_> = (0..f.labelled_count())
            .map(|i| {
                let t = f.problem(i);
                assert_eq!(t.states(), n);
                for x in 0..n {
                    let (lo, hi) = if x + 1 == n {
                        spec.goal_degree
                    } else {
                        spec.degree
                    };
                    assert!((lo..=hi).contains(&t.moves(x).len()), "{spec:?} {t:?}");
                    assert!(t.moves(x).len() <= MAX_DEGREE);
                    assert!(t.moves(x).windows(2).all(|w| w[0] <= w[1]));
                    assert!(t.moves(x).iter().all(|m| spec.costs.contains(&m.cost)));
                }
                key(&t)
            })
            .collect();
        assert_eq!(all.len() as u64, expected, "distinct problems, {spec:?}");
    }
}

#[test]
fn canonical_problems_are_the_least_of_their_classes() {
    for spec in scopes() {
        let f = Family::new(&spec);
        let n = spec.states;
        let first_free = usize::from(spec.initial_fixed);
        let free: Vec<usize> = (first_free..n.saturating_sub(1)).collect();
        let maps: Vec<Vec<usize>> = permutations(&free)
            .into_iter()
            .map(|image| {
                let mut map: Vec<usize> = (0..n).collect();
                for (k, &x) in free.iter().enumerate() {
                    map[x] = image[k];
                }
                map
            })
            .collect();
        let mut classes = BTreeSet::new();
        let mut expected = Vec::new();
        for i in 0..f.labelled_count() {
            let t = f.problem(i);
            let least = maps
                .iter()
                .map(|map| key(&relabel(&t, map)))
                .min()
                .expect("the identity at least");
            classes.insert(least.clone());
            if least == key(&t) {
                expected.push(key(&t));
            }
        }
        let canonical: Vec<_> = f.canonical().map(|t| key(&t)).collect();
        assert_eq!(canonical, expected, "{spec:?}");
        assert_eq!(canonical.len(), classes.len(), "one per class, {spec:?}");
        let expected: BTreeSet<_> = expected.into_iter().collect();
        for i in 0..f.labelled_count() {
            let t = f.problem(i);
            assert_eq!(f.is_canonical(&t), expected.contains(&key(&t)));
        }
    }
}

//! Pins the compiled planning graph (`kernel/src/model.rs`): the preconditions `from_csr`
//! checks (each malformed input panics with its own message, before any other code can trip
//! over it), and the accessors the planners and `truecost` read (`initial`, `edge_range`,
//! `origins`) on nodes other than 0.
//!
//! Why: the mutation run of 1 Dec 2026 (`--re '^kernel/src/[^/]+\.rs'`) left `check_rows`
//! (removed entirely, or its ordered-rows fold `&` → `|`), `initial` → 0, `edge_range`'s
//! `v + 1` and `origins` untested by the kernel's own tests. Expected values are written by hand
//! from the rows passed in.

use truecost_kernel::model::Graph;

/// 0 → 1 (cost 1), 0 → 2 (cost 2), 1 → 2 (cost 3), 2: no moves; initial 1, goal 2; origins
/// 10, 20, 30 (a sub-graph of some problem).
fn three() -> Graph<f64, u8> {
    Graph::from_csr(
        vec![0, 2, 3, 3],
        vec![1, 2, 2],
        vec![1.0, 2.0, 3.0],
        1,
        &[2],
        vec![10, 20, 30],
        7,
    )
}

#[test]
fn accessors_read_the_rows_of_the_node_asked_for() {
    let g = three();
    assert_eq!(g.initial(), 1);
    assert_eq!(g.nodes(), 3);
    assert_eq!(g.edge_count(), 3);
    assert_eq!(g.goals(), vec![2]);
    assert_eq!(
        (g.edge_range(0), g.edge_range(1), g.edge_range(2)),
        (0..2, 2..3, 3..3)
    );
    assert_eq!(g.edge(2), (2, &3.0));
    assert_eq!(g.degree(1), 1);
    assert_eq!(g.edges(1).collect::<Vec<_>>(), vec![(2, &3.0)]);
    assert_eq!(g.edge_slices(1), (&[2u32][..], &[3.0][..]));
    assert_eq!(g.origins(), &[10, 20, 30]);
    assert_eq!(g.origin(2), 30);
    assert_eq!(*g.unit(), 7);
    let (first, successor, cost) = g.compressed_rows();
    assert_eq!(
        (first, successor, cost),
        (&[0, 2, 3, 3][..], &[1, 2, 2][..], &[1.0, 2.0, 3.0][..])
    );
}

#[test]
fn adjacency_lists_build_the_same_rows() {
    let g = Graph::<f64, u8>::from_adjacency(
        vec![vec![(1, 1.0), (2, 2.0)], vec![(2, 3.0)], vec![]],
        1,
        &[2],
        vec![10, 20, 30],
        7,
    );
    let h = three();
    assert_eq!(g.compressed_rows(), h.compressed_rows());
    assert_eq!(g.initial(), 1);
    assert_eq!(g.origins(), h.origins());
    for v in 0..3 {
        assert_eq!(g.edge_range(v), h.edge_range(v));
    }
}

#[test]
#[should_panic(expected = "malformed compressed rows")]
fn rows_that_go_backwards_are_rejected() {
    // Node 1's row would be 2..1: `first` decreases, although it starts at 0 and ends at the
    // number of moves.
    let _ = Graph::<f64>::from_csr(
        vec![0, 2, 1, 2],
        vec![1, 0],
        vec![1.0, 1.0],
        0,
        &[],
        vec![0, 1, 2],
        (),
    );
}

#[test]
#[should_panic(expected = "malformed compressed rows")]
fn rows_that_do_not_end_at_the_move_count_are_rejected() {
    let _ = Graph::<f64>::from_csr(vec![0, 1], vec![0, 0], vec![1.0, 1.0], 0, &[], vec![0], ());
}

#[test]
#[should_panic(expected = "malformed compressed rows")]
fn costs_that_do_not_match_the_moves_are_rejected() {
    let _ = Graph::<f64>::from_csr(vec![0, 1], vec![0], vec![1.0, 2.0], 0, &[], vec![0], ());
}

#[test]
#[should_panic(expected = "successor out of range")]
fn a_successor_outside_the_graph_is_rejected() {
    let _ = Graph::<f64>::from_csr(vec![0, 1, 1], vec![2], vec![1.0], 0, &[], vec![0, 1], ());
}

#[test]
#[should_panic(expected = "initial < n")]
fn an_initial_node_outside_the_graph_is_rejected() {
    let _ = Graph::<f64>::from_csr(vec![0, 0, 0], vec![], vec![], 2, &[], vec![0, 1], ());
}

#[test]
#[should_panic(expected = "origin.len() == n")]
fn origins_must_name_every_node() {
    let _ = Graph::<f64>::from_csr(vec![0, 0, 0], vec![], vec![], 0, &[], vec![0], ());
}

#[test]
#[should_panic(expected = "first has one entry per node plus one")]
fn rows_need_at_least_the_leading_zero() {
    let _ = Graph::<f64>::from_csr(vec![], vec![], vec![], 0, &[], vec![], ());
}

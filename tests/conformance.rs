//! Conformance with the published numbers (`shared/reference/problem10.md`): problem facts in
//! exact mode, and the reference-mode counts of Problem 10. Expected values are copied from the
//! published table, never from truecost's output.

use truecost::model::ExactGraph;
use truecost::planning::{plan_exact, plan_reference, Algorithm};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::exploration::explore;
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::solvers::{dijkstra, follow_policy};
use truecost::value::{CostValue, Extended};

/// (problem, states, edges, x1, goal, optimal moves) — the published table for problems 0–5.
const FACTS: [(usize, usize, usize, usize, usize, u64); 6] = [
    (0, 400, 760, 181, 198, 17),
    (1, 299, 535, 182, 197, 27),
    (2, 294, 499, 343, 57, 29),
    (3, 135, 167, 38, 398, 90),
    (4, 299, 515, 21, 337, 31),
    (5, 290, 507, 42, 336, 30),
];

#[test]
fn facts_of_problems_0_to_5_match_the_published_table() {
    for (id, states, edges, initial, goal, moves) in FACTS {
        let f = GridLayout::exact(id).unwrap().facts();
        assert_eq!(
            (f.grid_nodes, f.states, f.edges, f.initial, f.goal, f.optimal_moves),
            (400, states, edges, initial, goal, Some(moves)),
            "problem {id}"
        );
    }
}

#[test]
fn problem_10_facts_and_exact_optimum() {
    let layout = GridLayout::exact(10).unwrap();
    let f = layout.facts();
    assert_eq!((f.states, f.edges, f.initial, f.goal), (339, 592, 41, 206));
    assert_eq!(f.optimal_moves, Some(63));
    let unit = plan_exact(&layout.to_problem(StepCost::Unit), Algorithm::Dijkstra, false);
    assert_eq!(unit.cost_to_go_initial, "63");
    assert_eq!(unit.path.len(), 64);
    let euclid = plan_exact(
        &layout.to_problem(StepCost::Euclidean),
        Algorithm::Dijkstra,
        false,
    );
    assert_eq!(euclid.cost_to_go_initial, "50400/19"); // 63 × 800/19
}

#[test]
fn problem_10_reference_counts() {
    let graph = GridLayout::reference(10).unwrap().to_reference_graph();
    let e = explore(&graph);
    assert_eq!(e.actions, 3266, "model-free exploration actions");
    assert_eq!(e.graph.nodes(), 339);
    assert_eq!(e.graph.edge_count(), 2 * 592);

    let d = dijkstra::from_initial(&e.graph);
    assert_eq!((d.counts.pops, d.counts.relaxations), (331, 1157));
    assert_eq!(d.path.len(), 64);

    let a = value_iteration(&e.graph, Schedule::Asynchronous, Some(1000));
    assert_eq!((a.iterations, a.actions), (56, 66304));
    let s = value_iteration(&e.graph, Schedule::Synchronous, Some(1000));
    assert_eq!((s.iterations, s.actions), (67, 79328));

    // The same through the planning layer, with the published totals.
    let total = |alg| plan_reference(&graph, alg, true).actions;
    assert_eq!(total(Algorithm::Dijkstra), 4423);
    assert_eq!(total(Algorithm::AsyncVi), 69570);
    assert_eq!(total(Algorithm::Vi), 82594);
}

#[test]
fn reference_optimum_is_the_exact_euclidean_optimum_up_to_rounding() {
    for id in 0..19 {
        let exact = plan_exact(
            &GridLayout::exact(id)
                .unwrap()
                .to_problem(StepCost::Euclidean),
            Algorithm::Dijkstra,
            false,
        );
        let reference = plan_reference(
            &GridLayout::reference(id).unwrap().to_reference_graph(),
            Algorithm::Dijkstra,
            true,
        );
        assert_eq!(exact.reachable, reference.reachable, "problem {id}");
        assert_eq!(exact.path.len(), reference.path.len(), "problem {id}");
        if exact.reachable {
            let e: Extended = exact.cost_to_go_initial.parse().unwrap();
            let r: f64 = reference.cost_to_go_initial.parse().unwrap();
            assert!((e.to_f64() - r).abs() < 1e-9 * r, "problem {id}: {e} vs {r}");
        }
    }
}

#[test]
fn every_problem_every_planner_agrees_exactly_on_every_state() {
    for id in 0..19 {
        for step in [StepCost::Unit, StepCost::Euclidean] {
            let problem = GridLayout::exact(id).unwrap().to_problem(step);
            let ExactGraph::Units(g) = ExactGraph::new(&problem) else {
                panic!("grid problems fit in u64 units");
            };
            let d = dijkstra::to_goals(&g);
            let s = value_iteration(&g, Schedule::Synchronous, None);
            let a = value_iteration(&g, Schedule::Asynchronous, None);
            assert_eq!(d.cost_to_go, s.cost_to_go, "problem {id}");
            assert_eq!(d.cost_to_go, a.cost_to_go, "problem {id}");
            // The policy reaches the goal from x1 in G* / step moves.
            let g1 = &d.cost_to_go[g.initial()];
            match follow_policy(&g, &d.policy, g.initial()) {
                Some(path) => {
                    let moves = (path.len() - 1) as u64;
                    let per_move = if step == StepCost::Unit { 1 } else { 800 };
                    assert_eq!(g1.0, moves * per_move, "problem {id}");
                }
                None => assert!(!g1.is_finite(), "problem {id}"),
            }
        }
    }
}

#[test]
fn problem_6_has_no_path_and_every_planner_says_so() {
    let problem = GridLayout::exact(6).unwrap().to_problem(StepCost::Unit);
    assert_eq!(GridLayout::exact(6).unwrap().facts().optimal_moves, None);
    for alg in [Algorithm::Dijkstra, Algorithm::Vi, Algorithm::AsyncVi] {
        for model_free in [false, true] {
            let r = plan_exact(&problem, alg, model_free);
            assert!(!r.reachable);
            assert_eq!(r.cost_to_go_initial, "inf");
            assert!(r.path.is_empty());
        }
        let r = plan_reference(
            &GridLayout::reference(6).unwrap().to_reference_graph(),
            alg,
            true,
        );
        assert!(!r.reachable);
        assert_eq!(r.cost_to_go_initial, "inf");
    }
}

#[test]
fn pruned_problems_keep_the_goal_and_lose_the_pocket() {
    // Problem 3's published component has 135 states; without pruning it is larger.
    for id in [3, 13, 14, 16] {
        let layout = GridLayout::exact(id).unwrap();
        let component = layout.component_of_initial();
        assert!(component[layout.goal], "problem {id}: goal kept");
        // Every state of the component other than the goal reaches x1 without the goal.
        let mut seen = vec![false; component.len()];
        let mut stack = vec![layout.initial];
        seen[layout.initial] = true;
        while let Some(v) = stack.pop() {
            if v == layout.goal {
                continue;
            }
            for &w in &layout.neighbours[v] {
                if !seen[w] {
                    seen[w] = true;
                    stack.push(w);
                }
            }
        }
        assert_eq!(seen, component, "problem {id}");
    }
}

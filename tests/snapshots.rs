//! Pinned outputs (insta; files in the top-level `snapshots/`). A change to any fact or count
//! fails CI until reviewed with `cargo insta review`; CI never accepts snapshots by itself.

use serde_json::json;
use truecost::planning::{plan_exact, plan_reference, Algorithm};
use truecost::problems::{GridLayout, StepCost, GRID_NODES};

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

#[test]
fn facts_of_all_19_problems_in_both_modes() {
    let exact: Vec<_> = (0..19)
        .map(|id| GridLayout::exact(id).unwrap().facts())
        .collect();
    let reference: Vec<_> = (0..19)
        .map(|id| GridLayout::reference(id).unwrap().facts())
        .collect();
    settings().bind(|| {
        insta::assert_json_snapshot!("problem_facts", json!({"exact": exact, "reference": reference}));
    });
}

/// The dynamic-programming rows of the paper's deterministic table, reference mode, every
/// problem (Problem 10's are published; the others are pinned here).
#[test]
fn reference_mode_model_free_planner_counts_for_all_problems() {
    let rows: Vec<_> = (0..19)
        .map(|id| {
            let graph = GridLayout::reference(id).unwrap().to_reference_graph();
            assert_eq!(graph.nodes(), GRID_NODES);
            let run = |alg| {
                let r = plan_reference(&graph, alg, true);
                json!({
                    "iterations": r.iterations,
                    "exploration_actions": r.exploration_actions,
                    "planner_actions": r.planner_actions,
                    "actions": r.actions,
                    "path_moves": r.path.len().saturating_sub(1),
                    "cost_to_go_initial": r.cost_to_go_initial,
                })
            };
            json!({
                "problem": id,
                "dijkstra": run(Algorithm::Dijkstra),
                "async_vi": run(Algorithm::AsyncVi),
                "vi": run(Algorithm::Vi),
            })
        })
        .collect();
    settings().bind(|| insta::assert_json_snapshot!("reference_model_free_counts", rows));
}

/// Exact optima of every problem with both step costs.
#[test]
fn exact_optima_for_all_problems() {
    let rows: Vec<_> = (0..19)
        .map(|id| {
            let layout = GridLayout::exact(id).unwrap();
            let unit = plan_exact(&layout.to_problem(StepCost::Unit), Algorithm::Dijkstra, true);
            let euclid = plan_exact(
                &layout.to_problem(StepCost::Euclidean),
                Algorithm::Dijkstra,
                true,
            );
            json!({
                "problem": id,
                "unit": unit.cost_to_go_initial,
                "euclidean": euclid.cost_to_go_initial,
                "exploration_actions": unit.exploration_actions,
                "dijkstra_pops": unit.iterations,
                "dijkstra_relaxations": unit.planner_actions,
            })
        })
        .collect();
    settings().bind(|| insta::assert_json_snapshot!("exact_optima", rows));
}

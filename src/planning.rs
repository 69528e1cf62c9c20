//! One planning run, as the CLI and the experiments ask for it: a problem in a mode, a planner,
//! optionally model-free, and a report in the problem's own state numbering.
//!
//! Modes (docs/spec.md §7): `exact` is the paper's text — exact costs (unit or `800/19` per grid move),
//! exact values, Dijkstra backwards from the goal set. `reference` reproduces the paper's code —
//! `f64` Euclidean costs on its coordinates, its action orders, Dijkstra forwards from `x1`
//! stopping at the goal, value iteration capped at 1000 sweeps. Every report names its mode.

use serde::Serialize;

use crate::model::{Decision, ExactGraph, Graph, Problem, RenderValue};
use crate::solvers::exploration::explore;
use crate::solvers::value_iteration::{value_iteration, Schedule};
use crate::solvers::{dijkstra, follow_policy};
use crate::value::{CostValue, ExactValue};

/// Which model produced the numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// The paper's text, in exact arithmetic (default).
    #[default]
    Exact,
    /// The paper's reference code (f64 geometry and costs, its orders and counting rules).
    Reference,
}

/// A planner of docs/spec.md §2.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Algorithm {
    /// Dijkstra's algorithm.
    Dijkstra,
    /// Synchronous value iteration.
    Vi,
    /// Asynchronous (Gauss–Seidel) value iteration.
    AsyncVi,
}

impl Algorithm {
    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Algorithm::Dijkstra => "dijkstra",
            Algorithm::Vi => "vi",
            Algorithm::AsyncVi => "async-vi",
        }
    }
}

/// The cap on value-iteration sweeps in the reference mode (the paper's code).
pub const REFERENCE_MAX_SWEEPS: u64 = 1000;

/// The result of one planning run, in the problem's state numbering.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlanReport {
    /// The mode.
    pub mode: Mode,
    /// The planner.
    pub algorithm: Algorithm,
    /// Whether the planner ran on the graph discovered by exploration.
    pub model_free: bool,
    /// The value type the planner computed with: `units` (exact `u64` multiples of
    /// `unit`), `big-rational` (exact), or `f64` (reference mode only).
    pub value_type: &'static str,
    /// The exact value of one unit, for `units` (e.g. `"1"`, `"800/19"`).
    pub unit: String,
    /// How Dijkstra searched (`backward-from-goals` or `forward-from-initial`), if it ran.
    pub dijkstra_direction: Option<&'static str>,
    /// Whether a goal is reachable from `x1`.
    pub reachable: bool,
    /// `G*(x1)` as text: exact (`"63"`, `"50400/19"`, `"inf"`) or, in reference mode, the f64.
    pub cost_to_go_initial: String,
    /// The path from `x1` to a goal (state ids), empty if unreachable.
    pub path: Vec<usize>,
    /// Sweeps (VI) or heap pops (Dijkstra).
    pub iterations: u64,
    /// Actions counted by the exploration (0 unless model-free).
    pub exploration_actions: u64,
    /// Actions counted by the planner: backups (VI) or relaxations (Dijkstra).
    pub planner_actions: u64,
    /// `exploration_actions + planner_actions`.
    pub actions: u64,
    /// `G*` per state as text; `None` for states the planner never saw (model-free runs see
    /// only what exploration from `x1` discovered).
    pub cost_to_go: Vec<Option<String>>,
    /// The policy as the successor chosen per state (a goal names itself: termination);
    /// `None` where no goal is reachable or the state was not seen.
    pub policy: Vec<Option<usize>>,
}

/// Plans on an exact problem, in the narrowest exact representation ([`ExactGraph`]).
///
/// ```
/// use truecost::planning::{plan_exact, Algorithm};
/// use truecost::problems::{GridLayout, StepCost};
/// let problem = GridLayout::exact(0).unwrap().to_problem(StepCost::Unit);
/// let r = plan_exact(&problem, Algorithm::Dijkstra, false);
/// assert_eq!(r.cost_to_go_initial, "17");
/// assert_eq!(r.path.len(), 18);
/// ```
pub fn plan_exact(problem: &Problem, algorithm: Algorithm, model_free: bool) -> PlanReport {
    let graph = ExactGraph::new(problem);
    let value_type = graph.representation();
    let states = problem.states();
    match &graph {
        ExactGraph::Units(g) => plan_on(g, algorithm, model_free, Mode::Exact, states, value_type),
        ExactGraph::Big(g) => plan_on(g, algorithm, model_free, Mode::Exact, states, value_type),
    }
}

/// Plans in the reference mode on an `f64` graph (docs/spec.md §7).
pub fn plan_reference(graph: &Graph<f64>, algorithm: Algorithm, model_free: bool) -> PlanReport {
    plan_on(
        graph,
        algorithm,
        model_free,
        Mode::Reference,
        graph.nodes(),
        "f64",
    )
}

fn plan_on<V: ExactValue>(
    graph: &Graph<V>,
    algorithm: Algorithm,
    model_free: bool,
    mode: Mode,
    states: usize,
    value_type: &'static str,
) -> PlanReport {
    let explored;
    let (work, exploration_actions) = if model_free {
        explored = explore(graph);
        (&explored.graph, explored.actions)
    } else {
        (graph, 0)
    };
    let max_sweeps = (mode == Mode::Reference).then_some(REFERENCE_MAX_SWEEPS);
    let (solution, path, iterations, planner_actions, direction) = match algorithm {
        Algorithm::Dijkstra if mode == Mode::Reference => {
            // Counts and path from the paper's forward search; G* for every state from the
            // backward search (not counted: the paper's code does not compute it).
            let forward = dijkstra::from_initial(work);
            let all = dijkstra::to_goals(work);
            let (p, r) = (forward.counts.pops, forward.counts.relaxations);
            (all, forward.path, p, r, Some("forward-from-initial"))
        }
        Algorithm::Dijkstra => {
            let s = dijkstra::to_goals(work);
            let path = follow_policy(work, &s.policy, work.initial()).unwrap_or_default();
            let (i, a) = (s.iterations, s.actions);
            (s, path, i, a, Some("backward-from-goals"))
        }
        Algorithm::Vi | Algorithm::AsyncVi => {
            let schedule = if algorithm == Algorithm::Vi {
                Schedule::Synchronous
            } else {
                Schedule::Asynchronous
            };
            let s = value_iteration(work, schedule, max_sweeps);
            let path = follow_policy(work, &s.policy, work.initial()).unwrap_or_default();
            let (i, a) = (s.iterations, s.actions);
            (s, path, i, a, None)
        }
    };
    let mut cost_to_go = vec![None; states];
    let mut policy = vec![None; states];
    for v in 0..work.nodes() {
        let x = work.origin(v);
        cost_to_go[x] = Some(work.render(&solution.cost_to_go[v]));
        policy[x] = match solution.policy[v] {
            Some(Decision::Terminate) => Some(x),
            Some(Decision::Move(i)) => work.edges(v).nth(i).map(|(y, _)| work.origin(y)),
            None => None,
        };
    }
    let initial = &solution.cost_to_go[work.initial()];
    PlanReport {
        mode,
        algorithm,
        model_free,
        value_type,
        unit: crate::value::Extended::Finite(work.unit().clone()).to_string(),
        dijkstra_direction: direction,
        reachable: initial.is_finite(),
        cost_to_go_initial: work.render(initial),
        path: path.into_iter().map(|v| work.origin(v)).collect(),
        iterations,
        exploration_actions,
        planner_actions,
        actions: exploration_actions + planner_actions,
        cost_to_go,
        policy,
    }
}

/// What one model-free planning run measures: counts only — no values, no text, nothing on the
/// heap (it is `Copy`), so the timed region that returns it cannot render or build a report.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PlanCounts {
    /// Sweeps (VI) or heap pops (Dijkstra).
    pub iterations: u64,
    /// Actions counted by the exploration.
    pub exploration_actions: u64,
    /// Actions counted by the planner: backups (VI) or relaxations (Dijkstra).
    pub planner_actions: u64,
    /// Whether the planner found a path from `x1` to a goal.
    pub reached_goal: bool,
    /// States on that path, `x1` and the goal included (0 if none).
    pub path_states: usize,
}

impl PlanCounts {
    /// `exploration_actions + planner_actions` (docs/spec.md §2).
    pub fn actions(&self) -> u64 {
        self.exploration_actions + self.planner_actions
    }
}

/// The timed region of a model-free planner row (docs/spec.md §2, the
/// model-free variants): the robot explores the **prepared** graph, then the planner runs on the
/// discovered graph and its path is read off — what the paper's code times. Problem
/// compilation happens before (the caller passes a compiled [`Graph`]); no oracle runs here (in
/// reference mode Dijkstra is only the paper's forward search, never the backward search
/// [`plan_reference`] adds for reporting `G*`), and nothing is rendered.
///
/// The counts agree with [`plan_exact`] / [`plan_reference`] with `model_free = true`.
///
/// ```
/// use truecost::planning::{model_free_counts, plan_reference, Algorithm, Mode};
/// use truecost::problems::GridLayout;
/// let graph = GridLayout::reference(10).unwrap().to_reference_graph();
/// let c = model_free_counts(&graph, Algorithm::Dijkstra, Mode::Reference);
/// // The published counts of Problem 10 (shared/reference/problem10.md).
/// assert_eq!((c.exploration_actions, c.iterations, c.planner_actions), (3266, 331, 1157));
/// assert_eq!((c.actions(), c.path_states), (4423, 64));
/// let report = plan_reference(&graph, Algorithm::Dijkstra, true);
/// assert_eq!((report.iterations, report.actions), (c.iterations, c.actions()));
/// ```
pub fn model_free_counts<V: CostValue>(
    graph: &Graph<V>,
    algorithm: Algorithm,
    mode: Mode,
) -> PlanCounts {
    let explored = explore(graph);
    let work = &explored.graph;
    let path_counts = |path: Option<Vec<usize>>| {
        let path = path.unwrap_or_default();
        (!path.is_empty(), path.len())
    };
    let (iterations, planner_actions, (reached_goal, path_states)) = match algorithm {
        Algorithm::Dijkstra if mode == Mode::Reference => {
            let forward = dijkstra::from_initial(work);
            let c = forward.counts;
            (c.pops, c.relaxations, path_counts(Some(forward.path)))
        }
        Algorithm::Dijkstra => {
            let s = dijkstra::to_goals(work);
            let path = follow_policy(work, &s.policy, work.initial());
            (s.iterations, s.actions, path_counts(path))
        }
        Algorithm::Vi | Algorithm::AsyncVi => {
            let schedule = if algorithm == Algorithm::Vi {
                Schedule::Synchronous
            } else {
                Schedule::Asynchronous
            };
            let max_sweeps = (mode == Mode::Reference).then_some(REFERENCE_MAX_SWEEPS);
            let s = value_iteration(work, schedule, max_sweeps);
            let path = follow_policy(work, &s.policy, work.initial());
            (s.iterations, s.actions, path_counts(path))
        }
    };
    PlanCounts {
        iterations,
        exploration_actions: explored.actions,
        planner_actions,
        reached_goal,
        path_states,
    }
}

//! What the Q-learning rows time (pinned by the timed region's type, as
//! `reproduce_published.rs` pins the planner rows'), and the LaTeX rendering of the published
//! numbers beside ours, pinned by a reviewed snapshot (times left out).
//!
//! Expected published values are copied from `shared/reference/problem10.md` and
//! `data/published/` (numbers from the paper's repository), never from truecost's output.

use truecost::experiments::deterministic::{
    self, against_published, time_learning, LearningClock, Settings,
};
use truecost::experiments::latex;
use truecost::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
use truecost::learning::q_learning::{LearningError, Outcome, QLearner, QLearningConfig, Rules};
use truecost::model::Graph;
use truecost::planning::Mode;
use truecost::solvers::value_iteration::{value_iteration, Schedule};

/// The timed region of a learning row takes a compiled graph and its prepared oracle values
/// (compilation and the oracle happen before) and returns counts and the clock — both `Copy`,
/// owning nothing on the heap, so no rendering and no report can be built inside — plus the
/// learner, whose greedy path is read after the clock stopped.
#[test]
fn the_q_learning_timed_region_takes_a_prepared_graph_and_returns_counts_only() {
    fn copy<T: Copy>() {}
    copy::<Outcome>();
    copy::<LearningClock>();
    assert!(!std::mem::needs_drop::<Outcome>());
    assert!(!std::mem::needs_drop::<LearningClock>());
    type Region = fn(
        &Graph<f64>,
        &[f64],
        &QLearningConfig,
        rand_chacha::ChaCha8Rng,
        Plan<'static>,
    )
        -> Result<(Outcome, LearningClock, QLearner<'static, f64>), LearningError>;
    let region: Region = time_learning::<f64>;
    let graph = truecost::problems::GridLayout::reference(10)
        .unwrap()
        .to_reference_graph();
    // The reference code's oracle, prepared before the clock.
    let optimum = value_iteration(&graph, Schedule::Asynchronous, Some(1000)).cost_to_go;
    let config = QLearningConfig {
        rules: Rules::Reference,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let (outcome, clock, learner) =
        region(&graph, &optimum, &config, sample_rng(0, 0), Plan::Random).unwrap();
    // Problem 10, greedy Q-learning (published): never converged, 101214 actions, goal first
    // entered at action 2015, V(x1) optimal at the check after 52000 actions.
    assert_eq!(outcome.actions, 101214);
    assert!(!outcome.converged);
    assert_eq!(outcome.goal_discovered_at, Some(2015));
    assert_eq!(outcome.initial_optimal_at, Some(52000));
    assert_eq!(outcome.last_episode_index(), Some(999));
    // The milestones were timed inside the run, before its end.
    let goal = clock.goal_discovered_s.unwrap();
    let initial = clock.initial_optimal_s.unwrap();
    assert!(0.0 <= goal && goal <= initial && initial <= clock.seconds);
    // The greedy path (after the clock): the optimal 64 nodes.
    assert_eq!(learner.greedy_path().states.len(), 64);
}

fn reference_problem_16() -> deterministic::Report {
    let settings = Settings {
        problems: vec![16],
        samples: 2,
        mode: Mode::Reference,
        ..Settings::default()
    };
    let mut report = deterministic::run(&settings, &|_| {}).unwrap();
    against_published(&mut report, &settings).unwrap();
    report
}

#[test]
fn latex_shows_the_published_value_beside_ours_with_the_verdict() {
    let report = reference_problem_16();
    let t = latex::deterministic(&report, false);
    // Problem 16 (published): model-free Dijkstra 6 pops and 28 actions; greedy Q-learning
    // converges in episode 244 after 1000 actions.
    assert!(t.contains("Model-free Dijkstra & mean\\_actions & 28.0 & 28 & exact \\\\"));
    assert!(t.contains("Model-free Dijkstra & mean\\_iterations & 6.0 & 6 & exact \\\\"));
    assert!(
        t.contains("Q-learning ($\\varepsilon$=0) & mean\\_iterations & 244.0 & 244 & exact \\\\")
    );
    assert!(t.contains("\\subsection*{Reproduction summary}"));
    // Without times: no run-time column and no `machine` verdict.
    assert!(!t.contains("machine (ours"));
    assert!(!t.contains("Run time"));
    // With times: both.
    let timed = latex::deterministic(&report, true);
    assert!(timed.contains("machine (ours/published"));
    assert!(timed.contains("Run time s"));
    // Every table that begins ends; math is balanced on every line.
    assert_eq!(
        t.matches("\\begin{longtable}").count(),
        t.matches("\\end{longtable}").count()
    );
    for line in t.lines().filter(|l| !l.starts_with('%')) {
        let unescaped = line.replace("\\$", "");
        assert_eq!(unescaped.matches('$').count() % 2, 0, "{line}");
        assert!(!unescaped.contains("$$"), "{line}");
    }
    insta::with_settings!({snapshot_path => "../snapshots", prepend_module_to_snapshot => false}, {
        insta::assert_snapshot!("reproduce_deterministic_reference_latex", t);
    });
}

/// The stochastic experiment's LaTeX: Problem 10, γ = 0.999, ρ = ε = 0.9 and
/// both value iterations under the reference code's noise and tolerance, two samples, against
/// the published table; pinned without times by a reviewed snapshot.
#[test]
fn stochastic_latex_shows_the_published_value_beside_ours_with_the_verdict() {
    use truecost::experiments::stochastic::{self as st, EpsilonSpec, RateSpec};
    use truecost::stochastic::{NoiseModel, Predictability};
    let settings = st::Settings {
        problems: vec![10],
        gammas: vec![Predictability::parse("0.999").unwrap()],
        rhos: vec![RateSpec::parse("0.9").unwrap()],
        epsilons: vec![EpsilonSpec::parse("0.9").unwrap()],
        samples: 2,
        noise: NoiseModel::Reference,
        tolerance: truecost::learning::stochastic_q::Tolerance::Reference,
        ..st::Settings::default()
    };
    let mut report = st::run(&settings, &|_| {}).unwrap();
    st::against_published(&mut report, &settings).unwrap();
    let t = latex::stochastic(&report, false);
    // Published (example_10_stochastic_results_100_samples.csv): asynchronous VI 58 sweeps and
    // 178292 actions, synchronous VI 94 and 288956 — counts, so `exact` in this model.
    for line in [
        "mean\\_iterations & 58.0 & 58 & exact \\\\",
        "mean\\_actions & 178292.0 & 178292 & exact \\\\",
        "mean\\_iterations & 94.0 & 94 & exact \\\\",
        "mean\\_actions & 288956.0 & 288956 & exact \\\\",
    ] {
        assert!(t.contains(line), "{line} missing from\n{t}");
    }
    assert!(t.contains("\\subsection*{Reproduction summary}"));
    assert!(!t.contains("machine (ours"));
    let timed = latex::stochastic(&report, true);
    assert!(timed.contains("machine (ours/published"));
    assert_eq!(
        t.matches("\\begin{longtable}").count(),
        t.matches("\\end{longtable}").count()
    );
    for line in t.lines().filter(|l| !l.starts_with('%')) {
        let unescaped = line.replace("\\$", "");
        assert_eq!(unescaped.matches('$').count() % 2, 0, "{line}");
    }
    insta::with_settings!({snapshot_path => "../snapshots", prepend_module_to_snapshot => false}, {
        insta::assert_snapshot!("reproduce_stochastic_reference_latex", t);
    });
}

//! The paper's deterministic comparison (`truecost reproduce deterministic`): Q-learning with
//! several ε, the π universal plan and ε-decay against model-free Dijkstra and value iteration,
//! on the paper's grid problems, over seeded samples (docs/spec.md §2, §4, §7).
//!
//! # Rows ([`PAPER_ROWS`], configuration as data)
//!
//! Q-learning (`ρ = 1`, `Q₀ = 0`, [`Settings::episodes`] × [`Settings::max_steps`], default the
//! paper's 1000 × 3000) with ε ∈ {0, 0.25, 0.5, 0.75, 0.9, 1} over the random plan; the π plan
//! with ε = 1; ε-decay (linear from 1 in the first episode to 0.1 in the last, over the random
//! plan); model-free Dijkstra, asynchronous and synchronous value iteration (explore first, then
//! plan; docs/spec.md §2).
//!
//! # Modes
//!
//! * [`Mode::Exact`] — the paper's text: exact stage costs and values (the problem compiled to
//!   [`ExactGraph`]), metrics tracked after every action ([`Rules::Exact`]); `iterations` of a
//!   learning row is the number of episodes run.
//! * [`Mode::Reference`] — the paper's code (docs/spec.md §7): `f64` graph, checks every 1000 actions,
//!   `iterations` is the 0-based index of the last episode (999 = never converged). With the
//!   default settings this reproduces the published deterministic counts: the DP rows, the
//!   greedy ε = 0 rows and the π rows.
//!
//! # Samples and reproducibility
//!
//! Sample `k` of row `r` on problem `p` draws from [`sample_rng`]`(seed, p·2^32 + r·2^24 + k)`,
//! so every number but the times is a pure function of the settings, whatever the number of
//! threads. The π rows share **one** digit stream ([`PiStream`], fresh for each experiment):
//! they run one after another, problems in the order given, samples in order `0, 1, …`, while
//! everything else runs in parallel. The learning rows are not run where the goal is
//! unreachable from `x1` (as in the paper's code, which skips such problems; so they consume no
//! π digits).

use rayon::prelude::*;
use serde::Serialize;

use std::collections::BTreeMap;

use super::clock::{timed, Stopwatch};
use super::published::{self, Comparison, DataError, Kind, Observations, Observed, Summary};
use super::runs::{check_shard_size, in_pool, owned, row_groups, RunSettings};
use super::stats::{mean_of_present, mean_std};
use crate::claims::shard::{self, Entry, Part, ShardFile};
use crate::learning::plan::{
    python_coin, sample_rng, EpsilonSchedule, PiStream, Plan, Probability,
};
use crate::learning::q_learning::{
    Event, LearningError, LearningValue, Milestone, Outcome, QLearner, QLearningConfig, Rules,
};
use crate::model::{ExactGraph, Graph};
use crate::planning::{model_free_counts, Algorithm, Mode, PlanCounts};
use crate::problems::{GridLayout, StepCost, PAPER_PROBLEMS};
use crate::solvers::dijkstra;
use crate::solvers::value_iteration::{value_iteration, Schedule};
use crate::value::{CostValue, Rational};

/// Which exploration plan a learning row uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlanKind {
    /// Uniformly random actions.
    Random,
    /// The π universal plan.
    Pi,
}

/// One row of the experiment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Row {
    /// Q-learning with constant `ε = numerator/denominator`.
    QLearning {
        /// ε as an exact fraction `(numerator, denominator)`.
        epsilon: (u64, u64),
        /// Where exploring actions come from.
        plan: PlanKind,
    },
    /// Q-learning with ε decaying from `start` to 0.1: linearly to 0.1 at the last episode in
    /// exact mode (the text), by the code's `f64` steps in reference mode
    /// ([`EpsilonSchedule::CodeDecay`]).
    EpsilonDecay {
        /// ε in the first episode, `(numerator, denominator)`.
        start: (u64, u64),
    },
    /// A model-free planner: exploration, then the planner on the discovered graph.
    ModelFree(Algorithm),
}

/// The paper's rows, in the paper's order.
pub const PAPER_ROWS: [Row; 11] = [
    Row::QLearning {
        epsilon: (0, 1),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (1, 4),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (1, 2),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (3, 4),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (9, 10),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (1, 1),
        plan: PlanKind::Random,
    },
    Row::QLearning {
        epsilon: (1, 1),
        plan: PlanKind::Pi,
    },
    Row::EpsilonDecay { start: (1, 1) },
    Row::ModelFree(Algorithm::Dijkstra),
    Row::ModelFree(Algorithm::AsyncVi),
    Row::ModelFree(Algorithm::Vi),
];

impl Row {
    /// The row's algorithm name in reports.
    pub fn algorithm(&self) -> &'static str {
        match self {
            Row::QLearning {
                plan: PlanKind::Random,
                ..
            } => "q-learning",
            Row::QLearning {
                plan: PlanKind::Pi, ..
            } => "q-learning-pi",
            Row::EpsilonDecay { .. } => "q-learning-epsilon-decay",
            Row::ModelFree(Algorithm::Dijkstra) => "model-free-dijkstra",
            Row::ModelFree(Algorithm::AsyncVi) => "model-free-async-vi",
            Row::ModelFree(Algorithm::Vi) => "model-free-vi",
        }
    }

    /// ε (the first episode's, for ε-decay); `None` for planners.
    pub fn epsilon(&self) -> Option<(u64, u64)> {
        match *self {
            Row::QLearning { epsilon, .. } => Some(epsilon),
            Row::EpsilonDecay { start } => Some(start),
            Row::ModelFree(_) => None,
        }
    }

    fn is_pi(&self) -> bool {
        matches!(
            self,
            Row::QLearning {
                plan: PlanKind::Pi,
                ..
            }
        )
    }

    fn learning_config(
        &self,
        settings: &Settings,
        rules: Rules,
    ) -> Result<Option<QLearningConfig>, ExperimentError> {
        let probability = |(n, d): (u64, u64)| {
            Probability::new(
                "ε",
                &Rational::new(num_bigint::BigInt::from(n), num_bigint::BigInt::from(d)),
            )
            .map_err(LearningError::from)
        };
        let epsilon = match *self {
            // The paper's code flips `random.random() < ε` with ε a float literal (docs/spec.md §7).
            Row::QLearning { epsilon, .. } => EpsilonSchedule::Constant(match rules {
                Rules::Exact => probability(epsilon)?,
                Rules::Reference => python_coin(epsilon.0 as f64 / epsilon.1 as f64),
            }),
            // The text decays linearly to 0.1; the paper's code by f64 steps (docs/spec.md §7).
            Row::EpsilonDecay { start } => match rules {
                Rules::Exact => EpsilonSchedule::decay_to_one_tenth(probability(start)?),
                Rules::Reference => EpsilonSchedule::CodeDecay {
                    start: probability(start)?,
                },
            },
            Row::ModelFree(_) => return Ok(None),
        };
        Ok(Some(QLearningConfig {
            episodes: settings.episodes,
            max_steps: settings.max_steps,
            rules,
            ..QLearningConfig::paper(epsilon)
        }))
    }
}

/// What to run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Settings {
    /// Problem ids, in the order the π rows run.
    pub problems: Vec<usize>,
    /// Samples per row.
    pub samples: u32,
    /// The master seed.
    pub seed: u64,
    /// Paper text (exact) or paper code (reference).
    pub mode: Mode,
    /// Grid step cost in exact mode.
    pub step_cost: StepCost,
    /// Episodes of a learning run.
    pub episodes: u32,
    /// Steps per episode.
    pub max_steps: u32,
    /// Worker threads (`None`: rayon's default).
    pub threads: Option<usize>,
}

pub use super::runs::{RunError as ExperimentError, MAX_ACTIONS_PER_RUN, MAX_SAMPLES};

impl Default for Settings {
    /// The paper's experiment: its 16 problems, 100 samples, seed 0, exact mode.
    fn default() -> Self {
        Settings {
            problems: PAPER_PROBLEMS.to_vec(),
            samples: 100,
            seed: 0,
            mode: Mode::Exact,
            step_cost: StepCost::Unit,
            episodes: 1000,
            max_steps: 3000,
            threads: None,
        }
    }
}

impl Settings {
    /// Checks every parameter (one clear error for the first bad one).
    pub fn validate(&self) -> Result<(), ExperimentError> {
        self.runs().validate()
    }

    fn runs(&self) -> RunSettings<'_> {
        RunSettings {
            problems: &self.problems,
            samples: self.samples,
            episodes: self.episodes,
            max_steps: self.max_steps,
            threads: self.threads,
        }
    }

    /// The model in words, for every output.
    pub fn model(&self) -> String {
        match self.mode {
            Mode::Exact => format!(
                "exact (paper text): {} step costs, exact values; metrics tracked after every \
                 action; iterations = episodes run",
                match self.step_cost {
                    StepCost::Unit => "unit",
                    StepCost::Euclidean => "Euclidean (800/19)",
                }
            ),
            Mode::Reference => {
                "reference (paper code, docs/spec.md §7): f64 Euclidean step costs on the \
                                reference grid; checks every 1000 actions; iterations = 0-based \
                                last episode index; coins random() < ε with ε a float, ε-decay \
                                by f64 steps of (ε0 − 0.1)/E"
                    .to_string()
            }
        }
    }
}

/// The measurements of one sample run.
#[derive(Clone, Debug, PartialEq, Serialize, serde::Deserialize)]
pub struct Sample {
    /// Wall time of the run in seconds (the only non-reproducible number).
    pub time_s: f64,
    /// Actions applied (learning) or exploration + planner actions (DP).
    pub actions: u64,
    /// Actions counted by the planner alone (DP rows; 0 for learning).
    pub planner_actions: u64,
    /// Episodes (see the mode) or sweeps / heap pops.
    pub iterations: u64,
    /// Whether `Q̂` reached `Q*` on every tracked state (DP: the planner solved it).
    pub converged: bool,
    /// The convergence action, if converged (learning rows).
    pub converged_at: Option<u64>,
    /// The action after which `V(x1) = G*(x1)` first held.
    pub initial_optimal_at: Option<u64>,
    /// Seconds until then.
    pub initial_optimal_time_s: Option<f64>,
    /// The action that first entered the goal.
    pub goal_discovered_at: Option<u64>,
    /// Seconds until then.
    pub goal_discovered_time_s: Option<f64>,
    /// States on the extracted path (`x1` and the goal included, as the paper counts).
    pub path_states: usize,
    /// Whether the path reaches the goal.
    pub reached_goal: bool,
    /// Whether the path extraction ran into a loop.
    pub looped: bool,
    /// Whether the path reaches the goal at cost `G*(x1)`.
    pub path_optimal: bool,
}

/// One row of the result: a summary over the samples.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RowSummary {
    /// Problem id.
    pub problem: usize,
    /// `q-learning`, `q-learning-pi`, `q-learning-epsilon-decay`, `model-free-dijkstra`,
    /// `model-free-async-vi`, `model-free-vi`.
    pub algorithm: &'static str,
    /// ε (the first episode's for ε-decay); `null` for planners.
    pub epsilon: Option<f64>,
    /// ε in the last episode (ε-decay only).
    pub epsilon_final: Option<f64>,
    /// `random` or `pi` (learning rows).
    pub plan: Option<&'static str>,
    /// Samples summarised (0 when the row was not run).
    pub samples: u32,
    /// Mean run time (s).
    pub mean_time_s: Option<f64>,
    /// Standard deviation of the run time (s).
    pub std_time_s: Option<f64>,
    /// Fraction of samples that converged.
    pub convergence_rate: Option<f64>,
    /// Mean convergence action over converged samples.
    pub mean_actions_converged: Option<f64>,
    /// Mean actions.
    pub mean_actions: Option<f64>,
    /// Standard deviation of the actions.
    pub std_actions: Option<f64>,
    /// Mean actions of the planner alone, after exploration (model-free rows: relaxations or
    /// backups; the paper's "convergence action" column of these rows).
    pub mean_planner_actions: Option<f64>,
    /// Mean nanoseconds per counted action: total run time over total actions,
    /// comparable across machines and languages.
    pub mean_ns_per_action: Option<f64>,
    /// Mean iterations (episodes / sweeps / pops; see the mode).
    pub mean_iterations: Option<f64>,
    /// Standard deviation of the iterations.
    pub std_iterations: Option<f64>,
    /// Fewest states on an extracted path.
    pub shortest_path: Option<usize>,
    /// Most states on an extracted path.
    pub longest_path: Option<usize>,
    /// Fraction of samples whose path reaches the goal.
    pub goal_reached_rate: Option<f64>,
    /// Fraction of samples whose path reaches the goal at optimal cost.
    pub optimal_path_rate: Option<f64>,
    /// Samples whose path extraction looped.
    pub loops: u32,
    /// Fraction of samples in which `V(x1)` became optimal.
    pub initial_optimal_rate: Option<f64>,
    /// Mean action at which `V(x1)` became optimal (over those samples).
    pub mean_actions_initial_optimal: Option<f64>,
    /// Mean seconds until `V(x1)` became optimal (over those samples).
    pub mean_time_initial_optimal_s: Option<f64>,
    /// Fraction of samples that entered the goal.
    pub goal_discovery_rate: Option<f64>,
    /// Mean action that first entered the goal (over those samples).
    pub mean_actions_goal_discovered: Option<f64>,
    /// Mean seconds until the goal was first entered (over those samples).
    pub mean_time_goal_discovered_s: Option<f64>,
    /// `exact` or `reference`.
    pub mode: Mode,
    /// The master seed.
    pub seed: u64,
    /// The value type the run computed with (`units`, `big-rational`, `f64`).
    pub value_type: &'static str,
    /// Why a row was not run, if it was not.
    pub note: Option<String>,
    /// With `--against-published`: `published` (metric → the paper's value) and `agreement`
    /// (metric → verdict), see [`published`].
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub comparison: Option<Comparison>,
    /// Our side of every metric the paper publishes, for the comparison.
    #[serde(skip)]
    pub observed: BTreeMap<&'static str, Observed>,
    /// Whether the row's counts are a pure function of the settings and the settings are the
    /// published ones (see [`published`]: the verdict `exact`).
    #[serde(skip)]
    pub exact_comparable: bool,
}

/// The whole result.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The settings.
    pub mode: Mode,
    /// The model in words.
    pub model: String,
    /// The master seed.
    pub seed: u64,
    /// Samples per row.
    pub samples: u32,
    /// Episodes per learning run.
    pub episodes: u32,
    /// Steps per episode.
    pub max_steps: u32,
    /// Problems in the order run.
    pub problems: Vec<usize>,
    /// One summary per (problem, row), problems in the given order, rows as [`PAPER_ROWS`].
    pub rows: Vec<RowSummary>,
    /// The closing counts of [`against_published`], once it ran.
    pub against_published: Option<Summary>,
}

impl RowSummary {
    /// The row's name in the paper's words, as every rendering labels it.
    ///
    /// ```
    /// use truecost::experiments::deterministic::{run, Settings};
    /// let s = Settings { problems: vec![16], samples: 1, ..Settings::default() };
    /// let labels: Vec<String> = run(&s, &|_| {}).unwrap().rows.iter().map(|r| r.label()).collect();
    /// assert_eq!(labels[4], "Q-learning (ε=0.9)");
    /// assert_eq!(labels[6], "Q-learning, π plan (ε=1)");
    /// assert_eq!(labels[7], "Q-learning (ε-decay 1→0.1)");
    /// assert_eq!(labels[8], "Model-free Dijkstra");
    /// ```
    pub fn label(&self) -> String {
        let e = |x: Option<f64>, default: f64| format!("{}", x.unwrap_or(default));
        match self.algorithm {
            "q-learning" => format!("Q-learning (ε={})", e(self.epsilon, 0.0)),
            "q-learning-pi" => format!("Q-learning, π plan (ε={})", e(self.epsilon, 1.0)),
            "q-learning-epsilon-decay" => format!(
                "Q-learning (ε-decay {}→{})",
                e(self.epsilon, 1.0),
                e(self.epsilon_final, 0.1)
            ),
            "model-free-dijkstra" => "Model-free Dijkstra".into(),
            "model-free-async-vi" => "Model-free asynchronous VI".into(),
            "model-free-vi" => "Model-free synchronous VI".into(),
            other => other.into(),
        }
    }
}

impl Report {
    /// The run's settings in one line, as every rendering's title gives them.
    ///
    /// ```
    /// let r = truecost::experiments::deterministic::Report {
    ///     mode: truecost::planning::Mode::Reference, model: String::new(), seed: 7, samples: 2,
    ///     episodes: 1000, max_steps: 3000, problems: vec![16, 10], rows: vec![],
    ///     against_published: None,
    /// };
    /// assert_eq!(r.settings(), "mode reference; seed 7; 2 samples per row; \
    ///     1000 episodes × 3000 steps; problems 16,10");
    /// ```
    pub fn settings(&self) -> String {
        format!(
            "mode {}; seed {}; {} samples per row; {} episodes × {} steps; problems {}",
            match self.mode {
                Mode::Exact => "exact",
                Mode::Reference => "reference",
            },
            self.seed,
            self.samples,
            self.episodes,
            self.max_steps,
            super::runs::comma_list(&self.problems)
        )
    }
}

/// A problem compiled for one mode, with the oracle values `G*` of the convergence checks.
enum Prepared {
    /// The paper's text: the compiled exact graph with its optimum.
    Exact { graph: ExactOptimum },
    /// The paper's code: the `f64` graph and its value iteration's values.
    Reference {
        graph: Graph<f64>,
        optimum: Vec<f64>,
    },
}

/// An exact graph with its exact optimum (Dijkstra backwards from the goals).
enum ExactOptimum {
    Units(Graph<crate::value::Units>, Vec<crate::value::Units>),
    Big(Graph<crate::value::Extended>, Vec<crate::value::Extended>),
}

struct ProblemRun {
    id: usize,
    prepared: Prepared,
    reachable: bool,
    value_type: &'static str,
}

fn prepare(id: usize, settings: &Settings) -> Result<ProblemRun, ExperimentError> {
    match settings.mode {
        Mode::Exact => {
            let problem = GridLayout::exact(id)?.to_problem(settings.step_cost);
            // Compiled once, before any clock starts.
            let compiled = ExactGraph::new(&problem);
            let value_type = compiled.representation();
            let (graph, reachable) = match compiled {
                ExactGraph::Units(g) => {
                    let opt = dijkstra::to_goals(&g).cost_to_go;
                    let r = opt[g.initial()].is_finite();
                    (ExactOptimum::Units(g, opt), r)
                }
                ExactGraph::Big(g) => {
                    let opt = dijkstra::to_goals(&g).cost_to_go;
                    let r = opt[g.initial()].is_finite();
                    (ExactOptimum::Big(g, opt), r)
                }
            };
            Ok(ProblemRun {
                id,
                prepared: Prepared::Exact { graph },
                reachable,
                value_type,
            })
        }
        Mode::Reference => {
            let graph = GridLayout::reference(id)?.to_reference_graph();
            // The reference code's oracle: its value iteration (in place, 1000 sweeps at most).
            let optimum = value_iteration(&graph, Schedule::Asynchronous, Some(1000)).cost_to_go;
            let reachable = optimum[graph.initial()].is_finite();
            Ok(ProblemRun {
                id,
                prepared: Prepared::Reference { graph, optimum },
                reachable,
                value_type: "f64",
            })
        }
    }
}

/// What the clock of a learning row reads: seconds to the end of the run and
/// to each milestone. `Copy`: nothing is rendered inside the timed region.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LearningClock {
    /// Seconds from the learner's set-up to the end of the run.
    pub seconds: f64,
    /// Seconds until the goal was first entered.
    pub goal_discovered_s: Option<f64>,
    /// Seconds until `V(x1) = G*(x1)` first held.
    pub initial_optimal_s: Option<f64>,
}

/// The timed region of a learning row: the clock wraps the learner only —
/// setting up its Q-table on a graph compiled before, and learning until it finishes, with
/// milestones read between calls to [`QLearner::advance`]. The oracle values `optimum` are
/// prepared before; the learner compares with them through a counter updated with each `Q̂`
/// update (`O(1)` per action, see [`crate::learning::q_learning`]). It returns the counts
/// ([`Outcome`], `Copy`) and the clock; the learner is
/// handed back so that the greedy path is read after the clock stopped.
///
/// ```
/// use truecost::experiments::deterministic::time_learning;
/// use truecost::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability};
/// use truecost::learning::q_learning::{QLearningConfig, Rules};
/// use truecost::solvers::value_iteration::{value_iteration, Schedule};
/// let graph = truecost::problems::GridLayout::reference(16).unwrap().to_reference_graph();
/// let optimum = value_iteration(&graph, Schedule::Asynchronous, Some(1000)).cost_to_go;
/// let config = QLearningConfig { rules: Rules::Reference, max_steps: 100,
///     ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO)) };
/// let (outcome, clock, learner) =
///     time_learning(&graph, &optimum, &config, sample_rng(0, 0), Plan::Random).unwrap();
/// // The paper's code: greedy Q-learning on Problem 16 converges after 1000 actions.
/// assert_eq!((outcome.actions, outcome.converged), (1000, true));
/// assert!(clock.seconds >= 0.0);
/// assert_eq!(learner.greedy_path().states.len(), 5);
/// ```
pub fn time_learning<'a, V: LearningValue>(
    graph: &Graph<V>,
    optimum: &[V],
    config: &QLearningConfig,
    rng: rand_chacha::ChaCha8Rng,
    plan: Plan<'a>,
) -> Result<(Outcome, LearningClock, QLearner<'a, V>), LearningError> {
    let watch = Stopwatch::start();
    let mut learner = QLearner::new(graph, optimum, V::zero(), config, rng, plan)?;
    let (mut goal_time, mut initial_time) = (None, None);
    loop {
        match learner.advance() {
            Event::Milestone(Milestone::GoalDiscovered) => goal_time = Some(watch.seconds()),
            Event::Milestone(Milestone::InitialOptimal) => initial_time = Some(watch.seconds()),
            Event::Milestone(Milestone::Converged) => {}
            Event::Finished => break,
        }
    }
    let clock = LearningClock {
        seconds: watch.seconds(),
        goal_discovered_s: goal_time,
        initial_optimal_s: initial_time,
    };
    Ok((learner.outcome(), clock, learner))
}

/// One learning sample on a prepared graph: [`time_learning`], then the greedy path, read
/// after the clock stopped.
fn learn_sample<V: LearningValue>(
    graph: &Graph<V>,
    optimum: &[V],
    config: &QLearningConfig,
    rng: rand_chacha::ChaCha8Rng,
    plan: Plan<'_>,
    mode: Mode,
) -> Result<Sample, LearningError> {
    let (outcome, clock, learner) = time_learning(graph, optimum, config, rng, plan)?;
    let path = learner.greedy_path();
    let iterations = match mode {
        Mode::Exact => u64::from(outcome.episodes_run),
        Mode::Reference => u64::from(outcome.last_episode_index().unwrap_or(0)),
    };
    Ok(Sample {
        time_s: clock.seconds,
        actions: outcome.actions,
        planner_actions: 0,
        iterations,
        converged: outcome.converged,
        converged_at: outcome.converged_at,
        initial_optimal_at: outcome.initial_optimal_at,
        initial_optimal_time_s: clock.initial_optimal_s,
        goal_discovered_at: outcome.goal_discovered_at,
        goal_discovered_time_s: clock.goal_discovered_s,
        path_states: path.states.len(),
        reached_goal: path.reached_goal,
        looped: path.looped,
        path_optimal: path.reached_goal && path.cost == optimum[graph.initial()],
    })
}

/// The generator stream of sample `k` of row `r` on problem `p`.
pub(crate) fn stream(problem: usize, row: usize, sample: u32) -> u64 {
    ((problem as u64) << 32) | ((row as u64) << 24) | u64::from(sample)
}

/// Runs one sample of a row on a prepared problem.
fn run_sample(
    run: &ProblemRun,
    row_index: usize,
    row: &Row,
    sample: u32,
    settings: &Settings,
    pi: Option<&mut PiStream>,
) -> Result<Sample, ExperimentError> {
    let rng = sample_rng(settings.seed, stream(run.id, row_index, sample));
    let plan = match pi {
        Some(s) => Plan::Pi(s),
        None => Plan::Random,
    };
    let rules = match settings.mode {
        Mode::Exact => Rules::Exact,
        Mode::Reference => Rules::Reference,
    };
    if let Some(config) = row.learning_config(settings, rules)? {
        let sample = match &run.prepared {
            Prepared::Exact {
                graph: ExactOptimum::Units(g, optimum),
                ..
            } => learn_sample(g, optimum, &config, rng, plan, settings.mode)?,
            Prepared::Exact {
                graph: ExactOptimum::Big(g, optimum),
                ..
            } => learn_sample(g, optimum, &config, rng, plan, settings.mode)?,
            Prepared::Reference { graph, optimum } => {
                learn_sample(graph, optimum, &config, rng, plan, settings.mode)?
            }
        };
        return Ok(sample);
    }
    let Row::ModelFree(algorithm) = *row else {
        unreachable!("learning rows handled above")
    };
    let mode = settings.mode;
    let (counts, time_s) = match &run.prepared {
        Prepared::Exact {
            graph: ExactOptimum::Units(g, _),
        } => time_model_free(g, algorithm, mode),
        Prepared::Exact {
            graph: ExactOptimum::Big(g, _),
        } => time_model_free(g, algorithm, mode),
        Prepared::Reference { graph, .. } => time_model_free(graph, algorithm, mode),
    };
    Ok(Sample {
        time_s,
        actions: counts.actions(),
        planner_actions: counts.planner_actions,
        iterations: counts.iterations,
        // A DP planner on the explored graph (x1's whole component: every reachable move was
        // tried) computes the optimum itself, so its values equal G* — also where G* = +inf,
        // as on Problem 6, where it is converged too.
        converged: true,
        converged_at: None,
        initial_optimal_at: None,
        initial_optimal_time_s: None,
        goal_discovered_at: None,
        goal_discovered_time_s: None,
        path_states: counts.path_states,
        reached_goal: counts.reached_goal,
        looped: false,
        // Every planner here is exact on the discovered graph (reference mode: on the paper's
        // f64 costs), so a path found is optimal.
        path_optimal: counts.reached_goal,
    })
}

/// The timed region of a model-free row: the clock wraps
/// [`model_free_counts`] on a graph compiled before — exploration, the planner on the
/// discovered graph, its path — and the region returns counts only ([`PlanCounts`] is `Copy`).
///
/// ```
/// use truecost::experiments::deterministic::time_model_free;
/// use truecost::planning::{Algorithm, Mode};
/// use truecost::problems::GridLayout;
/// let graph = GridLayout::reference(16).unwrap().to_reference_graph();
/// let (counts, seconds) = time_model_free(&graph, Algorithm::Dijkstra, Mode::Reference);
/// assert_eq!((counts.iterations, counts.actions()), (6, 28)); // published: 6 pops, 28 actions
/// assert!(seconds >= 0.0);
/// ```
pub fn time_model_free<V: CostValue>(
    graph: &Graph<V>,
    algorithm: Algorithm,
    mode: Mode,
) -> (PlanCounts, f64) {
    timed(|| model_free_counts(graph, algorithm, mode))
}

/// Summarises the samples of one row.
fn summarise(
    run: &ProblemRun,
    row: &Row,
    samples: &[Sample],
    settings: &Settings,
    note: Option<String>,
) -> RowSummary {
    let n = samples.len() as f64;
    let f = |get: &dyn Fn(&Sample) -> f64| -> Vec<f64> { samples.iter().map(get).collect() };
    let rate = |pred: &dyn Fn(&Sample) -> bool| {
        (!samples.is_empty()).then(|| samples.iter().filter(|s| pred(s)).count() as f64 / n)
    };
    let (mean_time, std_time) = mean_std(&f(&|s| s.time_s)).unzip();
    let (mean_actions, std_actions) = mean_std(&f(&|s| s.actions as f64)).unzip();
    let (mean_iterations, std_iterations) = mean_std(&f(&|s| s.iterations as f64)).unzip();
    let opt = |get: &dyn Fn(&Sample) -> Option<f64>| -> Vec<Option<f64>> {
        samples.iter().map(get).collect()
    };
    let learning = !matches!(row, Row::ModelFree(_));
    let when = |x: Option<f64>| if learning { x } else { None };
    let total_actions: u64 = samples.iter().map(|s| s.actions).sum();
    let total_time: f64 = samples.iter().map(|s| s.time_s).sum();
    let to_f64 = |(a, b): (u64, u64)| a as f64 / b as f64;
    RowSummary {
        problem: run.id,
        algorithm: row.algorithm(),
        epsilon: row.epsilon().map(to_f64),
        epsilon_final: matches!(row, Row::EpsilonDecay { .. }).then_some(0.1),
        plan: match row {
            Row::QLearning {
                plan: PlanKind::Pi, ..
            } => Some("pi"),
            Row::ModelFree(_) => None,
            _ => Some("random"),
        },
        samples: samples.len() as u32,
        mean_time_s: mean_time,
        std_time_s: std_time,
        convergence_rate: rate(&|s| s.converged),
        mean_actions_converged: when(mean_of_present(&opt(&|s| s.converged_at.map(|a| a as f64)))),
        mean_actions,
        std_actions,
        mean_planner_actions: (!learning)
            .then(|| mean_std(&f(&|s| s.planner_actions as f64)).map(|(m, _)| m))
            .flatten(),
        mean_ns_per_action: (total_actions > 0).then(|| total_time * 1e9 / total_actions as f64),
        mean_iterations,
        std_iterations,
        shortest_path: samples.iter().map(|s| s.path_states).min(),
        longest_path: samples.iter().map(|s| s.path_states).max(),
        goal_reached_rate: rate(&|s| s.reached_goal),
        optimal_path_rate: rate(&|s| s.path_optimal),
        loops: samples.iter().filter(|s| s.looped).count() as u32,
        initial_optimal_rate: when(rate(&|s| s.initial_optimal_at.is_some())),
        mean_actions_initial_optimal: when(mean_of_present(&opt(&|s| {
            s.initial_optimal_at.map(|a| a as f64)
        }))),
        mean_time_initial_optimal_s: when(mean_of_present(&opt(&|s| s.initial_optimal_time_s))),
        goal_discovery_rate: when(rate(&|s| s.goal_discovered_at.is_some())),
        mean_actions_goal_discovered: when(mean_of_present(&opt(&|s| {
            s.goal_discovered_at.map(|a| a as f64)
        }))),
        mean_time_goal_discovered_s: when(mean_of_present(&opt(&|s| s.goal_discovered_time_s))),
        mode: settings.mode,
        seed: settings.seed,
        value_type: run.value_type,
        note,
        comparison: None,
        observed: observe(row, samples),
        exact_comparable: false,
    }
}

/// Our side of every metric the paper publishes for a row (names as in
/// `data/published/deterministic.csv`).
fn observe(row: &Row, samples: &[Sample]) -> BTreeMap<&'static str, Observed> {
    let mut o = Observations::new(samples);
    let n = o.n();
    if n == 0 {
        return o.finish();
    }
    o.time("mean_time_s", |s| Some(s.time_s));
    o.count("mean_iterations", |s| Some(s.iterations));
    o.count("mean_actions", |s| Some(s.actions));
    o.rate("convergence_rate", |s| s.converged);
    let path = samples.iter().map(|s| s.path_states as u64);
    o.put(
        "shortest_path",
        path.clone().min().map(|v| Observed::value(v, n)),
    );
    o.put("longest_path", path.max().map(|v| Observed::value(v, n)));
    let all_reached = u64::from(o.hits(|s| s.reached_goal) == n);
    o.put("goal_reached_all", Some(Observed::value(all_reached, n)));
    let any_loop = u64::from(o.hits(|s| s.looped) > 0);
    o.put("loops_any", Some(Observed::value(any_loop, n)));
    if matches!(row, Row::ModelFree(_)) {
        o.count("mean_planner_actions", |s| Some(s.planner_actions));
    } else {
        o.count("mean_actions_converged", |s| s.converged_at);
        o.count("mean_actions_goal_discovered", |s| s.goal_discovered_at);
        o.time("mean_time_goal_discovered_s", |s| s.goal_discovered_time_s);
        o.count("mean_actions_initial_optimal", |s| s.initial_optimal_at);
        o.time("mean_time_initial_optimal_s", |s| s.initial_optimal_time_s);
    }
    o.finish()
}

/// How a published deterministic metric is judged (`None`: not a metric of this table).
fn metric_kind(metric: &str) -> Option<Kind> {
    Some(match metric {
        "mean_time_s" | "mean_time_goal_discovered_s" | "mean_time_initial_optimal_s" => Kind::Time,
        "convergence_rate" => Kind::Rate,
        "shortest_path" | "longest_path" | "goal_reached_all" | "loops_any" => Kind::Extreme,
        "mean_iterations"
        | "mean_actions"
        | "mean_planner_actions"
        | "mean_actions_converged"
        | "mean_actions_goal_discovered"
        | "mean_actions_initial_optimal" => Kind::Mean,
        _ => return None,
    })
}

/// Whether row `row` on the `index`-th problem of `settings` is a pure function of settings
/// the paper published (so its counts must be `exact`): reference mode, the paper's 1000 ×
/// 3000 run; model-free planners and greedy ε = 0 always; the π rows only with the paper's 100
/// samples and the paper's problems before it in the paper's order (one digit stream is shared
/// in problem order). Every other learning row draws from our generator, not the paper's.
fn exact_comparable(row: &Row, index: usize, settings: &Settings) -> bool {
    if settings.mode != Mode::Reference || settings.episodes != 1000 || settings.max_steps != 3000 {
        return false;
    }
    match row {
        Row::ModelFree(_) => true,
        Row::QLearning {
            epsilon: (0, _),
            plan: PlanKind::Random,
        } => true,
        Row::QLearning {
            plan: PlanKind::Pi, ..
        } => {
            settings.samples == 100
                && settings.problems.len() > index
                && PAPER_PROBLEMS.len() > index
                && settings.problems[..=index] == PAPER_PROBLEMS[..=index]
        }
        _ => false,
    }
}

/// A row in words, for the summary's lines.
fn row_label(r: &RowSummary) -> String {
    match (r.algorithm, r.epsilon) {
        ("q-learning" | "q-learning-pi", Some(e)) => format!("{} ε={e}", r.algorithm),
        ("q-learning-epsilon-decay", Some(e)) => format!("{} from ε={e}", r.algorithm),
        (a, _) => a.to_string(),
    }
}

/// The published key of a row: algorithm and ε as in `data/published/deterministic.csv`.
fn published_key(r: &RowSummary) -> published::RowKey {
    let eps = match r.algorithm {
        "model-free-dijkstra" | "model-free-async-vi" | "model-free-vi" => String::new(),
        _ => r.epsilon.map_or(String::new(), |e| e.to_string()),
    };
    (
        r.problem,
        vec![
            published::KeyPart::parse(r.algorithm),
            published::KeyPart::parse(&eps),
        ],
    )
}

/// Puts the paper's published numbers beside ours: every row the
/// paper's CSV files publish gains `published` and `agreement`, and the report its closing
/// [`Summary`]. Rows the paper does not publish stay as they are.
///
/// ```
/// use truecost::experiments::deterministic::{against_published, run, Settings};
/// use truecost::planning::Mode;
/// let settings = Settings { problems: vec![16], samples: 2, mode: Mode::Reference,
///     ..Settings::default() };
/// let mut report = run(&settings, &|_| {}).unwrap();
/// let summary = against_published(&mut report, &settings).unwrap();
/// let dijkstra = report.rows.iter().find(|r| r.algorithm == "model-free-dijkstra").unwrap();
/// let verdict = &dijkstra.comparison.as_ref().unwrap().agreement["mean_actions"];
/// assert_eq!(verdict.name(), "exact");
/// assert!(summary.exact > 0 && summary.compared >= summary.exact + summary.machine);
/// ```
pub fn against_published(report: &mut Report, settings: &Settings) -> Result<Summary, DataError> {
    let data = published::deterministic()?;
    let mut summary = Summary {
        sources: data.sources.clone(),
        ..Summary::default()
    };
    for (index, &problem) in settings.problems.iter().enumerate() {
        let mut rows: Vec<&mut RowSummary> = report
            .rows
            .iter_mut()
            .filter(|r| r.problem == problem)
            .collect();
        for (r, row) in rows.iter_mut().zip(PAPER_ROWS.iter()) {
            let Some(values) = data.rows.get(&published_key(r)) else {
                continue;
            };
            r.exact_comparable = exact_comparable(row, index, settings);
            let observed = &r.observed;
            r.comparison = Some(published::compare_row(
                values,
                metric_kind,
                |m| observed.get(m).cloned(),
                r.exact_comparable,
            ));
        }
        let dijkstra = rows
            .iter()
            .find(|r| r.algorithm == "model-free-dijkstra")
            .and_then(|r| r.comparison.as_ref())
            .map(published::Comparison::run_time);
        if let Some(d) = dijkstra {
            for c in rows.iter_mut().filter_map(|r| r.comparison.as_mut()) {
                c.relate_time(d);
            }
        }
        for r in rows.iter() {
            if let Some(c) = &r.comparison {
                summary.add(&format!("problem {}, {}", r.problem, row_label(r)), c);
            }
        }
    }
    report.against_published = Some(summary.clone());
    Ok(summary)
}

/// The number of sample runs an experiment performs (for a progress bar).
pub fn total_runs(settings: &Settings) -> u64 {
    settings.problems.len() as u64 * PAPER_ROWS.len() as u64 * u64::from(settings.samples)
}

/// Runs the experiment. `progress(k)` is called (from any thread) each time `k` more sample
/// runs have finished.
///
/// ```
/// use truecost::experiments::deterministic::{run, Settings};
/// use truecost::planning::Mode;
/// // Problem 16 is tiny: its greedy episodes are short, 100 steps per episode suffice.
/// let settings = Settings { problems: vec![16], samples: 2, mode: Mode::Reference,
///     max_steps: 100, ..Settings::default() };
/// let report = run(&settings, &|_| {}).unwrap();
/// assert_eq!(report.rows.len(), 11);
/// let greedy = &report.rows[0];
/// // The paper's code: greedy Q-learning converges in episode 244 after 1000 actions.
/// assert_eq!((greedy.mean_iterations, greedy.mean_actions), (Some(244.0), Some(1000.0)));
/// ```
pub fn run(
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Report, ExperimentError> {
    settings.validate()?;
    in_pool(settings.threads, || run_validated(settings, progress))?
}

/// The whole run with memory bounded by one group of rows ([`row_groups`]): the π rows (one
/// shared digit stream, problems in order) beside the other rows, each row summarised as soon
/// as its samples are in, its samples then dropped.
fn run_validated(
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Report, ExperimentError> {
    let runs = prepare_all(settings)?;
    let pi_row = pi_row();
    let units: Vec<(usize, usize)> = (0..runs.len())
        .flat_map(|p| {
            PAPER_ROWS
                .iter()
                .enumerate()
                .filter(|(_, row)| !row.is_pi())
                .map(move |(r, _)| (p, r))
        })
        .collect();
    let (pi, others) = rayon::join(
        || -> Result<Vec<RowSummary>, ExperimentError> {
            let mut out = Vec::with_capacity(runs.len());
            pi_chain(&runs, settings, progress, |p, samples| {
                out.push(row_summary(
                    &runs[p],
                    &PAPER_ROWS[pi_row],
                    &samples,
                    settings,
                ));
            })?;
            Ok(out)
        },
        || -> Result<Vec<RowSummary>, ExperimentError> {
            let samples = settings.samples;
            let mut out = Vec::with_capacity(units.len());
            for group in row_groups(units.len(), samples) {
                let group = &units[group];
                let count = group.len() as u64 * u64::from(samples);
                let results = (0..count)
                    .into_par_iter()
                    .map(|i| -> Result<Option<Sample>, ExperimentError> {
                        let (p, r) = group[(i / u64::from(samples)) as usize];
                        let k = (i % u64::from(samples)) as u32;
                        let (run, row) = (&runs[p], &PAPER_ROWS[r]);
                        let s = if skip(run, row) {
                            None
                        } else {
                            Some(run_sample(run, r, row, k, settings, None)?)
                        };
                        progress(1);
                        Ok(s)
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                let mut results = results.into_iter();
                for &(p, r) in group {
                    let row: Vec<Sample> =
                        results.by_ref().take(samples as usize).flatten().collect();
                    out.push(row_summary(&runs[p], &PAPER_ROWS[r], &row, settings));
                }
            }
            Ok(out)
        },
    );
    let (mut pi, mut others) = (pi?.into_iter(), others?.into_iter());
    let rows = (0..runs.len())
        .flat_map(|_| PAPER_ROWS.iter())
        .map(|row| {
            if row.is_pi() {
                pi.next()
            } else {
                others.next()
            }
            .expect("one summary per row")
        })
        .collect();
    Ok(report(settings, rows))
}

/// The index of the π row in [`PAPER_ROWS`].
fn pi_row() -> usize {
    PAPER_ROWS
        .iter()
        .position(Row::is_pi)
        .expect("a π row exists")
}

/// The π rows: one shared digit stream, problems in the given order, samples in order; each
/// problem's samples go to `sink(problem index, samples)` (no samples where the goal is
/// unreachable).
fn pi_chain(
    runs: &[ProblemRun],
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
    mut sink: impl FnMut(usize, Vec<Sample>),
) -> Result<(), ExperimentError> {
    let mut stream = PiStream::new();
    // Compute the digits the π runs can accept before any clock starts (a run of A
    // actions accepts A digits; skipped digits beyond this are computed on demand).
    let reachable = runs.iter().filter(|r| r.reachable).count() as u64;
    stream.prefetch(
        reachable
            .saturating_mul(u64::from(settings.samples))
            .saturating_mul(u64::from(settings.episodes))
            .saturating_mul(u64::from(settings.max_steps)),
    );
    let pi_row = pi_row();
    for (p, run) in runs.iter().enumerate() {
        if skip(run, &PAPER_ROWS[pi_row]) {
            progress(u64::from(settings.samples));
            sink(p, Vec::new());
            continue;
        }
        let samples = (0..settings.samples)
            .map(|k| {
                let s = run_sample(
                    run,
                    pi_row,
                    &PAPER_ROWS[pi_row],
                    k,
                    settings,
                    Some(&mut stream),
                );
                progress(1);
                s
            })
            .collect::<Result<Vec<_>, _>>()?;
        sink(p, samples);
    }
    Ok(())
}

fn prepare_all(settings: &Settings) -> Result<Vec<ProblemRun>, ExperimentError> {
    settings
        .problems
        .par_iter()
        .map(|&id| prepare(id, settings))
        .collect()
}

/// Every `(problem index, row index, sample)` except the π rows, in report order.
fn tasks(problems: usize, samples: u32) -> Vec<(usize, usize, u32)> {
    (0..problems)
        .flat_map(|p| {
            PAPER_ROWS
                .iter()
                .enumerate()
                .filter(|(_, row)| !row.is_pi())
                .flat_map(move |(r, _)| (0..samples).map(move |k| (p, r, k)))
        })
        .collect()
}

fn skip(run: &ProblemRun, row: &Row) -> bool {
    !run.reachable && !matches!(row, Row::ModelFree(_))
}

/// The π rows' samples per problem (`None`: another shard runs them) and every task's sample
/// (`None`: another shard's task; `Some(None)`: not run, the goal is unreachable). `part`
/// selects a shard's share: task `t` (in [`tasks`] order) when
/// `part.owns(t)`, and the π rows — one chain sharing one digit stream, so indivisible —
/// on shard 1.
#[allow(clippy::type_complexity)]
fn compute(
    runs: &[ProblemRun],
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
    part: Option<Part>,
) -> Result<(Option<Vec<Vec<Sample>>>, Vec<Option<Option<Sample>>>), ExperimentError> {
    let tasks = tasks(runs.len(), settings.samples);
    let (pi_results, results) = rayon::join(
        || -> Result<Option<Vec<Vec<Sample>>>, ExperimentError> {
            if part.is_some_and(|p| !p.owns(0)) {
                return Ok(None);
            }
            let mut out = Vec::with_capacity(runs.len());
            pi_chain(runs, settings, progress, |_, samples| out.push(samples))?;
            Ok(Some(out))
        },
        || -> Result<Vec<Option<Option<Sample>>>, ExperimentError> {
            tasks
                .par_iter()
                .enumerate()
                .map(|(t, &(p, r, k))| {
                    if part.is_some_and(|part| !part.owns(t as u64)) {
                        return Ok(None);
                    }
                    let run = &runs[p];
                    let row = &PAPER_ROWS[r];
                    let s = if skip(run, row) {
                        None
                    } else {
                        Some(run_sample(run, r, row, k, settings, None)?)
                    };
                    progress(1);
                    Ok(Some(s))
                })
                .collect()
        },
    );
    Ok((pi_results?, results?))
}

/// The report from every sample: the π rows' per problem and the tasks' in [`tasks`] order.
fn assemble(
    runs: &[ProblemRun],
    settings: &Settings,
    pi_results: Vec<Vec<Sample>>,
    results: Vec<Option<Sample>>,
) -> Report {
    let mut rows = Vec::new();
    let mut next = results.into_iter();
    for (p, run) in runs.iter().enumerate() {
        for row in PAPER_ROWS.iter() {
            let samples: Vec<Sample> = if row.is_pi() {
                pi_results[p].clone()
            } else {
                (0..settings.samples)
                    .filter_map(|_| next.next().expect("one result per task"))
                    .collect()
            };
            rows.push(row_summary(run, row, &samples, settings));
        }
    }
    report(settings, rows)
}

/// A row's summary (with the note of a row not run).
fn row_summary(run: &ProblemRun, row: &Row, samples: &[Sample], settings: &Settings) -> RowSummary {
    let note = skip(run, row)
        .then(|| "not run: the goal is unreachable from x1 (as in the paper's code)".into());
    summarise(run, row, samples, settings, note)
}

/// The report of the rows' summaries.
fn report(settings: &Settings, rows: Vec<RowSummary>) -> Report {
    Report {
        mode: settings.mode,
        model: settings.model(),
        seed: settings.seed,
        samples: settings.samples,
        episodes: settings.episodes,
        max_steps: settings.max_steps,
        problems: settings.problems.clone(),
        rows,
        against_published: None,
    }
}

/// The format tag of a shard file of `reproduce deterministic`.
pub const SHARD_FORMAT: &str = "truecost-reproduce-deterministic-shard/1";

/// The settings a shard shares with the other shards of its run (threads aside), and the build.
fn fingerprint(settings: &Settings) -> serde_json::Value {
    serde_json::json!({
        "tool": format!("truecost {}", env!("CARGO_PKG_VERSION")),
        "commit": option_env!("TRUECOST_GIT_COMMIT").unwrap_or("unknown"),
        "problems": settings.problems,
        "samples": settings.samples,
        "seed": settings.seed,
        "mode": settings.mode,
        "step_cost": settings.step_cost,
        "episodes": settings.episodes,
        "max_steps": settings.max_steps,
    })
}

/// The number of sample runs shard `part` performs (for its progress bar).
pub fn shard_runs(settings: &Settings, part: Part) -> u64 {
    let owned = owned(task_count(settings), part);
    let pi = if part.owns(0) {
        settings.problems.len() as u64 * u64::from(settings.samples)
    } else {
        0
    };
    owned + pi
}

/// The number of sample runs outside the π rows (the shard files' sites but one).
fn task_count(settings: &Settings) -> u64 {
    let rows = PAPER_ROWS.iter().filter(|r| !r.is_pi()).count() as u64;
    settings.problems.len() as u64 * rows * u64::from(settings.samples)
}

/// `reproduce deterministic --shard K/N`: runs the sample runs `t` (every
/// `(problem, row, sample)` but the π rows, in report order) with `t mod N = K − 1`, and the
/// π rows on shard 1 (one digit stream shared in problem order: indivisible), and returns the
/// shard file's text. [`merge`] combines the N files into the report of [`run`]; every number,
/// the times included, is the one a shard measured.
///
/// ```
/// use truecost::claims::shard::Part;
/// use truecost::experiments::deterministic::{merge, run, run_shard, Settings};
/// use truecost::planning::Mode;
/// let settings = Settings { problems: vec![16], samples: 2, mode: Mode::Reference,
///     max_steps: 100, ..Settings::default() };
/// let files: Vec<(String, String)> = (1..=2)
///     .map(|k| (format!("{k}"), run_shard(&settings, Part::parse(&format!("{k}/2")).unwrap(), &|_| {}).unwrap()))
///     .collect();
/// let (merged, merged_settings) = merge(&files).unwrap();
/// let whole = run(&settings, &|_| {}).unwrap();
/// assert_eq!(merged_settings, settings);
/// assert_eq!(merged.rows.len(), whole.rows.len());
/// for (a, b) in merged.rows.iter().zip(&whole.rows) {
///     assert_eq!((a.mean_actions, a.mean_iterations), (b.mean_actions, b.mean_iterations));
/// }
/// ```
pub fn run_shard(
    settings: &Settings,
    part: Part,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<String, ExperimentError> {
    settings.validate()?;
    check_shard_size(task_count(settings) + 1, part)?;
    let watch = Stopwatch::start();
    let (pi, results) = in_pool(settings.threads, || -> Result<_, ExperimentError> {
        let runs = prepare_all(settings)?;
        compute(&runs, settings, progress, Some(part))
    })??;
    let mut entries = vec![Entry {
        site: "pi rows".into(),
        value: pi.as_ref().map(encode),
    }];
    for (t, r) in results.iter().enumerate() {
        entries.push(Entry {
            site: format!("sample run {t}"),
            value: r.as_ref().map(encode),
        });
    }
    Ok(ShardFile {
        part,
        fingerprint: fingerprint(settings),
        entries,
        seconds: watch.seconds(),
    }
    .to_json(SHARD_FORMAT))
}

/// A value a shard records, as JSON text.
fn encode<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("serialisable")
}

/// `reproduce merge` of deterministic shard files `(name, text)`: the
/// report of [`run`] with the settings the shards ran (every shard present once, all of one
/// run and build). The problems are prepared again (compiled, their oracle solved: no clock);
/// no sample is rerun.
pub fn merge(files: &[(String, String)]) -> Result<(Report, Settings), String> {
    let shards = shard::read_complete_set(files, SHARD_FORMAT)?;
    let fp = shard::Fingerprint(&shards[0].fingerprint);
    let settings = Settings {
        problems: fp.field("problems")?,
        samples: fp.field("samples")?,
        seed: fp.field("seed")?,
        mode: clap::ValueEnum::from_str(fp.text("mode"), false).map_err(|_| fp.bad("mode"))?,
        step_cost: clap::ValueEnum::from_str(fp.text("step_cost"), false)
            .map_err(|_| fp.bad("step cost"))?,
        episodes: fp.field("episodes")?,
        max_steps: fp.field("max_steps")?,
        threads: None,
    };
    fp.confirm(&fingerprint(&settings))?;
    settings.validate().map_err(|e| e.to_string())?;
    let count = task_count(&settings) as usize;
    if shards[0].entries.len() != count + 1 {
        return Err(format!(
            "the shards record {} sites, these settings have {}",
            shards[0].entries.len(),
            count + 1
        ));
    }
    let runs = in_pool(None, || prepare_all(&settings))
        .map_err(|e| e.to_string())?
        .map_err(|e| e.to_string())?;
    // Site j's value: the one shard that recorded it.
    let owner = |j: usize| -> Result<&str, String> {
        let mut present = shards.iter().filter_map(|s| s.entries[j].value.as_deref());
        match (present.next(), present.next()) {
            (Some(v), None) => Ok(v),
            (None, _) => Err(format!(
                "site '{}': no shard ran it",
                shards[0].entries[j].site
            )),
            (Some(_), Some(_)) => Err(format!(
                "site '{}': run by two shards",
                shards[0].entries[j].site
            )),
        }
    };
    let malformed = |j: usize, e: serde_json::Error| {
        format!(
            "site '{}': malformed value ({e})",
            shards[0].entries[j].site
        )
    };
    let pi: Vec<Vec<Sample>> = serde_json::from_str(owner(0)?).map_err(|e| malformed(0, e))?;
    if pi.len() != runs.len() {
        return Err("the π rows do not cover the problems".into());
    }
    let results = (1..=count)
        .map(|j| serde_json::from_str::<Option<Sample>>(owner(j)?).map_err(|e| malformed(j, e)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((assemble(&runs, &settings, pi, results), settings))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each mode's ε-decay row runs its own schedule: the text's in exact mode, the code's in
    /// reference mode; reference constant-ε rows flip the code's coin.
    #[test]
    fn each_mode_runs_its_own_epsilon_schedule() {
        let settings = Settings::default();
        let config = |row: Row, rules| row.learning_config(&settings, rules).unwrap().unwrap();
        let decay = Row::EpsilonDecay { start: (1, 1) };
        assert_eq!(
            config(decay, Rules::Exact).epsilon,
            EpsilonSchedule::decay_to_one_tenth(Probability::ONE)
        );
        assert_eq!(
            config(decay, Rules::Reference).epsilon,
            EpsilonSchedule::CodeDecay {
                start: Probability::ONE
            }
        );
        let nine_tenths = Row::QLearning {
            epsilon: (9, 10),
            plan: PlanKind::Random,
        };
        let EpsilonSchedule::Constant(exact) = config(nine_tenths, Rules::Exact).epsilon else {
            panic!("constant ε expected");
        };
        assert_eq!((exact.numerator(), exact.denominator()), (9, 10));
        let EpsilonSchedule::Constant(code) = config(nine_tenths, Rules::Reference).epsilon else {
            panic!("constant ε expected");
        };
        // ⌈0.9·2^53⌉ = 8106479329266893 (0.9 as an f64 is 0.90000000000000002220…).
        assert_eq!(
            (code.numerator(), code.denominator()),
            (8_106_479_329_266_893, 1 << 53)
        );
    }
}

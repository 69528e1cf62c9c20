//! The paper's stochastic comparison (`truecost reproduce stochastic`): stochastic Q-learning
//! over a grid of `γ × ρ × ε`, and stochastic asynchronous and synchronous value iteration, on
//! the paper's grid problems, judged against the **exact** optimum (docs/spec.md §3, §4, §7).
//!
//! # Rows
//!
//! Per problem and `γ` (in the order given): one Q-learning row per `(ρ, ε)`
//! ([`crate::learning::stochastic_q`], random exploration plan, `Q₀ = 0`,
//! [`Settings::episodes`] × [`Settings::max_steps`]), then `stochastic-async-vi` and
//! `stochastic-vi` with the reference code's rules ([`ViOptions::reference`]: values from
//! `10³⁰`, decrease only, stop when the largest change is ≤ 0.1 or after 1000 sweeps; counted
//! actions `Σ k·(k−1)` per sweep).
//!
//! # Problems, tolerance, optimum
//!
//! The learners run on the exact grid ([`exact_grid`]) with the chosen noise model: unit step
//! costs under the `relative` tolerance (scale free), Euclidean step costs 800/19 under the
//! `reference` tolerance (its ±5 units presume them). `G*` is the exact optimum
//! ([`optimum`]); every "within tolerance" is decided exactly against it
//! ([`Target`]). The VI rows run on the same exact grid rounded to `f64` under `relative`, and on
//! the reference code's grid ([`reference_grid`]: its action order, `f64` Euclidean costs and
//! probabilities) under `reference`, so that they reproduce the published sweep counts; their
//! values are compared with the same exact `G*` (state ids agree on every paper grid).
//!
//! # Samples and reproducibility
//!
//! Sample `k` of the `r`-th learning row of the grid (`r` counts `γ`-major, then `ρ`, then `ε`,
//! in the order listed) on problem `p` draws from `sample_rng(seed, p·2³² + r·2²⁴ + k)`; the
//! greedy simulation after the run continues the same generator. So every number but the times
//! is a pure function of the settings, whatever the number of threads.

use rayon::prelude::*;
use serde::Serialize;

use std::collections::BTreeMap;

use super::clock::Stopwatch;
use super::deterministic::stream;
use super::published::{self, Comparison, DataError, Kind, Observations, Observed, Summary};
use super::runs::{check_shard_size, in_pool, owned, row_groups, RunError, RunSettings};
use super::stats::{mean_of_present, mean_std};
use crate::claims::shard::{self, Entry, Part, ShardFile};
use crate::learning::plan::{sample_rng, EpsilonSchedule, Plan, Probability, ProbabilityError};
use crate::learning::q_learning::{Event, LearningError, Milestone};
use crate::learning::stochastic_q::{
    optimal_action_flags, LearningRate, RateError, StochasticQConfig, StochasticQLearner, Target,
    Tolerance,
};
use crate::problems::{StepCost, PAPER_PROBLEMS};
use crate::stochastic::grid::{exact_grid, reference_grid, GridError};
use crate::stochastic::policy_iteration::{optimum, Optimum};
use crate::stochastic::value_iteration::{value_iteration_f64, FloatModel, Schedule, ViOptions};
use crate::stochastic::{decimal, NoiseModel, Predictability, StochasticError, StochasticProblem};
use crate::value::{parse_rational, Rational};

/// A learning rate as listed: a constant `ρ` or the decay `1/n^ω`.
#[derive(Clone, Debug, PartialEq)]
pub struct RateSpec {
    /// The text as given (`0.99`, `1/n^0.8`).
    pub text: String,
    /// The rate.
    pub rate: LearningRate,
}

impl RateSpec {
    /// Parses `ρ` (a decimal or fraction in `(0, 1]`) or `1/n^ω` (`ω ∈ (0.5, 1]`).
    ///
    /// ```
    /// use truecost::experiments::stochastic::RateSpec;
    /// use truecost::learning::stochastic_q::LearningRate;
    /// assert_eq!(RateSpec::parse("0.99").unwrap().rate, LearningRate::Constant(0.99));
    /// assert_eq!(RateSpec::parse("1/n^0.8").unwrap().rate, LearningRate::Decay(0.8));
    /// assert!(RateSpec::parse("1.5").is_err());
    /// assert!(RateSpec::parse("1/n^0.4").is_err());
    /// // Checked on the f64 the learner runs with, and printed as it runs.
    /// assert!(RateSpec::parse("1/n^0.50000000000000001").is_err());
    /// assert!(RateSpec::parse("1e-400").is_err());
    /// assert_eq!(RateSpec::parse("0.5000000000000000000000001").unwrap().text, "0.5");
    /// ```
    pub fn parse(text: &str) -> Result<Self, ExperimentError> {
        let t = text.trim();
        let rate = if let Some(w) = t.strip_prefix("1/n^") {
            let omega = parse_rational(w).map_err(|e| ExperimentError::Parse {
                what: "omega",
                text: w.into(),
                message: e.to_string(),
            })?;
            LearningRate::decay(&omega)?
        } else {
            let rho = parse_rational(t).map_err(|e| ExperimentError::Parse {
                what: "rho",
                text: t.into(),
                message: e.to_string(),
            })?;
            LearningRate::constant(&rho)?
        };
        // The text printed is what runs: the input when its f64 prints back as the same exact
        // number (0.99, 1/n^0.8), else the f64's shortest decimal.
        let (value, prefix) = match rate {
            LearningRate::Constant(r) => (r, ""),
            LearningRate::Decay(w) => (w, "1/n^"),
        };
        let shortest = format!("{value:?}");
        let given = parse_rational(t.strip_prefix("1/n^").unwrap_or(t)).ok();
        let text = if given == parse_rational(&shortest).ok() {
            t.to_string()
        } else {
            format!("{prefix}{shortest}")
        };
        Ok(RateSpec { text, rate })
    }
}

/// An ε as listed: a constant or `decay` (linear from 1 to 0.1 over the episodes).
#[derive(Clone, Debug, PartialEq)]
pub struct EpsilonSpec {
    /// The text as given.
    pub text: String,
    /// The schedule.
    pub schedule: EpsilonSchedule,
}

impl EpsilonSpec {
    /// Parses `ε ∈ [0, 1]` or `decay`.
    ///
    /// ```
    /// use truecost::experiments::stochastic::EpsilonSpec;
    /// assert!(EpsilonSpec::parse("0.9").is_ok());
    /// assert!(EpsilonSpec::parse("decay").is_ok());
    /// assert!(EpsilonSpec::parse("1.2").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, ExperimentError> {
        let t = text.trim();
        let schedule = if t == "decay" {
            EpsilonSchedule::decay_to_one_tenth(Probability::ONE)
        } else {
            let e = parse_rational(t).map_err(|e| ExperimentError::Parse {
                what: "epsilon",
                text: t.into(),
                message: e.to_string(),
            })?;
            EpsilonSchedule::Constant(Probability::new("ε", &e)?)
        };
        Ok(EpsilonSpec {
            text: t.into(),
            schedule,
        })
    }
}

/// What to run.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Problem ids.
    pub problems: Vec<usize>,
    /// `γ` values.
    pub gammas: Vec<Predictability>,
    /// Learning rates.
    pub rhos: Vec<RateSpec>,
    /// Exploration rates.
    pub epsilons: Vec<EpsilonSpec>,
    /// Samples per learning row.
    pub samples: u32,
    /// The master seed.
    pub seed: u64,
    /// The noise model.
    pub noise: NoiseModel,
    /// The tolerance of "learnt".
    pub tolerance: Tolerance,
    /// Episodes per run.
    pub episodes: u32,
    /// Steps per episode.
    pub max_steps: u32,
    /// Worker threads (`None`: rayon's default).
    pub threads: Option<usize>,
}

/// The default `γ` values (each affordable in minutes on two cores).
pub const DEFAULT_GAMMAS: [&str; 3] = ["0.999", "0.99", "0.9"];
/// The default learning rates.
pub const DEFAULT_RHOS: [&str; 2] = ["0.99", "1/n^0.8"];
/// The default exploration rates.
pub const DEFAULT_EPSILONS: [&str; 2] = ["0.9", "decay"];

impl Default for Settings {
    /// The paper's 16 problems, [`DEFAULT_GAMMAS`] × [`DEFAULT_RHOS`] × [`DEFAULT_EPSILONS`],
    /// 10 samples, 3000 episodes × 3000 steps, paper noise, relative tolerance, seed 0.
    fn default() -> Self {
        Settings {
            problems: PAPER_PROBLEMS.to_vec(),
            gammas: DEFAULT_GAMMAS
                .iter()
                .map(|g| Predictability::parse(g).expect("valid"))
                .collect(),
            rhos: DEFAULT_RHOS
                .iter()
                .map(|r| RateSpec::parse(r).expect("valid"))
                .collect(),
            epsilons: DEFAULT_EPSILONS
                .iter()
                .map(|e| EpsilonSpec::parse(e).expect("valid"))
                .collect(),
            samples: 10,
            seed: 0,
            noise: NoiseModel::Paper,
            tolerance: Tolerance::Relative,
            episodes: 3000,
            max_steps: 3000,
            threads: None,
        }
    }
}

/// The most learning rows per problem (`|γ|·|ρ|·|ε|`, the generator stream has 8 bits for it).
pub const MAX_LEARNING_ROWS: usize = 256;

/// Why an experiment cannot run. Every message is one line.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    /// A bad common setting (problems, samples, run length, threads).
    #[error(transparent)]
    Run(#[from] RunError),
    /// A grid could not be built.
    #[error(transparent)]
    Grid(#[from] GridError),
    /// A stochastic input or computation failed.
    #[error(transparent)]
    Stochastic(#[from] StochasticError),
    /// An empty list.
    #[error("no {0} given")]
    Empty(&'static str),
    /// A value listed twice (the same rows would run twice).
    #[error("{0} {1} is listed twice")]
    Duplicate(&'static str, String),
    /// Too many learning rows.
    #[error("|gammas| x |rhos| x |epsilons| = {0} exceeds {MAX_LEARNING_ROWS} learning rows per problem")]
    TooManyRows(usize),
    /// Text that is not a number.
    #[error("{what} {text:?}: {message}")]
    Parse {
        /// The parameter.
        what: &'static str,
        /// The text.
        text: String,
        /// Why.
        message: String,
    },
    /// A bad learning rate.
    #[error(transparent)]
    Rate(#[from] RateError),
    /// A bad ε.
    #[error(transparent)]
    Probability(#[from] ProbabilityError),
    /// A bad learning parameter.
    #[error(transparent)]
    Learning(#[from] LearningError),
}

impl Settings {
    /// Checks every parameter (one clear error for the first bad one).
    pub fn validate(&self) -> Result<(), ExperimentError> {
        RunSettings {
            problems: &self.problems,
            samples: self.samples,
            episodes: self.episodes,
            max_steps: self.max_steps,
            threads: self.threads,
        }
        .validate()?;
        for (list, name) in [
            (self.gammas.len(), "gamma"),
            (self.rhos.len(), "rho"),
            (self.epsilons.len(), "epsilon"),
        ] {
            if list == 0 {
                return Err(ExperimentError::Empty(name));
            }
        }
        for (i, g) in self.gammas.iter().enumerate() {
            if self.gammas[..i].contains(g) {
                return Err(ExperimentError::Duplicate("gamma", g.to_string()));
            }
        }
        let rows = self.gammas.len() * self.rhos.len() * self.epsilons.len();
        if rows > MAX_LEARNING_ROWS {
            return Err(ExperimentError::TooManyRows(rows));
        }
        for e in &self.epsilons {
            e.schedule.validate(self.episodes)?;
        }
        Ok(())
    }

    fn step_cost(&self) -> StepCost {
        match self.tolerance {
            Tolerance::Relative => StepCost::Unit,
            Tolerance::Reference => StepCost::Euclidean,
        }
    }

    /// The model in words, for every output.
    pub fn model(&self) -> String {
        format!(
            "noise {}; tolerance {}; {} step costs; judged against the exact optimum G* (policy iteration, exact rational solves); Q-learning in f64, random exploration plan, Q0 = 0",
            self.noise.describe(),
            self.tolerance.describe(),
            match self.step_cost() {
                StepCost::Unit => "unit",
                StepCost::Euclidean => "Euclidean (800/19)",
            }
        )
    }
}

/// One row of the result: a summary over the samples (VI rows: one deterministic run).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RowSummary {
    /// Problem id.
    pub problem: usize,
    /// `γ` as given.
    pub gamma: String,
    /// `q-learning`, `stochastic-async-vi` or `stochastic-vi`.
    pub algorithm: &'static str,
    /// `ρ` as given (learning rows).
    pub rho: Option<String>,
    /// `ε` as given (learning rows).
    pub epsilon: Option<String>,
    /// Samples (1 for VI).
    pub samples: u32,
    /// Exact `G*(x1)` to 9 significant digits.
    pub optimum_initial: String,
    /// Mean wall time of a run, seconds.
    pub mean_time_s: Option<f64>,
    /// Its population standard deviation.
    pub std_time_s: Option<f64>,
    /// Fraction of runs whose values came within tolerance on every tracked state.
    pub convergence_rate: Option<f64>,
    /// Mean action of convergence (over converged runs).
    pub mean_actions_converged: Option<f64>,
    /// Mean actions (VI: counted actions, docs/spec.md §7).
    pub mean_actions: Option<f64>,
    /// Their standard deviation.
    pub std_actions: Option<f64>,
    /// Mean nanoseconds per counted action: total run time over total actions,
    /// comparable across machines and languages.
    pub mean_ns_per_action: Option<f64>,
    /// Mean episodes run (VI: sweeps).
    pub mean_iterations: Option<f64>,
    /// Their standard deviation.
    pub std_iterations: Option<f64>,
    /// Fraction of runs in which `V(x1)` came within tolerance.
    pub initial_within_rate: Option<f64>,
    /// Mean first action with `V(x1)` within tolerance.
    pub mean_actions_initial_within: Option<f64>,
    /// Mean 1-based episode of it.
    pub mean_episode_initial_within: Option<f64>,
    /// Mean seconds until then.
    pub mean_time_initial_within_s: Option<f64>,
    /// Fraction of runs that entered the goal.
    pub goal_discovery_rate: Option<f64>,
    /// Mean 1-based action of the first goal entry.
    pub mean_actions_goal_discovered: Option<f64>,
    /// Mean seconds until then.
    pub mean_time_goal_discovered_s: Option<f64>,
    /// Mean final `V(x1)`.
    pub mean_value_initial: Option<f64>,
    /// Largest `|V − G*|` over tracked states, worst sample (exact, 6 significant digits).
    pub max_error: Option<String>,
    /// Shortest simulated greedy path (states, x1 and goal counted) over the samples.
    pub shortest_path: Option<u64>,
    /// Longest one (a path cut at the cap counts 100002 states).
    pub longest_path: Option<u64>,
    /// Fraction of simulations that reached the goal within the cap.
    pub goal_reached_rate: Option<f64>,
    /// Fraction of simulations that reached the goal using optimal actions only.
    pub optimal_path_rate: Option<f64>,
    /// The noise model.
    pub noise: NoiseModel,
    /// The tolerance.
    pub tolerance: Tolerance,
    /// The seed.
    pub seed: u64,
    /// Why the row was not run.
    pub note: Option<String>,
    /// With `--against-published`: `published` (metric → the paper's value) and `agreement`
    /// (metric → verdict), see [`published`].
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub comparison: Option<Comparison>,
    /// Our side of every metric the paper publishes, for the comparison.
    #[serde(skip)]
    pub observed: BTreeMap<&'static str, Observed>,
}

/// The result of an experiment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The noise model.
    pub noise: NoiseModel,
    /// The tolerance.
    pub tolerance: Tolerance,
    /// The model in words.
    pub model: String,
    /// The seed.
    pub seed: u64,
    /// Samples per learning row.
    pub samples: u32,
    /// Episodes per run.
    pub episodes: u32,
    /// Steps per episode.
    pub max_steps: u32,
    /// Problems.
    pub problems: Vec<usize>,
    /// `γ` values as given.
    pub gammas: Vec<String>,
    /// The rows: per problem, per `γ`, learning rows then the two VIs.
    pub rows: Vec<RowSummary>,
    /// The closing counts of [`against_published`], once it ran.
    pub against_published: Option<Summary>,
}

impl RowSummary {
    /// The row's name in the paper's words, as every rendering labels it.
    pub fn label(&self) -> String {
        match self.algorithm {
            "q-learning" => format!(
                "Q-learning (ρ={}, ε={})",
                self.rho.as_deref().unwrap_or("?"),
                self.epsilon.as_deref().unwrap_or("?")
            ),
            "stochastic-async-vi" => "Stochastic asynchronous VI".into(),
            "stochastic-vi" => "Stochastic synchronous VI".into(),
            other => other.into(),
        }
    }
}

impl Report {
    /// The rows of one problem at one `γ` (as given), in order: one table of a rendering.
    pub fn rows_of(&self, problem: usize, gamma: &str) -> Vec<&RowSummary> {
        self.rows
            .iter()
            .filter(|r| r.problem == problem && r.gamma == gamma)
            .collect()
    }

    /// The run's settings in one line, as every rendering's title gives them.
    pub fn settings(&self) -> String {
        format!(
            "noise {}; tolerance {}; seed {}; {} samples per row; {} episodes × {} steps; problems {}; gammas {}",
            self.noise.name(),
            self.tolerance.name(),
            self.seed,
            self.samples,
            self.episodes,
            self.max_steps,
            super::runs::comma_list(&self.problems),
            self.gammas.join(",")
        )
    }
}

/// A problem at one `γ`, with its exact optimum.
struct Prepared {
    id: usize,
    gamma: usize,
    problem: StochasticProblem,
    cost: Vec<f64>,
    optimum: Optimum,
    target: Target,
    optimal: Vec<bool>,
    reachable: bool,
}

fn prepare(id: usize, gamma: usize, settings: &Settings) -> Result<Prepared, ExperimentError> {
    let problem = exact_grid(
        id,
        settings.step_cost(),
        settings.noise,
        &settings.gammas[gamma],
    )?;
    let optimum = optimum(&problem)?;
    let target = Target::new(&problem, &optimum, settings.tolerance);
    let optimal = optimal_action_flags(&problem, &optimum);
    let cost = FloatModel::nearest(&problem).cost;
    let reachable = matches!(
        optimum.cost_to_go(problem.initial()),
        crate::value::Extended::Finite(_)
    );
    Ok(Prepared {
        id,
        gamma,
        problem,
        cost,
        optimum,
        target,
        optimal,
        reachable,
    })
}

/// One learning sample's measurements.
#[derive(Clone, Debug, PartialEq)]
struct Sample {
    time_s: f64,
    actions: u64,
    episodes: u32,
    converged_at: Option<u64>,
    initial_at: Option<u64>,
    initial_episode: Option<u32>,
    initial_time_s: Option<f64>,
    goal_at: Option<u64>,
    goal_time_s: Option<f64>,
    value_initial: f64,
    max_error: Rational,
    path_states: u64,
    reached_goal: bool,
    path_optimal: bool,
}

fn learn_sample(
    prepared: &Prepared,
    config: &StochasticQConfig,
    seed: u64,
    row: usize,
    k: u32,
) -> Result<Sample, ExperimentError> {
    let rng = sample_rng(seed, stream(prepared.id, row, k));
    let watch = Stopwatch::start();
    let mut learner = StochasticQLearner::new(
        &prepared.problem,
        &prepared.cost,
        &prepared.target,
        config,
        rng,
        Plan::Random,
    )?;
    let (mut goal_time, mut initial_time) = (None, None);
    loop {
        match learner.advance() {
            Event::Milestone(Milestone::GoalDiscovered) => goal_time = Some(watch.seconds()),
            Event::Milestone(Milestone::InitialOptimal) => initial_time = Some(watch.seconds()),
            Event::Milestone(Milestone::Converged) => {}
            Event::Finished => break,
        }
    }
    let time_s = watch.seconds();
    let outcome = learner.outcome();
    let x1 = prepared.problem.initial();
    let v = learner.cost_to_go().to_vec();
    let max_error = tracked_error(prepared, &v);
    let path = learner.simulate_greedy(Some(&prepared.optimal));
    Ok(Sample {
        time_s,
        actions: outcome.actions,
        episodes: outcome.episodes_run,
        converged_at: outcome.converged_at,
        initial_at: outcome.initial_within_at,
        initial_episode: outcome.initial_within_episode,
        initial_time_s: initial_time,
        goal_at: outcome.goal_discovered_at,
        goal_time_s: goal_time,
        value_initial: v[x1],
        max_error,
        path_states: path.states,
        reached_goal: path.reached_goal,
        path_optimal: path.optimal_actions,
    })
}

/// `max |V − G*|` over the tracked states, exactly (`f64` values are exact rationals).
fn tracked_error(prepared: &Prepared, v: &[f64]) -> Rational {
    let d = prepared.optimum.distance(prepared.problem.initial(), |x| {
        if prepared.target.is_tracked(x) {
            Rational::from_float(v[x])
        } else {
            None
        }
    });
    d.max_abs
}

fn learning_rows(settings: &Settings) -> Vec<(usize, usize, usize)> {
    let mut rows = Vec::new();
    for g in 0..settings.gammas.len() {
        for r in 0..settings.rhos.len() {
            for e in 0..settings.epsilons.len() {
                rows.push((g, r, e));
            }
        }
    }
    rows
}

/// The number of learning sample runs plus VI runs (for a progress bar).
pub fn total_runs(settings: &Settings) -> u64 {
    let per_problem = learning_rows(settings).len() as u64 * u64::from(settings.samples)
        + 2 * settings.gammas.len() as u64;
    settings.problems.len() as u64 * per_problem
}

/// Runs the experiment; `progress(k)` is called (from any thread) when `k` more runs finished.
///
/// ```
/// use truecost::experiments::stochastic::{run, Settings, RateSpec, EpsilonSpec};
/// use truecost::stochastic::Predictability;
/// let settings = Settings { problems: vec![16], gammas: vec![Predictability::parse("0.9").unwrap()],
///     rhos: vec![RateSpec::parse("0.5").unwrap()], epsilons: vec![EpsilonSpec::parse("1").unwrap()],
///     samples: 2, episodes: 20, max_steps: 200, ..Settings::default() };
/// let report = run(&settings, &|_| {}).unwrap();
/// assert_eq!(report.rows.len(), 3); // one learning row, two VIs
/// ```
pub fn run(
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Report, ExperimentError> {
    settings.validate()?;
    in_pool(settings.threads, || run_validated(settings, progress))?
}

/// The whole run with memory bounded by one group of rows ([`row_groups`]): the learning
/// rows in groups, each row summarised as soon as its samples are in, its samples then dropped;
/// the VI runs after.
fn run_validated(
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Report, ExperimentError> {
    let prepared = prepare_all(settings)?;
    let units = units(&prepared, settings);
    let rows = learning_rows(settings);
    let samples = settings.samples;
    let mut learned = Vec::with_capacity(units.len());
    for group in row_groups(units.len(), samples) {
        let group = &units[group];
        let count = group.len() as u64 * u64::from(samples);
        let results = (0..count)
            .into_par_iter()
            .map(|i| {
                let (pair, row) = group[(i / u64::from(samples)) as usize];
                let k = (i % u64::from(samples)) as u32;
                let s = learning_task(&prepared[pair], row, k, settings)?;
                progress(1);
                Ok(s)
            })
            .collect::<Result<Vec<_>, ExperimentError>>()?;
        let mut results = results.into_iter();
        for &(pair, row) in group {
            let row_samples: Vec<Sample> =
                results.by_ref().take(samples as usize).flatten().collect();
            let (_, r, e) = rows[row];
            learned.push((
                pair,
                summarise(&prepared[pair], r, e, &row_samples, settings),
            ));
        }
    }
    let vi = vi_runs(&prepared, settings, progress, None)?;
    let mut learned = learned.into_iter().peekable();
    let mut out = Vec::new();
    for (i, (pr, v)) in prepared.iter().zip(vi).enumerate() {
        let [a, s] = v.expect("the whole run runs every VI");
        while let Some((_, row)) = learned.next_if(|(pair, _)| *pair == i) {
            out.push(row);
        }
        out.push(vi_summary(pr, Schedule::Asynchronous, a, settings));
        out.push(vi_summary(pr, Schedule::Synchronous, s, settings));
    }
    Ok(report(settings, out))
}

fn prepare_all(settings: &Settings) -> Result<Vec<Prepared>, ExperimentError> {
    let pairs: Vec<(usize, usize)> = settings
        .problems
        .iter()
        .flat_map(|&p| (0..settings.gammas.len()).map(move |g| (p, g)))
        .collect();
    pairs
        .par_iter()
        .map(|&(p, g)| prepare(p, g, settings))
        .collect()
}

/// Every `(pair, learning row)`, in report order.
fn units(prepared: &[Prepared], settings: &Settings) -> Vec<(usize, usize)> {
    let rows = learning_rows(settings);
    prepared
        .iter()
        .enumerate()
        .flat_map(|(i, pr)| {
            rows.iter()
                .enumerate()
                .filter(move |(_, t)| t.0 == pr.gamma)
                .map(move |(row, _)| (i, row))
        })
        .collect()
}

/// The number of learning sample runs (the shard files' sites but the VI runs').
fn task_count(settings: &Settings) -> u64 {
    settings.problems.len() as u64
        * learning_rows(settings).len() as u64
        * u64::from(settings.samples)
}

/// Sample `k` of learning row `row` on a prepared pair (`None`: not run, the goal is
/// unreachable).
fn learning_task(
    pr: &Prepared,
    row: usize,
    k: u32,
    settings: &Settings,
) -> Result<Option<Sample>, ExperimentError> {
    if !pr.reachable {
        return Ok(None);
    }
    let (_, r, e) = learning_rows(settings)[row];
    let config = StochasticQConfig {
        episodes: settings.episodes,
        max_steps: settings.max_steps,
        rate: settings.rhos[r].rate,
        epsilon: settings.epsilons[e].schedule.clone(),
        initial_value: 0.0,
    };
    Ok(Some(learn_sample(pr, &config, settings.seed, row, k)?))
}

/// Every pair's two VI runs (`None`: another shard's, pair `i` belonging to `part` when
/// `part.owns(i)`).
#[allow(clippy::type_complexity)]
fn vi_runs(
    prepared: &[Prepared],
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
    part: Option<Part>,
) -> Result<Vec<Option<[ViMeasured; 2]>>, ExperimentError> {
    prepared
        .par_iter()
        .enumerate()
        .map(
            |(i, pr)| -> Result<Option<[ViMeasured; 2]>, ExperimentError> {
                if part.is_some_and(|p| !p.owns(i as u64)) {
                    return Ok(None);
                }
                let a = vi_measure(pr, Schedule::Asynchronous, settings)?;
                progress(1);
                let s = vi_measure(pr, Schedule::Synchronous, settings)?;
                progress(1);
                Ok(Some([a, s]))
            },
        )
        .collect()
}

/// Every learning task's sample (`None`: another shard's; `Some(None)`: not run, the goal is
/// unreachable) and every pair's two VI runs (`None`: another shard's). `part` selects a
/// shard's share: task `t` when `part.owns(t)`, pair `i`'s VIs when
/// `part.owns(i)`.
#[allow(clippy::type_complexity)]
fn compute(
    prepared: &[Prepared],
    settings: &Settings,
    progress: &(dyn Fn(u64) + Sync),
    part: Option<Part>,
) -> Result<(Vec<Option<Option<Sample>>>, Vec<Option<[ViMeasured; 2]>>), ExperimentError> {
    let samples = settings.samples;
    let tasks: Vec<(usize, usize)> = units(prepared, settings);
    let count = tasks.len() as u64 * u64::from(samples);
    let results: Vec<Option<Option<Sample>>> = (0..count)
        .into_par_iter()
        .map(|t| -> Result<Option<Option<Sample>>, ExperimentError> {
            if part.is_some_and(|p| !p.owns(t)) {
                return Ok(None);
            }
            let (i, row) = tasks[(t / u64::from(samples)) as usize];
            let k = (t % u64::from(samples)) as u32;
            let out = learning_task(&prepared[i], row, k, settings)?;
            progress(1);
            Ok(Some(out))
        })
        .collect::<Result<_, _>>()?;
    let vi = vi_runs(prepared, settings, progress, part)?;
    Ok((results, vi))
}

/// The report from every task's sample (in [`tasks`] order) and every pair's VI runs.
fn assemble(
    prepared: &[Prepared],
    settings: &Settings,
    results: Vec<Option<Sample>>,
    vi: Vec<[ViMeasured; 2]>,
) -> Report {
    let rows = learning_rows(settings);
    let mut out = Vec::new();
    let mut next = results.into_iter();
    for (pr, [a, s]) in prepared.iter().zip(vi) {
        for &(g, r, e) in rows.iter().filter(|(g, _, _)| *g == pr.gamma) {
            debug_assert_eq!(g, pr.gamma);
            let samples: Vec<Sample> = (0..settings.samples)
                .filter_map(|_| next.next().expect("one result per task"))
                .collect();
            out.push(summarise(pr, r, e, &samples, settings));
        }
        out.push(vi_summary(pr, Schedule::Asynchronous, a, settings));
        out.push(vi_summary(pr, Schedule::Synchronous, s, settings));
    }
    report(settings, out)
}

/// The report of the rows' summaries.
fn report(settings: &Settings, rows: Vec<RowSummary>) -> Report {
    Report {
        noise: settings.noise,
        tolerance: settings.tolerance,
        model: settings.model(),
        seed: settings.seed,
        samples: settings.samples,
        episodes: settings.episodes,
        max_steps: settings.max_steps,
        problems: settings.problems.clone(),
        gammas: settings.gammas.iter().map(gamma_text).collect(),
        rows,
        against_published: None,
    }
}

fn empty_row(pr: &Prepared, algorithm: &'static str, settings: &Settings) -> RowSummary {
    RowSummary {
        problem: pr.id,
        gamma: gamma_text(&settings.gammas[pr.gamma]),
        algorithm,
        rho: None,
        epsilon: None,
        samples: 0,
        optimum_initial: decimal(&pr.optimum.cost_to_go(pr.problem.initial()), 9),
        mean_time_s: None,
        std_time_s: None,
        convergence_rate: None,
        mean_actions_converged: None,
        mean_actions: None,
        std_actions: None,
        mean_ns_per_action: None,
        mean_iterations: None,
        std_iterations: None,
        initial_within_rate: None,
        mean_actions_initial_within: None,
        mean_episode_initial_within: None,
        mean_time_initial_within_s: None,
        goal_discovery_rate: None,
        mean_actions_goal_discovered: None,
        mean_time_goal_discovered_s: None,
        mean_value_initial: None,
        max_error: None,
        shortest_path: None,
        longest_path: None,
        goal_reached_rate: None,
        optimal_path_rate: None,
        noise: settings.noise,
        tolerance: settings.tolerance,
        seed: settings.seed,
        note: None,
        comparison: None,
        observed: BTreeMap::new(),
    }
}

fn summarise(
    pr: &Prepared,
    r: usize,
    e: usize,
    samples: &[Sample],
    settings: &Settings,
) -> RowSummary {
    let mut row = empty_row(pr, "q-learning", settings);
    row.rho = Some(settings.rhos[r].text.clone());
    row.epsilon = Some(settings.epsilons[e].text.clone());
    row.samples = samples.len() as u32;
    if !pr.reachable {
        row.note = Some("not run: the goal is unreachable from x1".into());
        return row;
    }
    let n = samples.len() as f64;
    let f = |get: &dyn Fn(&Sample) -> f64| -> Vec<f64> { samples.iter().map(get).collect() };
    let o = |get: &dyn Fn(&Sample) -> Option<f64>| -> Vec<Option<f64>> {
        samples.iter().map(get).collect()
    };
    let rate = |pred: &dyn Fn(&Sample) -> bool| {
        (!samples.is_empty()).then(|| samples.iter().filter(|s| pred(s)).count() as f64 / n)
    };
    (row.mean_time_s, row.std_time_s) = mean_std(&f(&|s| s.time_s)).unzip();
    (row.mean_actions, row.std_actions) = mean_std(&f(&|s| s.actions as f64)).unzip();
    (row.mean_iterations, row.std_iterations) = mean_std(&f(&|s| f64::from(s.episodes))).unzip();
    row.convergence_rate = rate(&|s| s.converged_at.is_some());
    row.mean_actions_converged = mean_of_present(&o(&|s| s.converged_at.map(|a| a as f64)));
    row.initial_within_rate = rate(&|s| s.initial_at.is_some());
    row.mean_actions_initial_within = mean_of_present(&o(&|s| s.initial_at.map(|a| a as f64)));
    row.mean_episode_initial_within = mean_of_present(&o(&|s| s.initial_episode.map(f64::from)));
    row.mean_time_initial_within_s = mean_of_present(&o(&|s| s.initial_time_s));
    row.goal_discovery_rate = rate(&|s| s.goal_at.is_some());
    row.mean_actions_goal_discovered = mean_of_present(&o(&|s| s.goal_at.map(|a| a as f64)));
    row.mean_time_goal_discovered_s = mean_of_present(&o(&|s| s.goal_time_s));
    row.mean_value_initial = mean_std(&f(&|s| s.value_initial)).map(|(m, _)| m);
    row.max_error = samples
        .iter()
        .map(|s| &s.max_error)
        .max()
        .map(|m| decimal(&crate::value::Extended::Finite(m.clone()), 6));
    row.shortest_path = samples.iter().map(|s| s.path_states).min();
    row.longest_path = samples.iter().map(|s| s.path_states).max();
    row.goal_reached_rate = rate(&|s| s.reached_goal);
    row.optimal_path_rate = rate(&|s| s.path_optimal);
    let total_actions: u64 = samples.iter().map(|s| s.actions).sum();
    let total_time: f64 = samples.iter().map(|s| s.time_s).sum();
    row.mean_ns_per_action = (total_actions > 0).then(|| total_time * 1e9 / total_actions as f64);
    row.observed = observe(samples);
    row
}

/// Our side of every metric the paper publishes for a learning row (names as in
/// `data/published/stochastic.csv`).
fn observe(samples: &[Sample]) -> BTreeMap<&'static str, Observed> {
    let mut o = Observations::new(samples);
    o.time("mean_time_s", |s| Some(s.time_s));
    o.count("mean_actions", |s| Some(s.actions));
    o.rate("convergence_rate", |s| s.converged_at.is_some());
    o.rate("initial_within_rate", |s| s.initial_at.is_some());
    o.count("mean_actions_converged", |s| s.converged_at);
    o.count("mean_actions_goal_discovered", |s| s.goal_at);
    o.time("mean_time_goal_discovered_s", |s| s.goal_time_s);
    o.count("mean_actions_initial_within", |s| s.initial_at);
    o.time("mean_time_initial_within_s", |s| s.initial_time_s);
    o.finish()
}

/// How a published stochastic metric is judged (`None`: not a metric of this table).
fn metric_kind(metric: &str) -> Option<Kind> {
    Some(match metric {
        "mean_time_s" | "mean_time_goal_discovered_s" | "mean_time_initial_within_s" => Kind::Time,
        "convergence_rate" | "initial_within_rate" => Kind::Rate,
        "mean_actions"
        | "mean_iterations"
        | "mean_actions_converged"
        | "mean_actions_goal_discovered"
        | "mean_actions_initial_within" => Kind::Mean,
        _ => return None,
    })
}

/// Puts the paper's published stochastic numbers beside ours. The
/// paper's files publish problems 1, 10 and 11 at `γ` 0.999 and 0.99 (100 samples,
/// `ρ` 0.5–0.99, `ε` 0–1) under the reference code's noise model and ±5 tolerance: rows are
/// matched on problem, `γ`, `ρ` and `ε` (as exact numbers). The VI rows are deterministic:
/// with `--noise reference --tolerance reference` their counts must be `exact`; the learning
/// rows draw from our generator and are judged statistically.
///
/// ```
/// use truecost::experiments::stochastic::{against_published, run, Settings, RateSpec, EpsilonSpec};
/// use truecost::learning::stochastic_q::Tolerance;
/// use truecost::stochastic::{NoiseModel, Predictability};
/// let settings = Settings { problems: vec![10], gammas: vec![Predictability::parse("0.999").unwrap()],
///     rhos: vec![RateSpec::parse("0.99").unwrap()], epsilons: vec![EpsilonSpec::parse("0.9").unwrap()],
///     samples: 1, episodes: 2, max_steps: 10, noise: NoiseModel::Reference,
///     tolerance: Tolerance::Reference, ..Settings::default() };
/// let mut report = run(&settings, &|_| {}).unwrap();
/// let summary = against_published(&mut report, &settings).unwrap();
/// let vi = report.rows.iter().find(|r| r.algorithm == "stochastic-async-vi").unwrap();
/// assert_eq!(vi.comparison.as_ref().unwrap().agreement["mean_actions"].name(), "exact");
/// assert!(summary.compared > 0);
/// ```
pub fn against_published(report: &mut Report, settings: &Settings) -> Result<Summary, DataError> {
    let data = published::stochastic()?;
    let mut summary = Summary {
        sources: data.sources.clone(),
        ..Summary::default()
    };
    let vi_exact =
        settings.noise == NoiseModel::Reference && settings.tolerance == Tolerance::Reference;
    for r in report.rows.iter_mut() {
        let key = (
            r.problem,
            [
                r.gamma.as_str(),
                r.algorithm,
                r.rho.as_deref().unwrap_or(""),
                r.epsilon.as_deref().unwrap_or(""),
            ]
            .map(published::KeyPart::parse)
            .to_vec(),
        );
        let Some(values) = data.rows.get(&key) else {
            continue;
        };
        let exact = r.algorithm != "q-learning" && vi_exact;
        let observed = &r.observed;
        let c = published::compare_row(values, metric_kind, |m| observed.get(m).cloned(), exact);
        let label = match (&r.rho, &r.epsilon) {
            (Some(rho), Some(e)) => format!("{} ρ={rho} ε={e}", r.algorithm),
            _ => r.algorithm.to_string(),
        };
        summary.add(
            &format!("problem {}, γ={}, {label}", r.problem, r.gamma),
            &c,
        );
        r.comparison = Some(c);
    }
    report.against_published = Some(summary.clone());
    Ok(summary)
}

/// A VI run's measurements (the timed region's output).
#[derive(Clone, Debug, PartialEq)]
struct ViMeasured {
    cost_to_go: Vec<f64>,
    sweeps: u64,
    reference_counted: u64,
    converged: bool,
    time_s: f64,
}

fn vi_measure(
    pr: &Prepared,
    schedule: Schedule,
    settings: &Settings,
) -> Result<ViMeasured, ExperimentError> {
    let options = ViOptions::reference(schedule);
    let (run, time_s) = match settings.tolerance {
        Tolerance::Relative => {
            let model = FloatModel::nearest(&pr.problem);
            let watch = Stopwatch::start();
            let run = value_iteration_f64(&pr.problem, &model, &options);
            (run, watch.seconds())
        }
        Tolerance::Reference => {
            let grid = reference_grid(pr.id, settings.noise, &settings.gammas[pr.gamma])?;
            let watch = Stopwatch::start();
            let run = value_iteration_f64(&grid.problem, &grid.float, &options);
            (run, watch.seconds())
        }
    };
    Ok(ViMeasured {
        cost_to_go: run.cost_to_go,
        sweeps: run.sweeps,
        reference_counted: run.reference_counted,
        converged: run.converged,
        time_s,
    })
}

fn vi_summary(
    pr: &Prepared,
    schedule: Schedule,
    run: ViMeasured,
    settings: &Settings,
) -> RowSummary {
    let name = match schedule {
        Schedule::Asynchronous => "stochastic-async-vi",
        Schedule::Synchronous => "stochastic-vi",
    };
    let mut row = empty_row(pr, name, settings);
    row.samples = 1;
    let time_s = run.time_s;
    let v = &run.cost_to_go;
    if v.len() != pr.problem.states() {
        row.note = Some("not run: the reference grid differs from the exact grid".into());
        return row;
    }
    let x1 = pr.problem.initial();
    let tracked: Vec<usize> = (0..v.len()).filter(|&x| pr.target.is_tracked(x)).collect();
    let all_within = tracked.iter().all(|&x| pr.target.within(x, v[x]));
    row.mean_time_s = Some(time_s);
    row.std_time_s = Some(0.0);
    row.mean_actions = Some(run.reference_counted as f64);
    row.mean_ns_per_action =
        (run.reference_counted > 0).then(|| time_s * 1e9 / run.reference_counted as f64);
    let one = |v: u64| Observed::counts(&[v]);
    row.observed.extend(
        [
            ("mean_time_s", Observed::times(&[time_s])),
            ("mean_actions", one(run.reference_counted)),
            ("mean_iterations", one(run.sweeps)),
        ]
        .into_iter()
        .filter_map(|(k, v)| v.map(|v| (k, v))),
    );
    row.std_actions = Some(0.0);
    row.mean_iterations = Some(run.sweeps as f64);
    row.std_iterations = Some(0.0);
    if !pr.reachable {
        row.note =
            Some("the goal is unreachable from x1 (G*(x1) = inf): nothing to converge to".into());
        return row;
    }
    row.convergence_rate = Some(if all_within { 1.0 } else { 0.0 });
    row.observed
        .extend(Observed::rate(u64::from(all_within), 1).map(|o| ("convergence_rate", o)));
    row.initial_within_rate = Some(if pr.target.within(x1, v[x1]) {
        1.0
    } else {
        0.0
    });
    row.mean_value_initial = Some(v[x1]);
    row.max_error = Some(decimal(
        &crate::value::Extended::Finite(tracked_error(pr, v)),
        6,
    ));
    if !run.converged {
        row.note = Some(format!(
            "stopped after {} sweeps without meeting the 0.1 stopping rule",
            run.sweeps
        ));
    }
    row
}

/// `γ` as exact decimal text when it has a finite decimal expansion (as every `γ` given as
/// decimal text has), else as a fraction.
///
/// ```
/// use truecost::experiments::stochastic::gamma_text;
/// use truecost::stochastic::Predictability;
/// assert_eq!(gamma_text(&Predictability::parse("0.999").unwrap()), "0.999");
/// assert_eq!(gamma_text(&Predictability::parse("1").unwrap()), "1");
/// assert_eq!(gamma_text(&Predictability::parse("2/3").unwrap()), "2/3");
/// ```
pub fn gamma_text(gamma: &Predictability) -> String {
    let r = gamma.value();
    let mut scaled = r.clone();
    for d in 0..40usize {
        if scaled.is_integer() {
            let digits = scaled.to_integer().to_string();
            if d == 0 {
                return digits;
            }
            let padded = format!("{digits:0>width$}", width = d + 1);
            let (int, frac) = padded.split_at(padded.len() - d);
            return format!("{int}.{frac}");
        }
        scaled *= Rational::from_integer(10.into());
    }
    gamma.to_string()
}

/// The format tag of a shard file of `reproduce stochastic`.
pub const SHARD_FORMAT: &str = "truecost-reproduce-stochastic-shard/1";

/// A learning sample as a shard records it: floats as their bits (exact), the error as `n/d`.
#[derive(serde::Serialize, serde::Deserialize)]
struct SampleRecord {
    time_s: u64,
    actions: u64,
    episodes: u32,
    converged_at: Option<u64>,
    initial_at: Option<u64>,
    initial_episode: Option<u32>,
    initial_time_s: Option<u64>,
    goal_at: Option<u64>,
    goal_time_s: Option<u64>,
    value_initial: u64,
    max_error: String,
    path_states: u64,
    reached_goal: bool,
    path_optimal: bool,
}

impl SampleRecord {
    fn of(s: &Sample) -> Self {
        SampleRecord {
            time_s: s.time_s.to_bits(),
            actions: s.actions,
            episodes: s.episodes,
            converged_at: s.converged_at,
            initial_at: s.initial_at,
            initial_episode: s.initial_episode,
            initial_time_s: s.initial_time_s.map(f64::to_bits),
            goal_at: s.goal_at,
            goal_time_s: s.goal_time_s.map(f64::to_bits),
            value_initial: s.value_initial.to_bits(),
            max_error: s.max_error.to_string(),
            path_states: s.path_states,
            reached_goal: s.reached_goal,
            path_optimal: s.path_optimal,
        }
    }

    fn sample(self) -> Option<Sample> {
        Some(Sample {
            time_s: f64::from_bits(self.time_s),
            actions: self.actions,
            episodes: self.episodes,
            converged_at: self.converged_at,
            initial_at: self.initial_at,
            initial_episode: self.initial_episode,
            initial_time_s: self.initial_time_s.map(f64::from_bits),
            goal_at: self.goal_at,
            goal_time_s: self.goal_time_s.map(f64::from_bits),
            value_initial: f64::from_bits(self.value_initial),
            max_error: self.max_error.parse().ok()?,
            path_states: self.path_states,
            reached_goal: self.reached_goal,
            path_optimal: self.path_optimal,
        })
    }
}

/// A VI run as a shard records it (floats as bits).
#[derive(serde::Serialize, serde::Deserialize)]
struct ViRecord {
    cost_to_go: Vec<u64>,
    sweeps: u64,
    reference_counted: u64,
    converged: bool,
    time_s: u64,
}

impl ViRecord {
    fn of(m: &ViMeasured) -> Self {
        ViRecord {
            cost_to_go: m.cost_to_go.iter().map(|v| v.to_bits()).collect(),
            sweeps: m.sweeps,
            reference_counted: m.reference_counted,
            converged: m.converged,
            time_s: m.time_s.to_bits(),
        }
    }

    fn measured(self) -> ViMeasured {
        ViMeasured {
            cost_to_go: self.cost_to_go.into_iter().map(f64::from_bits).collect(),
            sweeps: self.sweeps,
            reference_counted: self.reference_counted,
            converged: self.converged,
            time_s: f64::from_bits(self.time_s),
        }
    }
}

/// The settings a shard shares with the other shards of its run (threads aside), and the build.
fn fingerprint(settings: &Settings) -> serde_json::Value {
    serde_json::json!({
        "tool": format!("truecost {}", env!("CARGO_PKG_VERSION")),
        "commit": option_env!("TRUECOST_GIT_COMMIT").unwrap_or("unknown"),
        "problems": settings.problems,
        "gammas": settings.gammas.iter().map(|g| g.value().to_string()).collect::<Vec<_>>(),
        "rhos": settings.rhos.iter().map(|r| r.text.clone()).collect::<Vec<_>>(),
        "epsilons": settings.epsilons.iter().map(|e| e.text.clone()).collect::<Vec<_>>(),
        "samples": settings.samples,
        "seed": settings.seed,
        "noise": settings.noise.name(),
        "tolerance": settings.tolerance.name(),
        "episodes": settings.episodes,
        "max_steps": settings.max_steps,
    })
}

/// The number of runs shard `part` performs (for its progress bar).
pub fn shard_runs(settings: &Settings, part: Part) -> u64 {
    let pairs = settings.problems.len() as u64 * settings.gammas.len() as u64;
    owned(task_count(settings), part) + 2 * owned(pairs, part)
}

/// `reproduce stochastic --shard K/N`: runs the learning sample runs `t`
/// (every `(problem, γ, row, sample)` in report order) with `t mod N = K − 1` and the two VI
/// runs of the `(problem, γ)` pairs `i` with `i mod N = K − 1`, and returns the shard file's
/// text. [`merge`] combines the N files into the report of [`run`].
///
/// ```
/// use truecost::claims::shard::Part;
/// use truecost::experiments::stochastic::{merge, run, run_shard, Settings, RateSpec, EpsilonSpec};
/// use truecost::stochastic::Predictability;
/// let settings = Settings { problems: vec![16], gammas: vec![Predictability::parse("0.9").unwrap()],
///     rhos: vec![RateSpec::parse("0.5").unwrap()], epsilons: vec![EpsilonSpec::parse("1").unwrap()],
///     samples: 3, episodes: 20, max_steps: 200, ..Settings::default() };
/// let files: Vec<(String, String)> = (1..=2)
///     .map(|k| (format!("{k}"), run_shard(&settings, Part::parse(&format!("{k}/2")).unwrap(), &|_| {}).unwrap()))
///     .collect();
/// let (merged, _) = merge(&files).unwrap();
/// let whole = run(&settings, &|_| {}).unwrap();
/// for (a, b) in merged.rows.iter().zip(&whole.rows) {
///     assert_eq!((a.mean_actions, &a.max_error), (b.mean_actions, &b.max_error));
/// }
/// ```
pub fn run_shard(
    settings: &Settings,
    part: Part,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<String, ExperimentError> {
    settings.validate()?;
    let pairs = settings.problems.len() as u64 * settings.gammas.len() as u64;
    check_shard_size(task_count(settings) + pairs, part)?;
    let watch = Stopwatch::start();
    let (samples, vi) = in_pool(settings.threads, || -> Result<_, ExperimentError> {
        let prepared = prepare_all(settings)?;
        compute(&prepared, settings, progress, Some(part))
    })??;
    let mut entries = Vec::new();
    for (t, r) in samples.iter().enumerate() {
        entries.push(Entry {
            site: format!("sample run {t}"),
            value: r.as_ref().map(|s| {
                serde_json::to_string(&s.as_ref().map(SampleRecord::of)).expect("serialisable")
            }),
        });
    }
    for (i, v) in vi.iter().enumerate() {
        entries.push(Entry {
            site: format!("vi runs {i}"),
            value: v.as_ref().map(|[a, s]| {
                serde_json::to_string(&[ViRecord::of(a), ViRecord::of(s)]).expect("serialisable")
            }),
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

/// `reproduce merge` of stochastic shard files `(name, text)`: the report
/// of [`run`] with the settings the shards ran (every shard present once, all of one run and
/// build). The problems are prepared again (their exact optima solved: no clock); no sample
/// or VI is rerun.
pub fn merge(files: &[(String, String)]) -> Result<(Report, Settings), String> {
    let shards = shard::read_complete_set(files, SHARD_FORMAT)?;
    let fp = shard::Fingerprint(&shards[0].fingerprint);
    let texts = |key: &str| fp.field::<Vec<String>>(key);
    let settings = Settings {
        problems: fp.field("problems")?,
        gammas: texts("gammas")?
            .iter()
            .map(|g| Predictability::parse(g).map_err(|_| fp.bad("gammas")))
            .collect::<Result<_, _>>()?,
        rhos: texts("rhos")?
            .iter()
            .map(|r| RateSpec::parse(r).map_err(|_| fp.bad("rhos")))
            .collect::<Result<_, _>>()?,
        epsilons: texts("epsilons")?
            .iter()
            .map(|e| EpsilonSpec::parse(e).map_err(|_| fp.bad("epsilons")))
            .collect::<Result<_, _>>()?,
        samples: fp.field("samples")?,
        seed: fp.field("seed")?,
        noise: clap::ValueEnum::from_str(fp.text("noise"), false).map_err(|_| fp.bad("noise"))?,
        tolerance: clap::ValueEnum::from_str(fp.text("tolerance"), false)
            .map_err(|_| fp.bad("tolerance"))?,
        episodes: fp.field("episodes")?,
        max_steps: fp.field("max_steps")?,
        threads: None,
    };
    fp.confirm(&fingerprint(&settings))?;
    settings.validate().map_err(|e| e.to_string())?;
    let count = task_count(&settings) as usize;
    let pairs = settings.problems.len() * settings.gammas.len();
    if shards[0].entries.len() != count + pairs {
        return Err(format!(
            "the shards record {} sites, these settings have {}",
            shards[0].entries.len(),
            count + pairs
        ));
    }
    let prepared = in_pool(None, || prepare_all(&settings))
        .map_err(|e| e.to_string())?
        .map_err(|e| e.to_string())?;
    let owner = |j: usize| -> Result<&str, String> {
        let site = &shards[0].entries[j].site;
        let mut present = shards.iter().filter_map(|s| s.entries[j].value.as_deref());
        match (present.next(), present.next()) {
            (Some(v), None) => Ok(v),
            (None, _) => Err(format!("site '{site}': no shard ran it")),
            (Some(_), Some(_)) => Err(format!("site '{site}': run by two shards")),
        }
    };
    let malformed = |j: usize| format!("site '{}': malformed value", shards[0].entries[j].site);
    let samples = (0..count)
        .map(|j| {
            let record: Option<SampleRecord> =
                serde_json::from_str(owner(j)?).map_err(|_| malformed(j))?;
            match record {
                None => Ok(None),
                Some(r) => r.sample().map(Some).ok_or_else(|| malformed(j)),
            }
        })
        .collect::<Result<Vec<_>, String>>()?;
    let vi = (0..prepared.len())
        .map(|i| {
            let j = count + i;
            let [a, s]: [ViRecord; 2] =
                serde_json::from_str(owner(j)?).map_err(|_| malformed(j))?;
            Ok([a.measured(), s.measured()])
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok((assemble(&prepared, &settings, samples, vi), settings))
}

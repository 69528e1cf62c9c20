//! Stochastic Q-learning (docs/spec.md §3, §4): Q-learning on a [`StochasticProblem`] whose next state
//! is sampled from the noise model, with `f64` values, judged against the exact optimum.
//!
//! # The algorithm
//!
//! `Q̂` has one `f64` entry per action of the problem (global action ids,
//! [`StochasticProblem::actions`]); every entry starts at `Q₀` (0 by default). A run is `E`
//! episodes of at most `M` steps, each starting at `x1`. At a non-goal state `x` with actions a
//! step
//!
//! 1. chooses an action: with probability ε (exact coins, [`EpsilonSchedule`]) the exploration
//!    plan's action ([`Plan`]), otherwise the greedy action, the *first* minimiser of `Q̂(x, ·)`;
//! 2. samples the next state `x'` from the action's outcomes with one uniform draw
//!    ([`StochasticProblem::sample`]; an action with a single outcome draws nothing, so with
//!    `γ = 1` the generator is consumed exactly as by the deterministic engine);
//! 3. updates `Q̂(x,u) ← (1−ρ)·Q̂(x,u) + ρ·(l(x,u) + min_{u'} Q̂(x',u'))` (with `ρ = 1`: the
//!    target itself), where `min Q̂ = 0` at a goal (termination is free) and `+∞` at a state
//!    without actions;
//! 4. counts one action; the episode ends when a goal is entered, after `M` steps, or at a state
//!    without actions.
//!
//! The learning rate ([`LearningRate`]) is a constant `ρ ∈ (0, 1]` or the per-pair decay
//! `ρ(x,u) = 1/n(x,u)^ω`, `n(x,u)` the number of updates of the pair so far, this one included
//! (so the first update has `ρ = 1`). `ω` must lie in `(1/2, 1]`: exactly the range where
//! `Σ_n ρ = ∞` and `Σ_n ρ² < ∞` (the Robbins–Monro conditions under which Q-learning converges
//! with probability 1); outside it the run is refused.
//!
//! # Metrics (docs/spec.md §4) against the exact optimum
//!
//! A [`Target`] holds, per tracked state, the interval of values within the named
//! [`Tolerance`] of the exact `G*` ([`crate::stochastic::policy_iteration::optimum`]):
//! `relative` is `|V − G*| ≤ G*/10` (the paper's text, "within 10%"), `reference` is
//! `|V − G*| ≤ 5` (the reference code's ±5 cost units, meaningful with Euclidean step costs).
//! The interval's ends are exact rationals rounded *inwards* to `f64`, so the test
//! `lo ≤ V(x) ≤ hi` on an `f64` value is the exact comparison with the exact bounds.
//!
//! The **tracked states** are the non-goal states with actions and finite `G*` reachable from
//! `x1` through outcomes. As in the deterministic engine, `V(x) = min_u Q̂(x,u)` is cached and a
//! count of tracked states within tolerance is kept after every action, so:
//!
//! * `converged_at` — the first action after which every tracked state is within tolerance; the
//!   run then stops at the end of that episode (`converged`);
//! * `initial_within_at` / `initial_within_episode` — the first action (and its 1-based episode)
//!   after which `V(x1)` is within tolerance;
//! * `goal_discovered_at` — the 1-based action that first entered a goal.
//!
//! [`StochasticQLearner::simulate_greedy`] then runs the learnt greedy policy from `x1` with
//! sampled outcomes (capped at [`GREEDY_SIMULATION_CAP`] steps). The learner never reads a
//! clock: [`StochasticQLearner::advance`] returns at each milestone, for a runner to time; it
//! reuses the deterministic engine's [`Milestone`]s, where `InitialOptimal` means "`V(x1)`
//! within tolerance" and `Converged` "every tracked state within tolerance".

use num_traits::{One, Signed, ToPrimitive};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::plan::{explore, EpsilonSchedule, Epsilons, Plan, Probability};
use super::q_learning::{Event, LearningError, Milestone};
use crate::stochastic::policy_iteration::Optimum;
use crate::stochastic::StochasticProblem;
use crate::value::{Extended, Rational};

/// The cap on the steps of one greedy simulation (the paper's code stops at 100001).
pub const GREEDY_SIMULATION_CAP: u64 = 100_001;

/// How close to `G*` counts as learnt (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default, clap::ValueEnum, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Tolerance {
    /// `|V − G*| ≤ G*/10` (the paper's text: within 10%).
    #[default]
    Relative,
    /// `|V − G*| ≤ 5` cost units (the reference code, with Euclidean step costs).
    Reference,
}

impl Tolerance {
    /// The name used on the command line and in every output.
    pub fn name(self) -> &'static str {
        match self {
            Tolerance::Relative => "relative",
            Tolerance::Reference => "reference",
        }
    }

    /// A one-line description for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Tolerance::Relative => "relative (|V - G*| <= 10% of G*, paper text)",
            Tolerance::Reference => {
                "reference (|V - G*| <= 5 cost units, reference code; Euclidean step costs 800/19)"
            }
        }
    }

    /// The exact interval `[lo, hi]` around a finite `g`.
    ///
    /// ```
    /// use truecost::learning::stochastic_q::Tolerance;
    /// use truecost::value::parse_rational;
    /// let g = parse_rational("30").unwrap();
    /// let (lo, hi) = Tolerance::Relative.interval(&g);
    /// assert_eq!((lo, hi), (parse_rational("27").unwrap(), parse_rational("33").unwrap()));
    /// let (lo, _) = Tolerance::Reference.interval(&g);
    /// assert_eq!(lo, parse_rational("25").unwrap());
    /// ```
    pub fn interval(self, g: &Rational) -> (Rational, Rational) {
        let width = match self {
            Tolerance::Relative => g / Rational::from_integer(10.into()),
            Tolerance::Reference => Rational::from_integer(5.into()),
        };
        (g - &width, g + width)
    }
}

/// The smallest `f64` `≥ r` (exact directed rounding): `+∞` above the largest finite `f64`,
/// `−f64::MAX` (not `−∞`) below the smallest.
///
/// ```
/// use truecost::learning::stochastic_q::{f64_at_least, f64_at_most};
/// use truecost::value::parse_rational;
/// let tenth = parse_rational("0.1").unwrap();
/// assert!(f64_at_most(&tenth) < f64_at_least(&tenth));
/// assert_eq!(f64_at_least(&parse_rational("3").unwrap()), 3.0);
/// ```
pub fn f64_at_least(r: &Rational) -> f64 {
    // Start from a finite f64 (an out-of-range r converts to ±∞, and −∞ is never ≥ r):
    // the loops below then step to the answer, +∞ included. (`to_f64` is `None` only for NaN.)
    let nearest = r.to_f64().expect("a rational converts to an f64 or ±∞");
    let mut f = nearest.clamp(-f64::MAX, f64::MAX);
    while f.is_finite() && Rational::from_float(f).is_some_and(|x| &x < r) {
        f = next_up(f);
    }
    while f.is_finite() && Rational::from_float(next_down(f)).is_some_and(|x| &x >= r) {
        f = next_down(f);
    }
    f
}

/// The next `f64` above a finite `f` (`f64::next_up`, written out for the crate's MSRV).
fn next_up(f: f64) -> f64 {
    if f == 0.0 {
        return f64::from_bits(1);
    }
    let bits = f.to_bits();
    f64::from_bits(if f > 0.0 { bits + 1 } else { bits - 1 })
}

/// The next `f64` below a finite `f`.
fn next_down(f: f64) -> f64 {
    -next_up(-f)
}

/// The largest `f64` `≤ r` (exact directed rounding): `−∞` below the smallest finite `f64`,
/// `f64::MAX` (not `+∞`) above the largest.
pub fn f64_at_most(r: &Rational) -> f64 {
    -f64_at_least(&-r)
}

/// The tracked states and their tolerance intervals (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    tracked: Vec<bool>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    tolerance: Tolerance,
}

impl Target {
    /// The target of `problem` with exact optimum `optimum` under `tolerance`.
    pub fn new(problem: &StochasticProblem, optimum: &Optimum, tolerance: Tolerance) -> Self {
        let g = optimum.cost_to_go_all();
        Self::from_values(problem, g, tolerance)
    }

    /// The same from explicit exact values `G*` (one per state).
    ///
    /// # Panics
    ///
    /// If `g` does not hold exactly one value per state of `problem` (a caller's bug: the
    /// command line always passes the optimum of the same problem).
    pub fn from_values(problem: &StochasticProblem, g: &[Extended], tolerance: Tolerance) -> Self {
        let n = problem.states();
        assert_eq!(g.len(), n, "Target::from_values: one value per state");
        let mut reachable = vec![false; n];
        let mut stack = vec![problem.initial()];
        reachable[problem.initial()] = true;
        while let Some(x) = stack.pop() {
            if problem.is_goal(x) {
                continue;
            }
            for a in problem.actions(x) {
                for o in problem.outcomes(a) {
                    if !reachable[o.successor] {
                        reachable[o.successor] = true;
                        stack.push(o.successor);
                    }
                }
            }
        }
        // Empty intervals where G* = +∞: nothing is within tolerance there.
        let mut lo = vec![f64::INFINITY; n];
        let mut hi = vec![f64::NEG_INFINITY; n];
        let mut tracked = vec![false; n];
        for x in 0..n {
            if let Extended::Finite(v) = &g[x] {
                let (l, h) = tolerance.interval(v);
                lo[x] = f64_at_least(&l);
                hi[x] = f64_at_most(&h);
                tracked[x] = reachable[x] && !problem.is_goal(x) && !problem.actions(x).is_empty();
            }
        }
        Target {
            tracked,
            lo,
            hi,
            tolerance,
        }
    }

    /// Whether `x` is tracked.
    pub fn is_tracked(&self, x: usize) -> bool {
        self.tracked[x]
    }

    /// The number of tracked states.
    pub fn tracked_count(&self) -> usize {
        self.tracked.iter().filter(|&&t| t).count()
    }

    /// Whether `v` is within tolerance of `G*(x)` (exact; `false` where `G* = +∞`).
    #[inline]
    pub fn within(&self, x: usize, v: f64) -> bool {
        self.lo[x] <= v && v <= self.hi[x]
    }

    /// The tolerance.
    pub fn tolerance(&self) -> Tolerance {
        self.tolerance
    }
}

/// Why a learning rate is refused.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RateError {
    /// `ρ ∉ (0, 1]`.
    #[error("learning rate rho = {} is outside (0, 1]", crate::echo::echo(.0))]
    Rho(String),
    /// `ω ∉ (1/2, 1]`.
    #[error("learning-rate exponent omega = {} is outside (0.5, 1] (the range where sum rho = inf and sum rho^2 < inf)", crate::echo::echo(.0))]
    Omega(String),
    /// In range exactly, but not once rounded to the learner's `f64`.
    #[error(
        "{name} = {text} rounds to {rounded} in f64 (the learner's arithmetic), outside {range}"
    )]
    Rounded {
        /// `rho` or `omega`.
        name: &'static str,
        /// The exact value as text (echoed, shortened).
        text: String,
        /// The `f64` it rounds to, as Rust prints it.
        rounded: String,
        /// The admissible range.
        range: &'static str,
    },
}

/// The learning rate of stochastic Q-learning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LearningRate {
    /// A constant `ρ ∈ (0, 1]`.
    Constant(f64),
    /// `ρ(x,u) = 1/n(x,u)^ω`, `ω ∈ (1/2, 1]`.
    Decay(f64),
}

impl LearningRate {
    /// A constant rate from its exact value, checked to lie in `(0, 1]`.
    ///
    /// ```
    /// use truecost::learning::stochastic_q::LearningRate;
    /// use truecost::value::parse_rational;
    /// assert_eq!(LearningRate::constant(&parse_rational("0.5").unwrap()), Ok(LearningRate::Constant(0.5)));
    /// assert!(LearningRate::constant(&parse_rational("0").unwrap()).is_err());
    /// ```
    /// The range is checked on the exact value **and** on the `f64` the learner uses (`1e-400`
    /// rounds to 0 and is refused before any run).
    pub fn constant(rho: &Rational) -> Result<Self, RateError> {
        let text = || crate::stochastic::short_text(rho);
        if !rho.is_positive() || rho > &Rational::one() {
            return Err(RateError::Rho(text()));
        }
        let rounded = rho.to_f64().unwrap_or(0.0);
        if !(rounded > 0.0 && rounded <= 1.0) {
            return Err(RateError::Rounded {
                name: "learning rate rho",
                text: text(),
                rounded: format!("{rounded:?}"),
                range: "(0, 1]",
            });
        }
        Ok(LearningRate::Constant(rounded))
    }

    /// The decaying rate `1/n^ω`, `ω` checked to lie in `(1/2, 1]`.
    ///
    /// ```
    /// use truecost::learning::stochastic_q::LearningRate;
    /// use truecost::value::parse_rational;
    /// assert!(LearningRate::decay(&parse_rational("0.8").unwrap()).is_ok());
    /// assert!(LearningRate::decay(&parse_rational("0.5").unwrap()).is_err());
    /// assert!(LearningRate::decay(&parse_rational("1.1").unwrap()).is_err());
    /// ```
    /// Checked exactly and on the `f64` the learner uses (`0.50000000000000001` rounds to 0.5
    /// and is refused).
    pub fn decay(omega: &Rational) -> Result<Self, RateError> {
        let half = Rational::new(1.into(), 2.into());
        let text = || crate::stochastic::short_text(omega);
        if omega <= &half || omega > &Rational::one() {
            return Err(RateError::Omega(text()));
        }
        let rounded = omega.to_f64().unwrap_or(0.0);
        if !(rounded > 0.5 && rounded <= 1.0) {
            return Err(RateError::Rounded {
                name: "learning-rate exponent omega",
                text: text(),
                rounded: format!("{rounded:?}"),
                range: "(0.5, 1]",
            });
        }
        Ok(LearningRate::Decay(rounded))
    }
}

/// The parameters of a stochastic Q-learning run.
#[derive(Clone, Debug, PartialEq)]
pub struct StochasticQConfig {
    /// Episodes `E ≥ 1` (the paper's stochastic runs: 3000).
    pub episodes: u32,
    /// Steps per episode `M ≥ 1`.
    pub max_steps: u32,
    /// `ρ`.
    pub rate: LearningRate,
    /// ε per episode.
    pub epsilon: EpsilonSchedule,
    /// `Q₀`.
    pub initial_value: f64,
}

/// The counts of a run (docs/spec.md §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub struct StochasticOutcome {
    /// Actions applied.
    pub actions: u64,
    /// Episodes started.
    pub episodes_run: u32,
    /// Whether every tracked state was within tolerance after some action (the run stopped at
    /// the end of that episode).
    pub converged: bool,
    /// The first action after which every tracked state was within tolerance.
    pub converged_at: Option<u64>,
    /// The first action after which `V(x1)` was within tolerance.
    pub initial_within_at: Option<u64>,
    /// Its 1-based episode.
    pub initial_within_episode: Option<u32>,
    /// The 1-based action that first entered a goal.
    pub goal_discovered_at: Option<u64>,
}

/// One simulation of the learnt greedy policy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct GreedySimulation {
    /// States visited, `x1` and the final state included (steps + 1).
    pub states: u64,
    /// Whether a goal was reached within the cap.
    pub reached_goal: bool,
    /// Whether every action taken was optimal (`Q* = G*`), given per-action optimality flags.
    pub optimal_actions: bool,
}

const PENDING_GOAL: u8 = 1;
const PENDING_INITIAL: u8 = 2;
const PENDING_CONVERGED: u8 = 4;

/// A stochastic Q-learning run in progress (module docs).
#[derive(Debug)]
pub struct StochasticQLearner<'a> {
    action_first: Vec<u32>,
    cost: Vec<f64>,
    outcome_first: Vec<u32>,
    cumulative: Vec<f64>,
    successor: Vec<u32>,
    is_goal: Vec<bool>,
    initial: usize,
    q: Vec<f64>,
    v: Vec<f64>,
    visits: Vec<u32>,
    target: &'a Target,
    within_count: usize,
    tracked_total: usize,
    config: StochasticQConfig,
    rng: ChaCha8Rng,
    plan: Plan<'a>,
    epsilons: Epsilons,
    epsilon: Probability,
    actions: u64,
    episodes_started: u32,
    step: u32,
    state: usize,
    in_episode: bool,
    finished: bool,
    outcome: StochasticOutcome,
    pending: u8,
}

impl<'a> StochasticQLearner<'a> {
    /// Sets up a run on `problem` with `f64` stage costs `cost` (one per action, e.g.
    /// [`crate::stochastic::value_iteration::FloatModel::nearest`]), judged by `target`.
    ///
    /// ```
    /// use truecost::learning::plan::{EpsilonSchedule, Plan, Probability, sample_rng};
    /// use truecost::learning::stochastic_q::*;
    /// use truecost::model::{Move, Problem};
    /// use truecost::stochastic::{policy_iteration::optimum, NoiseModel, Predictability, StochasticProblem};
    /// use truecost::value::parse_rational;
    /// let one = parse_rational("1").unwrap();
    /// // 0 <-> 1 -> 2 (goal)
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: one.clone() }],
    ///     vec![Move { successor: 0, cost: one.clone() }, Move { successor: 2, cost: one }], vec![]], 0, vec![2]).unwrap();
    /// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
    /// let target = Target::new(&s, &optimum(&s).unwrap(), Tolerance::Relative);
    /// let config = StochasticQConfig { episodes: 500, max_steps: 50, rate: LearningRate::Decay(1.0),
    ///     epsilon: EpsilonSchedule::Constant(Probability::ONE), initial_value: 0.0 };
    /// let costs = vec![1.0; s.action_total()];
    /// let mut learner = StochasticQLearner::new(&s, &costs, &target, &config, sample_rng(1, 0), Plan::Random).unwrap();
    /// let outcome = learner.run();
    /// assert!(outcome.converged);
    /// assert!(learner.simulate_greedy(None).reached_goal);
    /// ```
    pub fn new(
        problem: &StochasticProblem,
        cost: &[f64],
        target: &'a Target,
        config: &StochasticQConfig,
        rng: ChaCha8Rng,
        plan: Plan<'a>,
    ) -> Result<Self, LearningError> {
        if config.episodes == 0 {
            return Err(LearningError::NoEpisodes);
        }
        if config.max_steps == 0 {
            return Err(LearningError::NoSteps);
        }
        match config.rate {
            LearningRate::Constant(r) if !(r > 0.0 && r <= 1.0) => {
                return Err(LearningError::RateOutOfRange(r.to_string()))
            }
            LearningRate::Decay(w) if !(w > 0.5 && w <= 1.0) => {
                return Err(LearningError::RateOutOfRange(format!("1/n^{w}")))
            }
            _ => {}
        }
        config.epsilon.validate(config.episodes)?;
        let n = problem.states();
        let total = problem.action_total();
        if cost.len() != total {
            return Err(LearningError::OptimumLength {
                given: cost.len(),
                nodes: total,
            });
        }
        let mut action_first = Vec::with_capacity(n + 1);
        let mut outcome_first = Vec::with_capacity(total + 1);
        let mut cumulative = Vec::with_capacity(problem.outcome_total());
        let mut successor = Vec::with_capacity(problem.outcome_total());
        for x in 0..n {
            action_first.push(problem.actions(x).start as u32);
        }
        action_first.push(total as u32);
        for a in 0..total {
            outcome_first.push(successor.len() as u32);
            cumulative.extend_from_slice(problem.cumulative(a));
            successor.extend(problem.outcomes(a).iter().map(|o| o.successor as u32));
        }
        outcome_first.push(successor.len() as u32);
        let is_goal: Vec<bool> = (0..n).map(|x| problem.is_goal(x)).collect();
        let q0 = config.initial_value;
        let v: Vec<f64> = (0..n)
            .map(|x| {
                if is_goal[x] {
                    0.0
                } else if problem.actions(x).is_empty() {
                    f64::INFINITY
                } else {
                    q0
                }
            })
            .collect();
        let tracked_total = target.tracked_count();
        let within_count = (0..n)
            .filter(|&x| target.is_tracked(x) && target.within(x, v[x]))
            .count();
        let mut learner = StochasticQLearner {
            action_first,
            cost: cost.to_vec(),
            outcome_first,
            cumulative,
            successor,
            is_goal,
            initial: problem.initial(),
            q: vec![q0; total],
            v,
            visits: vec![
                0;
                if matches!(config.rate, LearningRate::Decay(_)) {
                    total
                } else {
                    0
                }
            ],
            target,
            within_count,
            tracked_total,
            config: config.clone(),
            rng,
            plan,
            epsilons: config.epsilon.episodes(config.episodes),
            epsilon: config.epsilon.start(),
            actions: 0,
            episodes_started: 0,
            step: 0,
            state: problem.initial(),
            in_episode: false,
            finished: false,
            outcome: StochasticOutcome::default(),
            pending: 0,
        };
        let x1 = learner.initial;
        if target.within(x1, learner.v[x1]) {
            learner.outcome.initial_within_at = Some(0);
            learner.outcome.initial_within_episode = Some(0);
            learner.pending |= PENDING_INITIAL;
        }
        if learner.within_count == tracked_total {
            learner.outcome.converged_at = Some(0);
            learner.outcome.converged = true;
            learner.finished = true;
            learner.pending |= PENDING_CONVERGED;
        }
        if learner.is_goal[x1] {
            learner.finished = true;
        }
        Ok(learner)
    }

    /// Runs to the end and returns the outcome.
    pub fn run(&mut self) -> StochasticOutcome {
        while self.advance() != Event::Finished {}
        self.outcome()
    }

    /// The counts so far.
    pub fn outcome(&self) -> StochasticOutcome {
        StochasticOutcome {
            actions: self.actions,
            episodes_run: self.episodes_started,
            ..self.outcome
        }
    }

    /// `Q̂`, one entry per action (global ids of the problem).
    pub fn q_values(&self) -> &[f64] {
        &self.q
    }

    /// `V(x) = min_u Q̂(x, u)` (0 at goals, `+∞` without actions).
    pub fn cost_to_go(&self) -> &[f64] {
        &self.v
    }

    /// Runs until the next milestone or the end.
    pub fn advance(&mut self) -> Event {
        loop {
            for (bit, m) in [
                (PENDING_GOAL, Milestone::GoalDiscovered),
                (PENDING_INITIAL, Milestone::InitialOptimal),
                (PENDING_CONVERGED, Milestone::Converged),
            ] {
                if self.pending & bit != 0 {
                    self.pending &= !bit;
                    return Event::Milestone(m);
                }
            }
            if self.finished {
                return Event::Finished;
            }
            if !self.in_episode {
                self.epsilon = self.epsilons.next_episode().expect("schedule validated");
                self.episodes_started += 1;
                self.state = self.initial;
                self.step = 0;
                self.in_episode = true;
            }
            self.run_steps();
        }
    }

    fn end_episode(&mut self) {
        self.in_episode = false;
        if self.outcome.converged_at.is_some() {
            self.outcome.converged = true;
            self.finished = true;
        } else if self.episodes_started >= self.config.episodes {
            self.finished = true;
        }
    }

    /// Steps of the current episode until it ends or a milestone is pending.
    fn run_steps(&mut self) {
        let epsilon = self.epsilon;
        let x1 = self.initial;
        let max_steps = self.config.max_steps;
        let rate = self.config.rate;
        let tracked_total = self.tracked_total;
        let episode = self.episodes_started;
        let StochasticQLearner {
            action_first,
            cost,
            outcome_first,
            cumulative,
            successor,
            is_goal,
            q,
            v,
            visits,
            target,
            rng,
            plan,
            outcome,
            ..
        } = self;
        let mut s = self.state;
        let mut step = self.step;
        let mut actions = self.actions;
        let mut within_count = self.within_count;
        let mut pending = self.pending;
        let mut ended = false;
        while step < max_steps {
            let lo = action_first[s] as usize;
            let hi = action_first[s + 1] as usize;
            if lo == hi {
                ended = true;
                break;
            }
            let a = if epsilon.flip(rng) {
                explore(plan, rng, hi - lo)
            } else {
                first_minimiser(&q[lo..hi])
            };
            let e = lo + a;
            let (o_lo, o_hi) = (outcome_first[e] as usize, outcome_first[e + 1] as usize);
            let y = if o_hi - o_lo == 1 {
                successor[o_lo] as usize
            } else {
                successor[o_lo + outcome_index(&cumulative[o_lo..o_hi], rng.random())] as usize
            };
            let t = cost[e] + v[y];
            let rho = match rate {
                LearningRate::Constant(r) => r,
                LearningRate::Decay(w) => {
                    visits[e] = visits[e].saturating_add(1);
                    let n = f64::from(visits[e]);
                    if w == 1.0 {
                        1.0 / n
                    } else {
                        n.powf(-w)
                    }
                }
            };
            let new = if rho == 1.0 {
                t
            } else {
                (1.0 - rho) * q[e] + rho * t
            };
            let old = std::mem::replace(&mut q[e], new);
            let refreshed = if new < v[s] {
                Some(new)
            } else if old == v[s] && new != old {
                Some(q[lo..hi][first_minimiser(&q[lo..hi])])
            } else {
                None
            };
            actions += 1;
            step += 1;
            if let Some(value) = refreshed {
                if target.is_tracked(s) {
                    let was = target.within(s, v[s]);
                    let is = target.within(s, value);
                    if is && !was {
                        within_count += 1;
                    } else if was && !is {
                        within_count -= 1;
                    }
                }
                v[s] = value;
                if outcome.converged_at.is_none() && within_count == tracked_total {
                    outcome.converged_at = Some(actions);
                    pending |= PENDING_CONVERGED;
                }
                if s == x1 && outcome.initial_within_at.is_none() && target.within(x1, value) {
                    outcome.initial_within_at = Some(actions);
                    outcome.initial_within_episode = Some(episode);
                    pending |= PENDING_INITIAL;
                }
            }
            s = y;
            if is_goal[y] {
                if outcome.goal_discovered_at.is_none() {
                    outcome.goal_discovered_at = Some(actions);
                    pending |= PENDING_GOAL;
                }
                ended = true;
                break;
            }
            if pending != 0 {
                break;
            }
        }
        self.state = s;
        self.step = step;
        self.actions = actions;
        self.within_count = within_count;
        self.pending = pending;
        if ended || step >= max_steps {
            self.end_episode();
        }
    }

    /// Runs the learnt greedy policy (first minimiser of `Q̂`) from `x1` with outcomes sampled
    /// from the run's generator, for at most [`GREEDY_SIMULATION_CAP`] steps. `optimal` (one
    /// flag per action, e.g. from [`Optimum::is_optimal_action`]) decides
    /// [`GreedySimulation::optimal_actions`] (`false` when not given).
    pub fn simulate_greedy(&mut self, optimal: Option<&[bool]>) -> GreedySimulation {
        let mut x = self.initial;
        let mut steps = 0u64;
        let mut all_optimal = optimal.is_some();
        while !self.is_goal[x] && steps < GREEDY_SIMULATION_CAP {
            let (lo, hi) = (
                self.action_first[x] as usize,
                self.action_first[x + 1] as usize,
            );
            if lo == hi {
                break;
            }
            let e = lo + first_minimiser(&self.q[lo..hi]);
            if let Some(flags) = optimal {
                all_optimal &= flags[e];
            }
            let (o_lo, o_hi) = (
                self.outcome_first[e] as usize,
                self.outcome_first[e + 1] as usize,
            );
            x = if o_hi - o_lo == 1 {
                self.successor[o_lo] as usize
            } else {
                self.successor
                    [o_lo + outcome_index(&self.cumulative[o_lo..o_hi], self.rng.random())]
                    as usize
            };
            steps += 1;
        }
        GreedySimulation {
            states: steps + 1,
            reached_goal: self.is_goal[x],
            optimal_actions: all_optimal && self.is_goal[x],
        }
    }
}

/// Per-action flags `Q*(x,u) = G*(x)` (exact), for [`StochasticQLearner::simulate_greedy`].
pub fn optimal_action_flags(problem: &StochasticProblem, optimum: &Optimum) -> Vec<bool> {
    (0..problem.action_total())
        .map(|a| optimum.is_optimal_action(problem, a))
        .collect()
}

/// The outcome a uniform draw `u ∈ [0, 1)` selects: the first whose cumulative threshold
/// exceeds `u` (the last if none), as [`StochasticProblem::sample`]; `cumulative` is non-empty.
///
/// ```
/// use truecost::learning::stochastic_q::outcome_index;
/// assert_eq!(outcome_index(&[0.9, 0.95, 1.0], 0.0), 0);
/// assert_eq!(outcome_index(&[0.9, 0.95, 1.0], 0.9), 1);
/// assert_eq!(outcome_index(&[0.9, 0.95, 1.0], 0.99), 2);
/// ```
#[inline]
pub fn outcome_index(cumulative: &[f64], u: f64) -> usize {
    let mut i = 0;
    while i + 1 < cumulative.len() && cumulative[i] <= u {
        i += 1;
    }
    i
}

/// The index of the first minimum (ties go to the earlier action). `values` is non-empty.
#[inline]
fn first_minimiser(values: &[f64]) -> usize {
    let mut best = 0;
    for i in 1..values.len() {
        if values[i] < values[best] {
            best = i;
        }
    }
    best
}

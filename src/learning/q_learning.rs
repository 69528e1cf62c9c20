//! Q-learning with ε-greedy exploration over an exploration plan (docs/spec.md §2), and the metrics of
//! docs/spec.md §4 tracked while it learns.
//!
//! # The algorithm
//!
//! The Q-table has one entry per state–action pair: the state's moves in their order, then, at
//! a goal, the termination action `uT` (successor: the goal itself, cost 0) **last**. Every
//! entry starts at `Q₀` (default 0). A run is `E` episodes of at most `M` steps; each episode
//! starts at `x1`. At a state `x` with actions, a step
//!
//! 1. chooses an action: with probability ε ([`EpsilonSchedule`], exact coins) the exploration
//!    plan's next action ([`Plan`]), otherwise the **greedy** action — the *first* minimiser of
//!    `Q̂(x, ·)` in the state's action order (ties always go to the earlier action);
//! 2. applies it, observes `x' = f(x, u)` and updates
//!    `Q̂(x,u) ← (1−ρ)·Q̂(x,u) + ρ·(l(x,u) + min_{u'} Q̂(x',u'))`; with `ρ = 1` (derandomized
//!    Q-learning) this is `Q̂(x,u) ← l(x,u) + min_{u'} Q̂(x',u')` and is computed exactly in the
//!    graph's value type; a state without actions has `min = +∞`;
//! 3. counts one action; the episode ends when a goal is entered, after `M` steps, or at a
//!    state without actions.
//!
//! Exact value types ([`crate::value::Units`], [`crate::value::Extended`]) require `ρ = 1`;
//! `ρ < 1` runs on `f64` graphs (its iterates are not finite sums of stage costs).
//!
//! # Metrics (docs/spec.md §4)
//!
//! `V(x) = min_u Q̂(x,u)` is cached per state and refreshed on every update (only the updated
//! state's `V` can change, so this is `O(1)` amortised: `O(|U(x)|)` only when the old minimum
//! rises). The **tracked states** are the states reachable from `x1` that have an action (for
//! the paper's grids: x1's component). A counter of tracked states with `V(x) = G*(x)` is kept
//! exactly, so convergence is known after every action without a scan. Under
//! [`Rules::Exact`]:
//!
//! * `converged_at` — the first action after which `V = G*` on every tracked state;
//! * `initial_optimal_at` — the first action after which `V(x1) = G*(x1)`;
//! * `goal_discovered_at` — the (1-based) action that first entered a goal.
//!
//! (0 means "before the first action".) The run stops at the end of the episode in which it
//! converged. Under [`Rules::Reference`] the paper's code is reproduced instead (docs/spec.md §7):
//! convergence and `V(x1)` are only checked after every 1000th action, `converged_at` is the
//! *last* successful check of the converging episode, and equality is exact `f64` equality
//! against the given values.
//!
//! Which states are tracked matters for the reference mode: the paper's code compares `V` with
//! its value iteration on "every state with an action", and its published convergence rates of
//! 1.0 on problems 13 and 14 (whose grids have edges outside x1's component, where `Q̂` stays
//! at `Q₀ = 0` while `G* = ∞`) are only possible if the comparison is restricted to x1's
//! component; with that restriction the published π rows of all 16 problems, whose counts
//! depend on when convergence is detected, are reproduced exactly.
//!
//! The learner never reads a clock: [`QLearner::advance`] returns at each milestone so that a
//! runner can time the milestones from outside.

use num_traits::{One, Signed, ToPrimitive};
use rand_chacha::ChaCha8Rng;

use super::plan::{explore, EpsilonSchedule, Epsilons, Plan, Probability, ProbabilityError};
use crate::model::Graph;
use crate::value::{CostValue, Extended, Rational, Units};

/// The interval of the reference code's convergence checks (docs/spec.md §7).
pub const REFERENCE_CHECK_INTERVAL: u64 = 1000;

/// Which rules define the metrics.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rules {
    /// Tracked after every action, exactly (the default).
    Exact,
    /// The paper's code: checks after every 1000th action (docs/spec.md §7).
    Reference,
}

/// The parameters of a Q-learning run.
#[derive(Clone, Debug, PartialEq)]
pub struct QLearningConfig {
    /// Episodes `E ≥ 1`.
    pub episodes: u32,
    /// Steps per episode `M ≥ 1`.
    pub max_steps: u32,
    /// The learning rate `ρ ∈ (0, 1]` (exact; `1` is derandomized Q-learning).
    pub learning_rate: Rational,
    /// ε per episode.
    pub epsilon: EpsilonSchedule,
    /// How the metrics are defined.
    pub rules: Rules,
}

impl QLearningConfig {
    /// The paper's deterministic setting: 1000 episodes × 3000 steps, `ρ = 1`, exact rules.
    ///
    /// ```
    /// use truecost::learning::plan::{EpsilonSchedule, Probability};
    /// use truecost::learning::q_learning::QLearningConfig;
    /// let c = QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO));
    /// assert_eq!((c.episodes, c.max_steps), (1000, 3000));
    /// ```
    pub fn paper(epsilon: EpsilonSchedule) -> Self {
        QLearningConfig {
            episodes: 1000,
            max_steps: 3000,
            learning_rate: Rational::one(),
            epsilon,
            rules: Rules::Exact,
        }
    }
}

/// Why a Q-learning run cannot be set up.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LearningError {
    /// `E = 0`.
    #[error("the number of episodes must be at least 1")]
    NoEpisodes,
    /// `M = 0`.
    #[error("the number of steps per episode must be at least 1")]
    NoSteps,
    /// `ρ ∉ (0, 1]`.
    #[error("learning rate ρ = {0} is outside (0, 1]")]
    RateOutOfRange(String),
    /// `ρ < 1` on exact values.
    #[error(
        "learning rate ρ = {0} < 1 needs f64 values; exact Q-learning is derandomized (ρ = 1)"
    )]
    FractionalRateNeedsFloat(String),
    /// A bad ε.
    #[error(transparent)]
    Probability(#[from] ProbabilityError),
    /// The optimum does not match the graph.
    #[error("{given} optimal values given for a graph of {nodes} nodes")]
    OptimumLength {
        /// Values given.
        given: usize,
        /// Nodes.
        nodes: usize,
    },
}

/// A value type Q-learning can run on: exact types only with `ρ = 1`.
pub trait LearningValue: CostValue {
    /// `(1 − ρ)·old + ρ·target` for `ρ < 1` (never called for exact types).
    fn blend(old: &Self, target: Self, rate: f64) -> Self;
}

impl LearningValue for f64 {
    #[inline]
    fn blend(old: &Self, target: Self, rate: f64) -> Self {
        (1.0 - rate) * old + rate * target
    }
}

impl LearningValue for Units {
    #[inline]
    fn blend(_old: &Self, target: Self, _rate: f64) -> Self {
        target // unreachable: ρ < 1 is refused for exact types
    }
}

impl LearningValue for Extended {
    fn blend(_old: &Self, target: Self, _rate: f64) -> Self {
        target // unreachable: ρ < 1 is refused for exact types
    }
}

/// An event in a run, reported by [`QLearner::advance`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Milestone {
    /// A goal was entered for the first time.
    GoalDiscovered,
    /// `V(x1) = G*(x1)` for the first time (at a check, under the reference rules).
    InitialOptimal,
    /// `V = G*` on every tracked state for the first time.
    Converged,
}

/// What [`QLearner::advance`] stopped at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// A milestone was reached; call `advance` again to continue.
    Milestone(Milestone),
    /// The run is over.
    Finished,
}

/// The counts of a run (docs/spec.md §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize)]
pub struct Outcome {
    /// Actions applied.
    pub actions: u64,
    /// Episodes started (the last one possibly cut short by convergence).
    pub episodes_run: u32,
    /// Whether the run stopped because it converged.
    pub converged: bool,
    /// See the module documentation (exact: first action; reference: last check of the
    /// converging episode).
    pub converged_at: Option<u64>,
    /// The action after which `V(x1) = G*(x1)` first held (at a check, for the reference).
    pub initial_optimal_at: Option<u64>,
    /// The 1-based action that first entered a goal.
    pub goal_discovered_at: Option<u64>,
}

impl Outcome {
    /// The 0-based index of the last episode run (the paper's "episode" column: `E − 1` when
    /// the run never converged).
    pub fn last_episode_index(&self) -> Option<u32> {
        self.episodes_run.checked_sub(1)
    }
}

/// Watches every update of a run (for tests and diagnostics; [`Unobserved`] costs nothing).
pub trait Observer<V> {
    /// Called after `Q̂(state, action)` changed from `old` to `new`; `cost_to_go` is `V` after
    /// the update.
    fn update(&mut self, state: usize, action: usize, old: &V, new: &V, cost_to_go: &[V]);
}

/// The observer that watches nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Unobserved;

impl<V> Observer<V> for Unobserved {
    #[inline(always)]
    fn update(&mut self, _: usize, _: usize, _: &V, _: &V, _: &[V]) {}
}

impl<V, F: FnMut(usize, usize, &V, &V, &[V])> Observer<V> for F {
    fn update(&mut self, state: usize, action: usize, old: &V, new: &V, cost_to_go: &[V]) {
        self(state, action, old, new, cost_to_go)
    }
}

/// The greedy path read off `Q̂` at the end of a run (docs/spec.md §4): from `x1`, repeatedly the first
/// minimiser of `Q̂(x, ·)`, until a goal, a state without actions, or a state already on the
/// path (a loop).
#[derive(Clone, Debug, PartialEq)]
pub struct GreedyPath<V> {
    /// The states visited, `x1` first (the paper reports `states.len()` as the path length).
    pub states: Vec<usize>,
    /// Whether it ends at a goal.
    pub reached_goal: bool,
    /// Whether it stopped because the next state was already on the path.
    pub looped: bool,
    /// The cost of its moves (`l` summed from the last move backwards, as value iteration
    /// composes it); meaningful when `reached_goal`.
    pub cost: V,
}

const PENDING_GOAL: u8 = 1;
const PENDING_INITIAL: u8 = 2;
const PENDING_CONVERGED: u8 = 4;

/// A Q-learning run in progress on a graph (see the module documentation).
#[derive(Debug)]
pub struct QLearner<'a, V: LearningValue> {
    first: Vec<u32>,
    successor: Vec<u32>,
    cost: Vec<V>,
    is_goal: Vec<bool>,
    initial: usize,
    q: Vec<V>,
    v: Vec<V>,
    optimum: Vec<V>,
    tracked: Vec<bool>,
    tracked_total: usize,
    optimal_count: usize,
    episodes: u32,
    max_steps: u32,
    rate: Option<f64>,
    schedule: Epsilons,
    rules: Rules,
    rng: ChaCha8Rng,
    plan: Plan<'a>,
    epsilon: Probability,
    actions: u64,
    episodes_started: u32,
    step: u32,
    state: usize,
    in_episode: bool,
    finished: bool,
    converged: bool,
    converged_at: Option<u64>,
    initial_optimal_at: Option<u64>,
    goal_discovered_at: Option<u64>,
    pending: u8,
}

impl<'a, V: LearningValue> QLearner<'a, V> {
    /// Sets up a run on `graph` with every `Q̂` entry at `initial_value`, judged against the
    /// optimal cost-to-go `optimum` (one value per node, e.g. from
    /// [`crate::solvers::dijkstra::to_goals`]); `rng` drives coins and the random plan.
    ///
    /// ```
    /// use truecost::learning::plan::{EpsilonSchedule, Plan, Probability, sample_rng};
    /// use truecost::learning::q_learning::{QLearner, QLearningConfig};
    /// use truecost::model::Graph;
    /// use truecost::solvers::dijkstra;
    /// use truecost::value::Units;
    /// // 0 -> 1 -> 2 (goal), unit costs
    /// let g = Graph::from_adjacency(vec![vec![(1, Units(1))], vec![(0, Units(1)), (2, Units(1))], vec![]],
    ///     0, &[2], vec![0, 1, 2], num_rational::BigRational::from_integer(1.into()));
    /// let optimum = dijkstra::to_goals(&g).cost_to_go;
    /// let config = QLearningConfig { episodes: 50, max_steps: 10,
    ///     ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ONE)) };
    /// let mut learner = QLearner::new(&g, &optimum, Units(0), &config, sample_rng(1, 0), Plan::Random).unwrap();
    /// let outcome = learner.run();
    /// assert!(outcome.converged);
    /// assert_eq!(learner.cost_to_go()[..2], [Units(2), Units(1)]);
    /// assert_eq!(learner.greedy_path().states, vec![0, 1, 2]);
    /// ```
    pub fn new(
        graph: &Graph<V>,
        optimum: &[V],
        initial_value: V,
        config: &QLearningConfig,
        rng: ChaCha8Rng,
        plan: Plan<'a>,
    ) -> Result<Self, LearningError> {
        if config.episodes == 0 {
            return Err(LearningError::NoEpisodes);
        }
        if config.max_steps == 0 {
            return Err(LearningError::NoSteps);
        }
        let rho = &config.learning_rate;
        let rho_text = || Extended::Finite(rho.clone()).to_string();
        if !rho.is_positive() || rho > &Rational::one() {
            return Err(LearningError::RateOutOfRange(rho_text()));
        }
        let rate = if rho.is_one() {
            None
        } else if V::EXACT {
            return Err(LearningError::FractionalRateNeedsFloat(rho_text()));
        } else {
            Some(rho.to_f64().unwrap_or(1.0))
        };
        config.epsilon.validate(config.episodes)?;
        let n = graph.nodes();
        if optimum.len() != n {
            return Err(LearningError::OptimumLength {
                given: optimum.len(),
                nodes: n,
            });
        }
        // The Q-table: moves in order, then termination at goals.
        let mut first = Vec::with_capacity(n + 1);
        let mut successor = Vec::with_capacity(graph.edge_count() + n);
        let mut cost = Vec::with_capacity(graph.edge_count() + n);
        first.push(0u32);
        for x in 0..n {
            let (succ, c) = graph.edge_slices(x);
            successor.extend_from_slice(succ);
            cost.extend_from_slice(c);
            if graph.is_goal(x) {
                successor.push(x as u32);
                cost.push(V::zero());
            }
            first.push(u32::try_from(successor.len()).expect("fewer than 2^32 Q-table entries"));
        }
        let q = vec![initial_value.clone(); successor.len()];
        let v: Vec<V> = (0..n)
            .map(|x| {
                if first[x] == first[x + 1] {
                    V::infinity()
                } else {
                    initial_value.clone()
                }
            })
            .collect();
        // Tracked: reachable from x1 over moves, with at least one action.
        let mut reachable = vec![false; n];
        let mut stack = vec![graph.initial()];
        reachable[graph.initial()] = true;
        while let Some(x) = stack.pop() {
            for (y, _) in graph.edges(x) {
                if !reachable[y] {
                    reachable[y] = true;
                    stack.push(y);
                }
            }
        }
        let tracked: Vec<bool> = (0..n)
            .map(|x| reachable[x] && first[x] < first[x + 1])
            .collect();
        let tracked_total = tracked.iter().filter(|&&t| t).count();
        let optimal_count = (0..n).filter(|&x| tracked[x] && v[x] == optimum[x]).count();
        let is_goal = (0..n).map(|x| graph.is_goal(x)).collect();
        let epsilon = config.epsilon.start();
        let mut learner = QLearner {
            first,
            successor,
            cost,
            is_goal,
            initial: graph.initial(),
            q,
            v,
            optimum: optimum.to_vec(),
            tracked,
            tracked_total,
            optimal_count,
            episodes: config.episodes,
            max_steps: config.max_steps,
            rate,
            schedule: config.epsilon.episodes(config.episodes),
            rules: config.rules,
            rng,
            plan,
            epsilon,
            actions: 0,
            episodes_started: 0,
            step: 0,
            state: graph.initial(),
            in_episode: false,
            finished: false,
            converged: false,
            converged_at: None,
            initial_optimal_at: None,
            goal_discovered_at: None,
            pending: 0,
        };
        if learner.rules == Rules::Exact {
            // Already optimal before any action (e.g. x1 is a goal): report action 0.
            if learner.v[learner.initial] == learner.optimum[learner.initial] {
                learner.initial_optimal_at = Some(0);
                learner.pending |= PENDING_INITIAL;
            }
            if learner.optimal_count == learner.tracked_total {
                learner.converged_at = Some(0);
                learner.converged = true;
                learner.finished = true;
                learner.pending |= PENDING_CONVERGED;
            }
        }
        Ok(learner)
    }

    /// Runs to the end and returns the outcome.
    pub fn run(&mut self) -> Outcome {
        while self.advance() != Event::Finished {}
        self.outcome()
    }

    /// Runs until the next milestone or the end.
    pub fn advance(&mut self) -> Event {
        self.drive(&mut Unobserved)
    }

    /// Runs to the end, calling `observer` after every update.
    pub fn run_observed<O: Observer<V>>(&mut self, observer: &mut O) -> Outcome {
        while self.drive(observer) != Event::Finished {}
        self.outcome()
    }

    /// The counts so far (final once [`Event::Finished`] was returned).
    pub fn outcome(&self) -> Outcome {
        Outcome {
            actions: self.actions,
            episodes_run: self.episodes_started,
            converged: self.converged,
            converged_at: self.converged_at,
            initial_optimal_at: self.initial_optimal_at,
            goal_discovered_at: self.goal_discovered_at,
        }
    }

    /// `Q̂` as a flat table; the entries of state `x` are [`QLearner::actions_of`]`(x)`.
    pub fn q_values(&self) -> &[V] {
        &self.q
    }

    /// The index range of state `x`'s entries in [`QLearner::q_values`] (moves in order, then
    /// termination at a goal).
    pub fn actions_of(&self, x: usize) -> std::ops::Range<usize> {
        self.first[x] as usize..self.first[x + 1] as usize
    }

    /// Successor and stage cost of Q-table entry `e`.
    pub fn entry(&self, e: usize) -> (usize, &V) {
        (self.successor[e] as usize, &self.cost[e])
    }

    /// `V(x) = min_u Q̂(x,u)` for every state (`+∞` without actions).
    pub fn cost_to_go(&self) -> &[V] {
        &self.v
    }

    /// Whether `x` is a tracked state (reachable from `x1`, with an action).
    pub fn is_tracked(&self, x: usize) -> bool {
        self.tracked[x]
    }

    /// The greedy path from `x1` (see [`GreedyPath`]).
    pub fn greedy_path(&self) -> GreedyPath<V> {
        let mut states = vec![self.initial];
        let mut on_path = vec![false; self.v.len()];
        let mut costs = Vec::new();
        let mut x = self.initial;
        let mut looped = false;
        while !self.is_goal[x] {
            on_path[x] = true;
            let range = self.actions_of(x);
            if range.is_empty() {
                break;
            }
            let e = range.start + first_minimiser(&self.q[range]);
            let y = self.successor[e] as usize;
            if on_path[y] {
                looped = true;
                break;
            }
            costs.push(&self.cost[e]);
            states.push(y);
            x = y;
        }
        let cost = costs.iter().rev().fold(V::zero(), |acc, c| c.plus(&acc));
        GreedyPath {
            reached_goal: self.is_goal[x],
            states,
            looped,
            cost,
        }
    }

    /// Ends the current episode and decides whether the run is over.
    fn end_episode(&mut self) {
        self.in_episode = false;
        if self.converged_at.is_some() {
            self.converged = true;
            self.finished = true;
        } else if self.episodes_started >= self.episodes {
            self.finished = true;
        }
    }

    fn take_pending(&mut self) -> Option<Milestone> {
        for (bit, m) in [
            (PENDING_GOAL, Milestone::GoalDiscovered),
            (PENDING_INITIAL, Milestone::InitialOptimal),
            (PENDING_CONVERGED, Milestone::Converged),
        ] {
            if self.pending & bit != 0 {
                self.pending &= !bit;
                return Some(m);
            }
        }
        None
    }

    /// The learning loop. Returns at a milestone or at the end.
    fn drive<O: Observer<V>>(&mut self, observer: &mut O) -> Event {
        loop {
            if let Some(m) = self.take_pending() {
                return Event::Milestone(m);
            }
            if self.finished {
                return Event::Finished;
            }
            if !self.in_episode {
                self.epsilon = self.schedule.next_episode().expect("schedule validated");
                self.episodes_started += 1;
                self.state = self.initial;
                self.step = 0;
                self.in_episode = true;
            }
            self.run_steps(observer);
        }
    }

    /// Steps of the current episode until it ends or a milestone is pending. The tables are
    /// borrowed into locals so that the loop keeps its counters in registers.
    #[inline]
    fn run_steps<O: Observer<V>>(&mut self, observer: &mut O) {
        let reference = self.rules == Rules::Reference;
        let epsilon = self.epsilon;
        let x1 = self.initial;
        let max_steps = self.max_steps;
        let rate = self.rate;
        let tracked_total = self.tracked_total;
        let QLearner {
            first,
            successor,
            cost,
            is_goal,
            q,
            v,
            optimum,
            tracked,
            rng,
            plan,
            ..
        } = self;
        let (first, successor, cost, is_goal) =
            (&first[..], &successor[..], &cost[..], &is_goal[..]);
        let (optimum, tracked) = (&optimum[..], &tracked[..]);
        let (q, v) = (&mut q[..], &mut v[..]);
        let mut s = self.state;
        let mut step = self.step;
        let mut actions = self.actions;
        let mut optimal_count = self.optimal_count;
        let mut converged_at = self.converged_at;
        let mut initial_optimal_at = self.initial_optimal_at;
        let mut goal_discovered_at = self.goal_discovered_at;
        let mut pending = self.pending;
        // Actions left until the reference rules' next check (a countdown instead of a division
        // per action): the check runs when `actions` reaches a multiple of the interval.
        let mut until_check = REFERENCE_CHECK_INTERVAL - actions % REFERENCE_CHECK_INTERVAL;
        let mut ended = false;
        while step < max_steps {
            let lo = first[s] as usize;
            let hi = first[s + 1] as usize;
            if lo == hi {
                ended = true; // no action: the episode ends (the paper's "No neighbors found")
                break;
            }
            let here = &q[lo..hi];
            let a = if epsilon.flip(rng) {
                explore(plan, rng, hi - lo)
            } else {
                first_minimiser(here)
            };
            let e = lo + a;
            let y = successor[e] as usize;
            let target = cost[e].plus(&v[y]);
            let new = match rate {
                None => target,
                Some(rate) => V::blend(&q[e], target, rate),
            };
            let old = std::mem::replace(&mut q[e], new);
            // Refresh V(s): only s's minimum can have changed, and only if the new value is
            // below it or the old value was it.
            let new = &q[e];
            // Both conditions are evaluated and combined without short-circuits: which holds is
            // data, and one branch on their union is mispredicted far less often than a chain of
            // three (27 % less time per run on Problem 10, ε = 0.9; docs/speed.md).
            let lower = *new < v[s];
            let moved_minimum = (old == v[s]) & (*new != old);
            let refreshed = if lower | moved_minimum {
                Some(if lower {
                    new.clone()
                } else {
                    minimum(&q[lo..hi])
                })
            } else {
                None
            };
            let changed = refreshed.is_some();
            if let Some(value) = refreshed {
                let was_optimal = v[s] == optimum[s];
                v[s] = value;
                if tracked[s] {
                    let is_optimal = v[s] == optimum[s];
                    if is_optimal && !was_optimal {
                        optimal_count += 1;
                    } else if was_optimal && !is_optimal {
                        optimal_count -= 1;
                    }
                }
            }
            actions += 1;
            step += 1;
            observer.update(s, a, &old, &q[e], v);
            if reference {
                until_check -= 1;
                if until_check == 0 {
                    until_check = REFERENCE_CHECK_INTERVAL;
                    if optimal_count == tracked_total {
                        if converged_at.is_none() {
                            pending |= PENDING_CONVERGED;
                        }
                        converged_at = Some(actions);
                    }
                    if initial_optimal_at.is_none() && v[x1] == optimum[x1] {
                        initial_optimal_at = Some(actions);
                        pending |= PENDING_INITIAL;
                    }
                }
            } else if changed {
                if converged_at.is_none() && optimal_count == tracked_total {
                    converged_at = Some(actions);
                    pending |= PENDING_CONVERGED;
                }
                if s == x1 && initial_optimal_at.is_none() && v[x1] == optimum[x1] {
                    initial_optimal_at = Some(actions);
                    pending |= PENDING_INITIAL;
                }
            }
            s = y;
            if is_goal[y] {
                if goal_discovered_at.is_none() {
                    goal_discovered_at = Some(actions);
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
        self.optimal_count = optimal_count;
        self.converged_at = converged_at;
        self.initial_optimal_at = initial_optimal_at;
        self.goal_discovered_at = goal_discovered_at;
        self.pending = pending;
        if ended || step >= max_steps {
            self.end_episode();
        }
    }
}

/// The index of the first minimum (ties go to the earlier action). `values` is non-empty.
#[inline]
fn first_minimiser<V: PartialOrd>(values: &[V]) -> usize {
    let mut best = 0;
    for i in 1..values.len() {
        if values[i] < values[best] {
            best = i;
        }
    }
    best
}

/// The minimum of a non-empty slice.
#[inline]
fn minimum<V: CostValue>(values: &[V]) -> V {
    values[first_minimiser(values)].clone()
}

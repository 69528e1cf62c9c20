//! Three objectives, exact, on any stochastic problem: the paper's
//! *truecost* (least expected cost among the policies that reach a goal with probability 1,
//! docs/spec.md §3), *reach* (the greatest probability of reaching a goal) and *discounted* (the RL
//! formulation: rewards discounted by `α ∈ (0, 1)`, maximised).
//!
//! All three reduce to the exact stochastic-shortest-path optimum of
//! [`crate::stochastic::policy_iteration::optimum`] (policy iteration with exact rational linear
//! solves) on an auxiliary problem; nothing is iterated in floating point:
//! * **truecost** — the problem itself.
//! * **reach** — first the graph precomputation of probabilistic model checking: `Z` = the
//!   states that cannot reach a goal (probability 0), `S1` = the states from which some policy
//!   reaches a goal with probability 1 (the almost-sure fixpoint of
//!   [`crate::stochastic::properness`]). Only the remaining *maybe* states `M` are solved: in
//!   the problem whose goals are all states outside `M` and whose stage cost is the probability
//!   of stepping into `Z`, the least expected cost over proper policies is `1 − max P(reach
//!   XG)` (a reach-optimal policy that is proper for `XG ∪ S1 ∪ Z` exists: strict policy
//!   improvement from a proper policy stays proper, and a proper fixed point `v = max_u P_u v`
//!   dominates every policy). On grids with noise every state is in `S1` and nothing is
//!   solved.
//!   The least success probability over a set of policies uses the dual construction: `S0` =
//!   the states from which some policy avoids the goals forever (greatest fixpoint, probability
//!   0), `A1` = the states from which no policy reaches `S0` (probability 1), goals everything
//!   outside `M = ∁(S0 ∪ A1)`, stage cost = the probability of stepping into `XG ∪ A1` (every
//!   policy is proper there).
//! * **discounted** — a killed process: every step continues with probability `α` and ends in an
//!   extra absorbing state with `1 − α`; rewards are shifted to costs `R − r ≥ 0`
//!   (`R = max(0, max r)`), and an ended episode (goal, trap) keeps paying `R` (reward 0). Then
//!   `V_α(x) = R/(1 − α) − C*(x)` exactly, and the discount-optimal actions are those with
//!   `Q = C*` in the auxiliary problem.
//!
//! Every objective reports its optimal policy's success probability — as `{min, max}` over all
//! the policies optimal for it (any choice among tied optimal actions) — and the expected
//! truecost and number of steps of the policy it reports (`+∞` if that policy is improper).
//! The reach objective reports, on `S1`, the truecost-optimal policy (it reaches a goal with
//! probability 1 and costs least there), so its expected truecost is `G*` (finite exactly when
//! the initial states are in `S1`) and costs one run of the exact optimum rather than an
//! exact evaluation of an arbitrary reach-optimal policy (whose cost can exceed `10³⁰⁰`).
//! Without its cost ([`PolicyCost::IfInfinite`]) the reach objective is graph analysis and
//! exact solves of the maybe-states only, and reports the attractor policy on `S1`.
//! The truecost objective's policy costs `G*`, read off the optimum; the other objectives'
//! policies are evaluated by one exact solve each, reduced at the initial states only.
//! With an initial distribution (Taxi), values at "the initial state" are expectations over it.

pub mod actions;
pub mod parametric;
pub mod report;

pub use report::facts;

use num_traits::{One, Signed, Zero};

use crate::envs::Environment;
use crate::model::file::FileObjective;
use crate::model::StateId;
use crate::stochastic::policy_iteration::{evaluate_at, optimum};
use crate::stochastic::properness::{almost_sure, avoids, reaches};
use crate::stochastic::{
    Outcome, OutcomeKind, StochasticAction, StochasticError, StochasticProblem,
};
use crate::value::{Extended, Rational};

/// A problem with everything the three objectives need.
#[derive(Clone, Debug)]
pub struct Model {
    /// What it is (the `--env` text, a problem number or a file name), printable
    /// ([`crate::echo::printable`]): reports print it as it is.
    pub name: String,
    /// The truecost problem: stage costs, goals; traps (non-goal states where the episode ends)
    /// have a single zero-cost self-loop.
    pub problem: StochasticProblem,
    /// Per action of [`Self::problem`]: the expected reward of the discounted objective
    /// (Gymnasium's rewards for environments, a problem file's own rewards when it gives them,
    /// the negated stage cost otherwise).
    pub reward: Vec<Rational>,
    /// Per state: the episode is over (goals, traps, the terminal states a problem file
    /// lists): no reward any more.
    pub terminal: Vec<bool>,
    /// The initial state distribution (a single state with probability 1 for paper problems
    /// and for files that name one initial state).
    pub initial: Vec<(StateId, Rational)>,
    /// The terminal bonus `M` of Proposition 4, if the benchmark has one (Taxi's +20).
    pub terminal_bonus: Option<Rational>,
    /// Where the rewards come from (said in every output).
    pub reward_source: &'static str,
}

/// [`Model::reward_source`] of a model whose rewards a problem file gives.
pub const FILE_REWARDS: &str = "the file's rewards";

/// One of the three objectives.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Objective {
    /// The paper's: least expected cost among the policies reaching a goal with probability 1.
    Truecost,
    /// The greatest probability of reaching a goal.
    Reach,
    /// The discounted rewards, maximised, with the discount factor `α ∈ (0, 1)`.
    Discounted(Rational),
}

impl Objective {
    /// The objective's name on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Objective::Truecost => "truecost",
            Objective::Reach => "reach",
            Objective::Discounted(_) => "discounted",
        }
    }
}

/// Why an objective could not be computed. One line each.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ObjectiveError {
    /// `α ∉ (0, 1)`.
    #[error("the discount factor alpha must be in (0, 1), got {0}")]
    Alpha(String),
    /// The exact solver refused (sizes, denominators).
    #[error("{0}")]
    Solver(#[from] StochasticError),
    /// The discounted objective's killed-process construction passed a limit of the exact
    /// solver: the text names the quantity (a probability denominator times `α`'s, or the
    /// largest reward minus a reward), its value and the bound.
    #[error("{0}")]
    Discounted(String),
}

/// `{min, max}` of a quantity over the tied optimal policies.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Bounds {
    /// The least value.
    pub min: Rational,
    /// The greatest value.
    pub max: Rational,
}

/// The answer for one objective.
#[derive(Clone, Debug)]
pub struct Solution {
    /// The objective.
    pub objective: Objective,
    /// The optimal value per state (truecost: `G*`, `+∞` allowed; reach: the probability;
    /// discounted: `V_α`, possibly negative).
    pub values: Vec<Extended>,
    /// The optimal value at the initial distribution.
    pub value_initial: Extended,
    /// The reported optimal policy: an action (global id of [`Model::problem`]) per state,
    /// `None` at ended episodes and where the objective prescribes nothing (truecost where
    /// `G* = +∞`: every policy is optimal there).
    pub policy: Vec<Option<usize>>,
    /// The success probability (reaching a goal) over all optimal policies, at the initial
    /// distribution.
    pub success: Bounds,
    /// The success probability of the reported policy (`0` where it prescribes nothing).
    pub policy_success: Rational,
    /// The expected truecost of the reported policy at the initial distribution (`+∞` if improper).
    pub truecost: Extended,
    /// The expected number of steps of the reported policy at the initial distribution
    /// (`+∞` if improper).
    pub steps: Extended,
    /// Whether [`Self::truecost`] and [`Self::steps`] were computed: always, except for the
    /// reach objective solved without its cost ([`Model::solve_with`] with
    /// [`PolicyCost::IfInfinite`]) when every initial state reaches a goal surely (both are
    /// finite then, and both fields hold `+∞` as a placeholder that means nothing).
    pub costs_computed: bool,
}

/// Whether [`Model::solve_with`] computes the reported policy's expected truecost and steps
/// for the reach objective (the other objectives always compute them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolicyCost {
    /// Computed: the reported policy is truecost-optimal where a goal is reached surely, its
    /// expected truecost is `G*` (one run of the exact optimum) and its steps one more exact
    /// evaluation ([`Model::solve`]).
    Computed,
    /// Only where it is `+∞` without work (some initial state reaches a goal with
    /// probability below 1: the reported policy is improper there): the reach probability is
    /// then graph analysis and exact solves of the maybe-states only, and the reported policy
    /// on the states that reach a goal surely is the attractor policy of
    /// [`crate::stochastic::properness::almost_sure`] (which does so too).
    IfInfinite,
}

impl Model {
    /// The model of a stochastic problem: discounted rewards are the negated stage costs
    /// (the paper's reward form, docs/spec.md §1); goals and action-less states end the episode.
    pub fn from_problem(problem: StochasticProblem, name: String) -> Self {
        let reward = (0..problem.action_total())
            .map(|a| -problem.cost(a).clone())
            .collect();
        let terminal = (0..problem.states())
            .map(|x| problem.is_goal(x) || problem.actions(x).is_empty())
            .collect();
        let initial = vec![(problem.initial(), Rational::one())];
        Model {
            name: crate::echo::printable(&name),
            problem,
            reward,
            terminal,
            initial,
            terminal_bonus: None,
            reward_source: "negated stage costs",
        }
    }

    /// The model with what a problem file says besides its problem ([`FileObjective`], read
    /// with the file's problem, of which `self` must keep every state and every action in
    /// order): the file's rewards replace the negated stage costs (and [`Self::reward_source`]
    /// says so), the listed states end the episode, and the file's initial distribution
    /// replaces the problem's single initial state (every value "at the initial state" is then
    /// the expectation over it, as for an environment's).
    ///
    /// # Panics
    ///
    /// If the file's rewards are not one per action of [`Self::problem`].
    ///
    /// ```
    /// use truecost::objectives::{Model, Objective};
    /// use truecost::stochastic::file::{from_json_with_objective, ProblemFile};
    /// // 0 -> 1 (goal): reward 1 on the way in; staying at 0 has reward 0.
    /// let text = r#"{"initial": 0, "goals": [1], "actions": [
    ///     [{"to": 0, "cost": "1", "reward": "0"}, {"to": 1, "cost": "5", "reward": "1"}], []]}"#;
    /// let (ProblemFile::Deterministic(d), extra) = from_json_with_objective(text).unwrap() else { panic!() };
    /// let p = truecost::stochastic::StochasticProblem::from_deterministic(
    ///     &d, truecost::stochastic::NoiseModel::Paper, &truecost::stochastic::Predictability::one()).unwrap();
    /// let m = Model::from_problem(p.clone(), "file".into()).with_file_objective(&extra);
    /// assert_eq!(m.reward_source, "the file's rewards");
    /// let v = m.solve(&Objective::Discounted("1/2".parse().unwrap())).unwrap();
    /// assert_eq!(v.value_initial.to_string(), "1"); // straight in: reward 1
    /// // Started at 0 or at the goal with probability 1/2 each: 1/2 * 1 + 1/2 * 0.
    /// let drawn = text.replace(r#""initial": 0"#, r#""initial": [{"state": 0, "p": "1/2"}, {"state": 1, "p": "1/2"}]"#);
    /// let (_, extra) = from_json_with_objective(&drawn).unwrap();
    /// let m = Model::from_problem(p, "file".into()).with_file_objective(&extra);
    /// assert_eq!(m.initial.len(), 2);
    /// let v = m.solve(&Objective::Discounted("1/2".parse().unwrap())).unwrap();
    /// assert_eq!(v.value_initial.to_string(), "1/2");
    /// ```
    pub fn with_file_objective(mut self, file: &FileObjective) -> Self {
        if let Some(rewards) = &file.rewards {
            assert_eq!(
                rewards.len(),
                self.problem.action_total(),
                "one reward per action"
            );
            self.reward = rewards.clone();
            self.reward_source = FILE_REWARDS;
        }
        for &x in &file.terminal {
            self.terminal[x] = true;
        }
        if let Some(initial) = &file.initial {
            self.initial = initial.clone();
        }
        self
    }

    /// The model of a Gymnasium environment: the same states and, at every
    /// state where the episode runs, the same actions in Gymnasium's order (so an action's
    /// index in `U(x)` is Gymnasium's action number). An action's stage cost is the expected
    /// truecost of its outcomes ([`Environment::truecost_cost`]) and its reward the expected
    /// Gymnasium reward — equal expectations give equal expected totals, discounted or not.
    /// Outcomes to the same state are merged, zero-probability entries dropped. Goals have no
    /// action (termination); traps a single zero-cost self-loop.
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::Model;
    /// let env = EnvSpec::parse("frozenlake").unwrap().build().unwrap();
    /// let m = Model::from_environment(&env).unwrap();
    /// let a = m.problem.actions(0).start; // LEFT at the start: 1/3 up (stays), 1/3 left (stays), 1/3 down
    /// let out: Vec<_> = m.problem.outcomes(a).iter().map(|o| (o.successor, o.probability.to_string())).collect();
    /// assert_eq!(out, vec![(0, "2/3".into()), (4, "1/3".into())]);
    /// ```
    pub fn from_environment(env: &Environment) -> Result<Self, StochasticError> {
        let n = env.states();
        let mut actions = Vec::with_capacity(n);
        let mut reward = Vec::new();
        let mut terminal = vec![false; n];
        for (x, row) in env.table.iter().enumerate() {
            if env.goals.contains(&x) {
                terminal[x] = true;
                actions.push(Vec::new());
            } else if env.traps.contains(&x) {
                terminal[x] = true;
                actions.push(vec![StochasticAction {
                    cost: Rational::zero(),
                    outcomes: vec![Outcome {
                        successor: x,
                        probability: Rational::one(),
                        kind: OutcomeKind::Stay,
                    }],
                }]);
                reward.push(Rational::zero());
            } else {
                let mut list = Vec::with_capacity(row.len());
                for transitions in row {
                    let mut cost = Rational::zero();
                    let mut r = Rational::zero();
                    let mut outcomes: Vec<Outcome> = Vec::new();
                    for t in transitions.iter().filter(|t| t.probability.is_positive()) {
                        cost += &t.probability * env.truecost_cost(t);
                        r += &t.probability * Rational::from_integer(t.reward.into());
                        match outcomes.iter_mut().find(|o| o.successor == t.next) {
                            Some(o) => o.probability += &t.probability,
                            None => outcomes.push(Outcome {
                                successor: t.next,
                                probability: t.probability.clone(),
                                kind: OutcomeKind::Listed,
                            }),
                        }
                    }
                    list.push(StochasticAction { cost, outcomes });
                    reward.push(r);
                }
                actions.push(list);
            }
        }
        let problem = StochasticProblem::new(actions, env.initial[0].0, env.goals.clone())?;
        Ok(Model {
            name: crate::echo::printable(&env.spec),
            problem,
            reward,
            terminal,
            initial: env.initial.clone(),
            terminal_bonus: env.terminal_bonus(),
            reward_source: "Gymnasium's rewards",
        })
    }

    /// The expectation of per-state values over the initial distribution (`+∞` if any state
    /// of positive probability has `+∞`).
    pub fn at_initial(&self, values: &[Extended]) -> Extended {
        self.at_initial_of(|x| values[x].clone())
    }

    /// [`Self::at_initial`] of the values `value(x)`, asked at the initial states only.
    fn at_initial_of(&self, value: impl Fn(StateId) -> Extended) -> Extended {
        expectation(self.initial.iter().map(|(x, p)| (value(*x), p)))
    }

    /// [`Self::at_initial`] of a policy's exact expected total cost in `problem` (the model's
    /// states with other costs: [`Self::problem`] itself, or [`Self::unit_costs`] for the
    /// expected number of steps), solved once and reduced at the initial states only
    /// ([`evaluate_at`]).
    fn evaluated_at_initial(
        &self,
        problem: &StochasticProblem,
        policy: &[Option<usize>],
    ) -> Result<Extended, StochasticError> {
        let initial: Vec<StateId> = self.initial.iter().map(|(x, _)| *x).collect();
        let values = evaluate_at(problem, policy, &initial)?;
        Ok(expectation(
            values.into_iter().zip(self.initial.iter().map(|(_, p)| p)),
        ))
    }

    pub(crate) fn at_initial_rational(&self, values: &[Rational]) -> Rational {
        self.initial
            .iter()
            .map(|(x, p)| &values[*x] * p)
            .fold(Rational::zero(), |a, b| a + b)
    }

    /// The same problem with every action costing 1 (0 where the episode is over): expected
    /// steps. Every action is kept, a goal's too (an evaluation ends at goals whatever their
    /// actions), so that the action ids are those of [`Self::problem`] and a policy of it
    /// applies as it is.
    fn unit_costs(&self) -> Result<StochasticProblem, StochasticError> {
        let p = &self.problem;
        let actions = (0..p.states())
            .map(|x| {
                let cost = if self.terminal[x] {
                    Rational::zero()
                } else {
                    Rational::one()
                };
                p.actions(x)
                    .map(|a| StochasticAction {
                        cost: cost.clone(),
                        outcomes: p.outcomes(a).to_vec(),
                    })
                    .collect()
            })
            .collect();
        StochasticProblem::new(actions, p.initial(), p.goals().to_vec())
    }

    /// Solves one objective exactly (module docs).
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::{Model, Objective};
    /// let env = EnvSpec::parse("frozenlake:slippery=false").unwrap().build().unwrap();
    /// let m = Model::from_environment(&env).unwrap();
    /// let t = m.solve(&Objective::Truecost).unwrap();
    /// assert_eq!(t.value_initial.to_string(), "6"); // six steps around the holes
    /// let d = m.solve(&Objective::Discounted("9/10".parse().unwrap())).unwrap();
    /// assert_eq!(d.value_initial.to_string(), "59049/100000"); // 0.9^5: the reward comes on the sixth step
    /// assert_eq!(d.success.min.to_string(), "1");
    /// ```
    pub fn solve(&self, objective: &Objective) -> Result<Solution, ObjectiveError> {
        self.solve_with(objective, PolicyCost::Computed)
    }

    /// [`Self::solve`], with the reach objective's policy cost computed or not
    /// ([`PolicyCost`]); the other objectives ignore `cost`.
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::{Model, Objective, PolicyCost};
    /// let sure = Model::from_environment(&EnvSpec::parse("frozenlake:slippery=false").unwrap().build().unwrap()).unwrap();
    /// let r = sure.solve_with(&Objective::Reach, PolicyCost::IfInfinite).unwrap();
    /// assert_eq!((r.value_initial.to_string(), r.costs_computed), ("1".into(), false));
    /// let r = sure.solve_with(&Objective::Reach, PolicyCost::Computed).unwrap();
    /// assert_eq!((r.truecost.to_string(), r.costs_computed), ("6".into(), true));
    /// // Slippery: the start reaches the goal with probability 14/17 at best, so the reach
    /// // policy's cost is +∞, known without computing it.
    /// let slippery = Model::from_environment(&EnvSpec::parse("frozenlake").unwrap().build().unwrap()).unwrap();
    /// let r = slippery.solve_with(&Objective::Reach, PolicyCost::IfInfinite).unwrap();
    /// assert_eq!((r.truecost.to_string(), r.steps.to_string(), r.costs_computed), ("inf".into(), "inf".into(), true));
    /// ```
    pub fn solve_with(
        &self,
        objective: &Objective,
        cost: PolicyCost,
    ) -> Result<Solution, ObjectiveError> {
        let p = &self.problem;
        let n = p.states();
        let (values, policy, allowed): (Vec<Extended>, Vec<Option<usize>>, Vec<bool>) =
            match objective {
                Objective::Truecost => {
                    let opt = optimum(p)?;
                    let allowed = (0..p.action_total())
                        .map(|a| {
                            let x = p.state_of(a);
                            opt.unreduced(x).is_none() || opt.is_optimal_action(p, a)
                        })
                        .collect();
                    let policy = opt.policy_actions().to_vec();
                    (opt.into_cost_to_go(), policy, allowed)
                }
                Objective::Reach => return self.reach(cost),
                Objective::Discounted(alpha) => self.discounted(alpha)?,
            };
        let allow = |a: usize| allowed[a];
        let (max, _) = max_reach(p, &allow)?;
        let min = min_reach(p, &allow)?;
        let success = Bounds {
            min: self.at_initial_rational(&min),
            max: self.at_initial_rational(&max),
        };
        let chosen = |a: usize| policy[p.state_of(a)] == Some(a);
        let policy_success = self.at_initial_rational(&min_reach(p, &chosen)?);
        let value_initial = self.at_initial(&values);
        // The truecost objective's policy is optimal and proper wherever `G*` is finite, and
        // prescribes nothing where it is `+∞`: its expected truecost is `G*` itself. The other
        // objectives' policies are evaluated, reduced at the initial states only.
        let truecost = match objective {
            Objective::Truecost => value_initial.clone(),
            _ => self.evaluated_at_initial(p, &policy)?,
        };
        let steps = self.evaluated_at_initial(&self.unit_costs()?, &policy)?;
        debug_assert_eq!(values.len(), n);
        Ok(Solution {
            objective: objective.clone(),
            values,
            value_initial,
            policy,
            success,
            policy_success,
            truecost,
            steps,
            costs_computed: true,
        })
    }

    /// The reach objective: the greatest probability of reaching a goal by [`max_reach`]
    /// (graph analysis, exact solves of the maybe-states only). The policy reported attains it
    /// everywhere: [`max_reach`]'s on the states where the probability is below 1, and on the
    /// states where some policy reaches a goal with probability 1 the truecost-optimal one
    /// (which does, and costs least there). Its expected truecost is therefore `G*` at the
    /// initial distribution (`+∞` unless every initial state reaches a goal surely) and costs
    /// one run of the exact optimum; its expected number of steps one more exact evaluation,
    /// only when that is finite. With [`PolicyCost::IfInfinite`] none of this runs: the
    /// policy on the surely-reaching states is [`max_reach`]'s attractor policy, and the cost
    /// and steps are `+∞` when some initial state reaches a goal with probability below 1,
    /// not computed otherwise.
    fn reach(&self, cost: PolicyCost) -> Result<Solution, ObjectiveError> {
        let p = &self.problem;
        let (max, mut policy) = max_reach(p, &|_| true)?;
        let surely = self.initial.iter().all(|(x, _)| max[*x].is_one());
        let values: Vec<Extended> = max.into_iter().map(Extended::Finite).collect();
        let opt = match cost {
            PolicyCost::Computed => Some(optimum(p)?),
            PolicyCost::IfInfinite => None,
        };
        for (x, a) in opt
            .iter()
            .flat_map(|o| o.policy_actions().iter().enumerate())
        {
            if a.is_some() {
                policy[x] = *a;
            }
        }
        let value_initial = self.at_initial(&values);
        let v = value_initial
            .finite()
            .cloned()
            .unwrap_or_else(Rational::zero);
        let chosen = |a: usize| policy[p.state_of(a)] == Some(a);
        let policy_success = self.at_initial_rational(&min_reach(p, &chosen)?);
        let (truecost, steps) = match &opt {
            None => (Extended::Infinite, Extended::Infinite),
            Some(opt) => {
                let truecost = self.at_initial_of(|x| opt.cost_to_go(x));
                let steps = match truecost {
                    Extended::Infinite => Extended::Infinite,
                    Extended::Finite(_) => {
                        self.evaluated_at_initial(&self.unit_costs()?, &policy)?
                    }
                };
                (truecost, steps)
            }
        };
        Ok(Solution {
            objective: Objective::Reach,
            values,
            value_initial,
            policy,
            success: Bounds {
                min: v.clone(),
                max: v,
            },
            policy_success,
            truecost,
            steps,
            costs_computed: opt.is_some() || !surely,
        })
    }

    /// The discounted objective by the killed-process construction (module docs).
    #[allow(clippy::type_complexity)]
    pub(crate) fn discounted(
        &self,
        alpha: &Rational,
    ) -> Result<(Vec<Extended>, Vec<Option<usize>>, Vec<bool>), ObjectiveError> {
        if !(alpha.is_positive() && alpha < &Rational::one()) {
            return Err(ObjectiveError::Alpha(alpha.to_string()));
        }
        let p = &self.problem;
        let n = p.states();
        let top = self
            .reward
            .iter()
            .cloned()
            .fold(Rational::zero(), |a, b| if b > a { b } else { a });
        let kill = n;
        let end = Rational::one() - alpha;
        let mut actions: Vec<Vec<StochasticAction>> = Vec::with_capacity(n + 1);
        let mut aux_of: Vec<Option<usize>> = Vec::new();
        for x in 0..n {
            if self.terminal[x] {
                actions.push(vec![StochasticAction {
                    cost: top.clone(),
                    outcomes: vec![listed(x, alpha.clone()), listed(kill, end.clone())],
                }]);
                aux_of.push(None);
            } else {
                let mut list = Vec::new();
                for a in p.actions(x) {
                    let mut outcomes: Vec<Outcome> = p
                        .outcomes(a)
                        .iter()
                        .map(|o| listed(o.successor, &o.probability * alpha))
                        .collect();
                    outcomes.push(listed(kill, end.clone()));
                    list.push(StochasticAction {
                        cost: &top - &self.reward[a],
                        outcomes,
                    });
                    aux_of.push(Some(a));
                }
                actions.push(list);
            }
        }
        actions.push(Vec::new());
        discounted_denominators(&actions, p, alpha)?;
        let aux = StochasticProblem::new(actions, p.initial(), vec![kill])?;
        let opt = optimum(&aux).map_err(|e| match e {
            StochasticError::CostTooLarge { state } => {
                ObjectiveError::Discounted(discounted_cost_text(self, state, &top, alpha))
            }
            e => e.into(),
        })?;
        let scale = &top / &end;
        let values: Vec<Extended> = opt.cost_to_go_all()[..n]
            .iter()
            .map(|c| Extended::Finite(&scale - c.finite().expect("every state is proper: α < 1")))
            .collect();
        let mut allowed = vec![true; p.action_total()];
        let mut policy = vec![None; n];
        for (aux_a, orig) in aux_of.iter().enumerate() {
            if let Some(a) = *orig {
                allowed[a] = opt.is_optimal_action(&aux, aux_a);
            }
        }
        for (x, slot) in policy.iter_mut().enumerate() {
            if !self.terminal[x] {
                *slot = opt.policy_actions()[x].and_then(|aux_a| aux_of[aux_a]);
            }
        }
        Ok((values, policy, allowed))
    }
}

/// Refuses a state of the killed-process construction whose probabilities (`α · p` and
/// `1 − α`) have a common denominator over the exact solver's `2^62`
/// ([`crate::stochastic::problem::MAX_DENOMINATOR`]), naming the state, the common denominator
/// of the problem's own probabilities there, `α`'s denominator and the bound.
fn discounted_denominators(
    actions: &[Vec<StochasticAction>],
    problem: &StochasticProblem,
    alpha: &Rational,
) -> Result<(), ObjectiveError> {
    use num_integer::Integer;
    let bound = num_bigint::BigInt::from(crate::stochastic::problem::MAX_DENOMINATOR);
    for (x, list) in actions.iter().enumerate().take(problem.states()) {
        let mut lcm = num_bigint::BigInt::one();
        for o in list.iter().flat_map(|a| &a.outcomes) {
            lcm = lcm.lcm(o.probability.denom());
        }
        if lcm > bound {
            let mut own = num_bigint::BigInt::one();
            for a in problem.actions(x) {
                for o in problem.outcomes(a) {
                    own = own.lcm(o.probability.denom());
                }
            }
            return Err(ObjectiveError::Discounted(format!(
                "state {x}: at alpha = {} the discounted objective multiplies the probabilities by alpha; their common denominator there, {own} (the problem's) times alpha's {}, is {lcm} > 2^62, the exact solver's limit",
                crate::stochastic::short_text(alpha),
                alpha.denom(),
            )));
        }
    }
    Ok(())
}

/// The refusal of a killed-process construction whose stage cost at `state` (the largest reward
/// `top` minus the state's rewards, or `top` itself where the episode is over) times the
/// probabilities' denominators passes the exact solver's `2^100`: names the rewards, not the
/// stage costs.
fn discounted_cost_text(model: &Model, state: StateId, top: &Rational, alpha: &Rational) -> String {
    let short = crate::stochastic::short_text;
    let charged = if model.terminal.get(state).copied().unwrap_or(false) {
        format!(
            "the episode is over there and the discounted objective (killed-process construction) charges it the model's largest reward, {}, per step",
            short(top)
        )
    } else {
        let least = model
            .problem
            .actions(state)
            .map(|a| &model.reward[a])
            .min()
            .cloned()
            .unwrap_or_else(Rational::zero);
        format!(
            "the discounted objective (killed-process construction) charges the model's largest reward, {}, minus this state's least reward, {}, per step",
            short(top),
            short(&least)
        )
    };
    format!(
        "state {state}: {charged}; times the probabilities' denominators (alpha's denominator {} included) that exceeds 2^100, the exact solver's limit",
        alpha.denom()
    )
}

/// `Σ p·v` over the (value, probability) pairs; `+∞` if a value is.
fn expectation<'a>(terms: impl Iterator<Item = (Extended, &'a Rational)>) -> Extended {
    let mut sum = Rational::zero();
    for (v, p) in terms {
        match v {
            Extended::Finite(v) => sum += v * p,
            Extended::Infinite => return Extended::Infinite,
        }
    }
    Extended::Finite(sum)
}

fn listed(successor: StateId, probability: Rational) -> Outcome {
    Outcome {
        successor,
        probability,
        kind: OutcomeKind::Listed,
    }
}

/// A problem on the same states with other goals and actions: `action(a)` gives the new form of
/// the original action `a` (or `None` to drop it); new goals get no actions. Returns the
/// problem and, per new action, the original action id.
pub(crate) fn derive(
    problem: &StochasticProblem,
    goals: Vec<StateId>,
    mut action: impl FnMut(usize) -> Option<StochasticAction>,
) -> Result<(StochasticProblem, Vec<usize>), StochasticError> {
    let n = problem.states();
    let mut is_goal = vec![false; n];
    for &g in &goals {
        is_goal[g] = true;
    }
    let mut origin = Vec::new();
    let actions = (0..n)
        .map(|x| {
            if is_goal[x] {
                return Vec::new();
            }
            problem
                .actions(x)
                .filter_map(|a| {
                    let new = action(a)?;
                    origin.push(a);
                    Some(new)
                })
                .collect()
        })
        .collect();
    Ok((
        StochasticProblem::new(actions, problem.initial(), goals)?,
        origin,
    ))
}

/// The greatest probability of reaching a goal from every state using only the actions with
/// `allowed(a)`, with a policy attaining it (proper for the goals and the probability-0
/// states). The standard precomputation of probabilistic model checking first: the states
/// that cannot reach a goal (probability 0, a backward search) and those where some policy
/// reaches one with probability 1 ([`almost_sure`]: probability 1, where the attractor policy
/// is used); only the remaining *maybe* states are solved exactly, as the least expected cost
/// of stepping into a probability-0 state in the problem whose goals are all the other states
/// (module docs).
pub fn max_reach(
    problem: &StochasticProblem,
    allowed: &dyn Fn(usize) -> bool,
) -> Result<(Vec<Rational>, Vec<Option<usize>>), StochasticError> {
    let n = problem.states();
    let goal: Vec<bool> = (0..n).map(|x| problem.is_goal(x)).collect();
    let zero: Vec<bool> = reaches(problem, allowed, &goal, &|_| true)
        .into_iter()
        .map(|r| !r)
        .collect();
    let sure = almost_sure(problem, allowed);
    let maybe: Vec<bool> = (0..n).map(|x| !zero[x] && !sure.finite[x]).collect();
    let mut values: Vec<Rational> = (0..n)
        .map(|x| {
            if sure.finite[x] {
                Rational::one()
            } else {
                Rational::zero()
            }
        })
        .collect();
    let mut policy = sure.attractor;
    if let Some((opt, origin)) = maybe_optimum(problem, allowed, &maybe, &zero)? {
        for x in (0..n).filter(|&x| maybe[x]) {
            values[x] = Rational::one()
                - opt
                    .cost_to_go(x)
                    .finite()
                    .expect("a state that can reach a goal has a proper policy");
            policy[x] = opt.policy_actions()[x].map(|a| origin[a]);
        }
    }
    Ok((values, policy))
}

/// The exact optimum of the maybe-states (none if there are none): the problem whose goals are
/// all the states outside `maybe`, with the allowed actions, each costing its probability of
/// stepping into `costly`; with the original id of every action of that problem.
fn maybe_optimum(
    problem: &StochasticProblem,
    allowed: &dyn Fn(usize) -> bool,
    maybe: &[bool],
    costly: &[bool],
) -> Result<Option<(crate::stochastic::policy_iteration::Optimum, Vec<usize>)>, StochasticError> {
    if !maybe.contains(&true) {
        return Ok(None);
    }
    let goals: Vec<StateId> = (0..problem.states()).filter(|&x| !maybe[x]).collect();
    let (aux, origin) = derive(problem, goals, |a| {
        allowed(a).then(|| StochasticAction {
            cost: probability_into(problem, a, costly),
            outcomes: problem.outcomes(a).to_vec(),
        })
    })?;
    Ok(Some((optimum(&aux)?, origin)))
}

/// The probability that action `a` steps into a state of `set`.
fn probability_into(problem: &StochasticProblem, a: usize, set: &[bool]) -> Rational {
    problem
        .outcomes(a)
        .iter()
        .filter(|o| set[o.successor])
        .map(|o| o.probability.clone())
        .fold(Rational::zero(), |s, p| s + p)
}

/// The least probability of reaching a goal from every state over the policies using only the
/// actions with `allowed(a)` (a state without allowed action ends there, unsuccessfully). The
/// precomputation first: the states from which some policy avoids the goals forever
/// ([`avoids`]: probability 0) and those from which no policy can reach one of them
/// (probability 1, a backward search); only the remaining states are solved exactly, as the
/// least expected cost of stepping into a probability-1 state in the problem whose goals are
/// all the other states (every policy is proper there).
pub fn min_reach(
    problem: &StochasticProblem,
    allowed: &dyn Fn(usize) -> bool,
) -> Result<Vec<Rational>, StochasticError> {
    let n = problem.states();
    let avoid = avoids(problem, allowed);
    let one: Vec<bool> = reaches(problem, allowed, &avoid, &|x| !problem.is_goal(x))
        .into_iter()
        .map(|r| !r)
        .collect();
    let maybe: Vec<bool> = (0..n).map(|x| !avoid[x] && !one[x]).collect();
    let mut values: Vec<Rational> = (0..n)
        .map(|x| {
            if one[x] {
                Rational::one()
            } else {
                Rational::zero()
            }
        })
        .collect();
    if let Some((opt, _)) = maybe_optimum(problem, allowed, &maybe, &one)? {
        for x in (0..n).filter(|&x| maybe[x]) {
            values[x] = opt
                .cost_to_go(x)
                .finite()
                .cloned()
                .expect("every policy leaves the avoiding states' complement");
        }
    }
    Ok(values)
}

/// The objective named on the command line (`truecost`, `reach`, `discounted`), with `α`'s
/// exact decimal text for `discounted`.
///
/// ```
/// use truecost::objectives::Objective;
/// assert_eq!(truecost::objectives::parse_objective("discounted", Some("0.99")).unwrap(), Objective::Discounted("99/100".parse().unwrap()));
/// assert!(truecost::objectives::parse_objective("discounted", None).is_err());
/// assert!(truecost::objectives::parse_objective("reach", Some("0.9")).is_err());
/// ```
pub fn parse_objective(name: &str, alpha: Option<&str>) -> Result<Objective, String> {
    match (name, alpha) {
        ("truecost", None) => Ok(Objective::Truecost),
        ("reach", None) => Ok(Objective::Reach),
        ("discounted", Some(text)) => Ok(Objective::Discounted(parse_alpha(text)?)),
        ("discounted", None) => Err("--objective discounted needs --alpha A (in (0, 1))".into()),
        ("truecost" | "reach", Some(_)) => {
            Err("--alpha applies to --objective discounted only".into())
        }
        (other, _) => Err(format!(
            "unknown objective '{other}' (truecost, reach, discounted)"
        )),
    }
}

/// Parses a discount factor `α ∈ (0, 1)` from its exact text.
///
/// Its exact denominator must be at most `2^62`, the exact solvers' limit on a common
/// denominator (a discounted solve multiplies the probabilities by `α`): more digits than that
/// are refused here, naming the bound, with the value shortened.
///
/// ```
/// use truecost::objectives::parse_alpha;
/// assert_eq!(parse_alpha("0.25").unwrap(), "1/4".parse().unwrap());
/// let long = format!("0.{}", "1".repeat(300));
/// let err = parse_alpha(&long).unwrap_err();
/// assert!(err.contains("2^62") && err.contains("…") && err.len() < 300, "{err}");
/// ```
pub fn parse_alpha(text: &str) -> Result<Rational, String> {
    let a = crate::value::parse_rational(text)
        .map_err(|e| format!("alpha {}: {e}", crate::echo::echo(text)))?;
    if !(a.is_positive() && a < Rational::one()) {
        return Err(ObjectiveError::Alpha(crate::echo::echo(text)).to_string());
    }
    if a.denom().bits() > MAX_ALPHA_DENOMINATOR_BITS {
        return Err(format!(
            "the discount factor alpha = {} has an exact denominator of {} bits ({} decimal digits), above the {MAX_ALPHA_DENOMINATOR_BITS} bits (2^{MAX_ALPHA_DENOMINATOR_BITS}) the exact solvers take; give alpha with fewer digits",
            crate::echo::echo(text),
            a.denom().bits(),
            a.denom().to_string().len(),
        ));
    }
    Ok(a)
}

/// The bits of the largest denominator of `α` ([`parse_alpha`]): `2^62`, the exact solvers'
/// limit on a state's common denominator.
pub const MAX_ALPHA_DENOMINATOR_BITS: u64 = 62;

/// Where a model comes from: an environment, a paper problem or a problem file
/// (`--env` wherever `--problem`/`--file` is accepted).
#[derive(Clone, Debug)]
pub enum Source {
    /// `--env SPEC`.
    Env(String),
    /// `--problem N` (exact paper text, unit or Euclidean step costs), with `γ` and a noise
    /// model (γ = 1: deterministic).
    Paper {
        /// The problem number.
        id: usize,
        /// The step cost.
        step: crate::problems::StepCost,
        /// The noise model.
        noise: crate::stochastic::NoiseModel,
        /// `γ`.
        gamma: crate::stochastic::Predictability,
    },
    /// `--file F` (a deterministic file gets the noise model and `γ`).
    File {
        /// The file.
        path: std::path::PathBuf,
        /// The noise model.
        noise: crate::stochastic::NoiseModel,
        /// `γ`, if given (refused for files that list outcomes).
        gamma: Option<crate::stochastic::Predictability>,
        /// A DRN file's goal label and cost reward model (`--goal-label`, `--cost-reward`).
        names: crate::formats::drn::DrnNames,
    },
}

impl Source {
    /// Builds the model (reads files, builds environments). Errors are one line.
    pub fn load(&self) -> Result<Model, String> {
        use crate::stochastic::file::ProblemFile;
        match self {
            Source::Env(spec) => {
                let env = crate::envs::EnvSpec::parse(spec)
                    .and_then(|s| s.build())
                    .map_err(|e| e.to_string())?;
                Model::from_environment(&env).map_err(|e| e.to_string())
            }
            Source::Paper {
                id,
                step,
                noise,
                gamma,
            } => {
                let p = crate::stochastic::grid::exact_grid(*id, *step, *noise, gamma)
                    .map_err(|e| e.to_string())?;
                Ok(Model::from_problem(p, format!("paper problem {id}")))
            }
            Source::File {
                path,
                noise,
                gamma,
                names,
            } => {
                // Noise keeps the states and one action per move, in order: the file's rewards
                // (paid whatever the outcome, like the costs), its terminal self-loops and its
                // initial distribution carry over.
                let (file, extra) =
                    crate::formats::read_with_names(path, names).map_err(|e| e.to_string())?;
                let p = match file {
                    ProblemFile::Deterministic(d) => StochasticProblem::from_deterministic(
                        &d,
                        *noise,
                        gamma
                            .as_ref()
                            .unwrap_or(&crate::stochastic::Predictability::one()),
                    )
                    .map_err(|e| e.to_string())?,
                    ProblemFile::Stochastic(s) => {
                        if gamma.is_some() {
                            return Err("this problem file lists its own outcome probabilities; --gamma applies to deterministic problems".into());
                        }
                        *s
                    }
                };
                Ok(Model::from_problem(p, format!("file {}", path.display()))
                    .with_file_objective(&extra))
            }
        }
    }
}

impl Model {
    /// The problem as a problem file holds it (`export`), with what the file says besides the
    /// problem: the rewards as the file's `reward` fields, the terminal non-goal states (traps)
    /// as its `terminal` list and an initial distribution of two or more states (Taxi's 300) as
    /// its `initial` list (the problem's own initial state is the first of them), so that
    /// reading the file back gives this model.
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::Model;
    /// let m = Model::from_environment(&EnvSpec::parse("taxi").unwrap().build().unwrap()).unwrap();
    /// let (p, extra) = m.exportable();
    /// assert_eq!(p.states(), 500);
    /// let initial = extra.initial.unwrap();
    /// assert_eq!((initial.len(), initial[0].0, initial[0].1.to_string()), (300, p.initial(), "1/300".to_string()));
    /// assert_eq!(extra.rewards.unwrap().len(), p.action_total());
    /// let lake = Model::from_environment(&EnvSpec::parse("frozenlake").unwrap().build().unwrap()).unwrap();
    /// let (_, extra) = lake.exportable();
    /// assert_eq!(extra.terminal, [5, 7, 11, 12]); // the holes
    /// assert_eq!(extra.initial, None); // the start, state 0
    /// ```
    pub fn exportable(&self) -> (StochasticProblem, FileObjective) {
        let p = &self.problem;
        let extra = FileObjective {
            rewards: Some(self.reward.clone()),
            terminal: (0..p.states())
                .filter(|&x| self.terminal[x] && !p.is_goal(x))
                .collect(),
            initial: (self.initial.len() > 1).then(|| self.initial.clone()),
        };
        (p.clone(), extra)
    }
}

impl Model {
    /// The model as the certificate checker reads it ([`crate::certificate::Mdp`]): per state
    /// its goal and terminal flags, per action its stage cost, reward and outcomes.
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::Model;
    /// let m = Model::from_environment(&EnvSpec::parse("frozenlake").unwrap().build().unwrap()).unwrap();
    /// let mdp = m.mdp();
    /// assert_eq!(mdp.actions.len(), 16);
    /// assert_eq!(mdp.goal.iter().filter(|&&g| g).count(), 1);
    /// // State 6 (row 1, column 2) has four neighbours: each slippery action has three outcomes.
    /// assert!(mdp.actions[6].iter().all(|a| a.outcomes.len() == 3));
    /// ```
    pub fn mdp(&self) -> crate::certificate::Mdp {
        let p = &self.problem;
        let actions = (0..p.states())
            .map(|x| {
                p.actions(x)
                    .map(|a| crate::certificate::MdpAction {
                        cost: p.cost(a).clone(),
                        reward: self.reward[a].clone(),
                        outcomes: p
                            .outcomes(a)
                            .iter()
                            .map(|o| (o.successor, o.probability.clone()))
                            .collect(),
                    })
                    .collect()
            })
            .collect();
        crate::certificate::Mdp {
            goal: (0..p.states()).map(|x| p.is_goal(x)).collect(),
            terminal: self.terminal.clone(),
            actions,
        }
    }
}

impl Model {
    /// The model as a deterministic planning problem (docs/spec.md §1) for the claims stated on one
    /// (C4, `verify --claim C4 --env SPEC`): every action must have a single
    /// outcome and the initial state must be a single state; goals keep no action (their
    /// termination), traps their zero-cost self-loop. Refusals are one line naming why.
    ///
    /// ```
    /// use truecost::envs::EnvSpec;
    /// use truecost::objectives::Model;
    /// let m = Model::from_environment(&EnvSpec::parse("frozenlake:slippery=false").unwrap().build().unwrap()).unwrap();
    /// let p = m.deterministic_problem().unwrap();
    /// assert_eq!((p.states(), p.initial(), p.moves(0).len()), (16, 0, 4));
    /// let s = Model::from_environment(&EnvSpec::parse("frozenlake").unwrap().build().unwrap()).unwrap();
    /// assert!(s.deterministic_problem().unwrap_err().contains("stochastic"));
    /// ```
    pub fn deterministic_problem(&self) -> Result<crate::model::Problem, String> {
        self.deterministic_problem_from(None)
    }

    /// [`Self::deterministic_problem`] with the initial state `x1` chosen (`Some(x)`: any state
    /// where the episode runs, e.g. one of Taxi's 300 initial states; `None`: the model's own,
    /// which must be a single state).
    ///
    /// ```
    /// use truecost::envs::{taxi, EnvSpec};
    /// use truecost::objectives::Model;
    /// let m = Model::from_environment(&EnvSpec::parse("taxi").unwrap().build().unwrap()).unwrap();
    /// let x1 = taxi::encode(4, 4, 0, 1); // taxi at (4, 4), passenger at R, destination G
    /// assert_eq!(m.deterministic_problem_from(Some(x1)).unwrap().initial(), x1);
    /// assert!(m.deterministic_problem_from(Some(taxi::encode(0, 0, 1, 1))).unwrap_err().contains("ended"));
    /// assert!(m.deterministic_problem_from(Some(500)).is_err());
    /// ```
    pub fn deterministic_problem_from(
        &self,
        initial: Option<StateId>,
    ) -> Result<crate::model::Problem, String> {
        let p = &self.problem;
        let x1 = match initial {
            Some(x) if x >= p.states() => {
                return Err(format!(
                    "initial state {x}: {} has states 0 to {}",
                    self.name,
                    p.states() - 1
                ))
            }
            Some(x) if self.terminal[x] => {
                return Err(format!(
                    "initial state {x}: the episode has ended there (a goal or a trap of {})",
                    self.name
                ))
            }
            Some(x) => x,
            None if self.initial.len() > 1 => {
                return Err(format!(
                "{} draws its initial state from {} states; this needs a single initial state x1",
                self.name,
                self.initial.len()
            ))
            }
            None => self.initial[0].0,
        };
        let mut moves = Vec::with_capacity(p.states());
        for x in 0..p.states() {
            let mut list = Vec::new();
            for a in p.actions(x) {
                match p.outcomes(a) {
                    [o] => list.push(crate::model::Move {
                        successor: o.successor,
                        cost: p.cost(a).clone(),
                    }),
                    many => {
                        return Err(format!(
                            "{} is stochastic (state {x}, action {} has {} outcomes); this needs a deterministic problem",
                            self.name,
                            a - p.actions(x).start,
                            many.len()
                        ))
                    }
                }
            }
            moves.push(list);
        }
        crate::model::Problem::new(moves, x1, p.goals().to_vec()).map_err(|e| e.to_string())
    }
}

impl Model {
    /// The model of a deterministic problem (docs/spec.md §1) for the parametric discount analysis:
    /// every move becomes an action with its single outcome (probability 1), rewards are the
    /// negated stage costs, goals end the episode.
    ///
    /// A dead end (a non-goal state without moves) has cost-to-go `+∞` in the deterministic
    /// model (docs/spec.md §1): no trajectory through it has a discounted value, so no discount-optimal
    /// policy enters it. Moves into dead ends are removed, repeatedly (a state whose every move
    /// leads into dead ends is one too); what remains are exactly the goal paths and lassos
    /// that the C3 claim's enumeration (`discount_set` of the claims engine) walks. A dead-end `x1` has no goal path: every policy
    /// fails there, as the model says (it ends at `x1`, unsuccessfully).
    ///
    /// ```
    /// use truecost::model::{Move, Problem};
    /// use truecost::objectives::Model;
    /// // 0 → 1 (dead end) or 0 → 2 (goal): the move into the dead end is removed.
    /// let mv = |successor, cost: &str| Move { successor, cost: cost.parse().unwrap() };
    /// let p = Problem::new(vec![vec![mv(1, "1"), mv(2, "5")], vec![], vec![]], 0, vec![2]).unwrap();
    /// let m = Model::from_deterministic(&p, "example".into()).unwrap();
    /// assert_eq!(m.problem.actions(0).len(), 1);
    /// assert!(truecost::objectives::parametric::is_deterministic(&m));
    /// ```
    pub fn from_deterministic(
        problem: &crate::model::Problem,
        name: String,
    ) -> Result<Self, StochasticError> {
        Self::from_deterministic_file(problem, name, &FileObjective::default())
    }

    /// [`Self::from_deterministic`] for a deterministic problem file with what it says besides
    /// the problem ([`FileObjective`], read with `problem`): the file's rewards (those of the
    /// moves removed with the dead ends dropped), terminal states and initial distribution, as
    /// [`Self::with_file_objective`].
    ///
    /// ```
    /// use truecost::model::file::FileObjective;
    /// use truecost::model::{Move, Problem};
    /// use truecost::objectives::{Model, Objective};
    /// // 0 -> 1 (a dead end, which files refuse but paper problems may have), 0 -> 2 (a trap,
    /// // terminal), 0 -> 3 (the goal, reward 2 on the way in).
    /// let q = |n: i64| truecost::value::Rational::from_integer(n.into());
    /// let mv = |successor, cost| Move { successor, cost: q(cost) };
    /// let p = Problem::new(vec![vec![mv(1, 1), mv(2, 1), mv(3, 1)], vec![], vec![mv(2, 0)], vec![]], 0, vec![3]).unwrap();
    /// let extra = FileObjective { rewards: Some(vec![q(9), q(1), q(2), q(0)]), terminal: vec![2], initial: None };
    /// let m = Model::from_deterministic_file(&p, "example".into(), &extra).unwrap();
    /// assert_eq!(m.problem.actions(0).len(), 2); // the move into the dead end is removed
    /// assert_eq!(m.reward, [q(1), q(2), q(0)]); // and its reward with it
    /// assert!(m.terminal[2]);
    /// let v = m.solve(&Objective::Discounted("1/2".parse().unwrap())).unwrap();
    /// assert_eq!(v.value_initial.to_string(), "2");
    /// ```
    pub fn from_deterministic_file(
        problem: &crate::model::Problem,
        name: String,
        file: &FileObjective,
    ) -> Result<Self, StochasticError> {
        let n = problem.states();
        let mut dead: Vec<bool> = (0..n)
            .map(|x| !problem.is_goal(x) && problem.moves(x).is_empty())
            .collect();
        loop {
            let mut changed = false;
            for x in 0..n {
                if !dead[x]
                    && !problem.is_goal(x)
                    && problem.moves(x).iter().all(|m| dead[m.successor])
                {
                    dead[x] = true;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        // The rewards of the moves kept, in order (one action per move).
        let mut kept_rewards = Vec::new();
        let mut a = 0;
        let moves = (0..n)
            .map(|x| {
                let mut row = Vec::new();
                for m in problem.moves(x) {
                    if !dead[m.successor] {
                        row.push(m.clone());
                        if let Some(r) = &file.rewards {
                            kept_rewards.push(r[a].clone());
                        }
                    }
                    a += 1;
                }
                row
            })
            .collect();
        let pruned = crate::model::Problem::new(moves, problem.initial(), problem.goals().to_vec())
            .expect("removing moves keeps the states, x1 and the goals well formed");
        let stochastic = StochasticProblem::from_deterministic(
            &pruned,
            crate::stochastic::NoiseModel::Paper,
            &crate::stochastic::Predictability::one(),
        )?;
        let kept = FileObjective {
            rewards: file.rewards.as_ref().map(|_| kept_rewards),
            terminal: file.terminal.clone(),
            initial: file.initial.clone(),
        };
        Ok(Model::from_problem(stochastic, name).with_file_objective(&kept))
    }
}

/// The set of `α ∈ (0, 1)` for which a discount-optimal policy fails to reach a goal from the
/// initial state, read off the parametric analysis of a deterministic model
/// ([`Model::from_deterministic`]): an open interval between breakpoints belongs to it iff
/// the policies optimal there have least success probability `< 1` from `x1`, and a breakpoint
/// iff the policies optimal at the point do (there the optimal actions of both neighbouring
/// intervals tie, so a point can belong to the set while neither neighbour does, or the
/// reverse). In a deterministic model a policy's success from `x1` is 0 or 1, and a policy
/// using only optimal actions follows a discount-optimal trajectory, so this is the set the
/// C3 claim's enumeration of goal paths and lassos (`discount_set` of the claims engine) gives
/// (checked in `tests/discount_engines.rs`). With an
/// initial distribution (a problem file's) the least success probability is taken at the
/// distribution: `α` belongs to the set iff a discount-optimal policy fails from some of its
/// states. Consecutive members are merged into maximal pieces.
pub fn failure_set(d: &parametric::DiscountAnalysis) -> crate::algebra::intervals::DiscountSet {
    use crate::algebra::intervals::{pieces_of_members, DiscountSet, Point};
    use crate::algebra::poly::Algebraic;
    let point = |r: &crate::algebra::poly::roots::Root| -> Point {
        Point::Root(match r.as_rational() {
            Some(q) => Algebraic::from_rational(q.clone()),
            // An open bracket (lo, hi) holding one simple root of the polynomial, not a root
            // at hi: the unique root of the square-free part in (lo, hi] (the polynomial
            // itself once reduced).
            None => Algebraic {
                poly: match r.reduction {
                    crate::algebra::poly::roots::Reduction::AsMet => r.poly.poly.squarefree(),
                    _ => r.poly.poly.clone(),
                },
                lo: r.lo.clone(),
                hi: r.hi.clone(),
            },
        })
    };
    let fails = |a: &parametric::Achievement| a.success.min < Rational::one();
    // Atoms in increasing order: interval 0, breakpoint 0, interval 1, …, interval k.
    let mut member = Vec::with_capacity(d.intervals.len() + d.breakpoints.len());
    for (i, interval) in d.intervals.iter().enumerate() {
        member.push(fails(&interval.achievement));
        if let Some(b) = d.breakpoints.get(i) {
            member.push(fails(&b.achievement));
        }
    }
    // Only a breakpoint where membership changes can end a piece: the others are never
    // read, so they are not converted (a placeholder keeps the indices).
    let ends: Vec<Point> = d
        .breakpoints
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let k = 2 * i + 1;
            if member[k - 1] != member[k] || member[k] != member[k + 1] {
                point(&b.at)
            } else {
                Point::Zero
            }
        })
        .collect();
    let pieces = pieces_of_members(&ends, &member);
    DiscountSet {
        pieces,
        method: format!(
            "{}; {} breakpoints in (0,1) where the discount-optimal policies change",
            report::discount_method(d),
            d.breakpoints.len()
        ),
    }
}

//! The stochastic planning problem: states, goals, and per state an ordered list of actions,
//! each with a stage cost and a list of outcomes carrying exact probabilities (docs/spec.md §3).
//!
//! Built from a deterministic [`Problem`] by a [`NoiseModel`] and `γ`
//! ([`StochasticProblem::from_deterministic`]) or given explicitly, e.g. by a problem file
//! ([`StochasticProblem::new`]).
//!
//! For samplers (a Q-learner): every action's outcomes carry, besides the exact probability,
//! its nearest `f64` and a cumulative `f64` threshold (the nearest `f64` of the exact partial
//! sum; the last one is exactly `1.0`). [`StochasticProblem::sample`] maps a uniform draw
//! `u ∈ [0, 1)` to the first outcome whose threshold exceeds `u`, so each outcome is drawn with
//! its exact probability up to the rounding of two thresholds (≤ 2⁻⁵³ each).

use std::ops::Range;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::{NoiseModel, Predictability, StochasticError};
use crate::model::{ModelError, Problem, StateId};
use crate::value::Rational;

/// What an outcome stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum OutcomeKind {
    /// The commanded move `f(x, u)` happened.
    Commanded,
    /// Nature applied another move of `U(x)` instead (its index in the state's action list).
    Other(usize),
    /// Nature applied the hold (at a goal: termination) action: the state did not change.
    Stay,
    /// An outcome given explicitly (problem file).
    Listed,
}

/// One outcome of an action: the next state and its exact probability.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Outcome {
    /// The next state.
    pub successor: StateId,
    /// Its probability, exact, in `(0, 1]`.
    pub probability: Rational,
    /// What it stands for.
    pub kind: OutcomeKind,
}

/// An action as given to [`StochasticProblem::new`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StochasticAction {
    /// The stage cost `l(x, u) ≥ 0` (paid whatever the outcome).
    pub cost: Rational,
    /// The outcomes; probabilities must be in `(0, 1]` and sum to exactly 1.
    pub outcomes: Vec<Outcome>,
}

/// Where a stochastic problem came from (every output names it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Provenance {
    /// A deterministic problem perturbed by a noise model with predictability `γ`.
    Noise {
        /// The noise model.
        model: NoiseModel,
        /// `γ`.
        gamma: Predictability,
    },
    /// Outcomes given explicitly.
    Explicit,
}

/// A stochastic planning problem, validated on construction.
///
/// Actions are numbered globally (`0..action_total()`); the actions of state `x` are the range
/// [`actions(x)`](Self::actions), in the state's order.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// // 0 <-> 1 -> 2 (goal)
/// let p = Problem::new(vec![
///     vec![Move { successor: 1, cost: one.clone() }],
///     vec![Move { successor: 0, cost: one.clone() }, Move { successor: 2, cost: one.clone() }],
///     vec![],
/// ], 0, vec![2]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// let a = s.actions(1).start + 1; // state 1, move to 2
/// let out: Vec<_> = s.outcomes(a).iter().map(|o| (o.successor, o.probability.to_string())).collect();
/// assert_eq!(out, vec![(2, "9/10".into()), (0, "1/20".into()), (1, "1/20".into())]);
/// assert_eq!(s.sample(a, 0.0), 2);
/// assert_eq!(s.sample(a, 0.92), 0);
/// assert_eq!(s.sample(a, 0.99), 1);
/// ```
#[derive(Clone, Debug)]
pub struct StochasticProblem {
    initial: StateId,
    is_goal: Vec<bool>,
    goals: Vec<StateId>,
    action_first: Vec<usize>,
    action_state: Vec<StateId>,
    cost: Vec<Rational>,
    commanded: Vec<Option<StateId>>,
    outcome_first: Vec<usize>,
    outcomes: Vec<Outcome>,
    weight: Vec<u64>,
    probability_f64: Vec<f64>,
    cumulative: Vec<f64>,
    denominator: Vec<u64>,
    cost_denominator: BigInt,
    provenance: Provenance,
}

/// The largest per-state common denominator of probabilities the exact solver accepts.
pub const MAX_DENOMINATOR: u64 = 1 << 62;

/// The most bits of the lcm `C` of the stage costs' denominators, and of each stage cost
/// scaled to an integer by it, checked as a problem is built, before any work: the exact
/// solver writes its equations in these integers (and takes only right-hand sides below
/// `2^100`), and every sum of stage costs has a denominator dividing `C`. An lcm without
/// bound made the exact solves of a 200-state chain of 33,000-bit costs run for minutes
/// before the solver refused them.
pub const MAX_SCALED_COST_BITS: u64 = 1024;

/// The refusal of stage costs over [`MAX_SCALED_COST_BITS`]: at `state`, `action`, the lcm of
/// the denominators up to there (`cost = None`) or the scaled cost, with its bits.
fn scaled_cost_refusal(
    state: StateId,
    action: usize,
    cost: Option<&Rational>,
    bits: u64,
) -> StochasticError {
    let what = match cost {
        None => "the lcm of the stage costs' denominators up to here takes".to_string(),
        Some(c) => format!(
            "the stage cost {} scaled to an integer by the lcm of the stage costs' denominators takes",
            super::short_text(c)
        ),
    };
    StochasticError::TooLarge(format!(
        "state {state}, action {action}: {what} {bits} bits; the exact solvers take at most {MAX_SCALED_COST_BITS} (refused before any work)"
    ))
}

impl StochasticProblem {
    /// Perturbs a deterministic problem with a noise model (table in [`super::noise`]).
    ///
    /// Fails only if a state's probabilities have a common denominator above 2⁶² (a `γ` with
    /// more than about 17 decimal digits): [`StochasticError::GammaDenominator`] names `γ`,
    /// the state and its number of moves.
    pub fn from_deterministic(
        problem: &Problem,
        model: NoiseModel,
        gamma: &Predictability,
    ) -> Result<Self, StochasticError> {
        // Refused before any probability is formed: every state with moves has the outcome
        // `γ` (commanded), so its common denominator is a multiple of `γ`'s, and the check of
        // `Self::build` certainly fails at the first such state when `γ`'s alone is too large
        // (its numerator is no larger: `γ ≤ 1`).
        if gamma.value().denom() > &BigInt::from(MAX_DENOMINATOR) {
            if let Some(state) = (0..problem.states()).find(|&x| !problem.moves(x).is_empty()) {
                return Err(StochasticError::GammaDenominator {
                    gamma: super::short_text(gamma.value()),
                    state,
                    moves: problem.moves(state).len(),
                });
            }
        }
        let mut actions = Vec::with_capacity(problem.states());
        let moves_total = (0..problem.states()).map(|x| problem.moves(x).len()).sum();
        let mut commanded = Vec::with_capacity(moves_total);
        for x in 0..problem.states() {
            let moves = problem.moves(x);
            let k = moves.len();
            let mut list = Vec::with_capacity(k);
            if k > 0 {
                let (pc, po, ps) = model.split(gamma, k);
                for (a, m) in moves.iter().enumerate() {
                    let mut outcomes = vec![Outcome {
                        successor: m.successor,
                        probability: pc.clone(),
                        kind: OutcomeKind::Commanded,
                    }];
                    if po.is_positive() {
                        for (b, other) in moves.iter().enumerate() {
                            if b != a {
                                outcomes.push(Outcome {
                                    successor: other.successor,
                                    probability: po.clone(),
                                    kind: OutcomeKind::Other(b),
                                });
                            }
                        }
                    }
                    if ps.is_positive() {
                        outcomes.push(Outcome {
                            successor: x,
                            probability: ps.clone(),
                            kind: OutcomeKind::Stay,
                        });
                    }
                    list.push(StochasticAction {
                        cost: m.cost.clone(),
                        outcomes,
                    });
                    commanded.push(Some(m.successor));
                }
            }
            actions.push(list);
        }
        let mut s = Self::build(
            actions,
            problem.initial(),
            problem.goals().to_vec(),
            Provenance::Noise {
                model,
                gamma: gamma.clone(),
            },
        )
        .map_err(|e| match e {
            // The only source of a large denominator here is γ: say so.
            StochasticError::DenominatorTooLarge { state } => StochasticError::GammaDenominator {
                gamma: super::short_text(gamma.value()),
                state,
                moves: problem.moves(state).len(),
            },
            e => e,
        })?;
        s.commanded = commanded;
        Ok(s)
    }

    /// Builds and validates a problem from explicit actions (`actions[x]` is the ordered action
    /// list of `x`). Checks: at least one state and one goal, every index in range, costs
    /// `≥ 0`, every action has outcomes with probabilities in `(0, 1]` summing to exactly 1.
    pub fn new(
        actions: Vec<Vec<StochasticAction>>,
        initial: StateId,
        goals: Vec<StateId>,
    ) -> Result<Self, StochasticError> {
        Self::build(actions, initial, goals, Provenance::Explicit)
    }

    fn build(
        actions: Vec<Vec<StochasticAction>>,
        initial: StateId,
        goals: Vec<StateId>,
        provenance: Provenance,
    ) -> Result<Self, StochasticError> {
        let n = actions.len();
        if n == 0 {
            return Err(ModelError::NoStates.into());
        }
        if n >= u32::MAX as usize {
            return Err(ModelError::TooManyStates(n).into());
        }
        if initial >= n {
            return Err(ModelError::InitialOutOfRange { initial, states: n }.into());
        }
        if goals.is_empty() {
            return Err(ModelError::NoGoal.into());
        }
        let mut is_goal = vec![false; n];
        let mut unique = Vec::new();
        for &g in &goals {
            if g >= n {
                return Err(ModelError::GoalOutOfRange { goal: g, states: n }.into());
            }
            if !is_goal[g] {
                is_goal[g] = true;
                unique.push(g);
            }
        }
        // Every list is allocated at its final length (no spare capacity from growing by
        // doubling), so a problem holds what `policy_iteration::problem_bytes` estimates.
        let action_total: usize = actions.iter().map(Vec::len).sum();
        let outcome_total: usize = actions.iter().flatten().map(|a| a.outcomes.len()).sum();
        let with_first = |len: usize| {
            let mut v = vec![0];
            v.reserve_exact(len);
            v
        };
        let mut s = StochasticProblem {
            initial,
            is_goal,
            goals: unique,
            action_first: with_first(n),
            action_state: Vec::with_capacity(action_total),
            cost: Vec::with_capacity(action_total),
            commanded: Vec::with_capacity(action_total),
            outcome_first: with_first(action_total),
            outcomes: Vec::with_capacity(outcome_total),
            weight: Vec::with_capacity(outcome_total),
            probability_f64: Vec::with_capacity(outcome_total),
            cumulative: Vec::with_capacity(outcome_total),
            denominator: Vec::with_capacity(n),
            cost_denominator: BigInt::one(),
            provenance,
        };
        for (x, list) in actions.into_iter().enumerate() {
            let mut lcm = BigInt::one();
            let first_outcome = s.outcomes.len();
            for (a, action) in list.into_iter().enumerate() {
                if action.cost.is_negative() {
                    return Err(ModelError::NegativeCost {
                        state: x,
                        action: a,
                        cost: super::short_text(&action.cost),
                    }
                    .into());
                }
                if action.outcomes.is_empty() {
                    return Err(StochasticError::NoOutcomes {
                        state: x,
                        action: a,
                    });
                }
                let mut sum = Rational::zero();
                for o in &action.outcomes {
                    if o.successor >= n {
                        return Err(ModelError::SuccessorOutOfRange {
                            state: x,
                            action: a,
                            successor: o.successor,
                            states: n,
                        }
                        .into());
                    }
                    if !crate::value::in_unit_interval_open_closed(&o.probability) {
                        return Err(StochasticError::ProbabilityRange {
                            state: x,
                            action: a,
                            probability: super::short_text(&o.probability),
                        });
                    }
                    sum += &o.probability;
                    lcm = lcm.lcm(o.probability.denom());
                }
                if !sum.is_one() {
                    let (off, distance) = super::off_one(&sum);
                    return Err(StochasticError::ProbabilitySum {
                        state: x,
                        action: a,
                        sum: super::short_text(&sum),
                        off,
                        distance,
                    });
                }
                s.cost_denominator = s.cost_denominator.lcm(action.cost.denom());
                let bits = s.cost_denominator.bits();
                if bits > MAX_SCALED_COST_BITS {
                    return Err(scaled_cost_refusal(x, a, None, bits));
                }
                let mut partial = Rational::zero();
                let last = action.outcomes.len() - 1;
                for (i, o) in action.outcomes.into_iter().enumerate() {
                    partial += &o.probability;
                    s.probability_f64
                        .push(o.probability.to_f64().unwrap_or(0.0));
                    s.cumulative.push(if i == last {
                        1.0
                    } else {
                        partial.to_f64().unwrap_or(1.0)
                    });
                    s.outcomes.push(o);
                }
                s.outcome_first.push(s.outcomes.len());
                s.cost.push(action.cost);
                s.commanded.push(None);
                s.action_state.push(x);
            }
            s.action_first.push(s.cost.len());
            let d = lcm
                .to_u64()
                .filter(|&d| d <= MAX_DENOMINATOR)
                .ok_or(StochasticError::DenominatorTooLarge { state: x })?;
            for o in &s.outcomes[first_outcome..] {
                let w = (o.probability.numer() * BigInt::from(d)) / o.probability.denom();
                s.weight
                    .push(w.to_u64().expect("a probability times its denominator"));
            }
            s.denominator.push(d);
        }
        for (a, cost) in s.cost.iter().enumerate() {
            let bits = (cost.numer() * (&s.cost_denominator / cost.denom())).bits();
            if bits > MAX_SCALED_COST_BITS {
                let x = s.action_state[a];
                return Err(scaled_cost_refusal(
                    x,
                    a - s.action_first[x],
                    Some(cost),
                    bits,
                ));
            }
        }
        Ok(s)
    }

    /// `|X|`.
    pub fn states(&self) -> usize {
        self.is_goal.len()
    }

    /// `x1`.
    pub fn initial(&self) -> StateId {
        self.initial
    }

    /// `XG` (duplicates removed, in the order given).
    pub fn goals(&self) -> &[StateId] {
        &self.goals
    }

    /// Whether `x ∈ XG`.
    pub fn is_goal(&self, x: StateId) -> bool {
        self.is_goal[x]
    }

    /// Where the problem came from.
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// The global ids of the actions of `x`, in order (termination not included).
    pub fn actions(&self, x: StateId) -> Range<usize> {
        self.action_first[x]..self.action_first[x + 1]
    }

    /// The number of actions of all states.
    pub fn action_total(&self) -> usize {
        self.cost.len()
    }

    /// The state an action belongs to.
    pub fn state_of(&self, action: usize) -> StateId {
        self.action_state[action]
    }

    /// `l(x, u)`.
    pub fn cost(&self, action: usize) -> &Rational {
        &self.cost[action]
    }

    /// The commanded successor `f(x, u)`, for problems built from a deterministic one.
    pub fn commanded(&self, action: usize) -> Option<StateId> {
        self.commanded[action]
    }

    /// The successor an action aims at: the commanded one, or (for an action of a problem that
    /// lists only outcomes, such as a stochastic problem file) its most likely outcome, the
    /// first of equals. The exact optimum's initial policy is the deterministic optimum over
    /// these moves ([`super::policy_iteration`]).
    ///
    /// ```
    /// use truecost::stochastic::file::{from_json, ProblemFile};
    /// let text = r#"{"initial":0,"goals":[2],"actions":[[{"cost":"1","outcomes":[
    ///     {"to":0,"p":"1/4"},{"to":1,"p":"3/8"},{"to":2,"p":"3/8"}]}],
    ///     [{"to":2,"cost":"1"}],[]]}"#;
    /// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { unreachable!() };
    /// assert_eq!((p.intended(0), p.intended(1)), (1, 2));
    /// ```
    pub fn intended(&self, action: usize) -> StateId {
        self.commanded(action).unwrap_or_else(|| {
            let outcomes = self.outcomes(action);
            let weights = self.weights(action);
            let best = (0..outcomes.len())
                .rev()
                .max_by_key(|&k| weights[k])
                .expect("an action has at least one outcome");
            outcomes[best].successor
        })
    }

    /// The outcomes of an action, in order (commanded, other moves, stay for noise models).
    pub fn outcomes(&self, action: usize) -> &[Outcome] {
        &self.outcomes[self.outcome_first[action]..self.outcome_first[action + 1]]
    }

    /// Every state's actions as [`StochasticAction`]s, in order: what [`Self::new`] takes, so a
    /// problem can be rebuilt with states or actions added.
    ///
    /// ```
    /// use truecost::stochastic::StochasticProblem;
    /// use truecost::stochastic::file::{from_json, ProblemFile};
    /// let text = r#"{"initial":0,"goals":[1],"actions":[[{"cost":"1","outcomes":[{"to":1,"p":"1/2"},{"to":0,"p":"1/2"}]}],[]]}"#;
    /// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { unreachable!() };
    /// let again = StochasticProblem::new(p.action_lists(), p.initial(), p.goals().to_vec()).unwrap();
    /// assert_eq!(again.action_lists(), p.action_lists());
    /// assert_eq!(p.action_lists()[0][0].outcomes.len(), 2);
    /// ```
    pub fn action_lists(&self) -> Vec<Vec<StochasticAction>> {
        (0..self.states())
            .map(|x| {
                self.actions(x)
                    .map(|a| StochasticAction {
                        cost: self.cost(a).clone(),
                        outcomes: self.outcomes(a).to_vec(),
                    })
                    .collect()
            })
            .collect()
    }

    /// The positions of an action's outcomes in the problem-wide outcome numbering (for
    /// per-outcome data kept outside the problem, e.g. `f64` probabilities).
    pub fn outcome_range(&self, action: usize) -> Range<usize> {
        self.outcome_first[action]..self.outcome_first[action + 1]
    }

    /// The number of outcomes of all actions.
    pub fn outcome_total(&self) -> usize {
        self.outcomes.len()
    }

    /// The outcomes' probabilities as integers over the state's [`denominator`](Self::denominator).
    pub fn weights(&self, action: usize) -> &[u64] {
        &self.weight[self.outcome_first[action]..self.outcome_first[action + 1]]
    }

    /// The outcomes' probabilities rounded to `f64`.
    pub fn probabilities_f64(&self, action: usize) -> &[f64] {
        &self.probability_f64[self.outcome_first[action]..self.outcome_first[action + 1]]
    }

    /// The outcomes' cumulative `f64` thresholds (non-decreasing, the last is `1.0`).
    pub fn cumulative(&self, action: usize) -> &[f64] {
        &self.cumulative[self.outcome_first[action]..self.outcome_first[action + 1]]
    }

    /// The common denominator (≤ 2⁶²) of the probabilities of every outcome of every action of `x`.
    pub fn denominator(&self, x: StateId) -> u64 {
        self.denominator[x]
    }

    /// The lcm of the denominators of all stage costs.
    pub fn cost_denominator(&self) -> &BigInt {
        &self.cost_denominator
    }

    /// The successor drawn by a uniform `u ∈ [0, 1)`: the first outcome whose cumulative
    /// threshold exceeds `u` (a `u ≥ 1` gives the last outcome).
    pub fn sample(&self, action: usize, u: f64) -> StateId {
        let cumulative = self.cumulative(action);
        let i = cumulative.partition_point(|&c| c <= u);
        self.outcomes(action)[i.min(cumulative.len() - 1)].successor
    }

    /// The reference code's count for backing up state `x` once (docs/spec.md §7): the outcome terms
    /// that are neither the commanded move nor stay, `k·(k − 1)` for `k` actions (counted from
    /// the structure, whatever `γ`).
    pub fn reference_terms(&self, x: StateId) -> u64 {
        let k = self.actions(x).len() as u64;
        k * k.saturating_sub(1)
    }
}

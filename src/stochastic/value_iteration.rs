//! Stochastic value iteration (docs/spec.md §3), synchronous and asynchronous, in exact arithmetic and
//! in `f64`, with an explicit stopping rule; and the reference code's variant (docs/spec.md §7).
//!
//! The backup at a non-goal state is `G(x) ← min_u { l(x,u) + Σ_o p_o·G(o) }`; a goal's value
//! is always 0 (termination is free). One *sweep* backs up the swept states in index order:
//! [`Schedule::Synchronous`] from the previous sweep's values, [`Schedule::Asynchronous`]
//! (Gauss–Seidel) in place.
//!
//! **Stopping rule**: stop after the first sweep whose largest change `max_x |G_new(x) − G_old(x)|`
//! is `≤ tolerance` (that sweep counted), or after `max_sweeps` sweeps, whichever comes first.
//! The result says which ([`ViRun::converged`]). Value iteration for a stochastic problem does
//! not reach `G*` in finitely many sweeps; compare with [`super::policy_iteration::optimum`].
//!
//! Two configurations matter ([`ViOptions`]):
//! * [`ViOptions::from_below`] (truecost's default): sweep the states with finite `G*` (known
//!   from [`super::properness`]; the others are `+∞` and never swept), start at 0, assign every
//!   backup, min over safe actions. The iterates increase monotonically towards the least
//!   fixed point of the Bellman operator, which is `G*` when no cycle avoiding the goals costs
//!   0 (true on the paper's grids); every iterate is a lower bound on `G*`.
//! * [`ViOptions::reference`] (the paper's code, docs/spec.md §7): sweep every state of the full graph
//!   (goals included, their value staying 0), start at `10³⁰`, replace a value only if the
//!   backup is strictly smaller, tolerance 0.1, at most 1000 sweeps. Its counted actions are
//!   `Σ k·(k−1)` per sweep over the swept states ([`StochasticProblem::reference_terms`]).
//!   With these rules and the reference noise model in `f64`, Problem 10 gives the published
//!   58 / 94 sweeps (γ = 0.999) and 69 / 112 (γ = 0.99).
//!
//! Exact arithmetic without gcds: with `D` the lcm of the states' probability denominators and
//! `C` that of the costs, every value is kept as `N / (C·D^e)` with an integer `N` and a
//! per-state exponent `e`; a backup at `x` aligns its outcomes to the largest exponent `E` and
//! produces exponent `E + 1`.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::problem::Provenance;
use super::properness::{analyse, Properness};
use super::{OutcomeKind, StochasticError, StochasticProblem};
use crate::model::Decision;
pub use crate::solvers::value_iteration::Schedule;
use crate::value::{Extended, Rational};

/// Where non-goal swept states start.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Initial {
    /// 0 (a lower bound on `G*`).
    Zero,
    /// An integer constant (the reference code uses `10³⁰`).
    Constant(BigInt),
}

/// How a backup changes a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UpdateRule {
    /// `G(x) ← backup`.
    Assign,
    /// `G(x) ← backup` only if strictly smaller (the reference code).
    Decrease,
}

/// Which states a sweep backs up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepSet {
    /// The non-goal states with finite `G*` (others are `+∞`); only safe actions are compared.
    Finite,
    /// Every state with an action, goals included (their value stays 0): the reference code's
    /// "full graph". Every state starts finite; use with [`Initial::Constant`].
    All,
}

/// The configuration of a value-iteration run (module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ViOptions {
    /// Synchronous or asynchronous.
    pub schedule: Schedule,
    /// Initial values.
    pub initial: Initial,
    /// Update rule.
    pub rule: UpdateRule,
    /// States swept.
    pub sweep: SweepSet,
    /// Stop after a sweep whose largest change is at most this (exact, `≥ 0`).
    pub tolerance: Rational,
    /// Stop after this many sweeps at the latest.
    pub max_sweeps: u64,
}

impl ViOptions {
    /// truecost's default: from below on the finite states, assign, the given stopping rule.
    pub fn from_below(
        schedule: Schedule,
        tolerance: Rational,
        max_sweeps: u64,
    ) -> Result<Self, StochasticError> {
        check_tolerance(&tolerance)?;
        Ok(ViOptions {
            schedule,
            initial: Initial::Zero,
            rule: UpdateRule::Assign,
            sweep: SweepSet::Finite,
            tolerance,
            max_sweeps,
        })
    }

    /// The paper's code (docs/spec.md §7): full graph, `10³⁰`, decrease only, tolerance 0.1, 1000 sweeps.
    pub fn reference(schedule: Schedule) -> Self {
        ViOptions {
            schedule,
            initial: Initial::Constant(BigInt::from(10u32).pow(30)),
            rule: UpdateRule::Decrease,
            sweep: SweepSet::All,
            tolerance: Rational::new(BigInt::one(), BigInt::from(10)),
            max_sweeps: REFERENCE_MAX_SWEEPS,
        }
    }
}

/// The reference code's cap on sweeps.
pub const REFERENCE_MAX_SWEEPS: u64 = 1000;

fn check_tolerance(t: &Rational) -> Result<(), StochasticError> {
    if t.is_negative() {
        Err(StochasticError::Tolerance(
            Extended::Finite(t.clone()).to_string(),
        ))
    } else {
        Ok(())
    }
}

/// The result of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct ViRun<V> {
    /// The values when the run stopped.
    pub cost_to_go: Vec<V>,
    /// Sweeps performed (the last one included).
    pub sweeps: u64,
    /// Whether the run stopped by the tolerance (else by `max_sweeps`).
    pub converged: bool,
    /// The largest change in the last sweep.
    pub last_change: V,
    /// Actions evaluated (one `Q` each).
    pub backups: u64,
    /// Outcome terms `p_o·G(o)` evaluated.
    pub outcome_terms: u64,
    /// The reference code's count: `Σ k·(k−1)` per sweep over the swept states.
    pub reference_counted: u64,
    /// The greedy policy of the final values (first minimising action; `Terminate` at goals;
    /// `None` where the value is `+∞` or there is no action).
    pub policy: Vec<Option<Decision>>,
}

/// Exact stochastic value iteration.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// use truecost::stochastic::value_iteration::{value_iteration_exact, ViOptions, Schedule};
/// use truecost::value::parse_rational;
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: parse_rational("1").unwrap() }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.5").unwrap()).unwrap();
/// // G = 1 + G/2 from 0: 1, 3/2, 7/4, ... ; stop when the change is ≤ 1/4.
/// let o = ViOptions::from_below(Schedule::Synchronous, parse_rational("1/4").unwrap(), 100).unwrap();
/// let r = value_iteration_exact(&s, &o);
/// assert_eq!((r.sweeps, r.cost_to_go[0].to_string()), (3, "7/4".to_string()));
/// assert!(r.converged);
/// ```
pub fn value_iteration_exact(problem: &StochasticProblem, options: &ViOptions) -> ViRun<Extended> {
    let properness = analyse(problem);
    ExactVi::new(problem, &properness, options).run()
}

/// A value `N / (C·D^e)`, or `+∞`.
#[derive(Clone, Debug)]
enum Scaled {
    Finite { n: BigInt, e: usize },
    Infinite,
}

struct ExactVi<'a> {
    problem: &'a StochasticProblem,
    properness: &'a Properness,
    options: &'a ViOptions,
    /// `w_o · D / s_x` per outcome.
    multiplier: Vec<BigInt>,
    /// `l · C` per action.
    cost: Vec<BigInt>,
    c: BigInt,
    powers: Vec<BigInt>,
    d: BigInt,
}

impl<'a> ExactVi<'a> {
    fn new(
        problem: &'a StochasticProblem,
        properness: &'a Properness,
        options: &'a ViOptions,
    ) -> Self {
        let mut d = BigInt::one();
        for x in 0..problem.states() {
            d = d.lcm(&BigInt::from(problem.denominator(x)));
        }
        let c = problem.cost_denominator().clone();
        let mut multiplier = vec![BigInt::zero(); problem.outcome_total()];
        let mut cost = Vec::with_capacity(problem.action_total());
        for a in 0..problem.action_total() {
            let x = problem.state_of(a);
            let f = &d / BigInt::from(problem.denominator(x));
            for (i, &w) in problem.outcome_range(a).zip(problem.weights(a)) {
                multiplier[i] = &f * BigInt::from(w);
            }
            cost.push((problem.cost(a) * Rational::from_integer(c.clone())).to_integer());
        }
        ExactVi {
            problem,
            properness,
            options,
            multiplier,
            cost,
            c,
            powers: vec![BigInt::one()],
            d,
        }
    }

    /// Makes `D^0 ..= D^e` available.
    fn ensure(&mut self, e: usize) {
        while self.powers.len() <= e {
            let next = self.powers.last().expect("non-empty") * &self.d;
            self.powers.push(next);
        }
    }

    fn swept(&self, x: usize) -> bool {
        match self.options.sweep {
            SweepSet::Finite => self.properness.finite[x] && !self.problem.is_goal(x),
            SweepSet::All => !self.problem.actions(x).is_empty(),
        }
    }

    fn usable(&self, a: usize) -> bool {
        self.options.sweep == SweepSet::All || self.properness.safe[a]
    }

    /// The best backup at `x` from `values`: `(K, E + 1, i)` meaning `K / (C·D^{E+1})`,
    /// attained first by the `i`-th action of `x`.
    fn backup(&mut self, x: usize, values: &[Scaled]) -> Option<(BigInt, usize, usize)> {
        let problem = self.problem;
        let actions: Vec<usize> = problem.actions(x).filter(|&a| self.usable(a)).collect();
        let mut e_max = 0;
        for &a in &actions {
            for o in problem.outcomes(a) {
                match &values[o.successor] {
                    Scaled::Finite { e, .. } => e_max = e_max.max(*e),
                    Scaled::Infinite => return None,
                }
            }
        }
        self.ensure(e_max + 1);
        let top = &self.powers[e_max + 1];
        let mut best: Option<(BigInt, usize)> = None;
        for &a in &actions {
            let mut k = &self.cost[a] * top;
            for (i, o) in problem.outcome_range(a).zip(problem.outcomes(a)) {
                if let Scaled::Finite { n, e } = &values[o.successor] {
                    if !n.is_zero() {
                        let term = &self.multiplier[i] * n;
                        if *e == e_max {
                            k += term;
                        } else {
                            k += term * &self.powers[e_max - e];
                        }
                    }
                }
            }
            if best.as_ref().is_none_or(|(b, _)| &k < b) {
                best = Some((k, a - problem.actions(x).start));
            }
        }
        best.map(|(k, i)| (k, e_max + 1, i))
    }

    fn exact_value(&mut self, v: &Scaled) -> Extended {
        match v {
            Scaled::Finite { n, e } => {
                self.ensure(*e);
                let den = &self.powers[*e] * &self.c;
                Extended::Finite(Rational::new(n.clone(), den))
            }
            Scaled::Infinite => Extended::Infinite,
        }
    }

    fn run(mut self) -> ViRun<Extended> {
        let problem = self.problem;
        let n = problem.states();
        let mut values: Vec<Scaled> = (0..n)
            .map(|x| {
                if problem.is_goal(x) {
                    Scaled::Finite {
                        n: BigInt::zero(),
                        e: 0,
                    }
                } else if self.options.sweep == SweepSet::Finite && !self.properness.finite[x] {
                    Scaled::Infinite
                } else {
                    match &self.options.initial {
                        Initial::Zero => Scaled::Finite {
                            n: BigInt::zero(),
                            e: 0,
                        },
                        Initial::Constant(k) => Scaled::Finite {
                            n: k * &self.c,
                            e: 0,
                        },
                    }
                }
            })
            .collect();
        let swept: Vec<usize> = (0..n).filter(|&x| self.swept(x)).collect();
        let per_sweep_backups: u64 = swept
            .iter()
            .map(|&x| problem.actions(x).filter(|&a| self.usable(a)).count() as u64)
            .sum();
        let per_sweep_terms: u64 = swept
            .iter()
            .flat_map(|&x| problem.actions(x))
            .filter(|&a| self.usable(a))
            .map(|a| problem.outcomes(a).len() as u64)
            .sum();
        let per_sweep_reference: u64 = swept.iter().map(|&x| problem.reference_terms(x)).sum();
        let tol_n = self.options.tolerance.numer().clone();
        let tol_d = self.options.tolerance.denom().clone();
        let mut sweeps = 0;
        let mut previous = values.clone();
        let (last_change, converged) = loop {
            sweeps += 1;
            if self.options.schedule == Schedule::Synchronous {
                previous.clone_from(&values);
            }
            // Largest change as (numerator, exponent) of |Δ| = num / (C·D^e).
            let mut largest: (BigInt, usize) = (BigInt::zero(), 0);
            for &x in &swept {
                if problem.is_goal(x) {
                    // Termination keeps a goal at 0; its moves are still evaluated (counted).
                    continue;
                }
                let source = if self.options.schedule == Schedule::Synchronous {
                    &previous
                } else {
                    &values
                };
                let Some((k, e_new, _)) = self.backup(x, source) else {
                    continue;
                };
                let Scaled::Finite { n: old, e: e_old } = &values[x] else {
                    continue;
                };
                // Compare k/(C D^e_new) with old/(C D^e_old) on the common exponent e_new + e_old.
                self.ensure(e_new + e_old);
                let lhs = &k * &self.powers[*e_old];
                let rhs = old * &self.powers[e_new];
                let replace = match self.options.rule {
                    UpdateRule::Assign => true,
                    UpdateRule::Decrease => lhs < rhs,
                };
                if !replace {
                    continue;
                }
                let delta = (&lhs - &rhs).abs();
                let e_delta = e_new + e_old;
                // delta/(C D^e_delta) > largest.0/(C D^largest.1) ?
                if &delta * &self.powers[largest.1] > &largest.0 * &self.powers[e_delta] {
                    largest = (delta, e_delta);
                }
                values[x] = Scaled::Finite { n: k, e: e_new };
            }
            // |Δ| ≤ tol  ⇔  num·tol_d ≤ tol_n·C·D^e.
            self.ensure(largest.1);
            let within = &largest.0 * &tol_d <= &tol_n * &self.c * &self.powers[largest.1];
            if within || sweeps >= self.options.max_sweeps {
                let change = Scaled::Finite {
                    n: largest.0,
                    e: largest.1,
                };
                break (self.exact_value(&change), within);
            }
        };
        let policy: Vec<Option<Decision>> = (0..n)
            .map(|x| {
                if problem.is_goal(x) {
                    Some(Decision::Terminate)
                } else if matches!(values[x], Scaled::Infinite) {
                    None
                } else {
                    self.backup(x, &values).map(|(_, _, i)| Decision::Move(i))
                }
            })
            .collect();
        let cost_to_go: Vec<Extended> = values.iter().map(|v| self.exact_value(v)).collect();
        ViRun {
            cost_to_go,
            sweeps,
            converged,
            last_change,
            backups: sweeps * per_sweep_backups,
            outcome_terms: sweeps * per_sweep_terms,
            reference_counted: sweeps * per_sweep_reference,
            policy,
        }
    }
}

/// The first minimising usable action at every non-goal state with a finite value.
fn greedy<V: PartialOrd>(
    problem: &StochasticProblem,
    usable: impl Fn(usize) -> bool,
    q: impl Fn(usize) -> V,
    finite: impl Fn(usize) -> bool,
) -> Vec<Option<Decision>> {
    (0..problem.states())
        .map(|x| {
            if problem.is_goal(x) {
                return Some(Decision::Terminate);
            }
            if !finite(x) {
                return None;
            }
            let mut best: Option<(V, usize)> = None;
            for (i, a) in problem.actions(x).enumerate() {
                if !usable(a) {
                    continue;
                }
                let v = q(a);
                if best
                    .as_ref()
                    .is_none_or(|(b, _)| v.partial_cmp(b) == Some(Ordering::Less))
                {
                    best = Some((v, i));
                }
            }
            best.map(|(_, i)| Decision::Move(i))
        })
        .collect()
}

/// The `f64` numbers a float run uses: a cost per action and a probability per outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct FloatModel {
    /// `l(x, u)` per action (global id).
    pub cost: Vec<f64>,
    /// `p_o` per outcome (problem-wide numbering, [`StochasticProblem::outcome_range`]).
    pub probability: Vec<f64>,
}

impl FloatModel {
    /// The exact problem rounded: the nearest `f64` of every cost and probability.
    pub fn nearest(problem: &StochasticProblem) -> Self {
        FloatModel {
            cost: (0..problem.action_total())
                .map(|a| problem.cost(a).to_f64().unwrap_or(f64::MAX))
                .collect(),
            probability: (0..problem.action_total())
                .flat_map(|a| problem.probabilities_f64(a).to_vec())
                .collect(),
        }
    }

    /// The reference code's numbers (docs/spec.md §7): the given `f64` step costs (one per action, in
    /// order) and probabilities computed in `f64` from the `f64` γ as that code does
    /// ([`super::NoiseModel::split_f64`]). `None` unless the problem came from a noise model.
    pub fn reference(problem: &StochasticProblem, cost: Vec<f64>) -> Option<Self> {
        let Provenance::Noise { model, gamma } = problem.provenance() else {
            return None;
        };
        if cost.len() != problem.action_total() {
            return None;
        }
        let g = gamma.value().to_f64()?;
        let mut probability = vec![0.0; problem.outcome_total()];
        for a in 0..problem.action_total() {
            let k = problem.actions(problem.state_of(a)).len();
            let (pc, po, ps) = model.split_f64(g, k);
            for (i, o) in problem.outcome_range(a).zip(problem.outcomes(a)) {
                probability[i] = match o.kind {
                    OutcomeKind::Commanded => pc,
                    OutcomeKind::Other(_) => po,
                    OutcomeKind::Stay => ps,
                    OutcomeKind::Listed => {
                        problem.probabilities_f64(a)[i - problem.outcome_range(a).start]
                    }
                };
            }
        }
        Some(FloatModel { cost, probability })
    }
}

/// Stochastic value iteration in `f64` (same rules as [`value_iteration_exact`]; the tolerance
/// and initial constant are rounded to `f64`). Not exact: compare with the exact optimum.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// use truecost::stochastic::value_iteration::{value_iteration_f64, FloatModel, ViOptions, Schedule};
/// use truecost::value::parse_rational;
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: parse_rational("1").unwrap() }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.5").unwrap()).unwrap();
/// let o = ViOptions::from_below(Schedule::Synchronous, parse_rational("1/4").unwrap(), 100).unwrap();
/// let r = value_iteration_f64(&s, &FloatModel::nearest(&s), &o);
/// assert_eq!((r.sweeps, r.cost_to_go[0]), (3, 1.75));
/// ```
pub fn value_iteration_f64(
    problem: &StochasticProblem,
    model: &FloatModel,
    options: &ViOptions,
) -> ViRun<f64> {
    let properness = analyse(problem);
    let n = problem.states();
    let usable = |a: usize| options.sweep == SweepSet::All || properness.safe[a];
    let swept: Vec<usize> = (0..n)
        .filter(|&x| match options.sweep {
            SweepSet::Finite => properness.finite[x] && !problem.is_goal(x),
            SweepSet::All => !problem.actions(x).is_empty(),
        })
        .collect();
    let start = match &options.initial {
        Initial::Zero => 0.0,
        Initial::Constant(k) => k.to_f64().unwrap_or(f64::MAX),
    };
    let mut values: Vec<f64> = (0..n)
        .map(|x| {
            if problem.is_goal(x) {
                0.0
            } else if options.sweep == SweepSet::Finite && !properness.finite[x] {
                f64::INFINITY
            } else {
                start
            }
        })
        .collect();
    let tolerance = options.tolerance.to_f64().unwrap_or(0.0);
    let q = |a: usize, values: &[f64]| -> f64 {
        let mut s = model.cost[a];
        for (i, o) in problem.outcome_range(a).zip(problem.outcomes(a)) {
            s += model.probability[i] * values[o.successor];
        }
        s
    };
    let mut previous = values.clone();
    let mut sweeps = 0;
    let (last_change, converged) = loop {
        sweeps += 1;
        if options.schedule == Schedule::Synchronous {
            previous.clone_from(&values);
        }
        let mut largest: f64 = 0.0;
        for &x in &swept {
            if problem.is_goal(x) {
                continue;
            }
            let source = if options.schedule == Schedule::Synchronous {
                &previous
            } else {
                &values
            };
            let mut best = f64::INFINITY;
            for a in problem.actions(x).filter(|&a| usable(a)) {
                let v = q(a, source);
                if v < best {
                    best = v;
                }
            }
            let old = values[x];
            let replace = match options.rule {
                UpdateRule::Assign => true,
                UpdateRule::Decrease => best < old,
            };
            if replace {
                largest = largest.max((best - old).abs());
                values[x] = best;
            }
        }
        let within = largest <= tolerance;
        if within || sweeps >= options.max_sweeps {
            break (largest, within);
        }
    };
    let per_sweep_backups: u64 = swept
        .iter()
        .map(|&x| problem.actions(x).filter(|&a| usable(a)).count() as u64)
        .sum();
    let per_sweep_terms: u64 = swept
        .iter()
        .flat_map(|&x| problem.actions(x))
        .filter(|&a| usable(a))
        .map(|a| problem.outcomes(a).len() as u64)
        .sum();
    let per_sweep_reference: u64 = swept.iter().map(|&x| problem.reference_terms(x)).sum();
    let policy = greedy(
        problem,
        usable,
        |a| q(a, &values),
        |x| values[x].is_finite(),
    );
    ViRun {
        cost_to_go: values,
        sweeps,
        converged,
        last_change,
        backups: sweeps * per_sweep_backups,
        outcome_terms: sweeps * per_sweep_terms,
        reference_counted: sweeps * per_sweep_reference,
        policy,
    }
}

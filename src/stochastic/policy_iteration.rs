//! The exact optimum of a stochastic problem (docs/spec.md §3): `G*`, `Q*` and an optimal policy by
//! policy iteration with exact rational linear solves.
//!
//! Problem class and assumptions (checked, not assumed): costs `l ≥ 0`; `G*(x)` is the least
//! expected cost over policies proper at `x` (module [`super::properness`]), `+∞` where there is
//! none. Unsafe actions (an outcome with `G* = +∞`) are never chosen.
//!
//! Algorithm:
//! 1. **Initial proper policy**: the deterministic optimum of the intended moves (the commanded
//!    move, or for an action that only lists outcomes its most likely outcome:
//!    [`StochasticProblem::intended`]; first optimal move making progress, as in
//!    [`crate::solvers::greedy_policy`]), where its action is safe; if that policy is not
//!    proper on the finite states, the attractor policy (always proper). A problem read from
//!    an explicit file thus starts where the same problem built from a grid and `γ` does.
//! 2. **Warm start in `f64`**: policy iteration with `f64` evaluations, switching an action only
//!    when it is better by a relative margin of 10⁻⁹, and only while the policy stays proper.
//!    This only proposes a policy; nothing of it is reported.
//! 3. **Mixed-precision policy iteration** ([`super::refine`]): evaluations in fixed point by
//!    iterative refinement with a certified error bound, switching only where an improvement
//!    is certified strict, raising the precision where gaps are within the bound. On grids
//!    with many ties the `Q`-values of two actions differ by far less than `f64` resolves
//!    (relative gaps down to `10⁻³⁰⁰`); this stage resolves them, so the exact stage starts from
//!    a policy that is optimal up to exact ties. Nothing of it is reported.
//! 4. **Exact policy iteration**: evaluate the policy `μ` exactly by solving
//!    `(I − P_μ)·G = l_μ` over the finite non-goal states ([`super::linear::solve_exact`]),
//!    then improve: at every state switch to the first action whose exact `Q` is *strictly*
//!    smaller than `G_μ(x)`. Stop when no state switches (one exact evaluation and this check
//!    in the common case).
//!
//! Why this is exact and terminates: with `l ≥ 0`, strict improvement from a proper policy gives
//! a proper policy (a closed class avoiding the goals would have zero cost and no strict
//! switch inside it, so it would be closed under the old policy too); `G_μ` decreases, so no
//! policy repeats; at the end `G_μ` solves the Bellman equation `G = min_safe u (l + P_u G)`
//! exactly, and for any proper `ν`, `G_ν = lim T_ν^k G_μ ≥ G_μ`. So `G_μ = G*`.
//!
//! The policy reported is canonical: at each state the first action (in `U(x)` order) whose
//! exact `Q*` equals `G*`; if that policy is improper (possible only with zero-cost cycles),
//! the policy found by policy iteration is reported instead.

use num_bigint::BigInt;
use num_traits::{ToPrimitive, Zero};

use super::linear::{
    solve_exact, solve_exact_with, solve_f64, BandOrdering, LiftProgress, LinearError, SparseSystem,
};
use super::properness::{analyse, is_proper, Properness};
use super::{StochasticError, StochasticProblem};
use crate::model::{Decision, ExactGraph, Move, Problem};
use crate::solvers::{dijkstra, greedy_policy};
use crate::value::{Extended, Rational};

/// The exact optimum: `G*(x) = numerator[x] / denominator` where finite.
#[derive(Clone, Debug, PartialEq)]
pub struct Optimum {
    numerators: Vec<Option<BigInt>>,
    /// `d·C`: the solver's common denominator times the costs' lcm denominator.
    denominator: BigInt,
    /// The solver's common denominator `d`.
    solution_denominator: BigInt,
    /// The reduced values, computed on first use.
    reduced: std::sync::OnceLock<Vec<Extended>>,
    /// An optimal proper policy: the action (global id) at every finite non-goal state.
    policy: Vec<Option<usize>>,
    is_goal: Vec<bool>,
    action_first: Vec<usize>,
    /// How the optimum was found.
    pub stats: PolicyIterationStats,
}

/// What policy iteration did.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct PolicyIterationStats {
    /// Where the initial proper policy came from: `deterministic-optimum` or `attractor`.
    pub initial_policy: &'static str,
    /// Improvement rounds of the `f64` warm start.
    pub float_iterations: usize,
    /// Certified improvement rounds of the mixed-precision stage ([`super::refine`]).
    pub refinement_rounds: usize,
    /// The precision (bits after the point) the mixed-precision stage ended at.
    pub refinement_bits: u64,
    /// Exact evaluations (the last one confirms optimality).
    pub exact_iterations: usize,
    /// Dixon lifting steps over all exact evaluations.
    pub lifting_steps: usize,
    /// Unknowns of the linear systems (finite non-goal states).
    pub unknowns: usize,
    /// States with finite `G*` (goals included).
    pub finite_states: usize,
}

impl Optimum {
    /// `G*(x)`, exact (`+∞` where no policy reaches a goal with probability 1).
    pub fn cost_to_go(&self, x: usize) -> Extended {
        match &self.numerators[x] {
            Some(n) => Extended::Finite(super::linear::reduced(n, &self.denominator)),
            None => Extended::Infinite,
        }
    }

    /// `G*` for every state (reduced once, then cached): the common factors with the shared
    /// denominator are found together ([`super::linear::reduced_all`]), not by one gcd of
    /// full-size numbers per state.
    pub fn cost_to_go_all(&self) -> &[Extended] {
        self.reduced.get_or_init(|| self.reduce())
    }

    /// [`cost_to_go_all`](Self::cost_to_go_all), taken out of the optimum (no copy of the
    /// values, which on a 100×100 grid hold hundreds of megabytes).
    pub fn into_cost_to_go(mut self) -> Vec<Extended> {
        match self.reduced.take() {
            Some(values) => values,
            None => self.reduce(),
        }
    }

    /// Every state's `G*`, reduced together by [`super::linear::reduced_all`] (not cached).
    fn reduce(&self) -> Vec<Extended> {
        let finite: Vec<&BigInt> = self.numerators.iter().flatten().collect();
        let mut values = super::linear::reduced_all(&finite, &self.denominator).into_iter();
        self.numerators
            .iter()
            .map(|n| match n {
                Some(_) => Extended::Finite(values.next().expect("one value a numerator")),
                None => Extended::Infinite,
            })
            .collect()
    }

    /// Every state's `G*` as [`Extended`]'s text (`"n/d"`, `"n"` or `"inf"`), the same strings
    /// as `cost_to_go_all()[x].to_string()` ([`for_each_cost_to_go_text`](Self::for_each_cost_to_go_text)
    /// collected).
    ///
    /// ```
    /// use truecost::model::{Move, Problem};
    /// use truecost::stochastic::{policy_iteration::optimum, NoiseModel, Predictability, StochasticProblem};
    /// use truecost::value::parse_rational;
    /// let one = parse_rational("1").unwrap();
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
    /// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
    /// assert_eq!(optimum(&s).unwrap().cost_to_go_texts(), ["10/9", "0"]);
    /// ```
    pub fn cost_to_go_texts(&self) -> Vec<String> {
        let mut texts = Vec::with_capacity(self.numerators.len());
        self.for_each_cost_to_go_text(&mut |pieces| {
            texts.push(pieces.concat());
            Ok(())
        })
        .expect("collecting never fails");
        texts
    }

    /// Every state's `G*` text, in state order, handed to `each` as pieces whose concatenation
    /// is `cost_to_go_all()[x].to_string()` (`[n, "/", d]`, `[n]` or `["inf"]`; digits, `-`,
    /// `/` and `inf` only), for a writer that streams them. The numerators are printed in
    /// parallel, a batch at a time, with one table of powers of ten for all of them
    /// ([`DecimalPowers`](crate::algebra::radix::DecimalPowers)), and each distinct reduced
    /// denominator only once (the reduced values share a few denominators, `d·C` divided by
    /// small factors; printing numbers of 10⁴ digits is the bulk of writing them all). Unless
    /// [`cost_to_go_all`](Self::cost_to_go_all) has cached them already, the reduced values
    /// are not cached (on a 100×100 grid they are 300 MB). Stops at the first error of `each`.
    ///
    /// ```
    /// use truecost::model::{Move, Problem};
    /// use truecost::stochastic::{policy_iteration::optimum, NoiseModel, Predictability, StochasticProblem};
    /// use truecost::value::parse_rational;
    /// let one = parse_rational("1").unwrap();
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
    /// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
    /// let mut pieces: Vec<Vec<String>> = Vec::new();
    /// optimum(&s).unwrap().for_each_cost_to_go_text(&mut |p| {
    ///     pieces.push(p.iter().map(|s| s.to_string()).collect());
    ///     Ok(())
    /// }).unwrap();
    /// assert_eq!(pieces, [vec!["10", "/", "9"], vec!["0"]]);
    /// ```
    pub fn for_each_cost_to_go_text(
        &self,
        each: &mut dyn FnMut(&[&str]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        use rayon::prelude::*;
        let owned;
        let values: &[Extended] = match self.reduced.get() {
            Some(values) => values,
            None => {
                owned = self.reduce();
                &owned
            }
        };
        let (denominators, slots) = denominator_texts(values);
        let bits = values
            .iter()
            .map(|v| match v {
                Extended::Finite(r) => r.numer().bits(),
                Extended::Infinite => 0,
            })
            .max()
            .unwrap_or(0);
        let powers = crate::algebra::radix::DecimalPowers::new(bits);
        let batch = 64 * rayon::current_num_threads();
        for (chunk, chunk_slots) in values.chunks(batch).zip(slots.chunks(batch)) {
            let numerators: Vec<String> = chunk
                .par_iter()
                .map(|v| match v {
                    Extended::Finite(r) => powers.text(r.numer()),
                    Extended::Infinite => "inf".to_string(),
                })
                .collect();
            for (numerator, &slot) in numerators.iter().zip(chunk_slots) {
                if slot == usize::MAX {
                    each(&[numerator])?;
                } else {
                    each(&[numerator, "/", &denominators[slot]])?;
                }
            }
        }
        Ok(())
    }

    /// `G*(x)` as the pair (numerator, common denominator) without reduction, `None` if `+∞`.
    pub fn unreduced(&self, x: usize) -> Option<(&BigInt, &BigInt)> {
        self.numerators[x].as_ref().map(|n| (n, &self.denominator))
    }

    /// `Q*(x, u)·s_x·d·C` as an integer (`s_x` the state's probability denominator), `None` if
    /// an outcome has `G* = +∞`.
    fn scaled_q(&self, problem: &StochasticProblem, action: usize) -> Option<BigInt> {
        let x = problem.state_of(action);
        let c = Rational::from_integer(problem.cost_denominator().clone());
        let cost = (problem.cost(action) * c).to_integer();
        let mut k = cost * BigInt::from(problem.denominator(x)) * &self.solution_denominator;
        for (o, &w) in problem.outcomes(action).iter().zip(problem.weights(action)) {
            k += self.numerators[o.successor].as_ref()? * BigInt::from(w);
        }
        Some(k)
    }

    /// `Q*(x, u) = l(x, u) + Σ_o p_o G*(o)` for an action (global id) of the problem this
    /// optimum was computed for; `+∞` if an outcome has `G* = +∞`.
    pub fn q_value(&self, problem: &StochasticProblem, action: usize) -> Extended {
        let x = problem.state_of(action);
        match self.scaled_q(problem, action) {
            Some(k) => Extended::Finite(super::linear::reduced(
                &k,
                &(&self.denominator * BigInt::from(problem.denominator(x))),
            )),
            None => Extended::Infinite,
        }
    }

    /// Whether `Q*(x, u) = G*(x)` for an action of a state with finite `G*` (exact integer
    /// comparison, no rational arithmetic).
    pub fn is_optimal_action(&self, problem: &StochasticProblem, action: usize) -> bool {
        let x = problem.state_of(action);
        match (&self.numerators[x], self.scaled_q(problem, action)) {
            (Some(n), Some(k)) => k == n * BigInt::from(problem.denominator(x)),
            _ => false,
        }
    }

    /// The reported optimal policy: [`Decision::Terminate`] at goals, the index of the action
    /// in `U(x)` elsewhere, `None` where `G* = +∞`.
    pub fn policy(&self) -> Vec<Option<Decision>> {
        (0..self.numerators.len())
            .map(|x| {
                if self.is_goal[x] {
                    Some(Decision::Terminate)
                } else {
                    self.policy[x].map(|a| Decision::Move(a - self.action_first[x]))
                }
            })
            .collect()
    }

    /// The reported optimal policy as global action ids (`None` at goals and infinite states).
    pub fn policy_actions(&self) -> &[Option<usize>] {
        &self.policy
    }
}

/// The distinct denominators of the non-integer values of `values`, printed once each, and
/// every value's index among them (`usize::MAX` for integers and `+∞`).
fn denominator_texts(values: &[Extended]) -> (Vec<String>, Vec<usize>) {
    use rayon::prelude::*;
    use std::collections::HashMap;
    let mut slot: HashMap<&BigInt, usize> = HashMap::new();
    let mut distinct: Vec<&BigInt> = Vec::new();
    let slots = values
        .iter()
        .map(|v| match v {
            Extended::Finite(r) if !r.is_integer() => *slot.entry(r.denom()).or_insert_with(|| {
                distinct.push(r.denom());
                distinct.len() - 1
            }),
            _ => usize::MAX,
        })
        .collect();
    (
        distinct
            .par_iter()
            .map(|d| crate::value::integer_text(d))
            .collect(),
        slots,
    )
}

/// How far a value function is from `G*`, exactly (over the states with finite `G*`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Distance {
    /// `V(x1) − G*(x1)` (signed), `None` if `G*(x1) = +∞` or `V(x1)` is not finite.
    pub initial: Option<Rational>,
    /// `max_x |V(x) − G*(x)|` over the compared states (0 if none).
    pub max_abs: Rational,
    /// A state attaining `max_abs` (the lowest index).
    pub worst_state: Option<usize>,
    /// States compared (finite `G*` and finite `V`).
    pub compared: usize,
    /// States with finite `G*` where `V` is not finite.
    pub not_finite: usize,
}

impl Optimum {
    /// The exact distance of a value function from `G*`; `value(x)` is `V(x)` exactly (`None`
    /// if not finite). For `f64` values use `Rational::from_float`, which is exact.
    ///
    /// ```
    /// use truecost::model::{Move, Problem};
    /// use truecost::stochastic::{policy_iteration::optimum, NoiseModel, Predictability, StochasticProblem};
    /// use truecost::value::{parse_rational, Rational};
    /// let p = Problem::new(vec![vec![Move { successor: 1, cost: parse_rational("1").unwrap() }], vec![]], 0, vec![1]).unwrap();
    /// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.5").unwrap()).unwrap();
    /// let o = optimum(&s).unwrap(); // G*(0) = 2
    /// let d = o.distance(0, |x| Some(if x == 0 { parse_rational("1.75").unwrap() } else { Rational::from_integer(0.into()) }));
    /// assert_eq!(d.initial.unwrap().to_string(), "-1/4");
    /// assert_eq!((d.worst_state, d.compared), (Some(0), 2));
    /// ```
    pub fn distance(&self, initial: usize, value: impl Fn(usize) -> Option<Rational>) -> Distance {
        // Differences are kept as unreduced fractions and compared by cross-multiplication:
        // big-rational subtraction would reduce by a gcd of thousands of digits each time.
        let mut worst: Option<(BigInt, BigInt, usize)> = None;
        let mut at_initial = None;
        let (mut compared, mut not_finite) = (0, 0);
        for x in 0..self.numerators.len() {
            let Some(n) = &self.numerators[x] else {
                continue;
            };
            let Some(v) = value(x) else {
                not_finite += 1;
                continue;
            };
            // V − G* = (v_n·Den − n·v_d) / (v_d·Den)
            let num = v.numer() * &self.denominator - n * v.denom();
            let den = v.denom() * &self.denominator;
            let larger = match &worst {
                None => true,
                Some((wn, wd, _)) => {
                    num.magnitude() * wd.magnitude() > wn.magnitude() * den.magnitude()
                }
            };
            if x == initial {
                at_initial = Some((num.clone(), den.clone()));
            }
            if larger {
                worst = Some((num, den, x));
            }
            compared += 1;
        }
        let abs = |(n, d): (BigInt, BigInt)| Rational::new(num_traits::Signed::abs(&n), d);
        Distance {
            initial: at_initial.map(|(n, d)| Rational::new(n, d)),
            worst_state: worst.as_ref().map(|w| w.2),
            max_abs: worst.map_or_else(Rational::zero, |(n, d, _)| abs((n, d))),
            compared,
            not_finite,
        }
    }

    /// The states where the action `policy[x]` (global id, `None` = no action) is not optimal:
    /// `Q*(x, u) > G*(x)` (or no action where `G*` is finite). Goals are not counted.
    pub fn suboptimal_states(
        &self,
        problem: &StochasticProblem,
        policy: &[Option<usize>],
    ) -> Vec<usize> {
        (0..self.numerators.len())
            .filter(|&x| !self.is_goal[x])
            .filter(|&x| match (&self.numerators[x], policy[x]) {
                (None, _) => false,
                (_, None) => true,
                (Some(_), Some(a)) => !self.is_optimal_action(problem, a),
            })
            .collect()
    }
}

/// Computes the exact optimum (module docs).
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{policy_iteration::optimum, NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// // 0 -> 1 (goal); paper noise with one move: stay with probability 1 - γ.
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// let o = optimum(&s).unwrap();
/// assert_eq!(o.cost_to_go(0).to_string(), "10/9"); // G = 1 + 0.1 G
/// ```
pub fn optimum(problem: &StochasticProblem) -> Result<Optimum, StochasticError> {
    optimum_with(problem, &mut |_| {})
}

/// What [`optimum_with`] is doing, for a progress display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Progress {
    /// An `f64` policy evaluation of the warm start begins (its round, from 1).
    FloatEvaluation {
        /// The round.
        round: usize,
    },
    /// A fixed-point evaluation of the mixed-precision stage ([`super::refine`]) begins: the
    /// policy's number in that stage (from 1) and the precision in bits after the point (it
    /// doubles while gaps stay within the certified error bound).
    Refinement {
        /// The policy evaluated (1 for the warm start's, then one more per certified round).
        policy: usize,
        /// The precision `B` (bits after the point).
        bits: u64,
    },
    /// An exact policy evaluation begins (its number, from 1).
    ExactEvaluation {
        /// The evaluation.
        evaluation: usize,
    },
    /// A Dixon lifting step of the current exact evaluation is done.
    Lifting(LiftProgress),
}

/// [`optimum`], calling `progress` as it goes (evaluations, refinement precisions and lifting
/// steps). The result does not depend on `progress`.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::policy_iteration::{optimum_with, Progress};
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: one }], vec![]], 0, vec![1]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// let mut exact = 0;
/// let o = optimum_with(&s, &mut |e| if let Progress::ExactEvaluation { .. } = e { exact += 1 }).unwrap();
/// assert_eq!((exact, o.stats.exact_iterations), (1, 1));
/// ```
pub fn optimum_with(
    problem: &StochasticProblem,
    progress: &mut dyn FnMut(Progress),
) -> Result<Optimum, StochasticError> {
    let properness = analyse(problem);
    let (mut policy, initial_policy) = initial_policy(problem, &properness);
    let index = Unknowns::new(problem, &properness.finite);
    let mut stats = PolicyIterationStats {
        initial_policy,
        unknowns: index.states.len(),
        finite_states: properness.finite.iter().filter(|&&f| f).count(),
        ..Default::default()
    };
    let scaled_costs = scaled_costs(problem)?;

    // 2. f64 warm start.
    for round in 1..=100 {
        progress(Progress::FloatEvaluation { round });
        let system = build_system(problem, &index, &policy, &scaled_costs)?;
        let z = solve_f64(&system).map_err(linear_error)?;
        let value = |y: usize| index.of[y].map_or(0.0, |i| z[i]);
        let mut next = policy.clone();
        let mut changed = false;
        for (i, &x) in index.states.iter().enumerate() {
            let current = z[i];
            let margin = 1e-9 * current.abs().max(1.0);
            let mut best = (current - margin, None);
            for a in problem.actions(x).filter(|&a| properness.safe[a]) {
                let q = scaled_costs.float[a]
                    + problem
                        .outcomes(a)
                        .iter()
                        .zip(problem.probabilities_f64(a))
                        .map(|(o, p)| p * value(o.successor))
                        .sum::<f64>();
                if q < best.0 {
                    best = (q, Some(a));
                }
            }
            if let (_, Some(a)) = best {
                if policy[x] != Some(a) {
                    next[x] = Some(a);
                    changed = true;
                }
            }
        }
        if !changed || !is_proper(problem, &properness.finite, &next) {
            break;
        }
        policy = next;
        stats.float_iterations += 1;
    }

    // 3. Mixed-precision policy iteration (certified strict improvements only).
    let refined = super::refine::improve(
        problem,
        &properness.safe,
        &index.states,
        &index.of,
        &scaled_costs.exact,
        &mut policy,
        super::refine::Hooks {
            build: &|p| build_system(problem, &index, p, &scaled_costs).ok(),
            progress: &mut |policy, bits| progress(Progress::Refinement { policy, bits }),
        },
    );
    stats.refinement_rounds = refined.rounds;
    stats.refinement_bits = refined.bits;
    debug_assert!(is_proper(problem, &properness.finite, &policy));

    // 4. Exact policy iteration.
    loop {
        progress(Progress::ExactEvaluation {
            evaluation: stats.exact_iterations + 1,
        });
        let system = build_system(problem, &index, &policy, &scaled_costs)?;
        let z = solve_exact_with(&system, &mut |l| progress(Progress::Lifting(l)))
            .map_err(linear_error)?;
        stats.exact_iterations += 1;
        stats.lifting_steps += z.lifting_steps;
        // Per state (in parallel; each verdict depends only on `z`): the first action with
        // the least exact `Q`, and whether it is strictly below `G_μ`.
        let verdicts = improvement_check(problem, &properness.safe, &index, &scaled_costs, &z);
        let mut changed = false;
        let mut canonical = policy.clone();
        for (&x, &(a, better)) in index.states.iter().zip(&verdicts) {
            canonical[x] = Some(a);
            if better {
                policy[x] = Some(a);
                changed = true;
            }
        }
        // Strict improvement from a proper policy with costs ≥ 0 stays proper (module docs).
        debug_assert!(is_proper(problem, &properness.finite, &policy));
        if !changed {
            let chosen = if is_proper(problem, &properness.finite, &canonical) {
                canonical
            } else {
                policy
            };
            return Ok(finish(problem, &properness, &index, z, chosen, stats));
        }
    }
}

/// The exact improvement test of policy iteration at every unknown (in parallel over the
/// states): the first safe action (in `U(x)` order) with the least `Q_μ(x, a)`, and whether
/// that `Q` is strictly below `G_μ(x)`. Integer comparisons of `s_x·d·Q`, no rationals.
fn improvement_check(
    problem: &StochasticProblem,
    safe: &[bool],
    index: &Unknowns,
    costs: &ScaledCosts,
    z: &super::linear::ExactSolution,
) -> Vec<(usize, bool)> {
    use rayon::prelude::*;
    index
        .states
        .par_iter()
        .enumerate()
        .map(|(i, &x)| {
            let s = problem.denominator(x);
            let current = &z.numerators[i] * BigInt::from(s);
            let mut best: Option<(BigInt, usize)> = None;
            for a in problem.actions(x).filter(|&a| safe[a]) {
                let mut k = (&costs.exact[a] * BigInt::from(s)) * &z.denominator;
                for (o, &w) in problem.outcomes(a).iter().zip(problem.weights(a)) {
                    if let Some(j) = index.of[o.successor] {
                        k += &z.numerators[j] * BigInt::from(w);
                    }
                }
                if best.as_ref().is_none_or(|(b, _)| &k < b) {
                    best = Some((k, a));
                }
            }
            let (k, a) = best.expect("a finite non-goal state has a safe action");
            (a, k < current)
        })
        .collect()
}

/// The exact expected cost `G_μ(x)` of a stationary policy from every state: `policy[x]` is an
/// action id of `x` (`None`: no action). `+∞` at the states from which `μ` does not reach a
/// goal with probability 1 (some state reachable from them under `μ` cannot reach a goal, or
/// has no valid action). Goals are 0 (termination). Useful to judge a learned greedy policy.
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{policy_iteration::evaluate, NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// // 0 <-> 1 -> 2 (goal)
/// let p = Problem::new(vec![
///     vec![Move { successor: 1, cost: one.clone() }],
///     vec![Move { successor: 0, cost: one.clone() }, Move { successor: 2, cost: one.clone() }],
///     vec![],
/// ], 0, vec![2]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.5").unwrap()).unwrap();
/// let g = evaluate(&s, &[Some(0), Some(2), None]).unwrap();
/// assert_eq!(g.iter().map(|v| v.to_string()).collect::<Vec<_>>(), ["5", "3", "0"]);
/// // Commanding "back" at 1 still reaches the goal through noise: G(1) = 1 + G(0)/2 + G(1)/4.
/// let back_and_forth = evaluate(&s, &[Some(0), Some(1), None]).unwrap();
/// assert_eq!(back_and_forth.iter().map(|v| v.to_string()).collect::<Vec<_>>(), ["10", "8", "0"]);
/// // Without noise it never does: +∞.
/// let d = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::one()).unwrap();
/// let g = evaluate(&d, &[Some(0), Some(1), None]).unwrap();
/// assert_eq!(g.iter().map(|v| v.to_string()).collect::<Vec<_>>(), ["inf", "inf", "0"]);
/// ```
pub fn evaluate(
    problem: &StochasticProblem,
    policy: &[Option<usize>],
) -> Result<Vec<Extended>, StochasticError> {
    let all: Vec<usize> = (0..problem.states()).collect();
    evaluate_at(problem, policy, &all)
}

/// [`evaluate`]'s values at the given states only, in their order: the same exact solve, but
/// only these values are reduced to lowest terms (on a large grid, reducing every state's
/// fraction of thousands of digits costs several times the solve).
///
/// ```
/// use truecost::model::{Move, Problem};
/// use truecost::stochastic::{policy_iteration::evaluate_at, NoiseModel, Predictability, StochasticProblem};
/// use truecost::value::parse_rational;
/// let one = parse_rational("1").unwrap();
/// let p = Problem::new(vec![vec![Move { successor: 1, cost: one.clone() }], vec![Move { successor: 2, cost: one }], vec![]], 0, vec![2]).unwrap();
/// let s = StochasticProblem::from_deterministic(&p, NoiseModel::Paper, &Predictability::parse("0.5").unwrap()).unwrap();
/// let g = evaluate_at(&s, &[Some(0), Some(1), None], &[1, 0]).unwrap();
/// assert_eq!(g.iter().map(|v| v.to_string()).collect::<Vec<_>>(), ["2", "4"]);
/// ```
pub fn evaluate_at(
    problem: &StochasticProblem,
    policy: &[Option<usize>],
    states: &[usize],
) -> Result<Vec<Extended>, StochasticError> {
    let n = problem.states();
    let action = |x: usize| -> Option<usize> {
        policy
            .get(x)
            .copied()
            .flatten()
            .filter(|a| problem.actions(x).contains(a))
    };
    // Backward reachability of the goals, and of the "stuck" states, over the policy's edges.
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for x in 0..n {
        if problem.is_goal(x) {
            continue;
        }
        if let Some(a) = action(x) {
            for o in problem.outcomes(a) {
                into[o.successor].push(x);
            }
        }
    }
    let backward = |seeds: Vec<usize>| {
        let mut seen = vec![false; n];
        let mut stack = seeds;
        for &s in &stack {
            seen[s] = true;
        }
        while let Some(y) = stack.pop() {
            for &x in &into[y] {
                if !seen[x] && !problem.is_goal(x) {
                    seen[x] = true;
                    stack.push(x);
                }
            }
        }
        seen
    };
    let reaches_goal = backward(problem.goals().to_vec());
    let stuck: Vec<usize> = (0..n).filter(|&x| !reaches_goal[x]).collect();
    let improper = backward(stuck);
    let mut finite = vec![false; n];
    for x in 0..n {
        finite[x] = problem.is_goal(x) || !improper[x];
    }
    let index = Unknowns::new(problem, &finite);
    let costs = scaled_costs(problem)?;
    let full: Vec<Option<usize>> = (0..n).map(action).collect();
    let system = build_system(problem, &index, &full, &costs)?;
    let z = solve_exact(&system).map_err(linear_error)?;
    let den = &z.denominator * problem.cost_denominator();
    Ok(states
        .iter()
        .map(|&x| {
            if problem.is_goal(x) {
                Extended::Finite(Rational::zero())
            } else {
                match index.of[x] {
                    Some(i) => {
                        Extended::Finite(Rational::new(z.numerators[i].clone(), den.clone()))
                    }
                    None => Extended::Infinite,
                }
            }
        })
        .collect())
}

/// The estimated peak memory of [`optimum`] on a problem, computed from its structure alone
/// before any work (`--max-memory`).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MemoryEstimate {
    /// Estimated peak bytes.
    pub bytes: u64,
    /// Unknowns of the linear systems (at most: non-goal states with an action).
    pub unknowns: usize,
    /// Band width `lower + upper + 1` after the reverse Cuthill–McKee ordering of the pattern
    /// of every action's outcomes.
    pub band_width: usize,
    /// Lifting steps from the Hadamard bound (an upper estimate; a 100×100 grid needs 94%):
    /// `⌈lifted_bits / 31⌉ + 2`.
    pub lifting_steps: usize,
    /// The bits of the lifted solution: `2·(Σᵢ ½·log₂ maxₐ ‖rowᵢ(a)‖² + log₂ max(1, maxₐ bₐ) +
    /// log₂(n + 1)) + 8`, where `rowᵢ(a)` is the row of `s·(I − P)` of action `a` of the
    /// `i`-th unknown (`s` its state's [`denominator`](StochasticProblem::denominator)), `bₐ
    /// = s·l(x, a)·` [`cost_denominator`](StochasticProblem::cost_denominator) its right-hand
    /// side and `n` the number of unknowns: Hadamard's bound on the determinant and the
    /// numerators (Cramer's rule), both signs and a margin.
    pub lifted_bits: f64,
    /// The mixed-precision stage's own peak ([`super::refine`], over before the exact stage
    /// starts): its `f64` band LU (8 bytes a band entry), the fixed-point unknowns and their
    /// residuals at the stage's precision cap (two numbers of
    /// [`refinement_cap_bits`](Self::refinement_cap_bits) a unknown, each with a 32-byte
    /// header) and four `f64` vectors. The estimate counts the larger of this and the exact
    /// stage.
    pub refinement_bytes: u64,
    /// The mixed-precision stage's precision cap, estimated from above: `Σᵢ ½·log₂ maxₐ
    /// ‖rowᵢ(a)‖²` (Hadamard's bound on `log₂|det A|`) plus 192 bits (the stage's margins and
    /// `log₂` of its step bound).
    pub refinement_cap_bits: f64,
}

/// Bytes per unknown besides its numbers (indices, policy, the problem's per-state lists,
/// vectors of the warm start); the problem's actions and outcomes are [`problem_bytes`].
const PER_UNKNOWN: u64 = 1024;

/// Bytes the problem holds per outcome: its exact probability (two one-limb integers in their
/// own allocations, 32 bytes each from the allocator), weight, `f64` probability, cumulative
/// probability and successor. Measured 114 on complete graphs (`tests/stochastic_memory.rs`,
/// 3 Dec 2026, with the allocator's rounding); until then the estimate counted 48 and, with
/// the problem's lists still holding their spare capacity, was below the measured peak on a
/// complete graph of 80 states.
const PER_OUTCOME: u64 = 128;

/// Bytes the problem holds per action (its exact cost, ranges, state and commanded move) on
/// top of its outcomes: measured about 100–120 on chains and grids.
const PER_ACTION: u64 = 160;

/// The process itself (code, allocator, the parsed problem file's leftovers): 16 MiB, measured
/// as the peak of the smallest runs.
const BASE_BYTES: u64 = 16 << 20;

/// An upper estimate of the heap a built problem holds (its outcomes and actions; a built
/// problem's lists keep no spare capacity): the first part of [`memory_estimate`].
///
/// ```
/// use truecost::stochastic::benchmark::cost_grid;
/// use truecost::stochastic::policy_iteration::problem_bytes;
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// let grid = cost_grid(10, 10, 0).unwrap();
/// let s = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &Predictability::parse("0.9").unwrap()).unwrap();
/// // More than 100 bytes an outcome (tests/stochastic_memory.rs measures what problems hold).
/// assert!(problem_bytes(&s) > 100 * s.outcome_total() as u64);
/// ```
pub fn problem_bytes(problem: &StochasticProblem) -> u64 {
    problem.outcome_total() as u64 * PER_OUTCOME + problem.action_total() as u64 * PER_ACTION
}

/// Estimates the peak memory of [`optimum`] (see [`MemoryEstimate`]); with `all_values`, also
/// the reduced exact value of every state and its decimal text, as `solve --format json`
/// prints them. The parts: the problem and per-unknown bookkeeping, then the larger of the two
/// stages that are never alive together: the exact stage — two band matrices (`u32`/`u64`
/// modular and `f64` warm-start LU), the lifted digits (4 bytes per unknown and step), the
/// numerators (three copies at the peak, each of `⌈lifted_bits / 16⌉ + 32` bytes, half the
/// lifted bits and a header) — and the mixed-precision stage
/// ([`MemoryEstimate::refinement_bytes`]); with `all_values`, two more copies and four
/// decimal texts (2.41 digits a byte).
///
/// ```
/// use truecost::stochastic::benchmark::cost_grid;
/// use truecost::stochastic::policy_iteration::memory_estimate;
/// use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
/// let grid = cost_grid(10, 10, 0).unwrap();
/// let s = StochasticProblem::from_deterministic(&grid, NoiseModel::Paper, &Predictability::parse("0.99").unwrap()).unwrap();
/// let e = memory_estimate(&s, false);
/// assert_eq!(e.unknowns, 99);
/// assert!(e.bytes > 16 << 20 && e.bytes < 32 << 20, "{e:?}");
/// assert!(memory_estimate(&s, true).bytes > e.bytes);
/// ```
pub fn memory_estimate(problem: &StochasticProblem, all_values: bool) -> MemoryEstimate {
    let n = problem.states();
    let mut of = vec![None; n];
    let mut states = Vec::new();
    for (x, index) in of.iter_mut().enumerate() {
        if !problem.is_goal(x) && !problem.actions(x).is_empty() {
            *index = Some(states.len());
            states.push(x);
        }
    }
    // The union pattern of every action (any policy's system is a sub-pattern), and per row the
    // largest squared norm over the actions, for the Hadamard bound.
    let mut pattern = SparseSystem::new();
    let mut bits = 0.0f64;
    let mut max_rhs = 1.0f64;
    let mut entries: Vec<(usize, i64)> = Vec::new();
    for (i, &x) in states.iter().enumerate() {
        let s = problem.denominator(x) as f64;
        entries.clear();
        entries.push((i, 1));
        let mut norm2 = 1.0f64;
        for a in problem.actions(x) {
            let mut row = vec![(i, s)];
            for (o, &w) in problem.outcomes(a).iter().zip(problem.weights(a)) {
                if let Some(j) = of[o.successor] {
                    entries.push((j, 1));
                    match row.iter_mut().find(|(c, _)| *c == j) {
                        Some(e) => e.1 -= w as f64,
                        None => row.push((j, -(w as f64))),
                    }
                }
            }
            norm2 = norm2.max(row.iter().map(|(_, v)| v * v).sum());
            let cost = (problem.cost(a)
                * Rational::from_integer(problem.cost_denominator().clone()))
            .to_f64()
            .unwrap_or(f64::MAX);
            max_rhs = max_rhs.max(cost * s);
        }
        bits += 0.5 * norm2.log2();
        entries.sort_unstable();
        entries.dedup();
        let _ = pattern.push_row(&entries, 0);
    }
    let unknowns = states.len();
    let ordering = BandOrdering::new(&pattern);
    let (lower, upper) = ordering.bandwidths();
    let band_width = lower + upper + 1;
    let lifted_bits = 2.0 * (bits + max_rhs.log2() + (unknowns as f64 + 1.0).log2()) + 8.0;
    let lifting_steps = (lifted_bits / 31.0).ceil() as usize + 2;
    let u = unknowns as u64;
    let number_bytes = (lifted_bits / 16.0).ceil() as u64 + 32;
    let exact_bytes =
        u * band_width as u64 * (8 + 4 + 8) + u * lifting_steps as u64 * 4 + 3 * u * number_bytes;
    let refinement_cap_bits = bits + 192.0;
    let refinement_bytes = u * band_width as u64 * 8
        + 2 * u * ((refinement_cap_bits / 8.0).ceil() as u64 + 32)
        + 4 * u * 8;
    let mut bytes =
        BASE_BYTES + problem_bytes(problem) + u * PER_UNKNOWN + exact_bytes.max(refinement_bytes);
    if all_values {
        // Reduced fractions (numerator and denominator) and their decimal text, twice (the
        // strings and the JSON document).
        bytes += u * number_bytes * 2 + 4 * u * (number_bytes as f64 * 2.41) as u64;
    }
    MemoryEstimate {
        bytes,
        unknowns,
        band_width,
        lifting_steps,
        lifted_bits,
        refinement_bytes,
        refinement_cap_bits,
    }
}

fn linear_error(e: LinearError) -> StochasticError {
    match e {
        LinearError::TooLarge => StochasticError::TooLarge(
            "the exact linear solve needs numbers beyond its limits (matrix entries below 2^62, right-hand sides below 2^100, at most 2^32 states)".into(),
        ),
        e @ LinearError::TooWide { .. } => StochasticError::TooLarge(e.to_string()),
        LinearError::Singular => {
            unreachable!("policy evaluation of a proper policy is never singular (a truecost bug)")
        }
    }
}

fn finish(
    problem: &StochasticProblem,
    properness: &Properness,
    index: &Unknowns,
    z: super::linear::ExactSolution,
    policy: Vec<Option<usize>>,
    stats: PolicyIterationStats,
) -> Optimum {
    let n = problem.states();
    let denominator = &z.denominator * problem.cost_denominator();
    let numerators: Vec<Option<BigInt>> = (0..n)
        .map(|x| {
            if problem.is_goal(x) {
                Some(BigInt::zero())
            } else {
                index.of[x].map(|i| z.numerators[i].clone())
            }
        })
        .collect();
    debug_assert!(numerators
        .iter()
        .zip(&properness.finite)
        .all(|(v, &f)| v.is_some() == f));
    Optimum {
        numerators,
        denominator,
        solution_denominator: z.denominator,
        reduced: std::sync::OnceLock::new(),
        policy,
        is_goal: (0..n).map(|x| problem.is_goal(x)).collect(),
        action_first: (0..n).map(|x| problem.actions(x).start).collect(),
        stats,
    }
}

/// The unknowns: finite non-goal states, compactly numbered.
struct Unknowns {
    states: Vec<usize>,
    of: Vec<Option<usize>>,
}

impl Unknowns {
    fn new(problem: &StochasticProblem, finite: &[bool]) -> Self {
        let mut states = Vec::new();
        let mut of = vec![None; problem.states()];
        for x in 0..problem.states() {
            if finite[x] && !problem.is_goal(x) {
                of[x] = Some(states.len());
                states.push(x);
            }
        }
        Unknowns { states, of }
    }
}

/// Stage costs times the lcm `C` of their denominators (integers), and as `f64`.
struct ScaledCosts {
    exact: Vec<BigInt>,
    float: Vec<f64>,
}

fn scaled_costs(problem: &StochasticProblem) -> Result<ScaledCosts, StochasticError> {
    let c = Rational::from_integer(problem.cost_denominator().clone());
    let mut exact = Vec::with_capacity(problem.action_total());
    let mut float = Vec::with_capacity(problem.action_total());
    for a in 0..problem.action_total() {
        let scaled = problem.cost(a) * &c;
        debug_assert!(scaled.is_integer());
        exact.push(scaled.to_integer());
        float.push(scaled.to_f64().unwrap_or(f64::MAX));
    }
    Ok(ScaledCosts { exact, float })
}

/// The system `s_x·G(x) − Σ_o w_o·G(o) = s_x·C·l(x, μ(x))` over the unknowns (its solution is
/// `C·G_μ`).
fn build_system(
    problem: &StochasticProblem,
    index: &Unknowns,
    policy: &[Option<usize>],
    costs: &ScaledCosts,
) -> Result<SparseSystem, StochasticError> {
    let mut system = SparseSystem::new();
    let mut entries = Vec::new();
    for (i, &x) in index.states.iter().enumerate() {
        let a = policy[x].expect("a proper policy acts at every finite state");
        let s = problem.denominator(x);
        entries.clear();
        entries.push((i, s as i64));
        for (o, &w) in problem.outcomes(a).iter().zip(problem.weights(a)) {
            if let Some(j) = index.of[o.successor] {
                entries.push((j, -(w as i64)));
            }
        }
        let rhs = (&costs.exact[a] * BigInt::from(s))
            .to_i128()
            .ok_or(StochasticError::CostTooLarge { state: x })?;
        system
            .push_row(&entries, rhs)
            .map_err(|_| StochasticError::CostTooLarge { state: x })?;
    }
    Ok(system)
}

/// Step 1 of the module docs.
fn initial_policy(
    problem: &StochasticProblem,
    properness: &Properness,
) -> (Vec<Option<usize>>, &'static str) {
    if let Some(policy) = deterministic_policy(problem, properness) {
        if is_proper(problem, &properness.finite, &policy) {
            return (policy, "deterministic-optimum");
        }
    }
    (properness.attractor.clone(), "attractor")
}

/// The deterministic optimum over intended moves ([`StochasticProblem::intended`]), where safe
/// (attractor action elsewhere).
fn deterministic_policy(
    problem: &StochasticProblem,
    properness: &Properness,
) -> Option<Vec<Option<usize>>> {
    let n = problem.states();
    let mut moves = Vec::with_capacity(n);
    for x in 0..n {
        let mut list = Vec::new();
        for a in problem.actions(x) {
            list.push(Move {
                successor: problem.intended(a),
                cost: problem.cost(a).clone(),
            });
        }
        moves.push(list);
    }
    let deterministic = Problem::new(moves, problem.initial(), problem.goals().to_vec()).ok()?;
    let decisions = match ExactGraph::new(&deterministic) {
        ExactGraph::Units(g) => greedy_policy(&g, &dijkstra::to_goals(&g).cost_to_go),
        ExactGraph::Big(g) => greedy_policy(&g, &dijkstra::to_goals(&g).cost_to_go),
    };
    Some(
        (0..n)
            .map(|x| {
                if !properness.finite[x] || problem.is_goal(x) {
                    return None;
                }
                match decisions[x] {
                    Some(Decision::Move(i)) => {
                        let a = problem.actions(x).start + i;
                        if properness.safe[a] {
                            Some(a)
                        } else {
                            properness.attractor[x]
                        }
                    }
                    _ => properness.attractor[x],
                }
            })
            .collect(),
    )
}

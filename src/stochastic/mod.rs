//! The stochastic model of docs/spec.md §3: a predictability factor `γ ∈ (0, 1]`, two named noise models
//! that turn a deterministic problem into a stochastic one, the exact optimum (policy iteration
//! with exact rational linear solves), and stochastic value iteration (exact and `f64`).
//!
//! * [`noise`] — `γ` ([`Predictability`], parsed exactly from its decimal text) and the two
//!   noise models ([`NoiseModel::Paper`], the default, and [`NoiseModel::Reference`]).
//! * [`problem`] — [`StochasticProblem`]: per state an ordered action list, each action a stage
//!   cost and a list of outcomes with exact probabilities (and `f64` cumulative thresholds for
//!   samplers such as a Q-learner).
//! * [`benchmark`] — the seeded cost-grid files of the scale benchmarks (large models).
//! * [`file`](mod@file) — stochastic extensions of the JSON problem file.
//! * [`grid`] — the paper's grid problems in the stochastic model, exact and as its code runs them.
//! * [`properness`] — which states can reach a goal with probability 1 (finite `G*`), which
//!   actions are safe, proper policies.
//! * [`linear`] — the exact sparse linear solver (Dixon p-adic lifting, rational reconstruction,
//!   exact verification) and its `f64` twin, from the exact-algebra layer
//!   ([`crate::algebra::linear`]).
//! * [`policy_iteration`] — the exact optimum `G*`, `Q*` and an optimal policy.
//! * [`refine`] — the mixed-precision policy iteration (certified improvements) that hands
//!   the exact stage an optimal policy up to exact ties.
//! * [`scale`] — the `--max-memory` budget of the exact optimum (sizes parsed exactly).
//! * [`value_iteration`] — stochastic VI and asynchronous VI, exact and `f64`, with an explicit
//!   stopping rule and the reference code's counting rule (docs/spec.md §7).
//!
//! Conventions (documented once here, used everywhere):
//! * The stage cost of an action is the cost of the **commanded** move, whatever nature does.
//! * A goal's termination action is deterministic and free: `G*(goal) = 0`.
//! * A trajectory that does not reach a goal has true cost `+∞` (as in the deterministic
//!   model), so a policy that fails to reach a goal with probability 1 from `x` has expected cost
//!   `+∞` at `x` — even around a zero-cost cycle. `G*(x)` is the least expected cost over the
//!   policies that reach a goal with probability 1 from `x` (*proper* at `x`), `+∞` if none.

pub mod benchmark;
pub mod certified;
pub mod file;
pub mod grid;
pub mod noise;
pub mod policy_iteration;
pub mod problem;
pub mod properness;
pub mod record;
pub mod refine;
pub mod scale;
pub mod value_iteration;

use crate::algebra::linear;

pub use noise::{NoiseModel, Predictability};
pub use problem::{Outcome, OutcomeKind, Provenance, StochasticAction, StochasticProblem};

/// Why a stochastic computation or input was refused. Every message fits on one line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum StochasticError {
    /// `γ` is not an exact number.
    #[error("predictability (gamma) {0}")]
    GammaText(#[from] crate::value::ParseRationalError),
    /// `γ ∉ (0, 1]`.
    #[error("predictability (gamma) must be in (0, 1], got {0}")]
    GammaRange(String),
    /// A probability outside `(0, 1]`.
    #[error("state {state}, action {action}: probability {probability} is not in (0, 1]")]
    ProbabilityRange {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
        /// The probability as text.
        probability: String,
    },
    /// An action whose outcome probabilities do not sum to exactly 1: the sum and its exact
    /// distance from 1, so a sum within `10^-17` of 1 is still shown apart.
    #[error("state {state}, action {action}: outcome probabilities sum to {sum}, not 1 ({off} 1 by {distance})")]
    ProbabilitySum {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
        /// The sum as text (shortened).
        sum: String,
        /// `above` or `below`.
        off: &'static str,
        /// `|sum − 1|`, exact when short enough.
        distance: String,
    },
    /// An action without outcomes.
    #[error("state {state}, action {action}: no outcomes")]
    NoOutcomes {
        /// The state.
        state: usize,
        /// The action index.
        action: usize,
    },
    /// The common denominator of a state's probabilities is too large for the exact solver.
    #[error("state {state}: the probabilities' common denominator exceeds 2^62 (the exact solver's limit)")]
    DenominatorTooLarge {
        /// The state.
        state: usize,
    },
    /// `γ`'s denominator makes a state's probabilities exceed [`problem::MAX_DENOMINATOR`].
    #[error("gamma = {gamma} has too large a denominator: at state {state} ({moves} moves) the common denominator of the noise model's probabilities exceeds 2^62, the exact solver's limit (gamma with at most 15 significant digits fits states of up to 2000 moves)")]
    GammaDenominator {
        /// `γ` as text (echoed, shortened).
        gamma: String,
        /// The first state where the limit is passed.
        state: usize,
        /// Its number of moves.
        moves: usize,
    },
    /// A stage cost too large for the exact solver.
    #[error("state {state}: stage costs times the probabilities' denominators exceed 2^100 (the exact solver's limit)")]
    CostTooLarge {
        /// The state.
        state: usize,
    },
    /// A problem too large for the exact solver.
    #[error("{0}")]
    TooLarge(String),
    /// A tolerance that is negative or not a number.
    #[error("tolerance must be a number >= 0, got {0}")]
    Tolerance(String),
    /// The deterministic problem is ill formed.
    #[error("{0}")]
    Model(#[from] crate::model::ModelError),
}

/// An exact value as it may appear in a message: its exact text when at most 40 characters,
/// else `≈` and 17 significant digits (so `1e-400` does not become a 401-digit fraction).
///
/// ```
/// use truecost::stochastic::short_text;
/// use truecost::value::parse_rational;
/// assert_eq!(short_text(&parse_rational("0.75").unwrap()), "3/4");
/// assert_eq!(short_text(&parse_rational("1e-400").unwrap()), "≈1e-400");
/// ```
pub fn short_text(r: &crate::value::Rational) -> String {
    let exact = crate::value::Extended::Finite(r.clone());
    let text = exact.to_string();
    if text.chars().count() <= 40 {
        text
    } else {
        format!("≈{}", decimal(&exact, 17))
    }
}

/// Where a sum of probabilities other than 1 lies: `above` or `below` 1, and by how much
/// (exact, shortened like [`short_text`]).
///
/// ```
/// use truecost::stochastic::off_one;
/// assert_eq!(off_one(&"5/6".parse().unwrap()), ("below", "1/6".to_string()));
/// assert_eq!(off_one(&"11/10".parse().unwrap()), ("above", "1/10".to_string()));
/// ```
pub fn off_one(sum: &crate::value::Rational) -> (&'static str, String) {
    use num_traits::One;
    let one = crate::value::Rational::one();
    if *sum > one {
        ("above", short_text(&(sum - &one)))
    } else {
        ("below", short_text(&(&one - sum)))
    }
}

/// The decimal expansion of an exact value rounded (half away from zero) to `significant`
/// significant digits: plain notation for magnitudes in `[1e-4, 1e{significant})`, otherwise
/// scientific (`1.25e-7`); `"0"` and `"inf"` as such.
///
/// ```
/// use truecost::stochastic::decimal;
/// use truecost::value::Extended;
/// let v: Extended = "10/9".parse().unwrap();
/// assert_eq!(decimal(&v, 5), "1.1111");
/// assert_eq!(decimal(&"-1/80000000".parse().unwrap(), 3), "-1.25e-8");
/// assert_eq!(decimal(&"2/3".parse().unwrap(), 3), "0.667");
/// assert_eq!(decimal(&"99.96".parse().unwrap(), 3), "100");
/// ```
pub fn decimal(value: &crate::value::Extended, significant: usize) -> String {
    use num_bigint::BigInt;
    use num_integer::Integer;
    use num_traits::{Signed, Zero};
    let significant = significant.max(1);
    let r = match value {
        crate::value::Extended::Infinite => return "inf".into(),
        crate::value::Extended::Finite(r) => r,
    };
    if r.is_zero() {
        return "0".into();
    }
    let sign = if r.is_negative() { "-" } else { "" };
    let (n, d) = (r.numer().abs(), r.denom().clone());
    let ten = BigInt::from(10);
    // k = floor(log10(n/d)).
    let text_len = |m: &BigInt| crate::value::integer_text(m).len() as i64;
    let mut k = text_len(&n) - text_len(&d);
    let at_least = |k: i64| -> bool {
        // n/d ≥ 10^k ?
        if k >= 0 {
            n >= &d * num_traits::pow(ten.clone(), k as usize)
        } else {
            &n * num_traits::pow(ten.clone(), (-k) as usize) >= d
        }
    };
    while !at_least(k) {
        k -= 1;
    }
    while at_least(k + 1) {
        k += 1;
    }
    let digits = |k: i64| -> BigInt {
        // round(n/d · 10^(significant−1−k)), half away from zero.
        let shift = significant as i64 - 1 - k;
        let (num, den) = if shift >= 0 {
            (&n * num_traits::pow(ten.clone(), shift as usize), d.clone())
        } else {
            (
                n.clone(),
                &d * num_traits::pow(ten.clone(), (-shift) as usize),
            )
        };
        (num * BigInt::from(2) + &den).div_floor(&(den * BigInt::from(2)))
    };
    let mut s = digits(k);
    if s.to_string().len() > significant {
        k += 1;
        s = digits(k);
    }
    let s = s.to_string();
    if k < -4 || k >= significant as i64 {
        let (head, tail) = s.split_at(1);
        let tail = tail.trim_end_matches('0');
        let mantissa = if tail.is_empty() {
            head.to_string()
        } else {
            format!("{head}.{tail}")
        };
        format!("{sign}{mantissa}e{k}")
    } else if k >= 0 {
        let (int, frac) = s.split_at(k as usize + 1);
        if frac.is_empty() {
            format!("{sign}{int}")
        } else {
            format!("{sign}{int}.{frac}")
        }
    } else {
        format!("{sign}0.{}{s}", "0".repeat((-k - 1) as usize))
    }
}

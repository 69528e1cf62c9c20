//! The bounds of the parametric analysis checked before any work (module docs of [`super`],
//! "Effort"): the size of the numbers that enter the polynomials; on a deterministic model, a
//! degree that the covering of `(0, 1)` is certain to meet; on a stochastic one, the room its
//! probabilities leave the denominators of the probes' `α`.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed};

use super::degree::{self, Certain};
use super::ParametricError;
#[cfg(doc)]
use super::MAX_CHAIN_DEGREE;
use crate::model::StateId;
use crate::objectives::Model;
use crate::stochastic::problem::MAX_DENOMINATOR;
use crate::value::Rational;

/// The largest magnitude of a stage cost or reward where the episode runs, as a power of two:
/// `|r| ≤ 2^100` (the exact solvers' limit on stage costs).
pub const MAX_MAGNITUDE_BITS: u64 = 100;

/// The most bits of a stage reward scaled to an integer by the lcm of the rewards'
/// denominators (the coefficients the value polynomials start from), and of that lcm. Root
/// isolation near `1` takes time growing with the square of these bits: a two-state problem
/// whose breakpoint is `1 − 10^-300` (about 1000 bits) takes 0.7 s, `1 − 10^-1000` 7.6 s.
pub const MAX_SCALED_BITS: u64 = 160;

/// A stage cost or reward where the episode runs that is too large, named by state and action
/// index (the file's numbering).
fn locate(model: &Model, a: usize) -> (StateId, usize) {
    let x = model.problem.state_of(a);
    (x, a - model.problem.actions(x).start)
}

/// Refuses, before any work, stage costs or rewards over `2^100` in magnitude
/// ([`MAX_MAGNITUDE_BITS`]) and rewards that take more than [`MAX_SCALED_BITS`] bits scaled to
/// integers (or whose denominators' lcm does), naming the state, the action, the number and the
/// bound. `1e10000`, `1e-10000` and a 4096-digit reward are refused at once.
pub fn check_numbers(model: &Model, running: &[StateId]) -> Result<(), ParametricError> {
    let p = &model.problem;
    let limit = BigInt::one() << MAX_MAGNITUDE_BITS;
    let too_large = |r: &Rational| r.abs() > Rational::from_integer(limit.clone());
    let mut lcm = BigInt::one();
    for &x in running {
        for a in p.actions(x) {
            for (quantity, r) in [("stage cost", p.cost(a)), ("reward", &model.reward[a])] {
                if too_large(r) {
                    let (state, action) = locate(model, a);
                    return Err(ParametricError::Magnitude {
                        state,
                        action,
                        quantity,
                        value: crate::stochastic::short_text(r),
                        bound: MAX_MAGNITUDE_BITS,
                    });
                }
            }
            lcm = lcm.lcm(model.reward[a].denom());
            if lcm.bits() > MAX_SCALED_BITS {
                let (state, action) = locate(model, a);
                return Err(ParametricError::ScaledBits {
                    state,
                    action,
                    value: crate::stochastic::short_text(&model.reward[a]),
                    what: "the lcm of the rewards' denominators up to it takes",
                    bits: lcm.bits(),
                    bound: MAX_SCALED_BITS,
                });
            }
        }
    }
    for &x in running {
        for a in p.actions(x) {
            let r = &model.reward[a];
            let bits = (r.numer() * (&lcm / r.denom())).bits();
            if bits > MAX_SCALED_BITS {
                let (state, action) = locate(model, a);
                return Err(ParametricError::ScaledBits {
                    state,
                    action,
                    value: crate::stochastic::short_text(r),
                    what: "scaled to an integer by the lcm of the rewards' denominators it takes",
                    bits,
                    bound: MAX_SCALED_BITS,
                });
            }
        }
    }
    Ok(())
}

/// A degree the covering of `(0, 1)` is certain to meet on a deterministic model, found before
/// any probe from the chain structure (module [`super::degree`]): the greater of
/// [`degree::near_one`] and [`degree::near_zero`].
pub fn certain_degree(model: &Model, running: &[StateId]) -> Option<Certain> {
    let one = degree::near_one(model, running);
    let zero = degree::near_zero(model, running);
    match (one, zero) {
        (Some(a), Some(b)) => Some(if b.degree > a.degree { b } else { a }),
        (a, b) => a.or(b),
    }
}

/// Refuses, before any probe, a deterministic model whose [`certain_degree`] exceeds `bound`
/// ([`MAX_CHAIN_DEGREE`] in the analysis), naming the state, the degree, why and the bound.
pub fn check_certain_degree(
    model: &Model,
    running: &[StateId],
    bound: usize,
) -> Result<(), ParametricError> {
    match certain_degree(model, running) {
        Some(c) if c.degree > bound => Err(ParametricError::CertainDegree {
            state: c.state,
            degree: c.degree,
            reason: c.reason,
            bound,
        }),
        _ => Ok(()),
    }
}

/// The room a stochastic model leaves `α`'s denominator: a probe at `α` solves the discounted
/// problem with probabilities `α·p` and `1 − α`, whose common denominator at a state divides
/// the state's own common denominator `D` times `α`'s denominator `q`; the exact solver takes
/// at most `2^62` ([`MAX_DENOMINATOR`]), so the probes take `α` with `q ≤ ⌊2^62 / D⌋` for the
/// largest `D` (at `state`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AlphaRoom {
    /// The state with the largest common denominator of its probabilities.
    pub state: StateId,
    /// That common denominator `D`.
    pub own: BigInt,
    /// `⌊2^62 / D⌋`: the largest denominator of a probe's `α`.
    pub room: BigInt,
}

impl AlphaRoom {
    /// The room of `model` ([`AlphaRoom`]), over the states where the episode runs.
    pub fn of(model: &Model, running: &[StateId]) -> AlphaRoom {
        let p = &model.problem;
        let (mut state, mut own) = (running.first().copied().unwrap_or(0), BigInt::one());
        for &x in running {
            let mut lcm = BigInt::one();
            for a in p.actions(x) {
                for o in p.outcomes(a) {
                    lcm = lcm.lcm(o.probability.denom());
                }
            }
            if lcm > own {
                (state, own) = (x, lcm);
            }
        }
        let room = BigInt::from(MAX_DENOMINATOR) / &own;
        AlphaRoom { state, own, room }
    }

    /// Whether a probe may take `alpha`: its denominator within the room.
    pub fn fits(&self, alpha: &Rational) -> bool {
        alpha.denom() <= &self.room
    }

    /// The refusal of `alpha` (`gap`: the gap of `(0, 1)` it was the simplest rational of, as
    /// text, with the probes run; `None`: before any work, `alpha = 1/2` the simplest of all).
    pub fn refusal(&self, alpha: &Rational, gap: Option<(String, usize)>) -> ParametricError {
        let product = &self.own * alpha.denom();
        let detail = match gap {
            None => format!(
                "every alpha in (0,1) has a denominator >= 2, which gives {product} (refused before any work)"
            ),
            Some((gap, probes)) => format!(
                "after {probes} probes the gap {gap} is left, whose simplest rational {} gives {product} (refused before that probe)",
                crate::stochastic::short_text(alpha),
            ),
        };
        ParametricError::AlphaDenominator {
            state: self.state,
            own: self.own.clone(),
            detail,
        }
    }
}

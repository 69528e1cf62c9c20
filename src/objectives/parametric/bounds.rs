//! The bounds of the parametric analysis checked before any work (module docs of [`super`],
//! "Effort"): the size of the numbers that enter the polynomials; on a deterministic model, a
//! degree that the covering of `(0, 1)` is certain to meet; on a stochastic one, the room its
//! probabilities leave the denominators of the probes' `α`.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

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

/// The exact solver's bound on a stage cost scaled to an integer times its state's common
/// denominator of probabilities: the right-hand sides of its equations stay below `2^100`.
pub const MAX_SCALED_COST_BITS: u64 = 100;

/// The room a stochastic model leaves `α`'s denominator `q`. A probe at `α` solves the
/// discounted problem (the killed-process construction of [`Model`]) with probabilities `α·p`
/// and `1 − α`, whose common denominator at a state divides the state's own common
/// denominator `D` times `q`. The exact solver takes at most `2^62` there
/// ([`MAX_DENOMINATOR`]): `q ≤ ⌊2^62 / D⌋` for the largest `D` (at `state`). It also takes
/// each stage cost of the construction (the largest reward minus the action's, or the largest
/// reward where the episode is over), scaled to an integer by the lcm `C` of their
/// denominators, times the state's common denominator, below `2^100`
/// ([`MAX_SCALED_COST_BITS`]): with `K` the largest `|cost · C| · D` over the states and their
/// actions ([`CostRoom`]), `q ≤ ⌊(2^100 − 1) / K⌋` keeps every equation of every probe within
/// it. Both are known before the first probe, so no probe fails on them; the second counts
/// every action, where the solver meets only those of the policies it evaluates.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AlphaRoom {
    /// The state with the largest common denominator of its probabilities.
    pub state: StateId,
    /// That common denominator `D`.
    pub own: BigInt,
    /// `⌊2^62 / D⌋`: the largest denominator of a probe's `α` the probabilities leave.
    pub room: BigInt,
    /// The room the stage costs leave (`None`: every stage cost of the construction is 0).
    pub costs: Option<CostRoom>,
}

/// The room the stage costs of the killed-process construction leave `α`'s denominator
/// ([`AlphaRoom`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CostRoom {
    /// The state with the largest `|cost · C| · D`.
    pub state: StateId,
    /// That product `K`.
    pub scaled: BigInt,
    /// `⌊(2^100 − 1) / K⌋`: the largest denominator of a probe's `α` the stage costs leave.
    pub room: BigInt,
}

impl AlphaRoom {
    /// The room of `model` ([`AlphaRoom`]), over the states where the episode runs for the
    /// probabilities, over every state for the stage costs.
    pub fn of(model: &Model, running: &[StateId]) -> AlphaRoom {
        let p = &model.problem;
        let own_of = |x: StateId| {
            let mut lcm = BigInt::one();
            for a in p.actions(x) {
                for o in p.outcomes(a) {
                    lcm = lcm.lcm(o.probability.denom());
                }
            }
            lcm
        };
        let (mut state, mut own) = (running.first().copied().unwrap_or(0), BigInt::one());
        for &x in running {
            let lcm = own_of(x);
            if lcm > own {
                (state, own) = (x, lcm);
            }
        }
        let room = BigInt::from(MAX_DENOMINATOR) / &own;
        // The construction's stage costs, as `Model::discounted` forms them.
        let top = model
            .reward
            .iter()
            .fold(Rational::zero(), |a, b| if *b > a { b.clone() } else { a });
        let costs_at = |x: StateId| -> Vec<Rational> {
            if model.terminal[x] {
                vec![top.clone()]
            } else {
                p.actions(x).map(|a| &top - &model.reward[a]).collect()
            }
        };
        let mut c = BigInt::one();
        for x in 0..p.states() {
            for cost in costs_at(x) {
                c = c.lcm(cost.denom());
            }
        }
        let c = Rational::from_integer(c);
        let mut costs: Option<(StateId, BigInt)> = None;
        for x in 0..p.states() {
            let largest = costs_at(x)
                .iter()
                .map(|cost| (cost * &c).to_integer().abs())
                .max()
                .unwrap_or_default();
            if largest.is_zero() {
                continue;
            }
            let d = if model.terminal[x] {
                BigInt::one()
            } else {
                own_of(x)
            };
            let k = largest * d;
            if costs.as_ref().is_none_or(|(_, best)| k > *best) {
                costs = Some((x, k));
            }
        }
        let costs = costs.map(|(state, scaled)| CostRoom {
            state,
            room: ((BigInt::one() << MAX_SCALED_COST_BITS) - 1u8) / &scaled,
            scaled,
        });
        AlphaRoom {
            state,
            own,
            room,
            costs,
        }
    }

    /// Whether a probe may take `alpha`: its denominator within both rooms.
    pub fn fits(&self, alpha: &Rational) -> bool {
        alpha.denom() <= &self.room && self.costs.as_ref().is_none_or(|c| alpha.denom() <= &c.room)
    }

    /// The refusal of `alpha` (`gap`: the gap of `(0, 1)` it was the simplest rational of, as
    /// text, with the probes run; `None`: before any work, `alpha = 1/2` the simplest of all),
    /// naming the room it does not fit: the probabilities' first, else the stage costs'.
    pub fn refusal(&self, alpha: &Rational, gap: Option<(String, usize)>) -> ParametricError {
        let over_costs = match &self.costs {
            Some(c) if alpha.denom() <= &self.room => Some(c),
            _ => None,
        };
        let product = match over_costs {
            Some(c) => &c.scaled * alpha.denom(),
            None => &self.own * alpha.denom(),
        };
        let detail = match gap {
            None => format!(
                "every alpha in (0,1) has a denominator >= 2, which gives {product} (refused before any work)"
            ),
            Some((gap, probes)) => format!(
                "after {probes} probes the gap {gap} is left, whose simplest rational {} gives {product} (refused before that probe)",
                crate::stochastic::short_text(alpha),
            ),
        };
        match over_costs {
            Some(c) => ParametricError::AlphaCost {
                state: c.state,
                scaled: c.scaled.clone(),
                detail,
            },
            None => ParametricError::AlphaDenominator {
                state: self.state,
                own: self.own.clone(),
                detail,
            },
        }
    }
}

//! The bounds of the parametric analysis checked before any work (module docs of [`super`],
//! "Effort"): the size of the numbers that enter the polynomials, and, on a deterministic
//! model, a degree that the covering of `(0, 1)` is certain to meet.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed};

use super::{ParametricError, MAX_CHAIN_DEGREE};
use crate::model::StateId;
use crate::objectives::Model;
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
/// any probe: when every reward where the episode runs is negative, a policy that never ends
/// the episode from a state loses without bound as `α → 1`, so the policies optimal on the
/// region next to `1` end it from every state that can end it, along a successor path of at
/// least the state's fewest moves `d` to an end: a value of degree `d − 1`. Returns the state
/// farthest from an end and `d − 1` (`None` when some reward is not negative, or no state
/// can end the episode).
pub fn certain_degree(model: &Model, running: &[StateId]) -> Option<(StateId, usize)> {
    let p = &model.problem;
    let n = p.states();
    if running
        .iter()
        .any(|&x| p.actions(x).any(|a| !model.reward[a].is_negative()))
    {
        return None;
    }
    // Fewest moves to an end: breadth-first search backwards from the ended states.
    let mut before: Vec<Vec<StateId>> = vec![Vec::new(); n];
    for &x in running {
        for a in p.actions(x) {
            for o in p.outcomes(a) {
                before[o.successor].push(x);
            }
        }
    }
    let mut moves: Vec<Option<usize>> = vec![None; n];
    let mut queue = std::collections::VecDeque::new();
    for x in (0..n).filter(|&x| model.terminal[x]) {
        moves[x] = Some(0);
        queue.push_back(x);
    }
    let mut farthest = None;
    while let Some(y) = queue.pop_front() {
        let d = moves[y].expect("queued states have a distance") + 1;
        for &x in &before[y] {
            if moves[x].is_none() {
                moves[x] = Some(d);
                farthest = Some((x, d - 1));
                queue.push_back(x);
            }
        }
    }
    farthest
}

/// Refuses, before any probe, a deterministic model whose [`certain_degree`] exceeds
/// [`MAX_CHAIN_DEGREE`], naming the state, its moves to an end and the bound.
pub fn check_certain_degree(model: &Model, running: &[StateId]) -> Result<(), ParametricError> {
    match certain_degree(model, running) {
        Some((state, degree)) if degree > MAX_CHAIN_DEGREE => Err(ParametricError::CertainDegree {
            state,
            moves: degree + 1,
            degree,
            bound: MAX_CHAIN_DEGREE,
        }),
        _ => Ok(()),
    }
}

//! The counted work of the phase after the probes (module docs of [`super`], step 4): each
//! breakpoint made rational or given a reduced polynomial, and the optimal sets with their
//! achievements on every interval and at every breakpoint. It is charged to the same work
//! bound as the probes, in the same units (on a deterministic model words of arithmetic,
//! [`chains::evaluation`]; on a stochastic one the probes' estimate,
//! [`stochastic_achievement`]), so that the bound governs the whole analysis; a region's share
//! is reserved as soon as its probe finds it ([`region`], [`stochastic_region`]), so the
//! probes stop before the phase after them would pass the bound.

use num_traits::{One, Signed, Zero};

use super::{chains, Region};
use crate::algebra::poly::roots::Root;
use crate::objectives::Model;

/// The counted work of one breakpoint's reduction: the bracket narrowed to `2^-100` and the
/// simplest rational in it tried (about 100 signs at points of about 100 bits), and the
/// square-free part, rational roots and degree test of its polynomial (a few products of
/// polynomials of its degree: `degree²` steps on its coefficients, per word).
pub fn reduction(root: &Root) -> u128 {
    if root.exact {
        return 1;
    }
    let poly = &root.poly.poly;
    let degree = poly.degree().unwrap_or(0);
    let bits = poly
        .coefficients()
        .iter()
        .map(|c| c.numer().bits() + c.denom().bits())
        .max()
        .unwrap_or(0);
    let d = degree as u128 + 1;
    101 * chains::evaluation(degree, bits, 100) + 8 * d * d * (u128::from(bits) / 64 + 1)
}

/// The counted work of one achievement of a set of optimal actions (step 4): on a
/// deterministic model with non-negative stage costs, the graph searches of module `paths`
/// (every state and action a few times, Dijkstra's heap included, on the stage costs' sums:
/// 16 units per state and per action, per word of the largest sum of stage costs); otherwise
/// `solve`, an estimate of one exact solve (the probes' estimate on a stochastic model).
pub fn achievement(model: &Model, graph: bool, solve: u128) -> u128 {
    if !graph {
        return solve;
    }
    let p = &model.problem;
    // The largest sum of stage costs along a path: the number of states times the largest
    // stage cost, over the lcm of the denominators.
    let (mut lcm, mut top) = (num_bigint::BigInt::one(), num_bigint::BigInt::zero());
    for x in (0..p.states()).filter(|&x| !model.terminal[x]) {
        for a in p.actions(x) {
            lcm = num_integer::Integer::lcm(&lcm, p.cost(a).denom());
            top = top.max(p.cost(a).numer().abs());
        }
    }
    let bits = top.bits() + lcm.bits() + u64::from(u64::BITS - (p.states() as u64).leading_zeros());
    16 * (p.states() + p.action_total()) as u128 * (u128::from(bits) / 64 + 1)
}

/// The share of the phase after the probes a region reserves: every point it ends at or
/// touches reduced once, with the optimal sets and achievements at it and on one interval
/// next to it (`per_achievement`, [`achievement`]). A breakpoint shared by two regions is
/// reserved by both, so the reservation is at most twice the work the phase is charged.
pub fn region(region: &Region, per_achievement: u128) -> u128 {
    region
        .lo
        .iter()
        .chain(region.hi.iter())
        .chain(region.touches.iter())
        .map(|r| reduction(r) + 2 * per_achievement)
        .sum()
}

/// The estimated work of the exact solves of one achievement on a deterministic model whose
/// stage costs are not all non-negative (module docs of [`super`], step 4: reachability and
/// exact policy iteration on the model): a policy evaluation and improvement over every state
/// and action for each of up to `states` policies, 16 units per state and per action each.
pub fn exact_solves(model: &Model) -> u128 {
    let p = &model.problem;
    let (n, actions) = (p.states() as u128, p.action_total() as u128);
    16 * n * (n + actions)
}

/// How many achievements of a stochastic model are charged as one probe's estimate
/// ([`super::probe_work`]): an achievement is a few exact solves of the model at `α`-free
/// numbers (reachability, the least truecost by policy iteration, the greatest one when every
/// optimal policy reaches the goal), a probe one exact policy iteration of the discounted model
/// and then the polynomials of the policy's values and advantages, with their roots. Measured
/// in release on FrozenLake-style maps (the guide's table): an achievement took 0.05 to 0.17
/// of a probe's time.
pub const ACHIEVEMENTS_PER_PROBE: u128 = 4;

/// The charge of one achievement on a stochastic model whose probes are estimated at
/// `per_probe` units: `per_probe / ACHIEVEMENTS_PER_PROBE`, at least 1.
pub fn stochastic_achievement(per_probe: u128) -> u128 {
    (per_probe / ACHIEVEMENTS_PER_PROBE).max(1)
}

/// The charge of one breakpoint's reduction on a stochastic model: one probe's estimate (its
/// polynomial has the degree and coefficients of a probe's advantages; measured in release,
/// a reduction took 0.3 to 0.86 of a probe's time).
pub fn stochastic_reduction(per_probe: u128) -> u128 {
    per_probe
}

/// The share of the phase after the probes a region of a stochastic model reserves: every
/// point it ends at or touches reduced once ([`stochastic_reduction`]), with the optimal sets
/// and achievements at it and on one interval next to it ([`stochastic_achievement`]). A
/// breakpoint shared by two regions is reserved by both.
pub fn stochastic_region(region: &Region, per_probe: u128) -> u128 {
    let points = region.lo.iter().count() + region.hi.iter().count() + region.touches.len();
    (stochastic_reduction(per_probe) + 2 * stochastic_achievement(per_probe)) * points as u128
}

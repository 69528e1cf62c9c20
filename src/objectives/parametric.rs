//! The discount question on stochastic problems: the exact breakpoints
//! `α ∈ (0, 1)` where the set of discount-optimal policies changes, and for every interval
//! between them (and at every breakpoint) the success probability and truecost of its optimal
//! policies — the parametric policy analysis of PRISM/Storm's parametric engine, done exactly.
//!
//! **Design.** The discounted objective is the one of [`super::Model`]: maximise
//! `V_α(x) = r(x, u) + α Σ p(y | x, u) V_α(y)`, `V = 0` where the episode is over.
//!
//! 1. *A policy's value is a rational function of `α`.* For a stationary policy `π` with reward
//!    vector `r` and transition matrix `P` on the running states, `V = Σ_k α^k P^k r`. The
//!    Krylov vectors `c_k = P^k r` (`m` running states) satisfy a shortest linear recurrence
//!    `D(α) = Σ_{j≤L} d_j α^j`, `d_0 = 1`, found modulo primes (Berlekamp–Massey on a
//!    projection of the first `2m` vectors, Chinese remaindering; `annihilator`) and then
//!    **verified** exactly: `Σ_j d_j c_{L−j} = 0` (so `q(P) r = 0` for `q(t) = t^L D(1/t)`,
//!    hence `Σ_j d_j c_{k−j} = 0` for every `k ≥ L`), computed as the last step of the
//!    numerator recurrence. Then `N = D·V` is a polynomial vector of degree `< L`, read off
//!    the first `L` terms. A failed verification asks for more primes. `D` has no root in
//!    `(0, 1)` (its roots are `1/λ` for eigenvalues `λ` of a substochastic matrix, `|λ| ≤ 1`)
//!    and `D(0) = 1`, so `D > 0` on `(0, 1)`.
//!
//!    **1′.** *Deterministic models* (every action where the episode runs has one outcome: Taxi,
//!    CliffWalking, FrozenLake unslippery, single-outcome files). A stationary policy follows
//!    one successor chain from each state: a path to where the episode ends, or a lasso. Its
//!    value is written down along the chain — on a cycle `c_0 … c_{k−1}`,
//!    `V = Σ_{j<k} α^j r(c_j) / (1 − α^k)`; elsewhere `V_x = r_x + α V_{f(x)}` over the
//!    successor's denominator (`1` at the end of a path) — so its degree is the chain's length,
//!    not the number of states, and the states of one policy have different denominators
//!    (each positive on `(0, 1)`). The optimal policy at a probe is found by exact policy
//!    iteration evaluated along the same chains. [`MAX_RUNNING_STATES`] does not apply;
//!    [`MAX_CHAIN_DEGREE`] bounds the chains met, checked while running. The probes keep
//!    what they built: values, advantage polynomials with all their roots, and the roots
//!    themselves, shared by equal chains and reused by the next probe (module `chains`:
//!    neighbouring regions' policies differ at a few states).
//! 2. *Optimality region of a policy.* The advantage of action `a` at `x` over `π`,
//!    `Q_a − V_x`, has the sign of the polynomial `A = r_a D + α Σ_y p_a(y) N_y − N_x` on
//!    `(0, 1)` (with several denominators: `Q_a − V_x` times their product). `π` is optimal
//!    exactly where every `A ≤ 0`; the optimal actions there are the policy's and those with
//!    `A = 0`. The roots of every non-zero `A` in `(0, 1)` are isolated
//!    exactly (Descartes' rule with bisection, [`crate::algebra::poly::roots`]) and the sign of `A` on each gap
//!    between them is evaluated at a rational point, so the maximal interval `[β_L, β_R]` around a point
//!    where `π` is optimal is exact, and so are the points inside where some `A` touches 0
//!    without changing sign (a tie at a single `α`: the optimal set changes there too).
//! 3. *Covering `(0, 1)`.* A probe at a rational `t` (the simplest rational of a small
//!    interval, so the exact solves stay small) computes the optimal policy at `t` by exact
//!    policy iteration ([`super::Model::solve`]'s killed-process construction) and its region; a
//!    probe at a root of some `A` is retried at another point. Gaps not yet covered are probed
//!    next, first just right of their left end, so consecutive regions usually meet exactly at
//!    a breakpoint. Each probe covers a maximal region of a new policy, so the loop ends.
//! 4. *The answer.* The breakpoints are the region ends inside `(0, 1)` and the touching
//!    points, sorted and deduplicated as algebraic numbers. On each open interval between
//!    breakpoints the optimal set is the region's policy plus the actions with `A ≡ 0`; at a
//!    breakpoint it is the policy plus the actions with `A(β) = 0` (decided exactly). For each,
//!    the success probability `{min, max}` over the optimal policies
//!    ([`super::max_reach`]/[`super::min_reach`] restricted to the optimal actions) and their
//!    truecost `{min, max}` (least: exact SSP optimum restricted to them; greatest: `+∞` if one
//!    of them fails with positive probability, else exact policy iteration maximising the cost,
//!    all restricted policies being proper) at the initial distribution. On a deterministic
//!    model with non-negative stage costs the same four numbers come from searches of the
//!    graph of the optimal actions (module `paths`).
//!
//! Effort is bounded: before any work, the numbers (stage costs and rewards of magnitude at
//! most `2^100`, rewards of at most [`bounds::MAX_SCALED_BITS`] bits scaled to integers:
//! [`bounds::check_numbers`]); [`MAX_RUNNING_STATES`] bounds the degree of every rational
//! function of a stochastic model, [`probe_work`] estimates each of its probes
//! ([`MAX_PROBE_WORK`] in all, with the phase after the probes charged in the same units) and
//! [`bounds::AlphaRoom`] the room its probabilities and stage costs leave the probes' `α`
//! within the exact solver's limits; a deterministic model has at most
//! [`MAX_DETERMINISTIC_RUNNING_STATES`], chains of degree at most [`MAX_CHAIN_DEGREE`] (refused
//! before the first probe when the chain structure forces more, [`bounds::certain_degree`],
//! else checked while running) and probes whose counted work stays within
//! [`MAX_DETERMINISTIC_WORK`]; [`MAX_REGIONS`] bounds the number of probes. Each refusal names
//! the quantity, its value and its bound.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

use super::{derive, max_reach, min_reach, Bounds, Model, ObjectiveError};
use crate::algebra::annihilator;
use crate::algebra::poly::roots::{
    between, homogeneous, integer_sign, no_root_between, roots_in_unit_interval, roots_in_window,
    simplest_between, Root,
};
use crate::algebra::poly::Poly;
use crate::model::StateId;
use crate::stochastic::policy_iteration::{evaluate, optimum};
use crate::stochastic::StochasticAction;
use crate::value::{Extended, Rational};

pub mod bounds;
pub mod certificate;
mod chains;
mod closing;
pub mod degree;
mod paths;

/// The most states where the episode runs: a policy's values are rational functions of `α`
/// of degree at most this, and so are the advantages whose roots are isolated.
pub const MAX_RUNNING_STATES: usize = 256;

/// The deterministic path's degree bound: the longest successor chain (steps to where the
/// episode ends, or to and around a cycle) of a policy met while covering `(0, 1)`; checked
/// while running.
pub const MAX_CHAIN_DEGREE: usize = 200;

/// The most probes (regions of optimal policies) the covering of `(0, 1)` may take.
pub const MAX_REGIONS: usize = 4_000;

/// The most work one stochastic analysis may do, in units of [`probe_work`] (`n⁵·b⁴` per
/// probe): the probes, and the phase after them (each breakpoint's reduction charged as a
/// probe, each achievement as a quarter of one: module `closing`, reserved region by region);
/// checked before every probe. Measured in release (processor time, 7 Dec 2026, 2 cores
/// shared with other work): slippery FrozenLake-style maps of 53 to 195 running states are
/// charged 10¹³ to 2.7·10¹⁴ units a second, the larger the faster; a 16×16 map (195 running
/// states, 47 probes) is charged 2.0·10¹⁶ units and takes 75 s. This bound (≈ 3.6·10¹⁶) keeps
/// such an analysis to about two to three minutes of processor time.
pub const MAX_PROBE_WORK: u128 = 1 << 55;

/// The most work one probe may take before any work starts: a problem that cannot afford 64
/// probes within [`MAX_PROBE_WORK`] (`2^49`) is refused at once.
pub const MAX_SINGLE_PROBE_WORK: u128 = MAX_PROBE_WORK / 64;

/// The most states where the episode runs of a deterministic model: more are refused before
/// any work.
pub const MAX_DETERMINISTIC_RUNNING_STATES: usize = 2_500;

/// The most work the probes of one deterministic analysis may do together, counted in words
/// of arithmetic (the pruned search, module `chains`: polynomials built, roots isolated, signs
/// and halvings of root brackets, hash lookups; the full search: `deterministic_probe_work`);
/// with the phase after the probes (module `closing`, reserved region by region); checked
/// before every probe with the last probe's work as the estimate of the next, inside a probe
/// with memory, and after it. Measured in release (processor time on 2 shared cores, 7 Dec
/// 2026), whole analyses are charged 1.5·10⁸ to 7.3·10⁸ units a second: grids of `export
/// --grid NxN --pattern random --costs 1-9 --seed 0` take 1.06·10⁹ units (20×20, 385 probes,
/// 3.3 s) and 4.8·10¹⁰ (50×50, 2534 probes, 82 s, its work done and reserved reaching three
/// quarters of the bound); twelve chains of 200 states with costs `k/13` (939 breakpoints)
/// take 4.9·10¹⁰ units and 67 s. The bound (`2^36` ≈ 6.9·10¹⁰) keeps such analyses to about
/// a minute of processor time.
pub const MAX_DETERMINISTIC_WORK: u128 = 1 << 36;

/// The estimated work of one probe of a stochastic analysis: `n⁵·b⁴`, with `n` the running
/// states (the degree of the rational functions and the size of the exact solve) and `b` the
/// bits of the numbers that enter them: the lcm of every probability denominator, the lcm of
/// every stage-cost denominator and the largest stage-cost numerator (exact policy iteration
/// scales a policy's equations by these lcms, and root isolation grows with a high power of
/// the coefficients' size). The exponents fit the measurements of [`MAX_PROBE_WORK`].
///
/// ```
/// use truecost::objectives::parametric::probe_work;
/// assert_eq!(probe_work(10, 4), 10u128.pow(5) * 4u128.pow(4));
/// assert_eq!(probe_work(0, 0), 1);
/// ```
pub fn probe_work(running: usize, bits: u64) -> u128 {
    let (n, b) = (running.max(1) as u128, bits.max(1) as u128);
    n.pow(5).saturating_mul(b.pow(4))
}

/// The bits `b` of [`probe_work`] for a model: over the actions of the running states.
fn number_bits(model: &Model, running: &[StateId]) -> u64 {
    use num_integer::Integer;
    let p = &model.problem;
    let (mut probabilities, mut rewards) = (BigInt::one(), BigInt::one());
    let mut numerator = 0;
    for &x in running {
        for a in p.actions(x) {
            rewards = rewards.lcm(model.reward[a].denom());
            numerator = numerator.max(model.reward[a].numer().bits());
            for o in p.outcomes(a) {
                probabilities = probabilities.lcm(o.probability.denom());
            }
        }
    }
    probabilities.bits() + rewards.bits() + numerator
}

/// Wall-clock phases of one analysis on standard error when `TRUECOST_PROFILE` is set (for
/// profiling; the result does not depend on it).
struct Timer {
    start: Option<std::time::Instant>,
}

impl Timer {
    fn new() -> Timer {
        Timer {
            start: std::env::var_os("TRUECOST_PROFILE").map(|_| std::time::Instant::now()),
        }
    }

    fn mark(&self, phase: &str) {
        if let Some(start) = self.start {
            eprintln!(
                "profile: {phase} done at {:.3} s",
                start.elapsed().as_secs_f64()
            );
        }
    }
}

/// What [`discount_breakpoints_with`] is doing, for a progress display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeProgress {
    /// Probes run (exact policy iterations at a rational `α`).
    pub probes: usize,
    /// Regions of `(0, 1)` with a known optimal policy set.
    pub regions: usize,
    /// Gaps of `(0, 1)` still to cover.
    pub gaps: usize,
    /// Work done: in units of [`probe_work`] for a stochastic model, of
    /// `deterministic_probe_work` for a deterministic one.
    pub work: u128,
    /// The bound on `work`: [`MAX_PROBE_WORK`] or [`MAX_DETERMINISTIC_WORK`].
    pub bound: u128,
}

/// Why the parametric analysis refused or failed. One line each.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParametricError {
    /// Too many running states: the degree bound.
    #[error("the stochastic problem has {states} states where the episode runs; the exact parametric analysis of stochastic problems handles at most {bound} (its rational functions of alpha have degree up to that number)")]
    Degree {
        /// Running states.
        states: usize,
        /// [`MAX_RUNNING_STATES`].
        bound: usize,
    },
    /// A deterministic policy's successor chain longer than [`MAX_CHAIN_DEGREE`].
    #[error("a policy's successor chain gives its discounted value a degree-{degree} rational function of alpha; the exact parametric analysis of deterministic problems handles degree at most {bound}")]
    ChainDegree {
        /// The degree met.
        degree: usize,
        /// [`MAX_CHAIN_DEGREE`].
        bound: usize,
    },
    /// A deterministic model whose policies optimal next to `α = 1` or `α = 0` must have a
    /// value of degree over the bound ([`bounds::certain_degree`]): refused before any probe.
    #[error("state {state} {reason}: degree >= {degree}; the exact analysis of deterministic problems takes at most {bound} (refused before any probe)")]
    CertainDegree {
        /// The state.
        state: usize,
        /// The degree its value must have (at least).
        degree: usize,
        /// Why ([`degree::Reason`]).
        reason: degree::Reason,
        /// [`MAX_CHAIN_DEGREE`].
        bound: usize,
    },
    /// A stochastic model whose probabilities leave a probe's `α` too little room for its
    /// denominator ([`bounds::AlphaRoom`]).
    #[error("state {state}: the probabilities' common denominator {own} times alpha's must be at most 2^62 (the exact solver's limit): {detail}")]
    AlphaDenominator {
        /// The state with the largest common denominator of its probabilities.
        state: usize,
        /// That common denominator.
        own: BigInt,
        /// The denominators, the product and where (before any work, or the gap).
        detail: String,
    },
    /// A stochastic model whose stage costs, scaled and times the probabilities' common
    /// denominator, leave a probe's `α` too little room for its denominator
    /// ([`bounds::CostRoom`]).
    #[error("state {state}: discounted stage cost, scaled, times the probabilities' denominator: {scaled}; times alpha's must stay below 2^100 (the exact solver's limit): {detail}")]
    AlphaCost {
        /// The state with the largest product.
        state: usize,
        /// The product `K` ([`bounds::CostRoom::scaled`]).
        scaled: BigInt,
        /// The product with `α`'s denominator and where (before any work, or the gap).
        detail: String,
    },
    /// A stage cost or reward over `2^100` in magnitude ([`bounds::MAX_MAGNITUDE_BITS`]).
    #[error("state {state}, action {action}: the {quantity} {value} exceeds 2^{bound} in magnitude; the exact parametric analysis takes stage costs and rewards up to 2^{bound} (refused before any work)")]
    Magnitude {
        /// The state.
        state: usize,
        /// The action's index at the state.
        action: usize,
        /// `stage cost` or `reward`.
        quantity: &'static str,
        /// The number (shortened).
        value: String,
        /// [`bounds::MAX_MAGNITUDE_BITS`].
        bound: u64,
    },
    /// Rewards too large scaled to integers ([`bounds::MAX_SCALED_BITS`]).
    #[error("state {state}, action {action}: the reward {value}: {what} {bits} bits; the exact parametric analysis takes at most {bound} (refused before any work: isolating roots near 1 slows with the square of the bits)")]
    ScaledBits {
        /// The state.
        state: usize,
        /// The action's index at the state.
        action: usize,
        /// The reward (shortened).
        value: String,
        /// What took the bits.
        what: &'static str,
        /// The bits.
        bits: u64,
        /// [`bounds::MAX_SCALED_BITS`].
        bound: u64,
    },
    /// One probe alone would exceed [`MAX_SINGLE_PROBE_WORK`].
    #[error("one exact probe of this problem is estimated at {work} units ({states} running states, numbers of {bits} bits: n^5 b^4); the exact parametric analysis takes at most {bound} per probe (about 5 to 20 s)")]
    ProbeWork {
        /// Running states.
        states: usize,
        /// Bits of the numbers.
        bits: u64,
        /// Estimated units.
        work: u128,
        /// [`MAX_SINGLE_PROBE_WORK`].
        bound: u128,
    },
    /// The probes together would exceed [`MAX_PROBE_WORK`].
    #[error("the exact parametric analysis stopped after {probes} probes ({regions} regions of (0,1) covered, {gaps} gaps left): its work, {work} units done and {reserved} reserved for the breakpoints' optimal sets, would pass the bound of {bound} units (one to three minutes of processor time)")]
    Work {
        /// Probes run.
        probes: usize,
        /// The work counted so far.
        work: u128,
        /// The work reserved for the phase after the probes (module `closing`).
        reserved: u128,
        /// Regions found.
        regions: usize,
        /// Gaps left.
        gaps: usize,
        /// [`MAX_PROBE_WORK`] or [`MAX_DETERMINISTIC_WORK`].
        bound: u128,
    },
    /// A deterministic model with more than [`MAX_DETERMINISTIC_RUNNING_STATES`].
    #[error("{states} states where the episode runs: the exact parametric analysis of a deterministic problem takes at most {bound}")]
    DeterministicStates {
        /// Running states.
        states: usize,
        /// [`MAX_DETERMINISTIC_RUNNING_STATES`].
        bound: usize,
    },
    /// Too many regions: the piece bound.
    #[error("the discount-optimal policy changes more than {0} times on (0,1): beyond the bound of the exact parametric analysis")]
    Pieces(usize),
    /// No verified annihilating polynomial (never expected; reported rather than guessed).
    #[error("the exact parametric analysis found no verified denominator for a policy's values after {0} projections")]
    Annihilator(usize),
    /// An exact solve refused (sizes, denominators).
    #[error("{0}")]
    Objective(#[from] ObjectiveError),
    /// An internal consistency check failed (a truecost bug, reported rather than hidden).
    #[error("internal check failed: {0}")]
    Internal(String),
}

/// What the optimal policies of a piece achieve from the initial distribution.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Achievement {
    /// Success probability over the optimal policies.
    pub success: Bounds,
    /// Least expected truecost over the optimal policies (`+∞` if none reaches the goal with
    /// probability 1).
    pub truecost_min: Extended,
    /// Greatest expected truecost over the optimal policies (`+∞` if one fails with positive
    /// probability).
    pub truecost_max: Extended,
}

/// An open interval between consecutive breakpoints, with its optimal policies.
#[derive(Clone, Debug)]
pub struct Interval {
    /// Lower end: a breakpoint, or `None` for 0.
    pub lo: Option<Root>,
    /// Upper end: a breakpoint, or `None` for 1.
    pub hi: Option<Root>,
    /// A rational strictly inside.
    pub sample: Rational,
    /// An optimal policy on the whole interval: per state its action index in `U(x)`
    /// (Gymnasium's action number for environments), `None` where the episode is over.
    pub policy: Vec<Option<usize>>,
    /// Per state, the optimal actions on the interval (indices in `U(x)`; empty where the
    /// episode is over).
    pub optimal: Vec<Vec<usize>>,
    /// Success and truecost of the optimal policies.
    pub achievement: Achievement,
}

/// A breakpoint: an `α` where the set of optimal actions changes.
#[derive(Clone, Debug)]
pub struct Breakpoint {
    /// The exact point (algebraic number with a rational bracket).
    pub at: Root,
    /// The optimal sets just left and just right are the same: the change is a tie at this
    /// point only.
    pub touch: bool,
    /// The states whose optimal actions at the point differ from those of a neighbouring
    /// interval, with the optimal actions at the point (indices in `U(x)`): the ties.
    pub ties: Vec<(StateId, Vec<usize>)>,
    /// Success and truecost of the policies optimal at the point.
    pub achievement: Achievement,
}

/// The answer of [`discount_breakpoints`].
#[derive(Clone, Debug)]
pub struct DiscountAnalysis {
    /// The breakpoints in increasing order.
    pub breakpoints: Vec<Breakpoint>,
    /// The intervals, in increasing order (one more than the breakpoints).
    pub intervals: Vec<Interval>,
    /// Probes made (exact policy iterations at rational `α`).
    pub probes: usize,
    /// The largest degree `L` of a policy-value denominator met.
    pub degree: usize,
    /// States where the episode runs.
    pub running_states: usize,
    /// Whether the deterministic path (successor chains, module docs step 1′) was taken.
    pub deterministic: bool,
    /// The work of the probes: units of [`probe_work`] (stochastic, estimated) or of
    /// `deterministic_probe_work` (deterministic, measured).
    pub work: u128,
}

/// A policy's discounted values as rational functions `N_x / D_x` (module docs, step 1; the
/// deterministic path of step 1′ gives each state the denominator of its own successor chain).
struct PolicyValues {
    /// The distinct denominators, integer coefficients, constant first; each positive on
    /// `(0, 1)`.
    dens: Vec<Vec<BigInt>>,
    /// Per state: the index of its denominator in `dens` (unused where the episode is over).
    den_of: Vec<usize>,
    /// Per state (empty where the episode is over).
    n: Vec<Vec<BigInt>>,
    degree: usize,
}

/// A policy's values (module docs, step 1): the denominator `D` from `annihilator::Search`
/// (modular Krylov sequences, Berlekamp–Massey and Chinese remaindering), **verified exactly**
/// through the numerator recurrence — `n_L = Σ_{j≤L} d_j e_{L−j}` is zero exactly when `D`
/// annihilates the Krylov sequence — so the result is exact whatever the primes and
/// projections chose; it is the minimal recurrence of the sequence.
fn policy_values(
    model: &Model,
    running: &[StateId],
    index: &[Option<usize>],
    policy: &[Option<usize>],
) -> Result<PolicyValues, ParametricError> {
    use num_integer::Integer;
    let p = &model.problem;
    let m = running.len();
    let action = |i: usize| policy[running[i]].expect("a policy acts where the episode runs");
    // Integer scaling: e_k = R·Q^k·c_k with R, Q the lcm of the reward and probability
    // denominators, so that e_{k+1} = (Q·P) e_k in integers.
    let (mut big_r, mut big_q) = (BigInt::one(), BigInt::one());
    for i in 0..m {
        let a = action(i);
        big_r = big_r.lcm(model.reward[a].denom());
        for o in p.outcomes(a) {
            big_q = big_q.lcm(o.probability.denom());
        }
    }
    let int = |r: Rational| -> BigInt {
        debug_assert!(r.is_integer());
        r.to_integer()
    };
    let r_scale = Rational::from_integer(big_r.clone());
    let q_scale = Rational::from_integer(big_q.clone());
    let rows: Vec<Vec<(usize, BigInt)>> = (0..m)
        .map(|i| {
            p.outcomes(action(i))
                .iter()
                .filter_map(|o| index[o.successor].map(|j| (j, int(&o.probability * &q_scale))))
                .collect()
        })
        .collect();
    let start: Vec<BigInt> = (0..m)
        .map(|i| int(&model.reward[action(i)] * &r_scale))
        .collect();
    let mut search = annihilator::search(&rows, &start);
    // Each failed verification asks for a larger degree; a few failures already mean every
    // prime met so far was unlucky (never expected).
    const ATTEMPTS: usize = 4;
    for _ in 0..ATTEMPTS {
        // The recurrence of e in integers, d_0 = 1.
        let Some(d) = search.candidate() else {
            break;
        };
        let l = d.len() - 1;
        // The numerator coefficients `n_k = Σ_{j≤k} d_j e_{k−j}` (per state) by the recurrence
        // `n_k = d_k e_0 + (Q·P) n_{k−1}` (since `e_{k+1} = (Q·P) e_k`): one sparse product
        // per degree instead of a convolution per state; `n_L` is the verification.
        let mut coefficients: Vec<Vec<BigInt>> = vec![Vec::with_capacity(l); m];
        let mut current: Vec<BigInt> = vec![BigInt::zero(); m];
        for (k, dk) in d.iter().enumerate() {
            let next: Vec<BigInt> = rows
                .iter()
                .zip(&start)
                .map(|(row, e0)| {
                    row.iter()
                        .fold(dk * e0, |acc, (j, w)| acc + w * &current[*j])
                })
                .collect();
            if k == 0 {
                debug_assert!(next.iter().zip(&start).all(|(a, e)| *a == dk * e));
            }
            if k < l {
                for (c, v) in coefficients.iter_mut().zip(&next) {
                    c.push(v.clone());
                }
            }
            current = next;
        }
        if !current.iter().all(Zero::is_zero) {
            continue;
        }
        // Back to α: coefficient k of D_e(α/Q), of N_e(α/Q)/R, times R·Q^L.
        let powers: Vec<BigInt> = (0..=l)
            .scan(BigInt::one(), |acc, _| {
                let v = acc.clone();
                *acc *= &big_q;
                Some(v)
            })
            .collect();
        let to_poly = |c: Vec<BigInt>| -> Vec<BigInt> {
            c.into_iter()
                .enumerate()
                .map(|(k, x)| x * &powers[l - k])
                .collect()
        };
        let mut n = vec![Vec::new(); p.states()];
        for (i, &x) in running.iter().enumerate() {
            n[x] = to_poly(std::mem::take(&mut coefficients[i]));
        }
        let d = to_poly(d.into_iter().map(|x| x * &big_r).collect());
        return Ok(PolicyValues {
            dens: vec![d],
            den_of: vec![0; p.states()],
            n,
            degree: l,
        });
    }
    Err(ParametricError::Annihilator(annihilator::PROJECTIONS))
}

/// A policy's discounted values as rational functions of `α`, `V_x = N_x / D_x` (module
/// docs, steps 1 and 1′): read-only, for the certificate of an interval's witness policy.
#[derive(Clone, Debug)]
pub struct WitnessValues {
    /// The distinct denominators, integer coefficients, constant first.
    pub denominators: Vec<Vec<BigInt>>,
    /// Per state, the index of its denominator (unused where the episode is over).
    pub denominator_of: Vec<usize>,
    /// Per state, the numerator (empty where the episode is over).
    pub numerators: Vec<Vec<BigInt>>,
}

/// The values of `policy` (per state its action index in `U(x)`, as [`Interval::policy`];
/// `None` where the episode is over) as rational functions of `α`, computed as the analysis
/// computes them.
pub fn witness_values(
    model: &Model,
    policy: &[Option<usize>],
) -> Result<WitnessValues, ParametricError> {
    let p = &model.problem;
    let running: Vec<StateId> = (0..p.states()).filter(|&x| !model.terminal[x]).collect();
    let mut index = vec![None; p.states()];
    for (i, &x) in running.iter().enumerate() {
        index[x] = Some(i);
    }
    let global: Vec<Option<usize>> = (0..p.states())
        .map(|x| policy[x].map(|i| p.actions(x).start + i))
        .collect();
    let v = if is_deterministic(model) {
        chain_values(model, &running, &global, MAX_CHAIN_DEGREE)?
    } else {
        policy_values(model, &running, &index, &global)?
    };
    Ok(WitnessValues {
        denominators: v.dens,
        denominator_of: v.den_of,
        numerators: v.n,
    })
}

/// The product of two integer polynomials (constant first).
fn poly_mul(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// `acc += w · α^shift · f`.
fn poly_add_scaled(acc: &mut Vec<BigInt>, f: &[BigInt], w: &BigInt, shift: usize) {
    if acc.len() < f.len() + shift {
        acc.resize(f.len() + shift, BigInt::zero());
    }
    for (k, fk) in f.iter().enumerate() {
        acc[k + shift] += w * fk;
    }
}

/// The work of one probe of a deterministic analysis (module docs, step 1′), measured on the
/// probe: the words of its advantage polynomials that are negative at the probe (the ones
/// whose roots the region's ends are searched among), `Σ (degree + 1) · ⌈bits / 64⌉`. It is
/// counted, not timed, so an analysis stops at the same probe on every machine.
fn deterministic_probe_work(found: &[Found]) -> u128 {
    found
        .iter()
        .map(|f| match f {
            Found::Negative(_, c, _) => {
                let bits = c.iter().map(|x| x.bits()).max().unwrap_or(0);
                c.len() as u128 * u128::from(bits.div_ceil(64).max(1))
            }
            _ => 0,
        })
        .sum()
}

/// Whether every action where the episode runs has a single outcome (probability 1): the
/// model is deterministic and takes the successor-chain path (module docs, step 1′).
pub fn is_deterministic(model: &Model) -> bool {
    let p = &model.problem;
    (0..p.states())
        .filter(|&x| !model.terminal[x])
        .all(|x| p.actions(x).all(|a| p.outcomes(a).len() == 1))
}

/// The single successor of a deterministic action.
fn successor(model: &Model, a: usize) -> StateId {
    model.problem.outcomes(a)[0].successor
}

/// The running states of a deterministic policy in an order where every state comes after its
/// successor, unless the successor is on the same cycle: per state `Some(cycle)` for the
/// states on a cycle (the cycle in successor order, starting at the state), `None` for the
/// others (module docs, step 1′). Each state is visited once: `O(|X|)`.
fn chains(
    model: &Model,
    running: &[StateId],
    policy: &[Option<usize>],
) -> Vec<(StateId, Option<Vec<StateId>>)> {
    let n = model.problem.states();
    let next = |x: StateId| {
        successor(
            model,
            policy[x].expect("a policy acts where the episode runs"),
        )
    };
    // 0 unvisited, 1 on the current walk, 2 done.
    let mut mark = vec![0u8; n];
    let mut order = Vec::with_capacity(running.len());
    for &x in running {
        let mut walk = Vec::new();
        let mut y = x;
        while !model.terminal[y] && mark[y] == 0 {
            mark[y] = 1;
            walk.push(y);
            y = next(y);
        }
        if !model.terminal[y] && mark[y] == 1 {
            let start = walk.iter().position(|&z| z == y).expect("on the walk");
            let cycle: Vec<StateId> = walk[start..].to_vec();
            for (i, &z) in cycle.iter().enumerate() {
                let mut rotated = cycle[i..].to_vec();
                rotated.extend_from_slice(&cycle[..i]);
                order.push((z, Some(rotated)));
                mark[z] = 2;
            }
            walk.truncate(start);
        }
        for &z in walk.iter().rev() {
            mark[z] = 2;
            order.push((z, None));
        }
    }
    order
}

/// A deterministic policy's discounted values as rational functions, by following each
/// state's successor chain (module docs, step 1′): a state on a cycle `c_0 … c_{k−1}` has
/// `V = Σ_{j<k} α^j r(c_j) / (1 − α^k)`; any other state `V_x = r_x + α V_{f(x)}` with its
/// successor's denominator (`1` when the chain ends where the episode is over). Refuses when
/// a degree exceeds `bound` ([`MAX_CHAIN_DEGREE`] in the analysis).
fn chain_values(
    model: &Model,
    running: &[StateId],
    policy: &[Option<usize>],
    bound: usize,
) -> Result<PolicyValues, ParametricError> {
    use num_integer::Integer;
    let n = model.problem.states();
    let action = |x: StateId| policy[x].expect("a policy acts where the episode runs");
    let mut big_r = BigInt::one();
    for &x in running {
        big_r = big_r.lcm(model.reward[action(x)].denom());
    }
    let r_scale = Rational::from_integer(big_r.clone());
    let reward = |x: StateId| -> BigInt { (&model.reward[action(x)] * &r_scale).to_integer() };
    // `unscaled[k]`: the denominator without the factor R (1, or 1 − α^k).
    let mut unscaled: Vec<Vec<BigInt>> = vec![vec![BigInt::one()]];
    let mut den_of = vec![0; n];
    let mut num: Vec<Vec<BigInt>> = vec![Vec::new(); n];
    let mut degree = 0;
    let too_long =
        |degree: usize| (degree > bound).then_some(ParametricError::ChainDegree { degree, bound });
    for (x, cycle) in chains(model, running, policy) {
        match cycle {
            Some(cycle) => {
                let k = cycle.len();
                if let Some(e) = too_long(k) {
                    return Err(e);
                }
                let mut d = vec![BigInt::zero(); k + 1];
                d[0] = BigInt::one();
                d[k] = -BigInt::one();
                let index = match unscaled.iter().position(|u| *u == d) {
                    Some(i) => i,
                    None => {
                        unscaled.push(d);
                        unscaled.len() - 1
                    }
                };
                den_of[x] = index;
                num[x] = cycle.iter().map(|&c| reward(c)).collect();
                degree = degree.max(k);
            }
            None => {
                let y = successor(model, action(x));
                let k = if model.terminal[y] { 0 } else { den_of[y] };
                let mut nx: Vec<BigInt> = Vec::new();
                poly_add_scaled(&mut nx, &unscaled[k], &reward(x), 0);
                if !model.terminal[y] {
                    poly_add_scaled(&mut nx, &num[y], &BigInt::one(), 1);
                }
                let deg = nx.len().saturating_sub(1).max(unscaled[k].len() - 1);
                if let Some(e) = too_long(deg) {
                    return Err(e);
                }
                degree = degree.max(deg);
                den_of[x] = k;
                num[x] = nx;
            }
        }
    }
    let dens = unscaled
        .into_iter()
        .map(|u| u.into_iter().map(|c| c * &big_r).collect())
        .collect();
    Ok(PolicyValues {
        dens,
        den_of,
        n: num,
        degree,
    })
}

/// The running states breadth-first backwards from where the episode is over, the rest after:
/// the improvement order of [`deterministic_optimum`] and [`float_optimum`].
fn sweep_order(model: &Model, running: &[StateId]) -> Vec<StateId> {
    let p = &model.problem;
    let n = p.states();
    let mut predecessors: Vec<Vec<StateId>> = vec![Vec::new(); n];
    for &x in running {
        for a in p.actions(x) {
            predecessors[successor(model, a)].push(x);
        }
    }
    let mut seen: Vec<bool> = model.terminal.clone();
    let mut order: Vec<StateId> = Vec::with_capacity(running.len());
    let mut frontier: Vec<StateId> = (0..n).filter(|&x| model.terminal[x]).collect();
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for y in frontier {
            for &x in &predecessors[y] {
                if !seen[x] {
                    seen[x] = true;
                    order.push(x);
                    next.push(x);
                }
            }
        }
        frontier = next;
    }
    order.extend(running.iter().copied().filter(|&x| !seen[x]));
    order
}

/// An optimal policy of a deterministic model at the rational discount `t`: exact policy
/// iteration, each policy evaluated along its successor chains, with in-place (Gauss–Seidel)
/// improvement in order of distance to where the episode ends (so that improvements travel
/// back along shortest chains in one sweep). An action is replaced only by a strictly better
/// one against the current values `w`; `w` only grows, and `w ≤ T_π′ w` gives `v_π′ ≥ w ≥ v_π`
/// with a strict gain where an action changed, so no policy repeats and the loop ends. A
/// sweep without change leaves `w = v_π` with no improving action: `π` is optimal (Bellman).
fn deterministic_optimum(model: &Model, running: &[StateId], t: &Rational) -> Vec<Option<usize>> {
    let p = &model.problem;
    let n = p.states();
    let order = sweep_order(model, running);
    let mut policy: Vec<Option<usize>> = (0..n)
        .map(|x| (!model.terminal[x]).then(|| p.actions(x).start))
        .collect();
    loop {
        // Evaluation at t along the chains.
        let mut w = vec![Rational::zero(); n];
        for (x, cycle) in chains(model, running, &policy) {
            let a = policy[x].expect("acts");
            w[x] = match cycle {
                Some(cycle) => {
                    let mut sum = Rational::zero();
                    let mut power = Rational::one();
                    for &c in &cycle {
                        sum += &power * &model.reward[policy[c].expect("acts")];
                        power *= t;
                    }
                    sum / (Rational::one() - power)
                }
                None => &model.reward[a] + t * &w[successor(model, a)],
            };
        }
        let mut changed = false;
        for &x in &order {
            let q = |w: &[Rational], a: usize| &model.reward[a] + t * &w[successor(model, a)];
            let mut best = q(&w, policy[x].expect("acts"));
            for a in p.actions(x) {
                let qa = q(&w, a);
                if qa > best {
                    best = qa;
                    policy[x] = Some(a);
                    changed = true;
                }
            }
            w[x] = best;
        }
        if !changed {
            return policy;
        }
    }
}

/// A non-zero advantage polynomial (integer form) with the roots met in `(0, 1)`: every root
/// in its probe's region (module docs, step 2), and possibly others.
struct Advantage {
    /// Global action id.
    action: usize,
    roots: Vec<Root>,
}

/// How a probe finds its region's ends (module docs, step 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Search {
    /// Every advantage's roots in all of `(0, 1)`; the optimal policy at a probe by exact
    /// policy iteration from the first actions.
    Full,
    /// Only the roots that can bound the region: an advantage is dismissed on an interval
    /// next to the probe by a derivative bound or by Descartes' rule on the interval, and the
    /// others are isolated only there, nearest candidates first, the interval shrinking to the
    /// nearest region end found; the optimal policy at a probe from a floating-point policy
    /// iteration, corrected by exact policy iteration on the advantages' signs. On a
    /// deterministic model the probes keep their values, advantages and roots instead (module
    /// docs, step 1′): each advantage met is isolated in all of `(0, 1)` once, and policy
    /// iteration starts from the last probe's policy.
    Pruned,
}

/// The maximal closed interval around a probe where its optimal policy stays optimal.
struct Region {
    /// `None`: reaches 0.
    lo: Option<Root>,
    /// `None`: reaches 1.
    hi: Option<Root>,
    /// Global action ids, `None` where the episode is over.
    policy: Vec<Option<usize>>,
    /// Actions tied with the policy's on all of `(0, 1)` (`A ≡ 0`).
    persistent: Vec<usize>,
    advantages: Vec<Advantage>,
    /// Points inside where some advantage touches 0.
    touches: Vec<Root>,
}

fn zero_point() -> Root {
    Root::rational(Rational::zero())
}

fn one_point() -> Root {
    Root::rational(Rational::one())
}

impl Region {
    fn contains(&self, a: &Root) -> bool {
        self.lo
            .as_ref()
            .is_none_or(|l| l.compare(a) != Ordering::Greater)
            && self
                .hi
                .as_ref()
                .is_none_or(|h| h.compare(a) != Ordering::Less)
    }

    fn contains_rational(&self, t: &Rational) -> bool {
        self.lo
            .as_ref()
            .is_none_or(|l| l.cmp_rational(t) == Ordering::Less)
            && self
                .hi
                .as_ref()
                .is_none_or(|h| h.cmp_rational(t) == Ordering::Greater)
    }

    /// Per global action: optimal at the point `at` of the region, or on an open interval of
    /// the region free of breakpoints (`at = None`). Actions where the episode is over count
    /// as optimal.
    fn optimal(&self, model: &Model, at: Option<&Root>) -> Vec<bool> {
        let p = &model.problem;
        let mut allowed = vec![false; p.action_total()];
        for x in 0..p.states() {
            match self.policy[x] {
                Some(a) => allowed[a] = true,
                None => p.actions(x).for_each(|a| allowed[a] = true),
            }
        }
        for &a in &self.persistent {
            allowed[a] = true;
        }
        if let Some(b) = at {
            for adv in &self.advantages {
                if adv.roots.iter().any(|r| r.compare(b) == Ordering::Equal) {
                    allowed[adv.action] = true;
                }
            }
        }
        allowed
    }
}

/// An advantage negative at the probe `t`, with two bounds that dismiss it cheaply near `t`.
/// * The polynomial `c`: `|c(t)| = value / scale` and `lipschitz = Σ k |c_k|` bounds `|c′|` on
///   `[0, 1]`, so `c < 0` on `[t − w, t + w]` whenever `|c(t)| > lipschitz · w`.
/// * The advantage itself, `A = Q_a − V_x = c / factor` (`factor > 0`): a policy's values are
///   `V = Σ_k α^k P^k r` with `|r| ≤ R` (the largest reward magnitude) and `P`
///   substochastic, so `|V| ≤ R/(1 − α)` and `|V′| ≤ R/(1 − α)²`; then
///   `Q_a′ = Σ p (V_y + α V_y′)` has `|Q_a′| ≤ R/(1 − α)²` and `|A′| ≤ 2R/(1 − α)²`, increasing
///   in `α`. So `A < 0` on an interval of width `w` next to `t` ending at most at `u` whenever
///   `|A(t)| (1 − u)² > 2R w`. This one is blind to the size of the coefficients.
struct Candidate {
    /// Index in the probe's advantages.
    index: usize,
    poly: Vec<BigInt>,
    value: BigInt,
    scale: BigInt,
    lipschitz: BigInt,
    /// `|A(t)| / 2R` as the fraction `by_values.0 / by_values.1` (not reduced: comparisons
    /// cross-multiply, so no gcd of large numbers is taken; the second is 0 when `R = 0`).
    by_values: (BigInt, BigInt),
    /// Approximate `log2` of how far from `t` the bounds keep `A < 0`: the order in which
    /// candidates are tried.
    radius: f64,
}

fn log2_big(x: &BigInt) -> f64 {
    use num_traits::ToPrimitive;
    let bits = x.bits();
    if bits == 0 {
        return f64::NEG_INFINITY;
    }
    let shift = bits.saturating_sub(60);
    (x.abs() >> shift).to_f64().unwrap_or(1.0).log2() + shift as f64
}

impl Candidate {
    fn new(
        index: usize,
        poly: Vec<BigInt>,
        factor: &(BigInt, BigInt),
        top: &Rational,
        t: &Rational,
    ) -> Candidate {
        let value = homogeneous(&poly, t).abs();
        let d = poly.len().saturating_sub(1);
        let scale = num_traits::pow(t.denom().clone(), d);
        let lipschitz = poly
            .iter()
            .enumerate()
            .skip(1)
            .fold(BigInt::zero(), |acc, (k, c)| {
                acc + c.abs() * BigInt::from(k)
            });
        // |A(t)| = value / (scale · factor), 2R = 2 top.
        let by_values = (
            &value * &factor.1 * top.denom(),
            &scale * &factor.0 * top.numer() * 2,
        );
        let by_coefficients = log2_big(&value) - log2_big(&scale) - log2_big(&lipschitz);
        let gap = Rational::one() - t;
        let log2_gap = log2_big(gap.numer()) - log2_big(gap.denom());
        let radius = log2_big(&by_values.0) - log2_big(&by_values.1) + 2.0 * log2_gap;
        Candidate {
            index,
            poly,
            value,
            scale,
            lipschitz,
            by_values,
            radius: by_coefficients.max(radius),
        }
    }

    /// Whether `A < 0` on the closed interval of width `w ≥ 0` next to the probe (either
    /// side) whose far end from 0 is `u`.
    fn clear(&self, w: &Rational, u: &Rational) -> bool {
        if &self.value * w.denom() > &self.lipschitz * w.numer() * &self.scale {
            return true;
        }
        let gap = Rational::one() - u;
        // |A(t)| (1 − u)² > 2R w, cross-multiplied.
        let (n, d) = &self.by_values;
        gap.is_positive()
            && n * gap.numer() * gap.numer() * w.denom() > d * w.numer() * gap.denom() * gap.denom()
    }
}

/// Walking right from the probe `t` over the roots of `f` in `(t, b)` (all of them among
/// `roots`): the first root after which `f` is positive, and the roots before it where `f`
/// only touches 0. The sign after a root is taken at a point before the next root (or `b`).
fn walk_right(
    f: &[BigInt],
    roots: &[Root],
    t: &Rational,
    b: &Rational,
) -> (Option<Root>, Vec<Root>) {
    let inside: Vec<&Root> = roots
        .iter()
        .filter(|r| r.cmp_rational(t) == Ordering::Greater && r.cmp_rational(b) == Ordering::Less)
        .collect();
    let end = Root::rational(b.clone());
    let mut touches = Vec::new();
    for (i, r) in inside.iter().enumerate() {
        let next = inside.get(i + 1).copied().unwrap_or(&end);
        if integer_sign(f, &between(r, next)) == Ordering::Greater {
            return (Some((*r).clone()), touches);
        }
        touches.push((*r).clone());
    }
    (None, touches)
}

/// Walking left from the probe `t` over the roots of `f` in `(a, t)` (all of them among
/// `roots`): the first root before which `f` is positive, and the touching roots after it.
fn walk_left(
    f: &[BigInt],
    roots: &[Root],
    t: &Rational,
    a: &Rational,
) -> (Option<Root>, Vec<Root>) {
    let inside: Vec<&Root> = roots
        .iter()
        .filter(|r| r.cmp_rational(a) == Ordering::Greater && r.cmp_rational(t) == Ordering::Less)
        .collect();
    let start = Root::rational(a.clone());
    let mut touches = Vec::new();
    for i in (0..inside.len()).rev() {
        let prev = if i == 0 { &start } else { inside[i - 1] };
        if integer_sign(f, &between(prev, inside[i])) == Ordering::Greater {
            return (Some(inside[i].clone()), touches);
        }
        touches.push(inside[i].clone());
    }
    (None, touches)
}

/// A rational just past the exact point `r` away from `t` (inside `(0, 1)`), so that an open
/// window ending there still holds `r`.
fn past(r: &Rational, t: &Rational) -> Rational {
    let two = Rational::from_integer(2.into());
    if r > t {
        let far = r + (r - t);
        if far < Rational::one() {
            far
        } else {
            (r + Rational::one()) / two
        }
    } else {
        let far = r - (t - r);
        if far > Rational::zero() {
            far
        } else {
            r / two
        }
    }
}

/// Whether candidate `i` may have a root in the window whose moving end is `end`, as the
/// sequential search decides it (`may_have_root`), with the later candidates screened in
/// parallel once the first region end is found: the window only shrinks, and a candidate
/// cleared on a window is cleared on every window inside it (its bounds hold on the smaller
/// interval, and Descartes' variations do not grow on a subinterval), so a candidate screened
/// out is skipped and one screened in on the same window is taken without a second test.
fn screen(
    screened: &mut Option<(Rational, Vec<bool>)>,
    candidates: &[Candidate],
    i: usize,
    end: &Rational,
    best: &Option<Root>,
    may_have_root: impl Fn(&Candidate, &Rational) -> bool + Sync,
) -> bool {
    use rayon::prelude::*;
    if screened.is_none() && best.is_some() {
        let flags = candidates[i..]
            .par_iter()
            .map(|c| may_have_root(c, end))
            .collect();
        *screened = Some((end.clone(), flags));
    }
    match screened {
        Some((at, flags)) => {
            let first = candidates.len() - flags.len();
            flags[i - first] && (at == end || may_have_root(&candidates[i], end))
        }
        None => may_have_root(&candidates[i], end),
    }
}

/// The region's right end by the pruned search (module docs, step 2): candidates in order of
/// their dismissal radius; each is dismissed on `[t, b]` by its derivative bound or by
/// Descartes' rule on `(t, b)`, or its roots in `(t, b)` are isolated and walked, and `b`
/// shrinks to just past the nearest end found. Every root of every advantage in
/// `(t, end]` is recorded.
fn right_end(
    candidates: &[Candidate],
    advantages: &mut [Advantage],
    t: &Rational,
    touches: &mut Vec<Root>,
) -> Option<Root> {
    let mut b = Rational::one();
    let mut best: Option<Root> = None;
    let may_have_root =
        |c: &Candidate, b: &Rational| !(c.clear(&(b - t), b) || no_root_between(&c.poly, t, b));
    let mut screened: Option<(Rational, Vec<bool>)> = None;
    for (i, c) in candidates.iter().enumerate() {
        if !screen(&mut screened, candidates, i, &b, &best, may_have_root) {
            continue;
        }
        let roots = roots_in_window(&int_poly(&c.poly), Some((t, &b)));
        let (end, mut met) = walk_right(&c.poly, &roots, t, &b);
        touches.append(&mut met);
        advantages[c.index].roots.extend(roots);
        if let Some(h) = end {
            if best.as_ref().is_none_or(|x| h.compare(x) == Ordering::Less) {
                b = if h.exact {
                    past(&h.lo, t)
                } else {
                    // Narrowed to about its distance from t, so the window shrinks with it.
                    let mut n = h.clone();
                    while !n.exact && &n.hi - &n.lo > &n.lo - t {
                        n.halve();
                    }
                    if n.exact {
                        past(&n.lo, t)
                    } else {
                        n.hi
                    }
                };
                best = Some(h);
            }
        }
    }
    best
}

/// The region's left end by the pruned search, from `a` (every region end lies right of it):
/// as [`right_end`], mirrored. `None` means no end in `(a, t)`.
fn left_end(
    candidates: &[Candidate],
    advantages: &mut [Advantage],
    t: &Rational,
    a: &Rational,
    touches: &mut Vec<Root>,
) -> Option<Root> {
    let mut a = a.clone();
    let mut best: Option<Root> = None;
    let may_have_root =
        |c: &Candidate, a: &Rational| !(c.clear(&(t - a), t) || no_root_between(&c.poly, a, t));
    let mut screened: Option<(Rational, Vec<bool>)> = None;
    for (i, c) in candidates.iter().enumerate() {
        if !screen(&mut screened, candidates, i, &a, &best, may_have_root) {
            continue;
        }
        let roots = roots_in_window(&int_poly(&c.poly), Some((&a, t)));
        let (end, mut met) = walk_left(&c.poly, &roots, t, &a);
        touches.append(&mut met);
        advantages[c.index].roots.extend(roots);
        if let Some(l) = end {
            if best
                .as_ref()
                .is_none_or(|x| l.compare(x) == Ordering::Greater)
            {
                a = if l.exact {
                    past(&l.lo, t)
                } else {
                    let mut n = l.clone();
                    while !n.exact && &n.hi - &n.lo > t - &n.hi {
                        n.halve();
                    }
                    if n.exact {
                        past(&n.lo, t)
                    } else {
                        n.lo
                    }
                };
                best = Some(l);
            }
        }
    }
    best
}

/// The integer polynomial as a [`Poly`].
fn int_poly(c: &[BigInt]) -> Poly {
    Poly::new(c.iter().cloned().map(Rational::from_integer).collect())
}

/// The advantage of one state-action pair over the policy (module docs, step 2).
enum Found {
    Persistent(usize),
    /// Negative at the probe: the action, its polynomial and the positive factor at `t`
    /// between the polynomial and the advantage `Q_a − V_x` itself (an unreduced fraction).
    Negative(usize, Vec<BigInt>, (BigInt, BigInt)),
    AtRoot,
    /// Positive at the probe: the state and the action.
    Positive(StateId, usize),
}

/// Every other action's advantage polynomial over the policy with the given values and its
/// sign at `t` (in parallel: each pair is independent).
fn advantages_at(
    model: &Model,
    running: &[StateId],
    policy: &[Option<usize>],
    values: &PolicyValues,
    t: &Rational,
) -> Vec<Found> {
    let p = &model.problem;
    let pairs: Vec<(StateId, usize)> = running
        .iter()
        .flat_map(|&x| p.actions(x).map(move |a| (x, a)))
        .filter(|&(x, a)| Some(a) != policy[x])
        .collect();
    // Each denominator at t (positive), as an unreduced fraction.
    let dens_at: Vec<(BigInt, BigInt)> = values
        .dens
        .iter()
        .map(|d| {
            let m = num_traits::pow(t.denom().clone(), d.len().saturating_sub(1));
            (homogeneous(d, t), m)
        })
        .collect();
    use rayon::prelude::*;
    pairs
        .par_iter()
        .map(|&(x, a)| {
            let value = |y: StateId| (values.den_of[y], values.n[y].as_slice());
            let (c, scale, involved) = advantage_polynomial(model, x, a, &value, &values.dens);
            if c.iter().all(Zero::is_zero) {
                return Found::Persistent(a);
            }
            match integer_sign(&c, t) {
                Ordering::Equal => Found::AtRoot,
                Ordering::Greater => Found::Positive(x, a),
                Ordering::Less => {
                    let factor = involved
                        .iter()
                        .fold((scale.clone(), BigInt::one()), |(n, d), &k| {
                            (n * &dens_at[k].0, d * &dens_at[k].1)
                        });
                    Found::Negative(a, c, factor)
                }
            }
        })
        .collect()
}

/// The advantage polynomial of action `a` at `x` over a policy (module docs, step 2):
/// `A = r_a D + α Σ p N_y − N_x` times the lcm `scale` of the denominators of `r_a` and of
/// the probabilities, and — with several denominators (the deterministic path) — times the
/// product of the distinct ones involved (each positive on `(0, 1)`, so the sign is kept).
/// `value(y)` gives the index of `y`'s denominator in `dens` and its numerator. Returns the
/// polynomial, `scale` and the indices of the denominators involved.
fn advantage_polynomial<'v>(
    model: &Model,
    x: StateId,
    a: usize,
    value: &dyn Fn(StateId) -> (usize, &'v [BigInt]),
    dens: &[Vec<BigInt>],
) -> (Vec<BigInt>, BigInt, Vec<usize>) {
    let p = &model.problem;
    let mut scale = model.reward[a].denom().clone();
    for o in p.outcomes(a) {
        scale = num_integer::Integer::lcm(&scale, o.probability.denom());
    }
    let times = |q: &Rational| (q * Rational::from_integer(scale.clone())).to_integer();
    let (den_x, num_x) = value(x);
    let mut involved = vec![den_x];
    for o in p.outcomes(a) {
        if !model.terminal[o.successor] {
            let k = value(o.successor).0;
            if !involved.contains(&k) {
                involved.push(k);
            }
        }
    }
    let product = |skip: Option<usize>| -> Vec<BigInt> {
        involved
            .iter()
            .filter(|&&k| Some(k) != skip)
            .fold(vec![BigInt::one()], |acc, &k| poly_mul(&acc, &dens[k]))
    };
    let mut c: Vec<BigInt> = Vec::new();
    let ra = times(&model.reward[a]);
    if !ra.is_zero() {
        poly_add_scaled(&mut c, &product(None), &ra, 0);
    }
    for o in p.outcomes(a) {
        if model.terminal[o.successor] {
            continue;
        }
        let (den_y, num_y) = value(o.successor);
        let w = times(&o.probability);
        let rest = product(Some(den_y));
        poly_add_scaled(&mut c, &poly_mul(num_y, &rest), &w, 1);
    }
    let rest = product(Some(den_x));
    poly_add_scaled(&mut c, &poly_mul(num_x, &rest), &-&scale, 0);
    (c, scale, involved)
}

/// The most floating-point sweeps of [`float_optimum`].
const FLOAT_SWEEPS: usize = 400;

/// A candidate optimal policy of a deterministic model at `t` in floating point: policy
/// iteration evaluated along the successor chains, improving only by more than a relative
/// `10⁻⁹`, at most [`FLOAT_SWEEPS`] sweeps. Only a starting point: the probe corrects it by
/// exact policy iteration on the exact advantages' signs.
fn float_optimum(model: &Model, running: &[StateId], t: &Rational) -> Vec<Option<usize>> {
    use num_traits::ToPrimitive;
    let p = &model.problem;
    let n = p.states();
    let tf = t.to_f64().unwrap_or(0.5);
    let reward: Vec<f64> = model
        .reward
        .iter()
        .map(|r| r.to_f64().unwrap_or(0.0))
        .collect();
    let order = sweep_order(model, running);
    let mut policy: Vec<Option<usize>> = (0..n)
        .map(|x| (!model.terminal[x]).then(|| p.actions(x).start))
        .collect();
    for _ in 0..FLOAT_SWEEPS {
        let mut w = vec![0.0f64; n];
        for (x, cycle) in chains(model, running, &policy) {
            let a = policy[x].expect("acts");
            w[x] = match cycle {
                Some(cycle) => {
                    let (mut sum, mut power) = (0.0, 1.0);
                    for &c in &cycle {
                        sum += power * reward[policy[c].expect("acts")];
                        power *= tf;
                    }
                    sum / (1.0 - power)
                }
                None => reward[a] + tf * w[successor(model, a)],
            };
        }
        let mut changed = false;
        for &x in &order {
            let q = |w: &[f64], a: usize| reward[a] + tf * w[successor(model, a)];
            let mut best = q(&w, policy[x].expect("acts"));
            for a in p.actions(x) {
                let qa = q(&w, a);
                if qa > best + 1e-9 * (1.0 + best.abs()) {
                    best = qa;
                    policy[x] = Some(a);
                    changed = true;
                }
            }
            w[x] = best;
        }
        if !changed {
            break;
        }
    }
    policy
}

/// The probe at the rational `t`: `None` if `t` is a root of some non-zero advantage (then the
/// caller probes elsewhere). `left`: the end of the gap `t` lies in (every region end found
/// from `t` lies right of it; the pruned search starts there).
#[allow(clippy::too_many_arguments)]
fn probe(
    model: &Model,
    running: &[StateId],
    index: &[Option<usize>],
    t: &Rational,
    degree: &mut usize,
    work: &mut u128,
    deterministic: bool,
    left: Option<&Root>,
    search: Search,
    memory: Option<&mut chains::ChainMemory>,
    degree_bound: usize,
) -> Result<Option<Region>, ParametricError> {
    if let Some(memory) = memory {
        return memory.probe(model, running, t, degree, work);
    }
    let p = &model.problem;
    let (policy, values, found) = if deterministic {
        // The full search (the pruned one has memory): exact policy iteration.
        let mut policy = deterministic_optimum(model, running, t);
        loop {
            let values = chain_values(model, running, &policy, degree_bound)?;
            let found = advantages_at(model, running, &policy, &values, t);
            // Exact policy iteration: switch every state with an improving action to one
            // (the values grow strictly, so no policy repeats).
            let mut improved = vec![false; p.states()];
            for f in &found {
                if let Found::Positive(x, a) = *f {
                    if !improved[x] {
                        improved[x] = true;
                        policy[x] = Some(a);
                    }
                }
            }
            if !improved.contains(&true) {
                break (policy, values, found);
            }
        }
    } else {
        let (_, policy, _) = model.discounted(t)?;
        let values = policy_values(model, running, index, &policy)?;
        let found = advantages_at(model, running, &policy, &values, t);
        (policy, values, found)
    };
    *degree = (*degree).max(values.degree);
    if deterministic {
        *work += deterministic_probe_work(&found);
    }
    let mut persistent = Vec::new();
    let mut advantages = Vec::new();
    let mut polys = Vec::new();
    for f in found {
        match f {
            Found::Persistent(a) => persistent.push(a),
            Found::Negative(a, c, factor) => {
                advantages.push(Advantage {
                    action: a,
                    roots: Vec::new(),
                });
                polys.push((c, factor));
            }
            Found::AtRoot => return Ok(None),
            Found::Positive(..) => {
                return Err(ParametricError::Internal(format!(
                    "the policy optimal at alpha = {t} has a positive advantage there"
                )))
            }
        }
    }
    let mut touches: Vec<Root> = Vec::new();
    let (lo, hi) = match search {
        Search::Full => {
            let polys: Vec<Vec<BigInt>> = polys.into_iter().map(|(c, _)| c).collect();
            full_ends(&polys, &mut advantages, t, &mut touches)
        }
        Search::Pruned => {
            use rayon::prelude::*;
            let top = model
                .reward
                .iter()
                .map(|r| r.abs())
                .fold(Rational::zero(), |m, r| if r > m { r } else { m });
            let mut candidates: Vec<Candidate> = polys
                .into_par_iter()
                .enumerate()
                .map(|(i, (c, factor))| Candidate::new(i, c, &factor, &top, t))
                .collect();
            candidates.sort_by(|a, b| a.radius.total_cmp(&b.radius));
            let hi = right_end(&candidates, &mut advantages, t, &mut touches);
            // Every region end from t lies right of the gap's end `l` (two policies optimal
            // on a common open interval have equal values, so equal regions): the search
            // starts left of `l`'s bracket; with nothing found there, again from 0.
            let start = left.map_or_else(Rational::zero, |l| {
                // The bracket of `l` narrowed to about its distance from t.
                let mut l = l.clone();
                while !l.exact && &l.hi - &l.lo > t - &l.hi {
                    l.halve();
                }
                let lo = &l.lo;
                let far = lo - (t - lo);
                if far > Rational::zero() {
                    far
                } else {
                    Rational::zero()
                }
            });
            let mut lo = left_end(&candidates, &mut advantages, t, &start, &mut touches);
            if lo.is_none() && start.is_positive() {
                lo = left_end(
                    &candidates,
                    &mut advantages,
                    t,
                    &Rational::zero(),
                    &mut touches,
                );
            }
            (lo, hi)
        }
    };
    let mut region = Region {
        lo,
        hi,
        policy,
        persistent,
        advantages,
        touches: Vec::new(),
    };
    region.touches = touches
        .into_iter()
        .filter(|r| {
            region
                .lo
                .as_ref()
                .is_none_or(|l| r.compare(l) == Ordering::Greater)
                && region
                    .hi
                    .as_ref()
                    .is_none_or(|h| r.compare(h) == Ordering::Less)
        })
        .collect();
    Ok(Some(region))
}

/// The region's ends by the full search: every advantage's roots in `(0, 1)` (in parallel),
/// walked from `t` both ways.
fn full_ends(
    polys: &[Vec<BigInt>],
    advantages: &mut [Advantage],
    t: &Rational,
    touches: &mut Vec<Root>,
) -> (Option<Root>, Option<Root>) {
    use rayon::prelude::*;
    let all: Vec<Vec<Root>> = polys
        .par_iter()
        .map(|c| roots_in_unit_interval(&int_poly(c)))
        .collect();
    let (mut lo, mut hi): (Option<Root>, Option<Root>) = (None, None);
    for ((c, roots), adv) in polys.iter().zip(all).zip(advantages.iter_mut()) {
        let (h, mut met) = walk_right(c, &roots, t, &Rational::one());
        touches.append(&mut met);
        if let Some(h) = h {
            if hi.as_ref().is_none_or(|x| h.compare(x) == Ordering::Less) {
                hi = Some(h);
            }
        }
        let (l, mut met) = walk_left(c, &roots, t, &Rational::zero());
        touches.append(&mut met);
        if let Some(l) = l {
            if lo
                .as_ref()
                .is_none_or(|x| l.compare(x) == Ordering::Greater)
            {
                lo = Some(l);
            }
        }
        adv.roots = roots;
    }
    (lo, hi)
}

/// Rationals strictly between `l` and `r` (`None`: 0, 1), the first ones close to `l`, each
/// the simplest rational of a sub-interval (small denominators keep the exact solves small).
fn probe_points(l: Option<&Root>, r: Option<&Root>) -> impl Iterator<Item = Rational> {
    let la = l.cloned().unwrap_or_else(zero_point);
    let ra = r.cloned().unwrap_or_else(one_point);
    let mid = between(&la, &ra);
    let mut la = la;
    while la.hi >= mid {
        la.halve();
    }
    // The bracket of `l` narrowed to 2^-20 of its distance from `mid`, so that the first
    // probe lies close to `l` itself (the pruned search then looks left of the probe only
    // over a short interval).
    let scale = Rational::from_integer(BigInt::one() << 20u32);
    while !la.exact && (&la.hi - &la.lo) * &scale > &mid - &la.hi {
        la.halve();
    }
    let base = la.hi;
    let delta = &mid - &base;
    // Last, the simplest rational of the whole gap and of each side of it: the least
    // denominators the gap holds (a stochastic model's probes need small ones,
    // [`bounds::AlphaRoom`]); found only when asked for.
    let (l, r) = (l.cloned(), r.cloned());
    let least = std::iter::once_with(move || {
        let (lo, hi) = inside(l.as_ref(), r.as_ref());
        let simplest = simplest_between(&lo, &hi);
        let sides = [
            simplest_between(&lo, &simplest),
            simplest_between(&simplest, &hi),
        ];
        std::iter::once(simplest).chain(sides)
    })
    .flatten();
    [24u32, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16]
        .into_iter()
        .map(move |k| {
            let at = |k: u32| &base + &delta / Rational::from_integer(BigInt::one() << k);
            simplest_between(&at(k + 1), &at(k))
        })
        .chain(least)
}

/// Rationals `lo < hi` with `(lo, hi)` inside the gap `(l, r)` (`None`: 0, 1), the brackets of
/// `l` and `r` narrowed to `2^-10` of what is left between them.
fn inside(l: Option<&Root>, r: Option<&Root>) -> (Rational, Rational) {
    let mut la = l.cloned().unwrap_or_else(zero_point);
    let mut ra = r.cloned().unwrap_or_else(one_point);
    let scale = Rational::from_integer(BigInt::from(1024));
    loop {
        let wide = |a: &Root| !a.exact && (&a.hi - &a.lo) * &scale > &ra.lo - &la.hi;
        if la.hi < ra.lo && !wide(&la) && !wide(&ra) {
            return (la.hi, ra.lo);
        }
        if !la.exact {
            la.halve();
        }
        if !ra.exact {
            ra.halve();
        }
    }
}

/// The gap `(l, r)` of `(0, 1)` (`None`: 0, 1) in decimals, for a refusal.
fn gap_text(l: &Option<Root>, r: &Option<Root>) -> String {
    let end = |a: &Option<Root>, default: &str| {
        a.as_ref()
            .map_or_else(|| default.to_string(), |a| format!("≈{}", a.decimal(8)))
    };
    format!("({}, {})", end(l, "0"), end(r, "1"))
}

/// The success probability and truecost `{min, max}` of the policies using only the allowed
/// actions, from the initial distribution (module docs, step 4).
fn achievement(model: &Model, allowed: &[bool]) -> Result<Achievement, ParametricError> {
    let p = &model.problem;
    let allow = |a: usize| allowed[a];
    let (max, _) = max_reach(p, &allow).map_err(ObjectiveError::from)?;
    let min = min_reach(p, &allow).map_err(ObjectiveError::from)?;
    let success = Bounds {
        min: model.at_initial_rational(&min),
        max: model.at_initial_rational(&max),
    };
    let (restricted, origin) = derive(p, p.goals().to_vec(), |a| {
        allowed[a].then(|| StochasticAction {
            cost: p.cost(a).clone(),
            outcomes: p.outcomes(a).to_vec(),
        })
    })
    .map_err(ObjectiveError::from)?;
    let least = optimum(&restricted).map_err(ObjectiveError::from)?;
    let truecost_min = model.at_initial(least.cost_to_go_all());
    let truecost_max = if success.min < Rational::one() {
        Extended::Infinite
    } else {
        let start: Vec<Option<usize>> = least
            .policy_actions()
            .iter()
            .map(|a| a.map(|a| origin[a]))
            .collect();
        most_truecost(model, allowed, start)?
    };
    Ok(Achievement {
        success,
        truecost_min,
        truecost_max,
    })
}

/// The greatest expected truecost over the allowed policies when all of them reach a goal with
/// probability 1 from the initial distribution: exact policy iteration maximising the cost on
/// the states reachable from the initial ones (every allowed policy is proper there).
fn most_truecost(
    model: &Model,
    allowed: &[bool],
    mut policy: Vec<Option<usize>>,
) -> Result<Extended, ParametricError> {
    let p = &model.problem;
    let n = p.states();
    let mut reach = vec![false; n];
    let mut stack: Vec<StateId> = model.initial.iter().map(|(x, _)| *x).collect();
    for &x in &stack {
        reach[x] = true;
    }
    while let Some(x) = stack.pop() {
        if p.is_goal(x) {
            continue;
        }
        for a in p.actions(x).filter(|&a| allowed[a]) {
            for o in p.outcomes(a) {
                if !reach[o.successor] {
                    reach[o.successor] = true;
                    stack.push(o.successor);
                }
            }
        }
    }
    loop {
        let v = evaluate(p, &policy).map_err(ObjectiveError::from)?;
        let q = |a: usize| -> Option<Rational> {
            let mut s = p.cost(a).clone();
            for o in p.outcomes(a) {
                s += &o.probability * v[o.successor].finite()?;
            }
            Some(s)
        };
        let mut changed = false;
        for x in (0..n).filter(|&x| reach[x] && !p.is_goal(x)) {
            let Some(mut best) = policy[x].and_then(q) else {
                continue;
            };
            for a in p.actions(x).filter(|&a| allowed[a]) {
                if let Some(qa) = q(a) {
                    if qa > best {
                        best = qa;
                        policy[x] = Some(a);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            return Ok(model.at_initial(&v));
        }
    }
}

/// The exact breakpoints `α ∈ (0, 1)` where the set of discount-optimal policies changes, and
/// for every interval between them and every breakpoint the success probability and truecost
/// of the optimal policies (the paper's Proposition 3 on any stochastic
/// problem). Method in the module docs.
///
/// ```
/// use truecost::objectives::{parametric::discount_breakpoints, Model};
/// use truecost::stochastic::file::{from_json, ProblemFile};
/// // At 0: a safe detour (cost 1, then 3 to the goal) or a gamble (cost 1: goal with 1/2,
/// // else a trap loop costing 1 forever).
/// let text = r#"{"initial":0,"goals":[3],"actions":[
///   [{"to":1,"cost":"1"},{"cost":"1","outcomes":[{"to":3,"p":"1/2"},{"to":2,"p":"1/2"}]}],
///   [{"to":3,"cost":"3"}],
///   [{"to":2,"cost":"1"}],
///   []]}"#;
/// let ProblemFile::Stochastic(p) = from_json(text).unwrap() else { panic!() };
/// let m = Model::from_problem(*p, "example".into());
/// let d = discount_breakpoints(&m).unwrap();
/// // Rewards: safe -1 - 3a; gamble -1 - (a/2)/(1-a); equal iff 1/(2(1-a)) = 3, a = 5/6.
/// assert_eq!(d.breakpoints.len(), 1);
/// assert_eq!(d.breakpoints[0].at.as_rational().map(|r| r.to_string()).as_deref(), Some("5/6"));
/// assert_eq!(d.intervals[0].achievement.success.min.to_string(), "1/2"); // gamble below 5/6
/// assert_eq!(d.intervals[1].achievement.success.min.to_string(), "1");
/// ```
pub fn discount_breakpoints(model: &Model) -> Result<DiscountAnalysis, ParametricError> {
    discount_breakpoints_with(model, &mut |_| {})
}

/// [`discount_breakpoints`], calling `progress` before every probe. The result does not
/// depend on `progress`. A stochastic problem is refused before any work when one probe would
/// exceed [`MAX_SINGLE_PROBE_WORK`] ([`probe_work`]), and stopped while running when the next
/// probe, with the phase after the probes reserved so far, would take the work past
/// [`MAX_PROBE_WORK`]; a deterministic one is refused over
/// [`MAX_DETERMINISTIC_RUNNING_STATES`] and stopped when its measured work would pass
/// [`MAX_DETERMINISTIC_WORK`].
pub fn discount_breakpoints_with(
    model: &Model,
    progress: &mut dyn FnMut(ProbeProgress),
) -> Result<DiscountAnalysis, ParametricError> {
    discount_breakpoints_search(model, Search::Pruned, progress)
}

/// [`discount_breakpoints_with`] with the given [`Search`]: both give the same breakpoints,
/// intervals, optimal sets and achievements (the full search is the reference the pruned one
/// is tested against).
pub fn discount_breakpoints_search(
    model: &Model,
    search: Search,
    progress: &mut dyn FnMut(ProbeProgress),
) -> Result<DiscountAnalysis, ParametricError> {
    discount_breakpoints_within(model, search, MAX_DETERMINISTIC_WORK, progress)
}

/// [`discount_breakpoints_search`] with the bound on the work of a deterministic analysis
/// given (in place of [`MAX_DETERMINISTIC_WORK`]; stochastic models keep [`MAX_PROBE_WORK`]).
/// The work done is [`DiscountAnalysis::work`]; an analysis succeeds within any bound of at
/// least twice that (before a probe, the check adds the last probe's work to the work done:
/// at most twice the total).
pub fn discount_breakpoints_within(
    model: &Model,
    search: Search,
    deterministic_bound: u128,
    progress: &mut dyn FnMut(ProbeProgress),
) -> Result<DiscountAnalysis, ParametricError> {
    let limits = Limits {
        deterministic_work: deterministic_bound,
        ..Limits::default()
    };
    discount_breakpoints_limited(model, search, limits, progress)
}

/// The bounds of an analysis that [`discount_breakpoints_limited`] takes as given: the
/// analysis uses [`Limits::default`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The work bound of a deterministic model ([`MAX_DETERMINISTIC_WORK`]).
    pub deterministic_work: u128,
    /// The work bound of a stochastic model ([`MAX_PROBE_WORK`]): its probes and its
    /// achievements (`closing::stochastic_achievement`).
    pub stochastic_work: u128,
    /// The largest degree of a value along a successor chain ([`MAX_CHAIN_DEGREE`]), checked
    /// before the first probe ([`bounds::check_certain_degree`]) and on every value built.
    pub chain_degree: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            deterministic_work: MAX_DETERMINISTIC_WORK,
            stochastic_work: MAX_PROBE_WORK,
            chain_degree: MAX_CHAIN_DEGREE,
        }
    }
}

/// [`discount_breakpoints_search`] within the given [`Limits`] (to see what an analysis
/// refused by a bound would need: tests lift the bounds with it).
pub fn discount_breakpoints_limited(
    model: &Model,
    search: Search,
    limits: Limits,
    progress: &mut dyn FnMut(ProbeProgress),
) -> Result<DiscountAnalysis, ParametricError> {
    analyse(model, search, limits, chains::MAX_MEMORY_WORDS, progress)
}

/// [`discount_breakpoints_limited`] with the deterministic probes' memory cleared past
/// `memory_words` words.
fn analyse(
    model: &Model,
    search: Search,
    limits: Limits,
    memory_words: usize,
    progress: &mut dyn FnMut(ProbeProgress),
) -> Result<DiscountAnalysis, ParametricError> {
    let p = &model.problem;
    let running: Vec<StateId> = (0..p.states()).filter(|&x| !model.terminal[x]).collect();
    let deterministic = is_deterministic(model);
    bounds::check_numbers(model, &running)?;
    if !deterministic && running.len() > MAX_RUNNING_STATES {
        return Err(ParametricError::Degree {
            states: running.len(),
            bound: MAX_RUNNING_STATES,
        });
    }
    // Deterministic problems: the chain degree is checked before the first probe where the
    // chain structure forces it, and while running; each probe counts the work it measured
    // (`deterministic_probe_work`); the next probe is expected to cost as much as the last
    // one. Stochastic problems: each probe is estimated before any work, and so is the room
    // the probabilities leave the probes' alpha.
    let (per_probe, room) = if deterministic {
        if running.len() > MAX_DETERMINISTIC_RUNNING_STATES {
            return Err(ParametricError::DeterministicStates {
                states: running.len(),
                bound: MAX_DETERMINISTIC_RUNNING_STATES,
            });
        }
        bounds::check_certain_degree(model, &running, limits.chain_degree)?;
        (None, None)
    } else {
        let bits = number_bits(model, &running);
        let work = probe_work(running.len(), bits);
        if work > MAX_SINGLE_PROBE_WORK {
            return Err(ParametricError::ProbeWork {
                states: running.len(),
                bits,
                work,
                bound: MAX_SINGLE_PROBE_WORK,
            });
        }
        let room = bounds::AlphaRoom::of(model, &running);
        let half = Rational::new(BigInt::one(), BigInt::from(2));
        if !room.fits(&half) {
            return Err(room.refusal(&half, None));
        }
        (Some(work), Some(room))
    };
    let bound = if deterministic {
        limits.deterministic_work
    } else {
        limits.stochastic_work
    };
    let timer = Timer::new();
    let mut work = 0u128;
    let mut last = 0u128;
    let mut index = vec![None; p.states()];
    for (i, &x) in running.iter().enumerate() {
        index[x] = Some(i);
    }
    let mut degree = 0;
    // Achievements by graph search where that is exact (deterministic, costs non-negative).
    let graph = deterministic && paths::costs_non_negative(model);
    let achieve = |allowed: &[bool]| {
        if graph {
            Ok(paths::achievement(model, allowed))
        } else {
            achievement(model, allowed)
        }
    };
    // The phase after the probes: charged in the probes' units, each region's share
    // reserved as its probe finds it (module `closing`); the interval next to 1 is reserved
    // from the start.
    let per_achievement = match per_probe {
        None => closing::achievement(model, graph, closing::exact_solves(model)),
        Some(per_probe) => closing::stochastic_achievement(per_probe),
    };
    let mut reserved = per_achievement;
    let mut memory = (deterministic && search == Search::Pruned)
        .then(|| chains::ChainMemory::new(model, &running, memory_words, limits.chain_degree));
    let mut regions: Vec<Region> = Vec::new();
    let mut gaps: Vec<(Option<Root>, Option<Root>)> = vec![(None, None)];
    let mut probes = 0;
    // The refusal when the work bound is met (`gaps` open besides the one being probed).
    let stopped = |probes, work, reserved, regions, gaps: usize| ParametricError::Work {
        probes,
        work,
        reserved,
        regions,
        gaps: gaps + 1,
        bound,
    };
    while let Some((l, r)) = gaps.pop() {
        if regions.len() >= MAX_REGIONS {
            return Err(ParametricError::Pieces(MAX_REGIONS));
        }
        let mut found = None;
        // The simplest rational of the gap refused for its denominator, if any.
        let mut refused: Option<Rational> = None;
        for t in probe_points(l.as_ref(), r.as_ref()) {
            if let Some(room) = &room {
                if !room.fits(&t) {
                    if refused.as_ref().is_none_or(|q| t.denom() < q.denom()) {
                        refused = Some(t);
                    }
                    continue;
                }
            }
            if work + reserved + per_probe.unwrap_or(last) > bound {
                return Err(stopped(probes, work, reserved, regions.len(), gaps.len()));
            }
            progress(ProbeProgress {
                probes,
                regions: regions.len(),
                gaps: gaps.len() + 1,
                work: work + reserved,
                bound,
            });
            let before = work;
            work += per_probe.unwrap_or(0);
            probes += 1;
            if let Some(memory) = memory.as_mut() {
                memory.set_budget(bound.saturating_sub(reserved));
            }
            let region = probe(
                model,
                &running,
                &index,
                &t,
                &mut degree,
                &mut work,
                deterministic,
                l.as_ref(),
                search,
                memory.as_mut(),
                limits.chain_degree,
            );
            // A probe with memory stops as soon as its counted work passes the bound.
            let region = match region {
                Err(ParametricError::Work { .. }) => {
                    return Err(stopped(probes, work, reserved, regions.len(), gaps.len()))
                }
                region => region?,
            };
            last = work - before;
            if let Some(region) = &region {
                reserved += if deterministic {
                    closing::region(region, per_achievement)
                } else {
                    closing::stochastic_region(region, per_probe.unwrap_or(0))
                };
            }
            if work + reserved > bound {
                return Err(stopped(probes, work, reserved, regions.len(), gaps.len()));
            }
            if let Some(region) = region {
                found = Some(region);
                break;
            }
        }
        let region = match (found, refused, &room) {
            (Some(region), _, _) => region,
            (None, Some(alpha), Some(room)) => {
                return Err(room.refusal(&alpha, Some((gap_text(&l, &r), probes))));
            }
            _ => {
                return Err(ParametricError::Internal(
                    "every probe point of a gap was a breakpoint".into(),
                ))
            }
        };
        if let Some(lo) = &region.lo {
            if l.as_ref()
                .is_none_or(|l| lo.compare(l) == Ordering::Greater)
            {
                gaps.push((l.clone(), Some(lo.clone())));
            }
        }
        if let Some(hi) = &region.hi {
            if r.as_ref().is_none_or(|r| hi.compare(r) == Ordering::Less) {
                gaps.push((Some(hi.clone()), r.clone()));
            }
        }
        regions.push(region);
    }
    // Breakpoints: region ends and touching points, sorted, distinct.
    let mut points: Vec<Root> = Vec::new();
    for region in &regions {
        points.extend(region.lo.iter().cloned());
        points.extend(region.hi.iter().cloned());
        points.extend(region.touches.iter().cloned());
    }
    timer.mark(&format!("probes ({probes}, {work} units)"));
    // The regions in order of their left ends (they meet only at their ends): the region of a
    // point is found by bisection.
    regions.sort_by(|a, b| match (&a.lo, &b.lo) {
        (None, None) => Ordering::Equal,
        (None, Some(_)) => Ordering::Less,
        (Some(_), None) => Ordering::Greater,
        (Some(x), Some(y)) => x.compare(y),
    });
    let region_of = |contains: &dyn Fn(&Region) -> bool, left_of: &dyn Fn(&Root) -> bool| {
        let k = regions.partition_point(|g| g.lo.as_ref().is_none_or(left_of));
        (k.saturating_sub(1)..regions.len())
            .chain(0..k.saturating_sub(1))
            .map(|i| &regions[i])
            .find(|g| contains(g))
            .expect("the regions cover (0,1)")
    };
    points.sort_by(|a, b| a.compare(b));
    // Equal points met through different polynomials keep their common factor.
    points.dedup_by(|a, b| b.absorb_if_equal(a));
    // Within the reservation (module `closing`), so within the bound.
    let reductions = match per_probe {
        None => points.iter().map(closing::reduction).sum::<u128>(),
        Some(per_probe) => points.len() as u128 * closing::stochastic_reduction(per_probe),
    };
    let charged = reductions + (2 * points.len() as u128 + 1) * per_achievement;
    debug_assert!(charged <= reserved, "{charged} > {reserved}");
    work += charged.min(reserved);
    use rayon::prelude::*;
    // Each point on its own (in parallel): rational or reduced polynomial.
    points.par_iter_mut().for_each(|b| {
        b.recognise_rational();
        b.reduce();
    });
    timer.mark("breakpoints reduced");
    let indices = |allowed: &[bool]| -> Vec<Vec<usize>> {
        (0..p.states())
            .map(|x| {
                if model.terminal[x] {
                    return Vec::new();
                }
                p.actions(x)
                    .filter(|&a| allowed[a])
                    .map(|a| a - p.actions(x).start)
                    .collect()
            })
            .collect()
    };
    // The intervals and breakpoints in parallel, each on its own; the first error in order
    // is reported.
    let intervals: Vec<Result<Interval, ParametricError>> = (0..=points.len())
        .into_par_iter()
        .map(|i| {
            let lo = i.checked_sub(1).map(|j| points[j].clone());
            let hi = points.get(i).cloned();
            let sample = between(
                lo.as_ref().unwrap_or(&zero_point()),
                hi.as_ref().unwrap_or(&one_point()),
            );
            let region = region_of(&|g| g.contains_rational(&sample), &|l| {
                l.cmp_rational(&sample) != Ordering::Greater
            });
            let allowed = region.optimal(model, None);
            let optimal = indices(&allowed);
            // The reported policy: the first optimal action at every state (any choice among
            // the optimal actions is optimal; this one does not depend on the search).
            let policy = optimal.iter().map(|o| o.first().copied()).collect();
            Ok(Interval {
                lo,
                hi,
                sample,
                policy,
                optimal,
                achievement: achieve(&allowed)?,
            })
        })
        .collect();
    let intervals: Vec<Interval> = intervals.into_iter().collect::<Result<_, _>>()?;
    let breakpoints: Vec<Result<Breakpoint, ParametricError>> = points
        .par_iter()
        .enumerate()
        .map(|(i, b)| {
            let region = region_of(&|g| g.contains(b), &|l| l.compare(b) != Ordering::Greater);
            let allowed = region.optimal(model, Some(b));
            let at = indices(&allowed);
            let (left, right) = (&intervals[i].optimal, &intervals[i + 1].optimal);
            let ties = (0..p.states())
                .filter(|&x| at[x] != left[x] || at[x] != right[x])
                .map(|x| (x, at[x].clone()))
                .collect();
            Ok(Breakpoint {
                at: b.clone(),
                touch: left == right,
                ties,
                achievement: achieve(&allowed)?,
            })
        })
        .collect();
    let breakpoints: Vec<Breakpoint> = breakpoints.into_iter().collect::<Result<_, _>>()?;
    timer.mark(&format!(
        "achievements ({work} units charged in all, {reserved} reserved, bound {bound})"
    ));
    Ok(DiscountAnalysis {
        breakpoints,
        intervals,
        probes,
        degree,
        running_states: running.len(),
        deterministic,
        work,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stochastic::{Outcome, OutcomeKind, StochasticProblem};

    fn det(cost: i64, to: usize) -> StochasticAction {
        StochasticAction {
            cost: Rational::from_integer(cost.into()),
            outcomes: vec![Outcome {
                successor: to,
                probability: Rational::one(),
                kind: OutcomeKind::Listed,
            }],
        }
    }

    fn eval(p: &[BigInt], a: &Rational) -> Rational {
        p.iter().rev().fold(Rational::zero(), |acc, c| {
            acc * a + Rational::from_integer(c.clone())
        })
    }

    /// The deterministic probes' memory cleared before every probe (nothing kept) gives the
    /// same analysis as the memory kept, with more work: on random benchmark grids.
    #[test]
    fn a_cleared_memory_gives_the_same_analysis() {
        use crate::stochastic::benchmark::{pattern_grid, CostRange, GridPattern};
        let decimals = |d: &DiscountAnalysis| -> Vec<String> {
            d.breakpoints.iter().map(|b| b.at.decimal(40)).collect()
        };
        for seed in 0..3 {
            let range = CostRange { lo: 1, hi: 9 };
            let grid = pattern_grid(6, 6, GridPattern::Random, range, seed).unwrap();
            let m = Model::from_deterministic(&grid, format!("grid {seed}")).unwrap();
            let run =
                |words| analyse(&m, Search::Pruned, Limits::default(), words, &mut |_| {}).unwrap();
            let (kept, cleared) = (run(chains::MAX_MEMORY_WORDS), run(0));
            assert!(!kept.breakpoints.is_empty(), "seed {seed}");
            assert_eq!(decimals(&kept), decimals(&cleared), "seed {seed}");
            for (a, b) in kept.intervals.iter().zip(&cleared.intervals) {
                assert_eq!((&a.optimal, &a.achievement), (&b.optimal, &b.achievement));
            }
            assert_eq!(kept.probes, cleared.probes, "seed {seed}");
            assert!(cleared.work > kept.work, "seed {seed}");
        }
    }

    /// A gap of width `2^-30` next to `1/3` holds no probe point whose denominator fits the
    /// room `2^22` left by probabilities of common denominator `2^40`: the refusal names the
    /// state, the denominator, the gap, its simplest rational and the product; a gap of
    /// width `2^-10` holds one.
    #[test]
    fn a_gap_too_narrow_for_the_alpha_room_is_refused() {
        let big = |k: u32| BigInt::one() << k;
        let room = bounds::AlphaRoom {
            state: 3,
            own: big(40),
            room: big(22),
            costs: None,
        };
        let third = Rational::new(1.into(), 3.into());
        let gap = |k: u32| {
            let l = Root::rational(third.clone());
            let r = Root::rational(&third + Rational::new(1.into(), big(k)));
            (Some(l), Some(r))
        };
        let (l, r) = gap(30);
        let points: Vec<Rational> = probe_points(l.as_ref(), r.as_ref()).collect();
        assert!(points.iter().all(|t| !room.fits(t)), "{points:?}");
        // The least denominator of the gap: its simplest rational.
        let least = points.iter().map(|t| t.denom()).min().unwrap();
        let simplest = points.iter().find(|t| t.denom() == least).unwrap();
        let text = room
            .refusal(simplest, Some((gap_text(&l, &r), 7)))
            .to_string();
        let product = big(40) * simplest.denom();
        assert!(simplest.denom() > &big(22), "{simplest}");
        for w in [
            format!("state 3: the probabilities' common denominator {}", big(40)),
            "after 7 probes the gap (≈0.33333333, ≈0.33333333) is left".to_string(),
            format!("whose simplest rational {simplest} gives {product}"),
            "refused before that probe".to_string(),
        ] {
            assert!(text.contains(&w), "{w:?} missing from {text}");
        }
        let (l, r) = gap(10);
        assert!(probe_points(l.as_ref(), r.as_ref()).any(|t| room.fits(&t)));
    }

    /// A lasso and a path: 0 → 1 → 2 → 1 (costs 1, 2, 3) and 3 → goal 4 (cost 5). By hand at
    /// α = 1/3 (rewards are the negated costs): on the cycle, `V_1 = −(2 + 3α)/(1 − α²)`,
    /// `V_2 = −(3 + 2α)/(1 − α²)`, `V_0 = −1 + α V_1`; off it `V_3 = −5`.
    #[test]
    fn chain_values_of_a_lasso_and_a_path() {
        let actions = vec![
            vec![det(1, 1)],
            vec![det(2, 2)],
            vec![det(3, 1)],
            vec![det(5, 4)],
            vec![],
        ];
        let m = Model::from_problem(
            StochasticProblem::new(actions, 0, vec![4]).unwrap(),
            "lasso".into(),
        );
        let running = [0, 1, 2, 3];
        let policy: Vec<Option<usize>> = (0..5)
            .map(|x| (x < 4).then(|| m.problem.actions(x).start))
            .collect();
        let v = chain_values(&m, &running, &policy, MAX_CHAIN_DEGREE).unwrap();
        let a = Rational::new(1.into(), 3.into());
        let value = |x: usize| eval(&v.n[x], &a) / eval(&v.dens[v.den_of[x]], &a);
        let q = |n: i64, d: i64| Rational::new(n.into(), d.into());
        let one_minus = Rational::one() - &a * &a; // 8/9
        let v1 = -(q(2, 1) + q(3, 1) * &a) / &one_minus;
        let v2 = -(q(3, 1) + q(2, 1) * &a) / &one_minus;
        assert_eq!(value(1), v1);
        assert_eq!(value(2), v2);
        assert_eq!(value(0), q(-1, 1) + &a * &v1);
        assert_eq!(value(3), q(-5, 1));
        // Degrees: the cycle's denominator 1 − α², the path's 1.
        assert_eq!(v.degree, 2);
        assert_eq!(v.dens[v.den_of[3]].len(), 1);
        // The optimum at 1/3 of a choice: at 0 also a direct move to the goal costing 10
        // (−10 against −1 + V_1/3 ≈ −3.08: the lasso is better at α = 1/3).
        let mut actions = vec![
            vec![det(1, 1), det(10, 4)],
            vec![det(2, 2)],
            vec![det(3, 1)],
            vec![det(5, 4)],
            vec![],
        ];
        let m2 = Model::from_problem(
            StochasticProblem::new(std::mem::take(&mut actions), 0, vec![4]).unwrap(),
            "choice".into(),
        );
        let best = deterministic_optimum(&m2, &running, &a);
        assert_eq!(best[0], Some(m2.problem.actions(0).start));
        // Near α = 1 the lasso costs about 2.5 per step forever: the goal is better.
        let best = deterministic_optimum(&m2, &running, &Rational::new(99.into(), 100.into()));
        assert_eq!(best[0], Some(m2.problem.actions(0).start + 1));
    }
}

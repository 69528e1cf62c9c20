//! Mixed-precision policy iteration: the stage between the `f64` warm start and the exact
//! policy iteration of [`super::policy_iteration`] (docs/spec.md §3).
//!
//! Why it exists: on grids whose deterministic optimum has many ties (unit costs, regular cost
//! patterns), the stochastic `Q`-values of two actions differ by amounts like `((1−γ)/k)^d`
//! (`d` the distance to where the two paths' noise first differs): relative gaps of `10⁻¹⁰`
//! to `10⁻³⁰⁰` on a 50×50 grid. No `f64` evaluation resolves them: exact policy iteration
//! started from the `f64` policy needs one exact evaluation per "layer" of such gaps (8 on a
//! 20×20 grid, 23 on a 50×50 grid). This stage resolves them at a fraction of an exact
//! solve's cost.
//!
//! Each policy `μ` is evaluated in fixed point: `z ≈ X / 2^B` (integers `X`, the unknowns of
//! `A·z = r`, `A = diag(s)(I − P_μ)`) by **iterative refinement**: the residual
//! `R = 2^B·r − A·X` is computed exactly in big integers, the correction solved with one `f64`
//! band LU of `A` (factored once per policy), until `|R|` stops shrinking. The error is then
//! **certified**: with `t̂ ≥ 0` an integer vector checked exactly to satisfy
//! `(I − P_μ)·t̂ ≥ 1` (so `t̂ ≥ (I − P_μ)⁻¹·1`, the expected number of steps to a goal; `P_μ ≥
//! 0` and `μ` proper), `|z − X/2^B| ≤ t̂ · ρ / 2^B` with `ρ = maxᵢ |Rᵢ| / sᵢ`.
//!
//! Improvement is switched only on a **certified strict** improvement: `s·(Q_μ(x, a) − G_μ(x))`
//! computed from `X` differs from the exact one by at most `M = 2·s·max t̂·ρ` (in units of
//! `2^−B`), so `D < −M` proves `Q_μ(x, a) < G_μ(x)` exactly. The policies are thus those of an
//! exact policy iteration with strict improvement (proper, strictly decreasing `G_μ`). Where
//! `|D| ≤ M` for some other action (unresolved), the precision `B` is doubled, up to a cap
//! past `log₂|det A|`: beyond it a non-zero gap (a multiple of `1/|det A|`) is always resolved,
//! so what is still unresolved is an exact tie. The policy handed on is checked by the exact
//! stage (one exact evaluation and improvement check in the common case); nothing of this
//! stage is reported as a value.

use num_bigint::{BigInt, Sign};
use num_traits::{FromPrimitive, Signed, ToPrimitive, Zero};
use rayon::prelude::*;

use super::linear::{FloatFactor, SparseSystem};
use super::StochasticProblem;

/// What the stage did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Refinement {
    /// Improvement rounds with at least one certified switch.
    pub rounds: usize,
    /// The precision `B` (bits after the point) at the end.
    pub bits: u64,
    /// Whether it ended with every state resolved (certified optimal up to exact ties at the
    /// cap, or with no unresolved action at all).
    pub resolved: bool,
}

/// The starting precision, in bits after the point.
const START_BITS: u64 = 128;

/// Refinement stops when the largest residual is below `2^FLOOR_BITS` (in units of `2^−B`).
const FLOOR_BITS: u64 = 12;

/// The precision is not raised further once the unresolved states have stayed the same for
/// this many doublings and `B ≥ PLATEAU_BITS`: they are then most likely exact ties, which no
/// precision below the cap resolves, and the exact stage decides them (going on to the cap
/// would cost about as much as an exact evaluation).
const STABLE_DOUBLINGS: usize = 2;

/// See [`STABLE_DOUBLINGS`].
const PLATEAU_BITS: u64 = 1024;

/// At most this many certified improvement rounds.
const MAX_ROUNDS: usize = 200;

/// A certificate `t̂` with `(I − P_μ)·t̂ ≥ 1`: its maximum, rounded up (`None` if none found).
fn steps_bound(system: &SparseSystem, factor: &FloatFactor, s: &[u64]) -> Option<f64> {
    const K: f64 = 65536.0;
    let ones: Vec<f64> = s.iter().map(|&v| v as f64).collect();
    let t = factor.solve(&ones);
    let mut scale = 1.001;
    for _ in 0..4 {
        let hat: Option<Vec<i128>> = t
            .iter()
            .map(|&v| {
                let w = (v.max(0.0) * scale * K).ceil() + K;
                (w.is_finite() && w < 2f64.powi(60)).then_some(w as i128)
            })
            .collect();
        let hat = hat?;
        let ok = (0..system.len()).into_par_iter().all(|i| {
            let mut acc: i128 = 0;
            for (c, v) in system.row(i) {
                let Some(term) = hat[c].checked_mul(v as i128) else {
                    return false;
                };
                let Some(sum) = acc.checked_add(term) else {
                    return false;
                };
                acc = sum;
            }
            acc >= s[i] as i128 * K as i128
        });
        if ok {
            let max = hat.iter().copied().max().unwrap_or(0);
            return Some((max as f64 / K) * (1.0 + 1e-12) + 1.0);
        }
        scale *= 2.0;
    }
    None
}

/// `v` rounded to an integer, times `2^shift`.
fn scaled_integer(v: f64, shift: u64) -> BigInt {
    let r = BigInt::from_f64(v.round()).unwrap_or_default();
    r << shift
}

/// The refined evaluation of one policy.
struct Evaluation {
    /// `max |Rᵢ| / sᵢ`, rounded up, in units of `2^−B`.
    rho: f64,
}

/// Iterative refinement of `X` (scale `2^bits`) for `system` until the residual stops
/// shrinking; returns the residual bound.
fn refine(
    system: &SparseSystem,
    factor: &FloatFactor,
    x: &mut [BigInt],
    bits: u64,
    s: &[u64],
) -> Evaluation {
    let n = system.len();
    let mut previous = u64::MAX;
    let mut stalls = 0;
    loop {
        let residual: Vec<BigInt> = (0..n)
            .into_par_iter()
            .map(|i| {
                let mut r = BigInt::from(system.rhs(i)) << bits;
                for (c, v) in system.row(i) {
                    r -= &x[c] * v;
                }
                r
            })
            .collect();
        let m = residual.iter().map(|r| r.bits()).max().unwrap_or(0);
        let rho = residual
            .iter()
            .zip(s)
            .map(|(r, &si)| r.abs().to_f64().unwrap_or(f64::INFINITY) / si as f64)
            .fold(0.0f64, f64::max);
        if m <= FLOOR_BITS || stalls >= 3 {
            return Evaluation {
                rho: rho * (1.0 + 1e-9) + 1.0,
            };
        }
        if m + 4 > previous {
            stalls += 1;
        }
        previous = previous.min(m);
        let shift = m.saturating_sub(60);
        let r: Vec<f64> = residual
            .par_iter()
            .map(|r| (r >> shift).to_f64().unwrap_or(0.0))
            .collect();
        let delta = factor.solve(&r);
        x.par_iter_mut()
            .zip(delta.par_iter())
            .for_each(|(xi, &d)| *xi += scaled_integer(d, shift));
    }
}

/// What [`improve`] calls back: `build` gives the system of a policy (rows in the order of
/// `states`), `progress(policy, bits)` is told when an evaluation of the stage's `policy`-th
/// policy (from 1) at precision `bits` begins.
pub(crate) struct Hooks<'a> {
    pub build: &'a dyn Fn(&[Option<usize>]) -> Option<SparseSystem>,
    pub progress: &'a mut dyn FnMut(usize, u64),
}

/// Improves `policy` (proper, at every unknown `states[i]` an action) by mixed-precision
/// policy iteration (module docs). `cost[a]` is the action's scaled integer cost (`C·l`).
pub(crate) fn improve(
    problem: &StochasticProblem,
    safe: &[bool],
    states: &[usize],
    of: &[Option<usize>],
    cost: &[BigInt],
    policy: &mut [Option<usize>],
    hooks: Hooks<'_>,
) -> Refinement {
    let Hooks { build, progress } = hooks;
    let n = states.len();
    let s: Vec<u64> = states.iter().map(|&x| problem.denominator(x)).collect();
    let mut bits = START_BITS;
    let mut x: Vec<BigInt> = vec![BigInt::zero(); n];
    let mut out = Refinement::default();
    if n == 0 {
        out.resolved = true;
        return out;
    }
    'policies: while let Some(system) = build(policy) {
        let Ok(factor) = FloatFactor::new(&system) else {
            break;
        };
        let Some(t_max) = steps_bound(&system, &factor, &s) else {
            break;
        };
        let cap = (factor.log2_det.max(0.0).ceil() as u64)
            .saturating_add(64 + (2.0 * t_max).log2().ceil() as u64 + 64);
        // The unresolved states of the previous precision, and for how many doublings in a
        // row they have not changed.
        let mut last_unresolved: Vec<bool> = Vec::new();
        let mut stable = 0;
        loop {
            progress(out.rounds + 1, bits);
            let eval = refine(&system, &factor, &mut x, bits, &s);
            // Per state: the best certified improving action, and whether any is unresolved.
            let verdicts: Vec<(Option<usize>, bool)> = (0..n)
                .into_par_iter()
                .map(|i| {
                    let xs = states[i];
                    let si = s[i];
                    // |s·(Q − G)·2^B − D| ≤ 2·s·t̂·ρ (module docs); no bound, nothing certified.
                    let Some(margin) =
                        BigInt::from_f64((2.0 * si as f64 * t_max * eval.rho).ceil() + 1.0)
                    else {
                        let others = problem
                            .actions(xs)
                            .any(|a| safe[a] && Some(a) != policy[xs]);
                        return (None, others);
                    };
                    let current = &x[i] * si;
                    let mut best: Option<(BigInt, usize)> = None;
                    let mut unresolved = false;
                    for a in problem.actions(xs).filter(|&a| safe[a]) {
                        if Some(a) == policy[xs] {
                            continue;
                        }
                        let mut q = (&cost[a] * si) << bits;
                        for (o, &w) in problem.outcomes(a).iter().zip(problem.weights(a)) {
                            if let Some(j) = of[o.successor] {
                                q += &x[j] * w;
                            }
                        }
                        let d = q - &current;
                        if d.sign() == Sign::Minus && -&d > margin {
                            if best.as_ref().is_none_or(|(b, _)| &d < b) {
                                best = Some((d, a));
                            }
                        } else if d.abs() <= margin {
                            unresolved = true;
                        }
                    }
                    (best.map(|(_, a)| a), unresolved)
                })
                .collect();
            let mut switched = false;
            for (i, (a, _)) in verdicts.iter().enumerate() {
                if let Some(a) = a {
                    policy[states[i]] = Some(*a);
                    switched = true;
                }
            }
            out.bits = bits;
            if switched {
                out.rounds += 1;
                if out.rounds >= MAX_ROUNDS {
                    break 'policies;
                }
                continue 'policies;
            }
            let unresolved: Vec<bool> = verdicts.iter().map(|v| v.1).collect();
            if !unresolved.contains(&true) || bits >= cap {
                out.resolved = true;
                break 'policies;
            }
            if unresolved == last_unresolved {
                stable += 1;
            } else {
                stable = 0;
            }
            if stable >= STABLE_DOUBLINGS && bits >= PLATEAU_BITS {
                break 'policies;
            }
            last_unresolved = unresolved;
            let next = (bits * 2).min(cap);
            x.par_iter_mut().for_each(|v| *v <<= next - bits);
            bits = next;
        }
    }
    out
}

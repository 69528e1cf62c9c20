//! Claim C3: the dangers of discounting — truecost's certificate (`claims::c3::certificate`)
//! checked by its own discounted-policy oracle on symbolic structures.

use truecost_kernel::claims::c3::{
    certificate, goal_avoiding_core, goal_reachable, optimal_policy_avoids_goal,
};
use truecost_kernel::claims::exact::{ExactInt, Q};
use truecost_kernel::claims::tiny::Tiny;

use crate::symbolic::{any_tiny, TINY_STATES};

/// C3's statement for one concrete `alpha` on the problem `t`: a certificate only under the
/// hypotheses, under it the discount-optimal policy avoids the goal, and a certificate
/// whenever the hypotheses hold and its cost `K = ⌊1/((1−α) α²)⌋ + 1` (n = 4 states) fits a
/// `u8`.
fn check_at<I: ExactInt>(t: &Tiny, alpha: Q<I>, hypotheses: bool) {
    match certificate(t, alpha) {
        Some(c) => {
            kani::cover!(true, "a certificate exists");
            kani::assert(hypotheses, "a certificate only under the hypotheses");
            kani::assert(
                optimal_policy_avoids_goal(&c, alpha),
                "the discount-optimal policy avoids the goal",
            );
        }
        None => {
            // K <= 255 iff floor(bound) < 255 (bound > 0).
            let bound = Q::one() / ((Q::one() - alpha) * alpha * alpha);
            let fits = bound.numer().to_i128() / bound.denom().to_i128() < 255;
            kani::cover!(
                hypotheses && !fits,
                "the hypotheses hold but K does not fit"
            );
            kani::cover!(!hypotheses, "the hypotheses fail");
            kani::assert(!(hypotheses && fits), "a certificate whenever K fits");
        }
    }
}

/// On any 4-state problem (symbolic successors, 1–2 moves per non-goal state; the certificate
/// replaces the costs), at each of the discounts `α ∈ {1/16, 1/2, 2/3, 9/10}` (the product's
/// 1/2 and 9/10; 1/16, where `K = ⌊4096/15⌋ + 1 = 274` does not fit a `u8`; 2/3): when C3's
/// hypotheses hold (the goal is reachable from `x1`, and a goal-avoiding cycle is reachable:
/// `x1` in the goal-avoiding core), truecost's certificate exists whenever its cost `K` fits a
/// `u8`, and under it a discount-optimal policy from `x1` never reaches the goal (every
/// policy's exact discounted value compared). Domain 2^99 (the structure).
///
/// Widths: `α` is concrete, so `K` (9 at 1/2, 7 at 2/3, 13 at 9/10) and every `Q` operation
/// on `α` are constants. A policy's value `n/d` has `d = b^p (b^c − a^c) ≤ b^3 (b − a)` and
/// `|n| ≤ K d/(1 − α)`: at 1/2, `d ≤ 8`, `|n| ≤ 144`; at 2/3, `d ≤ 27`, `|n| ≤ 567`, so the
/// order's cross products stay below `567·27 = 15309` in `Q<i16>`; at 9/10, `d ≤ 1000`,
/// `|n| ≤ 13·(1000 + 900 + 810) = 35230` (a cycle's `≤ 130·271`), products below `2^26` in
/// `Q<i32>`. 1/16 runs at `Q<i16>` (`4096/15` fits; no certificate, so no oracle).
///
/// CBMC: at most 8 policies; trajectories of at most 4 stages; the certificate's lasso walk
/// and the goal-avoiding core's fixed point take at most 4 and 5 rounds. `lowest_terms` (the
/// extended Euclid loop of `Q`'s arithmetic) is replaced by its proven contract; its operands
/// here are concrete anyway (`α`'s arithmetic), the largest `(1000, 81)` (5 iterations), and
/// unwind 17 is Lamé's bound for operands below 1000 (`1 + 15 = 16`) plus one, in case Kani
/// runs the `Q<i32>` instance's loop instead of the contract. `kissat` for the symbolic
/// products of the oracle.
#[kani::proof]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(17)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c3_certificate_makes_discounting_avoid_the_goal() {
    let t = any_tiny(TINY_STATES);
    let hypotheses = goal_reachable(&t) && goal_avoiding_core(&t)[0];
    check_at(&t, Q::<i16>::ratio(1, 16), hypotheses);
    check_at(&t, Q::<i16>::ratio(1, 2), hypotheses);
    check_at(&t, Q::<i16>::ratio(2, 3), hypotheses);
    check_at(&t, Q::<i32>::ratio(9, 10), hypotheses);
}

/// The stationary policies of C3's worked example over states `0..5` (up or down at each).
pub const EXAMPLE_POLICIES: u32 = 1 << 5;

/// Small exhaustive variant (C3's worked example is one fixed problem and one parameter: a
/// harness over it is a finite check, enumerated completely by the stand-in). The worked example
/// at `α = k/32`, `k = 1..=31` (any `u8`, assumed in range; `α* ≈ 0.916` lies between 29/32 and
/// 30/32): the discount-optimal policy from 0 (over every stationary policy of states 0..4,
/// exact integer arithmetic) avoids the goal iff the printed inequality
/// `1/(1-α) < Σ_{i=1..5} i α^{i-1}` holds iff `5α⁴ − α³ − α² − α − 1 < 0`.
///
/// Width `i64`: a policy's value `num/den` has `den = 32^p (32^q − k^q) ≤ 32^5 = 2^25` and
/// `|num| < 2^29` (stage costs at most 5, value at most `5·32`), so the order's cross products
/// stay below `2^54`; the printed inequality's terms are below `2^25`. Only `k` is symbolic
/// (the policies, trajectories and powers of 32 are concrete), so CBMC multiplies symbolic
/// values only in `k^j` and the cross products. Unwind 34: the 32 policies (33), trajectories
/// of at most 6 steps, sums of at most 5 terms.
#[kani::proof]
#[kani::unwind(34)]
pub fn c3_example_sides_of_alpha_star_exhaustive_small() {
    let k: u8 = kani::any();
    kani::assume((1..=31).contains(&k));
    let (a, b) = (k as i64, 32i64);
    // Best avoiding policy and best reaching policy, over all 32 policies of states 0..4
    // (the goal terminates): trajectories from 0 are simple paths up then a bounce or a loop.
    let mut best: Option<(i64, i64, bool)> = None; // (numerator, denominator, reaches)
    for mask in 0u32..EXAMPLE_POLICIES {
        // bit x: state x moves up (+1) if set, else down (-1, clamped at 0).
        let mut seen = [usize::MAX; 6];
        let mut costs = [0i64; 6];
        let mut x = 0usize;
        let mut steps = 0usize;
        let (prefix, cycle_start, reaches) = loop {
            if x == 5 {
                break (steps, steps, true);
            }
            if seen[x] != usize::MAX {
                break (seen[x], seen[x], false);
            }
            seen[x] = steps;
            costs[steps] = x as i64 + 1;
            steps += 1;
            x = if mask >> x & 1 == 1 {
                x + 1
            } else {
                x.saturating_sub(1)
            };
        };
        let _ = prefix;
        // value = Σ_{j<p} c_j α^j + α^p (Σ_{j<q} c_{p+j} α^j)/(1 − α^q), p = cycle_start
        let p = cycle_start;
        let q = steps - cycle_start;
        let pw = |e: usize| -> (i64, i64) {
            let mut n = 1i64;
            let mut d = 1i64;
            for _ in 0..e {
                n *= a;
                d *= b;
            }
            (n, d)
        };
        let bp = pw(p).1;
        let head: i64 = (0..p).map(|j| costs[j] * pw(j).0 * pw(p - j).1).sum(); // / b^p
        let (num, den) = if reaches {
            (head, bp)
        } else {
            let (aq, bq) = pw(q);
            let cyc: i64 = (0..q).map(|j| costs[p + j] * pw(j).0 * pw(q - j).1).sum(); // / b^q
                                                                                       // head/b^p + a^p/b^p · cyc/b^q · b^q/(b^q − a^q)
            (head * (bq - aq) + pw(p).0 * cyc, bp * (bq - aq))
        };
        best = match best {
            Some((n, d, r)) if n * den <= num * d => Some((n, d, r)),
            _ => Some((num, den, reaches)),
        };
    }
    let (_, _, optimal_reaches) = best.expect("32 policies");
    // Printed inequality ×32^4·(32−k): 32^5 < (32−k) Σ i k^{i−1} 32^{5−i}.
    let sum: i64 = (1..=5)
        .map(|i: u32| i as i64 * a.pow(i - 1) * b.pow(5 - i))
        .sum();
    let printed = b.pow(5) < (b - a) * sum;
    let p_negative = 5 * a.pow(4) - a.pow(3) * b - a * a * b * b - a * b.pow(3) - b.pow(4) < 0;
    kani::cover!(printed, "alpha below alpha*: the optimum avoids the goal");
    kani::cover!(!printed, "alpha above alpha*: the optimum reaches the goal");
    kani::assert(printed == p_negative, "printed inequality iff P(alpha) < 0");
    kani::assert(
        printed != optimal_reaches,
        "the optimum avoids the goal iff the inequality holds",
    );
}

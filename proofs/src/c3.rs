//! Claim C3: the dangers of discounting — truecost's certificate (`claims::c3::certificate`)
//! checked by its own discounted-policy oracle on symbolic structures.

use truecost_kernel::claims::c3::{
    certificate, goal_avoiding_core, goal_reachable, optimal_policy_avoids_goal,
};
use truecost_kernel::claims::exact::Q;

use crate::symbolic::{any_tiny, TINY_STATES};

/// On any 4-state problem (symbolic successors, 1–2 moves per non-goal state; the certificate
/// replaces the costs) and any discount `α = k/256`, `k ∈ 1..=255`: when C3's hypotheses hold
/// (the goal is reachable from `x1`, and a goal-avoiding cycle is reachable: `x1` in the
/// goal-avoiding core), truecost's certificate exists whenever its cost `K` fits a `u8`, and
/// under it a discount-optimal policy from `x1` never reaches the goal (every policy's exact
/// discounted value compared). Domain 2^107 (structure 2^99 × α 2^8). CBMC: at most 8
/// policies, trajectories of at most 4 stages; the `Q` arithmetic (on `α` alone) runs Euclid's
/// loop in `Q::new` on operands below `256^3 = 2^24`, at most 36 iterations by Lamé's theorem
/// (`tests/unwind_bounds.rs`): unwind 37.
#[kani::proof]
#[kani::unwind(37)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c3_certificate_makes_discounting_avoid_the_goal() {
    let t = any_tiny(TINY_STATES);
    let k = kani::any::<u8>();
    kani::assume(k > 0);
    let alpha = Q::new(k as i128, 256);
    let hypotheses = goal_reachable(&t) && goal_avoiding_core(&t)[0];
    match certificate(&t, alpha) {
        Some(c) => {
            kani::assert(hypotheses, "a certificate only under the hypotheses");
            kani::assert(
                optimal_policy_avoids_goal(&c, alpha),
                "the discount-optimal policy avoids the goal",
            );
        }
        None => {
            // K = floor(1/((1-α) α^2)) + 1 must then exceed 255 (n = 4 states): K <= 255 iff
            // floor(...) < 255.
            let bound = Q::ONE / ((Q::ONE - alpha) * alpha * alpha);
            let fits = bound.numer() / bound.denom() < 255;
            kani::assert(!(hypotheses && fits), "a certificate whenever K fits");
        }
    }
}

/// The stationary policies of C3's worked example over states `0..5` (up or down at each).
pub const EXAMPLE_POLICIES: u32 = 1 << 5;

/// Small exhaustive variant (C3's worked example is one fixed problem and one parameter: a
/// harness over it is a finite check, enumerated completely by the stand-in). The worked example
/// at `α = k/64`, `k = 1..=63` (any `u8`, assumed in range): the discount-optimal policy from 0 (over
/// every stationary policy of states 0..4, exact integer arithmetic) avoids the goal iff the
/// printed inequality `1/(1-α) < Σ_{i=1..5} i α^{i-1}` holds iff `5α⁴ − α³ − α² − α − 1 < 0`.
#[kani::proof]
#[kani::unwind(34)]
pub fn c3_example_sides_of_alpha_star_exhaustive_small() {
    let k: u8 = kani::any();
    kani::assume((1..=63).contains(&k));
    let (a, b) = (k as i128, 64i128);
    // Best avoiding policy and best reaching policy, over all 32 policies of states 0..4
    // (the goal terminates): trajectories from 0 are simple paths up then a bounce or a loop.
    let mut best: Option<(i128, i128, bool)> = None; // (numerator, denominator, reaches)
    for mask in 0u32..EXAMPLE_POLICIES {
        // bit x: state x moves up (+1) if set, else down (-1, clamped at 0).
        let mut seen = [usize::MAX; 6];
        let mut costs = [0i128; 6];
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
            costs[steps] = x as i128 + 1;
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
        let pw = |e: usize| -> (i128, i128) {
            let mut n = 1i128;
            let mut d = 1i128;
            for _ in 0..e {
                n *= a;
                d *= b;
            }
            (n, d)
        };
        let bp = pw(p).1;
        let head: i128 = (0..p).map(|j| costs[j] * pw(j).0 * pw(p - j).1).sum(); // / b^p
        let (num, den) = if reaches {
            (head, bp)
        } else {
            let (aq, bq) = pw(q);
            let cyc: i128 = (0..q).map(|j| costs[p + j] * pw(j).0 * pw(q - j).1).sum(); // / b^q
                                                                                        // head/b^p + a^p/b^p · cyc/b^q · b^q/(b^q − a^q)
            (head * (bq - aq) + pw(p).0 * cyc, bp * (bq - aq))
        };
        best = match best {
            Some((n, d, r)) if n * den <= num * d => Some((n, d, r)),
            _ => Some((num, den, reaches)),
        };
    }
    let (_, _, optimal_reaches) = best.expect("32 policies");
    // Printed inequality ×64^4·(64−k): 64^5 < (64−k) Σ i k^{i−1} 64^{5−i}.
    let sum: i128 = (1..=5)
        .map(|i: u32| i as i128 * a.pow(i - 1) * b.pow(5 - i))
        .sum();
    let printed = b.pow(5) < (b - a) * sum;
    let p_negative = 5 * a.pow(4) - a.pow(3) * b - a * a * b * b - a * b.pow(3) - b.pow(4) < 0;
    kani::assert(printed == p_negative, "printed inequality iff P(alpha) < 0");
    kani::assert(
        printed != optimal_reaches,
        "the optimum avoids the goal iff the inequality holds",
    );
}

//! Claim C3: the dangers of discounting (general form and the worked example).

/// 0, 1 or the goal 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq, kani::Arbitrary)]
pub enum Target {
    /// State 0.
    Zero,
    /// State 1.
    One,
    /// The goal.
    Goal,
}

/// Every 3-state structure in which state 0 has a self-loop (a goal-avoiding cycle) and a move
/// to 1 or the goal, and state 1 one move anywhere: when the goal is reachable, the certificate
/// (cost 1 on the self-loop, `K = 2^(n-1) + 1 = 5` elsewhere, `α = 1/2`) makes a
/// discount-optimal policy from 0 avoid the goal. Values are scaled by 2 (exact integers).
#[kani::proof]
#[kani::unwind(8)]
pub fn c3_certificate_makes_the_discount_optimal_policy_avoid_the_goal() {
    let first: bool = kani::any(); // state 0's second move: to 1 (false) or to the goal (true)
    let from1: Target = kani::any();
    let reachable = first || from1 == Target::Goal;
    if !reachable {
        return; // hypothesis fails: nothing to check
    }
    let k = 5i64;
    // Value ×2 of "stay at 0": Σ 1/2^j = 2 → 4.
    let stay = 4i64;
    // Value ×2 of the second move at 0 followed by the best continuation:
    let second = if first {
        2 * k // K then terminate
    } else {
        // K, then from 1 (discounted by 1/2): from 1 the only move costs K and goes to from1.
        let after = match from1 {
            Target::Goal => 2 * k,
            // back to 0, where staying is the best (value ×2 = 4) or the loop 0→1→0...: ≥ 2K
            Target::Zero => 2 * k + stay / 2,
            Target::One => 4 * k, // 1 loops on itself: K forever = 2K (×2 = 4K)
        };
        2 * k + after / 2
    };
    kani::assert(
        stay < second,
        "the goal-avoiding self-loop is strictly discount-optimal",
    );
}

/// The worked example at `α = k/64`, `k = 1..=63`: the discount-optimal policy from 0 (over
/// every stationary policy of states 0..4, exact integer arithmetic) avoids the goal iff the
/// printed inequality `1/(1-α) < Σ_{i=1..5} i α^{i-1}` holds iff `5α⁴ − α³ − α² − α − 1 < 0`.
#[kani::proof]
#[kani::unwind(34)]
pub fn c3_example_sides_of_alpha_star() {
    let k: u8 = kani::any();
    kani::assume((1..=63).contains(&k));
    let (a, b) = (k as i128, 64i128);
    // Best avoiding policy and best reaching policy, over all 32 policies of states 0..4
    // (the goal terminates): trajectories from 0 are simple paths up then a bounce or a loop.
    let mut best: Option<(i128, i128, bool)> = None; // (numerator, denominator, reaches)
    for mask in 0u32..32 {
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

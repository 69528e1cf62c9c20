//! Claim C2: cost–reward equivalence, over truecost's own policy-enumeration oracle
//! (`claims::oracle`, `claims::c2::check_problem`).

use truecost_kernel::claims::c2::{check_problem, functionals};

use crate::symbolic::{any_tiny, TINY_STATES};

/// On any 4-state problem (3 non-goal states with 1–2 moves each, symbolic successors, any `u8`
/// costs) and for each of C2's seven functionals (total, discounted 1/2 and 9/10, average,
/// 3-stage total, 3-stage discounted, 4-stage average), truecost's oracle finds the policies
/// minimising the cost from `x1` to be exactly those maximising the reward `−l`. Kani also
/// checks the oracle's exact `i128` arithmetic for overflow at every cost up to 255. Domain
/// 2^99. CBMC: at most 8 policies, trajectories of at most 4 stages; loops bounded by 8.
#[kani::proof]
#[kani::unwind(9)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c2_oracle_argmin_cost_is_argmax_reward() {
    let t = any_tiny(TINY_STATES);
    let (failure, comparisons) = check_problem(&t, &functionals(), 1);
    kani::assert(comparisons == 7, "every functional compared");
    kani::assert(failure.is_none(), "argmin cost = argmax reward");
}

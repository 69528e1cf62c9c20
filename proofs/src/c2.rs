//! Claim C2: cost–reward equivalence, over truecost's own policy-enumeration oracle
//! (`claims::oracle`, `claims::c2::optimisers`, the per-functional step of
//! `claims::c2::check_problem`), instantiated at small widths (`Q<i16>`, `Q<i32>`).

use truecost_kernel::claims::c2::optimisers;
use truecost_kernel::claims::exact::{ExactInt, Q};
use truecost_kernel::claims::oracle::{policies, trajectory, Functional, Trajectory};

use crate::symbolic::{any_tiny, TINY_STATES};

/// Cost minimisers = reward maximisers under `f` (the oracle's argmin and argmax masks).
fn check<I: ExactInt>(trs: &[Trajectory], f: Functional<I>) {
    let (argmin, argmax) = optimisers(trs, f);
    kani::cover!(argmin.count_ones() >= 2, "several cost-minimising policies");
    kani::cover!(
        argmin.count_ones() == 1 && trs.len() >= 2,
        "a unique minimiser among several policies"
    );
    kani::assert(argmin == argmax, "argmin cost = argmax reward");
}

/// On any 4-state problem (3 non-goal states with 1–2 moves each, symbolic successors, any `u8`
/// costs) and for each of C2's seven functionals (total, discounted 1/2 and 9/10, average,
/// 3-stage total, 3-stage discounted 1/2, 4-stage average), truecost's oracle finds the
/// policies minimising the cost from `x1` to be exactly those maximising the reward `−l`.
/// Kani also checks the oracle's exact arithmetic for overflow at every cost up to `C = 255`.
/// Domain 2^99.
///
/// Widths. A trajectory from `x1` has a prefix of `p` and a cycle of `c` stages with
/// `p + c ≤ 4` (3 non-goal moves, then possibly the goal's frozen zero stage), and a value's
/// fraction has `|n| ≤ value · d`. The six functionals with denominators 1, 2, 3 or 4 run at
/// `Q<i16>`: the largest cross-multiplication (`Frac`'s order) is discounted 1/2, where
/// `d = 2^p (2^c − 1) ≤ 8` and the value is at most `2C`, so `|n1·d2| ≤ 2C·8·8 = 128·255 =
/// 32640 ≤ 32767`; the others are smaller (3-stage discounted: `n ≤ 7C`, `d = 4`; averages:
/// `n ≤ 4C`, `d ≤ 4`; totals: `n ≤ 3C`). Discounted 9/10 runs at `Q<i32>`: `d = 10^p (10^c −
/// 9^c) ≤ 1000` (terminating after 3 moves; a cycle's `d ≤ 10^3 − 9^3 = 271`) and `|n| ≤
/// C·(1000 + 900 + 810) = 2710C` (a cycle's `|n| ≤ 10C·271`), so `|n1·d2| ≤ 2710·255·1000 <
/// 2^30`.
///
/// CBMC: at most 8 policies and 7 functionals; trajectories of at most 4 stages; the `Q`
/// constants (1/2, 9/10) are concrete, and `lowest_terms` (the one loop of `Q`'s arithmetic)
/// is replaced by its proven contract, so no Euclid loop runs: the largest loop is the 8
/// policies (unwind 9; the extended Euclid loop on the constants' operands, at most 10, would
/// take at most 6 iterations by Lamé's theorem, were it run). `kissat` for the symbolic
/// products.
#[kani::proof]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(9)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c2_oracle_argmin_cost_is_argmax_reward() {
    let t = any_tiny(TINY_STATES);
    let ps = policies(&t, true);
    let trs: Vec<Trajectory> = ps.iter().map(|p| trajectory(&t, p, 0)).collect();
    kani::cover!(trs.len() == 8, "8 policies");
    let half = Q::<i16>::ratio(1, 2);
    for f in [
        Functional::Total,
        Functional::Discounted(half),
        Functional::Average,
        Functional::HorizonTotal(3),
        Functional::HorizonDiscounted(3, half),
        Functional::HorizonAverage(4),
    ] {
        check(&trs, f);
    }
    check(&trs, Functional::Discounted(Q::<i32>::ratio(9, 10)));
}

//! Claim C4: episodic equivalence (average cost with a reset bonus `M < 0`), over truecost's
//! own policy-enumeration oracle (`claims::c4::bonus_sets`: exact averages of every policy).

use truecost_kernel::claims::c4::{bonus_sets, Instance};
use truecost_kernel::claims::exact::Q;

use crate::symbolic::{any_tiny, TINY_STATES};

fn any_bonus() -> Q {
    // M = -(n + 1)/(d + 1): every negative rational with numerator ≤ 2^16 and denominator ≤ 2^8.
    let n = kani::any::<u16>() as i128 + 1;
    let d = kani::any::<u8>() as i128 + 1;
    Q::new(-n, d)
}

/// **C4-corrected** on any 4-state problem (`x1 = 0`, goal 3, 1–2 moves per state, symbolic
/// successors, any `u8` costs) with a goal path, for every distinct `S*`, at any bonus
/// `M = −n/d` (`n ≤ 2^16`, `d ≤ 2^8`): `π*` is average-cost optimal (policy-enumeration oracle)
/// iff `M` lies in the corrected set, and the two sets are equal as sets. Domain 2^123.
/// CBMC: at most 8 policies and goal paths of at most 3 moves; Euclid's loop in `Q::new` runs
/// on operands of at most `4·(4·3·255) = 12240` (the printed formula's `S*·L(u)` scaled by `S`)
/// or, for `M`, below `2^8`: at most 21 iterations by Lamé's theorem (`tests/unwind_bounds.rs`;
/// `M = −144/233` alone takes 12): unwind 22.
#[kani::proof]
#[kani::unwind(22)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c4_corrected_set_is_the_oracles() {
    let t = any_tiny(TINY_STATES);
    let m = any_bonus();
    let sets = bonus_sets(&Instance::from_tiny(&t), 1 << 12).expect("Karp agrees with policies");
    let Some(sets) = sets else {
        kani::assume(false); // no goal path: the claim says nothing
        return;
    };
    for s in &sets {
        kani::assert(
            s.exact.same_set(&s.corrected),
            "corrected set = oracle's set",
        );
        kani::assert(
            s.exact.contains(m) == s.corrected.contains(m),
            "pi* optimal at M iff M in the corrected set",
        );
    }
}

/// **C4 as printed** over the same domain: wherever the printed formula is defined, `π*` is
/// average-cost optimal iff `a ≤ M ≤ min{b, S*·Lav(Ĉ) − L*}`. Must fail (the printed `A(u)`
/// does not scale with the costs). Domain 2^123. Unwind 22, as for the corrected set.
#[kani::proof]
#[kani::unwind(22)]
#[kani::solver(kissat)]
#[kani::should_panic]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c4_as_printed_set_is_the_oracles() {
    let t = any_tiny(TINY_STATES);
    let m = any_bonus();
    let sets = bonus_sets(&Instance::from_tiny(&t), 1 << 12).expect("Karp agrees with policies");
    let Some(sets) = sets else {
        kani::assume(false);
        return;
    };
    for s in &sets {
        if let Some(printed) = s.printed {
            kani::assert(
                s.exact.contains(m) == printed.contains(m),
                "pi* optimal at M iff M in the printed set",
            );
        }
    }
}

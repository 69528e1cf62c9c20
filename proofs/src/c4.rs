//! Claim C4: episodic equivalence (average cost with a reset bonus `M < 0`), over truecost's
//! own policy-enumeration oracle (`claims::c4::bonus_analysis_in`: exact averages of every
//! policy), instantiated at `Q<i16>`.

use truecost_kernel::claims::c4::{bonus_analysis_in, BonusSets, Instance};
use truecost_kernel::claims::exact::Q;
use truecost_kernel::claims::tiny::{Tiny, TinyMove};

use crate::symbolic::{any_tiny, TINY_STATES};

/// The bonus sets of `t` at `Q<i16>` (`printed`: with the printed formula's set). Prunes the
/// problems without a goal path (the claim says nothing about them).
fn bonus_sets_i16(t: &Tiny, printed: bool) -> Vec<BonusSets<i16>> {
    let r = bonus_analysis_in::<i16>(&Instance::from_tiny(t), 1 << 12, printed);
    kani::assert(
        r.is_ok(),
        "Karp agrees with the policies, within the effort bounds",
    );
    let Ok(Some(sets)) = r else {
        kani::assume(false); // no goal path
        unreachable!()
    };
    sets
}

/// `M = −n/d`, `n ∈ 1..=2^12`, `d ∈ 1..=8` (every end of the corrected and exact sets has a
/// denominator at most 4).
fn any_bonus_corrected() -> Q<i16> {
    let n = (kani::any::<u16>() >> 4) as i16 + 1;
    let d = (kani::any::<u8>() >> 5) as i16 + 1;
    Q::ratio(-n, d)
}

/// **C4-corrected** on any 4-state problem (`x1 = 0`, goal 3, 1–2 moves per state, symbolic
/// successors, any `u8` costs, `C = 255`) with a goal path, for every distinct `S*`, at any
/// bonus `M = −n/d` (`n ≤ 2^12`, `d ≤ 8`): `π*` is average-cost optimal (policy-enumeration
/// oracle) iff `M` lies in the corrected set, and the two sets are equal as sets. Domain
/// 2^123.
///
/// Widths (`Q<i16>`, max 32767; the printed formula is not computed here): a goal path has
/// `L ≤ 3C = 765` and `S ∈ 2..=4` states; an exact end is `(c·S* − L*·k)/(k − r·S*)` with
/// `|numerator| ≤ 4·765 = 3060` and `|denominator| ≤ 4`; a corrected end is
/// `(S*·L(u) − S(u)·L*)/(S(u) − S*)`, `|numerator| ≤ 3060`, `|denominator| ≤ 2`; the cycle
/// bound `S*·Lav − L*` has `|numerator| ≤ 3060`, denominator `≤ 3`; Karp's means are at most
/// `4C = 1020` over at most 4. So the order's cross products are at most `3060·4 = 12240`, and
/// with `M`: `2^12·4 = 16384`, `3060·8 = 24480`.
///
/// CBMC: at most 8 policies, goal paths of at most 3 moves (at most 8 of them), walks of at
/// most 4 arcs in Karp's algorithm. `lowest_terms` (the extended Euclid loop of every `Q`
/// operation) is replaced by its proven contract, so no Euclid loop runs (were it run, its
/// operands' smaller magnitude is a denominator at most 8 (`M`) or 4 (every other end, mean
/// and bound): by Lamé's theorem at most `1 + 5 = 6` iterations). The largest loop is the
/// enumeration of the 8 policies: unwind 9.
#[kani::proof]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(9)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c4_corrected_set_is_the_oracles() {
    let t = any_tiny(TINY_STATES);
    let m = any_bonus_corrected();
    let sets = bonus_sets_i16(&t, false);
    kani::cover!(sets.len() >= 2, "several optimal paths with distinct S*");
    for s in &sets {
        kani::cover!(s.exact.empty, "pi* is never optimal");
        kani::cover!(s.exact.contains(m), "M inside the corrected set");
        kani::cover!(
            !s.exact.empty && !s.exact.contains(m),
            "M outside a non-empty corrected set"
        );
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

/// The largest stage cost of `any_small_tiny`.
pub const PRINTED_MAX_COST: u8 = 5;

/// Any 4-state problem as [`any_tiny`] builds it, with costs in `0..=PRINTED_MAX_COST`.
fn any_small_tiny() -> Tiny {
    let mut t = any_tiny(TINY_STATES);
    for x in 0..TINY_STATES - 1 {
        for k in 0..t.deg[x] as usize {
            let TinyMove { to, cost } = t.moves[x][k];
            t.moves[x][k] = TinyMove {
                to,
                cost: cost % (PRINTED_MAX_COST + 1),
            };
        }
    }
    t
}

/// **C4 as printed**: on any 4-state problem (`x1 = 0`, goal 3, 1–2 moves per state, symbolic
/// successors, costs `0..=5`) with a goal path, at any bonus `M = −n/d` (`n, d ∈ 1..=128`),
/// wherever the printed formula is defined, `π*` is average-cost optimal iff
/// `a ≤ M ≤ min{b, S*·Lav(Ĉ) − L*}`. Must fail (the printed `A(u)` does not scale with the
/// costs). Domain 2^115.
///
/// Widths (`Q<i16>`, `C = 5`): `S(u)·L*/(S*·L(u))` has terms at most `4·3C = 60`, minus 1 at
/// most 60 in magnitude over at most 60; times `1 − S(u)/S* = (S* − S(u))/S*`
/// (`|S* − S(u)| ≤ 2`, `S* ≤ 4`): `A(u)` has `|numerator| ≤ 120`, denominator `≤ 240`. The
/// order's largest cross products: `120·240 = 28800` between two `A(u)`; with `M`:
/// `128·240 = 30720`, `120·128 = 15360`; the exact and corrected ends are smaller
/// (`|numerator| ≤ 60`, denominator `≤ 4`).
///
/// CBMC: `lowest_terms` (the extended Euclid loop of every `Q` operation) is replaced by its
/// proven contract, so no Euclid loop runs (its operands' smaller magnitude would be at most
/// 128 (`M`), 120 or 60 (`A(u)`'s terms), or a denominator at most 4); the largest loop is the
/// enumeration of the 8 policies, as in C4-corrected: unwind 9.
#[kani::proof]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(9)]
#[kani::solver(kissat)]
#[kani::should_panic]
#[cfg_attr(not(kani), kani::samples(4000))]
pub fn c4_as_printed_set_is_the_oracles() {
    let t = any_small_tiny();
    let n = (kani::any::<u8>() >> 1) as i16 + 1;
    let d = (kani::any::<u8>() >> 1) as i16 + 1;
    let m = Q::<i16>::ratio(-n, d);
    let sets = bonus_sets_i16(&t, true);
    for s in &sets {
        kani::cover!(
            s.printed.is_none(),
            "the printed formula undefined (L(u) = 0)"
        );
        if let Some(printed) = s.printed {
            kani::cover!(s.exact.contains(m) && printed.contains(m), "M in both sets");
            kani::cover!(
                !s.exact.same_set(&printed),
                "the printed set differs from the oracle's"
            );
            kani::assert(
                s.exact.contains(m) == printed.contains(m),
                "pi* optimal at M iff M in the printed set",
            );
        }
    }
}

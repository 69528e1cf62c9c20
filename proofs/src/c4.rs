//! Claim C4: episodic equivalence (average cost with a reset bonus `M < 0`).

use crate::Four;

/// The printed formula on a fixed problem with costs scaled by `k ∈ 1..=4`: `x1 → 1` (cost 0),
/// `x1 → goal` (cost `k`), `1 → goal` (cost 0). `π*` goes through 1 (`S* = 3`, `L* = 0`); the
/// other path has `S = 2`, `L = k`. The true lower threshold on `M` is where
/// `(0 + M)/3 = (k + M)/2`, i.e. `M = −3k`; the printed `a = A(u) = (1 − 2/3)(2·0/(3k) − 1) =
/// −1/3` does not scale. Must fail.
#[kani::proof]
#[kani::unwind(8)]
#[kani::should_panic]
pub fn c4_printed_formula_fails() {
    let k = kani::any::<Four>().value() + 1;
    // Thresholds as fractions n/d.
    let (true_n, true_d) = (-3 * k, 1i64);
    let (printed_n, printed_d) = (-1i64, 3i64);
    kani::assert(
        true_n * printed_d == printed_n * true_d,
        "printed a equals the true threshold",
    );
}

/// For `x1 → goal` (cost `d`) and `x1 → 1 → goal` (costs `e1`, `e2`), all in `0..=3`, and every
/// bonus `M ∈ −8..=−1`: `π*` (the cheaper path; the direct one on ties) has the least average
/// cost `(L + M)/S` iff the corrected threshold `T(u) = (S*·L(u) − S(u)·L*)/(S(u) − S*)` says so.
#[kani::proof]
#[kani::unwind(10)]
pub fn c4_corrected_threshold_matches_averages() {
    let d = kani::any::<Four>().value();
    let e = kani::any::<Four>().value() + kani::any::<Four>().value();
    let (lstar, sstar, l, s) = if d <= e {
        (d, 2i64, e, 3i64)
    } else {
        (e, 3, d, 2)
    };
    for m in -8i64..=-1 {
        // Oracle: (L* + M)/S* <= (L + M)/S, cross-multiplied (S, S* > 0).
        let oracle = (lstar + m) * s <= (l + m) * sstar;
        // Corrected: M >= T if S < S*, M <= T if S > S*; T = (S*·L − S·L*)/(S − S*).
        let (tn, td) = (sstar * l - s * lstar, s - sstar);
        // S > S* (td > 0): M <= tn/td ⇔ M·td <= tn; S < S* (td < 0): M >= tn/td ⇔ M·td <= tn.
        let formula = m * td <= tn;
        kani::assert(oracle == formula, "corrected threshold = oracle");
    }
}

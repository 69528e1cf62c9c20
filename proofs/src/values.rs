//! The exact value types' checked arithmetic: `value::Units` (the planners' fast exact type)
//! and `claims::exact::Q` (the oracles' rationals, generic over the integer width: `i128` in
//! the product, `i16` here). Never a silent wrap: every sum that fits is exact, every overflow
//! is reported (`None` or a panic, never a wrong number).

use truecost_kernel::claims::exact::Q;
use truecost_kernel::value::{CostValue, Units};

/// `Units::plus` on any two `u64` values (`u64::MAX` is `+∞`): `+∞` absorbs, and a finite sum
/// below `u64::MAX` is the exact sum. Domain 2^128. No loop, no multiplication.
#[kani::proof]
pub fn units_plus_is_exact_when_it_fits() {
    let (a, b): (u64, u64) = (kani::any(), kani::any());
    let exact = a as u128 + b as u128;
    kani::assume(a == u64::MAX || b == u64::MAX || exact < u64::MAX as u128);
    let s = Units(a).plus(&Units(b));
    kani::cover!(a == u64::MAX || b == u64::MAX, "+inf absorbs");
    kani::cover!(a != u64::MAX && b != u64::MAX, "a finite sum that fits");
    if a == u64::MAX || b == u64::MAX {
        kani::assert(!s.is_finite(), "+inf absorbs");
    } else {
        kani::assert(s.0 as u128 == exact, "the exact sum");
        kani::assert(s.is_finite(), "a sum below u64::MAX is finite");
    }
}

/// Every overflow is reported, as a universal statement over any two `u64` values `a`, `b`
/// (`u64::MAX` is `+∞`): `Units::checked_plus` is `None` exactly when both are finite and
/// `a + b ≥ u64::MAX` (the sum does not fit: it would wrap, or read as `+∞`); otherwise it is
/// `+∞` if either is, else the exact sum, and `Units::plus` (which panics on `None`) returns
/// the same value. Domain 2^128. No loop, no multiplication.
#[kani::proof]
pub fn units_plus_reports_every_overflow() {
    let (a, b): (u64, u64) = (kani::any(), kani::any());
    let infinite = a == u64::MAX || b == u64::MAX;
    let exact = a as u128 + b as u128;
    let fits = infinite || exact < u64::MAX as u128;
    let checked = Units(a).checked_plus(&Units(b));
    kani::cover!(!fits, "a finite sum that does not fit is reported");
    kani::cover!(
        !fits && exact > u64::MAX as u128,
        "a sum that would wrap is reported"
    );
    kani::cover!(fits && !infinite, "a finite sum that fits");
    kani::cover!(infinite, "+inf absorbs");
    kani::assert(
        checked.is_some() == fits,
        "None exactly when a finite sum does not fit",
    );
    if let Some(s) = checked {
        if infinite {
            kani::assert(!s.is_finite(), "+inf absorbs");
        } else {
            kani::assert(s.is_finite() && s.0 as u128 == exact, "the exact sum");
        }
        kani::assert(s == Units(a).plus(&Units(b)), "plus agrees where it fits");
    }
}

/// `Q<i16>` addition and multiplication on any fractions `n1/d1`, `n2/d2` with numerators and
/// denominators in `[-127, 127]` (any `i8` but `-128`; denominators non-zero): the result is
/// normalised (positive denominator, coprime parts) and equals the exact value, checked by
/// cross-multiplication in `i32`. Domain 2^32.
///
/// No intermediate overflows `i16` (max 32767): a sum forms `n1·d2 + n2·d1`, at most
/// `2·127² = 32258`, and `d1·d2 ≤ 127² = 16129`; a product forms `(n1/g1)(n2/g2)` and
/// `(d1/g2)(d2/g1)`, at most `127² = 16129`. The check's products are at most
/// `32258 · 16129 < 2^30` in `i32`.
///
/// CBMC: the subject is `Q`'s arithmetic, not Euclid's loop: `lowest_terms` (which `Q::ratio`
/// and the cross-cancelling call) is replaced by its proven contract
/// (`contracts::lowest_terms_has_a_bezout_witness`), so no loop runs but the two results'
/// check (unwind 3). "Normalised" is checked without a loop of its own: `Q::ratio` of the
/// result's parts is the result itself (the reduction of a fraction in lowest terms with a
/// positive denominator changes nothing, and of any other fraction changes it). `kissat` for
/// the 16-bit multiplications and divisions.
#[kani::proof]
#[kani::stub_verified(truecost_kernel::claims::exact::lowest_terms)]
#[kani::unwind(3)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(20000))]
pub fn rational_add_and_mul_are_exact() {
    let n1 = kani::any_where(|v: &i8| *v != i8::MIN) as i16;
    let d1 = kani::any_where(|v: &i8| *v != i8::MIN && *v != 0) as i16;
    let n2 = kani::any_where(|v: &i8| *v != i8::MIN) as i16;
    let d2 = kani::any_where(|v: &i8| *v != i8::MIN && *v != 0) as i16;
    let (a, b) = (Q::<i16>::ratio(n1, d1), Q::<i16>::ratio(n2, d2));
    let sum = a + b;
    let product = a * b;
    kani::cover!(sum.is_zero(), "a zero sum");
    kani::cover!(
        sum.denom() < (d1 as i32 * d2 as i32).abs() as i16,
        "a sum that reduces"
    );
    kani::cover!(product.signum() < 0, "a negative product");
    kani::cover!(d1 < 0 && d2 < 0, "two negative denominators");
    // Exact: sum = (n1 d2 + n2 d1)/(d1 d2), product = n1 n2/(d1 d2), in i32.
    let (n1, d1, n2, d2) = (n1 as i32, d1 as i32, n2 as i32, d2 as i32);
    for (r, num) in [(sum, n1 * d2 + n2 * d1), (product, n1 * n2)] {
        kani::assert(r.denom() > 0, "positive denominator");
        kani::assert(
            r.numer() as i32 * (d1 * d2) == num * r.denom() as i32,
            "the exact value",
        );
        let again = Q::<i16>::ratio(r.numer(), r.denom());
        kani::assert(
            again.numer() == r.numer() && again.denom() == r.denom(),
            "normalised",
        );
    }
}

//! The exact value types' checked arithmetic: `value::Units` (the planners' fast exact type)
//! and `claims::exact::Q` (the oracles' `i128` rationals). Never a silent wrap: every sum that
//! fits is exact, every overflow is reported (a panic, never a wrong number).

use truecost_kernel::claims::exact::Q;
use truecost_kernel::value::{CostValue, Units};

/// `Units::plus` on any two `u64` values (`u64::MAX` is `+∞`): `+∞` absorbs, and a finite sum
/// below `u64::MAX` is the exact sum. Domain 2^128.
#[kani::proof]
pub fn units_plus_is_exact_when_it_fits() {
    let (a, b): (u64, u64) = (kani::any(), kani::any());
    let exact = a as u128 + b as u128;
    kani::assume(a == u64::MAX || b == u64::MAX || exact < u64::MAX as u128);
    let s = Units(a).plus(&Units(b));
    if a == u64::MAX || b == u64::MAX {
        kani::assert(!s.is_finite(), "+inf absorbs");
    } else {
        kani::assert(s.0 as u128 == exact, "the exact sum");
        kani::assert(s.is_finite(), "a sum below u64::MAX is finite");
    }
}

/// `Units::plus` on two finite values whose sum does not fit (`≥ u64::MAX`, which would read as
/// `+∞`): the addition must report it (panic) rather than wrap or saturate. Must fail on every
/// execution (the stand-in's test checks that all of them fail). Domain 2^128.
#[kani::proof]
#[kani::should_panic]
pub fn units_plus_reports_every_overflow() {
    let (a, b): (u64, u64) = (kani::any(), kani::any());
    let finite = a != u64::MAX && b != u64::MAX;
    let a = if finite { a.max(1) } else { u64::MAX - 1 };
    let b = if finite { b } else { u64::MAX - 1 };
    // Map every pair to a finite one whose sum does not fit: (a ≥ 1, max(b, u64::MAX - a)).
    let b = b.max(u64::MAX - a);
    let _ = Units(a).plus(&Units(b));
}

/// `Q` addition and multiplication on any `i32` fractions (denominators non-zero): the result
/// is normalised (`gcd = 1`, positive denominator) and equals the exact value, checked by
/// cross-multiplication in `i128` (every product fits). Domain 2^128. CBMC: Euclid's loop runs
/// at most 93 times on values below 2^64 (unwind 100); `kissat` for the multiplications.
#[kani::proof]
#[kani::unwind(100)]
#[kani::solver(kissat)]
#[cfg_attr(not(kani), kani::samples(20000))]
pub fn rational_add_and_mul_are_exact() {
    let (n1, d1, n2, d2): (i32, i32, i32, i32) = kani::any();
    kani::assume(d1 != 0 && d2 != 0);
    let (n1, d1, n2, d2) = (n1 as i128, d1 as i128, n2 as i128, d2 as i128);
    let (a, b) = (Q::new(n1, d1), Q::new(n2, d2));
    let sum = a + b;
    let product = a * b;
    // Exact: sum = (n1 d2 + n2 d1)/(d1 d2), product = n1 n2/(d1 d2).
    for (r, num) in [(sum, n1 * d2 + n2 * d1), (product, n1 * n2)] {
        kani::assert(r.denom() > 0, "positive denominator");
        kani::assert(r.numer() * (d1 * d2) == num * r.denom(), "the exact value");
        kani::assert(coprime(r.numer(), r.denom()), "normalised");
    }
}

fn coprime(mut a: i128, mut b: i128) -> bool {
    a = a.abs();
    while b != 0 {
        let t = a % b;
        a = b;
        b = t;
    }
    a == 1
}

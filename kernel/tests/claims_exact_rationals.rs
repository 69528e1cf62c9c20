//! Pins the claims engines' small exact rationals (`kernel/src/claims/exact.rs`): `Q` is always
//! normalised (`d > 0`, `gcd(n, d) = 1`), its arithmetic and order are those of the rationals,
//! every overflow panics, and `Frac` compares by value (unnormalised), `ipow`/`pow` are powers.
//!
//! Why: the claims oracles are exercised mostly by `truecost`'s suite; the kernel's own tests
//! pinned these operations by a doctest only. Expected values: by hand, and on a grid of small
//! fractions the cross-multiplication identities (`a/b + c/d = (ad + cb)/bd`, …) checked with
//! plain `i128` arithmetic written here.

use std::cmp::Ordering;

use truecost_kernel::claims::exact::{ipow, Ext, Frac, FracExt, Q};

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 {
        a.abs()
    } else {
        gcd(b, a % b)
    }
}

/// Whether `q` is `n/d` in lowest terms with a positive denominator.
fn is_exactly(q: Q, n: i128, d: i128) -> bool {
    q.denom() > 0 && gcd(q.numer(), q.denom()) == 1 && q.numer() * d == n * q.denom()
}

fn grid() -> Vec<(i128, i128)> {
    let mut out = Vec::new();
    for n in -7..=7 {
        for d in (-6..=6).filter(|&d| d != 0) {
            out.push((n, d));
        }
    }
    out
}

#[test]
fn new_normalises_sign_and_common_factors() {
    for (n, d) in grid() {
        let q = Q::new(n, d);
        assert!(is_exactly(q, n, d), "{n}/{d} gave {q:?}");
        assert_eq!(q.is_zero(), n == 0);
        assert_eq!(q.signum(), (n * d).signum());
    }
    assert_eq!((Q::new(6, -4).numer(), Q::new(6, -4).denom()), (-3, 2));
    assert_eq!((Q::new(0, -5).numer(), Q::new(0, -5).denom()), (0, 1));
    assert_eq!(Q::int(-4), Q::new(8, -2));
    assert_eq!((Q::ZERO.numer(), Q::ZERO.denom()), (0, 1));
    assert_eq!((Q::ONE.numer(), Q::ONE.denom()), (1, 1));
}

#[test]
fn arithmetic_is_that_of_the_rationals() {
    for (a, b) in grid() {
        for (c, d) in grid() {
            let (x, y) = (Q::new(a, b), Q::new(c, d));
            assert!(is_exactly(x + y, a * d + c * b, b * d), "{x} + {y}");
            assert!(is_exactly(x - y, a * d - c * b, b * d), "{x} - {y}");
            assert!(is_exactly(x * y, a * c, b * d), "{x} * {y}");
            if c != 0 {
                assert!(is_exactly(x / y, a * d, b * c), "{x} / {y}");
            }
            assert!(is_exactly(-x, -a, b));
            // a/b < c/d  iff  a·d·(b·d) < c·b·(b·d), with b·d·b·d > 0.
            let expected = (a * d * b * d).cmp(&(c * b * b * d));
            assert_eq!(x.cmp(&y), expected, "{x} vs {y}");
            assert_eq!(x.partial_cmp(&y), Some(expected));
            assert_eq!(x == y, expected == Ordering::Equal);
        }
    }
}

#[test]
fn powers_multiply_k_times() {
    assert_eq!(Q::new(-2, 3).pow(0), Q::ONE);
    assert_eq!(Q::new(-2, 3).pow(1), Q::new(-2, 3));
    assert_eq!(Q::new(-2, 3).pow(3), Q::new(-8, 27));
    assert_eq!(Q::new(9, 10).pow(4), Q::new(6561, 10000));
    for b in -5..=5 {
        for k in 0..8 {
            assert_eq!(ipow(b, k), b.pow(k as u32), "{b}^{k}");
        }
    }
}

#[test]
fn display_writes_integers_without_a_denominator() {
    assert_eq!(Q::new(6, 2).to_string(), "3");
    assert_eq!(Q::new(7, -2).to_string(), "-7/2");
    assert_eq!(Q::ZERO.to_string(), "0");
    assert_eq!(Ext::NegInf.to_string(), "-inf");
    assert_eq!(Ext::PosInf.to_string(), "inf");
    assert_eq!(Ext::Fin(Q::new(1, 3)).to_string(), "1/3");
}

#[test]
fn extended_values_order_minus_infinity_finite_plus_infinity() {
    let q = Q::new(-1000, 1);
    assert!(Ext::NegInf < Ext::Fin(q) && Ext::Fin(q) < Ext::PosInf);
    assert!(Ext::Fin(Q::new(1, 3)) < Ext::Fin(Q::new(1, 2)));
    let f = |n, d| FracExt::Fin(Frac { n, d });
    assert!(FracExt::NegInf < f(-1000, 1) && f(1000, 1) < FracExt::PosInf);
    assert!(f(1, 3) < f(1, 2));
}

#[test]
fn fractions_compare_by_value_not_by_representation() {
    for (a, b) in grid().into_iter().filter(|&(_, d)| d > 0) {
        for (c, d) in grid().into_iter().filter(|&(_, d)| d > 0) {
            let (x, y) = (Frac { n: a, d: b }, Frac { n: c, d });
            let expected = (a * d).cmp(&(c * b));
            assert_eq!(x.cmp(&y), expected, "{a}/{b} vs {c}/{d}");
            assert_eq!(x.partial_cmp(&y), Some(expected));
            assert_eq!(x == y, expected == Ordering::Equal, "{a}/{b} == {c}/{d}");
        }
    }
    assert_eq!(Frac { n: 2, d: 4 }, Frac { n: 3, d: 6 });
    assert_ne!(Frac { n: 2, d: 4 }, Frac { n: 2, d: 5 });
}

#[test]
#[should_panic(expected = "exact arithmetic overflow")]
fn an_overflowing_sum_panics() {
    let _ = Q::int(i128::MAX) + Q::int(1);
}

#[test]
#[should_panic(expected = "exact arithmetic overflow")]
fn an_overflowing_sum_of_unlike_denominators_panics() {
    let _ = Q::new(i128::MAX, 2) + Q::new(1, 3);
}

#[test]
#[should_panic(expected = "exact arithmetic overflow")]
fn an_overflowing_product_panics() {
    let _ = Q::int(i128::MAX / 2 + 1) * Q::int(2);
}

#[test]
#[should_panic(expected = "exact arithmetic overflow")]
fn negating_the_least_integer_panics() {
    let _ = -Q::int(i128::MIN);
}

#[test]
#[should_panic(expected = "exact arithmetic overflow")]
fn an_overflowing_power_panics() {
    let _ = ipow(2, 127);
}

#[test]
#[should_panic(expected = "division by zero")]
fn dividing_by_zero_panics() {
    let _ = Q::ONE / Q::ZERO;
}

#[test]
#[should_panic(expected = "zero denominator")]
fn a_zero_denominator_panics() {
    let _ = Q::new(1, 0);
}

/// Only with the `bignum` feature (which `truecost` enables; `cargo test --workspace` unifies
/// it into this crate's build).
#[cfg(feature = "bignum")]
#[test]
fn to_rational_keeps_the_normalised_value() {
    use num_bigint::BigInt;
    let r = Q::new(6, -8).to_rational();
    assert_eq!(
        (r.numer(), r.denom()),
        (&BigInt::from(-3), &BigInt::from(4))
    );
    let r = Q::int(i128::MAX).to_rational();
    assert_eq!(
        (r.numer(), r.denom()),
        (&BigInt::from(i128::MAX), &BigInt::from(1))
    );
}

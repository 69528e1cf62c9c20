//! `stochastic::decimal` (the rounded display of exact values) against a brute force in exact
//! rationals: the shown number, read back exactly, is `v` rounded half away from zero to
//! `significant` digits, and the notation is plain in `[1e-4, 1e{significant})`, scientific
//! outside (the rounding mutants `num·2 + den` → `num + 2 + den` and the carry test
//! `>` → `<` survived the snapshot tests).

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};
use truecost::stochastic::decimal;
use truecost::value::{parse_rational, Extended, Rational};

fn ten_to(k: i64) -> Rational {
    let p = Rational::from_integer(num_traits::pow(BigInt::from(10), k.unsigned_abs() as usize));
    if k >= 0 {
        p
    } else {
        p.recip()
    }
}

/// `(rounded, k)`: `v` rounded half away from zero to `significant` digits, and the decimal
/// exponent of the result, found by stepping powers of ten.
fn brute_force(v: &Rational, significant: usize) -> (Rational, i64) {
    let a = v.abs();
    // k = floor(log10 a): the k with 10^k ≤ a < 10^(k+1).
    let mut k = 0i64;
    while ten_to(k) > a {
        k -= 1;
    }
    while ten_to(k + 1) <= a {
        k += 1;
    }
    let unit = ten_to(k - significant as i64 + 1);
    let half = Rational::new(BigInt::one(), BigInt::from(2));
    let rounded = ((&a / &unit) + half).floor() * &unit;
    let k = if rounded >= ten_to(k + 1) { k + 1 } else { k };
    let rounded = if v.is_negative() { -rounded } else { rounded };
    (rounded, k)
}

#[test]
fn decimal_is_exact_rounding_half_away_from_zero() {
    let mut checked = 0;
    let numerators = (-2000i64..=2000)
        .step_by(37)
        .chain([5, 15, 25, 95, 995, 9995, 99_995, 1, -1, 7, 125, 9, 99, 999]);
    for n in numerators {
        for d in [
            1i64, 2, 3, 4, 7, 8, 16, 40, 125, 999, 1000, 10_000, 100_000, 3_000_000,
        ] {
            let v = Rational::new(BigInt::from(n), BigInt::from(d));
            for significant in 1..=6 {
                let shown = decimal(&Extended::Finite(v.clone()), significant);
                if v.is_zero() {
                    assert_eq!(shown, "0");
                    continue;
                }
                let (want, k) = brute_force(&v, significant);
                let read = parse_rational(&shown).unwrap();
                assert_eq!(read, want, "{n}/{d} to {significant}: {shown}");
                let scientific = k < -4 || k >= significant as i64;
                assert_eq!(
                    shown.contains('e'),
                    scientific,
                    "{n}/{d} to {significant}: {shown}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 5000, "{checked}");
    assert_eq!(decimal(&Extended::Infinite, 3), "inf");
    // significant 0 is read as 1.
    assert_eq!(
        decimal(&Extended::Finite(parse_rational("2/3").unwrap()), 0),
        "0.7"
    );
}

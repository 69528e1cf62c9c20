//! The base-4 digits of π, computed with exact big-integer arithmetic (SPEC §2: the universal
//! plan reads them; no digits file is shipped).
//!
//! π = 3.0210 0333 1222 2020 … in base 4 (each hexadecimal digit of π, 3.243F6A88…, is two
//! base-4 digits).

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// The first `count` base-4 digits of π after the point.
///
/// Exact: π·2^B is enclosed between two integers computed with Machin's formula
/// `π = 16·atan(1/5) − 4·atan(1/239)` in fixed point with guard bits, and digits are only
/// returned once both ends of the enclosure agree on them (otherwise the precision is raised).
///
/// ```
/// let d = truecost::learning::pi::fractional_base4_digits(16);
/// assert_eq!(d, vec![0, 2, 1, 0, 0, 3, 3, 3, 1, 2, 2, 2, 2, 0, 2, 0]); // 0x243F6A88
/// ```
pub fn fractional_base4_digits(count: usize) -> Vec<u8> {
    let mut guard = 64usize;
    loop {
        let bits = 2 * count + guard;
        let (approx, error) = pi_fixed_point(bits);
        let lo = (&approx - &error) >> guard;
        let hi = (&approx + &error) >> guard;
        if lo == hi {
            // lo = floor(π · 4^count); strip the integer part 3 and read base-4 digits.
            let mut digits = vec![0u8; count];
            let mut v = lo;
            let four = BigInt::from(4);
            for d in digits.iter_mut().rev() {
                let r = &v % &four;
                *d = u8::try_from(r).expect("a base-4 digit");
                v /= &four;
            }
            debug_assert_eq!(v, BigInt::from(3));
            return digits;
        }
        guard *= 2;
    }
}

/// `(a, e)` with `|π·2^bits − a| ≤ e`.
fn pi_fixed_point(bits: usize) -> (BigInt, BigInt) {
    let (a5, e5) = atan_inverse(5, bits);
    let (a239, e239) = atan_inverse(239, bits);
    (a5 * 16 - a239 * 4, e5 * 16 + e239 * 4)
}

/// `(a, e)` with `|atan(1/x)·2^bits − a| ≤ e`, by the alternating series with truncated
/// divisions (each term errs by less than 1 unit; the tail is below the last term).
fn atan_inverse(x: u64, bits: usize) -> (BigInt, BigInt) {
    let x = BigInt::from(x);
    let x2 = &x * &x;
    let mut power: BigInt = (BigInt::one() << bits) / &x; // 2^bits / x^(2k+1)
    let mut sum = BigInt::zero();
    let mut terms = 0u64;
    let mut k = 0u64;
    while !power.is_zero() {
        let term = &power / (2 * k + 1);
        if k % 2 == 0 {
            sum += term;
        } else {
            sum -= term;
        }
        power /= &x2;
        k += 1;
        terms += 1;
    }
    debug_assert!(!sum.is_negative());
    // Each truncated division errs by < 1; the power chain accumulates < 1 per step too.
    (sum, BigInt::from(2 * terms + 2))
}

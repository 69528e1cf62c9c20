//! Cost-to-go values: the exact extended rationals of docs/spec.md §1 and the value types the solvers
//! run on.
//!
//! A cost-to-go `G(x)` is a non-negative rational or `+∞` (no goal reachable). The solvers are
//! generic over [`CostValue`] (the arithmetic core, with [`Units`], in the bignum-free kernel
//! `truecost_kernel::value`; re-exported here); [`ExactValue`] adds the exact meaning of a
//! value. Three implementations exist:
//!
//! * [`Units`] — a `u64` count of a problem-wide cost unit `1/D`. Every deterministic cost-to-go
//!   is a sum of stage costs, so when all stage costs are multiples of `1/D` every value is too.
//!   [`crate::model::ExactGraph::new`] chooses it only when `(states + 1) × max stage cost`
//!   is below `u64::MAX`, which bounds every value a planner can form (it never builds a sum of
//!   more than `states + 1` stage costs), so an addition can never wrap. This is the fast exact
//!   representation.
//! * [`Extended`] — a big rational or `+∞`; the fallback when `Units` is not provably safe.
//! * `f64` — only for the reference mode of docs/spec.md §7, which reproduces the paper's float code.

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// An exact rational (arbitrary precision).
pub type Rational = BigRational;

pub use truecost_kernel::value::{CostValue, Units};

/// The exact meaning of a planner's value (docs/spec.md §1): the big-rational side of [`CostValue`],
/// kept out of the bignum-free kernel that the Kani harnesses verify.
///
/// ```
/// use truecost::value::{ExactValue, Extended, Units};
/// let unit = truecost::value::parse_rational("1/19").unwrap();
/// assert_eq!(Units(50400).render(&unit), "50400/19");
/// assert_eq!(Units(19).to_extended(&unit), Some(Extended::from_integer(1)));
/// assert_eq!(1.5f64.to_extended(&unit), None);
/// ```
pub trait ExactValue: CostValue {
    /// The exact value, given the value of one unit of this type in the graph it came from
    /// (`1/D` for [`Units`], 1 otherwise); `None` for the inexact `f64`.
    fn to_extended(&self, unit: &Rational) -> Option<Extended>;
    /// The value as output text: exact (`"63"`, `"50400/19"`, `"inf"`) or, for `f64`, Rust's
    /// shortest round-trip decimal.
    fn render(&self, unit: &Rational) -> String;
}

impl ExactValue for Units {
    fn to_extended(&self, unit: &Rational) -> Option<Extended> {
        Some(if self.is_finite() {
            Extended::Finite(Rational::from_integer(BigInt::from(self.0)) * unit)
        } else {
            Extended::Infinite
        })
    }
    fn render(&self, unit: &Rational) -> String {
        self.to_extended(unit)
            .map(|e| e.to_string())
            .unwrap_or_default()
    }
}

/// A non-negative exact rational or `+∞`.
///
/// ```
/// use truecost::value::{CostValue, Extended};
/// let a: Extended = "50400/19".parse().unwrap();
/// assert_eq!(a.to_string(), "50400/19");
/// assert_eq!(Extended::infinity().to_string(), "inf");
/// ```
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Extended {
    /// A finite value.
    Finite(Rational),
    /// `+∞`.
    Infinite,
}

impl Extended {
    /// The finite value, if any.
    pub fn finite(&self) -> Option<&Rational> {
        match self {
            Extended::Finite(r) => Some(r),
            Extended::Infinite => None,
        }
    }

    /// A finite integer value.
    pub fn from_integer(n: i64) -> Self {
        Extended::Finite(Rational::from_integer(BigInt::from(n)))
    }

    /// The nearest `f64` (for display next to the exact value only).
    pub fn to_f64(&self) -> f64 {
        match self {
            Extended::Finite(r) => r.to_f64().unwrap_or(f64::INFINITY),
            Extended::Infinite => f64::INFINITY,
        }
    }
}

impl PartialOrd for Extended {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Extended {
    fn cmp(&self, other: &Self) -> Ordering {
        match (self, other) {
            (Extended::Infinite, Extended::Infinite) => Ordering::Equal,
            (Extended::Infinite, _) => Ordering::Greater,
            (_, Extended::Infinite) => Ordering::Less,
            (Extended::Finite(a), Extended::Finite(b)) => a.cmp(b),
        }
    }
}

impl CostValue for Extended {
    const EXACT: bool = true;
    fn zero() -> Self {
        Extended::Finite(Rational::zero())
    }
    fn infinity() -> Self {
        Extended::Infinite
    }
    fn is_finite(&self) -> bool {
        matches!(self, Extended::Finite(_))
    }
    fn plus(&self, other: &Self) -> Self {
        match (self, other) {
            (Extended::Finite(a), Extended::Finite(b)) => Extended::Finite(a + b),
            _ => Extended::Infinite,
        }
    }
    fn compare(&self, other: &Self) -> Ordering {
        self.cmp(other)
    }
}

impl ExactValue for Extended {
    fn to_extended(&self, unit: &Rational) -> Option<Extended> {
        Some(match self {
            Extended::Finite(r) => Extended::Finite(r * unit),
            Extended::Infinite => Extended::Infinite,
        })
    }
    fn render(&self, unit: &Rational) -> String {
        self.to_extended(unit)
            .map(|e| e.to_string())
            .unwrap_or_default()
    }
}

/// `f64` is the value type of the reference mode only (docs/spec.md §7). It is not exact.
impl ExactValue for f64 {
    fn to_extended(&self, _unit: &Rational) -> Option<Extended> {
        None
    }
    fn render(&self, _unit: &Rational) -> String {
        if f64::is_finite(*self) {
            format!("{self:?}")
        } else {
            "inf".to_string()
        }
    }
}

impl fmt::Display for Extended {
    /// `"63"`, `"50400/19"` or `"inf"` (integers printed by [`integer_text`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Extended::Infinite => write!(f, "inf"),
            Extended::Finite(r) if r.is_integer() => f.write_str(&integer_text(r.numer())),
            Extended::Finite(r) => {
                write!(f, "{}/{}", integer_text(r.numer()), integer_text(r.denom()))
            }
        }
    }
}

/// Limbs (64 bits each) from which [`integer_text`] converts through `malachite`.
const FAST_TEXT_LIMBS: usize = 32;

/// The decimal text of an integer, the same string as `n.to_string()`. Past a few hundred
/// digits it is converted by `malachite`, whose radix conversion is quasi-linear in the number
/// of digits where `num-bigint`'s divides quadratically (a value of `G*` on a 100×100 grid has
/// tens of thousands of digits, and printing 10⁴ of them dominated a JSON report).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::value::integer_text;
/// let n: BigInt = "-123456789012345678901234567890".parse().unwrap();
/// assert_eq!(integer_text(&n), "-123456789012345678901234567890");
/// let big = num_traits::pow(BigInt::from(7), 5000) - 1;
/// assert_eq!(integer_text(&big), big.to_string());
/// assert_eq!(integer_text(&-big.clone()), (-big).to_string());
/// ```
pub fn integer_text(n: &BigInt) -> String {
    let (sign, limbs) = n.to_u64_digits();
    if limbs.len() < FAST_TEXT_LIMBS {
        return n.to_string();
    }
    let magnitude = malachite_nz::natural::Natural::from_owned_limbs_asc(limbs);
    match sign {
        num_bigint::Sign::Minus => format!("-{magnitude}"),
        _ => magnitude.to_string(),
    }
}

impl std::str::FromStr for Extended {
    type Err = ParseRationalError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let t = s.trim();
        if t == "inf" || t == "+inf" || t == "∞" {
            return Ok(Extended::Infinite);
        }
        parse_rational(t).map(Extended::Finite)
    }
}

/// The longest number text [`parse_rational`] reads, in bytes (surrounding blanks excluded):
/// 4096 digits are far more than any exact input needs (the paper's largest exact values have
/// about 1500 digits), and the bound keeps every parse and every message small.
pub const MAX_NUMBER_TEXT: usize = 4096;

/// The largest decimal exponent `|e|` of `1e…` that [`parse_rational`] reads: `10^10000`
/// already has 10001 digits.
pub const MAX_EXPONENT: u64 = 10_000;

/// Why a text is not an exact rational: the input (escaped and shortened by
/// [`crate::echo::echo`], so a message stays one short line) and the reason.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("'{}' {reason}", crate::echo::echo(.text))]
pub struct ParseRationalError {
    /// The offending text (as given; echoed escaped and shortened).
    pub text: String,
    /// Why it was refused.
    pub reason: ParseRationalReason,
}

/// Why [`parse_rational`] refused a text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ParseRationalReason {
    /// Not of the accepted shapes.
    #[error("is not an exact number (expected an integer, a decimal such as 0.999, or a fraction such as 800/19)")]
    Syntax,
    /// Longer than [`MAX_NUMBER_TEXT`].
    #[error("is too long for an exact number ({0} bytes; the limit is 4096)")]
    TooLong(usize),
    /// An exponent beyond [`MAX_EXPONENT`].
    #[error("has an exponent outside the supported range -10000..=10000")]
    Exponent,
    /// A zero denominator.
    #[error("divides by zero")]
    ZeroDenominator,
}

/// Parses an exact rational from its text: an integer (`"42"`), a decimal (`"0.999"`, `"-1.5"`,
/// `"2e-3"`) or a fraction (`"800/19"`, each side such a number). Never goes through `f64`.
///
/// Limits: at most [`MAX_NUMBER_TEXT`] bytes and exponents within
/// ±[`MAX_EXPONENT`]; each refusal says which rule was broken.
///
/// ```
/// use truecost::value::{parse_rational, ParseRationalReason};
/// use num_rational::BigRational;
/// use num_bigint::BigInt;
/// assert_eq!(parse_rational("0.999").unwrap(),
///            BigRational::new(BigInt::from(999), BigInt::from(1000)));
/// assert_eq!(parse_rational("800/19").unwrap(),
///            BigRational::new(BigInt::from(800), BigInt::from(19)));
/// assert!(parse_rational("0.1.2").is_err());
/// assert_eq!(parse_rational("1/0").unwrap_err().reason, ParseRationalReason::ZeroDenominator);
/// assert!(parse_rational("1e10000").is_ok());
/// assert_eq!(parse_rational("1e10001").unwrap_err().reason, ParseRationalReason::Exponent);
/// assert_eq!(parse_rational(&"9".repeat(5000)).unwrap_err().reason, ParseRationalReason::TooLong(5000));
/// ```
pub fn parse_rational(text: &str) -> Result<Rational, ParseRationalError> {
    let err = |reason| ParseRationalError {
        text: text.to_string(),
        reason,
    };
    let t = text.trim();
    if t.len() > MAX_NUMBER_TEXT {
        return Err(err(ParseRationalReason::TooLong(t.len())));
    }
    let decimal = |s: &str| parse_decimal(s.trim()).map_err(err);
    let value = match t.split_once('/') {
        Some((n, d)) => {
            let (n, d) = (decimal(n)?, decimal(d)?);
            if d.mantissa.is_zero() {
                return Err(err(ParseRationalReason::ZeroDenominator));
            }
            n.over(d)
        }
        None => decimal(t)?.over(Decimal::one()),
    };
    Ok(value)
}

/// A parsed decimal `±m · 2^twos · 5^fives` with `m ≥ 0` prime to 10 (`0` for zero): the
/// factors 2 and 5 kept as exponents, so that the reduced fraction of a quotient is found
/// without a greatest common divisor of the powers of ten (only of the two mantissas, which
/// the text's length bounds).
struct Decimal {
    negative: bool,
    mantissa: num_bigint::BigUint,
    twos: i64,
    fives: i64,
}

impl Decimal {
    fn one() -> Self {
        Decimal {
            negative: false,
            mantissa: num_bigint::BigUint::one(),
            twos: 0,
            fives: 0,
        }
    }

    /// `self / d` in lowest terms (`d` non-zero).
    fn over(self, d: Decimal) -> Rational {
        use num_bigint::Sign;
        if self.mantissa.is_zero() {
            return Rational::zero();
        }
        let g = mantissa_gcd(&self.mantissa, &d.mantissa);
        let (twos, fives) = (self.twos - d.twos, self.fives - d.fives);
        let power = |twos: i64, fives: i64| power_of_five(fives.max(0) as usize) << twos.max(0);
        let quotient = |m: num_bigint::BigUint| if g.is_one() { m } else { m / &g };
        let numer = quotient(self.mantissa) * power(twos, fives);
        let denom = quotient(d.mantissa) * power(-twos, -fives);
        let sign = if self.negative != d.negative {
            Sign::Minus
        } else {
            Sign::Plus
        };
        // Coprime: the mantissas' common divisor is removed and both are prime to 10, and only
        // one side carries 2s, only one side 5s.
        Rational::new_raw(
            BigInt::from_biguint(sign, numer),
            BigInt::from_biguint(Sign::Plus, denom),
        )
    }
}

/// The greatest common divisor of two mantissas, by `malachite` (whose gcd is subquadratic:
/// `num-bigint`'s binary gcd took a third of a millisecond on two 2000-digit mantissas, which
/// a file of thousands of them turned into seconds).
fn mantissa_gcd(a: &num_bigint::BigUint, b: &num_bigint::BigUint) -> num_bigint::BigUint {
    use malachite_base::num::arithmetic::traits::Gcd;
    use malachite_nz::natural::Natural;
    let natural = |m: &num_bigint::BigUint| Natural::from_owned_limbs_asc(m.to_u64_digits());
    let g = natural(a).gcd(natural(b));
    let bytes: Vec<u8> = g
        .into_limbs_asc()
        .into_iter()
        .flat_map(u64::to_le_bytes)
        .collect();
    num_bigint::BigUint::from_bytes_le(&bytes)
}

/// `5^k`, as a product of a cached `5^(256·j)` and a small power: linear in its size, so that
/// a file of many large exponents is read in time proportional to its numbers' bits.
fn power_of_five(k: usize) -> num_bigint::BigUint {
    use num_bigint::BigUint;
    const STEP: usize = 256;
    static POWERS: std::sync::Mutex<Vec<BigUint>> = std::sync::Mutex::new(Vec::new());
    let small = num_traits::pow(BigUint::from(5u8), k % STEP);
    let mut powers = POWERS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if powers.is_empty() {
        powers.push(BigUint::one());
    }
    while powers.len() <= k / STEP {
        let next =
            powers.last().expect("starts with 1") * num_traits::pow(BigUint::from(5u8), STEP);
        powers.push(next);
    }
    &powers[k / STEP] * small
}

/// The exponent of the largest power of 5 dividing `m` (`m > 0`), which it divides out.
fn take_fives(m: &mut num_bigint::BigUint) -> i64 {
    use num_integer::Integer;
    let mut count = 0;
    // 5^27 < 2^64: strip whole chunks first, then single fives.
    for (step, size) in [(7_450_580_596_923_828_125u64, 27), (5, 1)] {
        loop {
            let (q, r) = m.div_rem(&num_bigint::BigUint::from(step));
            if !r.is_zero() {
                break;
            }
            *m = q;
            count += size;
        }
    }
    count
}

/// Parses `[+-]digits[.digits][e[+-]digits]` exactly, without forming `10^e`: the work is
/// linear in the result's size apart from the digits' conversion.
fn parse_decimal(t: &str) -> Result<Decimal, ParseRationalReason> {
    use ParseRationalReason::{Exponent, Syntax};
    let (negative, rest) = match t.as_bytes().first().ok_or(Syntax)? {
        b'-' => (true, &t[1..]),
        b'+' => (false, &t[1..]),
        _ => (false, t),
    };
    let (mantissa, exponent) = match rest.find(['e', 'E']) {
        Some(i) => (&rest[..i], Some(&rest[i + 1..])),
        None => (rest, None),
    };
    let (int_part, frac_part) = match mantissa.split_once('.') {
        Some((a, b)) => (a, b),
        None => (mantissa, ""),
    };
    if int_part.is_empty() && frac_part.is_empty() {
        return Err(Syntax);
    }
    if !int_part.bytes().all(|b| b.is_ascii_digit())
        || !frac_part.bytes().all(|b| b.is_ascii_digit())
    {
        return Err(Syntax);
    }
    let mut scale: i64 = -(frac_part.len() as i64);
    if let Some(e) = exponent {
        let (e_neg, e_digits) = match e.as_bytes().first() {
            Some(b'-') => (true, &e[1..]),
            Some(b'+') => (false, &e[1..]),
            _ => (false, e),
        };
        if e_digits.is_empty() || !e_digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(Syntax);
        }
        // Leading zeros aside, more than 5 digits is beyond the limit (and beyond i64).
        let significant = e_digits.trim_start_matches('0');
        if significant.len() > 5 {
            return Err(Exponent);
        }
        let magnitude: i64 = if significant.is_empty() {
            0
        } else {
            significant.parse().map_err(|_| Syntax)?
        };
        if magnitude.unsigned_abs() > MAX_EXPONENT {
            return Err(Exponent);
        }
        scale += if e_neg { -magnitude } else { magnitude };
    }
    let digits = format!("{int_part}{frac_part}");
    let mut m: num_bigint::BigUint = digits.parse().map_err(|_| Syntax)?;
    if m.is_zero() {
        return Ok(Decimal {
            negative,
            mantissa: m,
            twos: 0,
            fives: 0,
        });
    }
    let twos = m.trailing_zeros().unwrap_or(0);
    m >>= twos;
    let fives = take_fives(&mut m);
    Ok(Decimal {
        negative,
        mantissa: m,
        twos: scale + twos as i64,
        fives: scale + fives,
    })
}

/// A lower bound on the bits [`parse_rational`]'s value of `text` takes, numerator and
/// denominator together in lowest terms, read from the digit counts and exponents alone
/// (no number formed): `0` for a text it does not read. A decimal is `M · 10^s` with `M` free
/// of trailing zeros; a fraction's value is `(M_n / M_d) · 10^s`, whose factors 2 and 5 in
/// lowest terms are `v_p = s + v_p(M_n) − v_p(M_d)`, and `v_p(M)` is 0 unless `M`'s last digit
/// is even (`p = 2`) or 5 (`p = 5`), and below `digits(M) · log_p 10` in any case. The bound
/// is `|v_2| + |v_5| · log₂ 5` at the least `|v_p|` these ranges allow; a reader adds it up over
/// a file before reading any number, so that a file of huge exponents is refused before any
/// of its numbers is reduced.
///
/// ```
/// use truecost::value::{bits_lower_bound, parse_rational};
/// let bits = |t: &str| { let r = parse_rational(t).unwrap(); r.numer().bits() + r.denom().bits() };
/// for t in ["1e10000", "3e-10000", "1/2e-500", "25e300/7", "0", "12.5", "x"] {
///     assert!(bits_lower_bound(t) <= parse_rational(t).map_or(0, |_| bits(t)), "{t}");
/// }
/// assert!(bits_lower_bound("1e10000") >= 33_000);
/// ```
pub fn bits_lower_bound(text: &str) -> u64 {
    let t = text.trim();
    if t.len() > MAX_NUMBER_TEXT {
        return 0;
    }
    let (n, d) = match t.split_once('/') {
        Some((n, d)) => (decimal_shape(n.trim()), decimal_shape(d.trim())),
        None => (decimal_shape(t), Some(DecimalShape::ONE)),
    };
    let (Some(n), Some(d)) = (n, d) else {
        return 0;
    };
    if n.digits == 0 || d.digits == 0 {
        return 0;
    }
    let s = n.scale - d.scale;
    // The least |v| over v ∈ [s + lo_n − hi_d, s + hi_n − lo_d].
    let least = |(lo_n, hi_n): (i64, i64), (lo_d, hi_d): (i64, i64)| -> u64 {
        let (lo, hi) = (s + lo_n - hi_d, s + hi_n - lo_d);
        if lo > 0 {
            lo.unsigned_abs()
        } else if hi < 0 {
            hi.unsigned_abs()
        } else {
            0
        }
    };
    let twos = least(n.twos(), d.twos());
    let fives = least(n.fives(), d.fives());
    // log₂ 5 > 2.32.
    twos + fives * 232 / 100
}

/// The shape of a decimal text `[+-]digits[.digits][e[+-]digits]` as [`bits_lower_bound`]
/// reads it: `M · 10^scale` with `M` free of leading and trailing zeros.
struct DecimalShape {
    /// Digits of `M` (0 for zero).
    digits: i64,
    /// Last digit of `M`.
    last: u8,
    scale: i64,
}

impl DecimalShape {
    const ONE: DecimalShape = DecimalShape {
        digits: 1,
        last: b'1',
        scale: 0,
    };

    /// The range of `v_2(M)`: 0 when `M` is odd, else `1..` below `digits · log₂ 10 < digits · 3.33`.
    fn twos(&self) -> (i64, i64) {
        if self.last % 2 == 1 {
            (0, 0)
        } else {
            (1, self.digits * 333 / 100 + 1)
        }
    }

    /// The range of `v_5(M)`: 0 unless `M` ends in 5, else `1..` below `digits · log₅ 10 < digits · 1.44`.
    fn fives(&self) -> (i64, i64) {
        if self.last != b'5' {
            (0, 0)
        } else {
            (1, self.digits * 144 / 100 + 1)
        }
    }
}

/// [`DecimalShape`] of a text [`parse_decimal`] reads (`None` for any other).
fn decimal_shape(t: &str) -> Option<DecimalShape> {
    let rest = t.strip_prefix(['-', '+']).unwrap_or(t);
    let (mantissa, exponent) = match rest.find(['e', 'E']) {
        Some(i) => (&rest[..i], Some(&rest[i + 1..])),
        None => (rest, None),
    };
    let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digit = |s: &str| s.bytes().all(|b| b.is_ascii_digit());
    if (int_part.is_empty() && frac_part.is_empty()) || !digit(int_part) || !digit(frac_part) {
        return None;
    }
    let mut scale = -(frac_part.len() as i64);
    if let Some(e) = exponent {
        let digits = e.strip_prefix(['-', '+']).unwrap_or(e);
        let significant = digits.trim_start_matches('0');
        if digits.is_empty() || !digit(digits) || significant.len() > 5 {
            return None;
        }
        let magnitude: i64 = significant.parse().unwrap_or(0);
        if magnitude.unsigned_abs() > MAX_EXPONENT {
            return None;
        }
        scale += if e.starts_with('-') {
            -magnitude
        } else {
            magnitude
        };
    }
    let all = || int_part.bytes().chain(frac_part.bytes());
    let leading = all().take_while(|&b| b == b'0').count();
    let total = int_part.len() + frac_part.len();
    if leading == total {
        return Some(DecimalShape {
            digits: 0,
            last: b'0',
            scale: 0,
        });
    }
    let trailing = all().rev().take_while(|&b| b == b'0').count();
    let last = all().rev().nth(trailing).unwrap_or(b'1');
    Some(DecimalShape {
        digits: (total - leading - trailing) as i64,
        last,
        scale: scale + trailing as i64,
    })
}

/// Whether `r` lies in the half-open interval `(0, 1]` (used to validate γ, ρ).
pub fn in_unit_interval_open_closed(r: &Rational) -> bool {
    r.is_positive() && r <= &Rational::one()
}

/// Exact rationals as integers on one scale: `(d, [v·d])` with `d` the least common multiple of
/// the denominators (`1` for none). A positive common scale changes no comparison, argmin or
/// ratio of costs, which is why the claims' integer oracles can replay rational models.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::value::{to_common_scale, Rational};
/// let r = |n: i64, d: i64| Rational::new(n.into(), d.into());
/// let (d, ints) = to_common_scale(&[r(1, 4), r(-5, 6), r(2, 1)]);
/// assert_eq!(d, BigInt::from(12));
/// assert_eq!(ints, vec![BigInt::from(3), BigInt::from(-10), BigInt::from(24)]);
/// ```
pub fn to_common_scale(values: &[Rational]) -> (BigInt, Vec<BigInt>) {
    use num_integer::Integer;
    let d = values
        .iter()
        .fold(BigInt::one(), |acc, v| acc.lcm(v.denom()));
    let ints = values
        .iter()
        .map(|v| v.numer() * (&d / v.denom()))
        .collect();
    (d, ints)
}

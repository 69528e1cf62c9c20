//! Cost-to-go values: the exact extended rationals of SPEC §1 and the value types the solvers
//! run on.
//!
//! A cost-to-go `G(x)` is a non-negative rational or `+∞` (no goal reachable). The solvers are
//! generic over [`CostValue`]; three implementations exist:
//!
//! * [`Units`] — a `u64` count of a problem-wide cost unit `1/D`. Every deterministic cost-to-go
//!   is a sum of stage costs, so when all stage costs are multiples of `1/D` every value is too.
//!   [`crate::model::ExactGraph::new`] chooses it only when `(states + 1) × max stage cost`
//!   is below `u64::MAX`, which bounds every value a planner can form (it never builds a sum of
//!   more than `states + 1` stage costs), so an addition can never wrap. This is the fast exact
//!   representation.
//! * [`Extended`] — a big rational or `+∞`; the fallback when `Units` is not provably safe.
//! * `f64` — only for the reference mode of SPEC §7, which reproduces the paper's float code.

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// An exact rational (arbitrary precision).
pub type Rational = BigRational;

/// The value type a planner computes with (SPEC §2: "generic over the value type").
///
/// `plus` is the extended addition of the cost model (`+∞` absorbs); implementations must be
/// exact or, for `f64`, say that they are not.
pub trait CostValue: Clone + PartialEq + PartialOrd + fmt::Debug + Send + Sync + 'static {
    /// Whether values of this type are exact (false only for `f64`).
    const EXACT: bool;
    /// The additive identity (the value of a goal).
    fn zero() -> Self;
    /// `+∞`: no goal is reachable.
    fn infinity() -> Self;
    /// Whether the value is finite.
    fn is_finite(&self) -> bool;
    /// Extended addition: `a + ∞ = ∞`, otherwise the exact (or, for `f64`, rounded) sum.
    fn plus(&self, other: &Self) -> Self;
    /// The total order used by planners (`f64` values here are never NaN).
    fn compare(&self, other: &Self) -> Ordering;
    /// The exact value, given the value of one unit of this type in the graph it came from
    /// (`1/D` for [`Units`], 1 otherwise); `None` for the inexact `f64`.
    fn to_extended(&self, unit: &Rational) -> Option<Extended>;
    /// The value as output text: exact (`"63"`, `"50400/19"`, `"inf"`) or, for `f64`, Rust's
    /// shortest round-trip decimal.
    fn render(&self, unit: &Rational) -> String;
}

/// A count of the problem's cost unit `1/D`; `u64::MAX` stands for `+∞`.
///
/// ```
/// use truecost::value::{CostValue, Units};
/// assert_eq!(Units(2).plus(&Units(3)), Units(5));
/// assert!(!Units(2).plus(&Units::infinity()).is_finite());
/// ```
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub struct Units(pub u64);

impl CostValue for Units {
    const EXACT: bool = true;
    #[inline]
    fn zero() -> Self {
        Units(0)
    }
    #[inline]
    fn infinity() -> Self {
        Units(u64::MAX)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        self.0 != u64::MAX
    }
    #[inline]
    fn plus(&self, other: &Self) -> Self {
        if self.0 == u64::MAX || other.0 == u64::MAX {
            return Units(u64::MAX);
        }
        // The graph constructor proves `states × max cost < u64::MAX`; planners never add more
        // than `states` stage costs, so this cannot fail. If it ever did, failing loudly is the
        // only acceptable outcome: a wrapped or saturated sum would be a silently wrong number.
        match self.0.checked_add(other.0) {
            Some(s) if s != u64::MAX => Units(s),
            _ => panic!("exact cost overflow: the Units bound was violated (a truecost bug)"),
        }
    }
    #[inline]
    fn compare(&self, other: &Self) -> Ordering {
        self.0.cmp(&other.0)
    }
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

/// `f64` is the value type of the reference mode only (SPEC §7). It is not exact.
impl CostValue for f64 {
    const EXACT: bool = false;
    #[inline]
    fn zero() -> Self {
        0.0
    }
    #[inline]
    fn infinity() -> Self {
        f64::INFINITY
    }
    #[inline]
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    #[inline]
    fn plus(&self, other: &Self) -> Self {
        self + other
    }
    #[inline]
    fn compare(&self, other: &Self) -> Ordering {
        self.total_cmp(other)
    }
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
    /// `"63"`, `"50400/19"` or `"inf"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Extended::Infinite => write!(f, "inf"),
            Extended::Finite(r) if r.is_integer() => write!(f, "{}", r.numer()),
            Extended::Finite(r) => write!(f, "{}/{}", r.numer(), r.denom()),
        }
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

/// Why a text is not an exact rational.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("'{text}' is not an exact number (expected an integer, a decimal such as 0.999, or a fraction such as 800/19)")]
pub struct ParseRationalError {
    /// The offending text.
    pub text: String,
}

/// Parses an exact rational from its text: an integer (`"42"`), a decimal (`"0.999"`, `"-1.5"`,
/// `"2e-3"`) or a fraction (`"800/19"`). Never goes through `f64`.
///
/// ```
/// use truecost::value::parse_rational;
/// use num_rational::BigRational;
/// use num_bigint::BigInt;
/// assert_eq!(parse_rational("0.999").unwrap(),
///            BigRational::new(BigInt::from(999), BigInt::from(1000)));
/// assert_eq!(parse_rational("800/19").unwrap(),
///            BigRational::new(BigInt::from(800), BigInt::from(19)));
/// assert!(parse_rational("0.1.2").is_err());
/// assert!(parse_rational("1/0").is_err());
/// ```
pub fn parse_rational(text: &str) -> Result<Rational, ParseRationalError> {
    let err = || ParseRationalError {
        text: text.to_string(),
    };
    let t = text.trim();
    if t.is_empty() || t.len() > 4096 {
        return Err(err());
    }
    if let Some((n, d)) = t.split_once('/') {
        let n = parse_decimal(n.trim()).ok_or_else(err)?;
        let d = parse_decimal(d.trim()).ok_or_else(err)?;
        if d.is_zero() {
            return Err(err());
        }
        return Ok(n / d);
    }
    parse_decimal(t).ok_or_else(err)
}

/// Parses `[+-]digits[.digits][e[+-]digits]` exactly.
fn parse_decimal(t: &str) -> Option<Rational> {
    let (neg, rest) = match t.as_bytes().first()? {
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
        return None;
    }
    if !int_part.bytes().all(|b| b.is_ascii_digit())
        || !frac_part.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let digits = format!("{int_part}{frac_part}");
    let mut value = Rational::from_integer(digits.parse::<BigInt>().ok()?);
    let mut scale: i64 = -(frac_part.len() as i64);
    if let Some(e) = exponent {
        let e: i64 = e.parse().ok()?;
        if e.unsigned_abs() > 10_000 {
            return None;
        }
        scale += e;
    }
    let ten = BigInt::from(10);
    let p = Rational::from_integer(num_traits::pow(ten, scale.unsigned_abs() as usize));
    if scale >= 0 {
        value *= p;
    } else {
        value /= p;
    }
    Some(if neg { -value } else { value })
}

/// Whether `r` lies in the half-open interval `(0, 1]` (used to validate γ, ρ).
pub fn in_unit_interval_open_closed(r: &Rational) -> bool {
    r.is_positive() && r <= &Rational::one()
}

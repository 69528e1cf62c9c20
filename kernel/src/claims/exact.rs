//! Small exact rationals for the enumeration engines, generic over the integer width.
//!
//! The engines run millions of tiny problems; big rationals would dominate their time. Every
//! operation here is checked: an overflow is reported as an internal error (a panic that the
//! CLI turns into a non-zero exit), never a wrapped number. The scopes are small enough that
//! no overflow occurs (values have at most a few dozen bits).
//!
//! The product computes with `i128` ([`Q`] is `Q<i128>`); the same code instantiated at `i8`,
//! `i16` or `i32` ([`ExactInt`]) is what the Kani harnesses verify on small bit-vectors, where
//! a symbolic product or remainder costs a model checker a small fraction of its `i128` price.

use std::cmp::Ordering;
use std::fmt;
use std::hash::Hash;

fn overflow() -> ! {
    panic!("exact arithmetic overflow in the claims engine (a truecost bug: scope bound violated)")
}

/// A signed machine integer the exact types compute with: `i8`, `i16`, `i32`, `i64`, `i128`.
/// Every operation is checked; the `_exact` forms panic on overflow (never wrap).
pub trait ExactInt:
    Copy + Ord + Eq + Hash + fmt::Debug + fmt::Display + Send + Sync + 'static
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// `self + o`, `None` on overflow.
    fn checked_add(self, o: Self) -> Option<Self>;
    /// `self - o`, `None` on overflow.
    fn checked_sub(self, o: Self) -> Option<Self>;
    /// `self · o`, `None` on overflow.
    fn checked_mul(self, o: Self) -> Option<Self>;
    /// `self / o` truncated towards zero, `None` on overflow or `o = 0`.
    fn checked_div(self, o: Self) -> Option<Self>;
    /// `self mod o` (sign of `self`), `None` on overflow or `o = 0`.
    fn checked_rem(self, o: Self) -> Option<Self>;
    /// `-self`, `None` on overflow.
    fn checked_neg(self) -> Option<Self>;
    /// `|self|`, `None` on overflow.
    fn checked_abs(self) -> Option<Self>;
    /// `-1`, `0` or `1`.
    fn signum(self) -> Self;
    /// `v` in this width, `None` if it does not fit.
    fn from_i128(v: i128) -> Option<Self>;
    /// The value as an `i128` (exact: every width is at most 128 bits).
    fn to_i128(self) -> i128;

    /// `v` in this width; panics (an overflow) if it does not fit.
    #[inline]
    fn from_i64(v: i64) -> Self {
        Self::from_i128(v as i128).unwrap_or_else(|| overflow())
    }
    /// `self + o`; panics on overflow.
    #[inline]
    fn add_exact(self, o: Self) -> Self {
        self.checked_add(o).unwrap_or_else(|| overflow())
    }
    /// `self - o`; panics on overflow.
    #[inline]
    fn sub_exact(self, o: Self) -> Self {
        self.checked_sub(o).unwrap_or_else(|| overflow())
    }
    /// `self · o`; panics on overflow.
    #[inline]
    fn mul_exact(self, o: Self) -> Self {
        self.checked_mul(o).unwrap_or_else(|| overflow())
    }
    /// `-self`; panics on overflow.
    #[inline]
    fn neg_exact(self) -> Self {
        self.checked_neg().unwrap_or_else(|| overflow())
    }
}

macro_rules! exact_int {
    ($($t:ty),*) => {$(
        exact_int!($t, |a: $t, b: $t| <$t>::checked_mul(a, b));
    )*};
    ($t:ty, $mul:expr) => {
        impl ExactInt for $t {
            const ZERO: Self = 0;
            const ONE: Self = 1;
            #[inline]
            fn checked_add(self, o: Self) -> Option<Self> {
                <$t>::checked_add(self, o)
            }
            #[inline]
            fn checked_sub(self, o: Self) -> Option<Self> {
                <$t>::checked_sub(self, o)
            }
            #[inline]
            fn checked_mul(self, o: Self) -> Option<Self> {
                ($mul)(self, o)
            }
            #[inline]
            fn checked_div(self, o: Self) -> Option<Self> {
                <$t>::checked_div(self, o)
            }
            #[inline]
            fn checked_rem(self, o: Self) -> Option<Self> {
                <$t>::checked_rem(self, o)
            }
            #[inline]
            fn checked_neg(self) -> Option<Self> {
                <$t>::checked_neg(self)
            }
            #[inline]
            fn checked_abs(self) -> Option<Self> {
                <$t>::checked_abs(self)
            }
            #[inline]
            fn signum(self) -> Self {
                <$t>::signum(self)
            }
            #[inline]
            fn from_i128(v: i128) -> Option<Self> {
                <$t>::try_from(v).ok()
            }
            #[inline]
            fn to_i128(self) -> i128 {
                self as i128
            }
        }
    };
}
exact_int!(i8, i16, i32, i64);
// The product's width: the engines' operands are almost always within `i64`, whose product
// cannot overflow `i128` (|a·b| ≤ 2^126); only otherwise the full overflow check runs.
exact_int!(i128, |a: i128, b: i128| {
    if a == a as i64 as i128 && b == b as i64 as i128 {
        Some(a.wrapping_mul(b))
    } else {
        a.checked_mul(b)
    }
});

/// The greatest common divisor of `|a|` and `|b|` by Euclid's algorithm (`gcd(0, 0) = 0`).
/// By Lamé's theorem the loop runs at most `1 + k` times when the smaller magnitude is below
/// the Fibonacci number `F(k+2)` (the `1` for a first iteration that only swaps the operands).
///
/// Contract (proved once by `proofs::contracts::gcd_divides_both`): for operands whose
/// magnitude fits `I`, the result is non-negative, zero exactly when both operands are, and
/// divides both.
#[kani::requires(a.checked_abs().is_some() && b.checked_abs().is_some())]
#[kani::ensures(|g: &I| spec::is_common_divisor(a, b, *g))]
pub fn gcd<I: ExactInt>(a: I, b: I) -> I {
    let mut a = a.checked_abs().unwrap_or_else(|| overflow());
    let mut b = b.checked_abs().unwrap_or_else(|| overflow());
    while b != I::ZERO {
        let t = a.checked_rem(b).unwrap_or_else(|| overflow());
        a = b;
        b = t;
    }
    a
}

/// An exact rational `n/d` with `d > 0` and `gcd(n, d) = 1`, over the integer type `I`
/// (`i128` unless stated: the product's type).
///
/// ```
/// use truecost_kernel::claims::exact::Q;
/// assert_eq!(Q::new(2, 4) + Q::int(1), Q::new(3, 2));
/// assert!(Q::new(1, 3) < Q::new(1, 2));
/// // The same arithmetic at 16 bits (what the Kani harnesses verify).
/// let h = Q::<i16>::ratio(2, 4) + Q::<i16>::integer(1);
/// assert_eq!((h.numer(), h.denom()), (3, 2));
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Q<I: ExactInt = i128> {
    n: I,
    d: I,
}

impl<I: ExactInt> Q<I> {
    /// Zero (in any width; [`Q::ZERO`] is the `i128` one).
    pub const fn zero() -> Self {
        Q {
            n: I::ZERO,
            d: I::ONE,
        }
    }

    /// One (in any width; [`Q::ONE`] is the `i128` one).
    pub const fn one() -> Self {
        Q {
            n: I::ONE,
            d: I::ONE,
        }
    }

    /// `n/d`, normalised. Panics if `d == 0` (a bug, never input) or on overflow.
    ///
    /// Contract (proved by `proofs::contracts::ratio_is_exact_and_normalised`): for `d ≠ 0`
    /// and operands whose magnitude fits `I`, the result has the value `n/d` (checked by
    /// cross-multiplication, exactly), a positive denominator and coprime parts.
    #[kani::requires(d != I::ZERO && n.checked_abs().is_some() && d.checked_abs().is_some())]
    #[kani::ensures(|q: &Self| spec::is_normalised(q.n, q.d) && spec::same_value(q.n, q.d, n, d))]
    pub fn ratio(n: I, d: I) -> Self {
        assert!(d != I::ZERO, "zero denominator");
        let g = gcd(n, d).max(I::ONE);
        let mut n = n.checked_div(g).unwrap_or_else(|| overflow());
        let mut d = d.checked_div(g).unwrap_or_else(|| overflow());
        if d < I::ZERO {
            n = n.neg_exact();
            d = d.neg_exact();
        }
        Q { n, d }
    }

    /// The integer `n`.
    pub const fn integer(n: I) -> Self {
        Q { n, d: I::ONE }
    }

    /// `n/d` from `i64` values, normalised; panics if either does not fit `I` or `d == 0`.
    pub fn from_i64s(n: i64, d: i64) -> Self {
        Q::ratio(I::from_i64(n), I::from_i64(d))
    }

    /// Numerator.
    pub fn numer(self) -> I {
        self.n
    }

    /// Denominator (positive).
    pub fn denom(self) -> I {
        self.d
    }

    /// Whether the value is zero.
    pub fn is_zero(self) -> bool {
        self.n == I::ZERO
    }

    /// The sign: -1, 0 or 1.
    pub fn signum(self) -> I {
        self.n.signum()
    }

    /// `self + o`, `None` on overflow: the sum is exact, and `None` only when the unreduced sum
    /// `(n₁d₂ + n₂d₁)/(d₁d₂)` has a part outside `±I::MAX`.
    ///
    /// Contract (proved by `proofs::contracts::checked_add_is_exact`): for operands with
    /// positive denominators, a `Some` is normalised with the exact value of the sum
    /// (cross-multiplied), and `None` only when the unreduced sum does not fit.
    #[kani::requires(self.d > I::ZERO && o.d > I::ZERO)]
    #[kani::ensures(|r: &Option<Self>| match r {
        Some(q) => spec::is_normalised(q.n, q.d) && spec::is_sum(self.n, self.d, o.n, o.d, q.n, q.d),
        None => !spec::unreduced_sum_fits::<I>(self.n, self.d, o.n, o.d),
    })]
    pub fn checked_add(self, o: Q<I>) -> Option<Q<I>> {
        let fits = |v: I| v.checked_abs().is_some();
        let (n, d) = if self.d == o.d {
            (self.n.checked_add(o.n)?, self.d)
        } else {
            let n = self
                .n
                .checked_mul(o.d)?
                .checked_add(o.n.checked_mul(self.d)?)?;
            (n, self.d.checked_mul(o.d)?)
        };
        (fits(n) && fits(d)).then(|| Q::ratio(n, d))
    }

    /// `self · o`, `None` on overflow: the product is exact, and `None` only when the product
    /// in lowest terms has a part outside `±I::MAX`.
    ///
    /// Contract (proved by `proofs::contracts::checked_mul_is_exact`): for normalised operands
    /// whose numerators' magnitudes fit `I`, a `Some` is normalised with the exact value of the
    /// product (cross-multiplied), and `None` only when the product in lowest terms does not
    /// fit.
    #[kani::requires(spec::is_normalised(self.n, self.d) && spec::is_normalised(o.n, o.d)
        && self.n.checked_abs().is_some() && o.n.checked_abs().is_some())]
    #[kani::ensures(|r: &Option<Self>| match r {
        Some(q) => spec::is_normalised(q.n, q.d) && spec::is_product(self.n, self.d, o.n, o.d, q.n, q.d),
        None => !spec::lowest_product_fits::<I>(self.n, self.d, o.n, o.d),
    })]
    pub fn checked_mul(self, o: Q<I>) -> Option<Q<I>> {
        let g1 = gcd(self.n, o.d).max(I::ONE);
        let g2 = gcd(o.n, self.d).max(I::ONE);
        let n = self.n.checked_div(g1)?.checked_mul(o.n.checked_div(g2)?)?;
        let d = self.d.checked_div(g2)?.checked_mul(o.d.checked_div(g1)?)?;
        n.checked_abs()?;
        Some(Q::ratio(n, d))
    }

    /// `self^k`.
    pub fn pow(self, k: u32) -> Self {
        let mut r = Self::one();
        for _ in 0..k {
            r = r * self;
        }
        r
    }
}

impl Q {
    /// Zero (`i128`).
    pub const ZERO: Q = Q { n: 0, d: 1 };
    /// One (`i128`).
    pub const ONE: Q = Q { n: 1, d: 1 };

    /// `n/d`, normalised (`i128`). Panics if `d == 0` (a bug, never input).
    pub fn new(n: i128, d: i128) -> Q {
        Q::ratio(n, d)
    }

    /// The integer `n` (`i128`).
    pub const fn int(n: i128) -> Q {
        Q { n, d: 1 }
    }

    /// The big-rational value (exact). Only with the `bignum` feature, which `truecost`
    /// enables and the Kani build (`truecost-proofs`) does not.
    #[cfg(feature = "bignum")]
    pub fn to_rational(self) -> num_rational::BigRational {
        use num_bigint::BigInt;
        num_rational::BigRational::new(BigInt::from(self.n), BigInt::from(self.d))
    }
}

impl<I: ExactInt> std::ops::Add for Q<I> {
    type Output = Q<I>;
    fn add(self, o: Q<I>) -> Q<I> {
        self.checked_add(o).unwrap_or_else(|| overflow())
    }
}

impl<I: ExactInt> std::ops::Neg for Q<I> {
    type Output = Q<I>;
    fn neg(self) -> Q<I> {
        Q {
            n: self.n.neg_exact(),
            d: self.d,
        }
    }
}

impl<I: ExactInt> std::ops::Sub for Q<I> {
    type Output = Q<I>;
    fn sub(self, o: Q<I>) -> Q<I> {
        self + (-o)
    }
}

impl<I: ExactInt> std::ops::Mul for Q<I> {
    type Output = Q<I>;
    fn mul(self, o: Q<I>) -> Q<I> {
        self.checked_mul(o).unwrap_or_else(|| overflow())
    }
}

impl<I: ExactInt> std::ops::Div for Q<I> {
    type Output = Q<I>;
    fn div(self, o: Q<I>) -> Q<I> {
        assert!(o.n != I::ZERO, "division by zero");
        self * Q::ratio(o.d, o.n)
    }
}

impl<I: ExactInt> PartialOrd for Q<I> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<I: ExactInt> Ord for Q<I> {
    fn cmp(&self, o: &Self) -> Ordering {
        self.n.mul_exact(o.d).cmp(&o.n.mul_exact(self.d))
    }
}

impl<I: ExactInt> fmt::Display for Q<I> {
    /// `"3"` or `"-7/2"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.d == I::ONE {
            write!(f, "{}", self.n)
        } else {
            write!(f, "{}/{}", self.n, self.d)
        }
    }
}

/// The guarantees of [`gcd`], [`Q::ratio`], [`Q::checked_add`] and [`Q::checked_mul`] (their
/// contracts' clauses), stated independently of how those functions compute: values are
/// compared by cross-multiplication in 256 bits (exact for every width), coprimality by a
/// Euclid loop of its own on `u128` magnitudes. The "does not fit" statements are computed in
/// `i128`: exact for every width up to `i64`; for `i128` operands whose products leave `i128`
/// they hold trivially (they then claim nothing).
pub mod spec {
    use super::ExactInt;

    /// `g ≥ 0`, `g = 0` exactly when `a = b = 0`, and `g` divides `a` and `b` (`gcd`'s contract).
    pub fn is_common_divisor<I: ExactInt>(a: I, b: I, g: I) -> bool {
        let (a, b, g) = (a.to_i128(), b.to_i128(), g.to_i128());
        g >= 0 && ((g == 0) == (a == 0 && b == 0)) && (g == 0 || (a % g == 0 && b % g == 0))
    }

    /// `d > 0` and `gcd(|n|, d) = 1` (Euclid written here, on magnitudes).
    pub fn is_normalised<I: ExactInt>(n: I, d: I) -> bool {
        let (n, d) = (n.to_i128(), d.to_i128());
        d > 0 && coprime(n.unsigned_abs(), d.unsigned_abs())
    }

    fn coprime(mut a: u128, mut b: u128) -> bool {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a == 1
    }

    /// The 256-bit magnitude of `a · b` as (high, low) halves, and whether it is negative.
    fn product(a: i128, b: i128) -> (bool, u128, u128) {
        let (x, y) = (a.unsigned_abs(), b.unsigned_abs());
        let (x1, x0, y1, y0) = (x >> 64, x & u64::MAX as u128, y >> 64, y & u64::MAX as u128);
        let (lo, mid1, mid2, hi) = (x0 * y0, x0 * y1, x1 * y0, x1 * y1);
        let (mid, carry_mid) = mid1.overflowing_add(mid2);
        let (low, carry_low) = lo.overflowing_add(mid << 64);
        let high = hi + (mid >> 64) + ((carry_mid as u128) << 64) + carry_low as u128;
        let zero = high == 0 && low == 0;
        (!zero && ((a < 0) != (b < 0)), high, low)
    }

    /// `a · b = c · d`, exactly.
    fn products_equal(a: i128, b: i128, c: i128, d: i128) -> bool {
        product(a, b) == product(c, d)
    }

    /// `n1/d1 = n2/d2` (non-zero denominators), by cross-multiplication.
    pub fn same_value<I: ExactInt>(n1: I, d1: I, n2: I, d2: I) -> bool {
        products_equal(n1.to_i128(), d2.to_i128(), n2.to_i128(), d1.to_i128())
    }

    /// `n/d = n1/d1 + n2/d2`: `n·d1·d2 = (n1·d2 + n2·d1)·d`, checked as
    /// `(n·d1 − n1·d)·d2 = n2·d1·d` in 128-bit values where they fit (widths up to `i32`
    /// always), else `false`.
    pub fn is_sum<I: ExactInt>(n1: I, d1: I, n2: I, d2: I, n: I, d: I) -> bool {
        let [n1, d1, n2, d2, n, d] = [n1, d1, n2, d2, n, d].map(ExactInt::to_i128);
        let lhs = n
            .checked_mul(d1)
            .zip(n1.checked_mul(d))
            .and_then(|(a, b)| a.checked_sub(b));
        let rhs = n2.checked_mul(d1);
        match (lhs, rhs) {
            (Some(l), Some(r)) => products_equal(l, d2, r, d),
            _ => false,
        }
    }

    /// `n/d = (n1/d1)·(n2/d2)`: `n·d1·d2 = n1·n2·d`, in 128-bit values where they fit (widths
    /// up to `i32` always), else `false`.
    pub fn is_product<I: ExactInt>(n1: I, d1: I, n2: I, d2: I, n: I, d: I) -> bool {
        let [n1, d1, n2, d2, n, d] = [n1, d1, n2, d2, n, d].map(ExactInt::to_i128);
        match (n.checked_mul(d1), n1.checked_mul(n2)) {
            (Some(l), Some(r)) => products_equal(l, d2, r, d),
            _ => false,
        }
    }

    /// `v` lies in `±I::MAX`.
    fn fits<I: ExactInt>(v: i128) -> bool {
        I::from_i128(v).is_some_and(|x| x.checked_abs().is_some())
    }

    /// The unreduced sum `(n1·d2 + n2·d1)/(d1·d2)` has both parts in `±I::MAX`.
    pub fn unreduced_sum_fits<I: ExactInt>(n1: I, d1: I, n2: I, d2: I) -> bool {
        let [n1, d1, n2, d2] = [n1, d1, n2, d2].map(ExactInt::to_i128);
        let n = n1
            .checked_mul(d2)
            .zip(n2.checked_mul(d1))
            .and_then(|(a, b)| a.checked_add(b));
        let d = d1.checked_mul(d2);
        n.zip(d).is_some_and(|(n, d)| fits::<I>(n) && fits::<I>(d))
    }

    /// The product `(n1·n2)/(d1·d2)` in lowest terms has both parts in `±I::MAX`.
    pub fn lowest_product_fits<I: ExactInt>(n1: I, d1: I, n2: I, d2: I) -> bool {
        let [n1, d1, n2, d2] = [n1, d1, n2, d2].map(ExactInt::to_i128);
        let (Some(n), Some(d)) = (n1.checked_mul(n2), d1.checked_mul(d2)) else {
            return false;
        };
        let (mut a, mut b) = (n.unsigned_abs(), d.unsigned_abs());
        while b != 0 {
            (a, b) = (b, a % b);
        }
        let g = a.max(1);
        let (n, d) = (n.unsigned_abs() / g, d.unsigned_abs() / g);
        i128::try_from(n).is_ok_and(fits::<I>) && i128::try_from(d).is_ok_and(fits::<I>)
    }
}

/// An exact extended rational: `-∞`, a rational, or `+∞` (total costs and rewards).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum Ext {
    /// `-∞`.
    NegInf,
    /// A finite value.
    Fin(Q),
    /// `+∞`.
    PosInf,
}

impl fmt::Display for Ext {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Ext::NegInf => write!(f, "-inf"),
            Ext::Fin(q) => write!(f, "{q}"),
            Ext::PosInf => write!(f, "inf"),
        }
    }
}

/// An unnormalised exact fraction `n/d` (`d > 0`), compared by cross-multiplication: the fast
/// path of the enumeration engines (no gcd). Checked arithmetic.
#[derive(Clone, Copy, Debug)]
pub struct Frac<I: ExactInt = i128> {
    /// Numerator.
    pub n: I,
    /// Denominator (positive).
    pub d: I,
}

impl<I: ExactInt> PartialEq for Frac<I> {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl<I: ExactInt> Eq for Frac<I> {}
impl<I: ExactInt> PartialOrd for Frac<I> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl<I: ExactInt> Ord for Frac<I> {
    fn cmp(&self, o: &Self) -> Ordering {
        self.n.mul_exact(o.d).cmp(&o.n.mul_exact(self.d))
    }
}

/// An extended unnormalised fraction (`-∞ < finite < +∞`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum FracExt<I: ExactInt = i128> {
    /// `-∞`.
    NegInf,
    /// Finite.
    Fin(Frac<I>),
    /// `+∞`.
    PosInf,
}

/// `b^k` checked (`i128`).
pub fn ipow(b: i128, k: usize) -> i128 {
    power(b, k)
}

/// `b^k` checked, in any width.
pub fn power<I: ExactInt>(b: I, k: usize) -> I {
    let mut r = I::ONE;
    for _ in 0..k {
        r = r.mul_exact(b);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation at 16 bits gives the `i128` result wherever the 16-bit one does not
    /// overflow (the widths differ only in where they report overflow).
    #[test]
    fn narrow_widths_agree_with_i128() {
        let values: Vec<(i16, i16)> = (-12..=12)
            .flat_map(|n| (1..=12).flat_map(move |d| [(n, d), (n, -d)]))
            .collect();
        let wide = |q: Q<i16>| Q::new(q.numer() as i128, q.denom() as i128);
        for &(n1, d1) in &values {
            let a = Q::<i16>::ratio(n1, d1);
            let wa = Q::new(n1 as i128, d1 as i128);
            assert_eq!(wide(a), wa);
            for &(n2, d2) in &values {
                let b = Q::<i16>::ratio(n2, d2);
                let wb = Q::new(n2 as i128, d2 as i128);
                assert_eq!(wide(a + b), wa + wb);
                assert_eq!(wide(a - b), wa - wb);
                assert_eq!(wide(a * b), wa * wb);
                if !b.is_zero() {
                    assert_eq!(wide(a / b), wa / wb);
                }
                assert_eq!(a.cmp(&b), wa.cmp(&wb));
            }
        }
    }

    /// The contracts' clauses on hand-checked values: a wrong sum, product or unreduced result
    /// is rejected; the 256-bit cross product is exact where `i128` would overflow.
    #[test]
    fn spec_clauses_reject_wrong_results() {
        assert!(spec::is_sum(1i16, 2, 1, 3, 5, 6));
        assert!(!spec::is_sum(1i16, 2, 1, 3, 2, 5));
        assert!(spec::is_product(2i16, 3, 3, 4, 1, 2));
        assert!(!spec::is_product(2i16, 3, 3, 4, 1, 3));
        assert!(spec::is_normalised(-3i8, 4) && !spec::is_normalised(2i8, 4));
        assert!(!spec::is_normalised(1i8, -1));
        assert!(spec::is_common_divisor(12i32, -18, 6) && spec::is_common_divisor(0i32, 0, 0));
        assert!(!spec::is_common_divisor(12i32, 18, 4) && !spec::is_common_divisor(0i32, 5, 0));
        // (2^100)·(2^100) = (2^101)·(2^99), far beyond i128.
        let (a, b) = (1i128 << 100, 1i128 << 99);
        assert!(spec::same_value(a, b, 2 * a, 2 * b));
        assert!(!spec::same_value(a, b, 2 * a + 1, 2 * b));
        assert!(spec::unreduced_sum_fits(100i8, 1, 27, 1));
        assert!(!spec::unreduced_sum_fits(100i8, 1, 28, 1));
        assert!(spec::lowest_product_fits(100i8, 3, 3, 100));
        assert!(!spec::lowest_product_fits(16i8, 1, 8, 1));
    }

    /// An overflow at a narrow width panics, never wraps: 100 + 100 does not fit an `i8`, nor
    /// does the cross product of 100/1 and 1/100, nor `-(-128)`.
    #[test]
    fn narrow_overflow_panics() {
        let big = Q::<i8>::integer(100);
        assert!(std::panic::catch_unwind(|| big + big).is_err());
        let small = Q::<i8>::ratio(1, 100);
        assert!(std::panic::catch_unwind(|| big.cmp(&small)).is_err());
        assert!(std::panic::catch_unwind(|| -Q::<i8>::integer(i8::MIN)).is_err());
        assert!(std::panic::catch_unwind(|| Q::<i8>::ratio(i8::MIN, -1)).is_err());
        assert!(std::panic::catch_unwind(|| Q::<i8>::from_i64s(128, 1)).is_err());
        assert_eq!(Q::<i8>::from_i64s(-6, 4), Q::<i8>::ratio(-3, 2));
    }
}

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
    /// The width in bits.
    const BITS: u32;
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
            const BITS: u32 = <$t>::BITS;
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

/// A fraction in lowest terms together with the witness that it is: `num/den` with
/// `den > 0` and Bézout coefficients `x`, `y` with `num·x + den·y = 1`. The identity proves
/// `gcd(num, den) = 1` without a loop (a common divisor of `num` and `den` divides `1`), which
/// is what lets a contract state coprimality (see [`lowest_terms`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Lowest<I: ExactInt> {
    /// Numerator (sign of the fraction).
    pub num: I,
    /// Denominator (positive).
    pub den: I,
    /// Bézout coefficient of `num`.
    pub x: I,
    /// Bézout coefficient of `den`.
    pub y: I,
}

/// `n/d` in lowest terms with a Bézout witness, by the extended Euclid algorithm on `|n|` and
/// `|d|`: the remainders `r` with coefficients `s`, `t` (`r = s·|n| + t·|d|`), until the
/// remainder is zero. Then the last non-zero remainder is `g = gcd(|n|, |d|) = s₀·|n| + t₀·|d|`,
/// and the next row `s₁·|n| + t₁·|d| = 0` has `|s₁| = |d|/g`, `|t₁| = |n|/g`: the reduced
/// fraction is read off it (no division by `g`), and `(s₀, t₀)` is its witness. Every
/// coefficient is at most `max(|n|, |d|)/g` in magnitude, so nothing overflows `I`. Panics if
/// `d == 0` (a bug, never input) or if a magnitude does not fit `I`. The loop runs as often as
/// Euclid's (Lamé: at most `1 + k` times when the smaller magnitude is below `F(k+2)`).
///
/// ```
/// use truecost_kernel::claims::exact::lowest_terms;
/// let l = lowest_terms::<i16>(6, -4);
/// assert_eq!((l.num, l.den), (-3, 2));
/// assert_eq!(l.num * l.x + l.den * l.y, 1);
/// ```
///
/// Contract (proved once by `proofs::contracts::lowest_terms_has_a_bezout_witness`; the
/// harnesses use it through `stub_verified`, so none of them unrolls this loop): for `d ≠ 0`
/// and magnitudes that fit `I`, the result has a positive denominator, the value `n/d`
/// (cross-multiplied, exactly) and the witness `num·x + den·y = 1` (in a wider integer). Every
/// clause is loop-free.
#[kani::requires(d != I::ZERO && n.checked_abs().is_some() && d.checked_abs().is_some())]
#[kani::ensures(|r: &Lowest<I>| spec::is_lowest_form(n, d, r))]
pub fn lowest_terms<I: ExactInt>(n: I, d: I) -> Lowest<I> {
    assert!(d != I::ZERO, "zero denominator");
    // The product's `i128` values almost always fit `i64`, where a division is one machine
    // instruction instead of a library call: the same algorithm, run at 64 bits. (A constant
    // condition at the harnesses' widths.)
    if I::BITS > 64 {
        let narrow = |v: I| i64::from_i128(v.to_i128()).filter(|&v| v != i64::MIN);
        if let (Some(n), Some(d)) = (narrow(n), narrow(d)) {
            let l = extended_euclid(n, d);
            let wide = |v: i64| I::from_i128(v as i128).unwrap_or_else(|| overflow());
            return Lowest {
                num: wide(l.num),
                den: wide(l.den),
                x: wide(l.x),
                y: wide(l.y),
            };
        }
    }
    extended_euclid(n, d)
}

/// The extended Euclid algorithm of [`lowest_terms`] (`d ≠ 0`), at the width `I`.
fn extended_euclid<I: ExactInt>(n: I, d: I) -> Lowest<I> {
    let a = n.checked_abs().unwrap_or_else(|| overflow());
    let b = d.checked_abs().unwrap_or_else(|| overflow());
    let (mut r0, mut r1) = (a, b);
    let (mut s0, mut s1) = (I::ONE, I::ZERO);
    let (mut t0, mut t1) = (I::ZERO, I::ONE);
    while r1 != I::ZERO {
        let q = r0.checked_div(r1).unwrap_or_else(|| overflow());
        (r0, r1) = (r1, r0.sub_exact(q.mul_exact(r1)));
        (s0, s1) = (s1, s0.sub_exact(q.mul_exact(s1)));
        (t0, t1) = (t1, t0.sub_exact(q.mul_exact(t1)));
    }
    let reduced_n = t1.checked_abs().unwrap_or_else(|| overflow());
    let reduced_d = s1.checked_abs().unwrap_or_else(|| overflow());
    // `(σ·|n|/g)·(σ·s₀) + (|d|/g)·t₀ = (s₀·|n| + t₀·|d|)/g = 1` for either sign `σ`.
    if (n < I::ZERO) != (d < I::ZERO) {
        Lowest {
            num: reduced_n.neg_exact(),
            den: reduced_d,
            x: s0.neg_exact(),
            y: t0,
        }
    } else {
        Lowest {
            num: reduced_n,
            den: reduced_d,
            x: s0,
            y: t0,
        }
    }
}

/// The greatest common divisor of `|a|` and `|b|` (`gcd(0, 0) = 0`): `|a|` when `b = 0`,
/// otherwise `|b|` over the denominator of `a/b` in lowest terms ([`lowest_terms`], whose
/// extended Euclid loop is the only one of this module).
///
/// Contract (proved once by `proofs::contracts::gcd_divides_both`, with [`lowest_terms`]
/// replaced by its contract): for operands whose magnitude fits `I`, the result is
/// non-negative, zero exactly when both operands are, and divides both.
#[kani::requires(a.checked_abs().is_some() && b.checked_abs().is_some())]
#[kani::ensures(|g: &I| spec::is_common_divisor(a, b, *g))]
pub fn gcd<I: ExactInt>(a: I, b: I) -> I {
    let magnitude_b = b.checked_abs().unwrap_or_else(|| overflow());
    if b == I::ZERO {
        return a.checked_abs().unwrap_or_else(|| overflow());
    }
    magnitude_b
        .checked_div(lowest_terms(a, b).den)
        .unwrap_or_else(|| overflow())
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

    /// `n/d`, normalised: the fraction of [`lowest_terms`]`(n, d)` (positive denominator,
    /// coprime parts, the value `n/d`; its contract is this function's). Panics if `d == 0` (a
    /// bug, never input) or on overflow.
    pub fn ratio(n: I, d: I) -> Self {
        let l = lowest_terms(n, d);
        Q { n: l.num, d: l.den }
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
    /// Contract (proved by `proofs::contracts::checked_add_is_exact`, with [`lowest_terms`]
    /// replaced by its contract): for operands with positive denominators, a `Some` has a
    /// positive denominator and the exact value of the sum (cross-multiplied), and `None` comes
    /// only when the unreduced sum does not fit. (That a `Some` is in lowest terms is
    /// [`lowest_terms`]' contract: the result is `Q::ratio` of the sum.)
    #[kani::requires(self.d > I::ZERO && o.d > I::ZERO)]
    #[kani::ensures(|r: &Option<Self>| match r {
        Some(q) => q.d > I::ZERO && spec::is_sum(self.n, self.d, o.n, o.d, q.n, q.d),
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

    /// `self · o`, `None` on overflow: the product is exact. It cross-cancels first (`n₁/d₂`
    /// and `n₂/d₁` in lowest terms, by [`lowest_terms`]), so for normalised operands `None`
    /// comes only when the product in lowest terms has a part outside `±I::MAX`.
    ///
    /// Contract (proved by `proofs::contracts::checked_mul_is_exact`, with [`lowest_terms`]
    /// replaced by its contract): for operands with positive denominators whose numerators'
    /// magnitudes fit `I`, a `Some` has a positive denominator and the exact value of the
    /// product (cross-multiplied), and `None` comes only when the unreduced product
    /// `(n₁n₂)/(d₁d₂)` does not fit.
    #[kani::requires(self.d > I::ZERO && o.d > I::ZERO
        && self.n.checked_abs().is_some() && o.n.checked_abs().is_some())]
    #[kani::ensures(|r: &Option<Self>| match r {
        Some(q) => q.d > I::ZERO && spec::is_product(self.n, self.d, o.n, o.d, q.n, q.d),
        None => !spec::unreduced_product_fits::<I>(self.n, self.d, o.n, o.d),
    })]
    pub fn checked_mul(self, o: Q<I>) -> Option<Q<I>> {
        // n₁/d₂ and n₂/d₁ in lowest terms; the denominators stay positive.
        let a = lowest_terms(self.n, o.d);
        let b = lowest_terms(o.n, self.d);
        let n = a.num.checked_mul(b.num)?;
        let d = b.den.checked_mul(a.den)?;
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

/// The guarantees of [`lowest_terms`], [`gcd`], [`Q::checked_add`] and [`Q::checked_mul`]
/// (their contracts' clauses), stated independently of how those functions compute, and
/// without a loop (a contract's clause is evaluated at every call a verified stub replaces):
/// values are compared by cross-multiplication — in `i32` for widths up to 16 bits, in 256
/// bits otherwise (exact for every width) — and coprimality by a Bézout identity
/// `num·x + den·y = 1` on the witness the function returns. The "does not fit" statements are
/// computed in `i128`: exact for every width up to `i64`; for `i128` operands whose products
/// leave `i128` they hold trivially (they then claim nothing).
pub mod spec {
    use super::{ExactInt, Lowest};

    /// `g ≥ 0`, `g = 0` exactly when `a = b = 0`, and `g` divides `a` and `b` (`gcd`'s contract).
    pub fn is_common_divisor<I: ExactInt>(a: I, b: I, g: I) -> bool {
        let (a, b, g) = (a.to_i128(), b.to_i128(), g.to_i128());
        g >= 0 && ((g == 0) == (a == 0 && b == 0)) && (g == 0 || (a % g == 0 && b % g == 0))
    }

    /// `l` is `n/d` in lowest terms with its witness: `l.den > 0`, `l.num/l.den = n/d` and
    /// `l.num·l.x + l.den·l.y = 1` (`lowest_terms`' contract; `d ≠ 0`).
    pub fn is_lowest_form<I: ExactInt>(n: I, d: I, l: &Lowest<I>) -> bool {
        l.den > I::ZERO && same_value(l.num, l.den, n, d) && is_bezout_one(l.num, l.x, l.den, l.y)
    }

    /// `a·x + b·y = 1`, exactly: in `i32` for widths up to 16 bits (each product is below
    /// `2^30` in magnitude; a sum that leaves `i32` is not 1), in 256 bits otherwise.
    pub fn is_bezout_one<I: ExactInt>(a: I, x: I, b: I, y: I) -> bool {
        let [a, x, b, y] = [a, x, b, y].map(ExactInt::to_i128);
        if I::BITS <= 16 {
            let (a, x, b, y) = (a as i32, x as i32, b as i32, y as i32);
            return (a * x).checked_add(b * y) == Some(1);
        }
        // a·x + b·y = 1 with magnitudes P = |a·x|, R = |b·y|: both non-negative means
        // {P, R} = {0, 1}; opposite signs mean the non-negative one exceeds the other by 1.
        let (p_neg, p_high, p_low) = product(a, x);
        let (r_neg, r_high, r_low) = product(b, y);
        let (p, r) = ((p_high, p_low), (r_high, r_low));
        match (p_neg, r_neg) {
            (false, false) => (p == (0, 1) && r == (0, 0)) || (p == (0, 0) && r == (0, 1)),
            (false, true) => p == successor(r),
            (true, false) => r == successor(p),
            (true, true) => false,
        }
    }

    /// `m + 1` for a 256-bit magnitude `m < 2^255` (every product of two `i128` values is).
    fn successor((high, low): (u128, u128)) -> (u128, u128) {
        match low.checked_add(1) {
            Some(l) => (high, l),
            None => (high + 1, 0),
        }
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

    /// `n1/d1 = n2/d2` (non-zero denominators), by cross-multiplication: in `i32` for widths
    /// up to 16 bits (products below `2^30` in magnitude), in 256 bits otherwise.
    pub fn same_value<I: ExactInt>(n1: I, d1: I, n2: I, d2: I) -> bool {
        let [n1, d1, n2, d2] = [n1, d1, n2, d2].map(ExactInt::to_i128);
        if I::BITS <= 16 {
            let (n1, d1, n2, d2) = (n1 as i32, d1 as i32, n2 as i32, d2 as i32);
            return n1 * d2 == n2 * d1;
        }
        products_equal(n1, d2, n2, d1)
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

    /// The unreduced product `(n1·n2)/(d1·d2)` has both parts in `±I::MAX`.
    pub fn unreduced_product_fits<I: ExactInt>(n1: I, d1: I, n2: I, d2: I) -> bool {
        let [n1, d1, n2, d2] = [n1, d1, n2, d2].map(ExactInt::to_i128);
        let n = n1.checked_mul(n2);
        let d = d1.checked_mul(d2);
        n.zip(d).is_some_and(|(n, d)| fits::<I>(n) && fits::<I>(d))
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

    /// The contracts' clauses on hand-checked values: a wrong sum, product, unreduced result or
    /// witness is rejected; the 256-bit cross product is exact where `i128` would overflow.
    #[test]
    fn spec_clauses_reject_wrong_results() {
        assert!(spec::is_sum(1i16, 2, 1, 3, 5, 6));
        assert!(!spec::is_sum(1i16, 2, 1, 3, 2, 5));
        assert!(spec::is_product(2i16, 3, 3, 4, 1, 2));
        assert!(!spec::is_product(2i16, 3, 3, 4, 1, 3));
        let lowest = |num, den, x, y| Lowest { num, den, x, y };
        // 6/-4 = -3/2, and -3·1 + 2·2 = 1.
        assert!(spec::is_lowest_form(6i8, -4, &lowest(-3, 2, 1, 2)));
        assert!(
            !spec::is_lowest_form(6i8, -4, &lowest(-3, 2, 1, 1)),
            "not a witness"
        );
        assert!(
            !spec::is_lowest_form(6i8, -4, &lowest(3, -2, 1, 2)),
            "negative denominator"
        );
        assert!(
            !spec::is_lowest_form(6i8, -4, &lowest(-6, 4, 1, 2)),
            "not reduced"
        );
        assert!(
            !spec::is_lowest_form(6i8, -4, &lowest(-1, 2, 1, 1)),
            "another value"
        );
        assert!(spec::is_common_divisor(12i32, -18, 6) && spec::is_common_divisor(0i32, 0, 0));
        assert!(!spec::is_common_divisor(12i32, 18, 4) && !spec::is_common_divisor(0i32, 5, 0));
        // (2^100)·(2^100) = (2^101)·(2^99), far beyond i128.
        let (a, b) = (1i128 << 100, 1i128 << 99);
        assert!(spec::same_value(a, b, 2 * a, 2 * b));
        assert!(!spec::same_value(a, b, 2 * a + 1, 2 * b));
        // A witness whose products leave i128: (2^100 + 1)·(2^100 − 1) − 2^100·2^100 = −1.
        let (p, m) = ((1i128 << 100) + 1, (1i128 << 100) - 1);
        assert!(spec::is_bezout_one(p, -m, a, a));
        assert!(!spec::is_bezout_one(p, m, a, -a), "the sum is -1");
        assert!(
            !spec::is_bezout_one(p, -m, a, a + 1),
            "the sum is 1 + 2^100"
        );
        assert!(spec::unreduced_sum_fits(100i8, 1, 27, 1));
        assert!(!spec::unreduced_sum_fits(100i8, 1, 28, 1));
        assert!(spec::unreduced_product_fits(10i8, 3, 12, 7));
        assert!(!spec::unreduced_product_fits(16i8, 1, 8, 1));
        assert!(!spec::unreduced_product_fits(1i8, 16, 1, 8));
    }

    /// `a·x + b·y = 1` by the narrow path (`i16`, in `i32`) and the 256-bit path (the same
    /// values as `i32`) agree, on a grid with both signs and every boundary value.
    #[test]
    fn bezout_clause_paths_agree() {
        let values: Vec<i16> = [
            i16::MIN,
            i16::MIN + 1,
            -300,
            -7,
            -2,
            -1,
            0,
            1,
            2,
            3,
            7,
            255,
            301,
        ]
        .into_iter()
        .chain([i16::MAX - 1, i16::MAX])
        .collect();
        let mut ones = 0;
        for &a in &values {
            for &x in &values {
                for &b in &values {
                    for &y in &values {
                        let narrow = spec::is_bezout_one(a, x, b, y);
                        let wide = spec::is_bezout_one(a as i32, x as i32, b as i32, y as i32);
                        let exact = a as i64 * x as i64 + b as i64 * y as i64 == 1;
                        assert_eq!((narrow, wide), (exact, exact), "{a}·{x} + {b}·{y}");
                        ones += exact as u32;
                    }
                }
            }
        }
        assert!(ones > 50, "the grid has solutions ({ones})");
    }

    /// `lowest_terms` on every `i8` pair (`d ≠ 0`, no `-128`): the reduced fraction found by
    /// trial division here, a positive denominator, and a witness `num·x + den·y = 1`; `gcd`
    /// is the largest common divisor found by trial.
    #[test]
    fn lowest_terms_of_every_i8_pair() {
        for n in -127i8..=127 {
            for d in -127i8..=127 {
                let (ni, di) = (n as i32, d as i32);
                let g = (1..=127)
                    .filter(|k| ni % k == 0 && di % k == 0)
                    .max()
                    .unwrap_or(0);
                let expected = if n == 0 && d == 0 { 0 } else { g };
                assert_eq!(gcd(n, d) as i32, expected, "gcd({n}, {d})");
                if d == 0 {
                    continue;
                }
                let l = lowest_terms(n, d);
                let sign = if (ni < 0) != (di < 0) { -1 } else { 1 };
                assert_eq!(
                    (l.num as i32, l.den as i32),
                    (sign * ni.abs() / g, di.abs() / g),
                    "{n}/{d}"
                );
                assert_eq!(l.num as i32 * l.x as i32 + l.den as i32 * l.y as i32, 1);
            }
        }
    }

    /// `lowest_terms` at `i128` on values far beyond `i64` (Fibonacci neighbours: the longest
    /// Euclid runs), with the witness checked by the 256-bit clause.
    #[test]
    fn lowest_terms_at_i128_with_long_runs() {
        let (mut a, mut b) = (1i128, 1i128);
        while let Some(c) = a.checked_add(b) {
            (a, b) = (b, c);
        }
        // a, b consecutive Fibonacci numbers near i128::MAX: coprime.
        // Beyond i64, at its edge (i64::MIN takes the 128-bit loop) and inside it (the 64-bit
        // one).
        let (min, max) = (i64::MIN as i128, i64::MAX as i128);
        for (n, d) in [
            (a, b),
            (-b, a),
            (a, -a),
            (6 * (a / 6), 4 * (a / 6)),
            (min, 6),
            (max, min),
            (-max, max - 1),
            (6, -4),
        ] {
            let l = lowest_terms(n, d);
            assert!(spec::is_lowest_form(n, d, &l), "{n}/{d}: {l:?}");
        }
        assert_eq!((lowest_terms(a, b).num, lowest_terms(a, b).den), (a, b));
        let l = lowest_terms(a, -a);
        assert_eq!((l.num, l.den, l.num * l.x + l.den * l.y), (-1, 1, 1));
        let l = lowest_terms(6 * (a / 6), 4 * (a / 6));
        assert_eq!((l.num, l.den), (3, 2));
        // 2^63 / 6 = 2^62 / 3 (negative); 6 / -4 = -3/2.
        let l = lowest_terms(min, 6);
        assert_eq!((l.num, l.den), (-(1i128 << 62), 3));
        let l = lowest_terms(6i128, -4);
        assert_eq!((l.num, l.den), (-3, 2));
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

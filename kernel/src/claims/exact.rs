//! Small exact rationals (`i128` numerator and denominator) for the enumeration engines.
//!
//! The engines run millions of tiny problems; big rationals would dominate their time. Every
//! operation here is checked: an overflow is reported as an internal error (a panic that the
//! CLI turns into a non-zero exit), never a wrapped number. The scopes are small enough that
//! no overflow occurs (values have at most a few dozen bits).

use std::cmp::Ordering;
use std::fmt;

/// An exact rational `n/d` with `d > 0` and `gcd(n, d) = 1`.
///
/// ```
/// use truecost_kernel::claims::exact::Q;
/// assert_eq!(Q::new(2, 4) + Q::int(1), Q::new(3, 2));
/// assert!(Q::new(1, 3) < Q::new(1, 2));
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Q {
    n: i128,
    d: i128,
}

fn overflow() -> ! {
    panic!("exact arithmetic overflow in the claims engine (a truecost bug: scope bound violated)")
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        let t = a % b;
        a = b;
        b = t;
    }
    a
}

impl Q {
    /// Zero.
    pub const ZERO: Q = Q { n: 0, d: 1 };
    /// One.
    pub const ONE: Q = Q { n: 1, d: 1 };

    /// `n/d`, normalised. Panics if `d == 0` (a bug, never input).
    pub fn new(n: i128, d: i128) -> Q {
        assert!(d != 0, "zero denominator");
        let g = gcd(n, d).max(1);
        let (mut n, mut d) = (n / g, d / g);
        if d < 0 {
            n = n.checked_neg().unwrap_or_else(|| overflow());
            d = d.checked_neg().unwrap_or_else(|| overflow());
        }
        Q { n, d }
    }

    /// The integer `n`.
    pub const fn int(n: i128) -> Q {
        Q { n, d: 1 }
    }

    /// Numerator.
    pub fn numer(self) -> i128 {
        self.n
    }

    /// Denominator (positive).
    pub fn denom(self) -> i128 {
        self.d
    }

    /// Whether the value is zero.
    pub fn is_zero(self) -> bool {
        self.n == 0
    }

    /// The sign: -1, 0 or 1.
    pub fn signum(self) -> i128 {
        self.n.signum()
    }

    /// `self^k`.
    pub fn pow(self, k: u32) -> Q {
        let mut r = Q::ONE;
        for _ in 0..k {
            r = r * self;
        }
        r
    }

    /// The big-rational value (exact). Only with the `bignum` feature, which `truecost`
    /// enables and the Kani build (`truecost-proofs`) does not (issue 10, item 3).
    #[cfg(feature = "bignum")]
    pub fn to_rational(self) -> num_rational::BigRational {
        use num_bigint::BigInt;
        num_rational::BigRational::new(BigInt::from(self.n), BigInt::from(self.d))
    }
}

fn mul(a: i128, b: i128) -> i128 {
    a.checked_mul(b).unwrap_or_else(|| overflow())
}

impl std::ops::Add for Q {
    type Output = Q;
    fn add(self, o: Q) -> Q {
        if self.d == o.d {
            return Q::new(
                self.n.checked_add(o.n).unwrap_or_else(|| overflow()),
                self.d,
            );
        }
        let n = mul(self.n, o.d)
            .checked_add(mul(o.n, self.d))
            .unwrap_or_else(|| overflow());
        Q::new(n, mul(self.d, o.d))
    }
}

impl std::ops::Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        Q {
            n: self.n.checked_neg().unwrap_or_else(|| overflow()),
            d: self.d,
        }
    }
}

impl std::ops::Sub for Q {
    type Output = Q;
    fn sub(self, o: Q) -> Q {
        self + (-o)
    }
}

impl std::ops::Mul for Q {
    type Output = Q;
    fn mul(self, o: Q) -> Q {
        let g1 = gcd(self.n, o.d).max(1);
        let g2 = gcd(o.n, self.d).max(1);
        Q::new(mul(self.n / g1, o.n / g2), mul(self.d / g2, o.d / g1))
    }
}

impl std::ops::Div for Q {
    type Output = Q;
    fn div(self, o: Q) -> Q {
        assert!(o.n != 0, "division by zero");
        self * Q::new(o.d, o.n)
    }
}

impl PartialOrd for Q {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Q {
    fn cmp(&self, o: &Self) -> Ordering {
        mul(self.n, o.d).cmp(&mul(o.n, self.d))
    }
}

impl fmt::Display for Q {
    /// `"3"` or `"-7/2"`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.d == 1 {
            write!(f, "{}", self.n)
        } else {
            write!(f, "{}/{}", self.n, self.d)
        }
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
pub struct Frac {
    /// Numerator.
    pub n: i128,
    /// Denominator (positive).
    pub d: i128,
}

impl PartialEq for Frac {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Frac {}
impl PartialOrd for Frac {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Frac {
    fn cmp(&self, o: &Self) -> Ordering {
        mul(self.n, o.d).cmp(&mul(o.n, self.d))
    }
}

/// An extended unnormalised fraction (`-∞ < finite < +∞`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum FracExt {
    /// `-∞`.
    NegInf,
    /// Finite.
    Fin(Frac),
    /// `+∞`.
    PosInf,
}

/// `b^k` checked.
pub fn ipow(b: i128, k: usize) -> i128 {
    let mut r: i128 = 1;
    for _ in 0..k {
        r = mul(r, b);
    }
    r
}

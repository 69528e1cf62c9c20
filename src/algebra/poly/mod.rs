//! Exact univariate polynomials with rational coefficients, Sturm sequences, real-root
//! isolation and algebraic numbers given by an isolating interval; [`roots`] holds the exact
//! root finding and minimal polynomials of the discount breakpoints.

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

use crate::value::Rational;

pub mod roots;

/// A polynomial `Σ c_i x^i` (coefficients from the constant up; no trailing zeros).
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub struct Poly {
    c: Vec<Rational>,
}

fn r(n: i64) -> Rational {
    Rational::from_integer(BigInt::from(n))
}

impl Poly {
    /// From coefficients, constant first.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// let p = Poly::from_i64(&[-2, 0, 1]); // x^2 - 2
    /// assert_eq!(p.degree(), Some(2));
    /// assert_eq!(p.to_string(), "x^2 - 2");
    /// ```
    pub fn from_i64(c: &[i64]) -> Poly {
        Poly::new(c.iter().map(|&x| r(x)).collect())
    }

    /// From rational coefficients, constant first.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // Trailing zeros are dropped: 1 + 0·x is the constant 1.
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let p = Poly::new(vec![q("1"), q("0")]);
    /// assert_eq!((p.degree(), p.to_string()), (Some(0), "1".to_string()));
    /// ```
    pub fn new(mut c: Vec<Rational>) -> Poly {
        while c.last().is_some_and(Zero::is_zero) {
            c.pop();
        }
        Poly { c }
    }

    /// The zero polynomial.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// assert!(Poly::zero().is_zero() && Poly::zero().degree().is_none());
    /// assert_eq!(Poly::zero().to_string(), "0");
    /// ```
    pub fn zero() -> Poly {
        Poly { c: Vec::new() }
    }

    /// `x^k`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// assert_eq!(Poly::monomial(3).to_string(), "x^3");
    /// ```
    pub fn monomial(k: usize) -> Poly {
        let mut c = vec![Rational::zero(); k + 1];
        c[k] = Rational::one();
        Poly { c }
    }

    /// The degree (`None` for zero).
    pub fn degree(&self) -> Option<usize> {
        self.c.len().checked_sub(1)
    }

    /// Whether this is the zero polynomial.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// assert!(!Poly::from_i64(&[0, 1]).is_zero() && Poly::from_i64(&[0, 0]).is_zero());
    /// ```
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    /// Coefficients, constant first.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// let c: Vec<String> = Poly::from_i64(&[-2, 0, 1]).coefficients().iter().map(|c| c.to_string()).collect();
    /// assert_eq!(c, ["-2", "0", "1"]);
    /// ```
    pub fn coefficients(&self) -> &[Rational] {
        &self.c
    }

    /// The value at `x`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // x² − 2 at 3/2: 9/4 − 2 = 1/4.
    /// let v = Poly::from_i64(&[-2, 0, 1]).eval(&"3/2".parse().unwrap());
    /// assert_eq!(v, "1/4".parse().unwrap());
    /// ```
    pub fn eval(&self, x: &Rational) -> Rational {
        let mut acc = Rational::zero();
        for c in self.c.iter().rev() {
            acc = acc * x + c;
        }
        acc
    }

    /// The sign of the value at `x`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use std::cmp::Ordering;
    /// let p = Poly::from_i64(&[-2, 0, 1]); // x² − 2: −1 at 1, 2 at 2
    /// assert_eq!(p.sign_at(&"1".parse().unwrap()), Ordering::Less);
    /// assert_eq!(p.sign_at(&"2".parse().unwrap()), Ordering::Greater);
    /// ```
    pub fn sign_at(&self, x: &Rational) -> Ordering {
        self.eval(x).cmp(&Rational::zero())
    }

    /// The derivative.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x³ − 2x + 1)' = 3x² − 2
    /// assert_eq!(Poly::from_i64(&[1, -2, 0, 1]).derivative().to_string(), "3x^2 - 2");
    /// ```
    pub fn derivative(&self) -> Poly {
        Poly::new(
            self.c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, c)| c * r(i as i64))
                .collect(),
        )
    }

    /// `self + o`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x − 1) + (x + 1) = 2x
    /// assert_eq!(Poly::from_i64(&[-1, 1]).add(&Poly::from_i64(&[1, 1])).to_string(), "2x");
    /// ```
    pub fn add(&self, o: &Poly) -> Poly {
        let n = self.c.len().max(o.c.len());
        Poly::new(
            (0..n)
                .map(|i| {
                    self.c.get(i).cloned().unwrap_or_else(Rational::zero)
                        + o.c.get(i).cloned().unwrap_or_else(Rational::zero)
                })
                .collect(),
        )
    }

    /// `self - o`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x − 1) − (x + 1) = −2
    /// assert_eq!(Poly::from_i64(&[-1, 1]).sub(&Poly::from_i64(&[1, 1])).to_string(), "-2");
    /// ```
    pub fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.scale(&r(-1)))
    }

    /// `k · self`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x − 1)/2
    /// let half = "1/2".parse().unwrap();
    /// assert_eq!(Poly::from_i64(&[-1, 1]).scale(&half).to_string(), "(1/2)x - (1/2)");
    /// ```
    pub fn scale(&self, k: &Rational) -> Poly {
        Poly::new(self.c.iter().map(|c| c * k).collect())
    }

    /// `self · o`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x − 1)(x + 1) = x² − 1; a zero factor gives zero.
    /// assert_eq!(Poly::from_i64(&[-1, 1]).mul(&Poly::from_i64(&[1, 1])).to_string(), "x^2 - 1");
    /// assert!(Poly::from_i64(&[-1, 1]).mul(&Poly::zero()).is_zero());
    /// ```
    pub fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::zero();
        }
        let mut c = vec![Rational::zero(); self.c.len() + o.c.len() - 1];
        for (i, a) in self.c.iter().enumerate() {
            for (j, b) in o.c.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::new(c)
    }

    /// Quotient and remainder of the division by `d` (non-zero).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // x³ − 1 = (x − 1)(x² + x + 1); x² + 1 = (x − 1)(x + 1) + 2.
    /// let (q, r) = Poly::from_i64(&[-1, 0, 0, 1]).div_rem(&Poly::from_i64(&[-1, 1]));
    /// assert_eq!((q.to_string(), r.is_zero()), ("x^2 + x + 1".to_string(), true));
    /// let (q, r) = Poly::from_i64(&[1, 0, 1]).div_rem(&Poly::from_i64(&[-1, 1]));
    /// assert_eq!((q.to_string(), r.to_string()), ("x + 1".to_string(), "2".to_string()));
    /// ```
    pub fn div_rem(&self, d: &Poly) -> (Poly, Poly) {
        let dd = d.degree().expect("division by the zero polynomial");
        let lead = d.c[dd].clone();
        let mut rem = self.c.clone();
        let mut quo = vec![Rational::zero(); self.c.len().saturating_sub(dd).max(1)];
        while rem.len() > dd && !rem.is_empty() {
            let k = rem.len() - 1 - dd;
            let f = &rem[rem.len() - 1] / &lead;
            for (i, c) in d.c.iter().enumerate() {
                rem[k + i] -= &f * c;
            }
            quo[k] = f;
            rem.pop();
            while rem.last().is_some_and(Zero::is_zero) {
                rem.pop();
            }
        }
        (Poly::new(quo), Poly::new(rem))
    }

    /// The monic greatest common divisor.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // gcd((x − 1)(x − 2), 2(x − 1)(x + 3)) = x − 1 (monic)
    /// let a = Poly::from_i64(&[2, -3, 1]);
    /// let b = Poly::from_i64(&[-6, 4, 2]);
    /// assert_eq!(a.gcd(&b).to_string(), "x - 1");
    /// ```
    pub fn gcd(&self, o: &Poly) -> Poly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let (_, rem) = a.div_rem(&b);
            a = b;
            b = rem;
        }
        a.monic()
    }

    /// Divided by the leading coefficient.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// assert_eq!(Poly::from_i64(&[-4, 0, 2]).monic().to_string(), "x^2 - 2");
    /// ```
    pub fn monic(&self) -> Poly {
        match self.c.last() {
            None => Poly::zero(),
            Some(l) => {
                let l = l.clone();
                self.scale(&(Rational::one() / l))
            }
        }
    }

    /// The primitive integer multiple with a positive leading coefficient (for display).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // x/2 − 1/3 → 3x − 2; −2x + 4 → x − 2 (positive leading coefficient, content 1).
    /// let p = Poly::new(vec!["-1/3".parse().unwrap(), "1/2".parse().unwrap()]);
    /// assert_eq!(p.primitive().to_string(), "3x - 2");
    /// assert_eq!(Poly::from_i64(&[4, -2]).primitive().to_string(), "x - 2");
    /// ```
    pub fn primitive(&self) -> Poly {
        let mut ints = roots::integer_form(self);
        if ints.last().is_some_and(Signed::is_negative) {
            ints.iter_mut().for_each(|c| *c = -&*c);
        }
        Poly::new(ints.into_iter().map(Rational::from_integer).collect())
    }

    /// The square-free part `p / gcd(p, p')` (monic).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // (x − 1)²(x + 2) = x³ − 3x + 2 → (x − 1)(x + 2) = x² + x − 2
    /// assert_eq!(Poly::from_i64(&[2, -3, 0, 1]).squarefree().to_string(), "x^2 + x - 2");
    /// ```
    pub fn squarefree(&self) -> Poly {
        let g = self.gcd(&self.derivative());
        if g.degree() == Some(0) {
            return self.monic();
        }
        self.div_rem(&g).0.monic()
    }

    /// The Sturm sequence `p, p', -rem(p, p'), ...`.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// // x² − 2, its derivative 2x, and −rem(x² − 2, 2x) = 2.
    /// let seq: Vec<String> = Poly::from_i64(&[-2, 0, 1]).sturm().iter().map(|p| p.to_string()).collect();
    /// assert_eq!(seq, ["x^2 - 2", "2x", "2"]);
    /// ```
    pub fn sturm(&self) -> Vec<Poly> {
        let mut seq = vec![self.clone(), self.derivative()];
        while !seq[seq.len() - 1].is_zero() {
            let n = seq.len();
            let (_, rem) = seq[n - 2].div_rem(&seq[n - 1]);
            seq.push(rem.scale(&r(-1)));
        }
        seq.pop();
        seq
    }
}

fn variations(seq: &[Poly], x: &Rational) -> usize {
    let mut last = Ordering::Equal;
    let mut v = 0;
    for p in seq {
        let s = p.sign_at(x);
        if s == Ordering::Equal {
            continue;
        }
        if last != Ordering::Equal && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// Number of distinct real roots of `seq[0]` in `(lo, hi]` (Sturm's theorem).
///
/// ```
/// use truecost::algebra::poly::{count_roots, Poly};
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// // x² − 2 has the roots ±√2: one in (0, 2], two in (−2, 2], none in (3/2, 2].
/// let seq = Poly::from_i64(&[-2, 0, 1]).sturm();
/// assert_eq!(count_roots(&seq, &q("0"), &q("2")), 1);
/// assert_eq!(count_roots(&seq, &q("-2"), &q("2")), 2);
/// assert_eq!(count_roots(&seq, &q("3/2"), &q("2")), 0);
/// ```
pub fn count_roots(seq: &[Poly], lo: &Rational, hi: &Rational) -> usize {
    variations(seq, lo) - variations(seq, hi)
}

/// A real algebraic number: the unique root of `poly` in `(lo, hi]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Algebraic {
    /// A square-free polynomial vanishing at the number.
    pub poly: Poly,
    /// Lower end (exclusive).
    pub lo: Rational,
    /// Upper end (inclusive).
    pub hi: Rational,
}

impl Algebraic {
    /// Halves the bracket until its width is at most `width`.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// let mut r = sqrt2.clone();
    /// r.refine_to(&q("1/1000"));
    /// // Still a bracket (lo, hi] of √2, now at most 1/1000 wide.
    /// assert!(&r.hi - &r.lo <= q("1/1000"));
    /// assert!(&r.lo * &r.lo < q("2") && &r.hi * &r.hi > q("2"));
    /// ```
    pub fn refine_to(&mut self, width: &Rational) {
        let ints = crate::algebra::poly::roots::integer_form(&self.poly);
        if let Some(sign_lo) = self.sign_bracket(&ints) {
            // The same halves as Sturm's count: the root lies in (lo, mid] iff the sign at
            // mid is 0 or differs from the sign at lo.
            let two = r(2);
            while &(&self.hi - &self.lo) > width {
                let mid = (&self.lo + &self.hi) / &two;
                let s = crate::algebra::poly::roots::integer_sign(&ints, &mid);
                if s == Ordering::Equal || s != sign_lo {
                    self.hi = mid;
                } else {
                    self.lo = mid;
                }
            }
            return;
        }
        let seq = self.poly.sturm();
        let two = r(2);
        while &(&self.hi - &self.lo) > width {
            let mid = (&self.lo + &self.hi) / &two;
            if count_roots(&seq, &self.lo, &mid) == 1 {
                self.hi = mid;
            } else {
                self.lo = mid;
            }
        }
    }

    /// The sign of the polynomial (integer form `ints`) at `lo` when the bracket can be halved
    /// by signs alone: non-zero at both ends, of opposite signs — then the one root in the
    /// bracket is a simple root strictly inside (the polynomial is square-free), where the
    /// sign changes. `None`: Sturm's theorem decides.
    fn sign_bracket(&self, ints: &[BigInt]) -> Option<Ordering> {
        use crate::algebra::poly::roots::integer_sign;
        let (l, h) = (integer_sign(ints, &self.lo), integer_sign(ints, &self.hi));
        (l != Ordering::Equal && h != Ordering::Equal && l != h).then_some(l)
    }

    /// The rational `q` as an algebraic number (the root of `x − q` in `(q − 1, q]`).
    ///
    /// ```
    /// use truecost::algebra::poly::Algebraic;
    /// let h = Algebraic::from_rational("1/2".parse().unwrap());
    /// assert_eq!(h.as_rational(), Some("1/2".parse().unwrap()));
    /// ```
    pub fn from_rational(q: Rational) -> Algebraic {
        Algebraic {
            poly: Poly::new(vec![-q.clone(), Rational::one()]),
            lo: &q - Rational::one(),
            hi: q,
        }
    }

    /// Halves the bracket once, given the Sturm sequence of [`Self::poly`] (callers that refine
    /// often compute it once).
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// let mut r = sqrt2.clone();
    /// let width = &r.hi - &r.lo;
    /// let seq = r.poly.sturm();
    /// r.halve_with(&seq);
    /// assert_eq!(&r.hi - &r.lo, width / q("2"));
    /// assert!(&r.lo * &r.lo < q("2") && &r.hi * &r.hi > q("2"));
    /// ```
    pub fn halve_with(&mut self, seq: &[Poly]) {
        let mid = (&self.lo + &self.hi) / r(2);
        if count_roots(seq, &self.lo, &mid) == 1 {
            self.hi = mid;
        } else {
            self.lo = mid;
        }
    }

    /// The sign of the polynomial `f` at this number, exactly: `Equal` iff `f` vanishes here
    /// (a common root of `f` and [`Self::poly`] in the bracket), else the sign at a rational
    /// point of a bracket refined until it holds no root of `f`.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// use std::cmp::Ordering;
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &"0".parse().unwrap(), &"2".parse().unwrap()).remove(0);
    /// assert_eq!(sqrt2.sign_of(&Poly::from_i64(&[-2, 0, 1])), Ordering::Equal);
    /// assert_eq!(sqrt2.sign_of(&Poly::from_i64(&[-3, 2])), Ordering::Less); // 2√2 − 3 < 0
    /// ```
    pub fn sign_of(&self, f: &Poly) -> Ordering {
        if f.is_zero() {
            return Ordering::Equal;
        }
        let g = f.gcd(&self.poly);
        if g.degree().unwrap_or(0) > 0 && count_roots(&g.sturm(), &self.lo, &self.hi) >= 1 {
            return Ordering::Equal;
        }
        let seq = f.squarefree().sturm();
        let own = self.poly.sturm();
        let mut c = self.clone();
        while count_roots(&seq, &c.lo, &c.hi) > 0 || f.eval(&c.hi).is_zero() {
            c.halve_with(&own);
        }
        f.sign_at(&c.hi)
    }

    /// Whether the number is exactly the rational `hi` (the bracket's closed end).
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// use truecost::algebra::poly::Algebraic;
    /// assert!(!sqrt2.is_rational());
    /// assert!(Algebraic::from_rational(q("1/2")).is_rational());
    /// ```
    pub fn is_rational(&self) -> bool {
        self.poly.eval(&self.hi).is_zero()
    }

    /// The number as a rational, when its polynomial is linear or it is the bracket's end.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// use truecost::algebra::poly::Algebraic;
    /// assert_eq!(sqrt2.as_rational(), None);
    /// assert_eq!(Algebraic::from_rational(q("1/3")).as_rational(), Some(q("1/3")));
    /// ```
    pub fn as_rational(&self) -> Option<Rational> {
        if self.poly.degree() == Some(1) {
            let c = self.poly.coefficients();
            return Some(-&c[0] / &c[1]);
        }
        self.is_rational().then(|| self.hi.clone())
    }

    /// Compares with a rational.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// use std::cmp::Ordering;
    /// // 7/5 = 1.4 < √2 = 1.41421… < 3/2
    /// assert_eq!(sqrt2.cmp_rational(&q("7/5")), Ordering::Greater);
    /// assert_eq!(sqrt2.cmp_rational(&q("3/2")), Ordering::Less);
    /// ```
    pub fn cmp_rational(&self, x: &Rational) -> Ordering {
        if x > &self.hi {
            return Ordering::Less;
        }
        if x <= &self.lo {
            return Ordering::Greater;
        }
        // lo < x <= hi: is the root in (lo, x]?
        if self.poly.eval(x).is_zero() {
            return Ordering::Equal;
        }
        let ints = crate::algebra::poly::roots::integer_form(&self.poly);
        if let Some(sign_lo) = self.sign_bracket(&ints) {
            return if crate::algebra::poly::roots::integer_sign(&ints, x) != sign_lo {
                Ordering::Less
            } else {
                Ordering::Greater
            };
        }
        let seq = self.poly.sturm();
        if count_roots(&seq, &self.lo, x) == 1 {
            Ordering::Less
        } else {
            Ordering::Greater
        }
    }

    /// Exact comparison of two algebraic numbers.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// use std::cmp::Ordering;
    /// // √2 < √3, and √2 as the root of 2x² − 4 is the same number.
    /// let sqrt3 = isolate_roots(&Poly::from_i64(&[-3, 0, 1]), &q("0"), &q("2")).remove(0);
    /// let again = isolate_roots(&Poly::from_i64(&[-4, 0, 2]), &q("0"), &q("2")).remove(0);
    /// assert_eq!(sqrt2.compare(&sqrt3), Ordering::Less);
    /// assert_eq!(sqrt2.compare(&again), Ordering::Equal);
    /// ```
    pub fn compare(&self, o: &Algebraic) -> Ordering {
        let g = self.poly.gcd(&o.poly);
        let lo = if self.lo > o.lo { &self.lo } else { &o.lo };
        let hi = if self.hi < o.hi { &self.hi } else { &o.hi };
        if g.degree().unwrap_or(0) > 0 && lo < hi && count_roots(&g.sturm(), lo, hi) >= 1 {
            // A common root in the overlap: both brackets hold exactly one root each, so it
            // is the same number.
            return Ordering::Equal;
        }
        let (mut a, mut b) = (self.clone(), o.clone());
        loop {
            if a.hi <= b.lo {
                return Ordering::Less;
            }
            if b.hi <= a.lo {
                return Ordering::Greater;
            }
            let wa = &a.hi - &a.lo;
            let wb = &b.hi - &b.lo;
            a.refine_to(&(wa / r(2)));
            b.refine_to(&(wb / r(2)));
        }
    }

    /// The factor of [`Self::poly`] vanishing at the number, as a primitive integer polynomial
    /// with a positive leading coefficient, and what is proved of it: `x − q` for a rational
    /// `q`; otherwise the square-free part without rational roots, [`Reduction::Minimal`]
    /// when proved irreducible over `Q` ([`crate::algebra::poly::roots::reduce_polynomial`]).
    /// The bracket isolates the number for it too (it divides [`Self::poly`]).
    ///
    /// [`Reduction::Minimal`]: crate::algebra::poly::roots::Reduction::Minimal
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// use truecost::algebra::poly::roots::Reduction;
    /// // (x^2 − 2)(2x − 3)(x + 1): the root √2 in (1, 29/20) has the minimal polynomial x^2 − 2.
    /// let p = Poly::from_i64(&[-2, 0, 1]).mul(&Poly::from_i64(&[-3, 2])).mul(&Poly::from_i64(&[1, 1]));
    /// let a = isolate_roots(&p, &"1".parse().unwrap(), &"29/20".parse().unwrap()).remove(0);
    /// let (m, how) = a.reduced_polynomial();
    /// assert_eq!((m.to_string(), how), ("x^2 - 2".to_string(), Reduction::Minimal));
    /// ```
    pub fn reduced_polynomial(&self) -> (Poly, crate::algebra::poly::roots::Reduction) {
        use crate::algebra::poly::roots::{integer_form, reduce_polynomial, Reduction};
        if let Some(q) = self.as_rational() {
            return (
                Poly::new(vec![-q, Rational::one()]).primitive(),
                Reduction::Minimal,
            );
        }
        let (g, _, how) = reduce_polynomial(&integer_form(&self.poly));
        let (g, how) = match how {
            Reduction::SquareFree => {
                match crate::algebra::poly::roots::irreducible_factor_at(&g, &self.lo, &self.hi) {
                    Some(f) => (f, Reduction::Minimal),
                    None => (g, how),
                }
            }
            _ => (g, how),
        };
        (
            Poly::new(g.into_iter().map(Rational::from_integer).collect()).primitive(),
            how,
        )
    }

    /// The number truncated (towards −∞) to `digits` digits after the point: the digits of
    /// the number itself (the bracket is cut at the digit boundary it may contain).
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    /// // √2 = 1.41421356…: truncated, not rounded.
    /// assert_eq!(sqrt2.decimal(3), "1.414");
    /// assert_eq!(sqrt2.decimal(4), "1.4142");
    /// ```
    pub fn decimal(&self, digits: usize) -> String {
        if let Some(q) = self.as_rational() {
            return decimal(&q, digits);
        }
        let unit = Rational::new(BigInt::one(), num_traits::pow(BigInt::from(10), digits));
        self.decimal_in_cells(&unit, &Rational::zero(), digits, decimal)
    }

    /// The number correctly rounded to `digits` digits after the point (to nearest; a tie,
    /// only possible for a rational, away from zero), as [`decimal_rounded`] of the exact value.
    ///
    /// ```
    /// use truecost::algebra::poly::{isolate_roots, Poly};
    /// let sqrt2 = isolate_roots(&Poly::from_i64(&[-2, 0, 1]), &"0".parse().unwrap(), &"2".parse().unwrap()).remove(0);
    /// assert_eq!(sqrt2.decimal_rounded(10), "1.4142135624"); // √2 = 1.41421356237…
    /// assert_eq!(sqrt2.decimal(10), "1.4142135623");
    /// ```
    pub fn decimal_rounded(&self, digits: usize) -> String {
        if let Some(q) = self.as_rational() {
            return decimal_rounded(&q, digits);
        }
        let unit = Rational::new(BigInt::one(), num_traits::pow(BigInt::from(10), digits));
        let half = &unit / r(2);
        self.decimal_in_cells(&unit, &half, digits, decimal_rounded)
    }

    /// An irrational number's digits by `print`, whose cells are `[k·unit − offset,
    /// (k + 1)·unit − offset)`: the bracket is refined below one unit and cut at the cell
    /// boundary inside it, then a point strictly inside the bracket, in the number's cell, is
    /// printed.
    fn decimal_in_cells(
        &self,
        unit: &Rational,
        offset: &Rational,
        digits: usize,
        print: fn(&Rational, usize) -> String,
    ) -> String {
        let mut a = self.clone();
        a.refine_to(unit);
        let boundary = ((&a.lo + offset) / unit).floor() * unit + unit - offset;
        if a.lo < boundary && boundary < a.hi {
            // Irrational: not the boundary itself.
            if self.cmp_rational(&boundary) == Ordering::Less {
                a.hi = boundary;
            } else {
                a.lo = boundary;
            }
        }
        print(&((&a.lo + &a.hi) / r(2)), digits)
    }
}

/// `x` correctly rounded to `digits` digits after the point: to nearest, a tie away from zero
/// (no point when `digits` is 0).
///
/// ```
/// use truecost::algebra::poly::decimal_rounded;
/// use truecost::value::parse_rational;
/// let q = |t: &str| parse_rational(t).unwrap();
/// assert_eq!(decimal_rounded(&q("2/3"), 5), "0.66667");
/// assert_eq!(decimal_rounded(&q("1/8"), 2), "0.13");
/// assert_eq!(decimal_rounded(&q("-1/8"), 2), "-0.13");
/// assert_eq!(decimal_rounded(&q("999/1000"), 2), "1.00");
/// assert_eq!(decimal_rounded(&q("-1/1000"), 2), "0.00");
/// ```
pub fn decimal_rounded(x: &Rational, digits: usize) -> String {
    let scale = Rational::from_integer(num_traits::pow(BigInt::from(10), digits));
    let half = Rational::new(BigInt::one(), BigInt::from(2));
    let scaled = x * scale;
    let k = if scaled.is_negative() {
        -(-scaled + half).floor()
    } else {
        (scaled + half).floor()
    };
    fixed(&k.to_integer(), digits)
}

/// The integer `k` as `k / 10^digits` with `digits` digits after the point.
fn fixed(k: &BigInt, digits: usize) -> String {
    let scale = num_traits::pow(BigInt::from(10), digits);
    let neg = k.is_negative();
    let a = k.abs();
    let int = &a / &scale;
    let frac = &a % &scale;
    if digits == 0 {
        return format!("{}{int}", if neg { "-" } else { "" });
    }
    format!(
        "{}{}.{:0>width$}",
        if neg { "-" } else { "" },
        int,
        frac.to_string(),
        width = digits
    )
}

/// `x` in decimal, truncated to `digits` digits after the point (no point when `digits` is 0).
///
/// ```
/// use truecost::algebra::poly::decimal;
/// use truecost::value::parse_rational;
/// assert_eq!(decimal(&parse_rational("7/2").unwrap(), 0), "3");
/// assert_eq!(decimal(&parse_rational("7/2").unwrap(), 2), "3.50");
/// ```
pub fn decimal(x: &Rational, digits: usize) -> String {
    let scale = num_traits::pow(BigInt::from(10), digits);
    let scaled = (x * Rational::from_integer(scale)).floor().to_integer();
    fixed(&scaled, digits)
}

/// A rational strictly between the algebraic numbers `a < b` (brackets refined as needed).
///
/// ```
/// use truecost::algebra::poly::{between, Algebraic};
/// let a = Algebraic::from_rational("1/3".parse().unwrap());
/// let b = Algebraic::from_rational("1/2".parse().unwrap());
/// let t = between(&a, &b);
/// assert!(t > "1/3".parse().unwrap() && t < "1/2".parse().unwrap());
/// ```
pub fn between(a: &Algebraic, b: &Algebraic) -> Rational {
    let (mut a, mut b) = (a.clone(), b.clone());
    let (sa, sb) = (a.poly.sturm(), b.poly.sturm());
    while a.hi >= b.lo {
        a.halve_with(&sa);
        b.halve_with(&sb);
    }
    (&a.hi + &b.lo) / r(2)
}

/// Every real root of `p` (non-zero) in the open interval `(lo, hi)`, in increasing order,
/// each with a bracket not wider than `hi - lo` and containing no other root.
///
/// ```
/// use truecost::algebra::poly::{isolate_roots, Poly};
/// use truecost::value::parse_rational;
/// let p = Poly::from_i64(&[-2, 0, 1]); // roots ±√2
/// let roots = isolate_roots(&p, &parse_rational("0").unwrap(), &parse_rational("2").unwrap());
/// assert_eq!(roots.len(), 1);
/// assert!(roots[0].lo < parse_rational("1.4143").unwrap() && roots[0].hi > parse_rational("1.4142").unwrap());
/// ```
pub fn isolate_roots(p: &Poly, lo: &Rational, hi: &Rational) -> Vec<Algebraic> {
    let sf = p.squarefree();
    if sf.degree().unwrap_or(0) == 0 {
        return Vec::new();
    }
    let seq = sf.sturm();
    let mut out = Vec::new();
    // Work on (lo, hi): exclude a root at hi itself.
    let mut stack = vec![(lo.clone(), hi.clone())];
    let two = r(2);
    while let Some((a, b)) = stack.pop() {
        let total = count_roots(&seq, &a, &b);
        let at_end = &b == hi && sf.eval(&b).is_zero();
        let inner = total - usize::from(at_end);
        if inner == 0 {
            continue;
        }
        if total == 1 {
            out.push(Algebraic {
                poly: sf.clone(),
                lo: a,
                hi: b,
            });
            continue;
        }
        let mid = (&a + &b) / &two;
        stack.push((a, mid.clone()));
        stack.push((mid, b));
    }
    out.sort_by(|x, y| x.lo.cmp(&y.lo));
    out
}

impl fmt::Display for Poly {
    /// `5x^4 - x^3 - x^2 - x - 1`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.c.is_empty() {
            return write!(f, "0");
        }
        let mut first = true;
        for (i, c) in self.c.iter().enumerate().rev() {
            if c.is_zero() {
                continue;
            }
            let neg = c.is_negative();
            let a = c.abs();
            let coef = if a.is_one() && i > 0 {
                String::new()
            } else if a.is_integer() {
                a.numer().to_string()
            } else {
                format!("({}/{})", a.numer(), a.denom())
            };
            let var = match i {
                0 => String::new(),
                1 => "x".into(),
                _ => format!("x^{i}"),
            };
            if first {
                write!(f, "{}{coef}{var}", if neg { "-" } else { "" })?;
            } else {
                write!(f, " {} {coef}{var}", if neg { "-" } else { "+" })?;
            }
            first = false;
        }
        Ok(())
    }
}

//! Integer polynomials and exact root counting by Sturm sequences, for the discount
//! certificate's checker ([`super::discount`]). Self-contained: big integers and rationals
//! only, nothing from the solver or `crate::algebra`.
//!
//! A polynomial is its integer coefficients, constant first, with no trailing zero (the zero
//! polynomial is empty). **Sturm's theorem** (for a square-free `p`): with `p_0 = p`,
//! `p_1 = p'`, `p_{i+1} = −rem(p_{i−1}, p_i)` until the remainder is zero, and `V(x)` the
//! number of sign changes of `p_0(x), p_1(x), …` (zeros skipped), `p` has exactly `V(a) − V(b)`
//! distinct real roots in `(a, b]` for every `a < b`. (Crossing a root `c` of `p`, `p·p'`
//! goes from negative to positive, so `V` drops by one there and `V(c) = V(c⁺)`; crossing a
//! root of some `p_i`, `i ≥ 1`, the neighbours `p_{i−1}, p_{i+1}` have opposite signs, so `V`
//! does not change.) Every element may be scaled by a *positive* constant without changing
//! `V`: the remainders here are pseudo-remainders made positive multiples of the remainder,
//! divided by their content, so the arithmetic stays in integers.
//!
//! **Descartes' rule of signs** ([`descartes_bound`]) answers most questions without a chain:
//! the number of roots of `p` in `(a, b)`, with multiplicity, is the number of sign changes
//! of the coefficients of `(1 + x)^d p((a + b x) / (1 + x))` minus an even number, so a count
//! of 0 or 1 is exact; [`Roots`] uses it and builds the Sturm chain only when the count is 2
//! or more. The rule's transform costs two Taylor shifts (`O(d²)` additions and
//! multiplications by the ends' numerators); a chain costs `d` pseudo-divisions with
//! coefficients that grow with each, and gcds to keep them primitive.
//!
//! A polynomial that is not square-free has the chain ending in `g = gcd(p, p')` (up to a
//! constant); dividing every element by `g` gives the Sturm chain of the square-free part
//! `p / g`, which has the same roots.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

use crate::value::Rational;

/// Removes trailing zero coefficients.
pub(crate) fn trim(mut p: Vec<BigInt>) -> Vec<BigInt> {
    while p.last().is_some_and(Zero::is_zero) {
        p.pop();
    }
    p
}

/// The degree (`None` for the zero polynomial).
pub(crate) fn degree(p: &[BigInt]) -> Option<usize> {
    p.len().checked_sub(1)
}

/// The sign of `p(x)`, exactly: `Σ p_i n^i m^(d−i)` for `x = n/m` (`m > 0`) by Horner's rule,
/// which is `p(x)·m^d`.
///
/// ```
/// use num_bigint::BigInt;
/// use std::cmp::Ordering;
/// use truecost::certificate::sturm::sign_at;
/// // x² − 2 at 7/5 (49/25 − 2 < 0) and at 3/2 (9/4 − 2 > 0).
/// let p: Vec<BigInt> = [-2, 0, 1].into_iter().map(BigInt::from).collect();
/// assert_eq!(sign_at(&p, &"7/5".parse().unwrap()), Ordering::Less);
/// assert_eq!(sign_at(&p, &"3/2".parse().unwrap()), Ordering::Greater);
/// ```
pub fn sign_at(p: &[BigInt], x: &Rational) -> Ordering {
    let (n, m) = (x.numer(), x.denom());
    let mut acc = BigInt::zero();
    let mut power = BigInt::one();
    for c in p.iter().rev() {
        acc = acc * n + c * &power;
        power *= m;
    }
    acc.sign().cmp(&num_bigint::Sign::NoSign)
}

/// `p` divided by the gcd of its coefficients (a positive number: signs kept).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::certificate::sturm::primitive;
/// let p: Vec<BigInt> = [-6, 0, 4].into_iter().map(BigInt::from).collect();
/// assert_eq!(primitive(p), [-3, 0, 2].map(BigInt::from));
/// ```
pub fn primitive(p: Vec<BigInt>) -> Vec<BigInt> {
    // From the shortest coefficient, one division before each binary gcd (which is slow on
    // numbers of very different lengths), stopping at 1.
    let Some(start) = p.iter().filter(|c| !c.is_zero()).min_by_key(|c| c.bits()) else {
        return p;
    };
    let mut g = start.abs();
    for c in &p {
        if g.is_one() {
            return p;
        }
        let r = c % &g;
        if !r.is_zero() {
            g = g.gcd(&r);
        }
    }
    if g.is_one() {
        return p;
    }
    p.into_iter().map(|c| c / &g).collect()
}

/// The derivative.
pub(crate) fn derivative(p: &[BigInt]) -> Vec<BigInt> {
    trim(
        p.iter()
            .enumerate()
            .skip(1)
            .map(|(i, c)| c * BigInt::from(i))
            .collect(),
    )
}

/// A positive multiple of the remainder of `a` by `b` (`b` not zero), made primitive: the
/// pseudo-remainder `lc(b)^k a mod b`, negated when `lc(b)^k < 0`.
pub(crate) fn positive_remainder(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let db = degree(b).expect("a non-zero divisor");
    let lead = b[db].clone();
    let mut r = a.to_vec();
    let mut factor_negative = false;
    while let Some(dr) = degree(&r).filter(|&d| d >= db) {
        let c = r[dr].clone();
        // r ← lead·r − c·x^(dr−db)·b: the leading term cancels.
        for x in r.iter_mut() {
            *x *= &lead;
        }
        for (i, bi) in b.iter().enumerate() {
            r[i + dr - db] -= &c * bi;
        }
        factor_negative ^= lead.is_negative();
        r = trim(r);
    }
    if factor_negative {
        r = r.into_iter().map(|c| -c).collect();
    }
    primitive(r)
}

/// The exact quotient `a / b` when `b` divides `a` over the rationals and `b` is primitive
/// (Gauss's lemma makes the quotient integral); `None` otherwise.
pub(crate) fn divide_exact(a: &[BigInt], b: &[BigInt]) -> Option<Vec<BigInt>> {
    let db = degree(b)?;
    let mut r = a.to_vec();
    let Some(da) = degree(&r) else {
        return Some(Vec::new());
    };
    if da < db {
        return None;
    }
    let mut q = vec![BigInt::zero(); da - db + 1];
    while let Some(dr) = degree(&r).filter(|&d| d >= db) {
        let (c, rem) = r[dr].div_rem(&b[db]);
        if !rem.is_zero() {
            return None;
        }
        for (i, bi) in b.iter().enumerate() {
            r[i + dr - db] -= &c * bi;
        }
        q[dr - db] = c;
        r = trim(r);
    }
    r.is_empty().then(|| trim(q))
}

/// The greatest common divisor, primitive with a positive leading coefficient (empty if both
/// are zero).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::certificate::sturm::gcd;
/// let p = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
/// // (x − 1)(x + 2) and (x − 1)(2x + 3): x − 1.
/// assert_eq!(gcd(&p(&[-2, 1, 1]), &p(&[-3, 1, 2])), p(&[-1, 1]));
/// ```
pub fn gcd(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let (mut x, mut y) = (primitive(trim(a.to_vec())), primitive(trim(b.to_vec())));
    while !y.is_empty() {
        let r = positive_remainder(&x, &y);
        x = y;
        y = r;
    }
    if x.last().is_some_and(Signed::is_negative) {
        x = x.into_iter().map(|c| -c).collect();
    }
    x
}

/// Descartes' rule of signs on the open interval `(a, b)` (`a < b`): the number of sign
/// changes of the coefficients of `q(x) = (1 + x)^d p((a + b x) / (1 + x))` (zeros skipped),
/// `d` the degree of `p`. `x ↦ (a + b x) / (1 + x)` maps `(0, ∞)` one to one onto `(a, b)`,
/// so `q`'s positive roots are `p`'s roots in `(a, b)` with their multiplicities, and by the
/// rule of signs their number is the returned count minus an even number: 0 means no root
/// in `(a, b)`, 1 exactly one (a simple one). Computed in integers: with `a = A/D`,
/// `b = B/D`, `q` is `D^d p((A + (B − A) y) / D)` (a Taylor shift by `A`, then `y^i` scaled by
/// `(B − A)^i`), reversed (`y = 1/z`), then shifted by one (`z = 1 + x`).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::certificate::sturm::descartes_bound;
/// let q = |t: &str| t.parse().unwrap();
/// // 6x² − 5x + 1 = (2x − 1)(3x − 1): both roots in (0, 1), none in (0, 3/10), one in
/// // (2/5, 1).
/// let p: Vec<BigInt> = [1, -5, 6].into_iter().map(BigInt::from).collect();
/// assert_eq!(descartes_bound(&p, &q("0"), &q("1")), 2);
/// assert_eq!(descartes_bound(&p, &q("0"), &q("3/10")), 0);
/// assert_eq!(descartes_bound(&p, &q("2/5"), &q("1")), 1);
/// ```
pub fn descartes_bound(p: &[BigInt], a: &Rational, b: &Rational) -> usize {
    assert!(a < b, "an open interval (a, b) with a < b");
    let p = trim(p.to_vec());
    let Some(d) = degree(&p) else {
        return 0;
    };
    let den = a.denom().lcm(b.denom());
    let lo = a.numer() * (&den / a.denom());
    let width = b.numer() * (&den / b.denom()) - &lo;
    // D^d p(z / D) = Σ c_i D^(d−i) z^i.
    let mut q = p;
    let mut power = BigInt::one();
    for c in q.iter_mut().rev() {
        *c *= &power;
        power *= &den;
    }
    taylor_shift(&mut q, &lo);
    let mut power = BigInt::one();
    for c in q.iter_mut() {
        *c *= &power;
        power *= &width;
    }
    q.reverse();
    taylor_shift(&mut q, &BigInt::one());
    debug_assert_eq!(q.len(), d + 1);
    let mut last = num_bigint::Sign::NoSign;
    let mut changes = 0;
    for c in &q {
        let s = c.sign();
        if s == num_bigint::Sign::NoSign {
            continue;
        }
        if last != num_bigint::Sign::NoSign && s != last {
            changes += 1;
        }
        last = s;
    }
    changes
}

/// `p(x)` replaced by `p(x + t)` in place: `p_j += t·p_(j+1)` for `j` from the top down,
/// once per degree (Horner's rule, the classical Taylor shift).
fn taylor_shift(p: &mut [BigInt], t: &BigInt) {
    if t.is_zero() {
        return;
    }
    let n = p.len();
    for i in 0..n.saturating_sub(1) {
        for j in (i..n - 1).rev() {
            let next = if t.is_one() {
                p[j + 1].clone()
            } else {
                &p[j + 1] * t
            };
            p[j] += next;
        }
    }
}

/// Exact counts of the distinct real roots of one non-zero polynomial on half-open
/// intervals: Descartes' rule of signs ([`descartes_bound`]) where it is conclusive (a bound
/// of 0 or 1 is the exact number of roots in the open interval), the Sturm chain (built on
/// first use) where it is not.
#[derive(Debug)]
pub struct Roots<'a> {
    p: &'a [BigInt],
    chain: std::cell::OnceCell<Sturm>,
}

impl<'a> Roots<'a> {
    /// The counter of `p` (not zero).
    pub fn new(p: &'a [BigInt]) -> Roots<'a> {
        assert!(
            p.iter().any(|c| !c.is_zero()),
            "the roots of a non-zero polynomial"
        );
        Roots {
            p,
            chain: std::cell::OnceCell::new(),
        }
    }

    /// The number of distinct real roots in `(a, b]` (`a < b`), as [`Sturm::count`]: those in
    /// `(a, b)` (Descartes' bound when 0 or 1, else Sturm's count minus a root at `b`), plus
    /// one if `p(b) = 0`.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Roots;
    /// let q = |t: &str| t.parse().unwrap();
    /// // 6x² − 5x + 1 = (2x − 1)(3x − 1): roots 1/3 and 1/2.
    /// let p: Vec<BigInt> = [1, -5, 6].into_iter().map(BigInt::from).collect();
    /// let r = Roots::new(&p);
    /// assert_eq!(r.count(&q("0"), &q("1")), 2); // Descartes' bound 2: Sturm's count
    /// assert_eq!(r.count(&q("0"), &q("1/3")), 1); // the root at the right end
    /// assert_eq!(r.count(&q("2/5"), &q("1")), 1); // Descartes' bound 1
    /// ```
    pub fn count(&self, a: &Rational, b: &Rational) -> usize {
        let at_b = usize::from(sign_at(self.p, b) == Ordering::Equal);
        match descartes_bound(self.p, a, b) {
            n @ (0 | 1) => n + at_b,
            _ => self.chain().count(a, b),
        }
    }

    /// The Sturm chain, built on first use.
    pub fn chain(&self) -> &Sturm {
        self.chain.get_or_init(|| Sturm::new(self.p))
    }
}

/// The Sturm chain of the square-free part of a non-zero polynomial (module docs).
#[derive(Clone, Debug)]
pub struct Sturm {
    chain: Vec<Vec<BigInt>>,
    square_free: bool,
}

impl Sturm {
    /// The chain of `p` (not zero), reduced to its square-free part when `p` has a repeated
    /// factor.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Sturm;
    /// let q = |t: &str| t.parse().unwrap();
    /// // (x − 1/2)²(x − 3/4) = x³ − 7/4 x² + x − 3/16, times 16: two distinct roots.
    /// let p: Vec<BigInt> = [-3, 16, -28, 16].into_iter().map(BigInt::from).collect();
    /// let s = Sturm::new(&p);
    /// assert!(!s.is_square_free());
    /// assert_eq!(s.count(&q("0"), &q("1")), 2);
    /// assert_eq!(s.count(&q("0"), &q("1/2")), 1); // (0, 1/2] holds 1/2
    /// assert_eq!(s.count(&q("1/2"), &q("3/4") ), 1); // (1/2, 3/4] holds 3/4 only
    /// ```
    pub fn new(p: &[BigInt]) -> Sturm {
        let p = primitive(trim(p.to_vec()));
        assert!(!p.is_empty(), "the Sturm chain of a non-zero polynomial");
        let mut chain = vec![p.clone()];
        let mut next = primitive(derivative(&p));
        while !next.is_empty() {
            let r = positive_remainder(&chain[chain.len() - 1], &next);
            chain.push(next);
            next = r.into_iter().map(|c| -c).collect();
        }
        let last = chain.last().expect("non-empty").clone();
        let square_free = degree(&last) == Some(0);
        if !square_free {
            let g = primitive(last);
            chain = chain
                .iter()
                .map(|q| divide_exact(q, &g).expect("every element is a multiple of the gcd"))
                .collect();
        }
        Sturm { chain, square_free }
    }

    /// Whether the polynomial is square-free (its chain ends in a non-zero constant).
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Sturm;
    /// let p = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
    /// assert!(Sturm::new(&p(&[-2, 0, 1])).is_square_free()); // x² − 2
    /// assert!(!Sturm::new(&p(&[1, -2, 1])).is_square_free()); // (x − 1)²
    /// ```
    pub fn is_square_free(&self) -> bool {
        self.square_free
    }

    /// The square-free part the chain counts the roots of.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Sturm;
    /// let p = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
    /// // (x − 1)²(x + 1) = x³ − x² − x + 1: square-free part x² − 1, up to sign.
    /// let s = Sturm::new(&p(&[1, -1, -1, 1]));
    /// let part = s.square_free_part();
    /// assert!(part == p(&[-1, 0, 1]).as_slice() || part == p(&[1, 0, -1]).as_slice());
    /// ```
    pub fn square_free_part(&self) -> &[BigInt] {
        &self.chain[0]
    }

    /// `V(x)`: the sign changes along the chain at `x`, zeros skipped.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Sturm;
    /// // x² − 2: chain x² − 2, x, 1 (positive multiples); at 0 the signs −, 0, + (one change),
    /// // at 2 the signs +, +, + (none).
    /// let s = Sturm::new(&[-2, 0, 1].map(BigInt::from));
    /// assert_eq!(s.variations(&"0".parse().unwrap()), 1);
    /// assert_eq!(s.variations(&"2".parse().unwrap()), 0);
    /// ```
    pub fn variations(&self, x: &Rational) -> usize {
        let mut last = Ordering::Equal;
        let mut changes = 0;
        for p in &self.chain {
            let s = sign_at(p, x);
            if s == Ordering::Equal {
                continue;
            }
            if last != Ordering::Equal && s != last {
                changes += 1;
            }
            last = s;
        }
        changes
    }

    /// The number of distinct real roots in `(a, b]` (`a < b`): `V(a) − V(b)`.
    ///
    /// ```
    /// use num_bigint::BigInt;
    /// use truecost::certificate::sturm::Sturm;
    /// let q = |t: &str| t.parse().unwrap();
    /// // 6x² − 5x + 1 = (2x − 1)(3x − 1): roots 1/3 and 1/2.
    /// let s = Sturm::new(&[1, -5, 6].map(BigInt::from));
    /// assert_eq!(s.count(&q("0"), &q("1")), 2);
    /// assert_eq!(s.count(&q("1/3"), &q("1/2")), 1); // 1/2 counted, 1/3 not
    /// ```
    pub fn count(&self, a: &Rational, b: &Rational) -> usize {
        assert!(a < b, "a half-open interval (a, b] with a < b");
        self.variations(a) - self.variations(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(c: &[i64]) -> Vec<BigInt> {
        c.iter().map(|&x| BigInt::from(x)).collect()
    }

    fn q(t: &str) -> Rational {
        t.parse().unwrap()
    }

    /// Hand-derived root counts: `(polynomial, a, b, roots in (a, b])`.
    fn cases() -> Vec<(Vec<BigInt>, Rational, Rational, usize)> {
        vec![
            // x² − 2: roots ±1.41421…
            (poly(&[-2, 0, 1]), q("0"), q("2"), 1),
            (poly(&[-2, 0, 1]), q("-2"), q("2"), 2),
            (poly(&[-2, 0, 1]), q("7/5"), q("3/2"), 1),
            (poly(&[-2, 0, 1]), q("3/2"), q("2"), 0),
            (poly(&[-2, 0, 1]), q("0"), q("1"), 0),
            // x² + 1: no real root.
            (poly(&[1, 0, 1]), q("-10"), q("10"), 0),
            // (2x − 1)(3x − 1) = 6x² − 5x + 1: roots 1/3, 1/2; the right end counts, the left
            // does not.
            (poly(&[1, -5, 6]), q("0"), q("1"), 2),
            (poly(&[1, -5, 6]), q("1/3"), q("1/2"), 1),
            (poly(&[1, -5, 6]), q("0"), q("1/3"), 1),
            (poly(&[1, -5, 6]), q("1/3"), q("2/5"), 0),
            (poly(&[1, -5, 6]), q("1/2"), q("1"), 0),
            // x³ − x = x(x − 1)(x + 1): roots −1, 0, 1.
            (poly(&[0, -1, 0, 1]), q("-1"), q("1"), 2),
            (poly(&[0, -1, 0, 1]), q("-2"), q("-1"), 1),
            (poly(&[0, -1, 0, 1]), q("-1/2"), q("1/2"), 1),
            // (x − 1/2)² (4x² − 4x + 1, a double root): one distinct root.
            (poly(&[1, -4, 4]), q("0"), q("1"), 1),
            (poly(&[1, -4, 4]), q("0"), q("1/2"), 1),
            (poly(&[1, -4, 4]), q("1/2"), q("1"), 0),
            // −x² + 2 (a negative leading coefficient): roots ±√2.
            (poly(&[2, 0, -1]), q("0"), q("2"), 1),
            (poly(&[2, 0, -1]), q("-2"), q("2"), 2),
            // 5x⁴ − x³ − x² − x − 1 (the discount example's α*): one root in (0, 1), at
            // 0.9163…, none in (0, 9/10], since the polynomial is −1 at 0, negative at 9/10
            // (−0.0465) and 1 at 1; its other real root is negative (−0.5…).
            (poly(&[-1, -1, -1, -1, 5]), q("0"), q("1"), 1),
            (poly(&[-1, -1, -1, -1, 5]), q("0"), q("9/10"), 0),
            (poly(&[-1, -1, -1, -1, 5]), q("-1"), q("0"), 1),
            // A constant: none.
            (poly(&[3]), q("0"), q("1"), 0),
            // x: the root 0 counted in (−1, 0], not in (0, 1].
            (poly(&[0, 1]), q("-1"), q("0"), 1),
            (poly(&[0, 1]), q("0"), q("1"), 0),
        ]
    }

    /// Runs every hand-derived case through `count`; the first mismatch.
    fn run(count: impl Fn(&[BigInt], &Rational, &Rational) -> usize) -> Result<(), String> {
        for (p, a, b, want) in cases() {
            let got = count(&p, &a, &b);
            if got != want {
                return Err(format!("{p:?} on ({a}, {b}]: {got}, not {want}"));
            }
        }
        Ok(())
    }

    #[test]
    fn sturm_counts_match_the_hand_derived_roots() {
        run(|p, a, b| Sturm::new(p).count(a, b)).unwrap();
    }

    /// Planted bugs in the count are caught by the hand-derived cases: zeros not skipped
    /// (counted as a sign of their own), the chain built with `+rem` instead of `−rem`, and
    /// an open interval `(a, b)` counted instead of `(a, b]`.
    #[test]
    fn planted_bugs_in_the_sturm_count_are_caught() {
        let zeros_counted = |p: &[BigInt], a: &Rational, b: &Rational| {
            let s = Sturm::new(p);
            let v = |x: &Rational| {
                let signs: Vec<Ordering> = s.chain.iter().map(|c| sign_at(c, x)).collect();
                signs.windows(2).filter(|w| w[0] != w[1]).count()
            };
            v(a).saturating_sub(v(b))
        };
        assert!(run(zeros_counted).is_err());
        let plus_remainder = |p: &[BigInt], a: &Rational, b: &Rational| {
            let p = primitive(p.to_vec());
            let mut chain = vec![p.clone()];
            let mut next = primitive(derivative(&p));
            while !next.is_empty() {
                let r = positive_remainder(&chain[chain.len() - 1], &next);
                chain.push(next);
                next = r; // the planted bug: not negated
            }
            let s = Sturm {
                chain,
                square_free: true,
            };
            s.variations(a).saturating_sub(s.variations(b))
        };
        assert!(run(plus_remainder).is_err());
        let open = |p: &[BigInt], a: &Rational, b: &Rational| {
            let n = Sturm::new(p).count(a, b);
            if sign_at(p, b) == Ordering::Equal {
                n - 1
            } else {
                n
            }
        };
        assert!(run(open).is_err());
    }

    #[test]
    fn descartes_and_sturm_counts_match_the_hand_derived_roots() {
        run(|p, a, b| Roots::new(p).count(a, b)).unwrap();
    }

    /// Descartes' bounds derived by hand: `q(x) = (1 + x)^d p((a + b x)/(1 + x))`.
    #[test]
    fn descartes_bounds_by_hand() {
        // 6x² − 5x + 1 on (0, 1): q = 6x² − 5x(1 + x) + (1 + x)² = 2x² − 3x + 1, two changes.
        assert_eq!(descartes_bound(&poly(&[1, -5, 6]), &q("0"), &q("1")), 2);
        // On (0, 3/10): q = 6(3x/10)² − 5(3x/10)(1 + x) + (1 + x)² = (4x² + 50x + 100)/100.
        assert_eq!(descartes_bound(&poly(&[1, -5, 6]), &q("0"), &q("3/10")), 0);
        // On (2/5, 1): q = 6(2/5 + x)² − 5(2/5 + x)(1 + x) + (1 + x)² = 2x² − x/5 − 1/25.
        assert_eq!(descartes_bound(&poly(&[1, -5, 6]), &q("2/5"), &q("1")), 1);
        // x² + 1 on (−10, 10): q = 100(x − 1)² + (1 + x)² = 101x² − 198x + 101, two changes
        // for no real root: inconclusive, so the count falls back to Sturm.
        assert_eq!(descartes_bound(&poly(&[1, 0, 1]), &q("-10"), &q("10")), 2);
        assert_eq!(Roots::new(&poly(&[1, 0, 1])).count(&q("-10"), &q("10")), 0);
        // x − 1/2 on (1/2, 1): q = (1/2 + x) − (1 + x)/2 = x/2, no change (the root is an end).
        assert_eq!(descartes_bound(&poly(&[-1, 2]), &q("1/2"), &q("1")), 0);
        // A constant: none.
        assert_eq!(descartes_bound(&poly(&[-7]), &q("-1"), &q("1")), 0);
    }

    /// Planted bugs in the fast count are caught by the hand-derived cases: Descartes' bound
    /// taken as the count whatever it is, the root at the right end forgotten, and the rule
    /// applied to `p` itself (its positive roots) instead of the transformed polynomial.
    #[test]
    fn planted_bugs_in_the_descartes_count_are_caught() {
        let bound_as_count = |p: &[BigInt], a: &Rational, b: &Rational| {
            descartes_bound(p, a, b) + usize::from(sign_at(p, b) == Ordering::Equal)
        };
        assert!(run(bound_as_count).is_err());
        let end_forgotten =
            |p: &[BigInt], a: &Rational, b: &Rational| match descartes_bound(p, a, b) {
                n @ (0 | 1) => n,
                _ => Sturm::new(p).count(a, b),
            };
        assert!(run(end_forgotten).is_err());
        let untransformed = |p: &[BigInt], a: &Rational, b: &Rational| {
            let at_b = usize::from(sign_at(p, b) == Ordering::Equal);
            let signs: Vec<_> = p
                .iter()
                .filter(|c| !c.is_zero())
                .map(|c| c.sign())
                .collect();
            match signs.windows(2).filter(|w| w[0] != w[1]).count() {
                n @ (0 | 1) => n + at_b,
                _ => Sturm::new(p).count(a, b),
            }
        };
        assert!(run(untransformed).is_err());
    }

    /// A seeded generator of small integers.
    struct Draw(rand_chacha::ChaCha8Rng);

    impl Draw {
        fn new(seed: u64) -> Draw {
            use rand::SeedableRng;
            Draw(rand_chacha::ChaCha8Rng::seed_from_u64(seed))
        }
        /// Uniform in `lo..=hi`.
        fn int(&mut self, lo: i64, hi: i64) -> i64 {
            use rand::Rng;
            lo + (self.0.next_u64() % (hi - lo + 1) as u64) as i64
        }
    }

    fn product(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
        let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                c[i + j] += x * y;
            }
        }
        c
    }

    /// Products of linear factors `k x − j` (rational roots `j/k` in `[−2, 2]`, repeats
    /// allowed) and quadratics `x² + c`, `c > 0` (no real root), with random half-open
    /// intervals, some ending at a root: the fast count equals the number of distinct `j/k`
    /// in the interval, computed from the factors, and Sturm's.
    #[test]
    fn fast_counts_match_known_roots_and_sturm() {
        let mut draw = Draw::new(48);
        for _ in 0..300 {
            let mut p = poly(&[1]);
            let mut roots: Vec<Rational> = Vec::new();
            for _ in 0..draw.int(0, 7) {
                let k = draw.int(1, 9);
                let j = draw.int(-2 * k, 2 * k);
                p = product(&p, &poly(&[-j, k]));
                roots.push(Rational::new(j.into(), k.into()));
            }
            for _ in 0..draw.int(0, 3) {
                p = product(&p, &poly(&[draw.int(1, 50), 0, 1]));
            }
            roots.sort();
            roots.dedup();
            let mut ends = [
                Rational::new(draw.int(-30, 30).into(), draw.int(1, 12).into()),
                Rational::new(draw.int(-30, 30).into(), draw.int(1, 12).into()),
            ];
            if !roots.is_empty() && draw.int(0, 1) == 1 {
                ends[1] = roots[draw.int(0, roots.len() as i64 - 1) as usize].clone();
            }
            ends.sort();
            if ends[0] == ends[1] {
                continue;
            }
            let (a, b) = (&ends[0], &ends[1]);
            let want = roots.iter().filter(|r| a < *r && *r <= b).count();
            assert_eq!(Roots::new(&p).count(a, b), want, "{p:?} on ({a}, {b}]");
            assert_eq!(Sturm::new(&p).count(a, b), want, "{p:?} on ({a}, {b}]");
        }
    }

    /// Random integer polynomials of degree up to 12 (complex roots near the interval make
    /// Descartes' bound inconclusive at times): the fast count equals Sturm's.
    #[test]
    fn fast_counts_match_sturm_on_random_polynomials() {
        let mut draw = Draw::new(5);
        let mut inconclusive = 0;
        for _ in 0..400 {
            let d = draw.int(1, 12);
            let p = trim((0..=d).map(|_| BigInt::from(draw.int(-20, 20))).collect());
            if p.is_empty() {
                continue;
            }
            let mut ends = [
                Rational::new(draw.int(-40, 40).into(), draw.int(1, 20).into()),
                Rational::new(draw.int(-40, 40).into(), draw.int(1, 20).into()),
            ];
            ends.sort();
            if ends[0] == ends[1] {
                continue;
            }
            let (a, b) = (&ends[0], &ends[1]);
            if descartes_bound(&p, a, b) > 1 {
                inconclusive += 1;
            }
            assert_eq!(
                Roots::new(&p).count(a, b),
                Sturm::new(&p).count(a, b),
                "{p:?} on ({a}, {b}]"
            );
        }
        // Both paths of the fast count were taken.
        assert!(inconclusive > 20, "{inconclusive}");
    }

    #[test]
    fn square_freeness_is_read_off_the_chain() {
        assert!(Sturm::new(&poly(&[-2, 0, 1])).is_square_free());
        assert!(!Sturm::new(&poly(&[1, -4, 4])).is_square_free());
        // (x − 1/2)²(x − 3/4) ·16 = 16x³ − 28x² + 16x − 3: square-free part (2x − 1)(4x − 3).
        let s = Sturm::new(&poly(&[-3, 16, -28, 16]));
        assert_eq!(s.square_free_part(), poly(&[3, -10, 8]).as_slice());
    }

    #[test]
    fn gcd_and_exact_division_by_hand() {
        // (x − 1)(x + 2) and (x − 1)(2x + 3): gcd x − 1.
        assert_eq!(gcd(&poly(&[-2, 1, 1]), &poly(&[-3, 1, 2])), poly(&[-1, 1]));
        // Coprime: a constant.
        assert_eq!(gcd(&poly(&[-2, 0, 1]), &poly(&[-1, 1])), poly(&[1]));
        assert_eq!(
            divide_exact(&poly(&[-2, 1, 1]), &poly(&[-1, 1])),
            Some(poly(&[2, 1]))
        );
        assert_eq!(divide_exact(&poly(&[-2, 0, 1]), &poly(&[-1, 1])), None);
        // 2x − 1 divides 4x² − 1 with quotient 2x + 1.
        assert_eq!(
            divide_exact(&poly(&[-1, 0, 4]), &poly(&[-1, 2])),
            Some(poly(&[1, 2]))
        );
    }

    #[test]
    fn signs_at_rationals_by_hand() {
        // 6x² − 5x + 1 at 1/3 (0), 2/5 (24/25 − 2 + 1 = −1/25), 1 (2).
        let p = poly(&[1, -5, 6]);
        assert_eq!(sign_at(&p, &q("1/3")), Ordering::Equal);
        assert_eq!(sign_at(&p, &q("2/5")), Ordering::Less);
        assert_eq!(sign_at(&p, &q("1")), Ordering::Greater);
        assert_eq!(sign_at(&[], &q("1")), Ordering::Equal);
    }
}

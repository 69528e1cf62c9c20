//! Exact real roots in `(0, 1)` for the parametric discount analysis (issue 11, item 3), fast
//! enough for the degree-50 advantage polynomials of FrozenLake 8x8.
//!
//! * **Isolation**: Descartes' rule of signs with bisection (Vincent–Collins–Akritas) on the
//!   integer multiple of the polynomial: the number of sign variations of
//!   `(1 + x)^d q(1/(1 + x))` bounds the roots of `q` in `(0, 1)` and equals it when it is 0 or 1;
//!   halves are `2^d q(x/2)` and its shift by 1. A split point that is a root is an exact
//!   rational root: it is divided out and the search restarts; a search too deep (a multiple
//!   root) restarts on the square-free part. Factors `x` and `x − 1` are divided out first.
//! * **A root** is an exact rational, or an open interval `(lo, hi)` holding exactly one root,
//!   simple, of its polynomial `p`, with `p(lo)`, `p(hi)` non-zero of opposite signs;
//!   refinement is bisection by the sign of `p`.
//! * **Comparison** of roots of different polynomials refines both brackets until they are
//!   disjoint, unless the polynomials may share a factor (their gcd modulo a prime not dividing
//!   the leading coefficients has positive degree); then the exact gcd over `Q` decides: the
//!   roots are equal iff the gcd changes sign over the brackets' overlap.

use std::cmp::Ordering;
use std::sync::Arc;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};

use crate::claims::poly::Poly;
use crate::value::Rational;

/// The deepest bisection before the search restarts on the square-free part.
const MAX_DEPTH: u32 = 400;

/// A polynomial with its primitive integer multiple (same sign of the leading coefficient).
#[derive(Debug)]
pub struct RootPoly {
    /// The polynomial whose root it is.
    pub poly: Poly,
    ints: Vec<BigInt>,
}

impl RootPoly {
    fn new(poly: Poly) -> Arc<RootPoly> {
        let ints = integer_form(&poly);
        Arc::new(RootPoly { poly, ints })
    }

    /// The sign of the polynomial at `x`, in integer arithmetic.
    fn sign(&self, x: &Rational) -> Ordering {
        integer_sign(&self.ints, x)
    }
}

/// The sign at `x = n/m` of the integer polynomial `a` (constant first): the sign of
/// `Σ a_i n^i m^(d−i)` (homogeneous Horner; `m > 0`), no rational normalisation.
pub fn integer_sign(a: &[BigInt], x: &Rational) -> Ordering {
    let (n, m) = (x.numer(), x.denom());
    let mut acc = BigInt::zero();
    let mut mpow = BigInt::one();
    for c in a.iter().rev() {
        acc = acc * n + c * &mpow;
        mpow *= m;
    }
    acc.sign().cmp(&num_bigint::Sign::NoSign)
}

/// A real algebraic number in `(0, 1)` (module docs).
#[derive(Clone, Debug)]
pub struct Root {
    /// The polynomial (for an exact root: `x − value`).
    pub poly: Arc<RootPoly>,
    /// Lower end (the value if exact).
    pub lo: Rational,
    /// Upper end (the value if exact).
    pub hi: Rational,
    /// Whether `lo = hi` is the value.
    pub exact: bool,
    /// The sign of `poly` at `lo` (open brackets).
    sign_lo: Ordering,
}

/// `p` scaled to integer coefficients with gcd 1, the sign kept.
pub fn integer_form(p: &Poly) -> Vec<BigInt> {
    let mut l = BigInt::one();
    for c in p.coefficients() {
        l = l.lcm(c.denom());
    }
    let scaled: Vec<BigInt> = p
        .coefficients()
        .iter()
        .map(|c| (c * Rational::from_integer(l.clone())).to_integer())
        .collect();
    let mut g = BigInt::zero();
    for c in &scaled {
        g = g.gcd(c);
    }
    if g.is_zero() {
        return scaled;
    }
    scaled.into_iter().map(|c| c / &g).collect()
}

fn variations(c: &[BigInt]) -> usize {
    let mut last = 0i8;
    let mut v = 0;
    for x in c {
        let s = match x.sign() {
            num_bigint::Sign::Minus => -1,
            num_bigint::Sign::NoSign => continue,
            num_bigint::Sign::Plus => 1,
        };
        if last != 0 && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

/// `q(x + 1)` in place (coefficients constant first).
fn taylor_shift(q: &mut [BigInt]) {
    let n = q.len();
    for i in 0..n {
        for j in (i..n - 1).rev() {
            let t = q[j + 1].clone();
            q[j] += t;
        }
    }
}

/// An upper bound on the roots of `q` in `(0, 1)` (exact when 0 or 1).
fn descartes(q: &[BigInt]) -> usize {
    let mut r: Vec<BigInt> = q.iter().rev().cloned().collect();
    taylor_shift(&mut r);
    variations(&r)
}

enum Isolation {
    Done(Vec<(Rational, Rational)>),
    Midpoint(Rational),
    TooDeep,
}

/// Isolating open intervals of the roots of `p` (integer, no root at 0, 1) in `(0, 1)`.
fn isolate(p: &[BigInt]) -> Isolation {
    let d = p.len() - 1;
    let mut out = Vec::new();
    // (q, c, k): q(x) = 2^{kd} p((c + x) / 2^k) on x ∈ (0, 1).
    let mut stack: Vec<(Vec<BigInt>, BigInt, u32)> = vec![(p.to_vec(), BigInt::zero(), 0)];
    while let Some((q, c, k)) = stack.pop() {
        let v = descartes(&q);
        let scale = Rational::from_integer(BigInt::one() << k);
        if v == 0 {
            continue;
        }
        if v == 1 {
            out.push((
                Rational::from_integer(c.clone()) / &scale,
                Rational::from_integer(&c + 1) / &scale,
            ));
            continue;
        }
        if k >= MAX_DEPTH {
            return Isolation::TooDeep;
        }
        let left: Vec<BigInt> = q.iter().enumerate().map(|(i, a)| a << (d - i)).collect();
        let mut right = left.clone();
        taylor_shift(&mut right);
        if right[0].is_zero() {
            return Isolation::Midpoint(
                Rational::from_integer(2 * &c + 1) / (scale * Rational::from_integer(2.into())),
            );
        }
        stack.push((right, 2 * &c + 1, k + 1));
        stack.push((left, 2 * c, k + 1));
    }
    Isolation::Done(out)
}

/// Every root of the non-zero `f` in the open interval `(0, 1)`, in increasing order, distinct.
///
/// ```
/// use truecost::claims::poly::Poly;
/// use truecost::objectives::roots::roots_in_unit_interval;
/// // (x - 1/2)(3x - 2)(x^2 - 1/2) · x · (x - 1): roots 1/2, √2/2 ≈ 0.7071, 2/3 in (0, 1)
/// let f = Poly::from_i64(&[-1, 2]).mul(&Poly::from_i64(&[-2, 3])).mul(&Poly::from_i64(&[-1, 0, 2]))
///     .mul(&Poly::from_i64(&[0, 1])).mul(&Poly::from_i64(&[-1, 1]));
/// let r = roots_in_unit_interval(&f);
/// assert_eq!(r.len(), 3);
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// assert!(r[0].exact && r[0].lo == q("1/2"));
/// // 2/3, then √2/2: each bracket contains its root.
/// assert!(r[1].lo <= q("2/3") && q("2/3") <= r[1].hi);
/// let two = q("2");
/// assert!(&r[2].lo * &r[2].lo * &two < q("1") && &r[2].hi * &r[2].hi * &two > q("1"));
/// ```
pub fn roots_in_unit_interval(f: &Poly) -> Vec<Root> {
    assert!(!f.is_zero(), "roots of the zero polynomial");
    // Divide out x (drop the zero low coefficients) and x − 1 (while the coefficients sum to 0).
    let low = f.coefficients().iter().take_while(|c| c.is_zero()).count();
    let mut p = Poly::new(f.coefficients()[low..].to_vec());
    let x1 = Poly::from_i64(&[-1, 1]);
    while p
        .coefficients()
        .iter()
        .fold(Rational::zero(), |s, c| s + c)
        .is_zero()
    {
        p = p.div_rem(&x1).0;
    }
    let mut exact: Vec<Rational> = Vec::new();
    let mut squarefree = false;
    let intervals = loop {
        if p.degree().unwrap_or(0) == 0 {
            break Vec::new();
        }
        match isolate(&integer_form(&p)) {
            Isolation::Done(v) => break v,
            Isolation::Midpoint(r) => {
                p = p.div_rem(&Poly::new(vec![-r.clone(), Rational::one()])).0;
                exact.push(r);
            }
            Isolation::TooDeep => {
                assert!(!squarefree, "a square-free polynomial isolates");
                p = p.squarefree();
                squarefree = true;
            }
        }
    };
    let shared = RootPoly::new(p);
    let mut roots: Vec<Root> = Vec::new();
    exact.sort();
    exact.dedup();
    let exact_values = exact.clone();
    for r in exact {
        roots.push(Root::rational(r));
    }
    for (lo, hi) in intervals {
        if roots
            .iter()
            .any(|e| e.lo > lo && e.lo < hi && shared.poly.eval(&e.lo).is_zero())
        {
            continue; // a deflated rational root met again (multiple root)
        }
        let sign_lo = shared.sign(&lo);
        let mut root = Root {
            poly: shared.clone(),
            lo,
            hi,
            exact: false,
            sign_lo,
        };
        // An exact root divided out earlier may lie inside this bracket (it is no root of the
        // deflated polynomial): narrow the bracket past it, so that sorting by the lower ends
        // sorts by value (otherwise consecutive roots could come in the wrong order, and
        // `between` would never separate them).
        while let Some(e) = exact_values.iter().find(|e| root.lo < **e && **e < root.hi) {
            if root.exact {
                break;
            }
            // Cut at the exact root itself: it is not a root of `p`, so the bracket shrinks
            // to one side of it (an end equal to an exact root sorts correctly).
            root.cut(e.clone());
        }
        roots.push(root);
    }
    roots.sort_by(|a, b| a.lo.cmp(&b.lo));
    roots
}

/// The rational with the least denominator in the open interval `(lo, hi)`, `0 ≤ lo < hi`
/// (continued fractions).
///
/// ```
/// use truecost::objectives::roots::simplest_between;
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// assert_eq!(simplest_between(&q("3/10"), &q("17/50")), q("1/3"));
/// assert_eq!(simplest_between(&q("0"), &q("3/10")), q("1/4"));
/// ```
pub fn simplest_between(lo: &Rational, hi: &Rational) -> Rational {
    let fl = lo.floor();
    let next = &fl + Rational::one();
    if &next < hi {
        return next;
    }
    // fl ≤ lo < hi ≤ fl + 1.
    if lo == &fl {
        let inv = Rational::one() / (hi - &fl);
        return fl + Rational::one() / (inv.floor() + Rational::one());
    }
    let a = Rational::one() / (hi - &fl);
    let b = Rational::one() / (lo - &fl);
    fl + Rational::one() / simplest_between(&a, &b)
}

/// `gcd(a, b)` modulo `m` has positive degree (`None` if `m` divides a leading coefficient).
fn common_mod(a: &[BigInt], b: &[BigInt], m: u64) -> Option<bool> {
    let red = |p: &[BigInt]| -> Vec<u64> {
        let mb = BigInt::from(m);
        p.iter()
            .map(|c| c.mod_floor(&mb).to_u64().expect("reduced"))
            .collect()
    };
    let (mut x, mut y) = (red(a), red(b));
    if x.last() == Some(&0) || y.last() == Some(&0) {
        return None;
    }
    let mulm = |u: u64, v: u64| ((u as u128 * v as u128) % m as u128) as u64;
    let inv = |u: u64| {
        let (mut r, mut base, mut e) = (1u64, u, m - 2);
        while e > 0 {
            if e & 1 == 1 {
                r = mulm(r, base);
            }
            base = mulm(base, base);
            e >>= 1;
        }
        r
    };
    let trim = |p: &mut Vec<u64>| {
        while p.last() == Some(&0) {
            p.pop();
        }
    };
    loop {
        if y.is_empty() {
            return Some(x.len() > 1);
        }
        // x mod y
        let ly = inv(*y.last().expect("non-empty"));
        while x.len() >= y.len() {
            let f = mulm(*x.last().expect("non-empty"), ly);
            let shift = x.len() - y.len();
            for (i, c) in y.iter().enumerate() {
                let t = mulm(f, *c);
                x[i + shift] = (x[i + shift] + m - t) % m;
            }
            trim(&mut x);
            if x.is_empty() {
                break;
            }
        }
        std::mem::swap(&mut x, &mut y);
    }
}

fn narrow() -> Rational {
    Rational::new(BigInt::one(), BigInt::one() << 64u32)
}

/// The primitive part (content removed, sign kept).
fn primitive_part(p: Vec<BigInt>) -> Vec<BigInt> {
    let mut g = BigInt::zero();
    for c in &p {
        g = g.gcd(c);
    }
    if g.is_zero() || g.is_one() {
        return p;
    }
    p.into_iter().map(|c| c / &g).collect()
}

/// The gcd of two integer polynomials up to a constant (primitive pseudo-remainder sequence).
fn primitive_gcd(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let trim = |mut p: Vec<BigInt>| {
        while p.last().is_some_and(Zero::is_zero) {
            p.pop();
        }
        p
    };
    let (mut a, mut b) = (
        primitive_part(trim(a.to_vec())),
        primitive_part(trim(b.to_vec())),
    );
    if a.len() < b.len() {
        std::mem::swap(&mut a, &mut b);
    }
    while !b.is_empty() {
        // Pseudo-remainder of a by b: lc(b)·a − (lead of a)·x^k·b, repeated.
        let lb = b.last().expect("non-empty").clone();
        let mut r = a;
        while r.len() >= b.len() {
            let lr = r.last().expect("non-empty").clone();
            let shift = r.len() - b.len();
            for c in r.iter_mut() {
                *c *= &lb;
            }
            for (i, c) in b.iter().enumerate() {
                r[i + shift] -= &lr * c;
            }
            r = trim(r);
            if r.is_empty() {
                break;
            }
        }
        a = b;
        b = primitive_part(r);
    }
    a
}

/// Whether `a` and `b` may have a common factor (false: certainly coprime).
fn may_share(a: &RootPoly, b: &RootPoly) -> bool {
    for m in [2_305_843_009_213_693_951u64, 1_000_000_007, 998_244_353] {
        if let Some(c) = common_mod(&a.ints, &b.ints, m) {
            return c;
        }
    }
    true
}

impl Root {
    /// The exact rational `r`.
    pub fn rational(r: Rational) -> Root {
        Root {
            poly: RootPoly::new(Poly::new(vec![-r.clone(), Rational::one()])),
            lo: r.clone(),
            hi: r,
            exact: true,
            sign_lo: Ordering::Equal,
        }
    }

    /// Makes the root exact if it is a rational: the simplest rational of a bracket narrowed to
    /// `2^-100` is tried (exactly); otherwise the bracket is left narrowed.
    pub fn recognise_rational(&mut self) {
        self.refine_to(&Rational::new(BigInt::one(), BigInt::one() << 100u32));
        if !self.exact {
            let r = simplest_between(&self.lo, &self.hi);
            if self.poly.poly.eval(&r).is_zero() {
                *self = Root::rational(r);
            }
        }
    }

    /// The value if it is rational and known to be (exact roots).
    pub fn as_rational(&self) -> Option<&Rational> {
        self.exact.then_some(&self.lo)
    }

    /// Halves the bracket (no-op when exact).
    pub fn halve(&mut self) {
        if self.exact {
            return;
        }
        let mid = (&self.lo + &self.hi) / Rational::from_integer(2.into());
        self.cut(mid);
    }

    /// Narrows the bracket at a rational `x` inside it.
    fn cut(&mut self, x: Rational) {
        match self.poly.sign(&x) {
            Ordering::Equal => {
                self.lo = x.clone();
                self.hi = x;
                self.exact = true;
            }
            s if s == self.sign_lo => self.lo = x,
            _ => self.hi = x,
        }
    }

    /// Refines until the bracket is at most `width` wide.
    pub fn refine_to(&mut self, width: &Rational) {
        while !self.exact && &(&self.hi - &self.lo) > width {
            self.halve();
        }
    }

    /// Exact comparison (module docs).
    pub fn compare(&self, other: &Root) -> Ordering {
        let (mut a, mut b) = (self.clone(), other.clone());
        let mut checked = false;
        loop {
            if a.exact && b.exact {
                return a.lo.cmp(&b.lo);
            }
            if a.hi <= b.lo {
                return Ordering::Less;
            }
            if b.hi <= a.lo {
                return Ordering::Greater;
            }
            if a.exact {
                if b.poly.poly.eval(&a.lo).is_zero() {
                    return Ordering::Equal;
                }
                b.cut(a.lo.clone());
                continue;
            }
            if b.exact {
                if a.poly.poly.eval(&b.lo).is_zero() {
                    return Ordering::Equal;
                }
                a.cut(b.lo.clone());
                continue;
            }
            // Distinct roots separate by bisection; the gcd is consulted once, when the
            // brackets are narrow (roots closer than 2^-64 are rare).
            if !checked && &a.hi - &a.lo < narrow() && &b.hi - &b.lo < narrow() {
                checked = true;
                if Arc::ptr_eq(&a.poly, &b.poly) {
                    // One polynomial: its distinct roots have disjoint brackets.
                    return Ordering::Equal;
                }
                if may_share(&a.poly, &b.poly) {
                    let g = primitive_gcd(&a.poly.ints, &b.poly.ints);
                    if g.len() > 1 {
                        let g = Poly::new(g.into_iter().map(Rational::from_integer).collect());
                        let lo = if a.lo > b.lo { &a.lo } else { &b.lo };
                        let hi = if a.hi < b.hi { &a.hi } else { &b.hi };
                        let (sl, sh) = (g.sign_at(lo), g.sign_at(hi));
                        if sl != Ordering::Equal && sh != Ordering::Equal && sl != sh {
                            return Ordering::Equal;
                        }
                    }
                }
            }
            a.halve();
            b.halve();
        }
    }

    /// Compares with a rational.
    pub fn cmp_rational(&self, x: &Rational) -> Ordering {
        self.compare(&Root::rational(x.clone()))
    }

    /// A decimal approximation with `digits` digits after the point (truncated from a bracket
    /// end; display only).
    pub fn decimal(&self, digits: usize) -> String {
        let mut a = self.clone();
        let width = Rational::new(BigInt::one(), num_traits::pow(BigInt::from(10), digits + 2));
        a.refine_to(&width);
        crate::claims::poly::decimal(&a.lo, digits)
    }

    /// The polynomial as a primitive integer polynomial with a positive leading coefficient.
    pub fn polynomial(&self) -> Poly {
        self.poly.poly.primitive()
    }
}

/// A rational strictly between the roots `a < b`.
///
/// ```
/// use truecost::objectives::roots::{between, Root};
/// let a = Root::rational("1/3".parse().unwrap());
/// let b = Root::rational("1/2".parse().unwrap());
/// let t = between(&a, &b);
/// assert!(t > "1/3".parse().unwrap() && t < "1/2".parse().unwrap());
/// ```
pub fn between(a: &Root, b: &Root) -> Rational {
    let two = Rational::from_integer(2.into());
    let (mut a, mut b) = (a.clone(), b.clone());
    loop {
        if a.hi < b.lo {
            return (&a.hi + &b.lo) / &two;
        }
        if a.hi == b.lo && !b.exact {
            // A point of (b.lo, b): the sign there is the sign at b.lo.
            loop {
                let mid = (&b.lo + &b.hi) / &two;
                if b.poly.sign(&mid) == b.sign_lo {
                    return mid;
                }
                b.hi = mid;
            }
        }
        if a.hi == b.lo && !a.exact {
            // A point of (a, a.hi): the sign there is the opposite of the sign at a.lo.
            loop {
                let mid = (&a.lo + &a.hi) / &two;
                let s = a.poly.sign(&mid);
                if s != a.sign_lo && s != Ordering::Equal {
                    return mid;
                }
                a.lo = mid;
            }
        }
        a.halve();
        b.halve();
    }
}

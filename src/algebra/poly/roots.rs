//! Exact real roots in `(0, 1)`, fast enough for the degree-50 advantage polynomials of
//! FrozenLake 8x8 (the breakpoints of the parametric discount analysis, `objectives::parametric`).
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
//! * **Reduction** ([`Root::reduce`]) replaces a root's polynomial by the factor that vanishes
//!   at it: the square-free part, without its rational roots (every rational root `a/b` of an
//!   integer polynomial has `b` dividing the leading coefficient `L`, so `L·r` is an integer
//!   for each real root `r` that is rational: an exact check of one candidate per real root),
//!   and split by gcds with other polynomials known to vanish at the same point
//!   ([`Root::absorb_if_equal`]). The result is proved irreducible over `Q` — the minimal
//!   polynomial up to a constant — when the degrees of its irreducible factors modulo several
//!   primes (distinct-degree factorisation) admit no common proper sub-sum: a factorisation
//!   over `Z` reduces to one modulo every prime not dividing the leading coefficient and the
//!   discriminant. Otherwise it is labelled square-free without rational roots, irreducibility
//!   not proved.
//! * **Decimals** ([`Root::decimal`]) are correctly rounded (to nearest; an exact tie, only
//!   possible for a rational, away from zero): the bracket is cut at the rounding boundary.

use std::cmp::Ordering;
use std::sync::Arc;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::Poly;
use crate::value::Rational;

/// The deepest bisection before the search restarts on the square-free part.
const MAX_DEPTH: u32 = 400;

/// Halvings [`Root::refine_to`] makes one by one before taking the rest at once.
const PLAIN_HALVINGS: usize = 16;

/// The most Newton steps of a guess in [`Root::refine_to`].
const NEWTON_STEPS: usize = 40;

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
/// [`homogeneous`] (`m > 0`), no rational normalisation.
///
/// ```
/// use num_bigint::BigInt;
/// use std::cmp::Ordering;
/// use truecost::algebra::poly::roots::integer_sign;
/// // x² − 2 at 7/5: 49/25 − 2 < 0; at 3/2: 9/4 − 2 > 0.
/// let a: Vec<BigInt> = [-2, 0, 1].into_iter().map(BigInt::from).collect();
/// assert_eq!(integer_sign(&a, &"7/5".parse().unwrap()), Ordering::Less);
/// assert_eq!(integer_sign(&a, &"3/2".parse().unwrap()), Ordering::Greater);
/// ```
pub fn integer_sign(a: &[BigInt], x: &Rational) -> Ordering {
    homogeneous(a, x).sign().cmp(&num_bigint::Sign::NoSign)
}

/// `Σ a_i n^i m^(d−i)` for `x = n/m` and the integer polynomial `a` of degree `d` (constant
/// first): `a(x)·m^d`, by homogeneous Horner.
///
/// ```
/// use truecost::algebra::poly::roots::homogeneous;
/// use num_bigint::BigInt;
/// // 1 + 2x + 3x² at x = 1/2: (4 + 4 + 3) = 11 = (1 + 1 + 3/4)·2².
/// let a: Vec<BigInt> = [1, 2, 3].into_iter().map(BigInt::from).collect();
/// assert_eq!(homogeneous(&a, &"1/2".parse().unwrap()), BigInt::from(11));
/// ```
pub fn homogeneous(a: &[BigInt], x: &Rational) -> BigInt {
    let (n, m) = (x.numer(), x.denom());
    let mut acc = BigInt::zero();
    let mut mpow = BigInt::one();
    for c in a.iter().rev() {
        acc = acc * n + c * &mpow;
        mpow *= m;
    }
    acc
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
    /// What is known of `poly` (module docs, reduction).
    pub reduction: Reduction,
}

/// What is known of a root's polynomial.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reduction {
    /// As met (it may carry other factors, repeated ones included).
    AsMet,
    /// Square-free, without rational roots; irreducibility over `Q` not proved.
    SquareFree,
    /// Irreducible over `Q`: the minimal polynomial (up to a constant factor).
    Minimal,
}

/// `p` scaled to integer coefficients with gcd 1, the sign kept.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::Poly;
/// use truecost::algebra::poly::roots::integer_form;
/// // −x/2 + 1/3 → −3x + 2 (lcm of the denominators 6, content 1, sign kept)
/// let p = Poly::new(vec!["1/3".parse().unwrap(), "-1/2".parse().unwrap()]);
/// assert_eq!(integer_form(&p), [2, -3].map(BigInt::from));
/// ```
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
    let g = content(&scaled);
    if g.is_zero() {
        return scaled;
    }
    scaled.into_iter().map(|c| c / &g).collect()
}

/// The content of integer coefficients: their gcd (`≥ 0`; `0` when all are zero). Taken from
/// the smallest non-zero magnitude up, stopping at 1, each gcd by
/// [`crate::algebra::linear::gcd`].
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::content;
/// let c: Vec<BigInt> = [0, -12, 18, 30].into_iter().map(BigInt::from).collect();
/// assert_eq!(content(&c), BigInt::from(6));
/// assert_eq!(content(&[BigInt::from(0)]), BigInt::from(0));
/// ```
pub fn content(coefficients: &[BigInt]) -> BigInt {
    let mut order: Vec<&BigInt> = coefficients.iter().filter(|c| !c.is_zero()).collect();
    order.sort_by_key(|c| c.bits());
    let mut g = BigInt::zero();
    for c in order {
        if g.is_one() {
            break;
        }
        g = crate::algebra::linear::gcd(&g, c);
    }
    g
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
            let (low, high) = q.split_at_mut(j + 1);
            low[j] += &high[0];
        }
    }
}

/// An upper bound on the roots of `q` in `(0, 1)` (exact when 0 or 1).
fn descartes(q: &[BigInt]) -> usize {
    let mut r: Vec<BigInt> = q.iter().rev().cloned().collect();
    taylor_shift(&mut r);
    variations(&r)
}

/// Whether [`descartes`] of `q` is 0, decided first on `q` truncated to `deg q + 64`
/// significant bits. With `lᵢ = ⌊qᵢ / 2^s⌋`, `qᵢ / 2^s ∈ [lᵢ, lᵢ + 1]`; reversing and shifting
/// (`c_j = Σ_{i≥j} C(i, j) cᵢ`) is linear with non-negative weights, so every shifted
/// coefficient over `2^s` lies in `[L_j, L_j + C(d + 1, j + 1)]` (`Σ_{i≥j} C(i, j) =
/// C(d + 1, j + 1)`) with `L` the shifted `l`. All intervals in `[0, ∞)` (or all in
/// `(−∞, 0]`): no sign variation; one interval positive and one negative: a variation;
/// otherwise the exact test decides.
fn descartes_is_zero(q: &[BigInt]) -> bool {
    let d = q.len().saturating_sub(1);
    let bits = q.iter().map(|c| c.bits()).max().unwrap_or(0);
    let keep = d as u64 + 64;
    if bits <= 2 * keep {
        return descartes(q) == 0;
    }
    let s = bits - keep;
    // Arithmetic shift: rounds towards −∞.
    let mut low: Vec<BigInt> = q.iter().rev().map(|c| c >> s).collect();
    taylor_shift(&mut low);
    // C(d + 1, j + 1) for j = 0..=d.
    let mut width = Vec::with_capacity(d + 1);
    let mut c = BigInt::from(d + 1);
    for j in 0..=d {
        width.push(c.clone());
        c = c * (d - j) / (j + 2);
    }
    let (mut non_negative, mut non_positive) = (true, true);
    let (mut positive, mut negative) = (false, false);
    for (l, w) in low.iter().zip(&width) {
        let h = l + w;
        non_negative &= !l.is_negative();
        non_positive &= !h.is_positive();
        positive |= l.is_positive();
        negative |= h.is_negative();
    }
    if non_negative || non_positive {
        return true;
    }
    if positive && negative {
        return false;
    }
    descartes(q) == 0
}

/// Whether the integer polynomial `p` (constant first) has no root in the open interval
/// `(a, b)`, `a < b`, proved by Descartes' rule on `p(a + (b − a)x)` over `(0, 1)` (no sign
/// variation: no root). `false` means it may have one.
///
/// With `a = A/E`, `b − a = W/E`, the test runs on a non-zero constant multiple of
/// `E^d p(a + (b − a)x)` (the same sign variations), built with `O(d)` products and a Taylor
/// shift (additions only): for `A ≠ 0`, `g(z) = E^d p(A z / E)` has coefficients
/// `p_k A^k E^(d−k)`, `h(u) = g(1 + u)`, and `A^d h(W x / A) = Σ h_i W^i A^(d−i) x^i` is
/// `A^d E^d p((A + W x)/E)`; for `A = 0` the coefficients are `p_k W^k E^(d−k)`.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::no_root_between;
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// let p: Vec<BigInt> = [-1, 0, 2].into_iter().map(BigInt::from).collect(); // 2x^2 - 1
/// assert!(no_root_between(&p, &q("0"), &q("7/10")));
/// assert!(!no_root_between(&p, &q("7/10"), &q("3/4")));
/// assert!(!no_root_between(&p, &q("-3/4"), &q("-7/10")));
/// ```
pub fn no_root_between(p: &[BigInt], a: &Rational, b: &Rational) -> bool {
    if p.iter().all(Zero::is_zero) {
        return false;
    }
    let w = b - a;
    let e = a.denom().lcm(w.denom());
    let big_a = a.numer() * (&e / a.denom());
    let big_w = w.numer() * (&e / w.denom());
    let d = p.len() - 1;
    // powers(x)[k] = x^k, k ≤ d.
    let powers = |x: &BigInt| -> Vec<BigInt> {
        let mut out = Vec::with_capacity(d + 1);
        out.push(BigInt::one());
        for k in 1..=d {
            let next = &out[k - 1] * x;
            out.push(next);
        }
        out
    };
    let epow = powers(&e);
    if big_a.is_zero() {
        let wpow = powers(&big_w);
        let r: Vec<BigInt> = (0..=d).map(|k| &p[k] * &wpow[k] * &epow[d - k]).collect();
        return descartes_is_zero(&r);
    }
    let apow = powers(&big_a);
    let mut h: Vec<BigInt> = (0..=d).map(|k| &p[k] * &apow[k] * &epow[d - k]).collect();
    taylor_shift(&mut h);
    let wpow = powers(&big_w);
    let r: Vec<BigInt> = h
        .iter()
        .enumerate()
        .map(|(i, hi)| hi * &wpow[i] * &apow[d - i])
        .collect();
    descartes_is_zero(&r)
}

enum Isolation {
    Done(Vec<(Rational, Rational)>),
    Midpoint(Rational),
    TooDeep,
}

/// Isolating open intervals of the roots of `p` (integer, no root at 0, 1) in `(0, 1)`; with a
/// window `(a, b)`, only the dyadic nodes of the bisection that meet it are searched, so the
/// intervals returned are those of the full search that meet the window (every root in the
/// window is among them).
fn isolate(p: &[BigInt], window: Option<(&Rational, &Rational)>) -> Isolation {
    let d = p.len() - 1;
    let mut out = Vec::new();
    // (q, c, k): q(x) = 2^{kd} p((c + x) / 2^k) on x ∈ (0, 1).
    let mut stack: Vec<(Vec<BigInt>, BigInt, u32)> = vec![(p.to_vec(), BigInt::zero(), 0)];
    while let Some((q, c, k)) = stack.pop() {
        let scale = Rational::from_integer(BigInt::one() << k);
        if let Some((a, b)) = window {
            // The node [c/2^k, (c+1)/2^k] misses the open window (a, b).
            let left = Rational::from_integer(c.clone()) / &scale;
            let right = Rational::from_integer(&c + 1) / &scale;
            if &right <= a || &left >= b {
                continue;
            }
        }
        let v = descartes(&q);
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
/// use truecost::algebra::poly::Poly;
/// use truecost::algebra::poly::roots::roots_in_unit_interval;
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
    roots_in_window(f, None)
}

/// The roots of the non-zero `f` in `(0, 1)` whose isolating intervals (those of
/// [`roots_in_unit_interval`]'s bisection) meet the open window `(a, b)`, in increasing order:
/// every root of `f` in `(a, b)` is among them, each with the bracket the full search gives it
/// unless the full search divides out a rational root outside the window first. `None`: all of
/// `(0, 1)`.
///
/// ```
/// use truecost::algebra::poly::Poly;
/// use truecost::algebra::poly::roots::{roots_in_unit_interval, roots_in_window};
/// // (4x - 1)(4x - 3)(x^2 - 1/2): roots 1/4, √2/2, 3/4.
/// let f = Poly::from_i64(&[-1, 4]).mul(&Poly::from_i64(&[-3, 4])).mul(&Poly::from_i64(&[-1, 0, 2]));
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// let w = roots_in_window(&f, Some((&q("3/5"), &q("7/10"))));
/// assert!(w.iter().any(|r| r.cmp_rational(&q("7/10")) == std::cmp::Ordering::Greater
///     && r.cmp_rational(&q("3/4")) == std::cmp::Ordering::Less));
/// assert!(w.len() < roots_in_unit_interval(&f).len());
/// ```
pub fn roots_in_window(f: &Poly, window: Option<(&Rational, &Rational)>) -> Vec<Root> {
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
        match isolate(&integer_form(&p), window) {
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
            reduction: Reduction::AsMet,
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
/// use truecost::algebra::poly::roots::simplest_between;
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

/// Whether the bracket is narrower than `2^-64` (cross-multiplied: no gcd).
fn narrower_than_2_64(r: &Root) -> bool {
    let (lo, hi) = (&r.lo, &r.hi);
    let width = hi.numer() * lo.denom() - lo.numer() * hi.denom();
    (width << 64u32) < hi.denom() * lo.denom()
}

/// The primitive part (content removed, sign kept).
fn primitive_part(p: Vec<BigInt>) -> Vec<BigInt> {
    let g = content(&p);
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

/// The integer polynomial `a` (constant first) as a [`Poly`].
fn int_poly(a: &[BigInt]) -> Poly {
    Poly::new(a.iter().cloned().map(Rational::from_integer).collect())
}

/// The primitive part of `a / b`, `b` dividing `a` over `Q` (Gauss's lemma: an integer
/// polynomial, up to sign).
fn exact_quotient(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let (q, r) = int_poly(a).div_rem(&int_poly(b));
    debug_assert!(r.is_zero(), "an exact divisor");
    integer_form(&q)
}

/// The primes tried by [`squarefree_part`] before the exact gcd: the three largest below
/// `2^31` (`2^31 − 1`, `2^31 − 19`, `2^31 − 61`).
const SQUAREFREE_PRIMES: [u64; 3] = [2_147_483_647, 2_147_483_629, 2_147_483_587];

/// Whether `a` (degree ≥ 1, derivative `d`) is proved square-free by a prime `p` not dividing
/// its leading coefficient with `gcd(a mod p, a′ mod p) = 1`: a repeated factor `f²` of `a`
/// over `Z` (`f` primitive, so `p` does not divide its leading coefficient either) would give
/// `f mod p`, of degree at least 1, dividing both. `false` means not proved.
fn squarefree_modulo_a_prime(a: &[BigInt], d: &[BigInt]) -> bool {
    SQUAREFREE_PRIMES
        .into_iter()
        .any(|p| common_mod(a, d, p) == Some(false))
}

/// The square-free part of the integer polynomial `a` (`a / gcd(a, a')`, primitive, with a
/// positive leading coefficient).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::squarefree_part;
/// // (x − 2)^2 (x + 1) = x^3 − 3x^2 + 4 → (x − 2)(x + 1) = x^2 − x − 2.
/// let a: Vec<BigInt> = [4, 0, -3, 1].iter().map(|&c| BigInt::from(c)).collect();
/// let want: Vec<BigInt> = [-2, -1, 1].iter().map(|&c| BigInt::from(c)).collect();
/// assert_eq!(squarefree_part(&a), want);
/// ```
pub fn squarefree_part(a: &[BigInt]) -> Vec<BigInt> {
    let a = primitive_part(a.to_vec());
    let d = int_derivative(&a);
    if d.iter().all(Zero::is_zero) {
        return a;
    }
    let g = (!squarefree_modulo_a_prime(&a, &d)).then(|| primitive_gcd(&a, &d));
    let s = match g {
        Some(g) if g.len() > 1 => exact_quotient(&a, &g),
        _ => a,
    };
    if s.last().is_some_and(Signed::is_negative) {
        s.into_iter().map(|c| -c).collect()
    } else {
        s
    }
}

/// The real roots of the integer polynomial `a` in `(0, 1)`, as brackets mapped by `map` to
/// the real line, checked for rationality: every rational root `r` has `L·r` an integer, `L`
/// the leading coefficient of `f` (the polynomial whose roots are sought), so a bracket of
/// `L·r` narrower than 1 leaves one candidate, checked exactly.
fn rational_among(
    f: &[BigInt],
    a: &[BigInt],
    map: &dyn Fn(&Rational) -> Rational,
    out: &mut Vec<Rational>,
) {
    if a.len() < 2 {
        return;
    }
    let lead = Rational::from_integer(f.last().expect("non-zero").abs());
    for mut s in roots_in_unit_interval(&int_poly(a)) {
        loop {
            if s.exact {
                out.push(map(&s.lo));
                break;
            }
            if s.lo.is_zero() {
                s.halve();
                continue;
            }
            let (u, v) = (map(&s.lo), map(&s.hi));
            let (u, v) = if u < v { (u, v) } else { (v, u) };
            let (u, v) = (&u * &lead, &v * &lead);
            if &v - &u >= Rational::one() {
                s.halve();
                continue;
            }
            // The integers strictly between u and v: at most one.
            let k = u.floor() + Rational::one();
            if k < v {
                let r = k / &lead;
                if integer_sign(f, &r) == Ordering::Equal {
                    out.push(r);
                }
            }
            break;
        }
    }
}

/// Every rational root of the non-zero integer polynomial `f`, in increasing order (distinct).
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::rational_roots;
/// // (2x − 3)(x + 5)(x^2 − 2)(3x − 1)
/// let f: Vec<BigInt> = [-30, 104, -23, -64, 19, 6].iter().map(|&c| BigInt::from(c)).collect();
/// let got: Vec<String> = rational_roots(&f).iter().map(|r| r.to_string()).collect();
/// assert_eq!(got, ["-5", "1/3", "3/2"]);
/// ```
pub fn rational_roots(f: &[BigInt]) -> Vec<Rational> {
    let mut f: Vec<BigInt> = f.to_vec();
    while f.last().is_some_and(Zero::is_zero) {
        f.pop();
    }
    let mut out = Vec::new();
    if f.len() < 2 {
        return out;
    }
    if f[0].is_zero() {
        out.push(Rational::zero());
        let low = f.iter().take_while(|c| c.is_zero()).count();
        f.drain(..low);
    }
    for x in [Rational::one(), -Rational::one()] {
        if f.len() > 1 && integer_sign(&f, &x) == Ordering::Equal {
            out.push(x);
        }
    }
    // Roots in (0, 1), (1, ∞), (−1, 0), (−∞, −1): of f(x), x^d f(1/x), f(−x), x^d f(−1/x).
    let neg: Vec<BigInt> = f
        .iter()
        .enumerate()
        .map(|(i, c)| if i % 2 == 1 { -c } else { c.clone() })
        .collect();
    let rev = |p: &[BigInt]| -> Vec<BigInt> { p.iter().rev().cloned().collect() };
    rational_among(&f, &f, &|s| s.clone(), &mut out);
    rational_among(&f, &rev(&f), &|s| Rational::one() / s, &mut out);
    rational_among(&f, &neg, &|s| -s.clone(), &mut out);
    rational_among(&f, &rev(&neg), &|s| -(Rational::one() / s), &mut out);
    out.sort();
    out.dedup();
    out
}

/// The square-free part of the integer polynomial `f` without its rational roots (primitive,
/// degree ≥ 2 unless every root is rational), those rational roots, and whether the result is
/// proved irreducible ([`Reduction::Minimal`]) or only square-free without rational roots. An
/// irrational root of `f` is a root of the result.
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::{reduce_polynomial, Reduction};
/// let ints = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
/// // −(2x − 3)(x^2 − x − 1)^2 → x^2 − x − 1, with the rational root 3/2.
/// let f = ints(&[3, 4, -7, -4, 7, -2]);
/// let (g, rationals, how) = reduce_polynomial(&f);
/// assert_eq!(g, ints(&[-1, -1, 1]));
/// assert_eq!(rationals, ["3/2".parse().unwrap()]);
/// assert_eq!(how, Reduction::Minimal);
/// ```
pub fn reduce_polynomial(f: &[BigInt]) -> (Vec<BigInt>, Vec<Rational>, Reduction) {
    let mut g = squarefree_part(f);
    let rationals = rational_roots(&g);
    for r in &rationals {
        g = exact_quotient(&g, &[-r.numer().clone(), r.denom().clone()]);
    }
    if g.last().is_some_and(|c| c.is_negative()) {
        g = g.into_iter().map(|c| -c).collect();
    }
    let reduction = if g.len() <= 2 || irreducible_by_degrees(&g) {
        Reduction::Minimal
    } else {
        Reduction::SquareFree
    };
    (g, rationals, reduction)
}

/// Arithmetic modulo a prime `p < 2^31` on polynomials (coefficients constant first, no
/// trailing zeros): enough for distinct-degree factorisation.
mod modp {
    pub fn trim(a: &mut Vec<u64>) {
        while a.last() == Some(&0) {
            a.pop();
        }
    }

    pub fn inv(u: u64, p: u64) -> u64 {
        let (mut r, mut b, mut e) = (1u64, u % p, p - 2);
        while e > 0 {
            if e & 1 == 1 {
                r = r * b % p;
            }
            b = b * b % p;
            e >>= 1;
        }
        r
    }

    /// Long division of `a` by `b` (`b` non-zero, coefficients below `p < 2^32`): the
    /// quotient and the remainder. The working coefficients are `u128` sums of products
    /// `< 2^64`, reduced only where a leading coefficient is read and at the end (one `%` per
    /// step instead of one per term).
    fn divide(a: &[u64], b: &[u64], p: u64) -> (Vec<u64>, Vec<u64>) {
        let lb = inv(*b.last().expect("non-zero divisor"), p);
        let db = b.len();
        let wide = u128::from(p);
        let negated: Vec<u128> = b[..db - 1]
            .iter()
            .map(|&c| u128::from((p - c % p) % p))
            .collect();
        let mut r: Vec<u128> = a.iter().map(|&x| u128::from(x)).collect();
        let mut q = vec![0u64; r.len().saturating_sub(db - 1)];
        let mut top = r.len();
        while top >= db {
            let lead = (r[top - 1] % wide) as u64;
            if lead != 0 {
                let f = lead * lb % p;
                let shift = top - db;
                q[shift] = f;
                let f = u128::from(f);
                for (ri, c) in r[shift..top - 1].iter_mut().zip(&negated) {
                    *ri += f * c;
                }
            }
            top -= 1;
        }
        r.truncate(top.min(db - 1));
        let mut rem: Vec<u64> = r.into_iter().map(|x| (x % wide) as u64).collect();
        trim(&mut rem);
        trim(&mut q);
        (q, rem)
    }

    /// `a mod b` (`b` non-zero).
    pub fn rem(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        divide(a, b, p).1
    }

    /// `a / b`, exact or not (the quotient).
    pub fn quo(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        divide(a, b, p).0
    }

    pub fn mul(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        if a.is_empty() || b.is_empty() {
            return Vec::new();
        }
        let mut c = vec![0u128; a.len() + b.len() - 1];
        for (i, &x) in a.iter().enumerate() {
            let x = u128::from(x);
            for (ci, &y) in c[i..].iter_mut().zip(b) {
                *ci += x * u128::from(y);
            }
        }
        let wide = u128::from(p);
        let mut c: Vec<u64> = c.into_iter().map(|x| (x % wide) as u64).collect();
        trim(&mut c);
        c
    }

    /// The monic gcd.
    pub fn gcd(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        let (mut a, mut b) = (a.to_vec(), b.to_vec());
        trim(&mut a);
        trim(&mut b);
        while !b.is_empty() {
            let r = rem(&a, &b, p);
            a = b;
            b = r;
        }
        if let Some(&l) = a.last() {
            let l = inv(l, p);
            for c in &mut a {
                *c = *c * l % p;
            }
        }
        a
    }

    /// `h^e mod f`.
    pub fn pow_mod(h: &[u64], mut e: u64, f: &[u64], p: u64) -> Vec<u64> {
        let mut r = vec![1u64];
        let mut b = rem(h, f, p);
        while e > 0 {
            if e & 1 == 1 {
                r = rem(&mul(&r, &b, p), f, p);
            }
            b = rem(&mul(&b, &b, p), f, p);
            e >>= 1;
        }
        r
    }

    /// The Frobenius map `h ↦ h^p mod f` of the monic `f` of degree `d ≥ 1` as the rows
    /// `x^(jp) mod f`, `j < d` (`h^p = Σ h_j x^(jp)` modulo `p`): one power and `d`
    /// products build it, then each application is `d²` products.
    fn frobenius(f: &[u64], p: u64) -> Vec<Vec<u64>> {
        let d = f.len() - 1;
        let xp = pow_mod(&[0, 1], p, f, p);
        let mut rows: Vec<Vec<u64>> = Vec::with_capacity(d);
        rows.push(rem(&[1], f, p));
        for j in 1..d {
            let next = rem(&mul(&rows[j - 1], &xp, p), f, p);
            rows.push(next);
        }
        rows
    }

    /// `h^p mod f` (`f` monic) by the rows of [`frobenius`] (for the tests).
    #[cfg(test)]
    pub fn frobenius_power(h: &[u64], f: &[u64], p: u64) -> Vec<u64> {
        apply(&rem(h, f, p), &frobenius(f, p), p)
    }

    /// `h^p mod f` for `h` of degree below `deg f`, by the rows of [`frobenius`].
    fn apply(h: &[u64], rows: &[Vec<u64>], p: u64) -> Vec<u64> {
        let mut out = vec![0u128; rows.len()];
        for (&hj, row) in h.iter().zip(rows) {
            if hj == 0 {
                continue;
            }
            let hj = u128::from(hj);
            for (o, &c) in out.iter_mut().zip(row) {
                *o += hj * u128::from(c);
            }
        }
        let wide = u128::from(p);
        let mut out: Vec<u64> = out.into_iter().map(|x| (x % wide) as u64).collect();
        trim(&mut out);
        out
    }

    /// The distinct-degree factorisation of `f` modulo `p`: for each `i`, the product of the
    /// irreducible factors of degree `i` (monic), or `None` when `p` divides the leading
    /// coefficient or `f` is not square-free modulo `p`.
    pub fn distinct_degree(f: &[u64], p: u64) -> Option<Vec<(usize, Vec<u64>)>> {
        let mut f = f.to_vec();
        if f.last().is_none_or(|&l| l == 0) {
            return None;
        }
        let d: Vec<u64> = f
            .iter()
            .enumerate()
            .skip(1)
            .map(|(i, c)| (i as u64 % p) * c % p)
            .collect();
        if gcd(&f, &d, p).len() != 1 {
            return None;
        }
        let l = inv(*f.last().expect("non-zero"), p);
        for c in &mut f {
            *c = *c * l % p;
        }
        let mut classes = Vec::new();
        // h = x^(p^i) modulo the original f (so modulo every factor of it left in f).
        let frobenius = frobenius(&f, p);
        let mut h = vec![0u64, 1];
        let mut i = 0;
        while 2 * (i + 1) < f.len() {
            i += 1;
            h = apply(&h, &frobenius, p);
            let mut t = h.clone();
            t.resize(t.len().max(2), 0);
            t[1] = (t[1] + p - 1) % p;
            trim(&mut t);
            let g = gcd(&t, &f, p);
            if g.len() > 1 {
                f = quo(&f, &g, p);
                classes.push((i, g));
            }
        }
        if f.len() > 1 {
            classes.push((f.len() - 1, f));
        }
        Some(classes)
    }

    /// The irreducible factors (monic) of `g`, a product of distinct irreducible factors of
    /// degree `i` modulo an odd prime `p` (equal-degree splitting, Cantor–Zassenhaus, with
    /// pseudo-random trial polynomials from `seed`).
    pub fn equal_degree(g: &[u64], i: usize, p: u64, seed: &mut u64) -> Vec<Vec<u64>> {
        if g.len() - 1 == i {
            return vec![g.to_vec()];
        }
        loop {
            // a: a pseudo-random polynomial of degree < deg g.
            let mut a: Vec<u64> = (0..g.len() - 1)
                .map(|_| {
                    *seed = seed
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    (*seed >> 33) % p
                })
                .collect();
            trim(&mut a);
            if a.len() < 2 {
                continue;
            }
            // a^((p^i − 1)/2) = (a · a^p ⋯ a^(p^(i−1)))^((p − 1)/2) modulo g.
            let mut frob = rem(&a, g, p);
            let mut norm = frob.clone();
            for _ in 1..i {
                frob = pow_mod(&frob, p, g, p);
                norm = rem(&mul(&norm, &frob, p), g, p);
            }
            let mut b = pow_mod(&norm, (p - 1) / 2, g, p);
            b = sub(&b, &[1], p);
            let d = gcd(&b, g, p);
            if d.len() > 1 && d.len() < g.len() {
                let mut out = equal_degree(&d, i, p, seed);
                out.extend(equal_degree(&quo(g, &d, p), i, p, seed));
                return out;
            }
        }
    }

    /// `(s, t)` with `s·a + t·b = 1` modulo `p` (`a`, `b` coprime).
    pub fn bezout(a: &[u64], b: &[u64], p: u64) -> (Vec<u64>, Vec<u64>) {
        // Invariants: r0 = s0·a + t0·b, r1 = s1·a + t1·b.
        let (mut r0, mut r1) = (a.to_vec(), b.to_vec());
        let (mut s0, mut s1) = (vec![1u64], Vec::new());
        let (mut t0, mut t1) = (Vec::new(), vec![1u64]);
        while !r1.is_empty() {
            let q = quo(&r0, &r1, p);
            let r2 = sub(&r0, &mul(&q, &r1, p), p);
            let s2 = sub(&s0, &mul(&q, &s1, p), p);
            let t2 = sub(&t0, &mul(&q, &t1, p), p);
            (r0, r1) = (r1, r2);
            (s0, s1) = (s1, s2);
            (t0, t1) = (t1, t2);
        }
        let l = inv(r0[0], p);
        let scale = |v: Vec<u64>| -> Vec<u64> { v.into_iter().map(|c| c * l % p).collect() };
        (scale(s0), scale(t0))
    }

    pub fn sub(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        let mut c = vec![0u64; a.len().max(b.len())];
        for (i, x) in a.iter().enumerate() {
            c[i] = *x;
        }
        for (i, y) in b.iter().enumerate() {
            c[i] = (c[i] + p - y) % p;
        }
        trim(&mut c);
        c
    }
}

/// The largest degree whose irreducibility is tested (the factorisations modulo primes cost
/// about `d^3 log p` each: 0.1 s at degree 50, 0.4 s at 100, 2.4 s at 200 on a loaded
/// machine); a polynomial of higher degree is printed as square-free without rational roots.
pub const MAX_PROVED_DEGREE: usize = 120;

/// Primes below `2^31` tried by [`irreducible_factor_at`], at most.
pub const SPLIT_PRIMES: usize = 16;

/// The most factors modulo a prime whose sub-products are tried as factors over `Z`.
pub const MAX_RECOMBINED: usize = 14;

/// `v` reduced into `(−m/2, m/2]`.
fn symmetric(v: &BigInt, m: &BigInt) -> BigInt {
    let r = v.mod_floor(m);
    if &r * 2 > *m {
        r - m
    } else {
        r
    }
}

/// The derivative of an integer polynomial (constant first).
fn int_derivative(a: &[BigInt]) -> Vec<BigInt> {
    a.iter()
        .enumerate()
        .skip(1)
        .map(|(i, c)| c * BigInt::from(i))
        .collect()
}

fn int_mul(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

fn to_modp(a: &[BigInt], p: u64) -> Vec<u64> {
    let pb = BigInt::from(p);
    let mut v: Vec<u64> = a
        .iter()
        .map(|c| c.mod_floor(&pb).to_u64().expect("reduced"))
        .collect();
    modp::trim(&mut v);
    v
}

fn from_modp(a: &[u64]) -> Vec<BigInt> {
    a.iter().map(|&c| BigInt::from(c)).collect()
}

/// Lifts the monic factor `g` of `f` modulo `p` (`f ≡ lc(f)·g·h`, `g`, `h` coprime) to a monic
/// factor modulo `p^k` (linear Hensel lifting).
fn hensel(f: &[BigInt], g: &[u64], p: u64, k: u32) -> Vec<BigInt> {
    let lead = f.last().expect("non-zero").clone();
    let fp = to_modp(f, p);
    let linv = modp::inv(
        *fp.last()
            .expect("p does not divide the leading coefficient"),
        p,
    );
    let monic: Vec<u64> = fp.iter().map(|c| c * linv % p).collect();
    let hp = modp::quo(&monic, g, p);
    let (_, t) = modp::bezout(g, &hp, p);
    let (mut gz, mut hz) = (from_modp(g), from_modp(&hp));
    let pb = BigInt::from(p);
    let mut m = pb.clone();
    for _ in 1..k {
        // e = (f − lc·g·h) / m modulo p, divided by lc.
        let prod = int_mul(&int_mul(std::slice::from_ref(&lead), &gz), &hz);
        let mut e: Vec<BigInt> = (0..f.len())
            .map(|i| &f[i] - prod.get(i).cloned().unwrap_or_else(BigInt::zero))
            .collect();
        for c in &mut e {
            debug_assert!((&*c % &m).is_zero(), "a lifted factorisation");
            *c = &*c / &m;
        }
        let e: Vec<u64> = to_modp(&e, p).iter().map(|c| c * linv % p).collect();
        // g·δh + h·δg ≡ e: δg = t·e mod g, δh = (e − h·δg) / g.
        let g_now = to_modp(&gz, p);
        let h_now = to_modp(&hz, p);
        let dg = modp::rem(&modp::mul(&t, &e, p), &g_now, p);
        let dh = modp::quo(&modp::sub(&e, &modp::mul(&h_now, &dg, p), p), &g_now, p);
        for (i, c) in dg.iter().enumerate() {
            gz[i] += &m * c;
        }
        for (i, c) in dh.iter().enumerate() {
            hz[i] += &m * c;
        }
        m *= &pb;
    }
    gz.iter().map(|c| c.mod_floor(&m)).collect()
}

/// The irreducible factor over `Q` of the square-free integer polynomial `f` (no rational
/// roots) that vanishes at its only root in the open bracket `(lo, hi)` (a sign change there),
/// proved irreducible: modulo a prime where `f` is square-free, its irreducible factors
/// (distinct-degree, then equal-degree factorisation) are lifted (Hensel)
/// past twice Mignotte's bound on the coefficients of a factor over `Z` times the leading
/// coefficient, and every product of at most half the degree is tried as a factor over `Z`
/// (exact division); none means `f` is irreducible. `None` when every prime tried, within
/// [`SPLIT_PRIMES`], leaves more than [`MAX_RECOMBINED`] factors, or the degree exceeds
/// [`MAX_PROVED_DEGREE`].
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::irreducible_factor_at;
/// let ints = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
/// // (x^2 + x − 1)(x^3 − 2): the root (√5 − 1)/2 ≈ 0.618 in (3/5, 2/3) is a root of x^2 + x − 1.
/// let f = ints(&[2, -2, -2, -1, 1, 1]);
/// let g = irreducible_factor_at(&f, &"3/5".parse().unwrap(), &"2/3".parse().unwrap());
/// assert_eq!(g, Some(ints(&[-1, 1, 1])));
/// ```
pub fn irreducible_factor_at(f: &[BigInt], lo: &Rational, hi: &Rational) -> Option<Vec<BigInt>> {
    let n = f.len().checked_sub(1)?;
    if n <= 1 {
        return Some(f.to_vec());
    }
    if n > MAX_PROVED_DEGREE {
        return None;
    }
    let lead = f[n].abs();
    let max = f.iter().map(Signed::abs).max().expect("non-empty");
    // |coefficients of (lc f / lc G)·G| ≤ |lc f|·2^deg G·‖f‖₂ ≤ |lc f|·2^n·(n + 1)·max|f_i|.
    let bound = BigInt::from(2) * &lead * (BigInt::one() << n) * BigInt::from(n + 1) * &max;
    let mut tried = 0;
    let primes = (1u64 << 30..1 << 31).rev().filter(|&p| is_prime(p));
    for p in primes {
        if tried >= SPLIT_PRIMES {
            break;
        }
        let reduced = to_modp(f, p);
        if reduced.len() != f.len() {
            continue; // p divides the leading coefficient
        }
        let Some(classes) = modp::distinct_degree(&reduced, p) else {
            continue;
        };
        tried += 1;
        let count: usize = classes.iter().map(|(i, g)| (g.len() - 1) / i).sum();
        if count > MAX_RECOMBINED {
            continue;
        }
        if count == 1 {
            return Some(f.to_vec()); // irreducible modulo p
        }
        let mut seed = p;
        let factors: Vec<Vec<u64>> = classes
            .iter()
            .flat_map(|(i, g)| modp::equal_degree(g, *i, p, &mut seed))
            .collect();
        let mut k = 1u32;
        let mut pk = BigInt::from(p);
        while pk <= bound {
            pk *= p;
            k += 1;
        }
        let lifted: Vec<Vec<BigInt>> = factors.iter().map(|g| hensel(f, g, p, k)).collect();
        let fq = int_poly(f);
        // Depth-first over the subsets of total degree ≤ n/2 (a proper factor or its cofactor
        // has such a degree).
        let mut stack: Vec<(usize, Vec<BigInt>)> = vec![(0, vec![f[n].clone()])];
        while let Some((next, prod)) = stack.pop() {
            for (j, g) in lifted.iter().enumerate().skip(next) {
                if prod.len() - 1 + g.len() - 1 > n / 2 {
                    continue;
                }
                let cand: Vec<BigInt> =
                    int_mul(&prod, g).iter().map(|c| c.mod_floor(&pk)).collect();
                let sym: Vec<BigInt> = cand.iter().map(|c| symmetric(c, &pk)).collect();
                let g_try = primitive_part(sym);
                // The constant term of a factor divides f's.
                if !g_try[0].is_zero() && (&f[0] % &g_try[0]).is_zero() {
                    let (q, r) = fq.div_rem(&int_poly(&g_try));
                    if r.is_zero() {
                        let cofactor = integer_form(&q);
                        let (sl, sh) = (integer_sign(&g_try, lo), integer_sign(&g_try, hi));
                        let with_root = if sl != sh { g_try } else { cofactor };
                        return irreducible_factor_at(&with_root, lo, hi);
                    }
                }
                stack.push((j + 1, cand));
            }
        }
        return Some(f.to_vec());
    }
    None
}

/// Primes below `2^31` tried by [`irreducible_by_degrees`], at most.
pub const IRREDUCIBILITY_PRIMES: usize = 24;

fn is_prime(n: u64) -> bool {
    n >= 2
        && (2..)
            .take_while(|d| d * d <= n)
            .all(|d| !n.is_multiple_of(d))
}

/// Whether the square-free integer polynomial `f` (degree ≥ 1) is proved irreducible over `Q`:
/// the degrees a factor over `Z` could have modulo each prime (sub-sums of the degrees of the
/// irreducible factors there, distinct-degree factorisation) leave only `0` and `deg f` in
/// common. `false` means not proved (the polynomial may still be irreducible), and always
/// above degree [`MAX_PROVED_DEGREE`].
///
/// ```
/// use num_bigint::BigInt;
/// use truecost::algebra::poly::roots::irreducible_by_degrees;
/// let ints = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
/// assert!(irreducible_by_degrees(&ints(&[-2, 0, 0, 0, 0, 1]))); // x^5 − 2 (Eisenstein)
/// assert!(!irreducible_by_degrees(&ints(&[2, 0, -3, 0, 1]))); // (x^2 − 1)(x^2 − 2)
/// ```
pub fn irreducible_by_degrees(f: &[BigInt]) -> bool {
    let n = f.len().saturating_sub(1);
    if n <= 1 {
        return n == 1;
    }
    if n > MAX_PROVED_DEGREE {
        return false;
    }
    let mut possible = vec![true; n + 1];
    let mut tried = 0;
    let mut p: u64 = (1 << 31) - 1;
    while tried < IRREDUCIBILITY_PRIMES && p > 1 << 30 {
        if is_prime(p) {
            let pb = BigInt::from(p);
            let red: Vec<u64> = f
                .iter()
                .map(|c| c.mod_floor(&pb).to_u64().expect("reduced"))
                .collect();
            if let Some(classes) = modp::distinct_degree(&red, p) {
                tried += 1;
                let degrees = classes
                    .iter()
                    .flat_map(|(i, g)| std::iter::repeat_n(*i, (g.len() - 1) / i));
                let mut sums = vec![false; n + 1];
                sums[0] = true;
                for d in degrees {
                    for k in (d..=n).rev() {
                        if sums[k - d] {
                            sums[k] = true;
                        }
                    }
                }
                for (k, s) in sums.iter().enumerate() {
                    possible[k] &= *s;
                }
                if possible[1..n].iter().all(|s| !s) {
                    return true;
                }
            }
        }
        p -= 2;
    }
    false
}

impl Root {
    /// The exact rational `r`.
    ///
    /// ```
    /// use truecost::algebra::poly::roots::Root;
    /// let r = Root::rational("2/3".parse().unwrap());
    /// assert!(r.exact);
    /// assert_eq!(r.polynomial().to_string(), "3x - 2");
    /// ```
    pub fn rational(r: Rational) -> Root {
        Root {
            poly: RootPoly::new(Poly::new(vec![-r.clone(), Rational::one()])),
            lo: r.clone(),
            hi: r,
            exact: true,
            sign_lo: Ordering::Equal,
            reduction: Reduction::Minimal,
        }
    }

    /// Replaces the polynomial by the factor vanishing at the root (module docs): square-free,
    /// no rational roots, [`Reduction::Minimal`] when proved irreducible. A rational root
    /// found on the way makes the root exact. The bracket is kept (it isolates the root of
    /// every factor of the polynomial vanishing there).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::{roots_in_unit_interval, Reduction};
    /// // (x² + x − 1)(x³ − 2): its one root in (0, 1) is (√5 − 1)/2 = 0.618…, a root of x² + x − 1.
    /// let f = Poly::from_i64(&[-1, 1, 1]).mul(&Poly::from_i64(&[-2, 0, 0, 1]));
    /// let mut r = roots_in_unit_interval(&f).remove(0);
    /// r.reduce();
    /// assert_eq!(r.reduction, Reduction::Minimal);
    /// assert_eq!(r.polynomial().to_string(), "x^2 + x - 1");
    /// ```
    pub fn reduce(&mut self) {
        if self.exact || self.reduction != Reduction::AsMet {
            return;
        }
        let (f, rationals, reduction) = reduce_polynomial(&self.poly.ints);
        if let Some(r) = rationals.into_iter().find(|r| &self.lo < r && r < &self.hi) {
            *self = Root::rational(r);
            return;
        }
        let (f, reduction) = match reduction {
            Reduction::SquareFree => match irreducible_factor_at(&f, &self.lo, &self.hi) {
                Some(g) => (g, Reduction::Minimal),
                None => (f, reduction),
            },
            _ => (f, reduction),
        };
        self.set_poly(f);
        self.reduction = reduction;
    }

    /// A new polynomial (a factor of the old one vanishing at the root, so the bracket still
    /// isolates it).
    fn set_poly(&mut self, f: Vec<BigInt>) {
        let lead_negative = f
            .last()
            .is_some_and(|c| c.sign() == num_bigint::Sign::Minus);
        let f: Vec<BigInt> = if lead_negative {
            f.into_iter().map(|c| -c).collect()
        } else {
            f
        };
        self.poly = RootPoly::new(int_poly(&f));
        self.sign_lo = self.poly.sign(&self.lo);
        debug_assert!(self.sign_lo != Ordering::Equal && self.poly.sign(&self.hi) != self.sign_lo);
    }

    /// Whether `other` is the same number; if so, this root keeps the exact value if either
    /// has it, else the gcd of the two polynomials (it vanishes at the common root, which is
    /// simple, and divides this root's polynomial, so the bracket isolates its root).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// // 1/√2 as a root of (2x² − 1)(x + 1) and of (2x² − 1)(x + 2): the same number, and the gcd
    /// // 2x² − 1 becomes its polynomial. 1/2 is another number.
    /// let a = Poly::from_i64(&[-1, 0, 2]);
    /// let mut r = roots_in_unit_interval(&a.mul(&Poly::from_i64(&[1, 1]))).remove(0);
    /// let s = roots_in_unit_interval(&a.mul(&Poly::from_i64(&[2, 1]))).remove(0);
    /// assert!(r.absorb_if_equal(&s));
    /// assert_eq!(r.polynomial().to_string(), "2x^2 - 1");
    /// let half = roots_in_unit_interval(&Poly::from_i64(&[-1, 2])).remove(0);
    /// assert!(!r.absorb_if_equal(&half));
    /// ```
    pub fn absorb_if_equal(&mut self, other: &Root) -> bool {
        if self.compare(other) != Ordering::Equal {
            return false;
        }
        if other.exact && !self.exact {
            *self = other.clone();
            return true;
        }
        if self.exact || Arc::ptr_eq(&self.poly, &other.poly) {
            return true;
        }
        let g = primitive_gcd(&self.poly.ints, &other.poly.ints);
        if g.len() > 1 && g.len() < self.poly.ints.len() {
            self.set_poly(g);
            self.reduction = Reduction::AsMet;
        }
        true
    }

    /// Makes the root exact if it is a rational: the simplest rational of a bracket narrowed to
    /// `2^-100` is tried (exactly); otherwise the bracket is left narrowed.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// let mut s = r.clone();
    /// s.recognise_rational();
    /// assert!(!s.exact && &s.hi - &s.lo <= q("1") / q("1267650600228229401496703205376")); // 2^-100
    /// // 3x − 1: its root is recognised as exactly 1/3.
    /// let mut third = roots_in_unit_interval(&Poly::from_i64(&[-1, 3])).remove(0);
    /// third.recognise_rational();
    /// assert_eq!(third.as_rational(), Some(&q("1/3")));
    /// ```
    pub fn recognise_rational(&mut self) {
        self.refine_to(&Rational::new(BigInt::one(), BigInt::one() << 100u32));
        if !self.exact {
            let r = simplest_between(&self.lo, &self.hi);
            if self.poly.sign(&r) == Ordering::Equal {
                *self = Root::rational(r);
            }
        }
    }

    /// The value if it is rational and known to be (exact roots).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// use truecost::algebra::poly::roots::Root;
    /// assert_eq!(r.as_rational(), None);
    /// assert_eq!(Root::rational(q("1/3")).as_rational(), Some(&q("1/3")));
    /// ```
    pub fn as_rational(&self) -> Option<&Rational> {
        self.exact.then_some(&self.lo)
    }

    /// Halves the bracket (no-op when exact).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// let mut s = r.clone();
    /// s.halve();
    /// assert_eq!(&s.hi - &s.lo, (&r.hi - &r.lo) / q("2"));
    /// assert!(q("2") * &s.lo * &s.lo < q("1") && q("2") * &s.hi * &s.hi > q("1"));
    /// ```
    pub fn halve(&mut self) {
        if self.exact {
            return;
        }
        // (lo + hi)/2 with one normalisation (dashu's gcd: the binary gcd of num-bigint is
        // quadratic when one side is small).
        let mid = crate::algebra::linear::reduced(
            &(self.lo.numer() * self.hi.denom() + self.hi.numer() * self.lo.denom()),
            &(2 * self.lo.denom() * self.hi.denom()),
        );
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

    /// Refines until the bracket is at most `width` wide: the bracket of bisection (halving
    /// until narrow enough, exact if a midpoint is the root). After 16 halvings the remaining
    /// ones are taken at once where a Newton guess of the final cell is confirmed by the signs
    /// at its ends.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// let mut s = r.clone();
    /// s.refine_to(&q("1/1000000"));
    /// assert!(&s.hi - &s.lo <= q("1/1000000"));
    /// assert!(q("2") * &s.lo * &s.lo < q("1") && q("2") * &s.hi * &s.hi > q("1"));
    /// ```
    pub fn refine_to(&mut self, width: &Rational) {
        let mut plain = 0;
        while !self.exact && &(&self.hi - &self.lo) > width {
            if plain == PLAIN_HALVINGS && self.leap(width) {
                return;
            }
            self.halve();
            plain += 1;
        }
    }

    /// The outcome of the `s` halvings bisection would still make to reach `width`, in one
    /// step: after `s` halvings of `(lo, hi)` (width `w`) the bracket is the cell
    /// `(lo + j w/2^s, lo + (j + 1) w/2^s)` holding the root, unless a cell end is the root
    /// (then some midpoint was, and the root is exact). A Newton iteration guesses `j`; the
    /// signs of the polynomial at the cell's ends confirm it exactly (a simple root lies where
    /// the sign changes). `false` (nothing changed) when the guess is not confirmed.
    fn leap(&mut self, width: &Rational) -> bool {
        let w = &self.hi - &self.lo;
        let mut s = 0u32;
        let mut cell = w.clone();
        while &cell > width {
            cell /= Rational::from_integer(2.into());
            s += 1;
        }
        let Some(x) = self.newton(&cell) else {
            return false;
        };
        let last = (BigInt::one() << s) - 1;
        let guess = ((&x - &self.lo) / &cell).floor().to_integer();
        for j in [guess.clone(), &guess - 1, &guess + 1] {
            if j.is_negative() || j > last {
                continue;
            }
            let a = &self.lo + &cell * Rational::from_integer(j.clone());
            let b = &a + &cell;
            let sa = if j.is_zero() {
                self.sign_lo
            } else {
                self.poly.sign(&a)
            };
            if sa == Ordering::Equal {
                *self = Root {
                    lo: a.clone(),
                    hi: a,
                    exact: true,
                    ..self.clone()
                };
                return true;
            }
            if sa != self.sign_lo {
                continue;
            }
            match self.poly.sign(&b) {
                Ordering::Equal => {
                    *self = Root {
                        lo: b.clone(),
                        hi: b,
                        exact: true,
                        ..self.clone()
                    };
                    return true;
                }
                sb if sb != self.sign_lo => {
                    self.lo = a;
                    self.hi = b;
                    return true;
                }
                _ => {}
            }
        }
        false
    }

    /// The root to within about `cell / 8` by Newton's iteration from the bracket's midpoint,
    /// on dyadic rationals of fixed precision; `None` if an iterate leaves the bracket (the
    /// caller then bisects). Only a guess: [`Root::leap`] confirms it.
    fn newton(&self, cell: &Rational) -> Option<Rational> {
        let f = &self.poly.ints;
        let derivative = int_derivative(f);
        // 2^-bits below cell / 2^8.
        let bits = cell.denom().bits() - cell.numer().bits() + 10;
        let scale = BigInt::one() << bits;
        let dyadic = |y: &Rational| -> Rational {
            Rational::new(
                (y * Rational::from_integer(scale.clone()))
                    .floor()
                    .to_integer(),
                scale.clone(),
            )
        };
        let mut x = dyadic(&((&self.lo + &self.hi) / Rational::from_integer(2.into())));
        let tolerance = cell / Rational::from_integer(BigInt::from(8));
        for _ in 0..NEWTON_STEPS {
            let (value, slope) = (homogeneous(f, &x), homogeneous(&derivative, &x));
            if slope.is_zero() {
                return None;
            }
            // p(x) / p'(x) = (value / m^d) / (slope / m^(d−1)).
            let step = Rational::new(value, slope * x.denom());
            let next = dyadic(&(&x - &step));
            if next <= self.lo || next >= self.hi {
                return None;
            }
            let moved = (&next - &x).abs();
            x = next;
            if moved < tolerance {
                return Some(x);
            }
        }
        Some(x)
    }

    /// Exact comparison (module docs).
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// use std::cmp::Ordering;
    /// use truecost::algebra::poly::roots::Root;
    /// // 2/3 < 1/√2 = 0.7071… < 3/4
    /// assert_eq!(r.compare(&Root::rational(q("2/3"))), Ordering::Greater);
    /// assert_eq!(r.compare(&Root::rational(q("3/4"))), Ordering::Less);
    /// // 4x² − 2 vanishes at the same number.
    /// let same = roots_in_unit_interval(&Poly::from_i64(&[-2, 0, 4])).remove(0);
    /// assert_eq!(r.compare(&same), Ordering::Equal);
    /// ```
    pub fn compare(&self, other: &Root) -> Ordering {
        // Disjoint brackets (or two exact values) decide without refining.
        if self.exact && other.exact {
            return self.lo.cmp(&other.lo);
        }
        if self.hi <= other.lo {
            return Ordering::Less;
        }
        if other.hi <= self.lo {
            return Ordering::Greater;
        }
        // Brackets from one isolation (one shared polynomial) are disjoint and refinement only
        // narrows them: overlapping ones hold the same root.
        if Arc::ptr_eq(&self.poly, &other.poly) {
            return Ordering::Equal;
        }
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
                if b.poly.sign(&a.lo) == Ordering::Equal {
                    return Ordering::Equal;
                }
                b.cut(a.lo.clone());
                continue;
            }
            if b.exact {
                if a.poly.sign(&b.lo) == Ordering::Equal {
                    return Ordering::Equal;
                }
                a.cut(b.lo.clone());
                continue;
            }
            // Distinct roots separate by bisection; the gcd is consulted once, when the
            // brackets are narrow (roots closer than 2^-64 are rare).
            if !checked && narrower_than_2_64(&a) && narrower_than_2_64(&b) {
                checked = true;
                if Arc::ptr_eq(&a.poly, &b.poly) {
                    // One polynomial: its distinct roots have disjoint brackets.
                    return Ordering::Equal;
                }
                if may_share(&a.poly, &b.poly) {
                    let g = primitive_gcd(&a.poly.ints, &b.poly.ints);
                    if g.len() > 1 {
                        let lo = if a.lo > b.lo { &a.lo } else { &b.lo };
                        let hi = if a.hi < b.hi { &a.hi } else { &b.hi };
                        let (sl, sh) = (integer_sign(&g, lo), integer_sign(&g, hi));
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
    /// (The bracket decides, else the sign of the integer polynomial at `x`: the same answer as
    /// [`Root::compare`] with the exact root `x`, without building its polynomial.)
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
    /// // 2x² − 1: the root 1/√2 = 0.70710678… in (0, 1).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// use std::cmp::Ordering;
    /// assert_eq!(r.cmp_rational(&q("7/10")), Ordering::Greater);
    /// assert_eq!(r.cmp_rational(&q("71/100")), Ordering::Less);
    /// ```
    pub fn cmp_rational(&self, x: &Rational) -> Ordering {
        if self.exact {
            return self.lo.cmp(x);
        }
        if &self.hi <= x {
            return Ordering::Less;
        }
        if x <= &self.lo {
            return Ordering::Greater;
        }
        match self.poly.sign(x) {
            Ordering::Equal => Ordering::Equal,
            // The polynomial keeps its sign at `lo` up to the root.
            s if s == self.sign_lo => Ordering::Greater,
            _ => Ordering::Less,
        }
    }

    /// The value correctly rounded to `digits` digits after the point (to nearest; a tie,
    /// only possible when the value is rational, away from zero). The bracket is refined below
    /// one unit of the last digit, then cut at the rounding boundary it may contain, so the
    /// digits are those of the number itself, not of an approximation.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// // 2x^2 - 1: 1/√2 = 0.70710678118654752440084...; 6 digits: 0.707107 (truncated: 0.707106).
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[-1, 0, 2])).remove(0);
    /// assert_eq!(r.decimal(6), "0.707107");
    /// assert_eq!(r.decimal(20), "0.70710678118654752440");
    /// ```
    pub fn decimal(&self, digits: usize) -> String {
        let mut a = self.clone();
        let unit = Rational::new(BigInt::one(), num_traits::pow(BigInt::from(10), digits));
        a.refine_to(&unit);
        if !a.exact {
            // lo lies in the rounding cell of k: [(k − 1/2)·unit, (k + 1/2)·unit).
            let k = (&a.lo / &unit + Rational::new(BigInt::one(), BigInt::from(2))).floor();
            let boundary = (k + Rational::new(BigInt::one(), BigInt::from(2))) * &unit;
            if a.lo < boundary && boundary < a.hi {
                a.cut(boundary);
            }
        }
        if a.exact {
            return crate::algebra::poly::decimal_rounded(&a.lo, digits);
        }
        // The root lies strictly inside (lo, hi), within the closure of one rounding cell
        // (width at most one unit, no boundary strictly inside): the bracket's midpoint lies
        // strictly inside the same cell, so it rounds to the same digits.
        let mid = (&a.lo + &a.hi) / Rational::from_integer(2.into());
        crate::algebra::poly::decimal_rounded(&mid, digits)
    }

    /// The polynomial as a primitive integer polynomial with a positive leading coefficient.
    ///
    /// ```
    /// use truecost::algebra::poly::Poly;
    /// use truecost::algebra::poly::roots::roots_in_unit_interval;
    /// // The root of −4x² + 2 (= 1/√2), as the primitive 2x² − 1.
    /// let r = roots_in_unit_interval(&Poly::from_i64(&[2, 0, -4])).remove(0);
    /// assert_eq!(r.polynomial().to_string(), "2x^2 - 1");
    /// ```
    pub fn polynomial(&self) -> Poly {
        self.poly.poly.primitive()
    }
}

/// A rational strictly between the roots `a < b`.
///
/// ```
/// use truecost::algebra::poly::roots::{between, Root};
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

#[cfg(test)]
mod tests {
    use super::modp;
    use num_bigint::BigInt;

    /// `squarefree_part` of `c·Π fᵢ^eᵢ` for distinct linear factors `fᵢ = kᵢx − mᵢ`
    /// (`gcd(kᵢ, mᵢ) = 1`) is `Π fᵢ` with a positive leading coefficient, whether the modular
    /// proof or the exact gcd answers; the modular proof never accepts a square factor.
    #[test]
    fn squarefree_part_of_products_of_linear_factors() {
        use num_integer::Integer;
        use num_traits::{One, Signed};
        let mul = |a: &[BigInt], b: &[BigInt]| super::int_mul(a, b);
        let derivative = |a: &[BigInt]| super::int_derivative(a);
        let mut seed = 5u64;
        let mut next = |k: u64| step(&mut seed) % k;
        let mut squares = 0;
        for case in 0..200 {
            let mut factors: Vec<(i64, i64)> = Vec::new();
            // The first factor's k a multiple of 2^31 − 1 in some cases (that prime is skipped).
            while factors.len() < 1 + next(5) as usize {
                let k = 1 + next(30) as i64;
                let k = if case % 5 == 0 && factors.is_empty() {
                    k * 2_147_483_647
                } else {
                    k
                };
                let m = next(61) as i64 - 30;
                if k.gcd(&m) == 1 && !factors.iter().any(|&(k2, m2)| k2 * m == m2 * k) {
                    factors.push((k, m));
                }
            }
            let (mut a, mut want) = (vec![BigInt::from(1 + next(9) as i64)], vec![BigInt::one()]);
            let mut square = false;
            for &(k, m) in &factors {
                let f = [BigInt::from(-m), BigInt::from(k)];
                want = mul(&want, &f);
                for _ in 0..1 + next(3) {
                    a = mul(&a, &f);
                }
                square |= a.len() > want.len();
            }
            if case % 2 == 1 {
                a = a.into_iter().map(|c| -c).collect();
            }
            if want.last().is_some_and(Signed::is_negative) {
                want = want.into_iter().map(|c| -c).collect();
            }
            assert_eq!(super::squarefree_part(&a), want, "case {case}");
            if square {
                squares += 1;
                assert!(
                    !super::squarefree_modulo_a_prime(&a, &derivative(&a)),
                    "case {case}"
                );
            }
        }
        assert!(squares > 50, "{squares}");
        // A square-free polynomial whose leading coefficient the first prime divides.
        let a: Vec<BigInt> = mul(
            &[BigInt::from(-1), BigInt::from(2_147_483_647)],
            &[BigInt::from(-2), BigInt::one()],
        );
        assert!(super::squarefree_modulo_a_prime(&a, &derivative(&a)));
    }

    /// `no_root_between` agrees with Descartes' rule applied as stated: the sign variations of
    /// `(1 + x)^d r(1/(1 + x))` for `r(x) = p(a + (b − a)x)`, here computed in rationals
    /// (Horner's rule for `r`, the reversal and the shift by 1 term by term), on pseudo-random
    /// integer polynomials and windows, negative, at 0 and inside (0, 1).
    #[test]
    fn no_root_between_is_descartes_rule_on_the_window() {
        use crate::value::Rational;
        use num_traits::{Signed, Zero};
        let q = |n: i64, d: i64| Rational::new(n.into(), d.into());
        let variations_on = |p: &[BigInt], a: &Rational, b: &Rational| -> usize {
            let w = b - a;
            let mut r: Vec<Rational> = vec![Rational::from_integer(p[p.len() - 1].clone())];
            for k in (0..p.len() - 1).rev() {
                let mut next = vec![Rational::zero(); r.len() + 1];
                for (i, ri) in r.iter().enumerate() {
                    next[i] += ri * a;
                    next[i + 1] += ri * &w;
                }
                next[0] += Rational::from_integer(p[k].clone());
                r = next;
            }
            let mut c: Vec<Rational> = r.into_iter().rev().collect();
            for i in 0..c.len() {
                for j in (i..c.len() - 1).rev() {
                    let high = c[j + 1].clone();
                    c[j] += high;
                }
            }
            let signs: Vec<bool> = c
                .iter()
                .filter(|x| !x.is_zero())
                .map(|x| x.is_positive())
                .collect();
            signs.windows(2).filter(|s| s[0] != s[1]).count()
        };
        let mut seed = 11u64;
        let mut next = |k: u64| step(&mut seed) % k;
        let (mut with, mut without) = (0, 0);
        for case in 0..400 {
            let d = 1 + next(9) as usize;
            let p: Vec<BigInt> = (0..=d)
                .map(|_| BigInt::from(next(2001) as i64 - 1000) << (next(3) * 40))
                .collect();
            let den = 1 + next(60) as i64;
            let lo = match case % 4 {
                0 => q(0, 1),
                1 => q(-(next(3 * den as u64) as i64), den),
                _ => q(next(den as u64) as i64, den),
            };
            let hi = &lo + q(1 + next(1000) as i64, 1 + next(5000) as i64);
            let want = variations_on(&p, &lo, &hi) == 0;
            assert_eq!(super::no_root_between(&p, &lo, &hi), want, "case {case}");
            if want {
                without += 1;
            } else {
                with += 1;
            }
        }
        // Both answers are exercised.
        assert!(with > 50 && without > 50, "{with} {without}");
    }

    /// The truncated Descartes test decides as the exact one: on products of linear factors
    /// with roots inside and outside (0, 1), scaled by large integers so that truncation
    /// happens, and on their negations.
    #[test]
    fn truncated_descartes_decides_as_the_exact_test() {
        let mut seed = 11u64;
        let mut next = || step(&mut seed);
        let (mut zero, mut some) = (0, 0);
        for case in 0..60 {
            // Factors (m x − n): root n/m; in (0, 1) when 0 < n < m.
            let mut p = vec![BigInt::from(1)];
            let degree = 3 + case % 12;
            for _ in 0..degree {
                let m = BigInt::from(next() % 1000 + 1);
                let n = BigInt::from(next() % 3000) - BigInt::from(1000);
                p = super::int_mul(&p, &[-n, m]);
            }
            let scale = BigInt::from(3).pow(200 + (next() % 400) as u32);
            for sign in [1, -1] {
                let q: Vec<BigInt> = p.iter().map(|c| c * &scale * sign).collect();
                let exact = super::descartes(&q) == 0;
                assert_eq!(super::descartes_is_zero(&q), exact, "case {case}");
                if exact {
                    zero += 1;
                } else {
                    some += 1;
                }
            }
        }
        assert!(zero > 0 && some > 0, "both outcomes met: {zero} {some}");
        // A variation only in a tiny last coefficient: after the shift the coefficients are
        // -M, ..., -M, 1 (M = 3^300), so the truncated bounds of the last one straddle 0 and
        // the exact test must decide (one variation).
        let d = 10;
        let big = BigInt::from(3).pow(300);
        let mut shifted: Vec<BigInt> = vec![-big; d];
        shifted.push(BigInt::from(1));
        // Undo the shift: T(x - 1) by Horner, then reverse.
        let mut unshifted = vec![BigInt::from(0)];
        for c in shifted.iter().rev() {
            let mut next = vec![BigInt::from(0); unshifted.len() + 1];
            for (i, u) in unshifted.iter().enumerate() {
                next[i + 1] += u;
                next[i] -= u;
            }
            next[0] += c;
            unshifted = next;
        }
        unshifted.truncate(d + 1);
        let q: Vec<BigInt> = unshifted.into_iter().rev().collect();
        assert_eq!(super::descartes(&q), 1);
        assert!(!super::descartes_is_zero(&q));
    }

    /// Schoolbook products and long division with a reduction after every operation: the
    /// lazily reduced ones must agree.
    fn naive_mul(a: &[u64], b: &[u64], p: u64) -> Vec<u64> {
        let mut c = vec![0u64; (a.len() + b.len()).saturating_sub(1)];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                c[i + j] = (c[i + j] + x * y % p) % p;
            }
        }
        modp::trim(&mut c);
        c
    }

    fn random(seed: &mut u64, len: usize, p: u64) -> Vec<u64> {
        (0..len).map(|_| step(seed) % p).collect()
    }

    /// The next number of a 64-bit linear congruential generator (its top 31 bits).
    fn step(seed: &mut u64) -> u64 {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        *seed >> 33
    }

    #[test]
    fn lazy_products_and_division_agree_with_reduction_at_every_step() {
        let p = (1u64 << 31) - 1;
        let mut seed = 7;
        for (la, lb) in [(1, 1), (5, 3), (40, 17), (200, 199), (300, 2), (3, 9)] {
            let a = random(&mut seed, la, p);
            let mut b = random(&mut seed, lb, p);
            if b.last() == Some(&0) || b.is_empty() {
                b.push(1);
            }
            let mut ta = a.clone();
            modp::trim(&mut ta);
            assert_eq!(modp::mul(&a, &b, p), naive_mul(&a, &b, p), "{la} x {lb}");
            let (q, r) = (modp::quo(&a, &b, p), modp::rem(&a, &b, p));
            assert!(r.len() < b.len(), "remainder degree, {la} / {lb}");
            let mut back = naive_mul(&q, &b, p);
            back.resize(back.len().max(r.len()), 0);
            for (x, y) in back.iter_mut().zip(&r) {
                *x = (*x + y) % p;
            }
            modp::trim(&mut back);
            assert_eq!(back, ta, "q b + r = a, {la} / {lb}");
        }
    }

    #[test]
    fn the_frobenius_rows_give_the_pth_power() {
        // f = x^5 + 3x + 7 modulo p; h^p by repeated squaring against the rows.
        let p = 1_000_000_007u64;
        let f = [7u64, 3, 0, 0, 0, 1];
        let mut seed = 3;
        for _ in 0..4 {
            let h = random(&mut seed, 5, p);
            assert_eq!(
                modp::frobenius_power(&h, &f, p),
                modp::pow_mod(&h, p, &f, p),
                "{h:?}"
            );
        }
    }

    /// Plain bisection: what `refine_to` must end with.
    fn bisected(mut r: super::Root, width: &crate::value::Rational) -> super::Root {
        while !r.exact && &(&r.hi - &r.lo) > width {
            r.halve();
        }
        r
    }

    /// The refinement that takes the last halvings at once ends where plain bisection does:
    /// on the roots of random integer polynomials (products of linear and quadratic factors),
    /// to binary and decimal widths, and on dyadic roots deep in the bisection (exact there).
    #[test]
    fn refine_to_ends_where_bisection_does() {
        use super::{int_poly, roots_in_unit_interval};
        use crate::value::Rational;
        let mut seed = 5u64;
        let mut next = || step(&mut seed);
        let widths = [
            Rational::new(BigInt::from(1), BigInt::from(1) << 100u32),
            Rational::new(BigInt::from(1), num_traits::pow(BigInt::from(10), 30)),
            Rational::new(BigInt::from(1), BigInt::from(1) << 20u32),
        ];
        let compare = |root: &super::Root, label: &str| {
            for width in &widths {
                let (mut fast, slow) = (root.clone(), bisected(root.clone(), width));
                fast.refine_to(width);
                assert_eq!(
                    (fast.exact, &fast.lo, &fast.hi),
                    (slow.exact, &slow.lo, &slow.hi),
                    "{label}"
                );
            }
        };
        let mut checked = 0;
        for case in 0..40 {
            let mut p = vec![BigInt::from(1)];
            for k in 0..2 + case % 6 {
                let factor: Vec<BigInt> = if k % 2 == 0 {
                    vec![
                        -BigInt::from(next() % 997 + 1),
                        BigInt::from(next() % 997 + 998),
                    ]
                } else {
                    vec![
                        -BigInt::from(next() % 50 + 1),
                        BigInt::from(next() % 7) - 3,
                        BigInt::from(next() % 90 + 60),
                    ]
                };
                p = super::int_mul(&p, &factor);
            }
            for root in roots_in_unit_interval(&int_poly(&p)) {
                compare(&root, &format!("case {case}"));
                checked += widths.len();
            }
        }
        assert!(checked > 100, "{checked} refinements compared");
        // 2^40 x − c: bracket (0, 1) at once, the root c/2^40 a midpoint at depth 40.
        for c in [1u64, 3, 0x5_5555_5555, (1 << 40) - 1] {
            let p = vec![-BigInt::from(c), BigInt::from(1u64 << 40)];
            compare(
                &roots_in_unit_interval(&int_poly(&p))[0],
                &format!("c = {c}"),
            );
        }
    }

    /// The square-free part with and without the modular shortcut: a square-free polynomial
    /// with large coefficients is its own (primitive, leading coefficient positive), and a
    /// product with a squared factor loses one copy of it.
    #[test]
    fn square_free_parts() {
        use super::squarefree_part;
        let ints = |c: &[i64]| -> Vec<BigInt> { c.iter().map(|&x| BigInt::from(x)).collect() };
        let big: BigInt = BigInt::from(1u64 << 62) * BigInt::from(1u64 << 62) + 1;
        let f = vec![-big.clone(), BigInt::from(3), -BigInt::from(7)];
        assert_eq!(
            squarefree_part(&f),
            vec![big, BigInt::from(-3), BigInt::from(7)]
        );
        // (x − 2)^2 (x + 3) = x^3 − x^2 − 8x + 12 → (x − 2)(x + 3) = x^2 + x − 6.
        assert_eq!(squarefree_part(&ints(&[12, -8, -1, 1])), ints(&[-6, 1, 1]));
        assert_eq!(squarefree_part(&ints(&[6, -5, 1])), ints(&[6, -5, 1]));
    }
}

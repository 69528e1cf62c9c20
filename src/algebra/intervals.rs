//! Subsets of the open unit interval `(0, 1)` as finite unions of maximal intervals whose ends
//! are `0`, `1` or real algebraic numbers, and their exact text: the form in which the discount
//! analyses (the C3 claim's enumeration of goal paths and lassos, the parametric discount
//! engine) state for which discount factors a discount-optimal policy fails to reach the goal.

use num_traits::One;

use crate::algebra::poly::roots::Reduction;
use crate::algebra::poly::Algebraic;
use crate::value::Rational;

/// An end of a piece of the set.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Point {
    /// 0.
    Zero,
    /// 1.
    One,
    /// An algebraic number in `(0,1)`.
    Root(Algebraic),
}

/// A maximal interval of the set (possibly a single point: `lo == hi`, both closed).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Piece {
    /// Lower end.
    pub lo: Point,
    /// Whether `lo` belongs to the set.
    pub lo_closed: bool,
    /// Upper end.
    pub hi: Point,
    /// Whether `hi` belongs to the set.
    pub hi_closed: bool,
}

/// A subset of `(0, 1)` of discount factors `α` (the answer of the discount analyses: the
/// factors for which a discount-optimal policy fails to reach the goal).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DiscountSet {
    /// The maximal pieces, in increasing order.
    pub pieces: Vec<Piece>,
    /// How the set was obtained.
    pub method: String,
}

/// The maximal pieces of a subset of `(0, 1)` given by membership on its atoms in increasing
/// order: `member[2i]` for the open gap before `points[i]` (the last gap ends at 1),
/// `member[2i + 1]` for `points[i]` itself. A run of members becomes one piece, closed at an
/// end that is a point, open at an end that is a gap's.
///
/// ```
/// use truecost::algebra::intervals::{pieces_of_members, Point};
/// use truecost::algebra::poly::Algebraic;
/// use num_rational::BigRational;
/// let half = Point::Root(Algebraic::from_rational(BigRational::new(1.into(), 2.into())));
/// // (0, 1/2) out, 1/2 in, (1/2, 1) in: the piece [1/2, 1).
/// let p = pieces_of_members(&[half.clone()], &[false, true, true]);
/// assert_eq!(p.len(), 1);
/// assert_eq!((p[0].lo.clone(), p[0].lo_closed, p[0].hi.clone(), p[0].hi_closed), (half, true, Point::One, false));
/// ```
pub fn pieces_of_members(points: &[Point], member: &[bool]) -> Vec<Piece> {
    assert_eq!(
        member.len(),
        2 * points.len() + 1,
        "a gap around every point"
    );
    let lo_of = |a: usize| -> (Point, bool) {
        if a % 2 == 1 {
            (points[a / 2].clone(), true)
        } else if a == 0 {
            (Point::Zero, false)
        } else {
            (points[a / 2 - 1].clone(), false)
        }
    };
    let hi_of = |a: usize| -> (Point, bool) {
        if a % 2 == 1 {
            (points[a / 2].clone(), true)
        } else if a / 2 < points.len() {
            (points[a / 2].clone(), false)
        } else {
            (Point::One, false)
        }
    };
    let mut pieces = Vec::new();
    let mut k = 0;
    while k < member.len() {
        if !member[k] {
            k += 1;
            continue;
        }
        let start = k;
        while k + 1 < member.len() && member[k + 1] {
            k += 1;
        }
        let ((lo, lo_closed), (hi, hi_closed)) = (lo_of(start), hi_of(k));
        pieces.push(Piece {
            lo,
            lo_closed,
            hi,
            hi_closed,
        });
        k += 1;
    }
    pieces
}

/// `a` as text: `0`, `1`, `p/q`, or its decimal correctly rounded to 30 digits followed by
/// `...`, with the factor of its polynomial that vanishes there (named the minimal polynomial
/// when proved irreducible) and an isolating bracket `(lo, hi]`.
///
/// ```
/// use num_rational::BigRational;
/// use truecost::algebra::intervals::{point_text, Point};
/// use truecost::algebra::poly::{isolate_roots, Poly};
/// let q = |n: i64| BigRational::from_integer(n.into());
/// // 2α² − 1 vanishes at 1/√2 = 0.7071067811865475244008443621048…
/// let roots = isolate_roots(&Poly::new(vec![q(-1), q(0), q(2)]), &q(0), &q(1));
/// let text = point_text(&Point::Root(roots[0].clone()));
/// assert!(text.starts_with("0.707106781186547524400844362105... (the root of the minimal polynomial "));
/// assert_eq!(point_text(&Point::One), "1");
/// ```
pub fn point_text(p: &Point) -> String {
    match p {
        Point::Zero => "0".into(),
        Point::One => "1".into(),
        Point::Root(a) if a.as_rational().is_some() => rat(&a.as_rational().expect("rational")),
        Point::Root(a) => {
            let mut b = a.clone();
            b.refine_to(&Rational::new(
                One::one(),
                num_bigint::BigInt::one() << 100usize,
            ));
            let (poly, how) = b.reduced_polynomial();
            format!(
                "{}... (the root of {}{poly} in ({}, {}]{}; decimal rounded to 30 digits)",
                b.decimal_rounded(30),
                if how == Reduction::Minimal {
                    "the minimal polynomial "
                } else {
                    ""
                },
                rat(&b.lo),
                rat(&b.hi),
                if how == Reduction::Minimal {
                    ""
                } else {
                    ", square-free without rational roots, irreducibility not proved"
                }
            )
        }
    }
}

/// `p/q` text of a rational (an integer without `/1`).
///
/// ```
/// use num_rational::BigRational;
/// use truecost::algebra::intervals::rat;
/// assert_eq!(rat(&BigRational::new((-6).into(), 4.into())), "-3/2");
/// assert_eq!(rat(&BigRational::from_integer(7.into())), "7");
/// ```
pub fn rat(x: &Rational) -> String {
    if x.is_integer() {
        x.numer().to_string()
    } else {
        format!("{}/{}", x.numer(), x.denom())
    }
}

/// The set in interval notation: its pieces joined by ` U `, a single point in braces, `empty`
/// for the empty set.
///
/// ```
/// use num_rational::BigRational;
/// use truecost::algebra::intervals::{set_text, DiscountSet, Piece, Point};
/// use truecost::algebra::poly::Algebraic;
/// let third = Point::Root(Algebraic::from_rational(BigRational::new(1.into(), 3.into())));
/// let piece = |lo: &Point, lo_closed, hi: &Point, hi_closed| Piece {
///     lo: lo.clone(),
///     lo_closed,
///     hi: hi.clone(),
///     hi_closed,
/// };
/// let set = |pieces| DiscountSet { pieces, method: String::new() };
/// let two = vec![piece(&Point::Zero, false, &third, false), piece(&third, true, &third, true)];
/// assert_eq!(set_text(&set(two)), "(0, 1/3) U {1/3}");
/// assert_eq!(set_text(&set(vec![])), "empty");
/// ```
pub fn set_text(s: &DiscountSet) -> String {
    if s.pieces.is_empty() {
        return "empty".into();
    }
    s.pieces
        .iter()
        .map(|p| {
            if p.lo == p.hi {
                format!("{{{}}}", point_text(&p.lo))
            } else {
                format!(
                    "{}{}, {}{}",
                    if p.lo_closed { "[" } else { "(" },
                    point_text(&p.lo),
                    point_text(&p.hi),
                    if p.hi_closed { "]" } else { ")" }
                )
            }
        })
        .collect::<Vec<_>>()
        .join(" U ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::poly::{isolate_roots, Poly};
    use num_traits::Zero;

    /// A breakpoint that is rational is printed as the fraction; an irrational one as its
    /// decimal expansion and the polynomial and bracket that define it. `3α − 2` has the root
    /// 2/3; `2α² − 1` the root 1/√2 = 0.70710678118654752440084436210…
    #[test]
    fn rational_breakpoints_print_as_fractions() {
        let poly = |c: &[i64]| {
            Poly::new(
                c.iter()
                    .map(|&x| Rational::from_integer(x.into()))
                    .collect(),
            )
        };
        let (zero, one) = (Rational::zero(), Rational::one());
        let root = |c: &[i64]| {
            let roots = isolate_roots(&poly(c), &zero, &one);
            assert_eq!(roots.len(), 1, "{c:?}");
            Point::Root(roots[0].clone())
        };
        assert_eq!(point_text(&root(&[-2, 3])), "2/3");
        let text = point_text(&root(&[-1, 0, 2]));
        assert!(
            text.starts_with("0.70710678118654752440084436210"),
            "{text}"
        );
        assert!(text.contains(" (the root of "), "{text}");
        assert_eq!(
            (point_text(&Point::Zero), point_text(&Point::One)),
            ("0".into(), "1".into())
        );
    }

    /// The pieces of a membership that is not closed (`objectives::failure_set` gives such: a
    /// point may belong while neither neighbour does, or the reverse), by hand. Points 1/4, 1/2,
    /// 3/4; atoms gap, 1/4, gap, 1/2, gap, 3/4, gap. A run that starts at a gap after a point
    /// is open at that point; one that ends at a gap before a point is open at that point, and
    /// one that ends at the last gap at 1.
    #[test]
    fn pieces_start_and_end_at_gaps_between_points() {
        let q = |n: i64, d: i64| {
            Point::Root(Algebraic::from_rational(Rational::new(n.into(), d.into())))
        };
        let points = [q(1, 4), q(1, 2), q(3, 4)];
        let piece = |lo: &Point, lo_closed, hi: &Point, hi_closed| Piece {
            lo: lo.clone(),
            lo_closed,
            hi: hi.clone(),
            hi_closed,
        };
        // The gap (1/4, 1/2) alone.
        let gap = [false, false, true, false, false, false, false];
        assert_eq!(
            pieces_of_members(&points, &gap),
            [piece(&points[0], false, &points[1], false)]
        );
        // The point 1/4 alone, then (1/2, 3/4), 3/4 and (3/4, 1).
        let two = [false, true, false, false, true, true, true];
        assert_eq!(
            pieces_of_members(&points, &two),
            [
                piece(&points[0], true, &points[0], true),
                piece(&points[1], false, &Point::One, false)
            ]
        );
    }
}

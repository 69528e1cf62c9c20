//! The polynomials and decimals `discount` prints for its breakpoints: the polynomial is the
//! factor vanishing at the point (square-free part, rational roots removed, split down to the
//! irreducible factor), labelled minimal only when proved irreducible; decimals are correctly
//! rounded, not truncated.
//!
//! Cross-check with a computer-algebra system (sympy 1.14, `factor_list` over `Q`): on the 25
//! breakpoints of `truecost discount --env frozenlake:map=8x8 --format json`, every printed
//! polynomial is irreducible (one factor, multiplicity 1), equal up to a constant to the
//! factor with a sign change over the bracket of the polynomial printed before the reduction
//! (degrees 18 to 49; before, 36 to 49, with rational factors, a repeated one, and two
//! products of irreducible factors of degrees 18·18 and 18·20), and every 30-digit decimal is
//! sympy's root rounded to nearest. The command prints each degree with sympy's factors (one
//! `(degree, 1)` each):
//!
//! ```text
//! truecost discount --env frozenlake:map=8x8 --format json | python3 -c "import json,sys
//! from sympy import symbols, Poly, factor_list
//! from sympy.parsing.sympy_parser import parse_expr, standard_transformations as S, implicit_multiplication_application as I
//! x = symbols('x')
//! for b in json.load(sys.stdin)['breakpoints']:
//!     p = Poly(parse_expr(b['polynomial'].replace('^', '**'), transformations=S + (I,)), x)
//!     print(b['polynomial_degree'], [(f.degree(), e) for f, e in factor_list(p)[1]])"
//! ```
//!
//! Expected values below are derived by hand or with sympy/mpmath, not from this crate.

mod common;

use num_bigint::BigInt;
use truecost::algebra::poly::roots::{
    irreducible_factor_at, reduce_polynomial, roots_in_unit_interval, Reduction, Root,
};
use truecost::algebra::poly::{decimal, decimal_rounded, isolate_roots, Poly};
use truecost::objectives::report::point_text;
use truecost::value::Rational;

fn q(s: &str) -> Rational {
    s.parse().unwrap()
}

fn ints(c: &[i64]) -> Vec<BigInt> {
    c.iter().map(|&x| BigInt::from(x)).collect()
}

fn poly(c: &[i64]) -> Poly {
    Poly::from_i64(c)
}

/// `(2x − 3)(x^2 + x − 1)^2 (x^2 − 3)`: one root in (0, 1), the golden section
/// `(√5 − 1)/2 = 0.618033988749894848204586834365638…`.
fn golden_with_company() -> Poly {
    let g = poly(&[-1, 1, 1]);
    poly(&[-3, 2]).mul(&g).mul(&g).mul(&poly(&[-3, 0, 1]))
}

#[test]
fn a_rational_factor_and_a_repeated_factor_reduce_to_the_minimal_polynomial() {
    let mut roots = roots_in_unit_interval(&golden_with_company());
    assert_eq!(roots.len(), 1);
    let mut r = roots.remove(0);
    assert_eq!(r.reduction, Reduction::AsMet);
    r.reduce();
    // x^2 + x − 1: no rational root (±1 are not roots), so irreducible over Q.
    assert_eq!(r.polynomial(), poly(&[-1, 1, 1]));
    assert_eq!(r.reduction, Reduction::Minimal);
    // The bracket still isolates the root for the reduced polynomial: a sign change, and it
    // contains 0.6180339887 < (√5 − 1)/2 < 0.6180339888.
    let m = poly(&[-1, 1, 1]);
    assert!(m.sign_at(&r.lo) != m.sign_at(&r.hi));
    assert_eq!(
        r.cmp_rational(&q("6180339887/10000000000")),
        std::cmp::Ordering::Greater
    );
    assert_eq!(
        r.cmp_rational(&q("6180339888/10000000000")),
        std::cmp::Ordering::Less
    );
    // Refinement goes on working with the new polynomial.
    r.refine_to(&q("1/1000000000000"));
    assert!(q("618033988749/1000000000000") <= r.hi && r.lo <= q("618033988750/1000000000000"));
}

#[test]
fn square_free_part_and_rational_roots_are_removed_exactly() {
    // (2x − 3)(x + 5)^2 (x^2 − 2)^3, expanded by hand from its factors.
    let f = poly(&[-3, 2])
        .mul(&poly(&[5, 1]))
        .mul(&poly(&[5, 1]))
        .mul(&poly(&[-2, 0, 1]))
        .mul(&poly(&[-2, 0, 1]))
        .mul(&poly(&[-2, 0, 1]));
    let f: Vec<BigInt> = f.coefficients().iter().map(|c| c.to_integer()).collect();
    let (g, rationals, how) = reduce_polynomial(&f);
    assert_eq!(g, ints(&[-2, 0, 1]));
    assert_eq!(rationals, vec![q("-5"), q("3/2")]);
    assert_eq!(how, Reduction::Minimal);
}

#[test]
fn two_irrational_factors_split_to_the_one_with_the_root() {
    // (x^2 + x − 1)(x^3 − 2): the degrees modulo primes allow 2 + 3, so the lifted
    // factorisation decides; 2^(1/3) ≈ 1.26 lies outside the bracket (3/5, 2/3).
    let f = ints(&[2, -2, -2, -1, 1, 1]);
    assert_eq!(
        irreducible_factor_at(&f, &q("3/5"), &q("2/3")),
        Some(ints(&[-1, 1, 1]))
    );
    // With the bracket around 2^(1/3) instead: x^3 − 2.
    assert_eq!(
        irreducible_factor_at(&f, &q("5/4"), &q("13/10")),
        Some(ints(&[-2, 0, 0, 1]))
    );
}

#[test]
fn the_same_point_met_through_two_polynomials_keeps_their_common_factor() {
    let a = roots_in_unit_interval(&poly(&[-1, 1, 1]).mul(&poly(&[-3, 0, 1])));
    let b = roots_in_unit_interval(&poly(&[-1, 1, 1]).mul(&poly(&[-2, 0, 0, 1])));
    let (mut a, b) = (a[0].clone(), b[0].clone());
    assert!(a.absorb_if_equal(&b));
    assert_eq!(a.polynomial(), poly(&[-1, 1, 1]));
    // A different point is not absorbed: 1/2 is not the golden section.
    assert!(!a.absorb_if_equal(&Root::rational(q("1/2"))));
}

#[test]
fn two_quadratic_factors_split_and_the_swinnerton_dyer_quartic_is_minimal() {
    // (x^2 + x − 1)(x^2 − 3): equal degrees, split modulo a prime by equal-degree
    // factorisation before lifting.
    let f = ints(&[3, -3, -4, 1, 1]);
    assert_eq!(
        irreducible_factor_at(&f, &q("3/5"), &q("2/3")),
        Some(ints(&[-1, 1, 1]))
    );
    // x^4 − 10x^2 + 1 (root √3 − √2 ≈ 0.3178) is irreducible over Q but splits modulo every
    // prime into factors of degree at most 2: the degree test cannot prove it; the lifted
    // factors show that no product of them is a factor over Z.
    let mut r = roots_in_unit_interval(&poly(&[1, 0, -10, 0, 1])).remove(0);
    r.reduce();
    assert_eq!(r.reduction, Reduction::Minimal);
    assert_eq!(r.polynomial(), poly(&[1, 0, -10, 0, 1]));
    let t = point_text(&r);
    assert!(t.minimal);
    assert_eq!(t.degree, 4);
    // √3 − √2 = 0.317837245195782244725757617296174… (mpmath).
    assert_eq!(t.decimal, "0.317837245195782244725757617296");
}

#[test]
fn too_many_factors_modulo_every_prime_leave_the_label_not_proved() {
    // The product of k x^2 − 1 over 15 square-free k > 1: no rational roots, square-free,
    // reducible, and modulo every prime at least 15 factors (each quadratic gives 1 or 2), more
    // than are recombined: printed as square-free without rational roots, not as minimal.
    let mut f = poly(&[1]);
    for k in [2, 3, 5, 6, 7, 10, 11, 13, 14, 15, 17, 19, 21, 22, 23] {
        f = f.mul(&poly(&[-1, 0, k]));
    }
    let roots = roots_in_unit_interval(&f);
    assert_eq!(roots.len(), 15);
    // The smallest is 1/√23 = 0.2085144140570746…
    let mut r = roots[0].clone();
    r.reduce();
    assert_eq!(r.reduction, Reduction::SquareFree);
    let t = point_text(&r);
    assert!(!t.minimal);
    assert_eq!(t.degree, 30);
    assert_eq!(t.short, "0.208514414057");
}

#[test]
fn decimals_are_rounded_where_truncation_differs() {
    // 2/3: truncation 0.666666666666, rounding 0.666666666667.
    assert_eq!(decimal(&q("2/3"), 12), "0.666666666666");
    assert_eq!(decimal_rounded(&q("2/3"), 12), "0.666666666667");
    // A tie is rounded away from zero.
    assert_eq!(decimal_rounded(&q("1/8"), 2), "0.13");
    // (√5 − 1)/2 = 0.618033988749|8948…: 12 digits round up, the 13th is 8.
    let r = roots_in_unit_interval(&golden_with_company()).remove(0);
    assert_eq!(r.decimal(12), "0.618033988750");
    assert_eq!(r.decimal(20), "0.61803398874989484820");
    // 1/√2 = 0.707106781186547524400844362104|849…: the 30th digit rounds up to 5.
    let h = roots_in_unit_interval(&poly(&[-1, 0, 2])).remove(0);
    assert_eq!(h.decimal(30), "0.707106781186547524400844362105");
    // √2 = 1.41421356237|31…: rounded 1.4142135624, truncated 1.4142135623.
    let s = isolate_roots(&poly(&[-2, 0, 1]), &q("0"), &q("2")).remove(0);
    assert_eq!(s.decimal_rounded(10), "1.4142135624");
    assert_eq!(s.decimal(10), "1.4142135623");
    // A rational root exactly on a rounding tie: 1/8 from 8x − 1 (times x^2 + 1).
    let e = roots_in_unit_interval(&poly(&[-1, 8]).mul(&poly(&[1, 0, 1]))).remove(0);
    assert_eq!(e.decimal(2), "0.13");
}

#[test]
fn the_breakpoint_text_names_the_minimal_polynomial() {
    let mut r = roots_in_unit_interval(&golden_with_company()).remove(0);
    r.reduce();
    let t = point_text(&r);
    assert_eq!(t.polynomial.as_deref(), Some("x^2 + x - 1"));
    assert!(t.minimal);
    assert_eq!(t.degree, 2);
    // 0.618033988749894848204586834365|638… rounds to …366.
    assert_eq!(t.decimal, "0.618033988749894848204586834366");
    assert_eq!(t.short, "0.618033988750");
}

#[test]
fn frozenlake_breakpoints_print_their_minimal_polynomials() {
    // sympy factors the polynomial the 4x4 map's first breakpoint was printed with before the
    // reduction, 8x^6 − 84x^5 + 108x^4 + 702x^3 − 2187x^2 + 2187x − 729, as
    // (2x − 3)(x^2 − 9x + 9)(4x^3 − 36x + 27); the root 0.8087833… is the cubic's. The second
    // breakpoint's polynomial is irreducible of degree 8.
    let v = common::cli::json(&["discount", "--env", "frozenlake", "--format", "json"]);
    let bps = v["breakpoints"].as_array().unwrap();
    assert_eq!(bps.len(), 2);
    assert_eq!(bps[0]["polynomial"], "4x^3 - 36x + 27");
    assert_eq!(bps[0]["polynomial_minimal"], true);
    assert_eq!(bps[0]["polynomial_degree"], 3);
    assert_eq!(bps[1]["polynomial_degree"], 8);
    assert_eq!(bps[1]["polynomial_minimal"], true);
    // mpmath: the cubic's root in (0, 1) is 0.80878330921633367478881385404|79…, rounded …048.
    assert_eq!(bps[0]["alpha_decimal"], "0.808783309216333674788813854048");
    let text = common::cli::stdout(&["discount", "--env", "frozenlake"]);
    assert!(
        text.contains("(the root of the minimal polynomial 4x^3 - 36x + 27 in ("),
        "{text}"
    );
    assert!(text.contains("correctly rounded"), "{text}");
}

//! Unit tests of `truecost::value` (exact rationals, extended values, the value types) and of
//! the representation `ExactGraph::new` chooses.

mod common;

use std::cmp::Ordering;

use common::*;
use num_bigint::BigInt;
use num_traits::One;
use truecost::model::{ExactGraph, Problem, RenderValue};
use truecost::solvers::dijkstra;
use truecost::solvers::value_iteration::{value_iteration, Schedule};
use truecost::value::{
    in_unit_interval_open_closed, parse_rational, to_common_scale, CostValue, ExactValue, Extended,
    ParseRationalReason, Units, MAX_EXPONENT, MAX_NUMBER_TEXT,
};

fn p(text: &str) -> Q {
    parse_rational(text).unwrap_or_else(|e| panic!("{text:?} should parse: {e}"))
}

fn big(text: &str) -> BigInt {
    text.parse().unwrap()
}

#[test]
fn parse_integers() {
    assert_eq!(p("42"), int(42));
    assert_eq!(p("0"), int(0));
    assert_eq!(p("-7"), int(-7));
    assert_eq!(p("+3"), int(3));
    assert_eq!(p("007"), int(7));
    assert_eq!(p(" 12 "), int(12));
    // Beyond u64/i128: exact big integers.
    assert_eq!(
        p("123456789012345678901234567890"),
        Q::from_integer(big("123456789012345678901234567890"))
    );
}

#[test]
fn parse_decimals_exactly() {
    assert_eq!(p("0.999"), frac(999, 1000));
    assert_eq!(p("1e-3"), frac(1, 1000));
    assert_eq!(p("-2.5"), frac(-5, 2));
    assert_eq!(p("2E3"), int(2000));
    assert_eq!(p("1e+3"), int(1000));
    assert_eq!(p("1.5e2"), int(150));
    assert_eq!(p("0.1"), frac(1, 10)); // not the f64 0.1000000000000000055...
    assert_eq!(p("12.50"), frac(25, 2));
    assert_eq!(p("-0"), int(0));
    // 10^-30, far below f64's decimal precision, kept exact.
    assert_eq!(
        p("0.000000000000000000000000000001"),
        Q::new(BigInt::one(), BigInt::from(10).pow(30))
    );
}

#[test]
fn parse_fractions() {
    assert_eq!(p("800/19"), frac(800, 19));
    assert_eq!(p("50400/19"), frac(50400, 19));
    assert_eq!(p("6/4"), frac(3, 2));
    assert_eq!(p("-1/2"), frac(-1, 2));
    assert_eq!(p("1.5/3"), frac(1, 2));
    assert_eq!(p("0/5"), int(0));
    assert_eq!(p("1/1e3"), frac(1, 1000));
}

#[test]
fn parse_rejections() {
    for bad in [
        "", "abc", "1/0", "0.1.2", "1e99999", "--1", ".", "1/", "/2", " ", "1/2/3", "1e", "e5",
        "+-1", "1,5", "0x10", "1_000", "inf", "NaN", "1 2", "1/0.0", "١",
    ] {
        let err = parse_rational(bad);
        assert!(err.is_err(), "{bad:?} should be rejected, got {err:?}");
        let e = err.unwrap_err();
        assert_eq!(e.text, bad, "the error keeps the offending text");
        let msg = e.to_string();
        assert!(msg.contains(&format!("'{bad}'")), "{msg}");
        assert!(!msg.contains('\n'), "{msg}");
    }
}

/// An exponent of `i64::MIN` is parsed as an `i64` and then `abs()`-ed, which overflows.
/// Expected: `Err` like any other out-of-range exponent. (Fails with a panic if the overflow
/// is not handled.)
#[test]
fn parse_rejects_exponent_i64_min_without_panicking() {
    let text = "1e-9223372036854775808";
    let result = std::panic::catch_unwind(|| parse_rational(text));
    assert!(
        matches!(result, Ok(Err(_))),
        "parse_rational({text:?}) must return Err, got {}",
        match &result {
            Ok(r) => format!("{r:?}"),
            Err(_) => "a panic".to_string(),
        }
    );
    // Its neighbours are rejected too.
    assert!(parse_rational("1e-9223372036854775807").is_err());
    assert!(parse_rational("1e9223372036854775807").is_err());
    assert!(parse_rational("1e9223372036854775808").is_err());
}

#[test]
fn extended_display_and_parse() {
    assert_eq!(Extended::from_integer(63).to_string(), "63");
    assert_eq!(Extended::Finite(frac(50400, 19)).to_string(), "50400/19");
    assert_eq!(Extended::Finite(frac(100800, 38)).to_string(), "50400/19");
    assert_eq!(Extended::Infinite.to_string(), "inf");
    assert_eq!(Extended::from_integer(0).to_string(), "0");
    assert_eq!(Extended::Finite(frac(-1, 2)).to_string(), "-1/2");
    assert_eq!(
        "50400/19".parse::<Extended>(),
        Ok(Extended::Finite(frac(50400, 19)))
    );
    assert_eq!("inf".parse::<Extended>(), Ok(Extended::Infinite));
    assert_eq!("+inf".parse::<Extended>(), Ok(Extended::Infinite));
    assert_eq!("∞".parse::<Extended>(), Ok(Extended::Infinite));
    assert_eq!(" 63 ".parse::<Extended>(), Ok(Extended::from_integer(63)));
    assert!("infinity?".parse::<Extended>().is_err());
    assert!("-inf".parse::<Extended>().is_err());
    assert_eq!(Extended::Finite(frac(1, 4)).finite(), Some(&frac(1, 4)));
    assert_eq!(Extended::Infinite.finite(), None);
    assert_eq!(Extended::Finite(frac(1, 4)).to_f64(), 0.25);
    assert_eq!(Extended::Infinite.to_f64(), f64::INFINITY);
}

#[test]
fn extended_order_inf_greatest() {
    let inf = Extended::Infinite;
    let huge = Extended::Finite(pow2(1000));
    let a = Extended::Finite(frac(1, 3));
    let b = Extended::Finite(frac(1, 2));
    assert!(inf > huge);
    assert!(huge > b);
    assert!(b > a);
    assert!(Extended::from_integer(0) < a);
    assert_eq!(inf.cmp(&Extended::Infinite), Ordering::Equal);
    assert_eq!(a.compare(&b), Ordering::Less);
    assert_eq!(inf.compare(&huge), Ordering::Greater);
    let mut v = vec![inf.clone(), b.clone(), huge.clone(), a.clone()];
    v.sort();
    assert_eq!(v, vec![a, b, huge, inf]);
}

#[test]
fn extended_arithmetic() {
    let a = Extended::Finite(frac(1, 3));
    let b = Extended::Finite(frac(1, 6));
    assert_eq!(a.plus(&b), Extended::Finite(frac(1, 2)));
    assert_eq!(a.plus(&Extended::Infinite), Extended::Infinite);
    assert_eq!(Extended::Infinite.plus(&a), Extended::Infinite);
    assert_eq!(<Extended as CostValue>::zero(), Extended::from_integer(0));
    assert!(!<Extended as CostValue>::infinity().is_finite());
    assert!(a.is_finite());
    assert_eq!(a.to_extended(&int(3)), Some(Extended::from_integer(1)));
    assert_eq!(a.render(&int(1)), "1/3");
    const { assert!(<Extended as CostValue>::EXACT) };
}

#[test]
fn units_plus_absorbs_infinity() {
    let inf = Units::infinity();
    assert_eq!(inf, Units(u64::MAX));
    assert!(!inf.is_finite());
    assert!(Units(u64::MAX - 1).is_finite());
    assert_eq!(Units(2).plus(&Units(3)), Units(5));
    assert_eq!(Units(0).plus(&Units::zero()), Units(0));
    assert_eq!(Units(5).plus(&inf), inf);
    assert_eq!(inf.plus(&Units(5)), inf);
    assert_eq!(inf.plus(&inf), inf);
    assert_eq!(Units(u64::MAX - 1).plus(&inf), inf);
    assert_eq!(Units(u64::MAX - 3).plus(&Units(2)), Units(u64::MAX - 1));
    assert_eq!(Units(1).compare(&Units(2)), Ordering::Less);
    assert_eq!(inf.compare(&Units(u64::MAX - 1)), Ordering::Greater);
    const { assert!(<Units as CostValue>::EXACT) };
}

#[test]
#[should_panic(expected = "exact cost overflow")]
fn units_plus_overflow_into_infinity_panics() {
    // A finite sum equal to the infinity sentinel must not silently become +∞.
    let _ = Units(u64::MAX - 1).plus(&Units(1));
}

#[test]
#[should_panic(expected = "exact cost overflow")]
fn units_plus_wrapping_overflow_panics() {
    let _ = Units(u64::MAX - 1).plus(&Units(u64::MAX - 1));
}

#[test]
fn units_to_extended_and_render() {
    let unit = frac(1, 19);
    assert_eq!(
        Units(50400).to_extended(&unit),
        Some(Extended::Finite(frac(50400, 19)))
    );
    assert_eq!(Units(50400).render(&unit), "50400/19");
    assert_eq!(Units(63 * 19).render(&unit), "63");
    assert_eq!(
        Units::infinity().to_extended(&unit),
        Some(Extended::Infinite)
    );
    assert_eq!(Units::infinity().render(&unit), "inf");
}

#[test]
fn f64_value_type_is_inexact() {
    const { assert!(!<f64 as CostValue>::EXACT) };
    assert_eq!(1.5f64.to_extended(&int(1)), None);
    assert_eq!(ExactValue::render(&1.5f64, &int(1)), "1.5");
    assert_eq!(ExactValue::render(&42.0f64, &int(1)), "42.0");
    assert_eq!(ExactValue::render(&f64::INFINITY, &int(1)), "inf");
    assert_eq!(CostValue::plus(&1.0f64, &f64::INFINITY), f64::INFINITY);
    assert!(!CostValue::is_finite(&<f64 as CostValue>::infinity()));
}

#[test]
fn unit_interval() {
    assert!(!in_unit_interval_open_closed(&int(0)));
    assert!(in_unit_interval_open_closed(&int(1)));
    assert!(in_unit_interval_open_closed(&frac(1, 2)));
    assert!(in_unit_interval_open_closed(&frac(1, 1_000_000)));
    assert!(!in_unit_interval_open_closed(&frac(3, 2)));
    assert!(!in_unit_interval_open_closed(&frac(1_000_001, 1_000_000)));
    assert!(!in_unit_interval_open_closed(&int(-1)));
}

/// 0 -(c)-> 1 (goal), plus a self-loop of the same cost at 0.
fn chain(c: Q) -> Problem {
    Problem::new(vec![vec![mv(1, c.clone()), mv(0, c)], vec![]], 0, vec![1]).unwrap()
}

/// G*(0) by all three planners, as exact values.
fn solve0(p: &Problem) -> (String, Vec<Ext>) {
    let eg = ExactGraph::new(p);
    let values = with_exact_graph!(&eg, g => vec![
        exact(g, &dijkstra::to_goals(g).cost_to_go[0]),
        exact(g, &value_iteration(g, Schedule::Synchronous, None).cost_to_go[0]),
        exact(g, &value_iteration(g, Schedule::Asynchronous, None).cost_to_go[0]),
    ]);
    (eg.representation().to_string(), values)
}

#[test]
fn representation_units_for_small_rationals() {
    let c = frac(800, 19);
    let eg = ExactGraph::new(&chain(c.clone()));
    assert_eq!(eg.representation(), "units");
    match &eg {
        ExactGraph::Units(g) => {
            assert_eq!(g.unit(), &frac(1, 19));
            let costs: Vec<Units> = g.edges(0).map(|(_, c)| *c).collect();
            assert_eq!(costs, vec![Units(800), Units(800)]);
            let s = dijkstra::to_goals(g);
            assert_eq!(g.render(&s.cost_to_go[0]), "800/19");
        }
        ExactGraph::Big(_) => panic!("800/19 must use Units"),
    }
    assert_eq!(solve0(&chain(c.clone())).1, vec![Some(c); 3]);

    // Mixed denominators: the unit is 1/lcm = 1/1000 for 0.999 and 1/2.
    let p = Problem::new(
        vec![vec![mv(1, p("0.999")), mv(1, frac(1, 2))], vec![]],
        0,
        vec![1],
    )
    .unwrap();
    match ExactGraph::new(&p) {
        ExactGraph::Units(g) => {
            assert_eq!(g.unit(), &frac(1, 1000));
            let costs: Vec<Units> = g.edges(0).map(|(_, c)| *c).collect();
            assert_eq!(costs, vec![Units(999), Units(500)]);
        }
        ExactGraph::Big(_) => panic!("must use Units"),
    }

    // Zero costs only, and no moves at all: Units with unit 1.
    for p in [
        chain(int(0)),
        Problem::new(vec![vec![]], 0, vec![0]).unwrap(),
    ] {
        match ExactGraph::new(&p) {
            ExactGraph::Units(g) => assert_eq!(g.unit(), &int(1)),
            ExactGraph::Big(_) => panic!("must use Units"),
        }
    }
}

#[test]
fn representation_big_for_huge_cost() {
    // 2 states, cost 2^63: (2 + 1) × 2^63 > u64::MAX.
    let (repr, values) = solve0(&chain(pow2(63)));
    assert_eq!(repr, "big-rational");
    assert_eq!(values, vec![Some(pow2(63)); 3]);
    // A cost that does not even fit u64.
    let (repr, values) = solve0(&chain(pow2(64) + frac(1, 3)));
    assert_eq!(repr, "big-rational");
    assert_eq!(values, vec![Some(pow2(64) + frac(1, 3)); 3]);
}

#[test]
fn representation_boundary() {
    // Units iff (states + 1) × max scaled cost < u64::MAX; u64::MAX = 3 × 6148914691236517205.
    let m = 6_148_914_691_236_517_204u64;
    assert_eq!(m, boundary_max(2));
    let (repr, values) = solve0(&chain(from_u64(m)));
    assert_eq!(repr, "units");
    assert_eq!(values, vec![Some(from_u64(m)); 3]);
    let (repr, values) = solve0(&chain(from_u64(m + 1)));
    assert_eq!(repr, "big-rational");
    assert_eq!(values, vec![Some(from_u64(m + 1)); 3]);
    // With a unit of 1/2, m/2 + 1/2 scales to m + 1 (Big) and m/2 - 1/2 to m - 1 (Units).
    let (repr, _) = solve0(&chain(from_u64(m / 2) + frac(1, 2)));
    assert_eq!(repr, "big-rational");
    let (repr, values) = solve0(&chain(from_u64(m / 2 - 1) + frac(1, 2)));
    assert_eq!(repr, "units");
    assert_eq!(values, vec![Some(from_u64(m / 2 - 1) + frac(1, 2)); 3]);
}

#[test]
fn representation_with_coprime_denominators() {
    // Denominators 2^40 and 3^26 are coprime; their lcm D ≈ 2.8e24 exceeds u64, but the scaled
    // costs D/2^40 = 3^26 and D/3^26 = 2^40 fit: Units with unit 1/D.
    let a = Q::new(BigInt::one(), BigInt::one() << 40);
    let b = Q::new(BigInt::one(), BigInt::from(3).pow(26));
    let d: BigInt = (BigInt::one() << 40) * BigInt::from(3).pow(26);
    assert!(d > BigInt::from(u64::MAX));
    let line = |extra: Option<Q>| {
        let mut first = vec![mv(1, a.clone())];
        if let Some(c) = extra {
            first.push(mv(2, c));
        }
        Problem::new(vec![first, vec![mv(2, b.clone())], vec![]], 0, vec![2]).unwrap()
    };
    let p1 = line(None);
    match ExactGraph::new(&p1) {
        ExactGraph::Units(g) => assert_eq!(g.unit(), &Q::new(BigInt::one(), d.clone())),
        ExactGraph::Big(_) => panic!("scaled costs fit: Units expected"),
    }
    assert_eq!(solve0(&p1).1, vec![Some(&a + &b); 3]);
    // Adding a cost of 1 (scaled: D, which does not fit u64) forces Big; G* is unchanged.
    let p2 = line(Some(int(1)));
    let (repr, values) = solve0(&p2);
    assert_eq!(repr, "big-rational");
    assert_eq!(values, vec![Some(&a + &b); 3]);
    // Three pairwise-coprime ~2^22 denominators: lcm ≈ 2^66 overflows u64, and with an
    // integer cost the scaled cost overflows too.
    let dens = [4_194_301i64, 4_194_303, 4_194_304]; // odd, odd (coprime to each other), 2^22
    let mut moves: Vec<_> = dens.iter().map(|&q| mv(1, frac(1, q))).collect();
    moves.push(mv(1, int(1)));
    let p3 = Problem::new(vec![moves, vec![]], 0, vec![1]).unwrap();
    let (repr, values) = solve0(&p3);
    assert_eq!(repr, "big-rational");
    assert_eq!(values, vec![Some(frac(1, 4_194_304)); 3]);
}

/// The length limit on a number's text is `MAX_NUMBER_TEXT` bytes after trimming: a text of
/// exactly that length parses, one byte more is refused with its length named.
#[test]
fn number_texts_are_refused_exactly_above_the_length_limit() {
    let at = "9".repeat(MAX_NUMBER_TEXT);
    assert_eq!(p(&at), p(&at[1..]) * BigInt::from(10) + p("9"));
    assert_eq!(p(&format!("  {at}\t")), p(&at));
    let above = format!("{at}9");
    assert_eq!(
        parse_rational(&above).unwrap_err().reason,
        ParseRationalReason::TooLong(MAX_NUMBER_TEXT + 1)
    );
}

/// Exponents are limited to `|e| ≤ MAX_EXPONENT` (leading zeros aside): the limit itself parses,
/// one more is refused, and so is an exponent too long for any integer type.
#[test]
fn exponents_are_refused_exactly_above_the_limit() {
    let limit = MAX_EXPONENT;
    let ten_to = |e: u64| Q::from_integer((0..e).fold(BigInt::one(), |a, _| a * 10));
    assert_eq!(p(&format!("1e{limit}")), ten_to(limit));
    assert_eq!(p(&format!("1e-{limit}")), ten_to(limit).recip());
    assert_eq!(
        p(&format!("2E+000{limit}")),
        ten_to(limit) * BigInt::from(2)
    );
    for text in [
        format!("1e{}", limit + 1),
        format!("1e-{}", limit + 1),
        format!("1e{}", "9".repeat(25)),
        format!("1e0000{}", "9".repeat(6)),
    ] {
        assert_eq!(
            parse_rational(&text).unwrap_err().reason,
            ParseRationalReason::Exponent,
            "{text}"
        );
    }
}

/// `to_common_scale` against a brute force: the scale is the least `n ≥ 1` that makes every
/// value an integer, and each integer is its value times the scale.
#[test]
fn the_common_scale_is_the_least_common_denominator() {
    let sets: [&[&str]; 5] = [
        &[],
        &["3"],
        &["1/4", "-5/6", "2"],
        &["7/9", "1/12", "-3/8", "0", "5/18"],
        &["-1/7", "1/7", "22/7"],
    ];
    for set in sets {
        let values: Vec<Q> = set.iter().map(|t| p(t)).collect();
        let (d, ints) = to_common_scale(&values);
        let least = (1..=1000)
            .map(BigInt::from)
            .find(|n| values.iter().all(|v| (v * n).is_integer()))
            .unwrap();
        assert_eq!(d, least, "{set:?}");
        assert_eq!(ints.len(), values.len());
        for (v, i) in values.iter().zip(&ints) {
            assert_eq!(Q::from_integer(i.clone()), v * &d, "{set:?}");
        }
    }
}

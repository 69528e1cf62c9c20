//! The bridge between the Coq theorem `c3_alpha_star` (α* lies strictly between the
//! rationals `alpha_lo` and `alpha_hi` of the embedded Coq sources) and the bracket
//! `truecost verify` prints (`claims::alpha::alpha_star()`): the two brackets must be the same
//! rationals. The test also checks, with its own arithmetic, that the quartic
//! `5a^4 - a^3 - a^2 - a - 1` changes sign between the two ends, and that a planted wrong end
//! (on either side) is caught.

use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

use truecost::claims::alpha::alpha_star;
use truecost::claims::coq::SOURCES;
use truecost::value::Rational;

/// The rational of `Definition <name> : Q := <numerator> # <denominator>.` in `text`.
fn coq_constant(text: &str, name: &str) -> Result<Rational, String> {
    let head = format!("Definition {name} : Q :=");
    let start = text
        .find(&head)
        .ok_or_else(|| format!("no `{head}` in the Coq sources"))?;
    let rest = &text[start + head.len()..];
    let body = &rest[..rest
        .find('.')
        .ok_or_else(|| format!("`{head}` has no end"))?];
    let (n, d) = body
        .split_once('#')
        .ok_or_else(|| format!("`{head}{body}` is not `n # d`"))?;
    let n: BigInt = n.trim().parse().map_err(|e| format!("{name}: {e}"))?;
    let d: BigInt = d.trim().parse().map_err(|e| format!("{name}: {e}"))?;
    if !d.is_positive() {
        return Err(format!("{name}: denominator {d}"));
    }
    Ok(Rational::new(n, d))
}

/// The Coq bracket `(alpha_lo, alpha_hi)` from whichever embedded source defines it.
fn coq_bracket(sources: &[(&str, &str)]) -> Result<(Rational, Rational), String> {
    let (_, text) = sources
        .iter()
        .find(|(_, t)| t.contains("Definition alpha_lo : Q"))
        .ok_or("no embedded Coq source defines alpha_lo")?;
    Ok((
        coq_constant(text, "alpha_lo")?,
        coq_constant(text, "alpha_hi")?,
    ))
}

/// `5a^4 - a^3 - a^2 - a - 1`, the printed inequality's quartic, evaluated directly.
fn quartic(a: &Rational) -> Rational {
    let int = |k: i64| Rational::from_integer(BigInt::from(k));
    let a2 = a * a;
    let a3 = &a2 * a;
    let a4 = &a3 * a;
    int(5) * a4 - a3 - a2 - a - int(1)
}

/// `None` when the Coq bracket and Rust's are the same rationals; otherwise what differs.
fn bracket_mismatch(coq: &(Rational, Rational), rust: &(Rational, Rational)) -> Option<String> {
    let mut why = Vec::new();
    if coq.0 != rust.0 {
        why.push(format!("lower end: Coq {} vs Rust {}", coq.0, rust.0));
    }
    if coq.1 != rust.1 {
        why.push(format!("upper end: Coq {} vs Rust {}", coq.1, rust.1));
    }
    (!why.is_empty()).then(|| why.join("; "))
}

fn rust_bracket() -> (Rational, Rational) {
    let a = alpha_star().expect("alpha* is unique");
    (a.lo, a.hi)
}

#[test]
fn the_coq_bracket_is_the_bracket_verify_prints() {
    let coq = coq_bracket(SOURCES).unwrap();
    let rust = rust_bracket();
    assert_eq!(bracket_mismatch(&coq, &rust), None);
    // Independently of both: the quartic is negative at the lower end, positive at the upper
    // one, both in (0, 1), and the width is 2^-100.
    assert!(quartic(&coq.0).is_negative());
    assert!(quartic(&coq.1).is_positive());
    assert!(coq.0.is_positive() && coq.1 < Rational::one());
    let width = Rational::new(BigInt::one(), BigInt::one() << 100usize);
    assert_eq!(&coq.1 - &coq.0, width);
}

/// The comparison can fail: a Coq constant or a Rust end moved by one unit of 2^-101 is
/// reported, on the side where it was planted.
#[test]
fn planted_wrong_brackets_are_reported() {
    let coq = coq_bracket(SOURCES).unwrap();
    let rust = rust_bracket();
    let nudge = Rational::new(BigInt::one(), BigInt::one() << 101usize);
    let moved_lo = (&rust.0 + &nudge, rust.1.clone());
    let why = bracket_mismatch(&coq, &moved_lo).expect("a wrong lower end is caught");
    assert!(why.starts_with("lower end"), "{why}");
    let moved_hi = (rust.0.clone(), &rust.1 - &nudge);
    let why = bracket_mismatch(&coq, &moved_hi).expect("a wrong upper end is caught");
    assert!(why.starts_with("upper end"), "{why}");

    // A Coq source whose constant has one digit changed.
    let (name, text) = SOURCES
        .iter()
        .find(|(_, t)| t.contains("Definition alpha_lo : Q"))
        .unwrap();
    let head = "Definition alpha_hi : Q := ";
    let at = text.find(head).unwrap() + head.len();
    let digit = text.as_bytes()[at];
    let other = if digit == b'1' { '2' } else { '1' };
    let edited = format!("{}{other}{}", &text[..at], &text[at + 1..]);
    let planted = coq_bracket(&[(name, edited.as_str())]).unwrap();
    let why = bracket_mismatch(&planted, &rust).expect("a wrong Coq constant is caught");
    assert!(why.starts_with("upper end"), "{why}");
    assert!(coq_bracket(&[("A.v", "Definition x := 1.")]).is_err());
    assert!(coq_constant("Definition alpha_lo : Q := 1 # 0.", "alpha_lo").is_err());
    assert!(Rational::zero() < quartic(&Rational::one()));
}

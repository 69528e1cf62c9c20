//! SMT-LIB 2.6 terms as text: the obligations are written in the standard
//! language first, so that the very text Z3 solves is the text `verify --smt-out` writes and
//! any other solver (cvc5, Yices) can re-check. Only standard theory symbols are produced.

use num_bigint::BigInt;
use num_traits::Signed;

use crate::value::Rational;

/// A real literal (`3.0`, `(- 3.0)`, `(/ 1.0 3.0)`, `(- (/ 1.0 3.0))`).
///
/// ```
/// use truecost::claims::smt::term::real;
/// use truecost::value::Rational;
/// assert_eq!(real(&Rational::new(1.into(), 3.into())), "(/ 1.0 3.0)");
/// assert_eq!(real(&Rational::from_integer((-2).into())), "(- 2.0)");
/// ```
pub fn real(q: &Rational) -> String {
    let magnitude = if q.denom() == &BigInt::from(1) {
        format!("{}.0", q.numer().abs())
    } else {
        format!("(/ {}.0 {}.0)", q.numer().abs(), q.denom())
    };
    if q.is_negative() {
        format!("(- {magnitude})")
    } else {
        magnitude
    }
}

/// A real literal from an integer.
pub fn real_int(n: i64) -> String {
    real(&Rational::from_integer(n.into()))
}

/// An integer literal (`3`, `(- 3)`), for the integer sort.
pub fn int(n: i64) -> String {
    if n < 0 {
        format!("(- {})", n.unsigned_abs())
    } else {
        n.to_string()
    }
}

/// `(op a b …)`.
pub fn app(op: &str, args: &[String]) -> String {
    let mut s = String::with_capacity(8 + args.iter().map(|a| a.len() + 1).sum::<usize>());
    s.push('(');
    s.push_str(op);
    for a in args {
        s.push(' ');
        s.push_str(a);
    }
    s.push(')');
    s
}

/// `a + b + …` (`0.0` for no term).
pub fn sum(args: &[String]) -> String {
    match args.len() {
        0 => "0.0".into(),
        1 => args[0].clone(),
        _ => app("+", args),
    }
}

/// `a − b`.
pub fn sub(a: &str, b: &str) -> String {
    app("-", &[a.into(), b.into()])
}

/// `a · b`.
pub fn mul(a: &str, b: &str) -> String {
    app("*", &[a.into(), b.into()])
}

/// `a ≤ b`.
pub fn le(a: &str, b: &str) -> String {
    app("<=", &[a.into(), b.into()])
}

/// `a < b`.
pub fn lt(a: &str, b: &str) -> String {
    app("<", &[a.into(), b.into()])
}

/// `a ≥ b`.
pub fn ge(a: &str, b: &str) -> String {
    app(">=", &[a.into(), b.into()])
}

/// `a > b`.
pub fn gt(a: &str, b: &str) -> String {
    app(">", &[a.into(), b.into()])
}

/// `a = b`.
pub fn eq(a: &str, b: &str) -> String {
    app("=", &[a.into(), b.into()])
}

/// `a ≠ b`.
pub fn ne(a: &str, b: &str) -> String {
    not(&eq(a, b))
}

/// `¬a`.
pub fn not(a: &str) -> String {
    app("not", &[a.into()])
}

/// `a ⇒ b`.
pub fn implies(a: &str, b: &str) -> String {
    app("=>", &[a.into(), b.into()])
}

/// Conjunction (`true` for none).
pub fn and(args: &[String]) -> String {
    match args.len() {
        0 => "true".into(),
        1 => args[0].clone(),
        _ => app("and", args),
    }
}

/// Disjunction (`false` for none).
pub fn or(args: &[String]) -> String {
    match args.len() {
        0 => "false".into(),
        1 => args[0].clone(),
        _ => app("or", args),
    }
}

/// `if c then a else b`.
pub fn ite(c: &str, a: &str, b: &str) -> String {
    app("ite", &[c.into(), a.into(), b.into()])
}

/// The least of a non-empty list, as nested `ite`.
///
/// ```
/// use truecost::claims::smt::term::min;
/// assert_eq!(min(&["a".into(), "b".into()]), "(ite (<= a b) a b)");
/// ```
pub fn min(args: &[String]) -> String {
    assert!(!args.is_empty(), "min of nothing");
    let mut acc = args[0].clone();
    for a in &args[1..] {
        acc = ite(&le(&acc, a), &acc, a);
    }
    acc
}

/// The greatest of a non-empty list, as nested `ite`.
pub fn max(args: &[String]) -> String {
    assert!(!args.is_empty(), "max of nothing");
    let mut acc = args[0].clone();
    for a in &args[1..] {
        acc = ite(&ge(&acc, a), &acc, a);
    }
    acc
}

/// `v` is the least of `args`, stated without `ite`: `v ≤ a` for every `a`, `v = a` for one.
pub fn is_min(v: &str, args: &[String]) -> String {
    let mut parts: Vec<String> = args.iter().map(|a| le(v, a)).collect();
    parts.push(or(&args.iter().map(|a| eq(v, a)).collect::<Vec<_>>()));
    and(&parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An integer literal is a numeral, negated only when negative (SMT-LIB 2.6 has no
    /// negative numerals: `-3` is `(- 3)`). Zero is the numeral `0`, not the term `(- 0)`
    /// (which denotes the same integer, but is not what the contract promises and would be
    /// text the other solvers re-check for nothing).
    #[test]
    fn integer_literals() {
        assert_eq!(int(0), "0");
        assert_eq!(int(3), "3");
        assert_eq!(int(-1), "(- 1)");
        assert_eq!(int(i64::MIN), "(- 9223372036854775808)");
    }
}

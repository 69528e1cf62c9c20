//! Hostile numbers: refusals of huge exact numbers come before the work they would cost, each
//! one escaped line naming the quantity, its value and the bound; the exact reader stays exact.

mod common;

use std::time::{Duration, Instant};

use common::cli::{assert_contract, fails_one_line, write};
use common::Lcg;
use num_bigint::BigInt;
use num_rational::BigRational;
use truecost::value::parse_rational;

/// `10^k` as an integer, by repeated multiplication (independent of the reader).
fn ten_to(k: u64) -> BigInt {
    (0..k).fold(BigInt::from(1), |acc, _| acc * 10)
}

/// The reference value of `±digits·10^e`: the integer of the digits times or over a power of
/// ten, reduced by `BigRational::new`.
fn reference(negative: bool, digits: &str, e: i64) -> BigRational {
    let m: BigInt = digits.parse().unwrap();
    let m = if negative { -m } else { m };
    if e >= 0 {
        BigRational::from_integer(m * ten_to(e as u64))
    } else {
        BigRational::new(m, ten_to(e.unsigned_abs()))
    }
}

/// A random decimal text and its reference value: digits (trailing zeros and factors of 2
/// and 5 frequent), a decimal point somewhere, an exponent.
fn random_decimal(rng: &mut Lcg) -> (String, BigRational) {
    let len = 1 + rng.below(12) as usize;
    let digits: String = (0..len)
        .map(|_| {
            let d = match rng.below(4) {
                0 => 0,
                1 => 5,
                _ => rng.below(10),
            };
            char::from(b'0' + d as u8)
        })
        .collect();
    let point = rng.below(len as u64 + 1) as usize;
    let exponent = rng.below(61) as i64 - 30;
    let negative = rng.below(3) == 0;
    let mut text = String::new();
    if negative {
        text.push('-');
    }
    text.push_str(&digits[..point]);
    text.push('.');
    text.push_str(&digits[point..]);
    text.push_str(&format!("e{exponent}"));
    let value = reference(negative, &digits, exponent - (len - point) as i64);
    (text, value)
}

// The reader agrees with the reference on decimals and fractions of them, in lowest terms
// (a numerator and denominator equal to the reduced reference's).
#[test]
fn decimals_and_fractions_are_read_exactly_in_lowest_terms() {
    let mut rng = Lcg(49);
    for _ in 0..3000 {
        let (a, va) = random_decimal(&mut rng);
        let got = parse_rational(&a).unwrap();
        assert_eq!(got, va, "{a}");
        assert_eq!((got.numer(), got.denom()), (va.numer(), va.denom()), "{a}");
        let (b, vb) = random_decimal(&mut rng);
        let text = format!("{a}/{b}");
        match parse_rational(&text) {
            Ok(q) => {
                let expected = va.clone() / vb.clone();
                assert_eq!(
                    (q.numer(), q.denom()),
                    (expected.numer(), expected.denom()),
                    "{text}"
                );
            }
            Err(e) => {
                assert!(vb == BigRational::from_integer(0.into()), "{text}: {e}");
                assert!(e.to_string().contains("divides by zero"), "{e}");
            }
        }
    }
    for (text, n, d) in [
        ("1e10000/1e9999", "10", "1"),
        ("-2.5e-3", "-1", "400"),
        ("0.000/7", "0", "1"),
        ("64e-6/-125e3", "-1", "1953125000"),
    ] {
        let q = parse_rational(text).unwrap();
        assert_eq!(
            (q.numer().to_string(), q.denom().to_string()),
            (n.to_string(), d.to_string()),
            "{text}"
        );
    }
}

/// A chain of `n` states, each move costing `cost`.
fn chain(n: usize, cost: &str) -> String {
    let actions: Vec<String> = (0..n)
        .map(|s| {
            if s + 1 < n {
                format!(r#"[{{"to": {}, "cost": "{cost}"}}]"#, s + 1)
            } else {
                "[]".to_string()
            }
        })
        .collect();
    format!(
        r#"{{"format": "truecost-problem/1", "states": {n}, "initial": 0, "goals": [{}], "actions": [{}]}}"#,
        n - 1,
        actions.join(",")
    )
}

// 9,000 costs of `1e10000` (a 314 KB file) pass the 2^28-bit budget of the file's numbers: the
// refusal names the bits counted and the bound, and comes before any number is reduced (the
// bits counted from the digits and exponents already pass the budget).
#[test]
fn a_file_of_huge_exponents_is_refused_promptly_naming_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    for cost in ["1e10000", "1e-10000", "7e10000/3"] {
        let file = write(dir.path(), "m.json", &chain(9000, cost));
        let start = Instant::now();
        let err = fails_one_line(&[
            "solve",
            "--algorithm",
            "dijkstra",
            "--file",
            file.to_str().unwrap(),
        ]);
        let took = start.elapsed();
        assert_contract(&err);
        assert!(
            err.contains("more than 2^28 = 268435456 bits in all"),
            "{err}"
        );
        // Counted from the text before any number is read.
        assert!(
            err.contains("take at least")
                && err.contains("counted from their digits and exponents before reading them"),
            "{err}"
        );
        // The bits counted up to the refusal: over the bound, under it plus one number.
        let bits: u64 = err
            .split(" bits up to here")
            .next()
            .and_then(|s| s.rsplit(' ').next())
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("no bit count in {err}"));
        assert!(bits > 1 << 28 && bits < (1 << 28) + 40_000, "{err}");
        assert!(took < Duration::from_secs(8), "{cost}: {took:?}");
    }
}

// The documented edge is still read exactly: `1e10000` (10001 digits) and `1e-10000`.
#[test]
fn the_documented_edge_is_read() {
    let big = parse_rational("1e10000").unwrap();
    assert_eq!(big, BigRational::from_integer(ten_to(10_000)));
    let small = parse_rational("1e-10000").unwrap();
    assert_eq!(small, BigRational::new(1.into(), ten_to(10_000)));
}

// A γ whose denominator alone passes 2^62 is refused before the perturbed model is built, by
// every command that builds it, naming γ and the bound.
#[test]
fn a_gamma_with_a_huge_denominator_is_refused_before_the_model() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.json");
    let out = out.to_str().unwrap();
    for gamma in ["1e-10000", "1/4611686018427387905"] {
        let commands: [&[&str]; 3] = [
            &["export", "--problem", "0", "--gamma", gamma, "--out", out],
            &[
                "solve",
                "--problem",
                "0",
                "--gamma",
                gamma,
                "--algorithm",
                "exact",
            ],
            &["compare", "--problem", "0", "--gamma", gamma],
        ];
        for args in commands {
            let start = Instant::now();
            let err = fails_one_line(args);
            assert!(start.elapsed() < Duration::from_secs(5), "{args:?}");
            assert_contract(&err);
            assert!(err.contains("gamma = "), "{err}");
            assert!(err.contains("too large a denominator"), "{err}");
            assert!(err.contains("2^62"), "{err}");
        }
    }
    // 2^62 itself is the bound of the later check: `1/2^62` passes the early refusal, and the
    // paper model's `(1-γ)/k` then has denominator `k·2^62`, refused naming a state's moves.
    let err = fails_one_line(&[
        "solve",
        "--problem",
        "0",
        "--gamma",
        "1/4611686018427387904",
        "--algorithm",
        "exact",
    ]);
    assert!(err.contains("too large a denominator"), "{err}");
}

// `compare --alphas` refuses a discount factor listed twice, however written, and more than 64
// of them, counted before any is read.
#[test]
fn compare_alphas_are_distinct_and_few() {
    for (alphas, expected) in [
        (
            "0.9,0.95,9/10",
            "alpha 9/10 is listed twice (as discount factor 1 and 3)",
        ),
        (
            "0.99,990e-3",
            "alpha 990e-3 is listed twice (as discount factor 1 and 2)",
        ),
    ] {
        let err = fails_one_line(&["compare", "--problem", "0", "--alphas", alphas]);
        assert_contract(&err);
        assert!(err.contains(expected), "{err}");
    }
    let many: Vec<String> = (1..=65).map(|i| format!("{i}/100")).collect();
    let err = fails_one_line(&["compare", "--problem", "0", "--alphas", &many.join(",")]);
    assert!(
        err.contains("--alphas lists 65 discount factors, more than the 64 compare takes"),
        "{err}"
    );
    // Counted before reading: 65 texts that are not numbers are refused by the count.
    let junk = vec!["x"; 65].join(",");
    let err = fails_one_line(&["compare", "--problem", "0", "--alphas", &junk]);
    assert!(err.contains("65 discount factors"), "{err}");
    let exactly: Vec<String> = (1..=64).map(|i| format!("{i}/100")).collect();
    let o = common::cli::truecost()
        .args(["compare", "--problem", "0", "--alphas", &exactly.join(",")])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = String::from_utf8(o.stdout).unwrap();
    assert_eq!(rows.matches("discounted a=").count(), 64, "{rows}");
}

// `check` checks a certificate as it reads it: random bytes and zeros are refused at their
// first byte that cannot be JSON text, in a fraction of a second, naming the byte.
#[test]
fn a_streamed_certificate_is_checked_as_it_is_read() {
    let line = concat!(env!("CARGO_MANIFEST_DIR"), "/problems/line.json");
    for (stream, expected) in [
        (
            "/dev/zero",
            "is not a JSON certificate: byte 0 is 0x00, a control character",
        ),
        ("/dev/urandom", "/dev/urandom is not"),
    ] {
        let start = Instant::now();
        let err = fails_one_line(&["check", "--file", line, stream]);
        assert!(start.elapsed() < Duration::from_secs(3), "{stream}");
        assert_contract(&err);
        assert!(err.contains("cannot read the certificate"), "{err}");
        assert!(err.contains(expected), "{err}");
    }
    // Invalid UTF-8 split across the reader's chunks is named at its byte.
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = vec![b' '; (1 << 16) - 1];
    bytes.extend_from_slice(&[0xe2, 0x28, 0xa1]);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, &bytes).unwrap();
    let err = fails_one_line(&["check", "--file", line, bad.to_str().unwrap()]);
    assert!(err.contains("is not UTF-8 text (byte 65535)"), "{err}");
    // A multi-byte character split across chunks is text: the parser then reads it.
    let mut bytes = vec![b' '; (1 << 16) - 1];
    bytes.extend_from_slice("é".as_bytes());
    let split = dir.path().join("split.json");
    std::fs::write(&split, &bytes).unwrap();
    let err = fails_one_line(&["check", "--file", line, split.to_str().unwrap()]);
    assert!(err.contains("malformed certificate"), "{err}");
}

/// The bits a rational takes, numerator and denominator together.
fn bits_of(q: &BigRational) -> u64 {
    q.numer().bits() + q.denom().bits()
}

// The reader's count from digits and exponents alone is a lower bound of the bits each number
// takes in lowest terms, on random decimals and fractions of them (factors of 2 and 5
// frequent, so that the mantissas cancel powers of ten) and on fractions whose mantissas
// cancel most of a large exponent; it is close to the bits when a power of ten dominates.
#[test]
fn the_bits_counted_from_the_text_never_exceed_the_numbers_bits() {
    use truecost::value::bits_lower_bound;
    let mut rng = Lcg(57);
    for _ in 0..3000 {
        let (a, va) = random_decimal(&mut rng);
        assert!(bits_lower_bound(&a) <= bits_of(&va), "{a}");
        let (b, vb) = random_decimal(&mut rng);
        if vb == BigRational::from_integer(0.into()) {
            continue;
        }
        let text = format!("{a}/{b}");
        let exact = va.clone() / vb.clone();
        assert!(bits_lower_bound(&text) <= bits_of(&exact), "{text}");
    }
    // 2^k·5^j against 10^e: the mantissas take away as much as they can.
    for (text, at_least) in [
        (format!("{}e-300", BigInt::from(2).pow(900)), 0),
        (format!("1e300/{}", BigInt::from(5).pow(400)), 0),
        (format!("{}e400", BigInt::from(5).pow(300)), 1300),
        ("1e10000".to_string(), 33_000),
        ("3e-10000/7e10000".to_string(), 66_000),
    ] {
        let q = parse_rational(&text).unwrap();
        let bound = bits_lower_bound(&text);
        assert!(bound <= bits_of(&q), "{text}: {bound} > {}", bits_of(&q));
        assert!(bound >= at_least, "{text}: {bound} < {at_least}");
    }
    for text in ["", "x", "1/0", "0", "0/5", "1e10001", "--1"] {
        assert_eq!(bits_lower_bound(text), 0, "{text:?}");
    }
}

/// A stochastic file of `n` costs, each a fraction of two 2000-digit mantissas and exponents
/// `e10000` and `e-10000` (about 80,000 bits each, 4,014 bytes of text; the stochastic reader
/// counts every number before the model's bound on the stage costs' lcm applies).
fn huge_fractions(n: usize) -> String {
    let mut rng = Lcg(3);
    let mut mantissa = || -> String {
        (0..2000)
            .map(|_| char::from(b'1' + rng.below(9) as u8))
            .collect()
    };
    let actions: Vec<String> = (0..n)
        .map(|s| {
            format!(
                r#"[{{"cost": "{}e10000/{}e-10000", "outcomes": [{{"to": {}, "p": "1"}}]}}]"#,
                mantissa(),
                mantissa(),
                s + 1
            )
        })
        .chain(["[]".to_string()])
        .collect();
    format!(
        r#"{{"format": "truecost-stochastic/1", "states": {}, "initial": 0, "goals": [{n}], "actions": [{}]}}"#,
        n + 1,
        actions.join(",")
    )
}

// A stochastic file of 3,400 fractions of 2000-digit mantissas with exponents ±10000
// (13.7 MB) passes the 2^28-bit budget: it is refused naming the budget, promptly (0.5 s of
// processor time in release; the bound here is for a debug build on a loaded machine), each
// number reduced through a subquadratic gcd of its mantissas.
#[test]
fn a_file_of_huge_fractions_is_refused_promptly() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(dir.path(), "fractions.json", &huge_fractions(3400));
    let start = Instant::now();
    let err = fails_one_line(&["discount", "--file", file.to_str().unwrap()]);
    let took = start.elapsed();
    assert_contract(&err);
    assert!(
        err.contains("more than 2^28 = 268435456 bits in all"),
        "{err}"
    );
    assert!(took < Duration::from_secs(10), "{took:?}: {err}");
}

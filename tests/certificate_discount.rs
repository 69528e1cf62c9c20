//! Discount certificates: `discount --certificate` then `truecost check` accepts on a
//! hand-made problem (breakpoint derived by hand), the discount example, paper problems,
//! FrozenLake 4x4 (`--env`) and random small stochastic files; every kind of tampering is
//! rejected naming the first failing interval, breakpoint or state and the condition.

mod common;

use std::path::Path;

use common::cli::{fails_one_line, json, stdout, write};
use num_bigint::BigInt;
use num_rational::BigRational;
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

/// One running state 0 and the goal 1: `a0` stays at 0 with reward 1, `a1` enters the goal
/// with reward 3, `a2` is a copy of `a1`. By hand: staying forever pays `1/(1 − α)`, entering
/// pays 3; they tie where `1/(1 − α) = 3`, at `α = 2/3`. Below it the optimal actions are
/// `{a1, a2}` (values `3`), above it `{a0}` (value `1/(1 − α)`), at it all three.
const TIE: &str = r#"{"format": "truecost-stochastic/1", "initial": 0, "goals": [1], "actions": [
  [{"to": 0, "cost": "1", "reward": "1"}, {"to": 1, "cost": "1", "reward": "3"},
   {"to": 1, "cost": "1", "reward": "3"}],
  []
]}"#;

fn s(p: &Path) -> String {
    p.display().to_string()
}

/// `discount <source> --certificate C` and the certificate read back.
fn certify(dir: &Path, source: &[&str]) -> Value {
    let cert = dir.join("discount.cert.json");
    let c = s(&cert);
    let mut args = vec!["discount"];
    args.extend_from_slice(source);
    args.extend_from_slice(&["--certificate", &c]);
    stdout(&args);
    serde_json::from_str(&std::fs::read_to_string(&cert).unwrap()).unwrap()
}

/// `check <source> C --format json` on `cert`, which must be accepted.
fn accepted(dir: &Path, source: &[&str], cert: &Value) -> Value {
    let path = write(dir, "accept.cert.json", &cert.to_string());
    let p = s(&path);
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    args.extend_from_slice(&[&p, "--format", "json"]);
    let v = json(&args);
    assert_eq!(v["accepted"], true, "{v}");
    assert_eq!(v["objective"], "discount", "{v}");
    v
}

/// `check <source> C` on `cert`, which must be rejected (exit 1, one line): the line.
fn rejected(dir: &Path, source: &[&str], cert: &Value) -> String {
    let path = write(dir, "reject.cert.json", &cert.to_string());
    let p = s(&path);
    let mut args = vec!["check"];
    args.extend_from_slice(source);
    args.push(&p);
    fails_one_line(&args)
}

/// The place and the condition of a rejection line: `(interval, breakpoint, state, condition)`.
fn failure(line: &str) -> (Option<usize>, Option<usize>, Option<usize>, String) {
    let rest = line
        .trim_end()
        .strip_prefix("error: certificate rejected: ")
        .unwrap_or_else(|| panic!("not a rejection: {line}"));
    let (place, rest) = match rest.split_once(": condition ") {
        Some((p, r)) => (p, r),
        None => ("", rest.strip_prefix("condition ").unwrap()),
    };
    let mut at = (None, None, None);
    for part in place.split(", ").filter(|p| !p.is_empty()) {
        let (what, n) = part.split_once(' ').unwrap();
        let n = Some(n.parse().unwrap());
        match what {
            "interval" => at.0 = n,
            "breakpoint" => at.1 = n,
            "state" => at.2 = n,
            _ => panic!("unknown place {part}"),
        }
    }
    let condition = rest.split_once(':').unwrap().0.to_string();
    (at.0, at.1, at.2, condition)
}

/// Where a rejection is expected: interval, breakpoint, state (`None`: any) and condition.
type Place<'a> = (Option<usize>, Option<usize>, Option<usize>, &'a str);

fn tampered(cert: &Value, edit: impl FnOnce(&mut Value)) -> Value {
    let mut c = cert.clone();
    edit(&mut c);
    c
}

fn rat(v: &Value) -> BigRational {
    v.as_str().unwrap().parse().unwrap()
}

fn text(r: &BigRational) -> Value {
    json!(r.to_string())
}

#[test]
fn the_hand_tie_is_certified_at_two_thirds() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "tie.json", TIE);
    let source = ["--file", &s(&f)];
    let cert = certify(dir.path(), &source);
    assert_eq!(cert["format"], "truecost-certificate/1");
    assert_eq!(cert["objective"], "discount");
    let sha = format!("{:x}", Sha256::digest(TIE.as_bytes()));
    assert_eq!(cert["problem"]["sha256"], sha.as_str());
    let b = &cert["breakpoints"];
    assert_eq!(b.as_array().unwrap().len(), 1, "{b}");
    // The breakpoint 2/3: a root of its polynomial, which is of degree 1.
    let poly: Vec<BigRational> = b[0]["polynomial"]
        .as_array()
        .unwrap()
        .iter()
        .map(rat)
        .collect();
    assert_eq!(poly.len(), 2);
    let two_thirds: BigRational = "2/3".parse().unwrap();
    assert_eq!(
        &poly[0] + &poly[1] * &two_thirds,
        BigRational::from_integer(0.into())
    );
    assert!(rat(&b[0]["lo"]) <= two_thirds && two_thirds <= rat(&b[0]["hi"]));
    assert_eq!(b[0]["optimal"], json!([[0, 1, 2], []]));
    let t = &cert["intervals"];
    assert_eq!(t[0]["optimal"], json!([[1, 2], []]));
    assert_eq!(t[1]["optimal"], json!([[0], []]));
    let v = accepted(dir.path(), &source, &cert);
    let names: Vec<&str> = v["conditions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "problem",
            "shape",
            "polynomial",
            "isolating",
            "order",
            "sample",
            "denominator",
            "goal",
            "policy",
            "evaluation",
            "optimality",
            "continuity",
            "ties",
            "change"
        ]
    );
    // A missing action in the optimal set: a2 ties with a1 on the whole first interval.
    let missing = tampered(&cert, |c| c["intervals"][0]["optimal"][0] = json!([1]));
    let line = rejected(dir.path(), &source, &missing);
    assert_eq!(
        failure(&line),
        (Some(0), None, Some(0), "optimality".into()),
        "{line}"
    );
    // A wrong set at the breakpoint.
    let ties = tampered(&cert, |c| c["breakpoints"][0]["optimal"][0] = json!([0, 1]));
    let line = rejected(dir.path(), &source, &ties);
    assert_eq!(
        failure(&line),
        (None, Some(0), Some(0), "ties".into()),
        "{line}"
    );
    // A spurious breakpoint inside the first interval (1/2, where nothing changes): the
    // first interval split in two with the same witness on both sides.
    let spurious = tampered(&cert, |c| {
        let first = c["intervals"][0].clone();
        let mut left = first.clone();
        left["sample"] = json!("1/4");
        let mut right = first;
        right["sample"] = json!("3/5");
        let intervals = c["intervals"].as_array_mut().unwrap();
        intervals[0] = right;
        intervals.insert(0, left);
        let at_half = json!({"polynomial": ["-1", "2"], "lo": "1/2", "hi": "1/2",
                             "optimal": [[1, 2], []]});
        c["breakpoints"].as_array_mut().unwrap().insert(0, at_half);
    });
    let line = rejected(dir.path(), &source, &spurious);
    assert_eq!(
        failure(&line),
        (None, Some(0), None, "change".into()),
        "{line}"
    );
}

/// FrozenLake 4x4 (slippery): breakpoints of degree 3 and 8, and each tampering.
#[test]
fn frozenlake_certificate_is_accepted_and_each_tampering_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let source = ["--env", "frozenlake"];
    let cert = certify(dir.path(), &source);
    let v = accepted(dir.path(), &source, &cert);
    assert_eq!(v["breakpoints"], 2);
    assert_eq!(v["intervals"], 3);
    assert_eq!(v["states"], 16);
    // The first breakpoint's polynomial is 4x³ − 36x + 27 up to a constant factor (the
    // guide's statement): coefficients proportional to (27, −36, 0, 4).
    let m: Vec<BigRational> = cert["breakpoints"][0]["polynomial"]
        .as_array()
        .unwrap()
        .iter()
        .map(rat)
        .collect();
    let want: Vec<BigRational> = [27, -36, 0, 4]
        .iter()
        .map(|&c| BigRational::from_integer(BigInt::from(c)))
        .collect();
    assert_eq!(m.len(), 4);
    assert!(m.iter().zip(&want).all(|(a, b)| a * &want[0] == b * &m[0]));

    let bp0 = cert["breakpoints"][0].clone();
    let (lo, hi) = (rat(&bp0["lo"]), rat(&bp0["hi"]));
    let running = (0..16)
        .find(|&x| !cert["intervals"][0]["values"][x].is_null())
        .unwrap();
    let mut cases: Vec<(&str, Value, Place<'_>)> = Vec::new();
    // A bracket that isolates no root: (9/10, 19/20] (the root is 0.8087…).
    cases.push((
        "no root",
        tampered(&cert, |c| {
            c["breakpoints"][0]["lo"] = json!("9/10");
            c["breakpoints"][0]["hi"] = json!("19/20");
        }),
        (None, Some(0), None, "isolating"),
    ));
    // Two roots in the bracket: the polynomial times (x − hi).
    cases.push((
        "two roots",
        tampered(&cert, |c| {
            let mut p = vec![BigRational::from_integer(0.into()); m.len() + 1];
            for (i, a) in m.iter().enumerate() {
                p[i + 1] += a;
                p[i] -= a * &hi;
            }
            c["breakpoints"][0]["polynomial"] = Value::Array(p.iter().map(text).collect());
        }),
        (None, Some(0), None, "isolating"),
    ));
    // A shifted breakpoint: the rational 4/5 in place of 0.8087…; on (4/5, 0.8087…) the
    // right interval's witness is not optimal.
    cases.push((
        "shifted",
        tampered(&cert, |c| {
            c["breakpoints"][0] = json!({"polynomial": ["-4", "5"], "lo": "4/5", "hi": "4/5",
                                        "optimal": bp0["optimal"].clone()});
            c["intervals"][1]["sample"] = text(&hi);
        }),
        (Some(1), None, None, "optimality"),
    ));
    // A wrong witness action: one that is not listed as optimal.
    let (x, other) = {
        let t = &cert["intervals"][0];
        let x = running;
        let listed: Vec<u64> = t["optimal"][x]
            .as_array()
            .unwrap()
            .iter()
            .map(|a| a.as_u64().unwrap())
            .collect();
        (x, (0..4).find(|a| !listed.contains(a)).unwrap())
    };
    cases.push((
        "wrong witness",
        tampered(&cert, |c| c["intervals"][0]["policy"][x] = json!(other)),
        (Some(0), None, Some(x), "policy"),
    ));
    // The same action also listed as optimal: its Bellman identity fails.
    cases.push((
        "wrong witness, listed",
        tampered(&cert, |c| {
            c["intervals"][0]["policy"][x] = json!(other);
            c["intervals"][0]["optimal"][x] = json!([other]);
        }),
        (Some(0), None, Some(x), "evaluation"),
    ));
    // A value off by 10^-30: its numerator plus 10^-30 times its denominator.
    cases.push((
        "value off",
        tampered(&cert, |c| {
            let v = &mut c["intervals"][0]["values"][x];
            let k = v["denominator"].as_u64().unwrap() as usize;
            let d = cert["intervals"][0]["denominators"][k].as_array().unwrap();
            let tiny = BigRational::new(1.into(), BigInt::from(10).pow(30));
            let zero = json!("0");
            let len = d.len().max(v["numerator"].as_array().unwrap().len());
            let sum: Vec<Value> = (0..len)
                .map(|i| {
                    let n = rat(v["numerator"].get(i).unwrap_or(&zero));
                    let di = rat(d.get(i).unwrap_or(&zero));
                    text(&(n + di * &tiny))
                })
                .collect();
            v["numerator"] = Value::Array(sum);
        }),
        (Some(0), None, None, "evaluation"),
    ));
    // Swapped intervals: the first interval's sample is then above the first breakpoint.
    cases.push((
        "swapped intervals",
        tampered(&cert, |c| {
            c["intervals"].as_array_mut().unwrap().swap(0, 1);
        }),
        (Some(0), None, None, "sample"),
    ));
    // Swapped breakpoints: the brackets decrease.
    cases.push((
        "swapped breakpoints",
        tampered(&cert, |c| {
            c["breakpoints"].as_array_mut().unwrap().swap(0, 1);
        }),
        (None, Some(1), None, "order"),
    ));
    // A wrong SHA-256.
    cases.push((
        "sha",
        tampered(&cert, |c| c["problem"]["sha256"] = json!("0".repeat(64))),
        (None, None, None, "problem"),
    ));
    assert!(lo < hi);
    for (what, c, (i, b, x, condition)) in cases {
        let line = rejected(dir.path(), &source, &c);
        let (fi, fb, fx, fc) = failure(&line);
        assert_eq!(fc, condition, "{what}: {line}");
        assert_eq!((fi, fb), (i, b), "{what}: {line}");
        if x.is_some() {
            assert_eq!(fx, x, "{what}: {line}");
        }
    }
}

#[test]
fn the_discount_example_and_paper_problems_are_certified() {
    let dir = tempfile::tempdir().unwrap();
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("problems/discount-example.json");
    let source = ["--file", &s(&example)];
    let cert = certify(dir.path(), &source);
    let v = accepted(dir.path(), &source, &cert);
    // The guide: 4 breakpoints, the first the root of 5x⁴ − x³ − x² − x − 1 in (0, 1).
    assert_eq!(v["breakpoints"], 4, "{v}");
    for id in ["0", "6"] {
        let source = ["--problem", id];
        let cert = certify(dir.path(), &source);
        assert_eq!(cert["problem"]["step_cost"], "unit");
        accepted(dir.path(), &source, &cert);
        // The certificate names its source: checking it against another is refused.
        let line = rejected(dir.path(), &["--env", "frozenlake"], &cert);
        assert!(line.contains("not from env"), "{line}");
    }
}

/// A small deterministic generator (64-bit LCG), so the cases are the same on every run.
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 33) % n
    }
}

/// A random stochastic file: `n` running states and a goal `n`, two or three actions per
/// state, each with a reward in `−3..=3` and one or two outcomes with probabilities in
/// quarters.
fn random_problem(rng: &mut Lcg, n: u64) -> String {
    let mut states = Vec::new();
    for _ in 0..n {
        let actions: Vec<Value> = (0..2 + rng.below(2))
            .map(|_| {
                let reward = rng.below(7) as i64 - 3;
                let to = rng.below(n + 1);
                if rng.below(2) == 0 {
                    json!({"to": to, "cost": "1", "reward": reward.to_string()})
                } else {
                    let other = (to + 1 + rng.below(n)) % (n + 1);
                    let k = 1 + rng.below(3);
                    json!({"cost": "1", "reward": reward.to_string(), "outcomes": [
                        {"to": to, "p": format!("{k}/4")},
                        {"to": other, "p": format!("{}/4", 4 - k)}]})
                }
            })
            .collect();
        states.push(Value::Array(actions));
    }
    states.push(json!([]));
    json!({"format": "truecost-stochastic/1", "initial": 0, "goals": [n], "actions": states})
        .to_string()
}

#[test]
fn random_small_files_are_certified_and_agree_with_discount() {
    let dir = tempfile::tempdir().unwrap();
    let mut rng = Lcg(48);
    let mut breakpoints = 0;
    for case in 0..12 {
        let text = random_problem(&mut rng, 2 + case % 3);
        let f = write(dir.path(), "random.json", &text);
        let source = ["--file", &s(&f)];
        let cert = certify(dir.path(), &source);
        let v = accepted(dir.path(), &source, &cert);
        // The certificate's breakpoints are the ones `discount` prints.
        let report = json(&["discount", "--file", &s(&f), "--format", "json"]);
        let printed = report["breakpoints"].as_array().unwrap().len();
        assert_eq!(v["breakpoints"], printed, "case {case}: {text}");
        breakpoints += printed;
        // The problem edited after the certificate was written: its SHA-256 differs.
        let edited = text.replacen("\"reward\"", "\"reward\" ", 1);
        let g = write(dir.path(), "edited.json", &edited);
        let line = rejected(dir.path(), &["--file", &s(&g)], &cert);
        assert_eq!(failure(&line).3, "problem", "{line}");
    }
    assert!(breakpoints > 0, "some random case has a breakpoint");
}

#[test]
fn malformed_discount_certificates_and_coq_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = write(dir.path(), "tie.json", TIE);
    let source = ["--file", &s(&f)];
    let cert = certify(dir.path(), &source);
    let extra = tampered(&cert, |c| c["extra"] = json!(1));
    let line = rejected(dir.path(), &source, &extra);
    assert!(line.contains("malformed certificate"), "{line}");
    let bad = tampered(&cert, |c| c["intervals"][0]["sample"] = json!("0.5"));
    let line = rejected(dir.path(), &source, &bad);
    assert!(line.contains("interval 0: sample"), "{line}");
    let path = write(dir.path(), "c.json", &cert.to_string());
    let line = fails_one_line(&["check", "--file", &s(&f), "--coq", &s(&path)]);
    assert!(line.contains("--coq"), "{line}");
}

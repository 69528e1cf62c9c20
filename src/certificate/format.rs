//! The certificate file, `truecost-certificate/1`: JSON, read strictly (unknown fields, missing
//! fields and malformed numbers are refused in one line naming the field).
//!
//! ```json
//! {
//!   "format": "truecost-certificate/1",
//!   "objective": "truecost",
//!   "alpha": null,
//!   "problem": { "source": "file", "name": "g.json", "gamma": null, "noise": null,
//!                "step_cost": null, "sha256": "…", "sha256_of": "file bytes" },
//!   "states": 3,
//!   "values": ["2", "1", "0"],
//!   "policy": [0, 1, null]
//! }
//! ```
//!
//! * `objective`: `truecost`, `discounted` (with `alpha`, a fraction in `(0, 1)`),
//!   `deterministic` (the deterministic planners' `G*`: every action has one outcome) or
//!   `reach` (the greatest probability of reaching a goal); `discount` is the kind of
//!   `discount --certificate`, read by [`super::discount::parse_discount`].
//! * `problem`: how to rebuild the problem — `source` `file` (`name` the path as given),
//!   `problem` (`name` the paper problem's number, `step_cost` `unit` or `euclidean`) or `env`
//!   (`name` the `--env` text); `gamma` (a fraction) and `noise` (`paper` or `reference`) when
//!   the problem is a deterministic one perturbed by a noise model. `sha256` is the SHA-256 of
//!   the problem file's bytes (`sha256_of`: `file bytes`) or, for `problem` and `env`, of the
//!   model's canonical export ([`super::Mdp::canonical_text`]; `sha256_of`:
//!   `truecost-canonical-mdp/1`). For a DRN file read with a goal label or a cost reward
//!   model other than the defaults, `goal_label` and `cost_reward` name them (absent
//!   otherwise).
//! * `values`: one exact number per state, in state order: `"p/q"` or `"p"` (an optional `-`,
//!   the integer, a positive denominator), or `"inf"` (truecost, deterministic: no policy
//!   reaches a goal with probability 1). Each integer is decimal digits, or `0x` and lowercase
//!   hexadecimal digits without a leading `0`: [`write_over`] prints integers of more than
//!   [`DECIMAL_BITS`] bits in hexadecimal ([`push_integer`]), which is linear in their length
//!   where decimal printing is not; [`write`] writes the texts it is given.
//! * `policy`: per state, the index of the chosen action in the state's action list, or `null`
//!   (goals, terminal states, `inf` states; for reach, the states of probability 0).

use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, Zero};
use serde_json::{json, Map, Value};

use crate::value::{integer_text, Rational};

/// The format tag.
pub const FORMAT: &str = "truecost-certificate/1";

/// What the certificate claims to be optimal for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CertifiedObjective {
    /// Least expected cost among policies reaching a goal with probability 1.
    Truecost,
    /// Greatest expected discounted reward, with the discount factor `α`.
    Discounted(Rational),
    /// The deterministic planners' `G*` (every action has a single outcome).
    Deterministic,
    /// Greatest probability of reaching a goal.
    Reach,
}

impl CertifiedObjective {
    /// The name in the certificate.
    pub fn name(&self) -> &'static str {
        match self {
            CertifiedObjective::Truecost => "truecost",
            CertifiedObjective::Discounted(_) => "discounted",
            CertifiedObjective::Deterministic => "deterministic",
            CertifiedObjective::Reach => "reach",
        }
    }
}

/// Where the problem comes from, as recorded in the certificate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ProblemRecord {
    /// `file`, `problem` or `env`.
    pub source: String,
    /// The path, the problem number or the `--env` text.
    pub name: String,
    /// `γ` of a noise model, as a fraction, if the problem is a perturbed deterministic one.
    pub gamma: Option<String>,
    /// The noise model's name, if any.
    pub noise: Option<String>,
    /// The step cost of a paper problem (`unit` or `euclidean`).
    pub step_cost: Option<String>,
    /// SHA-256, 64 lowercase hexadecimal digits.
    pub sha256: String,
    /// What was hashed: `file bytes` or [`super::mdp::CANONICAL_FORMAT`].
    pub sha256_of: String,
    /// The label of a DRN file's goal states, when not the default (`--goal-label`).
    pub goal_label: Option<String>,
    /// The reward model of a DRN file's stage costs, when not the default (`--cost-reward`).
    pub cost_reward: Option<String>,
}

/// A certificate as read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Certificate {
    /// The objective.
    pub objective: CertifiedObjective,
    /// The problem.
    pub problem: ProblemRecord,
    /// Per state: the value, `None` for `inf`.
    pub values: Vec<Option<Rational>>,
    /// Per state: the action index, if any.
    pub policy: Vec<Option<u64>>,
}

/// Writes a certificate. `values` are the values' texts as [`Certificate`] reads them (`"p/q"`,
/// `"p"`, `"inf"`), taken as they are: the writer does no arithmetic.
pub fn write(
    objective: &CertifiedObjective,
    problem: &ProblemRecord,
    values: Vec<String>,
    policy: &[Option<usize>],
) -> String {
    let mut out = String::with_capacity(
        values.iter().map(|v| v.len() + 3).sum::<usize>() + 6 * policy.len() + 512,
    );
    head(&mut out, objective, problem, policy, values.len());
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        push_json_string(&mut out, v);
    }
    out.push_str("]}\n");
    out
}

/// Writes a certificate whose finite values are `numerators[x] / denominator` (`denominator >
/// 0`), not reduced: `"k/d"`, `"k"` when `d = 1` or `k = 0`, `"inf"` for `None`; every integer
/// as [`push_integer`] writes it, the denominator's text printed once. The same file as
/// [`write()`] with those texts, made without a `String` per value ([`write_over_to`] into one
/// buffer).
pub fn write_over(
    objective: &CertifiedObjective,
    problem: &ProblemRecord,
    numerators: &[Option<&BigInt>],
    denominator: &BigInt,
    policy: &[Option<usize>],
) -> String {
    let mut out = Vec::with_capacity(over_capacity(numerators, denominator, policy));
    write_over_to(
        &mut out,
        objective,
        problem,
        numerators,
        denominator,
        policy,
    )
    .expect("writing into memory never fails");
    String::from_utf8(out).expect("JSON text is UTF-8")
}

/// A buffer size that holds [`write_over`]'s text: at most bits/3 decimal digits (bits/4
/// hexadecimal ones) per integer, the fixed characters, and room for the record.
pub fn over_capacity(
    numerators: &[Option<&BigInt>],
    denominator: &BigInt,
    policy: &[Option<usize>],
) -> usize {
    let d = integer_len_bound(denominator);
    numerators
        .iter()
        .map(|k| k.map_or(6, |k| integer_len_bound(k) + 4 + d))
        .sum::<usize>()
        + 21 * policy.len()
        + 4096
}

/// At least the length of `n`'s text as [`push_integer`] writes it.
fn integer_len_bound(n: &BigInt) -> usize {
    n.bits() as usize / 3 + 4
}

/// Bytes of values text [`write_over_to`] makes before handing them to the writer: the
/// buffer is reused, and a batch of values is printed in parallel.
const BATCH_BYTES: usize = 1 << 22;

/// [`write_over`]'s text into `out`, a batch of values (about 4 MiB, `BATCH_BYTES`) at a time:
/// each batch's numerators are printed in parallel ([`rayon`]) into their places in one
/// buffer, sized exactly, and handed to `out` in one `write_all`.
pub fn write_over_to(
    out: &mut dyn std::io::Write,
    objective: &CertifiedObjective,
    problem: &ProblemRecord,
    numerators: &[Option<&BigInt>],
    denominator: &BigInt,
    policy: &[Option<usize>],
) -> std::io::Result<()> {
    let values = Values {
        numerators,
        denominator,
    };
    values.write(out, objective, problem, policy, BATCH_BYTES)
}

/// The values [`write_over_to`] writes: `numerators[x] / denominator`.
struct Values<'a> {
    numerators: &'a [Option<&'a BigInt>],
    denominator: &'a BigInt,
}

impl Values<'_> {
    /// [`write_over_to`] with batches of about `batch_bytes` bytes of values text.
    fn write(
        &self,
        out: &mut dyn std::io::Write,
        objective: &CertifiedObjective,
        problem: &ProblemRecord,
        policy: &[Option<usize>],
        batch_bytes: usize,
    ) -> std::io::Result<()> {
        use rayon::prelude::*;
        let (numerators, denominator) = (self.numerators, self.denominator);
        let mut d = String::new();
        push_integer(&mut d, denominator);
        let over = (!denominator.is_one()).then_some(d.as_bytes());
        let mut head_text = String::with_capacity(21 * policy.len() + 512);
        head(&mut head_text, objective, problem, policy, numerators.len());
        out.write_all(head_text.as_bytes())?;
        drop(head_text);
        let mut buffer: Vec<u8> = Vec::new();
        let mut first = 0;
        while first < numerators.len() {
            let mut end = first;
            let mut estimate = 0;
            while end < numerators.len() && (end == first || estimate < batch_bytes) {
                estimate += numerators[end].map_or(6, |k| k.bits() as usize / 4 + d.len() + 6);
                end += 1;
            }
            let texts: Vec<ValueText> = numerators[first..end]
                .par_iter()
                .map(|k| ValueText::new(*k, over))
                .collect();
            // A comma before every value but the very first.
            let commas = end - first - usize::from(first == 0);
            // Every byte of the batch is written below: the buffer is grown, never cleared.
            let total = texts.iter().map(ValueText::len).sum::<usize>() + commas;
            if buffer.len() < total {
                buffer.resize(total, 0);
            }
            let mut places: Vec<&mut [u8]> = Vec::with_capacity(texts.len());
            let mut rest = &mut buffer[..total];
            for (i, t) in texts.iter().enumerate() {
                let (place, after) = rest.split_at_mut(t.len() + usize::from(first + i > 0));
                places.push(place);
                rest = after;
            }
            texts
                .par_iter()
                .zip(places.par_iter_mut())
                .for_each(|(t, place)| {
                    let (comma, text) = place.split_at_mut(place.len() - t.len());
                    comma.fill(b',');
                    t.fill(text);
                });
            out.write_all(&buffer[..total])?;
            first = end;
        }
        out.write_all(b"]}\n")
    }
}

/// One value's text in the values list, `"…"` with its quotes, as [`write_over`] writes it.
enum ValueText<'a> {
    /// `"inf"`.
    Infinite,
    /// An integer of more than [`DECIMAL_BITS`] bits: `-`, `0x` and `digits` hexadecimal
    /// digits, then `/` and the denominator's text if `over`.
    Hex {
        k: &'a BigInt,
        digits: usize,
        over: Option<&'a [u8]>,
    },
    /// A shorter integer's decimal text, then `/` and the denominator's text if `over`.
    Decimal {
        text: String,
        over: Option<&'a [u8]>,
    },
}

impl<'a> ValueText<'a> {
    /// The text of `k` (`None`: `inf`) over the denominator's text `over` (`None`: 1).
    fn new(k: Option<&'a BigInt>, over: Option<&'a [u8]>) -> Self {
        let Some(k) = k else {
            return ValueText::Infinite;
        };
        let over = over.filter(|_| !k.is_zero());
        if k.bits() <= DECIMAL_BITS {
            ValueText::Decimal {
                text: integer_text(k),
                over,
            }
        } else {
            ValueText::Hex {
                k,
                digits: (k.bits() as usize).div_ceil(4),
                over,
            }
        }
    }

    /// The text's length in bytes, quotes included.
    fn len(&self) -> usize {
        let over = |o: &Option<&[u8]>| o.map_or(0, |d| d.len() + 1);
        2 + match self {
            ValueText::Infinite => 3,
            ValueText::Hex { k, digits, over: o } => {
                usize::from(k.is_negative()) + 2 + digits + over(o)
            }
            ValueText::Decimal { text, over: o } => text.len() + over(o),
        }
    }

    /// Writes the text into `place`, exactly [`len`](Self::len) bytes.
    fn fill(&self, place: &mut [u8]) {
        let last = place.len() - 1;
        place[0] = b'"';
        place[last] = b'"';
        let inner = &mut place[1..last];
        let (number, over) = match self {
            ValueText::Infinite => {
                inner.copy_from_slice(b"inf");
                return;
            }
            ValueText::Hex { k, digits, over } => {
                let sign = usize::from(k.is_negative());
                inner[..sign].fill(b'-');
                inner[sign..sign + 2].copy_from_slice(b"0x");
                put_hex(&mut inner[sign + 2..sign + 2 + digits], k.magnitude());
                (sign + 2 + digits, over)
            }
            ValueText::Decimal { text, over } => {
                inner[..text.len()].copy_from_slice(text.as_bytes());
                (text.len(), over)
            }
        };
        if let Some(d) = over {
            inner[number] = b'/';
            inner[number + 1..].copy_from_slice(d);
        }
    }
}

/// Writes the hexadecimal digits of `n` into `place`, which is exactly as long as they are
/// (no leading zero): eight digits of each 32-bit half of a limb at a time, spread one
/// nibble to a byte and turned into ASCII together.
fn put_hex(place: &mut [u8], n: &BigUint) {
    /// The eight lowercase hexadecimal digits of `v`, most significant first.
    fn eight(v: u32) -> [u8; 8] {
        let mut x = u64::from(v);
        x = (x | x << 16) & 0x0000_ffff_0000_ffff;
        x = (x | x << 8) & 0x00ff_00ff_00ff_00ff;
        x = (x | x << 4) & 0x0f0f_0f0f_0f0f_0f0f;
        // Nibble i of v in byte i; a byte is 10 or more exactly when adding 6 carries into
        // its bit 4.
        let letters = ((x + 0x0606_0606_0606_0606) >> 4) & 0x0101_0101_0101_0101;
        (x + 0x3030_3030_3030_3030 + letters * (b'a' - b'0' - 10) as u64).to_be_bytes()
    }
    let mut end = place.len();
    for limb in n.iter_u64_digits() {
        for half in [limb as u32, (limb >> 32) as u32] {
            let digits = eight(half);
            let take = end.min(8);
            place[end - take..end].copy_from_slice(&digits[8 - take..]);
            end -= take;
        }
    }
    debug_assert_eq!(end, 0, "the place is as long as the digits");
}

/// The text of a value as certificates write it: `"inf"` for `None`, else `"p/q"` (`"p"` when
/// `q = 1`) with both integers as [`push_integer`] writes them.
///
/// ```
/// use truecost::certificate::value_text;
/// use truecost::value::Rational;
/// assert_eq!(value_text(Some(&Rational::new(6.into(), 4.into()))), "3/2");
/// assert_eq!(value_text(Some(&Rational::from_integer((-5).into()))), "-5");
/// assert_eq!(value_text(None), "inf");
/// ```
pub fn value_text(value: Option<&Rational>) -> String {
    let Some(r) = value else {
        return "inf".into();
    };
    let mut out = String::new();
    push_integer(&mut out, r.numer());
    if !r.denom().is_one() {
        out.push('/');
        push_integer(&mut out, r.denom());
    }
    out
}

/// Integers of more than this many bits (309 decimal digits or more) are written in
/// hexadecimal: printing in decimal takes time that grows faster than the length (at the
/// thousands of digits of a large grid's exact values, longer than solving), hexadecimal is
/// a copy of the binary digits.
pub const DECIMAL_BITS: u64 = 1024;

/// Appends the text of `n` as certificates write integers: decimal (an optional `-`, digits)
/// up to [`DECIMAL_BITS`] bits, beyond that an optional `-`, `0x` and lowercase hexadecimal
/// digits, the first not `0`. [`parse_exact`] reads both.
pub fn push_integer(out: &mut String, n: &BigInt) {
    if n.bits() <= DECIMAL_BITS {
        out.push_str(&integer_text(n));
        return;
    }
    if n.is_negative() {
        out.push('-');
    }
    out.push_str("0x");
    let mut digits = vec![0u8; (n.bits() as usize).div_ceil(4)];
    put_hex(&mut digits, n.magnitude());
    out.push_str(std::str::from_utf8(&digits).expect("ASCII digits"));
}

/// The fields before the values, in the order `serde_json` writes an object's keys (sorted),
/// and the opening of the `values` list.
fn head(
    out: &mut String,
    objective: &CertifiedObjective,
    problem: &ProblemRecord,
    policy: &[Option<usize>],
    states: usize,
) {
    use std::fmt::Write;
    let alpha = match objective {
        CertifiedObjective::Discounted(a) => json!(a.to_string()),
        _ => Value::Null,
    };
    let _ = write!(
        out,
        "{{\"alpha\":{alpha},\"format\":\"{FORMAT}\",\"objective\":\"{}\",\"policy\":[",
        objective.name()
    );
    for (x, a) in policy.iter().enumerate() {
        if x > 0 {
            out.push(',');
        }
        match a {
            Some(i) => {
                let _ = write!(out, "{i}");
            }
            None => out.push_str("null"),
        }
    }
    let _ = write!(
        out,
        "],\"problem\":{},\"states\":{states},\"values\":[",
        problem_json(problem)
    );
}

/// `v` as a JSON string, escaped as `serde_json` escapes it.
fn push_json_string(out: &mut String, v: &str) {
    if v.bytes()
        .all(|b| (0x20..0x7f).contains(&b) && b != b'"' && b != b'\\')
    {
        out.push('"');
        out.push_str(v);
        out.push('"');
    } else {
        out.push_str(&Value::from(v).to_string());
    }
}

/// A certificate's `problem` record as JSON (every kind has the same).
pub(super) fn problem_json(p: &ProblemRecord) -> Value {
    let mut v = json!({
        "source": p.source,
        "name": p.name,
        "gamma": p.gamma,
        "noise": p.noise,
        "step_cost": p.step_cost,
        "sha256": p.sha256,
        "sha256_of": p.sha256_of,
    });
    for (key, name) in [
        ("goal_label", &p.goal_label),
        ("cost_reward", &p.cost_reward),
    ] {
        if let Some(name) = name {
            v[key] = Value::from(name.as_str());
        }
    }
    v
}

/// An exact number `p/q` or `p` with a positive denominator `q`, kept as written (not
/// reduced). Each integer is decimal (`-?[0-9]+`) or, as [`push_integer`] writes long ones,
/// hexadecimal (`-?0x[1-9a-f][0-9a-f]*`); `q` has no sign.
pub fn parse_exact(text: &str) -> Option<Rational> {
    let (num, den) = match text.split_once('/') {
        Some((n, d)) => (n, Some(d)),
        None => (text, None),
    };
    let n = match num.strip_prefix('-') {
        Some(magnitude) => -BigInt::from(natural(magnitude)?),
        None => BigInt::from(natural(num)?),
    };
    let d = match den {
        Some(d) => BigInt::from(natural(d)?),
        None => BigInt::from(1),
    };
    if d.is_zero() {
        return None;
    }
    // Not reduced: every comparison the checker makes is by cross-multiplication, and a gcd
    // per value of ten thousand digits would dominate the check.
    Some(Rational::new_raw(n, d))
}

/// The most bits of an integer in a certificate: 2^20, about 8.8 times the longest common
/// denominator measured (29,773 hexadecimal digits, the 100×100 grid with `γ = 0.999`). The
/// checker's rejections reduce fractions (gcds, quadratic in the length): measured in release,
/// a value of 2^20 bits is rejected in 1.1 s of processor time (22 s at 2^22 bits), a reach
/// value of two such integers above 1 in 11 s, an `alpha` of `1/n` with `n` of 2^20 bits in
/// 13 s.
pub const MAX_INTEGER_BITS: u64 = 1 << 20;

/// The most decimal digits of an integer of [`MAX_INTEGER_BITS`] bits: `⌈2^20 · log10 2⌉`.
const MAX_DECIMAL_DIGITS: usize = 315_653;

/// Why `text`, an exact number's text that [`parse_exact`] refused, was refused for its
/// length: an integer of more than [`MAX_INTEGER_BITS`] bits; `None` for another reason.
pub fn too_long(text: &str) -> Option<String> {
    let longest = text
        .split(['/', '-'])
        .filter_map(|part| match part.strip_prefix("0x") {
            Some(hex) if hex.len() * 4 > MAX_INTEGER_BITS as usize => {
                Some((hex.len(), "hexadecimal"))
            }
            None if part.len() >= MAX_DECIMAL_DIGITS => Some((part.len(), "decimal")),
            _ => None,
        })
        .max()?;
    Some(format!(
        "an integer of {} {} digits, more than the {MAX_INTEGER_BITS} bits (2^20) a certificate's numbers may have",
        longest.0, longest.1
    ))
}

/// A natural number in decimal (`[0-9]+`) or hexadecimal (`0x[1-9a-f][0-9a-f]*`) of at most
/// [`MAX_INTEGER_BITS`] bits.
fn natural(text: &str) -> Option<BigUint> {
    match text.strip_prefix("0x") {
        Some(hex) => {
            if hex.is_empty() || hex.starts_with('0') || hex.len() * 4 > MAX_INTEGER_BITS as usize {
                return None;
            }
            // Eight digits to a 32-bit digit of the number, from the last (linear time).
            let mut digits = Vec::with_capacity(hex.len().div_ceil(8));
            for chunk in hex.as_bytes().rchunks(8) {
                let mut digit = 0u32;
                for &b in chunk {
                    let nibble = match b {
                        b'0'..=b'9' => b - b'0',
                        b'a'..=b'f' => b - b'a' + 10,
                        _ => return None,
                    };
                    digit = digit << 4 | u32::from(nibble);
                }
                digits.push(digit);
            }
            Some(BigUint::new(digits))
        }
        None => {
            if text.is_empty()
                || text.len() > MAX_DECIMAL_DIGITS
                || !text.bytes().all(|b| b.is_ascii_digit())
            {
                return None;
            }
            text.parse()
                .ok()
                .filter(|n: &BigUint| n.bits() <= MAX_INTEGER_BITS)
        }
    }
}

pub(super) fn object<'a>(
    v: &'a Value,
    what: &str,
    allowed: &[&str],
) -> Result<&'a Map<String, Value>, String> {
    let map = v
        .as_object()
        .ok_or_else(|| format!("{what} is not a JSON object"))?;
    if let Some(k) = map.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(format!(
            "{what} has an unknown field {}",
            crate::echo::echo(k)
        ));
    }
    Ok(map)
}

pub(super) fn field<'a>(
    map: &'a Map<String, Value>,
    what: &str,
    name: &str,
) -> Result<&'a Value, String> {
    map.get(name)
        .ok_or_else(|| format!("{what} has no field \"{name}\""))
}

pub(super) fn string(map: &Map<String, Value>, what: &str, name: &str) -> Result<String, String> {
    field(map, what, name)?
        .as_str()
        .map(str::to_string)
        .ok_or_else(|| format!("{what}: \"{name}\" is not a string"))
}

fn optional_string(
    map: &Map<String, Value>,
    what: &str,
    name: &str,
) -> Result<Option<String>, String> {
    match map.get(name) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(_) => Err(format!("{what}: \"{name}\" is neither a string nor null")),
    }
}

/// Reads a certificate's `problem` record (every kind has the same).
pub(super) fn problem_record(v: &Value) -> Result<ProblemRecord, String> {
    let p = object(
        v,
        "\"problem\"",
        &[
            "source",
            "name",
            "gamma",
            "noise",
            "step_cost",
            "sha256",
            "sha256_of",
            "goal_label",
            "cost_reward",
        ],
    )?;
    Ok(ProblemRecord {
        source: string(p, "\"problem\"", "source")?,
        name: string(p, "\"problem\"", "name")?,
        gamma: optional_string(p, "\"problem\"", "gamma")?,
        noise: optional_string(p, "\"problem\"", "noise")?,
        step_cost: optional_string(p, "\"problem\"", "step_cost")?,
        sha256: string(p, "\"problem\"", "sha256")?,
        sha256_of: string(p, "\"problem\"", "sha256_of")?,
        goal_label: optional_string(p, "\"problem\"", "goal_label")?,
        cost_reward: optional_string(p, "\"problem\"", "cost_reward")?,
    })
}

/// Reads a certificate (one line on error, naming the field).
pub fn parse(text: &str) -> Result<Certificate, String> {
    let v: Value =
        serde_json::from_str(text).map_err(|e| format!("the certificate is not JSON: {e}"))?;
    let top = object(
        &v,
        "the certificate",
        &[
            "format",
            "objective",
            "alpha",
            "problem",
            "states",
            "values",
            "policy",
        ],
    )?;
    let format = string(top, "the certificate", "format")?;
    if format != FORMAT {
        return Err(format!(
            "the certificate's format is {}, not {FORMAT}",
            crate::echo::echo(&format)
        ));
    }
    let alpha = optional_string(top, "the certificate", "alpha")?;
    let objective = match string(top, "the certificate", "objective")?.as_str() {
        "truecost" | "deterministic" | "reach" if alpha.is_some() => {
            return Err("\"alpha\" is given but the objective is not discounted".into())
        }
        "truecost" => CertifiedObjective::Truecost,
        "deterministic" => CertifiedObjective::Deterministic,
        "reach" => CertifiedObjective::Reach,
        "discounted" => {
            let a = alpha.ok_or("the discounted objective needs \"alpha\"")?;
            let a = parse_exact(&a).ok_or_else(|| match too_long(&a) {
                Some(why) => format!("\"alpha\": {why}"),
                None => format!(
                    "\"alpha\" {} is not an exact number p/q",
                    crate::echo::echo(&a)
                ),
            })?;
            CertifiedObjective::Discounted(a)
        }
        other => {
            return Err(format!(
                "unknown objective {} (truecost, discounted, deterministic, reach, discount)",
                crate::echo::echo(other)
            ))
        }
    };
    let problem = problem_record(field(top, "the certificate", "problem")?)?;
    let states = field(top, "the certificate", "states")?
        .as_u64()
        .ok_or("the certificate: \"states\" is not a non-negative integer")?;
    let values = field(top, "the certificate", "values")?
        .as_array()
        .ok_or("the certificate: \"values\" is not a list")?;
    let policy = field(top, "the certificate", "policy")?
        .as_array()
        .ok_or("the certificate: \"policy\" is not a list")?;
    if values.len() as u64 != states || policy.len() as u64 != states {
        return Err(format!(
            "the certificate has \"states\" {states} but {} values and {} policy entries",
            values.len(),
            policy.len()
        ));
    }
    let values = values
        .iter()
        .enumerate()
        .map(|(x, v)| match v.as_str() {
            Some("inf") => Ok(None),
            Some(s) => parse_exact(s).map(Some).ok_or_else(|| match too_long(s) {
                Some(why) => format!("value of state {x}: {why}"),
                None => format!(
                    "value of state {x}: {} is not \"p/q\", \"p\" or \"inf\"",
                    crate::echo::echo(s)
                ),
            }),
            None => Err(format!("value of state {x} is not a string")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let policy = policy
        .iter()
        .enumerate()
        .map(|(x, v)| match v {
            Value::Null => Ok(None),
            v => v.as_u64().map(Some).ok_or_else(|| {
                format!("policy of state {x}: {v} is neither an action index nor null")
            }),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Certificate {
        objective,
        problem,
        values,
        policy,
    })
}

#[cfg(test)]
mod tests {
    use num_bigint::BigInt;
    use serde_json::json;

    use super::{
        parse_exact, problem_json, push_integer, write, write_over, CertifiedObjective,
        ProblemRecord, Values, DECIMAL_BITS, FORMAT,
    };

    #[test]
    fn exact_numbers_are_integers_or_fractions_with_positive_denominators() {
        let r = |s: &str| parse_exact(s).map(|q| (q.numer().to_string(), q.denom().to_string()));
        assert_eq!(r("3/2"), Some(("3".into(), "2".into())));
        assert_eq!(r("6/4"), Some(("6".into(), "4".into())));
        assert_eq!(r("-7"), Some(("-7".into(), "1".into())));
        assert_eq!(parse_exact("6/4"), parse_exact("3/2"));
        // Hexadecimal: 0x1f = 31, 0xa0 = 160.
        assert_eq!(r("0x1f/0xa0"), Some(("31".into(), "160".into())));
        assert_eq!(r("-0x1f/3"), Some(("-31".into(), "3".into())));
        assert_eq!(r("7/0x10"), Some(("7".into(), "16".into())));
        for bad in [
            "", "-", "1/", "/2", "1/0", "1/-2", "+1", "1.5", "1e3", " 1", "inf", "1/2/3", "0x",
            "0x0", "0x01", "0X1", "0xA", "0x-1", "-0x", "x1", "0x1g", "1/0x0", "1/-0x1", "--1",
            "0x 1", "0b1",
        ] {
            assert_eq!(parse_exact(bad), None, "{bad:?}");
        }
    }

    /// `n` as the writer should print it, by `num-bigint`'s own formatting: decimal up to
    /// 1024 bits, `0x` and `{:x}` beyond.
    fn expected_integer(n: &BigInt) -> String {
        if n.bits() <= 1024 {
            n.to_string()
        } else if n < &BigInt::from(0) {
            format!("-0x{:x}", -n)
        } else {
            format!("0x{n:x}")
        }
    }

    #[test]
    fn long_integers_are_hexadecimal_and_read_back() {
        assert_eq!(DECIMAL_BITS, 1024);
        let two = BigInt::from(2);
        let mut cases = vec![BigInt::from(0), BigInt::from(-5), BigInt::from(12345)];
        // Around the threshold, and numbers whose limbs hold zero nibbles.
        for bits in [1023u32, 1024, 1025, 1088, 4096, 40_000] {
            let p: BigInt = num_traits::pow(two.clone(), bits as usize);
            let third = &p * BigInt::from(3) / BigInt::from(7);
            let one = BigInt::from(1);
            cases.extend([
                &p - &one,
                p.clone(),
                &p + &one,
                -(&p + BigInt::from(7)),
                third,
            ]);
        }
        let seven = num_traits::pow(BigInt::from(7), 5000);
        cases.extend([seven.clone(), -seven]);
        for n in &cases {
            let mut text = String::new();
            push_integer(&mut text, n);
            assert_eq!(text, expected_integer(n));
            let back = parse_exact(&text).expect("read back");
            assert_eq!((back.numer(), back.denom()), (n, &BigInt::from(1)));
        }
    }

    fn record() -> ProblemRecord {
        ProblemRecord {
            source: "file".into(),
            name: "a \"quoted\" name\\ with \u{1b} and é".into(),
            gamma: Some("99/100".into()),
            noise: Some("paper".into()),
            step_cost: None,
            sha256: "ab".repeat(32),
            sha256_of: "file bytes".into(),
            goal_label: None,
            cost_reward: None,
        }
    }

    /// The certificate as `serde_json` builds it from a `Value` tree.
    fn by_serde(
        objective: &CertifiedObjective,
        problem: &ProblemRecord,
        values: &[String],
        policy: &[Option<usize>],
    ) -> String {
        let alpha = match objective {
            CertifiedObjective::Discounted(a) => json!(a.to_string()),
            _ => serde_json::Value::Null,
        };
        let v = json!({
            "format": FORMAT,
            "objective": objective.name(),
            "alpha": alpha,
            "problem": problem_json(problem),
            "states": values.len(),
            "values": values,
            "policy": policy,
        });
        serde_json::to_string(&v).unwrap() + "\n"
    }

    #[test]
    fn the_writer_prints_what_serde_json_prints() {
        let texts = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        let cases = [
            (CertifiedObjective::Truecost, texts(&["3/2", "inf", "0"])),
            (
                CertifiedObjective::Discounted("9/10".parse().unwrap()),
                texts(&["-1", "a \"b\"\\\n\u{7f}é"]),
            ),
            (CertifiedObjective::Reach, texts(&[])),
            (CertifiedObjective::Deterministic, texts(&["0x1f/3"])),
        ];
        for (objective, values) in cases {
            let policy: Vec<Option<usize>> = (0..values.len())
                .map(|x| (x % 2 == 0).then_some(x * 7))
                .collect();
            assert_eq!(
                write(&objective, &record(), values.clone(), &policy),
                by_serde(&objective, &record(), &values, &policy)
            );
        }
    }

    #[test]
    fn values_over_a_denominator_are_written_as_their_texts() {
        let two = BigInt::from(2);
        let long: BigInt = num_traits::pow(two.clone(), 2000) + BigInt::from(12345);
        for d in [BigInt::from(1), BigInt::from(6), long.clone() * 3] {
            let numerators: Vec<Option<BigInt>> = (0..200i64)
                .map(|x| match x % 5 {
                    0 => None,
                    1 => Some(BigInt::from(0)),
                    2 => Some(-&long * BigInt::from(x)),
                    _ => Some(BigInt::from(x) + &d * BigInt::from(x)),
                })
                .collect();
            let refs: Vec<Option<&BigInt>> = numerators.iter().map(Option::as_ref).collect();
            let texts: Vec<String> = numerators
                .iter()
                .map(|k| match k {
                    None => "inf".into(),
                    Some(k) if d == BigInt::from(1) || k == &BigInt::from(0) => expected_integer(k),
                    Some(k) => format!("{}/{}", expected_integer(k), expected_integer(&d)),
                })
                .collect();
            let policy = vec![Some(1); 200];
            let objective = CertifiedObjective::Truecost;
            let expected = by_serde(&objective, &record(), &texts, &policy);
            assert_eq!(
                write_over(&objective, &record(), &refs, &d, &policy),
                expected
            );
            // In batches of one value, of a few, and of all.
            let values = Values {
                numerators: &refs,
                denominator: &d,
            };
            for batch in [1, 3000, 40_000, usize::MAX] {
                let mut out = Vec::new();
                values
                    .write(&mut out, &objective, &record(), &policy, batch)
                    .unwrap();
                assert_eq!(String::from_utf8(out).unwrap(), expected, "batch {batch}");
            }
        }
        let empty = write_over(
            &CertifiedObjective::Truecost,
            &record(),
            &[],
            &BigInt::from(1),
            &[],
        );
        assert_eq!(
            empty,
            by_serde(&CertifiedObjective::Truecost, &record(), &[], &[])
        );
    }
}

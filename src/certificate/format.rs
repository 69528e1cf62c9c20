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
//!   `truecost-canonical-mdp/1`).
//! * `values`: one exact number per state, in state order: `"p/q"` or `"p"` (an optional `-`,
//!   decimal digits, a positive denominator), or `"inf"` (truecost, deterministic: no policy
//!   reaches a goal with probability 1).
//! * `policy`: per state, the index of the chosen action in the state's action list, or `null`
//!   (goals, terminal states, `inf` states; for reach, the states of probability 0).

use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use serde_json::{json, Map, Value};

use crate::value::Rational;

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
    let alpha = match objective {
        CertifiedObjective::Discounted(a) => json!(a.to_string()),
        _ => Value::Null,
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
    let mut s = serde_json::to_string(&v).expect("serialisable");
    s.push('\n');
    s
}

/// A certificate's `problem` record as JSON (every kind has the same).
pub(super) fn problem_json(p: &ProblemRecord) -> Value {
    json!({
        "source": p.source,
        "name": p.name,
        "gamma": p.gamma,
        "noise": p.noise,
        "step_cost": p.step_cost,
        "sha256": p.sha256,
        "sha256_of": p.sha256_of,
    })
}

/// An exact number `-?digits(/digits)?` with a positive denominator, kept as written (not
/// reduced).
pub fn parse_exact(text: &str) -> Option<Rational> {
    let (num, den) = match text.split_once('/') {
        Some((n, d)) => (n, Some(d)),
        None => (text, None),
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let unsigned = num.strip_prefix('-').unwrap_or(num);
    if !digits(unsigned) || den.is_some_and(|d| !digits(d)) {
        return None;
    }
    let n: BigInt = num.parse().ok()?;
    let d: BigInt = match den {
        Some(d) => d.parse().ok()?,
        None => BigInt::from(1),
    };
    if d.is_zero() || d.is_negative() {
        return None;
    }
    // Not reduced: every comparison the checker makes is by cross-multiplication, and a gcd
    // per value of ten thousand digits would dominate the check.
    Some(Rational::new_raw(n, d))
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
            let a = parse_exact(&a).ok_or_else(|| {
                format!(
                    "\"alpha\" {} is not an exact number p/q",
                    crate::echo::echo(&a)
                )
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
            Some(s) => parse_exact(s).map(Some).ok_or_else(|| {
                format!(
                    "value of state {x}: {} is not \"p/q\", \"p\" or \"inf\"",
                    crate::echo::echo(s)
                )
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
    use super::parse_exact;

    #[test]
    fn exact_numbers_are_integers_or_fractions_with_positive_denominators() {
        let r = |s: &str| parse_exact(s).map(|q| (q.numer().to_string(), q.denom().to_string()));
        assert_eq!(r("3/2"), Some(("3".into(), "2".into())));
        assert_eq!(r("6/4"), Some(("6".into(), "4".into())));
        assert_eq!(r("-7"), Some(("-7".into(), "1".into())));
        assert_eq!(parse_exact("6/4"), parse_exact("3/2"));
        for bad in [
            "", "-", "1/", "/2", "1/0", "1/-2", "+1", "1.5", "1e3", " 1", "inf", "1/2/3",
        ] {
            assert_eq!(parse_exact(bad), None, "{bad:?}");
        }
    }
}

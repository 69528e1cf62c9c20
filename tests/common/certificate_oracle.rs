//! An independent judge of certificates (`truecost-certificate/1`) of a [`Tiny`] model: read
//! with `serde_json` and a number reader of its own, every claim compared with the brute-force
//! optima of [`super::tiny`] (nothing from the checker or the solvers). The certificate fuzzer
//! asks it about every certificate `check` accepts.

use num_bigint::{BigInt, BigUint};
use num_traits::{One, Signed, Zero};
use serde_json::{Map, Value};
use sha2::{Digest, Sha256};

use super::tiny::{Policy, Tiny};
use super::Q;

/// A natural number as certificates spell one: decimal digits, or `0x` and lowercase
/// hexadecimal digits, the first not `0`.
fn natural(text: &str) -> Option<BigUint> {
    if let Some(hex) = text.strip_prefix("0x") {
        let ok = !hex.is_empty()
            && !hex.starts_with('0')
            && hex
                .bytes()
                .all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b));
        return ok.then(|| BigUint::parse_bytes(hex.as_bytes(), 16))?;
    }
    let ok = !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit());
    ok.then(|| BigUint::parse_bytes(text.as_bytes(), 10))?
}

/// An exact number as certificates spell one: an optional `-`, a natural, and optionally `/`
/// and a positive natural.
pub fn exact(text: &str) -> Option<Q> {
    let (num, den) = match text.split_once('/') {
        Some((n, d)) => (n, Some(d)),
        None => (text, None),
    };
    let (negative, magnitude) = match num.strip_prefix('-') {
        Some(m) => (true, m),
        None => (false, num),
    };
    let mut n = BigInt::from(natural(magnitude)?);
    if negative {
        n = -n;
    }
    let d = match den {
        Some(d) => BigInt::from(natural(d)?),
        None => BigInt::one(),
    };
    (!d.is_zero()).then(|| Q::new(n, d))
}

/// The lowercase hexadecimal SHA-256 of `bytes`.
pub fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

type Verdict = Result<(), String>;

fn object<'a>(
    v: &'a Value,
    what: &str,
    allowed: &[&str],
) -> Result<&'a Map<String, Value>, String> {
    let map = v.as_object().ok_or(format!("{what} is no object"))?;
    match map.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(format!("{what} has the unknown field {k:?}")),
        None => Ok(map),
    }
}

fn text<'a>(map: &'a Map<String, Value>, key: &str) -> Result<&'a str, String> {
    map.get(key)
        .and_then(Value::as_str)
        .ok_or(format!("{key:?} is no string"))
}

fn number(v: &Value, what: &str) -> Result<Q, String> {
    v.as_str()
        .and_then(exact)
        .ok_or(format!("{what} is no exact number"))
}

fn list<'a>(
    v: Option<&'a Value>,
    what: &str,
    len: Option<usize>,
) -> Result<&'a Vec<Value>, String> {
    let l = v
        .and_then(Value::as_array)
        .ok_or(format!("{what} is no list"))?;
    match len {
        Some(n) if l.len() != n => Err(format!("{what} has {} entries, not {n}", l.len())),
        _ => Ok(l),
    }
}

/// The policy entries: `null` or an action index of the state.
fn policy(model: &Tiny, v: Option<&Value>) -> Result<Policy, String> {
    list(v, "policy", Some(model.states()))?
        .iter()
        .enumerate()
        .map(|(x, p)| match p {
            Value::Null => Ok(None),
            p => p
                .as_u64()
                .map(|i| i as usize)
                .filter(|&i| i < model.actions[x].len())
                .map(Some)
                .ok_or(format!("policy of state {x} is {p}")),
        })
        .collect()
}

fn same<T: PartialEq + std::fmt::Debug>(what: &str, got: T, want: T) -> Verdict {
    if got == want {
        Ok(())
    } else {
        Err(format!("{what}: {got:?}, the oracle's {want:?}"))
    }
}

/// Whether `cert` (text) is a valid certificate of `model`, whose problem file has the bytes
/// `file`: `Err` says which claim is false.
pub fn judge(model: &Tiny, file: &[u8], cert: &str) -> Verdict {
    let v: Value = serde_json::from_str(cert).map_err(|e| format!("not JSON: {e}"))?;
    let top = v.as_object().ok_or("no object")?;
    same("format", text(top, "format")?, "truecost-certificate/1")?;
    let problem = object(
        top.get("problem").ok_or("no problem")?,
        "problem",
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
    same("source", text(problem, "source")?, "file")?;
    same("sha256_of", text(problem, "sha256_of")?, "file bytes")?;
    same("sha256", text(problem, "sha256")?.to_string(), sha256(file))?;
    text(problem, "name")?;
    same(
        "states",
        top.get("states").and_then(Value::as_u64),
        Some(model.states() as u64),
    )?;
    match text(top, "objective")? {
        "discount" => discount(model, &v),
        objective => solved(model, &v, objective),
    }
}

/// A certificate of `solve --certificate`.
fn solved(model: &Tiny, v: &Value, objective: &str) -> Verdict {
    let top = object(
        v,
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
    let n = model.states();
    let values = list(top.get("values"), "values", Some(n))?;
    let pi = policy(model, top.get("policy"))?;
    let alpha = match top.get("alpha") {
        None | Some(Value::Null) => None,
        Some(a) => Some(number(a, "alpha")?),
    };
    if (objective == "discounted") != alpha.is_some() {
        return Err(format!("objective {objective:?} with alpha {alpha:?}"));
    }
    match objective {
        "truecost" | "deterministic" => {
            let branching = model
                .actions
                .iter()
                .flatten()
                .any(|a| a.outcomes.len() != 1);
            if objective == "deterministic" && branching {
                return Err("deterministic, but an action has several outcomes".into());
            }
            let got: Vec<Option<Q>> = values
                .iter()
                .map(|s| match s.as_str() {
                    Some("inf") => Ok(None),
                    _ => number(s, "a value").map(Some),
                })
                .collect::<Result<_, _>>()?;
            let optimum = model.truecost_optimum();
            same("values", &got, &optimum)?;
            for x in 0..n {
                if (model.goals[x] || optimum[x].is_none()) && pi[x].is_some() {
                    return Err(format!("policy at state {x}, a goal or of value inf"));
                }
            }
            let of_policy = model.truecost_of(&pi);
            for x in (0..n).filter(|&x| optimum[x].is_some()) {
                same(
                    &format!("the policy's value at {x}"),
                    &of_policy[x],
                    &optimum[x],
                )?;
            }
            Ok(())
        }
        "discounted" => {
            let alpha = alpha.expect("given");
            if !(alpha.is_positive() && alpha < Q::one()) {
                return Err(format!("alpha {alpha}"));
            }
            let got: Vec<Q> = values
                .iter()
                .map(|s| number(s, "a value"))
                .collect::<Result<_, _>>()?;
            same("values", &got, &model.discounted_optimum(&alpha))?;
            if let Some(x) = (0..n).find(|&x| model.terminal(x) && pi[x].is_some()) {
                return Err(format!("policy at the terminal state {x}"));
            }
            let of_policy = model
                .discounted_of(&pi, &alpha)
                .ok_or("the policy skips a state")?;
            same("the policy's values", &of_policy, &got)
        }
        "reach" => {
            let got: Vec<Q> = values
                .iter()
                .map(|s| number(s, "a value"))
                .collect::<Result<_, _>>()?;
            same("values", &got, &model.reach_optimum())?;
            if let Some(x) =
                (0..n).find(|&x| (model.goals[x] || got[x].is_zero()) && pi[x].is_some())
            {
                return Err(format!("policy at state {x}, a goal or of value 0"));
            }
            same("the policy's values", &model.reach_of(&pi), &got)
        }
        other => Err(format!("objective {other:?}")),
    }
}

/// `p(α)`, coefficients constant first.
fn at(p: &[Q], alpha: &Q) -> Q {
    p.iter().rev().fold(Q::zero(), |s, c| s * alpha + c)
}

fn polynomial(v: Option<&Value>, what: &str) -> Result<Vec<Q>, String> {
    list(v, what, None)?
        .iter()
        .map(|c| number(c, what))
        .collect()
}

/// Per state the listed actions (increasing indices of the state's actions).
fn sets(model: &Tiny, v: Option<&Value>, what: &str) -> Result<Vec<Vec<usize>>, String> {
    list(v, what, Some(model.states()))?
        .iter()
        .enumerate()
        .map(|(x, s)| -> Result<Vec<usize>, String> {
            let l: Vec<usize> = list(Some(s), what, None)?
                .iter()
                .map(|a| a.as_u64().map(|a| a as usize).ok_or(format!("{what}: {a}")))
                .collect::<Result<_, _>>()?;
            if l.windows(2).any(|w| w[0] >= w[1]) || l.iter().any(|&a| a >= model.actions[x].len())
            {
                return Err(format!("{what}, state {x}: {l:?}"));
            }
            Ok(l)
        })
        .collect()
}

/// The optimal actions of every state at `alpha`, by the oracle.
fn optimal_sets(model: &Tiny, alpha: &Q) -> (Vec<Q>, Vec<Vec<usize>>) {
    let v = model.discounted_optimum(alpha);
    let sets = (0..model.states())
        .map(|x| {
            if model.terminal(x) {
                return Vec::new();
            }
            (0..model.actions[x].len())
                .filter(|&a| model.q_discounted(x, a, alpha, &v) == v[x])
                .collect()
        })
        .collect();
    (v, sets)
}

/// A certificate of `discount --certificate`: at every interval's sample and three more points
/// strictly inside it, the values are the oracle's optimum and the listed optimal actions its
/// optimal actions; a rational breakpoint's optimal actions are the oracle's there, an
/// irrational one's polynomial changes sign over its bracket, and the optimal actions change at
/// every breakpoint.
fn discount(model: &Tiny, v: &Value) -> Verdict {
    let top = object(
        v,
        "the certificate",
        &[
            "format",
            "objective",
            "problem",
            "states",
            "breakpoints",
            "intervals",
        ],
    )?;
    let n = model.states();
    let breakpoints = list(top.get("breakpoints"), "breakpoints", None)?;
    let intervals = list(
        top.get("intervals"),
        "intervals",
        Some(breakpoints.len() + 1),
    )?;
    // Brackets (lo, hi] and the optimal sets at rational breakpoints.
    let mut brackets: Vec<(Q, Q)> = Vec::new();
    let mut at_points: Vec<Option<Vec<Vec<usize>>>> = Vec::new();
    for (k, b) in breakpoints.iter().enumerate() {
        let m = object(b, "a breakpoint", &["polynomial", "lo", "hi", "optimal"])?;
        let p = polynomial(m.get("polynomial"), "polynomial")?;
        let lo = number(m.get("lo").unwrap_or(&Value::Null), "lo")?;
        let hi = number(m.get("hi").unwrap_or(&Value::Null), "hi")?;
        let listed = sets(model, m.get("optimal"), "breakpoint optimal")?;
        if lo == hi {
            if !(lo.is_positive() && lo < Q::one() && at(&p, &lo).is_zero()) {
                return Err(format!("breakpoint {k}: {lo} is not a root in (0, 1)"));
            }
            same(
                &format!("breakpoint {k}'s optimal actions"),
                &listed,
                &optimal_sets(model, &lo).1,
            )?;
            at_points.push(Some(listed));
        } else {
            if lo.is_negative() || hi > Q::one() || lo > hi || at(&p, &lo) * at(&p, &hi) > Q::zero()
            {
                return Err(format!("breakpoint {k}: bracket ({lo}, {hi}] of {p:?}"));
            }
            at_points.push(None);
        }
        if let Some((_, last)) = brackets.last() {
            if last >= &lo {
                return Err(format!("breakpoint {k} not after the previous one"));
            }
        }
        brackets.push((lo, hi));
    }
    let mut interval_sets: Vec<Vec<Vec<usize>>> = Vec::new();
    for (i, t) in intervals.iter().enumerate() {
        let m = object(
            t,
            "an interval",
            &["sample", "denominators", "values", "policy", "optimal"],
        )?;
        let low = if i == 0 {
            Q::zero()
        } else {
            brackets[i - 1].1.clone()
        };
        let high = if i == breakpoints.len() {
            Q::one()
        } else {
            brackets[i].0.clone()
        };
        let sample = number(m.get("sample").unwrap_or(&Value::Null), "sample")?;
        if !(low < sample && sample < high) {
            return Err(format!(
                "interval {i}: sample {sample} outside ({low}, {high})"
            ));
        }
        let denominators: Vec<Vec<Q>> = list(m.get("denominators"), "denominators", None)?
            .iter()
            .map(|d| polynomial(Some(d), "a denominator"))
            .collect::<Result<_, _>>()?;
        let values: Vec<Option<(usize, Vec<Q>)>> = list(m.get("values"), "values", Some(n))?
            .iter()
            .map(|v| -> Result<Option<(usize, Vec<Q>)>, String> {
                if v.is_null() {
                    return Ok(None);
                }
                let o = object(v, "a value", &["denominator", "numerator"])?;
                let d = o
                    .get("denominator")
                    .and_then(Value::as_u64)
                    .map(|d| d as usize)
                    .filter(|&d| d < denominators.len())
                    .ok_or("a denominator index")?;
                Ok(Some((d, polynomial(o.get("numerator"), "a numerator")?)))
            })
            .collect::<Result<_, _>>()?;
        let pi = policy(model, m.get("policy"))?;
        let listed = sets(model, m.get("optimal"), "interval optimal")?;
        let width = &high - &low;
        let eighth = Q::new(1.into(), 8.into());
        let points = [
            sample,
            &low + &width * &eighth,
            &low + &width / Q::from_integer(2.into()),
            &high - &width * &eighth,
        ];
        for alpha in &points {
            let (optimum, optimal) = optimal_sets(model, alpha);
            same(
                &format!("interval {i}'s optimal actions at {alpha}"),
                &listed,
                &optimal,
            )?;
            for x in 0..n {
                let value = match &values[x] {
                    None if model.terminal(x) && pi[x].is_none() => continue,
                    None => return Err(format!("interval {i}: no value at {x}")),
                    Some(_) if model.terminal(x) => {
                        return Err(format!("interval {i}: a value at the terminal state {x}"))
                    }
                    Some((d, numerator)) => {
                        let d = at(&denominators[*d], alpha);
                        if d.is_zero() {
                            return Err(format!("interval {i}: denominator 0 at {alpha}"));
                        }
                        at(numerator, alpha) / d
                    }
                };
                same(
                    &format!("interval {i}, state {x} at {alpha}"),
                    &value,
                    &optimum[x],
                )?;
                if !pi[x].is_some_and(|a| listed[x].contains(&a)) {
                    return Err(format!("interval {i}: policy {:?} at {x}", pi[x]));
                }
            }
        }
        interval_sets.push(listed);
    }
    for (k, point) in at_points.iter().enumerate() {
        let change = interval_sets[k] != interval_sets[k + 1]
            || point.as_ref().is_some_and(|p| p != &interval_sets[k]);
        if point.is_some() && !change {
            return Err(format!("breakpoint {k}: no change of the optimal actions"));
        }
        if point.is_none() && interval_sets[k] == interval_sets[k + 1] {
            // The set at an irrational breakpoint is not computed here: its listing must differ.
            let listed = sets(model, breakpoints[k].get("optimal"), "breakpoint optimal")?;
            if listed == interval_sets[k] {
                return Err(format!("breakpoint {k}: no change of the optimal actions"));
            }
        }
    }
    Ok(())
}

//! Discount certificates (`objective` `discount`): the breakpoints of `truecost discount` and
//! the discount-optimal policies between them, checked exactly with Sturm sequences
//! ([`super::sturm`]). The checker uses the model as plain data ([`Mdp`]), big rationals and
//! SHA-256, nothing from the solver or `crate::algebra`.
//!
//! **The objective.** `discount` maximises the expected discounted reward
//! `V_α(x) = max_a [r(x, a) + α Σ_y p(y | x, a) V_α(y)]`, `V_α = 0` at terminal states, for
//! every `α ∈ (0, 1)`: the rewards are the model's (the file's own, Gymnasium's, or the
//! negated stage costs), the same as `solve --objective discounted`.
//!
//! **What the certificate gives.** Breakpoints `β_1 < … < β_k` in `(0, 1)`, each a polynomial
//! `m` with rational coefficients and a rational bracket `(lo, hi]` holding exactly one root of
//! `m` (or `lo = hi = β` for a rational breakpoint); for each of the `k + 1` open intervals
//! `(β_i, β_{i+1})` (`β_0 = 0`, `β_{k+1} = 1`): a rational sample point, a witness policy `π`,
//! its values `V_x = N_x / D_x` as quotients of polynomials in `α` and the optimal actions of
//! every state; for each breakpoint, the optimal actions at the point.
//!
//! Write `A_{x,a}` for the numerator of `Q_a − V_x = r(x, a) + α Σ_y p(y | x, a) V_y − V_x`
//! over the product `E` of the distinct denominators it involves (a polynomial).
//!
//! **Conditions** (in the order checked; the first failure is reported):
//!
//! 1. **problem** — the SHA-256 and the number of states are those of the re-read problem.
//! 2. **shape** — `k + 1` intervals for `k` breakpoints, each listing every state.
//! 3. **polynomial** — each breakpoint's `m` is non-constant and square-free (its Sturm chain
//!    ends in a non-zero constant).
//! 4. **isolating** — `0 ≤ lo < hi ≤ 1` and `m` has exactly one root in `(lo, hi]` (Sturm), not
//!    at 1; or `0 < lo = hi < 1` and `m(lo) = 0`.
//! 5. **order** — each bracket ends strictly below the next one's start: the breakpoints
//!    increase.
//! 6. **sample** — per interval, the sample lies strictly between the brackets of its ends.
//! 7. **denominator** — every `D` has no root in the open interval and `D(sample) > 0`, so
//!    `D > 0` on it.
//! 8. **goal** — at terminal states no value, no policy, no optimal action (`V = 0`); every
//!    other state has `V_x = N_x / D_x` over a listed denominator.
//! 9. **policy** — `π(x)` indexes `x`'s actions and is among the listed optimal actions; the
//!    listed actions are valid indices in increasing order.
//! 10. **evaluation** — `A_{x,π(x)} = 0` as a polynomial at every non-terminal `x`.
//! 11. **optimality** — for every non-terminal `x` and action `a`: `A_{x,a} = 0` as a
//!     polynomial and `a` is listed as optimal, or `a` is not listed and `A_{x,a}` is negative
//!     on the whole open interval (its square-free part has no root there by Sturm — checked
//!     on the bracket of each end and between them — and `A_{x,a}(sample) < 0`).
//! 12. **continuity** — at each breakpoint no denominator of the interval on its left vanishes.
//! 13. **ties** — at each breakpoint `β`, the listed optimal actions of every state are exactly
//!     the `a` with `A_{x,a}(β) = 0` for the interval on its left (decided exactly: `β` is a
//!     root of `gcd(A, m)` in the bracket, the one root of `m` there).
//! 14. **change** — at each breakpoint the optimal actions of its two intervals differ, or
//!     those at the point differ from theirs.
//!
//! **Why these suffice.** On an interval, 7 makes each `V_x(α)` a well-defined function;
//! 8 and 10 say `V = r_π + α P_π V` with `V = 0` at terminal states for every `α` in it, whose
//! unique solution (`I − α P_π` is invertible for `α < 1`) is `π`'s value; 11 gives
//! `Q_a(α) ≤ V(α)` for every action (`E > 0` there by 7), so `V(α)` is the fixed point of the
//! Bellman optimality operator, the optimal value `V*_α`, and the optimal actions at every
//! `α` of the interval are exactly the listed ones (`Q_a = V` identically for them, `< V`
//! everywhere for the others). The optimal sets are therefore constant on each interval, so
//! every point where they change is one of the breakpoints (the listing is complete). At a
//! breakpoint `β`: `V*` is continuous in `α` on `(0, 1)`, so `V*_β` is the left interval's `V`
//! at `β` (12: it is defined there), and the optimal actions at `β` are those with
//! `Q_a(β) = V*_β`, i.e. `A(β) = 0` (13). By 14 the optimal set at `β` differs from that on one
//! side of it, so every listed breakpoint is a point where the optimal set changes (the
//! listing is sound). 5 and 6 make the brackets and intervals ordered and disjoint.
//!
//! Not certified: the success probabilities and truecosts `discount` prints for each interval
//! and breakpoint (and the failure set read off them on deterministic problems); they are
//! computed from the optimal sets this certificate does certify.
//!
//! Whether a polynomial `S` (square-free part of `A` or `D`) has a root in the open interval
//! `(β_i, β_{i+1})`: the interval is `(β_i, hi_i] ∪ (hi_i, lo_{i+1}] ∪ (lo_{i+1}, β_{i+1})`
//! (the outer parts empty at rational ends). The middle part is counted by Sturm (a rational
//! right end that is a root of `S` is taken off); in each bracket, `S` must have no root or
//! exactly one that is the breakpoint itself (a root of `gcd(S, m)` in the bracket), so none
//! on the interval's side of it. A bracket too wide for that is refused: the writer narrows it.
//! Before any of this, Descartes' rule of signs on `(lo_i, hi_{i+1})`, which holds the open
//! interval, settles the common case: a bound of 0 means no root there at all. The counts
//! themselves are [`Roots::count`] (Descartes' rule where conclusive, Sturm's theorem where
//! not), and `p(β) = 0` is decided without a gcd when Descartes' rule finds no root of `p` in
//! the bracket.
//!
//! The advantage numerators are computed in integers: each listed polynomial is written
//! `P / L` with `P` integral and `L > 0`, and `A_{x,a}` is multiplied by the (positive)
//! product of the `L` of its denominators and common denominator of its scalars, which
//! changes neither its roots nor its signs.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Zero};
use serde_json::{json, Value};

use super::check::{Checked, Identity};
use super::format::{
    field, object, parse_exact, problem_json, problem_record, string, ProblemRecord, FORMAT,
};
use super::mdp::{Mdp, CANONICAL_FORMAT};
use super::sha256::sha256_hex;
use super::sturm::{self, sign_at, Roots, Sturm};
use crate::value::Rational;

/// The `objective` of a discount certificate.
pub const DISCOUNT: &str = "discount";

/// Every condition of a discount certificate and its statement, in the order checked (module
/// docs give why they suffice).
pub const DISCOUNT_CONDITIONS: &[(&str, &str)] = &[
    (
        "problem",
        "the SHA-256 and the number of states are those of the re-read problem",
    ),
    (
        "shape",
        "one interval more than breakpoints, each listing every state; polynomials within the checker's bounds",
    ),
    (
        "polynomial",
        "each breakpoint's polynomial m is non-constant and square-free (Sturm chain ends in a constant)",
    ),
    (
        "isolating",
        "m has exactly one root in the bracket (lo, hi] within (0, 1) (Sturm), or lo = hi is a root",
    ),
    ("order", "each bracket ends below the next one's start"),
    (
        "sample",
        "each interval's sample lies strictly between the brackets of its ends",
    ),
    (
        "denominator",
        "every value denominator D has no root in the open interval (Sturm) and D(sample) > 0",
    ),
    (
        "goal",
        "terminal states have V = 0, pi = null and no optimal action; the others a value N/D",
    ),
    (
        "policy",
        "pi(x) indexes x's actions and is listed as optimal; listed actions valid and increasing",
    ),
    (
        "evaluation",
        "r(x, pi(x)) + alpha sum_y p V_y - V_x = 0 as a rational function (V is pi's value)",
    ),
    (
        "optimality",
        "for every action: Q_a - V_x = 0 identically and a listed optimal, or a not listed and Q_a - V_x < 0 on the whole interval (Sturm)",
    ),
    (
        "continuity",
        "no denominator of the interval left of a breakpoint vanishes at it",
    ),
    (
        "ties",
        "the optimal actions listed at a breakpoint are exactly those whose Q_a - V_x (left interval) vanishes there",
    ),
    (
        "change",
        "at each breakpoint the optimal actions change: its intervals' sets differ, or the point's differs from theirs",
    ),
];

/// A breakpoint as the certificate states it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BreakpointRecord {
    /// The polynomial `m`, constant coefficient first.
    pub polynomial: Vec<Rational>,
    /// The bracket's lower end (exclusive unless `lo = hi`).
    pub lo: Rational,
    /// The bracket's upper end (inclusive).
    pub hi: Rational,
    /// Per state, the optimal actions at the breakpoint (indices in the state's action list).
    pub optimal: Vec<Vec<u64>>,
}

/// A state's value on an interval: `numerator / denominators[denominator]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ValueRecord {
    /// The index of the denominator in [`IntervalRecord::denominators`].
    pub denominator: usize,
    /// The numerator, constant coefficient first.
    pub numerator: Vec<Rational>,
}

/// An open interval between consecutive breakpoints, as the certificate states it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IntervalRecord {
    /// A rational inside.
    pub sample: Rational,
    /// The distinct value denominators, constant coefficient first.
    pub denominators: Vec<Vec<Rational>>,
    /// Per state its value (`None` at terminal states).
    pub values: Vec<Option<ValueRecord>>,
    /// Per state the witness policy's action index (`None` at terminal states).
    pub policy: Vec<Option<u64>>,
    /// Per state the optimal actions on the interval.
    pub optimal: Vec<Vec<u64>>,
}

/// A discount certificate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DiscountCertificate {
    /// The problem.
    pub problem: ProblemRecord,
    /// The number of states.
    pub states: usize,
    /// The breakpoints, increasing.
    pub breakpoints: Vec<BreakpointRecord>,
    /// The intervals, increasing (one more than the breakpoints).
    pub intervals: Vec<IntervalRecord>,
}

fn texts(p: &[Rational]) -> Vec<String> {
    p.iter().map(ToString::to_string).collect()
}

/// Writes a discount certificate (JSON, one line and a newline); [`parse_discount`] reads it
/// back.
///
/// ```
/// use truecost::certificate::discount::{parse_discount, write_discount, DiscountCertificate};
/// use truecost::certificate::ProblemRecord;
/// let c = DiscountCertificate {
///     problem: ProblemRecord { source: "env".into(), name: "taxi".into(), gamma: None,
///         noise: None, step_cost: None, sha256: "0".repeat(64),
///         sha256_of: "truecost-canonical-mdp/1".into(), goal_label: None, cost_reward: None },
///     states: 0, breakpoints: vec![], intervals: vec![],
/// };
/// let text = write_discount(&c);
/// assert!(text.contains(r#""objective":"discount""#));
/// assert_eq!(parse_discount(&text).unwrap(), c);
/// ```
pub fn write_discount(c: &DiscountCertificate) -> String {
    let breakpoints: Vec<Value> = c
        .breakpoints
        .iter()
        .map(|b| {
            json!({"polynomial": texts(&b.polynomial), "lo": b.lo.to_string(),
                   "hi": b.hi.to_string(), "optimal": b.optimal})
        })
        .collect();
    let intervals: Vec<Value> = c
        .intervals
        .iter()
        .map(|i| {
            let values: Vec<Value> = i
                .values
                .iter()
                .map(|v| match v {
                    None => Value::Null,
                    Some(v) => json!({"denominator": v.denominator,
                                      "numerator": texts(&v.numerator)}),
                })
                .collect();
            let dens: Vec<Vec<String>> = i.denominators.iter().map(|d| texts(d)).collect();
            json!({"sample": i.sample.to_string(), "denominators": dens, "values": values,
                   "policy": i.policy, "optimal": i.optimal})
        })
        .collect();
    let v = json!({
        "format": FORMAT,
        "objective": DISCOUNT,
        "problem": problem_json(&c.problem),
        "states": c.states,
        "breakpoints": breakpoints,
        "intervals": intervals,
    });
    let mut s = serde_json::to_string(&v).expect("serialisable");
    s.push('\n');
    s
}

fn list<'a>(v: &'a Value, what: &str) -> Result<&'a Vec<Value>, String> {
    v.as_array().ok_or_else(|| format!("{what} is not a list"))
}

fn exact(v: &Value, what: &str) -> Result<Rational, String> {
    let text = v.as_str();
    text.and_then(parse_exact)
        .map(|r| {
            // In lowest terms; an integer already is (a gcd of millions of bits is slow).
            if r.denom().is_one() {
                r
            } else {
                Rational::new(r.numer().clone(), r.denom().clone())
            }
        })
        .ok_or_else(|| match text.and_then(super::format::too_long) {
            Some(why) => format!("{what} is {why}"),
            None => format!("{what} is not an exact number \"p/q\""),
        })
}

/// The most coefficients of a polynomial in a discount certificate: the analysis' values have
/// degree at most 256 (stochastic) or 200 (deterministic chains), so this leaves room, and a
/// Sturm chain of this degree stays affordable.
pub const MAX_COEFFICIENTS: usize = 513;

/// The most coefficients, in all, of the denominators one advantage numerator `A_{x,a}`
/// multiplies (module docs); above it the certificate is refused.
pub const MAX_ADVANTAGE_DEGREE: usize = 1024;

fn polynomial(v: &Value, what: &str) -> Result<Vec<Rational>, String> {
    let l = list(v, what)?;
    if l.len() > MAX_COEFFICIENTS {
        return Err(format!(
            "{what} has {} coefficients, more than the checker's bound {MAX_COEFFICIENTS}",
            l.len()
        ));
    }
    l.iter()
        .enumerate()
        .map(|(i, c)| exact(c, &format!("{what}, coefficient {i},")))
        .collect()
}

fn index(v: &Value, what: &str) -> Result<u64, String> {
    v.as_u64()
        .ok_or_else(|| format!("{what} is not an action index"))
}

fn optional_index(v: &Value, what: &str) -> Result<Option<u64>, String> {
    if v.is_null() {
        Ok(None)
    } else {
        index(v, what).map(Some)
    }
}

fn action_sets(v: &Value, what: &str) -> Result<Vec<Vec<u64>>, String> {
    list(v, what)?
        .iter()
        .enumerate()
        .map(|(x, s)| {
            let w = format!("{what}, state {x},");
            list(s, &w)?.iter().map(|a| index(a, &w)).collect()
        })
        .collect()
}

/// Reads a discount certificate (one line on error, naming the field).
///
/// ```
/// use truecost::certificate::discount::parse_discount;
/// let e = parse_discount(r#"{"format": "truecost-certificate/1", "objective": "discount", "x": 1}"#);
/// assert!(e.unwrap_err().contains("unknown field"));
/// ```
pub fn parse_discount(text: &str) -> Result<DiscountCertificate, String> {
    let v: Value =
        serde_json::from_str(text).map_err(|e| format!("the certificate is not JSON: {e}"))?;
    let top = object(
        &v,
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
    let format = string(top, "the certificate", "format")?;
    if format != FORMAT {
        return Err(format!(
            "the certificate's format is {}, not {FORMAT}",
            crate::echo::echo(&format)
        ));
    }
    if string(top, "the certificate", "objective")? != DISCOUNT {
        return Err(format!("the certificate's objective is not {DISCOUNT}"));
    }
    let problem = problem_record(field(top, "the certificate", "problem")?)?;
    let states = field(top, "the certificate", "states")?
        .as_u64()
        .and_then(|s| usize::try_from(s).ok())
        .ok_or("the certificate: \"states\" is not a non-negative integer")?;
    let breakpoints = list(
        field(top, "the certificate", "breakpoints")?,
        "\"breakpoints\"",
    )?
    .iter()
    .enumerate()
    .map(|(k, b)| {
        let what = format!("breakpoint {k}");
        let m = object(b, &what, &["polynomial", "lo", "hi", "optimal"])?;
        Ok(BreakpointRecord {
            polynomial: polynomial(
                field(m, &what, "polynomial")?,
                &format!("{what}: polynomial"),
            )?,
            lo: exact(field(m, &what, "lo")?, &format!("{what}: lo"))?,
            hi: exact(field(m, &what, "hi")?, &format!("{what}: hi"))?,
            optimal: action_sets(field(m, &what, "optimal")?, &format!("{what}: optimal"))?,
        })
    })
    .collect::<Result<Vec<_>, String>>()?;
    let intervals = list(field(top, "the certificate", "intervals")?, "\"intervals\"")?
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let what = format!("interval {i}");
            let m = object(
                t,
                &what,
                &["sample", "denominators", "values", "policy", "optimal"],
            )?;
            let denominators = list(field(m, &what, "denominators")?, &what)?
                .iter()
                .enumerate()
                .map(|(k, d)| polynomial(d, &format!("{what}: denominator {k}")))
                .collect::<Result<Vec<_>, _>>()?;
            let values = list(field(m, &what, "values")?, &what)?
                .iter()
                .enumerate()
                .map(|(x, v)| {
                    if v.is_null() {
                        return Ok(None);
                    }
                    let w = format!("{what}: value of state {x}");
                    let o = object(v, &w, &["denominator", "numerator"])?;
                    let denominator = field(o, &w, "denominator")?
                        .as_u64()
                        .and_then(|k| usize::try_from(k).ok())
                        .ok_or_else(|| format!("{w}: \"denominator\" is not an index"))?;
                    Ok(Some(ValueRecord {
                        denominator,
                        numerator: polynomial(field(o, &w, "numerator")?, &w)?,
                    }))
                })
                .collect::<Result<Vec<_>, String>>()?;
            let policy = list(field(m, &what, "policy")?, &what)?
                .iter()
                .enumerate()
                .map(|(x, a)| optional_index(a, &format!("{what}: policy of state {x}")))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(IntervalRecord {
                sample: exact(field(m, &what, "sample")?, &format!("{what}: sample"))?,
                denominators,
                values,
                policy,
                optimal: action_sets(field(m, &what, "optimal")?, &format!("{what}: optimal"))?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(DiscountCertificate {
        problem,
        states,
        breakpoints,
        intervals,
    })
}

/// The first violated condition of a discount certificate, with where it fails.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct DiscountRejection {
    /// The condition's name (one of [`DISCOUNT_CONDITIONS`]).
    pub condition: &'static str,
    /// The interval where it fails, if any.
    pub interval: Option<usize>,
    /// The breakpoint where it fails, if any (also for an interval whose end's bracket is
    /// too wide).
    pub breakpoint: Option<usize>,
    /// The state, if any.
    pub state: Option<usize>,
    /// What fails, in one line.
    pub detail: String,
}

impl std::fmt::Display for DiscountRejection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut place = Vec::new();
        if let Some(i) = self.interval {
            place.push(format!("interval {i}"));
        }
        if let Some(k) = self.breakpoint {
            place.push(format!("breakpoint {k}"));
        }
        if let Some(x) = self.state {
            place.push(format!("state {x}"));
        }
        if !place.is_empty() {
            write!(f, "{}: ", place.join(", "))?;
        }
        write!(f, "condition {}: {}", self.condition, self.detail)
    }
}

/// What an accepted discount certificate established.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct DiscountAcceptance {
    /// States.
    pub states: usize,
    /// Actions in the model.
    pub actions: usize,
    /// Breakpoints.
    pub breakpoints: usize,
    /// Intervals.
    pub intervals: usize,
    /// Every condition, in the order checked, with its instances.
    pub conditions: Vec<Checked>,
}

/// A breakpoint's polynomial in integers with its Sturm chain and bracket.
struct Bracket {
    m: Vec<BigInt>,
    lo: Rational,
    hi: Rational,
}

impl Bracket {
    fn exact(&self) -> bool {
        self.lo == self.hi
    }

    /// Whether `p` vanishes at the breakpoint: `p(lo) = 0` at a rational one, else
    /// `gcd(p, m)` has a root in `(lo, hi]` (which can only be the one root of `m` there).
    fn vanishes(&self, p: &[BigInt]) -> bool {
        if p.is_empty() {
            return true;
        }
        if self.exact() {
            return sign_at(p, &self.lo) == Ordering::Equal;
        }
        // No root of `p` in the bracket at all (Descartes' rule of signs): it does not vanish.
        if sign_at(p, &self.hi) != Ordering::Equal
            && sturm::descartes_bound(p, &self.lo, &self.hi) == 0
        {
            return false;
        }
        let g = sturm::gcd(p, &self.m);
        sturm::degree(&g).is_some_and(|d| d > 0) && Roots::new(&g).count(&self.lo, &self.hi) > 0
    }
}

/// An end of an interval: 0, 1 or a breakpoint.
#[derive(Clone, Copy)]
enum End<'a> {
    Point(&'a Rational),
    Breakpoint(usize, &'a Bracket),
}

impl End<'_> {
    fn lo(&self) -> &Rational {
        match self {
            End::Point(r) => r,
            End::Breakpoint(_, b) => &b.lo,
        }
    }

    fn hi(&self) -> &Rational {
        match self {
            End::Point(r) => r,
            End::Breakpoint(_, b) => &b.hi,
        }
    }
}

/// Whether the polynomial `p` (not zero) has no root in the open interval between `left` and
/// `right` (module docs); `Err` names the breakpoint whose bracket is too wide, or none.
fn no_root_between(p: &[BigInt], left: End<'_>, right: End<'_>) -> Result<(), Option<usize>> {
    // No root from the left end's bracket to the right end's (Descartes' rule of signs): none
    // in the interval, which lies inside.
    if sturm::descartes_bound(p, left.lo(), right.hi()) == 0 {
        return Ok(());
    }
    // `p`'s distinct roots are those of its square-free part, and the two vanish together.
    let s = Roots::new(p);
    // In a bracket: no root, or the breakpoint only.
    let bracket_side = |end: End<'_>| -> Result<(), Option<usize>> {
        match end {
            End::Breakpoint(k, b) if !b.exact() => match s.count(&b.lo, &b.hi) {
                0 => Ok(()),
                1 if b.vanishes(p) => Ok(()),
                _ => Err(Some(k)),
            },
            _ => Ok(()),
        }
    };
    bracket_side(left)?;
    let (a, b) = (left.hi(), right.lo());
    let mut middle = s.count(a, b);
    let right_exact = match right {
        End::Point(_) => true,
        End::Breakpoint(_, br) => br.exact(),
    };
    if right_exact && sign_at(p, b) == Ordering::Equal {
        middle -= 1;
    }
    if middle > 0 {
        return Err(None);
    }
    bracket_side(right)
}

/// `p = P / L` with `P` integral and `L > 0` the least common denominator: `(P, L)`.
fn scaled_form(p: &[Rational]) -> (Vec<BigInt>, BigInt) {
    let l = p.iter().fold(BigInt::one(), |l, c| l.lcm(c.denom()));
    let q = sturm::trim(p.iter().map(|c| c.numer() * (&l / c.denom())).collect());
    (q, l)
}

/// The product of integer polynomials.
fn mul_int(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    if a.len() == 1 && a[0].is_one() {
        return b.to_vec();
    }
    if b.len() == 1 && b[0].is_one() {
        return a.to_vec();
    }
    let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// `Σ w · α^shift · f` over the terms, times the least common denominator of the `w` (a
/// positive integer): an integer polynomial with no trailing zero.
fn combine(terms: &[(Rational, usize, Vec<BigInt>)]) -> Vec<BigInt> {
    let l = terms
        .iter()
        .fold(BigInt::one(), |l, (w, _, _)| l.lcm(w.denom()));
    let mut acc: Vec<BigInt> = Vec::new();
    for (w, shift, f) in terms {
        if w.is_zero() || f.is_empty() {
            continue;
        }
        let w = w.numer() * (&l / w.denom());
        if acc.len() < f.len() + shift {
            acc.resize(f.len() + shift, BigInt::zero());
        }
        for (k, c) in f.iter().enumerate() {
            acc[k + shift] += &w * c;
        }
    }
    sturm::trim(acc)
}

struct Failure {
    condition: &'static str,
    interval: Option<usize>,
    breakpoint: Option<usize>,
    state: Option<usize>,
    detail: String,
}

fn fail(condition: &'static str, detail: String) -> Failure {
    Failure {
        condition,
        interval: None,
        breakpoint: None,
        state: None,
        detail,
    }
}

impl Failure {
    fn at_interval(mut self, i: usize) -> Failure {
        self.interval = Some(i);
        self
    }
    fn at_breakpoint(mut self, k: usize) -> Failure {
        self.breakpoint = Some(k);
        self
    }
    fn at_state(mut self, x: usize) -> Failure {
        self.state = Some(x);
        self
    }
}

impl From<Failure> for DiscountRejection {
    fn from(f: Failure) -> Self {
        DiscountRejection {
            condition: f.condition,
            interval: f.interval,
            breakpoint: f.breakpoint,
            state: f.state,
            detail: f.detail,
        }
    }
}

/// Counts per condition, reported in [`DISCOUNT_CONDITIONS`] order.
struct Tally(Vec<usize>);

impl Tally {
    fn add(&mut self, name: &str, n: usize) {
        let i = DISCOUNT_CONDITIONS
            .iter()
            .position(|(c, _)| *c == name)
            .expect("a listed condition");
        self.0[i] += n;
    }
}

/// Checks a discount certificate against the re-read model `mdp`, whose SHA-256 is taken as
/// `identity` says (module docs: the conditions and why they suffice). `Ok` lists every
/// condition with its instances; `Err` is the first violation.
///
/// ```
/// use truecost::certificate::discount::*;
/// use truecost::certificate::{sha256_hex, Identity, Mdp, MdpAction, ProblemRecord};
/// let q = |t: &str| -> truecost::value::Rational { t.parse().unwrap() };
/// // State 0 stays with reward 1 or ends the episode (state 1) with reward 3: by hand,
/// // 1/(1 − α) = 3 at α = 2/3; ending is optimal below, staying above.
/// let act = |reward: &str, to: usize| MdpAction { cost: q("1"), reward: q(reward), outcomes: vec![(to, q("1"))] };
/// let mdp = Mdp { goal: vec![false, true], terminal: vec![false, true],
///                 actions: vec![vec![act("1", 0), act("3", 1)], vec![]] };
/// let problem = ProblemRecord { source: "problem".into(), name: "hand".into(), gamma: None,
///     noise: None, step_cost: None, sha256: sha256_hex(mdp.canonical_text().as_bytes()),
///     sha256_of: "truecost-canonical-mdp/1".into(), goal_label: None, cost_reward: None };
/// let interval = |sample: &str, den: Vec<_>, num: Vec<_>, a: u64| IntervalRecord {
///     sample: q(sample), denominators: vec![den],
///     values: vec![Some(ValueRecord { denominator: 0, numerator: num }), None],
///     policy: vec![Some(a), None], optimal: vec![vec![a], vec![]] };
/// let mut c = DiscountCertificate { problem, states: 2,
///     breakpoints: vec![BreakpointRecord { polynomial: vec![q("-2"), q("3")], lo: q("1/2"),
///         hi: q("3/4"), optimal: vec![vec![0, 1], vec![]] }],
///     intervals: vec![interval("1/4", vec![q("1")], vec![q("3")], 1),
///                     interval("4/5", vec![q("1"), q("-1")], vec![q("1")], 0)] };
/// assert!(check_discount(&mdp, Identity::Canonical, &c).is_ok());
/// c.breakpoints[0].hi = q("13/20"); // (1/2, 13/20] holds no root of 3α − 2
/// let e = check_discount(&mdp, Identity::Canonical, &c).unwrap_err();
/// assert_eq!((e.condition, e.breakpoint), ("isolating", Some(0)));
/// ```
pub fn check_discount(
    mdp: &Mdp,
    identity: Identity<'_>,
    c: &DiscountCertificate,
) -> Result<DiscountAcceptance, DiscountRejection> {
    let mut tally = Tally(vec![0; DISCOUNT_CONDITIONS.len()]);
    run(mdp, identity, c, &mut tally).map_err(DiscountRejection::from)?;
    Ok(DiscountAcceptance {
        states: mdp.states(),
        actions: mdp.actions.iter().map(Vec::len).sum(),
        breakpoints: c.breakpoints.len(),
        intervals: c.intervals.len(),
        conditions: DISCOUNT_CONDITIONS
            .iter()
            .zip(&tally.0)
            .map(|((name, statement), &instances)| Checked {
                name,
                statement,
                instances,
            })
            .collect(),
    })
}

fn problem(mdp: &Mdp, identity: Identity<'_>, c: &DiscountCertificate) -> Result<(), Failure> {
    if let Some(why) = mdp.malformed() {
        return Err(fail("problem", why));
    }
    let (hash, of) = match identity {
        Identity::FileBytes(bytes) => (sha256_hex(bytes), "file bytes"),
        Identity::Canonical => (
            sha256_hex(mdp.canonical_text().as_bytes()),
            CANONICAL_FORMAT,
        ),
    };
    let record = &c.problem;
    if record.sha256_of != of || record.sha256 != hash {
        return Err(fail(
            "problem",
            format!(
                "the certificate's SHA-256 {} of {} is not the problem's {hash} of its {of}",
                crate::echo::echo(&record.sha256),
                crate::echo::echo(&record.sha256_of)
            ),
        ));
    }
    if c.states != mdp.states() {
        return Err(fail(
            "problem",
            format!(
                "the certificate has {} states, the problem {}",
                c.states,
                mdp.states()
            ),
        ));
    }
    Ok(())
}

fn shape(c: &DiscountCertificate) -> Result<(), Failure> {
    let n = c.states;
    if c.intervals.len() != c.breakpoints.len() + 1 {
        return Err(fail(
            "shape",
            format!(
                "{} breakpoints but {} intervals",
                c.breakpoints.len(),
                c.intervals.len()
            ),
        ));
    }
    for (k, b) in c.breakpoints.iter().enumerate() {
        if b.optimal.len() != n {
            return Err(fail("shape", format!("{} optimal sets", b.optimal.len())).at_breakpoint(k));
        }
    }
    for (i, t) in c.intervals.iter().enumerate() {
        let (v, p, o) = (t.values.len(), t.policy.len(), t.optimal.len());
        if v != n || p != n || o != n {
            return Err(fail(
                "shape",
                format!("{v} values, {p} policy entries and {o} optimal sets for {n} states"),
            )
            .at_interval(i));
        }
    }
    Ok(())
}

fn brackets(c: &DiscountCertificate, tally: &mut Tally) -> Result<Vec<Bracket>, Failure> {
    let (zero, one) = (Rational::zero(), Rational::one());
    let mut out: Vec<Bracket> = Vec::new();
    for (k, b) in c.breakpoints.iter().enumerate() {
        let m = sturm::primitive(scaled_form(&b.polynomial).0);
        let bad = |detail: String| fail("polynomial", detail).at_breakpoint(k);
        if sturm::degree(&m).unwrap_or(0) == 0 {
            return Err(bad("the polynomial is constant".into()));
        }
        let s = Sturm::new(&m);
        if !s.is_square_free() {
            return Err(bad("the polynomial has a repeated factor".into()));
        }
        let iso = |detail: String| fail("isolating", detail).at_breakpoint(k);
        if b.lo == b.hi {
            if !(zero < b.lo && b.lo < one) {
                return Err(iso(format!(
                    "the rational breakpoint {} is not in (0, 1)",
                    b.lo
                )));
            }
            if sign_at(&m, &b.lo) != Ordering::Equal {
                return Err(iso(format!("{} is not a root of the polynomial", b.lo)));
            }
        } else {
            if !(zero <= b.lo && b.lo < b.hi && b.hi <= one) {
                return Err(iso(format!(
                    "the bracket ({}, {}] is not within [0, 1] with lo < hi",
                    b.lo, b.hi
                )));
            }
            let roots = s.count(&b.lo, &b.hi);
            if roots != 1 {
                return Err(iso(format!(
                    "the polynomial has {roots} roots in ({}, {}], not exactly one",
                    b.lo, b.hi
                )));
            }
            if b.hi == one && sign_at(&m, &one) == Ordering::Equal {
                return Err(iso("the root in the bracket is 1".into()));
            }
        }
        if let Some(prev) = out.last() {
            if prev.hi >= b.lo {
                tally.add("polynomial", k);
                tally.add("isolating", k);
                return Err(fail(
                    "order",
                    format!(
                        "the bracket starts at {}, not above the previous one's end {}",
                        b.lo, prev.hi
                    ),
                )
                .at_breakpoint(k));
            }
        }
        out.push(Bracket {
            m,
            lo: b.lo.clone(),
            hi: b.hi.clone(),
        });
    }
    tally.add("polynomial", out.len());
    tally.add("isolating", out.len());
    tally.add("order", out.len().saturating_sub(1));
    Ok(out)
}

/// The advantage numerators `A_{x,a}` of an interval (empty at terminal states), each with
/// integer coefficients (a positive multiple).
type Advantages = Vec<Vec<Vec<BigInt>>>;

/// Checks interval `i` between `left` and `right`; its advantage numerators.
fn interval(
    mdp: &Mdp,
    i: usize,
    t: &IntervalRecord,
    left: End<'_>,
    right: End<'_>,
    tally: &mut Tally,
) -> Result<Advantages, Failure> {
    let n = mdp.states();
    let here = |f: Failure| f.at_interval(i);
    let wide = |k: Option<usize>, f: Failure| match k {
        Some(k) => f.at_interval(i).at_breakpoint(k),
        None => f.at_interval(i),
    };
    if !(left.hi() < &t.sample && &t.sample < right.lo()) {
        return Err(here(fail(
            "sample",
            format!(
                "{} is not strictly between {} and {}",
                t.sample,
                left.hi(),
                right.lo()
            ),
        )));
    }
    tally.add("sample", 1);
    let dens: Vec<Vec<BigInt>> = t.denominators.iter().map(|d| scaled_form(d).0).collect();
    for (k, d) in dens.iter().enumerate() {
        if d.is_empty() {
            return Err(here(fail(
                "denominator",
                format!("denominator {k} is zero"),
            )));
        }
        if let Err(w) = no_root_between(d, left, right) {
            return Err(wide(
                w,
                fail(
                    "denominator",
                    format!("denominator {k} has a root in the interval (or its end's bracket holds another root)"),
                ),
            ));
        }
        if sign_at(d, &t.sample) != Ordering::Greater {
            return Err(here(fail(
                "denominator",
                format!("denominator {k} is not positive at the sample {}", t.sample),
            )));
        }
    }
    tally.add("denominator", dens.len());
    for x in 0..n {
        let at = |f: Failure| f.at_interval(i).at_state(x);
        if mdp.terminal[x] {
            if t.values[x].is_some() || t.policy[x].is_some() || !t.optimal[x].is_empty() {
                return Err(at(fail(
                    "goal",
                    "a terminal state with a value, a policy or optimal actions".into(),
                )));
            }
        } else {
            match &t.values[x] {
                None => return Err(at(fail("goal", "no value at a non-terminal state".into()))),
                Some(v) if v.denominator >= dens.len() => {
                    return Err(at(fail(
                        "goal",
                        format!("denominator {} is not listed", v.denominator),
                    )))
                }
                Some(_) => {}
            }
        }
    }
    tally.add("goal", n);
    let actions = |x: usize| mdp.actions[x].len() as u64;
    for x in (0..n).filter(|&x| !mdp.terminal[x]) {
        let at = |d: String| fail("policy", d).at_interval(i).at_state(x);
        let o = &t.optimal[x];
        if let Some(a) = o.iter().find(|&&a| a >= actions(x)) {
            return Err(at(format!(
                "optimal action {a} is out of range: the state has {} actions",
                actions(x)
            )));
        }
        if o.windows(2).any(|w| w[0] >= w[1]) {
            return Err(at("the optimal actions are not increasing".into()));
        }
        match t.policy[x] {
            None => return Err(at("pi(x) is null".into())),
            Some(a) if a >= actions(x) => {
                return Err(at(format!(
                    "pi(x) = {a} is out of range: the state has {} actions",
                    actions(x)
                )))
            }
            Some(a) if !o.contains(&a) => {
                return Err(at(format!("pi(x) = {a} is not listed as optimal")))
            }
            Some(_) => {}
        }
    }
    tally.add("policy", n);
    // The advantage numerators, in integers: each listed polynomial is `P / L` with `P`
    // integral and `L > 0` ([`scaled_form`]), and `A_{x,a}` is multiplied by the product of
    // the `L` of its denominators and by the common denominator of the scalars, both positive.
    let value = |y: usize| t.values[y].as_ref().expect("checked: a value");
    let den_forms: Vec<(Vec<BigInt>, BigInt)> =
        t.denominators.iter().map(|d| scaled_form(d)).collect();
    let num_forms: Vec<Option<(Vec<BigInt>, BigInt)>> = t
        .values
        .iter()
        .map(|v| v.as_ref().map(|v| scaled_form(&v.numerator)))
        .collect();
    let mut advantages: Advantages = vec![Vec::new(); n];
    for x in (0..n).filter(|&x| !mdp.terminal[x]) {
        for a in &mdp.actions[x] {
            let mut involved: Vec<usize> = vec![value(x).denominator];
            for (y, _) in a.outcomes.iter().filter(|(y, _)| !mdp.terminal[*y]) {
                involved.push(value(*y).denominator);
            }
            involved.sort_unstable();
            involved.dedup();
            let total: usize = involved.iter().map(|&k| t.denominators[k].len()).sum();
            if total > MAX_ADVANTAGE_DEGREE {
                return Err(fail(
                    "shape",
                    format!("the advantages of this state multiply denominators of {total} coefficients in all, above the checker's bound {MAX_ADVANTAGE_DEGREE}"),
                )
                .at_interval(i)
                .at_state(x));
            }
            // Π_{j ≠ k} P_j over the involved denominators, and L_k.
            let except = |k: usize| -> Vec<BigInt> {
                involved
                    .iter()
                    .filter(|&&j| j != k)
                    .fold(vec![BigInt::one()], |acc, &j| {
                        mul_int(&acc, &den_forms[j].0)
                    })
            };
            let term = |y: usize| -> (Rational, Vec<BigInt>) {
                let (pn, ln) = num_forms[y].as_ref().expect("checked: a value");
                let k = value(y).denominator;
                (
                    Rational::new(den_forms[k].1.clone(), ln.clone()),
                    mul_int(pn, &except(k)),
                )
            };
            // r E + α Σ_y p_y V_y E − V_x E, times Π L_j: terms (scalar, α power, polynomial).
            let mut terms: Vec<(Rational, usize, Vec<BigInt>)> =
                vec![(a.reward.clone(), 0, except(usize::MAX))];
            for (y, p) in a.outcomes.iter().filter(|(y, _)| !mdp.terminal[*y]) {
                let (w, f) = term(*y);
                terms.push((p * w, 1, f));
            }
            let (w, f) = term(x);
            terms.push((-w, 0, f));
            advantages[x].push(combine(&terms));
        }
    }
    for x in (0..n).filter(|&x| !mdp.terminal[x]) {
        let a = t.policy[x].expect("checked") as usize;
        if !advantages[x][a].is_empty() {
            return Err(fail(
                "evaluation",
                format!("V_x is not r + alpha P V for pi(x) = {a}: the difference is not the zero polynomial"),
            )
            .at_interval(i)
            .at_state(x));
        }
    }
    tally.add("evaluation", (0..n).filter(|&x| !mdp.terminal[x]).count());
    let mut pairs = 0;
    for x in (0..n).filter(|&x| !mdp.terminal[x]) {
        for (a, adv) in advantages[x].iter().enumerate() {
            pairs += 1;
            let listed = t.optimal[x].contains(&(a as u64));
            let at = |d: String| fail("optimality", d).at_interval(i).at_state(x);
            if adv.is_empty() {
                if !listed {
                    return Err(at(format!(
                        "action {a} is optimal on the interval (Q_a = V identically) but not listed"
                    )));
                }
                continue;
            }
            if listed {
                return Err(at(format!(
                    "action {a} is listed as optimal but Q_a - V_x is not identically zero"
                )));
            }
            if sign_at(adv, &t.sample) != Ordering::Less {
                return Err(at(format!(
                    "action {a} has Q_a >= V_x at the sample {}",
                    t.sample
                )));
            }
            if let Err(w) = no_root_between(adv, left, right) {
                let f = at(format!(
                    "Q_a - V_x of action {a} has a root in the interval (or an end's bracket holds a root other than the breakpoint)"
                ));
                return Err(match w {
                    Some(k) => f.at_breakpoint(k),
                    None => f,
                });
            }
        }
    }
    tally.add("optimality", pairs);
    Ok(advantages)
}

/// Checks breakpoint `k` with the advantages of the interval on its left.
fn breakpoint(
    mdp: &Mdp,
    k: usize,
    b: &Bracket,
    c: &DiscountCertificate,
    left: &Advantages,
    tally: &mut Tally,
) -> Result<(), Failure> {
    let n = mdp.states();
    let t = &c.intervals[k];
    for (j, d) in t.denominators.iter().enumerate() {
        if b.vanishes(&scaled_form(d).0) {
            return Err(fail(
                "continuity",
                format!("denominator {j} of interval {k} vanishes at the breakpoint"),
            )
            .at_breakpoint(k));
        }
    }
    tally.add("continuity", t.denominators.len());
    let listed = &c.breakpoints[k].optimal;
    for x in 0..n {
        let at_point: Vec<u64> = left[x]
            .iter()
            .enumerate()
            .filter(|(_, a)| b.vanishes(a))
            .map(|(a, _)| a as u64)
            .collect();
        if at_point != listed[x] {
            return Err(fail(
                "ties",
                format!(
                    "the optimal actions at the breakpoint are {at_point:?}, the certificate lists {:?}",
                    listed[x]
                ),
            )
            .at_breakpoint(k)
            .at_state(x));
        }
    }
    tally.add("ties", n);
    let (l, r) = (&c.intervals[k].optimal, &c.intervals[k + 1].optimal);
    if l == r && listed == l {
        return Err(fail(
            "change",
            "the optimal actions are the same on both sides and at the point".into(),
        )
        .at_breakpoint(k));
    }
    tally.add("change", 1);
    Ok(())
}

fn run(
    mdp: &Mdp,
    identity: Identity<'_>,
    c: &DiscountCertificate,
    tally: &mut Tally,
) -> Result<(), Failure> {
    problem(mdp, identity, c)?;
    tally.add("problem", 1);
    shape(c)?;
    tally.add("shape", c.intervals.len() + c.breakpoints.len());
    let brackets = brackets(c, tally)?;
    let (zero, one) = (Rational::zero(), Rational::one());
    let end = |k: Option<usize>| match k {
        None => End::Point(&zero),
        Some(k) if k == brackets.len() => End::Point(&one),
        Some(k) => End::Breakpoint(k, &brackets[k]),
    };
    let mut previous: Option<Advantages> = None;
    for (i, t) in c.intervals.iter().enumerate() {
        let left = if i == 0 { end(None) } else { end(Some(i - 1)) };
        let advantages = interval(mdp, i, t, left, end(Some(i)), tally)?;
        if let Some(prev) = previous.take() {
            breakpoint(mdp, i - 1, &brackets[i - 1], c, &prev, tally)?;
        }
        previous = Some(advantages);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certificate::MdpAction;

    fn q(t: &str) -> Rational {
        t.parse().unwrap()
    }

    /// One state, two actions, terminal state 1: `a0` stays (reward 1), `a1` ends the episode
    /// with reward 3. By hand: staying forever pays `1/(1 − α)`, ending pays 3; they tie at
    /// `α = 2/3` (`1/(1 − α) = 3`), ending is better below, staying above.
    fn model() -> Mdp {
        let one = Rational::one();
        Mdp {
            goal: vec![false, true],
            terminal: vec![false, true],
            actions: vec![
                vec![
                    MdpAction {
                        cost: one.clone(),
                        reward: q("1"),
                        outcomes: vec![(0, one.clone())],
                    },
                    MdpAction {
                        cost: one.clone(),
                        reward: q("3"),
                        outcomes: vec![(1, one.clone())],
                    },
                ],
                vec![],
            ],
        }
    }

    fn certificate(mdp: &Mdp) -> DiscountCertificate {
        let record = ProblemRecord {
            source: "problem".into(),
            name: "hand".into(),
            gamma: None,
            noise: None,
            step_cost: None,
            sha256: sha256_hex(mdp.canonical_text().as_bytes()),
            sha256_of: CANONICAL_FORMAT.into(),
            goal_label: None,
            cost_reward: None,
        };
        let interval =
            |sample: &str, den: Vec<Rational>, num: Vec<Rational>, a: u64| IntervalRecord {
                sample: q(sample),
                denominators: vec![den],
                values: vec![
                    Some(ValueRecord {
                        denominator: 0,
                        numerator: num,
                    }),
                    None,
                ],
                policy: vec![Some(a), None],
                optimal: vec![vec![a], vec![]],
            };
        DiscountCertificate {
            problem: record,
            states: 2,
            // 3α − 2, at 2/3 exactly.
            breakpoints: vec![BreakpointRecord {
                polynomial: vec![q("-2"), q("3")],
                lo: q("2/3"),
                hi: q("2/3"),
                optimal: vec![vec![0, 1], vec![]],
            }],
            intervals: vec![
                interval("1/2", vec![q("1")], vec![q("3")], 1),
                interval("3/4", vec![q("1"), q("-1")], vec![q("1")], 0),
            ],
        }
    }

    #[test]
    fn the_hand_certificate_is_accepted_and_reads_back() {
        let mdp = model();
        let c = certificate(&mdp);
        let ok = check_discount(&mdp, Identity::Canonical, &c).unwrap();
        assert_eq!((ok.breakpoints, ok.intervals), (1, 2));
        assert_eq!(parse_discount(&write_discount(&c)).unwrap(), c);
    }

    #[test]
    fn a_bracketed_breakpoint_is_accepted_and_a_wrong_one_rejected() {
        let mdp = model();
        let mut c = certificate(&mdp);
        // The same point as the root of 3α − 2 in (1/2, 3/4]; samples inside the gaps.
        c.breakpoints[0].lo = q("1/2");
        c.breakpoints[0].hi = q("3/4");
        c.intervals[0].sample = q("1/4");
        c.intervals[1].sample = q("4/5");
        check_discount(&mdp, Identity::Canonical, &c).unwrap();
        // 3α − 2 has no root in (7/10, 3/4].
        c.breakpoints[0].lo = q("7/10");
        let e = check_discount(&mdp, Identity::Canonical, &c).unwrap_err();
        assert_eq!((e.condition, e.breakpoint), ("isolating", Some(0)));
        // A shifted breakpoint 7/10 (10α − 7): staying is better on (2/3, 7/10), caught on
        // the left interval.
        c = certificate(&mdp);
        c.breakpoints[0].polynomial = vec![q("-7"), q("10")];
        c.breakpoints[0].lo = q("7/10");
        c.breakpoints[0].hi = q("7/10");
        let e = check_discount(&mdp, Identity::Canonical, &c).unwrap_err();
        assert_eq!(
            (e.condition, e.interval, e.state),
            ("optimality", Some(0), Some(0))
        );
    }

    #[test]
    fn wrong_ties_and_missing_changes_are_rejected() {
        let mdp = model();
        let mut c = certificate(&mdp);
        c.breakpoints[0].optimal[0] = vec![1];
        let e = check_discount(&mdp, Identity::Canonical, &c).unwrap_err();
        assert_eq!(
            (e.condition, e.breakpoint, e.state),
            ("ties", Some(0), Some(0))
        );
        let mut c = certificate(&mdp);
        c.intervals[1].denominators[0] = vec![q("2"), q("-2")];
        let e = check_discount(&mdp, Identity::Canonical, &c).unwrap_err();
        assert_eq!((e.condition, e.interval), ("evaluation", Some(1)));
    }
}

//! The pieces every objective's conditions are checked with ([`super::check`] for the
//! deterministic, truecost and discounted objectives, [`super::reach`] for reach): the first
//! violated condition, values over one common denominator, the Bellman comparison of a state
//! with its actions in exact integers, the action a policy names, and the backward search
//! along a policy's outcomes.

use std::collections::{HashMap, VecDeque};

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Zero};

use super::mdp::{Mdp, MdpAction};
use crate::value::Rational;

/// The first violated condition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rejection {
    /// The condition's name (one of [`super::CONDITIONS`]).
    pub condition: &'static str,
    /// The first state where it fails (`None` for conditions on the whole certificate).
    pub state: Option<usize>,
    /// What fails, in one line.
    pub detail: String,
}

impl std::fmt::Display for Rejection {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.state {
            Some(x) => write!(
                f,
                "state {x}: condition {}: {}",
                self.condition, self.detail
            ),
            None => write!(f, "condition {}: {}", self.condition, self.detail),
        }
    }
}

pub(super) fn reject(condition: &'static str, state: Option<usize>, detail: String) -> Rejection {
    Rejection {
        condition,
        state,
        detail,
    }
}

/// The values over one common denominator: `V(x) = numer[x] / scale`.
pub(super) struct Scaled {
    numer: Vec<Option<BigInt>>,
    pub(super) scale: BigInt,
}

impl Scaled {
    pub(super) fn new(values: &[Option<Rational>]) -> Self {
        let mut factor: HashMap<&BigInt, BigInt> = HashMap::new();
        let mut scale = BigInt::one();
        for v in values.iter().flatten() {
            if !factor.contains_key(v.denom()) {
                scale = scale.lcm(v.denom());
                factor.insert(v.denom(), BigInt::zero());
            }
        }
        for (d, f) in factor.iter_mut() {
            *f = &scale / *d;
        }
        let numer = values
            .iter()
            .map(|v| v.as_ref().map(|r| r.numer() * &factor[r.denom()]))
            .collect();
        Scaled { numer, scale }
    }

    /// `constant + weight · Σ p(y) V(y)` as `(K, D)` with value `K / (D · scale)`, `D > 0`;
    /// `None` if an outcome's value is `inf`.
    pub(super) fn affine(
        &self,
        constant: &Rational,
        weight: &Rational,
        a: &MdpAction,
    ) -> Option<(BigInt, BigInt)> {
        let coefficients: Vec<(usize, Rational)> =
            a.outcomes.iter().map(|(y, p)| (*y, p * weight)).collect();
        let mut d = constant.denom().clone();
        for (_, q) in &coefficients {
            d = d.lcm(q.denom());
        }
        let mut k = constant.numer() * (&d / constant.denom()) * &self.scale;
        for (y, q) in &coefficients {
            k += q.numer() * (&d / q.denom()) * self.numer[*y].as_ref()?;
        }
        Some((k, d))
    }

    /// `V(x) · D · scale`, to compare with an [`affine`](Self::affine) `K`.
    pub(super) fn value_times(&self, x: usize, d: &BigInt) -> BigInt {
        self.numer[x].as_ref().expect("a finite value") * d
    }
}

/// `k / d` (`d > 0`) for a rejection's message: in lowest terms when both have at most
/// 2^16 bits in all, as they stand otherwise (the gcd of numbers of millions of bits takes
/// minutes, and the message is cut to 300 characters anyway).
fn quotient(k: BigInt, d: BigInt) -> Rational {
    if k.bits() + d.bits() <= 1 << 16 {
        Rational::new(k, d)
    } else {
        Rational::new_raw(k, d)
    }
}

/// `Q(x, a) = constant(a) + weight · Σ_y p(y | x, a) V(y)` (`constant` 0 if `None`) over the
/// certificate's values,
/// compared with `V(x)` exactly (the "evaluation" and "optimality" conditions of every
/// objective).
pub(super) struct Bellman<'a> {
    scaled: Scaled,
    values: &'a [Option<Rational>],
    constant: Option<fn(&MdpAction) -> &Rational>,
    weight: Rational,
    zero: Rational,
}

impl<'a> Bellman<'a> {
    pub(super) fn new(
        values: &'a [Option<Rational>],
        constant: Option<fn(&MdpAction) -> &Rational>,
        weight: Rational,
    ) -> Self {
        Bellman {
            scaled: Scaled::new(values),
            values,
            constant,
            weight,
            zero: Rational::zero(),
        }
    }

    /// `(K, D)` with `Q(x, a) · D · scale = K`, or `None` if an outcome's value is `inf`.
    fn q(&self, a: &MdpAction) -> Option<(BigInt, BigInt)> {
        let constant = self.constant.map_or(&self.zero, |f| f(a));
        self.scaled.affine(constant, &self.weight, a)
    }

    fn shown(&self, x: usize) -> String {
        self.values[x]
            .as_ref()
            .map_or_else(|| "inf".into(), |r| r.to_string())
    }

    /// "evaluation": `V(x) = Q(x, π(x))` at every state of `states` (each with a chosen action
    /// whose outcomes are finite); the number checked.
    pub(super) fn evaluation(
        &self,
        states: &[usize],
        policy: &[Option<&MdpAction>],
    ) -> Result<usize, Rejection> {
        for &x in states {
            let a = policy[x].expect("a chosen action");
            let (k, d) = self.q(a).expect("the chosen action's outcomes are finite");
            if k != self.scaled.value_times(x, &d) {
                let q = quotient(k, d * &self.scaled.scale);
                return Err(reject(
                    "evaluation",
                    Some(x),
                    format!("V(x) = {} but Q(x, pi(x)) = {q}", self.shown(x)),
                ));
            }
        }
        Ok(states.len())
    }

    /// "optimality": `V(x) ≥ Q(x, a)` (`upper`) or `V(x) ≤ Q(x, a)` for every state of
    /// `states` and every action whose outcomes are all finite; the number of pairs checked.
    pub(super) fn optimality(
        &self,
        mdp: &Mdp,
        states: &[usize],
        upper: bool,
    ) -> Result<usize, Rejection> {
        let mut pairs = 0;
        for &x in states {
            for (i, a) in mdp.actions[x].iter().enumerate() {
                let Some((k, d)) = self.q(a) else { continue };
                pairs += 1;
                let v = self.scaled.value_times(x, &d);
                if (upper && k > v) || (!upper && k < v) {
                    let q = quotient(k, d * &self.scaled.scale);
                    let sign = if upper { ">" } else { "<" };
                    return Err(reject(
                        "optimality",
                        Some(x),
                        format!("action {i} has Q = {q} {sign} V(x) = {}", self.shown(x)),
                    ));
                }
            }
        }
        Ok(pairs)
    }
}

/// The action `π(x)` names, or why it names none.
pub(super) fn chosen(mdp: &Mdp, x: usize, index: Option<u64>) -> Result<&MdpAction, String> {
    let list = &mdp.actions[x];
    match index {
        None => Err("pi(x) is null".into()),
        Some(i) => usize::try_from(i)
            .ok()
            .and_then(|i| list.get(i))
            .ok_or_else(|| {
                format!(
                    "pi(x) = {i} is out of range: the state has {} actions",
                    list.len()
                )
            }),
    }
}

/// The states reached backwards from `start` along `edges_into`.
pub(super) fn backward<I: Iterator<Item = usize>>(
    n: usize,
    start: &[bool],
    edges_into: impl Fn(usize) -> I,
) -> Vec<bool> {
    let mut seen = start.to_vec();
    let mut queue: VecDeque<usize> = (0..n).filter(|&x| start[x]).collect();
    while let Some(y) = queue.pop_front() {
        for x in edges_into(y) {
            if !seen[x] {
                seen[x] = true;
                queue.push_back(x);
            }
        }
    }
    seen
}

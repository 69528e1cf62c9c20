//! The conditions of a reach certificate (module docs of [`super`] give why they suffice):
//! `V` in `[0, 1]`, `1` at goals; `V ≥ Q(·, a)` for every action (an inductive upper bound);
//! `V = Q(·, π)` where `V > 0`, with `π` reaching a goal or a state of value 0 from every such
//! state (a lower bound, attained by `π`). `Q(x, a) = Σ_y p(y | x, a) V(y)`.

use num_traits::{One, Signed, Zero};

use super::conditions::{backward, chosen, reject, Bellman, Rejection};
use super::format::Certificate;
use super::mdp::{Mdp, MdpAction};
use crate::value::Rational;

/// Checks the reach conditions in order (range, goal, policy, evaluation, optimality,
/// proper), reporting each that holds to `pass`.
pub(super) fn reach(
    mdp: &Mdp,
    c: &Certificate,
    pass: &mut impl FnMut(&'static str, usize),
) -> Result<(), Rejection> {
    let n = mdp.states();
    let one = Rational::one();
    for (x, v) in c.values.iter().enumerate() {
        match v {
            None => return Err(reject("range", Some(x), "V = inf".into())),
            Some(r) if r.is_negative() || r.numer() > r.denom() => {
                return Err(reject(
                    "range",
                    Some(x),
                    format!("V = {r} is not in [0, 1]"),
                ))
            }
            Some(_) => {}
        }
    }
    pass("range", n);
    let v: Vec<&Rational> = c
        .values
        .iter()
        .map(|v| v.as_ref().expect("range"))
        .collect();
    for x in (0..n).filter(|&x| mdp.goal[x]) {
        if v[x] != &one {
            return Err(reject("goal", Some(x), format!("V = {}, not 1", v[x])));
        }
        if let Some(i) = c.policy[x] {
            return Err(reject("goal", Some(x), format!("pi = {i}, not null")));
        }
    }
    pass("goal", mdp.goal.iter().filter(|g| **g).count());
    // The states the policy must carry to a goal: non-goals of positive value.
    let inner: Vec<usize> = (0..n)
        .filter(|&x| !mdp.goal[x] && v[x].is_positive())
        .collect();
    let mut policy: Vec<Option<&MdpAction>> = vec![None; n];
    for x in (0..n).filter(|&x| !mdp.goal[x]) {
        if v[x].is_positive() {
            policy[x] =
                Some(chosen(mdp, x, c.policy[x]).map_err(|e| reject("policy", Some(x), e))?);
        } else if let Some(i) = c.policy[x] {
            return Err(reject(
                "policy",
                Some(x),
                format!("V = 0 but pi = {i}, not null"),
            ));
        }
    }
    pass("policy", n);
    let q = Bellman::new(&c.values, None, Rational::one());
    pass("evaluation", q.evaluation(&inner, &policy)?);
    let non_goals: Vec<usize> = (0..n).filter(|&x| !mdp.goal[x]).collect();
    let pairs = q.optimality(mdp, &non_goals, true)?;
    pass("optimality", pairs);
    // Proper: backward search from the goals and the value-0 states along pi's outcomes.
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &x in &inner {
        for (y, _) in &policy[x].expect("a chosen action").outcomes {
            into[*y].push(x);
        }
    }
    let absorbing: Vec<bool> = (0..n).map(|x| mdp.goal[x] || v[x].is_zero()).collect();
    let reached = backward(n, &absorbing, |y| into[y].iter().copied());
    if let Some(&x) = inner.iter().find(|&&x| !reached[x]) {
        return Err(reject(
            "proper",
            Some(x),
            "neither a goal nor a state of value 0 is reachable from x along pi's outcomes".into(),
        ));
    }
    pass("proper", inner.len());
    Ok(())
}

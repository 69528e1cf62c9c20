//! The conditions of a certificate, checked in exact integer arithmetic (module docs of
//! [`super`] give each condition and why the set suffices). Conditions are checked one after
//! the other, each over every state in order; the first violation is reported.

use std::collections::VecDeque;

use num_traits::{One, Signed, Zero};

pub use super::conditions::Rejection;
use super::conditions::{backward, chosen, reject, Bellman};
use super::format::{Certificate, CertifiedObjective};
use super::mdp::{Mdp, MdpAction, CANONICAL_FORMAT};
use super::sha256::sha256_hex;
use crate::value::Rational;

/// What the problem's SHA-256 is taken of.
#[derive(Clone, Copy, Debug)]
pub enum Identity<'a> {
    /// The problem file's bytes (`--file`).
    FileBytes(&'a [u8]),
    /// The model's canonical export ([`Mdp::canonical_text`]; `--problem`, `--env`).
    Canonical,
}

/// One condition that held, with how many instances (states or state-action pairs) it covered.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Checked {
    /// The name.
    pub name: &'static str,
    /// What it states.
    pub statement: &'static str,
    /// Instances checked.
    pub instances: usize,
}

/// What an accepted certificate established.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Acceptance {
    /// The objective's name.
    pub objective: &'static str,
    /// States.
    pub states: usize,
    /// States with a finite value.
    pub finite_states: usize,
    /// Actions in the model (all states).
    pub actions: usize,
    /// Every condition, in the order checked.
    pub conditions: Vec<Checked>,
}

/// Every condition: its name, its statement for truecost and the deterministic `G*`, for the
/// discounted objective and for reach (empty where it does not apply), in the order checked.
/// `V` are the certificate's values, `pi` its policy, `F` the states with finite `V`,
/// `Q(x, a) = l(x, a) + sum_y p(y|x,a) V(y)`, discounted `Q(x, a) = r(x, a) + alpha sum_y
/// p(y|x,a) V(y)`, reach `Q(x, a) = sum_y p(y|x,a) V(y)`.
pub const CONDITIONS: &[(&str, &str, &str, &str)] = &[
    (
        "problem",
        "the SHA-256 and the number of states are those of the re-read problem",
        "the SHA-256 and the number of states are those of the re-read problem",
        "the SHA-256 and the number of states are those of the re-read problem",
    ),
    ("deterministic", "every action has exactly one outcome (objective deterministic)", "", ""),
    ("alpha", "", "0 < alpha < 1", ""),
    ("finite", "", "every value is finite", ""),
    ("range", "", "", "every value is finite and 0 <= V(x) <= 1"),
    (
        "goal",
        "V(x) = 0 and pi(x) = null at every goal",
        "V(x) = 0 and pi(x) = null at every terminal state",
        "V(x) = 1 and pi(x) = null at every goal",
    ),
    (
        "policy",
        "pi(x) indexes x's actions at every non-goal x in F, null outside F",
        "pi(x) indexes x's actions at every non-terminal x",
        "pi(x) indexes x's actions at every non-goal x with V(x) > 0, null where V(x) = 0",
    ),
    ("closed", "every outcome of pi(x) is in F, for x in F", "", ""),
    (
        "evaluation",
        "V(x) = Q(x, pi(x)) exactly at every non-goal x in F",
        "V(x) = Q(x, pi(x)) exactly at every non-terminal x",
        "V(x) = Q(x, pi(x)) exactly at every non-goal x with V(x) > 0",
    ),
    (
        "optimality",
        "V(x) <= Q(x, a) for every non-goal x in F and action a with all outcomes in F",
        "V(x) >= Q(x, a) for every non-terminal x and action a",
        "V(x) >= Q(x, a) for every non-goal x and action a (V is inductive: an upper bound)",
    ),
    (
        "proper",
        "every x in F reaches a goal in the graph of pi's outcomes",
        "",
        "every non-goal x with V(x) > 0 reaches a goal or a state with V = 0 in the graph of pi's outcomes",
    ),
    (
        "infinite",
        "no x outside F is in W*, the greatest W from each of whose states a goal is reachable by actions with all outcomes in W",
        "",
        "",
    ),
];

/// The statement of condition `name` for `objective`.
fn statement(name: &'static str, objective: &CertifiedObjective) -> &'static str {
    CONDITIONS
        .iter()
        .find(|(n, _, _, _)| *n == name)
        .map(|(_, t, d, r)| match objective {
            CertifiedObjective::Discounted(_) => *d,
            CertifiedObjective::Reach => *r,
            CertifiedObjective::Truecost | CertifiedObjective::Deterministic => *t,
        })
        .expect("a listed condition")
}

/// Checks `certificate` against the re-read model `mdp`, whose SHA-256 is taken as `identity`
/// says. `Ok` lists every condition checked; `Err` is the first violation.
pub fn check(
    mdp: &Mdp,
    identity: Identity<'_>,
    certificate: &Certificate,
) -> Result<Acceptance, Rejection> {
    let mut done = Vec::new();
    let objective = &certificate.objective;
    let mut pass = |name: &'static str, instances: usize| {
        done.push(Checked {
            name,
            statement: statement(name, objective),
            instances,
        })
    };
    if let Some(why) = mdp.malformed() {
        return Err(reject("problem", None, why));
    }
    let (hash, of) = match identity {
        Identity::FileBytes(bytes) => (sha256_hex(bytes), "file bytes"),
        Identity::Canonical => (
            sha256_hex(mdp.canonical_text().as_bytes()),
            CANONICAL_FORMAT,
        ),
    };
    if certificate.problem.sha256_of != of {
        return Err(reject(
            "problem",
            None,
            format!(
                "the certificate hashes {}, this source is checked by the SHA-256 of its {of}",
                crate::echo::echo(&certificate.problem.sha256_of)
            ),
        ));
    }
    if certificate.problem.sha256 != hash {
        return Err(reject(
            "problem",
            None,
            format!(
                "the certificate's SHA-256 {} is not the problem's {hash}",
                crate::echo::echo(&certificate.problem.sha256)
            ),
        ));
    }
    let n = mdp.states();
    if certificate.values.len() != n {
        return Err(reject(
            "problem",
            None,
            format!(
                "the certificate has {} states, the problem {n}",
                certificate.values.len()
            ),
        ));
    }
    pass("problem", 1);
    let actions = mdp.actions.iter().map(Vec::len).sum();
    let finite_states = certificate.values.iter().filter(|v| v.is_some()).count();
    let conditions = match &certificate.objective {
        CertifiedObjective::Discounted(alpha) => {
            discounted(mdp, certificate, alpha, &mut pass)?;
            done
        }
        CertifiedObjective::Reach => {
            super::reach::reach(mdp, certificate, &mut pass)?;
            done
        }
        objective => {
            if *objective == CertifiedObjective::Deterministic {
                for (x, list) in mdp.actions.iter().enumerate() {
                    if let Some(i) = list.iter().position(|a| a.outcomes.len() != 1) {
                        return Err(reject(
                            "deterministic",
                            Some(x),
                            format!("action {i} has {} outcomes", list[i].outcomes.len()),
                        ));
                    }
                }
                pass("deterministic", actions);
            }
            truecost(mdp, certificate, &mut pass)?;
            done
        }
    };
    Ok(Acceptance {
        objective: certificate.objective.name(),
        states: n,
        finite_states,
        actions,
        conditions,
    })
}

fn truecost(
    mdp: &Mdp,
    c: &Certificate,
    pass: &mut impl FnMut(&'static str, usize),
) -> Result<(), Rejection> {
    let n = mdp.states();
    let v = &c.values;
    let finite = |x: usize| v[x].is_some();
    for x in (0..n).filter(|&x| mdp.goal[x]) {
        match (&v[x], c.policy[x]) {
            (Some(r), None) if r.is_zero() => {}
            (Some(r), None) => return Err(reject("goal", Some(x), format!("V = {r}, not 0"))),
            (None, _) => return Err(reject("goal", Some(x), "V = inf, not 0".into())),
            (_, Some(i)) => return Err(reject("goal", Some(x), format!("pi = {i}, not null"))),
        }
    }
    pass("goal", mdp.goal.iter().filter(|g| **g).count());
    let inner: Vec<usize> = (0..n).filter(|&x| !mdp.goal[x] && finite(x)).collect();
    let mut policy: Vec<Option<&MdpAction>> = vec![None; n];
    for (x, slot) in policy.iter_mut().enumerate() {
        if mdp.goal[x] {
            continue;
        }
        if finite(x) {
            *slot = Some(chosen(mdp, x, c.policy[x]).map_err(|e| reject("policy", Some(x), e))?);
        } else if let Some(i) = c.policy[x] {
            return Err(reject(
                "policy",
                Some(x),
                format!("V = inf but pi = {i}, not null"),
            ));
        }
    }
    pass("policy", n);
    for &x in &inner {
        let a = policy[x].expect("a chosen action");
        if let Some((y, _)) = a.outcomes.iter().find(|(y, _)| !finite(*y)) {
            return Err(reject(
                "closed",
                Some(x),
                format!("pi(x) reaches state {y}, whose V is inf"),
            ));
        }
    }
    pass("closed", inner.len());
    let q = Bellman::new(v, Some(|a| &a.cost), Rational::one());
    pass("evaluation", q.evaluation(&inner, &policy)?);
    let pairs = q.optimality(mdp, &inner, false)?;
    pass("optimality", pairs);
    // Proper: backward search from the goals along pi's outcomes.
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for &x in &inner {
        for (y, _) in &policy[x].expect("a chosen action").outcomes {
            into[*y].push(x);
        }
    }
    let reached = backward(n, &mdp.goal, |y| into[y].iter().copied());
    if let Some(x) = (0..n).find(|&x| finite(x) && !reached[x]) {
        return Err(reject(
            "proper",
            Some(x),
            "no goal is reachable from x along pi's outcomes".into(),
        ));
    }
    pass("proper", n - v.iter().filter(|v| v.is_none()).count());
    let infinite = v.iter().filter(|v| v.is_none()).count();
    if infinite > 0 {
        let w = almost_sure(mdp);
        if let Some(x) = (0..n).find(|&x| !finite(x) && w[x]) {
            return Err(reject(
                "infinite",
                Some(x),
                "V = inf but some policy reaches a goal with probability 1 from x".into(),
            ));
        }
    }
    pass("infinite", infinite);
    Ok(())
}

/// `W*`: the greatest set `W` of states such that from every state of `W` a goal is reachable
/// using only actions all of whose outcomes are in `W` (goals' own actions play no part). It
/// is computed from `W` = all states by replacing `W` with the states that reach a goal that
/// way, until nothing changes (at most `n` rounds).
fn almost_sure(mdp: &Mdp) -> Vec<bool> {
    let n = mdp.states();
    // (state, action index) pairs into each successor.
    let mut into: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for x in (0..n).filter(|&x| !mdp.goal[x]) {
        for (i, a) in mdp.actions[x].iter().enumerate() {
            for (y, _) in &a.outcomes {
                into[*y].push((x, i));
            }
        }
    }
    let mut w = vec![true; n];
    loop {
        let stays = |x: usize, i: usize| mdp.actions[x][i].outcomes.iter().all(|(y, _)| w[*y]);
        let mut r = mdp.goal.clone();
        let mut queue: VecDeque<usize> = (0..n).filter(|&x| r[x]).collect();
        while let Some(y) = queue.pop_front() {
            for &(x, i) in &into[y] {
                if w[x] && !r[x] && stays(x, i) {
                    r[x] = true;
                    queue.push_back(x);
                }
            }
        }
        if r == w {
            return w;
        }
        w = r;
    }
}

fn discounted(
    mdp: &Mdp,
    c: &Certificate,
    alpha: &Rational,
    pass: &mut impl FnMut(&'static str, usize),
) -> Result<(), Rejection> {
    let n = mdp.states();
    if !(alpha.is_positive() && alpha < &Rational::one()) {
        return Err(reject(
            "alpha",
            None,
            format!("alpha = {alpha} is not in (0, 1)"),
        ));
    }
    pass("alpha", 1);
    if let Some(x) = (0..n).find(|&x| c.values[x].is_none()) {
        return Err(reject("finite", Some(x), "V = inf".into()));
    }
    pass("finite", n);
    let v: Vec<&Rational> = c
        .values
        .iter()
        .map(|v| v.as_ref().expect("finite"))
        .collect();
    for x in (0..n).filter(|&x| mdp.terminal[x]) {
        if !v[x].is_zero() {
            return Err(reject(
                "goal",
                Some(x),
                format!("terminal state with V = {}, not 0", v[x]),
            ));
        }
        if let Some(i) = c.policy[x] {
            return Err(reject(
                "goal",
                Some(x),
                format!("terminal state with pi = {i}, not null"),
            ));
        }
    }
    pass("goal", mdp.terminal.iter().filter(|t| **t).count());
    let inner: Vec<usize> = (0..n).filter(|&x| !mdp.terminal[x]).collect();
    let mut policy: Vec<Option<&MdpAction>> = vec![None; n];
    for &x in &inner {
        policy[x] = Some(chosen(mdp, x, c.policy[x]).map_err(|e| reject("policy", Some(x), e))?);
    }
    pass("policy", n);
    let q = Bellman::new(&c.values, Some(|a| &a.reward), alpha.clone());
    pass("evaluation", q.evaluation(&inner, &policy)?);
    let pairs = q.optimality(mdp, &inner, true)?;
    pass("optimality", pairs);
    Ok(())
}

//! The discount certificate of an analysis (`discount --certificate`,
//! [`crate::certificate::discount`]): the breakpoints as square-free polynomials with
//! isolating brackets, each interval's witness policy (the analysis' reported one) with its
//! values as rational functions of `α` ([`super::witness_values`]) and the optimal sets. The
//! writer runs the certificate's own checker before returning it, so no certificate that
//! `truecost check` refuses is written.

use num_bigint::BigInt;
use num_traits::{One, Zero};

use crate::algebra::poly::roots::{integer_form, simplest_between, Root};
use crate::certificate::discount::{
    check_discount, BreakpointRecord, DiscountCertificate, IntervalRecord, ValueRecord,
};
use crate::certificate::sturm::Sturm;
use crate::certificate::{Identity, Mdp, ProblemRecord};
use crate::objectives::Model;
use crate::value::Rational;

use super::{witness_values, DiscountAnalysis};

/// How many times the writer narrows a breakpoint's bracket (by 8 halvings) when its own
/// check finds the bracket holding another root of an advantage or denominator.
const MAX_NARROWINGS: usize = 64;

/// The certificate of analysis `d` of `model` (`mdp`: the model as the checker reads it;
/// `problem`, `identity`: the problem's record and how its hash is taken). A bracket that also
/// holds another root of an advantage is narrowed; any other rejection by the checker is an
/// error (the analysis and the checker disagree).
///
/// ```
/// use truecost::certificate::discount::check_discount;
/// use truecost::certificate::{sha256_hex, Identity, ProblemRecord, CANONICAL_FORMAT};
/// use truecost::envs::EnvSpec;
/// use truecost::objectives::parametric::{certificate::discount_certificate, discount_breakpoints};
/// use truecost::objectives::Model;
/// let m = Model::from_environment(&EnvSpec::parse("frozenlake").unwrap().build().unwrap()).unwrap();
/// let d = discount_breakpoints(&m).unwrap();
/// let mdp = m.mdp();
/// let record = ProblemRecord {
///     source: "env".into(),
///     name: "frozenlake".into(),
///     gamma: None,
///     noise: None,
///     step_cost: None,
///     sha256: sha256_hex(mdp.canonical_text().as_bytes()),
///     sha256_of: CANONICAL_FORMAT.into(),
///     goal_label: None,
///     cost_reward: None,
/// };
/// let c = discount_certificate(&m, &d, &mdp, record, Identity::Canonical).unwrap();
/// assert_eq!(c.breakpoints.len(), d.breakpoints.len());
/// assert_eq!(c.intervals.len(), d.breakpoints.len() + 1);
/// assert!(check_discount(&mdp, Identity::Canonical, &c).is_ok());
/// ```
pub fn discount_certificate(
    model: &Model,
    d: &DiscountAnalysis,
    mdp: &Mdp,
    problem: ProblemRecord,
    identity: Identity<'_>,
) -> Result<DiscountCertificate, String> {
    let n = model.problem.states();
    let q = |c: &BigInt| Rational::from_integer(c.clone());
    let ints = |p: &[BigInt]| -> Vec<Rational> { p.iter().map(q).collect() };
    let mut intervals = Vec::with_capacity(d.intervals.len());
    for t in &d.intervals {
        let w = witness_values(model, &t.policy).map_err(|e| e.to_string())?;
        let values = (0..n)
            .map(|x| {
                (!model.terminal[x]).then(|| ValueRecord {
                    denominator: w.denominator_of[x],
                    numerator: ints(&w.numerators[x]),
                })
            })
            .collect();
        intervals.push(IntervalRecord {
            sample: Rational::zero(),
            denominators: w.denominators.iter().map(|p| ints(p)).collect(),
            values,
            policy: t.policy.iter().map(|a| a.map(|a| a as u64)).collect(),
            optimal: t.optimal.iter().map(|o| wide(o)).collect(),
        });
    }
    let mut roots: Vec<Root> = d.breakpoints.iter().map(|b| b.at.clone()).collect();
    let breakpoints: Vec<BreakpointRecord> = d
        .breakpoints
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let mut optimal: Vec<Vec<u64>> =
                d.intervals[k].optimal.iter().map(|o| wide(o)).collect();
            for (x, at) in &b.ties {
                optimal[*x] = wide(at);
            }
            let m: Vec<BigInt> = integer_form(&b.at.polynomial());
            let m = Sturm::new(&m).square_free_part().to_vec();
            BreakpointRecord {
                polynomial: ints(&m),
                lo: Rational::zero(),
                hi: Rational::zero(),
                optimal,
            }
        })
        .collect();
    let mut c = DiscountCertificate {
        problem,
        states: n,
        breakpoints,
        intervals,
    };
    for _ in 0..MAX_NARROWINGS {
        // Consecutive brackets apart, then the samples between them.
        for k in 1..roots.len() {
            while roots[k - 1].hi >= roots[k].lo {
                roots[k - 1].halve();
                roots[k].halve();
            }
        }
        for (b, r) in c.breakpoints.iter_mut().zip(&roots) {
            (b.lo, b.hi) = (r.lo.clone(), r.hi.clone());
        }
        for (i, t) in c.intervals.iter_mut().enumerate() {
            let lo = i
                .checked_sub(1)
                .map_or_else(Rational::zero, |k| roots[k].hi.clone());
            let hi = roots.get(i).map_or_else(Rational::one, |r| r.lo.clone());
            t.sample = simplest_between(&lo, &hi);
        }
        match check_discount(mdp, identity, &c) {
            Ok(_) => return Ok(c),
            Err(e)
                if matches!(e.condition, "optimality" | "denominator")
                    && e.breakpoint.is_some() =>
            {
                let k = e.breakpoint.expect("a breakpoint");
                for _ in 0..8 {
                    roots[k].halve();
                }
            }
            Err(e) => {
                return Err(format!(
                    "internal check failed: the discount certificate fails its own check: {e}"
                ))
            }
        }
    }
    Err("internal check failed: the discount certificate's brackets still hold other roots after narrowing".into())
}

fn wide(o: &[usize]) -> Vec<u64> {
    o.iter().map(|&a| a as u64).collect()
}

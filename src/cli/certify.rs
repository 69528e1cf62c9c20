//! What a certificate records of the problem it certifies, and how it is written: the model as
//! the certificate checker reads it ([`truecost::certificate::Mdp`]) and the options that
//! rebuild the problem, shared by `solve --certificate` on every source; the discount
//! certificate of `discount --certificate`; and `truecost check`, which dispatches on the
//! certificate's kind. Parsing and wiring only; the checker is [`truecost::certificate`].

use clap::ValueEnum;
use num_bigint::BigInt;
use num_traits::{One, Zero};

use truecost::algebra::poly::roots::{simplest_between, Root};
use truecost::certificate::discount::{
    check_discount, parse_discount, write_discount, BreakpointRecord, DiscountCertificate,
    IntervalRecord, ValueRecord, DISCOUNT,
};
use truecost::certificate::sturm::Sturm;
use truecost::certificate::{
    sha256_hex, Identity, Mdp, MdpAction, ProblemRecord, CANONICAL_FORMAT,
};
use truecost::objectives::parametric::{witness_values, DiscountAnalysis};
use truecost::objectives::Model;
use truecost::value::Rational;

use super::env::EnvArg;
use super::ReportFormat;
use truecost::problems::StepCost;
use truecost::stochastic::NoiseModel;

/// The model as the certificate checker reads it ([`truecost::certificate::Mdp`]): per state
/// its goal and terminal flags, per action its stage cost, reward and outcomes.
pub fn mdp_of(model: &Model) -> Mdp {
    let p = &model.problem;
    let actions = (0..p.states())
        .map(|x| {
            p.actions(x)
                .map(|a| MdpAction {
                    cost: p.cost(a).clone(),
                    reward: model.reward[a].clone(),
                    outcomes: p
                        .outcomes(a)
                        .iter()
                        .map(|o| (o.successor, o.probability.clone()))
                        .collect(),
                })
                .collect()
        })
        .collect();
    Mdp {
        goal: (0..p.states()).map(|x| p.is_goal(x)).collect(),
        terminal: model.terminal.clone(),
        actions,
    }
}

/// Where a certified problem comes from: the options that rebuild it.
pub struct CertifiedSource<'a> {
    /// `--file`.
    pub file: Option<&'a std::path::Path>,
    /// `--problem`.
    pub problem: Option<usize>,
    /// `--env`.
    pub env: Option<&'a str>,
    /// `--step-cost`.
    pub step: Option<StepCost>,
    /// `--gamma`, as given.
    pub gamma: Option<&'a str>,
    /// `--noise`.
    pub noise: Option<NoiseModel>,
}

fn value_name<T: ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .expect("no skipped variants")
        .get_name()
        .to_string()
}

impl CertifiedSource<'_> {
    /// The certificate's record of this source: the file's SHA-256, or that of the model's
    /// canonical export (`model`, built only then).
    pub fn record(&self, model: impl FnOnce() -> Mdp) -> Result<ProblemRecord, String> {
        let gamma = self.gamma.map(str::to_string);
        let noise = gamma
            .as_ref()
            .map(|_| value_name(&self.noise.unwrap_or_default()));
        let canonical = |source: &str, name: String, step_cost: Option<String>| ProblemRecord {
            source: source.into(),
            name,
            gamma: gamma.clone(),
            noise: noise.clone(),
            step_cost,
            sha256: sha256_hex(model().canonical_text().as_bytes()),
            sha256_of: CANONICAL_FORMAT.into(),
        };
        Ok(match (self.file, self.problem, self.env) {
            (Some(path), _, _) => {
                let bytes = truecost::bounded::read_bytes(
                    path,
                    truecost::model::file::MAX_FILE_BYTES,
                    "problem files",
                )
                .map_err(|e| format!("--certificate hashes the problem file again: {e}"))?;
                ProblemRecord {
                    source: "file".into(),
                    name: path.display().to_string(),
                    gamma: gamma.clone(),
                    noise: noise.clone(),
                    step_cost: None,
                    sha256: sha256_hex(&bytes),
                    sha256_of: "file bytes".into(),
                }
            }
            (None, Some(id), _) => canonical(
                "problem",
                id.to_string(),
                Some(value_name(&self.step.unwrap_or_default())),
            ),
            (None, None, Some(spec)) => canonical("env", spec.to_string(), None),
            (None, None, None) => return Err("give --problem N, --file FILE or --env SPEC".into()),
        })
    }
}

/// Writes a certificate file whole (a temporary file, then a rename; one line on error).
pub fn write_certificate(path: &std::path::Path, text: &str) -> Result<(), String> {
    truecost::atomic::write(path, text.as_bytes())
}

/// How many times the writer narrows a breakpoint's bracket (by 8 halvings) when its own
/// check finds the bracket holding another root of an advantage or denominator.
const MAX_NARROWINGS: usize = 64;

/// The discount certificate of an analysis (`discount --certificate`): the breakpoints as
/// polynomials with brackets, each interval's witness policy (the analysis' reported one) with
/// its values as rational functions of `α` ([`truecost::objectives::parametric::witness_values`])
/// and the optimal sets. The writer checks it with the checker before returning it: a bracket
/// that also holds another root of an advantage is narrowed, and any other rejection is an
/// error (the analysis and the checker disagree), so no certificate that `check` refuses is
/// written.
pub fn discount_certificate(
    model: &Model,
    d: &DiscountAnalysis,
    source: &CertifiedSource<'_>,
    file_text: Option<&str>,
) -> Result<String, String> {
    let mdp = mdp_of(model);
    let mut problem = source.record(|| mdp.clone())?;
    if let Some(text) = file_text {
        problem.sha256 = sha256_hex(text.as_bytes());
    }
    let identity = match file_text {
        Some(text) => Identity::FileBytes(text.as_bytes()),
        None => Identity::Canonical,
    };
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
            let m: Vec<BigInt> = truecost::algebra::poly::roots::integer_form(&b.at.polynomial());
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
        match check_discount(&mdp, identity, &c) {
            Ok(_) => return Ok(write_discount(&c)),
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

/// `truecost check`: a discount certificate ([`check_discount_file`]) or any other
/// (`super::env::check`), by the certificate's `objective`.
pub fn check(
    source: &EnvArg,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    certificate_path: &std::path::Path,
    format: ReportFormat,
    coq: bool,
) -> Result<String, String> {
    let text = read_certificate(certificate_path)?;
    let kind = serde_json::from_str::<serde_json::Value>(&text)
        .ok()
        .and_then(|v| {
            v.get("objective")
                .and_then(|o| o.as_str().map(str::to_string))
        });
    if kind.as_deref() != Some(DISCOUNT) {
        return super::env::check(source, problem, file, certificate_path, format, coq);
    }
    if coq {
        return Err("--coq checks truecost and deterministic certificates; a discount certificate is checked by truecost's own checker (without --coq)".into());
    }
    check_discount_file(source.env.as_deref(), problem, file, &text, format)
}

fn read_certificate(path: &std::path::Path) -> Result<String, String> {
    const MAX_CERTIFICATE_BYTES: u64 = 1 << 30;
    truecost::bounded::read_text(path, MAX_CERTIFICATE_BYTES, "certificates")
        .map_err(|e| format!("cannot read the certificate: {e}"))
}

/// Checks a discount certificate (`text`) against the problem rebuilt from the source, as
/// `discount` builds it.
fn check_discount_file(
    env: Option<&str>,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    text: &str,
    format: ReportFormat,
) -> Result<String, String> {
    let cert = parse_discount(text).map_err(|e| format!("malformed certificate: {e}"))?;
    let record = &cert.problem;
    if record.gamma.is_some() || record.noise.is_some() {
        return Err("malformed certificate: a discount certificate has no gamma or noise".into());
    }
    let kind = match (env, problem, file) {
        (Some(_), None, None) => "env",
        (None, Some(_), None) => "problem",
        (None, None, Some(_)) => "file",
        _ => return Err("give one of --env SPEC, --problem N and --file FILE".into()),
    };
    if record.source != kind {
        return Err(format!(
            "the certificate is for a problem from {} {}, not from {kind}",
            truecost::echo::echo(&record.source),
            truecost::echo::echo(&record.name)
        ));
    }
    let step = match (&record.step_cost, problem) {
        (Some(s), Some(_)) => Some(StepCost::from_str(s, false).map_err(|_| {
            format!(
                "the certificate's step_cost {} is not unit or euclidean",
                truecost::echo::echo(s)
            )
        })?),
        _ => None,
    };
    let loaded = super::discount::discount_model(env, problem, file, step)?;
    let mdp = mdp_of(&loaded.model);
    let identity = match &loaded.text {
        Some(t) => Identity::FileBytes(t.as_bytes()),
        None => Identity::Canonical,
    };
    let name = &loaded.model.name;
    match check_discount(&mdp, identity, &cert) {
        Ok(a) => Ok(match format {
            ReportFormat::Json => super::env::pretty(&serde_json::json!({
                "accepted": true,
                "objective": DISCOUNT,
                "problem": name,
                "sha256": record.sha256,
                "states": a.states,
                "actions": a.actions,
                "breakpoints": a.breakpoints,
                "intervals": a.intervals,
                "conditions": a.conditions,
                "not_certified": NOT_CERTIFIED,
                "coq_checked": false,
            })),
            ReportFormat::Text => {
                let mut s = format!(
                    "accepted     discount certificate for {name} ({} states, {} actions, {} breakpoints, {} intervals; SHA-256 {})\n",
                    a.states, a.actions, a.breakpoints, a.intervals, record.sha256
                );
                for c in &a.conditions {
                    s.push_str(&format!(
                        "{:<12} {} ({} checked)\n",
                        c.name, c.statement, c.instances
                    ));
                }
                s.push_str(&format!("not certified {NOT_CERTIFIED}\n"));
                s
            }
        }),
        Err(rejection) => {
            if format == ReportFormat::Json {
                super::emit(&super::env::pretty(&serde_json::json!({
                    "accepted": false,
                    "objective": DISCOUNT,
                    "problem": name,
                    "condition": rejection.condition,
                    "interval": rejection.interval,
                    "breakpoint": rejection.breakpoint,
                    "state": rejection.state,
                    "detail": rejection.detail,
                })))?;
            }
            Err(format!("certificate rejected: {rejection}"))
        }
    }
}

/// What `discount` prints that a discount certificate does not certify.
const NOT_CERTIFIED: &str = "the success probabilities and truecosts of the optimal policies (and the failure set read off them), computed from the certified optimal sets";

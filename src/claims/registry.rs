//! The claims registry: every claim with its statement, the engines that check it, and the
//! Kani harnesses of `proofs/` that state it for symbolic checking. It turns `verify`'s options
//! into a plan of work units ([`plan`]) and reads the units' values back into the report
//! ([`report`]): what each engine's result means for a claim, and how the engines' verdicts
//! combine. [`run`] is the whole pipeline — plan, select, run, report — in one place.

use super::caught::{caught, ENGINE_FAILED};
use super::coq::{self, Kind};
use super::harnesses::{self, StandinRun, HARNESSES};
use super::plan::{Checker, Plan, Step, Unit, Work};
use super::report::{AlphaStar, HarnessSection, Report};
use super::runner::{self, Mode, Value, Values};
use super::sampled::PropertyRun;
use super::shard::{self, Share};
use super::smt::{self, Outcome, SmtVerdict};
use super::{alpha, c1, c2, c3, c4, ClaimResult, Counterexample, EngineRun, Scope, Verdict};

pub use super::plan::HarnessTable;

/// What `verify` runs besides the enumeration and proptest engines.
#[derive(Clone, Debug)]
pub struct Options {
    /// Run the SMT engine (engine 4).
    pub smt: bool,
    /// Per-obligation timeout of the SMT engine, in milliseconds.
    pub smt_timeout_ms: u32,
    /// Re-check the Coq development with `coqc` (engine 5, [`coq`]): `truecost verify` does
    /// unless `--no-coq`. Off by default here: it compiles the whole development, and a
    /// library caller (the test suite's pinned reports) asks for it explicitly.
    pub coq: bool,
    /// The time limit of the Coq re-check, in seconds (`verify --coq-timeout`).
    pub coq_timeout_s: u64,
    /// Run the Kani harnesses' bodies through the stand-in in this process, from this table
    /// (`None`: `--no-harnesses`; the report then says they were not run).
    pub harnesses: Option<HarnessTable>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            smt: true,
            smt_timeout_ms: smt::TIMEOUT_MS,
            coq: false,
            coq_timeout_s: coq::TIMEOUT_SECONDS,
            harnesses: Some(truecost_proofs::harnesses),
        }
    }
}

/// Adds the SMT engine's run to a claim and lets its verdict decide when it is stronger:
/// `proved` over `verified`; a contradiction between engines gives `inconclusive`.
fn attach_smt(result: &mut ClaimResult, outcome: &Outcome) {
    let s = &outcome.summary;
    let failures = match outcome.verdict {
        SmtVerdict::Refuted => s.printed_sat.max(1),
        _ => (s.proofs - s.proofs_unsat) + (s.trust_checks - s.trust_ok),
    };
    result.engines.push(EngineRun {
        engine: "smt (Z3)".into(),
        mode: match outcome.verdict {
            SmtVerdict::Proved => "proof".into(),
            SmtVerdict::Refuted => "refutation (model replayed exactly)".into(),
            SmtVerdict::Inconclusive => "inconclusive".into(),
        },
        scope: outcome.scope.clone(),
        cases: s.proofs + s.trust_checks + s.printed,
        failures,
        seconds: s.seconds,
    });
    result.notes.push(if s.printed > 0 {
        format!(
            "smt: the printed statement searched on {} structures, satisfiable (a counterexample) on {}; {} trust checks, {} as required; {} unknown",
            s.printed, s.printed_sat, s.trust_checks, s.trust_ok, s.unknown
        )
    } else {
        format!(
            "smt: {} proof obligations, {} unsat; {} trust checks, {} as required (hypotheses satisfiable; dropped hypotheses satisfiable); {} unknown",
            s.proofs, s.proofs_unsat, s.trust_checks, s.trust_ok, s.unknown
        )
    });
    result.notes.extend(outcome.notes.iter().cloned());
    match (outcome.verdict, result.verdict) {
        (SmtVerdict::Proved, Verdict::Verified) => {
            result.verdict = Verdict::Proved;
            result.engine = "smt (Z3)".into();
            result.scope = outcome.scope.clone();
            result.cases = s.proofs;
        }
        (SmtVerdict::Proved, Verdict::Refuted) | (SmtVerdict::Refuted, Verdict::Verified) => {
            result
                .notes
                .push("engines disagree (smt against enumeration/proptest): inconclusive".into());
            result.verdict = Verdict::Inconclusive;
        }
        _ => {}
    }
}

/// Adds the Coq engine's result to a claim that has theorems in [`coq::THEOREMS`], and gives
/// it the Coq level when every one of them that proves it was re-checked in this run and
/// accepted — its statement and axioms exactly the pinned ones ([`coq::judge`]): "proved for
/// every finite problem (Coq)", or "proved in Coq for the paper's example" when a theorem is
/// about the worked example only ([`coq::Quantifier`]); a refuting theorem confirms
/// `refuted`. A Coq result against another engine's verdict gives `inconclusive`; a check
/// that did not run, failed, or ran a `coqc` that did not behave as Coq leaves the verdict and
/// says so.
pub fn attach_coq(result: &mut ClaimResult, check: &coq::Check) {
    use coq::Quantifier;
    let theorems = coq::theorems_of(&result.id);
    if theorems.is_empty() {
        return;
    }
    let names: Vec<String> = theorems
        .iter()
        .map(|t| format!("{} ({})", t.name, t.file))
        .collect();
    let coq_name = check.coq();
    let quantifier = [
        Quantifier::Counterexample,
        Quantifier::PaperExample,
        Quantifier::EveryFiniteProblem,
    ]
    .into_iter()
    .find(|q| theorems.iter().any(|t| t.scope == *q))
    .expect("a theorem");
    let scope = format!("{}: {}", quantifier.describe(), names.join("; "));
    let coq_run = |mode: String, failures: u64| EngineRun {
        engine: "coq".into(),
        mode,
        scope: scope.clone(),
        cases: theorems.len() as u64,
        failures,
        // The re-check's time is the report's (one `coq:` line), not a rate per claim.
        seconds: 0.0,
    };
    let not_rechecked = |result: &mut ClaimResult, mode: &str, why: String| {
        result.engines.push(EngineRun {
            cases: 0,
            ..coq_run(mode.into(), 0)
        });
        result.notes.push(format!(
            "coq: the Coq proof was NOT re-checked {why}; the theorem(s) that would carry this \
claim: {}; the verdict above is the other engines'",
            names.join(", ")
        ));
    };
    match &check.outcome {
        coq::Outcome::NotAvailable(why) => {
            let why = format!("on this machine ({why})");
            return not_rechecked(result, "not re-checked on this machine", why);
        }
        coq::Outcome::NotCoq(what) => {
            let why = format!("(not re-checked: coqc did not behave as Coq ({what}))");
            return not_rechecked(result, "not re-checked: coqc did not behave as Coq", why);
        }
        coq::Outcome::TimedOut(what) => {
            let why = format!("(not re-checked: {what})");
            return not_rechecked(result, "not re-checked: coqc timed out", why);
        }
        coq::Outcome::SourcesRefused(found) => {
            result.engines.push(coq_run(
                "refused: the sources admit something".into(),
                theorems.len() as u64,
            ));
            result.notes.push(format!(
                "coq: the embedded Coq sources were refused before compiling (forbidden words: {}); not re-checked",
                found.join(", ")
            ));
            return;
        }
        coq::Outcome::BuildFailed(why) => {
            // The files before the failure compiled: their theorems are judged below.
            result.notes.push(format!(
                "coq: the Coq development did not fully build with {coq_name}: {why}"
            ));
        }
        coq::Outcome::Checked => {}
    }
    let mut failures = 0;
    for t in &theorems {
        let found = check.theorem(t.name);
        let refused = found.map_or(Some("not asked about".to_string()), |c| c.refused.clone());
        failures += u64::from(refused.is_some());
        let judged = match (&refused, found) {
            (None, Some(c)) => format!(
                "statement and axioms as pinned; {}",
                c.assumptions.describe()
            ),
            _ => format!(
                "NOT accepted: {}",
                refused.as_deref().unwrap_or("not asked about")
            ),
        };
        let weaker = t
            .weaker
            .map(|w| format!("; weaker than the paper: {w}"))
            .unwrap_or_default();
        let states = found
            .and_then(|c| c.statement.clone())
            .map(|s| format!(" Coq states: {s}"))
            .unwrap_or_default();
        result.notes.push(format!(
            "coq: {} ({}), re-checked by coqc ({coq_name}) in this run: {judged}. Statement: {}{weaker}.{states}",
            t.name, t.file, t.statement
        ));
    }
    let mode = if failures == 0 {
        format!("proof re-checked by coqc ({coq_name}), statements and Print Assumptions as pinned")
    } else {
        format!("re-checked by coqc ({coq_name}): {failures} theorem(s) not accepted")
    };
    result.engines.push(coq_run(mode, failures));
    if failures > 0 {
        return;
    }
    let kind = theorems[0].kind;
    let disagree = matches!(
        (kind, result.verdict),
        (Kind::Proves, Verdict::Refuted)
            | (
                Kind::Refutes,
                Verdict::Proved
                    | Verdict::Verified
                    | Verdict::ProvedCoq
                    | Verdict::ProvedCoqExample
            )
    );
    if disagree {
        result
            .notes
            .push("engines disagree (coq against the other engines): inconclusive".into());
        result.verdict = Verdict::Inconclusive;
        return;
    }
    let contradicted = result
        .notes
        .iter()
        .any(|n| n.starts_with("engines disagree"));
    let level = match (kind, quantifier) {
        (Kind::Proves, Quantifier::EveryFiniteProblem) => Verdict::ProvedCoq,
        (Kind::Proves, _) => Verdict::ProvedCoqExample,
        (Kind::Refutes, _) => Verdict::Refuted,
    };
    // A refutation another engine already found keeps that engine's counterexample.
    let already_refuted = kind == Kind::Refutes && result.verdict == Verdict::Refuted;
    if !contradicted && !already_refuted {
        result.verdict = level;
        result.engine = format!("coq ({coq_name})");
        result.scope = scope;
        result.cases = theorems.len() as u64;
    }
}

/// The claim ids, in report order.
pub const IDS: [&str; 7] = [
    "C1",
    "C1-corrected",
    "C2",
    "C3",
    "C3-example",
    "C4",
    "C4-corrected",
];

/// The harnesses on truecost's own code that state no claim of the report (the solvers, the
/// exact value types): lemmas the claims' engines rely on.
pub fn lemmas() -> Vec<&'static harnesses::Harness> {
    HARNESSES
        .iter()
        .filter(|h| !IDS.contains(&h.claim))
        .collect()
}

fn selected(id: &str, only: Option<&str>) -> bool {
    match only {
        None => true,
        Some(o) => id == o || (id.starts_with(o) && id[o.len()..].starts_with('-')),
    }
}

/// The harnesses `verify` runs for the claims selected by `only`: those stating a selected
/// claim, and, when every claim is selected, the lemmas on truecost's own code.
fn harness_plan(only: Option<&str>) -> Vec<&'static harnesses::Harness> {
    HARNESSES
        .iter()
        .filter(|h| {
            if IDS.contains(&h.claim) {
                selected(h.claim, only)
            } else {
                only.is_none()
            }
        })
        .collect()
}

/// The engine line of harness `h`, and what its run means for the claim: an assertion failing
/// in a harness that must hold contradicts a claim that holds (inconclusive, as any
/// disagreement between engines); any other way a harness fails (a cover never satisfied,
/// every execution pruned, a printed statement not refuted) is noted, the verdict left alone.
fn attach_harness(result: &mut ClaimResult, h: &harnesses::Harness, runs: Option<&[StandinRun]>) {
    let Some(runs) = runs else {
        result.engines.push(harnesses::not_run(h));
        return;
    };
    let run = runs
        .iter()
        .find(|r| r.name == h.name)
        .expect("every planned harness has a run");
    result.engines.push(harnesses::reported(h, run));
    let Some(problem) = &run.problem else { return };
    if run.engine_failed() {
        return;
    }
    if run.refutes() && result.verdict != Verdict::Refuted {
        result.notes.push(format!(
            "engines disagree (kani harness {}, run here by the stand-in, fails: {problem}): inconclusive",
            h.name
        ));
        result.verdict = Verdict::Inconclusive;
    } else {
        result.notes.push(format!(
            "kani harness {} did not do what it states when run here by the stand-in: {problem}",
            h.name
        ));
    }
}

fn attach(
    result: &mut ClaimResult,
    prop: Option<Result<(PropertyRun, f64), String>>,
    runs: Option<&[StandinRun]>,
) {
    for h in harnesses::of_claim(&result.id) {
        attach_harness(result, h, runs);
    }
    let (p, seconds) = match prop {
        None => return,
        Some(Err(failure)) => {
            result.engines.push(failed_engine("proptest", &failure));
            return;
        }
        Some(Ok(run)) => run,
    };
    result.engines.push(p.engine_run(seconds));
    if let Some((t, what)) = &p.counterexample {
        let text = format!(
            "proptest shrank a counterexample: {what} ({})",
            t.describe()
        );
        if result.id == "C3" {
            // An existential claim: a structure without a certificate is not a refutation.
            result.verdict = Verdict::Inconclusive;
        } else if result.verdict == Verdict::Verified {
            result.verdict = Verdict::Refuted;
            result.engine = "proptest".into();
            result.counterexample = Some(Counterexample::new(
                t,
                format!("{} counterexample (proptest): {what}", result.id),
                vec![],
                &format!("{}-proptest", result.id.to_lowercase()),
            ));
        }
        result.notes.push(text);
    }
}

/// The step names of the engines that [`report`] looks up by claim.
const PROPTEST: &str = "proptest";
const SMT: &str = "smt (Z3)";
const COQ: &str = "coq";

/// `truecost verify` as a pipeline: the plan of the selected claims (all when `only` is `None`;
/// `C1` selects `C1` and `C1-corrected`), every unit selected, run in full, read back into the
/// report.
pub fn run(scope: Scope, only: Option<&str>, options: &Options) -> Result<Report, String> {
    let plan = plan(scope, only, options)?;
    let units = shard::select(plan.units(), None);
    let ran = runner::run(&plan, &units, Mode::Whole)?;
    Ok(report(&plan, &ran.values))
}

/// The plan of `verify` for the claims selected by `only` (all when `None`): in the order the
/// whole run takes them, the harnesses of the stand-in; for each claim checker, its
/// enumeration (split among shards) and the proptest property of each selected claim it
/// decides; the SMT obligations of each selected claim; then the Coq re-check. Every unit but
/// the enumerations is owned by one shard, numbered in this order. An unknown claim is refused.
///
/// ```
/// use truecost::claims::shard::Share;
/// use truecost::claims::registry::{plan, Options};
/// use truecost::claims::Scope;
/// let options = Options { smt: false, harnesses: None, ..Options::default() };
/// let p = plan(Scope::Smoke, Some("C4"), &options).unwrap();
/// let ids: Vec<&str> = p.units().map(|u| u.id.as_str()).collect();
/// assert_eq!(
///     ids,
///     [
///         "exact solve C3-example",
///         "exhaustive enumeration C4, C4-corrected",
///         "proptest C4",
///         "proptest C4-corrected",
///     ]
/// );
/// assert!(matches!(p.units().nth(3).unwrap().share, Share::Owned(1)));
/// assert!(plan(Scope::Smoke, Some("C9"), &options).is_err());
/// ```
pub fn plan(scope: Scope, only: Option<&str>, options: &Options) -> Result<Plan, String> {
    if let Some(o) = only {
        if !IDS.iter().any(|id| selected(id, Some(o))) {
            return Err(format!("unknown claim '{o}' (known: {})", IDS.join(", ")));
        }
    }
    let claims: Vec<&'static str> = IDS.into_iter().filter(|id| selected(id, only)).collect();
    let harnesses = harness_plan(only);
    let mut owned = 0u64;
    let mut owned_unit = |id: String, work: Work| {
        owned += 1;
        Unit {
            id,
            work,
            share: Share::Owned(owned - 1),
        }
    };
    let step = |engine: &'static str, claim: Option<&'static str>, units: Vec<Unit>| Step {
        engine,
        claim,
        units,
        failed: None,
    };
    let mut steps = Vec::new();
    if options.harnesses.is_some() {
        let units = harnesses
            .iter()
            .map(|&h| owned_unit(format!("kani harness {}", h.name), Work::Harness(h)))
            .collect();
        steps.push(step("kani harnesses (stand-in)", None, units));
    }
    // The worked example's exact solve runs whatever the selection: it gives α*.
    for checker in [
        Checker::C1,
        Checker::C2,
        Checker::C3,
        Checker::Example,
        Checker::C4,
    ] {
        let decides = checker.claims().iter().any(|id| claims.contains(id));
        if !decides && checker != Checker::Example {
            continue;
        }
        let unit = Unit {
            id: format!("{} {}", checker.engine(), checker.claims().join(", ")),
            work: Work::Checker(checker),
            share: Share::Split,
        };
        steps.push(step(checker.engine(), None, vec![unit]));
        if checker == Checker::Example {
            continue;
        }
        for &id in checker.claims().iter().filter(|id| claims.contains(id)) {
            let unit = owned_unit(format!("proptest {id}"), Work::Property(id));
            steps.push(step(PROPTEST, Some(id), vec![unit]));
        }
    }
    let mut encodings = Vec::new();
    if options.smt {
        for &id in &claims {
            match caught(|| smt::encoding(id, scope)) {
                Ok(Some(enc)) => {
                    let units = (0..enc.obligations.len())
                        .map(|j| {
                            owned_unit(format!("smt {id} obligation {j}"), Work::Obligation(id, j))
                        })
                        .collect();
                    steps.push(step(SMT, Some(id), units));
                    encodings.push(enc);
                }
                Ok(None) => steps.push(step(SMT, Some(id), vec![])),
                Err(failure) => steps.push(Step {
                    failed: Some(failure),
                    ..step(SMT, Some(id), vec![])
                }),
            }
        }
    }
    if options.coq && claims.iter().any(|c| !coq::theorems_of(c).is_empty()) {
        let unit = owned_unit("coq re-check".into(), Work::Coq);
        steps.push(step(COQ, None, vec![unit]));
    }
    Ok(Plan {
        scope,
        claims,
        harnesses,
        harness_table: options.harnesses,
        smt_timeout_ms: options.smt.then_some(options.smt_timeout_ms),
        encodings,
        coq_timeout: std::time::Duration::from_secs(options.coq_timeout_s),
        steps,
    })
}

/// The value of unit `id`, or the failure of its engine (a value the runner did not give is a
/// failure too: the report then says so rather than claim anything).
fn value<'v>(values: &'v Values, id: &str) -> Result<&'v Value, String> {
    match values.get(id) {
        Some(Ok(v)) => Ok(v),
        Some(Err(failure)) => Err(failure.clone()),
        None => Err(format!(
            "the run gave no value for '{}'",
            crate::echo::one_line(id)
        )),
    }
}

/// The report of a plan's run from its units' `values` ([`runner::run`]): each selected
/// claim's checker result with its harnesses and proptest run attached, then the SMT engine's
/// verdict, then the Coq level; a claim with a failed engine is inconclusive.
pub fn report(plan: &Plan, values: &Values) -> Report {
    let runs: Option<Vec<StandinRun>> = plan.harness_table.map(|_| {
        plan.harnesses
            .iter()
            .map(
                |h| match value(values, &format!("kani harness {}", h.name)) {
                    Ok(Value::Harness(run)) => run.clone(),
                    Ok(_) => StandinRun::failed(h.name, h.should_panic, "not a harness run"),
                    Err(failure) => StandinRun::failed(h.name, h.should_panic, &failure),
                },
            )
            .collect()
    });
    let runs = runs.as_deref();
    let mut claims = Vec::new();
    let mut star = None;
    for step in &plan.steps {
        let [unit] = step.units.as_slice() else {
            continue;
        };
        let Work::Checker(checker) = unit.work else {
            continue;
        };
        let results = match value(values, &unit.id) {
            Ok(Value::Checked(results, found)) if results.len() == checker.claims().len() => {
                star = star.or(found.clone());
                results.clone()
            }
            Ok(_) => failed_claims(checker, "not the checker's claims"),
            Err(failure) => failed_claims(checker, &failure),
        };
        for mut result in results {
            if !plan.claims.contains(&result.id.as_str()) {
                continue;
            }
            let prop = plan.step(PROPTEST, &result.id).map(|s| {
                let id = &s.units[0].id;
                match value(values, id) {
                    Ok(Value::Property(p, seconds)) => Ok((p.clone(), *seconds)),
                    Ok(_) => Err("not a proptest run".to_string()),
                    Err(failure) => Err(failure),
                }
            });
            attach(&mut result, prop, runs);
            claims.push(result);
        }
    }
    let mut smt_outcomes = Vec::new();
    for c in claims.iter_mut() {
        let Some(step) = plan.step(SMT, &c.id) else {
            continue;
        };
        let judged = match (&step.failed, plan.encoding(&c.id)) {
            (Some(failure), _) => Err(failure.clone()),
            (None, None) => continue,
            (None, Some(enc)) => step
                .units
                .iter()
                .map(|u| match value(values, &u.id)? {
                    Value::Obligation(solved) => Ok(solved.clone()),
                    _ => Err("not an SMT obligation".to_string()),
                })
                .collect::<Result<Vec<_>, String>>()
                .and_then(|solved| caught(|| smt::judge(enc, solved))),
        };
        match judged {
            Ok(outcome) => {
                attach_smt(c, &outcome);
                smt_outcomes.push(outcome);
            }
            Err(failure) => c.engines.push(failed_engine(SMT, &failure)),
        }
    }
    let coq_step = plan.steps.iter().find(|s| s.engine == COQ);
    let coq_check = coq_step.map(|s| match value(values, &s.units[0].id) {
        Ok(Value::Coq(check)) => Ok(check.clone()),
        Ok(_) => Err("not a Coq re-check".to_string()),
        Err(failure) => Err(failure),
    });
    let coq_check = match coq_check {
        Some(Ok(check)) => {
            for c in claims.iter_mut() {
                attach_coq(c, &check);
            }
            Some(check)
        }
        Some(Err(failure)) => {
            for c in claims.iter_mut() {
                if !coq::theorems_of(&c.id).is_empty() {
                    c.engines.push(failed_engine(COQ, &failure));
                }
            }
            Some(coq::Check {
                version: None,
                outcome: coq::Outcome::NotAvailable(format!("{ENGINE_FAILED}{failure}")),
                theorems: vec![],
                files: 0,
                seconds: 0.0,
            })
        }
        None => None,
    };
    for c in claims.iter_mut() {
        settle_engine_failures(c);
    }
    Report {
        harnesses: Some(harness_section(&plan.harnesses, runs)),
        solver: plan.smt_timeout_ms.map(|_| smt::solver_version()),
        coq: coq_check,
        smt: smt_outcomes,
        tool: format!("truecost {}", env!("CARGO_PKG_VERSION")),
        commit: option_env!("TRUECOST_GIT_COMMIT")
            .unwrap_or("unknown")
            .to_string(),
        scope: plan.scope,
        claims,
        alpha_star: star.map(|a| AlphaStar::new(&a)),
    }
}

/// The claims of `checker` when it panicked with `failure`.
fn failed_claims(checker: Checker, failure: &str) -> Vec<ClaimResult> {
    checker
        .claims()
        .iter()
        .map(|id| failed_claim(id, checker.engine(), failure))
        .collect()
}

/// The engine line of `engine` when it panicked with `failure` ([`caught`]).
fn failed_engine(engine: &str, failure: &str) -> EngineRun {
    EngineRun {
        engine: engine.into(),
        mode: format!("{ENGINE_FAILED}{failure}"),
        scope: "not run to its end: truecost's code panicked".into(),
        cases: 0,
        failures: 0,
        seconds: 0.0,
    }
}

/// The statement of claim `id` (one of [`IDS`]), as its checker states it.
fn statement(id: &str) -> String {
    match id {
        "C1" => c1::STATEMENT.into(),
        "C1-corrected" => c1::corrected_statement(),
        "C2" => c2::STATEMENT.into(),
        "C3" => c3::STATEMENT.into(),
        "C3-example" => alpha::STATEMENT.into(),
        "C4" => c4::STATEMENT.into(),
        "C4-corrected" => c4::CORRECTED.into(),
        _ => String::new(),
    }
}

/// Claim `id` when its checker's `engine` panicked with `failure`: no verdict, one engine line
/// saying so; the other engines are attached to it as to any claim.
fn failed_claim(id: &str, engine: &str, failure: &str) -> ClaimResult {
    ClaimResult {
        id: id.into(),
        statement: statement(id),
        verdict: Verdict::Inconclusive,
        engine: format!("none: {engine} failed"),
        scope: "no verdict: an engine failed".into(),
        cases: 0,
        counterexample: None,
        engines: vec![failed_engine(engine, failure)],
        notes: vec![],
    }
}

/// The engines of `result` that failed (their lines say `engine failed: …`).
fn failed_engines(result: &ClaimResult) -> Vec<&str> {
    result
        .engines
        .iter()
        .filter(|e| e.mode.starts_with(ENGINE_FAILED))
        .map(|e| e.engine.as_str())
        .collect()
}

/// A claim with an engine that failed is inconclusive, whatever its other engines found: the
/// failure is a bug in truecost's code (or in the code it checks), which the claim's other
/// engines may share.
fn settle_engine_failures(result: &mut ClaimResult) {
    let failed = failed_engines(result).join(", ");
    if failed.is_empty() {
        return;
    }
    result.notes.push(format!(
        "engine failed ({failed}): inconclusive whatever the other engines found"
    ));
    result.verdict = Verdict::Inconclusive;
    result.engine = format!("none: {failed} failed");
    result.scope = "no verdict: an engine failed".into();
    result.cases = 0;
}

/// The engines of `report` that failed, as `claim: engine` (a lemma harness as `lemmas:
/// engine`): `verify` prints the whole report and then exits with a failure when there are any.
pub fn engine_failures(report: &Report) -> Vec<String> {
    let mut out: Vec<String> = report
        .claims
        .iter()
        .flat_map(|c| {
            failed_engines(c)
                .into_iter()
                .map(move |e| format!("{}: {e}", c.id))
        })
        .collect();
    if let Some(h) = &report.harnesses {
        out.extend(
            h.lemmas
                .iter()
                .filter(|e| e.mode.starts_with(ENGINE_FAILED))
                .map(|e| format!("lemmas: {}", e.engine)),
        );
    }
    out
}

/// The report's harness section: one line on what ran, and the lemma harnesses' engine lines.
fn harness_section(
    plan: &[&'static harnesses::Harness],
    runs: Option<&[StandinRun]>,
) -> HarnessSection {
    let lemmas: Vec<&harnesses::Harness> = plan
        .iter()
        .copied()
        .filter(|h| !IDS.contains(&h.claim))
        .collect();
    let Some(runs) = runs else {
        return HarnessSection {
            summary: format!(
                "the {} kani harnesses of proofs/ for these claims were NOT run (--no-harnesses)",
                plan.len()
            ),
            lemmas: lemmas.into_iter().map(harnesses::not_run).collect(),
            overflow_checks: None,
        };
    };
    let failing = runs.iter().filter(|r| r.problem.is_some()).count();
    HarnessSection {
        summary: format!(
            "{} kani harnesses of proofs/ run here by the stand-in with their stated executions, seeded: {} as stated, {failing} failing; evidence, not Kani results (Kani is not run here)",
            runs.len(),
            runs.len() - failing
        ),
        lemmas: lemmas
            .into_iter()
            .map(|h| {
                let run = runs.iter().find(|r| r.name == h.name).expect("planned");
                harnesses::reported(h, run)
            })
            .collect(),
        overflow_checks: Some(vec![
            (
                "truecost-proofs (the harness bodies)",
                truecost_proofs::overflow_checks(),
            ),
            (
                "truecost-kernel (the code they call)",
                caught(truecost_kernel::overflow_checks) == Ok(true),
            ),
        ]),
    }
}

/// What a shard file of `verify` must share with the other shards of its run: the tool and
/// commit (the sites must be the same), the scope, the claim filter and the options.
pub fn fingerprint(scope: Scope, only: Option<&str>, options: &Options) -> serde_json::Value {
    serde_json::json!({
        "tool": format!("truecost {}", env!("CARGO_PKG_VERSION")),
        "commit": option_env!("TRUECOST_GIT_COMMIT").unwrap_or("unknown"),
        "scope": scope.name(),
        "claim": only,
        "smt": options.smt,
        "smt_timeout_ms": options.smt_timeout_ms,
        "coq": options.coq,
        "coq_timeout": options.coq_timeout_s,
        "harnesses": options.harnesses.is_some(),
    })
}

/// The plan of the run a set of shards was made by (`verify merge`), from the settings their
/// `fingerprint` states: refused unless this build makes the same fingerprint from them (the
/// same build, nothing edited).
pub fn plan_of(fingerprint: &serde_json::Value) -> Result<Plan, String> {
    let fp = shard::Fingerprint(fingerprint);
    let scope = Scope::from_name(fp.text("scope")).ok_or_else(|| fp.bad("scope"))?;
    let only: Option<String> = fp.field("claim")?;
    let options = Options {
        smt: fp.field("smt")?,
        smt_timeout_ms: fp.field("smt_timeout_ms")?,
        coq: fp.field("coq")?,
        coq_timeout_s: fp.field("coq_timeout")?,
        harnesses: fp
            .field::<bool>("harnesses")?
            .then_some(truecost_proofs::harnesses as HarnessTable),
    };
    fp.confirm(&self::fingerprint(scope, only.as_deref(), &options))?;
    plan(scope, only.as_deref(), &options)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::smt::Summary;

    fn enumerated(verdict: Verdict) -> ClaimResult {
        ClaimResult {
            id: "C0".into(),
            statement: String::new(),
            verdict,
            engine: "exhaustive enumeration".into(),
            scope: "enumerated".into(),
            cases: 7,
            counterexample: None,
            engines: vec![],
            notes: vec![],
        }
    }

    fn smt(verdict: SmtVerdict) -> Outcome {
        Outcome {
            claim: "C0",
            scope: "symbolic".into(),
            verdict,
            summary: Summary {
                proofs: 11,
                proofs_unsat: 8,
                trust_checks: 5,
                trust_ok: 3,
                printed: 0,
                printed_sat: 0,
                unknown: 0,
                seconds: 0.5,
            },
            counterexample: None,
            notes: vec!["an outcome note".into()],
            solved: vec![],
        }
    }

    fn coq_check(outcome: coq::Outcome, each: coq::Assumptions) -> coq::Check {
        coq::Check {
            version: Some("8.16.1".into()),
            theorems: if matches!(
                outcome,
                coq::Outcome::Checked | coq::Outcome::BuildFailed(_)
            ) {
                coq::THEOREMS
                    .iter()
                    .map(|t| coq::TheoremCheck {
                        name: t.name.into(),
                        statement: Some("a statement".into()),
                        refused: (!each.accepted()).then(|| each.describe()),
                        assumptions: each.clone(),
                    })
                    .collect()
            } else {
                vec![]
            },
            outcome,
            files: 5,
            seconds: 1.0,
        }
    }

    fn claim(id: &str, verdict: Verdict) -> ClaimResult {
        ClaimResult {
            id: id.into(),
            ..enumerated(verdict)
        }
    }

    /// The Coq level is given only for a re-check that ran in this run and accepted every
    /// theorem of the claim; it names the theorem, the file and the Coq version.
    #[test]
    fn the_coq_level_needs_a_recheck_that_ran_and_accepted_every_theorem() {
        use coq::{Assumptions as A, Outcome as O};
        let clean = coq_check(O::Checked, A::Closed);
        let mut r = claim("C1-corrected", Verdict::Proved);
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::ProvedCoq);
        assert_eq!(r.engine, "coq (Coq 8.16.1)");
        assert!(
            r.scope
                .contains("Truecost.C1.c1_corrected (proofs/coq/C1.v)"),
            "{}",
            r.scope
        );
        let n = coq::theorems_of("C1-corrected").len() as u64;
        assert!(n >= 3);
        assert_eq!(r.cases, n);
        let e = r.engines.last().unwrap();
        assert_eq!((e.engine.as_str(), e.cases, e.failures), ("coq", n, 0));
        assert!(r.notes.iter().any(|n| n.starts_with(
            "coq: Truecost.C1.c1_corrected (proofs/coq/C1.v), re-checked by coqc (Coq 8.16.1) in this run: statement and axioms as pinned; closed"
        )));
        // The reals' axioms are accepted and listed.
        let reals = coq_check(
            O::Checked,
            A::Allowed(vec!["ClassicalDedekindReals.sig_forall_dec".into()]),
        );
        let mut r = claim("C2", Verdict::Verified);
        attach_coq(&mut r, &reals);
        assert_eq!(r.verdict, Verdict::ProvedCoq);
        assert!(r.notes.iter().any(|n| n.contains("sig_forall_dec")));
        // A forbidden axiom, a missing theorem, a refused or failed build, or no coqc: the
        // verdict stays the other engines'.
        for check in [
            coq_check(O::Checked, A::Forbidden(vec!["foo (Axioms)".into()])),
            coq_check(O::Checked, A::Missing("not found".into())),
            coq_check(
                O::SourcesRefused(vec!["C1.v:3: Admitted".into()]),
                A::Closed,
            ),
            coq_check(
                O::BuildFailed("C1.v does not compile".into()),
                A::Missing("C1.v was not compiled".into()),
            ),
            coq_check(O::NotAvailable(coq::NOT_FOUND.into()), A::Closed),
            coq_check(O::NotCoq("it accepted a false lemma".into()), A::Closed),
            coq_check(O::TimedOut("coqc did not finish".into()), A::Closed),
        ] {
            let mut r = claim("C1-corrected", Verdict::Proved);
            attach_coq(&mut r, &check);
            assert_eq!(r.verdict, Verdict::Proved, "{check:?}");
            assert_eq!(r.engine, "exhaustive enumeration");
            assert_eq!(r.engines.len(), 1);
        }
        // A later file that fails leaves the theorems of the files compiled before it judged
        // on their own (each file depends only on the ones before it), and is reported.
        let mut r = claim("C2", Verdict::Proved);
        attach_coq(
            &mut r,
            &coq_check(O::BuildFailed("C3.v does not compile".into()), A::Closed),
        );
        assert_eq!(r.verdict, Verdict::ProvedCoq);
        assert!(r.notes[0].contains("did not fully build") && r.notes[0].contains("C3.v"));
        let mut r = claim("C1-corrected", Verdict::Proved);
        attach_coq(
            &mut r,
            &coq_check(O::NotAvailable(coq::NOT_FOUND.into()), A::Closed),
        );
        assert_eq!(r.engines[0].mode, "not re-checked on this machine");
        assert!(r.notes[0].contains("NOT re-checked on this machine (coqc not found"));
        assert!(r.notes[0].contains("Truecost.C1.c1_corrected"));
        let mut r = claim("C2", Verdict::Proved);
        attach_coq(
            &mut r,
            &coq_check(O::NotCoq("it accepted a false lemma".into()), A::Closed),
        );
        assert_eq!(
            r.engines[0].mode,
            "not re-checked: coqc did not behave as Coq"
        );
        assert!(r.notes[0]
            .contains("not re-checked: coqc did not behave as Coq (it accepted a false lemma)"));
        // A theorem refused for its statement (closed, but not the pinned statement).
        let mut weakened = clean.clone();
        weakened.theorems[0].refused = Some("Coq's statement differs from the pinned one".into());
        let first = weakened.theorems[0].name.clone();
        let claim_of_first = coq::THEOREMS[0].claim;
        let mut r = claim(claim_of_first, Verdict::Refuted);
        attach_coq(&mut r, &weakened);
        assert_eq!(r.engine, "exhaustive enumeration");
        assert!(r.notes.iter().any(|n| n.contains(&first)
            && n.contains("NOT accepted: Coq's statement differs from the pinned one")));
        // Theorems about the paper's worked example give the example's level, never "every
        // finite problem"; the scope says what they quantify over.
        let mut r = claim("C3-example", Verdict::Proved);
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::ProvedCoqExample);
        assert_eq!(r.verdict.name(), "proved in Coq for the paper's example");
        assert!(
            r.scope
                .starts_with("the paper's worked example (one fixed problem): "),
            "{}",
            r.scope
        );
        let mut r = claim("C3", Verdict::Proved);
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::ProvedCoq);
        assert!(r.scope.starts_with("every finite problem: "), "{}", r.scope);
        // A claim without a Coq theorem is left alone.
        let mut r = claim("C9", Verdict::Proved);
        attach_coq(&mut r, &clean);
        assert_eq!((r.verdict, r.engines.len()), (Verdict::Proved, 0));
    }

    /// A Coq result against another engine's verdict is a disagreement: inconclusive. The
    /// refutation of C1 as printed confirms the enumeration's `refuted` and keeps its
    /// counterexample's engine.
    #[test]
    fn coq_against_another_engine_is_inconclusive() {
        let clean = coq_check(coq::Outcome::Checked, coq::Assumptions::Closed);
        let mut r = claim("C1-corrected", Verdict::Refuted);
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::Inconclusive);
        assert!(r
            .notes
            .iter()
            .any(|n| n.starts_with("engines disagree (coq")));
        let mut r = claim("C1", Verdict::Verified);
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::Inconclusive);
        let mut r = claim("C1", Verdict::Refuted);
        attach_coq(&mut r, &clean);
        assert_eq!(
            (r.verdict, r.engine.as_str()),
            (Verdict::Refuted, "exhaustive enumeration")
        );
        // An earlier disagreement is not overruled.
        let mut r = claim("C2", Verdict::Inconclusive);
        r.notes
            .push("engines disagree (smt against enumeration/proptest): inconclusive".into());
        attach_coq(&mut r, &clean);
        assert_eq!(r.verdict, Verdict::Inconclusive);
    }

    /// What a harness run here means for its claim: one that does what it states leaves the
    /// verdict; one whose assertion fails (a counterexample found by the stand-in) makes a claim
    /// that holds inconclusive, noted as a disagreement; one broken otherwise (a cover never
    /// satisfied) is noted and leaves the verdict; not run, the line says so.
    #[test]
    fn a_harness_failing_here_contradicts_a_claim_that_holds() {
        let h = harnesses::of_claim("C2")[0];
        let ok = StandinRun {
            name: h.name.into(),
            mode: "sampled".into(),
            executions: 10,
            distinct: 10,
            pruned: 0,
            failures: 0,
            choice_bits: 99,
            covers_hit: 2,
            covers: 2,
            should_panic: false,
            problem: None,
            seconds: 0.0,
        };
        let mut r = claim("C2", Verdict::Proved);
        attach_harness(&mut r, h, Some(std::slice::from_ref(&ok)));
        assert_eq!((r.verdict, r.notes.len()), (Verdict::Proved, 0));
        assert_eq!((r.engines[0].cases, r.engines[0].failures), (10, 0));
        let failing = StandinRun {
            failures: 3,
            problem: Some("c2 fails: argmin cost = argmax reward".into()),
            ..ok.clone()
        };
        let mut r = claim("C2", Verdict::Proved);
        attach_harness(&mut r, h, Some(std::slice::from_ref(&failing)));
        assert_eq!(r.verdict, Verdict::Inconclusive);
        assert!(r.notes[0].starts_with("engines disagree (kani harness"));
        assert!(r.engines[0]
            .mode
            .contains("sampled 10 executions, 3 failures, covers 2/2 hit"));
        assert!(r.engines[0].mode.contains("HARNESS FAILS: c2 fails"));
        // Later engines do not overrule the disagreement.
        attach_coq(
            &mut r,
            &coq_check(coq::Outcome::Checked, coq::Assumptions::Closed),
        );
        assert_eq!(r.verdict, Verdict::Inconclusive);
        let uncovered = StandinRun {
            covers_hit: 1,
            problem: Some("cover \"x\" was never satisfied".into()),
            ..ok.clone()
        };
        let mut r = claim("C2", Verdict::Proved);
        attach_harness(&mut r, h, Some(std::slice::from_ref(&uncovered)));
        assert_eq!(r.verdict, Verdict::Proved);
        assert!(r.notes[0].contains("did not do what it states"));
        let mut r = claim("C2", Verdict::Proved);
        attach_harness(&mut r, h, None);
        assert!(r.engines[0].mode.starts_with("NOT run by this verify"));
        assert_eq!(r.verdict, Verdict::Proved);
    }

    /// A panicking engine becomes its engine line, `engine failed: <message>` (escaped, with
    /// where it panicked): a claim checker's panic gives the claim from its statement with that
    /// one line, and the other engines still attach; a claim with a failed engine is
    /// inconclusive whatever the others found; the failures are listed for the exit status,
    /// and the text report prints each.
    #[test]
    fn a_panicking_engine_becomes_its_line_and_the_claim_is_inconclusive() {
        let failure = caught(|| -> ClaimResult { panic!("planted\nin the enumeration") });
        let mut a = failed_claims(Checker::C2, &failure.unwrap_err()).remove(0);
        assert_eq!(a.statement, c2::STATEMENT);
        assert_eq!((a.verdict, a.cases), (Verdict::Inconclusive, 0));
        assert_eq!(a.engines.len(), 1);
        let line = &a.engines[0];
        assert_eq!(line.engine, "exhaustive enumeration");
        assert!(
            line.mode.starts_with(
                "engine failed: planted\\nin the enumeration (at src/claims/registry.rs:"
            ),
            "{}",
            line.mode
        );
        attach(
            &mut a,
            Some(caught(|| -> (PropertyRun, f64) {
                panic!("planted in proptest")
            })),
            None,
        );
        let names: Vec<&str> = a.engines.iter().map(|e| e.engine.as_str()).collect();
        assert_eq!(
            names,
            [
                "exhaustive enumeration",
                "kani harness c2_oracle_argmin_cost_is_argmax_reward",
                "proptest"
            ]
        );
        assert!(a.engines[2]
            .mode
            .starts_with("engine failed: planted in proptest (at "));
        // A claim that holds by its other engines, with one failed engine: inconclusive.
        let mut d = claim("C4-corrected", Verdict::Proved);
        d.engines
            .push(failed_engine("smt (Z3)", "planted in the solver"));
        settle_engine_failures(&mut d);
        assert_eq!(d.verdict, Verdict::Inconclusive);
        assert_eq!(d.engine, "none: smt (Z3) failed");
        assert!(d.notes[0].starts_with("engine failed (smt (Z3)): inconclusive"));
        let mut e = claim("C3", Verdict::Verified);
        settle_engine_failures(&mut e);
        assert_eq!((e.verdict, e.notes.len()), (Verdict::Verified, 0));
        settle_engine_failures(&mut a);
        let report = Report {
            harnesses: Some(HarnessSection {
                summary: String::new(),
                lemmas: vec![failed_engine("kani harness h", "planted in the stand-in")],
                overflow_checks: None,
            }),
            solver: None,
            coq: None,
            smt: vec![],
            tool: "truecost".into(),
            commit: "unknown".into(),
            scope: Scope::Smoke,
            claims: vec![a, d, e],
            alpha_star: None,
        };
        assert_eq!(
            engine_failures(&report),
            [
                "C2: exhaustive enumeration",
                "C2: proptest",
                "C4-corrected: smt (Z3)",
                "lemmas: kani harness h"
            ]
        );
        let text = crate::claims::report::text(&report, false);
        assert!(
            text.contains("\n  engine: exhaustive enumeration: engine failed: planted\\nin the enumeration (at "),
            "{text}"
        );
        assert!(text.contains("\n  engine: smt (Z3): engine failed: planted in the solver\n"));
        assert!(
            text.contains("\n  engine: kani harness h: engine failed: planted in the stand-in\n")
        );
        assert!(text.contains("C2  INCONCLUSIVE\n"));
    }

    /// How the SMT engine's verdict combines with the enumeration's (the doc comment of
    /// `attach_smt`): `proved` over `verified`, a contradiction gives `inconclusive`, anything
    /// else leaves the enumeration's verdict. Every pair, worked by hand.
    #[test]
    fn the_smt_verdict_combines_with_the_enumeration_s() {
        use SmtVerdict as S;
        use Verdict as V;
        let all = [V::Verified, V::Refuted, V::Inconclusive];
        for (smt_verdict, before) in [S::Proved, S::Refuted, S::Inconclusive]
            .into_iter()
            .flat_map(|s| all.map(|v| (s, v)))
        {
            let mut r = enumerated(before);
            attach_smt(&mut r, &smt(smt_verdict));
            let expected = match (smt_verdict, before) {
                (S::Proved, V::Verified) => V::Proved,
                (S::Proved, V::Refuted) | (S::Refuted, V::Verified) => V::Inconclusive,
                (_, v) => v,
            };
            assert_eq!(r.verdict, expected, "{smt_verdict:?} with {before:?}");
            let disagree = r.notes.iter().any(|n| n.contains("engines disagree"));
            assert_eq!(
                disagree,
                expected == V::Inconclusive && before != V::Inconclusive,
                "{smt_verdict:?} with {before:?}"
            );
            let e = &r.engines[0];
            assert_eq!(e.engine, "smt (Z3)");
            // 11 obligations, 8 unsat; 5 trust checks, 3 as required; a refutation counts
            // its satisfiable printed searches, at least one.
            let failures = if smt_verdict == S::Refuted { 1 } else { 3 + 2 };
            assert_eq!((e.cases, e.failures), (11 + 5, failures));
            if expected == V::Proved {
                assert_eq!(
                    (r.engine.as_str(), r.scope.as_str(), r.cases),
                    ("smt (Z3)", "symbolic", 11)
                );
            } else {
                assert_eq!(
                    (r.engine.as_str(), r.scope.as_str(), r.cases),
                    ("exhaustive enumeration", "enumerated", 7)
                );
            }
            assert!(r.notes.iter().any(|n| n == "an outcome note"));
        }
    }
}

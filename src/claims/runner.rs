//! The runner of `truecost verify`: runs the units of a plan ([`super::plan`]) step by step and
//! returns their values, keyed by unit id, for the registry's report
//! ([`super::registry::report`]). It runs in one of three modes ([`Mode`]):
//!
//! * **whole** — every unit in full: the run `truecost verify` reports;
//! * **shard** `K/N` — the units [`super::shard::select`] chose, and of every split unit
//!   (a claim checker) only the labelled indices `i ≡ K − 1 (mod N)` of each enumeration it
//!   meets ([`split`]): what it computes is recorded, step by step, for the shard file;
//! * **merge** — no unit is computed: an owned unit's value is read from the record of the
//!   shard that owns it, and a claim checker is run again with every enumeration answered by the
//!   merge (the accumulator's own associative and commutative `merge`) of the shards' partial
//!   accumulators. The claims are then derived from exactly the values the whole run derives
//!   them from, so the merged report is the whole run's, byte for byte (times aside).
//!
//! **Engine failures.** Every step runs under [`caught`]: a panic in an engine (a bug in the
//! code it checks, or in itself) becomes the failure of the step's units, which the report
//! turns into that engine's line, `engine failed: <message>`. A shard records the failure as
//! the value of the unit or enumeration that panicked and as the failure of the step; the merge
//! raises it again where the failed shard would have answered, so the merged report has the
//! same engine line.

use std::cell::RefCell;
use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use serde::de::DeserializeOwned;
use serde::Serialize;

use super::caught::{caught, raise, ENGINE_FAILED};
use super::coq;
use super::harnesses::{self, StandinRun};
use super::plan::{Checker, Plan, Step, Unit, Work};
use super::sampled::{self, PropertyRun};
use super::shard::{Entry, Part, Share, StepRecord};
use super::smt::{self, Solved, SolvedRecord};
use super::tiny::Tiny;
use super::{alpha, c1, c2, c3, c4, ClaimResult};
use crate::algebra::poly::Algebraic;

/// What one unit gave.
#[derive(Clone, Debug)]
pub enum Value {
    /// A checker's claims, in the order of [`Checker::claims`]; C3's example also gives `α*`
    /// when it was isolated.
    Checked(Vec<ClaimResult>, Option<Algebraic>),
    /// A harness run through the stand-in.
    Harness(StandinRun),
    /// A proptest run and its wall-clock seconds.
    Property(PropertyRun, f64),
    /// An SMT obligation with Z3's answer.
    Obligation(Solved),
    /// The re-check of the Coq development.
    Coq(coq::Check),
}

/// Every unit's value, or the failure of its engine (`engine failed: …` follows), by unit id.
pub type Values = BTreeMap<String, Result<Value, String>>;

/// How the runner answers the units.
#[derive(Clone, Copy, Debug)]
pub enum Mode<'a> {
    /// Computes every selected unit in full.
    Whole,
    /// Computes shard `K/N`'s part of the selected units and records it.
    Shard(Part),
    /// Answers every unit from the shards' records: for each step of the plan, every shard's
    /// record of it, in shard order ([`super::shard::merge`]).
    Merge(&'a [Vec<StepRecord>]),
}

/// What a run gave.
#[derive(Debug, Default)]
pub struct Ran {
    /// Every unit's value (whole run and merge; a shard's values are partial).
    pub values: Values,
    /// What the shard records, one record per step of the plan (shard mode only).
    pub records: Vec<StepRecord>,
}

/// Runs the plan's units `selected` (from [`super::shard::select`]) step by step in `mode`.
/// Fails only in a merge, when the shards' records do not answer the plan (shards of a
/// different build, or edited records).
///
/// ```
/// use truecost::claims::registry::{fingerprint, plan, report, Options};
/// use truecost::claims::runner::{run, Mode};
/// use truecost::claims::shard::{self, Part};
/// use truecost::claims::{report as render, Scope};
/// let options = Options { smt: false, ..Options::default() };
/// let plan = plan(Scope::Smoke, Some("C2"), &options).unwrap();
/// let files: Vec<(String, String)> = (1..=2)
///     .map(|k| {
///         let part = Part::parse(&format!("{k}/2")).unwrap();
///         let ran = run(&plan, &shard::select(plan.units(), Some(part)), Mode::Shard(part)).unwrap();
///         let file = shard::file(part, fingerprint(Scope::Smoke, Some("C2"), &options), ran.records, 0.0);
///         (format!("shard{k}.json"), file.to_json(shard::VERIFY_FORMAT))
///     })
///     .collect();
/// let merged = shard::merge(&files).unwrap();
/// let replayed = run(&plan, &shard::select(plan.units(), None), Mode::Merge(&merged.steps)).unwrap();
/// let whole = run(&plan, &shard::select(plan.units(), None), Mode::Whole).unwrap();
/// assert_eq!(
///     render::json(&report(&plan, &replayed.values), false),
///     render::json(&report(&plan, &whole.values), false)
/// );
/// ```
pub fn run(plan: &Plan, selected: &[&Unit], mode: Mode) -> Result<Ran, String> {
    let chosen: BTreeSet<&str> = selected.iter().map(|u| u.id.as_str()).collect();
    let mut ran = Ran::default();
    if let Mode::Merge(steps) = mode {
        if steps.len() != plan.steps.len() {
            return Err(format!(
                "the shards recorded {} engine runs, this plan has {} (shards of a different build?)",
                steps.len(),
                plan.steps.len()
            ));
        }
    }
    for (i, step) in plan.steps.iter().enumerate() {
        let part = match mode {
            Mode::Merge(steps) => {
                let values = merge_step(plan, step, &steps[i])?;
                ran.values.extend(values);
                continue;
            }
            Mode::Whole => None,
            Mode::Shard(part) => Some(part),
        };
        let (values, record) = run_step(plan, step, &chosen, part);
        ran.values.extend(values);
        if part.is_some() {
            ran.records.push(record);
        }
    }
    Ok(ran)
}

/// Runs the chosen units of `step` (shard `part`'s part of a split unit; `None`: all of it):
/// their values, and what a shard records of the step.
fn run_step(
    plan: &Plan,
    step: &Step,
    chosen: &BTreeSet<&str>,
    part: Option<Part>,
) -> (Values, StepRecord) {
    if let Some(failure) = &step.failed {
        let record = StepRecord {
            entries: vec![],
            failure: Some(failure.clone()),
        };
        return (Values::new(), record);
    }
    if let [unit] = step.units.as_slice() {
        if let (Work::Checker(checker), Share::Split) = (unit.work, unit.share) {
            let (result, entries) = recording(part, || caught(|| check(plan, checker)));
            let record = StepRecord {
                entries,
                failure: result.as_ref().err().cloned(),
            };
            return (Values::from([(unit.id.clone(), result)]), record);
        }
    }
    let mine: Vec<&Unit> = step
        .units
        .iter()
        .filter(|u| chosen.contains(u.id.as_str()))
        .collect();
    let computed = caught(|| compute(plan, &mine));
    let failure = computed.as_ref().err().cloned();
    let values: Values = match computed {
        Ok(values) => mine
            .iter()
            .map(|u| u.id.clone())
            .zip(values.into_iter().map(Ok))
            .collect(),
        Err(failure) => mine
            .iter()
            .map(|u| (u.id.clone(), Err(failure.clone())))
            .collect(),
    };
    let entries = step
        .units
        .iter()
        .map(|u| Entry {
            site: u.id.clone(),
            value: match values.get(&u.id) {
                None => None,
                Some(Ok(v)) => Some(v.record()),
                Some(Err(failure)) => Some(format!("{ENGINE_FAILED}{failure}")),
            },
        })
        .collect();
    (values, StepRecord { entries, failure })
}

/// Computes owned units of one step together (in parallel where the engine runs so): their
/// values, in order.
fn compute(plan: &Plan, units: &[&Unit]) -> Vec<Value> {
    let Some(first) = units.first() else {
        return vec![];
    };
    match first.work {
        Work::Harness(_) => {
            let names: Vec<&str> = units
                .iter()
                .filter_map(|u| match u.work {
                    Work::Harness(h) => Some(h.name),
                    _ => None,
                })
                .collect();
            let table = plan
                .harness_table
                .expect("harness units are planned with a table");
            harnesses::run_standin(&table(), &names)
                .into_iter()
                .map(Value::Harness)
                .collect()
        }
        Work::Property(claim) => {
            let (p, seconds) = timed(|| property(plan, claim));
            vec![Value::Property(p, seconds)]
        }
        Work::Obligation(claim, _) => {
            let enc = plan
                .encoding(claim)
                .expect("obligations are planned from an encoding");
            let obligations = units
                .iter()
                .filter_map(|u| match u.work {
                    Work::Obligation(_, j) => Some(enc.obligations[j].clone()),
                    _ => None,
                })
                .collect();
            let timeout = plan.smt_timeout_ms.unwrap_or(smt::TIMEOUT_MS);
            smt::discharge(obligations, timeout)
                .into_iter()
                .map(Value::Obligation)
                .collect()
        }
        Work::Coq => vec![Value::Coq(coq::recheck(plan.coq_timeout))],
        Work::Checker(checker) => vec![check(plan, checker)],
    }
}

/// Runs a claim checker on the plan's scope.
fn check(plan: &Plan, checker: Checker) -> Value {
    let scope = plan.scope;
    match checker {
        Checker::C1 => {
            let (a, b) = c1::check(scope);
            Value::Checked(vec![a, b], None)
        }
        Checker::C2 => Value::Checked(vec![c2::check(scope)], None),
        Checker::C3 => Value::Checked(vec![c3::check(scope)], None),
        Checker::Example => {
            let (example, star) = alpha::check();
            Value::Checked(vec![example], star)
        }
        Checker::C4 => {
            let (a, b) = c4::check(scope);
            Value::Checked(vec![a, b], None)
        }
    }
}

/// Runs the proptest property of `claim` (engine 2) with the plan's number of cases.
fn property(plan: &Plan, claim: &'static str) -> PropertyRun {
    let n = sampled::cases(plan.scope);
    match claim {
        "C1" => sampled::c1_printed(n, None),
        "C1-corrected" => sampled::c1_corrected(n, None),
        "C2" => sampled::c2(n, None),
        "C3" => sampled::c3(n, None),
        "C4" => sampled::c4(true, n, None),
        "C4-corrected" => sampled::c4(false, n, None),
        other => unreachable!("no property is planned for {other}"),
    }
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let s = Instant::now();
    let v = f();
    (v, s.elapsed().as_secs_f64())
}

/// A proptest run as a shard records it.
#[derive(Serialize, serde::Deserialize)]
struct PropertyRecord {
    cases: u64,
    relevant: u64,
    counterexample: Option<(Tiny, String)>,
    scope: String,
    seconds: f64,
}

impl Value {
    /// The value as a shard file records it: JSON text (so that 128-bit integers survive
    /// exactly). A checker records its enumerations instead ([`split`]).
    fn record(&self) -> String {
        match self {
            Value::Harness(run) => encode(run),
            Value::Property(p, seconds) => encode(&PropertyRecord {
                cases: p.cases,
                relevant: p.relevant,
                counterexample: p.counterexample.clone(),
                scope: p.scope.clone(),
                seconds: *seconds,
            }),
            Value::Obligation(solved) => encode(&SolvedRecord::of(solved)),
            Value::Coq(check) => encode(check),
            Value::Checked(..) => unreachable!("a checker records its enumerations"),
        }
    }

    /// The value of owned unit `unit` from the record `text` of the shard that ran it.
    fn read(plan: &Plan, unit: &Unit, text: &str) -> Result<Value, String> {
        let site = unit.id.as_str();
        Ok(match unit.work {
            Work::Harness(_) => Value::Harness(decode(site, text)?),
            Work::Property(claim) => {
                let r: PropertyRecord = decode(site, text)?;
                let run = PropertyRun {
                    claim,
                    cases: r.cases,
                    relevant: r.relevant,
                    counterexample: r.counterexample,
                    scope: r.scope,
                };
                Value::Property(run, r.seconds)
            }
            Work::Obligation(claim, j) => {
                let r: SolvedRecord = decode(site, text)?;
                let enc = plan
                    .encoding(claim)
                    .expect("obligations are planned from an encoding");
                Value::Obligation(r.solved(enc.obligations[j].clone()))
            }
            Work::Coq => Value::Coq(decode(site, text)?),
            Work::Checker(_) => unreachable!("a checker is split, never owned"),
        })
    }
}

fn decode<T: DeserializeOwned>(site: &str, text: &str) -> Result<T, String> {
    serde_json::from_str(text).map_err(|e| format!("site '{site}': malformed value ({e})"))
}

fn encode<T: Serialize>(value: &T) -> String {
    serde_json::to_string(value).expect("a recorded value is serialisable")
}

/// The failure a shard recorded as a value, if it is one.
fn failed_value(text: &str) -> Option<&str> {
    text.strip_prefix(ENGINE_FAILED)
}

/// The values of `step` from every shard's record of it (shard order).
fn merge_step(plan: &Plan, step: &Step, records: &[StepRecord]) -> Result<Values, String> {
    if let [unit] = step.units.as_slice() {
        if let (Work::Checker(checker), Share::Split) = (unit.work, unit.share) {
            let result = replaying(records, || caught(|| check(plan, checker)))?;
            return Ok(Values::from([(unit.id.clone(), result)]));
        }
    }
    let mut values = Values::new();
    let mut failure = None;
    for (j, unit) in step.units.iter().enumerate() {
        let mut texts = Vec::new();
        for r in records {
            match r.entries.get(j) {
                Some(e) if e.site == unit.id => texts.extend(e.value.as_deref()),
                _ => return Err(met_another(&unit.id)),
            }
        }
        // The engine failed at this unit in some shard: the rest of the step is not read.
        if let Some(f) = texts.iter().find_map(|t| failed_value(t)) {
            failure = Some(f.to_string());
            break;
        }
        let value = match texts.as_slice() {
            [text] => Value::read(plan, unit, text)?,
            [] => return Err(format!("site '{}': no shard ran it", unit.id)),
            _ => return Err(format!("site '{}': run by two shards", unit.id)),
        };
        values.insert(unit.id.clone(), Ok(value));
    }
    if failure.is_none() {
        if let Some(r) = records.iter().find(|r| r.entries.len() > step.units.len()) {
            return Err(did_not_meet(r));
        }
    }
    let failure = failure.or_else(|| records.iter().find_map(|r| r.failure.clone()));
    if let Some(failure) = failure {
        for unit in &step.units {
            values.insert(unit.id.clone(), Err(failure.clone()));
        }
    }
    Ok(values)
}

fn met_another(site: &str) -> String {
    format!(
        "the merge met site '{site}' where the shards recorded another (shards of a different build?)"
    )
}

fn did_not_meet(r: &StepRecord) -> String {
    let site = r.entries.last().map_or("", |e| e.site.as_str());
    format!(
        "the shards recorded sites of an engine the merge did not meet (up to '{site}'; shards of a different build?)"
    )
}

/// What the enumerations of the checker running on this thread do ([`split`]).
enum Context {
    /// Visit shard `part`'s labelled indices and record each enumeration's accumulator.
    Part(Part, Vec<Entry>),
    /// Answer each enumeration from the shards' records of the step (`next[s]`: the next entry
    /// of shard `s`); the first problem met is kept.
    Replay {
        records: Vec<StepRecord>,
        next: Vec<usize>,
        error: Option<String>,
    },
}

thread_local! {
    static CONTEXT: RefCell<Option<Context>> = const { RefCell::new(None) };
}

/// Runs `f` (a checker) with its enumerations doing shard `part`'s part and recording it
/// (`None`: in full, nothing recorded); returns its value and the recorded entries.
fn recording<T>(part: Option<Part>, f: impl FnOnce() -> T) -> (T, Vec<Entry>) {
    let Some(part) = part else {
        return (f(), vec![]);
    };
    let previous = CONTEXT.with(|c| c.borrow_mut().replace(Context::Part(part, vec![])));
    let value = f();
    match CONTEXT.with(|c| std::mem::replace(&mut *c.borrow_mut(), previous)) {
        Some(Context::Part(_, entries)) => (value, entries),
        _ => unreachable!("the shard's context was replaced while its checker ran"),
    }
}

/// Runs `f` (a checker under [`caught`]) with its enumerations answered from the shards'
/// `records` of its step; then the step's failure: the checker's own, or, if it ran to its end,
/// the first shard's. Fails if the checker met an enumeration the shards did not record, or left
/// some unread although no shard failed.
fn replaying<T>(
    records: &[StepRecord],
    f: impl FnOnce() -> Result<T, String>,
) -> Result<Result<T, String>, String> {
    let context = Context::Replay {
        records: records.to_vec(),
        next: vec![0; records.len()],
        error: None,
    };
    let previous = CONTEXT.with(|c| c.borrow_mut().replace(context));
    let result = f();
    let context = CONTEXT.with(|c| std::mem::replace(&mut *c.borrow_mut(), previous));
    let Some(Context::Replay {
        records,
        next,
        error,
    }) = context
    else {
        unreachable!("the merge's context was replaced while its checker ran")
    };
    if let Some(e) = error {
        return Err(e);
    }
    for (r, &j) in records.iter().zip(&next) {
        if j < r.entries.len() && result.is_ok() && r.failure.is_none() {
            return Err(did_not_meet(r));
        }
    }
    Ok(
        match (result, records.iter().find_map(|r| r.failure.clone())) {
            (Ok(_), Some(failure)) => Err(failure),
            (result, _) => result,
        },
    )
}

/// An enumeration of a claim checker ([`super::enumerate`]): `compute(part)` does the part of
/// the work `part` owns (`None`: all of it), and `combine` is associative and commutative.
///
/// Whole run: `compute(None)`. Shard: `compute(Some(part))`, recorded under `site` (a panic is
/// recorded as its value, then raised again). Merge: the `combine` of every shard's recorded
/// value (`compute` is not called); `empty()` if a value is unreadable (the merge then fails
/// with the reason).
pub fn split<T: Serialize + DeserializeOwned>(
    site: &str,
    compute: impl FnOnce(Option<Part>) -> T,
    combine: impl Fn(T, T) -> T,
    empty: impl Fn() -> T,
) -> T {
    enum Answer {
        Whole,
        Shard(Part),
        Merged(Vec<Option<String>>),
        Broken,
    }
    let answer = CONTEXT.with(|c| match c.borrow_mut().as_mut() {
        None => Answer::Whole,
        Some(Context::Part(part, _)) => Answer::Shard(*part),
        Some(Context::Replay {
            records,
            next,
            error,
        }) => {
            let values: Option<Vec<Option<String>>> = records
                .iter()
                .zip(next.iter_mut())
                .map(|(r, j)| match r.entries.get(*j) {
                    None => r
                        .failure
                        .as_ref()
                        .map(|failure| Some(format!("{ENGINE_FAILED}{failure}"))),
                    Some(entry) => {
                        *j += 1;
                        (entry.site == site).then(|| entry.value.clone())
                    }
                })
                .collect();
            match values {
                Some(values) => Answer::Merged(values),
                None => {
                    error.get_or_insert_with(|| met_another(site));
                    Answer::Broken
                }
            }
        }
    });
    match answer {
        Answer::Whole => compute(None),
        Answer::Shard(part) => {
            let v = caught(|| compute(Some(part))).unwrap_or_else(|failure| {
                push(site, format!("{ENGINE_FAILED}{failure}"));
                raise(failure)
            });
            push(site, encode(&v));
            v
        }
        Answer::Merged(values) => {
            if let Some(failure) = values.iter().flatten().find_map(|t| failed_value(t)) {
                raise(failure.to_string());
            }
            let mut acc: Option<T> = None;
            for text in values {
                let Some(text) = text else {
                    fail(format!("site '{site}': a shard recorded no value"));
                    return empty();
                };
                match decode::<T>(site, &text) {
                    Ok(v) => {
                        acc = Some(match acc {
                            Some(a) => combine(a, v),
                            None => v,
                        })
                    }
                    Err(e) => {
                        fail(e);
                        return empty();
                    }
                }
            }
            acc.unwrap_or_else(empty)
        }
        Answer::Broken => empty(),
    }
}

fn push(site: &str, value: String) {
    CONTEXT.with(|c| {
        if let Some(Context::Part(_, entries)) = c.borrow_mut().as_mut() {
            entries.push(Entry {
                site: site.to_string(),
                value: Some(value),
            });
        }
    });
}

fn fail(message: String) {
    CONTEXT.with(|c| {
        if let Some(Context::Replay { error, .. }) = c.borrow_mut().as_mut() {
            error.get_or_insert(message);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum_of_owned(part: Option<Part>) -> u64 {
        (0..100u64)
            .filter(|&i| part.is_none_or(|p| p.owns(i)))
            .sum()
    }

    fn sum(site: &str) -> u64 {
        split(site, sum_of_owned, |a, b| a + b, || 0)
    }

    /// A checker with two enumerations.
    fn two_sums() -> (u64, u64) {
        (sum("first"), sum("second"))
    }

    fn part(k: u32, n: u32) -> Part {
        Part::parse(&format!("{k}/{n}")).unwrap()
    }

    /// Each shard's records of `f`, as a step of the plan records them.
    fn shards<T>(n: u32, f: impl Fn() -> T) -> Vec<StepRecord> {
        (1..=n)
            .map(|k| {
                let (result, entries) = recording(Some(part(k, n)), || caught(&f));
                StepRecord {
                    entries,
                    failure: result.err(),
                }
            })
            .collect()
    }

    /// Three shards split the sums 0+…+99 = 4950; the merge answers every enumeration as the
    /// whole run does, and the whole run records nothing.
    #[test]
    fn three_shards_merge_to_the_whole_run() {
        let (whole, entries) = recording(None, two_sums);
        assert_eq!((whole, entries.len()), ((4950, 4950), 0));
        let records = shards(3, two_sums);
        for (k, r) in records.iter().enumerate() {
            let names: Vec<&str> = r.entries.iter().map(|e| e.site.as_str()).collect();
            assert_eq!(names, ["first", "second"]);
            let own: u64 = (0..100).filter(|i| i % 3 == k as u64).sum();
            assert_eq!(r.entries[0].value, Some(own.to_string()));
        }
        assert_eq!(
            replaying(&records, || caught(two_sums)),
            Ok(Ok((4950, 4950)))
        );
    }

    /// An enumeration that panics in shard 1's part only: shard 1 records the failure as the
    /// enumeration's value and stops; the merge raises it again at the same site, with the same
    /// description, although shard 2 went on to the next enumeration.
    #[test]
    fn an_enumeration_failing_in_one_shard_fails_in_the_merge() {
        fn checker() -> u64 {
            let first = split(
                "first",
                |part| {
                    assert!(part.is_none_or(|p| p.k() != 1), "planted in shard 1");
                    sum_of_owned(part)
                },
                |a, b| a + b,
                || 0,
            );
            first + sum("second")
        }
        assert_eq!(caught(checker), Ok(2 * 4950));
        let records = shards(2, checker);
        let failure = records[0].failure.clone().unwrap();
        assert!(failure.starts_with("planted in shard 1 (at "), "{failure}");
        assert_eq!(records[0].entries.len(), 1);
        assert_eq!(
            records[0].entries[0].value,
            Some(format!("{ENGINE_FAILED}{failure}"))
        );
        assert_eq!((records[1].entries.len(), &records[1].failure), (2, &None));
        assert_eq!(replaying(&records, || caught(checker)), Ok(Err(failure)));
    }

    /// A merge that meets an enumeration the shards did not record, or leaves one unread
    /// although no shard failed, is refused; so are tampered values, naming the site.
    #[test]
    fn a_merge_of_other_or_tampered_records_is_refused() {
        let records = shards(1, two_sums);
        let swapped = || caught(|| (sum("second"), sum("first")));
        let e = replaying(&records, swapped).unwrap_err();
        assert!(e.contains("met site 'second'"), "{e}");
        let e = replaying(&records, || caught(|| sum("first"))).unwrap_err();
        assert!(e.contains("the merge did not meet (up to 'second'"), "{e}");
        let tampered = |edit: &dyn Fn(&mut Entry)| {
            let mut records = records.clone();
            edit(&mut records[0].entries[0]);
            replaying(&records, || caught(two_sums))
        };
        assert_eq!(
            tampered(&|e| e.value = None),
            Err("site 'first': a shard recorded no value".into())
        );
        let e = tampered(&|e| e.value = Some("not json".into())).unwrap_err();
        assert!(e.starts_with("site 'first': malformed value"), "{e}");
    }

    /// A plan of one owned unit, C2's proptest run.
    fn property_plan() -> Plan {
        let unit = Unit {
            id: "proptest C2".into(),
            work: Work::Property("C2"),
            share: Share::Owned(0),
        };
        Plan {
            scope: super::super::Scope::Smoke,
            claims: vec!["C2"],
            harnesses: vec![],
            harness_table: None,
            smt_timeout_ms: None,
            encodings: vec![],
            coq_timeout: std::time::Duration::from_secs(1),
            steps: vec![Step {
                engine: "proptest",
                claim: Some("C2"),
                units: vec![unit],
                failed: None,
            }],
        }
    }

    /// An owned unit is answered by the one shard that ran it; a unit no shard ran or two
    /// shards ran is refused; a failure recorded by its owner fails the unit with its
    /// description.
    #[test]
    fn an_owned_unit_is_answered_by_its_owner_alone() {
        let plan = property_plan();
        let step = &plan.steps[0];
        let run = PropertyRun {
            claim: "C2",
            cases: 5,
            relevant: 4,
            counterexample: None,
            scope: "five problems".into(),
        };
        let text = Value::Property(run.clone(), 0.25).record();
        let record = |value: Option<&str>, failure: Option<&str>| StepRecord {
            entries: vec![Entry {
                site: "proptest C2".into(),
                value: value.map(String::from),
            }],
            failure: failure.map(String::from),
        };
        let merged = merge_step(
            &plan,
            step,
            &[record(None, None), record(Some(&text), None)],
        );
        match merged.unwrap().get("proptest C2") {
            Some(Ok(Value::Property(p, seconds))) => assert_eq!((p, *seconds), (&run, 0.25)),
            other => panic!("{other:?}"),
        }
        let e = merge_step(&plan, step, &[record(None, None), record(None, None)]);
        assert_eq!(e.unwrap_err(), "site 'proptest C2': no shard ran it");
        let two = [record(Some(&text), None), record(Some(&text), None)];
        let e = merge_step(&plan, step, &two);
        assert_eq!(e.unwrap_err(), "site 'proptest C2': run by two shards");
        let failed = format!("{ENGINE_FAILED}planted");
        let values = merge_step(
            &plan,
            step,
            &[record(None, None), record(Some(&failed), Some("planted"))],
        )
        .unwrap();
        assert_eq!(values["proptest C2"].as_ref().unwrap_err(), "planted");
        let e = merge_step(&plan, step, &[record(None, None)]);
        assert!(e.is_err());
        let other = StepRecord {
            entries: vec![Entry {
                site: "proptest C3".into(),
                value: Some(text.clone()),
            }],
            failure: None,
        };
        let e = merge_step(&plan, step, &[other]).unwrap_err();
        assert!(e.contains("met site 'proptest C2'"), "{e}");
    }
}

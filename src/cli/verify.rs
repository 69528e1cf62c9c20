//! `truecost verify`: the paper's four propositions (`docs/spec.md`) checked by machine, and, with
//! `--claim C4 --file F | --problem N`, the exact set of bonuses `M` for one problem.

use std::fmt::Write;
use std::path::PathBuf;

use clap::{Args, Subcommand, ValueEnum};
use num_bigint::BigInt;
use serde_json::json;

use truecost::claims::c4::{
    bonus_analysis, bonus_policy_limit, contains_unscaled, End, Instance, Interval,
};
use truecost::claims::certificates::{self, Single};
use truecost::claims::exact::Q;
use truecost::claims::runner::{self, Mode};
use truecost::claims::shard::{self, Part};
use truecost::claims::{registry, report, Scope};
use truecost::model::{file, Problem};
use truecost::problems::{GridLayout, StepCost};

/// Output format of the claims report.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum VerifyFormat {
    /// Readable text.
    Text,
    /// One JSON object.
    Json,
    /// Markdown.
    Markdown,
    /// A LaTeX table (with the tool version and git commit).
    Latex,
}

/// Arguments of `verify`.
#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true)]
pub struct VerifyArgs {
    /// `verify merge FILES…`: combine shard files.
    #[command(subcommand)]
    command: Option<VerifyCommand>,
    /// Run shard K of N (1 <= K <= N <= 4096) and write its partial report (a JSON shard
    /// file) to stdout; `verify merge` combines the N files into the whole run's report.
    #[arg(long, value_name = "K/N", conflicts_with_all = ["counterexamples", "smt_out", "file", "problem", "env", "initial", "format", "no_times", "certificates"])]
    shard: Option<String>,
    /// Check one claim only (C1, C1-corrected, C2, C3, C3-example, C4, C4-corrected; C1 also
    /// selects C1-corrected, and so on).
    #[arg(long, value_name = "ID")]
    claim: Option<String>,
    /// How much to check: quick (CI, about a minute), full (larger problems); smoke is the
    /// test suite's small scope.
    #[arg(long, value_enum, default_value_t = Scope::Quick)]
    scope: Scope,
    /// Output format.
    #[arg(long, value_enum, default_value_t = VerifyFormat::Text)]
    format: VerifyFormat,
    /// Leave out times and cases per second (reproducible output).
    #[arg(long)]
    no_times: bool,
    /// Write each counterexample's problem file into this directory.
    #[arg(long, value_name = "DIR")]
    counterexamples: Option<PathBuf>,
    /// With --claim C4: the exact bonus set of this problem file instead of the report.
    #[arg(long, value_name = "FILE", conflicts_with = "problem")]
    file: Option<PathBuf>,
    /// With --claim C4: the exact bonus set of this paper problem.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// With --claim C4: the exact bonus set of a deterministic Gymnasium benchmark
    /// (frozenlake:slippery=false, cliffwalking, taxi).
    #[arg(long, value_name = "SPEC", conflicts_with_all = ["problem", "file"])]
    env: Option<String>,
    /// With --claim C4 --env SPEC: the initial state x1 (a state number of the environment;
    /// required for taxi, whose episodes start from 300 states: state
    /// ((row*5 + col)*5 + passenger)*4 + destination, e.g. 328 = taxi at (3, 1), passenger at
    /// Y, destination R).
    #[arg(long, value_name = "STATE", allow_negative_numbers = true)]
    initial: Option<usize>,
    /// Write every SMT obligation as a standard SMT-LIB 2.6 file (with Z3's answer as
    /// `:status`) under this directory, with an index (index.tsv), for cvc5 or Yices to
    /// re-check. The directory must be empty or not exist.
    #[arg(long, value_name = "DIR", conflicts_with = "no_smt")]
    smt_out: Option<PathBuf>,
    /// Write a certificate (`truecost-certificate/1`, with the problem file it is checked
    /// against) of every exact optimum the report prints into this directory, re-checked by
    /// truecost's checker before the report is printed: the deterministic G* of each
    /// counterexample's problem and the discounted optimum of C3's worked example at both ends
    /// of alpha*'s bracket; with --claim C4 --file/--problem/--env, the G* of that problem.
    /// Each is checked again by `truecost check` (docs/guide/certificates.md). Not with
    /// --shard.
    #[arg(long, value_name = "DIR")]
    certificates: Option<PathBuf>,
    /// Skip the SMT engine (no `proved` verdicts).
    #[arg(long)]
    no_smt: bool,
    /// Skip the re-check of the Coq proofs (proofs/coq) with coqc: no "proved for every
    /// finite problem (Coq)" verdicts. Without coqc on PATH the report says the proofs were
    /// not re-checked on this machine.
    #[arg(long)]
    no_coq: bool,
    /// Time limit of the whole Coq re-check, in seconds: past it coqc (and every process it
    /// started) is stopped and the proofs count as not re-checked.
    #[arg(long, value_name = "SECONDS", default_value_t = truecost::claims::coq::TIMEOUT_SECONDS, value_parser = clap::value_parser!(u64).range(1..=86400), conflicts_with = "no_coq")]
    coq_timeout: u64,
    /// Skip running the Kani harnesses' bodies (proofs/) through the stand-in in this process:
    /// the report then says they were not run. (They run seeded, sampled or exhaustive, in
    /// well under a second in a release build; Kani itself is never run by verify.)
    #[arg(long)]
    no_harnesses: bool,
    /// Per-obligation time limit of the SMT engine, in seconds (an obligation that runs out
    /// of time is `unknown`: the claim is then not proved).
    #[arg(long, value_name = "SECONDS", default_value_t = 60, value_parser = clap::value_parser!(u32).range(1..=3600))]
    smt_timeout: u32,
}

/// `verify merge`.
#[derive(Subcommand, Debug)]
pub enum VerifyCommand {
    /// Combine the shard files of `verify --shard K/N` (all N, of one run) into the report
    /// the unsharded run gives (without times: each shard timed only its own part).
    Merge(MergeArgs),
}

/// Arguments of `verify merge`.
#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The shard files (any order).
    #[arg(required = true, value_name = "FILES")]
    files: Vec<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = VerifyFormat::Text)]
    format: VerifyFormat,
    /// Write each counterexample's problem file into this directory.
    #[arg(long, value_name = "DIR")]
    counterexamples: Option<PathBuf>,
}

/// The options of the claims engines, from the command line.
fn options(args: &VerifyArgs) -> registry::Options {
    registry::Options {
        smt: !args.no_smt,
        smt_timeout_ms: args.smt_timeout * 1000,
        coq: !args.no_coq,
        coq_timeout_s: args.coq_timeout,
        harnesses: (!args.no_harnesses).then_some(truecost_proofs::harnesses as _),
    }
}

/// `verify` as a pipeline, the whole run or shard `part`: the registry plans the work units of
/// the options, the shard module selects the units this run does, the runner runs them, and
/// the registry's report reads their values back (a shard writes its records instead, for
/// `verify merge`).
fn pipeline(args: &VerifyArgs, part: Option<Part>) -> Result<Made, String> {
    let started = std::time::Instant::now();
    let options = options(args);
    let only = args.claim.as_deref();
    let plan = registry::plan(args.scope, only, &options)?; // plan
    let units = shard::select(plan.units(), part); // select
    let mode = part.map_or(Mode::Whole, Mode::Shard);
    let ran = runner::run(&plan, &units, mode)?; // run
    Ok(match part {
        None => Made::Report(Box::new(registry::report(&plan, &ran.values))), // report
        Some(part) => {
            let fingerprint = registry::fingerprint(args.scope, only, &options);
            let seconds = started.elapsed().as_secs_f64();
            let file = shard::file(part, fingerprint, ran.records, seconds);
            Made::Shard(file.to_json(shard::VERIFY_FORMAT))
        }
    })
}

/// What [`pipeline`] gave: the whole run's report, or a shard's file.
enum Made {
    Report(Box<report::Report>),
    Shard(String),
}

/// `verify merge FILES…`: the whole run's report from its shards — the same pipeline, with the
/// shards' records read back in place of the run: merge, plan (from the shards' fingerprint),
/// run (every unit answered from the records), report.
fn merge(args: &MergeArgs) -> Result<String, String> {
    if let Some(dir) = &args.counterexamples {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let files = shard::read_files(&args.files)?;
    let merged = shard::merge(&files)?; // merge
    let plan = registry::plan_of(&merged.fingerprint)?; // plan
    let units = shard::select(plan.units(), None);
    let ran = runner::run(&plan, &units, Mode::Merge(&merged.steps))?; // run
    let r = registry::report(&plan, &ran.values); // report
    if let Some(dir) = &args.counterexamples {
        write_counterexamples(dir, &r)?;
    }
    engine_failures(&r, render(&r, args.format, false))
}

fn render(r: &report::Report, format: VerifyFormat, with_times: bool) -> String {
    match format {
        VerifyFormat::Text => report::text(r, with_times),
        VerifyFormat::Json => report::json(r, with_times),
        VerifyFormat::Markdown => report::markdown(r, with_times),
        VerifyFormat::Latex => report::latex(r),
    }
}

fn write_counterexamples(dir: &std::path::Path, r: &report::Report) -> Result<(), String> {
    for c in &r.claims {
        if let Some(ce) = &c.counterexample {
            let name = std::path::Path::new(&ce.file)
                .file_name()
                .expect("a file name")
                .to_owned();
            let path = dir.join(name);
            std::fs::write(&path, &ce.problem_file)
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        }
    }
    Ok(())
}

/// Runs `verify`.
pub fn verify(args: &VerifyArgs) -> Result<String, String> {
    if let Some(VerifyCommand::Merge(m)) = &args.command {
        return merge(m);
    }
    if let Some(part) = &args.shard {
        let part = Part::parse(part)?;
        return match pipeline(args, Some(part))? {
            Made::Shard(file) => Ok(file),
            Made::Report(_) => unreachable!("a shard's pipeline writes its file"),
        };
    }
    if let Some(spec) = &args.env {
        return bonus_env(spec, args);
    }
    if args.initial.is_some() {
        return Err(
            "--initial chooses x1 of an environment: it goes with --claim C4 --env SPEC".into(),
        );
    }
    if args.file.is_some() || args.problem.is_some() {
        if args.claim.as_deref() != Some("C4") {
            return Err(
                "--file/--problem go with --claim C4 (the exact bonus set of one problem)".into(),
            );
        }
        prepare(args)?;
        let problem = match (&args.file, args.problem) {
            (Some(path), _) => file::read(path).map_err(|e| e.to_string())?,
            (None, Some(id)) => GridLayout::exact(id)
                .map_err(|e| e.to_string())?
                .to_problem(StepCost::Unit),
            _ => unreachable!(),
        };
        let (out, l_star) = bonus(&problem, args.format, None)?;
        let single = match (&args.file, args.problem) {
            (Some(path), _) => Single::File(path),
            (None, Some(id)) => Single::Paper(id),
            _ => unreachable!(),
        };
        let certified = match &args.certificates {
            None => None,
            Some(dir) => Some(certificates::of_problem(dir, single, l_star.as_deref())?),
        };
        return Ok(with_certificates(out, args.format, certified.as_ref()));
    }
    prepare(args)?;
    let with_times = !args.no_times;
    if let Some(dir) = &args.smt_out {
        truecost::claims::smt::prepare_out_dir(dir)?;
    }
    let Made::Report(r) = pipeline(args, None)? else {
        unreachable!("the whole run's pipeline gives its report")
    };
    let certified = match &args.certificates {
        Some(dir) => Some(certificates::of_report(&r, dir)?),
        None => None,
    };
    if let Some(dir) = &args.smt_out {
        for o in &r.smt {
            truecost::claims::smt::write_files(dir, &o.solved)?;
        }
    }
    if let Some(dir) = &args.counterexamples {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        write_counterexamples(dir, &r)?;
    }
    let text = render(&r, args.format, with_times);
    engine_failures(&r, with_certificates(text, args.format, certified.as_ref()))
}

/// The report `text` in `format` with the run's certificates said: a line at the end of text
/// and Markdown, an entry `certificates` in JSON, their number, directory and checker at the
/// end of the LaTeX caption.
fn with_certificates(
    text: String,
    format: VerifyFormat,
    certified: Option<&certificates::Certificates>,
) -> String {
    let Some(c) = certified else { return text };
    match format {
        VerifyFormat::Text | VerifyFormat::Markdown => format!("{text}\n{}\n", c.line()),
        VerifyFormat::Json => {
            let mut v: serde_json::Value =
                serde_json::from_str(&text).expect("the report is one JSON object");
            v.as_object_mut()
                .expect("the report is one JSON object")
                .insert("certificates".into(), c.json());
            let mut s = serde_json::to_string_pretty(&v).expect("serialisable");
            s.push('\n');
            s
        }
        VerifyFormat::Latex => {
            let sentence = format!(" {}.", tex_text(&c.summary()));
            match text.rfind("}\n\\end{table}") {
                Some(at) => format!("{}{sentence}{}", &text[..at], &text[at..]),
                None => format!("{text}% {}\n", c.line()),
            }
        }
    }
}

/// `s` with LaTeX's special characters escaped ([`truecost::echo::tex_special`]).
fn tex_text(s: &str) -> String {
    s.chars()
        .map(|c| truecost::echo::tex_special(c).map_or_else(|| c.to_string(), str::to_string))
        .collect()
}

/// Refuses a bad `--certificates` directory in one line, before any work.
fn prepare(args: &VerifyArgs) -> Result<(), String> {
    match &args.certificates {
        Some(dir) => certificates::prepare_dir(dir),
        None => Ok(()),
    }
}

/// The report's text, or, when an engine failed, the report written out and the failure
/// (`verify` then exits with status 1 after a whole report).
fn engine_failures(r: &report::Report, text: String) -> Result<String, String> {
    let failed = registry::engine_failures(r);
    if failed.is_empty() {
        return Ok(text);
    }
    super::emit(&text)?;
    Err(format!(
        "{} engine(s) failed ({}): the report above is whole, and its verdicts on those claims are inconclusive",
        failed.len(),
        failed.join("; ")
    ))
}

/// `verify --claim C4 --env SPEC`: the bonus set of a deterministic
/// environment; a stochastic one is refused with the reason.
fn bonus_env(spec: &str, args: &VerifyArgs) -> Result<String, String> {
    if args.claim.as_deref() != Some("C4") {
        return Err("--env goes with --claim C4 (the exact bonus set of one problem)".into());
    }
    prepare(args)?;
    let model = truecost::objectives::Source::Env(spec.to_string()).load()?;
    if model.initial.len() > 1 && args.initial.is_none() {
        return Err(format!(
            "C4 is stated for a single initial state x1; {} draws it from {} states: choose one with --initial STATE (e.g. --initial {})",
            model.name,
            model.initial.len(),
            model.initial[0].0
        ));
    }
    let problem = model
        .deterministic_problem_from(args.initial)
        .map_err(|e| format!("C4 is stated for deterministic problems: {e}"))?;
    let (mut out, l_star) = bonus(&problem, args.format, Some(model.terminal_bonus.as_ref()))?;
    if args.initial.is_some() && args.format != VerifyFormat::Json {
        out = format!("x1 = state {}\n{out}", problem.initial());
    }
    let certified = match &args.certificates {
        None => None,
        Some(dir) => Some(certificates::of_problem(
            dir,
            Single::Env {
                spec,
                problem: &model.problem,
                mdp: model.mdp(),
                initial: problem.initial(),
            },
            l_star.as_deref(),
        )?),
    };
    Ok(with_certificates(out, args.format, certified.as_ref()))
}

fn unscale(q: Q, d: &BigInt) -> String {
    let r = q.to_rational() / truecost::value::Rational::from_integer(d.clone());
    truecost::algebra::intervals::rat(&r)
}

fn interval_text(i: &Interval, d: &BigInt) -> String {
    if i.empty {
        return "empty".into();
    }
    let lo = match i.lo {
        End::Unbounded => "(-inf".to_string(),
        End::Closed(a) => format!("[{}", unscale(a, d)),
        End::Open(a) => format!("({}", unscale(a, d)),
    };
    let hi = match i.hi {
        End::Unbounded => "+inf)".to_string(),
        End::Closed(b) => format!("{}]", unscale(b, d)),
        End::Open(b) => format!("{})", unscale(b, d)),
    };
    format!("{lo}, {hi}")
}

/// The bonus sets by the violated-cycle search (`claims::c4_cycles`), when the enumeration
/// oracle refuses the problem's size: the exact set only (the printed and corrected formulas
/// need every simple goal path). With the text, the `L*` it prints.
fn bonus_by_cycles(
    inst: &Instance,
    d: &BigInt,
    format: VerifyFormat,
    refusal: &str,
    terminal_bonus: Option<&truecost::value::Rational>,
) -> Result<(String, Option<String>), String> {
    let sets = truecost::claims::c4_cycles::bonus_sets_by_cycles(inst)?
        .ok_or("no goal is reachable from x1: there is no single-shot path and no bonus set")?;
    let method = format!("exact violated-cycle search (Bellman-Ford, claims::c4_cycles); the enumeration oracle refuses: {refusal}; the printed and corrected formulas need every simple goal path and are not evaluated");
    let rows: Vec<_> = sets
        .iter()
        .map(|s| {
            json!({
                "optimal_cost": unscale(Q::int(s.optimal_cost as i128), d),
                "optimal_states": s.optimal_states,
                "least_mean_cycle": s.least_mean_cycle.map(|q| unscale(q, d)),
                "exact": interval_text(&s.exact, d),
                "bellman_ford_runs": s.steps,
                "printed": null,
                "corrected": null,
                "terminal_bonus_in_set": terminal_bonus.map(|m| contains_unscaled(&s.exact, m, d)),
            })
        })
        .collect();
    let l_star = rows
        .first()
        .and_then(|r| r["optimal_cost"].as_str())
        .map(str::to_string);
    let text = match format {
        VerifyFormat::Json => {
            let mut s = serde_json::to_string_pretty(&json!({
                "bonus_sets": rows,
                "method": method,
                "terminal_bonus": terminal_bonus.map(|m| m.to_string()),
            }))
            .expect("serialisable");
            s.push('\n');
            s
        }
        _ => {
            let mut s = format!(
                "Exact set of bonuses M < 0 for which pi* is average-cost optimal (C4), per optimal path length S*\nmethod: {method}\n"
            );
            for (r, set) in rows.iter().zip(&sets) {
                let _ = writeln!(
                    s,
                    "L* = {}, S* = {}, Lav(C^) = {}\n  exact (violated cycles, {} Bellman-Ford runs): {}",
                    r["optimal_cost"].as_str().unwrap_or(""),
                    r["optimal_states"],
                    r["least_mean_cycle"].as_str().unwrap_or("none (+inf)"),
                    r["bellman_ford_runs"],
                    r["exact"].as_str().unwrap_or(""),
                );
                if let Some(m) = terminal_bonus {
                    let _ = writeln!(
                        s,
                        "  the environment's own bonus M = {m}: {}",
                        if contains_unscaled(&set.exact, m, d) {
                            "in the set (pi* is average-cost optimal)"
                        } else {
                            "not in the set"
                        }
                    );
                }
            }
            s
        }
    };
    Ok((text, l_star))
}

/// The bonus sets of one problem; a problem beyond the enumeration oracle's bounds is answered
/// by the violated-cycle search. `environment`: `--env`, with the environment's own bonus if it
/// has one (then said to be in the set or not). With the text, the `L*` it prints.
fn bonus(
    problem: &Problem,
    format: VerifyFormat,
    environment: Option<Option<&truecost::value::Rational>>,
) -> Result<(String, Option<String>), String> {
    use truecost::claims::c4::BonusError;
    let (inst, d) = Instance::from_problem(problem)?;
    let sets = match bonus_analysis(&inst, bonus_policy_limit(inst.moves.len())) {
        Err(
            e @ (BonusError::TooManyPolicies { .. }
            | BonusError::SearchTooLong { .. }
            | BonusError::TooManyStates { .. }),
        ) => return bonus_by_cycles(&inst, &d, format, &e.to_string(), environment.flatten()),
        other => other.map_err(|e| e.to_string())?,
    }
    .ok_or("no goal is reachable from x1: there is no single-shot path and no bonus set")?;
    let rows: Vec<_> = sets
        .iter()
        .map(|s| {
            json!({
                "optimal_cost": unscale(Q::int(s.optimal_cost as i128), &d),
                "optimal_states": s.optimal_states,
                "least_mean_cycle": s.least_mean_cycle.map(|q| unscale(q, &d)),
                "exact": interval_text(&s.exact, &d),
                "printed": s.printed.map(|p| interval_text(&p, &d)),
                "corrected": interval_text(&s.corrected, &d),
                "printed_agrees": s.printed.map(|p| p.same_set(&s.exact)),
                "corrected_agrees": s.corrected.same_set(&s.exact),
            })
        })
        .collect();
    let l_star = rows
        .first()
        .and_then(|r| r["optimal_cost"].as_str())
        .map(str::to_string);
    let text = match format {
        VerifyFormat::Json => {
            let mut s =
                serde_json::to_string_pretty(&json!({"bonus_sets": rows})).expect("serialisable");
            s.push('\n');
            s
        }
        _ => {
            let mut s = String::from(
                "Exact set of bonuses M < 0 for which pi* is average-cost optimal (C4), per optimal path length S*\n",
            );
            for r in &rows {
                let _ = writeln!(
                    s,
                    "L* = {}, S* = {}, Lav(C^) = {}\n  exact (oracle):    {}\n  printed formula:   {}{}\n  corrected formula: {}{}",
                    r["optimal_cost"].as_str().unwrap_or(""),
                    r["optimal_states"],
                    r["least_mean_cycle"].as_str().unwrap_or("none (+inf)"),
                    r["exact"].as_str().unwrap_or(""),
                    r["printed"].as_str().unwrap_or("undefined (division by L(u) = 0)"),
                    match r["printed_agrees"].as_bool() {
                        Some(true) => "  (agrees)",
                        Some(false) => "  (DISAGREES)",
                        None => "",
                    },
                    r["corrected"].as_str().unwrap_or(""),
                    if r["corrected_agrees"].as_bool() == Some(true) { "  (agrees)" } else { "  (DISAGREES)" },
                );
            }
            s
        }
    };
    Ok((text, l_star))
}

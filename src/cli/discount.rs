//! `truecost discount`: for a deterministic problem (a paper grid or a deterministic file), the
//! exact set of discount factors for which a discount-optimal policy fails to reach the goal;
//! for an environment (`--env`) or a stochastic problem file, the exact breakpoints where the
//! discount-optimal policies change, with the success probability and truecost of each
//! interval's optimal policies. Every case is answered by the parametric policy analysis of
//! [`truecost::objectives::parametric`]; the set of a deterministic problem is read off its
//! breakpoints ([`truecost::objectives::failure_set`]).

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;

use truecost::algebra::intervals::{point_text, set_text, DiscountSet};
use truecost::certificate::discount::{check_discount, parse_discount, write_discount, DISCOUNT};
use truecost::certificate::{sha256_hex, Identity};
use truecost::echo::printable;
use truecost::objectives::parametric::{certificate, discount_breakpoints_with, DiscountAnalysis};
use truecost::objectives::report::{
    discount_json, discount_latex, discount_markdown, discount_text,
};
use truecost::objectives::{failure_set, Model, Source};
use truecost::problems::{GridLayout, StepCost};
use truecost::stochastic::file::{FileObjective, ProblemFile};

use super::certify::{write_certificate, CertifiedSource};
use super::compare::CompareFormat;
use super::env::{pretty, EnvArg};
use super::ReportFormat;

/// Arguments of `discount`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file", "env"])))]
pub struct DiscountArgs {
    #[command(flatten)]
    env: EnvArg,
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// A problem file (deterministic or stochastic).
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    /// Stage cost of a grid move (paper problems only) [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// Also write a certificate of the breakpoints and of the optimal policies between them to
    /// FILE, for `truecost check` (docs/guide/certificates.md).
    #[arg(long, value_name = "FILE")]
    certificate: Option<PathBuf>,
    /// Output format. Decimals are correctly rounded to the digits shown; "..." marks a value
    /// whose expansion goes on.
    #[arg(long, value_enum, default_value_t = CompareFormat::Text)]
    format: CompareFormat,
}

/// The model `discount` analyses, rebuilt the same way by `check` for a discount certificate.
pub struct DiscountModel {
    /// The model.
    pub model: Model,
    /// A deterministic problem (`--problem`, a deterministic file): `discount` prints its
    /// failure set; otherwise its breakpoint report.
    pub failure_set: bool,
    /// The source's name in the failure set's report.
    pub source: String,
    /// The problem file's text (`--file`), whose bytes a certificate hashes.
    pub text: Option<String>,
}

/// Builds the model of `discount` from one source (`step` for a paper problem).
pub fn discount_model(
    env: Option<&str>,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    step: Option<StepCost>,
) -> Result<DiscountModel, String> {
    let (problem, source, extra, text) = match (env, file, problem) {
        (Some(spec), None, None) => {
            let model = Source::Env(spec.to_string()).load()?;
            let source = model.name.clone();
            return Ok(DiscountModel {
                model,
                failure_set: false,
                source,
                text: None,
            });
        }
        (None, Some(path), None) => {
            let text = truecost::model::file::read_text(path).map_err(|e| e.to_string())?;
            match truecost::formats::from_text_with_objective(&text).map_err(|e| e.to_string())? {
                (ProblemFile::Deterministic(p), extra) => (
                    p,
                    format!("file {}", printable(&path.display().to_string())),
                    extra,
                    Some(text),
                ),
                (ProblemFile::Stochastic(p), extra) => {
                    let model = Model::from_problem(*p, format!("file {}", path.display()))
                        .with_file_objective(&extra);
                    let source = model.name.clone();
                    return Ok(DiscountModel {
                        model,
                        failure_set: false,
                        source,
                        text: Some(text),
                    });
                }
            }
        }
        (None, None, Some(id)) => (
            GridLayout::exact(id)
                .map_err(|e| e.to_string())?
                .to_problem(step.unwrap_or_default()),
            format!("paper problem {id}"),
            FileObjective::default(),
            None,
        ),
        _ => return Err("give one of --env SPEC, --problem N and --file FILE".into()),
    };
    let model = Model::from_deterministic_file(&problem, source.clone(), &extra)
        .map_err(|e| e.to_string())?;
    Ok(DiscountModel {
        model,
        failure_set: true,
        source,
        text,
    })
}

/// Runs `discount`.
pub fn discount(args: &DiscountArgs) -> Result<String, String> {
    if args.env.env.is_some() && (args.problem.is_some() || args.file.is_some()) {
        return Err("give one of --env, --problem and --file".into());
    }
    if args.step_cost.is_some() && args.problem.is_none() {
        return Err("--step-cost applies to the paper's problems (--problem N)".into());
    }
    if args.env.env.is_none() && args.file.is_none() && args.problem.is_none() {
        return Err("give --problem N, --file FILE or --env SPEC".into());
    }
    if let Some(path) = &args.certificate {
        truecost::atomic::check_target(path)?;
    }
    let loaded = discount_model(
        args.env.env.as_deref(),
        args.problem,
        args.file.as_deref(),
        args.step_cost,
    )?;
    let model = &loaded.model;
    let d = analysis(model)?;
    if let Some(path) = &args.certificate {
        let source = CertifiedSource {
            file: args.file.as_deref(),
            problem: args.problem,
            env: args.env.env.as_deref(),
            step: args.step_cost,
            gamma: None,
            noise: None,
            names: Default::default(),
        };
        let text = discount_certificate(model, &d, &source, loaded.text.as_deref())?;
        write_certificate(path, &text)?;
    }
    if !loaded.failure_set {
        return Ok(breakpoints(model, &d, args.format));
    }
    let source = loaded.source;
    let rewards = model.reward_source;
    // With an initial distribution, a policy fails if it misses the goal from any of its
    // states (its success probability at the distribution is below 1).
    let from = match model.initial.len() {
        1 => "x1".to_string(),
        k => format!("some of the {k} initial states"),
    };
    let set = failure_set(&d);
    Ok(match args.format {
        CompareFormat::Json => {
            let pieces: Vec<_> = set
                .pieces
                .iter()
                .map(|p| {
                    json!({
                        "lo": point_text(&p.lo), "lo_closed": p.lo_closed,
                        "hi": point_text(&p.hi), "hi_closed": p.hi_closed,
                    })
                })
                .collect();
            pretty(&json!({
                "problem": source,
                "rewards": rewards,
                "set": set_text(&set),
                "pieces": pieces,
                "method": set.method,
            }))
        }
        CompareFormat::Text => format!(
            "problem  {source}\nrewards  {rewards} (discounted, maximised)\nalpha in (0,1) where a discount-optimal policy fails to reach the goal from {from}:\n  {}\nmethod   {}\n",
            set_text(&set),
            set.method
        ),
        CompareFormat::Markdown => format!(
            "**{source}** ({rewards}): alpha in (0,1) where a discount-optimal policy fails to reach the goal from {from}\n\n| set | method |\n|---|---|\n| {} | {} |\n",
            set_text(&set),
            set.method
        ),
        CompareFormat::Latex => latex_set(&format!("{source} ({rewards})"), &from, &set),
    })
}

fn latex_set(source: &str, from: &str, set: &DiscountSet) -> String {
    format!(
        "% {source}: alpha in (0,1) where a discount-optimal policy fails to reach the goal from {from}\n\\begin{{tabular}}{{ll}}\n\\hline\nset & method \\\\\n\\hline\n{} & {} \\\\\n\\hline\n\\end{{tabular}}\n",
        set_text(set).replace('U', "$\\cup$"),
        set.method
    )
}

/// The parametric analysis of a model, with a progress bar on a terminal.
fn analysis(model: &Model) -> Result<DiscountAnalysis, String> {
    use std::io::IsTerminal;
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::with_draw_target(Some(100), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} {msg} [{bar:20}] work {pos}% of the bound {elapsed}",
            )
            .expect("a valid template")
            .progress_chars("=> "),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let d = discount_breakpoints_with(model, &mut |p| {
        bar.set_position((p.work * 100 / p.bound.max(1)) as u64);
        bar.set_message(format!(
            "probe {} ({} regions, {} gaps)",
            p.probes + 1,
            p.regions,
            p.gaps
        ));
    });
    bar.finish_and_clear();
    d.map_err(|e| e.to_string())
}

/// The breakpoint report of a stochastic model or an environment.
fn breakpoints(model: &Model, d: &DiscountAnalysis, format: CompareFormat) -> String {
    match format {
        CompareFormat::Text => discount_text(model, d),
        CompareFormat::Json => pretty(&discount_json(model, d)),
        CompareFormat::Markdown => discount_markdown(model, d),
        CompareFormat::Latex => discount_latex(model, d),
    }
}

/// The discount certificate of an analysis (`discount --certificate`), as text: the problem's
/// record from `source` (hashing `file_text`, the file's bytes, when there is one), then
/// [`truecost::objectives::parametric::certificate::discount_certificate`].
pub fn discount_certificate(
    model: &Model,
    d: &DiscountAnalysis,
    source: &CertifiedSource<'_>,
    file_text: Option<&str>,
) -> Result<String, String> {
    let mdp = model.mdp();
    let mut problem = source.record(|| mdp.clone())?;
    if let Some(text) = file_text {
        problem.sha256 = sha256_hex(text.as_bytes());
    }
    let identity = match file_text {
        Some(text) => Identity::FileBytes(text.as_bytes()),
        None => Identity::Canonical,
    };
    certificate::discount_certificate(model, d, &mdp, problem, identity).map(|c| write_discount(&c))
}

/// `truecost check`: a discount certificate ([`check_discount_file`]) or any other kind
/// (`super::env::check`), by the certificate's `objective`.
pub fn check_certificate(
    source: &EnvArg,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    names: &truecost::formats::drn::DrnNames,
    certificate_path: &std::path::Path,
    format: ReportFormat,
    coq: bool,
) -> Result<String, String> {
    let text = super::env::read_certificate(certificate_path)
        .map_err(|e| format!("cannot read the certificate: {e}"))?;
    // Only the kind is read here (the other fields skipped, not built): the checker of that
    // kind reads the whole certificate.
    #[derive(serde::Deserialize)]
    struct Kind {
        objective: Option<String>,
    }
    let kind = serde_json::from_str::<Kind>(&text)
        .ok()
        .and_then(|k| k.objective);
    if kind.as_deref() != Some(DISCOUNT) {
        return super::env::check(source, problem, file, names, &text, format, coq);
    }
    if !names.is_default() {
        return Err("--goal-label and --cost-reward apply to the certificates of solve; a discount certificate's file is read as discount reads it".into());
    }
    if coq {
        return Err("--coq checks truecost and deterministic certificates; a discount certificate is checked by truecost's own checker (without --coq)".into());
    }
    check_discount_file(source.env.as_deref(), problem, file, &text, format)
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
    let loaded = discount_model(env, problem, file, step)?;
    let mdp = loaded.model.mdp();
    let identity = match &loaded.text {
        Some(t) => Identity::FileBytes(t.as_bytes()),
        None => Identity::Canonical,
    };
    let name = &loaded.model.name;
    match check_discount(&mdp, identity, &cert) {
        Ok(a) => Ok(match format {
            ReportFormat::Json => pretty(&serde_json::json!({
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
                super::emit(&pretty(&serde_json::json!({
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

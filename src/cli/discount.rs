//! `truecost discount`: for a deterministic problem (a paper grid or a deterministic file), the
//! exact set of discount factors for which a discount-optimal policy fails to reach the goal;
//! for an environment (`--env`) or a stochastic problem file, the exact breakpoints where the
//! discount-optimal policies change, with the success probability and truecost of each
//! interval's optimal policies. Every case is answered by the parametric policy analysis of
//! [`truecost::objectives::parametric`]; the set of a deterministic problem is read off its
//! breakpoints ([`truecost::objectives::failure_set`]).

use std::path::PathBuf;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;

use truecost::algebra::intervals::{point_text, set_text, DiscountSet};
use truecost::echo::printable;
use truecost::objectives::parametric::{discount_breakpoints_with, DiscountAnalysis};
use truecost::objectives::report::{
    discount_json, discount_latex, discount_markdown, discount_text,
};
use truecost::objectives::{failure_set, Model, Source};
use truecost::problems::{GridLayout, StepCost};
use truecost::stochastic::file::{FileObjective, ProblemFile};

use super::certify::{write_certificate, CertifiedSource};
use super::compare::CompareFormat;
use super::env::{pretty, EnvArg};

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
        };
        let text =
            super::certify::discount_certificate(model, &d, &source, loaded.text.as_deref())?;
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

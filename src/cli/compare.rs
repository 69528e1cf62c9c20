//! `truecost compare` (issue 11, item 4): every objective side by side — success probability,
//! expected truecost, expected steps — in text, Markdown, JSON or LaTeX.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::objectives::parse_alpha;
use truecost::objectives::report::{
    compare, compare_json, compare_latex, compare_markdown, compare_text,
};
use truecost::problems::StepCost;
use truecost::stochastic::NoiseModel;

use super::env::{pretty, source, EnvArg};

/// Output formats of `compare`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CompareFormat {
    /// Aligned text.
    Text,
    /// A Markdown table.
    Markdown,
    /// One JSON object (exact strings).
    Json,
    /// A LaTeX tabular.
    Latex,
}

/// Arguments of `compare`.
#[derive(Args, Debug)]
pub struct CompareArgs {
    #[command(flatten)]
    env: EnvArg,
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N")]
    problem: Option<usize>,
    /// A problem file.
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    /// Stage cost of a grid move (paper problems only) [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// Predictability gamma in (0, 1] for --problem and deterministic --file.
    #[arg(long, value_name = "G")]
    gamma: Option<String>,
    /// How 1 - gamma is spread [default: paper].
    #[arg(long, value_enum)]
    noise: Option<NoiseModel>,
    /// The discount factors of the discounted rows, comma-separated exact numbers.
    #[arg(long, value_name = "A,A,...", default_value = "0.9,0.95,0.99,0.999")]
    alphas: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t = CompareFormat::Text)]
    format: CompareFormat,
}

/// Runs `compare`.
pub fn run(args: &CompareArgs) -> Result<String, String> {
    let alphas = args
        .alphas
        .split(',')
        .map(|a| parse_alpha(a.trim()))
        .collect::<Result<Vec<_>, _>>()?;
    let model = source(
        &args.env,
        args.problem,
        args.file.as_deref(),
        args.step_cost,
        args.gamma.as_deref(),
        args.noise,
    )?
    .load()?;
    let rows = compare(&model, &alphas).map_err(|e| e.to_string())?;
    Ok(match args.format {
        CompareFormat::Text => compare_text(&model, &rows),
        CompareFormat::Markdown => compare_markdown(&model, &rows),
        CompareFormat::Json => pretty(&compare_json(&model, &rows)),
        CompareFormat::Latex => compare_latex(&model, &rows),
    })
}

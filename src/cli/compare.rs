//! `truecost compare`: every objective side by side — success probability,
//! expected truecost, expected steps — in text, Markdown, JSON or LaTeX.

use clap::{Args, ValueEnum};

use super::env::{pretty, ModelArgs};
use truecost::objectives::parse_alpha;
use truecost::objectives::report::{
    compare, compare_json, compare_latex, compare_markdown, compare_text,
};

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
    model: ModelArgs,
    /// The discount factors of the discounted rows, comma-separated exact numbers.
    #[arg(
        long,
        value_name = "A,A,...",
        default_value = "0.9,0.95,0.99,0.999",
        allow_hyphen_values = true
    )]
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
    let model = args.model.load()?;
    let rows = compare(&model, &alphas).map_err(|e| e.to_string())?;
    Ok(match args.format {
        CompareFormat::Text => compare_text(&model, &rows),
        CompareFormat::Markdown => compare_markdown(&model, &rows),
        CompareFormat::Json => pretty(&compare_json(&model, &rows)),
        CompareFormat::Latex => compare_latex(&model, &rows),
    })
}

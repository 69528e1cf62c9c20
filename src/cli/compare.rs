//! `truecost compare`: every objective side by side — success probability,
//! expected truecost, expected steps — in text, Markdown, JSON or LaTeX.

use clap::{Args, ValueEnum};

use super::env::{pretty, ModelArgs};
#[cfg(doc)]
use truecost::objectives::report::compare;
use truecost::objectives::report::{
    compare_json, compare_latex, compare_markdown, compare_text, CompareRow,
};
use truecost::objectives::{parse_alpha, Objective};

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
    /// The discount factors of the discounted rows, comma-separated exact numbers in (0, 1),
    /// each listed once, at most 64 of them.
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

/// The most discount factors `compare --alphas` takes (each is one exact solve of the model).
pub const MAX_ALPHAS: usize = 64;

/// The discount factors of `--alphas` (each as [`parse_alpha`] reads it): at most
/// [`MAX_ALPHAS`], counted before any is read, and no value listed twice, however written.
pub fn parse_alphas(list: &str) -> Result<Vec<truecost::value::Rational>, String> {
    let count = list.split(',').count();
    if count > MAX_ALPHAS {
        return Err(format!(
            "--alphas lists {count} discount factors, more than the {MAX_ALPHAS} compare takes"
        ));
    }
    let mut alphas: Vec<truecost::value::Rational> = Vec::with_capacity(count);
    for text in list.split(',') {
        let a = parse_alpha(text.trim())?;
        if let Some(first) = alphas.iter().position(|b| *b == a) {
            return Err(format!(
                "alpha {} is listed twice (as discount factor {} and {})",
                truecost::echo::echo(text.trim()),
                first + 1,
                alphas.len() + 1
            ));
        }
        alphas.push(a);
    }
    Ok(alphas)
}

/// Runs `compare`: the discounted rows are solved first, so that a discounted objective the
/// exact solver refuses (the killed-process construction's stage costs, the largest reward
/// minus each action's, times the probabilities' denominators with `α`'s, within `2^100`) is
/// refused before the truecost and reach objectives' exact solves; the rows are printed in
/// the order of [`compare`] (truecost, reach, then each `α`).
pub fn run(args: &CompareArgs) -> Result<String, String> {
    let alphas = parse_alphas(&args.alphas)?;
    let model = args.model.load()?;
    let solve = |o: Objective| {
        model
            .solve(&o)
            .map(|solution| CompareRow {
                objective: o,
                solution,
            })
            .map_err(|e| e.to_string())
    };
    let discounted = alphas
        .iter()
        .map(|a| solve(Objective::Discounted(a.clone())))
        .collect::<Result<Vec<_>, _>>()?;
    let mut rows = vec![solve(Objective::Truecost)?, solve(Objective::Reach)?];
    rows.extend(discounted);
    Ok(match args.format {
        CompareFormat::Text => compare_text(&model, &rows),
        CompareFormat::Markdown => compare_markdown(&model, &rows),
        CompareFormat::Json => pretty(&compare_json(&model, &rows)),
        CompareFormat::Latex => compare_latex(&model, &rows),
    })
}

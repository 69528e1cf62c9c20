//! `truecost discount`: the exact set of discount factors for which a discount-optimal policy
//! fails to reach the goal (issue 5, item 6).

use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use truecost::claims::discount::{discount_set, point_text, set_text};
use truecost::model::file;
use truecost::problems::{GridLayout, StepCost};

use super::ReportFormat;

/// Arguments of `discount`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file"])))]
pub struct DiscountArgs {
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// A problem file.
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    /// Stage cost of a grid move (paper problems only) [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Text)]
    format: ReportFormat,
}

/// Runs `discount`.
pub fn discount(args: &DiscountArgs) -> Result<String, String> {
    let (problem, source) = match (&args.file, args.problem) {
        (Some(_), _) if args.step_cost.is_some() => {
            return Err("--step-cost applies to the paper's problems (--problem N)".into())
        }
        (Some(path), _) => (
            file::read(path).map_err(|e| e.to_string())?,
            format!("file {}", path.display()),
        ),
        (None, Some(id)) => (
            GridLayout::exact(id)
                .map_err(|e| e.to_string())?
                .to_problem(args.step_cost.unwrap_or_default()),
            format!("paper problem {id}"),
        ),
        (None, None) => return Err("give --problem N or --file FILE".into()),
    };
    let set = discount_set(&problem, 20_000).map_err(|e| e.to_string())?;
    Ok(match args.format {
        ReportFormat::Json => {
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
            let mut s = serde_json::to_string_pretty(&json!({
                "problem": source,
                "set": set_text(&set),
                "pieces": pieces,
                "method": set.method,
            }))
            .expect("serialisable");
            s.push('\n');
            s
        }
        ReportFormat::Text => format!(
            "problem  {source}\nalpha in (0,1) where a discount-optimal policy fails to reach the goal from x1:\n  {}\nmethod   {}\n",
            set_text(&set),
            set.method
        ),
    })
}

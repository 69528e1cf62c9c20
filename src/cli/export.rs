//! `truecost export --env SPEC --out F.json` (issue 11, item 1): an environment as a
//! stochastic problem file (truecost stage costs; an initial distribution becomes one extra
//! zero-cost initial state, see [`truecost::objectives::Model::exportable`]).

use std::path::PathBuf;

use clap::Args;

use truecost::objectives::Source;
use truecost::stochastic::file::to_json;

/// Arguments of `export`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// The environment (frozenlake[...], cliffwalking[...], taxi).
    #[arg(long, value_name = "SPEC", required = true)]
    env: String,
    /// The problem file to write (JSON).
    #[arg(long, value_name = "FILE.json")]
    out: PathBuf,
}

/// Runs `export`.
pub fn run(args: &ExportArgs) -> Result<String, String> {
    let model = Source::Env(args.env.clone()).load()?;
    let problem = model.exportable().map_err(|e| e.to_string())?;
    let name = if model.initial.len() > 1 {
        format!(
            "{} (state {} draws the initial state uniformly; truecost stage costs)",
            model.name,
            problem.initial()
        )
    } else {
        format!("{} (truecost stage costs)", model.name)
    };
    let text = to_json(&problem, Some(&name));
    std::fs::write(&args.out, text + "\n")
        .map_err(|e| format!("cannot write {}: {e}", args.out.display()))?;
    Ok(format!(
        "wrote {} ({} states, {} actions)\n",
        args.out.display(),
        problem.states(),
        problem.action_total()
    ))
}

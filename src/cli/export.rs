//! `truecost export --env SPEC --out F.json` (issue 11, item 1): an environment as a
//! stochastic problem file (truecost stage costs; an initial distribution becomes one extra
//! zero-cost initial state, see [`truecost::objectives::Model::exportable`]).

use std::path::PathBuf;

use clap::Args;

use truecost::objectives::Source;
use truecost::stochastic::file::to_json;

/// Arguments of `export`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["env", "grid"])))]
pub struct ExportArgs {
    /// The environment (frozenlake[...], cliffwalking[...], taxi).
    #[arg(long, value_name = "SPEC")]
    env: Option<String>,
    /// A benchmark grid ROWSxCOLS (4 neighbours, move costs 1-4 from --seed, start top-left,
    /// goal bottom-right) as a deterministic problem file; solve it with --gamma.
    #[arg(long, value_name = "ROWSxCOLS")]
    grid: Option<String>,
    /// The seed of the benchmark grid's costs.
    #[arg(long, value_name = "N", default_value_t = 0, requires = "grid")]
    seed: u64,
    /// The problem file to write (JSON).
    #[arg(long, value_name = "FILE.json")]
    out: PathBuf,
}

/// Runs `export`.
pub fn run(args: &ExportArgs) -> Result<String, String> {
    truecost::atomic::check_target(&args.out)?;
    if let Some(size) = &args.grid {
        return grid(size, args.seed, &args.out);
    }
    let env = args.env.clone().expect("clap requires --env or --grid");
    let model = Source::Env(env).load()?;
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
    truecost::atomic::write(&args.out, (text + "\n").as_bytes())?;
    Ok(format!(
        "wrote {} ({} states, {} actions)\n",
        args.out.display(),
        problem.states(),
        problem.action_total()
    ))
}

/// `export --grid` (issue 12, item 3): the seeded benchmark grid as a problem file.
fn grid(size: &str, seed: u64, out: &std::path::Path) -> Result<String, String> {
    use truecost::stochastic::benchmark::{cost_grid, exportable_size, parse_size};
    let (rows, cols) = parse_size(size).map_err(|e| e.to_string())?;
    exportable_size(rows, cols).map_err(|e| e.to_string())?;
    let problem = cost_grid(rows, cols, seed).map_err(|e| e.to_string())?;
    let name = format!("benchmark grid {rows}x{cols}, move costs 1-4 from seed {seed}");
    let text = truecost::model::file::to_json(&problem, Some(&name));
    truecost::atomic::write(out, (text + "\n").as_bytes())?;
    Ok(format!(
        "wrote {} ({} states, {} moves)\n",
        out.display(),
        problem.states(),
        (0..problem.states())
            .map(|x| problem.moves(x).len())
            .sum::<usize>()
    ))
}

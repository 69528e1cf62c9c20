//! `truecost export --env SPEC --out F.json`: an environment as a
//! stochastic problem file (truecost stage costs, Gymnasium's rewards, the terminal non-goal
//! states and the initial distribution, see [`truecost::objectives::Model::exportable`]).

use std::path::PathBuf;

use clap::Args;

use truecost::objectives::Source;
use truecost::stochastic::file::to_json_with_objective;

/// Arguments of `export`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["env", "grid"])))]
pub struct ExportArgs {
    /// The environment (frozenlake[...], cliffwalking[...], taxi).
    #[arg(long, value_name = "SPEC")]
    env: Option<String>,
    /// A benchmark grid ROWSxCOLS (4 neighbours, start top-left; costs and goals from
    /// --pattern, by default move costs 1-4 from --seed and the goal bottom-right) as a
    /// deterministic problem file; solve it with --gamma.
    #[arg(long, value_name = "ROWSxCOLS")]
    grid: Option<String>,
    /// The seed of the benchmark grid's costs (pattern random).
    #[arg(long, value_name = "N", default_value_t = 0, requires = "grid")]
    seed: u64,
    /// The grid's cost pattern: random (costs from --costs and --seed), unit, ties (cost
    /// 1 + (row + col) mod 4 of the cell left: many exact ties), walls (unit costs, serpentine
    /// walls), goals (the ties costs, four goals).
    #[arg(long, value_name = "PATTERN", requires = "grid")]
    pattern: Option<String>,
    /// The integer cost range LO-HI of pattern random (default 1-4).
    #[arg(long, value_name = "LO-HI", requires = "grid")]
    costs: Option<String>,
    /// The problem file to write (JSON).
    #[arg(long, value_name = "FILE.json")]
    out: PathBuf,
}

/// Runs `export`.
pub fn run(args: &ExportArgs) -> Result<String, String> {
    truecost::atomic::check_target(&args.out)?;
    if let Some(size) = &args.grid {
        return grid(
            size,
            args.pattern.as_deref(),
            args.costs.as_deref(),
            args.seed,
            &args.out,
        );
    }
    let env = args.env.clone().expect("clap requires --env or --grid");
    let model = Source::Env(env).load()?;
    let (problem, extra) = model.exportable();
    let name = format!(
        "{} (truecost stage costs, {})",
        model.name, model.reward_source
    );
    let text = to_json_with_objective(&problem, Some(&name), &extra);
    truecost::atomic::write(&args.out, (text + "\n").as_bytes())?;
    Ok(format!(
        "wrote {} ({} states, {} actions)\n",
        args.out.display(),
        problem.states(),
        problem.action_total()
    ))
}

/// `export --grid`: a grid of the pattern family as a problem file; every option is checked
/// before the grid is built.
fn grid(
    size: &str,
    pattern: Option<&str>,
    costs: Option<&str>,
    seed: u64,
    out: &std::path::Path,
) -> Result<String, String> {
    use truecost::stochastic::benchmark::{
        exportable_size, parse_size, pattern_grid, CostRange, GridPattern,
    };
    let (rows, cols) = parse_size(size).map_err(|e| e.to_string())?;
    exportable_size(rows, cols).map_err(|e| e.to_string())?;
    let pattern = match pattern {
        Some(p) => GridPattern::parse(p).map_err(|e| e.to_string())?,
        None => GridPattern::Random,
    };
    let range = match costs {
        Some(c) => CostRange::parse(c).map_err(|e| e.to_string())?,
        None => CostRange::DEFAULT,
    };
    if costs.is_some() && pattern != GridPattern::Random {
        return Err(format!(
            "--costs applies to --pattern random only (pattern {} has fixed costs)",
            pattern.name()
        ));
    }
    let problem = pattern_grid(rows, cols, pattern, range, seed).map_err(|e| e.to_string())?;
    let name = match pattern {
        GridPattern::Random => format!(
            "benchmark grid {rows}x{cols}, move costs {}-{} from seed {seed}",
            range.lo, range.hi
        ),
        p => format!("benchmark grid {rows}x{cols}, pattern {}", p.name()),
    };
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

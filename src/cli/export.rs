//! `truecost export (--env SPEC | --problem N | --file F | --grid RxC) [--format json|drn|prism]
//! --out F`: a problem as a truecost problem file (JSON), in Storm's explicit DRN format or in
//! the PRISM language ([`truecost::formats`]). An environment's file carries the truecost stage
//! costs, Gymnasium's rewards, the terminal non-goal states and the initial distribution (see
//! [`truecost::objectives::Model::exportable`]); `--gamma`/`--noise` perturb a paper problem,
//! a deterministic file or a grid.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::formats::{drn, prism};
use truecost::objectives::Source;
use truecost::problems::StepCost;
use truecost::stochastic::file::{to_json_with_objective, FileObjective};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

/// The formats `export` writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum ExportFormat {
    /// truecost's JSON problem file.
    #[default]
    Json,
    /// Storm's explicit format (exact rationals, reward model "cost", labels init and goal).
    Drn,
    /// The PRISM language (an mdp module, rewards "cost", label "goal").
    Prism,
}

/// Arguments of `export`.
#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["env", "grid", "problem", "file"])))]
pub struct ExportArgs {
    /// The environment (frozenlake[...], cliffwalking[...], taxi).
    #[arg(long, value_name = "SPEC")]
    env: Option<String>,
    /// One of the paper's problems, 0 to 18 (with --gamma and --noise: the stochastic model).
    #[arg(long, value_name = "N")]
    problem: Option<usize>,
    /// A problem file (JSON or DRN; a deterministic one perturbed by --gamma and --noise).
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    /// A benchmark grid ROWSxCOLS (4 neighbours, start top-left; costs and goals from
    /// --pattern, by default move costs 1-4 from --seed and the goal bottom-right): a
    /// deterministic problem, perturbed by --gamma and --noise if given.
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
    /// Stage cost of a grid move of a paper problem [default: unit].
    #[arg(long, value_enum, requires = "problem")]
    step_cost: Option<StepCost>,
    /// Predictability gamma in (0, 1] for --problem, --grid and a deterministic --file.
    #[arg(long, value_name = "G")]
    gamma: Option<String>,
    /// How 1 - gamma is spread [default: paper].
    #[arg(long, value_enum)]
    noise: Option<NoiseModel>,
    /// The format written: json (truecost's problem file), drn (Storm's explicit format) or
    /// prism (the PRISM language).
    #[arg(long, value_enum, default_value_t = ExportFormat::Json)]
    format: ExportFormat,
    /// The file to write.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// Runs `export`.
pub fn run(args: &ExportArgs) -> Result<String, String> {
    truecost::atomic::check_target(&args.out)?;
    if let Some(size) = &args.grid {
        return grid(args, size);
    }
    let env = super::env::EnvArg {
        env: args.env.clone(),
    };
    let source = super::env::source(
        &env,
        args.problem,
        args.file.as_deref(),
        args.step_cost,
        args.gamma.as_deref(),
        args.noise,
    )?;
    let model = source.load()?;
    let (problem, mut extra) = model.exportable();
    let name = if matches!(source, Source::Env(_)) {
        format!(
            "{} (truecost stage costs, {})",
            model.name, model.reward_source
        )
    } else {
        let gamma = args
            .gamma
            .as_deref()
            .map(|g| Predictability::parse(g).map_err(|e| e.to_string()))
            .transpose()?;
        perturbed(model.name.clone(), gamma.as_ref(), args.noise)
    };
    // Rewards that are the negated stage costs (the default) are not written.
    let negated = (0..problem.action_total()).all(|a| model.reward[a] == -problem.cost(a).clone());
    if negated && !matches!(source, Source::Env(_)) {
        extra.rewards = None;
    }
    write(args, &problem, &extra, &name)
}

/// Writes the problem in the format asked for and says what was written.
fn write(
    args: &ExportArgs,
    problem: &StochasticProblem,
    extra: &FileObjective,
    name: &str,
) -> Result<String, String> {
    let (problem, extra) = &truecost::formats::dead_ends_as_traps(problem, extra);
    let text = match args.format {
        ExportFormat::Json => to_json_with_objective(problem, Some(name), extra) + "\n",
        ExportFormat::Drn => drn::to_drn(problem, extra, Some(name)).map_err(|e| e.to_string())?,
        ExportFormat::Prism => {
            prism::to_prism(problem, extra, Some(name)).map_err(|e| e.to_string())?
        }
    };
    truecost::atomic::write(&args.out, text.as_bytes())?;
    Ok(format!(
        "wrote {} ({} states, {} actions)\n",
        args.out.display(),
        problem.states(),
        problem.action_total()
    ))
}

/// `export --grid`: a grid of the pattern family, deterministic (as a JSON problem file
/// without --gamma) or perturbed by --gamma and --noise; every option is checked before the
/// grid is built.
fn grid(args: &ExportArgs, size: &str) -> Result<String, String> {
    use truecost::stochastic::benchmark::{
        exportable_size, parse_size, pattern_grid, CostRange, GridPattern,
    };
    let (rows, cols) = parse_size(size).map_err(|e| e.to_string())?;
    exportable_size(rows, cols).map_err(|e| e.to_string())?;
    let pattern = match &args.pattern {
        Some(p) => GridPattern::parse(p).map_err(|e| e.to_string())?,
        None => GridPattern::Random,
    };
    let range = match &args.costs {
        Some(c) => CostRange::parse(c).map_err(|e| e.to_string())?,
        None => CostRange::DEFAULT,
    };
    if args.costs.is_some() && pattern != GridPattern::Random {
        return Err(format!(
            "--costs applies to --pattern random only (pattern {} has fixed costs)",
            pattern.name()
        ));
    }
    let gamma = args
        .gamma
        .as_deref()
        .map(|g| Predictability::parse(g).map_err(|e| e.to_string()))
        .transpose()?;
    let seed = args.seed;
    let problem = pattern_grid(rows, cols, pattern, range, seed).map_err(|e| e.to_string())?;
    let name = match pattern {
        GridPattern::Random => format!(
            "benchmark grid {rows}x{cols}, move costs {}-{} from seed {seed}",
            range.lo, range.hi
        ),
        p => format!("benchmark grid {rows}x{cols}, pattern {}", p.name()),
    };
    if args.format == ExportFormat::Json && gamma.is_none() && args.noise.is_none() {
        let text = truecost::model::file::to_json(&problem, Some(&name));
        truecost::atomic::write(&args.out, (text + "\n").as_bytes())?;
        return Ok(format!(
            "wrote {} ({} states, {} moves)\n",
            args.out.display(),
            problem.states(),
            (0..problem.states())
                .map(|x| problem.moves(x).len())
                .sum::<usize>()
        ));
    }
    let name = perturbed(name, gamma.as_ref(), args.noise);
    let noise = args.noise.unwrap_or_default();
    let gamma = gamma.unwrap_or_else(Predictability::one);
    let stochastic = StochasticProblem::from_deterministic(&problem, noise, &gamma)
        .map_err(|e| e.to_string())?;
    write(args, &stochastic, &FileObjective::default(), &name)
}

/// A deterministic source's name with the noise applied to it (nothing for `γ = 1`).
fn perturbed(name: String, gamma: Option<&Predictability>, noise: Option<NoiseModel>) -> String {
    match gamma.filter(|g| !g.is_deterministic()) {
        Some(g) => format!(
            "{name}, gamma {}, {} noise",
            truecost::stochastic::short_text(g.value()),
            noise.unwrap_or_default().name()
        ),
        None => name,
    }
}

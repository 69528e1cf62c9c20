//! Command-line interface (clap). Every error is one line on stderr and a non-zero exit:
//! 2 for usage errors (clap), 1 for bad input or a failed run.

mod certify;
mod compare;
mod discount;
mod env;
mod export;
mod learn;
mod output;
mod render;
mod reproduce;
mod stochastic;
mod verify;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand, ValueEnum};

use truecost::echo::echo;
use truecost::planning::{plan_exact, plan_reference, Mode};
use truecost::problems::{GridLayout, StepCost, GRID_NODES};
use truecost::stochastic::file::ProblemFile;

/// Exact planning, the paper's problems, and machine-checked claims of "Relating Reinforcement
/// Learning to Dynamic Programming-Based Planning" (Georgiev, Timperi, Sakçak, LaValle).
#[derive(Parser, Debug)]
#[command(name = "truecost", version, about, long_about = None, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Check the paper's claims C1-C4 by machine (exit 0 even when a claim is refuted).
    Verify(verify::VerifyArgs),
    /// The exact set of discount factors for which a discount-optimal policy misses the goal.
    Discount(discount::DiscountArgs),
    /// Replay derandomized Q-learning (rho = 1) on a problem file, round by round, in exact arithmetic.
    Learn(learn::LearnArgs),
    /// List the paper's 19 grid problems with their facts (states, edges, x1, goal, optimum).
    Problems(ProblemsArgs),
    /// Solve one problem with an exact planner (or the paper's code, in reference mode).
    Solve(SolveArgs),
    /// Draw a problem (obstacles, moves, start, goal) with an optional overlay, as SVG or PNG.
    Render(render::RenderArgs),
    /// Reproduce one of the paper's experiments over seeded samples.
    Reproduce(reproduce::ReproduceArgs),
    /// Every objective side by side: success probability, expected truecost, expected steps.
    Compare(compare::CompareArgs),
    /// Write a problem (--env, --problem, --file, --grid) as a problem file, in Storm's DRN format
    /// or in the PRISM language.
    Export(export::ExportArgs),
    /// Check a certificate of `solve --certificate` or `discount --certificate` against the
    /// problem, re-read, in exact arithmetic (exit 0 only if every condition holds).
    Check(CheckArgs),
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file", "env"])))]
struct CheckArgs {
    #[command(flatten)]
    env: env::EnvArg,
    /// One of the paper's problems, 0 to 18 (built with the certificate's step cost, gamma
    /// and noise model).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// A problem file (perturbed by the certificate's gamma and noise model, if it gives them).
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    #[command(flatten)]
    drn: stochastic::DrnNameArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Text)]
    format: ReportFormat,
    /// Also run the verified checker (proofs/coq/CertificateCheck.v and
    /// CertificateDiscounted.v, extracted to OCaml with zarith and built on first use; truecost,
    /// deterministic and discounted objectives): its acceptance implies the certificate's values
    /// are optimal (theorems Truecost.CertificateCheck.check_optimal,
    /// Truecost.CertificateDiscounted.check_discounted_optimal).
    #[arg(long)]
    coq: bool,
    /// The certificate file (`truecost-certificate/1`).
    #[arg(value_name = "CERT")]
    certificate: PathBuf,
}

/// Output format of a listing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ListFormat {
    /// Aligned text.
    Text,
    /// A JSON array.
    Json,
    /// Comma-separated values with a header.
    Csv,
    /// A Markdown table.
    Markdown,
}

/// Output format of a single result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ReportFormat {
    /// Readable text.
    Text,
    /// One JSON object.
    Json,
}

#[derive(Args, Debug)]
struct ProblemsArgs {
    /// Output format.
    #[arg(long, value_enum, default_value_t = ListFormat::Text)]
    format: ListFormat,
    /// Build the problems as the paper's reference code does (f64 geometry, its action order).
    #[arg(long, value_enum, default_value_t = Mode::Exact)]
    mode: Mode,
    #[command(flatten)]
    env: env::EnvArg,
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file", "env"])))]
struct SolveArgs {
    #[command(flatten)]
    env: env::EnvArg,
    #[command(flatten)]
    objective: env::ObjectiveArgs,
    /// One of the paper's problems, 0 to 18 (`truecost problems` lists them).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// A problem file: truecost's JSON format (docs/guide/problem-files.md) or Storm's DRN
    /// (docs/guide/formats.md), told apart by content.
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    #[command(flatten)]
    drn: stochastic::DrnNameArgs,
    /// The planner (`exact`: the exact optimum of the stochastic model, by policy iteration
    /// with exact rational linear solves).
    #[arg(long, value_enum)]
    algorithm: stochastic::SolveAlgorithm,
    /// Explore first (depth-first walk over edges, counting actions), then plan on the
    /// discovered graph; reported actions = exploration + planner.
    #[arg(long)]
    model_free: bool,
    /// `exact`: the paper's text in exact arithmetic. `reference`: the paper's code (f64
    /// Euclidean costs, its orders and counting rules; paper problems only).
    #[arg(long, value_enum, default_value_t = Mode::Exact)]
    mode: Mode,
    /// Stage cost of a grid move in exact mode: 1, or the exact segment length 800/19
    /// [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Text)]
    format: ReportFormat,
    /// Predictability gamma in (0, 1] (exact decimal text, e.g. 0.999): the stochastic model
    /// (docs/spec.md §3); 1 is deterministic.
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    gamma: Option<String>,
    /// How the probability 1 - gamma is spread: `paper` (the text) or `reference` (the
    /// paper's code) [default: paper].
    #[arg(long, value_enum)]
    noise: Option<truecost::stochastic::NoiseModel>,
    /// Stochastic VI: stop after a sweep whose largest change is at most this [default: 0.1].
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    tolerance: Option<String>,
    /// Stochastic VI: stop after this many sweeps at the latest [default: 1000].
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    max_sweeps: Option<u64>,
    /// Stochastic VI in exact mode: exact rationals or f64 [default: exact].
    #[arg(long, value_enum)]
    arithmetic: Option<stochastic::Arithmetic>,
    #[command(flatten)]
    scale: stochastic::ScaleArgs,
    /// With --algorithm exact: also write a certificate of the optimum (values, policy, the
    /// problem's SHA-256) to FILE, for `truecost check` (docs/guide/certificates.md).
    #[arg(long, value_name = "FILE")]
    certificate: Option<PathBuf>,
    /// With --objective reach: also compute the reported policy's expected truecost and steps
    /// when they are finite (one exact optimum and one exact evaluation; without it they are
    /// reported only where the graph analysis shows them infinite).
    #[arg(long)]
    with_cost: bool,
}

/// Runs the command line and maps every failure to a one-line message.
pub fn main() -> ExitCode {
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        let line = truecost::echo::one_line(msg.lines().next().unwrap_or(""));
        eprintln!("error: internal error (please report): {line}");
    }));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version: clap's own output on stdout.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("error: {}", usage_line(&e));
            return ExitCode::from(2);
        }
    };
    let threads = std::env::var_os("RAYON_NUM_THREADS").map(|v| v.to_string_lossy().into_owned());
    if let Err(message) = truecost::experiments::runs::check_thread_variable(threads.as_deref()) {
        eprintln!("error: {}", truecost::echo::one_line(&message));
        return ExitCode::from(2);
    }
    let result = match cli.command {
        Command::Problems(args) => problems(&args),
        Command::Solve(args) => solve(&args),
        Command::Render(args) => render::run(&args),
        Command::Reproduce(args) => reproduce::run(&args),
        Command::Verify(args) => verify::verify(&args),
        Command::Discount(args) => discount::discount(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Export(args) => export::run(&args),
        Command::Learn(args) => learn::learn(&args),
        Command::Check(args) => args.drn.names(args.file.as_deref()).and_then(|names| {
            discount::check_certificate(
                &args.env,
                args.problem,
                args.file.as_deref(),
                &names,
                &args.certificate,
                args.format,
                args.coq,
            )
        }),
    };
    match result.and_then(|text| emit(&text)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {}", truecost::echo::one_line(&message));
            ExitCode::from(1)
        }
    }
}

/// A clap usage error as one escaped line: its message (without clap's `error: ` prefix, tips
/// and usage block) and the help to read.
fn usage_line(e: &clap::Error) -> String {
    // The first paragraph of clap's message: for a missing argument, its heading line and the
    // indented lines naming what is missing.
    let rendered = e.render().to_string();
    let paragraph: Vec<&str> = rendered
        .lines()
        .map(str::trim)
        .skip_while(|l| l.is_empty())
        .take_while(|l| !l.is_empty())
        .collect();
    let joined = paragraph.join(" ");
    let message = if joined.is_empty() {
        "invalid arguments"
    } else {
        joined.as_str()
    };
    let message = message.strip_prefix("error: ").unwrap_or(message);
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .take(2)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    let mut help = String::from("truecost");
    let commands = [
        "verify",
        "discount",
        "problems",
        "solve",
        "render",
        "reproduce",
        "compare",
        "export",
        "learn",
        "check",
    ];
    if let Some(command) = args.first().filter(|a| commands.contains(&a.as_str())) {
        help.push(' ');
        help.push_str(command);
        if let Some(experiment) = args.get(1).filter(|a| {
            command == "reproduce" && ["deterministic", "stochastic"].contains(&a.as_str())
        }) {
            help.push(' ');
            help.push_str(experiment);
        }
    }
    truecost::echo::one_line(&format!("{message} (see '{help} --help')"))
}

/// Writes to stdout; a closed pipe (e.g. `| head`) is not an error.
fn emit(text: &str) -> Result<(), String> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.to_string()),
        _ => Ok(()),
    }
}

fn problems(args: &ProblemsArgs) -> Result<String, String> {
    if let Some(spec) = &args.env.env {
        return env::problems(spec, args.format);
    }
    let facts = (0..truecost::problems::paper_scenarios().len())
        .map(|id| {
            let layout = match args.mode {
                Mode::Exact => GridLayout::exact(id),
                Mode::Reference => GridLayout::reference(id),
            };
            layout.map(|l| l.facts()).map_err(|e| e.to_string())
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(output::problems(&facts, args.format, args.mode))
}

/// Reads a problem file (either format, once) for `command`, which needs a single initial
/// state: a file that draws its initial state from two or more states is refused in one line
/// naming the command, before any work.
fn read_single_initial(path: &std::path::Path, command: &str) -> Result<ProblemFile, String> {
    read_single_initial_named(path, &Default::default(), command)
}

/// [`read_single_initial`] with a DRN file's goal label and cost reward model.
fn read_single_initial_named(
    path: &std::path::Path,
    names: &truecost::formats::drn::DrnNames,
    command: &str,
) -> Result<ProblemFile, String> {
    let (file, extra) =
        truecost::formats::read_with_names(path, names).map_err(|e| e.to_string())?;
    extra.single_initial(command).map_err(|e| e.to_string())?;
    Ok(file)
}

fn solve(args: &SolveArgs) -> Result<String, String> {
    let names = args.drn.names(args.file.as_deref())?;
    if args.certificate.is_some()
        && (args.algorithm != stochastic::SolveAlgorithm::Exact
            || args.mode != Mode::Exact
            || args.model_free)
    {
        return Err("--certificate certifies the exact optimum: use --algorithm exact (without --mode reference or --model-free)".into());
    }
    if let Some(path) = &args.certificate {
        truecost::atomic::check_target(path)?;
    }
    if args.with_cost && args.objective.objective != Some(env::ObjectiveName::Reach) {
        return Err("--with-cost applies to --objective reach (the other objectives always compute the reported policy's expected truecost and steps)".into());
    }
    if env::wants(args) {
        return env::solve(args);
    }
    if args.file.is_some() && args.mode == Mode::Reference {
        return Err("--mode reference reproduces the paper's code and applies to the paper's problems (--problem N) only".into());
    }
    if args.file.is_some() && args.step_cost.is_some() {
        return Err("--step-cost applies to the paper's grid problems (--problem N); a problem file gives its own costs".into());
    }
    // A file is read once, in either format (pipes and FIFOs can be read only once). The
    // planners and the stochastic solvers answer from one initial state x1; the objectives
    // (env::solve above) take an initial distribution.
    let loaded = match &args.file {
        Some(path) => Some(read_single_initial_named(
            path,
            &names,
            "solve without --objective",
        )?),
        None => None,
    };
    let Some(algorithm) = stochastic::deterministic_algorithm(args, loaded.as_ref()) else {
        return stochastic::solve(args, loaded);
    };
    stochastic::refuse_scale_options(&args.scale)?;
    let (report, source) = match (loaded, args.problem, args.mode) {
        (Some(ProblemFile::Deterministic(problem)), _, _) => {
            let path = args.file.as_deref().expect("a file was read");
            let report = plan_exact(&problem, algorithm, args.model_free);
            (
                report,
                format!("file {}", echo(&path.display().to_string())),
            )
        }
        (Some(ProblemFile::Stochastic(_)), _, _) => {
            unreachable!("a file with outcomes goes to the stochastic solvers")
        }
        (None, Some(id), Mode::Exact) => {
            let step = args.step_cost.unwrap_or_default();
            let problem = GridLayout::exact(id)
                .map_err(|e| e.to_string())?
                .to_problem(step);
            let report = plan_exact(&problem, algorithm, args.model_free);
            let step = match step {
                StepCost::Unit => "unit step costs",
                StepCost::Euclidean => "Euclidean step costs 800/19",
            };
            (report, format!("paper problem {id} (paper text, {step})"))
        }
        (None, Some(id), Mode::Reference) => {
            if args.step_cost.is_some() {
                return Err("--step-cost applies to --mode exact; the reference mode always uses the paper code's f64 Euclidean costs".into());
            }
            let graph = GridLayout::reference(id)
                .map_err(|e| e.to_string())?
                .to_reference_graph();
            debug_assert_eq!(graph.nodes(), GRID_NODES);
            let report = plan_reference(&graph, algorithm, args.model_free);
            (
                report,
                format!("paper problem {id} (reference code: f64 Euclidean costs)"),
            )
        }
        (None, None, _) => return Err("give --problem N or --file FILE".into()),
    };
    Ok(match args.format {
        ReportFormat::Text => output::report_text(&report, &source),
        ReportFormat::Json => output::report_json(&report, &source),
    })
}

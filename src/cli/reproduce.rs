//! `truecost reproduce …`: the paper's experiments, with a progress bar and files.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use truecost::experiments::deterministic::{self, Settings};
use truecost::experiments::stochastic;
use truecost::experiments::tables::{self, Table};
use truecost::learning::stochastic_q::Tolerance;
use truecost::planning::Mode;
use truecost::problems::{StepCost, PAPER_PROBLEMS};
use truecost::stochastic::Predictability;

/// Which experiment to reproduce.
#[derive(Args, Debug)]
pub struct ReproduceArgs {
    #[command(subcommand)]
    experiment: Experiment,
}

#[derive(Subcommand, Debug)]
enum Experiment {
    /// The deterministic comparison: Q-learning (ε = 0, 0.25, 0.5, 0.75, 0.9, 1), the π plan,
    /// ε-decay, and model-free Dijkstra / asynchronous VI / synchronous VI, over seeded samples.
    Deterministic(DeterministicArgs),
    /// The stochastic comparison: stochastic Q-learning over γ × ρ × ε, and stochastic
    /// asynchronous / synchronous VI, judged against the exact optimum G*.
    Stochastic(StochasticArgs),
    /// Combine the shard files of `reproduce deterministic|stochastic --shard K/N` (all N, of
    /// one run) into the report the unsharded run gives.
    Merge(MergeArgs),
}

#[derive(Args, Debug)]
struct MergeArgs {
    /// The shard files (any order).
    #[arg(required = true, value_name = "FILES")]
    files: Vec<PathBuf>,
    /// Put the paper's published numbers beside ours (as the experiment's option).
    #[arg(long)]
    against_published: bool,
    #[command(flatten)]
    output: Output,
}

#[derive(Args, Debug)]
struct StochasticArgs {
    /// Problems, comma-separated [default: the paper's 16 problems 0-5,7-16].
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "LIST",
        allow_negative_numbers = true
    )]
    problems: Option<Vec<usize>>,
    /// Predictability factors γ ∈ (0, 1], decimal text, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "LIST", default_values_t = stochastic::DEFAULT_GAMMAS.map(String::from), allow_negative_numbers = true)]
    gammas: Vec<String>,
    /// Learning rates: ρ ∈ (0, 1] or the per-pair decay 1/n^ω with ω ∈ (0.5, 1].
    #[arg(long, value_delimiter = ',', value_name = "LIST", default_values_t = stochastic::DEFAULT_RHOS.map(String::from), allow_negative_numbers = true)]
    rhos: Vec<String>,
    /// Exploration rates ε ∈ [0, 1], or `decay` (linear from 1 to 0.1 over the episodes).
    #[arg(long, value_delimiter = ',', value_name = "LIST", default_values_t = stochastic::DEFAULT_EPSILONS.map(String::from), allow_negative_numbers = true)]
    epsilons: Vec<String>,
    /// Samples per learning row.
    #[arg(
        long,
        default_value_t = 10,
        value_name = "N",
        allow_negative_numbers = true
    )]
    samples: u32,
    /// Noise model: `paper` (text) or `reference` (code).
    #[arg(long, value_enum, default_value_t = truecost::stochastic::NoiseModel::Paper)]
    noise: truecost::stochastic::NoiseModel,
    /// Tolerance of "learnt": `relative` (within 10% of G*, unit step costs) or `reference`
    /// (±5 cost units, Euclidean step costs 800/19).
    #[arg(long, value_enum, default_value_t = Tolerance::Relative)]
    tolerance: Tolerance,
    /// Master seed: every random choice derives from it and the sample's coordinates.
    #[arg(
        long,
        default_value_t = 0,
        value_name = "S",
        allow_negative_numbers = true
    )]
    seed: u64,
    /// Episodes per learning run (the paper's stochastic runs: 3000).
    #[arg(
        long,
        default_value_t = 3000,
        value_name = "E",
        allow_negative_numbers = true
    )]
    episodes: u32,
    /// Steps per episode.
    #[arg(
        long,
        default_value_t = 3000,
        value_name = "M",
        allow_negative_numbers = true
    )]
    max_steps: u32,
    /// Put the paper's published numbers (data/published/) beside ours, with a verdict per
    /// metric and closing counts. The paper's VI counts need `--noise reference --tolerance
    /// reference`.
    #[arg(long)]
    against_published: bool,
    /// Run shard K of N (1 <= K <= N <= 4096): the learning runs t with t mod N = K-1 and the
    /// VI runs of the (problem, γ) pairs i with i mod N = K-1; writes the shard file (JSON) to
    /// stdout for `reproduce merge`.
    #[arg(long, value_name = "K/N", conflicts_with_all = ["against_published", "out", "plots", "format"])]
    shard: Option<String>,
    /// Also write the certificate of every exact optimum the comparison measures against (one
    /// per problem and γ: its truecost optimum under the noise model and the tolerance's step
    /// cost) to DIR, as `problem-<N>-gamma-<γ>.cert.json`; `truecost check --problem N FILE`
    /// checks each.
    #[arg(long, value_name = "DIR", conflicts_with = "shard")]
    certificates: Option<PathBuf>,
    #[command(flatten)]
    output: Output,
}

/// Output format of a reproduction report.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum Format {
    /// Aligned text.
    Text,
    /// JSON (the rows; with `--against-published` an object with the summary).
    Json,
    /// Comma-separated values with a header.
    Csv,
    /// Markdown tables.
    Markdown,
    /// LaTeX tables (booktabs, longtable), the published values beside ours.
    Latex,
}

impl Format {
    /// The library's table format (LaTeX has its own renderer; text is its stand-in here).
    fn table(self) -> Table {
        match self {
            Format::Text | Format::Latex => Table::Text,
            Format::Json => Table::Json,
            Format::Csv => Table::Csv,
            Format::Markdown => Table::Markdown,
        }
    }
}

/// Threads and outputs, as every experiment takes them.
#[derive(Args, Debug)]
struct Output {
    /// Worker threads [default: all cores, or RAYON_NUM_THREADS].
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    threads: Option<usize>,
    /// Also write the report as Markdown, CSV, JSON and LaTeX into DIR (deterministic.md,
    /// .csv, .json, .tex, or stochastic.*).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Also write the paper's plots as SVG and PNG into DIR: goal discovery and convergence
    /// rate against ε (deterministic); run time and convergence rate against ρ, convergence
    /// rate against ε, a series per γ (stochastic).
    #[arg(long, value_name = "DIR")]
    plots: Option<PathBuf>,
    /// Output format on stdout.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

/// The report files `--out` writes, by extension.
const REPORT_EXTENSIONS: [&str; 4] = ["md", "csv", "json", "tex"];

impl Output {
    /// Creates the `--out` and `--plots` directories before the (long) run, so a bad path
    /// fails at once and no result is lost.
    /// Each report file `stem.*` of `--out` and a file in `--plots` is checked writable too.
    fn prepare(&self, stem: &str) -> Result<(), String> {
        if let Some(dir) = &self.out {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot create output directory {}: {e}", dir.display()))?;
            for ext in REPORT_EXTENSIONS {
                truecost::atomic::check_target(&dir.join(format!("{stem}.{ext}")))?;
            }
        }
        if let Some(dir) = &self.plots {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot create plot directory {}: {e}", dir.display()))?;
            truecost::atomic::check_target(&dir.join(format!("{stem}.svg")))?;
        }
        Ok(())
    }

    /// Writes `DIR/stem.md`, `.csv`, `.json` (`--out`) and the charts (`--plots`), and returns
    /// the report in the `--format` asked for.
    fn finish(
        &self,
        stem: &str,
        render: impl Fn(Format) -> String,
        charts: impl FnOnce() -> Vec<(String, truecost::figures::chart::LineChart)>,
    ) -> Result<String, String> {
        if let Some(dir) = &self.out {
            for (ext, format) in REPORT_EXTENSIONS.into_iter().zip([
                Format::Markdown,
                Format::Csv,
                Format::Json,
                Format::Latex,
            ]) {
                write_file(&dir.join(format!("{stem}.{ext}")), &render(format))?;
            }
        }
        if let Some(dir) = &self.plots {
            write_plots(dir, charts())?;
        }
        Ok(render(self.format))
    }
}

#[derive(Args, Debug)]
struct DeterministicArgs {
    /// Problems, comma-separated, in the order the π rows run [default: the paper's 16
    /// problems 0-5,7-16].
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "LIST",
        allow_negative_numbers = true
    )]
    problems: Option<Vec<usize>>,
    /// Samples per row.
    #[arg(
        long,
        default_value_t = 100,
        value_name = "N",
        allow_negative_numbers = true
    )]
    samples: u32,
    /// Master seed: every random choice derives from it and the sample's coordinates.
    #[arg(
        long,
        default_value_t = 0,
        value_name = "S",
        allow_negative_numbers = true
    )]
    seed: u64,
    /// `exact`: the paper's text (exact values, unit step costs, metrics after every action).
    /// `reference`: the paper's code (f64, its orders and counting rules; reproduces the
    /// published counts).
    #[arg(long, value_enum, default_value_t = Mode::Exact)]
    mode: Mode,
    /// Grid step cost in exact mode [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// Episodes per learning run.
    #[arg(
        long,
        default_value_t = 1000,
        value_name = "E",
        allow_negative_numbers = true
    )]
    episodes: u32,
    /// Steps per episode.
    #[arg(
        long,
        default_value_t = 3000,
        value_name = "M",
        allow_negative_numbers = true
    )]
    max_steps: u32,
    /// Put the paper's published numbers (data/published/) beside ours, with a verdict per
    /// metric (exact / consistent / differs / machine) and closing counts. The published
    /// counts come out `exact` with `--mode reference`.
    #[arg(long)]
    against_published: bool,
    /// Run shard K of N (1 <= K <= N <= 4096): the sample runs t with t mod N = K-1 (the π
    /// rows, one shared digit stream, on shard 1); writes the shard file (JSON) to stdout for
    /// `reproduce merge`.
    #[arg(long, value_name = "K/N", conflicts_with_all = ["against_published", "out", "plots", "format"])]
    shard: Option<String>,
    #[command(flatten)]
    output: Output,
}

/// Runs a `reproduce` command; returns what to print.
pub fn run(args: &ReproduceArgs) -> Result<String, String> {
    match &args.experiment {
        Experiment::Deterministic(a) => deterministic_command(a),
        Experiment::Stochastic(a) => stochastic_command(a),
        Experiment::Merge(a) => merge_command(a),
    }
}

/// `reproduce merge FILES…`.
fn merge_command(args: &MergeArgs) -> Result<String, String> {
    let files = truecost::claims::shard::read_files(&args.files)?;
    let first: serde_json::Value = serde_json::from_str(&files[0].1).unwrap_or_default();
    let stochastic_shards = first["format"].as_str() == Some(stochastic::SHARD_FORMAT);
    args.output.prepare(if stochastic_shards {
        "stochastic"
    } else {
        "deterministic"
    })?;
    if stochastic_shards {
        let (mut report, settings) = stochastic::merge(&files)?;
        if args.against_published {
            stochastic::against_published(&mut report, &settings).map_err(|e| e.to_string())?;
        }
        return args.output.finish(
            "stochastic",
            |format| match format {
                Format::Latex => truecost::experiments::latex::stochastic(&report, true),
                f => tables::stochastic(&report, f.table()),
            },
            || truecost::figures::plots::stochastic(&report),
        );
    }
    let (mut report, settings) = deterministic::merge(&files)?;
    if args.against_published {
        deterministic::against_published(&mut report, &settings).map_err(|e| e.to_string())?;
    }
    args.output.finish(
        "deterministic",
        |format| match format {
            Format::Latex => truecost::experiments::latex::deterministic(&report, true),
            f => tables::deterministic(&report, f.table()),
        },
        || truecost::figures::plots::deterministic(&report),
    )
}

fn deterministic_command(args: &DeterministicArgs) -> Result<String, String> {
    if args.mode == Mode::Reference && args.step_cost.is_some() {
        return Err("--step-cost applies to --mode exact; the reference mode always uses the paper code's f64 Euclidean costs".into());
    }
    let settings = Settings {
        problems: args
            .problems
            .clone()
            .unwrap_or_else(|| PAPER_PROBLEMS.to_vec()),
        samples: args.samples,
        seed: args.seed,
        mode: args.mode,
        step_cost: args.step_cost.unwrap_or_default(),
        episodes: args.episodes,
        max_steps: args.max_steps,
        threads: args.output.threads,
    };
    settings.validate().map_err(|e| e.to_string())?;
    if let Some(part) = &args.shard {
        let part = truecost::claims::shard::Part::parse(part)?;
        let bar = progress_bar(
            args.output.quiet,
            deterministic::shard_runs(&settings, part),
        );
        let file = deterministic::run_shard(&settings, part, &|k| bar.inc(k));
        bar.finish_and_clear();
        return file.map_err(|e| e.to_string());
    }
    args.output.prepare("deterministic")?;
    let bar = progress_bar(args.output.quiet, deterministic::total_runs(&settings));
    let mut report = deterministic::run(&settings, &|k| bar.inc(k)).map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    if args.against_published {
        deterministic::against_published(&mut report, &settings).map_err(|e| e.to_string())?;
    }
    args.output.finish(
        "deterministic",
        |format| match format {
            Format::Latex => truecost::experiments::latex::deterministic(&report, true),
            f => tables::deterministic(&report, f.table()),
        },
        || truecost::figures::plots::deterministic(&report),
    )
}

/// Writes each chart as `DIR/stem.svg` and `DIR/stem.png`.
fn write_plots(
    dir: &Path,
    charts: Vec<(String, truecost::figures::chart::LineChart)>,
) -> Result<(), String> {
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("cannot create plot directory {}: {e}", dir.display()))?;
    for (stem, chart) in charts {
        let canvas = chart.draw(1000, 650).map_err(|e| e.to_string())?;
        for ext in ["svg", "png"] {
            canvas
                .save(&dir.join(format!("{stem}.{ext}")))
                .map_err(|e| e.to_string())?;
        }
    }
    Ok(())
}

/// A progress bar on stderr (hidden when quiet or not a terminal).
fn progress_bar(quiet: bool, total: u64) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(
            "{elapsed_precise} [{bar:40}] {pos}/{len} sample runs ({eta} left)",
        )
        .expect("a valid template")
        .progress_chars("=> "),
    );
    bar
}

fn stochastic_command(args: &StochasticArgs) -> Result<String, String> {
    let e = |e: stochastic::ExperimentError| e.to_string();
    let settings = stochastic::Settings {
        problems: args
            .problems
            .clone()
            .unwrap_or_else(|| PAPER_PROBLEMS.to_vec()),
        gammas: args
            .gammas
            .iter()
            .map(|g| Predictability::parse(g.trim()).map_err(|err| err.to_string()))
            .collect::<Result<_, _>>()?,
        rhos: args
            .rhos
            .iter()
            .map(|r| stochastic::RateSpec::parse(r))
            .collect::<Result<_, _>>()
            .map_err(e)?,
        epsilons: args
            .epsilons
            .iter()
            .map(|x| stochastic::EpsilonSpec::parse(x))
            .collect::<Result<_, _>>()
            .map_err(e)?,
        samples: args.samples,
        seed: args.seed,
        noise: args.noise,
        tolerance: args.tolerance,
        episodes: args.episodes,
        max_steps: args.max_steps,
        threads: args.output.threads,
    };
    settings.validate().map_err(e)?;
    if let Some(part) = &args.shard {
        let part = truecost::claims::shard::Part::parse(part)?;
        let bar = progress_bar(args.output.quiet, stochastic::shard_runs(&settings, part));
        let file = stochastic::run_shard(&settings, part, &|k| bar.inc(k));
        bar.finish_and_clear();
        return file.map_err(e);
    }
    args.output.prepare("stochastic")?;
    if let Some(dir) = &args.certificates {
        let step = match args.tolerance {
            Tolerance::Relative => StepCost::Unit,
            Tolerance::Reference => StepCost::Euclidean,
        };
        write_certificates(dir, &settings.problems, &args.gammas, args.noise, step)?;
    }
    let bar = progress_bar(args.output.quiet, stochastic::total_runs(&settings));
    let mut report = stochastic::run(&settings, &|k| bar.inc(k)).map_err(e)?;
    bar.finish_and_clear();
    if args.against_published {
        stochastic::against_published(&mut report, &settings).map_err(|e| e.to_string())?;
    }
    args.output.finish(
        "stochastic",
        |format| match format {
            Format::Latex => truecost::experiments::latex::stochastic(&report, true),
            f => tables::stochastic(&report, f.table()),
        },
        || truecost::figures::plots::stochastic(&report),
    )
}

/// The certificate of the exact truecost optimum of every paper problem of `problems` at
/// every `γ` of `gammas` (as given), under `noise` with step cost `step`, written to `dir`.
fn write_certificates(
    dir: &Path,
    problems: &[usize],
    gammas: &[String],
    noise: truecost::stochastic::NoiseModel,
    step: StepCost,
) -> Result<(), String> {
    use truecost::certificate::CertifiedObjective;
    std::fs::create_dir_all(dir).map_err(|e| {
        format!(
            "cannot create --certificates {}: {e}",
            truecost::echo::echo(&dir.display().to_string())
        )
    })?;
    for &id in problems {
        for g in gammas {
            let g = g.trim();
            let gamma = Predictability::parse(g).map_err(|e| e.to_string())?;
            let model = truecost::objectives::Source::Paper {
                id,
                step,
                noise,
                gamma,
            }
            .load()?;
            let opt = truecost::stochastic::policy_iteration::optimum(&model.problem)
                .map_err(|e| e.to_string())?;
            let origin = truecost::stochastic::record::Origin::Paper { id, step };
            let record =
                truecost::stochastic::record::problem_record(origin, Some(g), Some(noise), || {
                    model.mdp()
                })?;
            let text = truecost::stochastic::certified::optimum_certificate(
                &model.problem,
                &opt,
                &CertifiedObjective::Truecost,
                &record,
            );
            let name = format!("problem-{id}-gamma-{}.cert.json", g.replace('/', "over"));
            super::certify::write_certificate(&dir.join(name), &text)?;
        }
    }
    Ok(())
}

fn write_file(path: &Path, text: &str) -> Result<(), String> {
    truecost::atomic::write(path, text.as_bytes())
}

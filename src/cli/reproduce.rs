//! `truecost reproduce …`: the paper's experiments, with a progress bar and files.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::ListFormat;
use truecost::experiments::deterministic::{self, Report, RowSummary, Settings};
use truecost::experiments::published::{Comparison, Summary, Verdict};
use truecost::experiments::stochastic;
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
    fn list(self) -> ListFormat {
        match self {
            Format::Text | Format::Latex => ListFormat::Text,
            Format::Json => ListFormat::Json,
            Format::Csv => ListFormat::Csv,
            Format::Markdown => ListFormat::Markdown,
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

impl Output {
    /// Creates the `--out` and `--plots` directories before the (long) run, so a bad path
    /// fails at once and no result is lost (issue 12).
    fn prepare(&self) -> Result<(), String> {
        if let Some(dir) = &self.out {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot create output directory {}: {e}", dir.display()))?;
        }
        if let Some(dir) = &self.plots {
            std::fs::create_dir_all(dir)
                .map_err(|e| format!("cannot create plot directory {}: {e}", dir.display()))?;
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
            for (ext, format) in [
                ("md", Format::Markdown),
                ("csv", Format::Csv),
                ("json", Format::Json),
                ("tex", Format::Latex),
            ] {
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

/// `reproduce merge FILES…` (issue 12, item 4).
fn merge_command(args: &MergeArgs) -> Result<String, String> {
    args.output.prepare()?;
    let files = args
        .files
        .iter()
        .map(|p| {
            std::fs::read_to_string(p)
                .map(|text| (p.display().to_string(), text))
                .map_err(|e| format!("cannot read {}: {e}", p.display()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let first: serde_json::Value = serde_json::from_str(&files[0].1).unwrap_or_default();
    if first["format"].as_str() == Some(stochastic::SHARD_FORMAT) {
        let (mut report, settings) = stochastic::merge(&files)?;
        if args.against_published {
            stochastic::against_published(&mut report, &settings).map_err(|e| e.to_string())?;
        }
        return args.output.finish(
            "stochastic",
            |format| match format {
                Format::Latex => truecost::experiments::latex::stochastic(&report, true),
                f => render_stochastic(&report, f.list()),
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
            f => render(&report, f.list()),
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
    args.output.prepare()?;
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
            f => render(&report, f.list()),
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
    args.output.prepare()?;
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
            f => render_stochastic(&report, f.list()),
        },
        || truecost::figures::plots::stochastic(&report),
    )
}

/// Renders a stochastic report in a format. Every format names the noise model, tolerance and
/// seed (JSON and CSV in every row).
pub fn render_stochastic(report: &stochastic::Report, format: ListFormat) -> String {
    match format {
        ListFormat::Json => json(&report.rows, report.against_published.as_ref()),
        ListFormat::Csv => {
            let metrics = comparison_metrics(report.rows.iter().map(|r| r.comparison.as_ref()));
            let mut s = STOCHASTIC_CSV_COLUMNS.join(",") + &comparison_csv_header(&metrics) + "\n";
            for row in &report.rows {
                let value = serde_json::to_value(row).expect("serialisable");
                let cells: Vec<String> = STOCHASTIC_CSV_COLUMNS
                    .iter()
                    .map(|&c| match c {
                        "episodes" => report.episodes.to_string(),
                        "max_steps" => report.max_steps.to_string(),
                        _ => match &value[c] {
                            serde_json::Value::Null => String::new(),
                            serde_json::Value::String(t) => quote(t),
                            other => other.to_string(),
                        },
                    })
                    .collect();
                s += &(cells.join(",")
                    + &comparison_csv_cells(row.comparison.as_ref(), &metrics)
                    + "\n");
            }
            s + &summary_csv(report.against_published.as_ref())
        }
        ListFormat::Markdown | ListFormat::Text => stochastic_table(report, format),
    }
}

/// The columns of the stochastic CSV file, in order.
const STOCHASTIC_CSV_COLUMNS: [&str; 35] = [
    "problem",
    "gamma",
    "algorithm",
    "rho",
    "epsilon",
    "samples",
    "optimum_initial",
    "mean_time_s",
    "std_time_s",
    "convergence_rate",
    "mean_actions_converged",
    "mean_actions",
    "std_actions",
    "mean_ns_per_action",
    "mean_iterations",
    "std_iterations",
    "initial_within_rate",
    "mean_actions_initial_within",
    "mean_episode_initial_within",
    "mean_time_initial_within_s",
    "goal_discovery_rate",
    "mean_actions_goal_discovered",
    "mean_time_goal_discovered_s",
    "mean_value_initial",
    "max_error",
    "shortest_path",
    "longest_path",
    "goal_reached_rate",
    "optimal_path_rate",
    "noise",
    "tolerance",
    "seed",
    "episodes",
    "max_steps",
    "note",
];

const STOCHASTIC_HEADER: [&str; 11] = [
    "algorithm",
    "run time s (mean ± std)",
    "actions (mean ± std)",
    "ns/action",
    "episodes/sweeps (mean ± std)",
    "converged",
    "goal discovered: actions / s",
    "V(x1) within: actions / episode / s",
    "V(x1) mean, max |V-G*|",
    "greedy path states",
    "optimal paths",
];

fn stochastic_cells(row: &stochastic::RowSummary) -> Vec<String> {
    let label = match row.algorithm {
        "q-learning" => format!(
            "Q-learning (ρ={}, ε={})",
            row.rho.as_deref().unwrap_or("?"),
            row.epsilon.as_deref().unwrap_or("?")
        ),
        "stochastic-async-vi" => "Stochastic asynchronous VI".into(),
        "stochastic-vi" => "Stochastic synchronous VI".into(),
        other => other.into(),
    };
    if row.samples == 0 || (row.note.is_some() && row.mean_actions.is_none()) {
        let mut c = vec![label, row.note.clone().unwrap_or_default()];
        c.resize(STOCHASTIC_HEADER.len(), String::new());
        return c;
    }
    let learning = row.algorithm == "q-learning";
    let paths = match (row.shortest_path, row.longest_path) {
        (Some(a), Some(b)) if a == b => a.to_string(),
        (Some(a), Some(b)) => format!("{a}–{b}"),
        _ => "–".into(),
    };
    let pct = |x: Option<f64>| x.map_or("–".into(), |r| format!("{:.0} %", 100.0 * r));
    vec![
        label,
        pm(row.mean_time_s, row.std_time_s, 5),
        pm(row.mean_actions, row.std_actions, 1),
        opt(row.mean_ns_per_action, 1),
        pm(row.mean_iterations, row.std_iterations, 2),
        pct(row.convergence_rate),
        if learning {
            format!(
                "{} / {}",
                opt(row.mean_actions_goal_discovered, 1),
                opt(row.mean_time_goal_discovered_s, 5)
            )
        } else {
            "–".into()
        },
        if learning {
            format!(
                "{} / {} / {}",
                opt(row.mean_actions_initial_within, 1),
                opt(row.mean_episode_initial_within, 1),
                opt(row.mean_time_initial_within_s, 5)
            )
        } else {
            pct(row.initial_within_rate)
        },
        format!(
            "{}, {}",
            opt(row.mean_value_initial, 3),
            row.max_error.as_deref().unwrap_or("–")
        ),
        paths,
        pct(row.optimal_path_rate),
    ]
}

fn stochastic_table(report: &stochastic::Report, format: ListFormat) -> String {
    let mut s = String::new();
    let title = format!(
        "truecost reproduce stochastic — noise {}; tolerance {}; seed {}; {} samples per row; {} episodes × {} steps; problems {}; gammas {}",
        report.noise.name(),
        report.tolerance.name(),
        report.seed,
        report.samples,
        report.episodes,
        report.max_steps,
        report.problems.iter().map(|p| p.to_string()).collect::<Vec<_>>().join(","),
        report.gammas.join(",")
    );
    let notes = [
        format!("model: {}", report.model),
        "Learning rows: means of actions, episodes and times to an event are over the samples \
         that reached it; greedy paths are simulated once per sample (outcomes sampled, capped at \
         100001 steps) and count x1 and the goal. VI rows: the reference code's rules (from 1e30, \
         decrease only, stop at change <= 0.1), actions = its counted outcome terms; 'converged' \
         = every tracked state within tolerance."
            .to_string(),
    ];
    let markdown = format == ListFormat::Markdown;
    if markdown {
        let _ = writeln!(s, "# {title}\n");
        for n in &notes {
            let _ = writeln!(s, "{n}\n");
        }
    } else {
        let _ = writeln!(s, "{title}");
        for n in &notes {
            let _ = writeln!(s, "{n}");
        }
    }
    for p in &report.problems {
        for g in &report.gammas {
            let rows: Vec<&stochastic::RowSummary> = report
                .rows
                .iter()
                .filter(|r| r.problem == *p && &r.gamma == g)
                .collect();
            let optimum = rows.first().map_or("–", |r| r.optimum_initial.as_str());
            let cells: Vec<Vec<String>> = rows.iter().map(|r| stochastic_cells(r)).collect();
            if markdown {
                let _ = writeln!(s, "## Problem {p}, γ = {g} (G*(x1) = {optimum})\n");
                let _ = writeln!(s, "| {} |", STOCHASTIC_HEADER.join(" | "));
                let _ = writeln!(s, "|{}", "---|".repeat(STOCHASTIC_HEADER.len()));
                for c in &cells {
                    let _ = writeln!(s, "| {} |", c.join(" | "));
                }
                s.push('\n');
                s += &comparison_table(
                    rows.iter()
                        .map(|r| (stochastic_cells(r)[0].clone(), r.comparison.as_ref())),
                    true,
                );
            } else {
                let widths = column_widths(&STOCHASTIC_HEADER, cells.iter());
                let line = |c: &[String]| aligned(c, &widths);
                let _ = writeln!(s, "\nProblem {p}, γ = {g} (G*(x1) = {optimum})");
                let header: Vec<String> = STOCHASTIC_HEADER.iter().map(|h| h.to_string()).collect();
                let _ = writeln!(s, "{}", line(&header));
                for c in &cells {
                    let _ = writeln!(s, "{}", line(c));
                }
                s += &comparison_table(
                    rows.iter()
                        .map(|r| (stochastic_cells(r)[0].clone(), r.comparison.as_ref())),
                    false,
                );
            }
        }
    }
    s + &summary_text(report.against_published.as_ref(), markdown)
}

fn write_file(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// Renders a report in a format.
pub fn render(report: &Report, format: ListFormat) -> String {
    match format {
        ListFormat::Json => json(&report.rows, report.against_published.as_ref()),
        ListFormat::Csv => csv(report),
        ListFormat::Markdown => markdown(report),
        ListFormat::Text => text(report),
    }
}

/// The columns of the CSV file, in order.
const CSV_COLUMNS: [&str; 34] = [
    "problem",
    "algorithm",
    "epsilon",
    "epsilon_final",
    "plan",
    "samples",
    "mean_time_s",
    "std_time_s",
    "convergence_rate",
    "mean_actions_converged",
    "mean_actions",
    "std_actions",
    "mean_planner_actions",
    "mean_ns_per_action",
    "mean_iterations",
    "std_iterations",
    "shortest_path",
    "longest_path",
    "goal_reached_rate",
    "optimal_path_rate",
    "loops",
    "initial_optimal_rate",
    "mean_actions_initial_optimal",
    "mean_time_initial_optimal_s",
    "goal_discovery_rate",
    "mean_actions_goal_discovered",
    "mean_time_goal_discovered_s",
    "mode",
    "seed",
    "value_type",
    "episodes",
    "max_steps",
    "model",
    "note",
];

fn csv(report: &Report) -> String {
    let metrics = comparison_metrics(report.rows.iter().map(|r| r.comparison.as_ref()));
    let mut s = CSV_COLUMNS.join(",") + &comparison_csv_header(&metrics) + "\n";
    for row in &report.rows {
        let value = serde_json::to_value(row).expect("serialisable");
        let cells: Vec<String> = CSV_COLUMNS
            .iter()
            .map(|&c| match c {
                "episodes" => report.episodes.to_string(),
                "max_steps" => report.max_steps.to_string(),
                "model" => quote(&report.model),
                _ => match &value[c] {
                    serde_json::Value::Null => String::new(),
                    serde_json::Value::String(t) => quote(t),
                    other => other.to_string(),
                },
            })
            .collect();
        s += &(cells.join(",") + &comparison_csv_cells(row.comparison.as_ref(), &metrics) + "\n");
    }
    s + &summary_csv(report.against_published.as_ref())
}

/// A CSV cell: quoted when it contains a separator or a quote.
fn quote(t: &str) -> String {
    if t.contains([',', '"', '\n']) {
        format!("\"{}\"", t.replace('"', "\"\""))
    } else {
        t.to_string()
    }
}

/// `mean ± std` with a sensible number of digits.
fn pm(mean: Option<f64>, std: Option<f64>, digits: usize) -> String {
    match (mean, std) {
        (Some(m), Some(s)) => format!("{m:.digits$} ± {s:.digits$}"),
        _ => "–".into(),
    }
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn label(row: &RowSummary) -> String {
    let eps = |e: f64| {
        let t = format!("{e}");
        t
    };
    match row.algorithm {
        "q-learning" => format!("Q-learning (ε={})", eps(row.epsilon.unwrap_or(0.0))),
        "q-learning-pi" => format!("Q-learning, π plan (ε={})", eps(row.epsilon.unwrap_or(1.0))),
        "q-learning-epsilon-decay" => format!(
            "Q-learning (ε-decay {}→{})",
            eps(row.epsilon.unwrap_or(1.0)),
            eps(row.epsilon_final.unwrap_or(0.1))
        ),
        "model-free-dijkstra" => "Model-free Dijkstra".into(),
        "model-free-async-vi" => "Model-free asynchronous VI".into(),
        "model-free-vi" => "Model-free synchronous VI".into(),
        other => other.into(),
    }
}

/// The table cells of a row (shared by text and Markdown).
fn cells(row: &RowSummary) -> Vec<String> {
    if let Some(note) = &row.note {
        let mut c = vec![label(row), note.clone()];
        c.resize(HEADER.len(), String::new());
        return c;
    }
    let paths = match (row.shortest_path, row.longest_path) {
        (Some(a), Some(b)) if a == b => a.to_string(),
        (Some(a), Some(b)) => format!("{a}–{b}"),
        _ => "–".into(),
    };
    vec![
        label(row),
        pm(row.mean_time_s, row.std_time_s, 5),
        pm(row.mean_actions, row.std_actions, 1),
        opt(row.mean_ns_per_action, 1),
        pm(row.mean_iterations, row.std_iterations, 2),
        row.convergence_rate
            .map_or("–".into(), |r| format!("{:.1} %", 100.0 * r)),
        format!(
            "{} / {}",
            opt(row.mean_actions_goal_discovered, 1),
            opt(row.mean_time_goal_discovered_s, 5)
        ),
        format!(
            "{} / {}",
            opt(row.mean_actions_initial_optimal, 1),
            opt(row.mean_time_initial_optimal_s, 5)
        ),
        paths,
        format!(
            "{}{}",
            row.optimal_path_rate
                .map_or("–".into(), |r| format!("{:.0} %", 100.0 * r)),
            if row.loops > 0 {
                format!(", {} loops", row.loops)
            } else {
                String::new()
            }
        ),
    ]
}

const HEADER: [&str; 10] = [
    "algorithm",
    "run time s (mean ± std)",
    "actions (mean ± std)",
    "ns/action",
    "iterations (mean ± std)",
    "converged",
    "goal discovered: actions / s",
    "V(x1) optimal: actions / s",
    "path states",
    "optimal paths",
];

fn preamble(report: &Report) -> Vec<String> {
    vec![
        format!(
            "truecost reproduce deterministic — mode {}; seed {}; {} samples per row; {} episodes × {} steps; problems {}",
            match report.mode {
                Mode::Exact => "exact",
                Mode::Reference => "reference",
            },
            report.seed,
            report.samples,
            report.episodes,
            report.max_steps,
            report
                .problems
                .iter()
                .map(|p| p.to_string())
                .collect::<Vec<_>>()
                .join(",")
        ),
        format!("model: {}", report.model),
        "Q-learning: ρ = 1, Q₀ = 0, greedy = first minimiser in action order; means of actions \
         and times to an event are over the samples that reached it; path states count x1 and \
         the goal; π rows share one digit stream, problems in the order listed."
            .into(),
    ]
}

fn markdown(report: &Report) -> String {
    let mut s = String::new();
    let pre = preamble(report);
    let _ = writeln!(s, "# {}\n", pre[0]);
    for line in &pre[1..] {
        let _ = writeln!(s, "{line}\n");
    }
    for p in &report.problems {
        let _ = writeln!(s, "## Problem {p}\n");
        let _ = writeln!(s, "| {} |", HEADER.join(" | "));
        let _ = writeln!(s, "|{}", "---|".repeat(HEADER.len()));
        for row in report.rows.iter().filter(|r| r.problem == *p) {
            let _ = writeln!(s, "| {} |", cells(row).join(" | "));
        }
        s.push('\n');
        s += &comparison_table(
            report
                .rows
                .iter()
                .filter(|r| r.problem == *p)
                .map(|r| (label(r), r.comparison.as_ref())),
            true,
        );
    }
    s + &summary_text(report.against_published.as_ref(), true)
}

fn text(report: &Report) -> String {
    let mut s = String::new();
    for line in preamble(report) {
        let _ = writeln!(s, "{line}");
    }
    for p in &report.problems {
        let summaries: Vec<&RowSummary> = report.rows.iter().filter(|r| r.problem == *p).collect();
        let rows: Vec<Vec<String>> = summaries.iter().map(|r| cells(r)).collect();
        // Rows that were not run carry a note; it does not widen the columns.
        let measured = || {
            rows.iter()
                .zip(&summaries)
                .filter(|(_, s)| s.note.is_none())
                .map(|(r, _)| r)
        };
        let widths = column_widths(&HEADER, measured());
        let line = |cells: &[String]| aligned(cells, &widths);
        let _ = writeln!(s, "\nProblem {p}");
        let header: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
        let _ = writeln!(s, "{}", line(&header));
        for (r, summary) in rows.iter().zip(&summaries) {
            match &summary.note {
                None => {
                    let _ = writeln!(s, "{}", line(r));
                }
                Some(note) => {
                    let pad = widths[0].saturating_sub(r[0].chars().count());
                    let _ = writeln!(s, "{}{}  {note}", r[0], " ".repeat(pad));
                }
            }
        }
        s += &comparison_table(
            summaries.iter().map(|r| (label(r), r.comparison.as_ref())),
            false,
        );
    }
    s + &summary_text(report.against_published.as_ref(), false)
}

/// The width of each column: its widest cell among `header` and `rows`.
fn column_widths<'a>(
    header: &[&str],
    rows: impl Iterator<Item = &'a Vec<String>> + Clone,
) -> Vec<usize> {
    (0..header.len())
        .map(|c| {
            rows.clone()
                .map(|r| r[c].chars().count())
                .chain([header[c].chars().count()])
                .max()
                .unwrap_or(0)
        })
        .collect()
}

/// One line of an aligned text table: cells padded to `widths`, two spaces apart.
fn aligned(cells: &[String], widths: &[usize]) -> String {
    cells
        .iter()
        .zip(widths)
        .map(|(c, &w)| format!("{c}{}", " ".repeat(w.saturating_sub(c.chars().count()))))
        .collect::<Vec<_>>()
        .join("  ")
        .trim_end()
        .to_string()
}

/// JSON: the rows; with `--against-published` an object `{"rows": […], "against_published":
/// {counts, differs_lines, sources}}`.
fn json<T: serde::Serialize>(rows: &[T], summary: Option<&Summary>) -> String {
    let mut s = match summary {
        None => serde_json::to_string_pretty(rows),
        Some(summary) => serde_json::to_string_pretty(&serde_json::json!({
            "rows": rows,
            "against_published": summary,
        })),
    }
    .expect("serialisable");
    s.push('\n');
    s
}

/// Every metric compared in any row, sorted.
fn comparison_metrics<'a>(rows: impl Iterator<Item = Option<&'a Comparison>>) -> Vec<String> {
    let set: std::collections::BTreeSet<&String> =
        rows.flatten().flat_map(|c| c.agreement.keys()).collect();
    set.into_iter().cloned().collect()
}

/// `,published_M,agreement_M` for each metric.
fn comparison_csv_header(metrics: &[String]) -> String {
    metrics
        .iter()
        .map(|m| format!(",published_{m},agreement_{m}"))
        .collect()
}

/// The published value (as published) and the verdict of each metric (empty when none).
fn comparison_csv_cells(c: Option<&Comparison>, metrics: &[String]) -> String {
    metrics
        .iter()
        .map(|m| {
            let published = c
                .and_then(|c| c.published_text.get(m))
                .cloned()
                .unwrap_or_default();
            let verdict = c
                .and_then(|c| c.agreement.get(m))
                .map_or(String::new(), Verdict::to_string);
            format!(",{},{}", quote(&published), quote(&verdict))
        })
        .collect()
}

/// The summary as trailing `# ` lines of a CSV file (with `--against-published` only).
fn summary_csv(summary: Option<&Summary>) -> String {
    summary.map_or(String::new(), |s| {
        s.lines().iter().map(|l| format!("# {l}\n")).collect()
    })
}

const COMPARISON_HEADER: [&str; 5] = ["row", "metric", "published", "ours", "verdict"];

/// The published numbers beside ours, one line per (row, metric); empty without comparisons.
fn comparison_table<'a>(
    rows: impl Iterator<Item = (String, Option<&'a Comparison>)>,
    markdown: bool,
) -> String {
    let mut cells: Vec<Vec<String>> = Vec::new();
    for (label, c) in rows {
        let Some(c) = c else { continue };
        for (metric, verdict) in &c.agreement {
            cells.push(vec![
                label.clone(),
                metric.clone(),
                c.published_text.get(metric).cloned().unwrap_or_default(),
                c.ours
                    .get(metric)
                    .copied()
                    .flatten()
                    .map_or("–".into(), |o| format!("{o}")),
                verdict.to_string(),
            ]);
        }
    }
    if cells.is_empty() {
        return String::new();
    }
    let mut s = String::new();
    if markdown {
        let _ = writeln!(s, "Against published:\n");
        let _ = writeln!(s, "| {} |", COMPARISON_HEADER.join(" | "));
        let _ = writeln!(s, "|{}", "---|".repeat(COMPARISON_HEADER.len()));
        for c in &cells {
            let _ = writeln!(s, "| {} |", c.join(" | "));
        }
        s.push('\n');
    } else {
        let widths = column_widths(&COMPARISON_HEADER, cells.iter());
        let _ = writeln!(s, "Against published:");
        let header: Vec<String> = COMPARISON_HEADER.iter().map(|h| h.to_string()).collect();
        let _ = writeln!(s, "{}", aligned(&header, &widths));
        for c in &cells {
            let _ = writeln!(s, "{}", aligned(c, &widths));
        }
    }
    s
}

/// The closing summary and the sources (with `--against-published` only).
fn summary_text(summary: Option<&Summary>, markdown: bool) -> String {
    let Some(summary) = summary else {
        return String::new();
    };
    let mut s = String::new();
    let lines = summary.lines();
    if markdown {
        let _ = writeln!(s, "## Reproduction summary\n");
        let _ = writeln!(s, "{}\n", lines[0]);
        for l in &lines[1..] {
            let _ = writeln!(s, "- {l}");
        }
        if lines.len() > 1 {
            s.push('\n');
        }
    } else {
        let _ = writeln!(s, "\nReproduction summary");
        for l in &lines {
            let _ = writeln!(s, "{l}");
        }
    }
    let files = summary.sources.len();
    let commits: std::collections::BTreeSet<&str> =
        summary.sources.iter().map(|x| x.commit.as_str()).collect();
    let _ = writeln!(
        s,
        "{}Sources: {files} CSV files of the paper's repository at commits {} (data/published/sources.csv names each file, commit and machine).",
        if markdown { "\n" } else { "" },
        commits.into_iter().map(|c| &c[..c.len().min(12)]).collect::<Vec<_>>().join(", ")
    );
    s
}

//! `truecost solve` in the stochastic model (docs/spec.md §3, §7): `--gamma`, `--noise`,
//! `--algorithm exact`, and stochastic `vi` / `async-vi`. Every output names the noise model.

use std::fmt::Write;

use std::io::IsTerminal;

use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use serde_json::{json, Value};

use super::{ReportFormat, SolveArgs};
use truecost::certificate::CertifiedObjective;
use truecost::model::Decision;
use truecost::planning::{Algorithm, Mode};
use truecost::problems::StepCost;
use truecost::stochastic::file::ProblemFile;
use truecost::stochastic::grid::{exact_grid, exact_twin, reference_grid};
use truecost::stochastic::policy_iteration::{
    memory_estimate, optimum_with, Distance, Optimum, Progress,
};
use truecost::stochastic::problem::Provenance;
use truecost::stochastic::scale::{format_bytes, parse_size, DEFAULT_MAX_MEMORY};
use truecost::stochastic::value_iteration::{
    value_iteration_exact, value_iteration_f64, FloatModel, Schedule, ViOptions, ViRun,
};
use truecost::stochastic::{decimal, NoiseModel, Predictability, StochasticProblem};
use truecost::value::{integer_text, parse_rational, CostValue, Extended, Rational};

/// The planners `solve` accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SolveAlgorithm {
    /// Dijkstra's algorithm (deterministic model).
    Dijkstra,
    /// Synchronous value iteration (stochastic VI under --gamma).
    Vi,
    /// Asynchronous (Gauss–Seidel) value iteration (stochastic under --gamma).
    AsyncVi,
    /// The exact optimum of the stochastic model: policy iteration with exact rational linear
    /// solves (gamma = 1 unless --gamma is given).
    Exact,
}

/// The arithmetic of stochastic value iteration in exact mode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Arithmetic {
    /// Exact rationals.
    Exact,
    /// `f64` (the exact problem's numbers rounded).
    F64,
}

/// Options for large stochastic models.
#[derive(Args, Debug, Default)]
pub struct ScaleArgs {
    /// Memory budget of the exact optimum, e.g. 4G, 512M, 1.5G (K, M, G, T: powers of 1024;
    /// a bare number is bytes). The peak is estimated before any work and a larger estimate
    /// is refused [default: 4G].
    #[arg(long, value_name = "SIZE", allow_hyphen_values = true)]
    pub max_memory: Option<String>,
    /// No progress bar on stderr (it is also hidden when stderr is not a terminal).
    #[arg(long)]
    pub quiet: bool,
    /// Stochastic VI with --arithmetic f64: also compute the exact optimum G* and report the
    /// exact error of the stopped values (without it, f64 VI computes no exact value).
    #[arg(long)]
    pub exact_error: bool,
}

/// How a DRN file's goals and costs are read when its model names them otherwise than
/// truecost writes them (docs/guide/formats.md).
#[derive(Args, Debug, Default, Clone)]
pub struct DrnNameArgs {
    /// With --file of a DRN file: the label of the goal states [default: goal].
    #[arg(long, value_name = "LABEL")]
    pub goal_label: Option<String>,
    /// With --file of a DRN file: the reward model of the stage costs [default: cost, or the
    /// file's only reward model].
    #[arg(long, value_name = "MODEL")]
    pub cost_reward: Option<String>,
}

impl DrnNameArgs {
    /// The names as the DRN reader takes them; refused without `--file`.
    pub fn names(
        &self,
        file: Option<&std::path::Path>,
    ) -> Result<truecost::formats::drn::DrnNames, String> {
        let names = truecost::formats::drn::DrnNames {
            goal_label: self.goal_label.clone(),
            cost_reward: self.cost_reward.clone(),
        };
        if file.is_none() && !names.is_default() {
            return Err("--goal-label and --cost-reward apply to --file (a DRN file)".into());
        }
        Ok(names)
    }
}

/// Refuses the stochastic-only options in a deterministic run.
pub fn refuse_scale_options(scale: &ScaleArgs) -> Result<(), String> {
    if scale.max_memory.is_some() || scale.exact_error {
        return Err("--max-memory and --exact-error apply to the stochastic model (give --gamma, or a file with outcomes)".into());
    }
    Ok(())
}

/// The exact optimum with a progress bar (evaluations, lifting steps) on stderr, after the
/// memory estimate has been checked against the budget.
fn checked_optimum(
    problem: &StochasticProblem,
    budget: u64,
    all_values: bool,
    quiet: bool,
) -> Result<Optimum, String> {
    let estimate = memory_estimate(problem, all_values);
    if estimate.bytes > budget {
        return Err(format!(
            "the exact optimum needs an estimated {} of memory ({} unknowns, band width {}, up to {} lifting steps{}), above the budget --max-memory {}; raise --max-memory, or use --algorithm vi --arithmetic f64",
            format_bytes(estimate.bytes),
            estimate.unknowns,
            estimate.band_width,
            estimate.lifting_steps,
            if all_values { ", every exact value printed as JSON" } else { "" },
            format_bytes(budget),
        ));
    }
    let bar = progress_bar(
        quiet,
        "{spinner} {msg} [{bar:20}] {pos}/{len} lifting steps {elapsed}",
    );
    let mut exact = 0;
    let result = optimum_with(problem, &mut |event| match event {
        Progress::FloatEvaluation { round } => {
            bar.set_message(format!("f64 warm start, evaluation {round}"));
            bar.tick();
        }
        Progress::Refinement { policy, bits } => {
            bar.set_message(format!(
                "mixed-precision refinement, policy {policy} at {bits} bits"
            ));
            bar.tick();
        }
        Progress::ExactEvaluation { evaluation } => {
            exact = evaluation;
            bar.set_position(0);
            bar.set_message(format!("exact evaluation {evaluation}"));
        }
        Progress::Lifting(l) => {
            if l.steps == 1 || l.steps % 16 == 0 {
                bar.set_length(l.expected.max(l.steps) as u64);
                bar.set_position(l.steps as u64);
                bar.set_message(format!("exact evaluation {exact}"));
            }
        }
    });
    bar.finish_and_clear();
    result.map_err(|e| e.to_string())
}

/// A progress bar on stderr drawn by `template`, hidden with `--quiet` or when stderr is not a
/// terminal.
fn progress_bar(quiet: bool, template: &str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(1), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(template)
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar
}

/// Digits of the decimal expansions printed next to exact values.
const DIGITS: usize = 30;
/// Exact values longer than this are printed by digit counts in text output.
const SHORT: usize = 60;

/// The deterministic planner to run, or `None` when the stochastic model is asked for (any of
/// `--gamma`, `--noise`, `--tolerance`, `--max-sweeps`, `--arithmetic`, `--algorithm exact`, or
/// a problem file that lists outcomes). `file` is the problem file, already read.
pub fn deterministic_algorithm(args: &SolveArgs, file: Option<&ProblemFile>) -> Option<Algorithm> {
    if args.gamma.is_some()
        || args.noise.is_some()
        || args.tolerance.is_some()
        || args.max_sweeps.is_some()
        || args.arithmetic.is_some()
        || matches!(file, Some(ProblemFile::Stochastic(_)))
    {
        return None;
    }
    match args.algorithm {
        SolveAlgorithm::Dijkstra => Some(Algorithm::Dijkstra),
        SolveAlgorithm::Vi => Some(Algorithm::Vi),
        SolveAlgorithm::AsyncVi => Some(Algorithm::AsyncVi),
        SolveAlgorithm::Exact => None,
    }
}

/// Writes the certificate of the exact optimum (`--certificate`): the deterministic `G*` when
/// the problem is deterministic (no `--gamma` below 1, no listed outcomes), truecost otherwise.
fn certify(
    args: &SolveArgs,
    problem: &StochasticProblem,
    opt: &Optimum,
    path: &std::path::Path,
) -> Result<(), String> {
    let objective = match problem.provenance() {
        Provenance::Noise { gamma, .. } if gamma.is_deterministic() => {
            CertifiedObjective::Deterministic
        }
        _ => CertifiedObjective::Truecost,
    };
    let record = super::certify::CertifiedSource {
        file: args.file.as_deref(),
        problem: args.problem,
        env: None,
        step: args.step_cost,
        gamma: args.gamma.as_deref(),
        noise: args.noise,
        names: args.drn.names(args.file.as_deref())?,
    }
    .record(|| truecost::objectives::Model::from_problem(problem.clone(), String::new()).mdp())?;
    super::certify::write_certificate_with(path, |out| {
        truecost::stochastic::certified::write_optimum_certificate(
            out, problem, opt, &objective, &record,
        )
    })
}

/// A problem ready to solve, with what to say about it.
struct Prepared {
    problem: StochasticProblem,
    source: String,
    /// `Some` in reference mode: the reference code's `f64` numbers.
    float: Option<FloatModel>,
    /// The problem whose exact optimum the run is measured against (itself, or the exact twin
    /// of a reference grid; `None` if there is none).
    twin: Option<StochasticProblem>,
}

/// Runs `solve` in the stochastic model; `file` is the problem file of `--file`, already read.
pub fn solve(args: &SolveArgs, file: Option<ProblemFile>) -> Result<String, String> {
    if args.model_free {
        return Err("--model-free applies to the deterministic model; the stochastic solvers run on the whole problem, as the paper's code does".into());
    }
    if args.noise.is_some() && args.gamma.is_none() {
        return Err(
            "--noise chooses how the probability 1 - gamma is spread: give --gamma too".into(),
        );
    }
    let gamma = match &args.gamma {
        Some(text) => Predictability::parse(text).map_err(|e| e.to_string())?,
        None => Predictability::one(),
    };
    let noise = args.noise.unwrap_or_default();
    let schedule = match args.algorithm {
        SolveAlgorithm::Dijkstra => {
            return Err("dijkstra solves the deterministic model; in the stochastic model use --algorithm exact, vi or async-vi".into())
        }
        SolveAlgorithm::Exact => None,
        SolveAlgorithm::Vi => Some(Schedule::Synchronous),
        SolveAlgorithm::AsyncVi => Some(Schedule::Asynchronous),
    };
    if schedule.is_none()
        && (args.tolerance.is_some() || args.max_sweeps.is_some() || args.arithmetic.is_some())
    {
        return Err(
            "--tolerance, --max-sweeps and --arithmetic apply to --algorithm vi and async-vi"
                .into(),
        );
    }
    let tolerance = match &args.tolerance {
        None => None,
        Some(t) => {
            let r = parse_rational(t).map_err(|e| format!("tolerance: {e}"))?;
            if r < Rational::from_integer(0.into()) {
                return Err(format!("tolerance must be >= 0, got {t}"));
            }
            Some(r)
        }
    };
    if args.max_sweeps == Some(0) {
        return Err("--max-sweeps must be at least 1".into());
    }
    let budget = match &args.scale.max_memory {
        Some(text) => parse_size(text).map_err(|e| e.to_string())?,
        None => DEFAULT_MAX_MEMORY,
    };
    if schedule.is_none() && args.scale.exact_error {
        return Err("--exact-error applies to --algorithm vi and async-vi (the exact optimum is exact already)".into());
    }
    let prepared = prepare(args, file, noise, &gamma)?;
    // f64 VI in exact mode measures nothing exactly unless asked (10⁴ states take
    // seconds in f64, the exact optimum much longer); the reference mode always compares with
    // its exact twin (the published comparison, 400 states).
    let wants_optimum = schedule.is_none()
        || prepared.float.is_some()
        || args.arithmetic != Some(Arithmetic::F64)
        || args.scale.exact_error;
    let all_values = schedule.is_none() && args.format == ReportFormat::Json;
    let opt = match (&prepared.twin, wants_optimum) {
        (Some(t), true) => Some(checked_optimum(t, budget, all_values, args.scale.quiet)?),
        _ => None,
    };
    if let (Some(path), None) = (&args.certificate, schedule) {
        certify(
            args,
            &prepared.problem,
            opt.as_ref().expect("exact mode has itself as twin"),
            path,
        )?;
    }
    let report = match schedule {
        None => {
            let opt = opt.as_ref().expect("exact mode has itself as twin");
            let report = exact_report(&prepared, opt);
            if all_values {
                // Every state's exact value: streamed into standard output (hundreds of
                // megabytes at 10⁴ states), nothing left for the caller to print.
                let mut out = std::io::BufWriter::with_capacity(1 << 20, std::io::stdout().lock());
                // Lowest terms and decimal text take seconds at 10⁴ states.
                let bar = progress_bar(
                    args.scale.quiet,
                    "{spinner} every exact value, in lowest terms and in decimal [{bar:20}] {pos}/{len} states {elapsed}",
                );
                bar.set_length(prepared.problem.states() as u64);
                if !bar.is_hidden() {
                    bar.enable_steady_tick(std::time::Duration::from_millis(200));
                }
                let written = write_json_with_values(&report, opt, &mut out, &mut || bar.inc(1))
                    .and_then(|()| std::io::Write::flush(&mut out));
                bar.finish_and_clear();
                return match written {
                    Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.to_string()),
                    _ => Ok(String::new()),
                };
            }
            report
        }
        Some(schedule) => vi_report(args, &prepared, opt.as_ref(), schedule, tolerance)?,
    };
    Ok(match args.format {
        ReportFormat::Json => {
            let mut s = serde_json::to_string_pretty(&report).expect("serialisable");
            s.push('\n');
            s
        }
        ReportFormat::Text => text(&report),
    })
}

fn prepare(
    args: &SolveArgs,
    file: Option<ProblemFile>,
    noise: NoiseModel,
    gamma: &Predictability,
) -> Result<Prepared, String> {
    let noisy = |p: &truecost::model::Problem| {
        StochasticProblem::from_deterministic(p, noise, gamma).map_err(|e| e.to_string())
    };
    match (file, args.problem, args.mode) {
        (Some(file), _, _) => {
            let path = args.file.as_deref().expect("a file was read");
            let problem = match file {
                ProblemFile::Deterministic(p) => noisy(&p)?,
                ProblemFile::Stochastic(s) => {
                    if args.gamma.is_some() {
                        return Err("this problem file lists its own outcome probabilities; --gamma and --noise apply to deterministic problems".into());
                    }
                    *s
                }
            };
            Ok(Prepared {
                twin: Some(problem.clone()),
                problem,
                source: format!("file {}", truecost::echo::echo(&path.display().to_string())),
                float: None,
            })
        }
        (None, Some(id), Mode::Exact) => {
            let step = args.step_cost.unwrap_or_default();
            let problem = exact_grid(id, step, noise, gamma).map_err(|e| e.to_string())?;
            let step = match step {
                StepCost::Unit => "unit step costs",
                StepCost::Euclidean => "Euclidean step costs 800/19",
            };
            Ok(Prepared {
                twin: Some(problem.clone()),
                problem,
                source: format!("paper problem {id} (paper text, {step})"),
                float: None,
            })
        }
        (None, Some(id), Mode::Reference) => {
            if args.step_cost.is_some() {
                return Err("--step-cost applies to --mode exact; the reference mode always uses the paper code's f64 Euclidean costs".into());
            }
            if args.algorithm == SolveAlgorithm::Exact {
                return Err("--algorithm exact computes the exact optimum of the paper's text; for the exact counterpart of the paper's code use --mode exact --step-cost euclidean --noise reference".into());
            }
            if args.arithmetic == Some(Arithmetic::Exact) {
                return Err("--mode reference runs the paper's code in f64; --arithmetic exact applies to --mode exact".into());
            }
            let grid = reference_grid(id, noise, gamma).map_err(|e| e.to_string())?;
            let twin = exact_twin(id, noise, gamma).map_err(|e| e.to_string())?;
            Ok(Prepared {
                problem: grid.problem,
                source: format!("paper problem {id} (reference code: f64 Euclidean costs)"),
                float: Some(grid.float),
                twin,
            })
        }
        (None, None, _) => Err("give --problem N or --file FILE".into()),
    }
}

/// Everything `solve` reports in the stochastic model.
#[derive(Serialize)]
struct Report {
    problem: String,
    model: String,
    mode: Mode,
    noise: &'static str,
    noise_description: &'static str,
    gamma: Option<String>,
    algorithm: &'static str,
    value_type: &'static str,
    reachable: bool,
    cost_to_go_initial: Value,
    cost_to_go_initial_decimal: String,
    optimum: Option<OptimumSummary>,
    value_iteration: Option<ViSummary>,
    iterations: u64,
    cost_to_go: Vec<String>,
    policy: Vec<Option<usize>>,
    policy_action: Vec<Option<usize>>,
}

#[derive(Serialize)]
struct OptimumSummary {
    cost_to_go_initial: String,
    decimal: String,
    numerator_digits: usize,
    denominator_digits: usize,
    measured_on: &'static str,
    initial_policy: &'static str,
    float_iterations: usize,
    refinement_rounds: usize,
    refinement_bits: u64,
    exact_iterations: usize,
    lifting_steps: usize,
    unknowns: usize,
    finite_states: usize,
}

#[derive(Serialize)]
struct ViSummary {
    schedule: &'static str,
    arithmetic: &'static str,
    initial_values: &'static str,
    update_rule: &'static str,
    swept_states: &'static str,
    tolerance: String,
    max_sweeps: u64,
    sweeps: u64,
    converged: bool,
    last_change: String,
    backups: u64,
    outcome_terms: u64,
    counted_actions: u64,
    error_initial: Option<String>,
    max_error: Option<String>,
    worst_state: Option<usize>,
    suboptimal_policy_states: Option<usize>,
}

fn noise_fields(problem: &StochasticProblem) -> (&'static str, &'static str, Option<String>) {
    match problem.provenance() {
        Provenance::Noise { model, gamma } => {
            (model.name(), model.describe(), Some(gamma.to_string()))
        }
        Provenance::Explicit => (
            "explicit",
            "explicit (outcome probabilities given by the problem file)",
            None,
        ),
    }
}

fn digits(r: &Extended) -> (usize, usize) {
    match r {
        Extended::Finite(r) => (
            integer_text(r.numer()).trim_start_matches('-').len(),
            integer_text(r.denom()).len(),
        ),
        Extended::Infinite => (0, 0),
    }
}

fn optimum_summary(
    problem: &StochasticProblem,
    opt: &Optimum,
    measured_on: &'static str,
) -> OptimumSummary {
    let g = opt.cost_to_go(problem.initial());
    let (nd, dd) = digits(&g);
    OptimumSummary {
        cost_to_go_initial: g.to_string(),
        decimal: decimal(&g, DIGITS),
        numerator_digits: nd,
        denominator_digits: dd,
        measured_on,
        initial_policy: opt.stats.initial_policy,
        float_iterations: opt.stats.float_iterations,
        refinement_rounds: opt.stats.refinement_rounds,
        refinement_bits: opt.stats.refinement_bits,
        exact_iterations: opt.stats.exact_iterations,
        lifting_steps: opt.stats.lifting_steps,
        unknowns: opt.stats.unknowns,
        finite_states: opt.stats.finite_states,
    }
}

/// The policy as commanded successors (a goal names itself) and as action indices.
fn policy_columns(
    problem: &StochasticProblem,
    policy: &[Option<Decision>],
) -> (Vec<Option<usize>>, Vec<Option<usize>>) {
    policy
        .iter()
        .enumerate()
        .map(|(x, d)| match d {
            Some(Decision::Terminate) => (Some(x), None),
            Some(Decision::Move(i)) => (problem.commanded(problem.actions(x).start + i), Some(*i)),
            None => (None, None),
        })
        .unzip()
}

/// The report of `--algorithm exact`, without every state's exact value (reducing and printing
/// 10⁴ fractions of 10⁴ digits each is the bulk of a large run: [`write_json_with_values`]
/// streams them into the JSON output).
fn exact_report(prepared: &Prepared, opt: &Optimum) -> Report {
    let problem = &prepared.problem;
    let (noise, noise_description, gamma) = noise_fields(problem);
    let g = opt.cost_to_go(problem.initial());
    let (policy, policy_action) = policy_columns(problem, &opt.policy());
    Report {
        problem: prepared.source.clone(),
        model: "stochastic, exact (paper text)".into(),
        mode: Mode::Exact,
        noise,
        noise_description,
        gamma,
        algorithm: "exact",
        value_type: "big-rational",
        reachable: g.is_finite(),
        cost_to_go_initial: json!(g.to_string()),
        cost_to_go_initial_decimal: decimal(&g, DIGITS),
        optimum: Some(optimum_summary(problem, opt, "this problem")),
        value_iteration: None,
        iterations: opt.stats.exact_iterations as u64,
        cost_to_go: Vec::new(),
        policy,
        policy_action,
    }
}

/// `report` as JSON (`serde_json`'s pretty form, then a newline) with its `cost_to_go` array
/// holding every state's exact `G*` ([`Optimum::for_each_cost_to_go_text`]), written into `out`
/// as the values are printed (`written` called after each): the same bytes as the report with
/// those texts in `cost_to_go`, without holding them all (717 MB on a random 100×100 grid at
/// γ = 0.999).
fn write_json_with_values(
    report: &Report,
    opt: &Optimum,
    out: &mut impl std::io::Write,
    written: &mut dyn FnMut(),
) -> std::io::Result<()> {
    debug_assert!(report.cost_to_go.is_empty());
    let text = serde_json::to_string_pretty(report).expect("serialisable");
    // The array is a top-level field, indented by two spaces; its elements by four.
    let key = "\n  \"cost_to_go\": ";
    let at = text.find(key).expect("the report has a cost_to_go field") + key.len();
    let rest = text[at..]
        .strip_prefix("[]")
        .expect("cost_to_go is empty in the report");
    out.write_all(&text.as_bytes()[..at])?;
    let mut first = true;
    opt.for_each_cost_to_go_text(&mut |pieces| {
        out.write_all(if first { b"[\n    \"" } else { b",\n    \"" })?;
        first = false;
        for piece in pieces {
            // Digits, `-`, `/` and `inf`: nothing to escape in a JSON string.
            debug_assert!(piece
                .bytes()
                .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'/'));
            out.write_all(piece.as_bytes())?;
        }
        written();
        out.write_all(b"\"")
    })?;
    out.write_all(if first { b"[]" } else { b"\n  ]" })?;
    out.write_all(rest.as_bytes())?;
    out.write_all(b"\n")
}

fn vi_report(
    args: &SolveArgs,
    prepared: &Prepared,
    opt: Option<&Optimum>,
    schedule: Schedule,
    tolerance: Option<Rational>,
) -> Result<Report, String> {
    let problem = &prepared.problem;
    let (noise, noise_description, gamma) = noise_fields(problem);
    let reference = prepared.float.is_some();
    let mut options = if reference {
        ViOptions::reference(schedule)
    } else {
        ViOptions::from_below(schedule, Rational::new(1.into(), 10.into()), 1000)
            .map_err(|e| e.to_string())?
    };
    if let Some(t) = tolerance {
        options.tolerance = t;
    }
    if let Some(m) = args.max_sweeps {
        options.max_sweeps = m;
    }
    let arithmetic = if reference {
        Arithmetic::F64
    } else {
        args.arithmetic.unwrap_or(Arithmetic::Exact)
    };
    // Values as exact rationals (f64 converted exactly) for the comparison with G*.
    let (values_text, initial_value, initial_decimal, exact_values, run_meta, policy) =
        match arithmetic {
            Arithmetic::Exact => {
                let run = value_iteration_exact(problem, &options);
                let g = run.cost_to_go[problem.initial()].clone();
                let exact: Vec<Option<Rational>> =
                    run.cost_to_go.iter().map(|v| v.finite().cloned()).collect();
                let meta = meta(&run, decimal(&run.last_change, 6));
                (
                    run.cost_to_go
                        .iter()
                        .map(|v| v.to_string())
                        .collect::<Vec<_>>(),
                    json!(g.to_string()),
                    decimal(&g, DIGITS),
                    exact,
                    meta,
                    run.policy,
                )
            }
            Arithmetic::F64 => {
                let float = prepared
                    .float
                    .clone()
                    .unwrap_or_else(|| FloatModel::nearest(problem));
                let run = value_iteration_f64(problem, &float, &options);
                let g = run.cost_to_go[problem.initial()];
                let exact: Vec<Option<Rational>> = run
                    .cost_to_go
                    .iter()
                    .map(|&v| {
                        if v.is_finite() {
                            Rational::from_float(v)
                        } else {
                            None
                        }
                    })
                    .collect();
                let meta = meta(&run, format!("{:?}", run.last_change));
                (
                    run.cost_to_go
                        .iter()
                        .map(|v| render_f64(*v))
                        .collect::<Vec<_>>(),
                    // An f64 value is a JSON number; null where infinite (JSON has no inf).
                    json!(Some(g).filter(|g| g.is_finite())),
                    render_f64(g),
                    exact,
                    meta,
                    run.policy,
                )
            }
        };
    let (distance, suboptimal) = match (opt, &prepared.twin) {
        (Some(opt), Some(twin)) => {
            let d: Distance = opt.distance(problem.initial(), |x| exact_values[x].clone());
            // Map the greedy policy to the twin's actions by commanded successor (the action
            // orders differ between the reference and exact layouts on the pruned problems).
            let mapped: Vec<Option<usize>> = policy
                .iter()
                .enumerate()
                .map(|(x, d)| match d {
                    Some(Decision::Move(i)) => {
                        let a = problem.actions(x).start + i;
                        match problem.commanded(a) {
                            Some(y) => twin.actions(x).find(|&b| twin.commanded(b) == Some(y)),
                            None => Some(twin.actions(x).start + i),
                        }
                    }
                    _ => None,
                })
                .collect();
            (Some(d), Some(opt.suboptimal_states(twin, &mapped).len()))
        }
        _ => (None, None),
    };
    let reachable = match opt {
        Some(o) => o.cost_to_go(problem.initial()).is_finite(),
        None => exact_values[problem.initial()].is_some(),
    };
    let (policy_succ, policy_action) = policy_columns(problem, &policy);
    let (sweeps, converged, last_change, backups, terms, counted) = run_meta;
    let summary = ViSummary {
        schedule: if schedule == Schedule::Synchronous {
            "synchronous"
        } else {
            "asynchronous"
        },
        arithmetic: if arithmetic == Arithmetic::Exact {
            "exact"
        } else {
            "f64"
        },
        initial_values: if reference { "1e30 (goals 0)" } else { "0" },
        update_rule: if reference {
            "replace only if strictly smaller"
        } else {
            "assign"
        },
        swept_states: if reference {
            "every state with a move, goals included (the full graph)"
        } else {
            "states with finite G* (others are inf)"
        },
        tolerance: Extended::Finite(options.tolerance.clone()).to_string(),
        max_sweeps: options.max_sweeps,
        sweeps,
        converged,
        last_change,
        backups,
        outcome_terms: terms,
        counted_actions: counted,
        error_initial: distance
            .as_ref()
            .and_then(|d| d.initial.clone())
            .map(|e| decimal(&Extended::Finite(e), 6)),
        max_error: distance
            .as_ref()
            .map(|d| decimal(&Extended::Finite(d.max_abs.clone()), 6)),
        worst_state: distance.as_ref().and_then(|d| d.worst_state),
        suboptimal_policy_states: suboptimal,
    };
    let measured_on = if reference {
        "exact twin: exact geometry, step cost 800/19, same noise model and gamma"
    } else {
        "this problem"
    };
    Ok(Report {
        problem: prepared.source.clone(),
        model: if reference {
            "stochastic, reference (paper code, f64)".into()
        } else {
            "stochastic, exact (paper text)".into()
        },
        mode: if reference {
            Mode::Reference
        } else {
            Mode::Exact
        },
        noise,
        noise_description,
        gamma,
        algorithm: if schedule == Schedule::Synchronous {
            "vi"
        } else {
            "async-vi"
        },
        value_type: if arithmetic == Arithmetic::Exact {
            "big-rational"
        } else {
            "f64"
        },
        reachable,
        cost_to_go_initial: initial_value,
        cost_to_go_initial_decimal: initial_decimal,
        optimum: match (opt, &prepared.twin) {
            (Some(o), Some(t)) => Some(optimum_summary(t, o, measured_on)),
            _ => None,
        },
        value_iteration: Some(summary),
        iterations: sweeps,
        cost_to_go: values_text,
        policy: policy_succ,
        policy_action,
    })
}

type Meta = (u64, bool, String, u64, u64, u64);

fn meta<V>(run: &ViRun<V>, last_change: String) -> Meta {
    (
        run.sweeps,
        run.converged,
        last_change,
        run.backups,
        run.outcome_terms,
        run.reference_counted,
    )
}

fn render_f64(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else {
        "inf".into()
    }
}

fn text(r: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "problem      {}", r.problem);
    let gamma = r
        .gamma
        .as_ref()
        .map(|g| format!(", gamma {g}"))
        .unwrap_or_default();
    let _ = writeln!(
        s,
        "model        {}; noise {}{gamma}",
        r.model, r.noise_description
    );
    match &r.value_iteration {
        None => {
            let _ = writeln!(
                s,
                "planner      exact optimum: policy iteration with exact rational linear solves"
            );
        }
        Some(v) => {
            let _ = writeln!(
                s,
                "planner      {} stochastic value iteration ({}), {} arithmetic",
                r.algorithm, v.schedule, v.arithmetic
            );
            let _ = writeln!(
                s,
                "start        {}; update: {}; swept: {}",
                v.initial_values, v.update_rule, v.swept_states
            );
            let stop = if v.converged {
                "tolerance met"
            } else {
                "sweep limit reached"
            };
            let _ = writeln!(s, "stopping     largest change <= {} or {} sweeps: stopped after {} sweeps ({stop}; last change {})", v.tolerance, v.max_sweeps, v.sweeps, v.last_change);
        }
    }
    let value_type = match r.value_type {
        "big-rational" => "exact (big rationals)",
        _ => "f64 (not exact)",
    };
    let _ = writeln!(s, "values       {value_type}");
    let label = if r.value_iteration.is_some() {
        "G(x1)   "
    } else {
        "G*(x1)  "
    };
    if !r.reachable && r.value_iteration.is_none() {
        let _ = writeln!(
            s,
            "{label}     inf: no policy reaches a goal with probability 1 from the initial state"
        );
    } else {
        let exact = r
            .cost_to_go_initial
            .as_str()
            .map(str::to_string)
            .unwrap_or_else(|| match &r.cost_to_go_initial {
                Value::Null => "inf".to_string(),
                v => v.to_string(),
            });
        if r.value_type == "big-rational" && exact.len() > SHORT {
            let (n, d) = exact
                .split_once('/')
                .map_or((exact.len(), 1), |(n, d)| (n.len(), d.len()));
            let _ = writeln!(s, "{label}     {} (30 significant digits; exact value: a {n}-digit numerator over a {d}-digit denominator, printed by --format json)", r.cost_to_go_initial_decimal);
        } else if r.value_type == "big-rational" && exact.contains('/') {
            let _ = writeln!(s, "{label}     {exact} = {}", r.cost_to_go_initial_decimal);
        } else {
            let _ = writeln!(s, "{label}     {exact}");
        }
    }
    if let Some(o) = &r.optimum {
        if r.value_iteration.is_some() {
            let _ = writeln!(
                s,
                "G*(x1)       {} (exact optimum of {})",
                o.decimal, o.measured_on
            );
        }
        if r.value_iteration.is_none() {
            let _ = writeln!(
                s,
                "policy iter  initial policy: {}; {} f64 warm-start rounds, {} exact evaluations ({} Dixon lifting steps, {} unknowns)",
                o.initial_policy, o.float_iterations, o.exact_iterations, o.lifting_steps, o.unknowns
            );
        }
    }
    if let Some(v) = &r.value_iteration {
        if let (Some(e), Some(m)) = (&v.error_initial, &v.max_error) {
            let worst = v
                .worst_state
                .map(|w| format!(" (state {w})"))
                .unwrap_or_default();
            let _ = writeln!(
                s,
                "error        G(x1) - G*(x1) = {e}; max |G - G*| = {m}{worst}"
            );
        }
        if let Some(k) = v.suboptimal_policy_states {
            let verdict = if k == 0 {
                "optimal at every state".to_string()
            } else {
                format!("suboptimal at {k} states")
            };
            let _ = writeln!(
                s,
                "policy       greedy policy of the stopped values: {verdict}"
            );
        }
        let _ = writeln!(
            s,
            "actions      {} counted (reference rule: sum of deg*(deg-1) per sweep); {} backups; {} outcome terms",
            v.counted_actions, v.backups, v.outcome_terms
        );
    }
    s
}

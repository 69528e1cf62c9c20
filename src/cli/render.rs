//! `truecost render`: the paper's problem figure with an overlay, as SVG or PNG.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::echo::echo;
use truecost::experiments::visits::visit_counts;
use truecost::figures::canvas::Canvas;
use truecost::figures::policy::actions_overlay;
use truecost::figures::render::{draw, Overlay, Scene};
use truecost::figures::{file_scene, grid_scene, stochastic_file_scene};
use truecost::learning::plan::Probability;
use truecost::learning::q_learning::LearningValue;
use truecost::model::{ExactGraph, Graph};
use truecost::objectives::{Model, Objective};
use truecost::planning::{plan_exact, plan_reference, Algorithm, Mode, PlanReport};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::dijkstra;
use truecost::stochastic::file::ProblemFile;
use truecost::stochastic::policy_iteration::optimum;
use truecost::stochastic::problem::Provenance;
use truecost::stochastic::{decimal, NoiseModel, Predictability, StochasticProblem};
use truecost::value::{parse_rational, CostValue, Extended, Rational};

use super::env::{EnvArg, ObjectiveArgs};

/// What to draw over the problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OverlayKind {
    /// The bare problem.
    None,
    /// The optimal path from x1.
    Path,
    /// A cost-to-go heat map with a colour bar.
    Values,
    /// Policy arrows.
    Policy,
    /// How often each move was applied in a seeded derandomized Q-learning run (ρ = 1,
    /// Q₀ = 0, random exploration with --epsilon).
    Visits,
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file", "env"])))]
pub struct RenderArgs {
    #[command(flatten)]
    env: EnvArg,
    #[command(flatten)]
    objective: ObjectiveArgs,
    #[command(flatten)]
    slice: TaxiSliceArgs,
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    problem: Option<usize>,
    /// A problem file (states are drawn on a circle: files carry no geometry).
    #[arg(long, value_name = "FILE")]
    file: Option<PathBuf>,
    /// `exact` (paper text) or `reference` (paper code: its f64 coordinates and costs).
    #[arg(long, value_enum, default_value_t = Mode::Exact)]
    mode: Mode,
    /// Stage cost of a grid move in exact mode [default: unit].
    #[arg(long, value_enum)]
    step_cost: Option<StepCost>,
    /// The overlay.
    #[arg(long, value_enum, default_value_t = OverlayKind::None)]
    overlay: OverlayKind,
    /// Draw the exact optimum of the stochastic model with predictability gamma in (0, 1]
    /// (exact decimal text, e.g. 0.9) instead of the deterministic one: values, policy and path
    /// overlays (exact mode).
    #[arg(long, value_name = "G", allow_negative_numbers = true)]
    gamma: Option<String>,
    /// With --gamma: how the probability 1 - gamma is spread, `paper` (the text) or
    /// `reference` (the paper's code) [default: paper].
    #[arg(long, value_enum)]
    noise: Option<NoiseModel>,
    /// Width in pixels.
    #[arg(long, default_value_t = 900, allow_negative_numbers = true)]
    width: u32,
    /// Height in pixels.
    #[arg(long, default_value_t = 900, allow_negative_numbers = true)]
    height: u32,
    /// Visits overlay: exploration probability ε of the Q-learning run (exact decimal)
    /// [default: 0.9].
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    epsilon: Option<String>,
    /// Visits overlay: seed of the Q-learning run [default: 0].
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    seed: Option<u64>,
    /// Visits overlay: episodes of the Q-learning run [default: 1000].
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    episodes: Option<u32>,
    /// Visits overlay: steps per episode [default: 3000].
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    max_steps: Option<u32>,
    /// Output file; the format follows its extension (.svg or .png).
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    out: PathBuf,
}

/// The settings of the Q-learning run behind `--overlay visits`, checked before any work.
struct VisitsRun {
    epsilon: Rational,
    seed: u64,
    episodes: u32,
    max_steps: u32,
}

impl VisitsRun {
    /// The run's settings (defaults filled in), or a refusal when they are given without
    /// `--overlay visits` or out of range.
    fn from_args(args: &RenderArgs) -> Result<Option<VisitsRun>, String> {
        let given = args.epsilon.is_some()
            || args.seed.is_some()
            || args.episodes.is_some()
            || args.max_steps.is_some();
        if args.overlay != OverlayKind::Visits {
            if given {
                return Err("--epsilon, --seed, --episodes and --max-steps set the Q-learning run of --overlay visits; they do not apply to other overlays".into());
            }
            return Ok(None);
        }
        let text = args.epsilon.as_deref().unwrap_or("0.9");
        let epsilon = parse_rational(text).map_err(|e| format!("--epsilon: {e}"))?;
        Probability::new("epsilon", &epsilon).map_err(|e| format!("--epsilon: {e}"))?;
        let run = VisitsRun {
            epsilon,
            seed: args.seed.unwrap_or(0),
            episodes: args.episodes.unwrap_or(1000),
            max_steps: args.max_steps.unwrap_or(3000),
        };
        if run.episodes == 0 || run.max_steps == 0 {
            return Err("--episodes and --max-steps must be at least 1".into());
        }
        Ok(Some(run))
    }
}

/// Checks the output before any work: a size the canvas accepts and a `.svg` or `.png` name
/// in an existing directory.
fn check_output(args: &RenderArgs) -> Result<(), String> {
    Canvas::new(args.width, args.height).map_err(|e| e.to_string())?;
    let ext = args
        .out
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("svg" | "png")) {
        return Err(format!(
            "cannot tell the figure format of '{}': the file name must end in .svg or .png",
            echo(&args.out.display().to_string())
        ));
    }
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        if !dir.is_dir() {
            return Err(format!(
                "cannot write figure {}: no directory {}",
                echo(&args.out.display().to_string()),
                echo(&dir.display().to_string())
            ));
        }
    }
    if args.out.is_dir() {
        return Err(format!(
            "cannot write figure {}: it is a directory",
            echo(&args.out.display().to_string())
        ));
    }
    // A read-only disk or a missing permission: found before the work, not after it.
    truecost::atomic::check_target(&args.out)
}

/// Runs the command; returns the message printed on success.
pub fn run(args: &RenderArgs) -> Result<String, String> {
    if let Some(spec) = &args.env.env {
        VisitsRun::from_args(args)?;
        check_output(args)?;
        if args.gamma.is_some()
            || args.noise.is_some()
            || args.step_cost.is_some()
            || args.mode != Mode::Exact
        {
            return Err("--gamma, --noise, --step-cost and --mode apply to --problem and --file; an environment has its own transitions and costs".into());
        }
        return render_env(
            spec,
            &args.objective,
            &args.slice,
            args.overlay,
            args.width,
            args.height,
            &args.out,
        );
    }
    if args.slice.passenger.is_some() || args.slice.destination.is_some() {
        return Err(
            "--passenger and --destination choose the Taxi slice to draw: they go with --env taxi"
                .into(),
        );
    }
    let visits_run = VisitsRun::from_args(args)?;
    check_output(args)?;
    if args.file.is_some() && args.mode == Mode::Reference {
        return Err("--mode reference applies to the paper's problems (--problem N) only".into());
    }
    if args.file.is_some() && args.step_cost.is_some() {
        return Err("--step-cost applies to the paper's grid problems (--problem N)".into());
    }
    // The file is read once, in either format (pipes and FIFOs can be read only once); the
    // figure's path, values and visits start from one initial state.
    let loaded = match &args.file {
        Some(path) => Some(super::read_single_initial(path, "render")?),
        None => None,
    };
    if args.gamma.is_some()
        || args.noise.is_some()
        || matches!(loaded, Some(ProblemFile::Stochastic(_)))
    {
        return stochastic(args, loaded);
    }
    let mut visits: Option<PairCounts> = None;
    // The exact problem (none in the reference mode) and what its states are called.
    let mut exact: Option<(truecost::model::Problem, &str)> = None;
    let (mut scene, report, what) = match (loaded, args.problem) {
        (Some(ProblemFile::Deterministic(problem)), _) => {
            let path = args.file.as_deref().expect("a file was read");
            let report = plan_exact(&problem, Algorithm::Dijkstra, false);
            visits = exact_visits(&problem, visits_run.as_ref())?;
            let scene = file_scene(&problem);
            exact = Some((problem, "state"));
            (
                scene,
                report,
                format!("file {}", echo(&path.display().to_string())),
            )
        }
        (Some(ProblemFile::Stochastic(_)), _) => unreachable!("drawn by stochastic() above"),
        (None, Some(id)) => match args.mode {
            Mode::Exact => {
                let layout = GridLayout::exact(id).map_err(|e| e.to_string())?;
                let step = args.step_cost.unwrap_or_default();
                let problem = layout.to_problem(step);
                let report = plan_exact(&problem, Algorithm::Dijkstra, false);
                visits = exact_visits(&problem, visits_run.as_ref())?;
                exact = Some((problem, "grid point"));
                (
                    grid_scene(&layout, Mode::Exact),
                    report,
                    format!(
                        "Problem {id}, exact model (paper text, {})",
                        step_text(step)
                    ),
                )
            }
            Mode::Reference => {
                if args.step_cost.is_some() {
                    return Err("--step-cost applies to --mode exact; the reference mode uses the paper code's f64 Euclidean costs".into());
                }
                let layout = GridLayout::reference(id).map_err(|e| e.to_string())?;
                let report =
                    plan_reference(&layout.to_reference_graph(), Algorithm::Dijkstra, false);
                (
                    grid_scene(&layout, Mode::Reference),
                    report,
                    format!("Problem {id}, reference model (paper code, f64)"),
                )
            }
        },
        (None, None) => return Err("give --problem N or --file FILE".into()),
    };
    scene.caption = caption(&report, args.overlay, exact.is_some());
    if let Some(run) = &visits_run {
        scene.caption = format!(
            "{} (ε = {}, seed {}, ρ = 1, Q0 = 0, up to {} episodes x {} steps, stops at convergence)",
            scene.caption,
            Extended::Finite(run.epsilon.clone()),
            run.seed,
            run.episodes,
            run.max_steps
        );
    }
    let overlay = match args.overlay {
        OverlayKind::None => Overlay::None,
        OverlayKind::Path => {
            if !report.reachable {
                return Err(
                    "no goal is reachable from the initial state: there is no path to draw".into(),
                );
            }
            Overlay::Path(report.path.clone())
        }
        OverlayKind::Values => Overlay::Values {
            values: report
                .cost_to_go
                .iter()
                .map(|v| v.as_deref().and_then(value_for_colour))
                .collect(),
            label: "G*".into(),
        },
        OverlayKind::Policy => match &exact {
            Some((problem, place)) => {
                let model =
                    Model::from_deterministic(problem, what.clone()).map_err(|e| e.to_string())?;
                let s = model
                    .solve(&Objective::Truecost)
                    .map_err(|e| e.to_string())?;
                let to = |a: usize| model.problem.outcomes(a)[0].successor;
                actions_overlay(&model, &s, to, place)
            }
            None => Overlay::Policy(report.policy.clone()),
        },
        OverlayKind::Visits => Overlay::Visits(visits.unwrap_or_default()),
    };
    scene.title = what;
    save(&scene, &overlay, args)
}

/// Draws and writes the figure; returns the success message.
fn save(scene: &Scene, overlay: &Overlay, args: &RenderArgs) -> Result<String, String> {
    let canvas = draw(scene, overlay, args.width, args.height).map_err(|e| e.to_string())?;
    canvas.save(&args.out).map_err(|e| e.to_string())?;
    Ok(format!(
        "wrote {} ({}x{})\n",
        args.out.display(),
        args.width,
        args.height
    ))
}

/// The figure of the stochastic model (docs/spec.md §3): its exact optimum by policy iteration.
fn stochastic(args: &RenderArgs, loaded: Option<ProblemFile>) -> Result<String, String> {
    if args.noise.is_some() && args.gamma.is_none() {
        return Err(
            "--noise chooses how the probability 1 - gamma is spread: give --gamma too".into(),
        );
    }
    if args.mode == Mode::Reference {
        return Err("the stochastic model (--gamma, or a file with outcomes) is drawn from its exact optimum: use --mode exact (with --step-cost euclidean --noise reference for the exact counterpart of the paper's code)".into());
    }
    if args.overlay == OverlayKind::Visits {
        return Err("--overlay visits draws a deterministic Q-learning run; it does not take --gamma, --noise or a file with outcomes".into());
    }
    let gamma = match &args.gamma {
        Some(text) => Predictability::parse(text).map_err(|e| e.to_string())?,
        None => Predictability::one(),
    };
    let noise = args.noise.unwrap_or_default();
    let noisy = |p: &truecost::model::Problem| {
        StochasticProblem::from_deterministic(p, noise, &gamma).map_err(|e| e.to_string())
    };
    let (mut scene, problem, what) = match (loaded, args.problem) {
        (Some(loaded), _) => {
            let path = args.file.as_deref().expect("a file was read");
            let what = format!("file {}", echo(&path.display().to_string()));
            match loaded {
                ProblemFile::Deterministic(p) => (file_scene(&p), noisy(&p)?, what),
                ProblemFile::Stochastic(s) => {
                    if args.gamma.is_some() {
                        return Err("this problem file lists its own outcome probabilities; --gamma and --noise apply to deterministic problems".into());
                    }
                    (stochastic_file_scene(&s), *s, what)
                }
            }
        }
        (None, Some(id)) => {
            let layout = GridLayout::exact(id).map_err(|e| e.to_string())?;
            let step = args.step_cost.unwrap_or_default();
            let problem = noisy(&layout.to_problem(step))?;
            (
                grid_scene(&layout, Mode::Exact),
                problem,
                format!(
                    "Problem {id}, exact model (paper text, {})",
                    step_text(step)
                ),
            )
        }
        (None, None) => return Err("give --problem N or --file FILE".into()),
    };
    // One exact optimum: the objectives' solution where the policy overlay needs its optimal
    // actions, else policy iteration alone.
    let solved = match args.overlay {
        OverlayKind::Policy => {
            let model = Model::from_problem(problem.clone(), what.clone());
            let s = model
                .solve(&Objective::Truecost)
                .map_err(|e| e.to_string())?;
            Some((model, s))
        }
        _ => None,
    };
    let (values, policy) = match &solved {
        Some((_, s)) => (s.values.clone(), s.policy.clone()),
        None => {
            let optimum = optimum(&problem).map_err(|e| e.to_string())?;
            (
                optimum.cost_to_go_all().to_vec(),
                optimum.policy_actions().to_vec(),
            )
        }
    };
    let successor = |x: usize| {
        if problem.is_goal(x) {
            Some(x)
        } else {
            policy[x].map(|a| problem.intended(a))
        }
    };
    let model = match (problem.provenance(), &args.gamma) {
        (Provenance::Noise { model, .. }, Some(g)) => format!("{} noise, γ = {g}", model.name()),
        _ => "outcome probabilities from the file".to_string(),
    };
    let g = match &values[problem.initial()] {
        Extended::Infinite => "goal not reached with probability 1 from x1".to_string(),
        v => format!("G*(x1) = {}", decimal(v, 12)),
    };
    let (overlay, shown) = match args.overlay {
        OverlayKind::None => (Overlay::None, ""),
        OverlayKind::Values => (
            Overlay::Values {
                values: values
                    .iter()
                    .map(|v| Some(v.to_f64()).filter(|v| v.is_finite()))
                    .collect(),
                label: "G*".into(),
            },
            "; overlay: optimal expected cost-to-go G*",
        ),
        OverlayKind::Policy => {
            let (model, s) = solved.as_ref().expect("solved for the policy overlay");
            let place = if args.problem.is_some() {
                "grid point"
            } else {
                "state"
            };
            (
                actions_overlay(model, s, |a| problem.intended(a), place),
                "; overlay: every optimal action (arrow to the commanded or else the most likely successor; several arrows: tied actions)",
            )
        }
        OverlayKind::Path => (
            Overlay::Path(intended_path(&problem, &values[problem.initial()], successor)?),
            "; overlay: the optimal policy's intended path (every action reaching its commanded or else most likely successor)",
        ),
        OverlayKind::Visits => unreachable!("refused above"),
    };
    scene.title = what;
    scene.caption = format!(
        "{g} (stochastic model, {model}; exact optimum by policy iteration){shown}; grey segments: allowed moves"
    );
    save(&scene, &overlay, args)
}

/// From x1, the states the optimal policy visits when every move goes as commanded.
fn intended_path(
    problem: &StochasticProblem,
    initial_value: &Extended,
    successor: impl Fn(usize) -> Option<usize>,
) -> Result<Vec<usize>, String> {
    if matches!(initial_value, Extended::Infinite) {
        return Err(
            "no policy reaches a goal with probability 1 from the initial state: there is no path to draw".into(),
        );
    }
    let mut path = vec![problem.initial()];
    let mut x = problem.initial();
    while !problem.is_goal(x) {
        match successor(x) {
            Some(y) if path.len() <= problem.states() => {
                path.push(y);
                x = y;
            }
            _ => return Err("the optimal policy's commanded moves do not lead from x1 to a goal: there is no intended path to draw (try --overlay policy)".into()),
        }
    }
    Ok(path)
}

fn step_text(step: StepCost) -> &'static str {
    match step {
        StepCost::Unit => "unit step costs",
        StepCost::Euclidean => "step cost 800/19",
    }
}

/// The value as an `f64` for colouring only (the exact value is what `solve` reports).
fn value_for_colour(text: &str) -> Option<f64> {
    match text.parse::<Extended>() {
        Ok(e) => Some(e.to_f64()).filter(|v| v.is_finite()),
        Err(_) => text.parse::<f64>().ok().filter(|v| v.is_finite()),
    }
}

/// Visit counts per unordered move `{a, b}`.
type PairCounts = Vec<((usize, usize), u64)>;

/// Visit counts on the exact model (the narrowest exact representation), if asked for.
fn exact_visits(
    problem: &truecost::model::Problem,
    run: Option<&VisitsRun>,
) -> Result<Option<PairCounts>, String> {
    let Some(run) = run else {
        return Ok(None);
    };
    Ok(Some(match ExactGraph::new(problem) {
        ExactGraph::Units(g) => pair_counts(&g, learn_visits(&g, run)?),
        ExactGraph::Big(g) => pair_counts(&g, learn_visits(&g, run)?),
    }))
}

fn learn_visits<V: LearningValue>(
    graph: &Graph<V>,
    run: &VisitsRun,
) -> Result<Vec<Vec<u64>>, String> {
    let optimum = dijkstra::to_goals(graph).cost_to_go;
    visit_counts(
        graph,
        &optimum,
        &run.epsilon,
        run.seed,
        run.episodes,
        run.max_steps,
    )
    .map_err(|e| e.to_string())
}

/// Per-move counts summed over both directions of each unordered pair.
fn pair_counts<V: CostValue>(graph: &Graph<V>, counts: Vec<Vec<u64>>) -> PairCounts {
    let mut pairs: std::collections::BTreeMap<(usize, usize), u64> = Default::default();
    for (v, row) in counts.iter().enumerate() {
        for ((y, _), &c) in graph.edges(v).zip(row) {
            if y != v {
                let key = (
                    graph.origin(v).min(graph.origin(y)),
                    graph.origin(v).max(graph.origin(y)),
                );
                *pairs.entry(key).or_default() += c;
            }
        }
    }
    pairs.into_iter().collect()
}

/// The caption: `G*(x1)`, the planner, the overlay (`exact`: the policy overlay draws every
/// optimal move; the reference mode draws its one policy).
fn caption(report: &PlanReport, overlay: OverlayKind, exact: bool) -> String {
    let g = if report.reachable {
        format!("G*(x1) = {}", report.cost_to_go_initial)
    } else {
        "goal unreachable from x1".to_string()
    };
    let values = match report.value_type {
        "f64" => "f64 values",
        _ => "exact values",
    };
    let overlay = match overlay {
        OverlayKind::None => "",
        OverlayKind::Path => "; overlay: the optimal path",
        OverlayKind::Values => "; overlay: optimal cost-to-go G*",
        OverlayKind::Policy if exact => {
            "; overlay: every optimal move (exact; several arrows: tied moves)"
        }
        OverlayKind::Policy => "; overlay: the optimal policy",
        OverlayKind::Visits => "; overlay: move visits of one seeded Q-learning run",
    };
    format!(
        "{g} ({}, {values}){overlay}; grey segments: allowed moves",
        report.algorithm.name()
    )
}

/// Taxi's passenger place for `render --env taxi --passenger P`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PassengerPlace {
    /// Waiting at depot R (0, 0).
    R,
    /// Waiting at depot G (0, 4).
    G,
    /// Waiting at depot Y (4, 0).
    Y,
    /// Waiting at depot B (4, 3).
    B,
    /// In the taxi.
    Taxi,
}

/// Taxi's destination for `render --env taxi --destination D`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Depot {
    /// Depot R (0, 0).
    R,
    /// Depot G (0, 4).
    G,
    /// Depot Y (4, 0).
    Y,
    /// Depot B (4, 3).
    B,
}

/// `--passenger` and `--destination` of `render --env taxi`: which 25 of the 500 states.
#[derive(Args, Debug, Clone, Default)]
pub struct TaxiSliceArgs {
    /// With --env taxi: draw the 25 states (one per taxi cell) where the passenger is waiting
    /// at this depot (r, g, y, b) or is in the taxi (taxi); goes with --destination.
    #[arg(long, value_enum, ignore_case = true, value_name = "R|G|Y|B|TAXI")]
    pub passenger: Option<PassengerPlace>,
    /// With --env taxi: the destination depot of the slice drawn (r, g, y, b), marked as the
    /// goal; goes with --passenger.
    #[arg(long, value_enum, ignore_case = true, value_name = "R|G|Y|B")]
    pub destination: Option<Depot>,
}

/// `render --env SPEC [--objective O --alpha A] [--passenger P --destination D]
/// --overlay none|values|policy --out F`: the environment's map, with the optimum of the
/// objective as values or policy. Every option is checked before anything is solved.
fn render_env(
    spec: &str,
    objective: &ObjectiveArgs,
    slice: &TaxiSliceArgs,
    overlay: OverlayKind,
    width: u32,
    height: u32,
    out: &std::path::Path,
) -> Result<String, String> {
    use truecost::figures::envs::{
        policy_overlay, scene, taxi_actions_overlay, taxi_scene, taxi_value_overlay, value_overlay,
        TaxiSlice,
    };
    use truecost::figures::render::{draw, Overlay};
    let env = truecost::envs::EnvSpec::parse(spec)
        .and_then(|s| s.build())
        .map_err(|e| e.to_string())?;
    let slice = match (slice.passenger, slice.destination) {
        (None, None) => None,
        (Some(p), Some(d)) => Some(TaxiSlice::new(p as usize, d as usize)?),
        _ => {
            return Err(
                "--passenger and --destination go together: they choose the Taxi slice to draw"
                    .into(),
            )
        }
    };
    let is_taxi = env.layout == truecost::envs::Layout::Taxi;
    if slice.is_some() && !is_taxi {
        return Err(format!(
            "--passenger and --destination choose a slice of taxi; {} is drawn whole",
            env.spec
        ));
    }
    if !matches!(
        overlay,
        OverlayKind::None | OverlayKind::Values | OverlayKind::Policy
    ) {
        return Err("render --env draws --overlay none, values or policy".into());
    }
    if is_taxi && slice.is_none() && overlay != OverlayKind::None {
        return Err(truecost::figures::envs::NotDrawable.to_string());
    }
    let (name, objective) = objective.parse()?;
    let mut scene = if is_taxi {
        taxi_scene(&env, slice.as_ref())
    } else {
        scene(&env).map_err(|e| e.to_string())?
    };
    let overlay = match overlay {
        OverlayKind::None => Overlay::None,
        OverlayKind::Values | OverlayKind::Policy => {
            let model =
                truecost::objectives::Model::from_environment(&env).map_err(|e| e.to_string())?;
            let s = model.solve(&objective).map_err(|e| e.to_string())?;
            let p = |r: &truecost::value::Rational| {
                truecost::stochastic::decimal(&truecost::value::Extended::Finite(r.clone()), 6)
            };
            let success = if s.success.min == s.success.max {
                p(&s.success.min)
            } else {
                format!("{} to {}", p(&s.success.min), p(&s.success.max))
            };
            let over = match model.initial.len() {
                1 => String::new(),
                k => format!(" (expectation over the {k} initial states)"),
            };
            scene.caption = format!(
                "{}; {} objective, exact; initial value {}{over}; success probability {success}",
                scene.caption,
                name,
                truecost::stochastic::decimal(&s.value_initial, 6)
            );
            match (overlay, &slice) {
                (OverlayKind::Values, Some(slice)) => taxi_value_overlay(&s, slice),
                (OverlayKind::Values, None) => value_overlay(&s),
                (_, Some(slice)) => {
                    scene.caption.push_str("; marks: pick-up and drop-off");
                    let (overlay, marks) = taxi_actions_overlay(&model, &s, slice);
                    scene.marks.extend(marks);
                    overlay
                }
                (_, None) => policy_overlay(&env, &model, &s),
            }
        }
        _ => unreachable!("refused above"),
    };
    let canvas = draw(&scene, &overlay, width, height).map_err(|e| e.to_string())?;
    canvas.save(out).map_err(|e| e.to_string())?;
    Ok(format!("wrote {} ({width}x{height})\n", out.display()))
}

//! `truecost render`: the paper's problem figure with an overlay, as SVG or PNG.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::experiments::visits::visit_counts;
use truecost::figures::render::{draw, Overlay};
use truecost::figures::{file_scene, grid_scene};
use truecost::learning::q_learning::LearningValue;
use truecost::model::file;
use truecost::model::{ExactGraph, Graph};
use truecost::planning::{plan_exact, plan_reference, Algorithm, Mode, PlanReport};
use truecost::problems::{GridLayout, StepCost};
use truecost::solvers::dijkstra;
use truecost::value::{parse_rational, CostValue, Extended};

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
#[command(group(clap::ArgGroup::new("source").required(true).args(["problem", "file"])))]
pub struct RenderArgs {
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N")]
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
    /// Width in pixels.
    #[arg(long, default_value_t = 900)]
    width: u32,
    /// Height in pixels.
    #[arg(long, default_value_t = 900)]
    height: u32,
    /// Visits overlay: exploration probability ε of the Q-learning run (exact decimal).
    #[arg(long, default_value = "0.9", value_name = "E")]
    epsilon: String,
    /// Visits overlay: seed of the Q-learning run.
    #[arg(long, default_value_t = 0, value_name = "S")]
    seed: u64,
    /// Visits overlay: episodes of the Q-learning run.
    #[arg(long, default_value_t = 1000, value_name = "N")]
    episodes: u32,
    /// Visits overlay: steps per episode.
    #[arg(long, default_value_t = 3000, value_name = "N")]
    max_steps: u32,
    /// Output file; the format follows its extension (.svg or .png).
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    out: PathBuf,
}

/// Runs the command; returns the message printed on success.
pub fn run(args: &RenderArgs) -> Result<String, String> {
    let mut visits: Option<PairCounts> = None;
    let (mut scene, report, what) = match (&args.file, args.problem) {
        (Some(path), _) => {
            if args.mode == Mode::Reference {
                return Err(
                    "--mode reference applies to the paper's problems (--problem N) only".into(),
                );
            }
            if args.step_cost.is_some() {
                return Err(
                    "--step-cost applies to the paper's grid problems (--problem N)".into(),
                );
            }
            let problem = file::read(path).map_err(|e| e.to_string())?;
            let report = plan_exact(&problem, Algorithm::Dijkstra, false);
            (
                file_scene(&problem),
                report,
                format!("file {}", path.display()),
            )
        }
        (None, Some(id)) => match args.mode {
            Mode::Exact => {
                let layout = GridLayout::exact(id).map_err(|e| e.to_string())?;
                let step = args.step_cost.unwrap_or_default();
                let problem = layout.to_problem(step);
                let report = plan_exact(&problem, Algorithm::Dijkstra, false);
                visits = exact_visits(&problem, args)?;
                let step = match step {
                    StepCost::Unit => "unit step costs",
                    StepCost::Euclidean => "step cost 800/19",
                };
                (
                    grid_scene(&layout, Mode::Exact),
                    report,
                    format!("Problem {id}, exact model (paper text, {step})"),
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
    scene.title = what;
    scene.caption = caption(&report, args.overlay);
    if args.overlay == OverlayKind::Visits {
        scene.caption = format!(
            "{} (ε = {}, seed {}, ρ = 1, Q0 = 0, up to {} episodes x {} steps, stops at convergence)",
            scene.caption, args.epsilon, args.seed, args.episodes, args.max_steps
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
        OverlayKind::Policy => Overlay::Policy(report.policy.clone()),
        OverlayKind::Visits => Overlay::Visits(visits.unwrap_or_default()),
    };
    let canvas = draw(&scene, &overlay, args.width, args.height).map_err(|e| e.to_string())?;
    canvas.save(&args.out).map_err(|e| e.to_string())?;
    Ok(format!(
        "wrote {} ({}x{})\n",
        args.out.display(),
        args.width,
        args.height
    ))
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
    args: &RenderArgs,
) -> Result<Option<PairCounts>, String> {
    if args.overlay != OverlayKind::Visits {
        return Ok(None);
    }
    Ok(Some(match ExactGraph::new(problem) {
        ExactGraph::Units(g) => pair_counts(&g, learn_visits(&g, args)?),
        ExactGraph::Big(g) => pair_counts(&g, learn_visits(&g, args)?),
    }))
}

fn learn_visits<V: LearningValue>(
    graph: &Graph<V>,
    args: &RenderArgs,
) -> Result<Vec<Vec<u64>>, String> {
    let epsilon = parse_rational(&args.epsilon).map_err(|e| format!("--epsilon: {e}"))?;
    let optimum = dijkstra::to_goals(graph).cost_to_go;
    visit_counts(
        graph,
        &optimum,
        &epsilon,
        args.seed,
        args.episodes,
        args.max_steps,
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

fn caption(report: &PlanReport, overlay: OverlayKind) -> String {
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
        OverlayKind::Policy => "; overlay: the optimal policy",
        OverlayKind::Visits => "; overlay: move visits of one seeded Q-learning run",
    };
    format!(
        "{g} ({}, {values}){overlay}; grey segments: allowed moves",
        report.algorithm.name()
    )
}

//! `truecost render`: the paper's problem figure with an overlay, as SVG or PNG.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::figures::render::{draw, Overlay};
use truecost::figures::{file_scene, grid_scene};
use truecost::model::file;
use truecost::planning::{plan_exact, plan_reference, Algorithm, Mode, PlanReport};
use truecost::problems::{GridLayout, StepCost};
use truecost::value::Extended;

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
    /// Output file; the format follows its extension (.svg or .png).
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    out: PathBuf,
}

/// Runs the command; returns the message printed on success.
pub fn run(args: &RenderArgs) -> Result<String, String> {
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
                let report = plan_exact(&layout.to_problem(step), Algorithm::Dijkstra, false);
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
    };
    format!(
        "{g} ({}, {values}){overlay}; grey segments: allowed moves",
        report.algorithm.name()
    )
}

//! `--env SPEC` and `--objective` (issue 11, items 1 and 2): the shared options flattened into
//! `solve`, `problems`, `compare` and `export`, and the commands' bodies. Parsing only; the
//! library does the work ([`truecost::objectives`], [`truecost::envs`]).

use clap::{Args, ValueEnum};

use truecost::objectives::report::{solution_json, solution_text};
use truecost::objectives::{parse_objective, Model, Source};
use truecost::problems::StepCost;
use truecost::stochastic::{NoiseModel, Predictability};

use super::ReportFormat;

/// `--env SPEC`: one of Gymnasium's toy-text benchmarks, exactly.
#[derive(Args, Debug, Clone, Default)]
pub struct EnvArg {
    /// A Gymnasium benchmark, exactly: frozenlake[:map=4x4|8x8|FILE,slippery=true|false,
    /// success_rate=p/q], cliffwalking[:slippery=true|false], taxi.
    #[arg(long, value_name = "SPEC")]
    pub env: Option<String>,
}

/// The objective names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ObjectiveName {
    /// The paper's: least expected cost among policies reaching the goal with probability 1.
    Truecost,
    /// The greatest probability of reaching the goal.
    Reach,
    /// Discounted rewards (Gymnasium's for --env), maximised; needs --alpha.
    Discounted,
}

/// `--objective` and `--alpha`.
#[derive(Args, Debug, Clone, Default)]
pub struct ObjectiveArgs {
    /// What to optimise (with --algorithm exact): truecost, reach or discounted.
    #[arg(long, value_enum)]
    pub objective: Option<ObjectiveName>,
    /// The discount factor in (0, 1) of --objective discounted (exact decimal or p/q).
    #[arg(long, value_name = "A")]
    pub alpha: Option<String>,
}

/// `--env | --problem | --file` with the options of a paper problem or a deterministic file
/// (flattened into `compare`).
#[derive(Args, Debug, Clone, Default)]
pub struct ModelArgs {
    #[command(flatten)]
    pub env: EnvArg,
    /// One of the paper's problems, 0 to 18.
    #[arg(long, value_name = "N")]
    pub problem: Option<usize>,
    /// A problem file.
    #[arg(long, value_name = "FILE")]
    pub file: Option<std::path::PathBuf>,
    /// Stage cost of a grid move (paper problems only) [default: unit].
    #[arg(long, value_enum)]
    pub step_cost: Option<StepCost>,
    /// Predictability gamma in (0, 1] for --problem and deterministic --file.
    #[arg(long, value_name = "G")]
    pub gamma: Option<String>,
    /// How 1 - gamma is spread [default: paper].
    #[arg(long, value_enum)]
    pub noise: Option<NoiseModel>,
}

impl ModelArgs {
    /// Builds the model the options name (one line on error).
    pub fn load(&self) -> Result<Model, String> {
        source(
            &self.env,
            self.problem,
            self.file.as_deref(),
            self.step_cost,
            self.gamma.as_deref(),
            self.noise,
        )?
        .load()
    }
}

/// The source of a model from the usual options.
pub fn source(
    env: &EnvArg,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    step: Option<StepCost>,
    gamma: Option<&str>,
    noise: Option<NoiseModel>,
) -> Result<Source, String> {
    let gamma = gamma
        .map(|g| Predictability::parse(g).map_err(|e| e.to_string()))
        .transpose()?;
    if let Some(spec) = &env.env {
        if problem.is_some() || file.is_some() {
            return Err("give one of --env, --problem and --file".into());
        }
        if gamma.is_some() || noise.is_some() || step.is_some() {
            return Err("--gamma, --noise and --step-cost apply to --problem and --file; an environment has its own transitions and costs".into());
        }
        return Ok(Source::Env(spec.clone()));
    }
    let noise = noise.unwrap_or_default();
    match (problem, file) {
        (Some(id), None) => Ok(Source::Paper {
            id,
            step: step.unwrap_or_default(),
            noise,
            gamma: gamma.unwrap_or_else(Predictability::one),
        }),
        (None, Some(path)) => {
            if step.is_some() {
                return Err("--step-cost applies to the paper's grid problems (--problem N); a problem file gives its own costs".into());
            }
            Ok(Source::File {
                path: path.to_path_buf(),
                noise,
                gamma,
            })
        }
        _ => Err("give one of --env SPEC, --problem N and --file FILE".into()),
    }
}

/// Whether `solve` is asked for an objective or an environment (this module answers then).
pub fn wants(args: &super::SolveArgs) -> bool {
    args.env.env.is_some() || args.objective.objective.is_some() || args.objective.alpha.is_some()
}

/// `solve --env SPEC | --problem N | --file F --algorithm exact --objective O [--alpha A]`.
pub fn solve(args: &super::SolveArgs) -> Result<String, String> {
    if args.algorithm != super::stochastic::SolveAlgorithm::Exact {
        return Err("--env and --objective are solved exactly: use --algorithm exact".into());
    }
    if args.model_free
        || args.mode != truecost::planning::Mode::Exact
        || args.tolerance.is_some()
        || args.max_sweeps.is_some()
        || args.arithmetic.is_some()
    {
        return Err("--objective and --env take --algorithm exact without --model-free, --mode reference, --tolerance, --max-sweeps or --arithmetic".into());
    }
    let name = match args.objective.objective.unwrap_or(ObjectiveName::Truecost) {
        ObjectiveName::Truecost => "truecost",
        ObjectiveName::Reach => "reach",
        ObjectiveName::Discounted => "discounted",
    };
    let objective = parse_objective(name, args.objective.alpha.as_deref())?;
    let model = ModelArgs {
        env: args.env.clone(),
        problem: args.problem,
        file: args.file.clone(),
        step_cost: args.step_cost,
        gamma: args.gamma.clone(),
        noise: args.noise,
    }
    .load()?;
    let solution = model.solve(&objective).map_err(|e| e.to_string())?;
    Ok(match args.format {
        ReportFormat::Json => pretty(&solution_json(&model, &solution)),
        ReportFormat::Text => solution_text(&model, &solution),
    })
}

/// `problems --env SPEC`: the environment's facts.
pub fn problems(spec: &str, format: super::ListFormat) -> Result<String, String> {
    let model: Model = Source::Env(spec.to_string()).load()?;
    let facts = truecost::objectives::facts(&model).map_err(|e| e.to_string())?;
    Ok(match format {
        super::ListFormat::Json => pretty(&facts),
        _ => {
            let mut out = String::new();
            for k in [
                "source",
                "states",
                "actions",
                "outcomes",
                "initial_states",
                "goals",
                "traps",
                "terminal_bonus",
                "cost_to_go_initial",
                "reach_probability_initial",
                "reach_probability_initial_decimal",
            ] {
                let v = &facts[k];
                let v = v.as_str().map_or_else(|| v.to_string(), str::to_string);
                out.push_str(&format!("{k:<35}{v}\n"));
            }
            out
        }
    })
}

/// Pretty JSON with a final newline.
pub fn pretty(v: &serde_json::Value) -> String {
    let mut s = serde_json::to_string_pretty(v).expect("serialisable");
    s.push('\n');
    s
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
/// --overlay none|values|policy --out F` (issue 11, item 5). Every option is checked before
/// anything is solved.
pub fn render(
    spec: &str,
    objective: &ObjectiveArgs,
    slice: &TaxiSliceArgs,
    overlay: super::render::OverlayKind,
    width: u32,
    height: u32,
    out: &std::path::Path,
) -> Result<String, String> {
    use super::render::OverlayKind;
    use truecost::envs::figure::{
        policy_overlay, scene, taxi_policy_overlay, taxi_scene, taxi_value_overlay, value_overlay,
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
        return Err(truecost::envs::figure::NotDrawable.to_string());
    }
    let name = match objective.objective.unwrap_or(ObjectiveName::Truecost) {
        ObjectiveName::Truecost => "truecost",
        ObjectiveName::Reach => "reach",
        ObjectiveName::Discounted => "discounted",
    };
    let objective = parse_objective(name, objective.alpha.as_deref())?;
    let mut scene = if is_taxi {
        taxi_scene(&env, slice.as_ref())
    } else {
        scene(&env).map_err(|e| e.to_string())?
    };
    let overlay = match overlay {
        OverlayKind::None => Overlay::None,
        OverlayKind::Values | OverlayKind::Policy => {
            let model = Model::from_environment(&env).map_err(|e| e.to_string())?;
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
                    scene.caption.push_str(
                        "; arrows: the policy's moves, marks: its pick-up and drop-off (a move into a wall or the border is not drawn)",
                    );
                    let (overlay, marks) = taxi_policy_overlay(&model, &s, slice);
                    scene.marks.extend(marks);
                    overlay
                }
                (_, None) => {
                    scene
                        .caption
                        .push_str(" (an action aimed at the border is not drawn)");
                    policy_overlay(&env, &model, &s)
                }
            }
        }
        _ => unreachable!("refused above"),
    };
    let canvas = draw(&scene, &overlay, width, height).map_err(|e| e.to_string())?;
    canvas.save(out).map_err(|e| e.to_string())?;
    Ok(format!("wrote {} ({width}x{height})\n", out.display()))
}

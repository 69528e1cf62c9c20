//! `--env SPEC` and `--objective`: the shared options flattened into `solve`, `problems`,
//! `compare`, `export` and `render`, and the bodies of `solve --objective` and
//! `problems --env`. Parsing only; the library does the work ([`truecost::objectives`],
//! [`truecost::envs`]).

use clap::{Args, ValueEnum};

use truecost::certificate::{self, CertifiedObjective, Identity, ProblemRecord};
use truecost::objectives::report::{solution_json, solution_text};
use truecost::objectives::{parse_objective, Model, Objective, Source};
use truecost::problems::StepCost;
use truecost::stochastic::file::ProblemFile;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};

use super::certify::{write_certificate, CertifiedSource};
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

impl ObjectiveArgs {
    /// The objective the options name (the paper's `truecost` when none is given) and its
    /// name, checked by [`parse_objective`] (one line on error).
    pub fn parse(&self) -> Result<(&'static str, Objective), String> {
        let name = match self.objective.unwrap_or(ObjectiveName::Truecost) {
            ObjectiveName::Truecost => "truecost",
            ObjectiveName::Reach => "reach",
            ObjectiveName::Discounted => "discounted",
        };
        Ok((name, parse_objective(name, self.alpha.as_deref())?))
    }
}

impl ModelArgs {
    /// The source the options name (one line on error).
    pub fn source(&self) -> Result<Source, String> {
        source(
            &self.env,
            self.problem,
            self.file.as_deref(),
            self.step_cost,
            self.gamma.as_deref(),
            self.noise,
        )
    }

    /// Builds the model the options name (one line on error).
    pub fn load(&self) -> Result<Model, String> {
        self.source()?.load()
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
                names: Default::default(),
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
    let (_, objective) = args.objective.parse()?;
    let mut from = ModelArgs {
        env: args.env.clone(),
        problem: args.problem,
        file: args.file.clone(),
        step_cost: args.step_cost,
        gamma: args.gamma.clone(),
        noise: args.noise,
    }
    .source()?;
    if let Source::File { names, .. } = &mut from {
        *names = args.drn.names(args.file.as_deref())?;
    }
    let model = from.load()?;
    let cost = if args.with_cost {
        truecost::objectives::PolicyCost::Computed
    } else {
        truecost::objectives::PolicyCost::IfInfinite
    };
    let solution = model
        .solve_with(&objective, cost)
        .map_err(|e| e.to_string())?;
    if let Some(path) = &args.certificate {
        let record = CertifiedSource {
            file: args.file.as_deref(),
            problem: args.problem,
            env: args.env.env.as_deref(),
            step: args.step_cost,
            gamma: args.gamma.as_deref(),
            noise: args.noise,
            names: args.drn.names(args.file.as_deref())?,
        }
        .record(|| model.mdp())?;
        write_certificate(path, &solution_certificate(&model, &solution, &record)?)?;
    }
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

/// The certificate of an objective's solution (truecost, reach or discounted).
pub fn solution_certificate(
    model: &Model,
    solution: &truecost::objectives::Solution,
    record: &ProblemRecord,
) -> Result<String, String> {
    let objective = match &solution.objective {
        Objective::Truecost => CertifiedObjective::Truecost,
        Objective::Discounted(alpha) => CertifiedObjective::Discounted(alpha.clone()),
        Objective::Reach => CertifiedObjective::Reach,
    };
    let p = &model.problem;
    let policy: Vec<Option<usize>> = solution
        .policy
        .iter()
        .enumerate()
        .map(|(x, a)| a.map(|a| a - p.actions(x).start))
        .collect();
    let values = solution
        .values
        .iter()
        .map(|v| {
            certificate::value_text(match v {
                truecost::value::Extended::Finite(r) => Some(r),
                truecost::value::Extended::Infinite => None,
            })
        })
        .collect();
    Ok(certificate::write(&objective, record, values, &policy))
}

/// The largest certificate `check` reads, in bytes (1 GiB): the certificate of a 100×100 grid
/// at `γ = 0.999`, the largest model the exact solver takes in the guide's examples, has
/// 595 MB of exact values (429 MB at `γ = 0.99`; 37.1 MB at 50×50 and `γ = 0.999`), its long
/// integers in hexadecimal.
const MAX_CERTIFICATE_BYTES: u64 = 1 << 30;

/// The text of the certificate at `path`, read in chunks and checked as it is read: at most
/// [`MAX_CERTIFICATE_BYTES`] bytes (reading stops one byte past it), UTF-8, and no byte JSON
/// never holds raw (a control character other than tab, line feed and carriage return), so
/// that a stream of random bytes or zeros is refused at its first such byte.
pub(super) fn read_certificate(path: &std::path::Path) -> Result<String, String> {
    use std::io::Read;
    let shown = || truecost::echo::echo(&path.display().to_string());
    let io = |e: std::io::Error| format!("{}: {e}", shown());
    let mut file = std::fs::File::open(path).map_err(io)?;
    let mut bytes: Vec<u8> = Vec::new();
    let mut chunk = vec![0u8; 1 << 16];
    // The start of a UTF-8 sequence left incomplete at the end of the bytes read so far.
    let mut checked = 0;
    loop {
        let read = match file.read(&mut chunk) {
            Ok(0) => break,
            Ok(n) => n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(io(e)),
        };
        if (bytes.len() + read) as u64 > MAX_CERTIFICATE_BYTES {
            return Err(format!(
                "{} is larger than {MAX_CERTIFICATE_BYTES} bytes (1 GiB), the limit for certificates",
                shown()
            ));
        }
        if let Some(i) = chunk[..read]
            .iter()
            .position(|&b| b < 0x20 && !matches!(b, b'\t' | b'\n' | b'\r'))
        {
            return Err(format!(
                "{} is not a JSON certificate: byte {} is 0x{:02x}, a control character",
                shown(),
                bytes.len() + i,
                chunk[i]
            ));
        }
        bytes.extend_from_slice(&chunk[..read]);
        match std::str::from_utf8(&bytes[checked..]) {
            Ok(_) => checked = bytes.len(),
            Err(e) if e.error_len().is_none() => checked += e.valid_up_to(),
            Err(e) => {
                return Err(format!(
                    "{} is not UTF-8 text (byte {})",
                    shown(),
                    checked + e.valid_up_to()
                ))
            }
        }
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "{} is not UTF-8 text (byte {})",
            shown(),
            e.utf8_error().valid_up_to()
        )
    })
}

/// The goal label and cost reward model to read a DRN file with: those the certificate records
/// (how `solve` read the file), which `--goal-label` and `--cost-reward` may repeat but not
/// contradict.
fn recorded_names(
    given: &truecost::formats::drn::DrnNames,
    record: &truecost::certificate::ProblemRecord,
) -> Result<truecost::formats::drn::DrnNames, String> {
    let options = [
        (
            "--goal-label",
            "goal label",
            &given.goal_label,
            &record.goal_label,
        ),
        (
            "--cost-reward",
            "cost reward model",
            &given.cost_reward,
            &record.cost_reward,
        ),
    ];
    for (option, what, given, recorded) in options {
        if given.is_some() && given != recorded {
            let shown = |name: &Option<String>| {
                name.as_deref().map_or("the default".to_string(), |n| {
                    format!("'{}'", truecost::echo::echo(n))
                })
            };
            return Err(format!(
                "{option} {} contradicts the certificate, written for the {what} {}",
                shown(given),
                shown(recorded)
            ));
        }
    }
    Ok(truecost::formats::drn::DrnNames {
        goal_label: record.goal_label.clone(),
        cost_reward: record.cost_reward.clone(),
    })
}

/// `truecost check`: re-reads the problem (`--file`, `--problem`, `--env`; the certificate's
/// `gamma`, `noise` and `step_cost` say how it was built) and checks the certificate (`text`,
/// read by [`read_certificate`]); with
/// `coq`, the verified checker (`Truecost.CertificateCheck.check`, or
/// `Truecost.CertificateDiscounted.check_discounted` for the discounted objective, extracted to
/// OCaml) must accept it too.
pub fn check(
    source: &EnvArg,
    problem: Option<usize>,
    file: Option<&std::path::Path>,
    names: &truecost::formats::drn::DrnNames,
    text: &str,
    format: ReportFormat,
    coq: bool,
) -> Result<String, String> {
    let cert = certificate::parse(text).map_err(|e| format!("malformed certificate: {e}"))?;
    let record = &cert.problem;
    let names = &recorded_names(names, record)?;
    let gamma = record
        .gamma
        .as_deref()
        .map(|g| Predictability::parse(g).map_err(|e| format!("the certificate's gamma: {e}")))
        .transpose()?;
    let noise = match &record.noise {
        Some(name) => NoiseModel::from_str(name, false).map_err(|_| {
            format!(
                "the certificate's noise {} is not paper or reference",
                truecost::echo::echo(name)
            )
        })?,
        None => NoiseModel::default(),
    };
    let expect = |kind: &str| {
        if record.source == kind {
            Ok(())
        } else {
            Err(format!(
                "the certificate is for a problem from {} {}, not from {kind}",
                truecost::echo::echo(&record.source),
                truecost::echo::echo(&record.name)
            ))
        }
    };
    let (model, bytes) = match (&source.env, problem, file) {
        (Some(spec), None, None) => {
            expect("env")?;
            (Source::Env(spec.clone()).load()?, None)
        }
        (None, Some(id), None) => {
            expect("problem")?;
            let step = match &record.step_cost {
                Some(s) => StepCost::from_str(s, false).map_err(|_| {
                    format!(
                        "the certificate's step_cost {} is not unit or euclidean",
                        truecost::echo::echo(s)
                    )
                })?,
                None => StepCost::default(),
            };
            let source = Source::Paper {
                id,
                step,
                noise,
                gamma: gamma.unwrap_or_else(Predictability::one),
            };
            (source.load()?, None)
        }
        (None, None, Some(path)) => {
            expect("file")?;
            let bytes = truecost::bounded::read_bytes(
                path,
                truecost::model::file::MAX_FILE_BYTES,
                "problem files",
            )
            .map_err(|e| e.to_string())?;
            let text = String::from_utf8(bytes.clone()).map_err(|_| {
                format!(
                    "problem file {} is not UTF-8 text",
                    truecost::echo::echo(&path.display().to_string())
                )
            })?;
            let (read, extra) =
                truecost::formats::from_text_with_names(&text, names).map_err(|e| e.to_string())?;
            let p = match read {
                ProblemFile::Deterministic(d) => StochasticProblem::from_deterministic(
                    &d,
                    noise,
                    gamma.as_ref().unwrap_or(&Predictability::one()),
                )
                .map_err(|e| e.to_string())?,
                ProblemFile::Stochastic(s) => {
                    if gamma.is_some() {
                        return Err("the certificate gives a gamma, but this problem file lists its own outcome probabilities".into());
                    }
                    *s
                }
            };
            let model = Model::from_problem(p, format!("file {}", path.display()))
                .with_file_objective(&extra);
            (model, Some(bytes))
        }
        _ => return Err("give one of --env SPEC, --problem N and --file FILE".into()),
    };
    let mdp = model.mdp();
    let identity = match &bytes {
        Some(b) => Identity::FileBytes(b),
        None => Identity::Canonical,
    };
    if coq {
        certificate::coq::coq_applies(&mdp, &cert)?;
    }
    match certificate::check(&mdp, identity, &cert) {
        Ok(acceptance) => {
            let coq_checker = match cert.objective {
                certificate::CertifiedObjective::Discounted(_) => {
                    "Truecost.CertificateDiscounted.check_discounted"
                }
                _ => "Truecost.CertificateCheck.check",
            };
            let program = if coq {
                let (accepted, program) = certificate::coq::coq_check(&mdp, &cert)?;
                if !accepted {
                    return Err(format!(
                        "certificate rejected by the Coq checker ({coq_checker})"
                    ));
                }
                Some(program.display().to_string())
            } else {
                None
            };
            Ok(match format {
                ReportFormat::Json => pretty(&serde_json::json!({
                    "accepted": true,
                    "objective": acceptance.objective,
                    "problem": model.name,
                    "sha256": record.sha256,
                    "states": acceptance.states,
                    "finite_states": acceptance.finite_states,
                    "actions": acceptance.actions,
                    "conditions": acceptance.conditions,
                    "coq_checked": coq,
                    "coq_checker": program,
                })),
                ReportFormat::Text => {
                    let mut s = format!(
                    "accepted     {} certificate for {} ({} states, {} finite, {} actions; SHA-256 {})\n",
                    acceptance.objective,
                    model.name,
                    acceptance.states,
                    acceptance.finite_states,
                    acceptance.actions,
                    record.sha256
                );
                    for c in &acceptance.conditions {
                        s.push_str(&format!(
                            "{:<12} {} ({} checked)\n",
                            c.name, c.statement, c.instances
                        ));
                    }
                    if coq {
                        s.push_str(&format!(
                            "coq          accepted by the verified checker {coq_checker} (extracted to OCaml)\n"
                        ));
                    }
                    s
                }
            })
        }
        Err(rejection) => {
            if format == ReportFormat::Json {
                let v = serde_json::json!({
                    "accepted": false,
                    "objective": cert.objective.name(),
                    "problem": model.name,
                    "condition": rejection.condition,
                    "state": rejection.state,
                    "detail": rejection.detail,
                });
                super::emit(&pretty(&v))?;
            }
            Err(format!("certificate rejected: {rejection}"))
        }
    }
}

//! `truecost learn`: replays derandomized Q-learning on a problem file round by round
//! (the library function is `claims::replay::replay`).

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use truecost::claims::qlearning::Terminal;
use truecost::claims::replay::{replay, InitialValues, ReplayOrder};
use truecost::model::file;

use super::ReportFormat;

/// The fair update orders.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OrderName {
    /// Pairs in file order every round (at a goal, its termination pair first).
    Cyclic,
    /// Pairs in reverse file order every round.
    Reverse,
    /// Pairs whose successor is farthest from the goal first (the adversary).
    FarFirst,
    /// A fresh seeded permutation every round (needs --seed).
    Random,
}

/// Treatment of the goals' termination pairs `(g, uT)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TerminalName {
    /// Updated by the rho = 1 rule like every pair (C1 as printed).
    Updated,
    /// Held at 0 (H0 of C1-corrected).
    Held,
}

/// Replay derandomized Q-learning (rho = 1) in exact arithmetic: values per round and whether
/// and when Q reached Q*.
#[derive(Args, Debug)]
pub struct LearnArgs {
    /// The problem file.
    #[arg(long, value_name = "FILE")]
    file: PathBuf,
    /// Initial values: one exact value for every pair, or one per pair in pair order (states
    /// in file order; at a goal its termination pair first, then its moves), comma-separated.
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    q0: String,
    /// The fair order of updates within each round.
    #[arg(long, value_enum)]
    order: OrderName,
    /// Seed of the random order.
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Rounds to run at most.
    #[arg(long, value_name = "N")]
    rounds: u64,
    /// The goals' termination pairs.
    #[arg(long, value_enum, default_value_t = TerminalName::Updated)]
    terminal: TerminalName,
    #[arg(long, value_enum, default_value_t = ReportFormat::Text)]
    format: ReportFormat,
}

/// Runs `truecost learn`.
pub fn learn(args: &LearnArgs) -> Result<String, String> {
    let order = match (args.order, args.seed) {
        (OrderName::Random, Some(s)) => ReplayOrder::Random(s),
        (OrderName::Random, None) => return Err("--order random needs --seed S".into()),
        (_, Some(_)) => return Err("--seed applies to --order random only".into()),
        (OrderName::Cyclic, None) => ReplayOrder::Cyclic,
        (OrderName::Reverse, None) => ReplayOrder::Reverse,
        (OrderName::FarFirst, None) => ReplayOrder::FarFirst,
    };
    let terminal = match args.terminal {
        TerminalName::Updated => Terminal::Updated,
        TerminalName::Held => Terminal::HeldAtZero,
    };
    // The replay updates every state-action pair and compares with Q*, neither of which
    // depends on the initial state: a file's initial distribution is accepted and not used.
    let (problem, _) = file::read_with_objective(&args.file).map_err(|e| e.to_string())?;
    let q0 = InitialValues::parse(&args.q0)?;
    let r = replay(&problem, &q0, order, terminal, args.rounds)?;
    Ok(match args.format {
        ReportFormat::Text => r.text(),
        ReportFormat::Json => r.json(),
    })
}

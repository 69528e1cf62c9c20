//! The plan of a `truecost verify` run: the list of work units the registry derives from the
//! options ([`super::registry::plan`]), each a claim × engine × scope part. The shard module
//! selects a shard's units from it and merges the shards' records ([`super::shard`]), the
//! runner runs the selected units ([`super::runner`]), and the registry's report reads the
//! units' values back in plan order ([`super::registry::report`]).
//!
//! The units come in *steps*: the units of one engine's run (every harness of the stand-in, one
//! claim checker, one proptest property, the SMT obligations of one claim, the Coq re-check),
//! which the runner runs together and which fail together when the engine panics.

use std::time::Duration;

use super::harnesses::Harness;
use super::shard::{Share, Shared};
use super::smt::Encoding;
use super::Scope;

/// The table of harness bodies `verify` runs through the stand-in
/// (`truecost_proofs::harnesses`; a test may pass another, see
/// [`super::harnesses::run_standin`]).
pub type HarnessTable = fn() -> Vec<truecost_proofs::standin::Harness>;

/// A claim checker: the first engine of its claims (the exhaustive enumeration; for C3's
/// worked example, its exact solve).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Checker {
    /// Proposition 1 as printed and corrected.
    C1,
    /// Proposition 2.
    C2,
    /// Proposition 3.
    C3,
    /// The worked example of Proposition 3 (and `α*`).
    Example,
    /// Proposition 4 as printed and corrected.
    C4,
}

impl Checker {
    /// The claims it decides, in report order.
    ///
    /// ```
    /// use truecost::claims::plan::Checker;
    /// assert_eq!(Checker::C4.claims(), ["C4", "C4-corrected"]);
    /// assert_eq!(Checker::Example.engine(), "exact solve");
    /// ```
    pub fn claims(self) -> &'static [&'static str] {
        match self {
            Checker::C1 => &["C1", "C1-corrected"],
            Checker::C2 => &["C2"],
            Checker::C3 => &["C3"],
            Checker::Example => &["C3-example"],
            Checker::C4 => &["C4", "C4-corrected"],
        }
    }

    /// Its engine's name on the claims' engine lines.
    pub fn engine(self) -> &'static str {
        match self {
            Checker::Example => "exact solve",
            _ => "exhaustive enumeration",
        }
    }
}

/// What a unit runs.
#[derive(Clone, Copy, Debug)]
pub enum Work {
    /// One Kani harness body through the stand-in (engine 3).
    Harness(&'static Harness),
    /// A claim checker (engine 1; C3's example: its exact solve).
    Checker(Checker),
    /// The proptest property of a claim (engine 2).
    Property(&'static str),
    /// Obligation `j` of a claim's SMT encoding (engine 4).
    Obligation(&'static str, usize),
    /// The re-check of the Coq development (engine 5).
    Coq,
}

/// One unit of work: a claim × engine × scope part.
#[derive(Clone, Debug)]
pub struct Unit {
    /// Its name: a shard file lists an owned unit under it (`kani harness <name>`,
    /// `proptest C1`, `smt C1 obligation 3`, `coq re-check`); the runner's values are keyed by
    /// it.
    pub id: String,
    /// What it runs.
    pub work: Work,
    /// How shards share it.
    pub share: Share,
}

/// The units of one engine's run, run together; a panic in the engine fails all of them.
#[derive(Clone, Debug)]
pub struct Step {
    /// The engine, as the claims' engine lines name it (`proptest`, `smt (Z3)`, …).
    pub engine: &'static str,
    /// The claim it runs for, when it runs for one.
    pub claim: Option<&'static str>,
    /// The units, in plan order.
    pub units: Vec<Unit>,
    /// A failure met while planning the step (the SMT encoding of a claim that panicked): the
    /// step then has no units and fails as its engine would.
    pub failed: Option<String>,
}

/// The plan of one `verify` run.
pub struct Plan {
    /// How much each engine checks.
    pub scope: Scope,
    /// The claims reported, in report order.
    pub claims: Vec<&'static str>,
    /// The harnesses planned for these claims (those stating a selected claim, and the lemmas
    /// on truecost's own code when every claim is selected), run or not.
    pub harnesses: Vec<&'static Harness>,
    /// The harness bodies to run them from (`None`: `--no-harnesses`).
    pub harness_table: Option<HarnessTable>,
    /// The SMT engine's per-obligation timeout in milliseconds (`None`: `--no-smt`).
    pub smt_timeout_ms: Option<u32>,
    /// The SMT encodings of the claims that have one (when the SMT engine runs).
    pub encodings: Vec<Encoding>,
    /// The time limit of the Coq re-check.
    pub coq_timeout: Duration,
    /// The steps, in the order the whole run takes them.
    pub steps: Vec<Step>,
}

impl Shared for Unit {
    fn share(&self) -> Share {
        self.share
    }
}

impl Plan {
    /// Every unit, in plan order.
    pub fn units(&self) -> impl Iterator<Item = &Unit> {
        self.steps.iter().flat_map(|s| &s.units)
    }

    /// The SMT encoding of `claim`, if the plan has one.
    pub fn encoding(&self, claim: &str) -> Option<&Encoding> {
        self.encodings.iter().find(|e| e.claim == claim)
    }

    /// The step of `engine` run for `claim`, if the plan has one.
    pub fn step(&self, engine: &str, claim: &str) -> Option<&Step> {
        self.steps
            .iter()
            .find(|s| s.engine == engine && s.claim == Some(claim))
    }
}

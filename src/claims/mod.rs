//! The claims engine: the paper's four propositions (`docs/spec.md`) C1–C4 *exactly as
//! printed*, corrected statements where a printed one is refuted, and the engines that check
//! them against independent oracles.
//!
//! * Engine 1 — exhaustive small-scope enumeration ([`tiny`], parallel with rayon, symmetry
//!   reduced): every problem of a stated scope, checked against brute-force oracles
//!   ([`oracle`], [`qlearning`]).
//! * Engine 2 — proptest properties on larger random problems with shrinking ([`sampled`]).
//! * Engine 3 — Kani harnesses in `proofs/` (one source: symbolic under `cargo kani`, run by
//!   explicit-state enumeration or seeded sampling through a stand-in crate under `cargo test`
//!   and by `verify` in its own process); [`harnesses`] lists them.
//! * Engine 4 — SMT proofs over the reals for a stated scope ([`smt`], Z3).
//! * Engine 5 — the Coq development in `proofs/coq/`, theorems about every finite problem,
//!   re-checked by `coqc` when `verify` runs ([`coq`]).
//!
//! A claim is `proved for every finite problem (Coq)` only when its Coq theorems were
//! re-checked in the same run with their pinned statements (`proved in Coq for the paper's
//! example` when they are about the worked example only), `proved` for the SMT engine's stated scope, `verified` only for
//! the scope an engine checked, `refuted` with a minimal counterexample, or `inconclusive`. Nothing here reads a clock except [`run`], which wraps
//! each engine to report cases per second.

// Index loops over tiny fixed arrays read better than iterator chains in these oracles.
#![allow(clippy::needless_range_loop)]

pub mod alpha;
pub mod c1;
pub mod c2;
pub mod c3;
pub mod c4;
pub mod c4_cycles;
pub mod caught;
pub mod certificates;
pub mod coq;
pub mod discount;
pub mod exact;
pub mod harnesses;
pub mod oracle;
pub mod plan;
pub mod qlearning;
pub mod registry;
pub mod replay;
pub mod report;
pub mod runner;
pub mod sampled;
pub mod shard;
pub mod smt;
pub mod tiny;

use rayon::prelude::*;
use serde::Serialize;

use crate::model::Problem;
use tiny::{Family, FamilySpec, Tiny};

/// How much each engine checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Scope {
    /// A small scope for the test suite (debug builds).
    Smoke,
    /// The CI scope: at least 10^6 distinct cases per claim, about a minute on 2 cores.
    Quick,
    /// Larger problems and more samples.
    Full,
}

impl Scope {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Scope::Smoke => "smoke",
            Scope::Quick => "quick",
            Scope::Full => "full",
        }
    }

    /// The scope of a name given by [`Scope::name`] (`None` for any other text), read as the
    /// command line reads `--scope` (the `clap::ValueEnum` derive, case-sensitive).
    ///
    /// ```
    /// use truecost::claims::Scope;
    /// for s in [Scope::Smoke, Scope::Quick, Scope::Full] {
    ///     assert_eq!(Scope::from_name(s.name()), Some(s));
    /// }
    /// assert_eq!(Scope::from_name("Quick"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Scope> {
        <Scope as clap::ValueEnum>::from_str(name, false).ok()
    }
}

/// The verdict on a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// Coq theorems about every finite problem, re-checked by `coqc` in this run, their
    /// statements and `Print Assumptions` exactly the pinned ones ([`coq`]; the strongest
    /// level).
    ProvedCoq,
    /// Coq theorems about the paper's worked example (one fixed problem), re-checked as for
    /// [`Verdict::ProvedCoq`]: a proof for that problem, not for every finite problem.
    ProvedCoqExample,
    /// The SMT engine showed the negation unsatisfiable over the reals for every structure of
    /// its stated scope, with its trust checks passing (PROOFS.md).
    Proved,
    /// Holds on every case of the stated scope (not a proof beyond it).
    Verified,
    /// A counterexample was found (the smallest in the scope's order is reported).
    Refuted,
    /// Neither.
    Inconclusive,
}

impl Verdict {
    /// `proved for every finite problem (Coq)`, `proved in Coq for the paper's example`,
    /// `proved`, `verified`, `refuted` or `inconclusive`.
    ///
    /// ```
    /// use truecost::claims::Verdict;
    /// assert_eq!(Verdict::ProvedCoq.name(), "proved for every finite problem (Coq)");
    /// assert_eq!(Verdict::ProvedCoqExample.name(), "proved in Coq for the paper's example");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Verdict::ProvedCoq => "proved for every finite problem (Coq)",
            Verdict::ProvedCoqExample => "proved in Coq for the paper's example",
            Verdict::Proved => "proved",
            Verdict::Verified => "verified",
            Verdict::Refuted => "refuted",
            Verdict::Inconclusive => "inconclusive",
        }
    }
}

/// What one engine did for a claim.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EngineRun {
    /// `exhaustive enumeration`, `proptest`, `kani harness …` or `smt`.
    pub engine: String,
    /// `exhaustive` or `sampled`; for a Kani harness, how the stand-in ran it in this process
    /// (or that it was not run, with `--no-harnesses`).
    pub mode: String,
    /// What was checked.
    pub scope: String,
    /// Number of cases checked.
    pub cases: u64,
    /// Number of cases where the claim failed.
    pub failures: u64,
    /// Wall-clock seconds (never part of a pinned snapshot).
    #[serde(skip)]
    pub seconds: f64,
}

/// A counterexample: a small problem (replayable with `truecost solve --file`) and what fails.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Counterexample {
    /// One-line summary.
    pub summary: String,
    /// The problem (`x1 = 0`, goal = last state) as a one-line description.
    pub problem: String,
    /// Further exact data (initial values, bonus, intervals, ...).
    pub details: Vec<(String, String)>,
    /// The suggested file name under `problems/counterexamples/`.
    pub file: String,
    /// The problem file's text.
    #[serde(skip)]
    pub problem_file: String,
    /// A command that shows the failure, starting with `truecost `.
    pub replay: Option<String>,
}

impl Counterexample {
    /// Builds a counterexample for a tiny problem.
    pub fn new(t: &Tiny, summary: String, details: Vec<(String, String)>, file: &str) -> Self {
        let problem: Problem = t.to_problem();
        Counterexample {
            summary: summary.clone(),
            problem: t.describe(),
            details,
            file: format!("problems/counterexamples/{file}.json"),
            problem_file: crate::model::file::to_json(&problem, Some(&summary)) + "\n",
            replay: None,
        }
    }

    /// The same counterexample with the command that replays its failure.
    pub fn with_replay(self, command: String) -> Self {
        Counterexample {
            replay: Some(command),
            ..self
        }
    }
}

/// The result for one claim.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClaimResult {
    /// `C1`, `C1-corrected`, ...
    pub id: String,
    /// The statement checked, with its hypotheses.
    pub statement: String,
    /// The verdict.
    pub verdict: Verdict,
    /// The engine that decided the verdict.
    pub engine: String,
    /// The scope that engine checked.
    pub scope: String,
    /// Number of cases that engine checked.
    pub cases: u64,
    /// The minimal counterexample, if refuted.
    pub counterexample: Option<Counterexample>,
    /// Every engine's run.
    pub engines: Vec<EngineRun>,
    /// Further findings (necessity of hypotheses, tightness of bounds, cross-checks).
    pub notes: Vec<String>,
}

/// Runs `visit` on every canonical problem of `spec`, in parallel, and merges the
/// accumulators. Deterministic whatever the number of threads: `merge` must be associative and
/// commutative (sums, minima). Returns the merged accumulator and the number of distinct
/// problems.
///
/// Under `verify --shard K/N` it visits only the labelled indices `i ≡ K − 1 (mod N)` and
/// records its partial accumulator; `verify merge` merges the shards' accumulators with
/// `merge` instead of visiting anything ([`runner::split`]) — hence the serde bounds.
pub fn enumerate<A, I, V, M>(spec: &FamilySpec, init: I, visit: V, merge: M) -> (A, u64)
where
    A: Send + serde::Serialize + serde::de::DeserializeOwned,
    I: Fn() -> A + Sync + Send,
    V: Fn(&mut A, &Tiny, u64) + Sync + Send,
    M: Fn(A, A) -> A + Sync + Send,
{
    let family = Family::new(spec);
    let count = family.labelled_count();
    let count = usize::try_from(count).expect("scope fits in memory indices");
    runner::split(
        &format!("enumerate {} ({count} labelled)", spec.describe()),
        |part| {
            (0..count)
                .into_par_iter()
                .with_min_len(256)
                .filter(|&i| part.is_none_or(|p| p.owns(i as u64)))
                .fold(
                    || (init(), 0u64),
                    |(mut acc, mut distinct), i| {
                        let i = i as u64;
                        let t = family.problem(i);
                        if family.is_canonical(&t) {
                            distinct += 1;
                            visit(&mut acc, &t, i);
                        }
                        (acc, distinct)
                    },
                )
                .reduce(|| (init(), 0u64), |(a, da), (b, db)| (merge(a, b), da + db))
        },
        |(a, da), (b, db)| (merge(a, b), da + db),
        || (init(), 0),
    )
}

/// Keeps the minimal `(key, value)`; of equal keys the first, as [`min_of`] does, so a
/// counterexample found under several orders is reported under the first (`value` is computed
/// only when kept).
pub fn keep_min<K: Ord, T>(slot: &mut Option<(K, T)>, key: K, value: impl FnOnce() -> T) {
    if slot.as_ref().is_none_or(|(k, _)| key < *k) {
        *slot = Some((key, value()));
    }
}

/// Merges two optional minima; of equal keys the first (`a`).
pub fn min_of<K: Ord, T>(a: Option<(K, T)>, b: Option<(K, T)>) -> Option<(K, T)> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.0 < x.0 { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}

/// Runs the claims selected by `only` (all when `None`) in `scope`, every engine included.
pub fn run(scope: Scope, only: Option<&str>) -> Result<report::Report, String> {
    registry::run(scope, only, &registry::Options::default())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `keep_min` against the definition: the least key wins, of equal keys the first, and a
    /// value is computed only when kept; `min_of` picks the same on every pair.
    #[test]
    fn keep_min_keeps_the_first_least_key() {
        let mut slot = None;
        let mut computed = Vec::new();
        for (key, name) in [
            (3, "a"),
            (2, "b"),
            (2, "c"),
            (5, "d"),
            (2, "e"),
            (1, "f"),
            (1, "g"),
        ] {
            keep_min(&mut slot, key, || {
                computed.push(name);
                name
            });
            if name == "e" {
                assert_eq!(slot, Some((2, "b")));
            }
        }
        assert_eq!(slot, Some((1, "f")));
        assert_eq!(computed, ["a", "b", "f"]);
        assert_eq!(min_of(Some((2, "x")), Some((2, "y"))), Some((2, "x")));
        assert_eq!(min_of(Some((3, "x")), Some((2, "y"))), Some((2, "y")));
        assert_eq!(min_of(Some((2, "x")), Some((3, "y"))), Some((2, "x")));
        assert_eq!(min_of(None, Some((3, "y"))), Some((3, "y")));
        assert_eq!(min_of(Some((3, "x")), None::<(i32, &str)>), Some((3, "x")));
    }
}

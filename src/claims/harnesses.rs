//! The Kani harnesses of `proofs/` (engine 3): what each states, its domain, its
//! bounds, how the stand-in runs it, and what `cargo kani` adds; and the runner that executes
//! their bodies in this process ([`run_standin`]), which `verify` reports.
//!
//! Nothing here is hand-copied without a check: `tests/harnesses.rs` compares every entry with
//! the harness sources (names, files, `#[kani::unwind]`, `#[kani::should_panic]`, the stated
//! sample counts) and the proofs crate's test runs every harness through the stand-in and
//! compares its mode, executions, choice bits and failures with the entry.
//!
//! **What `verify` says about a harness.** Its line is what the stand-in did *in this
//! process*: the mode (exhaustive: every choice sequence; sampled: seeded, boundary values
//! first), the executions, the failures, the covers satisfied, and the domain (exhaustive: the
//! exact number of choice sequences; sampled: the number of distinct choice sequences drawn,
//! and the width in *choice bits*, which counts nondeterministic bits, not distinct inputs).
//! It is never a Kani result: Kani is not run here.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use truecost_proofs::standin;

use super::caught::ENGINE_FAILED;
use super::EngineRun;

/// How the stand-in runs a harness under `cargo test`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandinMode {
    /// Every choice enumerated (a small, deliberate second check).
    Exhaustive,
    /// Seeded sampling, boundary values first: evidence, not a proof.
    Sampled,
}

impl StandinMode {
    /// `exhaustive` or `sampled`.
    pub fn name(self) -> &'static str {
        match self {
            StandinMode::Exhaustive => "exhaustive",
            StandinMode::Sampled => "sampled",
        }
    }
}

/// A Kani harness of `proofs/` (engine 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Harness {
    /// Function name.
    pub name: &'static str,
    /// The claim or lemma it states.
    pub claim: &'static str,
    /// Source file under `proofs/src/`.
    pub file: &'static str,
    /// What it proves.
    pub proves: &'static str,
    /// `#[kani::unwind]` bound (`None`: the harness has no loop needing one).
    pub unwind: Option<u32>,
    /// Whether it is `#[kani::should_panic]` (the printed statement must fail).
    pub should_panic: bool,
    /// How the stand-in runs it.
    pub mode: StandinMode,
    /// Executions of the stand-in: the stated sample count (sampled) or the number of choice
    /// sequences (exhaustive).
    pub executions: u64,
    /// The domain's width in choice bits: the largest `Σ log2 |choice|` of one execution
    /// (rounded down), as the stand-in measures it. Bits of nondeterminism, not a count of
    /// distinct inputs (an exhaustive harness's exact count is its `executions`).
    pub choice_bits: u32,
    /// Executions that fail under the stand-in (seeded, so reproducible): non-zero only for
    /// `should_panic` harnesses, whose printed statement must fail.
    pub failing: u64,
    /// What `cargo kani` would add beyond the stand-in.
    pub kani_adds: &'static str,
}

const CONTRACT: &str = "a proof of the contract for every input its precondition admits (the postcondition checked symbolically, with Kani's overflow checks), which the claim harnesses then assume through #[kani::stub_verified] (the stand-in runs a seeded sample and checks the contract on every call it makes)";

const SYMBOLIC: &str = "every choice of the domain at once, symbolically, plus Kani's overflow and bounds checks on every \
path (the stand-in runs a seeded sample)";

/// Every harness of `proofs/`.
pub const HARNESSES: &[Harness] = &[
    Harness {
        name: "c1_as_printed_round_fixed_points_are_optimal",
        claim: "C1",
        file: "c1.rs",
        proves: "FAILS as expected (the printed claim): on 3 non-goal states with 2 moves each (symbolic successors, u16 costs >= 0), the goal's termination pair updated like every pair, any i32 initial values, every state reaching the goal: a cyclic round that changes nothing ends at Q* (6 rounds)",
        unwind: Some(8),
        should_panic: true,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 368,
        failing: 4066,
        kani_adds: "a failing execution found symbolically; the stand-in found failures by sampling",
    },
    Harness {
        name: "c1_corrected_round_lifts_the_exact_level",
        claim: "C1-corrected",
        file: "c1.rs",
        proves: "Part A inductive step: on 3 non-goal states with 2 moves each (symbolic successors, u16 costs >= 0, H0, H1), from ANY i32 values satisfying I_r (Q >= Q*, pairs with h(f(x,u)) <= r-1 exact), r in 0..=4, one arbitrary fair round (symbolic order, repeats allowed) through truecost's rho = 1 update re-establishes I_{r+1}",
        unwind: Some(19),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 448,
        failing: 0,
        kani_adds: "a proof of the inductive step for every structure, value vector, level and round of the domain, hence of Part A for every number of rounds (induction)",
    },
    Harness {
        name: "c1_corrected_round_raises_the_floor_by_c",
        claim: "C1-corrected",
        file: "c1.rs",
        proves: "Part B inductive step: on the same structures with every cost >= c >= 1, from ANY i32 threshold t and values satisfying J_t (Q >= min(Q*, t)), one arbitrary fair round re-establishes J_{t+c}",
        unwind: Some(19),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 472,
        failing: 0,
        kani_adds: "a proof of Lemma B1 for every structure, threshold, value vector and round of the domain",
    },
    Harness {
        name: "c1_corrected_round_is_monotone_below_q_star",
        claim: "C1-corrected",
        file: "c1.rs",
        proves: "Part B sandwich: on the same structures (costs >= 0), for ANY i32 values Q <= Q* and any Q' >= Q (up to 2^32 above), the same arbitrary fair round keeps Q <= Q' (monotonicity, B2) and Q <= Q* (B3)",
        unwind: Some(19),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 632,
        failing: 0,
        kani_adds: "a proof of Lemmas B2 and B3 for every structure, value pair and round of the domain",
    },
    Harness {
        name: "c2_oracle_argmin_cost_is_argmax_reward",
        claim: "C2",
        file: "c2.rs",
        proves: "on any 4-state problem (1-2 moves per non-goal state, symbolic successors, any u8 costs), for each of C2's seven functionals (six in Q<i16>, discounted 9/10 in Q<i32>), truecost's policy-enumeration oracle finds the cost minimisers from x1 to be exactly the reward maximisers, with no overflow",
        unwind: Some(9),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        choice_bits: 99,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "c3_certificate_makes_discounting_avoid_the_goal",
        claim: "C3",
        file: "c3.rs",
        proves: "on any 4-state problem (symbolic successors, 1-2 moves per non-goal state) and alpha in {1/16, 1/2, 2/3, 9/10} (Q<i16>, Q<i32> at 9/10): under C3's hypotheses truecost's certificate exists whenever its cost K fits a u8 (at 1/16, K = 274 does not), and under it a discount-optimal policy from x1 never reaches the goal (every policy's exact value compared)",
        unwind: Some(17),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        choice_bits: 99,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "c3_example_sides_of_alpha_star_exhaustive_small",
        claim: "C3-example",
        file: "c3.rs",
        proves: "small exhaustive variant: for alpha = k/32 (k any u8, assumed 1..=31; alpha* lies between 29/32 and 30/32), over all 32 policies of the worked example, the discount-optimal policy from 0 avoids the goal iff the printed inequality holds iff 5a^4 - a^3 - a^2 - a - 1 < 0",
        unwind: Some(34),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 256,
        choice_bits: 8,
        failing: 0,
        kani_adds: "nothing beyond the stand-in's complete enumeration except Kani's overflow checks on the i128 arithmetic (i64 here)",
    },
    Harness {
        name: "c4_as_printed_set_is_the_oracles",
        claim: "C4",
        file: "c4.rs",
        proves: "FAILS as expected (the printed claim): on any 4-state problem (x1 = 0, goal 3, 1-2 moves per state, symbolic successors, costs 0..=5) with a goal path, at any bonus M = -n/d (n, d <= 128; Q<i16>), wherever the printed formula is defined, pi* is average-cost optimal (oracle) iff M is in the printed set",
        unwind: Some(9),
        should_panic: true,
        mode: StandinMode::Sampled,
        executions: 4_000,
        choice_bits: 115,
        failing: 55,
        kani_adds: "a failing execution found symbolically; the stand-in found failures by sampling",
    },
    Harness {
        name: "c4_corrected_set_is_the_oracles",
        claim: "C4-corrected",
        file: "c4.rs",
        proves: "on any 4-state problem (x1 = 0, goal 3, 1-2 moves per state, symbolic successors, any u8 costs) with a goal path, at any bonus M = -n/d (n <= 2^12, d <= 8; Q<i16>, the printed formula skipped), for every distinct S*: the corrected set of M equals the policy-enumeration oracle's exact set, and pi* is optimal at M iff M is in it",
        unwind: Some(9),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        choice_bits: 123,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_cost_to_go_satisfies_bellman_optimality",
        claim: "solvers: Bellman optimality of G*",
        file: "solvers.rs",
        proves: "on any 4-state problem (1-2 moves per non-goal state, symbolic successors, any u32 costs), truecost's Dijkstra G* equals the least path cost computed by Bellman-Ford in the harness (+inf where no path reaches the goal), satisfies G*(goal) = 0 and Bellman optimality at every state, and its policy reaches the goal at cost G*",
        unwind: Some(8),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 5_000,
        choice_bits: 243,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_equals_value_iteration",
        claim: "solvers: Dijkstra = VI",
        file: "solvers.rs",
        proves: "an extra comparison between truecost's planners, on the same problems (u32 costs): Dijkstra's G* equals synchronous and asynchronous value iteration's, element by element",
        unwind: Some(8),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 5_000,
        choice_bits: 243,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_equals_value_iteration_exhaustive_small",
        claim: "solvers: Dijkstra = VI",
        file: "solvers.rs",
        proves: "small exhaustive variant: every 3-state problem with one or two moves per non-goal state (successor and cost in 0..=2): Dijkstra's G* equals the Bellman-Ford oracle's least path cost (optimality, least-ness, the policy) and synchronous value iteration's",
        unwind: Some(6),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 8_100,
        choice_bits: 14,
        failing: 0,
        kani_adds: "nothing beyond the stand-in's complete enumeration except Kani's overflow and bounds checks",
    },
    Harness {
        name: "exploration_discovers_the_reachable_states_exhaustive_small",
        claim: "solvers: termination of exploration",
        file: "solvers.rs",
        proves: "small exhaustive variant: on every 3-state problem with one or two unit-cost moves per state (successors anywhere), the model-free walk terminates, discovers exactly the states reachable from x1 and applies at most (2 x moves + 1) x 2 actions",
        unwind: Some(14),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 1_728,
        choice_bits: 12,
        failing: 0,
        kani_adds: "nothing beyond the stand-in's complete enumeration except Kani's overflow and bounds checks",
    },
    Harness {
        name: "units_plus_is_exact_when_it_fits",
        claim: "values: exact arithmetic",
        file: "values.rs",
        proves: "Units::plus on any two u64 values: +inf (u64::MAX) absorbs, and a finite sum below u64::MAX is the exact sum",
        unwind: None,
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 128,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "units_plus_reports_every_overflow",
        claim: "values: exact arithmetic",
        file: "values.rs",
        proves: "every overflow is reported, over any two u64 values (u64::MAX is +inf): Units::checked_plus is None exactly when both are finite and the sum does not fit below u64::MAX (it would wrap or read as +inf); otherwise +inf if either is, else the exact sum, and Units::plus returns the same value",
        unwind: None,
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 128,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "rational_add_and_mul_are_exact",
        claim: "values: exact arithmetic",
        file: "values.rs",
        proves: "claims::exact::Q<i16> addition and multiplication on any fractions with numerators and denominators in [-127, 127] (denominators non-zero): normalised (positive denominator, and Q::ratio of the result is the result) and exact (cross-multiplied in i32), with no overflow; lowest_terms (extended Euclid) replaced by its proven contract under Kani",
        unwind: Some(3),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits: 32,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    contract_proof(
        "gcd_divides_both",
        "contracts: gcd",
        "the contract of claims::exact::gcd (proof_for_contract) on any two i16 values whose magnitudes fit: the result is non-negative, zero exactly when both operands are, and divides both; lowest_terms replaced by its proven contract",
        None,
        32,
    ),
    contract_proof(
        "lowest_terms_has_a_bezout_witness",
        "contracts: lowest_terms",
        "the contract of claims::exact::lowest_terms (proof_for_contract; Q::ratio is its fraction) on any two i16 values (d != 0, magnitudes fit): a positive denominator, the value n/d exactly (cross-multiplied) and a Bezout witness num*x + den*y = 1 (coprime parts), every clause loop-free; the one harness that unrolls Euclid's loop",
        Some(24),
        32,
    ),
    contract_proof(
        "checked_add_is_exact",
        "contracts: Q::checked_add",
        "the contract of Q::<i16>::checked_add (proof_for_contract) on fractions with parts in [-127, 127] and on any two i16 integers: a Some has a positive denominator and exactly the sum, None only when the unreduced sum does not fit; lowest_terms replaced by its proven contract",
        None,
        33,
    ),
    contract_proof(
        "checked_mul_is_exact",
        "contracts: Q::checked_mul",
        "the contract of Q::<i16>::checked_mul (proof_for_contract) on fractions with parts in [-127, 127] and on any two i16 integers: a Some has a positive denominator and exactly the product, None only when the unreduced product does not fit; lowest_terms replaced by its proven contract",
        None,
        33,
    ),
    contract_proof(
        "units_checked_plus_is_exact",
        "contracts: Units::checked_plus",
        "the contract of value::Units::checked_plus (proof_for_contract) on any two u64 counts: +inf absorbs, a sum below u64::MAX is exact, None exactly when it is not",
        None,
        128,
    ),
    contract_proof(
        "update_is_the_rho_one_rule",
        "contracts: QProblem::update",
        "the contract of claims::qlearning::QProblem::update (proof_for_contract) on any structure of the C1 family, any i32 values and any pair (the termination pair held or updated): the new value is l + Q^ of some successor pair and at most that of every one (the rho = 1 rule), and no other value changes",
        Some(25),
        377,
    ),
];

/// The entry of a contract proof of `proofs/src/contracts.rs` (`#[kani::proof_for_contract]`):
/// a lemma named `contracts: <function>`, sampled by the stand-in with its default 20000
/// executions, never failing.
const fn contract_proof(
    name: &'static str,
    claim: &'static str,
    proves: &'static str,
    unwind: Option<u32>,
    choice_bits: u32,
) -> Harness {
    Harness {
        name,
        claim,
        file: "contracts.rs",
        proves,
        unwind,
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        choice_bits,
        failing: 0,
        kani_adds: CONTRACT,
    }
}

impl Harness {
    /// The domain as the registry states it: an exhaustive harness's exact number of choice
    /// sequences, a sampled one's width in choice bits.
    pub fn domain(&self) -> String {
        match self.mode {
            StandinMode::Exhaustive => format!(
                "every one of {} choice sequences ({} choice bits)",
                self.executions, self.choice_bits
            ),
            StandinMode::Sampled => format!(
                "{} executions of a domain of {} choice bits (bits of nondeterminism, not distinct inputs)",
                self.executions, self.choice_bits
            ),
        }
    }

    fn scope(&self) -> String {
        format!(
            "proofs/src/{}: {}{}",
            self.file,
            self.proves,
            self.unwind
                .map_or(String::new(), |u| format!(" (unwind {u})"))
        )
    }
}

/// The harnesses that state claim `id` (registry order).
pub fn of_claim(id: &str) -> Vec<&'static Harness> {
    HARNESSES.iter().filter(|h| h.claim == id).collect()
}

/// One harness run by the stand-in in this process: what `verify` reports (serialisable, so a
/// shard records it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StandinRun {
    /// Harness name.
    pub name: String,
    /// `exhaustive` or `sampled` (empty: not run).
    pub mode: String,
    /// Executions of the body.
    pub executions: u64,
    /// Distinct choice sequences among them.
    pub distinct: u64,
    /// Executions pruned by `assume`.
    pub pruned: u64,
    /// Failing executions.
    pub failures: u64,
    /// Width of the domain in choice bits.
    pub choice_bits: u32,
    /// Covers satisfied in some non-pruned execution.
    pub covers_hit: u64,
    /// Covers of the harness.
    pub covers: u64,
    /// `#[kani::should_panic]`: failures are the expected refutation.
    pub should_panic: bool,
    /// Why the harness fails as a harness (`None`: it did what it states).
    pub problem: Option<String>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl StandinRun {
    fn from_summary(h: &standin::Harness, s: &standin::Summary, seconds: f64) -> StandinRun {
        StandinRun {
            name: h.name.to_string(),
            mode: s.mode.name().to_string(),
            executions: s.executions,
            distinct: s.distinct,
            pruned: s.pruned,
            failures: s.failures,
            choice_bits: s.choice_bits,
            covers_hit: s.covers_hit() as u64,
            covers: s.covers.len() as u64,
            should_panic: h.should_panic,
            problem: s.verdict().err(),
            seconds,
        }
    }

    fn missing(name: &str) -> StandinRun {
        StandinRun {
            name: name.to_string(),
            mode: String::new(),
            executions: 0,
            distinct: 0,
            pruned: 0,
            failures: 0,
            choice_bits: 0,
            covers_hit: 0,
            covers: 0,
            should_panic: false,
            problem: Some(format!(
                "{name}: no harness of this name in truecost-proofs (the registry and proofs/ disagree)"
            )),
            seconds: 0.0,
        }
    }

    /// A run that did not finish: the stand-in (or the code around it) panicked with
    /// `failure` (described by [`super::caught::caught`]).
    pub fn failed(name: &str, should_panic: bool, failure: &str) -> StandinRun {
        StandinRun {
            mode: ENGINE_FAILED_MODE.into(),
            should_panic,
            problem: Some(format!("{ENGINE_FAILED}{failure}")),
            ..StandinRun::missing(name)
        }
    }

    /// Whether the run did not finish ([`StandinRun::failed`]).
    pub fn engine_failed(&self) -> bool {
        self.mode == ENGINE_FAILED_MODE
    }

    /// The harness failed as a harness by an assertion in a harness that must hold: a
    /// counterexample to what it states, found by the stand-in.
    pub fn refutes(&self) -> bool {
        !self.should_panic && self.failures > 0
    }
}

/// The mode of a [`StandinRun`] that did not finish.
const ENGINE_FAILED_MODE: &str = "engine failed";

/// Runs the harnesses `names` of `table` through the stand-in, in parallel, each with its
/// stated executions in every scope (all twenty-two together take well under two seconds on two
/// cores, release or test build, so no scope needs fewer). A name missing from `table` gives a
/// run that says so; a run of the stand-in that panics (its own failure: a body's panics are
/// failing executions) gives a run whose engine line says `engine failed`.
///
/// `verify` passes `truecost_proofs::harnesses()`; a test can pass a table whose body is a
/// deliberately wrong copy (see `tests/harnesses_planted.rs`), which is why the table is a
/// parameter.
pub fn run_standin(table: &[standin::Harness], names: &[&str]) -> Vec<StandinRun> {
    names
        .par_iter()
        .map(|name| match table.iter().find(|h| h.name == *name) {
            None => StandinRun::missing(name),
            Some(h) => {
                let started = std::time::Instant::now();
                match super::caught::caught(|| h.explore()) {
                    Ok(s) => StandinRun::from_summary(h, &s, started.elapsed().as_secs_f64()),
                    Err(failure) => StandinRun::failed(h.name, h.should_panic, &failure),
                }
            }
        })
        .collect()
}

/// The engine line of harness `h` as run here (`run`).
///
/// ```
/// use truecost::claims::harnesses::{reported, run_standin, HARNESSES};
/// let h = HARNESSES.iter().find(|h| h.name == "c3_example_sides_of_alpha_star_exhaustive_small").unwrap();
/// let run = &run_standin(&truecost_proofs::harnesses(), &[h.name])[0];
/// let e = reported(h, run);
/// assert!(e.mode.starts_with("run here by the stand-in: exhaustive"), "{}", e.mode);
/// assert!(e.mode.contains("not a Kani result"));
/// assert_eq!((e.cases, e.failures), (run.executions, 0));
/// ```
pub fn reported(h: &Harness, run: &StandinRun) -> EngineRun {
    if run.engine_failed() {
        return EngineRun {
            engine: format!("kani harness {}", h.name),
            mode: run.problem.clone().unwrap_or_default(),
            scope: h.scope(),
            cases: 0,
            failures: 0,
            seconds: 0.0,
        };
    }
    let executions = match run.mode.as_str() {
        "sampled" => format!("sampled {} executions", run.executions),
        "exhaustive" => format!(
            "exhaustive, every one of {} choice sequences",
            run.executions
        ),
        _ => "NOT run".to_string(),
    };
    let failures = if run.should_panic && run.failures > 0 && run.problem.is_none() {
        format!(
            "{} failures (the printed statement must fail: refuted as expected)",
            run.failures
        )
    } else {
        format!("{} failures", run.failures)
    };
    let domain = if run.mode == "sampled" {
        format!(
            "; {} distinct choice sequences, domain {} choice bits",
            run.distinct, run.choice_bits
        )
    } else {
        String::new()
    };
    let problem = run
        .problem
        .as_ref()
        .map_or(String::new(), |p| format!("; HARNESS FAILS: {p}"));
    EngineRun {
        engine: format!("kani harness {}", h.name),
        mode: format!(
            "run here by the stand-in: {executions}, {failures}, covers {}/{} hit{domain}{problem}; not a Kani result",
            run.covers_hit, run.covers
        ),
        scope: h.scope(),
        cases: run.executions,
        failures: run.failures,
        seconds: run.seconds,
    }
}

/// The engine line of harness `h` when this `verify` did not run it (`--no-harnesses`): what
/// the registry states, and that it was not run.
///
/// ```
/// let h = &truecost::claims::harnesses::HARNESSES[0];
/// let e = truecost::claims::harnesses::not_run(h);
/// assert!(e.mode.starts_with("NOT run by this verify (--no-harnesses)"));
/// assert_eq!((e.cases, e.failures), (0, 0));
/// ```
pub fn not_run(h: &Harness) -> EngineRun {
    EngineRun {
        engine: format!("kani harness {}", h.name),
        mode: format!(
            "NOT run by this verify (--no-harnesses); under cargo test the stand-in runs it {}: {}{}; Kani itself not run here",
            h.mode.name(),
            h.domain(),
            if h.should_panic {
                "; states the printed claim and must fail"
            } else {
                ""
            }
        ),
        scope: h.scope(),
        cases: 0,
        failures: 0,
        seconds: 0.0,
    }
}

//! The Kani harnesses of `proofs/` (engine 3; issue 10): what each states, its domain, its
//! bounds, how the stand-in runs it under `cargo test`, and what `cargo kani` adds. The registry
//! ([`super::registry`]) attaches them to the claims' reports.
//!
//! Nothing here is hand-copied without a check: `tests/harnesses.rs` compares every entry with
//! the harness sources (names, files, `#[kani::unwind]`, `#[kani::should_panic]`, the stated
//! sample counts) and the proofs crate's test runs every harness through the stand-in and
//! compares its mode, executions and domain size with the entry.

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
    /// The domain, in bits: `log2` of the number of choice combinations (rounded down), as the
    /// stand-in measures it.
    pub domain_bits: u32,
    /// Executions that fail under the stand-in (seeded, so reproducible): non-zero only for
    /// `should_panic` harnesses, whose printed statement must fail.
    pub failing: u64,
    /// What `cargo kani` would add beyond the stand-in.
    pub kani_adds: &'static str,
}

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
        domain_bits: 368,
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
        domain_bits: 448,
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
        domain_bits: 472,
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
        domain_bits: 632,
        failing: 0,
        kani_adds: "a proof of Lemmas B2 and B3 for every structure, value pair and round of the domain",
    },
    Harness {
        name: "c2_oracle_argmin_cost_is_argmax_reward",
        claim: "C2",
        file: "c2.rs",
        proves: "on any 4-state problem (1-2 moves per non-goal state, symbolic successors, any u8 costs), for C2's seven functionals, truecost's policy-enumeration oracle finds the cost minimisers from x1 to be exactly the reward maximisers",
        unwind: Some(9),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        domain_bits: 99,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "c3_certificate_makes_discounting_avoid_the_goal",
        claim: "C3",
        file: "c3.rs",
        proves: "on any 4-state problem (symbolic successors, 1-2 moves per non-goal state) and any alpha = k/256: under C3's hypotheses truecost's certificate exists whenever its cost K fits a u8, and under it a discount-optimal policy from x1 never reaches the goal (every policy's exact value compared)",
        unwind: Some(37),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        domain_bits: 107,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "c3_example_sides_of_alpha_star_exhaustive_small",
        claim: "C3-example",
        file: "c3.rs",
        proves: "small exhaustive variant: for alpha = k/64 (k any u8, assumed 1..=63), over all 32 policies of the worked example, the discount-optimal policy from 0 avoids the goal iff the printed inequality holds iff 5a^4 - a^3 - a^2 - a - 1 < 0",
        unwind: Some(34),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 256,
        domain_bits: 8,
        failing: 0,
        kani_adds: "nothing beyond the stand-in's complete enumeration except Kani's overflow checks on the i128 arithmetic (done by Rust's overflow checks here too)",
    },
    Harness {
        name: "c4_as_printed_set_is_the_oracles",
        claim: "C4",
        file: "c4.rs",
        proves: "FAILS as expected (the printed claim): on any 4-state problem (x1 = 0, goal 3, 1-2 moves per state, symbolic successors, any u8 costs) with a goal path, at any bonus M = -n/d (n <= 2^16, d <= 2^8), wherever the printed formula is defined, pi* is average-cost optimal (oracle) iff M is in the printed set",
        unwind: Some(22),
        should_panic: true,
        mode: StandinMode::Sampled,
        executions: 4_000,
        domain_bits: 123,
        failing: 28,
        kani_adds: "a failing execution found symbolically; the stand-in found failures by sampling",
    },
    Harness {
        name: "c4_corrected_set_is_the_oracles",
        claim: "C4-corrected",
        file: "c4.rs",
        proves: "on the same problems and bonuses, for every distinct S*: the corrected set of M equals the policy-enumeration oracle's exact set, and pi* is optimal at M iff M is in it",
        unwind: Some(22),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 4_000,
        domain_bits: 123,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_cost_to_go_satisfies_bellman_optimality",
        claim: "solvers: Bellman optimality of G*",
        file: "solvers.rs",
        proves: "on any 4-state problem (1-2 moves per non-goal state, symbolic successors, any u32 costs), truecost's Dijkstra G* satisfies G*(goal) = 0 and G*(x) = min_u l(x,u) + G*(f(x,u))",
        unwind: Some(10),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 5_000,
        domain_bits: 243,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_equals_value_iteration",
        claim: "solvers: Dijkstra = VI",
        file: "solvers.rs",
        proves: "on the same problems (u32 costs), Dijkstra's G* equals synchronous and asynchronous value iteration's",
        unwind: Some(10),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 5_000,
        domain_bits: 243,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "dijkstra_equals_value_iteration_exhaustive_small",
        claim: "solvers: Dijkstra = VI",
        file: "solvers.rs",
        proves: "small exhaustive variant: every 3-state problem with one or two moves per non-goal state (successor and cost in 0..=2): Dijkstra's G* equals synchronous value iteration's",
        unwind: Some(10),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 8_100,
        domain_bits: 14,
        failing: 0,
        kani_adds: "nothing beyond the stand-in's complete enumeration except Kani's overflow and bounds checks",
    },
    Harness {
        name: "exploration_discovers_the_reachable_states_exhaustive_small",
        claim: "solvers: termination of exploration",
        file: "solvers.rs",
        proves: "small exhaustive variant: on every 3-state problem with one or two unit-cost moves per state (successors anywhere), the model-free walk terminates, discovers exactly the states reachable from x1 and applies at most (2 x moves + 1) x 2 actions",
        unwind: Some(16),
        should_panic: false,
        mode: StandinMode::Exhaustive,
        executions: 1_728,
        domain_bits: 12,
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
        domain_bits: 128,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
    Harness {
        name: "units_plus_reports_every_overflow",
        claim: "values: exact arithmetic",
        file: "values.rs",
        proves: "FAILS as expected (overflow is reported): Units::plus on any two finite u64 values whose sum does not fit panics instead of wrapping or reading as +inf",
        unwind: None,
        should_panic: true,
        mode: StandinMode::Sampled,
        executions: 20_000,
        domain_bits: 128,
        failing: 20000,
        kani_adds: "a panicking path found symbolically (Kani's should_panic needs one; the stand-in checks that every sampled execution panics)",
    },
    Harness {
        name: "rational_add_and_mul_are_exact",
        claim: "values: exact arithmetic",
        file: "values.rs",
        proves: "claims::exact::Q addition and multiplication on any i32 fractions: normalised (gcd 1, positive denominator) and exact (cross-multiplied in i128), with no overflow",
        unwind: Some(100),
        should_panic: false,
        mode: StandinMode::Sampled,
        executions: 20_000,
        domain_bits: 128,
        failing: 0,
        kani_adds: SYMBOLIC,
    },
];

/// The engine runs of the harnesses that state claim `id`.
///
/// ```
/// let runs = truecost::claims::harnesses::harness_runs("C1-corrected");
/// assert!(runs.iter().all(|r| r.mode.contains("sampled (20000 executions")));
/// ```
pub fn harness_runs(id: &str) -> Vec<EngineRun> {
    HARNESSES
        .iter()
        .filter(|h| h.claim == id)
        .map(|h| EngineRun {
            engine: format!("kani harness {}", h.name),
            mode: format!(
                "stand-in under cargo test: {} ({} executions) of a 2^{}-choice domain{}; not run by verify; Kani itself not run here",
                h.mode.name(),
                h.executions,
                h.domain_bits,
                if h.should_panic { "; states the printed claim and must fail" } else { "" }
            ),
            scope: format!(
                "proofs/src/{}: {}{}",
                h.file,
                h.proves,
                h.unwind.map_or(String::new(), |u| format!(" (unwind {u})"))
            ),
            cases: h.executions,
            failures: h.failing,
            seconds: 0.0,
        })
        .collect()
}

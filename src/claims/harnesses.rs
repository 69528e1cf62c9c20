//! The Kani harnesses of `proofs/` (engine 3): what each states, its bounds, and what the
//! stand-in executes under `cargo test`. The registry ([`super::registry`]) attaches them to
//! the claims' reports.

use super::EngineRun;

/// A Kani harness of `proofs/` (engine 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Harness {
    /// Function name.
    pub name: &'static str,
    /// The claim or lemma it states.
    pub claim: &'static str,
    /// Source file under `proofs/src/`.
    pub file: &'static str,
    /// What it proves, with its bounds.
    pub proves: &'static str,
    /// `#[kani::unwind]` bound.
    pub unwind: u32,
    /// Whether it is `#[kani::should_panic]` (the statement must fail).
    pub should_panic: bool,
    /// Executions of the stand-in's exhaustive enumeration under `cargo test` (asserted by the
    /// proofs crate's tests; derived by hand from the harness's choice domains).
    pub standin_executions: u64,
    /// Executions that fail (non-zero only for `should_panic` harnesses; derived by hand).
    pub failing_executions: u64,
}

/// Every harness of `proofs/`.
pub const HARNESSES: &[Harness] = &[
    Harness {
        name: "c1_as_printed_fails_at_the_termination_pair",
        claim: "C1",
        file: "c1.rs",
        proves: "FAILS as expected: a lone goal whose termination pair starts at any Q0 in 0..=3 stays there under the rho = 1 rule, so Q != Q* for Q0 != 0",
        unwind: 5,
        should_panic: true,
        standin_executions: 4,
        failing_executions: 3,
    },
    Harness {
        name: "c1_as_printed_fails_on_a_zero_cost_cycle",
        claim: "C1",
        file: "c1.rs",
        proves: "FAILS as expected: state 0 with a zero-cost self-loop and a move of cost 1..=3 to the goal, Q0 in 0..=3, never converges for some choice",
        unwind: 10,
        should_panic: true,
        standin_executions: 48,
        failing_executions: 34,
    },
    Harness {
        name: "c1_corrected_converges_within_the_bound",
        claim: "C1-corrected",
        file: "c1.rs",
        proves: "a 3-state family (0 -> s in {0,1,2} cost 1..=2, 0 -> 1 cost 1..=2, 1 -> goal cost 1..=2), Q0 in 0..=3 on the three move pairs, each of 6 rounds forward or backward (adversary): Q = Q* from the end of round R on",
        unwind: 12,
        should_panic: false,
        standin_executions: 98304,
        failing_executions: 0,
    },
    Harness {
        name: "c2_argmin_cost_is_argmax_reward",
        claim: "C2",
        file: "c2.rs",
        proves: "in every 2-state problem with two moves at state 0 (to 0 or the goal, cost 0..=3), for total, discounted (1/2) and 3-stage total cost (192 executions), the cost minimisers are exactly the reward maximisers",
        unwind: 8,
        should_panic: false,
        standin_executions: 192,
        failing_executions: 0,
    },
    Harness {
        name: "c3_certificate_makes_the_discount_optimal_policy_avoid_the_goal",
        claim: "C3",
        file: "c3.rs",
        proves: "every 3-state structure where state 0 has a self-loop and a move to state 1 or the goal and state 1 one move anywhere: with the goal reachable, the certificate costs (1 on the loop, 5 elsewhere, alpha = 1/2) make the goal-avoiding loop strictly discount-optimal",
        unwind: 8,
        should_panic: false,
        standin_executions: 6,
        failing_executions: 0,
    },
    Harness {
        name: "c3_example_sides_of_alpha_star",
        claim: "C3-example",
        file: "c3.rs",
        proves: "for alpha = k/64 (k: any u8, assumed 1..=63: 256 executions, 193 pruned): over all 32 policies of the worked example (exact integers) the discount-optimal policy from 0 avoids the goal iff the printed inequality holds iff 5a^4 - a^3 - a^2 - a - 1 < 0",
        unwind: 34,
        should_panic: false,
        standin_executions: 256,
        failing_executions: 0,
    },
    Harness {
        name: "c4_printed_formula_fails",
        claim: "C4",
        file: "c4.rs",
        proves: "FAILS as expected: on a fixed 3-state problem with costs scaled by k in 1..=4, the printed threshold a is unchanged while the true threshold scales, so they cannot both be right",
        unwind: 8,
        should_panic: true,
        standin_executions: 4,
        failing_executions: 4,
    },
    Harness {
        name: "c4_corrected_threshold_matches_averages",
        claim: "C4-corrected",
        file: "c4.rs",
        proves: "for a direct goal move (cost 0..=3) and a 2-move detour (costs 0..=3 each), every bonus M in -8..=-1: pi* has the least average cost iff the corrected threshold T(u) says so",
        unwind: 8,
        should_panic: false,
        standin_executions: 64,
        failing_executions: 0,
    },
    Harness {
        name: "dijkstra_cost_to_go_satisfies_bellman_optimality",
        claim: "solvers: Bellman optimality of G*",
        file: "solvers.rs",
        proves: "on every 3-state problem with one or two moves per non-goal state (successor any state, cost 0..=2; 8100 executions), truecost's Dijkstra G* satisfies G*(goal) = 0 and G*(x) = min_u l(x,u) + G*(f(x,u))",
        unwind: 10,
        should_panic: false,
        standin_executions: 8100,
        failing_executions: 0,
    },
    Harness {
        name: "dijkstra_equals_value_iteration",
        claim: "solvers: Dijkstra = VI",
        file: "solvers.rs",
        proves: "on the same problems, Dijkstra's G* equals synchronous and asynchronous value iteration's",
        unwind: 10,
        should_panic: false,
        standin_executions: 8100,
        failing_executions: 0,
    },
    Harness {
        name: "exploration_terminates_and_discovers_every_reachable_move",
        claim: "solvers: termination of exploration",
        file: "solvers.rs",
        proves: "on every 3-state problem with one or two moves per state (successor any state, unit cost), the model-free walk ends within 2 x moves actions and discovers every state reachable from x1",
        unwind: 16,
        should_panic: false,
        standin_executions: 1728,
        failing_executions: 0,
    },
];

/// The engine runs of the harnesses that state claim `id`.
pub fn harness_runs(id: &str) -> Vec<EngineRun> {
    HARNESSES
        .iter()
        .filter(|h| h.claim == id)
        .map(|h| EngineRun {
            engine: format!("kani harness {}", h.name),
            mode: format!(
                "stand-in under cargo test: exhaustive, {} executions{}; not run by verify; Kani itself not run here",
                h.standin_executions,
                if h.should_panic { ", states the printed claim and must fail" } else { "" }
            ),
            scope: format!("proofs/src/{}: {} (unwind {})", h.file, h.proves, h.unwind),
            cases: h.standin_executions,
            failures: h.failing_executions,
            seconds: 0.0,
        })
        .collect()
}

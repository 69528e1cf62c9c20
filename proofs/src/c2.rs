//! Claim C2: cost–reward equivalence.

use crate::Four;

/// The functionals of this harness.
#[derive(Clone, Copy, Debug, PartialEq, Eq, kani::Arbitrary)]
pub enum Functional {
    /// Total cost (`±∞` as `i64::MAX`/`MIN`).
    Total,
    /// Discounted with `α = 1/2`, scaled by 2.
    HalfDiscounted,
    /// Total over the first 3 stages.
    ThreeStages,
}

/// The value of a policy of the 2-state problem whose single move at state 0 has cost `cost`
/// and loops (`to_goal = false`) or reaches the goal 1 (then 0 forever), for stage values
/// multiplied by `sign`.
fn value(f: Functional, cost: i64, to_goal: bool, sign: i64) -> i64 {
    let s = sign * cost;
    match (f, to_goal) {
        (Functional::Total, true) => s,
        (Functional::Total, false) => {
            if s > 0 {
                i64::MAX
            } else if s < 0 {
                i64::MIN
            } else {
                0
            }
        }
        // Scaled by 2: s (then zeros) → 2s; s forever → 2·Σ s/2^k = 4s.
        (Functional::HalfDiscounted, true) => 2 * s,
        (Functional::HalfDiscounted, false) => 4 * s,
        (Functional::ThreeStages, true) => s,
        (Functional::ThreeStages, false) => 3 * s,
    }
}

/// In every 2-state problem whose state 0 has two moves (each to 0 or to the goal, cost
/// `0..=3`), for each functional, the set of cost-minimising policies equals the set of
/// reward-maximising ones (rewards `-l`, evaluated from the negated stages).
#[kani::proof]
#[kani::unwind(8)]
pub fn c2_argmin_cost_is_argmax_reward() {
    let moves: [(bool, Four); 2] = [(kani::any(), kani::any()), (kani::any(), kani::any())];
    let f: Functional = kani::any();
    let cost = [0, 1].map(|i| value(f, moves[i].1.value(), moves[i].0, 1));
    let reward = [0, 1].map(|i| value(f, moves[i].1.value(), moves[i].0, -1));
    let min = cost[0].min(cost[1]);
    let max = reward[0].max(reward[1]);
    for i in 0..2 {
        kani::assert(
            (cost[i] == min) == (reward[i] == max),
            "argmin cost = argmax reward",
        );
    }
}

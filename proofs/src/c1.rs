//! Claim C1: derandomized Q-learning (`ρ = 1`).

use crate::Four;

/// Round-robin `ρ = 1` updates on the 2-state problem "state 0: a self-loop of cost 0 and a
/// move of cost `c` to the goal 1", termination pair of the goal held at 0.
fn zero_cost_cycle_rounds(q_self: i64, q_goal: i64, c: i64, rounds: usize) -> (i64, i64) {
    let (mut s, mut g) = (q_self, q_goal);
    for _ in 0..rounds {
        s = s.min(g); // Q(0,self) <- 0 + min(Q(0,self), Q(0,->1))
        g = c; // Q(0,->1) <- c + Q(1,uT) = c + 0
    }
    (s, g)
}

/// C1 as printed, at the goal's termination pair: the lone goal's pair `Q(g,uT)` is a
/// zero-cost self-loop, so the `ρ = 1` rule keeps any initial value: `Q ≠ Q* = 0` forever when
/// `Q0 ≠ 0`. The statement "converges from any initial value" must fail.
#[kani::proof]
#[kani::unwind(5)]
#[kani::should_panic]
pub fn c1_as_printed_fails_at_the_termination_pair() {
    let q0: Four = kani::any();
    let mut q = q0.value();
    for _ in 0..4 {
        q = q.min(q); // Q(g,uT) <- 0 + min over the goal's pairs = Q(g,uT)
    }
    kani::assert(q == 0, "Q(g,uT) = Q*(g,uT) = 0 after 4 rounds");
}

/// C1 as printed, on a zero-cost cycle: with `Q0(0,self) < c` the values settle at a fixed
/// point below `Q* = c`. Must fail for some choice.
#[kani::proof]
#[kani::unwind(10)]
#[kani::should_panic]
pub fn c1_as_printed_fails_on_a_zero_cost_cycle() {
    let c = match kani::any::<crate::Three>() {
        crate::Three::Zero => 1,
        crate::Three::One => 2,
        crate::Three::Two => 3,
    };
    let a: Four = kani::any();
    let b: Four = kani::any();
    let (s, g) = zero_cost_cycle_rounds(a.value(), b.value(), c, 8);
    kani::assert(s == c && g == c, "Q = Q* after 8 rounds");
}

/// C1-corrected on a 3-state family with positive costs: state 0 has a move to `s ∈ {0,1,2}`
/// with cost `a ∈ {1,2}` and a move to 1 with cost `b ∈ {1,2}`; state 1 moves to the goal 2
/// with cost `c ∈ {1,2}`; `Q0 ∈ 0..=3` on the three move pairs; each of 6 rounds updates the
/// three pairs forward or backward (chosen by the adversary). Then `Q = Q*` at the end of
/// round `R = max(R1, ⌈max Q* / min cost⌉)` and stays there.
#[kani::proof]
#[kani::unwind(12)]
pub fn c1_corrected_converges_within_the_bound() {
    let s = kani::any::<crate::Three>().value();
    let a = if kani::any::<bool>() { 2 } else { 1 };
    let b = if kani::any::<bool>() { 2 } else { 1 };
    let c = if kani::any::<bool>() { 2 } else { 1 };
    let q0: [i64; 3] = [
        kani::any::<Four>().value(),
        kani::any::<Four>().value(),
        kani::any::<Four>().value(),
    ];
    let mut q = q0;
    // Optimal values of this family, by cases (independent of the update rule).
    let g1 = c;
    let via_first = match s {
        1 => a + c,
        2 => a,
        _ => i64::MAX, // a positive-cost self-loop never helps
    };
    let g0 = (b + c).min(via_first);
    let g = [g0, g1, 0i64];
    let star = [a + g[s], b + g1, c];
    // h: fewest moves of an optimal path to the goal.
    let h = [if s == 2 && a == g0 { 1 } else { 2 }, 1, 0];
    let r1 = 1 + h[s].max(h[1]);
    let above = q0[0] >= star[0] && q0[1] >= star[1] && q0[2] >= star[2];
    let min_cost = a.min(b).min(c);
    let qmax = star[0].max(star[1]).max(star[2]);
    let r2 = (qmax + min_cost - 1) / min_cost; // Q0 >= 0, so min(0, min Q0) = 0
    let bound = if above { r1 } else { r1.max(r2) } as usize;
    kani::assert(bound <= 6, "the bound fits the 6 rounds checked");
    for round in 1..=6 {
        let forward: bool = kani::any();
        for k in 0..3 {
            let p = if forward { k } else { 2 - k };
            // successors: pair 0 -> s, pair 1 -> 1, pair 2 -> goal (termination held at 0)
            let min_at = |x: usize, q: &[i64; 3]| match x {
                0 => q[0].min(q[1]),
                1 => q[2],
                _ => 0,
            };
            q[p] = match p {
                0 => a + min_at(s, &q),
                1 => b + min_at(1, &q),
                _ => c,
            };
        }
        if round >= bound {
            kani::assert(q == star, "Q = Q* from the end of round R on");
        }
    }
}

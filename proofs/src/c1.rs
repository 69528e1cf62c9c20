//! Claim C1: derandomized Q-learning (`ρ = 1`), over truecost's own update
//! (`truecost_kernel::claims::qlearning::QProblem::update`).
//!
//! C1-corrected is proved by induction over rounds (the shared argument of `claims::c1` and the
//! SMT engine): the two inductive steps below each take *any* values satisfying the invariant
//! on *any* structure of the family and *one arbitrary fair round*, and re-establish the
//! invariant one level up — a statement about every number of rounds, not about R simulated
//! ones. Family: 3 non-goal states with 2 moves each (successors symbolic), the goal without
//! moves whose termination pair is held at 0 (H0), every state reaching the goal (H1, assumed),
//! `u16` costs, `i32` values (computed in `i64`: no overflow is possible, and Kani checks it).
//! The update only adds and takes minima (no symbolic multiplication), so the 64-bit values cost
//! CBMC adders and comparators, not multipliers.
//!
//! Loops CBMC unrolls (`tests/unwind_bounds.rs` derives each bound from the constants): a round
//! of at most `ROUND + MOVES = 18` updates (unwind 19 for the inductive steps); for C1 as
//! printed, 7 updates per round, 6 rounds and the element-wise round comparison over 7 pairs
//! (unwind 8). Values are compared element by element, never with `==` on `[i64; 24]`: that
//! would become CBMC's `memcmp`, one loop iteration per byte (192).
//!
//! Each harness runs its statement with truecost's `QProblem::update`, which Kani replaces by
//! its proven contract (`#[kani::stub_verified]`, proved by
//! `contracts::update_is_the_rho_one_rule`): the `ρ = 1` rule as a minimum over the successor's
//! pairs. The statements take the update as a parameter ([`Update`]) so that a test can run
//! them against a wrong update and see them fail (`tests/planted_update_bug.rs`).

/// The signature of the `ρ = 1` update the statements run (`QProblem::update` in every harness).
pub type Update = fn(&QProblem, &mut Values, usize);

use truecost_kernel::claims::qlearning::{QProblem, Terminal, Values};

use crate::symbolic::{
    any_round, any_structure, cost_to_go, learner, optimal_steps, optimum, values, MOVES, N,
    TERMINAL,
};

/// **C1-corrected, Part A, inductive step** (costs `≥ 0`, `Q₀ ≥ Q*`). Invariant `I_r`: `Q ≥ Q*`
/// on every pair, and every pair with `h(f(x,u)) ≤ r − 1` is exact. From any values satisfying
/// `I_r` (`r ∈ 0..=N+1`; a value not forced exact is `max(any i32, Q*)`, i.e. any `i32` value
/// `≥ Q*`), one arbitrary fair round (12 freely chosen updates at most — symbolic order, repeats
/// allowed — then any pair missed; `symbolic::any_round`) re-establishes `I_{r+1}` (Lemmas A1,
/// A2). Domain: structure 2^144 × values 2^192 × level 2^8 × round 2^104 = 2^448. CBMC: fixed
/// arrays, loops of at most 18 iterations (unwind 19).
#[kani::proof]
#[kani::unwind(19)]
#[kani::solver(kissat)]
#[kani::stub_verified(truecost_kernel::claims::qlearning::QProblem::update)]
pub fn c1_corrected_round_lifts_the_exact_level() {
    lifts_the_exact_level(QProblem::update);
}

/// The statement of [`c1_corrected_round_lifts_the_exact_level`], run with `update`.
pub fn lifts_the_exact_level(update: Update) {
    let s = any_structure(0);
    let g = cost_to_go(&s);
    kani::assume(g.iter().all(Option::is_some)); // H1
    let h = optimal_steps(&s, &g);
    let star = optimum(&s, &g);
    let r = (kani::any::<u8>() % (N as u8 + 2)) as u32;
    let q = learner(&s, Terminal::HeldAtZero);
    let mut v = values();
    for p in 0..MOVES {
        let raw = kani::any::<i32>() as i64;
        let exact = h[s.to[p]].expect("H1") < r;
        v[p] = if exact { star[p] } else { raw.max(star[p]) };
    }
    let before = v;
    let (order, len) = any_round();
    for k in 0..len {
        update(&q, &mut v, order[k]);
    }
    kani::assert(v[TERMINAL] == 0, "the termination pair stays 0 (H0)");
    let (mut changed, mut lifted) = (false, false);
    for p in 0..MOVES {
        kani::assert(v[p] >= star[p], "Q >= Q* after the round (Lemma A1)");
        if h[s.to[p]].expect("H1") < r + 1 {
            kani::assert(
                v[p] == star[p],
                "pairs with h(f(x,u)) <= r are exact (Lemma A2)",
            );
        }
        changed |= v[p] != before[p];
        lifted |= before[p] > star[p] && v[p] == star[p];
    }
    kani::cover!(changed, "the round changes some value");
    kani::cover!(lifted, "a pair above Q* becomes exact");
    kani::cover!(
        r == N as u32 + 1,
        "the top level: every pair exact before the round"
    );
}

/// **C1-corrected, Part B, inductive step** (every move costs `≥ c ≥ 1`, any `Q₀`). Invariant
/// `J_t`: every pair has `Q ≥ min(Q*, t)`. From any `t` (`i32`) and any values satisfying `J_t`
/// (`max(any i32, min(Q*, t))`), one arbitrary fair round re-establishes `J_{t+c}`, `c` the least
/// move cost (Lemma B1). Domain ≈ 2^(144 + 32 + 192 + 104) = 2^472.
#[kani::proof]
#[kani::unwind(19)]
#[kani::solver(kissat)]
#[kani::stub_verified(truecost_kernel::claims::qlearning::QProblem::update)]
pub fn c1_corrected_round_raises_the_floor_by_c() {
    raises_the_floor_by_c(QProblem::update);
}

/// The statement of [`c1_corrected_round_raises_the_floor_by_c`], run with `update`.
pub fn raises_the_floor_by_c(update: Update) {
    let s = any_structure(1);
    let g = cost_to_go(&s);
    kani::assume(g.iter().all(Option::is_some)); // H1
    let star = optimum(&s, &g);
    let c = s.cost.iter().copied().min().expect("moves");
    let t = kani::any::<i32>() as i64;
    let q = learner(&s, Terminal::HeldAtZero);
    let mut v = values();
    for p in 0..MOVES {
        v[p] = (kani::any::<i32>() as i64).max(star[p].min(t));
    }
    let before = v;
    let (order, len) = any_round();
    for k in 0..len {
        update(&q, &mut v, order[k]);
    }
    let (mut rises, mut tight) = (false, false);
    for p in 0..MOVES {
        kani::assert(
            v[p] >= star[p].min(t + c),
            "J_{t+c}: Q >= min(Q*, t + c) after the round (Lemma B1)",
        );
        rises |= before[p] < star[p] && v[p] > before[p];
        tight |= t + c < star[p] && v[p] < star[p];
    }
    kani::cover!(rises, "a value below Q* rises");
    kani::cover!(tight, "the new floor t + c binds below Q*");
}

/// **C1-corrected, Part B, the sandwich** (costs `≥ 0`): for any values `Q ≤ Q'` (`Q = min(any
/// i32, Q*)`, `Q' = Q + any u32`), after the same arbitrary fair round `Q ≤ Q'` (Lemma B2,
/// monotonicity) and `Q ≤ Q*` (Lemma B3). Domain ≈ 2^(144 + 192 + 192 + 104) = 2^632.
#[kani::proof]
#[kani::unwind(19)]
#[kani::solver(kissat)]
#[kani::stub_verified(truecost_kernel::claims::qlearning::QProblem::update)]
pub fn c1_corrected_round_is_monotone_below_q_star() {
    is_monotone_below_q_star(QProblem::update);
}

/// The statement of [`c1_corrected_round_is_monotone_below_q_star`], run with `update`.
pub fn is_monotone_below_q_star(update: Update) {
    let s = any_structure(0);
    let g = cost_to_go(&s);
    kani::assume(g.iter().all(Option::is_some)); // H1
    let star = optimum(&s, &g);
    let q = learner(&s, Terminal::HeldAtZero);
    let (mut low, mut high) = (values(), values());
    for p in 0..MOVES {
        low[p] = (kani::any::<i32>() as i64).min(star[p]);
        high[p] = low[p] + kani::any::<u32>() as i64;
    }
    let start = low;
    let (order, len) = any_round();
    for k in 0..len {
        update(&q, &mut low, order[k]);
        update(&q, &mut high, order[k]);
    }
    let (mut apart, mut reaches) = (false, false);
    for p in 0..MOVES {
        kani::assert(low[p] <= high[p], "Q <= Q' is preserved (Lemma B2)");
        kani::assert(low[p] <= star[p], "Q <= Q* is preserved (Lemma B3)");
        apart |= low[p] < high[p];
        reaches |= start[p] < star[p] && low[p] == star[p];
    }
    kani::cover!(apart, "Q < Q' strictly somewhere after the round");
    kani::cover!(reaches, "a value below Q* reaches Q*");
}

/// Cyclic rounds simulated by [`c1_as_printed_round_fixed_points_are_optimal`].
pub const PRINTED_ROUNDS: usize = 6;

/// **C1 as printed** (costs `≥ 0`, any `Q₀`, the termination pair updated by the same rule as
/// every pair), over the same wide domains, H1 assumed: it implies that a round of the cyclic
/// order (a fair order) that changes nothing ends at `Q*` — otherwise the cyclic order repeats
/// those values forever. Must fail: a zero-cost self-loop (the termination pair, or a zero-cost
/// cycle) started below `Q*` is such a fixed point. Domain ≈ 2^(144 + 224) = 2^368; 6 rounds.
#[kani::proof]
#[kani::unwind(8)]
#[kani::should_panic]
#[kani::stub_verified(truecost_kernel::claims::qlearning::QProblem::update)]
pub fn c1_as_printed_round_fixed_points_are_optimal() {
    as_printed_round_fixed_points_are_optimal(QProblem::update);
}

/// The statement of [`c1_as_printed_round_fixed_points_are_optimal`], run with `update`.
pub fn as_printed_round_fixed_points_are_optimal(update: Update) {
    let s = any_structure(0);
    let g = cost_to_go(&s);
    kani::assume(g.iter().all(Option::is_some)); // H1 (the failure does not need it absent)
    let star = optimum(&s, &g);
    let q = learner(&s, Terminal::Updated);
    let mut v = values();
    for p in 0..=TERMINAL {
        v[p] = kani::any::<i32>() as i64;
    }
    for _round in 0..PRINTED_ROUNDS {
        let before = v;
        for p in 0..=TERMINAL {
            update(&q, &mut v, p);
        }
        // Element-wise over the 7 pairs in use (not `v == before`: see the module comment).
        let (mut unchanged, mut optimal, mut below) = (true, v[TERMINAL] == 0, false);
        for p in 0..=TERMINAL {
            unchanged &= v[p] == before[p];
        }
        for p in 0..MOVES {
            optimal &= v[p] == star[p];
            below |= v[p] < star[p];
        }
        kani::cover!(unchanged && optimal, "a round that changes nothing at Q*");
        kani::cover!(
            unchanged && below,
            "a fixed point below Q* (the counterexample)"
        );
        if unchanged {
            kani::assert(optimal, "a round that changes nothing ends at Q*");
        }
    }
}

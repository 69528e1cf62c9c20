//! Issue 10: every `#[kani::unwind(N)]` is at least the largest iteration count of a loop the
//! harness runs, plus one — derived here from the constants the harnesses use (imported, never
//! copied) and, for Euclid's loop in `claims::exact::Q::new`/`Q::mul`, from Lamé's theorem on
//! the operands' magnitudes. (An insufficient bound would not make Kani unsound — its unwinding
//! assertions, on by default, report it as a failure — but the harness would then prove nothing.)
//!
//! What this does not derive: loops inside the standard library (`Vec` growth, slice equality,
//! iterator adaptors), each bounded by the same sizes as the loops that drive them.

use std::collections::BTreeMap;
use std::path::Path;

use truecost_kernel::claims::c2::functionals;
use truecost_kernel::claims::oracle::policies;
use truecost_kernel::claims::tiny::{Tiny, TinyMove};
use truecost_proofs::c1::PRINTED_ROUNDS;
use truecost_proofs::c3::EXAMPLE_POLICIES;
use truecost_proofs::solvers::STATES;
use truecost_proofs::symbolic::{MOVES, ROUND, TERMINAL, TINY_STATES};

/// `#[kani::unwind(N)]` of every harness in `proofs/src/` (`None`: no attribute).
fn unwinds() -> BTreeMap<String, Option<u64>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(dir).expect("proofs/src") {
        let text = std::fs::read_to_string(entry.expect("entry").path()).expect("source");
        let mut current: Option<Option<u64>> = None;
        for line in text.lines().map(str::trim) {
            if line == "#[kani::proof]" {
                current = Some(None);
            } else if let (Some(u), Some(rest)) =
                (current.as_mut(), line.strip_prefix("#[kani::unwind("))
            {
                *u = Some(rest.trim_end_matches(")]").parse().expect("a number"));
            } else if let Some(rest) = line.strip_prefix("pub fn ") {
                if let Some(u) = current.take() {
                    out.insert(rest.split('(').next().expect("name").to_string(), u);
                }
            }
        }
    }
    out
}

/// Lamé: Euclid's loop (`while b != 0 { (a, b) = (b, a % b) }`) on two integers whose smaller
/// magnitude is at most `m` runs at most `1 + max{k : F(k+1) <= m}` times (the `1` for a first
/// iteration that only swaps them).
fn euclid_iterations(m: u128) -> u64 {
    // max{k : F(k+1) <= m} = the number of Fibonacci numbers F(2) = 1, F(3) = 2, … at most m.
    let (mut count, mut f, mut next) = (0u64, 1u128, 2u128);
    while f <= m {
        count += 1;
        (f, next) = (next, f + next);
    }
    1 + count
}

/// The iteration count of Euclid's loop on `(a, b)`, run here independently of the kernel.
fn euclid(mut a: u128, mut b: u128) -> u64 {
    let mut n = 0;
    while b != 0 {
        (a, b) = (b, a % b);
        n += 1;
    }
    n
}

#[test]
fn lame_bound_is_attained_and_never_exceeded() {
    // Consecutive Fibonacci numbers are the worst case: the bound is exact there.
    let (mut a, mut b) = (1u128, 2u128);
    while b < 1 << 40 {
        assert_eq!(euclid(a, b), euclid_iterations(a), "F = {a}");
        (a, b) = (b, a + b);
    }
    for m in 1..3000u128 {
        for x in 1..40u128 {
            assert!(euclid(x * 37 + 1, m) <= euclid_iterations(m.min(x * 37 + 1)));
        }
    }
}

/// The largest number of policies `claims::oracle::policies` enumerates on the C2–C4 harness
/// structures: every non-goal state with the maximum 2 moves.
fn max_policies() -> u64 {
    let mut t = Tiny::empty(TINY_STATES);
    for x in 0..TINY_STATES - 1 {
        t.deg[x] = 2;
        t.moves[x][0] = TinyMove { to: 0, cost: 1 };
        t.moves[x][1] = TinyMove {
            to: (TINY_STATES - 1) as u8,
            cost: 1,
        };
    }
    policies(&t, true).len() as u64
}

#[test]
fn every_unwind_covers_its_loops() {
    let u = unwinds();
    let need = |name: &str, iterations: u64| {
        let n = u[name].unwrap_or_else(|| panic!("{name} has no #[kani::unwind]"));
        assert!(
            n > iterations,
            "{name}: unwind {n}, a loop runs {iterations} times"
        );
    };
    let moves = MOVES as u64;
    // C1's inductive steps: a round of at most ROUND free updates plus the missed pairs.
    for h in [
        "c1_corrected_round_lifts_the_exact_level",
        "c1_corrected_round_raises_the_floor_by_c",
        "c1_corrected_round_is_monotone_below_q_star",
    ] {
        need(h, (ROUND + MOVES) as u64);
    }
    // C1 as printed: PRINTED_ROUNDS cyclic rounds over every pair, the termination pair included.
    need(
        "c1_as_printed_round_fixed_points_are_optimal",
        (PRINTED_ROUNDS as u64).max(TERMINAL as u64 + 1).max(moves),
    );
    // C2: every functional, every policy; its Q constants (1/2, 9/10) are tiny.
    let c2 = (functionals().len() as u64).max(max_policies());
    need(
        "c2_oracle_argmin_cost_is_argmax_reward",
        c2.max(euclid_iterations(10)),
    );
    // C3's certificate: the policies, and Q on α = k/256 alone: operands below 256^3.
    need(
        "c3_certificate_makes_discounting_avoid_the_goal",
        max_policies().max(euclid_iterations(256u128.pow(3))),
    );
    need(
        "c3_example_sides_of_alpha_star_exhaustive_small",
        EXAMPLE_POLICIES as u64,
    );
    // C4: M = −(n+1)/(d+1) (d < 2^8) and the printed A(u): S(u)·L*/(S*·L(u)) with L ≤ 3·255
    // over at most TINY_STATES path states, times (1 − S(u)/S*): denominators ≤ S·S·L.
    let s = TINY_STATES as u128;
    let l = (s - 1) * u128::from(u8::MAX);
    let c4 = max_policies().max(euclid_iterations(256).max(euclid_iterations(s * s * l)));
    need("c4_corrected_set_is_the_oracles", c4);
    need("c4_as_printed_set_is_the_oracles", c4);
    // The planners on STATES nodes with at most 2 moves each: value iteration ends within
    // STATES + 1 sweeps; Dijkstra pops at most one entry per improvement (≤ edges + 1).
    let edges = 2 * (STATES as u64 - 1);
    for h in [
        "dijkstra_cost_to_go_satisfies_bellman_optimality",
        "dijkstra_equals_value_iteration",
        "dijkstra_equals_value_iteration_exhaustive_small",
    ] {
        need(h, (STATES as u64 + 1).max(edges + 1));
    }
    // The exploration walk takes at most 2·|moves| steps (3 states, 2 moves each).
    need(
        "exploration_discovers_the_reachable_states_exhaustive_small",
        2 * 6,
    );
    // Q on i32 fractions: denominators |d1·d2| ≤ 2^62 (the harness's own gcd loop too).
    need("rational_add_and_mul_are_exact", euclid_iterations(1 << 62));
    // The Units harnesses have no loop (Units::plus is straight-line code).
    for h in [
        "units_plus_is_exact_when_it_fits",
        "units_plus_reports_every_overflow",
    ] {
        assert_eq!(u[h], None, "{h}");
    }
    assert_eq!(u.len(), 16, "every harness is covered above");
}

/// The bounds above are what the harnesses need, not loose: with C4's old unwind 9, the bonus
/// `M = −144/233` alone (within its domain) runs Euclid's loop 12 times.
#[test]
fn the_old_c4_bound_was_too_small() {
    assert_eq!(euclid(144, 233), 12);
    assert!(euclid(144, 233) >= 9);
    assert_eq!(euclid_iterations(256), 13);
}

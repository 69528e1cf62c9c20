//! Every `#[kani::unwind(N)]` bounds every loop CBMC unrolls in its harness: `N` is at least the
//! largest iteration count of such a loop, plus one. An insufficient bound does not make Kani
//! unsound — its unwinding assertions (on by default) fail — but it is a failure of the harness
//! under `cargo kani`, even of a `should_panic` one (only an assertion failure is expected).
//!
//! What CBMC unrolls, and how each count is derived here (from the constants the harnesses use,
//! imported, never copied):
//! * the harness's loops and the kernel's (rounds, sweeps, heap pops, the walk, Euclid's loop —
//!   by Lamé's theorem on the operands' magnitudes);
//! * the standard library's loops: `vec![x; k]` fills `k` slots one by one unless `x` is zero
//!   (then it is one zeroed allocation); a `BinaryHeap` push or pop sifts at most
//!   `⌊log₂ len⌋` levels; iterator adaptors (`all`, `position`, `fold`, `sum`, `collect`,
//!   `windows`, `zip`) loop once per item;
//! * CBMC's C library: `==` on arrays or slices of integers is `memcmp`, **one iteration per
//!   byte** ([`memcmp_iterations`]); `memcpy`, `memmove`, `memset` and therefore `realloc` (Vec
//!   and BinaryHeap growth) are single array operations there, no loop; a panic is an
//!   assertion (Kani replaces the panic functions), so no formatting loop runs.
//!
//! The C1 and solver harnesses compare no whole arrays (`tests/array_comparisons.rs` scans for
//! it), so no `memcmp` runs there; their lists below are complete, and each unwind is exactly
//! the largest count plus one (every extra unrolling is CBMC time). The value-type and C2–C4
//! harnesses keep their own derivation (their Euclid bounds come from their integer widths).

use std::collections::BTreeMap;
use std::path::Path;

use truecost_kernel::claims::c2::functionals;
use truecost_kernel::claims::oracle::policies;
use truecost_kernel::claims::tiny::{Tiny, TinyMove};
use truecost_kernel::model::Graph;
use truecost_kernel::solvers::dijkstra;
use truecost_kernel::solvers::value_iteration::{value_iteration, Schedule};
use truecost_kernel::value::Units;
use truecost_proofs::c1::PRINTED_ROUNDS;
use truecost_proofs::c3::EXAMPLE_POLICIES;
use truecost_proofs::solvers::{SLOTS, STATES};
use truecost_proofs::symbolic::{D, MOVES, N, ROUND, TERMINAL, TINY_STATES};

/// `#[kani::unwind(N)]` of every harness in `proofs/src/` (`#[kani::proof]` and
/// `#[kani::proof_for_contract(…)]`; `None`: no attribute).
fn unwinds() -> BTreeMap<String, Option<u64>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = BTreeMap::new();
    for entry in std::fs::read_dir(dir).expect("proofs/src") {
        let text = std::fs::read_to_string(entry.expect("entry").path()).expect("source");
        let mut current: Option<Option<u64>> = None;
        for line in text.lines().map(str::trim) {
            if line == "#[kani::proof]" || line.starts_with("#[kani::proof_for_contract(") {
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

/// Iterations of CBMC's `memcmp` for `==` on `elements` integers of type `T`: one per byte.
fn memcmp_iterations<T>(elements: usize) -> u64 {
    (elements * std::mem::size_of::<T>()) as u64
}

/// Levels a binary heap of at most `len` entries sifts through on a push or a pop.
fn heap_levels(len: u64) -> u64 {
    u64::from(len.max(1).ilog2())
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

/// One loop CBMC unrolls in a harness: what it is and how often it runs at most.
type Loop = (&'static str, u64);

/// The loops of the C1 harnesses common to all four: the structure, its oracle (`symbolic`),
/// and the learner truecost's update runs on.
fn c1_common() -> Vec<Loop> {
    let (n, moves) = (N as u64, MOVES as u64);
    vec![
        ("any_structure: one draw per move pair", moves),
        ("cost_to_go / optimal_steps: N Bellman-Ford rounds", n),
        (
            "cost_to_go / optimal_steps: every move pair per round",
            moves,
        ),
        ("optimum: every move pair", moves),
        (
            "learner: vec![None; MOVES + 1] (Option<i64> is not zero-filled)",
            moves + 1,
        ),
        ("learner: first pair of every state", n + 1),
        ("g.iter().all(Option::is_some) (H1)", n + 1),
        // `pairs` is `Vec::with_capacity(MOVES + 1)` and gets MOVES + 1 pushes: no growth.
        (
            "QProblem::update: min over the successor's pairs",
            D.max(1) as u64,
        ),
        ("the harness's element-wise checks", moves),
    ]
}

/// The loops of C1-corrected's inductive steps: [`c1_common`] and one arbitrary fair round.
fn c1_corrected() -> Vec<Loop> {
    let mut l = c1_common();
    l.extend([
        ("values: one draw per move pair", MOVES as u64),
        ("any_round: the free part's draws", ROUND as u64),
        ("any_round: the missed pairs appended", MOVES as u64),
        (
            "the round: free updates plus missed pairs",
            (ROUND + MOVES) as u64,
        ),
        ("Part B: the least move cost (iter().min())", MOVES as u64),
    ]);
    l
}

/// The loops of C1 as printed: [`c1_common`] and its cyclic rounds.
fn c1_printed() -> Vec<Loop> {
    let pairs = TERMINAL as u64 + 1;
    let mut l = c1_common();
    l.extend([
        ("initial values: every pair", pairs),
        ("cyclic rounds", PRINTED_ROUNDS as u64),
        (
            "one cyclic round: every pair, the termination pair included",
            pairs,
        ),
        ("the round's element-wise comparison (not memcmp)", pairs),
    ]);
    l
}

/// The loops of the Dijkstra harnesses on `n` states with at most `m` moves (two slots per
/// non-goal state), value iteration included when `vi`.
fn dijkstra_loops(n: u64, m: u64, vi: bool) -> Vec<Loop> {
    let pushes = 1 + m; // the goal, then one per strict improvement: at most one per move
    let mut l = vec![
        ("the problem's draws: two slots per non-goal state", m),
        ("Problem::graph: the states, two slots each", n),
        ("from_adjacency: the rows and their moves", n.max(m)),
        (
            "check_rows / reverse_partners / in_edges: per node and per move",
            n.max(m),
        ),
        (
            "vec![NO_PARTNER; m], vec![u32::MAX; n], vec![+inf; n] fills",
            n.max(m),
        ),
        ("Dijkstra: heap pops (every pushed entry once)", pushes),
        ("Dijkstra: moves into the popped node", m),
        ("BinaryHeap push / pop: sift levels", heap_levels(pushes)),
        (
            "greedy policy: BFS queue, tight moves, first tight move",
            n.max(m),
        ),
        ("the oracle: n - 1 Bellman-Ford rounds", n - 1),
        ("the oracle: every slot per round", m),
        (
            "the policy followed from every state: at most n - 1 moves",
            n - 1,
        ),
    ];
    if vi {
        l.push(("value iteration: sweeps (at most n + 1)", n + 1));
        l.push(("value iteration: rows per sweep", n));
    }
    l
}

/// The loops of the exploration harness on `n` states with at most `m` moves.
fn exploration_loops(n: u64, m: u64) -> Vec<Loop> {
    vec![
        ("the harness's reachability: n - 1 rounds of n states", n),
        (
            "the walk: a step forward per move taken, a step back per step forward and start",
            2 * m + 1,
        ),
        ("Walk::new / from_csr_paired fills: per move", m),
        (
            "Graph::from_csr_paired's debug check, element-wise (not memcmp)",
            m,
        ),
        ("finish: per discovered node", n),
    ]
}

/// Asserts that `unwind(name)` exceeds every loop; `exact`: and is the largest count plus one.
fn check(u: &BTreeMap<String, Option<u64>>, name: &str, loops: &[Loop], exact: bool) {
    let n = u
        .get(name)
        .unwrap_or_else(|| panic!("no harness {name} in proofs/src"))
        .unwrap_or_else(|| panic!("{name} has no #[kani::unwind]"));
    let (what, most) = loops
        .iter()
        .copied()
        .max_by_key(|&(_, k)| k)
        .expect("loops");
    assert!(n > most, "{name}: unwind {n}, but {what} runs {most} times");
    if exact {
        assert_eq!(n, most + 1, "{name}: the longest loop is {what} ({most})");
    }
}

/// The harnesses of `c1.rs` and `solvers.rs`.
#[test]
fn c1_and_solver_unwinds_cover_their_loops() {
    let u = unwinds();
    for h in [
        "c1_corrected_round_lifts_the_exact_level",
        "c1_corrected_round_raises_the_floor_by_c",
        "c1_corrected_round_is_monotone_below_q_star",
    ] {
        check(&u, h, &c1_corrected(), true);
    }
    check(
        &u,
        "c1_as_printed_round_fixed_points_are_optimal",
        &c1_printed(),
        true,
    );
    let (n, m) = (STATES as u64, SLOTS as u64);
    check(
        &u,
        "dijkstra_cost_to_go_satisfies_bellman_optimality",
        &dijkstra_loops(n, m, false),
        true,
    );
    check(
        &u,
        "dijkstra_equals_value_iteration",
        &dijkstra_loops(n, m, true),
        true,
    );
    // The small variant: 3 states, two non-goal states with at most 2 moves.
    check(
        &u,
        "dijkstra_equals_value_iteration_exhaustive_small",
        &dijkstra_loops(3, 4, true),
        true,
    );
    // Exploration: 3 states, each with 1 or 2 moves.
    check(
        &u,
        "exploration_discovers_the_reachable_states_exhaustive_small",
        &exploration_loops(3, 6),
        true,
    );
}

/// The counts the Dijkstra and value-iteration entries rely on hold on truecost's own planners:
/// on every problem of the small exhaustive family and on many 4-state problems with few
/// distinct costs (many ties, zero-cost cycles), Dijkstra pops at most `1 + m` entries and value
/// iteration sweeps at most `n + 1` times.
#[test]
fn planner_loop_counts_stay_within_the_audit() {
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut draw = |k: u64| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed % k
    };
    let (mut most_pops, mut most_sweeps) = (0, 0);
    for case in 0..40_000 {
        let n = if case < 20_000 { 3 } else { STATES };
        let mut adjacency: Vec<Vec<(usize, Units)>> = vec![Vec::new(); n];
        for list in adjacency.iter_mut().take(n - 1) {
            for _ in 0..1 + draw(2) {
                list.push((draw(n as u64) as usize, Units(draw(3))));
            }
        }
        let m = adjacency.iter().map(Vec::len).sum::<usize>() as u64;
        let g = Graph::from_adjacency(adjacency, 0, &[n - 1], (0..n).collect(), ());
        let pops = dijkstra::to_goals(&g).iterations;
        assert!(pops <= 1 + m, "case {case}: {pops} pops, {m} moves");
        for schedule in [Schedule::Synchronous, Schedule::Asynchronous] {
            let sweeps = value_iteration(&g, schedule, None).iterations;
            assert!(sweeps <= n as u64 + 1, "case {case}: {sweeps} sweeps");
            most_sweeps = most_sweeps.max(sweeps);
        }
        most_pops = most_pops.max(pops);
    }
    // The bounds are reached, so the unwinds derived from them are not loose.
    assert_eq!(most_pops, 1 + SLOTS as u64);
    assert_eq!(most_sweeps, STATES as u64);
}

/// Why whole-array `==` is banned from the harnesses: the comparisons C1 as printed
/// (`[i64; 24]`) and the exploration's debug check (`Vec<u32>` of up to 6 moves) made needed
/// more unrollings of `memcmp` than their unwinds (8, 16) allowed.
#[test]
fn whole_array_comparisons_need_one_unrolling_per_byte() {
    use truecost_kernel::claims::qlearning::MAX_PAIRS;
    assert_eq!(memcmp_iterations::<i64>(MAX_PAIRS) + 1, 193);
    assert!(memcmp_iterations::<i64>(MAX_PAIRS) >= 8);
    assert_eq!(memcmp_iterations::<u32>(6) + 1, 25);
    assert!(memcmp_iterations::<u32>(6) >= 16);
    assert_eq!(heap_levels(7), 2);
    assert_eq!(heap_levels(1), 0);
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

/// The value-type and C2–C4 harnesses: the policies, the functionals and Euclid's loop in
/// `claims::exact::Q` on the operand magnitudes their integer widths allow.
#[test]
fn value_and_claim_unwinds_cover_their_loops() {
    let u = unwinds();
    // C2: every functional, every policy; its Q constants (1/2, 9/10) are tiny.
    let c2 = (functionals().len() as u64).max(max_policies());
    check(
        &u,
        "c2_oracle_argmin_cost_is_argmax_reward",
        &[(
            "functionals, policies, Euclid",
            c2.max(euclid_iterations(10)),
        )],
        false,
    );
    // C3's certificate: the policies, and Euclid's loop only on the concrete α values
    // (1/16, 1/2, 2/3, 9/10): operands at most 1000.
    check(
        &u,
        "c3_certificate_makes_discounting_avoid_the_goal",
        &[(
            "policies, Euclid",
            max_policies().max(euclid_iterations(1000)),
        )],
        false,
    );
    check(
        &u,
        "c3_example_sides_of_alpha_star_exhaustive_small",
        &[("the example's policies", EXAMPLE_POLICIES as u64)],
        false,
    );
    // C4-corrected (`Q<i16>`, the printed formula skipped): the policies, goal paths and
    // cycles (at most 8 each); Euclid's loop (`lowest_terms`, replaced by its contract; were it
    // run) with the smaller operand at most 8 (the bonus's
    // denominator d <= 8 and the path-count denominators S(u) - S* < 4).
    check(
        &u,
        "c4_corrected_set_is_the_oracles",
        &[("policies, Euclid", max_policies().max(euclid_iterations(8)))],
        false,
    );
    // C4 as printed (`Q<i16>` only): every Euclid loop is `lowest_terms`', replaced by its
    // contract; the policies, goal paths and cycles as in C4-corrected.
    check(
        &u,
        "c4_as_printed_set_is_the_oracles",
        &[("policies", max_policies())],
        false,
    );
    // Q<i16> with `lowest_terms` replaced by its contract: no Euclid loop; the harness checks
    // its two results (the sum and the product) in a loop.
    check(
        &u,
        "rational_add_and_mul_are_exact",
        &[("the two results", 2)],
        true,
    );
    // The Units harnesses have no loop (Units::plus is straight-line code).
    for h in [
        "units_plus_is_exact_when_it_fits",
        "units_plus_reports_every_overflow",
    ] {
        assert_eq!(u[h], None, "{h}");
    }
    assert_eq!(
        u.len(),
        16 + CONTRACT_HARNESSES.len(),
        "every harness is audited in one of the three tests"
    );
}

/// The contract proofs of `contracts.rs`.
const CONTRACT_HARNESSES: [&str; 6] = [
    "gcd_divides_both",
    "lowest_terms_has_a_bezout_witness",
    "checked_add_is_exact",
    "checked_mul_is_exact",
    "units_checked_plus_is_exact",
    "update_is_the_rho_one_rule",
];

/// The contract proofs: the extended Euclid loop on 16-bit magnitudes in `lowest_terms`' own
/// proof (its remainders are Euclid's, `r₀ − q·r₁ = r₀ mod r₁`, so Lamé's bound is its count),
/// and the update harness's frame check over the values. `gcd`, `checked_add` and
/// `checked_mul` are proved with `lowest_terms` replaced by its contract: no loop of theirs,
/// and the clauses are loop-free (`tests/feasibility.rs`); the default unwind of
/// `proofs/Cargo.toml` (16) covers the clauses' 4- and 6-element array maps.
#[test]
fn contract_unwinds_cover_their_loops() {
    use truecost_kernel::claims::qlearning::MAX_PAIRS;
    let u = unwinds();
    let euclid16 = euclid_iterations(i16::MAX as u128);
    assert_eq!(euclid16, 23);
    check(
        &u,
        "lowest_terms_has_a_bezout_witness",
        &[("extended Euclid on i16 magnitudes", euclid16)],
        true,
    );
    for h in [
        "gcd_divides_both",
        "checked_add_is_exact",
        "checked_mul_is_exact",
        "units_checked_plus_is_exact",
    ] {
        assert_eq!(u[h], None, "{h}: no loop");
    }
    let mut update = c1_common();
    update.extend([
        ("initial values: every pair", TERMINAL as u64 + 1),
        ("the frame check: every value", MAX_PAIRS as u64),
    ]);
    check(&u, "update_is_the_rho_one_rule", &update, true);
}

/// The check rejects an unwind below a loop's count and, where exactness is asked, one above
/// the count plus one.
#[test]
fn a_planted_unwind_too_small_or_loose_is_rejected() {
    let planted: BTreeMap<String, Option<u64>> = [
        ("too_small".to_string(), Some(12)),
        ("loose".to_string(), Some(40)),
        ("none".to_string(), None),
    ]
    .into();
    let loops: [Loop; 2] = [("a round", 18), ("a sweep", 5)];
    let run = |name: &'static str, exact: bool| {
        let p = planted.clone();
        std::panic::catch_unwind(move || check(&p, name, &loops, exact))
    };
    assert!(run("too_small", false).is_err());
    assert!(run("loose", false).is_ok());
    assert!(run("loose", true).is_err());
    assert!(run("none", false).is_err());
}

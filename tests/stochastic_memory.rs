//! `memory_estimate` (the estimate behind `solve --max-memory`) against the
//! heap actually used: this test binary counts every allocation (a global allocator around the
//! system one) and records the peak of the live bytes while a built problem is held and solved
//! by `optimum`, and — for `all_values` — every exact value is reduced and printed as JSON text, as
//! `solve --format json` does. The estimate's documented parts are a 16 MiB base for the process
//! (code, allocator, the parsed file's leftovers: not heap allocated by the solve) plus the
//! heap of the solve, so
//!
//! * the whole estimate must be at least the measured heap peak (`--max-memory` refuses before
//!   a run that would exceed it, not after), and
//! * the estimate without the base must be within a factor of the peak (`[0.9, 2]`, measured
//!   1.03–1.72 on 3 Dec 2026) on problems large enough for the solve's own memory to dominate —
//!   an estimate far above would refuse runs that fit, far below would let runs past the limit.
//!   (This test found the problem's own lists counted at 48 bytes an outcome where they hold
//!   119–152: on a complete graph of 80 states the whole estimate was below the peak.)
//!
//! The shapes are chosen so that each part of the estimate dominates somewhere: square grids
//! (a wide band, many lifting steps and long numerators), thin grids (band width 5–7, where the
//! per-unknown vectors weigh more), complete graphs (every action with an outcome per state:
//! the problem's own lists dominate), both noise models, γ from 0.5 to
//! 0.999999 (few or many lifted bits), with and without the printed values. Everything runs in
//! one test and on a rayon pool of two threads, so no other test's allocations and no machine's
//! core count change the peak.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::sync::Mutex;

mod common;
use common::stochastic_file;

use truecost::algebra::linear::{BandOrdering, SparseSystem};
use truecost::model::{Move, Problem};
use truecost::stochastic::benchmark::cost_grid;
use truecost::stochastic::policy_iteration::{memory_estimate, optimum, problem_bytes};
use truecost::stochastic::{decimal, NoiseModel, Predictability, StochasticProblem};
use truecost::value::parse_rational;

/// Counts live heap bytes and their peak.
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// One test at a time: the tests of this binary run on parallel threads, and every
/// allocation counts.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn exclusive() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

// SAFETY: every call is forwarded unchanged to the system allocator; the counters only observe.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let size = chunk(layout.size());
            let live = LIVE.fetch_add(size, Relaxed) + size;
            PEAK.fetch_max(live, Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, p: *mut u8, layout: Layout) {
        unsafe { System.dealloc(p, layout) };
        LIVE.fetch_sub(chunk(layout.size()), Relaxed);
    }
}

/// The memory an allocation of `size` bytes takes from glibc's malloc: a header of 8 bytes,
/// rounded up to 16, at least 32 (the exact rationals' one-limb numbers are 8-byte requests
/// that take 32).
fn chunk(size: usize) -> usize {
    (size + 8).next_multiple_of(16).max(32)
}

#[global_allocator]
static COUNTING: Counting = Counting;

/// The process base of the estimate (the `BASE_BYTES` of its documentation: 16 MiB).
const BASE: u64 = 16 << 20;

/// The heap peak, above what was live before the problem was built, of solving it with
/// `optimum` and (with `all_values`) printing every value as `solve --format json` does; and
/// the estimate. The problem's own memory counts (it is held throughout the solve), the
/// transient peak of building it does not (the estimate is made after building, as `solve`
/// does before it refuses or starts).
fn measure(
    deterministic: &Problem,
    noise: NoiseModel,
    gamma: &str,
    all_values: bool,
) -> (u64, u64) {
    let gamma = Predictability::parse(gamma).unwrap();
    let before = LIVE.load(Relaxed);
    let problem = StochasticProblem::from_deterministic(deterministic, noise, &gamma).unwrap();
    PEAK.store(LIVE.load(Relaxed), Relaxed);
    let estimate = memory_estimate(&problem, all_values).bytes;
    let o = optimum(&problem).unwrap();
    if all_values {
        let values: Vec<(String, String)> = o
            .cost_to_go_all()
            .iter()
            .map(|v| (v.to_string(), decimal(v, 20)))
            .collect();
        let json = serde_json::to_string(&values).unwrap();
        assert!(json.len() > 10 * values.len());
    }
    let peak = (PEAK.load(Relaxed) - before) as u64;
    (peak, estimate)
}

/// A problem on `n` states with goal `n − 1` (no moves) and the moves `x → successors(x)`
/// elsewhere, costs 1–5.
fn graph(n: usize, successors: impl Fn(usize) -> Vec<usize>) -> Problem {
    let moves = (0..n)
        .map(|x| {
            if x == n - 1 {
                return Vec::new();
            }
            successors(x)
                .into_iter()
                .map(|y| Move {
                    successor: y,
                    cost: parse_rational(&(1 + (7 * x + 3 * y) % 5).to_string()).unwrap(),
                })
                .collect()
        })
        .collect();
    Problem::new(moves, 0, vec![n - 1]).unwrap()
}

/// The complete graph on `n` states: every state has `n − 1` moves, so every action has `n`
/// outcomes and the problem's own lists outweigh the solve.
fn complete(n: usize) -> Problem {
    graph(n, |x| (0..n).filter(|&y| y != x).collect())
}

/// A chain `0 → 1 → … → n − 1`: one action of two outcomes (the move and stay) per state,
/// where the actions weigh most against the outcomes.
fn chain(n: usize) -> Problem {
    graph(n, |x| vec![x + 1])
}

#[test]
fn memory_estimate_brackets_the_measured_heap_peak() {
    let _alone = exclusive();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let grid = |rows, cols| {
        (
            format!("grid {rows}x{cols}"),
            cost_grid(rows, cols, 1).unwrap(),
        )
    };
    let shapes = [
        (grid(20, 20), NoiseModel::Paper, "0.99"),
        (grid(30, 30), NoiseModel::Reference, "0.999"),
        (grid(40, 40), NoiseModel::Paper, "0.5"),
        (grid(20, 20), NoiseModel::Paper, "0.999999"),
        (grid(3, 700), NoiseModel::Paper, "0.5"),
        (grid(2, 1000), NoiseModel::Reference, "0.5"),
        (grid(2, 300), NoiseModel::Paper, "0.999"),
        (
            ("complete 30".into(), complete(30)),
            NoiseModel::Paper,
            "0.9",
        ),
        (
            ("complete 60".into(), complete(60)),
            NoiseModel::Reference,
            "0.99",
        ),
    ];
    for ((name, problem), noise, gamma) in &shapes {
        for all_values in [false, true] {
            let (peak, estimate) = pool.install(|| measure(problem, *noise, gamma, all_values));
            let case = format!(
                "{name} {} γ={gamma} all_values={all_values}: heap peak {peak} B, estimate {estimate} B",
                noise.name()
            );
            assert!(peak <= estimate, "{case}: the estimate is below the peak");
            let ratio = (estimate - BASE) as f64 / peak as f64;
            assert!(
                (0.9..=2.0).contains(&ratio),
                "{case}: the solve's part of the estimate is {ratio:.2} × the peak"
            );
        }
    }
}

#[test]
fn the_problem_s_part_bounds_what_the_problem_holds() {
    let _alone = exclusive();
    // What a built problem holds on the heap (live bytes after building, less before) against
    // `problem_bytes`: never below, at most 1.5 times (measured 1.15–1.21 on 3 Dec 2026; before
    // the problem's lists were allocated at their final length, a 60×60 grid held 1.75 times what a
    // 40×40 one holds per outcome).
    let shapes = [
        ("chain 5000", chain(5000)),
        ("chain 300", chain(300)),
        ("grid 40x40", cost_grid(40, 40, 1).unwrap()),
        ("grid 60x60", cost_grid(60, 60, 1).unwrap()),
        ("grid 3x700", cost_grid(3, 700, 1).unwrap()),
        ("complete 40", complete(40)),
    ];
    let gamma = Predictability::parse("0.9").unwrap();
    for (name, deterministic) in &shapes {
        for noise in [NoiseModel::Paper, NoiseModel::Reference] {
            let before = LIVE.load(Relaxed);
            let problem =
                StochasticProblem::from_deterministic(deterministic, noise, &gamma).unwrap();
            let held = (LIVE.load(Relaxed) - before) as u64;
            let part = problem_bytes(&problem);
            assert!(
                held <= part && part as f64 <= 1.5 * held as f64,
                "{name} {}: holds {held} B, estimated {part} B",
                noise.name()
            );
        }
    }
}

#[test]
fn small_problems_fit_in_the_base() {
    let _alone = exclusive();
    // Below a few hundred unknowns the solve's heap is a fraction of the 16 MiB base, and the
    // estimate stays close to it: a 5×5 grid's whole run is under 1 MiB.
    let (peak, estimate) = measure(&cost_grid(5, 5, 1).unwrap(), NoiseModel::Paper, "0.9", true);
    assert!(peak < 1 << 20, "{peak}");
    assert!((BASE..BASE + (1 << 20)).contains(&estimate), "{estimate}");
}

#[test]
fn the_estimate_s_band_is_that_of_every_action_s_pattern() {
    let _alone = exclusive();
    // `band_width` is documented as `lower + upper + 1` of the band ordering of the pattern of
    // every action's outcomes over the unknowns (non-goal states with an action): rebuild
    // that pattern here from the problem's lists and order it.
    for (rows, cols) in [
        (2, 3),
        (2, 300),
        (3, 700),
        (5, 5),
        (7, 40),
        (20, 20),
        (30, 12),
    ] {
        for noise in [NoiseModel::Paper, NoiseModel::Reference] {
            let grid = cost_grid(rows, cols, 3).unwrap();
            let gamma = Predictability::parse("0.9").unwrap();
            let problem = StochasticProblem::from_deterministic(&grid, noise, &gamma).unwrap();
            let unknown: Vec<Option<usize>> = {
                let mut next = 0;
                (0..problem.states())
                    .map(|x| {
                        (!problem.is_goal(x) && !problem.actions(x).is_empty()).then(|| {
                            next += 1;
                            next - 1
                        })
                    })
                    .collect()
            };
            let mut pattern = SparseSystem::new();
            for x in 0..problem.states() {
                let Some(i) = unknown[x] else { continue };
                let mut row = vec![(i, 1)];
                for a in problem.actions(x) {
                    for o in problem.outcomes(a) {
                        if let Some(j) = unknown[o.successor] {
                            if !row.iter().any(|&(c, _)| c == j) {
                                row.push((j, 1));
                            }
                        }
                    }
                }
                pattern.push_row(&row, 0).unwrap();
            }
            let (lower, upper) = BandOrdering::new(&pattern).bandwidths();
            let e = memory_estimate(&problem, false);
            assert_eq!(e.unknowns, rows * cols - 1, "{rows}x{cols}");
            assert_eq!(e.unknowns, pattern.len());
            assert_eq!(
                e.band_width,
                lower + upper + 1,
                "{rows}x{cols} {}",
                noise.name()
            );
        }
    }
}

/// Every part of the estimate on a problem small enough to work by hand, each quantity an exact
/// power of two where a logarithm is taken (the formula is `MemoryEstimate::lifted_bits`'s and
/// `memory_estimate`'s documentation; the numbers below are worked from it, not from the code).
///
/// States 0, 1, 3 have actions, 2 is the goal; costs have denominator 2 (`B`), so the right-hand
/// side of an action is `s · l · 2`:
///
/// | state (`s`) | action | outcomes | row of `s(I − P)` | `‖row‖²` | rhs |
/// |---|---|---|---|---|---|
/// | 0 (`s = 2`) | A, cost 3 | ½ → 1, ½ → 0 | `(0: 2 − 1, 1: −1)` | 2 | 12 |
/// | | B, cost ½ | 1 → 2 | `(0: 2)` | 4 | 2 |
/// | 1 (`s = 4`) | C, cost 4 | ½ → 1, ¼ → 0, ¼ → 2 | `(1: 4 − 2, 0: −1)` | 5 | 32 |
/// | | D, cost 1 | 1 → 2 | `(1: 4)` | 16 | 8 |
/// | 3 (`s = 2`) | E, cost 1 | ½ → 0, ½ → 0 (twice the same state) | `(3: 2, 0: −1 − 1)` | 8 | 4 |
/// | | F, cost 1 | 1 → 2 | `(3: 2)` | 4 | 4 |
///
/// So `Σ ½ log₂ max ‖row‖² = ½(2 + 4 + 3) = 4.5`, `log₂ 32 = 5`, `log₂(3 + 1) = 2`: the lifted
/// bits are `2(4.5 + 5 + 2) + 8 = 31`, the steps `⌈31/31⌉ + 2 = 3`, a number `⌈31/16⌉ + 32 =
/// 34` bytes. The pattern couples 1–0 and 3–0, a path, which reverse Cuthill–McKee orders with
/// one band on each side: width 3. The problem holds 10 outcomes and 6 actions (`128·10 +
/// 160·6 = 2240` bytes), so the bytes are
/// `16 MiB + 2240 + 3·1024` and the larger of the exact stage `3·3·(8+4+8) + 3·3·4 + 3·3·34 =
/// 522` and the mixed-precision stage (precision cap `4.5 + 192 = 196.5` bits, so numbers of
/// `⌈196.5/8⌉ + 32 = 57` bytes): `3·3·8 + 2·3·57 + 4·3·8 = 510`; that is `16 MiB + 5834`, and
/// with the values `+ 3·34·2 + 4·3·⌊34·2.41⌋ = + 204 + 972`.
#[test]
fn every_part_of_the_estimate_worked_by_hand() {
    let _one = exclusive();
    let text = r#"{"initial": 0, "goals": [2], "actions": [
        [ { "cost": "3", "outcomes": [ { "to": 1, "p": "1/2" }, { "to": 0, "p": "1/2" } ] },
          { "cost": "1/2", "outcomes": [ { "to": 2, "p": "1" } ] } ],
        [ { "cost": "4", "outcomes": [ { "to": 1, "p": "1/2" }, { "to": 0, "p": "1/4" }, { "to": 2, "p": "1/4" } ] },
          { "cost": "1", "outcomes": [ { "to": 2, "p": "1" } ] } ],
        [],
        [ { "cost": "1", "outcomes": [ { "to": 0, "p": "1/2" }, { "to": 0, "p": "1/2" } ] },
          { "cost": "1", "outcomes": [ { "to": 2, "p": "1" } ] } ] ]}"#;
    let s = stochastic_file(text);
    assert_eq!((s.outcome_total(), s.action_total()), (10, 6));
    assert_eq!(
        (s.denominator(0), s.denominator(1), s.denominator(3)),
        (2, 4, 2)
    );
    assert_eq!(problem_bytes(&s), 2240);
    let e = memory_estimate(&s, false);
    assert_eq!(
        (e.unknowns, e.band_width, e.lifting_steps, e.lifted_bits),
        (3, 3, 3, 31.0)
    );
    assert_eq!((e.refinement_cap_bits, e.refinement_bytes), (196.5, 510));
    assert_eq!(e.bytes, (16 << 20) + 5834);
    let with_values = memory_estimate(&s, true);
    assert_eq!(with_values.bytes, (16 << 20) + 5834 + 204 + 972);
}

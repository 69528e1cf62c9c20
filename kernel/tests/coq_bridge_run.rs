//! The bridge between C1's Coq proofs (`proofs/coq/C1.v`, about `Model.v`'s `run` and
//! `run_printed`) and the kernel's Q-learning simulator (`QProblem::update`, `claims::qlearning::run`):
//! the updates the theorems are about must be the ones the kernel performs. Problems of
//! `claims::tiny`'s enumeration (every non-goal state with a move; costs up to 200) are run
//! by the kernel's `QProblem::update`, with the termination pair held (`Terminal::HeldAtZero`,
//! Model.v's `update`) or updated by the printed rule (`Terminal::Updated`,
//! `update_printed`), in three update orders (index order, reverse, a fresh permutation every
//! round) and from initial values with negative entries (the termination pair's included).
//! After every round the test records the kernel's values and its verdict `Q = Q*`
//! (`QProblem::is_optimal`); `BridgeRun.v`'s checker, evaluated by `coqc`, recomputes both
//! from Model.v's definitions. The verdict of `claims::qlearning::run` under the index and
//! reverse orders is checked against the same trajectories.
//!
//! A second test plants wrong values and a wrong simulator (the termination pair updated where
//! it must be held) and requires Coq to report them.
//!
//! Without `coqc` on `PATH` the test fails with the install line (no silent skip). The Coq
//! development is `../proofs/coq` from this crate, or the directory in `TRUECOST_COQ_DIR`.

#[path = "support/coq.rs"]
mod coq_support;

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use truecost_kernel::claims::qlearning::{run, Order, QProblem, Run, Terminal, Values, MAX_PAIRS};
use truecost_kernel::claims::tiny::{Family, FamilySpec, Tiny};

use coq_support::{check_all, list, prepare, Verdict};

/// Rounds simulated per run.
const ROUNDS: usize = 4;

/// The scopes, and how many labelled problems to sample from each (evenly spaced, kept if
/// they are their class's representative). Every non-goal state has a move, so every state
/// has a pair (the kernel's minimum over no pair is not a value).
fn scopes() -> Vec<(FamilySpec, u64)> {
    let spec = |states, degree, goal_degree, costs: &[u8]| FamilySpec {
        states,
        initial_fixed: true,
        degree,
        goal_degree,
        costs: costs.to_vec(),
        distinct_successors: false,
    };
    vec![
        (spec(2, (1, 2), (0, 2), &[0, 1, 7]), 200),
        (spec(3, (1, 2), (0, 1), &[0, 2, 9]), 300),
        (spec(3, (1, 2), (0, 1), &[1, 4, 200]), 300),
        (spec(4, (1, 2), (0, 1), &[1, 3, 50]), 350),
    ]
}

/// One run of the kernel's simulator.
#[derive(Clone, Debug)]
struct RunCase {
    q0: Vec<i64>,
    held: bool,
    rounds: Vec<Vec<usize>>,
    /// After round 0, 1, …: the kernel's values and `is_optimal`.
    after: Vec<(Vec<i64>, bool)>,
}

/// A problem and the kernel's runs on it.
#[derive(Clone)]
struct Case {
    tiny: Tiny,
    runs: Vec<RunCase>,
}

/// A small deterministic generator (splitmix64) for initial values and permutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn shuffled(&mut self, items: &[usize]) -> Vec<usize> {
        let mut v = items.to_vec();
        for i in (1..v.len()).rev() {
            v.swap(i, self.below(i as u64 + 1) as usize);
        }
        v
    }
}

/// Runs `rounds` with the kernel's `update` from `q0`, recording every round's values.
fn simulate(q: &QProblem, q0: &[i64], rounds: &[Vec<usize>]) -> Vec<(Vec<i64>, bool)> {
    let mut v: Values = [0; MAX_PAIRS];
    v[..q0.len()].copy_from_slice(q0);
    let mut after = vec![(q0.to_vec(), q.is_optimal(&v))];
    for r in rounds {
        for &p in r {
            q.update(&mut v, p);
        }
        after.push((v[..q.len()].to_vec(), q.is_optimal(&v)));
    }
    after
}

/// `claims::qlearning::run`'s verdict agrees with the recorded trajectory: `Converged(k)`
/// iff the values first equal `Q*` after round `k`.
fn check_run_verdict(q: &QProblem, q0: &[i64], order: Order, after: &[(Vec<i64>, bool)]) {
    let mut v: Values = [0; MAX_PAIRS];
    v[..q0.len()].copy_from_slice(q0);
    let first = after.iter().position(|a| a.1).map(|k| k as u64);
    match run(q, &v, order, ROUNDS as u64) {
        Run::Converged(k) => assert_eq!(Some(k), first, "{order:?} from {q0:?}"),
        other => assert_eq!(first, None, "{order:?} from {q0:?}: {other:?}"),
    }
}

/// Initial values, the rounds (pair indices), and the kernel's `Order` they are, if any.
type Plan = (Vec<i64>, Vec<Vec<usize>>, Option<Order>);

fn case(t: &Tiny, seed: u64) -> Case {
    let mut rng = Rng(seed);
    let mut runs = Vec::new();
    for (terminal, held) in [(Terminal::HeldAtZero, true), (Terminal::Updated, false)] {
        let q = QProblem::new(t, terminal);
        let seq: Vec<usize> = (0..q.len()).filter(|&p| q.updatable(p)).collect();
        let rev: Vec<usize> = seq.iter().rev().copied().collect();
        let zero = vec![0i64; q.len()];
        let mut random =
            || -> Vec<i64> { (0..q.len()).map(|_| rng.below(61) as i64 - 30).collect() };
        let (r1, r2, r3) = (random(), random(), random());
        let shuffled: Vec<Vec<usize>> = (0..ROUNDS).map(|_| rng.shuffled(&seq)).collect();
        let plans: Vec<Plan> = vec![
            (zero, vec![seq.clone(); ROUNDS], Some(Order::Cyclic)),
            (r1, vec![seq.clone(); ROUNDS], Some(Order::Cyclic)),
            (r2, vec![rev; ROUNDS], Some(Order::Reverse)),
            (r3, shuffled, None),
        ];
        for (q0, rounds, order) in plans {
            let after = simulate(&q, &q0, &rounds);
            if let Some(order) = order {
                check_run_verdict(&q, &q0, order, &after);
            }
            runs.push(RunCase {
                q0,
                held,
                rounds,
                after,
            });
        }
    }
    Case { tiny: *t, runs }
}

fn q(v: i64) -> String {
    format!("({v} # 1)")
}

fn nats(v: &[usize]) -> String {
    list(v.iter().map(|p| format!("{p}%nat")))
}

/// `(problem, expected)` as a Coq term.
fn coq_term(c: &Case) -> String {
    let t = &c.tiny;
    let moves = list((0..t.states()).map(|x| {
        list(
            t.moves(x)
                .iter()
                .map(|m| format!("({}%nat, {})", m.to, q(m.cost as i64))),
        )
    }));
    let runs = list(c.runs.iter().map(|r| {
        format!(
            "{{| r_q0 := {}; r_held := {}; r_rounds := {}; r_after := {} |}}",
            list(r.q0.iter().map(|&v| q(v))),
            r.held,
            list(r.rounds.iter().map(|v| nats(v))),
            list(
                r.after
                    .iter()
                    .map(|(v, opt)| format!("({}, {opt})", list(v.iter().map(|&x| q(x)))))
            ),
        )
    }));
    format!("(mk {} {moves}, {runs})", t.states())
}

/// Problems per `coqc` run: Coq's stack overflows on a few hundred of them at once.
const CHUNK: usize = 100;

/// Writes `cases` as Coq files in `work`, `CHUNK` problems each, and evaluates `check_all`
/// on each with `coqc`; the verdicts are added up, mismatches numbered across the chunks.
fn coq_check(dir: &Path, work: &Path, name: &str, cases: &[Case]) -> Verdict {
    let mut total = Verdict {
        problems: 0,
        values: 0,
        mismatches: Vec::new(),
    };
    for (k, chunk) in cases.chunks(CHUNK).enumerate() {
        let terms: Vec<String> = chunk.iter().map(coq_term).collect();
        let v = check_all(dir, work, &format!("{name}_{k}"), "BridgeRun", &terms);
        total.problems += v.problems;
        total.values += v.values;
        let offset = k * CHUNK;
        total.mismatches.extend(
            v.mismatches
                .into_iter()
                .map(|(i, what, pos)| (i + offset, what, pos)),
        );
    }
    total
}

/// The sampled problems of one scope.
fn sample(spec: &FamilySpec, wanted: u64) -> Vec<Tiny> {
    let family = Family::new(spec);
    let stride = (family.labelled_count() / wanted).max(1);
    (0..family.labelled_count())
        .step_by(stride as usize)
        .map(|i| family.problem(i))
        .filter(|t| family.is_canonical(t))
        .collect()
}

#[test]
fn model_run_equals_the_kernel_simulator_on_enumerated_problems() {
    let started = Instant::now();
    let (dir, work) = prepare("BridgeRun.vo", "coq-bridge-run");
    let mut all: Vec<Case> = Vec::new();
    let (mut checked, mut values) = (0u64, 0u64);
    let mut failures = String::new();
    let mut mismatches = 0usize;
    for (f, (spec, wanted)) in scopes().iter().enumerate() {
        let cases: Vec<Case> = sample(spec, *wanted)
            .iter()
            .enumerate()
            .map(|(i, t)| case(t, (f as u64) << 32 | i as u64))
            .collect();
        let v = coq_check(&dir, &work, &format!("bridge_run_{f}"), &cases);
        assert_eq!(v.problems, cases.len() as u64, "{}", spec.describe());
        for (i, what, k) in &v.mismatches {
            mismatches += 1;
            if mismatches <= 20 {
                let r = &cases[*i].runs[k / 100];
                writeln!(
                    failures,
                    "{} | problem {} ({}): Model.v's {what} differs after round {} of run {} \
                     (held: {}, q0 = {:?}; kernel: {:?})",
                    spec.describe(),
                    i,
                    cases[*i].tiny.describe(),
                    k % 100,
                    k / 100,
                    r.held,
                    r.q0,
                    r.after.get(k % 100)
                )
                .unwrap();
            }
        }
        eprintln!(
            "{}: {} problems, {} values, {} mismatches",
            spec.describe(),
            v.problems,
            v.values,
            v.mismatches.len()
        );
        checked += v.problems;
        values += v.values;
        all.extend(cases);
    }
    std::fs::remove_dir_all(&work).ok();
    eprintln!(
        "Coq checked {checked} problems ({values} values) against the kernel's Q-learning \
         simulator in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(
        mismatches == 0,
        "{mismatches} mismatches between Model.v's run and the kernel (the first {}):\n{failures}",
        mismatches.min(20)
    );
    assert_eq!(checked, all.len() as u64);
    assert!(checked >= 1_000, "only {checked} problems checked");

    // The sample has runs that converge and runs that do not, in both treatments of the
    // termination pair, negative initial values, and costs above 3.
    let runs: Vec<&RunCase> = all.iter().flat_map(|c| c.runs.iter()).collect();
    for held in [true, false] {
        let conv = runs
            .iter()
            .filter(|r| r.held == held && r.after.last().unwrap().1)
            .count();
        let not = runs
            .iter()
            .filter(|r| r.held == held && !r.after.last().unwrap().1)
            .count();
        assert!(conv >= 100 && not >= 100, "held {held}: {conv} / {not}");
    }
    assert!(runs.iter().filter(|r| r.q0.iter().any(|&v| v < 0)).count() >= 1_000);
    assert!(
        all.iter()
            .filter(|c| (0..c.tiny.states()).any(|x| c.tiny.moves(x).iter().any(|m| m.cost > 3)))
            .count()
            >= 100
    );
}

/// The checker can fail: planted wrong values and a wrong simulator are reported by Coq.
#[test]
fn planted_wrong_runs_are_reported() {
    let (dir, work) = prepare("BridgeRun.vo", "coq-bridge-run");
    // 0 -> 1 (cost 2), 0 -> 2 (cost 5), 1 -> 2 (cost 1), 1 -> 0 (cost 3), the goal 2 -> 0
    // (cost 4): pairs (0,0->1) (0,0->2) (1,1->2) (1,1->0) (2,uT) (2,2->0).
    let t = Tiny::from_lists(&[vec![(1, 2), (2, 5)], vec![(2, 1), (0, 3)], vec![(0, 4)]]);
    let good = case(&t, 7);
    let mut planted = Vec::new();
    // A value off by one after round 2 of run 1.
    let mut c = good.clone();
    c.runs[1].after[2].0[0] += 1;
    planted.push(c);
    // A wrong verdict after round 0 of run 0 (from Q0 = 0, Q != Q*).
    let mut c = good.clone();
    assert!(!c.runs[0].after[0].1);
    c.runs[0].after[0].1 = true;
    planted.push(c);
    planted.push(good.clone());
    // A simulator that updates the termination pair where it must be held: the printed
    // rule's run from Q0 = -10 at the goal's move (0 elsewhere) given as a held run. Model.v
    // holds Q(2, uT) at 0, the printed rule lowers it to -10 in round 1.
    let printed = QProblem::new(&t, Terminal::Updated);
    let seq: Vec<usize> = (0..printed.len()).collect();
    let q0 = vec![0, 0, 0, 0, 0, -10];
    let rounds = vec![seq; ROUNDS];
    let after = simulate(&printed, &q0, &rounds);
    assert_eq!(after[1].0[4], -10);
    let mut c = good;
    c.runs = vec![RunCase {
        q0,
        held: true,
        rounds,
        after,
    }];
    planted.push(c);
    let v = coq_check(&dir, &work, "bridge_run_planted", &planted);
    std::fs::remove_dir_all(&work).ok();
    assert_eq!(v.problems, 4);
    let first_two: Vec<_> = v.mismatches.iter().filter(|m| m.0 < 2).cloned().collect();
    assert_eq!(
        first_two,
        vec![(0, "run".to_string(), 100 + 2), (1, "run".to_string(), 0)]
    );
    assert!(!v.mismatches.iter().any(|m| m.0 == 2), "{:?}", v.mismatches);
    assert!(
        v.mismatches.contains(&(3, "run".to_string(), 1)),
        "{:?}",
        v.mismatches
    );
}

//! The claims engine: hand-derived facts, independent cross-checks, and the pinned smoke-scope
//! report (verdicts, scopes, counterexamples; no times).

use num_bigint::BigInt;
use num_traits::{One, Zero};
use truecost::algebra::intervals::Point;
use truecost::claims::alpha::{alpha_star, optimal_policies_from_initial, worked_example};
use truecost::claims::c4::{bonus_sets, Instance};
use truecost::claims::discount::discount_set;
use truecost::claims::exact::Q;
use truecost::claims::oracle::{karp_minimum_mean_cycle, simple_cycles};
use truecost::claims::tiny::Tiny;
use truecost::claims::{report, run, Scope, Verdict};
use truecost::value::{parse_rational, Rational};

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

/// 5a^4 - a^3 - a^2 - a - 1, typed from the paper's inequality by hand:
/// 1/(1-a) < 1 + 2a + 3a^2 + 4a^3 + 5a^4 ⇔ 1 < (1-a)(1 + 2a + 3a^2 + 4a^3 + 5a^4)
/// = 1 + a + a^2 + a^3 + a^4 - 5a^5 ⇔ 5a^4 - a^3 - a^2 - a - 1 < 0 (a > 0).
fn p(a: &Rational) -> Rational {
    let five = Rational::from_integer(BigInt::from(5));
    let a2 = a * a;
    let a3 = &a2 * a;
    let a4 = &a3 * a;
    five * a4 - a3 - a2 - a - Rational::one()
}

#[test]
fn alpha_star_is_bracketed_to_1e_30_and_separates_the_two_behaviours() {
    let a = alpha_star().unwrap();
    let width = &a.hi - &a.lo;
    assert!(width > Rational::zero());
    assert!(width <= parse_rational("1e-30").unwrap());
    // The hand-derived polynomial changes sign across the bracket.
    assert!(p(&a.lo) < Rational::zero());
    assert!(p(&a.hi) > Rational::zero());
    // Exact discounted solves (all policies) on both sides.
    let t = worked_example();
    assert_eq!(optimal_policies_from_initial(&t, &a.lo), (true, false));
    assert_eq!(optimal_policies_from_initial(&t, &a.hi), (false, true));
    // Far from the threshold, by hand: at a = 1/2 staying costs 2, going costs
    // 1 + 1 + 3/4 + 1/2 + 5/16 = 57/16 > 2: avoid. At a = 99/100 staying costs 100, going < 15.
    assert_eq!(
        optimal_policies_from_initial(&t, &parse_rational("1/2").unwrap()),
        (true, false)
    );
    assert_eq!(
        optimal_policies_from_initial(&t, &parse_rational("0.99").unwrap()),
        (false, true)
    );
}

#[test]
fn discount_set_of_the_worked_example_is_zero_to_alpha_star() {
    let problem =
        truecost::model::file::read(std::path::Path::new("problems/discount-example.json"))
            .unwrap();
    let set = discount_set(&problem, 10_000).unwrap();
    assert_eq!(set.pieces.len(), 1, "{set:?}");
    let piece = &set.pieces[0];
    assert_eq!(piece.lo, Point::Zero);
    assert!(!piece.lo_closed);
    assert!(piece.hi_closed, "at alpha* both policies are optimal");
    let Point::Root(root) = &piece.hi else {
        panic!("an algebraic end")
    };
    // The same number as alpha* from the printed polynomial (independent routes).
    assert_eq!(
        root.compare(&alpha_star().unwrap()),
        std::cmp::Ordering::Equal
    );
    // Membership agrees with the exact solve on a grid.
    let t = worked_example();
    for k in 1..100 {
        let a = Rational::new(BigInt::from(k), BigInt::from(100));
        let inside = root.cmp_rational(&a) != std::cmp::Ordering::Less;
        assert_eq!(
            inside,
            optimal_policies_from_initial(&t, &a).0,
            "alpha = {k}/100"
        );
    }
}

#[test]
fn discount_lemmas() {
    // Unit costs: never (a d-move path costs (1-a^d)/(1-a) < 1/(1-a)).
    let grid = truecost::problems::GridLayout::exact(10)
        .unwrap()
        .to_problem(truecost::problems::StepCost::Unit);
    assert!(discount_set(&grid, 10).unwrap().pieces.is_empty());
    // Problem 6 has no path at all: every alpha.
    let six = truecost::problems::GridLayout::exact(6)
        .unwrap()
        .to_problem(truecost::problems::StepCost::Unit);
    let s = discount_set(&six, 10).unwrap();
    assert_eq!(s.pieces.len(), 1);
    assert_eq!(
        (s.pieces[0].lo.clone(), s.pieces[0].hi.clone()),
        (Point::Zero, Point::One)
    );
}

#[test]
fn c4_counterexample_by_hand() {
    // x1 -> 1 (0), x1 -> goal (1), 1 -> goal (0). pi* = via 1: L* = 0, S* = 3. Other path:
    // L = 1, S = 2. (0 + M)/3 <= (1 + M)/2 ⇔ M >= -3; no cycle. Exact: [-3, 0).
    // Printed: A = (1 - 2/3)(2·0/(3·1) - 1) = -1/3: [-1/3, 0).
    let t = Tiny::from_lists(&[vec![(1, 0), (2, 1)], vec![(2, 0)], vec![]]);
    let sets = bonus_sets(&Instance::from_tiny(&t), 1000).unwrap().unwrap();
    assert_eq!(sets.len(), 1);
    assert_eq!(sets[0].exact.to_string(), "[-3, 0)");
    assert_eq!(sets[0].printed.unwrap().to_string(), "[-1/3, 0)");
    assert_eq!(sets[0].corrected.to_string(), "[-3, 0)");
}

#[test]
fn c4_cycle_bound_by_hand() {
    // x1 -> goal (4); x1 -> 1 (1), 1 -> x1 (1): cycle of mean 1. pi* direct: L* = 4, S* = 2.
    // (4 + M)/2 <= 1 ⇔ M <= -2. The other goal path goes 0 -> 1 -> 0? no: simple paths only.
    let t = Tiny::from_lists(&[vec![(2, 4), (1, 1)], vec![(0, 1)], vec![]]);
    let sets = bonus_sets(&Instance::from_tiny(&t), 1000).unwrap().unwrap();
    assert_eq!(sets[0].least_mean_cycle, Some(Q::int(1)));
    assert_eq!(sets[0].exact.to_string(), "(-inf, -2]");
    assert_eq!(sets[0].corrected.to_string(), "(-inf, -2]");
}

#[test]
fn karp_matches_cycle_enumeration_on_every_small_digraph() {
    // Every digraph on 3 nodes with arcs weighted 0..=2 among a fixed arc list subset.
    let all = [(0, 1), (1, 0), (1, 2), (2, 0), (0, 0), (2, 2)];
    for mask in 0u32..(1 << all.len()) {
        for w in 0u32..3u32.pow(3) {
            let arcs: Vec<(usize, usize, i64)> = all
                .iter()
                .enumerate()
                .filter(|(i, _)| mask >> i & 1 == 1)
                .map(|(i, &(a, b))| (a, b, ((w / 3u32.pow(i as u32 % 3)) % 3) as i64))
                .collect();
            let brute = simple_cycles(3, &arcs)
                .into_iter()
                .map(|(c, l)| Q::new(c as i128, l as i128))
                .min();
            assert_eq!(karp_minimum_mean_cycle(3, &arcs), brute, "{arcs:?}");
        }
    }
}

#[test]
fn smoke_report_verdicts_and_minimal_counterexamples() {
    let r = run(Scope::Smoke, None).unwrap();
    let verdict = |id: &str| r.claims.iter().find(|c| c.id == id).unwrap().verdict;
    assert_eq!(verdict("C1"), Verdict::Refuted);
    assert_eq!(verdict("C1-corrected"), Verdict::Proved);
    assert_eq!(verdict("C2"), Verdict::Proved);
    assert_eq!(verdict("C3"), Verdict::Proved);
    assert_eq!(verdict("C3-example"), Verdict::Proved);
    assert_eq!(verdict("C4"), Verdict::Refuted);
    assert_eq!(verdict("C4-corrected"), Verdict::Proved);
    // The proved claims were decided by the SMT engine, and every engine that ran agrees.
    for c in r.claims.iter().filter(|c| c.verdict == Verdict::Proved) {
        assert_eq!(c.engine, "smt (Z3)", "{}", c.id);
        let smt = c.engines.iter().find(|e| e.engine == "smt (Z3)").unwrap();
        assert_eq!((smt.mode.as_str(), smt.failures), ("proof", 0), "{}", c.id);
        assert!(c
            .engines
            .iter()
            .filter(|e| e.engine.starts_with("exhaustive"))
            .all(|e| e.failures == 0));
    }
    // C1: the headline counterexample is the zero-cost cycle started below Q*: state
    // 0 with a zero-cost self-loop and a move of cost 1 to the goal, every value 0: the self-loop
    // keeps Q(0->0) = 0 < Q* = 1. The lone goal whose termination value starts at 1 is a note.
    let c1 = r.claims.iter().find(|c| c.id == "C1").unwrap();
    let ce = c1.counterexample.as_ref().unwrap();
    assert_eq!(ce.problem, "0: ->0 (0), ->1 (1); 1 (goal)");
    assert!(ce
        .details
        .iter()
        .any(|(k, v)| k == "initial values Q0" && v == "Q(0->0)=0, Q(0->1)=0, Q(1,uT)=0"));
    assert!(c1.notes.iter().any(|n| n.contains("Q(0,uT)=1")));
    // Each counterexample's file replays with `solve --file` (it parses as a problem).
    for c in &r.claims {
        if let Some(ce) = &c.counterexample {
            truecost::model::file::from_json(&ce.problem_file).unwrap();
        }
    }
    // Engine 3 is listed for every claim, with at least 8 harnesses overall.
    assert!(truecost::claims::harnesses::HARNESSES.len() >= 8);
    for c in &r.claims {
        assert!(
            c.engines
                .iter()
                .any(|e| e.engine.starts_with("kani harness")),
            "{}",
            c.id
        );
    }
    settings().bind(|| {
        insta::assert_snapshot!("verify_smoke_json", report::json(&r, false));
        insta::assert_snapshot!("verify_smoke_text", report::text(&r, false));
    });
}

#[test]
fn selecting_a_claim_and_unknown_ids() {
    let r = run(Scope::Smoke, Some("C4")).unwrap();
    let ids: Vec<&str> = r.claims.iter().map(|c| c.id.as_str()).collect();
    assert_eq!(ids, ["C4", "C4-corrected"]);
    assert!(run(Scope::Smoke, Some("C9")).is_err());
    assert!(run(Scope::Smoke, Some("C")).is_err());
}

/// `discount` against the exact solve on every 3-state problem (x1 = 0, goal 2, one or two
/// moves per state, costs in {0,1,2,4}) at α = k/16: where every discount-optimal policy
/// avoids the goal, α is in the set; where every one reaches it, α is not.
#[test]
fn discount_set_agrees_with_exact_solves_on_every_3_state_problem() {
    use truecost::claims::tiny::{Family, FamilySpec};
    let spec = FamilySpec {
        states: 3,
        initial_fixed: true,
        degree: (1, 2),
        goal_degree: (0, 0),
        costs: vec![0, 1, 2, 4],
        distinct_successors: false,
    };
    let family = Family::new(&spec);
    let mut nontrivial = 0;
    for i in 0..family.labelled_count() {
        let t = family.problem(i);
        if !family.is_canonical(&t) {
            continue;
        }
        let set = discount_set(&t.to_problem(), 10_000).unwrap();
        if !set.pieces.is_empty()
            && set.pieces
                != [truecost::algebra::intervals::Piece {
                    lo: Point::Zero,
                    lo_closed: false,
                    hi: Point::One,
                    hi_closed: false,
                }]
        {
            nontrivial += 1;
        }
        for k in 1..16 {
            let a = Rational::new(BigInt::from(k), BigInt::from(16));
            let member = set.pieces.iter().any(|p| {
                let above_lo = match &p.lo {
                    Point::Zero => true,
                    Point::One => false,
                    Point::Root(r) => match r.cmp_rational(&a) {
                        std::cmp::Ordering::Less => true,
                        std::cmp::Ordering::Equal => p.lo_closed,
                        std::cmp::Ordering::Greater => false,
                    },
                };
                let below_hi = match &p.hi {
                    Point::Zero => false,
                    Point::One => true,
                    Point::Root(r) => match r.cmp_rational(&a) {
                        std::cmp::Ordering::Greater => true,
                        std::cmp::Ordering::Equal => p.hi_closed,
                        std::cmp::Ordering::Less => false,
                    },
                };
                above_lo && below_hi
            });
            let (all_avoid, all_reach) = optimal_policies_from_initial(&t, &a);
            if all_avoid {
                assert!(member, "{}: alpha = {k}/16", t.describe());
            }
            if all_reach {
                assert!(!member, "{}: alpha = {k}/16", t.describe());
            }
        }
    }
    assert!(
        nontrivial > 100,
        "{nontrivial} problems with a proper breakpoint"
    );
}

#[test]
fn bonus_analysis_scales_costs_exactly_and_refuses_2_to_the_40() {
    use truecost::claims::c4::Instance;
    use truecost::model::{Move, Problem};
    use truecost::value::Rational;
    let problem = |cost: Rational| {
        Problem::new(vec![vec![Move { successor: 1, cost }], vec![]], 0, vec![1]).unwrap()
    };
    let big = num_bigint::BigInt::from(1u64 << 40);
    // Just below the bound: 2^40 - 1 passes, on scale 1.
    let (inst, d) = Instance::from_problem(&problem(Rational::from_integer(&big - 1))).unwrap();
    assert_eq!(inst.moves[0], vec![(1, (1i64 << 40) - 1)]);
    assert_eq!(d, 1.into());
    // At the bound: refused, naming it.
    let e = Instance::from_problem(&problem(Rational::from_integer(big.clone()))).unwrap_err();
    assert!(e.contains("2^40"), "{e}");
    let (inst, d) = Instance::from_problem(&problem(Rational::new(7.into(), 3.into()))).unwrap();
    assert_eq!((inst.moves[0].clone(), d), (vec![(1, 7)], 3.into()));
}

/// The SMT engine's bookkeeping (PROOFS.md: `proved` only with every trust check passing):
/// which answer each role requires, and the summary's counts, for every role against every
/// answer — a `true` for an unexpected answer would turn a failed trust check into a proof.
#[test]
fn smt_answers_are_as_expected_only_for_their_role_and_summaries_count_them() {
    use truecost::claims::smt::{Answer, Logic, Obligation, Role, Solved, Summary};
    let solved = |role: Role, answer: Answer, seconds: f64| Solved {
        obligation: Obligation::new("C1", "lemma", "structure", role, Logic::QfLra),
        answer,
        seconds,
    };
    let unknown = || Answer::Unknown("timeout".into());
    let roles = [
        Role::Proof,
        Role::Hypotheses,
        Role::Dropped("H1".into()),
        Role::Printed,
    ];
    // (role, unsat, sat, unknown) → as expected?
    let table = [
        (true, false, false),
        (false, true, false),
        (false, true, false),
        (true, true, false),
    ];
    for (role, (unsat, sat, unk)) in roles.iter().zip(table) {
        assert_eq!(
            solved(role.clone(), Answer::Unsat, 0.0).as_expected(),
            unsat,
            "{role:?}"
        );
        assert_eq!(
            solved(role.clone(), Answer::Sat(None), 0.0).as_expected(),
            sat,
            "{role:?}"
        );
        assert_eq!(
            solved(role.clone(), unknown(), 0.0).as_expected(),
            unk,
            "{role:?}"
        );
    }

    // A proof: two proofs unsat, two trust checks sat, one printed search sat.
    let mut run = vec![
        solved(Role::Proof, Answer::Unsat, 0.25),
        solved(Role::Proof, Answer::Unsat, 0.5),
        solved(Role::Hypotheses, Answer::Sat(None), 1.0),
        solved(Role::Dropped("H1".into()), Answer::Sat(None), 2.0),
        solved(Role::Printed, Answer::Sat(None), 4.0),
    ];
    let s = Summary::of(&run);
    assert_eq!(
        (
            s.proofs,
            s.proofs_unsat,
            s.trust_checks,
            s.trust_ok,
            s.printed,
            s.printed_sat,
            s.unknown
        ),
        (2, 2, 2, 2, 1, 1, 0)
    );
    assert_eq!(s.seconds, 7.75);
    assert!(s.proved());
    // A trust check answered `unsat` (the hypotheses contradictory, or the dropped hypothesis
    // not needed) is no proof, nor is an unknown answer or a proof obligation found `sat`.
    run[3] = solved(Role::Dropped("H1".into()), Answer::Unsat, 2.0);
    let s = Summary::of(&run);
    assert_eq!((s.trust_checks, s.trust_ok), (2, 1));
    assert!(!s.proved());
    run[3] = solved(Role::Dropped("H1".into()), unknown(), 2.0);
    let s = Summary::of(&run);
    assert_eq!((s.trust_ok, s.unknown), (1, 1));
    assert!(!s.proved());
    run[3] = solved(Role::Dropped("H1".into()), Answer::Sat(None), 2.0);
    run[1] = solved(Role::Proof, Answer::Sat(None), 0.5);
    let s = Summary::of(&run);
    assert_eq!((s.proofs, s.proofs_unsat), (2, 1));
    assert!(!s.proved());
}

/// Z3 prints Boolean model values as `true`/`false`; the replay reads them as 1 and 0 (the
/// numerals' own forms are in `parse_numeral`'s documentation).
#[test]
fn smt_numerals_read_booleans_as_one_and_zero() {
    use truecost::claims::smt::parse_numeral;
    let int = |n: i64| Some(Rational::from_integer(n.into()));
    assert_eq!(parse_numeral("true"), int(1));
    assert_eq!(parse_numeral(" false "), int(0));
    assert_eq!(parse_numeral("(- 3.0)"), int(-3));
    assert_eq!(
        parse_numeral("(/ 1.0 4.0)"),
        Some(parse_rational("0.25").unwrap())
    );
    for bad in ["True", "(- true)x", "(/ 1.0)", "(/ 1.0 2.0 3.0)", "x"] {
        assert_eq!(parse_numeral(bad), None, "{bad}");
    }
}

/// `truecost learn`'s replay (`claims::replay`) under the orders whose schedule depends on
/// more than the file's order: far-first sorts the pairs by `h` (the fewest moves of an
/// optimal path from the successor), and random draws splitmix64 from the seed.
fn replay_line(json: &str, order: truecost::claims::replay::ReplayOrder, rounds: u64) -> String {
    use truecost::claims::qlearning::Terminal;
    use truecost::claims::replay::{replay, InitialValues};
    let p = truecost::model::file::from_json(json).unwrap();
    let q0 = InitialValues::parse("0").unwrap();
    replay(&p, &q0, order, Terminal::HeldAtZero, rounds)
        .unwrap()
        .verdict
        .line()
}

#[test]
fn far_first_replays_sort_by_the_successor_s_distance() {
    use truecost::claims::replay::ReplayOrder;
    // The chain 3 → 2 → 1 → 4 → 0 (goal), every move of cost 1: Q* = 4, 3, 2, 1 along it.
    // h of the successors: pair 1→4: 1, 2→1: 2, 3→2: 3, 4→0: 0. Far-first updates 3→2, 2→1,
    // 1→4, 4→0 in that order, always before what it reads: one step of information a round,
    // four rounds from Q₀ = 0 (by hand: round ends (1,1,1,1), (2,2,2,1), (3,3,2,1), (4,3,2,1)).
    // The file's order (1→4, 2→1, 3→2, 4→0) reads each value just after updating it: two
    // rounds. An `h` computed by one sweep in state order stops before 1, 2 and 3 are known
    // (their successors come later in the file), and sorting them by index would give three.
    let chain = r#"{"initial": 3, "goals": [0], "actions": [[],
        [{"to": 4, "cost": "1"}], [{"to": 1, "cost": "1"}], [{"to": 2, "cost": "1"}],
        [{"to": 0, "cost": "1"}]]}"#;
    assert_eq!(
        replay_line(chain, ReplayOrder::FarFirst, 10),
        "converged at round 4"
    );
    assert_eq!(
        replay_line(chain, ReplayOrder::FarFirst, 3),
        "not converged within 3 rounds"
    );
    assert_eq!(
        replay_line(chain, ReplayOrder::Cyclic, 10),
        "converged at round 2"
    );
}

#[test]
fn random_replays_draw_the_claims_engine_s_stream() {
    use truecost::claims::replay::ReplayOrder;
    // The same chains and seed as the kernel's `random_order_zero_by_hand`
    // (kernel/tests/claims_qlearning_orders.rs), whose rounds are worked out by hand from
    // splitmix64's published outputs: the replay must draw the same permutations.
    let chain = |n: usize| {
        let mut actions: Vec<String> = (0..n - 1)
            .map(|x| format!(r#"[{{"to": {}, "cost": "1"}}]"#, x + 1))
            .collect();
        actions.push("[]".into());
        format!(
            r#"{{"initial": 0, "goals": [{}], "actions": [{}]}}"#,
            n - 1,
            actions.join(",")
        )
    };
    assert_eq!(
        replay_line(&chain(4), ReplayOrder::Random(0), 5),
        "converged at round 1"
    );
    assert_eq!(
        replay_line(&chain(4), ReplayOrder::Cyclic, 5),
        "converged at round 3"
    );
    assert_eq!(
        replay_line(&chain(5), ReplayOrder::Random(0), 3),
        "not converged within 3 rounds"
    );
    assert_eq!(
        replay_line(&chain(5), ReplayOrder::Random(0), 10),
        "converged at round 4"
    );
}

/// `truecost learn`'s replay (`claims::replay`, exact rationals) and the claims engine's run
/// (`claims::qlearning::run`, the kernel's integers) are two implementations of derandomized
/// Q-learning: on 400 pseudo-random problems of 2 to 5 states, from a pseudo-random `Q₀`, under
/// every order and both treatments of the termination pair, they reach the same verdict — the
/// round of convergence, or the first round and the period of a repetition. The random order's
/// seeds include 0, γ = 0x9E37…7C15 (whose state is 0), `!γ` and seeds sharing bits with γ, so
/// a seed mixed in differently, or a different splitmix64 output, changes some permutation.
#[test]
fn the_replay_and_the_claims_engine_s_run_agree() {
    use rand::{RngExt, SeedableRng};
    use truecost::claims::qlearning::{run, Order, QProblem, Run, Terminal, MAX_PAIRS};
    use truecost::claims::replay::{replay, InitialValues, ReplayOrder, ReplayVerdict};
    const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut draw = rand_chacha::ChaCha8Rng::seed_from_u64(2026);
    let mut verdicts = std::collections::BTreeSet::new();
    for _ in 0..400 {
        let n = draw.random_range(2..=5usize);
        let lists: Vec<Vec<(u8, u8)>> = (0..n)
            .map(|x| {
                let degree = if x + 1 == n {
                    draw.random_range(0..=1)
                } else {
                    draw.random_range(1..=2)
                };
                (0..degree)
                    .map(|_| (draw.random_range(0..n as u8), draw.random_range(0..=2u8)))
                    .collect()
            })
            .collect();
        let t = Tiny::from_lists(&lists);
        let problem: truecost::model::Problem = t.to_problem();
        let seed = draw.random::<u64>();
        let orders = [
            Order::Cyclic,
            Order::Reverse,
            Order::FarFirst,
            Order::Random(0),
            Order::Random(GAMMA),
            Order::Random(!GAMMA),
            Order::Random(GAMMA | seed),
            Order::Random(seed),
        ];
        for terminal in [Terminal::Updated, Terminal::HeldAtZero] {
            let q = QProblem::new(&t, terminal);
            let mut q0 = [0i64; MAX_PAIRS];
            for (p, v) in q0.iter_mut().enumerate().take(q.len()) {
                if q.updatable(p) {
                    *v = draw.random_range(-1..=4);
                }
            }
            let exact = InitialValues::PerPair(
                q0[..q.len()]
                    .iter()
                    .map(|&v| Rational::from_integer(v.into()))
                    .collect(),
            );
            for order in orders {
                let expected = match run(&q, &q0, order, 12) {
                    Run::Converged(round) => ReplayVerdict::Converged { round },
                    Run::Cycles(from, period) => ReplayVerdict::NeverConverges { from, period },
                    Run::NotWithin(rounds) => ReplayVerdict::NotConverged { rounds },
                };
                let r = replay(&problem, &exact, ReplayOrder::from(order), terminal, 12).unwrap();
                assert_eq!(
                    r.verdict, expected,
                    "{lists:?} {terminal:?} {order:?} {q0:?}"
                );
                verdicts.insert(format!("{expected:?}"));
            }
        }
    }
    // The family reaches every kind of verdict, a repetition of period 2 from round 2 among them
    // (its period is `round − from`, not `round + from`).
    assert!(
        verdicts.iter().any(|v| v.starts_with("Converged")),
        "{verdicts:?}"
    );
    assert!(
        verdicts.iter().any(|v| v.starts_with("NotConverged")),
        "{verdicts:?}"
    );
    assert!(
        verdicts.contains("NeverConverges { from: 2, period: 2 }"),
        "{verdicts:?}"
    );
}

/// `discount`'s breakpoint-work bound, `pairs² · (d + 1)³` with `d` the largest lasso degree
/// plus the largest path degree, refuses before the search starts. `x1` has 60 self-loops
/// (lassos `c/(1 − α)`: degree 1) and 100 moves to the goal (paths `g/1`: degree 0), costs all
/// different, so `d = 1 + 0` and the work is `6000² · 2³ = 2.88·10⁸`, past the bound 2·10⁸
/// (with the degrees' product, `d = 0`, it would be 3.6·10⁷ and the search would run: minutes).
#[test]
fn discount_breakpoint_work_counts_the_sum_of_the_degrees() {
    use truecost::claims::discount::{DiscountError, MAX_PAIR_WORK};
    use truecost::model::{Move, Problem};
    let mut moves: Vec<Move> = (1..=60)
        .map(|c: i64| Move {
            successor: 0,
            cost: Rational::from_integer(c.into()),
        })
        .collect();
    moves.extend((1..=100).map(|g: i64| Move {
        successor: 1,
        cost: Rational::from_integer((1000 + g).into()),
    }));
    let problem = Problem::new(vec![moves, vec![]], 0, vec![1]).unwrap();
    const { assert!(6000u64 * 6000 * 8 > MAX_PAIR_WORK && 6000u64 * 6000 <= MAX_PAIR_WORK) };
    match discount_set(&problem, 10_000) {
        Err(DiscountError::Effort { what, bound }) => {
            assert_eq!(bound, MAX_PAIR_WORK);
            assert!(what.contains("breakpoint work"), "{what}");
        }
        other => panic!("{other:?}"),
    }
}

/// A scope's name reads back to the scope (the merge of shards reads the scope from their
/// fingerprint this way); other texts, other cases included, are no scope.
#[test]
fn scope_names_read_back() {
    for s in [Scope::Smoke, Scope::Quick, Scope::Full] {
        assert_eq!(Scope::from_name(s.name()), Some(s));
    }
    assert_eq!(
        [Scope::Smoke, Scope::Quick, Scope::Full].map(Scope::name),
        ["smoke", "quick", "full"]
    );
    for other in ["", "Quick", "quick ", "ful", "all"] {
        assert_eq!(Scope::from_name(other), None, "{other:?}");
    }
}

//! Q-learning and its exploration plans: the base-4 digits of π against known digits, the
//! digit stream, exact coins, and the learner's invariants (docs/spec.md §2, §4) as properties over
//! random problems, judged by an independent oracle (Bellman–Ford on exact rationals).

mod common;

use common::{bellman_ford, exact, huge_problem, small_problem, Ext, Q};
use num_bigint::BigInt;
use num_traits::Zero;
use proptest::prelude::*;
use rand::RngExt;
use truecost::learning::plan::{
    pi_digits, sample_rng, EpsilonSchedule, PiStream, Plan, Probability, PI_STREAM_PERIOD,
};
use truecost::learning::q_learning::{
    Event, LearningError, Milestone, QLearner, QLearningConfig, Rules,
};
use truecost::model::{ExactGraph, Graph, Problem};
use truecost::value::{parse_rational, Rational, Units};

/// π = 3.243F6A88… in hexadecimal: the first 128 hexadecimal digits after the point (public
/// knowledge, e.g. the initial Blowfish P-array and S-boxes are these digits).
const PI_HEX: &str = "243F6A8885A308D313198A2E03707344A4093822299F31D0082EFA98EC4E6C89\
                      452821E638D01377BE5466CF34E90C6CC0AC29B7C97C50DD3F84D5B5B5470917";

/// Each hexadecimal digit is two base-4 digits (16 = 4²).
fn base4_from_hex(hex: &str) -> Vec<u8> {
    hex.chars()
        .flat_map(|c| {
            let v = c.to_digit(16).expect("a hex digit") as u8;
            [v >> 2, v & 3]
        })
        .collect()
}

#[test]
fn pi_digits_match_256_known_base4_digits() {
    let known = base4_from_hex(PI_HEX);
    assert_eq!(known.len(), 256);
    let d = pi_digits(256);
    assert_eq!(&d[..256], &known[..]);
    // The stream is "3" followed by the fractional digits (docs/spec.md §7).
    let mut s = PiStream::new();
    assert_eq!(s.next_digit(), 3);
    let read: Vec<u8> = (0..256).map(|_| s.next_digit()).collect();
    assert_eq!(read, known);
    assert_eq!(s.position(), 257);
}

#[test]
fn spec_section_2_prints_pi_wrongly_in_base_4() {
    // docs/spec.md §2 writes π = 3.1032 0333 1222 … (base 4); π is 3.0210 0333 1222 2020 …: 0x2 = 02,
    // 0x4 = 10 (the printed first group differs), 0x3F = 0333, 0x6A = 1222, 0x88 = 2020.
    let d = pi_digits(16);
    assert_eq!(&d[..16], &[0, 2, 1, 0, 0, 3, 3, 3, 1, 2, 2, 2, 2, 0, 2, 0]);
    assert_ne!(&d[..4], &[1, 0, 3, 2]);
}

#[test]
fn pi_plan_skips_digits_beyond_the_actions() {
    // Stream: 3 0 2 1 0 0 3 3 3 1 2 2 …
    let mut s = PiStream::new();
    assert_eq!(s.next_action(4), 3); // 3 < 4 is taken
    assert_eq!(s.next_action(1), 0); // 0
    assert_eq!(s.next_action(2), 1); // 2 skipped, then 1
    assert_eq!(s.next_action(1), 0); // 0
    assert_eq!(s.next_action(1), 0); // 0
    assert_eq!(s.next_action(3), 1); // 3, 3, 3 skipped, then 1
    assert_eq!(s.position(), 10);
}

#[test]
fn pi_stream_period_is_the_reference_files_ten_million_characters() {
    assert_eq!(PI_STREAM_PERIOD, 10_000_000);
}

#[test]
fn probabilities_are_exact_and_validated() {
    let p = Probability::new("ε", &parse_rational("0.9").unwrap()).unwrap();
    assert_eq!((p.numerator(), p.denominator()), (9, 10));
    for bad in ["-0.1", "1.0000001", "2"] {
        assert!(
            Probability::new("ε", &parse_rational(bad).unwrap()).is_err(),
            "{bad}"
        );
    }
    // ε = 0 and ε = 1 draw nothing from the generator.
    let mut a = sample_rng(3, 4);
    let mut b = sample_rng(3, 4);
    assert!(!Probability::ZERO.flip(&mut a));
    assert!(Probability::ONE.flip(&mut a));
    assert_eq!(a.random::<u64>(), b.random::<u64>());
    // A fair coin over many draws is near one half (a loose sanity bound).
    let half = Probability::new("ε", &parse_rational("1/2").unwrap()).unwrap();
    let mut rng = sample_rng(0, 0);
    let heads = (0..10_000).filter(|_| half.flip(&mut rng)).count();
    assert!((4_500..5_500).contains(&heads), "{heads}");
}

#[test]
fn probabilities_print_as_their_nearest_f64() {
    let p = |t: &str| Probability::new("ε", &parse_rational(t).unwrap()).unwrap();
    assert_eq!(p("0.9").to_f64(), 0.9);
    assert_eq!(p("1/3").to_f64(), 1.0 / 3.0);
    assert_eq!(Probability::ZERO.to_f64(), 0.0);
}

#[test]
fn plans_are_named_in_reports() {
    assert_eq!(Plan::Random.name(), "random");
    let mut stream = PiStream::new();
    assert_eq!(Plan::Pi(&mut stream).name(), "pi");
}

/// A stream reads past the prefix computed so far in the process: the digit after it is
/// computed on demand and equals the one a longer prefix gives.
#[test]
fn a_stream_reads_past_the_cached_prefix() {
    let held = pi_digits(1).len();
    assert!(held + 2 < PI_STREAM_PERIOD as usize);
    let mut s = PiStream::new();
    let read: Vec<u8> = (0..held + 2).map(|_| s.next_digit()).collect();
    let longer = pi_digits(held + 1);
    assert_eq!(read[0], 3);
    assert_eq!(read[1..], longer[..held + 1]);
}

/// A linear decay's ε_k have denominators dividing `lcm(q_start, q_end)·(E − 1)`, which must
/// stay at most 2^63: with `q_start = 2^32` and `q_end = 2` that is `2^32·(E − 1)`, exactly
/// 2^63 at `E = 2^31 + 1` (accepted) and above it at `E = 2^31 + 2` (refused).
#[test]
fn decay_schedules_are_refused_exactly_above_a_denominator_of_2_pow_63() {
    let p = |t: &str| Probability::new("ε", &parse_rational(t).unwrap()).unwrap();
    let schedule = EpsilonSchedule::Linear {
        start: p("1/4294967296"),
        end: p("1/2"),
    };
    assert!(schedule.validate((1 << 31) + 1).is_ok());
    assert!(schedule.validate((1 << 31) + 2).is_err());
    assert!(schedule.validate(2).is_ok());
    assert!(EpsilonSchedule::Constant(p("1/4294967296"))
        .validate(u32::MAX)
        .is_ok());
}

#[test]
fn linear_decay_reaches_one_tenth_at_the_last_episode() {
    let s = EpsilonSchedule::decay_to_one_tenth(Probability::ONE);
    let at = |k| {
        let p = s.at(k, 1000).unwrap();
        (p.numerator(), p.denominator())
    };
    assert_eq!(at(0), (1, 1));
    assert_eq!(at(999), (1, 10));
    assert_eq!(at(333), (7, 10)); // 1 − 0.9·333/999
    assert!(s.validate(1000).is_ok());
}

/// The reference mode's ε-decay is the paper's code's: expected values printed by CPython 3.11
/// running the code's loop (`epsilon_delta = (epsilon - 0.1) / episodes`, then
/// `epsilon = max(0.1, epsilon - epsilon_delta)` after each episode) and
/// `math.ceil(eps * 2**53)`, the count of `random.random()` values below `eps`.
#[test]
fn code_decay_is_the_paper_codes_f64_schedule_and_python_coin() {
    let s = EpsilonSchedule::CodeDecay {
        start: Probability::ONE,
    };
    let exact = |p: Probability| p.to_rational();
    let over_2_53 = |n: u64| Rational::new(BigInt::from(n), BigInt::from(1u64 << 53));
    assert_eq!(s.at(0, 1000).unwrap(), Probability::ONE);
    // Episode 999 of 1000: ε = 0.10089999999998849 (0x1.9d495182a95f3p-4), not 0.1.
    assert_eq!(
        exact(s.at(999, 1000).unwrap()),
        over_2_53(908_826_404_803_263)
    );
    // Episode 500: ε = 0.549999999999994.
    assert_eq!(
        exact(s.at(500, 1000).unwrap()),
        over_2_53(4_953_959_590_107_492)
    );
    // The sequence a learner reads is the same as `at`.
    let mut run = s.episodes(1000);
    for k in 0..1000 {
        assert_eq!(
            run.next_episode().unwrap(),
            s.at(k, 1000).unwrap(),
            "episode {k}"
        );
    }
    // Three episodes: 1.0, 0.7, 0.39999999999999997, then the floor 0.1 (the f64 0.1's coin).
    let short: Vec<Rational> = {
        let mut r = s.episodes(3);
        (0..5).map(|_| exact(r.next_episode().unwrap())).collect()
    };
    assert_eq!(short[1], over_2_53(6_305_039_478_318_694)); // ⌈0.7·2^53⌉
    assert_eq!(short[2], over_2_53(3_602_879_701_896_397)); // ⌈0.39999999999999997·2^53⌉
    assert_eq!(short[3], over_2_53(900_719_925_474_100)); // ⌈0.1·2^53⌉
    assert_eq!(short[4], short[3]);
    assert!(s.validate(1000).is_ok());
}

/// A path graph 0 → 1 → … → n−1 (goal) with unit costs, and back moves.
fn line(n: usize) -> Graph<Units> {
    let adjacency = (0..n)
        .map(|x| {
            let mut moves = Vec::new();
            if x > 0 {
                moves.push((x - 1, Units(1)));
            }
            if x + 1 < n {
                moves.push((x + 1, Units(1)));
            }
            moves
        })
        .collect();
    Graph::from_adjacency(
        adjacency,
        0,
        &[n - 1],
        (0..n).collect(),
        num_rational::BigRational::from_integer(1.into()),
    )
}

#[test]
fn invalid_parameters_are_typed_errors() {
    let g = line(3);
    let optimum = vec![Units(2), Units(1), Units(0)];
    let base = QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ONE));
    let try_with = |c: QLearningConfig| {
        QLearner::new(&g, &optimum, Units(0), &c, sample_rng(0, 0), Plan::Random).map(|_| ())
    };
    assert_eq!(
        try_with(QLearningConfig {
            episodes: 0,
            ..base.clone()
        }),
        Err(LearningError::NoEpisodes)
    );
    assert_eq!(
        try_with(QLearningConfig {
            max_steps: 0,
            ..base.clone()
        }),
        Err(LearningError::NoSteps)
    );
    for bad in ["0", "1.5", "-1"] {
        assert!(matches!(
            try_with(QLearningConfig {
                learning_rate: parse_rational(bad).unwrap(),
                ..base.clone()
            }),
            Err(LearningError::RateOutOfRange(_))
        ));
    }
    assert!(matches!(
        try_with(QLearningConfig {
            learning_rate: parse_rational("0.5").unwrap(),
            ..base.clone()
        }),
        Err(LearningError::FractionalRateNeedsFloat(_))
    ));
    let short = vec![Units(0)];
    assert!(matches!(
        QLearner::new(&g, &short, Units(0), &base, sample_rng(0, 0), Plan::Random),
        Err(LearningError::OptimumLength { .. })
    ));
}

#[test]
fn greedy_on_a_line_has_hand_derived_counts() {
    // Line 0 – 1 – 2 – 3 (goal), unit costs, Q₀ = 0, greedy (ε = 0), ties to the first action.
    // Actions: 0: [→]; 1: [←, →]; 2: [←, →]; 3: [←, stop]. G* = (3, 2, 1, 0).
    // Episode 1: 0→1 Q(0,→)=1+V(1)=1 | 1: tie, ← : Q(1,←)=1+V(0)=2 | 0→1 Q(0,→)=1 |
    // 1: → (0 < 2): Q(1,→)=1+V(2)=1 | 2: tie, ←: Q(2,←)=1+V(1)=2 | 1: → : Q(1,→)=1 |
    // 2: → (0 < 2): Q(2,→)=1+V(3)=1, goal entered by action 7.
    let g = line(4);
    let optimum = vec![Units(3), Units(2), Units(1), Units(0)];
    let config = QLearningConfig {
        episodes: 10,
        max_steps: 100,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let mut l = QLearner::new(
        &g,
        &optimum,
        Units(0),
        &config,
        sample_rng(0, 0),
        Plan::Random,
    )
    .unwrap();
    assert_eq!(
        l.advance(),
        Event::Milestone(Milestone::GoalDiscovered),
        "the first milestone is entering the goal"
    );
    assert_eq!(l.outcome().goal_discovered_at, Some(7));
    assert_eq!(l.outcome().actions, 7);
    // Episode 2: Q(0,→)=1+V(1)=2 | 1: → (1 < 2): Q(1,→)=1+V(2)=2, so V(1)=2 = G*(1) |
    // 2: → : goal (action 10). Episode 3: Q(0,→)=1+V(1)=3 = G*(0): V = G* everywhere after
    // action 11 | 1: tie (2, 2), ←: Q(1,←)=4 | 0: Q(0,→)=3 | 1: → | 2: → goal (action 15);
    // the run stops at the end of the converging episode.
    let outcome = l.run();
    assert_eq!(outcome.initial_optimal_at, Some(11));
    assert_eq!(outcome.converged_at, Some(11));
    assert_eq!(outcome.actions, 15);
    assert_eq!(outcome.episodes_run, 3);
    assert!(outcome.converged);
    assert_eq!(l.greedy_path().states, vec![0, 1, 2, 3]);
}

#[test]
fn the_count_at_target_falls_when_a_state_leaves_its_target() {
    // 0 (x1): [→2 cost 10, →1 cost 1]; 1: [→2 cost 1]; 2 the goal (termination only). Q₀ = 2,
    // greedy, ties to the first action; target (2, 3, 2). V starts at (2, 2, 2): two of three
    // at target. Episode 1: Q(0,→2) = 10 + V(2) = 12, V(0) stays 2. Episode 2: Q(0,→1) =
    // 1 + V(1) = 3, so V(0) = 3 leaves its target (one of three); Q(1,→2) = 1 + V(2) = 3 reaches
    // it (two of three). Episodes 3–5: Q(0,→1) = 1 + V(1) = 4. V(0) never returns to 2, so the
    // run never converges; a count that did not fall at action 2 would reach three.
    let g = Graph::from_adjacency(
        vec![
            vec![(2, Units(10)), (1, Units(1))],
            vec![(2, Units(1))],
            vec![],
        ],
        0,
        &[2],
        vec![0, 1, 2],
        num_rational::BigRational::from_integer(1.into()),
    );
    let target = vec![Units(2), Units(3), Units(2)];
    let config = QLearningConfig {
        episodes: 5,
        max_steps: 10,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let mut l = QLearner::new(
        &g,
        &target,
        Units(2),
        &config,
        sample_rng(0, 0),
        Plan::Random,
    )
    .unwrap();
    let o = l.run();
    assert_eq!((o.actions, o.episodes_run), (9, 5));
    assert_eq!(l.cost_to_go(), &[Units(4), Units(3), Units(2)]);
    assert!(!o.converged);
    assert_eq!(o.converged_at, None);
    // V(x1) was at its target before any action.
    assert_eq!(o.initial_optimal_at, Some(0));
}

#[test]
fn exact_rules_report_each_milestone_at_its_action() {
    // The line of `greedy_on_a_line_has_hand_derived_counts`: the goal is entered by action 7,
    // V(x1) = G*(x1) and V = G* everywhere after action 11 (the run then finishes the episode,
    // action 15). `advance` returns at each milestone, so the action count it leaves is the
    // milestone's own.
    let g = line(4);
    let optimum = vec![Units(3), Units(2), Units(1), Units(0)];
    let config = QLearningConfig {
        episodes: 10,
        max_steps: 100,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let mut l = QLearner::new(
        &g,
        &optimum,
        Units(0),
        &config,
        sample_rng(0, 0),
        Plan::Random,
    )
    .unwrap();
    let mut seen = Vec::new();
    while let Event::Milestone(m) = l.advance() {
        seen.push((m, l.outcome().actions));
    }
    assert_eq!(
        seen,
        [
            (Milestone::GoalDiscovered, 7),
            (Milestone::InitialOptimal, 11),
            (Milestone::Converged, 11),
        ]
    );
    assert_eq!(l.outcome().actions, 15);
}

#[test]
fn reference_rules_report_milestones_at_their_checks() {
    // Line 0 – 1 (goal), Q₀ = 0, greedy: the goal is entered at action 1, and V = G* from then
    // on, but the reference rules see it only at the check after action 1000 — where both the
    // initial state's and the whole table's milestones are reported, in that order.
    let g = line(2);
    let optimum = vec![Units(1), Units(0)];
    let config = QLearningConfig {
        episodes: 5000,
        max_steps: 10,
        rules: Rules::Reference,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let mut l = QLearner::new(
        &g,
        &optimum,
        Units(0),
        &config,
        sample_rng(0, 0),
        Plan::Random,
    )
    .unwrap();
    let mut seen = Vec::new();
    loop {
        match l.advance() {
            Event::Finished => break,
            Event::Milestone(m) => seen.push((m, l.outcome().actions)),
        }
    }
    assert_eq!(
        seen,
        [
            (Milestone::GoalDiscovered, 1),
            (Milestone::InitialOptimal, 1000),
            (Milestone::Converged, 1000),
        ]
    );
}

#[test]
fn reference_rules_check_only_every_thousand_actions() {
    // The same line, long enough that checks matter: 2 states, goal 1 — converges at the first
    // action under exact rules, but the reference checks first after action 1000.
    let g = line(2);
    let optimum = vec![Units(1), Units(0)];
    let exact = QLearningConfig {
        episodes: 5000,
        max_steps: 10,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let reference = QLearningConfig {
        rules: Rules::Reference,
        ..exact.clone()
    };
    let run = |c: &QLearningConfig| {
        QLearner::new(&g, &optimum, Units(0), c, sample_rng(0, 0), Plan::Random)
            .unwrap()
            .run()
    };
    let e = run(&exact);
    assert_eq!((e.converged_at, e.actions, e.episodes_run), (Some(1), 1, 1));
    let r = run(&reference);
    // One action per episode: the check after action 1000 happens in episode 1000 (index 999).
    assert_eq!((r.converged_at, r.actions), (Some(1000), 1000));
    assert_eq!(r.last_episode_index(), Some(999));
    assert_eq!(r.initial_optimal_at, Some(1000));
}

#[test]
fn fractional_learning_rates_run_on_f64_and_approach_the_optimum() {
    // Line 0 – 1 (goal), cost 1, ρ = 1/2, greedy: Q(0,→) after k visits is 1 − 2^−k (V(1) = 0).
    let g = Graph::<f64>::from_adjacency(
        vec![vec![(1, 1.0)], vec![(0, 1.0)]],
        0,
        &[1],
        vec![0, 1],
        num_rational::BigRational::from_integer(1.into()),
    );
    let optimum = vec![1.0, 0.0];
    let config = QLearningConfig {
        episodes: 3,
        max_steps: 10,
        learning_rate: parse_rational("1/2").unwrap(),
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let mut l = QLearner::new(&g, &optimum, 0.0, &config, sample_rng(0, 0), Plan::Random).unwrap();
    let o = l.run();
    assert_eq!(o.actions, 3);
    assert_eq!(l.q_values()[0], 0.875);
    assert!(!o.converged);
    assert_eq!(o.converged_at, None);
}

#[test]
fn fractional_learning_rates_blend_the_old_value_with_the_target() {
    // Line 0 – 1 (goal), cost 3, ρ = 1/2, greedy, Q₀ = 0: each visit sets
    // Q(0,→) ← (1 − ρ)·Q(0,→) + ρ·(3 + V(1)), so after k visits Q(0,→) = 3·(1 − 2^−k).
    let g = Graph::<f64>::from_adjacency(
        vec![vec![(1, 3.0)], vec![(0, 3.0)]],
        0,
        &[1],
        vec![0, 1],
        num_rational::BigRational::from_integer(1.into()),
    );
    for (episodes, want) in [(1, 1.5), (2, 2.25), (3, 2.625), (4, 2.8125)] {
        let config = QLearningConfig {
            episodes,
            max_steps: 10,
            learning_rate: parse_rational("1/2").unwrap(),
            ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
        };
        let optimum = vec![3.0, 0.0];
        let mut l =
            QLearner::new(&g, &optimum, 0.0, &config, sample_rng(0, 0), Plan::Random).unwrap();
        let o = l.run();
        assert_eq!(o.actions, episodes as u64);
        assert_eq!(l.q_values()[0], want, "after {episodes} visits");
        assert_eq!(l.cost_to_go()[0], want, "V(0) after {episodes} visits");
    }
}

#[test]
fn tracked_states_are_those_reachable_from_x1_with_an_action() {
    // 0 → {1, 3}, 1 (goal) → 0, 2 → 1 (not reachable from 0), 3 without actions.
    let g = Graph::<f64>::from_adjacency(
        vec![
            vec![(1, 1.0), (3, 1.0)],
            vec![(0, 1.0)],
            vec![(1, 1.0)],
            vec![],
        ],
        0,
        &[1],
        vec![0, 1, 2, 3],
        num_rational::BigRational::from_integer(1.into()),
    );
    let config = QLearningConfig {
        episodes: 1,
        max_steps: 1,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(Probability::ZERO))
    };
    let optimum = vec![1.0, 0.0, 1.0, f64::INFINITY];
    let l = QLearner::new(&g, &optimum, 0.0, &config, sample_rng(0, 0), Plan::Random).unwrap();
    let tracked: Vec<bool> = (0..4).map(|x| l.is_tracked(x)).collect();
    assert_eq!(tracked, [true, true, false, false]);
}

/// Runs Q-learning (ρ = 1, Q₀ = 0, the given ε over the random plan) on an exact problem and
/// checks every update against the oracle.
fn check_invariants(p: &Problem, epsilon: &str, seed: u64) -> Result<(), TestCaseError> {
    let oracle = bellman_ford(p).cost_to_go;
    let eg = ExactGraph::new(p);
    with_exact_graph!(&eg, g => check_on(p, g, &oracle, epsilon, seed))
}

fn check_on<V>(
    p: &Problem,
    g: &Graph<V>,
    oracle: &[Ext],
    epsilon: &str,
    seed: u64,
) -> Result<(), TestCaseError>
where
    V: truecost::learning::q_learning::LearningValue + truecost::value::ExactValue,
{
    let n = p.states();
    // G* in the graph's value type, from the exact planner, checked against the oracle.
    let optimum = truecost::solvers::dijkstra::to_goals(g).cost_to_go;
    prop_assert_eq!(common::exact_all(g, &optimum), oracle.to_vec());
    // Q*(x, u): moves in order, then termination (0) at goals.
    let q_star: Vec<Vec<Ext>> = (0..n)
        .map(|x| {
            let mut row: Vec<Ext> = p
                .moves(x)
                .iter()
                .map(|m| common::add(&m.cost, &oracle[m.successor]))
                .collect();
            if p.is_goal(x) {
                row.push(Some(Q::zero()));
            }
            row
        })
        .collect();
    let successor: Vec<Vec<usize>> = (0..n)
        .map(|x| {
            let mut row: Vec<usize> = p.moves(x).iter().map(|m| m.successor).collect();
            if p.is_goal(x) {
                row.push(x);
            }
            row
        })
        .collect();
    // Tracked states, computed independently: reachable from x1, with an action.
    let reach = common::reachable(p);
    let tracked: Vec<bool> = (0..n)
        .map(|x| reach[x] && !successor[x].is_empty())
        .collect();
    let config = QLearningConfig {
        episodes: 30,
        max_steps: 40,
        ..QLearningConfig::paper(EpsilonSchedule::Constant(
            Probability::new("ε", &parse_rational(epsilon).unwrap()).unwrap(),
        ))
    };
    let mut learner = QLearner::new(
        g,
        &optimum,
        V::zero(),
        &config,
        sample_rng(seed, 0),
        Plan::Random,
    )
    .unwrap();
    let all_optimal = |v: &[V]| (0..n).all(|x| !tracked[x] || exact(g, &v[x]) == oracle[x]);
    let mut actions = 0u64;
    let mut first_converged: Option<u64> = all_optimal(learner.cost_to_go()).then_some(0);
    let mut first_initial: Option<u64> =
        (exact(g, &learner.cost_to_go()[p.initial()]) == oracle[p.initial()]).then_some(0);
    let mut first_goal: Option<u64> = None;
    let mut failure: Option<String> = None;
    let outcome = learner.run_observed(&mut |x: usize, a: usize, old: &V, new: &V, v: &[V]| {
        actions += 1;
        if failure.is_some() {
            return;
        }
        let (o, w) = (exact(g, old), exact(g, new));
        if common::lt_ext(&w, &o) {
            failure = Some(format!("Q̂({x},{a}) decreased from {o:?} to {w:?}"));
        } else if common::lt_ext(&q_star[x][a], &w) {
            failure = Some(format!(
                "Q̂({x},{a}) = {w:?} exceeds Q* = {:?}",
                q_star[x][a]
            ));
        }
        // V(x) is the minimum of x's entries: recomputed here from the oracle's side only at x.
        let converged_now = all_optimal(v);
        if first_converged.is_some() && !converged_now {
            failure = Some(format!("convergence lost after action {actions}"));
        }
        if first_converged.is_none() && converged_now {
            first_converged = Some(actions);
        }
        if first_initial.is_none() && exact(g, &v[p.initial()]) == oracle[p.initial()] {
            first_initial = Some(actions);
        }
        if first_goal.is_none() && p.is_goal(successor[x][a]) {
            first_goal = Some(actions);
        }
    });
    prop_assert!(failure.is_none(), "{}", failure.unwrap_or_default());
    prop_assert_eq!(outcome.actions, actions);
    prop_assert_eq!(outcome.converged_at, first_converged);
    prop_assert_eq!(outcome.initial_optimal_at, first_initial);
    prop_assert_eq!(outcome.goal_discovered_at, first_goal);
    // Every final V(x) is the minimum of x's final entries.
    for x in 0..n {
        let range = learner.actions_of(x);
        let min = learner.q_values()[range.clone()]
            .iter()
            .fold(None::<&V>, |m, q| match m {
                Some(b) if q.compare(b) != std::cmp::Ordering::Less => Some(b),
                _ => Some(q),
            });
        let expected = min.cloned().unwrap_or_else(V::infinity);
        prop_assert!(learner.cost_to_go()[x] == expected, "V({x})");
    }
    // The greedy path follows first minimisers from x1 and stops at a goal or a repeat.
    let path = learner.greedy_path();
    prop_assert_eq!(path.states[0], p.initial());
    if path.reached_goal {
        prop_assert!(p.is_goal(*path.states.last().unwrap()));
        // Its cost is at least G*(x1).
        let c = exact(g, &path.cost);
        prop_assert!(!common::lt_ext(&c, &oracle[p.initial()]));
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// docs/spec.md §2 derandomized Q-learning (ρ = 1, Q₀ = 0 ≤ Q*): every update is monotone and
    /// bounded by Q*; V = G* on every tracked state, once reached, stays; the reported
    /// milestones are the first actions at which they hold (checked against the oracle after
    /// every update).
    #[test]
    fn derandomized_q_learning_invariants(
        p in small_problem(),
        eps in prop::sample::select(vec!["0", "1/4", "1/2", "9/10", "1"]),
        seed in 0u64..1000,
    ) {
        check_invariants(&p, eps, seed)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// The same invariants on problems whose costs force big-rational values.
    #[test]
    fn derandomized_q_learning_invariants_on_big_rationals(
        p in huge_problem(),
        eps in prop::sample::select(vec!["0", "1/2", "1"]),
        seed in 0u64..1000,
    ) {
        prop_assert!(matches!(ExactGraph::new(&p), ExactGraph::Big(_)));
        check_invariants(&p, eps, seed)?;
    }
}

//! The degree a deterministic analysis is certain to meet, found before the first probe
//! (module `objectives::parametric::degree`), against the engine run with the degree bound
//! lifted: on random files with rewards of both signs, every bound found is met by the values
//! the analysis builds (so a file refused by it needs more than the bound), and long chains
//! with mixed rewards are refused before the first probe.

use num_traits::{One, Zero};
use truecost::objectives::parametric::bounds::certain_degree;
use truecost::objectives::parametric::degree::{near_one, near_zero, Reason};
use truecost::objectives::parametric::{
    discount_breakpoints, discount_breakpoints_limited, DiscountAnalysis, Limits, ParametricError,
    Search,
};
use truecost::objectives::Model;
use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use truecost::value::Rational;

/// A small generator (64-bit LCG).
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: u64) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) % n
    }
}

fn det(cost: u64, to: usize) -> StochasticAction {
    StochasticAction {
        cost: Rational::from_integer(cost.into()),
        outcomes: vec![Outcome {
            successor: to,
            probability: Rational::one(),
            kind: OutcomeKind::Listed,
        }],
    }
}

/// A model on `actions` (goal: the last state) with the given rewards, action by action.
fn model(actions: Vec<Vec<StochasticAction>>, rewards: &[i64], name: &str) -> Model {
    let goal = actions.len() - 1;
    let mut m = Model::from_problem(
        StochasticProblem::new(actions, 0, vec![goal]).unwrap(),
        name.into(),
    );
    assert_eq!(m.reward.len(), rewards.len());
    for (r, &v) in m.reward.iter_mut().zip(rewards) {
        *r = Rational::from_integer(v.into());
    }
    m
}

/// A random deterministic file of `n` states (the last the goal): 1 to 3 actions a state,
/// most of them one state on (long chains), the others anywhere; rewards of both signs
/// (`−3..=3`) or, one time in four, all negative.
fn random(seed: u64, n: usize) -> Model {
    let mut g = Lcg(seed);
    let negative = g.below(4) == 0;
    let mut actions = Vec::new();
    let mut rewards = Vec::new();
    for x in 0..n - 1 {
        let k = 1 + g.below(3);
        let mut list = Vec::new();
        for i in 0..k {
            let to = if i == 0 && g.below(5) > 0 {
                x + 1
            } else {
                g.below(n as u64) as usize
            };
            list.push(det(g.below(3), to));
            let r = g.below(7) as i64 - 3;
            rewards.push(if negative { -1 - r.abs() } else { r });
        }
        actions.push(list);
    }
    actions.push(Vec::new());
    model(actions, &rewards, &format!("random {seed}"))
}

fn running(m: &Model) -> Vec<usize> {
    (0..m.problem.states())
        .filter(|&x| !m.terminal[x])
        .collect()
}

/// The analysis with the degree bound lifted.
fn lifted(m: &Model) -> DiscountAnalysis {
    let limits = Limits {
        chain_degree: usize::MAX,
        ..Limits::default()
    };
    discount_breakpoints_limited(m, Search::Pruned, limits, &mut |_| {}).unwrap()
}

/// On 200 random files, each bound found before the first probe (next to 1, next to 0, and
/// their maximum) is at most the largest degree the analysis meets with the bound lifted;
/// the bounds are not trivial (some reach 5 or more, with rewards of both signs).
#[test]
fn the_certain_degree_is_met_by_the_analysis() {
    let (mut strong, mut mixed) = (0, 0);
    for seed in 0..200 {
        let n = 4 + (seed % 11) as usize;
        let m = random(seed, n);
        let run = running(&m);
        let d = lifted(&m);
        for (which, c) in [
            ("near one", near_one(&m, &run)),
            ("near zero", near_zero(&m, &run)),
            ("both", certain_degree(&m, &run)),
        ] {
            if let Some(c) = c {
                assert!(
                    d.degree >= c.degree,
                    "seed {seed} ({which}): the analysis meets degree {} < {c:?}",
                    d.degree
                );
            }
        }
        if let Some(c) = certain_degree(&m, &run) {
            if c.degree >= 5 {
                strong += 1;
                mixed += usize::from(m.reward.iter().any(|r| r > &Rational::zero()));
            }
        }
    }
    assert!(strong >= 10 && mixed >= 5, "{strong} strong, {mixed} mixed");
}

/// With a degree bound of 4, every random file refused before the first probe needs more
/// than 4 when analysed with the bound lifted, and some are refused so, with rewards of both
/// signs among them.
#[test]
fn every_early_refusal_needs_more_than_the_bound() {
    let small = Limits {
        chain_degree: 4,
        ..Limits::default()
    };
    let (mut refused, mut mixed) = (0, 0);
    for seed in 1000..1150 {
        let n = 6 + (seed % 9) as usize;
        let m = random(seed, n);
        let mut probes = 0;
        match discount_breakpoints_limited(&m, Search::Pruned, small, &mut |_| probes += 1) {
            Err(ParametricError::CertainDegree { degree, bound, .. }) => {
                assert_eq!((bound, probes), (4, 0), "seed {seed}");
                let d = lifted(&m);
                assert!(
                    d.degree > 4 && d.degree >= degree,
                    "seed {seed}: refused at {degree}, needs {}",
                    d.degree
                );
                refused += 1;
                mixed += usize::from(m.reward.iter().any(|r| r > &Rational::zero()));
            }
            Err(ParametricError::ChainDegree { .. }) => {}
            Err(e) => panic!("seed {seed}: {e}"),
            Ok(d) => assert!(d.degree <= 4, "seed {seed}"),
        }
    }
    assert!(
        refused >= 10 && mixed >= 5,
        "{refused} refused, {mixed} mixed"
    );
}

/// A chain of `n` running states to the goal `n`: moving on has reward `+2` and `−1` in turn,
/// staying `−3`, and moving back (from state 1 on) `back`. With `back = −3` every cycle has a
/// negative total, so next to 1 the optimal policies end the episode from state 0, `n` moves
/// away; with `back = −1` a step on and back totals `+1`, and nothing is certain next to 1.
fn mixed_chain(n: usize, back: i64) -> Model {
    let mut actions = Vec::new();
    let mut rewards = Vec::new();
    for x in 0..n {
        let mut list = vec![det(1, x + 1), det(1, x)];
        rewards.extend([if x % 2 == 0 { 2 } else { -1 }, -3]);
        if x > 0 {
            list.push(det(1, x - 1));
            rewards.push(back);
        }
        actions.push(list);
    }
    actions.push(Vec::new());
    model(actions, &rewards, "mixed chain")
}

/// A 202-state chain with rewards of both signs and cycles of negative total: refused before
/// the first probe (state 0 is 202 moves from the goal: degree ≥ 201), and with the bound
/// lifted the analysis indeed builds values of degree 201. With a cycle of positive total the
/// bound next to 1 does not apply.
#[test]
fn a_long_chain_with_mixed_rewards_is_refused_before_the_first_probe() {
    let m = mixed_chain(202, -3);
    let run = running(&m);
    let c = near_one(&m, &run).unwrap();
    assert_eq!(
        (c.state, c.degree, c.reason),
        (0, 201, Reason::NearOne { moves: 202 })
    );
    let e = discount_breakpoints(&m).unwrap_err();
    let text = e.to_string();
    assert!(
        matches!(
            e,
            ParametricError::CertainDegree {
                state: 0,
                degree: 201,
                bound: 200,
                ..
            }
        ),
        "{text}"
    );
    for w in [
        "state 0 is 202 moves",
        "reaching no cycle of rewards totalling 0 or more",
        "degree >= 201",
        "at most 200",
        "before any probe",
    ] {
        assert!(text.contains(w), "{w:?} missing from {text}");
    }
    let d = lifted(&m);
    assert_eq!(d.degree, 201);
    assert!(d.breakpoints.is_empty());
    // A step on (+2) and back (−1) totals +1: a cycle worth staying in, next to 1.
    let m = mixed_chain(202, -1);
    assert_eq!(near_one(&m, &running(&m)), None);
}

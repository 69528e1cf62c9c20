//! Taxi at full size: `discount` on deterministic models (successor chains instead of the
//! Krylov denominator, so Taxi's 400 running states are no longer refused), `render --env taxi`
//! of one slice of the state space, and `verify --claim C4 --env taxi --initial STATE`.
//!
//! Every expected value comes from an independent computation: brute force over all
//! stationary policies of small deterministic models (each evaluated by its own exact Gaussian
//! elimination), the general (Krylov) engine on the same model made formally stochastic,
//! breadth-first distances on Gymnasium's Taxi table with the closed-form discounted value of a
//! shortest path, and Taxi's map text.

mod common;

use num_bigint::BigInt;
use num_traits::{One, Zero};

use common::Lcg;

use truecost::envs::{taxi, EnvSpec, Environment};
use truecost::figures::envs::{taxi_policy_overlay, taxi_scene, taxi_value_overlay, TaxiSlice};
use truecost::figures::render::{draw, Overlay};
use truecost::objectives::parametric::degree::Reason;
use truecost::objectives::parametric::{discount_breakpoints, DiscountAnalysis, ParametricError};
use truecost::objectives::{Model, Objective};
use truecost::stochastic::{Outcome, OutcomeKind, StochasticAction, StochasticProblem};
use truecost::value::{Extended, Rational};

fn q(s: &str) -> Rational {
    s.parse().unwrap()
}

fn int(k: i64) -> Rational {
    Rational::from_integer(k.into())
}

// ---------------------------------------------------------------------------------------------
// Small deterministic models: brute force over every stationary policy.

/// A deterministic action (cost, successor).
fn det(cost: i64, to: usize) -> StochasticAction {
    StochasticAction {
        cost: int(cost),
        outcomes: vec![Outcome {
            successor: to,
            probability: Rational::one(),
            kind: OutcomeKind::Listed,
        }],
    }
}

/// A random deterministic problem: states `0..n-1` run (2 or 3 actions each, costs 0..=4,
/// random successors), state `n-1` is the goal, 0 is initial.
fn random_model(seed: u64, n: usize) -> Model {
    let mut g = Lcg(seed);
    let mut actions = Vec::new();
    for _ in 0..n - 1 {
        let k = 2 + g.below(2) as usize;
        actions.push(
            (0..k)
                .map(|_| det(g.below(5) as i64, g.below(n as u64) as usize))
                .collect(),
        );
    }
    actions.push(Vec::new());
    let p = StochasticProblem::new(actions, 0, vec![n - 1]).unwrap();
    Model::from_problem(p, format!("random {seed}"))
}

/// Solves `A z = b` exactly (Gauss–Jordan with pivot search).
fn gauss(mut a: Vec<Vec<Rational>>, mut b: Vec<Rational>) -> Vec<Rational> {
    let n = b.len();
    for c in 0..n {
        let p = (c..n).find(|&r| !a[r][c].is_zero()).expect("regular");
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c].clone();
        for r in 0..n {
            if r != c && !a[r][c].is_zero() {
                let f = &a[r][c] / &pivot[c];
                for (ark, pk) in a[r].iter_mut().zip(&pivot).skip(c) {
                    *ark -= &f * pk;
                }
                let t = &f * &b[c];
                b[r] -= t;
            }
        }
    }
    (0..n).map(|i| &b[i] / &a[i][i]).collect()
}

/// The discounted values of a policy (global action ids) at `α`: `(I − αP) v = r`.
fn values(m: &Model, choice: &[Option<usize>], alpha: &Rational) -> Vec<Rational> {
    let p = &m.problem;
    let n = p.states();
    let mut a = vec![vec![Rational::zero(); n]; n];
    let mut b = vec![Rational::zero(); n];
    for x in 0..n {
        a[x][x] = Rational::one();
        if m.terminal[x] {
            continue;
        }
        let u = choice[x].unwrap();
        b[x] = m.reward[u].clone();
        for o in p.outcomes(u) {
            if !m.terminal[o.successor] {
                a[x][o.successor] -= alpha * &o.probability;
            }
        }
    }
    gauss(a, b)
}

/// Every stationary deterministic policy (global action ids; `None` where the episode ended).
fn all_policies(m: &Model) -> Vec<Vec<Option<usize>>> {
    let p = &m.problem;
    let mut out = vec![vec![]];
    for x in 0..p.states() {
        let choices: Vec<Option<usize>> = if m.terminal[x] {
            vec![None]
        } else {
            p.actions(x).map(Some).collect()
        };
        out = out
            .into_iter()
            .flat_map(|prefix: Vec<Option<usize>>| {
                choices.iter().map(move |c| {
                    let mut v = prefix.clone();
                    v.push(*c);
                    v
                })
            })
            .collect();
    }
    out
}

/// Brute force at `α`: the optimal values (pointwise maximum over all policies, attained by one
/// policy) and per state the optimal actions (indices in `U(x)`).
fn brute_optimal(m: &Model, alpha: &Rational) -> (Vec<Rational>, Vec<Vec<usize>>) {
    let p = &m.problem;
    let all: Vec<Vec<Rational>> = all_policies(m)
        .iter()
        .map(|pol| values(m, pol, alpha))
        .collect();
    let n = p.states();
    let best: Vec<Rational> = (0..n)
        .map(|x| all.iter().map(|v| v[x].clone()).max().unwrap())
        .collect();
    assert!(
        all.contains(&best),
        "one policy attains the pointwise maximum"
    );
    let optimal = (0..n)
        .map(|x| {
            if m.terminal[x] {
                return Vec::new();
            }
            p.actions(x)
                .filter(|&a| {
                    let y = p.outcomes(a)[0].successor;
                    let vy = if m.terminal[y] {
                        Rational::zero()
                    } else {
                        best[y].clone()
                    };
                    &m.reward[a] + alpha * vy == best[x]
                })
                .map(|a| a - p.actions(x).start)
                .collect()
        })
        .collect();
    (best, optimal)
}

/// From the initial state, a deterministic policy: (reaches the goal, its total cost).
fn follow(m: &Model, pol: &[Option<usize>]) -> (bool, Rational) {
    let p = &m.problem;
    let (mut x, mut cost) = (p.initial(), Rational::zero());
    for _ in 0..=p.states() {
        if p.is_goal(x) {
            return (true, cost);
        }
        match pol[x] {
            Some(a) if !m.terminal[x] => {
                cost += p.cost(a);
                x = p.outcomes(a)[0].successor;
            }
            _ => return (false, cost),
        }
    }
    (false, cost)
}

fn tiny() -> Rational {
    Rational::new(BigInt::one(), BigInt::from(10).pow(40))
}

/// Checks an analysis of a small deterministic model against brute force.
fn check_against_brute_force(m: &Model, d: &DiscountAnalysis) {
    assert!(d.deterministic);
    assert_eq!(d.intervals.len(), d.breakpoints.len() + 1);
    let p = &m.problem;
    let width = Rational::new(BigInt::one(), BigInt::from(10).pow(30));
    let policies = all_policies(m);
    for (i, iv) in d.intervals.iter().enumerate() {
        // The optimal action sets at the sample are brute force's.
        let (_, optimal) = brute_optimal(m, &iv.sample);
        assert_eq!(iv.optimal, optimal, "interval {i} at {}", iv.sample);
        // Just inside both ends (brackets of at most 1e-30) the sets are the same.
        let mut points = Vec::new();
        if let Some(lo) = &iv.lo {
            let mut r = lo.clone();
            r.refine_to(&width);
            points.push(&r.hi + tiny());
        }
        if let Some(hi) = &iv.hi {
            let mut r = hi.clone();
            r.refine_to(&width);
            points.push(&r.lo - tiny());
        }
        for a in &points {
            assert_eq!(
                brute_optimal(m, a).1,
                optimal,
                "interval {i} near its end {a}"
            );
        }
        // Success and truecost over the optimal policies, by following each of them.
        let opt: Vec<(bool, Rational)> = policies
            .iter()
            .filter(|pol| {
                (0..p.states()).all(|x| match pol[x] {
                    Some(a) => optimal[x].contains(&(a - p.actions(x).start)),
                    None => true,
                })
            })
            .map(|pol| follow(m, pol))
            .collect();
        let reach = |r: bool| if r { Rational::one() } else { Rational::zero() };
        let min = opt.iter().map(|o| reach(o.0)).min().unwrap();
        let max = opt.iter().map(|o| reach(o.0)).max().unwrap();
        assert_eq!(
            (&iv.achievement.success.min, &iv.achievement.success.max),
            (&min, &max)
        );
        let costs: Vec<Extended> = opt
            .iter()
            .map(|(r, c)| {
                if *r {
                    Extended::Finite(c.clone())
                } else {
                    Extended::Infinite
                }
            })
            .collect();
        assert_eq!(
            iv.achievement.truecost_min,
            costs.iter().min().unwrap().clone()
        );
        assert_eq!(
            iv.achievement.truecost_max,
            costs.iter().max().unwrap().clone()
        );
    }
    // Consecutive intervals differ unless the breakpoint is a tie at a single point.
    for (k, b) in d.breakpoints.iter().enumerate() {
        let (l, r) = (&d.intervals[k].optimal, &d.intervals[k + 1].optimal);
        assert_eq!(b.touch, l == r, "breakpoint {k}");
        if let Some(at) = b.at.as_rational() {
            // At a rational breakpoint brute force sees both sides' actions as optimal.
            let (_, here) = brute_optimal(m, at);
            for x in 0..p.states() {
                assert!(l[x].iter().chain(&r[x]).all(|a| here[x].contains(a)));
            }
        }
    }
    // No change is missed: on a grid of α the brute-force optimal sets change only across a
    // breakpoint.
    let grid: Vec<Rational> = (1..40)
        .map(|k| Rational::new(k.into(), 40.into()))
        .collect();
    let sets: Vec<Vec<Vec<usize>>> = grid.iter().map(|a| brute_optimal(m, a).1).collect();
    for k in 1..grid.len() {
        if sets[k] != sets[k - 1] {
            assert!(
                d.breakpoints.iter().any(|b| {
                    b.at.cmp_rational(&grid[k - 1]) != std::cmp::Ordering::Less
                        && b.at.cmp_rational(&grid[k]) != std::cmp::Ordering::Greater
                }),
                "a change between {} and {} without a breakpoint",
                grid[k - 1],
                grid[k]
            );
        }
    }
}

#[test]
fn deterministic_path_agrees_with_brute_force_on_random_models() {
    let mut with_breakpoints = 0;
    for seed in 0..40 {
        let n = 3 + (seed % 3) as usize; // 3..=5 states
        let m = random_model(seed, n);
        let d = discount_breakpoints(&m).unwrap();
        with_breakpoints += usize::from(!d.breakpoints.is_empty());
        check_against_brute_force(&m, &d);
    }
    // The family is not trivial: discounting changes the optimal policy in some of them.
    assert!(with_breakpoints >= 5, "{with_breakpoints}");
}

/// The paper's C3 worked example (docs/spec.md §6): the discount-optimal policy from 0 avoids the goal
/// exactly when `1/(1−α) < Σ_{i=1..5} i α^{i−1}`; one breakpoint, the threshold.
#[test]
fn c3_example_threshold_by_the_deterministic_path() {
    let actions: Vec<Vec<StochasticAction>> = (0..6usize)
        .map(|x| {
            if x == 5 {
                return Vec::new();
            }
            [x.saturating_sub(1), (x + 1).min(5)]
                .into_iter()
                .map(|y| det(x as i64 + 1, y))
                .collect()
        })
        .collect();
    let m = Model::from_problem(
        StochasticProblem::new(actions, 0, vec![5]).unwrap(),
        "c3".into(),
    );
    let d = discount_breakpoints(&m).unwrap();
    check_against_brute_force(&m, &d);
    // At 0 the policy "stay" (u = −1, a self-loop costing 1) against "walk to the goal": the
    // threshold solves 1/(1−α) = 1 + 2α + 3α² + 4α³ + 5α⁴; both sides checked exactly.
    let at0: Vec<&truecost::algebra::poly::roots::Root> =
        d.breakpoints.iter().map(|b| &b.at).collect();
    assert!(!at0.is_empty());
    let f = |a: &Rational| {
        let lhs = Rational::one() / (Rational::one() - a);
        let rhs = (1..=5).fold(Rational::zero(), |s, i| {
            s + int(i) * num_traits::pow::pow(a.clone(), (i - 1) as usize)
        });
        lhs.cmp(&rhs)
    };
    let mut threshold = None;
    for b in &d.breakpoints {
        let mut r = b.at.clone();
        r.refine_to(&Rational::new(BigInt::one(), BigInt::from(10).pow(30)));
        if f(&r.lo) != f(&r.hi) {
            threshold = Some(r);
        }
    }
    let r = threshold.expect("the C3 threshold is a breakpoint");
    assert!(&r.hi - &r.lo <= Rational::new(BigInt::one(), BigInt::from(10).pow(30)));
    assert!(r.lo > q("1/2") && r.hi < q("1"));
}

/// The model with one extra, unreachable running state whose single action has two outcomes:
/// the same problem for the discount question, but the general (Krylov) engine runs.
fn made_stochastic(m: &Model) -> Model {
    let p = &m.problem;
    let n = p.states();
    let mut actions = p.action_lists();
    let goal = p.goals()[0];
    actions.push(vec![StochasticAction {
        cost: int(1),
        outcomes: vec![
            Outcome {
                successor: goal,
                probability: q("1/2"),
                kind: OutcomeKind::Listed,
            },
            Outcome {
                successor: n,
                probability: q("1/2"),
                kind: OutcomeKind::Listed,
            },
        ],
    }]);
    let p2 = StochasticProblem::new(actions, p.initial(), p.goals().to_vec()).unwrap();
    Model::from_problem(p2, "stochastic twin".into())
}

#[test]
fn deterministic_and_general_engines_agree() {
    let mut compared = 0;
    // Small models, and a few of 16 states (brute force is out of reach there, the general
    // engine is not).
    for seed in (100..130).chain(200..206) {
        let m = random_model(seed, if seed < 200 { 5 } else { 16 });
        let d = discount_breakpoints(&m).unwrap();
        let twin = made_stochastic(&m);
        let g = discount_breakpoints(&twin).unwrap();
        assert!(d.deterministic && !g.deterministic);
        assert_eq!(d.breakpoints.len(), g.breakpoints.len(), "seed {seed}");
        for (a, b) in d.breakpoints.iter().zip(&g.breakpoints) {
            assert_eq!(
                a.at.compare(&b.at),
                std::cmp::Ordering::Equal,
                "seed {seed}"
            );
            assert_eq!(a.touch, b.touch);
            assert_eq!(a.achievement, b.achievement);
        }
        for (a, b) in d.intervals.iter().zip(&g.intervals) {
            assert_eq!(a.optimal[..], b.optimal[..a.optimal.len()], "seed {seed}");
            assert_eq!(a.achievement, b.achievement);
        }
        compared += d.breakpoints.len();
    }
    assert!(compared >= 3, "{compared}");
}

#[test]
fn chain_degree_bound_is_checked_before_any_probe_and_while_running() {
    // A line of `n` states (cost `first` on the first step, 1 on the others).
    let line = |n: usize, first: i64| {
        let actions = (0..n)
            .map(|x| {
                if x + 1 < n {
                    vec![det(if x == 0 { first } else { 1 }, x + 1)]
                } else {
                    vec![]
                }
            })
            .collect();
        Model::from_problem(
            StochasticProblem::new(actions, 0, vec![n - 1]).unwrap(),
            "line".into(),
        )
    };
    // 251 states, every reward negative: state 0 is 250 moves from the goal, so every policy
    // optimal near alpha = 1 ends the episode from it and its value has degree 249 > 200,
    // refused before the first probe.
    let e = discount_breakpoints(&line(251, 1)).unwrap_err();
    assert!(
        matches!(
            e,
            ParametricError::CertainDegree {
                state: 0,
                degree: 249,
                reason: Reason::NearOne { moves: 250 },
                bound: 200
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("before any probe"), "{e}");
    assert!(e.to_string().contains("at most 200"), "{e}");
    // A first step of reward 0: not every reward is negative, but the line has no cycle, so
    // the same bound applies before the first probe.
    let e = discount_breakpoints(&line(251, 0)).unwrap_err();
    assert!(
        matches!(e, ParametricError::CertainDegree { degree: 249, .. }),
        "{e}"
    );
    // Every state may also stay (reward 0, a cycle of total 0) and every move forward has
    // reward 0 but the last, 1 (so the actions of greatest reward tie but at the last state):
    // neither bound before the probes applies, and the degree of the optimal policy (move on,
    // to collect the 1) is caught while the first probe evaluates it.
    let n = 251;
    let actions = (0..n)
        .map(|x| {
            if x + 1 < n {
                vec![det(0, x + 1), det(0, x)]
            } else {
                vec![]
            }
        })
        .collect();
    let mut stay = Model::from_problem(
        StochasticProblem::new(actions, 0, vec![n - 1]).unwrap(),
        "line with stays".into(),
    );
    let last = stay.problem.actions(n - 2).start;
    stay.reward[last] = Rational::one();
    let e = discount_breakpoints(&stay).unwrap_err();
    assert!(
        matches!(e, ParametricError::ChainDegree { degree, bound: 200 } if degree > 200),
        "{e}"
    );
    assert!(e.to_string().contains("at most 200"), "{e}");
    // A line of 150 is within the bound: no choice, no breakpoint, truecost 149.
    let n = 150;
    let actions = (0..n)
        .map(|x| {
            if x + 1 < n {
                vec![det(1, x + 1)]
            } else {
                vec![]
            }
        })
        .collect();
    let m = Model::from_problem(
        StochasticProblem::new(actions, 0, vec![n - 1]).unwrap(),
        "line".into(),
    );
    let d = discount_breakpoints(&m).unwrap();
    assert_eq!((d.breakpoints.len(), d.degree), (0, 148));
    assert_eq!(
        d.intervals[0].achievement.truecost_min,
        Extended::Finite(int(149))
    );
}

// ---------------------------------------------------------------------------------------------
// Taxi: breadth-first distances on Gymnasium's table.

fn taxi_env() -> Environment {
    EnvSpec::parse("taxi").unwrap().build().unwrap()
}

/// Per state, the least number of actions to a delivery (Gymnasium's table, `None` at goals),
/// by relaxation to a fixpoint.
fn taxi_distances(env: &Environment) -> Vec<Option<u32>> {
    let n = env.states();
    let mut dist: Vec<Option<u32>> = vec![None; n];
    loop {
        let mut changed = false;
        for x in (0..n).filter(|&x| !env.is_terminal(x)) {
            for t in env.table[x].iter().map(|o| &o[0]) {
                let via = if t.terminated {
                    Some(1)
                } else if env.is_terminal(t.next) {
                    None
                } else {
                    dist[t.next].map(|d| d + 1)
                };
                if let Some(v) = via {
                    if dist[x].is_none_or(|d| v < d) {
                        dist[x] = Some(v);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            return dist;
        }
    }
}

/// The actions on shortest paths: a delivery where one is possible, else a move (reward −1)
/// to a state one step closer.
fn taxi_shortest_actions(env: &Environment, dist: &[Option<u32>]) -> Vec<Vec<usize>> {
    (0..env.states())
        .map(|x| {
            if env.is_terminal(x) {
                return Vec::new();
            }
            let d = dist[x].unwrap();
            (0..6)
                .filter(|&a| {
                    let t = &env.table[x][a][0];
                    (t.terminated && d == 1)
                        || (t.reward == -1
                            && !env.is_terminal(t.next)
                            && dist[t.next] == Some(d - 1))
                })
                .collect()
        })
        .collect()
}

/// The discounted return (Gymnasium's rewards) of a shortest path of `d` actions: `d − 1`
/// rewards of −1, then +20.
fn shortest_return(d: u32, alpha: &Rational) -> Rational {
    let mut v = Rational::zero();
    let mut power = Rational::one();
    for _ in 0..d - 1 {
        v -= &power;
        power *= alpha;
    }
    v + int(20) * power
}

#[test]
fn taxi_discount_has_no_breakpoint_and_shortest_paths_are_optimal() {
    let env = taxi_env();
    let m = Model::from_environment(&env).unwrap();
    let d = discount_breakpoints(&m).unwrap();
    assert!(d.deterministic);
    assert_eq!(d.running_states, 400);
    let dist = taxi_distances(&env);
    let shortest = taxi_shortest_actions(&env, &dist);
    // Independently: the shortest-path actions are exactly the optimal ones at every α tried
    // (exact Bellman check with the closed-form return of a shortest path).
    for alpha in ["1/1000", "1/2", "9/10", "99/100", "9999/10000"] {
        let alpha = q(alpha);
        let v = |x: usize| -> Rational {
            if env.is_terminal(x) {
                Rational::zero()
            } else {
                shortest_return(dist[x].unwrap(), &alpha)
            }
        };
        for x in (0..500).filter(|&x| !env.is_terminal(x)) {
            let best: Vec<usize> = (0..6)
                .filter(|&a| {
                    let t = &env.table[x][a][0];
                    let qa = int(t.reward) + &alpha * v(t.next);
                    assert!(qa <= v(x), "state {x} action {a} at {alpha}");
                    qa == v(x)
                })
                .collect();
            assert_eq!(best, shortest[x], "state {x} at {alpha}");
        }
    }
    // So the analysis finds one interval, (0, 1), whose optimal actions are those.
    assert!(d.breakpoints.is_empty());
    assert_eq!(d.intervals.len(), 1);
    assert_eq!(d.intervals[0].optimal, shortest);
    // Every optimal policy delivers; its truecost is the mean shortest distance over the 300
    // initial states (all optimal policies are shortest-path policies: min = max).
    let total: u32 = env.initial.iter().map(|(x, _)| dist[*x].unwrap()).sum();
    let mean = Rational::new(total.into(), (env.initial.len() as u32).into());
    assert_eq!(mean, q("1307/100"));
    let a = &d.intervals[0].achievement;
    assert_eq!(
        (&a.success.min, &a.success.max),
        (&Rational::one(), &Rational::one())
    );
    assert_eq!(a.truecost_min, Extended::Finite(mean.clone()));
    assert_eq!(a.truecost_max, Extended::Finite(mean));
}

#[test]
fn discount_env_taxi_on_the_command_line() {
    let v = common::cli::json(&["discount", "--env", "taxi", "--format", "json"]);
    assert_eq!(v["breakpoints"].as_array().unwrap().len(), 0);
    let iv = &v["intervals"][0];
    assert_eq!(
        (iv["lo"].as_str(), iv["hi"].as_str()),
        (Some("0"), Some("1"))
    );
    assert_eq!(iv["success_probability"], "1");
    assert_eq!(iv["truecost"], "1307/100");
    assert_eq!(v["initial_states"], 300);
    assert!(v["method"].as_str().unwrap().contains("deterministic"));
    let text = common::cli::stdout(&["discount", "--env", "taxi"]);
    assert!(text.contains("breakpoints  0"), "{text}");
    assert!(text.contains("success probability 1.0"), "{text}");
}

// ---------------------------------------------------------------------------------------------
// render --env taxi: one slice.

/// The walls of Taxi's map text, as (row, column west of the wall).
fn map_walls() -> Vec<(usize, usize)> {
    let mut walls = Vec::new();
    for r in 0..5 {
        let line = taxi::MAP[1 + r].as_bytes();
        for c in 0..4 {
            if line[2 * c + 2] == b'|' {
                walls.push((r, c));
            }
        }
    }
    walls
}

#[test]
fn taxi_scene_draws_the_map_text() {
    let env = taxi_env();
    let walls = map_walls();
    assert_eq!(walls.len(), 6);
    let bare = taxi_scene(&env, None);
    assert_eq!(bare.positions.len(), 25);
    assert_eq!(bare.walls.len(), walls.len());
    // Each wall is the vertical segment east of its cell (cell side 10, row 0 on top).
    for &(r, c) in &walls {
        let x = 10.0 * (c as f64 + 1.0);
        let y = 10.0 * (4 - r) as f64;
        assert!(
            bare.walls.contains(&((x, y), (x, y + 10.0))),
            "wall east of ({r}, {c})"
        );
    }
    // Moves: every vertical neighbour pair and every horizontal one without a wall.
    assert_eq!(bare.moves.len(), 20 + (20 - walls.len()));
    assert!(bare.goals.is_empty() && bare.initial.is_none());
    let depots: Vec<&str> = bare
        .marks
        .iter()
        .filter(|m| m.class == "depot")
        .map(|m| m.text.as_str())
        .collect();
    assert_eq!(depots, ["R", "G", "Y", "B"]);
    // With a slice: the destination is the goal, the waiting passenger is marked.
    let s = taxi_scene(&env, Some(&TaxiSlice::new(2, 3).unwrap()));
    assert_eq!(s.goals, vec![4 * 5 + 3]); // B at (4, 3)
    assert_eq!(s.marks.iter().filter(|m| m.class == "passenger").count(), 1);
    let aboard = taxi_scene(&env, Some(&TaxiSlice::new(4, 0).unwrap()));
    assert_eq!(
        aboard
            .marks
            .iter()
            .filter(|m| m.class == "passenger")
            .count(),
        0
    );
}

#[test]
fn taxi_policy_overlay_follows_shortest_paths_in_every_slice() {
    let env = taxi_env();
    let m = Model::from_environment(&env).unwrap();
    let dist = taxi_distances(&env);
    for objective in [Objective::Truecost, Objective::Discounted(q("9/10"))] {
        let s = m.solve(&objective).unwrap();
        for passenger in 0..5 {
            for destination in 0..4 {
                let Ok(slice) = TaxiSlice::new(passenger, destination) else {
                    assert_eq!(passenger, destination);
                    continue;
                };
                let (Overlay::Policy(next), marks) = taxi_policy_overlay(&m, &s, &slice) else {
                    panic!("a policy overlay")
                };
                // The one pick-up (at the passenger's depot) or drop-off (at the destination).
                let (class, (r, c)) = if passenger < 4 {
                    ("pickup", taxi::LOCATIONS[passenger])
                } else {
                    ("dropoff", taxi::LOCATIONS[destination])
                };
                assert_eq!(marks.len(), 1);
                assert_eq!(marks[0].class, class);
                let centre = (10.0 * c as f64 + 5.0, 10.0 * (4 - r) as f64 + 5.0);
                assert!((marks[0].at.0 - centre.0).abs() < 1e-9);
                assert!((marks[0].at.1 - centre.1).abs() < 5.0);
                // Every other cell moves one step closer to the delivery.
                for (cell, target) in next.iter().enumerate() {
                    let x = slice.state(cell / 5, cell % 5);
                    match *target {
                        Some(target) => {
                            let y = slice.state(target / 5, target % 5);
                            assert_eq!(dist[y].unwrap() + 1, dist[x].unwrap(), "{x} -> {y}");
                        }
                        None => assert_eq!((cell / 5, cell % 5), (r, c)),
                    }
                }
                let Overlay::Values { values, .. } = taxi_value_overlay(&s, &slice) else {
                    panic!("a value overlay")
                };
                assert_eq!(values.len(), 25);
                if objective == Objective::Truecost {
                    for (cell, v) in values.iter().enumerate() {
                        let x = slice.state(cell / 5, cell % 5);
                        assert_eq!(*v, Some(f64::from(dist[x].unwrap())));
                    }
                }
                // The drawing: 24 arrows, one mark, 6 walls, 4 depots, 25 cells.
                let mut scene = taxi_scene(&env, Some(&slice));
                scene.marks.extend(marks);
                let canvas = draw(&scene, &Overlay::Policy(next), 700, 700).unwrap();
                assert_eq!(canvas.of_class("policy").count(), 24);
                assert_eq!(canvas.of_class("arrowhead").count(), 24);
                assert_eq!(canvas.of_class(class).count(), 1);
                assert_eq!(canvas.of_class("wall").count(), 6);
                assert_eq!(canvas.of_class("depot").count(), 4);
                assert_eq!(canvas.of_class("node").count(), 25);
                assert_eq!(canvas.of_class("goal").count(), 1);
                assert_eq!(canvas.of_class("start").count(), 0);
            }
        }
    }
}

fn count(svg: &str, class: &str) -> usize {
    svg.matches(&format!("class=\"{class}\"")).count()
}

#[test]
fn render_env_taxi_on_the_command_line() {
    use common::cli::{fails, fails_one_line, stdout};
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("taxi.svg");
    let svg = svg.to_str().unwrap();
    stdout(&[
        "render",
        "--env",
        "taxi",
        "--passenger",
        "Y",
        "--destination",
        "r",
        "--overlay",
        "policy",
        "--out",
        svg,
    ]);
    let text = std::fs::read_to_string(svg).unwrap();
    for (class, n) in [
        ("wall", 6),
        ("depot", 4),
        ("move", 34),
        ("node", 25),
        // Every optimal move is drawn: the shortest-path edges towards Y in Taxi's maze, 34
        // over the 24 cells other than Y (a breadth-first search by hand over the map's walls).
        ("policy", 34),
        ("pickup", 1),
        ("dropoff", 0),
        ("passenger", 1),
        ("goal", 1),
        ("start", 0),
    ] {
        assert_eq!(count(&text, class), n, "{class}");
    }
    assert!(text.contains("passenger waiting at Y, destination R"));
    assert!(text.contains("expectation over the 300 initial states"));
    // Values of the discounted objective, a slice with the passenger aboard.
    stdout(&[
        "render",
        "--env",
        "taxi",
        "--passenger",
        "taxi",
        "--destination",
        "G",
        "--overlay",
        "values",
        "--objective",
        "discounted",
        "--alpha",
        "0.9",
        "--out",
        svg,
    ]);
    let text = std::fs::read_to_string(svg).unwrap();
    assert_eq!(count(&text, "value"), 25);
    assert!(text.contains("discounted (exact)"));
    // The bare map, as PNG.
    let png = dir.path().join("taxi.png");
    stdout(&["render", "--env", "taxi", "--out", png.to_str().unwrap()]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // Refusals, before any work: one line (exit 1) or a usage error (exit 2).
    let e = fails_one_line(&[
        "render",
        "--env",
        "taxi",
        "--overlay",
        "policy",
        "--out",
        svg,
    ]);
    assert!(
        e.contains("--passenger") && e.contains("--destination"),
        "{e}"
    );
    let e = fails_one_line(&[
        "render",
        "--env",
        "taxi",
        "--passenger",
        "r",
        "--overlay",
        "policy",
        "--out",
        svg,
    ]);
    assert!(e.contains("go together"), "{e}");
    let e = fails_one_line(&[
        "render",
        "--env",
        "taxi",
        "--passenger",
        "g",
        "--destination",
        "G",
        "--out",
        svg,
    ]);
    assert!(e.contains("ended"), "{e}");
    let e = fails_one_line(&[
        "render",
        "--env",
        "frozenlake",
        "--passenger",
        "r",
        "--destination",
        "g",
        "--out",
        svg,
    ]);
    assert!(e.contains("slice of taxi"), "{e}");
    let e = fails_one_line(&[
        "render",
        "--env",
        "taxi",
        "--passenger",
        "r",
        "--destination",
        "g",
        "--out",
        "x.gif",
    ]);
    assert!(e.contains("figure format"), "{e}");
    let e = fails_one_line(&["render", "--problem", "0", "--passenger", "r", "--out", svg]);
    assert!(e.contains("--env taxi"), "{e}");
    fails(
        &[
            "render",
            "--env",
            "taxi",
            "--passenger",
            "q\u{1b}[31m",
            "--destination",
            "r",
            "--out",
            svg,
        ],
        2,
    );
}

// ---------------------------------------------------------------------------------------------
// verify --claim C4 --env taxi --initial STATE: the violated-cycle search.

use truecost::claims::c4::{bonus_analysis, BonusError, End, Instance};
use truecost::claims::c4_cycles::bonus_sets_by_cycles;
use truecost::claims::exact::Q;

/// A random small instance: `n` states, the last a goal, 1..=3 moves each (costs 0..=4).
fn random_instance(seed: u64, n: usize) -> Instance {
    let mut g = Lcg(seed);
    let moves = (0..n)
        .map(|x| {
            if x + 1 == n {
                return Vec::new();
            }
            let k = 1 + g.below(3) as usize;
            (0..k)
                .map(|_| (g.below(n as u64) as usize, g.below(5) as i64))
                .collect()
        })
        .collect();
    Instance {
        initial: 0,
        is_goal: (0..n).map(|x| x + 1 == n).collect(),
        moves,
    }
}

/// The violated-cycle search gives the policy-enumeration oracle's exact sets wherever the
/// oracle runs (same `L*`, same `S*` values, same intervals, empty ones included), and
/// refuses only what its documentation says it refuses.
#[test]
fn violated_cycle_search_agrees_with_the_enumeration_oracle() {
    let mut compared = 0;
    let mut bounded = 0;
    let mut empty = 0;
    for seed in 0..3000 {
        let inst = random_instance(seed, 3 + (seed % 4) as usize);
        let oracle = match bonus_analysis(&inst, 1 << 16) {
            Ok(Some(sets)) => sets,
            Ok(None) => {
                assert_eq!(bonus_sets_by_cycles(&inst).unwrap(), None, "seed {seed}");
                continue;
            }
            Err(BonusError::Internal(e)) => panic!("{e}"),
            Err(_) => continue,
        };
        let cycles = match bonus_sets_by_cycles(&inst) {
            Ok(Some(cycles)) => cycles,
            Ok(None) => panic!("seed {seed}: the oracle reaches a goal, the search does not"),
            // Refused, as documented: a reachable dead end or a zero-cost cycle on the optimal
            // paths. Any other error (an internal one: the search did not move) fails.
            Err(e) if e.contains("has no move") || e.contains("zero-cost cycle") => continue,
            Err(e) => panic!("seed {seed}: {e}"),
        };
        let mut a: Vec<_> = oracle
            .iter()
            .map(|s| (s.optimal_cost, s.optimal_states, s.exact))
            .collect();
        let mut b: Vec<_> = cycles
            .iter()
            .map(|s| (s.optimal_cost, s.optimal_states, s.exact))
            .collect();
        a.sort_by_key(|t| t.1);
        b.sort_by_key(|t| t.1);
        assert_eq!(a.len(), b.len(), "seed {seed}");
        for ((la, sa, ea), (lb, sb, eb)) in a.iter().zip(&b) {
            assert_eq!((la, sa), (lb, sb), "seed {seed}");
            assert!(ea.same_set(eb), "seed {seed}: oracle {ea}, cycles {eb}");
            bounded += usize::from(!ea.empty && ea.lo != End::Unbounded);
            empty += usize::from(ea.empty);
        }
        for (o, c) in oracle.iter().zip(&cycles) {
            assert_eq!(o.least_mean_cycle, c.least_mean_cycle, "seed {seed}");
        }
        compared += 1;
    }
    assert!(compared >= 1000, "{compared}");
    assert!(bounded >= 50, "{bounded}");
    // Empty sets: L* = 0 with zero-cost goal paths of two lengths (the shorter beats the
    // longer at every M < 0); 4 of these 3,000 instances.
    assert!(empty >= 2, "{empty}");
}

/// Taxi, from several initial states. Independently: every action costs at least 1 and the
/// shortest path is also the one with the fewest states (unit costs), so no goal path has a
/// line of slope above 1/S*; every other goal path has `L ≥ L* + (S − S*)`, crossing `π*`'s at
/// `M ≥ S* − L* = 1`; a goal-avoiding cycle has mean at least 1, bounding at
/// `S*·1 − L* = 1`. So the set is all of `M < 0`, with `L*` the breadth-first distance,
/// `S* = L* + 1` and `Lav(Ĉ) = 1` (moving back and forth).
#[test]
fn c4_on_taxi_initial_states() {
    let env = taxi_env();
    let m = Model::from_environment(&env).unwrap();
    let dist = taxi_distances(&env);
    for (x1, _) in env.initial.iter().step_by(37) {
        let p = m.deterministic_problem_from(Some(*x1)).unwrap();
        let (inst, d) = Instance::from_problem(&p).unwrap();
        assert_eq!(d, BigInt::one());
        let sets = bonus_sets_by_cycles(&inst).unwrap().unwrap();
        let l = i64::from(dist[*x1].unwrap());
        assert_eq!(sets.len(), 1);
        assert_eq!((sets[0].optimal_cost, sets[0].optimal_states), (l, l + 1));
        assert_eq!(sets[0].least_mean_cycle, Some(Q::int(1)));
        assert_eq!(
            (sets[0].exact.lo, sets[0].exact.hi, sets[0].exact.empty),
            (End::Unbounded, End::Open(Q::ZERO), false)
        );
    }
}

#[test]
fn verify_c4_env_taxi_on_the_command_line() {
    use common::cli::{fails, fails_one_line, json, stdout};
    let x1 = taxi::encode(3, 1, 2, 0).to_string();
    assert_eq!(x1, "328");
    let text = stdout(&["verify", "--claim", "C4", "--env", "taxi", "--initial", &x1]);
    assert!(text.starts_with("x1 = state 328\n"), "{text}");
    assert!(text.contains("L* = 10, S* = 11, Lav(C^) = 1"), "{text}");
    assert!(text.contains("(-inf, 0)"), "{text}");
    assert!(text.contains("M = -20: in the set"), "{text}");
    let v = json(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "taxi",
        "--initial",
        &x1,
        "--format",
        "json",
    ]);
    assert_eq!(v["bonus_sets"][0]["exact"], "(-inf, 0)");
    assert_eq!(v["bonus_sets"][0]["terminal_bonus_in_set"], true);
    assert_eq!(v["terminal_bonus"], "-20");
    assert!(v["bonus_sets"][0]["printed"].is_null());
    // Refusals: one line naming the option, the range, the ended episode; usage errors exit 2.
    let e = fails_one_line(&["verify", "--claim", "C4", "--env", "taxi"]);
    assert!(e.contains("--initial STATE"), "{e}");
    let e = fails_one_line(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "taxi",
        "--initial",
        "500",
    ]);
    assert!(e.contains("0 to 499"), "{e}");
    let goal = taxi::encode(0, 0, 1, 1).to_string();
    let e = fails_one_line(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "taxi",
        "--initial",
        &goal,
    ]);
    assert!(e.contains("ended"), "{e}");
    let e = fails_one_line(&[
        "verify",
        "--claim",
        "C4",
        "--problem",
        "3",
        "--initial",
        "5",
    ]);
    assert!(e.contains("--env"), "{e}");
    fails(
        &[
            "verify",
            "--claim",
            "C4",
            "--env",
            "taxi",
            "--initial",
            "x\u{7}",
        ],
        2,
    );
    // A small environment still takes the enumeration oracle, from a chosen x1.
    let out = stdout(&[
        "verify",
        "--claim",
        "C4",
        "--env",
        "frozenlake:slippery=false",
        "--initial",
        "14",
    ]);
    assert!(out.contains("exact (oracle)"), "{out}");
    assert!(out.contains("L* = 1,"), "{out}");
}

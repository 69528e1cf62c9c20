//! The three objectives on the Gymnasium benchmarks, against oracles that
//! share no code with the solvers: value iteration in `f64` and breadth-first search run on
//! Gymnasium's own `P` tables (the dumps of `tests/data/gymnasium/`), and values published
//! for these benchmarks.

use num_traits::ToPrimitive;
use serde_json::Value;
use truecost::envs::EnvSpec;
use truecost::objectives::{Model, Objective};
use truecost::value::{Extended, Rational};

fn model(spec: &str) -> Model {
    Model::from_environment(&EnvSpec::parse(spec).unwrap().build().unwrap()).unwrap()
}

fn q(s: &str) -> Rational {
    truecost::value::parse_rational(s).unwrap()
}

/// Gymnasium's table: per state, per action, (p, next, reward, terminated).
type Table = Vec<Vec<Vec<(f64, usize, f64, bool)>>>;

fn dump(name: &str) -> (Table, Vec<f64>) {
    let path = format!(
        "{}/tests/data/gymnasium/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let f = |x: &Value| x.as_str().unwrap().parse::<f64>().unwrap();
    let table = v["P"]
        .as_array()
        .unwrap()
        .iter()
        .map(|row| {
            row.as_array()
                .unwrap()
                .iter()
                .map(|list| {
                    list.as_array()
                        .unwrap()
                        .iter()
                        .map(|t| {
                            (
                                f(&t[0]),
                                t[1].as_u64().unwrap() as usize,
                                t[2].as_f64().unwrap(),
                                t[3].as_bool().unwrap(),
                            )
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    let init = v["initial_state_distrib"]
        .as_array()
        .unwrap()
        .iter()
        .map(f)
        .collect();
    (table, init)
}

/// Value iteration in f64 on Gymnasium's table: `V(s) = max_a Σ p (r + α V(s'))`, `V = 0` after
/// termination; states where an episode has ended (FrozenLake's G and H rows) are skipped by
/// the flag. `reward` maps Gymnasium's reward.
fn gym_vi(
    table: &Table,
    alpha: f64,
    reward: impl Fn(f64, bool, usize) -> f64,
    sweeps: usize,
) -> Vec<f64> {
    let mut v = vec![0.0; table.len()];
    for _ in 0..sweeps {
        let next: Vec<f64> = table
            .iter()
            .map(|row| {
                row.iter()
                    .map(|list| {
                        list.iter()
                            .map(|&(p, s2, r, t)| {
                                p * (reward(r, t, s2) + if t { 0.0 } else { alpha * v[s2] })
                            })
                            .sum::<f64>()
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .collect();
        v = next;
    }
    v
}

fn at_init(v: &[f64], init: &[f64]) -> f64 {
    v.iter()
        .zip(init)
        .filter(|(_, &b)| b > 0.0)
        .map(|(a, b)| a * b)
        .sum()
}

fn f(e: &Extended) -> f64 {
    e.to_f64()
}

#[test]
fn frozenlake_4x4_slippery_reach_is_14_17_and_no_policy_is_proper() {
    let m = model("frozenlake");
    let reach = m.solve(&Objective::Reach).unwrap();
    // 0.8235294… is the success probability published for FrozenLake 4x4 under gamma = 1.
    assert_eq!(reach.value_initial.to_string(), "14/17");
    let (table, init) = dump("frozenlake_4x4_slippery");
    // Reach as value iteration with Gymnasium's reward (1 on entering G), undiscounted.
    let oracle = at_init(&gym_vi(&table, 1.0, |r, _, _| r, 20_000), &init);
    assert!((oracle - 14.0 / 17.0).abs() < 1e-12, "{oracle}");
    let truecost = m.solve(&Objective::Truecost).unwrap();
    assert_eq!(truecost.value_initial, Extended::Infinite);
    assert_eq!(
        (
            truecost.success.min.to_string(),
            truecost.success.max.to_string()
        ),
        ("0".into(), "14/17".into())
    );
}

#[test]
fn discounted_values_agree_with_value_iteration_on_gymnasium_tables() {
    for (spec, name, alpha) in [
        ("frozenlake", "frozenlake_4x4_slippery", "0.9"),
        ("frozenlake:map=8x8", "frozenlake_8x8_slippery", "0.99"),
        ("cliffwalking:slippery=true", "cliffwalking_slippery", "0.9"),
        ("taxi", "taxi", "0.95"),
    ] {
        let m = model(spec);
        let s = m.solve(&Objective::Discounted(q(alpha))).unwrap();
        let (table, init) = dump(name);
        let a: f64 = alpha.parse().unwrap();
        let mut v = gym_vi(&table, a, |r, _, _| r, 6000);
        // Taxi's 100 "delivered" rows are never used; an episode ends on entering them.
        if name == "taxi" {
            for (x, val) in v.iter_mut().enumerate() {
                if (x / 4) % 5 == x % 4 {
                    *val = 0.0;
                }
            }
            v = {
                let mut w = v.clone();
                for _ in 0..6000 {
                    w = table
                        .iter()
                        .enumerate()
                        .map(|(x, row)| {
                            if (x / 4) % 5 == x % 4 {
                                0.0
                            } else {
                                row.iter()
                                    .map(|l| {
                                        l.iter()
                                            .map(|&(p, s2, r, t)| {
                                                p * (r + if t { 0.0 } else { a * w[s2] })
                                            })
                                            .sum::<f64>()
                                    })
                                    .fold(f64::NEG_INFINITY, f64::max)
                            }
                        })
                        .collect();
                }
                w
            };
        }
        let oracle = at_init(&v, &init);
        let ours = f(&s.value_initial);
        assert!(
            (oracle - ours).abs() < 1e-9 * oracle.abs().max(1.0),
            "{spec}: {ours} vs VI {oracle}"
        );
    }
}

#[test]
fn truecost_of_deterministic_benchmarks_is_the_shortest_path() {
    // Breadth-first distances on Gymnasium's tables (every action costs 1; CliffWalking's
    // optimal path never falls; Taxi's never makes an illegal move).
    for (spec, name, expected) in [
        ("cliffwalking", "cliffwalking", "13"),
        ("taxi", "taxi", "1307/100"),
        ("frozenlake:slippery=false", "frozenlake_4x4", "6"),
        ("frozenlake:map=8x8,slippery=false", "frozenlake_8x8", "14"),
    ] {
        let (table, init) = dump(name);
        let n = table.len();
        let mut d = vec![f64::INFINITY; n];
        for _ in 0..n {
            for s in 0..n {
                for list in &table[s] {
                    let (_, s2, r, t) = list[0];
                    let hole = t && r == 0.0 && name.starts_with("frozenlake");
                    let v = if hole {
                        f64::INFINITY
                    } else if t {
                        1.0
                    } else {
                        1.0 + d[s2]
                    };
                    if v < d[s] {
                        d[s] = v;
                    }
                }
            }
        }
        let oracle = at_init(&d, &init);
        let m = model(spec);
        let s = m.solve(&Objective::Truecost).unwrap();
        assert_eq!(s.value_initial.to_string(), expected, "{spec}");
        assert!(
            (f(&s.value_initial) - oracle).abs() < 1e-9,
            "{spec}: BFS {oracle}"
        );
        assert_eq!(s.success.min.to_string(), "1");
        assert_eq!(
            s.steps, s.value_initial,
            "{spec}: unit costs on the optimal path"
        );
    }
}

/// The paper's Proposition 3 on a standard benchmark: on FrozenLake 8x8 (slippery) a policy
/// reaches the goal with probability 1, yet the discount-optimal policy for α = 0.9 gives up
/// a quarter of the success probability, and its truecost is +∞.
#[test]
fn frozenlake_8x8_discounting_gives_up_success() {
    let m = model("frozenlake:map=8x8");
    let t = m.solve(&Objective::Truecost).unwrap();
    assert!(t.value_initial.finite().is_some());
    assert_eq!(t.policy_success.to_string(), "1");
    let d = m.solve(&Objective::Discounted(q("0.9"))).unwrap();
    assert!(d.success.max < q("0.76"), "{}", d.success.max);
    assert!(d.success.max > q("0.74"));
    assert_eq!(d.truecost, Extended::Infinite);
    // The truecost-optimal policy costs no more than any other proper policy (the reach row's).
    let r = m.solve(&Objective::Reach).unwrap();
    assert_eq!(r.value_initial.to_string(), "1");
    assert!(r.truecost >= t.value_initial);
}

#[test]
fn exact_probabilities_are_exact() {
    let m = model("frozenlake:success_rate=4/5");
    let a = m.problem.actions(5 - 4).start + 1; // state 1, DOWN: 1/10 right, 4/5 down (hole), 1/10 left
    let out: Vec<String> = m
        .problem
        .outcomes(a)
        .iter()
        .map(|o| format!("{}:{}", o.successor, o.probability))
        .collect();
    assert_eq!(out, ["0:1/10", "5:4/5", "2:1/10"]);
    // success_rate = 1: Gymnasium lists zero-probability entries; the problem drops them.
    let sure = model("frozenlake:success_rate=1");
    assert_eq!(
        sure.problem.outcomes(sure.problem.actions(0).start).len(),
        1
    );
    assert_eq!(
        sure.solve(&Objective::Truecost)
            .unwrap()
            .value_initial
            .to_string(),
        "6"
    );
}

#[test]
fn discounted_values_of_ended_episodes_are_zero_and_policies_are_gymnasium_actions() {
    let m = model("frozenlake");
    let d = m.solve(&Objective::Discounted(q("0.9"))).unwrap();
    for x in [5, 7, 11, 12, 15] {
        assert_eq!(d.values[x].to_string(), "0", "state {x}");
        assert_eq!(d.policy[x], None);
    }
    // Known optimal action at the start of FrozenLake 4x4 for gamma = 0.9: LEFT (0).
    assert_eq!(d.policy[0].map(|a| a - m.problem.actions(0).start), Some(0));
    assert!(d.value_initial.to_f64() > 0.0688 && d.value_initial.to_f64() < 0.0690);
}

#[test]
fn taxi_terminal_bonus_and_initial_expectation() {
    let m = model("taxi");
    assert_eq!(m.terminal_bonus.as_ref().unwrap().to_string(), "-20");
    assert_eq!(m.initial.len(), 300);
    let t = m.solve(&Objective::Truecost).unwrap();
    // The expectation over the 300 initial states of the per-state values.
    let mean = m
        .initial
        .iter()
        .map(|(x, p)| t.values[*x].finite().unwrap() * p)
        .fold(Rational::from_integer(0.into()), |a, b| a + b);
    assert_eq!(Extended::Finite(mean), t.value_initial);
    // Gymnasium's return of the truecost-optimal policy: 21 - steps (no illegal moves).
    assert_eq!(
        (Rational::from_integer(21.into()) - t.steps.finite().unwrap())
            .to_f64()
            .unwrap(),
        7.93
    );
}

#[test]
fn bad_objectives_and_specs_are_refused() {
    let m = model("frozenlake");
    for a in ["0", "1", "3/2"] {
        assert!(m.solve(&Objective::Discounted(q(a))).is_err(), "{a}");
    }
    for bad in [
        "lake",
        "frozenlake:map",
        "frozenlake:slippery=yes",
        "frozenlake:slippery=false,success_rate=1/2",
        "frozenlake:map=/nonexistent",
        "cliffwalking:wind=1",
        "frozenlake:success_rate=-1/3",
        "frozenlake:map=4x4,map=8x8",
    ] {
        assert!(
            EnvSpec::parse(bad).and_then(|s| s.build()).is_err(),
            "{bad}"
        );
    }
}

/// A map path naming an endless stream is refused after the map-file limit (not read until
/// memory runs out), and the refusal escapes the path.
#[test]
fn endless_map_files_are_refused_at_the_limit() {
    let err = EnvSpec::parse("frozenlake:map=/dev/zero")
        .and_then(|s| s.build())
        .unwrap_err()
        .to_string();
    assert!(err.contains("larger than 1048576 bytes"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    let odd = dir.path().join("m\x1bap");
    std::fs::write(&odd, "SFFG\nFHFH\n").unwrap();
    let spec = format!("frozenlake:map={}", odd.display());
    let env = EnvSpec::parse(&spec).and_then(|s| s.build());
    assert!(env.is_ok(), "a small map file is read");
    std::fs::write(&odd, "SFXG\n").unwrap();
    let err = EnvSpec::parse(&spec)
        .and_then(|s| s.build())
        .unwrap_err()
        .to_string();
    assert!(err.contains("m\\x1bap") && !err.contains('\x1b'), "{err}");
}

#[test]
fn figures_draw_the_map_and_every_optimal_action() {
    use truecost::figures::envs::{intended_cell, policy_overlay, scene, value_overlay};
    use truecost::figures::render::{draw, ActionGlyph, LegendKey, Overlay};
    use truecost::objectives::actions::optimal_actions;
    let env = EnvSpec::parse("frozenlake:map=8x8")
        .unwrap()
        .build()
        .unwrap();
    let m = Model::from_environment(&env).unwrap();
    let s = m.solve(&Objective::Discounted(q("0.9"))).unwrap();
    let sc = scene(&env).unwrap();
    let overlay = policy_overlay(&env, &m, &s);
    let Overlay::Actions { actions, legend } = &overlay else {
        panic!("an optimal-actions overlay")
    };
    let optimal = optimal_actions(&m, &s);
    // Every state with an action draws its reported action, the goal and the ten holes nothing.
    let (mut arrows, mut bars) = (0, 0);
    for x in 0..64 {
        match s.policy[x] {
            None => {
                assert!(env.is_terminal(x), "{x}");
                assert!(actions[x].is_empty(), "{x}");
            }
            Some(a) => {
                assert!(
                    optimal[x].contains(&a),
                    "{x}: the reported action is optimal"
                );
                let local = a - m.problem.actions(x).start;
                let y = intended_cell(&env, x, local);
                let (r, c) = (x / 8, x % 8);
                // LEFT 0 in column 0, DOWN 1 in row 7, RIGHT 2 in column 7, UP 3 in row 0.
                let wall = matches!((local, r, c), (0, _, 0) | (1, 7, _) | (2, _, 7) | (3, 0, _));
                assert_eq!(wall, y == x, "{x}");
                if !wall {
                    assert!(actions[x].contains(&ActionGlyph::Move(y)), "{x}");
                }
            }
        }
        for g in &actions[x] {
            match g {
                ActionGlyph::Move(_) => arrows += 1,
                ActionGlyph::Blocked { .. } => bars += 1,
            }
        }
    }
    let canvas = draw(&sc, &overlay, 600, 600).unwrap();
    assert_eq!(canvas.of_class("obstacle").count(), 10, "the ten holes");
    assert_eq!(canvas.of_class("policy").count(), arrows);
    assert_eq!(canvas.of_class("arrowhead").count(), arrows);
    assert_eq!(canvas.of_class("blocked").count(), bars);
    assert_eq!(canvas.of_class("blocked-bar").count(), bars);
    // The legend names the bar exactly when one is drawn (slippery: the agent may still slip).
    let bar_entry = legend.iter().find(|e| e.key == LegendKey::Blocked);
    assert_eq!(bar_entry.is_some(), bars > 0);
    if let Some(e) = bar_entry {
        assert!(
            e.text.contains("stays in place unless it slips"),
            "{}",
            e.text
        );
    }
    assert_eq!(canvas.of_class("legend").count(), legend.len());
    let cliff = EnvSpec::parse("cliffwalking").unwrap().build().unwrap();
    let cm = Model::from_environment(&cliff).unwrap();
    let cs = cm.solve(&Objective::Truecost).unwrap();
    let canvas = draw(&scene(&cliff).unwrap(), &value_overlay(&cs), 600, 300).unwrap();
    assert_eq!(canvas.of_class("obstacle").count(), 10, "the cliff");
    assert_eq!(canvas.of_class("value").count(), 48);
    assert!(scene(&EnvSpec::parse("taxi").unwrap().build().unwrap()).is_err());
}

/// A FrozenLake environment on a map written to a file.
fn map_env(dir: &tempfile::TempDir, rows: &str, slippery: bool) -> truecost::envs::Environment {
    let path = dir.path().join("map.txt");
    std::fs::write(&path, rows).unwrap();
    EnvSpec::parse(&format!(
        "frozenlake:map={},slippery={slippery}",
        path.display()
    ))
    .unwrap()
    .build()
    .unwrap()
}

/// The 2×2 map `SF / FG` without slipping: from S (0) RIGHT to 1 and DOWN to 2 are both two
/// steps from G (3), LEFT and UP hit the border; from 1 only DOWN and from 2 only RIGHT reach
/// G in one step. Gymnasium's actions: 0 LEFT, 1 DOWN, 2 RIGHT, 3 UP.
#[test]
fn tied_optimal_actions_are_all_drawn_and_named_in_the_legend() {
    use truecost::figures::envs::policy_overlay;
    use truecost::figures::render::{ActionGlyph::Move, LegendKey, Overlay};
    use truecost::objectives::actions::{optimal_actions, q_value};
    let dir = tempfile::tempdir().unwrap();
    let env = map_env(&dir, "SF\nFG\n", false);
    let m = Model::from_environment(&env).unwrap();
    let first = |x: usize| m.problem.actions(x).start;
    // Truecost: G*(1) = G*(2) = 1, G*(0) = 2; Q(0, RIGHT) = Q(0, DOWN) = 1 + 1 = 2, Q(0, LEFT)
    // = Q(0, UP) = 1 + G*(0) = 3. Discounted with α = 1/2: V(1) = V(2) = 1 (reward 1 on
    // entering G), V(0) = α·1 = 1/2 by RIGHT and by DOWN, α·V(0) = 1/4 by LEFT or UP.
    for (objective, value) in [
        (Objective::Truecost, "2"),
        (Objective::Discounted(q("1/2")), "1/2"),
    ] {
        let s = m.solve(&objective).unwrap();
        assert_eq!(s.values[0], Extended::Finite(q(value)), "{objective:?}");
        let optimal = optimal_actions(&m, &s);
        assert_eq!(
            optimal[0],
            vec![first(0) + 1, first(0) + 2],
            "{objective:?}"
        );
        assert_eq!(optimal[1], vec![first(1) + 1], "{objective:?}: only DOWN");
        assert_eq!(optimal[2], vec![first(2) + 2], "{objective:?}: only RIGHT");
        assert!(optimal[3].is_empty(), "the goal");
        // The tie is exact: the two Q-values are the same rational.
        assert_eq!(q_value(&m, &s, first(0) + 1), q_value(&m, &s, first(0) + 2));
        let Overlay::Actions { actions, legend } = policy_overlay(&env, &m, &s) else {
            panic!("an optimal-actions overlay")
        };
        assert_eq!(
            actions,
            vec![vec![Move(2), Move(1)], vec![Move(3)], vec![Move(3)], vec![]],
            "{objective:?}"
        );
        let keys: Vec<LegendKey> = legend.iter().map(|e| e.key).collect();
        assert_eq!(
            keys,
            vec![LegendKey::Arrow, LegendKey::Tie],
            "{objective:?}: no bar drawn"
        );
        assert!(legend[1].text.contains("tied optimal actions"));
        assert!(legend[1].text.contains("exactly equal Q-values"));
    }
    // Reach: every state reaches G with probability 1, so every action attains V = 1; but
    // LEFT and UP at 0, RIGHT and UP at 1, LEFT and DOWN at 2 keep the agent in place, and no
    // policy choosing them reaches G. Going back (1 LEFT to 0, 2 UP to 0) is reach-optimal:
    // 0 then goes on to the other side.
    let s = m.solve(&Objective::Reach).unwrap();
    let Overlay::Actions { actions, legend } = policy_overlay(&env, &m, &s) else {
        panic!("an optimal-actions overlay")
    };
    assert_eq!(
        actions,
        vec![
            vec![Move(2), Move(1)],
            vec![Move(0), Move(3)],
            vec![Move(3), Move(0)],
            vec![]
        ]
    );
    assert_eq!(
        legend.len(),
        2,
        "arrow and tie: no bar is an optimal action"
    );
}

/// The 1×3 slippery map `SFG` (success rate 1/3: the intended direction and each
/// perpendicular one with probability 1/3; moves off the map stay). At F (1) RIGHT reaches G
/// with 1/3 and stays otherwise: G*(1) = 3; DOWN and UP go to S, stay or reach G, 1/3 each:
/// 1 + 6/3 + 3/3 = 4; LEFT 1 + 6/3 + 2·3/3 = 5. At S (0) RIGHT, DOWN and UP each move to F
/// with 1/3 (RIGHT intended, DOWN and UP by slipping) and stay otherwise:
/// G*(0) = 1 + 2/3·G*(0) + 1/3·3, so G*(0) = 6 by all three; LEFT never leaves: 1 + 6 = 7.
/// So at S the optimal
/// actions are DOWN and UP — both aimed at the border — and RIGHT.
#[test]
fn moves_into_the_border_are_bars_with_a_legend_entry() {
    use truecost::figures::envs::{policy_overlay, scene};
    use truecost::figures::render::{draw, ActionGlyph::*, LegendKey, Overlay};
    let dir = tempfile::tempdir().unwrap();
    let env = map_env(&dir, "SFG\n", true);
    let m = Model::from_environment(&env).unwrap();
    let s = m.solve(&Objective::Truecost).unwrap();
    assert_eq!(s.values[0], Extended::from_integer(6));
    assert_eq!(s.values[1], Extended::from_integer(3));
    let overlay = policy_overlay(&env, &m, &s);
    let Overlay::Actions { actions, legend } = &overlay else {
        panic!("an optimal-actions overlay")
    };
    // DOWN pushes south (y grows upwards), UP north.
    assert_eq!(
        actions,
        &vec![
            vec![
                Blocked { toward: (0, -1) },
                Move(1),
                Blocked { toward: (0, 1) }
            ],
            vec![Move(2)],
            vec![]
        ]
    );
    let keys: Vec<LegendKey> = legend.iter().map(|e| e.key).collect();
    assert_eq!(
        keys,
        vec![LegendKey::Arrow, LegendKey::Tie, LegendKey::Blocked]
    );
    assert!(legend[2].text.contains("into the border"));
    assert!(legend[2].text.contains("stays in place unless it slips"));
    let canvas = draw(&scene(&env).unwrap(), &overlay, 600, 400).unwrap();
    assert_eq!(canvas.of_class("blocked").count(), 2);
    assert_eq!(canvas.of_class("blocked-bar").count(), 2);
    assert_eq!(canvas.of_class("policy").count(), 2, "S to F and F to G");
    let svg = canvas.to_svg();
    for entry in legend.iter() {
        assert!(svg.contains(&entry.text), "{}", entry.text);
    }
    // Reach: V = 1 everywhere; LEFT at S never leaves S, and LEFT at F only goes back to S or
    // stays: no policy choosing either reaches G. The rest attain V = 1 and can reach G.
    let r = m.solve(&Objective::Reach).unwrap();
    let Overlay::Actions { actions, .. } = policy_overlay(&env, &m, &r) else {
        panic!("an optimal-actions overlay")
    };
    assert_eq!(
        actions,
        vec![
            vec![
                Blocked { toward: (0, -1) },
                Move(1),
                Blocked { toward: (0, 1) }
            ],
            vec![
                Blocked { toward: (0, -1) },
                Move(2),
                Blocked { toward: (0, 1) }
            ],
            vec![]
        ]
    );
}

/// CliffWalking: from the start (36, bottom left) UP to 24 is the only optimal action: RIGHT
/// falls (cost 100), LEFT and DOWN hit the border. Taxi with the passenger aboard and the
/// destination R (0, 0): from (1, 1) north to (0, 1) and west to (1, 0) are both one move
/// from R (no wall between (0, 1) and (0, 0) nor between (1, 0) and (0, 0)), from (0, 1) only
/// west is.
#[test]
fn single_and_tied_actions_on_cliffwalking_and_taxi() {
    use truecost::figures::envs::{policy_overlay, taxi_actions_overlay, taxi_scene, TaxiSlice};
    use truecost::figures::render::{draw, ActionGlyph::Move, LegendKey, Overlay};
    let env = EnvSpec::parse("cliffwalking").unwrap().build().unwrap();
    let m = Model::from_environment(&env).unwrap();
    let s = m.solve(&Objective::Truecost).unwrap();
    let Overlay::Actions { actions, .. } = policy_overlay(&env, &m, &s) else {
        panic!("an optimal-actions overlay")
    };
    assert_eq!(actions[36], vec![Move(24)]);
    // Along row 2 only RIGHT (DOWN falls), at (2, 11) only DOWN to the goal.
    for c in 0..11 {
        assert_eq!(actions[24 + c], vec![Move(25 + c)], "(2, {c})");
    }
    assert_eq!(actions[35], vec![Move(47)]);
    let taxi = EnvSpec::parse("taxi").unwrap().build().unwrap();
    let m = Model::from_environment(&taxi).unwrap();
    let s = m.solve(&Objective::Truecost).unwrap();
    let slice = TaxiSlice::new(4, 0).unwrap();
    let (overlay, marks) = taxi_actions_overlay(&m, &s, &slice);
    let Overlay::Actions { actions, legend } = &overlay else {
        panic!("an optimal-actions overlay")
    };
    assert_eq!(
        actions[5 + 1],
        vec![Move(1), Move(5)],
        "(1, 1): north or west"
    );
    assert_eq!(actions[1], vec![Move(0)], "(0, 1): west");
    assert_eq!(actions[5], vec![Move(0)], "(1, 0): north");
    assert!(actions[0].is_empty(), "R: drop off, a mark");
    assert_eq!(marks.len(), 1);
    assert_eq!(marks[0].class, "dropoff");
    assert!(legend.iter().any(|e| e.key == LegendKey::Tie));
    let mut scene = taxi_scene(&taxi, Some(&slice));
    scene.marks.extend(marks);
    let canvas = draw(&scene, &overlay, 700, 700).unwrap();
    let arrows: usize = actions.iter().map(Vec::len).sum();
    assert!(
        arrows > 24,
        "ties add arrows to one per moving cell: {arrows}"
    );
    assert_eq!(canvas.of_class("policy").count(), arrows);
    assert_eq!(canvas.of_class("dropoff").count(), 1);
}

/// A map is at most 100 × 100 cells, a size every command builds: one cell more is refused
/// when the map is read, before any model is built.
#[test]
fn maps_are_bounded_to_what_can_be_built() {
    use truecost::envs::frozenlake::check_map;
    let map = |rows: usize, cols: usize| -> Vec<String> {
        let mut m = vec!["F".repeat(cols); rows];
        m[0].replace_range(0..1, "S");
        m[rows - 1].replace_range(cols - 1..cols, "G");
        m
    };
    assert!(check_map(&map(100, 100)).is_ok());
    let err = check_map(&map(101, 100)).unwrap_err();
    assert!(err.contains("at most 10000 cells"), "{err}");
    assert!(check_map(&map(1, 10_001)).is_err());
}

//! Conformance with Gymnasium: our exact environments against the `P`
//! tables Gymnasium 1.4.0 itself holds, dumped by `scripts/gymnasium_dump.py` into
//! `tests/data/gymnasium/`. Probabilities must agree within 1e-15 (Gymnasium's are floats:
//! FrozenLake's 1/3 is 0.33333333333333337 there); successors, rewards, terminations, the
//! numbering, the initial distributions and the maps exactly. No Python is needed.

use num_traits::{Signed, Zero};
use serde_json::Value;
use truecost::envs::{EnvSpec, Environment, Layout};
use truecost::value::Rational;

const DUMPS: [&str; 10] = [
    "frozenlake_4x4_slippery",
    "frozenlake_4x4",
    "frozenlake_8x8_slippery",
    "frozenlake_8x8",
    "frozenlake_4x4_success_4_5",
    "frozenlake_8x8_success_1_2",
    "frozenlake_map_3x5",
    "cliffwalking",
    "cliffwalking_slippery",
    "taxi",
];

fn load(name: &str) -> Value {
    let path = format!(
        "{}/tests/data/gymnasium/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

/// The exact value of Gymnasium's float, from its shortest round-trip text.
fn float(v: &Value) -> Rational {
    let f: f64 = v.as_str().unwrap().parse().unwrap();
    Rational::from_float(f).unwrap()
}

fn close(exact: &Rational, gym: &Rational) -> bool {
    (exact - gym).abs() <= Rational::new(1.into(), 1_000_000_000_000_000u64.into())
}

fn build(dump: &Value) -> Environment {
    let spec = dump["spec"].as_str().unwrap();
    let spec = spec.replace(
        "tests/data",
        &format!("{}/tests/data", env!("CARGO_MANIFEST_DIR")),
    );
    EnvSpec::parse(&spec).unwrap().build().unwrap()
}

#[test]
fn every_dump_is_from_gymnasium_1_4_0_and_covers_every_configuration() {
    for name in DUMPS {
        let dump = load(name);
        assert_eq!(dump["gymnasium_version"], "1.4.0", "{name}");
    }
    let files = std::fs::read_dir(format!(
        "{}/tests/data/gymnasium",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
    .filter(|e| {
        e.as_ref()
            .unwrap()
            .path()
            .extension()
            .is_some_and(|x| x == "json")
    })
    .count();
    assert_eq!(files, DUMPS.len(), "a dump without a test");
}

#[test]
fn transition_tables_match_gymnasium() {
    for name in DUMPS {
        let dump = load(name);
        let env = build(&dump);
        assert_eq!(env.gymnasium_id, dump["env_id"], "{name}");
        let table = dump["P"].as_array().unwrap();
        assert_eq!(
            env.states(),
            dump["states"].as_u64().unwrap() as usize,
            "{name}"
        );
        assert_eq!(env.states(), table.len(), "{name}");
        let mut compared = 0;
        for (s, row) in table.iter().enumerate() {
            let row = row.as_array().unwrap();
            assert_eq!(env.table[s].len(), row.len(), "{name} state {s}: actions");
            assert_eq!(
                env.action_names.len(),
                dump["actions"].as_u64().unwrap() as usize
            );
            for (a, list) in row.iter().enumerate() {
                let list = list.as_array().unwrap();
                let ours = &env.table[s][a];
                assert_eq!(ours.len(), list.len(), "{name} P[{s}][{a}]: outcome count");
                for (i, (t, g)) in ours.iter().zip(list).enumerate() {
                    let g = g.as_array().unwrap();
                    let p = float(&g[0]);
                    assert!(
                        close(&t.probability, &p),
                        "{name} P[{s}][{a}][{i}]: {} vs Gymnasium {}",
                        t.probability,
                        g[0]
                    );
                    assert_eq!(
                        t.next as u64,
                        g[1].as_u64().unwrap(),
                        "{name} P[{s}][{a}][{i}]: next"
                    );
                    assert_eq!(
                        t.reward,
                        g[2].as_i64().unwrap(),
                        "{name} P[{s}][{a}][{i}]: reward"
                    );
                    assert_eq!(
                        t.terminated,
                        g[3].as_bool().unwrap(),
                        "{name} P[{s}][{a}][{i}]: terminated"
                    );
                    compared += 1;
                }
            }
        }
        assert!(compared >= env.states() * env.action_names.len(), "{name}");
    }
}

#[test]
fn initial_distributions_match_gymnasium() {
    for name in DUMPS {
        let dump = load(name);
        let env = build(&dump);
        let gym: Vec<Rational> = dump["initial_state_distrib"]
            .as_array()
            .unwrap()
            .iter()
            .map(float)
            .collect();
        let mut ours = vec![Rational::zero(); env.states()];
        for (x, p) in &env.initial {
            ours[*x] = p.clone();
        }
        for (x, (o, g)) in ours.iter().zip(&gym).enumerate() {
            assert_eq!(o.is_zero(), g.is_zero(), "{name}: support at {x}");
            assert!(
                close(o, g),
                "{name}: initial probability of {x}: {o} vs {g}"
            );
        }
        let sum = env
            .initial
            .iter()
            .map(|(_, p)| p.clone())
            .fold(Rational::zero(), |a, b| a + b);
        assert_eq!(
            sum,
            Rational::from_integer(1.into()),
            "{name}: exact distribution"
        );
    }
    assert_eq!(build(&load("taxi")).initial.len(), 300);
    assert_eq!(build(&load("frozenlake_map_3x5")).initial.len(), 2);
}

#[test]
fn frozenlake_maps_match_gymnasium() {
    for name in DUMPS.iter().filter(|n| n.starts_with("frozenlake")) {
        let dump = load(name);
        let env = build(&dump);
        let Layout::FrozenLake { desc } = &env.layout else {
            panic!("{name}")
        };
        let gym: Vec<&str> = dump["desc"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_str().unwrap())
            .collect();
        assert_eq!(desc, &gym, "{name}");
    }
}

/// Our goals and traps are exactly the states Gymnasium's `terminated` flag leads to, on every
/// state an episode can visit (Taxi's rows for "passenger already at the destination, taxi
/// elsewhere" are never used: those states are entered by no step).
#[test]
fn terminations_are_entries_into_goals_and_traps() {
    for name in DUMPS {
        let dump = load(name);
        let env = build(&dump);
        let mut seen = vec![false; env.states()];
        let mut stack: Vec<usize> = env.initial.iter().map(|(x, _)| *x).collect();
        for &x in &stack {
            seen[x] = true;
        }
        let mut goals_entered = std::collections::BTreeSet::new();
        while let Some(s) = stack.pop() {
            assert!(
                !env.is_terminal(s),
                "{name}: an episode starts or runs on at {s}"
            );
            for t in env.table[s]
                .iter()
                .flatten()
                .filter(|t| t.probability > Rational::zero())
            {
                assert_eq!(
                    t.terminated,
                    env.is_terminal(t.next),
                    "{name}: {s} -> {}",
                    t.next
                );
                if env.goals.contains(&t.next) {
                    goals_entered.insert(t.next);
                }
                if !t.terminated && !seen[t.next] {
                    seen[t.next] = true;
                    stack.push(t.next);
                }
            }
        }
        let expected = if name == "taxi" { 4 } else { env.goals.len() };
        assert_eq!(
            goals_entered.len(),
            expected,
            "{name}: goals entered by an episode"
        );
    }
}

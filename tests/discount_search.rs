//! The pruned search of the parametric discount analysis (derivative and Descartes bounds
//! dismissing advantages near a probe, a floating-point start corrected by exact policy
//! iteration) against the full search (every advantage's roots in (0, 1), exact policy
//! iteration from the first actions): the same breakpoints, optimal sets and achievements on
//! random stochastic and deterministic problems, FrozenLake 4x4 and a benchmark grid; and the
//! refusal of a deterministic problem above the state bound before any work, and the measured
//! work bound of a deterministic analysis.

mod common;

use std::cmp::Ordering;

use common::Lcg;
use truecost::envs::EnvSpec;
use truecost::objectives::parametric::{
    discount_breakpoints_search, discount_breakpoints_within, DiscountAnalysis, ParametricError,
    Search, MAX_DETERMINISTIC_RUNNING_STATES,
};
use truecost::objectives::Model;
use truecost::stochastic::file::{from_json, ProblemFile};

/// A random problem file: `n` states, the last a goal, 1–3 actions per other state, each with
/// 1 or 2 outcomes (probabilities k/4) and integer costs 1–6.
fn random_problem(seed: u64, n: usize, deterministic: bool) -> Model {
    let mut g = Lcg(seed);
    let mut states = Vec::new();
    for x in 0..n - 1 {
        let mut actions = Vec::new();
        for _ in 0..1 + g.below(3) {
            let cost = 1 + g.below(6);
            let to = g.below(n as u64);
            if deterministic || g.below(2) == 0 {
                actions.push(format!(r#"{{"to":{to},"cost":"{cost}"}}"#));
            } else {
                let other = g.below(n as u64);
                let k = 1 + g.below(3);
                actions.push(format!(
                    r#"{{"cost":"{cost}","outcomes":[{{"to":{to},"p":"{k}/4"}},{{"to":{other},"p":"{}/4"}}]}}"#,
                    4 - k
                ));
            }
        }
        let _ = x;
        states.push(format!("[{}]", actions.join(",")));
    }
    states.push("[]".into());
    let text = format!(
        r#"{{"initial":0,"goals":[{}],"actions":[{}]}}"#,
        n - 1,
        states.join(",")
    );
    model_of(&text, &format!("random {seed}"))
}

/// The model of a problem file's text (deterministic or stochastic).
fn model_of(text: &str, name: &str) -> Model {
    match from_json(text).expect("a valid problem") {
        ProblemFile::Stochastic(p) => Model::from_problem(*p, name.into()),
        ProblemFile::Deterministic(p) => {
            Model::from_deterministic(&p, name.into()).expect("a valid model")
        }
    }
}

fn analyse(m: &Model, search: Search) -> Result<DiscountAnalysis, ParametricError> {
    discount_breakpoints_search(m, search, &mut |_| {})
}

/// Same breakpoints (as algebraic numbers), same optimal sets and achievements everywhere.
fn assert_same(a: &DiscountAnalysis, b: &DiscountAnalysis, label: &str) {
    assert_eq!(
        a.breakpoints.len(),
        b.breakpoints.len(),
        "{label}: breakpoints"
    );
    for (x, y) in a.breakpoints.iter().zip(&b.breakpoints) {
        assert_eq!(
            x.at.compare(&y.at),
            Ordering::Equal,
            "{label}: a breakpoint"
        );
        assert_eq!(x.touch, y.touch, "{label}: touch");
        assert_eq!(x.ties, y.ties, "{label}: ties");
        assert_eq!(x.achievement, y.achievement, "{label}: at a breakpoint");
    }
    assert_eq!(a.intervals.len(), b.intervals.len());
    for (x, y) in a.intervals.iter().zip(&b.intervals) {
        assert_eq!(x.optimal, y.optimal, "{label}: optimal sets");
        assert_eq!(x.policy, y.policy, "{label}: reported policy");
        assert_eq!(x.achievement, y.achievement, "{label}: on an interval");
    }
}

#[test]
fn pruned_and_full_searches_agree_on_random_problems() {
    let mut compared = 0;
    let mut with_breakpoints = 0;
    for seed in 0..60u64 {
        let deterministic = seed % 2 == 0;
        let m = random_problem(seed, 5 + (seed % 6) as usize, deterministic);
        let (full, pruned) = (analyse(&m, Search::Full), analyse(&m, Search::Pruned));
        match (full, pruned) {
            (Ok(f), Ok(p)) => {
                assert_same(&p, &f, &format!("seed {seed}"));
                compared += 1;
                with_breakpoints += usize::from(!f.breakpoints.is_empty());
            }
            (Err(e), Err(g)) => assert_eq!(e, g, "seed {seed}: the same refusal"),
            (f, p) => panic!(
                "seed {seed}: one search failed: {:?} / {:?}",
                f.err(),
                p.err()
            ),
        }
    }
    // The comparison is not vacuous: most problems are analysed, many with breakpoints.
    assert!(compared >= 40, "{compared} problems compared");
    assert!(
        with_breakpoints >= 10,
        "{with_breakpoints} with breakpoints"
    );
}

/// A `rows × cols` grid (4 neighbours, goal bottom-right) with move costs 1–9 from `seed`.
fn grid(rows: usize, cols: usize, seed: u64) -> Model {
    let mut g = Lcg(seed);
    let mut states = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            if r == rows - 1 && c == cols - 1 {
                states.push("[]".to_string());
                continue;
            }
            let mut moves = Vec::new();
            for (dr, dc) in [(0i64, 1i64), (1, 0), (0, -1), (-1, 0)] {
                let (nr, nc) = (r as i64 + dr, c as i64 + dc);
                if nr < 0 || nc < 0 || nr >= rows as i64 || nc >= cols as i64 {
                    continue;
                }
                let to = nr as usize * cols + nc as usize;
                moves.push(format!(r#"{{"to":{to},"cost":"{}"}}"#, 1 + g.below(9)));
            }
            states.push(format!("[{}]", moves.join(",")));
        }
    }
    let text = format!(
        r#"{{"initial":0,"goals":[{}],"actions":[{}]}}"#,
        rows * cols - 1,
        states.join(",")
    );
    model_of(&text, "grid")
}

#[test]
fn pruned_and_full_searches_agree_on_frozenlake_and_a_grid() {
    let env = EnvSpec::parse("frozenlake")
        .and_then(|s| s.build())
        .expect("a valid spec");
    let m = Model::from_environment(&env).expect("a valid environment");
    let (f, p) = (
        analyse(&m, Search::Full).unwrap(),
        analyse(&m, Search::Pruned).unwrap(),
    );
    assert!(!f.breakpoints.is_empty());
    assert_same(&p, &f, "frozenlake 4x4 slippery");
    // A 6x6 grid with random costs 1-9 (deterministic: the successor-chain path).
    let m = grid(6, 6, 7);
    let (f, p) = (
        analyse(&m, Search::Full).unwrap(),
        analyse(&m, Search::Pruned).unwrap(),
    );
    assert!(
        f.deterministic && f.breakpoints.len() >= 3,
        "{}",
        f.breakpoints.len()
    );
    assert_same(&p, &f, "6x6 grid");
}

#[test]
fn a_deterministic_problem_over_the_state_bound_is_refused_before_work() {
    // A chain of 2501 running states: over the bound (2500), refused at once with the bound
    // named; 2500 states are within it.
    let chain = |n: usize| -> Model {
        let states: Vec<String> = (0..n)
            .map(|x| format!(r#"[{{"to":{},"cost":"1"}}]"#, x + 1))
            .chain(std::iter::once("[]".to_string()))
            .collect();
        let text = format!(
            r#"{{"initial":0,"goals":[{n}],"actions":[{}]}}"#,
            states.join(",")
        );
        model_of(&text, "chain")
    };
    let mut probes = 0;
    let err = discount_breakpoints_search(&chain(2501), Search::Pruned, &mut |_| probes += 1)
        .unwrap_err();
    assert_eq!(probes, 0, "refused before any probe");
    assert_eq!(
        err,
        ParametricError::DeterministicStates {
            states: 2501,
            bound: MAX_DETERMINISTIC_RUNNING_STATES
        }
    );
    assert!(err.to_string().contains("takes at most 2500"), "{err}");
    // 2500 states pass the check: a star (every state one move from the goal) is answered,
    // with no breakpoint.
    let star: Vec<String> = (0..2500)
        .map(|_| r#"[{"to":2500,"cost":"1"}]"#.to_string())
        .chain(std::iter::once("[]".to_string()))
        .collect();
    let text = format!(
        r#"{{"initial":0,"goals":[2500],"actions":[{}]}}"#,
        star.join(",")
    );
    let done = analyse(&model_of(&text, "star"), Search::Pruned).expect("within the bound");
    assert_eq!((done.running_states, done.breakpoints.len()), (2500, 0));
}

#[test]
fn a_deterministic_analysis_stops_at_its_measured_work_bound() {
    let m = grid(8, 8, 3);
    let done = analyse(&m, Search::Pruned).unwrap();
    assert!(
        done.deterministic && done.work > 0 && done.probes >= 3,
        "{} probes, {} units",
        done.probes,
        done.work
    );
    // The work is counted, not timed: the same on a second run, and any bound of twice it
    // gives the same analysis.
    let again = discount_breakpoints_within(&m, Search::Pruned, 2 * done.work, &mut |_| {})
        .expect("within twice its work");
    assert_eq!(again.work, done.work);
    assert_same(&again, &done, "8x8 grid within twice its work");
    // Half its work: stopped while running, the bound named, never passed.
    let half = done.work / 2;
    let mut seen = Vec::new();
    let err =
        discount_breakpoints_within(&m, Search::Pruned, half, &mut |p| seen.push(p)).unwrap_err();
    assert!(err.to_string().contains(&half.to_string()), "{err}");
    match err {
        ParametricError::Work { bound, probes, .. } => {
            assert_eq!(bound, half);
            assert!(probes < done.probes, "{probes} of {}", done.probes);
        }
        other => panic!("{other:?}"),
    }
    assert!(!seen.is_empty());
    assert!(
        seen.iter().all(|p| p.bound == half && p.work <= half),
        "{seen:?}"
    );
}

//! The bounds `discount` checks before any work, on the hostile inputs that once ran for
//! minutes: numbers of huge exponents or many digits, chains whose values need a degree over
//! the bound, probabilities whose denominators pass the exact solver's limit once multiplied by
//! `α`, rewards too large for `compare`'s discounted solve, and outcome sums within `10^-28` of 1.
//! Each input is built here by a small generator; each refusal must come at once (the budget
//! [`REFUSAL_SECONDS`] is for a debug build on a loaded machine; in release each takes well
//! under a second), in one line naming the quantity, the file's value and the bound.

mod common;

use std::process::Command;

use common::cli::write;
use std::time::{Duration, Instant};

/// A refusal's time budget in this (debug) test build; the documented bound is one second in
/// release.
const REFUSAL_SECONDS: u64 = 4;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_truecost")
}

/// Runs `truecost args`; returns whether it succeeded, its stderr and its wall time.
fn run(args: &[&str]) -> (bool, String, Duration) {
    let start = Instant::now();
    let out = Command::new(bin())
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        start.elapsed(),
    )
}

/// A refusal in one line, within [`REFUSAL_SECONDS`], containing every one of `words`.
fn refused(args: &[&str], words: &[&str]) -> String {
    let (ok, err, took) = run(args);
    assert!(!ok, "accepted: {args:?}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        took < Duration::from_secs(REFUSAL_SECONDS),
        "refused after {took:?}: {err}"
    );
    for w in words {
        assert!(err.contains(w), "{w:?} missing from: {err}");
    }
    err
}

/// Two states: from 0, an action to the goal 1 with stage cost `to_goal` and a self-loop with
/// stage cost `stay` (the breakpoint, where staying stops paying, is `α = 1 − stay/to_goal`).
fn two_states(to_goal: &str, stay: &str) -> String {
    format!(
        r#"{{"states": 2, "initial": 0, "goals": [1], "actions": [[{{"to": 1, "cost": "{to_goal}"}}, {{"to": 0, "cost": "{stay}"}}], []]}}"#
    )
}

/// `n` running states in lines of `length` (the last one shorter): state `i` moves on to
/// `i + 1`, the last of each line to the goal `n`, at stage cost 1, or stays at cost 3. The
/// first state of a full line is `length` moves from the goal.
fn lines(n: usize, length: usize) -> String {
    common::line_chains(n, length, |i, next| {
        format!(r#"[{{"to": {next}, "cost": "1"}}, {{"to": {i}, "cost": "3"}}]"#)
    })
}

/// `n` running states in lines of `length`, with rewards of both signs: state `i` moves on
/// (the last of a line to the goal `n`) with reward `+2` or `−1` in turn, stays with `−3`, or
/// moves back (but the first of a line) with `−3`. Every cycle has a negative total, so the
/// first state of a full line, `length` moves from the goal, needs degree `length − 1` next to
/// `α = 1`.
fn mixed_lines(n: usize, length: usize) -> String {
    common::line_chains(n, length, |i, next| {
        let on = if i % 2 == 0 { "2" } else { "-1" };
        let mut list = vec![
            format!(r#"{{"to": {next}, "cost": "1", "reward": "{on}"}}"#),
            format!(r#"{{"to": {i}, "cost": "1", "reward": "-3"}}"#),
        ];
        if i % length != 0 {
            list.push(format!(
                r#"{{"to": {}, "cost": "1", "reward": "-3"}}"#,
                i - 1
            ));
        }
        format!("[{}]", list.join(", "))
    })
}

/// Twelve chains of 200 states (2,400 running states): state `s` moves on at stage cost
/// `k/13` (`k = 1 + 5s mod 13`; the last of a chain to the goal) or leaves for the goal at
/// once at cost 40, so that most states change their optimal action at their own `α`.
fn twelve_chains() -> String {
    let n = 2400;
    common::line_chains(n, 200, |s, next| {
        let k = 1 + (5 * s) % 13;
        format!(r#"[{{"to": {next}, "cost": "{k}/13"}}, {{"to": {n}, "cost": "40"}}]"#)
    })
}

/// A stochastic file whose state 0 reaches the goal with probability `1/2^k` per try (else
/// stays), or moves to state 1 (one step from the goal) at cost 3.
fn stochastic_power(k: u32) -> String {
    let (p, q) = (
        format!("1/{}", 1u64 << k),
        format!("{}/{}", (1u64 << k) - 1, 1u64 << k),
    );
    format!(
        r#"{{"format": "truecost-stochastic/1", "states": 3, "initial": 0, "goals": [2], "actions": [[{{"cost": "1", "outcomes": [{{"to": 2, "p": "{p}"}}, {{"to": 0, "p": "{q}"}}]}}, {{"cost": "3", "outcomes": [{{"to": 1, "p": "1"}}]}}], [{{"cost": "1", "outcomes": [{{"to": 2, "p": "1"}}]}}], []]}}"#
    )
}

/// Stage costs of `1e10000`, `1e-10000` and rewards of 4096 digits are refused at once, naming
/// the state, the action, the number and the bound (magnitude `2^100`, or 160 bits scaled).
#[test]
fn huge_exponents_and_digits_are_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let big = write(dir.path(), "big.json", &two_states("1e10000", "1"));
    let f = big.to_str().unwrap();
    // 10^10000 takes ⌊10000 · log2 10⌋ + 1 = 33220 bits: over the stochastic model's bound
    // on stage costs scaled to integers, checked as the model is built.
    refused(
        &["discount", "--file", f],
        &[
            "state 0, action 0",
            "stage cost ≈1e10000 scaled to an integer",
            "33220 bits",
            "at most 1024",
        ],
    );
    for (name, text, action) in [
        ("tiny-goal.json", two_states("1e-10000", "1"), "action 0"),
        ("tiny-loop.json", two_states("1", "1e-10000"), "action 1"),
    ] {
        let path = write(dir.path(), name, &text);
        refused(
            &["discount", "--file", path.to_str().unwrap()],
            &[
                &format!("state 0, {action}"),
                "the lcm of the stage costs' denominators up to here takes 33220 bits",
                "at most 1024",
            ],
        );
    }
    // Rewards are the discounted objective's own numbers: 10^-10000 is refused by its bound.
    let text = r#"{"states": 2, "initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1", "reward": "1e-10000"}, {"to": 0, "cost": "1", "reward": "1"}], []]}"#;
    let path = write(dir.path(), "tiny-reward.json", text);
    refused(
        &["discount", "--file", path.to_str().unwrap()],
        &["reward ≈1e-10000", "33220 bits", "at most 160"],
    );
    let digits = "9".repeat(4096);
    let text = format!(
        r#"{{"states": 2, "initial": 0, "goals": [1], "actions": [[{{"to": 1, "cost": "1", "reward": "{digits}"}}, {{"to": 0, "cost": "1", "reward": "1"}}], []]}}"#
    );
    let path = write(dir.path(), "digits.json", &text);
    refused(
        &["discount", "--file", path.to_str().unwrap()],
        &["the reward ≈1e4096", "exceeds 2^100"],
    );
}

/// The bounds are where they are said to be: a reward scaled to 160 bits passes (and the
/// breakpoint `1 − 2^-159` is found), 161 bits are refused; a stage cost of exactly `2^100`
/// passes, `2^100 + 1` is refused.
#[test]
fn the_number_bounds_are_exact() {
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str, text: String| write(dir.path(), name, &text);
    let inside = at("159.json", two_states("1", &format!("1/{}", num(159))));
    let (ok, err, _) = run(&["discount", "--file", inside.to_str().unwrap()]);
    assert!(ok, "{err}");
    let outside = at("160.json", two_states("1", &format!("1/{}", num(160))));
    refused(
        &["discount", "--file", outside.to_str().unwrap()],
        &["161 bits", "at most 160"],
    );
    let top = at("top.json", two_states(&num(100), "1"));
    let (ok, err, _) = run(&["discount", "--file", top.to_str().unwrap()]);
    assert!(ok, "{err}");
    let over = at(
        "over.json",
        two_states(&(pow2(100) + 1u32).to_string(), "1"),
    );
    refused(
        &["discount", "--file", over.to_str().unwrap()],
        &["stage cost 1267650600228229401496703205377", "2^100"],
    );
}

fn pow2(k: u32) -> num_bigint::BigUint {
    num_bigint::BigUint::from(1u32) << k
}

/// `2^k` in decimal.
fn num(k: u32) -> String {
    pow2(k).to_string()
}

/// A 2,500-state problem whose farthest state is 202 moves from the goal needs degree 201 for
/// `α` near 1: refused before any probe, naming the moves, the degree and the bound; 201 moves
/// (degree 200) are analysed.
#[test]
fn a_chain_over_the_degree_bound_is_refused_before_any_probe() {
    let dir = tempfile::tempdir().unwrap();
    // 12 lines of 202 states and one of 76: 2,500 running states.
    let path = write(dir.path(), "lines.json", &lines(2500, 202));
    refused(
        &["discount", "--file", path.to_str().unwrap()],
        &[
            "state 0 is 202 moves",
            "degree >= 201",
            "at most 200",
            "before any probe",
        ],
    );
    let long = write(dir.path(), "long.json", &lines(2500, 2500));
    refused(
        &["discount", "--file", long.to_str().unwrap()],
        &["2500 moves", "degree >= 2499"],
    );
    let fits = write(dir.path(), "fits.json", &lines(201, 201));
    let (ok, err, _) = run(&["discount", "--file", fits.to_str().unwrap()]);
    assert!(ok, "{err}");
    // Rewards of both signs (moving on +2 or −1, cycles of negative total): the same.
    let mixed = write(dir.path(), "mixed.json", &mixed_lines(2500, 202));
    refused(
        &["discount", "--file", mixed.to_str().unwrap()],
        &[
            "state 0 is 202 moves",
            "reaching no cycle of rewards totalling 0 or more",
            "degree >= 201",
            "at most 200",
            "before any probe",
        ],
    );
    let fits = write(dir.path(), "mixed-fits.json", &mixed_lines(201, 201));
    let (ok, err, _) = run(&["discount", "--file", fits.to_str().unwrap()]);
    assert!(ok, "{err}");
}

/// The model of a deterministic problem file's text.
fn deterministic_model(text: &str, name: &str) -> truecost::objectives::Model {
    use truecost::stochastic::file::{from_json, ProblemFile};
    let ProblemFile::Deterministic(p) = from_json(text).unwrap() else {
        panic!("a deterministic file")
    };
    truecost::objectives::Model::from_deterministic(&p, name.into()).unwrap()
}

/// Twelve chains of 200 states with costs `k/13`: the work bound stops the analysis in its
/// first probe, naming the probes run, the regions covered (none yet) and the gaps left (all
/// of `(0, 1)`), the work done, the work reserved for the phase after the probes and the
/// bound (here a bound of `2^24` units, so that the test stays short; within the documented
/// bound the analysis is answered, in about a minute in release).
#[test]
fn twelve_chains_are_stopped_by_the_work_bound() {
    use truecost::objectives::parametric::{discount_breakpoints_within, ParametricError, Search};
    let m = deterministic_model(&twelve_chains(), "twelve chains");
    let bound = 1u128 << 24;
    let start = Instant::now();
    let e = discount_breakpoints_within(&m, Search::Pruned, bound, &mut |_| {}).unwrap_err();
    assert!(
        start.elapsed() < Duration::from_secs(REFUSAL_SECONDS),
        "{e}"
    );
    let text = e.to_string();
    let ParametricError::Work { work, reserved, .. } = e else {
        panic!("{text}")
    };
    assert!(work > 0 && reserved > 0, "{text}");
    for w in [
        "stopped after 1 probes (0 regions of (0,1) covered, 1 gaps left)".to_string(),
        format!("{work} units done and {reserved} reserved"),
        format!("the bound of {bound} units"),
    ] {
        assert!(text.contains(&w), "{w:?} missing from {text}");
    }
}

/// The work refusal names the regions covered and the gaps left. Two states whose one
/// breakpoint is `α = 3/4` (staying at cost 1 costs `1/(1 − α)` in all, against 4 to the
/// goal): the first probe, next to 0, covers `(0, 3/4]` and leaves the gap `(3/4, 1)`, which
/// the second probe covers. A bound equal to the work done and reserved as the second probe
/// starts (the progress report's) leaves it no room: the analysis stops after one probe, one
/// region covered, one gap left.
#[test]
fn the_work_refusal_names_the_regions_covered_and_the_gaps_left() {
    use truecost::objectives::parametric::{
        discount_breakpoints_within, ParametricError, Search, MAX_DETERMINISTIC_WORK,
    };
    let m = deterministic_model(&two_states("4", "1"), "one breakpoint");
    let mut seen = Vec::new();
    let full = discount_breakpoints_within(&m, Search::Pruned, MAX_DETERMINISTIC_WORK, &mut |p| {
        seen.push(p)
    })
    .unwrap();
    let three_quarters: truecost::value::Rational = "3/4".parse().unwrap();
    assert_eq!(full.breakpoints.len(), 1);
    assert_eq!(full.breakpoints[0].at.as_rational(), Some(&three_quarters));
    assert_eq!(full.probes, 2);
    let second = seen[1];
    assert_eq!((second.probes, second.regions, second.gaps), (1, 1, 1));
    let e = discount_breakpoints_within(&m, Search::Pruned, second.work, &mut |_| {}).unwrap_err();
    let text = e.to_string();
    let ParametricError::Work {
        probes,
        regions,
        gaps,
        work,
        reserved,
        bound,
    } = e
    else {
        panic!("{text}")
    };
    assert_eq!((probes, regions, gaps), (1, 1, 1), "{text}");
    assert_eq!(
        (work + reserved, bound),
        (second.work, second.work),
        "{text}"
    );
    for w in [
        "stopped after 1 probes (1 regions of (0,1) covered, 1 gaps left)".to_string(),
        format!("{work} units done and {reserved} reserved"),
        format!("the bound of {} units", second.work),
    ] {
        assert!(text.contains(&w), "{w:?} missing from {text}");
    }
}

/// The probes' `α` are chosen within the room the probabilities leave their denominators
/// (the common denominator of a state's probabilities times `α`'s within the exact solver's
/// `2^62`), and a refusal says so with the numbers. `1/2^37` (room `2^25`) is answered: the
/// first probe passes over `1/(2^25 + 1)` for a simpler `α`. `1/2^62` leaves no room at all
/// (every `α` has a denominator of at least 2): refused before any work. (A gap too narrow
/// for the room met while running: the unit tests of `objectives::parametric`.)
#[test]
fn the_probes_alpha_stay_within_the_room_the_probabilities_leave() {
    let dir = tempfile::tempdir().unwrap();
    let p37 = write(dir.path(), "p37.json", &stochastic_power(37));
    let f = p37.to_str().unwrap();
    let (ok, err, _) = run(&["solve", "--algorithm", "exact", "--file", f]);
    assert!(ok, "{err}");
    let (ok, err, _) = run(&["discount", "--file", f]);
    assert!(ok, "{err}");
    let p62 = write(dir.path(), "p62.json", &stochastic_power(62));
    // 2^62 · 2 = 2^63.
    let product = pow2(63).to_string();
    refused(
        &["discount", "--file", p62.to_str().unwrap()],
        &[
            &format!("state 0: the probabilities' common denominator {}", num(62)),
            "times alpha's must be at most 2^62",
            &format!("denominator >= 2, which gives {product}"),
            "refused before any work",
        ],
    );
}

/// A large reward in a deterministic file is named as such by `compare` (the goal state is
/// charged the largest reward per step by the killed-process construction), not as "stage
/// costs times the probabilities' denominators".
#[test]
fn compare_names_the_reward_not_the_stage_cost() {
    let dir = tempfile::tempdir().unwrap();
    let text = r#"{"states": 2, "initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1", "reward": "1e40"}, {"to": 0, "cost": "1", "reward": "1"}], []]}"#;
    let path = write(dir.path(), "reward.json", text);
    let err = refused(
        &[
            "compare",
            "--file",
            path.to_str().unwrap(),
            "--alphas",
            "0.9",
        ],
        &[
            "state 1: the episode is over there",
            "largest reward, ≈1e40",
            "alpha's denominator 10",
            "2^100",
        ],
    );
    assert!(!err.contains("stage costs times"), "{err}");
}

/// Outcome probabilities summing to `1 + 10^-28` are refused with the exact excess, not a
/// rounded sum alone; a shortfall says so.
#[test]
fn a_sum_off_one_shows_its_exact_distance() {
    let dir = tempfile::tempdir().unwrap();
    let file = |p: &str, q: &str| {
        format!(
            r#"{{"format": "truecost-stochastic/1", "initial": 0, "goals": [1], "actions": [[{{"cost": "1", "outcomes": [{{"to": 1, "p": "{p}"}}, {{"to": 0, "p": "{q}"}}]}}], []]}}"#
        )
    };
    let over = write(
        dir.path(),
        "over.json",
        &file("0.5", "0.5000000000000000000000000001"),
    );
    let ten28 = format!("1/1{}", "0".repeat(28));
    for command in ["discount", "solve"] {
        let mut args = vec![command, "--file", over.to_str().unwrap()];
        if command == "solve" {
            args.extend(["--algorithm", "exact"]);
        }
        refused(
            &args,
            &["state 0, action 0", "not 1 (above 1 by", ten28.as_str()],
        );
    }
    let under = write(dir.path(), "under.json", &file("0.5", "0.49"));
    refused(
        &["discount", "--file", under.to_str().unwrap()],
        &["sum to 99/100, not 1 (below 1 by 1/100)"],
    );
}

/// A stochastic file whose state 0 pays `cost` once to reach the goal (one outcome) and whose
/// state 1 pays 1 to reach it with probability 1/2 (else stays): one policy, one region.
fn stochastic_cost(cost: &str) -> String {
    format!(
        r#"{{"format": "truecost-stochastic/1", "states": 3, "initial": 0, "goals": [2], "actions": [[{{"cost": "{cost}", "outcomes": [{{"to": 2, "p": "1"}}]}}], [{{"cost": "1", "outcomes": [{{"to": 2, "p": "1/2"}}, {{"to": 1, "p": "1/2"}}]}}], []]}}"#
    )
}

/// The exact solver's `2^100` on the killed-process construction's stage costs, predicted
/// before the first probe: with `K` the largest stage cost (scaled to an integer) times its
/// state's common denominator of probabilities, every probe's `α` takes a denominator
/// `q ≤ ⌊(2^100 − 1)/K⌋`. `K = 2^99 − 1` leaves `α = 1/2` (answered: one region);
/// `K = 2^99` leaves none, refused before any work naming the state, `K`, the product and the
/// bound.
#[test]
fn the_stage_costs_room_for_alpha_is_known_before_the_first_probe() {
    let dir = tempfile::tempdir().unwrap();
    let fits = write(
        dir.path(),
        "fits.json",
        &stochastic_cost(&(pow2(99) - 1u32).to_string()),
    );
    let (ok, err, _) = run(&["discount", "--file", fits.to_str().unwrap()]);
    assert!(ok, "{err}");
    let over = write(dir.path(), "over.json", &stochastic_cost(&num(99)));
    refused(
        &["discount", "--file", over.to_str().unwrap()],
        &[
            &format!(
                "state 0: discounted stage cost, scaled, times the probabilities' denominator: {}; times alpha's must stay below 2^100",
                num(99)
            ),
            &format!("denominator >= 2, which gives {}", num(100)),
            "refused before any work",
        ],
    );
}

/// A stochastic analysis is charged for the phase after its probes (each breakpoint's
/// reduction as a probe, each achievement as a quarter of one), reserved region by region: on
/// slippery FrozenLake 4 × 4 the work reported exceeds the probes' estimates alone, and a
/// bound one unit short of it stops the analysis with work reserved, though the probes run so
/// far fit it.
#[test]
fn a_stochastic_analysis_is_charged_for_the_phase_after_its_probes() {
    use truecost::envs::EnvSpec;
    use truecost::objectives::parametric::{
        discount_breakpoints, discount_breakpoints_limited, Limits, ParametricError, Search,
    };
    use truecost::objectives::Model;
    let env = EnvSpec::parse("frozenlake").unwrap().build().unwrap();
    let m = Model::from_environment(&env).unwrap();
    let d = discount_breakpoints(&m).unwrap();
    assert!(!d.deterministic && !d.breakpoints.is_empty());
    // Every probe costs the same estimate: the work is probes · p plus the phase after them,
    // (breakpoints · (1 + 2/4) + 1/4) · p, up to integer division.
    let (probes, points) = (d.probes as u128, d.breakpoints.len() as u128);
    let p = d.work * 4 / (4 * probes + 6 * points + 1);
    assert!(p > 0);
    assert!(
        d.work > probes * p,
        "{} <= {} probes of {p}",
        d.work,
        probes
    );
    let limits = Limits {
        stochastic_work: d.work - 1,
        ..Limits::default()
    };
    let start = Instant::now();
    let e = discount_breakpoints_limited(&m, Search::Pruned, limits, &mut |_| {}).unwrap_err();
    assert!(
        start.elapsed() < Duration::from_secs(REFUSAL_SECONDS),
        "{e}"
    );
    let ParametricError::Work { work, reserved, .. } = e else {
        panic!("{e}")
    };
    assert!(
        reserved > 0 && work < d.work,
        "{work} done, {reserved} reserved"
    );
}

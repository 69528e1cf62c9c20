//! `truecost learn`: derandomized Q-learning replayed round by round in
//! exact arithmetic, and the replay commands carried by the claims' counterexamples.

mod common;

use common::cli::{fails, fails_one_line, json, stdout, truecost};
use truecost::claims::{run, Scope};

/// A temporary problem file.
fn problem(text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.json");
    std::fs::write(&path, text).unwrap();
    (dir, path.to_str().unwrap().to_string())
}

/// 0 -> 1 (cost 2), 1 -> 2 (cost 3), goal 2: Q* = (5, 3, 0) in pair order
/// `Q(0->1), Q(1->2), Q(2,uT)`.
const LINE: &str = r#"{"initial": 0, "goals": [2], "actions": [[{"to": 1, "cost": "2"}], [{"to": 2, "cost": "3"}], []]}"#;

fn learn(file: &str, extra: &[&str]) -> String {
    let mut args = vec!["learn", "--file", file];
    args.extend_from_slice(extra);
    stdout(&args)
}

#[test]
fn orders_decide_how_fast_information_travels() {
    let (_d, f) = problem(LINE);
    // Cyclic: round 1 sets Q(0->1) = 2 + Q(1->2) = 2 + 0 before Q(1->2) = 3; round 2 gives 5.
    let cyclic = learn(
        &f,
        &[
            "--q0",
            "0",
            "--order",
            "cyclic",
            "--rounds",
            "5",
            "--terminal",
            "held",
        ],
    );
    assert!(
        cyclic.contains("Q*: Q(0->1)=5 Q(1->2)=3 Q(2,uT)=0"),
        "{cyclic}"
    );
    assert!(
        cyclic.contains("round 1: Q(0->1)=2 Q(1->2)=3 Q(2,uT)=0"),
        "{cyclic}"
    );
    assert!(
        cyclic.contains("round 2: Q(0->1)=5 Q(1->2)=3 Q(2,uT)=0"),
        "{cyclic}"
    );
    assert!(cyclic.ends_with("converged at round 2\n"), "{cyclic}");
    // Reverse: Q(2,uT) is held, then Q(1->2) = 3, then Q(0->1) = 5 in the same round.
    let reverse = learn(
        &f,
        &[
            "--q0",
            "0",
            "--order",
            "reverse",
            "--rounds",
            "5",
            "--terminal",
            "held",
        ],
    );
    assert!(reverse.ends_with("converged at round 1\n"), "{reverse}");
    // Far-first (the adversary): the pair into state 1 (h = 1) before the pair into the goal.
    let far = learn(
        &f,
        &[
            "--q0",
            "0",
            "--order",
            "far-first",
            "--rounds",
            "5",
            "--terminal",
            "held",
        ],
    );
    assert!(far.ends_with("converged at round 2\n"), "{far}");
    // Too few rounds.
    let short = learn(
        &f,
        &[
            "--q0",
            "0",
            "--order",
            "cyclic",
            "--rounds",
            "1",
            "--terminal",
            "held",
        ],
    );
    assert!(
        short.ends_with("not converged within 1 rounds\n"),
        "{short}"
    );
    // Started at Q*: converged at round 0.
    let at = learn(&f, &["--q0", "5,3,0", "--order", "cyclic", "--rounds", "1"]);
    assert!(at.ends_with("converged at round 0\n"), "{at}");
}

#[test]
fn exact_fractions_and_negative_initial_values() {
    let (_d, f) = problem(
        r#"{"initial": 0, "goals": [1], "actions": [[{"to": 1, "cost": "1/3"}, {"to": 0, "cost": "1/2"}], []]}"#,
    );
    // Pairs: Q(0->1), Q(0->0), Q(1,uT). From -1/3 everywhere, termination pair updated (as
    // printed): Q(1,uT) = 0 + Q(1,uT) stays -1/3 forever, so Q(0->1) = 1/3 - 1/3 = 0; then
    // Q(0->0) = 1/2 + min(0, -1/3) = 1/6 in round 1 and 1/2 + min(0, 1/6) = 1/2 from round 2 on:
    // round-end values repeat from round 2.
    let t = learn(&f, &["--q0", "-1/3", "--order", "cyclic", "--rounds", "10"]);
    assert!(t.contains("Q*: Q(0->1)=1/3 Q(0->0)=5/6 Q(1,uT)=0"), "{t}");
    assert!(
        t.contains("round 1: Q(0->1)=0 Q(0->0)=1/6 Q(1,uT)=-1/3"),
        "{t}"
    );
    assert!(
        t.contains("round 2: Q(0->1)=0 Q(0->0)=1/2 Q(1,uT)=-1/3"),
        "{t}"
    );
    assert!(
        t.ends_with("never converges: round-end values repeat from round 2\n"),
        "{t}"
    );
    // Held at 0 (H0) with positive costs: converges whatever Q0.
    let h = learn(
        &f,
        &[
            "--q0",
            "-7/2",
            "--order",
            "cyclic",
            "--rounds",
            "20",
            "--terminal",
            "held",
        ],
    );
    assert!(h.contains("converged at round"), "{h}");
}

#[test]
fn json_output_and_seeded_random_order() {
    let (_d, f) = problem(LINE);
    let args = [
        "learn",
        "--file",
        &f,
        "--q0",
        "7,-2,0",
        "--order",
        "random",
        "--seed",
        "9",
        "--rounds",
        "6",
        "--terminal",
        "held",
        "--format",
        "json",
    ];
    let a = json(&args);
    let b = json(&args);
    assert_eq!(a, b, "a seeded random order is reproducible");
    assert_eq!(a["order"], "random");
    assert_eq!(a["seed"], 9);
    assert_eq!(a["terminal"], "held");
    assert_eq!(a["pairs"][0]["optimum"], "5");
    assert_eq!(a["pairs"][2]["terminal"], true);
    assert_eq!(
        a["rounds"][0]["values"],
        serde_json::json!(["7", "-2", "0"])
    );
    assert_eq!(a["verdict"]["kind"], "converged");
    let r = a["verdict"]["round"].as_u64().unwrap();
    assert!((1..=2).contains(&r), "at most h + 1 = 2 rounds: {a}");
    assert_eq!(a["verdict_line"], format!("converged at round {r}"));
    assert_eq!(a["rounds"].as_array().unwrap().len() as u64, r + 1);
}

#[test]
fn bad_input_is_one_line_and_usage_errors_exit_2() {
    let (_d, f) = problem(LINE);
    let base = [
        "learn",
        "--file",
        f.as_str(),
        "--order",
        "cyclic",
        "--rounds",
        "3",
    ];
    let with = |extra: &[&str]| {
        let mut v: Vec<&str> = base.to_vec();
        v.extend_from_slice(extra);
        v.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let e = fails_one_line(&with(&["--q0", "1,2"]));
    assert!(e.contains("lists 2 values but the problem has 3"), "{e}");
    let e = fails_one_line(&with(&["--q0", "one"]));
    assert!(e.contains("--q0"), "{e}");
    let e = fails_one_line(&with(&["--q0", "1,1,5", "--terminal", "held"]));
    assert!(e.contains("held at 0"), "{e}");
    let e = fails_one_line(&with(&["--q0", "0", "--seed", "3"]));
    assert!(e.contains("--seed"), "{e}");
    let e = fails_one_line(&[
        "learn", "--file", &f, "--order", "random", "--rounds", "3", "--q0", "0",
    ]);
    assert!(e.contains("--seed"), "{e}");
    let e = fails_one_line(&[
        "learn", "--file", &f, "--order", "cyclic", "--rounds", "100001", "--q0", "0",
    ]);
    assert!(e.contains("at most"), "{e}");
    fails_one_line(&[
        "learn",
        "--file",
        "/nonexistent.json",
        "--q0",
        "0",
        "--order",
        "cyclic",
        "--rounds",
        "1",
    ]);
    fails(&with(&["--q0", "0", "--order", "sideways"]), 2);
    fails(
        &["learn", "--file", &f, "--q0", "0", "--order", "cyclic"],
        2,
    );
}

/// Runs a printed replay command (`truecost ...`) from the repository root.
fn run_replay(command: &str) -> String {
    let args: Vec<&str> = command.split_whitespace().collect();
    assert_eq!(args[0], "truecost", "{command}");
    let out = truecost()
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(&args[1..])
        .assert()
        .success()
        .get_output()
        .clone();
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn counterexamples_carry_a_replay_that_shows_the_failure() {
    let r = run(Scope::Smoke, None).unwrap();
    let c1 = r.claims.iter().find(|c| c.id == "C1").unwrap();
    let ce = c1.counterexample.as_ref().unwrap();
    // The headline is the zero-cost cycle started below Q*, not the termination pair.
    assert_eq!(ce.problem, "0: ->0 (0), ->1 (1); 1 (goal)");
    let replay = ce.replay.as_deref().unwrap();
    assert!(
        replay.starts_with("truecost learn --file problems/counterexamples/c1-as-printed.json "),
        "{replay}"
    );
    let out = run_replay(replay);
    assert!(out.contains("Q*: Q(0->0)=1 Q(0->1)=1 Q(1,uT)=0"), "{out}");
    assert!(
        out.contains("round 1: Q(0->0)=0 Q(0->1)=1 Q(1,uT)=0"),
        "{out}"
    );
    assert!(
        out.ends_with("never converges: round-end values repeat from round 1\n"),
        "{out}"
    );
    // The termination-pair case stays as a note.
    assert!(
        c1.notes
            .iter()
            .any(|n| n.contains("termination pair") && n.contains("Q(0,uT)=1")),
        "{:?}",
        c1.notes
    );
    // C4's replay shows the printed set disagreeing with the oracle.
    let c4 = r.claims.iter().find(|c| c.id == "C4").unwrap();
    let replay = c4
        .counterexample
        .as_ref()
        .unwrap()
        .replay
        .as_deref()
        .unwrap();
    assert_eq!(
        replay,
        "truecost verify --claim C4 --file problems/counterexamples/c4-as-printed.json"
    );
    let out = run_replay(replay);
    assert!(out.contains("(DISAGREES)"), "{out}");
    // Every counterexample has one.
    for c in &r.claims {
        if let Some(ce) = &c.counterexample {
            assert!(
                ce.replay
                    .as_deref()
                    .is_some_and(|s| s.starts_with("truecost ")),
                "{}",
                c.id
            );
        }
    }
}

/// On the command line, a negative initial value makes the
/// `⌈(max Q* − min(0, min Q₀))/c⌉` term of C1-corrected's bound decide, and the replay attains
/// it: `0 → 0 (1), 0 → goal (1)` from `Q₀ = −2`, by hand `Q(0→0)` = −1, 0, 1, 2 over rounds 1–4.
#[test]
fn a_negative_start_needs_the_negative_term_of_the_bound() {
    let (_d, f) = problem(
        r#"{"initial": 0, "goals": [1], "actions": [[{"to": 0, "cost": "1"}, {"to": 1, "cost": "1"}], []]}"#,
    );
    let t = learn(
        &f,
        &[
            "--q0",
            "-2,-2,0",
            "--order",
            "cyclic",
            "--rounds",
            "10",
            "--terminal",
            "held",
        ],
    );
    assert!(t.contains("round 1: Q(0->0)=-1 Q(0->1)=1 Q(1,uT)=0"), "{t}");
    assert!(t.contains("round 3: Q(0->0)=1 Q(0->1)=1 Q(1,uT)=0"), "{t}");
    assert!(t.ends_with("converged at round 4\n"), "{t}");
}

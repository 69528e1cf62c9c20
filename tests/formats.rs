//! Storm's DRN and the PRISM language ([`truecost::formats`]): a problem written as DRN and
//! read back is the same problem with the same exact answers (every objective, every state) for
//! every source; the PRISM text states every action once; hostile DRN input is refused in one
//! line before any work. (Storm's own answers on these files: python/tests/test_storm.py.)

mod common;

use common::cli::{fails_one_line, stdout};
use truecost::formats::{dead_ends_as_traps, drn, from_text_with_objective, prism, Kind};
use truecost::objectives::{Model, Objective, Source};
use truecost::problems::StepCost;
use truecost::stochastic::file::{FileObjective, ProblemFile};
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::Rational;

/// Every action as (state, cost, [(successor, probability)]), the goals' actions left out (a
/// goal ends the episode; DRN gives a goal without actions a stand-in self-loop).
type Moves = Vec<(usize, Rational, Vec<(usize, Rational)>)>;

fn moves(p: &StochasticProblem) -> Moves {
    (0..p.action_total())
        .filter(|&a| !p.is_goal(p.state_of(a)))
        .map(|a| {
            let outs = p.outcomes(a).iter();
            let outs = outs.map(|o| (o.successor, o.probability.clone())).collect();
            (p.state_of(a), p.cost(a).clone(), outs)
        })
        .collect()
}

/// The model of `source` written as DRN, read back through the `--file` reader.
fn round_trip(model: &Model) -> (Model, FileObjective, FileObjective) {
    let (problem, extra) = model.exportable();
    let (problem, extra) = dead_ends_as_traps(&problem, &extra);
    let text = drn::to_drn(&problem, &extra, Some(&model.name)).unwrap();
    let (file, back_extra) = from_text_with_objective(&text).unwrap();
    let ProblemFile::Stochastic(back) = file else {
        panic!("a DRN file is a stochastic problem")
    };
    // (Not assert_eq: a paper problem's actions would fill the terminal.)
    assert!(
        moves(&back) == moves(&problem),
        "{}: the actions differ",
        model.name
    );
    assert_eq!(back.goals(), problem.goals());
    assert_eq!(back.initial(), problem.initial());
    let back = Model::from_problem(*back, "back".into()).with_file_objective(&back_extra);
    (back, extra, back_extra)
}

/// The exact answers of both models agree: every state's value and the value at the initial
/// distribution, for the truecost, reach and discounted (α = 9/10) objectives.
fn same_answers(a: &Model, b: &Model) {
    let alpha = Rational::new(9.into(), 10.into());
    for objective in [
        Objective::Truecost,
        Objective::Reach,
        Objective::Discounted(alpha),
    ] {
        let (x, y) = (a.solve(&objective).unwrap(), b.solve(&objective).unwrap());
        assert_eq!(x.values, y.values, "{} {}", a.name, objective.name());
        assert_eq!(x.value_initial, y.value_initial, "{}", a.name);
    }
}

#[test]
fn paper_problems_round_trip_under_both_noise_models() {
    for noise in [NoiseModel::Paper, NoiseModel::Reference] {
        let model = Source::Paper {
            id: 3,
            step: StepCost::Euclidean,
            noise,
            gamma: Predictability::parse("0.9").unwrap(),
        }
        .load()
        .unwrap();
        let (back, extra, back_extra) = round_trip(&model);
        // The rewards (the negated costs, here written as the `reward` model) and the
        // obstacles (dead ends written as traps, listed terminal) come back.
        assert!(back_extra == extra, "rewards or terminal states differ");
        assert!(!extra.terminal.is_empty());
        same_answers(&model, &back);
    }
}

#[test]
fn environments_round_trip_with_rewards_terminal_states_and_initial_states() {
    for spec in ["frozenlake:map=8x8", "cliffwalking:slippery=true", "taxi"] {
        let model = Source::Env(spec.into()).load().unwrap();
        let (back, extra, back_extra) = round_trip(&model);
        // Gymnasium's rewards (the `reward` model), the holes (`terminal`) and Taxi's 300
        // initial states (several `init` labels: a uniform distribution) come back as they were.
        assert_eq!(back_extra, extra, "{spec}");
        same_answers(&model, &back);
    }
    let taxi = Source::Env("taxi".into()).load().unwrap();
    let (p, extra) = taxi.exportable();
    let text = drn::to_drn(&p, &extra, None).unwrap();
    assert_eq!(text.matches(" init").count(), 300);
    assert!(text.contains("@reward_models\ncost reward\n"));
}

#[test]
fn a_json_file_round_trips_and_a_non_uniform_initial_distribution_is_refused() {
    let text = r#"{"initial": [{"state": 0, "p": "1/2"}, {"state": 1, "p": "1/2"}], "goals": [2],
        "terminal": [3], "actions": [
        [{"cost": "1", "reward": "-1", "outcomes": [{"to": 2, "p": "1/3"}, {"to": 3, "p": "2/3"}]},
         {"cost": "0", "reward": "0", "outcomes": [{"to": 1, "p": "1"}]}],
        [{"cost": "5/2", "reward": "1/2", "outcomes": [{"to": 2, "p": "1"}]}],
        [],
        [{"cost": "0", "reward": "0", "outcomes": [{"to": 3, "p": "1"}]}]]}"#;
    let (file, extra) = from_text_with_objective(text).unwrap();
    let ProblemFile::Stochastic(p) = file else {
        panic!()
    };
    let model = Model::from_problem(*p.clone(), "json".into()).with_file_objective(&extra);
    let (back, _, back_extra) = round_trip(&model);
    assert_eq!(back_extra, extra);
    same_answers(&model, &back);
    // G*(0): the first action risks the trap, so 0 -> 1 (free) then 5/2; by hand.
    let t = model.solve(&Objective::Truecost).unwrap();
    assert_eq!(t.values[0].to_string(), "5/2");
    let skewed = text.replacen(
        "\"1/2\"}, {\"state\": 1, \"p\": \"1/2\"",
        "\"1/4\"}, {\"state\": 1, \"p\": \"3/4\"",
        1,
    );
    let (ProblemFile::Stochastic(p), extra) = from_text_with_objective(&skewed).unwrap() else {
        panic!()
    };
    let e = drn::to_drn(&p, &extra, None).unwrap_err().to_string();
    assert!(
        e.starts_with("the initial distribution is not uniform"),
        "{e}"
    );
    let e = prism::to_prism(&p, &extra, None).unwrap_err().to_string();
    assert!(
        e.starts_with("the initial distribution is not uniform"),
        "{e}"
    );
}

#[test]
fn prism_text_states_every_action_once_with_its_cost() {
    let model = Source::Env("taxi".into()).load().unwrap();
    let (p, extra) = model.exportable();
    let text = prism::to_prism(&p, &extra, Some("taxi")).unwrap();
    let commands = text.lines().filter(|l| l.contains("->")).count();
    // Every action, plus a stand-in self-loop at each state without actions (the goals).
    let bare = (0..p.states()).filter(|&x| p.actions(x).is_empty()).count();
    assert_eq!(commands, p.action_total() + bare);
    assert!(
        text.contains("  s : [0..499];\n"),
        "initial states in an init block instead"
    );
    assert_eq!(text.matches("init s=").count(), 1);
    let costs = text.split("rewards \"cost\"\n").nth(1).unwrap();
    let costs = costs.split("endrewards").next().unwrap();
    let nonzero = (0..p.action_total())
        .filter(|&a| !num_traits::Zero::is_zero(p.cost(a)))
        .count();
    assert_eq!(costs.lines().count(), nonzero);
}

#[test]
fn content_decides_the_format() {
    assert_eq!(truecost::formats::detect("\n// x\n@type: MDP"), Kind::Drn);
    assert_eq!(truecost::formats::detect("dtmc\n"), Kind::Prism);
    assert_eq!(truecost::formats::detect("[1, 2]"), Kind::Json);
}

const GOOD: &str = "@type: MDP\n@value_type: rational\n@parameters\n\n@reward_models\ncost\n\
    @nr_states\n2\n@nr_choices\n2\n@model\nstate 0 init\n\taction 0 [1]\n\t\t1 : 1/2\n\
    \t\t0 : 1/2\nstate 1 goal\n\taction 0 [0]\n\t\t1 : 1\n";

#[test]
fn the_command_line_solves_a_drn_file_and_exports_every_source() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.drn");
    std::fs::write(&good, GOOD).unwrap();
    // G(0) = 1 + G(0)/2: 2.
    let v = common::cli::solve_json(&["--file", good.to_str().unwrap()], "truecost");
    assert_eq!(v["cost_to_go_initial"], "2");
    for (i, source) in [
        vec!["--problem", "3", "--gamma", "0.9", "--noise", "reference"],
        vec!["--env", "frozenlake"],
        vec!["--grid", "4x5", "--pattern", "walls", "--gamma", "0.99"],
        vec!["--file", good.to_str().unwrap()],
    ]
    .into_iter()
    .enumerate()
    {
        for format in ["drn", "prism", "json"] {
            let out = dir.path().join(format!("{i}.{format}"));
            let mut args = vec!["export"];
            args.extend_from_slice(&source);
            args.extend_from_slice(&["--format", format, "--out", out.to_str().unwrap()]);
            assert!(stdout(&args).starts_with("wrote "), "{args:?}");
            if format == "prism" {
                continue;
            }
            // The export and the source give the same exact optimum.
            let file = ["--file", out.to_str().unwrap()];
            let a = common::cli::solve_json(&file, "truecost");
            let b = if source[0] == "--grid" {
                // A grid is not a source of solve: compare the two exports.
                common::cli::solve_json(
                    &[
                        "--file",
                        dir.path().join(format!("{i}.drn")).to_str().unwrap(),
                    ],
                    "truecost",
                )
            } else {
                common::cli::solve_json(&source, "truecost")
            };
            assert_eq!(a["values"], b["values"], "{args:?}");
        }
    }
}

/// `discount --file` reads DRN too: a file and its DRN export give the same analysis.
#[test]
fn discount_reads_a_drn_file_as_its_json_source() {
    let dir = tempfile::tempdir().unwrap();
    let drn = dir.path().join("fl.drn");
    let json = dir.path().join("fl.json");
    for (out, format) in [(&drn, "drn"), (&json, "json")] {
        let args = [
            "export",
            "--env",
            "frozenlake:slippery=false",
            "--format",
            format,
            "--out",
            out.to_str().unwrap(),
        ];
        assert!(stdout(&args).starts_with("wrote "), "{args:?}");
    }
    let analysis = |f: &std::path::Path| {
        let text = stdout(&[
            "discount",
            "--file",
            f.to_str().unwrap(),
            "--format",
            "json",
        ]);
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        v.as_object_mut().unwrap().remove("source");
        v
    };
    let (a, b) = (analysis(&drn), analysis(&json));
    assert!(a["breakpoints"].is_array(), "{a}");
    assert_eq!(a["breakpoints"], b["breakpoints"]);
    assert_eq!(a["intervals"], b["intervals"]);
}

#[test]
fn hostile_drn_input_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            GOOD.replacen("1/2", "1/3", 1),
            "sum to 5/6, not 1 (below 1 by 1/6)",
        ),
        // A sum within 10^-22 of 1: shortened in decimal, its distance from 1 exact.
        (
            GOOD.replacen("1/2", "0.5000000000000000000001", 1),
            "sum to ≈1.0000000000000000, not 1 (above 1 by 1/10000000000000000000000)",
        ),
        (GOOD.replacen("1/2", "0", 1), "not in (0, 1]"),
        (GOOD.replacen("1/2", "1/2x", 1), "DRN line 14"),
        (
            GOOD.replace("@nr_states\n2", "@nr_states\n18446744073709551616"),
            "is not a number",
        ),
        (
            GOOD.replace("@nr_states\n2", "@nr_states\n9999999"),
            "more than a file of",
        ),
        (
            GOOD.replace("@nr_choices\n2", "@nr_choices\n99999"),
            "more than a file of",
        ),
        (
            GOOD.replace("@nr_choices\n2", "@nr_choices\n1"),
            "more actions than declared",
        ),
        (
            GOOD.replace("@nr_states\n2", "@nr_states\n3"),
            "2 states given, 3 declared",
        ),
        (GOOD.replace("\t\t0 : 1/2", "\t\t9 : 1/2"), "target state 9"),
        (GOOD.replace("[1]", "[-1]"), "negative"),
        (GOOD.replace(" init", ""), "no state is labelled 'init'"),
        (
            GOOD.replace("@type: MDP", "@type: POMDP"),
            "model type 'POMDP'",
        ),
        (
            GOOD.replace("@parameters\n\n", "@parameters\np q\n"),
            "parametric",
        ),
        (
            GOOD.replace("@model\n", ""),
            "could not parse header line 'state 0 init'",
        ),
        (
            GOOD.split("@model").next().unwrap().to_string(),
            "ends before @model",
        ),
        (GOOD.replace("state 1", "state 7"), "expected 1 but got 7"),
        (
            GOOD.replace("\t\t1 : 1/2\n", "\t\t1 1/2\n"),
            "':' not found",
        ),
        (
            GOOD.replace("1/2", &format!("1/{}", "9".repeat(5000))),
            "too long",
        ),
        (GOOD.replace("@type: MDP", "@type: MDP\x1b[2J"), "\\x1b[2J"),
        (
            "mdp\nmodule m\nendmodule\n".to_string(),
            "PRISM-language input is not read",
        ),
    ];
    for (i, (text, expect)) in cases.iter().enumerate() {
        let path = dir.path().join(format!("bad{i}.drn"));
        std::fs::write(&path, text).unwrap();
        let file = path.to_str().unwrap();
        let err = fails_one_line(&["solve", "--file", file, "--algorithm", "exact"]);
        assert!(err.contains(expect), "case {i}: {err}");
        let out = dir.path().join("x.drn");
        let err = fails_one_line(&[
            "export",
            "--file",
            file,
            "--format",
            "drn",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(err.contains(expect), "case {i}: {err}");
    }
}

//! Like-for-like clocks, nanoseconds per action, and the paper's published numbers
//! beside ours (`reproduce deterministic|stochastic --against-published`).
//!
//! Expected published values are copied from `shared/reference/problem10.md` (numbers
//! established from the paper's repository), never from truecost's output.

mod common;

use common::cli::{json, stdout};
use serde_json::Value;
use truecost::experiments::deterministic::time_model_free;
use truecost::experiments::published::{
    self, judge, KeyPart, Kind, Observed, PublishedValue, Verdict,
};
use truecost::model::Graph;
use truecost::planning::{model_free_counts, Algorithm, Mode, PlanCounts};
use truecost::value::parse_rational;

// ---- what is inside the timed region, pinned by types ------------------------------------------

/// The timed region of a model-free row takes a compiled graph (compilation happens before)
/// and returns counts only: `PlanCounts` owns nothing on the heap (no strings, no vectors, so
/// no rendering and no report can be built inside) and is `Copy`.
#[test]
fn the_model_free_timed_region_takes_a_compiled_graph_and_returns_counts_only() {
    fn copy<T: Copy>() {}
    copy::<PlanCounts>();
    assert!(!std::mem::needs_drop::<PlanCounts>());
    // The clock wraps exactly `model_free_counts` on a prepared graph.
    let timed: fn(&Graph<f64>, Algorithm, Mode) -> (PlanCounts, f64) = time_model_free::<f64>;
    let region: fn(&Graph<f64>, Algorithm, Mode) -> PlanCounts = model_free_counts::<f64>;
    let graph = truecost::problems::GridLayout::reference(10)
        .unwrap()
        .to_reference_graph();
    let (counts, seconds) = timed(&graph, Algorithm::AsyncVi, Mode::Reference);
    assert_eq!(counts, region(&graph, Algorithm::AsyncVi, Mode::Reference));
    assert!(seconds.is_finite());
    // Problem 10, asynchronous VI on the explored graph: 56 sweeps, 69570 actions in total.
    assert_eq!((counts.iterations, counts.actions()), (56, 69570));
    assert_eq!(counts.exploration_actions, 3266);
}

/// In exact mode the timed region runs on the compiled exact graph and agrees with the full
/// planning report (which also renders values).
#[test]
fn exact_mode_counts_agree_with_the_planning_report() {
    use truecost::model::ExactGraph;
    use truecost::problems::{GridLayout, StepCost};
    let problem = GridLayout::exact(0).unwrap().to_problem(StepCost::Unit);
    let ExactGraph::Units(graph) = ExactGraph::new(&problem) else {
        panic!("unit costs compile to units")
    };
    for algorithm in [Algorithm::Dijkstra, Algorithm::Vi, Algorithm::AsyncVi] {
        let c = model_free_counts(&graph, algorithm, Mode::Exact);
        let r = truecost::planning::plan_exact(&problem, algorithm, true);
        assert_eq!(
            (c.iterations, c.actions(), c.path_states, c.reached_goal),
            (r.iterations, r.actions, r.path.len(), r.reachable),
            "{algorithm:?}"
        );
        // Problem 0: 17 optimal moves, so 18 states on the path.
        assert_eq!(c.path_states, 18);
    }
}

// ---- the shipped data -------------------------------------------------------------------------

#[test]
fn shipped_published_data_parses_and_names_its_provenance() {
    let det = published::deterministic().unwrap();
    let sto = published::stochastic().unwrap();
    assert!(!det.sources.is_empty());
    for s in &det.sources {
        assert_eq!(s.commit.len(), 40, "{}", s.file);
        assert!(s.commit.chars().all(|c| c.is_ascii_hexdigit()));
        assert!(s.file.starts_with("sims/"), "{}", s.file);
        assert_eq!(s.samples, 100);
    }
    // Every paper problem has the paper's 11 deterministic rows.
    for p in truecost::problems::PAPER_PROBLEMS {
        let rows = det.rows.keys().filter(|(q, _)| *q == p).count();
        assert_eq!(rows, 11, "problem {p}");
    }
    // Cross-check with shared/reference/problem10.md.
    let row =
        |alg: &str, eps: &str| &det.rows[&(10, vec![KeyPart::parse(alg), KeyPart::parse(eps)])];
    let value = |alg: &str, eps: &str, m: &str| row(alg, eps)[m].value.clone();
    let n = |t: &str| parse_rational(t).unwrap();
    assert_eq!(
        value("model-free-dijkstra", "", "mean_iterations"),
        n("331")
    );
    assert_eq!(
        value("model-free-dijkstra", "", "mean_planner_actions"),
        n("1157")
    );
    assert_eq!(value("model-free-dijkstra", "", "mean_actions"), n("4423"));
    assert_eq!(value("model-free-async-vi", "", "mean_iterations"), n("56"));
    assert_eq!(value("model-free-async-vi", "", "mean_actions"), n("69570"));
    assert_eq!(value("model-free-vi", "", "mean_iterations"), n("67"));
    assert_eq!(value("model-free-vi", "", "mean_actions"), n("82594"));
    assert_eq!(value("q-learning", "0", "mean_iterations"), n("999"));
    assert_eq!(value("q-learning", "0", "mean_actions"), n("101214"));
    assert_eq!(
        value("q-learning", "0", "mean_actions_goal_discovered"),
        n("2015")
    );
    assert_eq!(
        value("q-learning", "0", "mean_actions_initial_optimal"),
        n("52000")
    );
    // The paper's published times: Dijkstra 2.48 ms, greedy Q-learning 334 ms.
    let ms = |alg: &str, eps: &str| row(alg, eps)["mean_time_s"].approx() * 1000.0;
    assert!((ms("model-free-dijkstra", "") - 2.48).abs() < 0.005);
    assert!((ms("q-learning", "0") - 334.0).abs() < 0.5);
    // Stochastic VI, reference noise: γ = 0.999 async 58 / 178292, sync 94 / 288956;
    // γ = 0.99: 69 / 212106 and 112 / 344288.
    for (gamma, alg, sweeps, actions) in [
        ("0.999", "stochastic-async-vi", "58", "178292"),
        ("0.999", "stochastic-vi", "94", "288956"),
        ("0.99", "stochastic-async-vi", "69", "212106"),
        ("0.99", "stochastic-vi", "112", "344288"),
    ] {
        let key = (10, [gamma, alg, "", ""].map(KeyPart::parse).to_vec());
        assert_eq!(sto.rows[&key]["mean_iterations"].value, n(sweeps));
        assert_eq!(sto.rows[&key]["mean_actions"].value, n(actions));
    }
}

// ---- verdicts ---------------------------------------------------------------------------------

fn published_value(text: &str, std: Option<f64>) -> PublishedValue {
    PublishedValue {
        text: text.into(),
        value: parse_rational(text).unwrap(),
        std,
        samples: 100,
        source: 0,
    }
}

#[test]
fn verdicts_follow_the_stated_rules() {
    // Exact counts: equal is exact, off by one differs (with the difference).
    let ours = Observed::counts(&[101214, 101214]).unwrap();
    let p = published_value("101214.0", Some(0.0));
    assert_eq!(judge(Kind::Mean, &p, Some(&ours), true), Verdict::Exact);
    match judge(
        Kind::Mean,
        &published_value("101215", Some(0.0)),
        Some(&ours),
        true,
    ) {
        Verdict::Differs { difference, .. } => assert_eq!(difference, Some(-1.0)),
        v => panic!("{v:?}"),
    }
    // Exact means compare as rationals: 685022.72 = 68502272/100.
    let values: Vec<u64> = (0..100)
        .map(|k| if k < 72 { 685023 } else { 685022 })
        .collect();
    let ours = Observed::counts(&values).unwrap();
    assert_eq!(
        judge(
            Kind::Mean,
            &published_value("685022.72", None),
            Some(&ours),
            true
        ),
        Verdict::Exact
    );
    // A statistical mean: 1000 ± 100 (100 samples) against ours 1010 ± 100 is consistent;
    // against 1100 it differs (bound 2.5758 · 100 · √(2/100) ≈ 36.4).
    let ours = Observed::counts(&[910, 1110]).unwrap(); // mean 1010, population std 100
    let p = published_value("1000", Some(100.0));
    assert_eq!(
        judge(Kind::Mean, &p, Some(&ours), false).name(),
        "consistent"
    );
    let far = Observed::counts(&[1000, 1200]).unwrap(); // mean 1100
    let v = judge(
        Kind::Mean,
        &published_value("1000", Some(10.0)),
        Some(&far),
        false,
    );
    assert_eq!(v.name(), "differs");
    // Rates: 0.98 published (100 samples) against 10/10 is consistent; 0/10 differs.
    let p = published_value("0.98", None);
    assert_eq!(
        judge(Kind::Rate, &p, Observed::rate(10, 10).as_ref(), false).name(),
        "consistent"
    );
    assert_eq!(
        judge(Kind::Rate, &p, Observed::rate(0, 10).as_ref(), false).name(),
        "differs"
    );
    // Extremes: equal is consistent, unequal differs.
    let p = published_value("64", None);
    assert_eq!(
        judge(Kind::Extreme, &p, Some(&Observed::value(64, 3)), false).name(),
        "consistent"
    );
    assert_eq!(
        judge(Kind::Extreme, &p, Some(&Observed::value(66, 3)), false).name(),
        "differs"
    );
    // Times: the machine ratio, never exact even in an exact-comparable row.
    let t = Observed::times(&[0.001, 0.003]).unwrap();
    match judge(Kind::Time, &published_value("0.004", None), Some(&t), true) {
        Verdict::Machine { ratio, .. } => assert!((ratio.unwrap() - 0.5).abs() < 1e-12),
        v => panic!("{v:?}"),
    }
    // No value on our side differs.
    assert_eq!(judge(Kind::Mean, &p, None, false).name(), "differs");
}

// ---- the command ------------------------------------------------------------------------------

const P16: [&str; 9] = [
    "reproduce",
    "deterministic",
    "--problems",
    "16",
    "--samples",
    "2",
    "--mode",
    "reference",
    "--quiet",
];

fn with<'a>(base: &[&'a str], more: &[&'a str]) -> Vec<&'a str> {
    base.iter().chain(more).copied().collect()
}

#[test]
fn deterministic_json_rows_gain_published_and_agreement_and_the_summary_adds_up() {
    let v = json(&with(&P16, &["--against-published", "--format", "json"]));
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 11);
    let summary = &v["against_published"];
    let (mut exact, mut consistent, mut differs, mut machine, mut compared) = (0, 0, 0, 0, 0);
    for row in rows {
        let published = row["published"].as_object().unwrap();
        let agreement = row["agreement"].as_object().unwrap();
        assert_eq!(
            published.keys().collect::<Vec<_>>(),
            agreement.keys().collect::<Vec<_>>()
        );
        assert!(row["mean_ns_per_action"].as_f64().unwrap() > 0.0);
        let alg = row["algorithm"].as_str().unwrap();
        let deterministic = alg.starts_with("model-free") || row["epsilon"] == 0.0;
        for (metric, verdict) in agreement {
            compared += 1;
            let name = verdict["verdict"].as_str().unwrap();
            match name {
                "exact" => exact += 1,
                "consistent" => consistent += 1,
                "differs" => differs += 1,
                "machine" => machine += 1,
                other => panic!("{other}"),
            }
            if metric.ends_with("_s") {
                assert_eq!(name, "machine", "{alg} {metric}");
            } else if deterministic {
                // Reference mode, the paper's run length: every published count is exact.
                assert_eq!(name, "exact", "{alg} {metric}");
            }
        }
        if deterministic {
            // Problem 16 (published): Dijkstra 6 pops and 28 actions; greedy Q-learning
            // converges in episode 244 after 1000 actions.
            match alg {
                "model-free-dijkstra" => assert_eq!(published["mean_actions"], 28.0),
                "q-learning" => assert_eq!(published["mean_iterations"], 244.0),
                _ => {}
            }
        }
        // Run times carry the ratio to the published time and, relative to Dijkstra, both.
        let time = &agreement["mean_time_s"];
        assert!(time["ratio"].as_f64().unwrap() > 0.0);
        assert!(time["relative_published"].as_f64().unwrap() > 0.0);
        assert!(time["relative_ours"].as_f64().unwrap() > 0.0);
    }
    assert_eq!(summary["compared"], compared);
    assert_eq!(summary["exact"], exact);
    assert_eq!(summary["consistent"], consistent);
    assert_eq!(summary["differs"], differs);
    assert_eq!(summary["machine"], machine);
    assert_eq!(
        summary["differs_lines"].as_array().unwrap().len() as u64,
        differs
    );
    assert!(
        exact >= 3 * 8 + 9,
        "every DP count and the greedy counts: {exact}"
    );
    assert!(!summary["sources"].as_array().unwrap().is_empty());
}

#[test]
fn without_the_flag_the_json_shape_is_unchanged() {
    let v = json(&with(&P16, &["--format", "json"]));
    for row in v.as_array().unwrap() {
        assert!(row.get("published").is_none());
        assert!(row.get("agreement").is_none());
        assert!(row.get("mean_ns_per_action").is_some());
    }
}

#[test]
fn every_text_format_shows_the_published_numbers_and_the_summary() {
    let text = stdout(&with(&P16, &["--against-published"]));
    assert!(text.contains("Against published:"), "{text}");
    assert!(text.contains("Reproduction summary"));
    assert!(text.contains("metrics compared"));
    assert!(text.contains("mean_planner_actions"));
    assert!(text.contains("ns/action"));
    let md = stdout(&with(
        &P16,
        &["--against-published", "--format", "markdown"],
    ));
    assert!(md.contains("| row | metric | published | ours | verdict |"));
    assert!(md.contains("## Reproduction summary"));
    let csv = stdout(&with(&P16, &["--against-published", "--format", "csv"]));
    let header = csv.lines().next().unwrap();
    assert!(header.contains("published_mean_actions,agreement_mean_actions"));
    assert!(header.contains("mean_ns_per_action"));
    let dijkstra = csv
        .lines()
        .find(|l| l.starts_with("16,model-free-dijkstra"))
        .unwrap();
    assert!(dijkstra.contains(",28.0,exact"), "{dijkstra}");
    assert!(csv.lines().last().unwrap().starts_with("# "));
    assert!(csv.contains("# Against published"));
}

#[test]
fn exact_mode_is_compared_but_never_claims_exact() {
    let v = json(&with(
        &[
            "reproduce",
            "deterministic",
            "--problems",
            "16",
            "--samples",
            "1",
            "--quiet",
        ],
        &["--against-published", "--format", "json"],
    ));
    assert_eq!(v["against_published"]["exact"], 0);
    assert!(v["against_published"]["compared"].as_u64().unwrap() > 0);
}

#[test]
fn stochastic_vi_counts_are_exact_under_the_reference_model() {
    let v = json(&[
        "reproduce",
        "stochastic",
        "--problems",
        "10",
        "--gammas",
        "0.999",
        "--rhos",
        "0.99",
        "--epsilons",
        "0.9",
        "--samples",
        "1",
        "--episodes",
        "2",
        "--max-steps",
        "10",
        "--noise",
        "reference",
        "--tolerance",
        "reference",
        "--against-published",
        "--format",
        "json",
        "--quiet",
    ]);
    let rows = v["rows"].as_array().unwrap();
    let row = |alg: &str| rows.iter().find(|r| r["algorithm"] == alg).unwrap();
    for (alg, sweeps, actions) in [
        ("stochastic-async-vi", 58.0, 178292.0),
        ("stochastic-vi", 94.0, 288956.0),
    ] {
        let r = row(alg);
        assert_eq!(r["published"]["mean_iterations"], sweeps);
        assert_eq!(r["published"]["mean_actions"], actions);
        assert_eq!(r["agreement"]["mean_iterations"]["verdict"], "exact");
        assert_eq!(r["agreement"]["mean_actions"]["verdict"], "exact");
        assert_eq!(r["agreement"]["mean_time_s"]["verdict"], "machine");
        assert!(r["mean_ns_per_action"].as_f64().unwrap() > 0.0);
    }
    // The learning row (2 episodes × 10 steps) is compared statistically, never exactly.
    let q = row("q-learning");
    let verdicts: Vec<&Value> = q["agreement"].as_object().unwrap().values().collect();
    assert!(!verdicts.is_empty());
    assert!(verdicts.iter().all(|v| v["verdict"] != "exact"));
    let s = &v["against_published"];
    assert_eq!(
        s["compared"],
        s["exact"].as_u64().unwrap()
            + s["consistent"].as_u64().unwrap()
            + s["differs"].as_u64().unwrap()
            + s["machine"].as_u64().unwrap()
    );
    let text = stdout(&[
        "reproduce",
        "stochastic",
        "--problems",
        "10",
        "--gammas",
        "0.999",
        "--rhos",
        "0.99",
        "--epsilons",
        "0.9",
        "--samples",
        "1",
        "--episodes",
        "2",
        "--max-steps",
        "10",
        "--against-published",
        "--format",
        "markdown",
        "--quiet",
    ]);
    assert!(text.contains("| row | metric | published | ours | verdict |"));
    assert!(text.contains("## Reproduction summary"));
}

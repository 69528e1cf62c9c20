//! `truecost render`: structure, not pixels. Expected counts come from the paper's data and the
//! published facts (Problem 0: 760 moves; Problem 10: 63 optimal moves; Problem 2: 5 discs).

mod common;

use assert_cmd::Command;
use common::cli::fails_one_line;

fn render(args: &[&str], out: &std::path::Path) -> String {
    let mut cmd = Command::cargo_bin("truecost").unwrap();
    cmd.arg("render").args(args).arg("--out").arg(out);
    cmd.assert().success();
    std::fs::read_to_string(out).unwrap_or_default()
}

fn count(svg: &str, class: &str) -> usize {
    svg.matches(&format!("class=\"{class}\"")).count()
}

#[test]
fn one_disc_per_obstacle_and_one_segment_per_move() {
    let dir = tempfile::tempdir().unwrap();
    let svg = render(&["--problem", "2"], &dir.path().join("p2.svg"));
    assert_eq!(count(&svg, "obstacle"), 5);
    let svg = render(&["--problem", "0"], &dir.path().join("p0.svg"));
    assert_eq!(count(&svg, "obstacle"), 0);
    assert_eq!(count(&svg, "move"), 760);
    assert_eq!(count(&svg, "node"), 400);
    assert_eq!(count(&svg, "start"), 1);
    assert_eq!(count(&svg, "goal"), 1);
    assert!(svg.contains("exact model"));
}

#[test]
fn path_polyline_has_the_optimal_number_of_moves() {
    let dir = tempfile::tempdir().unwrap();
    for mode in ["exact", "reference"] {
        let svg = render(
            &["--problem", "10", "--overlay", "path", "--mode", mode],
            &dir.path().join(format!("p10-{mode}.svg")),
        );
        assert_eq!(count(&svg, "path"), 1);
        assert_eq!(path_points(&svg), 64, "{mode}: 63 moves");
        assert!(svg.contains(&format!("{mode} model")));
    }
}

#[test]
fn values_and_policy_overlays_are_present() {
    let dir = tempfile::tempdir().unwrap();
    let svg = render(
        &["--problem", "0", "--overlay", "values"],
        &dir.path().join("v.svg"),
    );
    assert_eq!(count(&svg, "value") + count(&svg, "value-none"), 400);
    assert_eq!(
        count(&svg, "value-none"),
        0,
        "every state of Problem 0 reaches the goal"
    );
    assert!(count(&svg, "colorbar") > 0);
    assert!(svg.contains(">G*<"));
    let svg = render(
        &["--problem", "10", "--overlay", "values"],
        &dir.path().join("v10.svg"),
    );
    assert_eq!(count(&svg, "value"), 339, "x1's component");
    // Every optimal move: Problem 0 is an open 20x20 grid with unit moves to its 4 neighbours,
    // so neighbours' distances to the goal differ by exactly 1 and every one of the
    // 2·20·19 = 760 edges is optimal in one direction: one arrow at the 38 points in the goal's
    // row or column, two tied arrows at the other 361.
    let svg = render(
        &["--problem", "0", "--overlay", "policy"],
        &dir.path().join("p.svg"),
    );
    assert_eq!(count(&svg, "arrowhead"), 760);
    assert_eq!(count(&svg, "policy"), 760);
    assert_eq!(count(&svg, "legend"), 2, "an arrow, and tied arrows");
    assert!(svg.contains("several at one grid point: tied optimal actions"));
    // The reference mode (the paper's code, f64) draws its one policy.
    let svg = render(
        &[
            "--problem",
            "0",
            "--mode",
            "reference",
            "--overlay",
            "policy",
        ],
        &dir.path().join("r.svg"),
    );
    assert_eq!(count(&svg, "policy"), 399, "every state but the goal");
    assert_eq!(count(&svg, "legend"), 0);
}

#[test]
fn a_files_tied_moves_are_drawn() {
    // 0 -> 1 -> 3 and 0 -> 2 -> 3, moves costing 1 but 0 -> 2 costing `second`: with 1,
    // G* = 2, 1, 1, 0 and both moves of state 0 are optimal; with 2 only 0 -> 1 is. 1 and 2
    // have one move each.
    let dir = tempfile::tempdir().unwrap();
    let policy_of = |second: &str| {
        let file = dir.path().join(format!("tie{second}.json"));
        let text = r#"{"initial":0,"goals":[3],"actions":[[{"to":1,"cost":"1"},{"to":2,"cost":"C"}],[{"to":3,"cost":"1"}],[{"to":3,"cost":"1"}],[]]}"#;
        std::fs::write(&file, text.replace('C', second)).unwrap();
        render(
            &["--file", file.to_str().unwrap(), "--overlay", "policy"],
            &dir.path().join(format!("t{second}.svg")),
        )
    };
    let svg = policy_of("1");
    assert_eq!(count(&svg, "policy"), 4);
    assert!(svg.contains("several at one state: tied optimal actions"));
    assert!(svg.contains("every optimal move (exact; several arrows: tied moves)"));
    // No tie: no tie legend.
    let svg = policy_of("2");
    assert_eq!(count(&svg, "policy"), 3);
    assert!(!svg.contains("several at one state"));
}

#[test]
fn png_decodes_with_the_requested_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p.png");
    render(
        &[
            "--problem",
            "1",
            "--overlay",
            "path",
            "--width",
            "640",
            "--height",
            "480",
        ],
        &out,
    );
    let decoder = png::Decoder::new(std::fs::File::open(&out).unwrap());
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    assert_eq!((info.width, info.height), (640, 480));
}

#[test]
fn files_render_too() {
    let dir = tempfile::tempdir().unwrap();
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/problems/line.json");
    let svg = render(
        &["--file", file, "--overlay", "path"],
        &dir.path().join("f.svg"),
    );
    assert_eq!(count(&svg, "node"), 4);
    assert_eq!(count(&svg, "move"), 4); // {0,1}, {0,3}, {1,2}, {2,3}
    assert_eq!(path_points(&svg), 4);
}

#[test]
fn bad_outputs_and_sizes_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "--problem".into(),
                "0".into(),
                "--out".into(),
                dir.path().join("x.jpg").display().to_string(),
            ],
            ".svg or .png",
        ),
        (
            vec![
                "--problem".into(),
                "0".into(),
                "--out".into(),
                "/nonexistent-dir/x.png".into(),
            ],
            "cannot write",
        ),
        (
            vec![
                "--problem".into(),
                "0".into(),
                "--out".into(),
                "/nonexistent-dir/x.svg".into(),
            ],
            "cannot write",
        ),
        (
            vec![
                "--problem".into(),
                "0".into(),
                "--width".into(),
                "10".into(),
                "--out".into(),
                dir.path().join("s.svg").display().to_string(),
            ],
            "out of range",
        ),
        (
            vec![
                "--problem".into(),
                "6".into(),
                "--overlay".into(),
                "path".into(),
                "--out".into(),
                dir.path().join("u.svg").display().to_string(),
            ],
            "no goal is reachable",
        ),
        (
            vec![
                "--problem".into(),
                "25".into(),
                "--out".into(),
                dir.path().join("u.svg").display().to_string(),
            ],
            "unknown problem",
        ),
    ];
    for (args, expect) in cases {
        assert_refused(&args, expect);
    }
}

/// `render ARGS` exits with 1 and one line on stderr that contains `expect`.
fn assert_refused<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S], expect: &str) {
    let mut all: Vec<std::ffi::OsString> = vec!["render".into()];
    all.extend(args.iter().map(|a| a.as_ref().to_owned()));
    let err = fails_one_line(&all);
    assert!(err.contains(expect), "{args:?}: {err}");
}

#[test]
fn visits_overlay_counts_moves_of_a_seeded_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.svg");
    let args = [
        "--problem",
        "0",
        "--overlay",
        "visits",
        "--seed",
        "3",
        "--epsilon",
        "1",
    ];
    let svg = render(&args, &out);
    let visited = count(&svg, "visits");
    // ε = 1 explores until every state is optimal, so it applies moves all over the grid:
    // Problem 0 has 760 moves and a run that converged must have tried many of them.
    assert!(visited > 100 && visited <= 760, "{visited}");
    assert!(svg.contains("seed 3"));
    assert!(count(&svg, "colorbar") > 0);
    // Same seed, same figure; another seed, another figure.
    let again = render(&args, &dir.path().join("v2.svg"));
    assert_eq!(svg, again);
    let other = render(
        &[
            "--problem",
            "0",
            "--overlay",
            "visits",
            "--seed",
            "4",
            "--epsilon",
            "1",
        ],
        &dir.path().join("v3.svg"),
    );
    assert_ne!(svg, other);
}

#[test]
fn reproduce_writes_the_plots() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("plots");
    Command::cargo_bin("truecost")
        .unwrap()
        .args([
            "reproduce",
            "deterministic",
            "--problems",
            "0,3",
            "--samples",
            "1",
            "--episodes",
            "30",
            "--max-steps",
            "300",
            "--quiet",
            "--seed",
            "5",
            "--format",
            "json",
            "--plots",
        ])
        .arg(&plots)
        .assert()
        .success();
    for stem in ["goal_discovery_vs_epsilon", "convergence_rate_vs_epsilon"] {
        let svg = std::fs::read_to_string(plots.join(format!("{stem}.svg"))).unwrap();
        // Problem 0 (17 moves) is easy and Problem 3 (90 moves) hard: one series each.
        assert_eq!(count(&svg, "series"), 2, "{stem}");
        assert!(
            svg.contains("easy (0)") && svg.contains("hard (3)"),
            "{stem}"
        );
        assert!(svg.contains("seed 5"), "{stem}");
        assert!(svg.contains("exact"), "{stem}: names the model");
        let png =
            png::Decoder::new(std::fs::File::open(plots.join(format!("{stem}.png"))).unwrap());
        assert_eq!(png.read_info().unwrap().info().width, 1000);
    }
}

/// The polyline's points in a rendered SVG.
fn path_points(svg: &str) -> usize {
    let line = svg.lines().find(|l| l.contains("class=\"path\"")).unwrap();
    line.split("points=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .split(' ')
        .count()
}

#[test]
fn gamma_draws_the_stochastic_optimum() {
    let dir = tempfile::tempdir().unwrap();
    // γ = 1 is the deterministic model: the intended path is an optimal one, 63 moves on
    // Problem 10 (published).
    let svg = render(
        &["--problem", "10", "--gamma", "1", "--overlay", "path"],
        &dir.path().join("g1.svg"),
    );
    assert_eq!(path_points(&svg), 64);
    assert!(svg.contains("stochastic model, paper noise, γ = 1"));
    // Under noise every state of Problem 0 (no obstacles) still reaches the goal.
    let svg = render(
        &["--problem", "0", "--gamma", "0.9", "--overlay", "values"],
        &dir.path().join("v.svg"),
    );
    assert_eq!(count(&svg, "value"), 400);
    assert!(count(&svg, "colorbar") > 0);
    assert!(svg.contains("γ = 0.9"));
    let svg = render(
        &[
            "--problem",
            "0",
            "--gamma",
            "0.5",
            "--noise",
            "reference",
            "--overlay",
            "policy",
        ],
        &dir.path().join("p.svg"),
    );
    // Every state but the goal has an optimal action; tied ones add arrows.
    assert!(count(&svg, "policy") >= 399, "{}", count(&svg, "policy"));
    assert_eq!(count(&svg, "policy"), count(&svg, "arrowhead"));
    assert!(svg.contains("every optimal action"));
    assert!(svg.contains("reference noise, γ = 0.5"));
    // The noise makes expected costs larger than the deterministic 17 of Problem 0.
    let g: f64 = svg
        .split("G*(x1) = ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(g > 17.0, "{g}");
}

#[test]
fn stochastic_files_render_with_their_own_outcomes() {
    let dir = tempfile::tempdir().unwrap();
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/problems/slippery.json");
    let svg = render(
        &["--file", file, "--overlay", "path"],
        &dir.path().join("s.svg"),
    );
    assert_eq!(count(&svg, "node"), 3);
    // 0 -> 1 (most likely outcome of its only action), 1 -> 2 (the cheaper action in
    // expectation: 1 + G(0)/4 against 1/2 + G(0)).
    assert_eq!(path_points(&svg), 3);
    // G*(0) = 76/27 (computed by hand in the file's name).
    assert!(svg.contains("G*(x1) = 2.81481481481"), "{svg}");
}

#[test]
fn bad_stochastic_render_arguments_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.svg").display().to_string();
    let slippery = concat!(env!("CARGO_MANIFEST_DIR"), "/problems/slippery.json");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["--problem", "0", "--noise", "paper"],
            "give --gamma too",
        ),
        (vec!["--problem", "0", "--gamma", "1.5"], "(0, 1]"),
        (vec!["--problem", "0", "--gamma", "0"], "(0, 1]"),
        (vec!["--problem", "0", "--gamma", "x"], "gamma"),
        (
            vec!["--problem", "0", "--gamma", "0.9", "--mode", "reference"],
            "--mode exact",
        ),
        (
            vec!["--problem", "0", "--gamma", "0.9", "--overlay", "visits"],
            "--overlay visits",
        ),
        (
            vec!["--problem", "6", "--gamma", "0.9", "--overlay", "path"],
            "no policy reaches a goal",
        ),
        (
            vec!["--file", slippery, "--gamma", "0.9"],
            "its own outcome",
        ),
    ];
    for (mut args, expect) in cases {
        args.extend(["--out", &out]);
        assert_refused(&args, expect);
    }
}

#[test]
fn reproduce_stochastic_writes_the_plots() {
    let dir = tempfile::tempdir().unwrap();
    let plots = dir.path().join("plots");
    Command::cargo_bin("truecost")
        .unwrap()
        .args([
            "reproduce",
            "stochastic",
            "--problems",
            "0",
            "--gammas",
            "0.9,0.5",
            "--rhos",
            "0.99,0.5,1/n^0.8",
            "--epsilons",
            "0.9",
            "--samples",
            "1",
            "--episodes",
            "20",
            "--max-steps",
            "100",
            "--quiet",
            "--seed",
            "7",
            "--format",
            "json",
            "--plots",
        ])
        .arg(&plots)
        .assert()
        .success();
    for (stem, ticks) in [
        ("run_time_vs_rho", &["0.99", "0.5", "1/n^0.8"][..]),
        ("convergence_rate_vs_rho", &["0.99", "0.5", "1/n^0.8"][..]),
        ("convergence_rate_vs_epsilon", &["0.9"][..]),
    ] {
        let svg = std::fs::read_to_string(plots.join(format!("{stem}.svg"))).unwrap();
        // One series per γ, one marker per (γ, category).
        assert_eq!(count(&svg, "series"), 2, "{stem}");
        assert_eq!(count(&svg, "marker"), 2 * ticks.len(), "{stem}");
        assert!(svg.contains("γ = 0.9") && svg.contains("γ = 0.5"), "{stem}");
        for t in ticks {
            assert!(svg.contains(&format!(">{t}<")), "{stem}: tick {t}");
        }
        assert!(svg.contains("seed 7"), "{stem}");
        assert!(svg.contains("noise paper"), "{stem}: names the model");
        let png =
            png::Decoder::new(std::fs::File::open(plots.join(format!("{stem}.png"))).unwrap());
        assert_eq!(png.read_info().unwrap().info().width, 1000);
    }
}

/// Three cells in a row: at 0 one move east and one push north into the border, at 1 two
/// tied moves (west and east), 2 the goal. Every glyph is found where the state is, and the
/// legend lines are drawn with their text under the map.
#[test]
fn optimal_actions_overlay_draws_ties_bars_and_the_legend() {
    use truecost::figures::canvas::Shape;
    use truecost::figures::render::{draw, ActionGlyph::*, LegendEntry, LegendKey, Overlay, Scene};
    let scene = Scene {
        title: "row".into(),
        caption: "three cells".into(),
        positions: vec![(5.0, 5.0), (15.0, 5.0), (25.0, 5.0)],
        extent: (30.0, 10.0),
        obstacles: vec![],
        moves: vec![(0, 1), (1, 2)],
        initial: Some(0),
        goals: vec![2],
        walls: vec![],
        marks: vec![],
    };
    let legend = vec![
        LegendEntry {
            key: LegendKey::Arrow,
            text: "arrow: one action".into(),
        },
        LegendEntry {
            key: LegendKey::Tie,
            text: "several: tied".into(),
        },
        LegendEntry {
            key: LegendKey::Blocked,
            text: "bar: into the border".into(),
        },
    ];
    let overlay = Overlay::Actions {
        actions: vec![
            vec![Move(1), Blocked { toward: (0, 1) }],
            vec![Move(0), Move(2)],
            vec![],
        ],
        legend: legend.clone(),
    };
    let canvas = draw(&scene, &overlay, 600, 400).unwrap();
    let nodes: Vec<(f64, f64)> = canvas
        .of_class("node")
        .map(|s| match s {
            Shape::Circle { c, .. } => *c,
            _ => panic!("a node is a circle"),
        })
        .collect();
    let lines = |class: &'static str| -> Vec<((f64, f64), (f64, f64))> {
        canvas
            .of_class(class)
            .map(|s| match s {
                Shape::Line { a, b, .. } => (*a, *b),
                _ => panic!("{class} is a line"),
            })
            .collect()
    };
    // Three arrows: 0 east, 1 west and 1 east (the tie), each from its state's node.
    let shafts = lines("policy");
    assert_eq!(shafts.len(), 3);
    assert_eq!(canvas.of_class("arrowhead").count(), 3);
    let from = |x: usize| shafts.iter().filter(|(a, _)| *a == nodes[x]).count();
    assert_eq!((from(0), from(1), from(2)), (1, 2, 0));
    let at_one: Vec<f64> = shafts
        .iter()
        .filter(|(a, _)| *a == nodes[1])
        .map(|(a, b)| b.0 - a.0)
        .collect();
    assert!(at_one.iter().any(|&d| d < 0.0) && at_one.iter().any(|&d| d > 0.0));
    // The bar: from node 0 straight up (pixel y grows downwards), stopping inside the cell
    // (less than half the distance to the next state), the bar across it.
    let spacing = nodes[1].0 - nodes[0].0;
    let stroke = lines("blocked");
    assert_eq!(stroke.len(), 1);
    let (a, b) = stroke[0];
    assert_eq!(a, nodes[0]);
    assert!((b.0 - a.0).abs() < 1e-9 && b.1 < a.1);
    assert!(a.1 - b.1 < spacing / 2.0, "{} {}", a.1 - b.1, spacing);
    let bar = lines("blocked-bar");
    assert_eq!(bar.len(), 1);
    let (p, q) = bar[0];
    assert!(
        (p.1 - b.1).abs() < 1e-9 && (q.1 - b.1).abs() < 1e-9,
        "horizontal, at the end"
    );
    assert!(((p.0 + q.0) / 2.0 - b.0).abs() < 1e-9 && p.0 != q.0);
    // The legend: one text per entry, in order, under the map and above the caption.
    let texts: Vec<(String, f64)> = canvas
        .of_class("legend")
        .map(|s| match s {
            Shape::Text { text, at, .. } => (text.clone(), at.1),
            _ => panic!("a legend line is text"),
        })
        .collect();
    assert_eq!(
        texts.iter().map(|(t, _)| t.as_str()).collect::<Vec<_>>(),
        vec!["arrow: one action", "several: tied", "bar: into the border"]
    );
    let map_bottom = nodes[0].1 + spacing / 2.0;
    let caption_top = canvas
        .of_class("caption")
        .map(|s| match s {
            Shape::Text { at, .. } => at.1,
            _ => panic!(),
        })
        .fold(f64::INFINITY, f64::min);
    for (k, (_, y)) in texts.iter().enumerate() {
        assert!(*y > map_bottom && *y < caption_top - 10.0, "{k}: {y}");
    }
    assert!(texts.windows(2).all(|w| w[0].1 < w[1].1));
    // The keys: an arrow (shaft and head), two arrows, a stroke and a bar — as drawn.
    assert_eq!(canvas.of_class("legend-key").count(), 2 + 4 + 2);
    let svg = canvas.to_svg();
    for entry in &legend {
        assert!(svg.contains(&format!(">{}<", entry.text)), "{}", entry.text);
    }
    assert_eq!(count(&svg, "legend"), 3);
    // The single-successor overlay has no legend.
    let plain = draw(
        &scene,
        &Overlay::Policy(vec![Some(1), Some(2), Some(2)]),
        600,
        400,
    )
    .unwrap();
    assert_eq!(plain.of_class("legend").count(), 0);
    assert_eq!(plain.of_class("policy").count(), 2);
}

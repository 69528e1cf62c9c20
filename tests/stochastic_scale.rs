//! Large stochastic models: the seeded benchmark grids, the fast exact
//! optimum against an exhaustive brute-force oracle and an independent exact Bellman check (so
//! the speed-up cannot silently change a number), `--max-memory`, the progress bar's silence
//! off a terminal, and f64 VI computing the exact `G*` only with `--exact-error`. Expected
//! values come from the oracles here or from the specification, never from the code under test.

mod common;

use num_traits::{One, Zero};

use common::cli::{fails, json, truecost};
use truecost::model::Problem;
use truecost::stochastic::benchmark::{cost_grid, parse_size as parse_grid};
use truecost::stochastic::policy_iteration::{
    memory_estimate, optimum, optimum_with, problem_bytes, Progress,
};
use truecost::stochastic::scale::parse_size;
use truecost::stochastic::{NoiseModel, Predictability, StochasticProblem};
use truecost::value::{Extended, Rational};

fn noisy(p: &Problem, noise: NoiseModel, gamma: &str) -> StochasticProblem {
    StochasticProblem::from_deterministic(p, noise, &Predictability::parse(gamma).unwrap()).unwrap()
}

fn int(n: i64) -> Rational {
    Rational::from_integer(n.into())
}

// ---------------------------------------------------------------------------------------------
// The benchmark grid generator.

#[test]
fn benchmark_grid_is_a_seeded_four_neighbour_grid_with_costs_one_to_four() {
    let (rows, cols) = (6, 9);
    let p = cost_grid(rows, cols, 11).unwrap();
    assert_eq!(p.states(), 54);
    assert_eq!((p.initial(), p.goals()), (0, &[53][..]));
    let mut seen = [false; 5];
    for x in 0..p.states() {
        let (r, c) = (x / cols, x % cols);
        // Up, left, right, down: only those inside the grid.
        let mut expected = Vec::new();
        if r > 0 {
            expected.push(x - cols);
        }
        if c > 0 {
            expected.push(x - 1);
        }
        if c + 1 < cols {
            expected.push(x + 1);
        }
        if r + 1 < rows {
            expected.push(x + cols);
        }
        let got: Vec<usize> = p.moves(x).iter().map(|m| m.successor).collect();
        assert_eq!(got, expected, "state {x}");
        for m in p.moves(x) {
            let k = (1..=4)
                .find(|&k| m.cost == int(k))
                .expect("a cost in 1..=4");
            seen[k as usize] = true;
        }
    }
    assert_eq!(
        seen,
        [false, true, true, true, true],
        "every cost 1–4 occurs"
    );
    // Deterministic from the seed; another seed gives other costs.
    assert_eq!(cost_grid(rows, cols, 11).unwrap(), p);
    assert_ne!(cost_grid(rows, cols, 12).unwrap(), p);
    assert_eq!(parse_grid("100x100").unwrap(), (100, 100));
    assert_eq!(parse_grid("3X7").unwrap(), (3, 7));
    for bad in ["0x4", "1x1", "1001x2", "ax3", "", "4x"] {
        assert!(parse_grid(bad).is_err(), "{bad}");
    }
}

/// The benchmark grid's size limits: sides `1..=MAX_SIDE` and at least two states, both in the
/// generator and in the `ROWSxCOLS` parser (`rows · cols < 2`, not `rows + cols < 2`).
#[test]
fn benchmark_grid_sizes_at_the_edges() {
    use truecost::stochastic::benchmark::MAX_SIDE;
    for (rows, cols) in [(1, 1), (0, 5), (5, 0), (MAX_SIDE + 1, 1), (1, MAX_SIDE + 1)] {
        assert!(cost_grid(rows, cols, 0).is_err(), "{rows}x{cols}");
        assert!(
            parse_grid(&format!("{rows}x{cols}")).is_err(),
            "{rows}x{cols}"
        );
    }
    for (rows, cols) in [(1, 2), (2, 1), (1, MAX_SIDE), (3, 3)] {
        let p = cost_grid(rows, cols, 0).unwrap();
        assert_eq!(p.states(), rows * cols);
        assert_eq!(parse_grid(&format!("{rows}x{cols}")).unwrap(), (rows, cols));
    }
    assert!(parse_grid("1").is_err());
    assert_eq!(parse_grid("2").unwrap(), (2, 2));
}

#[test]
fn export_grid_writes_the_generator_s_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("grid.json");
    let path = out.display().to_string();
    let args = ["export", "--grid", "4x6", "--seed", "3", "--out", &path];
    truecost().args(args).assert().success();
    let text = std::fs::read_to_string(&out).unwrap();
    let read = truecost::model::file::from_json(&text).unwrap();
    assert_eq!(read, cost_grid(4, 6, 3).unwrap());
    // The same command writes the same bytes.
    truecost().args(args).assert().success();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), text);
    let err = fails(&["export", "--grid", "0x6", "--out", &path], 1);
    assert!(err.contains("grid size"), "{err}");
    fails(&["export", "--seed", "3", "--out", &path], 2);
}

// ---------------------------------------------------------------------------------------------
// The exact optimum against oracles.

/// Dense exact Gauss–Jordan elimination (the oracle's own solver).
fn solve_dense(mut a: Vec<Vec<Rational>>, mut b: Vec<Rational>) -> Vec<Rational> {
    let n = b.len();
    for k in 0..n {
        let pivot = (k..n).find(|&i| !a[i][k].is_zero()).expect("non-singular");
        a.swap(k, pivot);
        b.swap(k, pivot);
        for i in 0..n {
            if i != k && !a[i][k].is_zero() {
                let f = &a[i][k] / &a[k][k];
                let row = a[k].clone();
                for (aij, akj) in a[i].iter_mut().zip(&row).skip(k) {
                    *aij -= &f * akj;
                }
                let t = &f * &b[k];
                b[i] -= t;
            }
        }
    }
    (0..n).map(|i| &b[i] / &a[i][i]).collect()
}

/// `G_π` of a policy on a noisy grid (every policy is proper there: noise reaches every
/// neighbour of a connected grid), goals 0.
fn oracle_evaluate(s: &StochasticProblem, policy: &[usize]) -> Vec<Rational> {
    let unknowns: Vec<usize> = (0..s.states()).filter(|&x| !s.is_goal(x)).collect();
    let pos = |x: usize| unknowns.iter().position(|&u| u == x);
    let m = unknowns.len();
    let mut a = vec![vec![Rational::zero(); m]; m];
    let mut b = vec![Rational::zero(); m];
    for (i, &x) in unknowns.iter().enumerate() {
        let act = policy[x];
        a[i][i] += Rational::one();
        b[i] = s.cost(act).clone();
        for o in s.outcomes(act) {
            if let Some(j) = pos(o.successor) {
                a[i][j] -= &o.probability;
            }
        }
    }
    let z = solve_dense(a, b);
    (0..s.states())
        .map(|x| pos(x).map_or(Rational::zero(), |i| z[i].clone()))
        .collect()
}

fn q_value(s: &StochasticProblem, g: &[Rational], a: usize) -> Rational {
    let mut q = s.cost(a).clone();
    for o in s.outcomes(a) {
        q += &o.probability * &g[o.successor];
    }
    q
}

fn finite(v: &Extended) -> Rational {
    v.finite().cloned().expect("finite on a connected grid")
}

/// Exhaustive brute force over every stationary policy: `G*(x) = min_π G_π(x)`, the optimal
/// actions and the reported policy, on small grids, both noise models, several γ and seeds.
#[test]
fn exact_optimum_equals_exhaustive_brute_force_on_small_grids() {
    let cases = [
        (3, 3, 0, NoiseModel::Paper, "0.9"),
        (3, 3, 1, NoiseModel::Paper, "0.5"),
        (3, 3, 2, NoiseModel::Reference, "0.99"),
        (2, 4, 3, NoiseModel::Paper, "0.7"),
        (2, 4, 4, NoiseModel::Reference, "0.6"),
    ];
    for (rows, cols, seed, noise, gamma) in cases {
        let s = noisy(&cost_grid(rows, cols, seed).unwrap(), noise, gamma);
        let n = s.states();
        // Every policy: each non-goal state picks one of its actions.
        let mut policies: Vec<Vec<usize>> = vec![vec![usize::MAX; n]];
        for x in (0..n).filter(|&x| !s.is_goal(x)) {
            policies = policies
                .into_iter()
                .flat_map(|p| {
                    s.actions(x).map(move |a| {
                        let mut p = p.clone();
                        p[x] = a;
                        p
                    })
                })
                .collect();
        }
        let values: Vec<Vec<Rational>> = policies.iter().map(|p| oracle_evaluate(&s, p)).collect();
        let best: Vec<Rational> = (0..n)
            .map(|x| values.iter().map(|v| v[x].clone()).min().unwrap())
            .collect();
        // Some policy attains the minimum everywhere at once (an SSP has a uniformly optimal one).
        assert!(values.contains(&best), "{rows}x{cols} seed {seed}");
        let o = optimum(&s).unwrap();
        for x in 0..n {
            assert_eq!(
                finite(&o.cost_to_go(x)),
                best[x],
                "G*({x}), {rows}x{cols} seed {seed}"
            );
            for a in s.actions(x).filter(|_| !s.is_goal(x)) {
                assert_eq!(
                    o.is_optimal_action(&s, a),
                    q_value(&s, &best, a) == best[x],
                    "action {a} at {x}, {rows}x{cols} seed {seed}"
                );
            }
        }
        let reported: Vec<usize> = (0..n)
            .map(|x| match o.policy()[x] {
                Some(truecost::model::Decision::Move(i)) => s.actions(x).start + i,
                _ => usize::MAX,
            })
            .collect();
        let mut fixed = reported.clone();
        for x in (0..n).filter(|&x| s.is_goal(x)) {
            fixed[x] = usize::MAX;
        }
        assert!(policies.contains(&fixed), "the reported policy is a policy");
        assert_eq!(
            oracle_evaluate(&s, &fixed),
            best,
            "the reported policy is optimal"
        );
    }
}

/// On grids too large for brute force, an independent certificate in plain big-rational
/// arithmetic: `G*` satisfies the Bellman equation exactly at every state, and the reported
/// policy's own cost (dense oracle solve) is `G*`. With costs ≥ 1 every solution of the
/// Bellman equation on a connected noisy grid is the optimum.
#[test]
fn exact_optimum_satisfies_the_bellman_equation_on_mid_size_grids() {
    for (side, seed, noise, gamma) in [
        (7, 5, NoiseModel::Paper, "0.99"),
        (8, 6, NoiseModel::Reference, "0.9"),
        (12, 7, NoiseModel::Paper, "0.99"),
    ] {
        let s = noisy(&cost_grid(side, side, seed).unwrap(), noise, gamma);
        let o = optimum(&s).unwrap();
        let g: Vec<Rational> = o.cost_to_go_all().iter().map(finite).collect();
        for x in (0..s.states()).filter(|&x| !s.is_goal(x)) {
            let best = s.actions(x).map(|a| q_value(&s, &g, a)).min().unwrap();
            assert_eq!(best, g[x], "Bellman at {x}, {side}x{side} seed {seed}");
        }
        assert!(g.iter().all(|v| *v >= Rational::zero()));
        if side <= 8 {
            let policy: Vec<usize> = (0..s.states())
                .map(|x| match o.policy()[x] {
                    Some(truecost::model::Decision::Move(i)) => s.actions(x).start + i,
                    _ => usize::MAX,
                })
                .collect();
            assert_eq!(oracle_evaluate(&s, &policy), g, "{side}x{side}");
        }
    }
}

/// The warm start leaves one exact evaluation on the benchmark grids (one or two exact
/// evaluations, not 23), and the progress events count what the statistics report.
#[test]
fn warm_start_leaves_one_exact_evaluation_and_progress_reports_it() {
    let s = noisy(&cost_grid(20, 20, 0).unwrap(), NoiseModel::Paper, "0.99");
    let (mut exact, mut float, mut last_lift) = (0, 0, 0);
    let mut refinements: Vec<(usize, u64)> = Vec::new();
    let o = optimum_with(&s, &mut |e| match e {
        Progress::Refinement { policy, bits } => {
            // Policies count up from 1; within a policy the precision only grows.
            if let Some(&(p, b)) = refinements.last() {
                assert!(
                    policy == p + 1 || (policy == p && bits > b),
                    "{p}/{b} then {policy}/{bits}"
                );
            } else {
                assert_eq!(policy, 1);
            }
            assert!(exact == 0, "refinement comes before the exact stage");
            refinements.push((policy, bits));
        }
        // Evaluations and rounds are numbered from 1, in order.
        Progress::ExactEvaluation { evaluation } => {
            exact += 1;
            assert_eq!(evaluation, exact);
        }
        Progress::FloatEvaluation { round } => {
            float += 1;
            assert_eq!(round, float);
        }
        Progress::Lifting(l) => {
            assert!(l.steps == last_lift + 1 || l.steps == 1, "steps count up");
            last_lift = l.steps;
        }
    })
    .unwrap();
    assert!(o.stats.exact_iterations <= 2, "{:?}", o.stats);
    assert_eq!(exact, o.stats.exact_iterations);
    assert!(
        float > o.stats.float_iterations,
        "one more f64 evaluation than switches"
    );
    assert!(last_lift > 0 && o.stats.lifting_steps >= last_lift);
    // One refinement policy more than certified rounds, ending at the reported precision.
    assert_eq!(
        refinements.last().copied(),
        Some((o.stats.refinement_rounds + 1, o.stats.refinement_bits)),
        "{:?}",
        o.stats
    );
    // The same numbers with or without a progress callback.
    assert_eq!(optimum(&s).unwrap().cost_to_go_all(), o.cost_to_go_all());
}

// ---------------------------------------------------------------------------------------------
// --max-memory.

#[test]
fn memory_sizes_parse_exactly() {
    assert_eq!(parse_size("4G").unwrap(), 4 * 1024 * 1024 * 1024);
    assert_eq!(parse_size("512M").unwrap(), 512 * 1024 * 1024);
    assert_eq!(parse_size("512mib").unwrap(), 512 * 1024 * 1024);
    assert_eq!(parse_size("1.5G").unwrap(), 1536 * 1024 * 1024);
    assert_eq!(parse_size("1024K").unwrap(), 1024 * 1024);
    assert_eq!(parse_size("2T").unwrap(), 2 * 1024u64.pow(4));
    assert_eq!(parse_size("3000000").unwrap(), 3_000_000);
    // A fraction longer than the integer part.
    assert_eq!(parse_size("0.25G").unwrap(), 1 << 28);
    assert_eq!(parse_size("1.125G").unwrap(), 9 << 27);
    // At most 30 digits in all: 7 + 23 are read, 1 + 30 are refused (even where the value,
    // here exactly 1 MiB, would be fine).
    assert_eq!(
        parse_size("1048576.00000000000000000000000").unwrap(),
        1 << 20
    );
    assert!(parse_size("1.000000000000000000000000000000M").is_err());
    for bad in [
        "",
        "G",
        "0",
        "1023K",
        "-1G",
        "1e9",
        "1.2.3G",
        "4X",
        "4 G B",
        "1.",
        ".5G",
        "99999999999T",
        // More than 30 digits are refused before any arithmetic, even when the value is fine.
        "1048576.000000000000000000000000",
        "0.000000000000000000000000000001T",
    ] {
        assert!(parse_size(bad).is_err(), "{bad:?}");
    }
}

#[test]
fn memory_estimate_grows_with_the_grid_and_with_json() {
    let small = noisy(&cost_grid(10, 10, 0).unwrap(), NoiseModel::Paper, "0.99");
    let large = noisy(&cost_grid(20, 20, 0).unwrap(), NoiseModel::Paper, "0.99");
    let (a, b) = (
        memory_estimate(&small, false),
        memory_estimate(&large, false),
    );
    assert_eq!((a.unknowns, b.unknowns), (99, 399));
    assert!(b.bytes > a.bytes);
    assert!(memory_estimate(&large, true).bytes > b.bytes);
    // The lifting estimate is an upper estimate of what the solve used.
    let o = optimum(&large).unwrap();
    assert!(
        b.lifting_steps >= o.stats.lifting_steps,
        "{b:?} {:?}",
        o.stats
    );
    // And against what `optimum` then does on smaller grids and other γ: the same unknowns
    // (every non-goal state of a cost grid has an action and a finite `G*`), and the lifting
    // estimate bounds each exact evaluation's steps.
    for (side, seed, gamma) in [(3, 0, "0.9"), (5, 1, "0.99"), (8, 2, "0.999")] {
        let s = noisy(
            &cost_grid(side, side, seed).unwrap(),
            NoiseModel::Paper,
            gamma,
        );
        let e = memory_estimate(&s, false);
        let o = optimum(&s).unwrap();
        assert_eq!(e.unknowns, side * side - 1);
        assert_eq!(o.stats.unknowns, e.unknowns, "{side}");
        assert_eq!(o.stats.finite_states, side * side, "{side}");
        assert!(o.stats.exact_iterations >= 1);
        assert!(
            o.stats.lifting_steps <= e.lifting_steps * o.stats.exact_iterations,
            "{side}: {:?} against {e:?}",
            o.stats
        );
        assert!(memory_estimate(&s, true).bytes > e.bytes);
    }
}

/// The estimate counts the mixed-precision stage too: at least its own peak (its `f64` band LU
/// and fixed-point numbers at the precision cap) on top of what every stage holds, and the
/// stage's cap is above the `log₂|det A|` the `f64` LU measures.
#[test]
fn memory_estimate_includes_the_refinement_stage() {
    for (side, gamma) in [(10, "0.99"), (20, "0.999")] {
        let s = noisy(&cost_grid(side, side, 0).unwrap(), NoiseModel::Paper, gamma);
        let e = memory_estimate(&s, false);
        let u = e.unknowns as u64;
        assert!(e.refinement_bytes >= u * e.band_width as u64 * 8, "{e:?}");
        assert!(
            e.refinement_bytes >= 2 * u * (e.refinement_cap_bits / 8.0) as u64,
            "{e:?}"
        );
        assert!(
            e.bytes >= (16 << 20) + problem_bytes(&s) + e.refinement_bytes,
            "{e:?}"
        );
        // The cap bounds the precision the stage reaches.
        let o = optimum(&s).unwrap();
        assert!(
            (o.stats.refinement_bits as f64) <= e.refinement_cap_bits,
            "{e:?} {:?}",
            o.stats
        );
    }
}

/// `--max-memory` at the estimate runs, one byte below it refuses, naming the estimate.
#[test]
fn max_memory_refuses_one_byte_below_the_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let f = grid_file(&dir, 10);
    let s = noisy(&cost_grid(10, 10, 0).unwrap(), NoiseModel::Paper, "0.99");
    for (format, all_values) in [("text", false), ("json", true)] {
        let bytes = memory_estimate(&s, all_values).bytes;
        let run = |budget: u64| -> Vec<String> {
            exact_solve(
                &f,
                &["--format", format, "--max-memory", &budget.to_string()],
            )
        };
        let err = fails(&run(bytes - 1), 1);
        assert!(err.contains("above the budget --max-memory"), "{err}");
        assert!(err.contains("99 unknowns"), "{err}");
        truecost().args(run(bytes)).assert().success();
    }
}

/// `solve --file FILE --gamma 0.99 --algorithm exact` followed by `extra`.
fn exact_solve(file: &str, extra: &[&str]) -> Vec<String> {
    [
        "solve",
        "--file",
        file,
        "--gamma",
        "0.99",
        "--algorithm",
        "exact",
    ]
    .iter()
    .chain(extra)
    .map(|s| s.to_string())
    .collect()
}

fn grid_file(dir: &tempfile::TempDir, side: usize) -> String {
    let path = dir.path().join(format!("grid{side}.json"));
    let text = truecost::model::file::to_json(&cost_grid(side, side, 0).unwrap(), None);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

#[test]
fn max_memory_refuses_before_any_work_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let f = grid_file(&dir, 10);
    let with = |extra: &[&str]| -> Vec<String> { exact_solve(&f, extra) };
    let err = fails(&with(&["--max-memory", "1M"]), 1);
    assert!(err.contains("estimated"), "{err}");
    assert!(err.contains("above the budget --max-memory 1 MiB"), "{err}");
    assert!(err.contains("99 unknowns"), "{err}");
    for bad in ["0", "12Q", "-1G", "1.2.3G"] {
        let err = fails(&with(&["--max-memory", bad]), 1);
        assert!(err.contains("--max-memory must be a size"), "{bad}: {err}");
    }
    // Within the budget (and the default budget) it runs; nothing on stderr off a terminal.
    for extra in [&["--max-memory", "1G"][..], &[], &["--quiet"]] {
        let out = truecost()
            .args(with(extra))
            .assert()
            .success()
            .get_output()
            .clone();
        assert!(
            out.stderr.is_empty(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8(out.stdout).unwrap().contains("G*(x1)"));
    }
    // A deterministic run refuses the stochastic-only options.
    let err = fails(
        &[
            "solve",
            "--file",
            &f,
            "--algorithm",
            "dijkstra",
            "--max-memory",
            "1G",
        ],
        1,
    );
    assert!(err.contains("apply to the stochastic model"), "{err}");
    let err = fails(&with(&["--exact-error"]), 1);
    assert!(
        err.contains("--exact-error applies to --algorithm vi"),
        "{err}"
    );
}

// ---------------------------------------------------------------------------------------------
// f64 value iteration computes the exact G* only with --exact-error.

#[test]
fn f64_value_iteration_measures_exactly_only_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    let f = grid_file(&dir, 6);
    for algorithm in ["vi", "async-vi"] {
        let args = |extra: &[&'static str]| -> Vec<String> {
            [
                "solve",
                "--file",
                &f,
                "--gamma",
                "0.9",
                "--algorithm",
                algorithm,
                "--format",
                "json",
            ]
            .iter()
            .map(|s| s.to_string())
            .chain(extra.iter().map(|s| s.to_string()))
            .collect()
        };
        let run = |extra: &[&'static str]| {
            let a = args(extra);
            json(&a.iter().map(String::as_str).collect::<Vec<_>>())
        };
        let plain = run(&["--arithmetic", "f64"]);
        assert!(plain["optimum"].is_null(), "{algorithm}: no exact optimum");
        assert!(plain["value_iteration"]["max_error"].is_null());
        assert!(plain["value_iteration"]["error_initial"].is_null());
        assert!(plain["value_iteration"]["suboptimal_policy_states"].is_null());
        assert!(plain["cost_to_go_initial"].is_f64());
        let measured = run(&["--arithmetic", "f64", "--exact-error"]);
        assert!(
            measured["optimum"]["cost_to_go_initial"].is_string(),
            "{algorithm}"
        );
        assert!(measured["value_iteration"]["max_error"].is_string());
        assert!(measured["value_iteration"]["error_initial"].is_string());
        // The f64 run itself is the same either way.
        assert_eq!(plain["cost_to_go"], measured["cost_to_go"]);
        // Its exact optimum is the one `--algorithm exact` reports.
        let exact = json(&[
            "solve",
            "--file",
            &f,
            "--gamma",
            "0.9",
            "--algorithm",
            "exact",
            "--format",
            "json",
        ]);
        assert_eq!(
            measured["optimum"]["cost_to_go_initial"],
            exact["cost_to_go_initial"]
        );
        // Exact arithmetic still measures against G* without the flag.
        let exact_vi = run(&[]);
        assert!(exact_vi["optimum"]["cost_to_go_initial"].is_string());
        // A memory budget too small refuses --exact-error's optimum, not the plain f64 run.
        let a = args(&["--arithmetic", "f64", "--exact-error", "--max-memory", "1M"]);
        let err = fails(&a, 1);
        assert!(err.contains("above the budget"), "{err}");
        let a = args(&["--arithmetic", "f64", "--max-memory", "1M"]);
        truecost().args(a).assert().success();
    }
}

/// `export --grid` writes only what the readers accept: the largest exportable grid's file is
/// below the problem-file limit (worst case of the seeded costs: 4 moves per inner state), and a
/// larger grid is refused before any work, with no file written.
#[test]
fn exported_grids_fit_the_readers_limit() {
    use truecost::model::file::{to_json, MAX_FILE_BYTES};
    use truecost::stochastic::benchmark::{exportable_size, MAX_EXPORT_STATES};
    let (rows, cols) = (MAX_EXPORT_STATES / 1000, 1000);
    assert!(exportable_size(rows, cols).is_ok());
    assert!(exportable_size(rows, cols + 1).is_err());
    let text = to_json(&cost_grid(rows, cols, 0).unwrap(), Some("largest"));
    assert!((text.len() as u64) < MAX_FILE_BYTES, "{} bytes", text.len());
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.json");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_truecost"))
        .args([
            "export",
            "--grid",
            "1000x1000",
            "--out",
            &out.display().to_string(),
        ])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8(o.stderr).unwrap();
    assert!(err.contains("at most 100000 states"), "{err}");
    assert!(!out.exists());
}

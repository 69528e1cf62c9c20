//! `verify --certificates DIR`: one certificate per optimum the report prints — the
//! deterministic `G*` of each counterexample's problem, the discounted optimum of C3's worked
//! example at both ends of `α*`'s bracket; with `--claim C4 --problem N`, the `G*` of that
//! problem — each accepted by `truecost check` run as a process (and by the Coq checker on
//! some), a tampered one rejected, the report's `certificates` entry; a bad `DIR` refused in
//! one line before any work, `--shard` refused.

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};
use serde_json::Value;

use common::cli::{assert_contract, fails, fails_one_line, json, truecost};

/// The smoke run, once for the binary: its directory and its JSON report.
fn smoke_run() -> &'static (PathBuf, Value) {
    static RUN: OnceLock<(PathBuf, Value)> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("verify_certificates");
        if dir.exists() {
            std::fs::remove_dir_all(&dir).unwrap();
        }
        let d = dir.display().to_string();
        let report = json(&[
            "verify",
            "--scope",
            "smoke",
            "--no-coq",
            "--no-smt",
            "--format",
            "json",
            "--certificates",
            &d,
        ]);
        (dir, report)
    })
}

/// The file names of `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn q(text: &str) -> BigRational {
    text.parse().unwrap()
}

/// `G*` of a deterministic problem file's JSON by Bellman-Ford (`None` = +inf), computed here
/// from the file's own numbers.
fn g_star(problem: &Value) -> Vec<Option<BigRational>> {
    let actions = problem["actions"].as_array().unwrap();
    let goals: Vec<usize> = problem["goals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g.as_u64().unwrap() as usize)
        .collect();
    let n = actions.len();
    let mut g: Vec<Option<BigRational>> = (0..n)
        .map(|x| goals.contains(&x).then(BigRational::zero))
        .collect();
    for _ in 0..n {
        for x in (0..n).filter(|x| !goals.contains(x)) {
            for a in actions[x].as_array().unwrap() {
                let to = a["to"].as_u64().unwrap() as usize;
                if let Some(v) = &g[to] {
                    let c = q(a["cost"].as_str().unwrap()) + v;
                    if g[x].as_ref().is_none_or(|old| c < *old) {
                        g[x] = Some(c);
                    }
                }
            }
        }
    }
    g
}

/// `truecost check --file PROBLEM CERT --format json` (plus `extra`), which must accept.
fn accepted(problem: &Path, cert: &Path, extra: &[&str]) -> Value {
    let (p, c) = (problem.display().to_string(), cert.display().to_string());
    let mut args = vec!["check", "--file", &p, &c, "--format", "json"];
    args.extend_from_slice(extra);
    let v = json(&args);
    assert_eq!(v["accepted"], true, "{}: {v}", cert.display());
    v
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The files the smoke run must write, from the report's list of problems: each
/// counterexample's problem file and its certificate, the worked example's problem file and its
/// two certificates. The known refutations (C1 and C4 as printed) are among them.
#[test]
fn smoke_run_writes_one_accepted_certificate_per_optimum_it_prints() {
    let (dir, report) = smoke_run();
    let mut stems: Vec<String> = report["claims"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|c| c["counterexample"]["file"].as_str())
        .map(|f| {
            Path::new(f)
                .file_stem()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    assert!(stems.contains(&"c1-as-printed".to_string()), "{stems:?}");
    assert!(stems.contains(&"c4-as-printed".to_string()), "{stems:?}");
    assert!(report["alpha_star"].is_object(), "the worked example ran");
    let mut expected: Vec<String> = stems
        .iter()
        .flat_map(|s| [format!("{s}.json"), format!("{s}.cert.json")])
        .collect();
    expected.extend([
        "c3-example.json".into(),
        "c3-example-alpha-lo.cert.json".into(),
        "c3-example-alpha-hi.cert.json".into(),
    ]);
    expected.sort();
    assert_eq!(names(dir), expected);

    // The report's entry: the count, the checker, one line per file.
    let c = &report["certificates"];
    let certificates = stems.len() + 2;
    assert_eq!(c["written"], certificates, "{c}");
    assert_eq!(c["accepted"], certificates, "{c}");
    assert_eq!(c["directory"], dir.display().to_string());
    assert!(c["checker"]
        .as_str()
        .unwrap()
        .contains("truecost::certificate::check"));
    assert!(c["not_certified"].as_str().unwrap().contains("enumerated"));
    assert_eq!(c["files"].as_array().unwrap().len(), certificates);

    // Every counterexample's certificate: accepted, and its values are G* of the file,
    // computed here by Bellman-Ford.
    stems.sort();
    for s in &stems {
        let problem = dir.join(format!("{s}.json"));
        let cert = dir.join(format!("{s}.cert.json"));
        let v = accepted(&problem, &cert, &[]);
        assert_eq!(v["objective"], "deterministic");
        let want = g_star(&read_json(&problem));
        let got: Vec<Option<BigRational>> = read_json(&cert)["values"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| match v.as_str().unwrap() {
                "inf" => None,
                t => Some(q(t)),
            })
            .collect();
        assert_eq!(got, want, "{s}");
    }
}

/// The worked example's certificates: accepted; below `α*` the optimal policy stays at 0 (value
/// `−1/(1−α)`: cost 1 per stage forever), above it walks straight up (value
/// `−(1 + 2α + 3α² + 4α³ + 5α⁴)`), as the paper's inequality says — values computed here.
#[test]
fn worked_example_certificates_are_the_two_sides_of_alpha_star() {
    let (dir, report) = smoke_run();
    let problem = dir.join("c3-example.json");
    for (end, stays) in [("lo", true), ("hi", false)] {
        let cert = dir.join(format!("c3-example-alpha-{end}.cert.json"));
        let v = accepted(&problem, &cert, &[]);
        assert_eq!(v["objective"], "discounted");
        let c = read_json(&cert);
        let alpha = q(report["alpha_star"][end].as_str().unwrap());
        assert_eq!(q(c["alpha"].as_str().unwrap()), alpha);
        let v0 = q(c["values"][0].as_str().unwrap());
        let one = BigRational::one();
        if stays {
            assert_eq!(c["policy"][0], 0, "{c}");
            assert_eq!(v0, -(&one / (&one - &alpha)));
        } else {
            for x in 0..5 {
                assert_eq!(c["policy"][x], 1, "{c}");
            }
            let mut cost = BigRational::zero();
            let mut power = one.clone();
            for i in 1..=5 {
                cost += &power * BigRational::from_integer(BigInt::from(i));
                power *= &alpha;
            }
            assert_eq!(v0, -cost);
        }
    }
}

/// The verified checker accepts a deterministic and a discounted certificate of the run.
#[test]
fn coq_checker_accepts_the_runs_certificates() {
    let built = truecost::certificate::coq::extracted_checker();
    assert!(built.is_ok(), "{built:?}");
    let (dir, _) = smoke_run();
    for (problem, cert) in [
        ("c4-as-printed.json", "c4-as-printed.cert.json"),
        ("c3-example.json", "c3-example-alpha-hi.cert.json"),
    ] {
        let v = accepted(&dir.join(problem), &dir.join(cert), &["--coq"]);
        assert_eq!(v["coq_checked"], true, "{cert}: {v}");
    }
}

/// A certificate with a value off by 10^-30, or checked against a changed problem file, is
/// rejected by `truecost check` in one line.
#[test]
fn tampered_certificates_are_rejected() {
    let (dir, _) = smoke_run();
    let work = tempfile::tempdir().unwrap();
    let mut cert = read_json(&dir.join("c4-as-printed.cert.json"));
    let v0 = q(cert["values"][0].as_str().unwrap());
    let off = v0 + BigRational::new(BigInt::one(), BigInt::from(10).pow(30));
    cert["values"][0] = Value::String(off.to_string());
    let tampered = common::cli::write(work.path(), "t.cert.json", &cert.to_string());
    let problem = dir.join("c4-as-printed.json").display().to_string();
    let err = fails_one_line(&["check", "--file", &problem, &tampered.display().to_string()]);
    assert_contract(&err);
    assert!(err.contains("certificate rejected"), "{err}");

    let text = std::fs::read_to_string(dir.join("c4-as-printed.json")).unwrap();
    let changed = common::cli::write(
        work.path(),
        "p.json",
        &text.replace("\"cost\": \"1\"", "\"cost\": \"2\""),
    );
    assert_ne!(std::fs::read_to_string(&changed).unwrap(), text);
    let cert = dir.join("c4-as-printed.cert.json").display().to_string();
    let err = fails_one_line(&["check", "--file", &changed.display().to_string(), &cert]);
    assert!(err.contains("problem") && err.contains("SHA-256"), "{err}");
}

/// `--claim C4 --problem 3`: the certificate of paper problem 3's G*, accepted by `check
/// --problem 3`; G*(x1) is the L* printed and the optimal number of moves `problems` lists
/// (unit step costs).
#[test]
fn single_problem_certificate_is_its_g_star() {
    let work = tempfile::tempdir().unwrap();
    let d = work.path().join("c");
    let ds = d.display().to_string();
    let v = json(&[
        "verify",
        "--claim",
        "C4",
        "--problem",
        "3",
        "--format",
        "json",
        "--certificates",
        &ds,
    ]);
    assert_eq!(names(&d), ["problem-3.cert.json"]);
    assert_eq!(v["certificates"]["written"], 1);
    let cert = d.join("problem-3.cert.json");
    let c = cert.display().to_string();
    let checked = json(&["check", "--problem", "3", &c, "--format", "json"]);
    assert_eq!(checked["accepted"], true, "{checked}");
    let problems = json(&["problems", "--format", "json"]);
    let x1 = problems[3]["initial"].as_u64().unwrap() as usize;
    let moves = problems[3]["optimal_moves"].as_u64().unwrap();
    let g = read_json(&cert)["values"][x1].as_str().unwrap().to_string();
    assert_eq!(g, moves.to_string());
    assert_eq!(v["bonus_sets"][0]["optimal_cost"], g);
}

/// `--claim C4 --file F` in text: the report's last line gives the count, the directory, the
/// checker and `G*(x1)`, which is the `L*` the counterexample prints (C4's `L* = 0`).
#[test]
fn single_file_certificate_line_in_text() {
    let (dir, report) = smoke_run();
    let c4 = report["claims"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["id"] == "C4")
        .unwrap();
    let l_star = c4["counterexample"]["details"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["name"] == "L*")
        .unwrap()["value"]
        .as_str()
        .unwrap()
        .to_string();
    let work = tempfile::tempdir().unwrap();
    let d = work.path().join("c").display().to_string();
    let f = dir.join("c4-as-printed.json").display().to_string();
    let out = common::cli::stdout(&[
        "verify",
        "--claim",
        "C4",
        "--file",
        &f,
        "--certificates",
        &d,
    ]);
    let last = out.lines().last().unwrap();
    let head = format!(
        "certificates: 1 written to {d}, 1 accepted by truecost's checker (truecost::certificate::check): deterministic G* of file {f} (G*(x1) = {l_star}, x1 = state 0)"
    );
    assert!(last.starts_with(&head), "{last}");
    let cert = work.path().join("c").join("c4-as-printed.cert.json");
    accepted(&dir.join("c4-as-printed.json"), &cert, &[]);
}

/// A `DIR` that is a file, or below a file, is refused in one line before any work (no report,
/// nothing written); `--shard` with `--certificates` is a usage error.
#[test]
fn bad_dir_and_shard_are_refused_before_work() {
    let work = tempfile::tempdir().unwrap();
    let file = common::cli::write(work.path(), "a-file", "x");
    for (dir, says) in [
        (file.clone(), "not a directory"),
        (file.join("below"), "cannot create"),
    ] {
        let d = dir.display().to_string();
        for args in [
            vec![
                "verify",
                "--scope",
                "smoke",
                "--no-coq",
                "--no-smt",
                "--certificates",
                &d,
            ],
            vec![
                "verify",
                "--claim",
                "C4",
                "--problem",
                "3",
                "--certificates",
                &d,
            ],
        ] {
            let out = truecost().args(&args).output().unwrap();
            assert_eq!(out.status.code(), Some(1), "{args:?}");
            assert!(out.stdout.is_empty(), "{args:?}: a report was printed");
            let err = String::from_utf8(out.stderr).unwrap();
            assert_contract(&err);
            assert!(
                err.contains("--certificates") && err.contains(says),
                "{err}"
            );
        }
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
    assert_eq!(names(work.path()), ["a-file"]);

    let d = work.path().join("shard").display().to_string();
    let err = fails(&["verify", "--shard", "1/2", "--certificates", &d], 2);
    assert_contract(&err);
    assert!(
        err.contains("--shard") && err.contains("--certificates"),
        "{err}"
    );
    assert!(!work.path().join("shard").exists());
}

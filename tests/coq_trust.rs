//! What `verify`'s Coq level trusts, tried against what could fool it: a theorem weakened under
//! its own name, a lemma the report relies on deleted, an axiom more or less than pinned, a
//! program called `coqc` that only prints success, one that never returns, one whose output
//! carries terminal escape sequences, and Ctrl-C during the re-check.
//!
//! The pinned statements (`proofs/coq/statements.txt`) are compared here with what a `coqc`
//! run directly by this test prints for `Check` and `Print Assumptions` (its own files and
//! its own reading of the output). `TRUECOST_PIN_COQ=1` rewrites the file from that output.
//! Without `coqc` these tests fail with the install line.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use std::time::Duration;

use serde_json::Value;
use truecost::claims::coq::{self, Assumptions, Outcome, Pin, Settings, ALLOWED_AXIOMS, THEOREMS};
use truecost::claims::registry::attach_coq;
use truecost::claims::{ClaimResult, Scope, Verdict};

fn require_coqc() {
    if let Err(why) = coq::coqc_version() {
        panic!("{why}");
    }
}

/// The re-check `verify` runs, once per test binary.
fn real() -> &'static coq::Check {
    static REAL: OnceLock<coq::Check> = OnceLock::new();
    REAL.get_or_init(|| {
        require_coqc();
        coq::recheck(Duration::from_secs(coq::TIMEOUT_SECONDS))
    })
}

/// What `coqc`, run by this test in a directory of its own, prints for every theorem of the
/// table: `(name, statement, axioms)`, the statement the text after the line break and colon
/// that follow the name (whitespace collapsed), the axioms the names before ` : ` in the
/// block after `Axioms:` (empty for "Closed under the global context"), sorted.
fn direct() -> &'static Vec<(String, String, Vec<String>)> {
    static DIRECT: OnceLock<Vec<(String, String, Vec<String>)>> = OnceLock::new();
    DIRECT.get_or_init(|| {
        require_coqc();
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in coq::SOURCES {
            std::fs::write(dir.path().join(name), text).unwrap();
        }
        let coqc = |file: &str| {
            let out = Command::new("coqc")
                .args(["-R", ".", "Truecost", file])
                .current_dir(dir.path())
                .output()
                .unwrap();
            assert!(out.status.success(), "{file}: {out:?}");
            String::from_utf8(out.stdout).unwrap()
        };
        for (name, _) in coq::SOURCES {
            coqc(name);
        }
        let mut ask = String::from(
            "From Coq Require Import Reals QArith List.\nSet Printing Width 1000000.\nSet Printing Depth 1000000.\n",
        );
        for t in THEOREMS {
            let module = t.name.rsplit_once('.').unwrap().0;
            ask.push_str(&format!(
                "Require {module}.\nGoal True. idtac \"@@ {}\". Abort.\nCheck {}.\nGoal True. idtac \"@@ axioms\". Abort.\nPrint Assumptions {}.\n",
                t.name, t.name, t.name
            ));
        }
        std::fs::write(dir.path().join("Ask.v"), ask).unwrap();
        let out = coqc("Ask.v");
        let mut answers = Vec::new();
        for block in out.split("@@ ").skip(1).collect::<Vec<_>>().chunks(2) {
            let (check, axioms) = (block[0], block[1]);
            let (name, rest) = check.split_once('\n').unwrap();
            let (_, statement) = rest.split_once("\n     : ").unwrap();
            let statement = statement.split_whitespace().collect::<Vec<_>>().join(" ");
            let mut listed: Vec<String> = if axioms.contains("Closed under the global context") {
                vec![]
            } else {
                let (_, list) = axioms.split_once("Axioms:\n").unwrap();
                list.lines()
                    .filter_map(|l| l.split_once(" : ").map(|(n, _)| n.to_string()))
                    .filter(|n| !n.starts_with(' '))
                    .collect()
            };
            listed.sort();
            answers.push((name.trim().to_string(), statement, listed));
        }
        assert_eq!(answers.len(), THEOREMS.len(), "{out}");
        answers
    })
}

/// The pinned file is exactly what `coqc` prints: the names of the table, each statement and
/// axiom list; every pinned axiom is an allowed one. `TRUECOST_PIN_COQ=1` rewrites it.
#[test]
fn the_pinned_statements_are_what_coqc_prints() {
    let pins: Vec<Pin> = direct()
        .iter()
        .map(|(name, statement, axioms)| Pin {
            name: name.clone(),
            axioms: axioms.clone(),
            statement: statement.clone(),
        })
        .collect();
    let names: Vec<&str> = THEOREMS.iter().map(|t| t.name).collect();
    let pinned_names: Vec<&str> = pins.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(pinned_names, names);
    for p in &pins {
        for a in &p.axioms {
            assert!(ALLOWED_AXIOMS.contains(&a.as_str()), "{}: {a}", p.name);
        }
    }
    let text = coq::render_pins(&pins);
    if std::env::var_os("TRUECOST_PIN_COQ").is_some() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("proofs/coq/statements.txt");
        std::fs::write(&path, &text).unwrap();
        eprintln!("wrote {}", path.display());
        return;
    }
    if text != coq::PINNED {
        let old: Vec<&str> = coq::PINNED.lines().collect();
        let new: Vec<&str> = text.lines().collect();
        let mut diff = String::new();
        for l in &old {
            if !new.contains(l) {
                diff.push_str(&format!("- {l}\n"));
            }
        }
        for l in &new {
            if !old.contains(l) {
                diff.push_str(&format!("+ {l}\n"));
            }
        }
        panic!(
            "proofs/coq/statements.txt is not what coqc prints (- pinned, + coqc):\n{diff}\
             regenerate: TRUECOST_PIN_COQ=1 cargo test -p truecost --test coq_trust the_pinned_statements"
        );
    }
    assert_eq!(coq::pins().unwrap(), pins);
}

/// The re-check `verify` runs accepts every theorem, and the report's JSON gives, per theorem,
/// as `coq_statement` exactly what `Check` printed in the test's own run of `coqc`.
#[test]
fn the_json_gives_each_theorem_s_statement_as_check_prints_it() {
    let check = real();
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    assert_eq!(check.files, coq::SOURCES.len());
    for t in &check.theorems {
        assert!(t.accepted(), "{}: {:?}", t.name, t.refused);
    }
    let report = truecost::claims::report::Report {
        tool: "truecost".into(),
        commit: "unknown".into(),
        scope: Scope::Smoke,
        claims: vec![],
        alpha_star: None,
        solver: None,
        smt: vec![],
        coq: Some(check.clone()),
        harnesses: None,
    };
    let v: Value = serde_json::from_str(&truecost::claims::report::json(&report, false)).unwrap();
    let theorems = v["coq"]["theorems"].as_array().unwrap();
    assert_eq!(theorems.len(), direct().len());
    for (json, (name, statement, _)) in theorems.iter().zip(direct()) {
        assert_eq!(json["theorem"], name.as_str());
        assert_eq!(json["coq_statement"], statement.as_str(), "{name}");
        assert_eq!(json["coq_statement_from"], "Check, in this run");
        assert_eq!(json["accepted"], true);
    }
    // The lemma behind the printed "2^-100 apart" is among the checked theorems.
    assert!(check
        .theorem("Truecost.C3Example.alpha_bracket_width")
        .is_some());
}

/// The sources up to C3.v, with `C3.v` changed by `edit`.
fn with_c3(edit: impl Fn(&str) -> String) -> Vec<(&'static str, String)> {
    let mut out = Vec::new();
    let mut edited = 0;
    for (name, text) in coq::SOURCES {
        if name.starts_with("Bridge") {
            continue;
        }
        let changed = edit(text);
        if &changed != text {
            edited += 1;
        }
        out.push((*name, changed));
        if *name == "C3.v" {
            break;
        }
    }
    assert_eq!(edited, 1, "the edit applies to one file of C3");
    out
}

fn recheck_c3(sources: &[(&'static str, String)]) -> coq::Check {
    require_coqc();
    let sources: Vec<(&str, &str)> = sources.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let names: Vec<&str> = coq::theorems_of("C3-example")
        .iter()
        .map(|t| t.name)
        .collect();
    coq::recheck_sources(
        &sources,
        &names,
        &Settings::with_timeout(Duration::from_secs(coq::TIMEOUT_SECONDS)),
    )
}

/// C3-example as the other engines leave it, then the Coq level added from `check`.
fn c3_example_with(check: &coq::Check) -> ClaimResult {
    let mut r = ClaimResult {
        id: "C3-example".into(),
        statement: String::new(),
        verdict: Verdict::Proved,
        engine: "smt (Z3)".into(),
        scope: "symbolic".into(),
        cases: 6,
        counterexample: None,
        engines: vec![],
        notes: vec![],
    };
    attach_coq(&mut r, check);
    r
}

/// `c3_alpha_star` with its bracket `lo < α* < hi` deleted still compiles under its name: the
/// statement differs from the pinned one, the theorem is refused, and C3-example keeps the
/// other engines' verdict with the reason in its notes.
#[test]
fn a_theorem_weakened_under_its_name_is_not_proved() {
    let sources = with_c3(|t| t.replacen("    Q2R alpha_lo < astar < Q2R alpha_hi /\\\n", "", 1));
    let check = recheck_c3(&sources);
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    let star = check.theorem("Truecost.C3.c3_alpha_star").unwrap();
    let why = star.refused.as_deref().unwrap();
    assert!(
        why.starts_with("Coq's statement differs from the pinned one"),
        "{why}"
    );
    assert!(!star.statement.as_ref().unwrap().contains("alpha_lo"));
    // The other theorems of the claim are untouched.
    for t in &check.theorems {
        if t.name != "Truecost.C3.c3_alpha_star" {
            assert!(t.accepted(), "{}: {:?}", t.name, t.refused);
        }
    }
    let r = c3_example_with(&check);
    assert_eq!(r.verdict, Verdict::Proved);
    assert!(
        r.notes
            .iter()
            .any(|n| n.contains("c3_alpha_star")
                && n.contains("NOT accepted: Coq's statement differs")),
        "{:?}",
        r.notes
    );
}

/// The bracket widened (α_lo = 1/2) with `alpha_bracket_width` deleted: `c3_alpha_star`'s
/// statement is unchanged (it names the bracket's ends), so only the missing lemma shows that
/// the printed "2^-100 apart" is no longer proved — and C3-example is not proved in Coq.
#[test]
fn a_widened_bracket_without_its_width_lemma_is_not_proved() {
    let sources = with_c3(|t| {
        t.replacen(
            "Definition alpha_lo : Q := 580808718285461345641984028243 # 633825300114114700748351602688.",
            "Definition alpha_lo : Q := 1 # 2.",
            1,
        )
        .replacen(
            "Lemma alpha_bracket_width : (alpha_hi - alpha_lo == 1 # 1267650600228229401496703205376)%Q.\nProof. vm_compute; reflexivity. Qed.\n",
            "",
            1,
        )
    });
    assert!(sources
        .iter()
        .all(|(_, text)| !text.contains("alpha_bracket_width :")));
    let check = recheck_c3(&sources);
    assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
    assert!(check
        .theorem("Truecost.C3.c3_alpha_star")
        .unwrap()
        .accepted());
    let width = check
        .theorem("Truecost.C3Example.alpha_bracket_width")
        .unwrap();
    assert!(
        matches!(width.assumptions, Assumptions::Missing(_)),
        "{width:?}"
    );
    assert!(!width.accepted());
    let r = c3_example_with(&check);
    assert_eq!(r.verdict, Verdict::Proved);
    assert_eq!(r.engines.last().unwrap().failures, 1);
}

/// A theorem with an axiom more than pinned, or one fewer, is refused; exactly the pinned list
/// is accepted. Small developments, pinned by hand: a lemma over `Q` (closed) and one over the
/// reals (which `lra` proves with the library's axioms of `R`).
#[test]
fn an_extra_or_a_missing_axiom_is_refused() {
    require_coqc();
    let text = "Require Import QArith Reals Lra.
Lemma over_q : ((1 # 2) + (1 # 2) == 1)%Q.
Proof. reflexivity. Qed.
Lemma over_r : forall x : R, (x + 0 = x)%R.
Proof. intros; lra. Qed.
";
    let names = ["Truecost.A.over_q", "Truecost.A.over_r"];
    let run = |pins: Vec<Pin>| {
        let check = coq::recheck_sources(
            &[("A.v", text)],
            &names,
            &Settings {
                pins,
                ..Settings::with_timeout(Duration::from_secs(120))
            },
        );
        assert_eq!(check.outcome, Outcome::Checked, "{check:?}");
        names.map(|n| check.theorem(n).unwrap().refused.clone())
    };
    // Coq 8.16.1 proves over_r with these two of the reals' axioms.
    let reals: Vec<String> = vec![
        "ClassicalDedekindReals.sig_forall_dec".into(),
        "FunctionalExtensionality.functional_extensionality_dep".into(),
    ];
    let pin = |name: &str, axioms: &[String], statement: &str| Pin {
        name: name.into(),
        axioms: axioms.to_vec(),
        statement: statement.into(),
    };
    let q = "(1 # 2) + (1 # 2) == 1";
    let r = "forall x : R, (x + 0)%R = x";
    // Exactly as Coq prints them: accepted.
    let exact = run(vec![pin(names[0], &[], q), pin(names[1], &reals, r)]);
    assert_eq!(exact, [None, None], "{exact:?}");
    // One axiom fewer pinned for over_r: Coq lists an extra one. One more pinned for over_q
    // (closed): Coq does not list it.
    let refused = run(vec![
        pin(names[0], &reals[..1], q),
        pin(names[1], &reals[..1], r),
    ]);
    let [over_q, over_r] = refused.map(|r| r.unwrap_or_default());
    assert_eq!(
        over_q,
        "Print Assumptions does not list exactly the pinned axioms: extra none; missing ClassicalDedekindReals.sig_forall_dec"
    );
    assert_eq!(
        over_r,
        "Print Assumptions does not list exactly the pinned axioms: extra FunctionalExtensionality.functional_extensionality_dep; missing none"
    );
    // A pinned axiom outside the allowed list is refused.
    let mut other = reals.clone();
    other.push("Classical_Prop.classic".into());
    let refused = run(vec![pin(names[0], &[], q), pin(names[1], &other, r)]);
    assert!(
        refused[1]
            .as_deref()
            .unwrap()
            .contains("Classical_Prop.classic is not an allowed axiom"),
        "{refused:?}"
    );
}

/// A directory with an executable `coqc` running `script` (sh).
fn fake_coqc(script: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("coqc");
    std::fs::write(&path, format!("#!/bin/sh\n{script}\n")).unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
    dir
}

/// `truecost verify` for C2 only (fast), the Coq re-check on, with `bin` first on `PATH` and
/// `tmp` as the temporary directory.
fn verify_with(bin: &Path, tmp: &Path, extra: &[&str]) -> Command {
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut c = Command::new(assert_cmd::cargo::cargo_bin("truecost"));
    c.args([
        "verify",
        "--scope",
        "smoke",
        "--claim",
        "C2",
        "--no-smt",
        "--no-harnesses",
        "--no-times",
    ])
    .args(extra)
    .env("PATH", path)
    .env("TMPDIR", tmp);
    c
}

fn left_in(tmp: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(tmp)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect()
}

/// A program on `PATH` called `coqc` that prints Coq's version and "Closed under the global
/// context" whatever it is asked is not Coq: the false canary "compiles". The report says so
/// and C2 keeps the SMT-less verdict, not the Coq level.
#[test]
fn a_coqc_that_only_prints_success_is_caught() {
    let bin = fake_coqc(
        "echo 'The Coq Proof Assistant, version 8.16.1'\necho 'Closed under the global context'\nexit 0",
    );
    let tmp = tempfile::tempdir().unwrap();
    let out = verify_with(bin.path(), tmp.path(), &[]).output().unwrap();
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("NOT re-checked: coqc did not behave as Coq (it accepted a false lemma: Lemma canary_false"),
        "{text}"
    );
    assert!(text.contains("C2  VERIFIED"), "{text}");
    assert!(!text.contains("(COQ)"), "{text}");
    assert!(left_in(tmp.path()).is_empty());
}

/// A `coqc` that answers `--version` and then sleeps is stopped by `--coq-timeout 2` (its
/// process group killed: the sleeping child is gone too), the report says why, and no
/// temporary directory is left.
#[test]
fn a_hanging_coqc_is_stopped_by_the_timeout() {
    let tmp = tempfile::tempdir().unwrap();
    let marks = tempfile::tempdir().unwrap();
    let pidfile = marks.path().join("sleeper");
    let bin = fake_coqc(&format!(
        "case \"$1\" in --version) echo 'The Coq Proof Assistant, version 8.16.1'; exit 0;; esac\n\
         sleep 300 &\necho $! > {}\nwait",
        pidfile.display()
    ));
    let started = std::time::Instant::now();
    let out = verify_with(bin.path(), tmp.path(), &["--coq-timeout", "2"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("NOT re-checked: coqc did not finish within 2 s (the re-check's limit, --coq-timeout) while compiling a false lemma; stopped"),
        "{text}"
    );
    assert!(started.elapsed() < Duration::from_secs(120));
    assert!(left_in(tmp.path()).is_empty(), "{:?}", left_in(tmp.path()));
    // Killed: gone, or a zombie (state Z) waiting for its new parent to reap it.
    let sleeper = std::fs::read_to_string(&pidfile).unwrap();
    let stat = std::fs::read_to_string(format!("/proc/{}/stat", sleeper.trim()));
    let state = stat
        .as_deref()
        .ok()
        .and_then(|s| s.rsplit_once(") "))
        .and_then(|(_, rest)| rest.chars().next());
    assert!(
        matches!(state, None | Some('Z')),
        "the sleeping child {sleeper} is still running: {stat:?}"
    );
}

/// SIGINT while `coqc` runs: the process group is killed, the temporary directory removed,
/// and `verify` ends by SIGINT.
#[test]
fn ctrl_c_during_the_recheck_leaves_nothing_behind() {
    let tmp = tempfile::tempdir().unwrap();
    let started = tmp.path().join("started");
    let bin = fake_coqc(&format!(
        "case \"$1\" in --version) echo 'The Coq Proof Assistant, version 8.16.1'; exit 0;; esac\n\
         touch {}\nexec sleep 300",
        started.display()
    ));
    let mut child = verify_with(bin.path(), tmp.path(), &[])
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t = std::time::Instant::now();
    while !started.exists() {
        assert!(t.elapsed() < Duration::from_secs(300), "coqc never started");
        std::thread::sleep(Duration::from_millis(50));
    }
    // The re-check's directory exists while coqc runs.
    assert!(left_in(tmp.path()).iter().any(|p| p
        .file_name()
        .unwrap()
        .to_string_lossy()
        .starts_with("truecost-coq-")));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let status = child.wait().unwrap();
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(status.signal(), Some(2), "{status:?}");
    let left: Vec<PathBuf> = left_in(tmp.path())
        .into_iter()
        .filter(|p| p.file_name().unwrap() != "started")
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// Escape sequences in what a fake `coqc` prints reach the text report escaped: no raw ESC.
#[test]
fn escape_sequences_from_coqc_are_escaped_in_the_report() {
    let bin = fake_coqc(
        "printf 'The Coq Proof Assistant, version 8.16.1\\033[2J\\033]0;owned\\007\\n'\n\
         case \"$1\" in --version) exit 0;; esac\nexit 1",
    );
    let tmp = tempfile::tempdir().unwrap();
    for format in ["text", "markdown", "json"] {
        let out = verify_with(bin.path(), tmp.path(), &["--format", format])
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(!text.contains('\x1b') && !text.contains('\x07'), "{text:?}");
        let escaped = if format == "json" {
            "8.16.1\\\\x1b[2J\\\\x1b]0;owned\\\\x07"
        } else {
            "8.16.1\\x1b[2J\\x1b]0;owned\\x07"
        };
        assert!(text.contains(escaped), "{format}: {text}");
    }
}

//! The verified checker, run: a truecost (or deterministic `G*`) certificate and the re-read
//! model written as Coq terms and decided by `vm_compute` with the checker `check` of
//! `proofs/coq/CertificateCheck.v`, whose soundness is the Coq theorems
//! `Truecost.CertificateCheck.check_policy` and `Truecost.CertificateCheck.check_optimal`.
//!
//! The Coq checker takes two kinds of hints that the Rust checker finds by search, computed
//! here and checked there (a wrong hint makes it reject, never accept wrongly): per finite
//! state, its distance to a goal along the policy's outcomes; per `inf` state, the round of
//! the `W*` iteration that removes it. What stays trusted outside Coq: reading the problem
//! and the certificate, and writing them as Coq terms ([`coq_case`]).

use std::collections::VecDeque;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::format::{Certificate, CertifiedObjective};
use super::mdp::Mdp;
use crate::value::Rational;

/// The Coq sources the checker needs, in dependency order (embedded: what runs is what this
/// build was made from).
pub const COQ_SOURCES: &[(&str, &str)] = &[
    (
        "Certificate.v",
        include_str!("../../proofs/coq/Certificate.v"),
    ),
    (
        "CertificateCheck.v",
        include_str!("../../proofs/coq/CertificateCheck.v"),
    ),
];

/// How long one `coqc` call may take before it is stopped.
pub const COQ_TIMEOUT: Duration = Duration::from_secs(600);

fn q(r: &Rational) -> String {
    format!("({} # {})", r.numer(), r.denom())
}

/// The hints: per finite state its distance to a goal along `π`'s outcomes (0 at goals; absent
/// when unreachable), per `inf` state the round of the `W*` iteration that removes it (absent
/// when it stays). An absent hint is written 0, which the Coq checker rejects.
pub fn hints(mdp: &Mdp, c: &Certificate) -> Vec<usize> {
    let n = mdp.states();
    let finite = |x: usize| c.values.get(x).is_some_and(Option::is_some);
    let mut rank = vec![0; n];
    // Distances: backward breadth-first search from the goals along pi's outcomes.
    let mut into: Vec<Vec<usize>> = vec![Vec::new(); n];
    for x in (0..n).filter(|&x| finite(x) && !mdp.goal[x]) {
        let chosen = c.policy.get(x).copied().flatten();
        if let Some(a) = chosen.and_then(|i| mdp.actions[x].get(usize::try_from(i).ok()?)) {
            for (y, _) in &a.outcomes {
                into[*y].push(x);
            }
        }
    }
    let mut seen = mdp.goal.clone();
    let mut queue: VecDeque<usize> = (0..n).filter(|&x| mdp.goal[x]).collect();
    while let Some(y) = queue.pop_front() {
        for &x in &into[y] {
            if !seen[x] {
                seen[x] = true;
                rank[x] = rank[y] + 1;
                queue.push_back(x);
            }
        }
    }
    // Removal rounds: W_0 = every state; W_k = the states of W_{k-1} reaching a goal by
    // actions whose outcomes all stay in W_{k-1}.
    let mut w = vec![true; n];
    for round in 1.. {
        let mut r = mdp.goal.clone();
        loop {
            let mut changed = false;
            for x in 0..n {
                if !w[x] || r[x] {
                    continue;
                }
                let survives = mdp.actions[x].iter().any(|a| {
                    a.outcomes.iter().all(|(y, _)| w[*y]) && a.outcomes.iter().any(|(y, _)| r[*y])
                });
                if survives {
                    r[x] = true;
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
        if r == w {
            break;
        }
        for x in (0..n).filter(|&x| w[x] && !r[x] && !finite(x)) {
            rank[x] = round;
        }
        w = r;
    }
    rank
}

/// The Coq term `check m V pi rk` for `c` against `mdp` (with [`hints`]): the model as a
/// list of `(goal, [(cost, [(successor, probability)])])`, values `Some (p # q)` or `None`,
/// the policy `Some i` or `None`.
pub fn coq_case(mdp: &Mdp, c: &Certificate) -> String {
    let mut s = String::from("CertificateCheck.check [");
    for (x, list) in mdp.actions.iter().enumerate() {
        if x > 0 {
            s.push(';');
        }
        let _ = write!(s, "({}, [", mdp.goal[x]);
        for (i, a) in list.iter().enumerate() {
            if i > 0 {
                s.push(';');
            }
            let _ = write!(s, "({}, [", q(&a.cost));
            for (j, (y, p)) in a.outcomes.iter().enumerate() {
                if j > 0 {
                    s.push(';');
                }
                let _ = write!(s, "({y}%nat, {})", q(p));
            }
            s.push_str("])");
        }
        s.push_str("])");
    }
    s.push_str("] [");
    for (x, v) in c.values.iter().enumerate() {
        if x > 0 {
            s.push(';');
        }
        match v {
            Some(r) => {
                let _ = write!(s, "Some {}", q(r));
            }
            None => s.push_str("None"),
        }
    }
    s.push_str("] [");
    for (x, i) in c.policy.iter().enumerate() {
        if x > 0 {
            s.push(';');
        }
        match i {
            Some(i) => {
                let _ = write!(s, "Some {i}%nat");
            }
            None => s.push_str("None"),
        }
    }
    s.push_str("] [");
    let ranks: Vec<String> = hints(mdp, c).iter().map(|r| format!("{r}%nat")).collect();
    s.push_str(&ranks.join(";"));
    s.push(']');
    s
}

/// Whether `c` is one the Coq checker decides: the truecost or deterministic objective, as
/// many values and policy entries as the model has states.
pub fn coq_applies(mdp: &Mdp, c: &Certificate) -> Result<(), String> {
    match c.objective {
        CertifiedObjective::Truecost | CertifiedObjective::Deterministic => {}
        _ => {
            return Err(format!(
                "the Coq checker covers the truecost and deterministic objectives, not {}",
                c.objective.name()
            ))
        }
    }
    if c.values.len() != mdp.states() || c.policy.len() != mdp.states() {
        return Err(format!(
            "the certificate has {} values and {} policy entries, the problem {} states",
            c.values.len(),
            c.policy.len(),
            mdp.states()
        ));
    }
    Ok(())
}

/// A fresh working directory under the system's temporary directory.
fn work_dir() -> Result<PathBuf, String> {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    let dir =
        std::env::temp_dir().join(format!("truecost-coq-check-{}-{nanos}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    Ok(dir)
}

/// Runs `coqc -R . Truecost file` in `dir`, stopped after [`COQ_TIMEOUT`]; its output.
fn coqc(dir: &Path, file: &str) -> Result<String, String> {
    let mut child = Command::new("coqc")
        .args(["-R", ".", "Truecost", file])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| {
            format!("cannot run coqc (install Coq 8.16 or later, e.g. apt-get install coq): {e}")
        })?;
    let started = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) if started.elapsed() > COQ_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!(
                    "coqc {file} did not finish within {} s",
                    COQ_TIMEOUT.as_secs()
                ));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(format!("coqc {file}: {e}")),
        }
    }
    let out = child
        .wait_with_output()
        .map_err(|e| format!("coqc {file}: {e}"))?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    if out.status.success() {
        Ok(text)
    } else {
        let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
        Err(format!(
            "coqc {file} failed: {}",
            crate::echo::echo(first.trim())
        ))
    }
}

/// The Coq checker's verdicts on `cases` (terms of [`coq_case`]), in order, from one `coqc`
/// call after compiling [`COQ_SOURCES`] in a fresh directory (removed afterwards).
pub fn coq_verdicts(cases: &[String]) -> Result<Vec<bool>, String> {
    let dir = work_dir()?;
    let result = (|| {
        for (name, text) in COQ_SOURCES {
            std::fs::write(dir.join(name), text)
                .map_err(|e| format!("cannot write {name}: {e}"))?;
            coqc(&dir, name)?;
        }
        let mut run = String::from(
            "From Coq Require Import QArith List.\nFrom Truecost Require CertificateCheck.\n\
             Import ListNotations.\nOpen Scope Q_scope.\n",
        );
        for case in cases {
            let _ = writeln!(run, "Eval vm_compute in {case}.");
        }
        std::fs::write(dir.join("Run.v"), run).map_err(|e| format!("cannot write Run.v: {e}"))?;
        let out = coqc(&dir, "Run.v")?;
        let verdicts: Vec<bool> = out
            .lines()
            .filter_map(|l| match l.trim() {
                "= true" => Some(true),
                "= false" => Some(false),
                _ => None,
            })
            .collect();
        if verdicts.len() != cases.len() {
            return Err(format!(
                "coqc printed {} verdicts for {} certificates",
                verdicts.len(),
                cases.len()
            ));
        }
        Ok(verdicts)
    })();
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// The Coq checker's verdict on one certificate: `Ok(true)` if `check` accepts it.
pub fn coq_check(mdp: &Mdp, c: &Certificate) -> Result<bool, String> {
    coq_applies(mdp, c)?;
    Ok(coq_verdicts(&[coq_case(mdp, c)])?[0])
}

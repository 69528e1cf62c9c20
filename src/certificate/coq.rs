//! The verified checkers, run: a truecost, deterministic `G*` or discounted certificate and the
//! re-read model decided by the Coq functions `check` (`proofs/coq/CertificateCheck.v`,
//! soundness `Truecost.CertificateCheck.check_policy` and `check_optimal`) and
//! `check_discounted` (`proofs/coq/CertificateDiscounted.v`, soundness
//! `Truecost.CertificateDiscounted.check_discounted_policy` and `check_discounted_optimal`).
//!
//! [`coq_check`] runs them extracted to OCaml (`proofs/coq/CertificateExtract.v`, integers by
//! zarith): [`extracted_checker`] builds the program once from the sources embedded here
//! (`coqc`, then `ocamlfind ocamlopt -package zarith`) into a cache directory named by their
//! SHA-256, and [`checker_input`] writes the model and the certificate as the text its driver
//! (`proofs/coq/extract/driver.ml`) reads. [`coq_verdicts`] decides terms of [`coq_case`] with
//! `vm_compute` instead, inside Coq, far slower on large numbers.
//!
//! The truecost checker takes two kinds of hints that the Rust checker finds by search,
//! computed here and checked there (a wrong hint makes it reject, never accept wrongly): per
//! finite state, its distance to a goal along the policy's outcomes; per `inf` state, the round
//! of the `W*` iteration that removes it. What stays trusted outside Coq: reading the problem
//! and the certificate, writing them for the checker, and the extraction's trusted base
//! (docs/guide/certificates.md).

use std::collections::VecDeque;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::format::{Certificate, CertifiedObjective};
use super::mdp::{Mdp, MdpAction};
use crate::value::Rational;

/// The Coq sources the checkers need, in dependency order (embedded: what runs is what this
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
    (
        "CertificateDiscounted.v",
        include_str!("../../proofs/coq/CertificateDiscounted.v"),
    ),
];

/// The extraction (writes `extract/checker.ml` and `extract/checker.mli`).
pub const EXTRACTION_SOURCE: (&str, &str) = (
    "CertificateExtract.v",
    include_str!("../../proofs/coq/CertificateExtract.v"),
);

/// The OCaml files compiled with the extracted checker, in `extract/`.
pub const OCAML_SOURCES: &[(&str, &str)] = &[
    ("bigz.ml", include_str!("../../proofs/coq/extract/bigz.ml")),
    (
        "driver.ml",
        include_str!("../../proofs/coq/extract/driver.ml"),
    ),
];

/// The extracted checker's file name.
pub const CHECKER_NAME: &str = "truecost-coq-check";

/// How long one `coqc`, `ocamlfind` or checker run may take before it is stopped.
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

/// The discount factor of a discounted certificate, `None` for the objectives of `check`.
fn discount(c: &Certificate) -> Option<&Rational> {
    match &c.objective {
        CertifiedObjective::Discounted(alpha) => Some(alpha),
        _ => None,
    }
}

/// Per state the flag the checker reads (goal; terminal for the discounted objective) and per
/// action its number (stage cost; expected reward for the discounted objective).
fn flags_and_numbers<'a>(
    mdp: &'a Mdp,
    c: &Certificate,
) -> (&'a [bool], fn(&MdpAction) -> &Rational) {
    if discount(c).is_some() {
        (&mdp.terminal, |a| &a.reward)
    } else {
        (&mdp.goal, |a| &a.cost)
    }
}

/// The policy's index at `x`, an index past the last action written as the number of actions
/// (the checkers reject both alike: no action has it).
fn index(mdp: &Mdp, c: &Certificate, x: usize) -> Option<usize> {
    c.policy[x]
        .map(|i| usize::try_from(i).map_or(mdp.actions[x].len(), |i| i.min(mdp.actions[x].len())))
}

/// The Coq term that decides `c` against `mdp`: `check m V pi rk` (with [`hints`]) or, for
/// the discounted objective, `check_discounted m alpha V pi`; the model as a list of
/// `(flag, [(number, [(successor, probability)])])` (`flags_and_numbers`), values
/// `Some (p # q)` or `None`, the policy `Some i` or `None`.
pub fn coq_case(mdp: &Mdp, c: &Certificate) -> String {
    let (flags, number) = flags_and_numbers(mdp, c);
    let mut s = match discount(c) {
        Some(_) => String::from("CertificateDiscounted.check_discounted ["),
        None => String::from("CertificateCheck.check ["),
    };
    for (x, list) in mdp.actions.iter().enumerate() {
        if x > 0 {
            s.push(';');
        }
        let _ = write!(s, "({}, [", flags[x]);
        for (i, a) in list.iter().enumerate() {
            if i > 0 {
                s.push(';');
            }
            let _ = write!(s, "({}, [", q(number(a)));
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
    s.push(']');
    if let Some(alpha) = discount(c) {
        let _ = write!(s, " {}", q(alpha));
    }
    s.push_str(" [");
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
    for x in 0..c.policy.len() {
        if x > 0 {
            s.push(';');
        }
        match index(mdp, c, x) {
            Some(i) => {
                let _ = write!(s, "Some {i}%nat");
            }
            None => s.push_str("None"),
        }
    }
    s.push(']');
    if discount(c).is_none() {
        let ranks: Vec<String> = hints(mdp, c).iter().map(|r| format!("{r}%nat")).collect();
        let _ = write!(s, " [{}]", ranks.join(";"));
    }
    s
}

/// The input of the extracted checker's driver (`proofs/coq/extract/driver.ml` gives the
/// format): the same model, certificate and hints as [`coq_case`], as whitespace-separated
/// decimal tokens.
pub fn checker_input(mdp: &Mdp, c: &Certificate) -> String {
    let (flags, number) = flags_and_numbers(mdp, c);
    let frac = |r: &Rational| format!("{} {}", r.numer(), r.denom());
    let mut s = String::from("truecost-coq-check 1\n");
    match discount(c) {
        Some(alpha) => {
            let _ = writeln!(s, "objective discounted {}", frac(alpha));
        }
        None => s.push_str("objective truecost\n"),
    }
    let ranks = match discount(c) {
        Some(_) => vec![0; mdp.states()],
        None => hints(mdp, c),
    };
    let _ = writeln!(s, "states {}", mdp.states());
    for (x, list) in mdp.actions.iter().enumerate() {
        let value = c.values[x].as_ref().map_or("inf".into(), frac);
        let pi = index(mdp, c, x).map_or("-".into(), |i| i.to_string());
        let _ = writeln!(
            s,
            "state {} {value} {pi} {} {}",
            u8::from(flags[x]),
            ranks[x],
            list.len()
        );
        for a in list {
            let _ = write!(s, "action {} {}", frac(number(a)), a.outcomes.len());
            for (y, p) in &a.outcomes {
                let _ = write!(s, " {y} {}", frac(p));
            }
            s.push('\n');
        }
    }
    s.push_str("end\n");
    s
}

/// Whether `c` is one the Coq checkers decide: the truecost, deterministic or discounted
/// objective, as many values and policy entries as the model has states.
pub fn coq_applies(mdp: &Mdp, c: &Certificate) -> Result<(), String> {
    match c.objective {
        CertifiedObjective::Truecost
        | CertifiedObjective::Deterministic
        | CertifiedObjective::Discounted(_) => {}
        _ => {
            return Err(format!(
            "the Coq checker covers the truecost, deterministic and discounted objectives, not {}",
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

/// A fresh private working directory under the system's temporary directory (an unpredictable
/// name, created with mode 0700; removed when dropped).
fn work_dir() -> Result<tempfile::TempDir, String> {
    let mut builder = tempfile::Builder::new();
    builder.prefix("truecost-coq-check-");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o700));
    builder.tempdir().map_err(|e| {
        format!(
            "cannot create a working directory in {}: {e}",
            std::env::temp_dir().display()
        )
    })
}

/// Writes `files` into `dir`.
fn write_all(dir: &Path, files: &[(&str, &str)]) -> Result<(), String> {
    for (name, text) in files {
        std::fs::write(dir.join(name), text).map_err(|e| format!("cannot write {name}: {e}"))?;
    }
    Ok(())
}

/// Runs `command` (described as `what` in messages), stopped after [`COQ_TIMEOUT`]: its exit
/// status's success and its standard output and error, or why it could not run. `missing`
/// says what to install when the program is not found.
fn run(mut command: Command, what: &str, missing: &str) -> Result<(bool, String), String> {
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run {what} ({missing}): {e}"))?;
    // Drain both pipes while waiting, so that a large output cannot block the child.
    let out = child.stdout.take().expect("piped");
    let err = child.stderr.take().expect("piped");
    let drain = |mut pipe: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut text = String::new();
            let _ = pipe.read_to_string(&mut text);
            text
        })
    };
    let (out, err) = (drain(Box::new(out)), drain(Box::new(err)));
    let started = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if started.elapsed() > COQ_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!(
                    "{what} did not finish within {} s",
                    COQ_TIMEOUT.as_secs()
                ));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(e) => return Err(format!("{what}: {e}")),
        }
    };
    let text = format!(
        "{}{}",
        out.join().unwrap_or_default(),
        err.join().unwrap_or_default()
    );
    Ok((status.success(), text))
}

/// [`run`], an error unless it succeeds (with the first line of its output).
fn run_ok(command: Command, what: &str, missing: &str) -> Result<String, String> {
    let (ok, text) = run(command, what, missing)?;
    if ok {
        Ok(text)
    } else {
        let first = text.lines().find(|l| !l.trim().is_empty()).unwrap_or("");
        Err(format!(
            "{what} failed: {}",
            crate::echo::echo(first.trim())
        ))
    }
}

const NEEDS_COQ: &str = "install Coq 8.16 or later, e.g. apt-get install coq";
const NEEDS_OCAML: &str =
    "the Coq checker is compiled with OCaml and zarith: apt-get install ocaml-findlib libzarith-ocaml-dev";

/// Runs `coqc -R . Truecost file` in `dir`; its output.
fn coqc(dir: &Path, file: &str) -> Result<String, String> {
    let mut command = Command::new("coqc");
    command.args(["-R", ".", "Truecost", file]).current_dir(dir);
    run_ok(command, &format!("coqc {file}"), NEEDS_COQ)
}

/// The SHA-256 of every embedded source, in order: what names a build of the checker.
fn sources_hash() -> String {
    let mut all = String::new();
    for (name, text) in COQ_SOURCES
        .iter()
        .chain(std::iter::once(&EXTRACTION_SOURCE))
        .chain(OCAML_SOURCES)
    {
        let _ = write!(all, "{name}\n{}\n{text}\n", text.len());
    }
    super::sha256_hex(all.as_bytes())
}

/// Where built checkers are kept: `$XDG_CACHE_HOME/truecost`, else `$HOME/.cache/truecost`,
/// else the system's temporary directory.
fn cache_root() -> PathBuf {
    let nonempty = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty());
    if let Some(d) = nonempty("XDG_CACHE_HOME") {
        PathBuf::from(d).join("truecost")
    } else if let Some(h) = nonempty("HOME") {
        PathBuf::from(h).join(".cache").join("truecost")
    } else {
        std::env::temp_dir().join("truecost-cache")
    }
}

/// Builds the extracted checker in `dir`: the Coq sources compiled, the extraction run, the
/// OCaml compiled against zarith. The binary's path.
fn build_checker(dir: &Path) -> Result<PathBuf, String> {
    let mut query = Command::new("ocamlfind");
    query.args(["query", "zarith"]);
    run_ok(query, "ocamlfind query zarith", NEEDS_OCAML).map_err(|e| {
        if e.contains(NEEDS_OCAML) {
            e
        } else {
            format!("{e} ({NEEDS_OCAML})")
        }
    })?;
    let extract = dir.join("extract");
    std::fs::create_dir_all(&extract)
        .map_err(|e| format!("cannot create {}: {e}", extract.display()))?;
    write_all(dir, COQ_SOURCES)?;
    write_all(dir, &[EXTRACTION_SOURCE])?;
    write_all(&extract, OCAML_SOURCES)?;
    for (name, _) in COQ_SOURCES
        .iter()
        .chain(std::iter::once(&EXTRACTION_SOURCE))
    {
        coqc(dir, name)?;
    }
    let mut compile = Command::new("ocamlfind");
    compile
        .args(["ocamlopt", "-package", "zarith", "-linkpkg"])
        .args([
            "bigz.ml",
            "checker.mli",
            "checker.ml",
            "driver.ml",
            "-o",
            CHECKER_NAME,
        ])
        .current_dir(&extract);
    run_ok(compile, "ocamlfind ocamlopt", NEEDS_OCAML)?;
    Ok(extract.join(CHECKER_NAME))
}

/// The extracted checker built from the embedded sources: found in the cache directory named
/// by their SHA-256, or built there first (about a minute; `coqc`, `ocamlfind` and zarith
/// needed). The binary's path.
pub fn extracted_checker() -> Result<PathBuf, String> {
    let root = cache_root();
    let home = root.join(format!("coq-checker-{}", &sources_hash()[..16]));
    let binary = home.join(CHECKER_NAME);
    let dir = work_dir()?;
    if binary.is_file() {
        private(&[&root, &home, &binary], dir.path())?;
        return Ok(binary);
    }
    let b = build_checker(dir.path())?;
    for d in [&root, &home] {
        create_private_dir(d)?;
    }
    private(&[&root, &home], dir.path())?;
    // Renamed into place whole: a concurrent build finds either nothing or the binary.
    let partial = home.join(format!("{CHECKER_NAME}.{}", std::process::id()));
    std::fs::copy(&b, &partial)
        .and_then(|_| std::fs::rename(&partial, &binary))
        .map_err(|e| format!("cannot install {}: {e}", binary.display()))?;
    Ok(binary)
}

/// Creates `dir` if missing, readable and writable by its owner only.
fn create_private_dir(dir: &Path) -> Result<(), String> {
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    #[cfg(unix)]
    std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
    builder
        .create(dir)
        .map_err(|e| format!("cannot create {}: {e}", dir.display()))
}

/// Refuses a cached checker that someone else could have replaced: each of `paths` must be
/// owned by the user running truecost (the owner of `ours`, a directory it just created) and
/// writable by no one else. The cache is trusted as far as the `truecost` binary itself is.
fn private(paths: &[&Path], ours: &Path) -> Result<(), String> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let uid = std::fs::metadata(ours)
            .map_err(|e| format!("cannot read {}: {e}", ours.display()))?
            .uid();
        for path in paths {
            let meta = std::fs::symlink_metadata(path)
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            if meta.uid() != uid || meta.mode() & 0o022 != 0 || meta.file_type().is_symlink() {
                return Err(format!(
                    "the cached Coq checker is not private: {} is {}owned by uid {} with mode \
                     {:o} (it must be yours, not a symbolic link, and writable by you only; \
                     remove it to rebuild)",
                    crate::echo::echo(&path.display().to_string()),
                    if meta.file_type().is_symlink() {
                        "a symbolic link "
                    } else {
                        ""
                    },
                    meta.uid(),
                    meta.mode() & 0o7777
                ));
            }
        }
    }
    #[cfg(not(unix))]
    let _ = (paths, ours);
    Ok(())
}

/// The extracted checker's verdict on `input` (of [`checker_input`]): `Ok(true)` if it prints
/// `accepted`, `Ok(false)` if `rejected`, an error otherwise.
pub fn extracted_verdict(checker: &Path, input: &str) -> Result<bool, String> {
    let dir = work_dir()?;
    let result = (|| {
        let file = dir.path().join("certificate.txt");
        std::fs::write(&file, input)
            .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
        let mut command = Command::new(checker);
        command.arg(&file);
        let (_, out) = run(command, CHECKER_NAME, "build it with make -C proofs/coq")?;
        match out.trim() {
            "accepted" => Ok(true),
            "rejected" => Ok(false),
            other => Err(format!(
                "{CHECKER_NAME}: {}",
                crate::echo::echo(other.lines().next().unwrap_or("no output"))
            )),
        }
    })();
    drop(dir);
    result
}

/// The `vm_compute` verdicts on `cases` (terms of [`coq_case`]), in order, from one `coqc`
/// call after compiling [`COQ_SOURCES`] in a fresh directory (removed afterwards).
pub fn coq_verdicts(cases: &[String]) -> Result<Vec<bool>, String> {
    let tmp = work_dir()?;
    let dir = tmp.path();
    let result = (|| {
        write_all(dir, COQ_SOURCES)?;
        for (name, _) in COQ_SOURCES {
            coqc(dir, name)?;
        }
        let mut run = String::from(
            "From Coq Require Import QArith List.\n\
             From Truecost Require CertificateCheck CertificateDiscounted.\n\
             Import ListNotations.\nOpen Scope Q_scope.\n",
        );
        for case in cases {
            let _ = writeln!(run, "Eval vm_compute in {case}.");
        }
        std::fs::write(dir.join("Run.v"), run).map_err(|e| format!("cannot write Run.v: {e}"))?;
        let out = coqc(dir, "Run.v")?;
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
    drop(tmp);
    result
}

/// The verified checker's verdict on one certificate, by the extracted checker: `Ok((true,
/// program))` if it accepts, with the path of the checker program that ran
/// ([`extracted_checker`]).
pub fn coq_check(mdp: &Mdp, c: &Certificate) -> Result<(bool, PathBuf), String> {
    coq_applies(mdp, c)?;
    let program = extracted_checker()?;
    let verdict = extracted_verdict(&program, &checker_input(mdp, c))?;
    Ok((verdict, program))
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::{symlink, PermissionsExt};

    fn set_mode(path: &Path, mode: u32) {
        std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode)).unwrap();
    }

    #[test]
    fn a_cache_writable_by_others_or_a_link_is_refused_and_a_private_one_accepted() {
        let ours = work_dir().unwrap();
        let cache = tempfile::tempdir().unwrap();
        let binary = cache.path().join(CHECKER_NAME);
        std::fs::write(&binary, "#!/bin/sh\necho accepted\n").unwrap();
        set_mode(cache.path(), 0o700);
        set_mode(&binary, 0o755);
        assert_eq!(private(&[cache.path(), &binary], ours.path()), Ok(()));
        for (path, mode) in [(cache.path(), 0o777), (binary.as_path(), 0o775)] {
            set_mode(path, mode);
            let refusal = private(&[cache.path(), &binary], ours.path()).unwrap_err();
            assert!(refusal.contains("not private"), "{refusal}");
            assert!(refusal.contains(&format!("mode {mode:o}")), "{refusal}");
            set_mode(path, if path == cache.path() { 0o700 } else { 0o755 });
        }
        let link = cache.path().join("link");
        symlink(&binary, &link).unwrap();
        let refusal = private(&[&link], ours.path()).unwrap_err();
        assert!(refusal.contains("a symbolic link"), "{refusal}");
    }

    #[test]
    fn working_directories_are_private_and_unpredictable() {
        use std::os::unix::fs::MetadataExt;
        let (a, b) = (work_dir().unwrap(), work_dir().unwrap());
        assert_ne!(a.path(), b.path());
        assert_eq!(std::fs::metadata(a.path()).unwrap().mode() & 0o777, 0o700);
        let kept = a.path().to_path_buf();
        drop(a);
        assert!(!kept.exists());
    }
}

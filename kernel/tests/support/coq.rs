//! What the Coq bridge tests share: where the development is, how `coqc` is run, and how the
//! verdict of a `check_all` evaluation is read back.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The message when `coqc` cannot be run.
pub const NO_COQC: &str =
    "coqc not found: install Coq (Debian/Ubuntu: apt-get install -y coq; the README's prerequisites)";

/// `proofs/coq/`, or `TRUECOST_COQ_DIR`.
pub fn coq_dir() -> PathBuf {
    match std::env::var_os("TRUECOST_COQ_DIR") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("../proofs/coq"),
    }
}

/// A Coq list of the items.
pub fn list(items: impl Iterator<Item = String>) -> String {
    format!("[{}]", items.collect::<Vec<_>>().join("; "))
}

/// What Coq printed for `check_all`: problems checked, values compared, and the mismatches
/// `(problem, field, position)`.
#[derive(Debug)]
pub struct Verdict {
    pub problems: u64,
    pub values: u64,
    pub mismatches: Vec<(usize, String, usize)>,
}

/// Parses `= (388%nat, 9000%nat, [(3%nat, "h"%string, 1%nat); ...])`.
pub fn parse(out: &str) -> Option<Verdict> {
    let text: String = out.chars().filter(|c| !c.is_whitespace()).collect();
    let body = text.strip_prefix("=(")?;
    let body = &body[..body.find(":nat*nat*")?];
    let (problems, rest) = body.split_once("%nat,")?;
    let (values, rest) = rest.split_once("%nat,")?;
    let inner = rest.strip_prefix('[')?.strip_suffix("])")?;
    let mut mismatches = Vec::new();
    for item in inner.split(");").filter(|s| !s.is_empty()) {
        let item = item.trim_start_matches('(').trim_end_matches(')');
        let mut parts = item.split(',');
        let i = parts.next()?.strip_suffix("%nat")?.parse().ok()?;
        let what = parts.next()?.strip_suffix("%string")?.trim_matches('"');
        let k = parts.next()?.strip_suffix("%nat")?.parse().ok()?;
        mismatches.push((i, what.to_string(), k));
    }
    Some(Verdict {
        problems: problems.parse().ok()?,
        values: values.parse().ok()?,
        mismatches,
    })
}

/// Runs `cmd`, failing with [`NO_COQC`] when the program is missing and with its output when
/// it fails; returns its standard output.
pub fn run(cmd: &mut Command, what: &str) -> String {
    let out = match cmd.output() {
        Ok(out) => out,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => panic!("{NO_COQC}"),
        Err(e) => panic!("{what}: {e}"),
    };
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// Runs `make -C <dir> <target>`, one at a time within the test process (the tests of one
/// binary run in parallel and build in the same directory).
pub fn make(dir: &Path, target: &str) {
    static LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = LOCK.lock().unwrap_or_else(|e| e.into_inner());
    run(
        Command::new("make").arg("-C").arg(dir).arg(target),
        &format!("make -C {} {target}", dir.display()),
    );
}

/// Writes the Coq terms `cases` (one `(problem, expected)` pair each) as the list `problems` of
/// a file `work/<name>.v` that imports `bridge`, evaluates `check_all problems` with `coqc`,
/// and reads the verdict back.
pub fn check_all(dir: &Path, work: &Path, name: &str, bridge: &str, cases: &[String]) -> Verdict {
    let mut file = format!(
        "From Coq Require Import QArith List String.\nFrom Truecost Require Import Model {bridge}.\n\
         Import ListNotations.\nOpen Scope Q_scope.\n\n\
         Definition problems : list (problem * expected) := [\n"
    );
    for (i, c) in cases.iter().enumerate() {
        let sep = if i + 1 < cases.len() { ";" } else { "" };
        file.push_str(&format!("  {c}{sep}\n"));
    }
    file.push_str("].\n\nEval vm_compute in check_all problems.\n");
    let path = work.join(format!("{name}.v"));
    std::fs::write(&path, file).unwrap();
    let out = run(
        Command::new("coqc")
            .arg("-q")
            .arg("-no-glob")
            .arg("-R")
            .arg(dir)
            .arg("Truecost")
            .arg(&path)
            .current_dir(work),
        &format!("coqc {}", path.display()),
    );
    parse(&out).unwrap_or_else(|| panic!("unreadable Coq output:\n{out}"))
}

/// Checks that `coqc` runs, builds `target` (a `.vo` of the development and what it needs),
/// and makes a fresh working directory named for `tag`, this process and this test's thread:
/// `(the development's directory, the working directory)`.
pub fn prepare(target: &str, tag: &str) -> (PathBuf, PathBuf) {
    if Command::new("coqc").arg("--version").output().is_err() {
        panic!("{NO_COQC}");
    }
    let dir = coq_dir();
    make(&dir, target);
    let work = std::env::temp_dir().join(format!(
        "truecost-{tag}-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    std::fs::create_dir_all(&work).unwrap();
    (dir, work)
}

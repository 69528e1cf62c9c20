//! Running the `truecost` binary in the command-line tests.

use assert_cmd::Command;
use serde_json::Value;

/// The binary under test.
pub fn truecost() -> Command {
    Command::cargo_bin("truecost").unwrap()
}

/// Runs a command that must succeed; returns its stdout.
pub fn stdout(args: &[&str]) -> String {
    let out = truecost()
        .args(args)
        .assert()
        .success()
        .get_output()
        .clone();
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a command that must succeed and print JSON.
pub fn json(args: &[&str]) -> Value {
    serde_json::from_str(&stdout(args)).unwrap()
}

/// `solve --algorithm exact --objective OBJ --format json` on `source` (`--env SPEC` or
/// `--file F`, possibly with `--alpha A`).
pub fn solve_json(source: &[&str], objective: &str) -> Value {
    let mut args = vec!["solve"];
    args.extend_from_slice(source);
    args.extend_from_slice(&[
        "--algorithm",
        "exact",
        "--objective",
        objective,
        "--format",
        "json",
    ]);
    json(&args)
}

/// Runs a command that must fail cleanly with exit `code` (no panic, no backtrace, nothing on
/// stdout); our own errors (exit 1) are exactly one line starting with `error: `. Returns stderr.
pub fn fails<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S], code: i32) -> String {
    let out = truecost()
        .args(args)
        .assert()
        .code(code)
        .get_output()
        .clone();
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(!err.to_lowercase().contains("backtrace"), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}: nothing on stdout");
    if code == 1 {
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("error: "), "{args:?}: {err}");
    }
    err
}

/// [`fails`] with exit code 1.
pub fn fails_one_line<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(args: &[S]) -> String {
    fails(args, 1)
}

/// The line contract of a refusal: `error: ` and at most 300 characters, no raw control
/// character.
pub fn assert_contract(err: &str) {
    let line = err.trim_end_matches('\n');
    assert_eq!(line.lines().count(), 1, "{err:?}");
    let body = line.strip_prefix("error: ").expect("starts with 'error: '");
    assert!(
        body.chars().count() <= 300,
        "{} characters: {body}",
        body.len()
    );
    assert!(
        !body.chars().any(char::is_control),
        "raw control character: {body:?}"
    );
}

/// Writes `text` as `name` in `dir`.
pub fn write(dir: &std::path::Path, name: &str, text: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

//! `verify` with a planted bug that makes the kernel panic: the ρ = 1 update reads only the first
//! of its successor's pairs (`.iter().take(1)`), so the C1 enumeration's exploration of every
//! fair order meets values outside its packed range and panics. The workspace is copied to a
//! temporary directory, the bug planted there by a text replacement, and `truecost` built there
//! with the test profile (about 5 minutes on 2 busy cores, with this workspace's compiled
//! dependencies seeded; the release build of the same copy, which gives the same report, takes
//! as long again and is left out). The report must be whole: the failing engines' lines say
//! `engine failed`, the harnesses and the other engines still report, and `verify` exits with
//! a failure, not with the panic's exit status 101.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The ρ = 1 update's read of the successor's pairs, and the planted bug.
const UPDATE: &str = "for &value in &v[self.first[y]..self.first[y + 1]] {";
const PLANTED: &str = "for &value in v[self.first[y]..self.first[y + 1]].iter().take(1) {";

fn workspace() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Copies `from` into `to`, leaving out build outputs and git's data.
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name();
        if name == "target" || name == ".git" {
            continue;
        }
        let (src, dst) = (entry.path(), to.join(&name));
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&src, &dst);
        } else {
            std::fs::copy(&src, &dst).unwrap();
        }
    }
}

/// Seeds the copy's target directory with this workspace's compiled dependencies, so that only
/// the workspace's own crates are compiled (their outputs are named after the copy's paths).
/// Small files (fingerprints, dep-info, build-script outputs: Cargo may rewrite them in place)
/// are copied; the large compiled libraries are hard-linked when both are on one file system
/// (a rebuilt library is written as a new file), else copied.
fn seed(from: &Path, to: &Path) {
    let Ok(entries) = std::fs::read_dir(from) else {
        return;
    };
    std::fs::create_dir_all(to).unwrap();
    for entry in entries.flatten() {
        let (src, dst) = (entry.path(), to.join(entry.file_name()));
        let Ok(meta) = entry.metadata() else { continue };
        if meta.is_dir() {
            seed(&src, &dst);
        } else if meta.len() < 1 << 20 || std::fs::hard_link(&src, &dst).is_err() {
            // Cargo compares modification times: a copy keeps the original's.
            let copied = std::fs::copy(&src, &dst).and_then(|_| {
                std::fs::File::options()
                    .write(true)
                    .open(&dst)?
                    .set_modified(meta.modified()?)
            });
            copied.unwrap();
        }
    }
}

/// Builds the planted copy's `truecost` with the test profile and runs `verify --claim C1`
/// with it; returns (exit code, stdout, stderr).
fn build_and_verify(copy: &Path, target: &Path) -> (Option<i32>, String, String) {
    let (profile, dir) = ("test", "debug");
    let own_target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace().join("target"));
    for sub in ["deps", "build", ".fingerprint"] {
        seed(&own_target.join(dir).join(sub), &target.join(dir).join(sub));
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let started = std::time::Instant::now();
    let built = Command::new(cargo)
        .args(["build", "--quiet", "--offline", "--profile", profile])
        .args(["--bin", "truecost"])
        .current_dir(copy)
        .env("CARGO_TARGET_DIR", target)
        .output()
        .unwrap();
    assert!(
        built.status.success(),
        "{}",
        String::from_utf8_lossy(&built.stderr)
    );
    eprintln!(
        "built the planted copy ({profile} profile) in {:.0} s",
        started.elapsed().as_secs_f64()
    );
    let out = Command::new(target.join(dir).join("truecost"))
        .args(["verify", "--claim", "C1", "--scope", "smoke", "--no-coq"])
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

/// What the report of the planted build must say.
fn check_report((code, stdout, stderr): &(Option<i32>, String, String)) {
    let ctx = format!("exit {code:?}\nstdout:\n{stdout}\nstderr:\n{stderr}");
    assert_ne!(*code, Some(101), "the panic escaped: {ctx}");
    assert_ne!(*code, Some(0), "a failed engine must fail the run: {ctx}");
    assert!(code.is_some(), "killed by a signal: {ctx}");
    assert!(!stderr.contains("internal error"), "{ctx}");
    assert!(!stderr.contains("panicked at"), "{ctx}");
    // The enumeration of each claim of C1 panicked: one line each, with the panic's message
    // and the kernel's source line.
    for claim in ["C1", "C1-corrected"] {
        let section = stdout
            .split("\n\n")
            .find(|s| s.starts_with(&format!("{claim}  ")))
            .unwrap_or_else(|| panic!("no section for {claim}: {ctx}"));
        assert!(
            section.starts_with(&format!("{claim}  INCONCLUSIVE\n")),
            "{ctx}"
        );
        let failed: Vec<&str> = section
            .lines()
            .filter(|l| l.starts_with("  engine: exhaustive enumeration: engine failed: "))
            .collect();
        assert_eq!(failed.len(), 1, "{ctx}");
        assert!(
            failed[0].contains("value out of the packed range")
                && failed[0].contains("kernel/src/claims/qlearning.rs:"),
            "{ctx}"
        );
        // Every harness of the claim and its proptest run still report.
        let harness_lines = section
            .lines()
            .filter(|l| l.starts_with("  engine: kani harness "))
            .count();
        let expected = if claim == "C1" { 1 } else { 3 };
        assert_eq!(harness_lines, expected, "{ctx}");
        assert!(section.contains("\n  engine: proptest"), "{ctx}");
        assert!(section.contains("\n  engine: smt (Z3)"), "{ctx}");
    }
    // The corrected claim's harnesses run the planted update: the stand-in finds it failing.
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("  engine: kani harness c1_corrected_")
                && l.contains("HARNESS FAILS")),
        "{ctx}"
    );
    // The rest of the report follows: the worked example's alpha*.
    assert!(stdout.contains("\nalpha* = "), "{ctx}");
}

/// The planted `.take(1)` in the ρ = 1 update, built with the test profile: `verify --claim
/// C1` reports the enumeration's panic as its engine line and exits with a failure after a
/// whole report.
#[test]
fn a_panicking_kernel_gives_engine_failed_lines_and_a_whole_report() {
    let tmp = tempfile::tempdir().unwrap();
    let copy = tmp.path().join("ws");
    copy_tree(&workspace(), &copy);
    let update = copy.join("kernel/src/claims/qlearning.rs");
    let text = std::fs::read_to_string(&update).unwrap();
    assert_eq!(text.matches(UPDATE).count(), 1, "the update's loop moved");
    std::fs::write(&update, text.replace(UPDATE, PLANTED)).unwrap();
    let target = tmp.path().join("target");
    check_report(&build_and_verify(&copy, &target));
}

//! Output files are written whole through a temporary file that cannot be predicted and is
//! created with `O_EXCL` beside the target, so a symlink planted where a temporary file could
//! be is never followed; a symlink at the target is replaced, never written through; devices
//! other than terminals are refused; no directory is created; a temporary directory (TMPDIR)
//! that does not exist is not created either.

use std::path::Path;
use std::process::Command;

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_truecost")
}

fn export(out: &Path) -> std::process::Output {
    Command::new(bin())
        .args(["export", "--grid", "3x3", "--out"])
        .arg(out)
        .output()
        .unwrap()
}

fn one_line_refusal(o: &std::process::Output) -> String {
    assert!(!o.status.success(), "accepted");
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

/// Symlinks planted at every name a process-numbered temporary file would take
/// (`.truecost-<pid>-out.json` for the next 3000 process ids) to a victim file: the export
/// writes its own file, and the victim and every planted link stay as they were.
#[test]
fn planted_symlinks_are_never_followed() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "victim\n").unwrap();
    let next: u32 = std::fs::read_to_string("/proc/sys/kernel/ns_last_pid")
        .ok()
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(std::process::id());
    let planted: Vec<_> = (next..next + 3000)
        .map(|pid| dir.path().join(format!(".truecost-{pid}-out.json")))
        .collect();
    for link in &planted {
        std::os::unix::fs::symlink(&victim, link).unwrap();
    }
    let out = dir.path().join("out.json");
    let o = export(&out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "victim\n");
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.starts_with('{') && text.ends_with("}\n"), "{text}");
    for link in &planted {
        let meta = std::fs::symlink_metadata(link).unwrap();
        assert!(meta.file_type().is_symlink(), "{} replaced", link.display());
    }
    // Nothing else left beside the target: the victim, the links and the output.
    let count = std::fs::read_dir(dir.path()).unwrap().count();
    assert_eq!(count, planted.len() + 2, "a temporary file was left");
}

/// A symlink at the target itself is replaced by the new file; the file it pointed to is
/// untouched.
#[test]
fn a_symlink_at_the_target_is_replaced_not_followed() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "victim\n").unwrap();
    let out = dir.path().join("out.json");
    std::os::unix::fs::symlink(&victim, &out).unwrap();
    let o = export(&out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "victim\n");
    let meta = std::fs::symlink_metadata(&out).unwrap();
    assert!(meta.file_type().is_file());
    assert!(std::fs::read_to_string(&out).unwrap().starts_with('{'));
}

/// Devices that are not terminals (`/dev/full`, `/dev/null`, or a symlink to one) are refused
/// in one line naming the path and the kind of file, before any work; nothing replaces them.
#[test]
fn devices_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let link = dir.path().join("full.json");
    std::os::unix::fs::symlink("/dev/full", &link).unwrap();
    for target in [
        Path::new("/dev/full"),
        Path::new("/dev/null"),
        link.as_path(),
    ] {
        let err = one_line_refusal(&export(target));
        assert!(
            err.contains("character device that is not a terminal"),
            "{err}"
        );
        assert!(err.contains(&target.display().to_string()), "{err}");
    }
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
}

/// An output in a directory that does not exist is refused; the directory is not created.
#[test]
fn no_directory_is_created() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("missing/deeper/out.json");
    let err = one_line_refusal(&export(&out));
    assert!(err.contains("cannot write"), "{err}");
    assert!(!dir.path().join("missing").exists());
}

/// The Coq bridge's scratch directory lives under the temporary directory; a TMPDIR that does
/// not exist is an error, never created (run in a child process, so that no other test sees
/// the variable).
#[test]
fn a_missing_tmpdir_is_not_created() {
    if std::env::var_os("TRUECOST_TMPDIR_CHILD").is_some() {
        let made = truecost::claims::coq::process::TempDir::new();
        let err = made.err().expect("no directory under a missing TMPDIR");
        assert!(err.contains("cannot create"), "{err}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/tmp");
    let o = Command::new(std::env::current_exe().unwrap())
        .args(["a_missing_tmpdir_is_not_created", "--exact", "--nocapture"])
        .env("TRUECOST_TMPDIR_CHILD", "1")
        .env("TMPDIR", &missing)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout) + String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("1 passed"),
        "the child ran the test"
    );
    assert!(!dir.path().join("no").exists(), "TMPDIR was created");
}

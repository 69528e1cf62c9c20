//! Writing output files whole.
//!
//! A report, figure or problem file is written to a temporary file beside its target and then
//! renamed over it, so that a full disk, a write error or an interrupted run leaves either the
//! old file or the new one — never a truncated one. Targets that are not regular files
//! (`/dev/stdout`, a pipe) cannot be replaced by a rename and are written directly.

use std::path::{Path, PathBuf};

/// The temporary file beside `path`: hidden, named after this process, and ending in the same
/// file name (so its extension still chooses the encoder of whatever writes it).
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".truecost-{}-{name}", std::process::id()))
}

/// Whether `path` names something a rename must not replace (a device, a pipe, a socket).
fn special(path: &Path) -> bool {
    std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Produces the file at `path` by calling `write` on a temporary path beside it and renaming
/// the result over `path`; on any error the temporary file is removed and `path` is left as it
/// was (a failed rename gives the I/O error's text). A special target (`/dev/stdout`, a FIFO)
/// is written directly.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("report.json");
/// std::fs::write(&path, "old").unwrap();
/// let failed: Result<(), String> = truecost::atomic::replace_with(&path, |tmp| {
///     std::fs::write(tmp, "half a rep").unwrap();
///     Err("disk full".to_string())
/// });
/// assert!(failed.is_err());
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
/// assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file left");
/// ```
pub fn replace_with<E: From<String>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    if special(path) {
        return write(path);
    }
    let tmp = temporary(path);
    let result =
        write(&tmp).and_then(|()| std::fs::rename(&tmp, path).map_err(|e| E::from(e.to_string())));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// Checks, before any work, that [`write()`] or [`replace_with`] will be able to produce `path`:
/// it is not a directory, its directory exists, and a file can be created there (a read-only
/// disk or a missing permission is found now, not after a long run). Special targets
/// (`/dev/stdout`) pass.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// assert!(truecost::atomic::check_target(&dir.path().join("x.json")).is_ok());
/// let err = truecost::atomic::check_target(dir.path()).unwrap_err();
/// assert!(err.contains("is a directory"), "{err}");
/// let err = truecost::atomic::check_target(&dir.path().join("no/x.json")).unwrap_err();
/// assert!(err.contains("cannot write"), "{err}");
/// ```
pub fn check_target(path: &Path) -> Result<(), String> {
    let shown = || crate::echo::echo(&path.display().to_string());
    if special(path) {
        return Ok(());
    }
    if path.is_dir() {
        return Err(format!("cannot write {}: it is a directory", shown()));
    }
    let probe = temporary(path);
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| format!("cannot write {}: {e}", shown()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Writes `bytes` to `path` whole ([`replace_with`]); the error names the path. A pipe whose
/// reader has closed it is not an error (as for the reports on stdout).
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("x.json");
/// truecost::atomic::write(&path, b"{}\n").unwrap();
/// assert_eq!(std::fs::read(&path).unwrap(), b"{}\n");
/// let err = truecost::atomic::write(&dir.path().join("missing/x.json"), b"{}").unwrap_err();
/// assert!(err.starts_with("cannot write"), "{err}");
/// ```
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    replace_with(path, |tmp| match std::fs::write(tmp, bytes) {
        // A pipe closed by its reader (`--out /dev/stdout | head`) took what it wanted.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe && special(tmp) => Ok(()),
        other => other.map_err(|e| e.to_string()),
    })
    .map_err(|e| {
        format!(
            "cannot write {}: {e}",
            crate::echo::echo(&path.display().to_string())
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_good_file_is_replaced_only_by_a_complete_one() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        write(&path, b"first").unwrap();
        write(&path, b"second").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.txt")]);
    }

    #[test]
    fn the_temporary_file_keeps_the_extension_and_is_hidden() {
        let t = temporary(Path::new("out/fig.png"));
        assert_eq!(t.extension().unwrap(), "png");
        assert_eq!(t.parent().unwrap(), Path::new("out"));
        assert!(t
            .file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with(".truecost-"));
    }

    #[test]
    fn special_files_are_written_directly() {
        assert!(special(Path::new("/dev/null")));
        assert!(!special(Path::new("/no/such/file")));
        write(Path::new("/dev/null"), b"anything").unwrap();
    }
}

//! Writing output files whole.
//!
//! A report, figure or problem file is written to a temporary file beside its target and then
//! renamed over it, so that a full disk, a write error or an interrupted run leaves either the
//! old file or the new one — never a truncated one. The temporary file has an unpredictable
//! name and is created with `O_EXCL` (the `tempfile` crate), so a symlink planted beside the
//! target is never followed; the rename replaces a symlink at the target itself, never the file
//! it points to. Targets that a rename must not replace are written directly when they are a
//! pipe, a socket or a terminal (`/dev/stdout`, a FIFO), and refused otherwise (a device such as
//! `/dev/full`). No directory is ever created.

use std::io::Write;
use std::path::{Path, PathBuf};

mod direct;
pub use direct::DirectFile;

/// What an output path names.
enum Target {
    /// Nothing yet, or a regular file: produced by a rename.
    Replace,
    /// A pipe, a socket or a terminal: written directly.
    Stream,
    /// A directory.
    Directory,
    /// Another special file (a device that is not a terminal): refused.
    Refused(&'static str),
}

/// What `path` names, following symlinks (`/dev/stdout` → a pipe or a terminal).
fn target(path: &Path) -> Target {
    use std::os::unix::fs::FileTypeExt;
    let Ok(meta) = std::fs::metadata(path) else {
        return Target::Replace;
    };
    let kind = meta.file_type();
    if kind.is_file() {
        Target::Replace
    } else if kind.is_dir() {
        Target::Directory
    } else if kind.is_fifo() || kind.is_socket() || (kind.is_char_device() && terminal(path)) {
        Target::Stream
    } else if kind.is_char_device() {
        Target::Refused("a character device that is not a terminal")
    } else if kind.is_block_device() {
        Target::Refused("a block device")
    } else {
        Target::Refused("not a regular file")
    }
}

/// Whether `path` opens (for writing, without creating or truncating) as a terminal.
fn terminal(path: &Path) -> bool {
    use std::io::IsTerminal;
    std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .is_ok_and(|f| f.is_terminal())
}

/// The refusal of a directory or a device as an output file.
fn refusal(path: &Path, target: &Target) -> Option<String> {
    let shown = || crate::echo::echo(&path.display().to_string());
    match target {
        Target::Directory => Some(format!("cannot write {}: it is a directory", shown())),
        Target::Refused(what) => Some(format!(
            "cannot write {}: it is {what}; an output file is a regular file (replaced whole), a pipe or a terminal",
            shown()
        )),
        Target::Replace | Target::Stream => None,
    }
}

/// A new, empty temporary file beside `path`, created with `O_EXCL` under an unpredictable
/// name: hidden, `.truecost-<random>-<file name>` (so its extension still chooses the encoder
/// of whatever writes it). Removed when dropped unless persisted.
fn temporary(path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    use std::os::unix::fs::PermissionsExt;
    // Mode 0666 less the umask, as a file created by `std::fs::write` (not tempfile's 0600).
    tempfile::Builder::new()
        .permissions(std::fs::Permissions::from_mode(0o666))
        .prefix(".truecost-")
        .suffix(&format!("-{name}"))
        .rand_bytes(12)
        .tempfile_in(dir)
}

/// Produces the file at `path` by calling `write` on a new temporary file beside it
/// (`temporary`: unpredictable name, created with `O_EXCL`) and renaming the result over
/// `path`; on any error the temporary file is removed and `path` is left as it was (a failed
/// rename gives the I/O error's text). A pipe, socket or terminal (`/dev/stdout`, a FIFO) is
/// written directly; a directory or another special file (a device) is refused.
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
    let kind = target(path);
    if let Some(e) = refusal(path, &kind) {
        return Err(E::from(e));
    }
    if let Target::Stream = kind {
        return write(path);
    }
    let tmp = temporary(path).map_err(|e| E::from(e.to_string()))?;
    write(tmp.path())?;
    tmp.persist(path)
        .map(drop)
        .map_err(|e| E::from(e.error.to_string()))
}

/// Checks, before any work, that [`write()`] or [`replace_with`] will be able to produce `path`:
/// it is not a directory or a device, its directory exists, and a file can be created there (a
/// read-only disk or a missing permission is found now, not after a long run). Pipes and
/// terminals (`/dev/stdout`) pass.
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
    let kind = target(path);
    if let Some(e) = refusal(path, &kind) {
        return Err(e);
    }
    if let Target::Replace = kind {
        temporary(path).map_err(|e| {
            format!(
                "cannot write {}: {e}",
                crate::echo::echo(&path.display().to_string())
            )
        })?;
    }
    Ok(())
}

/// Writes `bytes` to `path` whole ([`replace_with`]: through the temporary file's own handle,
/// never reopened by name); the error names the path. A pipe whose reader has closed it is not
/// an error (as for the reports on stdout).
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
    let shown = || crate::echo::echo(&path.display().to_string());
    let kind = target(path);
    if let Some(e) = refusal(path, &kind) {
        return Err(e);
    }
    let failed = |e: std::io::Error| format!("cannot write {}: {e}", shown());
    if let Target::Stream = kind {
        return match std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .and_then(|mut f| f.write_all(bytes))
        {
            // A pipe closed by its reader (`--out /dev/stdout | head`) took what it wanted.
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
            other => other.map_err(failed),
        };
    }
    let mut tmp = temporary(path).map_err(failed)?;
    tmp.write_all(bytes)
        .and_then(|()| tmp.as_file().sync_data())
        .map_err(failed)?;
    tmp.persist(path).map(drop).map_err(|e| failed(e.error))
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
    fn the_temporary_file_keeps_the_extension_and_is_hidden_and_unpredictable() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("fig.png");
        let (a, b) = (temporary(&target).unwrap(), temporary(&target).unwrap());
        for t in [&a, &b] {
            assert_eq!(t.path().extension().unwrap(), "png");
            assert_eq!(t.path().parent().unwrap(), dir.path());
            let name = t.path().file_name().unwrap().to_string_lossy().into_owned();
            assert!(
                name.starts_with(".truecost-") && name.ends_with("-fig.png"),
                "{name}"
            );
            assert!(!name.contains(&std::process::id().to_string()), "{name}");
        }
        assert_ne!(a.path(), b.path());
    }

    #[test]
    fn devices_other_than_terminals_are_refused_and_nothing_is_written() {
        let err = write(Path::new("/dev/full"), b"anything").unwrap_err();
        assert!(err.contains("character device"), "{err}");
        let err = check_target(Path::new("/dev/null")).unwrap_err();
        assert!(err.contains("not a terminal"), "{err}");
    }
}

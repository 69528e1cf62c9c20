//! Reading files with a byte limit.
//!
//! Every file truecost reads — problem files, map files, shard files, the π digit cache — may be
//! `/dev/zero`, a pipe fed without end or simply huge. Each reader states a limit and reads at
//! most one byte past it, so that memory stays bounded whatever the path names, and a file over
//! the limit is refused with one line naming the limit.

use std::io::Read;
use std::path::Path;

use crate::echo::echo;

/// Why a bounded read failed.
#[derive(Debug, thiserror::Error)]
pub enum BoundedError {
    /// The file could not be opened or read.
    #[error("cannot read {}: {source}", echo(.path))]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// The file has more than `limit` bytes.
    #[error("{} is larger than {limit} bytes, the limit for {what}", echo(.path))]
    TooLarge {
        /// The path.
        path: String,
        /// The limit, in bytes.
        limit: u64,
        /// What kind of file was expected (`map files`, `shard files`).
        what: &'static str,
    },
    /// The file is not valid UTF-8.
    #[error("{} is not UTF-8 text", echo(.path))]
    NotText {
        /// The path.
        path: String,
    },
}

/// The bytes of `path`, at most `limit` of them: a longer file (or an endless stream) is
/// refused after reading `limit + 1` bytes. `what` names the kind of file in the refusal.
///
/// ```
/// use truecost::bounded::{read_bytes, BoundedError};
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("f");
/// std::fs::write(&path, b"12345").unwrap();
/// assert_eq!(read_bytes(&path, 5, "test files").unwrap(), b"12345");
/// let err = read_bytes(&path, 4, "test files").unwrap_err();
/// assert!(matches!(err, BoundedError::TooLarge { limit: 4, .. }));
/// ```
pub fn read_bytes(path: &Path, limit: u64, what: &'static str) -> Result<Vec<u8>, BoundedError> {
    let io = |source| BoundedError::Io {
        path: path.display().to_string(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(BoundedError::TooLarge {
            path: path.display().to_string(),
            limit,
            what,
        });
    }
    Ok(bytes)
}

/// [`read_bytes`] as UTF-8 text.
///
/// ```
/// use truecost::bounded::{read_text, BoundedError};
/// let err = read_text(std::path::Path::new("/dev/zero"), 1 << 10, "map files").unwrap_err();
/// assert!(err.to_string().contains("larger than 1024 bytes, the limit for map files"));
/// ```
pub fn read_text(path: &Path, limit: u64, what: &'static str) -> Result<String, BoundedError> {
    String::from_utf8(read_bytes(path, limit, what)?).map_err(|_| BoundedError::NotText {
        path: path.display().to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_endless_stream_is_refused_after_the_limit() {
        let err = read_bytes(Path::new("/dev/zero"), 4096, "shard files").unwrap_err();
        match err {
            BoundedError::TooLarge { limit, what, .. } => {
                assert_eq!((limit, what), (4096, "shard files"))
            }
            other => panic!("expected TooLarge, got {other}"),
        }
    }

    #[test]
    fn a_missing_file_and_invalid_text_are_named() {
        let err = read_text(Path::new("/no/such\nfile"), 10, "map files").unwrap_err();
        assert!(matches!(err, BoundedError::Io { .. }));
        assert!(err.to_string().contains("/no/such\\nfile"), "{err}");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bin");
        std::fs::write(&path, [0xff, 0xfe]).unwrap();
        let err = read_text(&path, 10, "map files").unwrap_err();
        assert!(matches!(err, BoundedError::NotText { .. }), "{err}");
    }

    #[test]
    fn a_file_of_exactly_the_limit_is_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f");
        std::fs::write(&path, "abc").unwrap();
        assert_eq!(read_text(&path, 3, "test files").unwrap(), "abc");
        assert!(read_text(&path, 2, "test files").is_err());
    }
}

//! A new file written around the page cache (`O_DIRECT`), for outputs of hundreds of
//! megabytes (a certificate's values at 10⁴ states).
//!
//! Written through the page cache, every byte of such a file is copied by the kernel into
//! cache pages and later written back: on the project's machine about as much processor time
//! (system time) per megabyte as making the text. With `O_DIRECT` the disk reads the bytes from
//! the process's own buffer. Such writes need blocks aligned in memory, in length and in the
//! file ([`BLOCK`]): [`DirectFile`] gathers the bytes into aligned chunks, hands each full chunk
//! to a thread that writes it while the next one is filled, writes the last chunk padded to a
//! whole block and cuts the file back to its length. Where the file system refuses `O_DIRECT`
//! (on opening, or on the first write) the file is written through the page cache as usual:
//! the bytes written are the same either way.

use std::fs::File;
use std::io::{self, Write};
use std::path::Path;
use std::thread::JoinHandle;

/// The alignment of `O_DIRECT` transfers: buffer addresses, lengths and file offsets are
/// multiples of it (4096 bytes, the page size and the largest logical block size of common
/// disks).
pub const BLOCK: usize = 4096;

/// Bytes gathered before a chunk is handed to the writing thread (a multiple of [`BLOCK`]).
const CHUNK: usize = 1 << 22;

/// A byte buffer of `len` bytes whose first byte is [`BLOCK`]-aligned (safe code: a `Vec`
/// one block longer, used from its first aligned byte).
struct Aligned {
    storage: Vec<u8>,
    start: usize,
    len: usize,
}

impl Aligned {
    fn new(len: usize) -> Aligned {
        let storage = vec![0u8; len + BLOCK];
        let start = storage.as_ptr().align_offset(BLOCK);
        assert!(start < BLOCK, "a byte buffer can be aligned to {BLOCK}");
        Aligned {
            storage,
            start,
            len,
        }
    }

    fn bytes(&self) -> &[u8] {
        &self.storage[self.start..self.start + self.len]
    }

    fn bytes_mut(&mut self) -> &mut [u8] {
        &mut self.storage[self.start..self.start + self.len]
    }
}

/// A chunk being written by its thread: the file and the buffer come back when it is done.
type InFlight = JoinHandle<(File, Aligned, io::Result<()>)>;

/// A new regular file written with `O_DIRECT` where the file system allows it (see the module
/// docs); [`DirectFile::finish`] must be called to write the last bytes.
///
/// ```
/// use std::io::Write;
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("values.json");
/// let mut out = truecost::atomic::DirectFile::create(&path).unwrap();
/// out.write_all(&vec![b'7'; 10_000]).unwrap();
/// out.write_all(b"\n").unwrap();
/// out.finish().unwrap();
/// let text = std::fs::read(&path).unwrap();
/// assert_eq!(text.len(), 10_001);
/// assert!(text[..10_000].iter().all(|&b| b == b'7') && text[10_000] == b'\n');
/// ```
pub struct DirectFile {
    /// The file, while no chunk is in flight.
    file: Option<File>,
    /// The chunk being filled and how many of its bytes are filled.
    chunk: Aligned,
    filled: usize,
    /// The second buffer, while no chunk is in flight.
    spare: Option<Aligned>,
    in_flight: Option<InFlight>,
    /// Bytes handed to the file (all in whole chunks).
    written: u64,
    /// Whether the file is open with `O_DIRECT`.
    direct: bool,
}

impl DirectFile {
    /// Creates `path` anew (`O_CREAT | O_EXCL`, mode 0666 less the umask: no file that exists
    /// is opened, no symbolic link followed), with `O_DIRECT` where the file system takes it.
    pub fn create(path: &Path) -> io::Result<DirectFile> {
        let (file, direct) = match open_new(path, true) {
            Ok(file) => (file, true),
            Err(e) if e.raw_os_error() == Some(EINVAL) => {
                // The file system refused O_DIRECT after creating the file: ours, empty.
                std::fs::remove_file(path)?;
                (open_new(path, false)?, false)
            }
            Err(e) => return Err(e),
        };
        Ok(DirectFile::over(file, direct))
    }

    fn over(file: File, direct: bool) -> DirectFile {
        DirectFile {
            file: Some(file),
            chunk: Aligned::new(CHUNK),
            filled: 0,
            spare: Some(Aligned::new(CHUNK)),
            in_flight: None,
            written: 0,
            direct,
        }
    }

    /// Whether the bytes go around the page cache (`O_DIRECT`); when `false` they go through
    /// it, with the same result in the file.
    pub fn is_direct(&self) -> bool {
        self.direct
    }

    /// Waits for the chunk in flight, if any: the file and the spare buffer are back.
    fn settle(&mut self) -> io::Result<()> {
        if let Some(handle) = self.in_flight.take() {
            let (file, buffer, result) = handle
                .join()
                .map_err(|_| io::Error::other("the thread writing the file stopped"))?;
            self.file = Some(file);
            self.spare = Some(buffer);
            result?;
        }
        Ok(())
    }

    /// Hands the full chunk to a thread that writes it, and goes on with the spare buffer.
    fn hand_over(&mut self) -> io::Result<()> {
        self.settle()?;
        let (Some(mut file), Some(spare)) = (self.file.take(), self.spare.take()) else {
            return Err(io::Error::other("the file was lost by an earlier error"));
        };
        let full = std::mem::replace(&mut self.chunk, spare);
        self.filled = 0;
        self.written += full.len as u64;
        if !self.direct {
            let result = file.write_all(full.bytes());
            self.file = Some(file);
            self.spare = Some(full);
            return result;
        }
        self.in_flight = Some(std::thread::spawn(move || {
            let result = write_direct(&mut file, full.bytes());
            (file, full, result)
        }));
        Ok(())
    }

    /// Writes what is left, cuts the file to its length and waits for its data to be on disk
    /// (`sync_data`); returns the file.
    pub fn finish(mut self) -> io::Result<File> {
        self.settle()?;
        let mut file = self
            .file
            .take()
            .ok_or_else(|| io::Error::other("the file was lost by an earlier error"))?;
        let length = self.written + self.filled as u64;
        if self.direct {
            let padded = self.filled.div_ceil(BLOCK) * BLOCK;
            let bytes = self.chunk.bytes_mut();
            bytes[self.filled..padded].fill(0);
            write_direct(&mut file, &bytes[..padded])?;
            file.set_len(length)?;
        } else {
            file.write_all(&self.chunk.bytes()[..self.filled])?;
        }
        file.sync_data()?;
        Ok(file)
    }
}

impl Write for DirectFile {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        let room = CHUNK - self.filled;
        let n = bytes.len().min(room);
        self.chunk.bytes_mut()[self.filled..self.filled + n].copy_from_slice(&bytes[..n]);
        self.filled += n;
        if self.filled == CHUNK {
            self.hand_over()?;
        }
        Ok(n)
    }

    /// Chunks are written whole by [`DirectFile::finish`]; a flush waits for the one in flight.
    fn flush(&mut self) -> io::Result<()> {
        self.settle()
    }
}

impl Drop for DirectFile {
    fn drop(&mut self) {
        // Never leave a thread writing to a file the caller is about to remove.
        let _ = self.settle();
    }
}

/// `EINVAL`: what Linux answers to `O_DIRECT` where a file system cannot do it.
const EINVAL: i32 = 22;

#[cfg(target_os = "linux")]
const O_DIRECT: i32 = libc::O_DIRECT;
#[cfg(not(target_os = "linux"))]
const O_DIRECT: i32 = 0;

/// Creates `path` anew (`O_CREAT | O_EXCL`, mode 0666), with `O_DIRECT` if `direct`.
fn open_new(path: &Path, direct: bool) -> io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .mode(0o666)
        .custom_flags(if direct { O_DIRECT } else { 0 })
        .open(path)
}

/// Writes whole aligned blocks with the file open for `O_DIRECT`; if the file system refuses
/// the first such write (`EINVAL`: an alignment it cannot take), the file is switched to
/// ordinary writes and the bytes go through the page cache.
fn write_direct(file: &mut File, bytes: &[u8]) -> io::Result<()> {
    match file.write_all(bytes) {
        Err(e) if e.raw_os_error() == Some(EINVAL) => {
            without_direct(file)?;
            file.write_all(bytes)
        }
        other => other,
    }
}

/// Clears `O_DIRECT` on an open file (`fcntl(F_SETFL)`).
#[cfg(target_os = "linux")]
fn without_direct(file: &File) -> io::Result<()> {
    use std::os::fd::AsRawFd;
    let fd = file.as_raw_fd();
    // SAFETY: `fd` is an open descriptor owned by `file` for the whole call; F_GETFL and
    // F_SETFL read and set its status flags and touch no memory of this process.
    let flags = unsafe { libc::fcntl(fd, libc::F_GETFL) };
    if flags < 0 {
        return Err(io::Error::last_os_error());
    }
    // SAFETY: as above.
    if unsafe { libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_DIRECT) } < 0 {
        return Err(io::Error::last_os_error());
    }
    Ok(())
}

#[cfg(not(target_os = "linux"))]
fn without_direct(_file: &File) -> io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic bytes (a linear congruential sequence), so that a misplaced chunk shows.
    fn bytes(n: usize, seed: u64) -> Vec<u8> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 56) as u8
            })
            .collect()
    }

    /// Writes `pieces` (cut from one text) and reads the file back.
    fn round_trip(path: &Path, text: &[u8], cuts: &[usize]) -> Vec<u8> {
        let mut out = DirectFile::create(path).unwrap();
        let mut at = 0;
        for &cut in cuts {
            out.write_all(&text[at..cut]).unwrap();
            at = cut;
        }
        out.write_all(&text[at..]).unwrap();
        out.finish().unwrap();
        std::fs::read(path).unwrap()
    }

    #[test]
    fn every_length_around_blocks_and_chunks_reads_back_byte_for_byte() {
        let dir = tempfile::tempdir().unwrap();
        let lengths = [
            0,
            1,
            BLOCK - 1,
            BLOCK,
            BLOCK + 1,
            CHUNK - 1,
            CHUNK,
            CHUNK + 1,
            2 * CHUNK + 3 * BLOCK + 17,
        ];
        for (i, &n) in lengths.iter().enumerate() {
            let text = bytes(n, i as u64 + 1);
            let path = dir.path().join(format!("f{i}"));
            // Cuts that straddle chunk boundaries and single bytes.
            let cuts: Vec<usize> = [n / 3, n / 2, n / 2 + 1, (2 * n) / 3]
                .into_iter()
                .filter(|&c| c <= n)
                .collect();
            let mut sorted = cuts.clone();
            sorted.sort_unstable();
            assert_eq!(round_trip(&path, &text, &sorted), text, "length {n}");
        }
    }

    #[test]
    fn direct_writes_are_used_wherever_the_file_system_takes_them() {
        let dir = tempfile::tempdir().unwrap();
        let takes = open_new(&dir.path().join("probe"), true).is_ok();
        let out = DirectFile::create(&dir.path().join("f")).unwrap();
        assert_eq!(out.is_direct(), takes && O_DIRECT != 0);
    }

    #[test]
    fn an_existing_file_is_never_opened() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("taken");
        std::fs::write(&path, b"keep").unwrap();
        let err = DirectFile::create(&path).err().expect("refused");
        assert_eq!(err.kind(), io::ErrorKind::AlreadyExists);
        assert_eq!(std::fs::read(&path).unwrap(), b"keep");
    }

    #[test]
    fn a_file_written_through_the_page_cache_is_the_same() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("cached");
        let file = open_new(&path, false).unwrap();
        let mut out = DirectFile::over(file, false);
        assert!(!out.is_direct());
        let text = bytes(CHUNK + 5 * BLOCK + 3, 9);
        out.write_all(&text).unwrap();
        out.finish().unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), text);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_refused_direct_write_falls_back_to_the_page_cache() {
        // A buffer that is not aligned: every O_DIRECT file system refuses it (EINVAL).
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("fallback");
        let Ok(mut file) = open_new(&path, true) else {
            return assert!(open_new(&dir.path().join("plain"), false).is_ok());
        };
        let storage = bytes(3 * BLOCK, 5);
        let start = storage.as_ptr().align_offset(BLOCK) + 1;
        let unaligned = &storage[start..start + BLOCK];
        write_direct(&mut file, unaligned).unwrap();
        write_direct(&mut file, &storage[..7]).unwrap();
        drop(file);
        let mut expected = unaligned.to_vec();
        expected.extend_from_slice(&storage[..7]);
        assert_eq!(std::fs::read(&path).unwrap(), expected);
    }
}

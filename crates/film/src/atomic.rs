//! Atomic file output: the bytes go to a temporary file in the target's own directory, which
//! is synced and only then given the target's name, so the target is either its old self
//! (absent if it did not exist) or the complete new file.
//!
//! On Linux the temporary file is unnamed (`O_TMPFILE`): it has no name while it is written,
//! so a process killed at any moment there (even by SIGKILL) leaves nothing behind. When it
//! is complete it is linked (`linkat`) to a unique temporary name and renamed over the target:
//! `linkat` cannot replace an existing file, and the instant between the two calls is the only
//! one in which a kill leaves a name behind. Where the file system refuses `O_TMPFILE` (or the
//! link fails), a named temporary file is written instead.
//!
//! Temporary names are `.reyes-film-PID-RANDOM.tmp`, PID the writer's process id, so that
//! [`remove_stale_temporaries`] can tell the leftovers of a killed writer from the files of a
//! live one.
//!
//! Writes go through in chunks of at most [`CHUNK`] bytes; before each one the cancel flag is
//! polled ([`WriteOptions::cancel`]), and a set flag ends the write with
//! [`FilmError::Interrupted`], the temporary file removed.

use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use crate::FilmError;

/// The start of every temporary file name.
const PREFIX: &str = ".reyes-film-";
/// The end of every temporary file name.
const SUFFIX: &str = ".tmp";
/// The largest single write to the temporary file; the cancel flag is polled between them.
pub const CHUNK: usize = 64 * 1024;

/// A hook called after the first chunk with the temporary file's name (`None`: unnamed).
pub type ChunkHook<'a> = dyn Fn(Option<&Path>) + Sync + 'a;

/// How [`crate::write_with`] writes, beyond the path and the image.
#[derive(Default, Clone, Copy)]
pub struct WriteOptions<'a> {
    /// Polled before each chunk: once it is set the write stops with
    /// [`FilmError::Interrupted`] and the temporary file is removed.
    pub cancel: Option<&'a AtomicBool>,
    /// Called once, right after the first chunk reached the temporary file, with the
    /// temporary file's name (`None`: unnamed). A test hook: it lets a test interrupt a write
    /// that is known to be under way.
    pub after_first_chunk: Option<&'a ChunkHook<'a>>,
    /// Write a named temporary file even where an unnamed one is possible (to test the
    /// fallback).
    pub named_temporary: bool,
}

/// What the encoders write to: buffered, in chunks, polling the cancel flag.
pub(crate) type Out<'a> = BufWriter<Chunks<'a>>;

/// Write `path` atomically with the bytes `encode` writes (it may be called twice, if an
/// unnamed temporary file could not be linked into place). On any error, or on cancellation,
/// the target is untouched and no temporary file remains.
pub(crate) fn write_atomic(
    path: &Path,
    opts: &WriteOptions,
    encode: &dyn Fn(&mut Out<'_>) -> Result<(), FilmError>,
) -> Result<(), FilmError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    #[cfg(target_os = "linux")]
    {
        let unnamed = match opts.named_temporary {
            true => None,
            false => unnamed::open(dir).map_err(|e| io_error(path, e))?,
        };
        if let Some(mut file) = unnamed {
            fill(&mut file, path, opts, None, encode)?;
            match unnamed::link(&file, dir, &prefix()) {
                Ok(link) => {
                    // On failure the PersistError owns the link and removes it when dropped.
                    link.persist(path).map_err(|e| io_error(path, e.error))?;
                    return Ok(());
                }
                // No /proc and no privilege for AT_EMPTY_PATH: write a named file instead.
                Err(_) => drop(file),
            }
        }
    }
    write_named(path, dir, opts, encode)
}

/// The fallback: a named temporary file beside the target, renamed over it.
fn write_named(
    path: &Path,
    dir: &Path,
    opts: &WriteOptions,
    encode: &dyn Fn(&mut Out<'_>) -> Result<(), FilmError>,
) -> Result<(), FilmError> {
    let prefix = prefix();
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(SUFFIX);
    #[cfg(unix)]
    {
        // NamedTempFile defaults to 0600; ask for 0666 so the final file gets the usual
        // umask-restricted mode of a newly created file.
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    // Dropping `tmp` on any early return deletes the temporary file.
    let mut tmp = builder.tempfile_in(dir).map_err(|e| io_error(path, e))?;
    let name = tmp.path().to_path_buf();
    fill(tmp.as_file_mut(), path, opts, Some(&name), encode)?;
    // On failure the PersistError owns the temporary file and deletes it when dropped.
    tmp.persist(path).map_err(|e| io_error(path, e.error))?;
    Ok(())
}

/// Encode into `file`, flush, sync; [`FilmError::Interrupted`] if the cancel flag was set
/// by the end, whatever else happened.
fn fill(
    file: &mut File,
    path: &Path,
    opts: &WriteOptions,
    name: Option<&Path>,
    encode: &dyn Fn(&mut Out<'_>) -> Result<(), FilmError>,
) -> Result<(), FilmError> {
    let cancelled = || opts.cancel.is_some_and(|c| c.load(Ordering::SeqCst));
    let interrupted = || FilmError::Interrupted { path: path.to_path_buf() };
    let mut result = {
        let chunks = Chunks { file, cancel: opts.cancel, first: opts.after_first_chunk, name };
        let mut w = BufWriter::with_capacity(CHUNK, chunks);
        encode(&mut w).and_then(|()| w.flush().map_err(|e| io_error(path, e)))
    };
    if result.is_ok() {
        result = file.sync_all().map_err(|e| io_error(path, e));
    }
    if cancelled() {
        return Err(interrupted());
    }
    result
}

fn io_error(path: &Path, source: io::Error) -> FilmError {
    FilmError::Io { path: path.to_path_buf(), source }
}

/// `.reyes-film-PID-`.
fn prefix() -> String {
    format!("{PREFIX}{}-", std::process::id())
}

/// The temporary file seen by the encoder: writes of at most [`CHUNK`] bytes, each after a
/// look at the cancel flag.
pub(crate) struct Chunks<'a> {
    file: &'a mut File,
    cancel: Option<&'a AtomicBool>,
    /// The hook still to call after the first chunk.
    first: Option<&'a ChunkHook<'a>>,
    name: Option<&'a Path>,
}

/// The error a write returns once the cancel flag is set (not `ErrorKind::Interrupted`,
/// which `write_all` would retry).
fn cancelled_error() -> io::Error {
    io::Error::other("interrupted")
}

impl Write for Chunks<'_> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.cancel.is_some_and(|c| c.load(Ordering::SeqCst)) {
            return Err(cancelled_error());
        }
        let n = self.file.write(&buf[..buf.len().min(CHUNK)])?;
        if let Some(hook) = self.first.take() {
            hook(self.name);
        }
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

impl Seek for Chunks<'_> {
    fn seek(&mut self, pos: SeekFrom) -> io::Result<u64> {
        self.file.seek(pos)
    }
}

/// Unnamed temporary files (Linux `O_TMPFILE`).
#[cfg(target_os = "linux")]
mod unnamed {
    use std::fs::File;
    use std::io;
    use std::os::fd::AsRawFd;
    use std::path::Path;

    use rustix::fs::{AtFlags, CWD, Mode, OFlags};
    use rustix::io::Errno;

    use super::SUFFIX;

    /// An unnamed file in `dir`, or None where the file system (or kernel) does not do
    /// `O_TMPFILE`. Mode 0666 less the umask, as for any new file.
    pub(super) fn open(dir: &Path) -> io::Result<Option<File>> {
        let flags = OFlags::TMPFILE | OFlags::RDWR | OFlags::CLOEXEC;
        match rustix::fs::open(dir, flags, Mode::from_raw_mode(0o666)) {
            Ok(fd) => Ok(Some(File::from(fd))),
            // EOPNOTSUPP: the file system; EISDIR: a kernel without O_TMPFILE, which opens the
            // directory (O_TMPFILE contains O_DIRECTORY); EINVAL: flags refused.
            Err(Errno::OPNOTSUPP | Errno::ISDIR | Errno::INVAL) => Ok(None),
            Err(e) => Err(e.into()),
        }
    }

    /// Give `file` a unique temporary name `PREFIX...SUFFIX` in `dir`; the returned handle
    /// removes that name when dropped unless it is persisted.
    pub(super) fn link(
        file: &File,
        dir: &Path,
        prefix: &str,
    ) -> io::Result<tempfile::NamedTempFile<()>> {
        let by_proc = format!("/proc/self/fd/{}", file.as_raw_fd());
        tempfile::Builder::new().prefix(prefix).suffix(SUFFIX).make_in(dir, |name| {
            match rustix::fs::linkat(CWD, &by_proc, CWD, name, AtFlags::SYMLINK_FOLLOW) {
                Ok(()) => Ok(()),
                // Taken: tempfile tries another name.
                Err(Errno::EXIST) => Err(Errno::EXIST.into()),
                // No /proc: the descriptor itself (needs CAP_DAC_READ_SEARCH).
                Err(_) => {
                    rustix::fs::linkat(file, "", CWD, name, AtFlags::EMPTY_PATH).map_err(Into::into)
                }
            }
        })
    }
}

/// Remove the temporary files that writers which are no longer running left in `dir`
/// (`.reyes-film-PID-*.tmp` whose PID is not a live process; only a kill in the instant
/// between link and rename, or any kill where the file system refuses `O_TMPFILE`, leaves
/// one). Files of live processes, of this one, and any other name are kept; so is everything
/// where the liveness of a process cannot be checked (not Unix). Returns the files removed;
/// errors (an unreadable directory, a file that cannot be removed) are skipped, as the next
/// write reports whatever is wrong with the directory.
pub fn remove_stale_temporaries(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    entries
        .flatten()
        .filter_map(|entry| {
            let pid = temporary_pid(entry.file_name().to_str()?)?;
            if pid == std::process::id() || is_alive(pid) || !entry.file_type().ok()?.is_file() {
                return None;
            }
            let path = entry.path();
            std::fs::remove_file(&path).ok().map(|()| path)
        })
        .collect()
}

/// The PID in a temporary file name `.reyes-film-PID-RANDOM.tmp`, or None for any other name.
fn temporary_pid(name: &str) -> Option<u32> {
    let (pid, random) = name.strip_prefix(PREFIX)?.strip_suffix(SUFFIX)?.split_once('-')?;
    if random.is_empty() || pid.is_empty() || !pid.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` exists (kill with signal 0: only "no such process" says it does
/// not; a process of another user answers EPERM and counts as alive).
#[cfg(unix)]
fn is_alive(pid: u32) -> bool {
    match i32::try_from(pid).ok().and_then(rustix::process::Pid::from_raw) {
        Some(pid) => rustix::process::test_kill_process(pid) != Err(rustix::io::Errno::SRCH),
        None => true,
    }
}

#[cfg(not(unix))]
fn is_alive(_pid: u32) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A disk that fills up part-way (ENOSPC from a write, after some chunks went out): one
    /// line naming the target, the OS error kept, nothing left in the directory.
    #[test]
    fn a_failing_write_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        for named in [false, true] {
            let path = dir.path().join("full.exr");
            let opts = WriteOptions { named_temporary: named, ..Default::default() };
            let r = write_atomic(&path, &opts, &|w| {
                w.write_all(&[7; 3 * CHUNK]).map_err(|e| io_error(&path, e))?;
                Err(io_error(&path, io::Error::from_raw_os_error(28)))
            });
            match r {
                Err(e @ FilmError::Io { .. }) => {
                    let msg = e.to_string();
                    assert!(msg.contains("full.exr") && !msg.contains('\n'), "{msg}");
                    assert!(msg.contains("(os error 28)"), "{msg}");
                }
                other => panic!("expected Io, got {other:?}"),
            }
            let left = std::fs::read_dir(dir.path()).map(|d| d.count()).unwrap_or(usize::MAX);
            assert_eq!(left, 0, "named: {named}");
        }
    }

    #[test]
    fn temporary_names_carry_the_pid() {
        assert_eq!(temporary_pid(".reyes-film-123-abcdef.tmp"), Some(123));
        assert!(prefix().starts_with(".reyes-film-"));
        assert_eq!(
            temporary_pid(&format!("{}x1y2.tmp", prefix())),
            Some(std::process::id()),
            "{}",
            prefix()
        );
        for other in [
            ".reyes-film-abcdef.tmp",
            ".reyes-film-12-.tmp",
            ".reyes-film--abc.tmp",
            ".reyes-film-1x-abc.tmp",
            ".reyes-film-+1-abc.tmp",
            ".reyes-film-99999999999-abc.tmp",
            "reyes-film-12-abc.tmp",
            ".reyes-film-12-abc.tmp.exr",
            "out.exr",
        ] {
            assert_eq!(temporary_pid(other), None, "{other}");
        }
    }
}

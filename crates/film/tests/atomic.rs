//! Atomic output ([`reyes_film::atomic`]): what a directory holds while a write is under way
//! and after it was cancelled, the mode of the file written, and the clean-up of the
//! temporary files that killed writers leave.

use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use reyes_film::{Film, FilmError, WriteOptions, read_exr, remove_stale_temporaries, write_with};

/// A film whose EXR is several chunks long: noise-like values ZIP cannot squeeze much.
fn big_film() -> Film {
    let (w, h) = (256_u32, 256_u32);
    let n = (w * h) as usize;
    let mut x = 0x9e37_79b9_u32;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        (x >> 8) as f32 / (1 << 24) as f32
    };
    let rgba = (0..n).map(|_| [next(), next(), next(), 1.0]).collect();
    let z = (0..n).map(|_| 1.0 + next()).collect();
    Film::from_pixels(w, h, rgba, z).expect("film")
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("read_dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// What the directory held when the first chunk had been written, and the temporary name the
/// writer reported.
struct Seen {
    names: Vec<String>,
    temporary: Option<PathBuf>,
}

/// Write `name` into `dir`, with `cancel` set by the hook after the first chunk when
/// `interrupt`; returns the result and what the hook saw.
fn write_observed(
    dir: &Path,
    name: &str,
    named: bool,
    interrupt: bool,
) -> (Result<(), FilmError>, Seen) {
    let cancel = AtomicBool::new(false);
    let seen = Mutex::new(None);
    let hook = |temporary: Option<&Path>| {
        let now = Seen { names: names(dir), temporary: temporary.map(Path::to_path_buf) };
        *seen.lock().expect("lock") = Some(now);
        if interrupt {
            cancel.store(true, Ordering::SeqCst);
        }
    };
    let opts = WriteOptions {
        cancel: Some(&cancel),
        after_first_chunk: Some(&hook),
        named_temporary: named,
    };
    let r = write_with(&dir.join(name), &big_film(), &opts);
    let seen = seen.into_inner().expect("lock").expect("the hook was called");
    (r, seen)
}

/// While a write is under way the directory holds no name at all (unnamed temporary file) or
/// exactly the reported `.reyes-film-PID-*.tmp`; afterwards only the target.
#[test]
fn a_write_under_way_is_unnamed_or_one_named_temporary() {
    let dir = tempfile::tempdir().expect("tempdir");
    let pid_prefix = format!(".reyes-film-{}-", std::process::id());
    for (name, named) in [("a.exr", false), ("b.png", false), ("c.exr", true), ("d.png", true)] {
        let before = names(dir.path());
        let (r, seen) = write_observed(dir.path(), name, named, false);
        r.expect("write");
        match &seen.temporary {
            None => {
                assert!(!named, "{name}: asked for a named temporary file");
                assert_eq!(seen.names, before, "{name}: a name appeared while writing");
            }
            Some(tmp) => {
                let tmp_name = tmp.file_name().expect("name").to_string_lossy().into_owned();
                assert!(tmp_name.starts_with(&pid_prefix), "{tmp_name}");
                assert!(tmp_name.ends_with(".tmp"), "{tmp_name}");
                let mut expected = before.clone();
                expected.push(tmp_name);
                expected.sort();
                assert_eq!(seen.names, expected, "{name}");
            }
        }
        let mut after = before;
        after.push(name.to_string());
        after.sort();
        assert_eq!(names(dir.path()), after, "{name}");
    }
    assert_eq!(read_exr(&dir.path().join("a.exr")).ok(), Some(big_film()));
    assert_eq!(read_exr(&dir.path().join("c.exr")).ok(), Some(big_film()));
}

/// This machine's test directories are on a file system with O_TMPFILE (ext4, tmpfs, ...):
/// the unnamed path is the one taken.
#[cfg(target_os = "linux")]
#[test]
fn the_unnamed_temporary_file_is_used_on_linux() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (r, seen) = write_observed(dir.path(), "u.exr", false, false);
    r.expect("write");
    assert_eq!(seen.temporary, None);
    assert!(seen.names.is_empty(), "{:?}", seen.names);
}

/// Cancelled after the first chunk: `Interrupted` naming the file, nothing left, an existing
/// target untouched.
#[test]
fn a_cancelled_write_leaves_nothing_and_keeps_the_old_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("old.exr"), b"previous").expect("write");
    for (name, named) in
        [("x.exr", false), ("x.png", false), ("y.exr", true), ("y.png", true), ("old.exr", false)]
    {
        let (r, _) = write_observed(dir.path(), name, named, true);
        match r {
            Err(e @ FilmError::Interrupted { .. }) => {
                let msg = e.to_string();
                assert!(msg.contains(name) && !msg.contains('\n'), "{msg}");
            }
            other => panic!("{name}: expected Interrupted, got {other:?}"),
        }
        assert_eq!(names(dir.path()), ["old.exr"], "{name}");
    }
    assert_eq!(std::fs::read(dir.path().join("old.exr")).expect("read"), b"previous");

    // Cancelled before it starts: nothing is written either.
    let cancel = AtomicBool::new(true);
    for named in [false, true] {
        let opts =
            WriteOptions { cancel: Some(&cancel), named_temporary: named, ..Default::default() };
        let r = write_with(&dir.path().join("z.exr"), &big_film(), &opts);
        assert!(matches!(r, Err(FilmError::Interrupted { .. })), "{r:?}");
        assert_eq!(names(dir.path()), ["old.exr"]);
    }
}

/// The output gets the mode of any new file (0666 less the umask), whichever temporary file
/// it went through.
#[cfg(unix)]
#[test]
fn the_output_has_the_mode_of_a_new_file() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().expect("tempdir");
    let mode = |p: &Path| std::fs::metadata(p).expect("metadata").permissions().mode() & 0o7777;
    let plain = dir.path().join("plain");
    std::fs::File::create(&plain).expect("create");
    for (name, named) in [("u.exr", false), ("n.exr", true)] {
        let opts = WriteOptions { named_temporary: named, ..Default::default() };
        write_with(&dir.path().join(name), &big_film(), &opts).expect("write");
        assert_eq!(mode(&dir.path().join(name)), mode(&plain), "{name}");
    }
}

/// The pid of a process that has exited (and been reaped).
fn dead_pid() -> u32 {
    let mut child = std::process::Command::new("true").spawn().expect("spawn true");
    let pid = child.id();
    child.wait().expect("wait");
    pid
}

/// Only temporary files of processes that no longer run are removed.
#[cfg(unix)]
#[test]
fn stale_temporaries_of_dead_writers_are_removed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let dead = dead_pid();
    let me = std::process::id();
    let parent = std::os::unix::process::parent_id();
    let stale = [format!(".reyes-film-{dead}-AbC123.tmp"), format!(".reyes-film-{dead}-x.tmp")];
    let kept = [
        format!(".reyes-film-{me}-AbC123.tmp"),
        format!(".reyes-film-{parent}-AbC123.tmp"),
        ".reyes-film-AbC123.tmp".to_string(),
        format!(".reyes-film-{dead}-.tmp"),
        format!("reyes-film-{dead}-x.tmp"),
        format!(".reyes-film-{dead}-x.tmp.exr"),
        "frame.exr".to_string(),
    ];
    for name in stale.iter().chain(&kept) {
        std::fs::write(dir.path().join(name), b"x").expect("plant");
    }
    // A directory with a stale-looking name is not a temporary file of ours.
    let dir_like = format!(".reyes-film-{dead}-dir.tmp");
    std::fs::create_dir(dir.path().join(&dir_like)).expect("mkdir");

    let mut removed: Vec<String> = remove_stale_temporaries(dir.path())
        .iter()
        .map(|p| p.file_name().expect("name").to_string_lossy().into_owned())
        .collect();
    removed.sort();
    let mut expected = stale.to_vec();
    expected.sort();
    assert_eq!(removed, expected);
    let mut left: Vec<String> = kept.to_vec();
    left.push(dir_like);
    left.sort();
    assert_eq!(names(dir.path()), left);
    // A missing directory is no error.
    assert!(remove_stale_temporaries(&dir.path().join("missing")).is_empty());
}

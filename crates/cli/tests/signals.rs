//! Signals, output atomicity and output failures (docs/reliability.md), with real processes:
//! SIGINT, SIGTERM and SIGKILL during rendering and during writing, a file-size limit, a full
//! or closed standard output, usage errors.
//!
//! "During rendering" and "during writing" are made certain with the binary's test hook
//! `REYES_TEST_PAUSE` (it prints a marker on stderr and waits for a signal), never with a
//! guessed delay.
#![cfg(unix)]

use std::io::{BufRead, BufReader, Read};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStderr, Command, ExitStatus, Output, Stdio};

use rustix::process::{Pid, Signal, kill_process};

/// The binary, handling SIGINT and SIGTERM as a foreground job does even when this test
/// process was started with them ignored (`REYES_TEST_SIGNALS=default`).
fn bin() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_reyes-render"));
    cmd.env("REYES_TEST_SIGNALS", "default");
    cmd
}

/// A 640x480 sphere: about 250 kB of EXR, so several 64 KiB chunks.
fn scene(dir: &Path) -> PathBuf {
    let path = dir.join("s.ron");
    let text = "Scene(
  image: (width: 640, height: 480),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, hither: 0.1, yon: 100.0),
  hider: (pixel_samples: (1, 1), filter: (kind: Gaussian, width: 2.0)),
  lights: [Ambient(intensity: 1.0)],
  objects: [(name: \"ball\", shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 0.5, 0.2)))],
)
";
    std::fs::write(&path, text).expect("write the scene");
    path
}

use reyes_testkit::files::names;

fn sorted(names: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    v.sort();
    v
}

/// A render of `scene` to `out` paused by `REYES_TEST_PAUSE=pause` (`render` or `write`),
/// through a named temporary file when `named`: the child, the marker line it printed, and
/// the rest of its stderr.
fn start_paused(
    scene: &Path,
    out: &Path,
    pause: &str,
    named: bool,
) -> (Child, String, BufReader<ChildStderr>) {
    let mut cmd = bin();
    cmd.arg(scene).arg("-o").arg(out).args(["--threads", "1", "-q"]);
    cmd.env("REYES_TEST_PAUSE", pause);
    if named {
        cmd.env("REYES_TEST_NAMED_TEMPORARY", "1");
    }
    let mut child = cmd.stderr(Stdio::piped()).spawn().expect("spawn reyes-render");
    let mut err = BufReader::new(child.stderr.take().expect("stderr"));
    let mut line = String::new();
    loop {
        line.clear();
        // EOF (0) means the process ended without pausing: the test fails below.
        if err.read_line(&mut line).expect("read stderr") == 0 {
            break;
        }
        if line.starts_with("reyes-render: test: paused") {
            break;
        }
    }
    let expected = match pause {
        "render" => "reyes-render: test: paused rendering",
        _ => "reyes-render: test: paused writing",
    };
    assert!(line.starts_with(expected), "no pause marker: {line:?}");
    (child, line.trim_end().to_string(), err)
}

/// Send `signal` (None: SIGKILL), wait; the exit status and the rest of stderr.
fn stop(
    mut child: Child,
    mut err: BufReader<ChildStderr>,
    signal: Option<Signal>,
) -> (ExitStatus, String) {
    match signal {
        Some(s) => kill_process(Pid::from_child(&child), s).expect("kill"),
        None => child.kill().expect("SIGKILL"),
    }
    let status = child.wait().expect("wait");
    let mut rest = String::new();
    err.read_to_string(&mut rest).expect("read stderr");
    (status, rest)
}

/// The temporary file a write marker names (None: unnamed).
fn temporary_of(marker: &str) -> Option<PathBuf> {
    let (_, tmp) = marker.rsplit_once(", temporary file ").expect("marker");
    (tmp != "unnamed").then(|| PathBuf::from(tmp))
}

/// SIGINT or SIGTERM: exit 130 or 143, one line saying so and naming the output.
fn assert_stopped(status: ExitStatus, rest: &str, name: &str, out: &Path) {
    let code = if name == "SIGINT" { 130 } else { 143 };
    assert_eq!(status.code(), Some(code), "{name}: {status:?} {rest}");
    assert_eq!(rest.lines().count(), 1, "{name}: {rest}");
    let expected =
        format!("reyes-render: interrupted by {name}: {} was not written", out.display());
    assert_eq!(rest.trim_end(), expected);
}

const STOPS: [(Signal, &str); 2] = [(Signal::INT, "SIGINT"), (Signal::TERM, "SIGTERM")];

#[test]
fn sigint_and_sigterm_while_rendering_exit_130_and_143_and_write_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    for (signal, name) in STOPS {
        let out = dir.path().join("out.exr");
        let (child, _, err) = start_paused(&s, &out, "render", false);
        let (status, rest) = stop(child, err, Some(signal));
        assert_stopped(status, &rest, name, &out);
        assert_eq!(names(dir.path()), ["s.ron"], "{name}");
    }
}

/// A SIGINT ignored when the command starts (as a shell starts background jobs) stays
/// ignored, while SIGTERM is caught and stops it (Linux: the dispositions read from
/// `/proc/PID/status`).
#[test]
#[cfg(target_os = "linux")]
fn an_inherited_ignored_sigint_stays_ignored() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let out = dir.path().join("out.exr");
    // `trap '' INT` makes the shell, and what it execs, ignore SIGINT.
    let mut child = Command::new("sh")
        .arg("-c")
        .arg("trap '' INT; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_reyes-render"))
        .arg(&s)
        .arg("-o")
        .arg(&out)
        .args(["--threads", "1", "-q"])
        .env("REYES_TEST_PAUSE", "render")
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn sh");
    let mut err = BufReader::new(child.stderr.take().expect("stderr"));
    let mut line = String::new();
    err.read_line(&mut line).expect("read stderr");
    assert_eq!(line.trim_end(), "reyes-render: test: paused rendering");
    // The handlers are installed by now: SIGINT is still ignored, SIGTERM is caught.
    let status = std::fs::read_to_string(format!("/proc/{}/status", child.id())).expect("status");
    let mask = |field: &str| {
        let line = status.lines().find_map(|l| l.strip_prefix(field)).expect("mask");
        u64::from_str_radix(line.trim(), 16).expect("hex mask")
    };
    let bit = |signal: Signal| 1_u64 << (signal.as_raw() - 1);
    assert_ne!(mask("SigIgn:") & bit(Signal::INT), 0, "{status}");
    assert_eq!(mask("SigCgt:") & bit(Signal::INT), 0, "{status}");
    assert_ne!(mask("SigCgt:") & bit(Signal::TERM), 0, "{status}");
    kill_process(Pid::from_child(&child), Signal::INT).expect("SIGINT");
    let (status, rest) = stop(child, err, Some(Signal::TERM));
    assert_stopped(status, &rest, "SIGTERM", &out);
}

#[test]
fn sigkill_while_rendering_leaves_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let (child, _, err) = start_paused(&s, &dir.path().join("out.exr"), "render", false);
    let (status, _) = stop(child, err, None);
    assert_eq!(status.signal(), Some(9));
    assert_eq!(names(dir.path()), ["s.ron"]);
}

/// Interrupted mid-write, through either kind of temporary file, in either format: the
/// temporary file is gone and an earlier output is untouched.
#[test]
fn sigint_and_sigterm_while_writing_remove_the_temporary_and_keep_the_old_output() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    for out_name in ["out.exr", "out.png"] {
        let out = dir.path().join(out_name);
        std::fs::write(&out, b"previous").expect("write");
        for named in [false, true] {
            for (signal, name) in STOPS {
                let (child, marker, err) = start_paused(&s, &out, "write", named);
                let tmp = temporary_of(&marker);
                assert_eq!(tmp.is_some(), named, "{marker}");
                if let Some(tmp) = &tmp {
                    assert!(tmp.is_file(), "{marker}: no named temporary file while writing");
                }
                let (status, rest) = stop(child, err, Some(signal));
                assert_stopped(status, &rest, name, &out);
                assert_eq!(names(dir.path()), sorted(&[out_name, "s.ron"]), "{name} {marker}");
                assert_eq!(std::fs::read(&out).expect("read"), b"previous", "{name} {marker}");
            }
        }
        std::fs::remove_file(&out).expect("remove");
    }
}

/// SIGKILL mid-write with an unnamed temporary file: nothing to clean up, ever.
#[test]
fn sigkill_while_writing_an_unnamed_temporary_leaves_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let (child, marker, err) = start_paused(&s, &dir.path().join("out.exr"), "write", false);
    assert_eq!(temporary_of(&marker), None, "{marker}: O_TMPFILE not used");
    assert_eq!(names(dir.path()), ["s.ron"], "a name exists while writing");
    let (status, _) = stop(child, err, None);
    assert_eq!(status.signal(), Some(9));
    assert_eq!(names(dir.path()), ["s.ron"]);
}

/// SIGKILL mid-write through a named temporary file (a file system without O_TMPFILE): the
/// temporary file stays, and the next run in that directory removes it.
#[test]
fn sigkill_while_writing_a_named_temporary_is_cleaned_up_by_the_next_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let (child, marker, err) = start_paused(&s, &dir.path().join("out.exr"), "write", true);
    let tmp = temporary_of(&marker).expect("a named temporary file");
    let (status, _) = stop(child, err, None);
    assert_eq!(status.signal(), Some(9));
    let tmp_name = tmp.file_name().expect("name").to_string_lossy().into_owned();
    assert_eq!(names(dir.path()), sorted(&[&tmp_name, "s.ron"]));

    let o =
        bin().arg(&s).arg("-o").arg(dir.path().join("next.png")).arg("-q").output().expect("run");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(names(dir.path()), ["next.png", "s.ron"]);
}

/// The pid of a process that has exited and been reaped.
fn dead_pid() -> u32 {
    let mut child = Command::new("true").spawn().expect("spawn true");
    let pid = child.id();
    child.wait().expect("wait");
    pid
}

/// At start the command removes temporary files of dead writers from each output directory,
/// and keeps those of live ones.
#[test]
fn a_stale_temporary_of_a_dead_pid_is_removed_at_start() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let sub = dir.path().join("frames");
    std::fs::create_dir(&sub).expect("mkdir");
    let dead = format!(".reyes-film-{}-Qw3rTy.tmp", dead_pid());
    let live = format!(".reyes-film-{}-Qw3rTy.tmp", std::process::id());
    for d in [dir.path(), &sub] {
        std::fs::write(d.join(&dead), b"partial").expect("plant");
        std::fs::write(d.join(&live), b"in progress").expect("plant");
    }
    let o = bin().arg(&s).arg("-o").arg(sub.join("out.exr")).arg("-q").output().expect("run");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(names(&sub), sorted(&[&live, "out.exr"]));
    // Only the output directories are cleaned.
    assert_eq!(names(dir.path()), sorted(&[&dead, &live, "frames", "s.ron"]));
}

/// `prlimit --fsize`: the write fails with EFBIG instead of SIGXFSZ ending the process: exit
/// 1, one line naming the file, nothing left, an earlier output untouched.
#[test]
fn a_file_size_limit_is_exit_1_one_line_and_leaves_nothing() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    for out_name in ["big.exr", "big.png"] {
        let out = dir.path().join(out_name);
        std::fs::write(&out, b"previous").expect("write");
        for named in [false, true] {
            let mut cmd = Command::new("prlimit");
            cmd.arg("--fsize=2000").arg("--").arg(env!("CARGO_BIN_EXE_reyes-render"));
            cmd.arg(&s).arg("-o").arg(&out).arg("-q");
            if named {
                cmd.env("REYES_TEST_NAMED_TEMPORARY", "1");
            }
            let o = cmd.output().expect("prlimit (util-linux) runs reyes-render");
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(1), "{out_name} {named}: {:?} {err}", o.status);
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(err.contains(&format!("{}: ", out.display())), "{err}");
            assert!(err.contains("(os error 27)"), "not EFBIG: {err}");
            assert_eq!(names(dir.path()), sorted(&[out_name, "s.ron"]), "{out_name} {named}");
            assert_eq!(std::fs::read(&out).expect("read"), b"previous");
        }
        std::fs::remove_file(&out).expect("remove");
    }
}

/// A standard output that is full (`> /dev/full`): exit 1, one line; the image itself was
/// written whole.
#[test]
fn a_full_standard_output_is_exit_1_with_one_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    let full = || std::fs::OpenOptions::new().write(true).open("/dev/full").expect("/dev/full");
    let out = dir.path().join("o.exr");
    let renders = bin().arg(&s).arg("-o").arg(&out).args(["--stats", "-q"]).stdout(full()).output();
    let measures = bin()
        .arg("measure")
        .arg(&s)
        .args(["--object", "ball", "--samples", "1000"])
        .stdout(full())
        .output();
    let version = bin().arg("--version").stdout(full()).output();
    for o in [renders, measures, version] {
        let o = o.expect("run");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert_eq!(
            err.trim_end(),
            "reyes-render: error: standard output: No space left on device (os error 28)"
        );
    }
    assert!(reyes_film::read_exr(&out).is_ok());
}

/// A standard output whose reader is gone (`| head -0`): no panic, no message, exit 0.
#[test]
fn a_closed_standard_output_ends_quietly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());
    // The read end is closed before the process starts, so every write fails with EPIPE.
    let closed = || {
        let (reader, writer) = rustix::pipe::pipe().expect("pipe");
        drop(reader);
        Stdio::from(writer)
    };
    let out = dir.path().join("o.exr");
    let runs: [(&str, Vec<&std::ffi::OsStr>); 4] = [
        (
            "render --stats",
            vec![s.as_os_str(), "-o".as_ref(), out.as_os_str(), "--stats".as_ref(), "-q".as_ref()],
        ),
        (
            "measure",
            vec![
                "measure".as_ref(),
                s.as_os_str(),
                "--object".as_ref(),
                "ball".as_ref(),
                "--samples".as_ref(),
                "1000".as_ref(),
            ],
        ),
        ("--help", vec!["--help".as_ref()]),
        ("measure --help", vec!["measure".as_ref(), "--help".as_ref()]),
    ];
    for (what, args) in runs {
        let o = bin().args(args).stdout(closed()).output().expect("run");
        assert_eq!(
            o.status.code(),
            Some(0),
            "{what}: {:?} {}",
            o.status,
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(o.stderr.is_empty(), "{what}: {}", String::from_utf8_lossy(&o.stderr));
    }
    assert!(reyes_film::read_exr(&out).is_ok());

    // A closed standard error does not make an error message panic either.
    let o = bin().arg("--nope").stderr(closed()).output().expect("run");
    assert_eq!(o.status.code(), Some(2));
}

/// Usage errors: one line, `reyes-render: error: ...`, exit 2; --help and --version still
/// print as before and exit 0.
#[test]
fn usage_errors_are_one_line_with_exit_2() {
    let run = |args: &[&str]| -> Output { bin().args(args).output().expect("run") };
    let cases: [(&[&str], &str); 7] = [
        (&["--foo"], "reyes-render: error: unexpected argument '--foo' found (see --help)"),
        (
            &[],
            "reyes-render: error: the following required arguments were not provided: <SCENE> (see --help)",
        ),
        (
            &["s.ron", "-o", "x.exr", "--stat"],
            "reyes-render: error: unexpected argument '--stat' found; did you mean '--stats'? (see --help)",
        ),
        (
            &["s.ron", "-o", "x.exr", "--threads", "0"],
            "reyes-render: error: invalid value '0' for '--threads <N>': 0 is not in 1..=1024 (see --help)",
        ),
        (
            &["s.ron", "-o", "x.exr", "--samples", "4"],
            "reyes-render: error: invalid value '4' for '--samples <NxM>': expected NxM with N and M from 1 to 64, got '4' (see --help)",
        ),
        (
            &["measure", "s.ron"],
            "reyes-render: error: the following required arguments were not provided: --object <NAME> (see reyes-render measure --help)",
        ),
        (
            &["measure", "s.ron", "--object", "b", "--sample", "9"],
            "reyes-render: error: unexpected argument '--sample' found; did you mean '--samples'? (see reyes-render measure --help)",
        ),
    ];
    for (args, expected) in cases {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert_eq!(String::from_utf8_lossy(&o.stderr), format!("{expected}\n"), "{args:?}");
        assert!(o.stdout.is_empty());
    }
    for args in [&["--help"][..], &["--version"], &["-V"], &["measure", "--help"]] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(0), "{args:?}");
        assert!(o.stderr.is_empty(), "{args:?}");
        assert!(!o.stdout.is_empty(), "{args:?}");
    }
    let o = run(&["--version"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        format!("reyes-render {}\n", env!("CARGO_PKG_VERSION"))
    );
    let o = run(&["--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).lines().count() > 10);
}

/// A pseudo-terminal: its controlling side and the terminal itself, opened without becoming
/// anyone's controlling terminal.
fn pty() -> (std::os::fd::OwnedFd, std::fs::File) {
    use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
    use std::os::unix::fs::OpenOptionsExt;
    let master =
        openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).expect("openpt");
    grantpt(&master).expect("grantpt");
    unlockpt(&master).expect("unlockpt");
    let name = ptsname(&master, Vec::new()).expect("ptsname");
    let terminal = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .custom_flags(rustix::fs::OFlags::NOCTTY.bits() as i32)
        .open(name.to_str().expect("utf-8 name"))
        .expect("open the terminal");
    (master, terminal)
}

/// Read `master` until its text contains each of `needles` (or it ends), then close it.
fn read_until(
    master: std::os::fd::OwnedFd,
    needles: &'static [&'static str],
) -> std::thread::JoinHandle<String> {
    let mut master = std::fs::File::from(master);
    std::thread::spawn(move || {
        let mut seen = Vec::new();
        let mut buf = [0_u8; 4096];
        // A read fails with EIO once the last descriptor of the terminal is closed.
        while let Ok(n @ 1..) = master.read(&mut buf) {
            seen.extend_from_slice(&buf[..n]);
            let text = String::from_utf8_lossy(&seen);
            if !needles.is_empty() && needles.iter().all(|w| text.contains(w)) {
                break;
            }
        }
        String::from_utf8_lossy(&seen).into_owned()
    })
}

/// The progress bar (stderr a terminal) is drawn; a terminal that goes away under it (every
/// write then fails with EIO) makes nothing panic: the bar is cleared into the void and the
/// run ends as it would have.
#[test]
fn the_progress_bar_survives_a_terminal_that_goes_away() {
    let dir = tempfile::tempdir().expect("tempdir");
    let s = scene(dir.path());

    // Drawn, read to the end.
    let (master, terminal) = pty();
    let reader = read_until(master, &[]);
    let out = dir.path().join("tty.exr");
    let o = bin()
        .arg(&s)
        .arg("-o")
        .arg(&out)
        .args(["--threads", "1"])
        .stderr(Stdio::from(terminal))
        .output()
        .expect("run");
    assert_eq!(o.status.code(), Some(0), "{:?}", o.status);
    assert!(reyes_film::read_exr(&out).is_ok());
    let seen = reader.join().expect("reader");
    assert!(seen.contains("buckets"), "no progress bar drawn: {seen:?}");

    // The terminal closed while the render is paused after its first bucket (bar drawn), then
    // SIGINT: the bar's clearing and the one-line message both hit the dead terminal.
    let (master, terminal) = pty();
    let reader = read_until(master, &["buckets", "test: paused rendering"]);
    let child = bin()
        .arg(&s)
        .arg("-o")
        .arg(dir.path().join("gone.exr"))
        .args(["--threads", "1"])
        .env("REYES_TEST_PAUSE", "render")
        .stderr(Stdio::from(terminal))
        .spawn()
        .expect("spawn");
    let seen = reader.join().expect("reader");
    assert!(seen.contains("buckets") && seen.contains("paused rendering"), "{seen:?}");
    kill_process(Pid::from_child(&child), Signal::INT).expect("SIGINT");
    let status = {
        let mut child = child;
        child.wait().expect("wait")
    };
    assert_eq!(status.code(), Some(130), "{status:?}");
    assert_eq!(names(dir.path()), ["s.ron", "tty.exr"]);
}

//! The fuzzer's short run in CI, and the fuzzer's own checks.
//!
//! `cargo test` builds `reyes-fuzz` without coverage instrumentation, so the CI run is a
//! deterministic mutational run (fixed seeds, fixed counts) over the committed corpus, which
//! the instrumented runs of `cargo xtask fuzz` grew: every target's seeds, then mutants of
//! them. Any failure (a panic, a broken error promise, an abort, a hang, a render child
//! killed or over its memory cap) fails the test, with the saved input's path in the message.
//! The counts keep the three runs at about a minute on two idle cores (they run in parallel),
//! two under load.
//!
//! The canary tests plant a bug in the fuzzer's own process (`REYES_FUZZ_CANARY`) to show that
//! a panic, an abort and a hang of a loader, and an abort and a hang of a render child, are
//! each caught, blamed on the right input and make the run fail.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

const FUZZ: &str = env!("CARGO_BIN_EXE_reyes-fuzz");

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus")
}

/// Runs `reyes-fuzz fuzz` with `args`, its files in `out` (emptied first).
fn fuzz(args: &[&str], corpus: &Path, out: &Path, env: Option<(&str, &str)>) -> Output {
    let _ = std::fs::remove_dir_all(out);
    let mut cmd = Command::new(FUZZ);
    cmd.arg("fuzz").arg("--quiet").arg("--corpus").arg(corpus).arg("--out").arg(out);
    cmd.args(args);
    if let Some((k, v)) = env {
        cmd.env(k, v);
    }
    cmd.output().unwrap()
}

/// The number of `word` in the summary line of `target` (`1234 execs`, `failures 0`).
fn figure(stdout: &str, target: &str, word: &str) -> u64 {
    let line = stdout.lines().find(|l| l.starts_with(&format!("{target}: "))).unwrap_or("");
    let words: Vec<&str> = line.split([' ', ',']).filter(|w| !w.is_empty()).collect();
    words
        .iter()
        .position(|w| *w == word)
        .and_then(|i| words.get(if word == "failures" { i + 1 } else { i.checked_sub(1)? }))
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no '{word}' figure for {target} in {stdout}"))
}

/// A CI run of `target`: `execs` mutants (renders for `render`) with a fixed seed; no failure.
fn ci_run(target: &str, execs: u64) {
    let t = Instant::now();
    let count = execs.to_string();
    let flag = if target == "render" { "--renders" } else { "--execs" };
    // The run's folder is kept after the test, so that a failing input can be looked at.
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fuzz-ci-{target}"));
    let out = fuzz(&["--targets", target, flag, &count, "--seed", "20"], &corpus(), &dir, None);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "the fuzzer found failures:\n{stdout}\n{stderr}");
    assert_eq!(figure(&stdout, target, "failures"), 0, "{stdout}");
    assert!(figure(&stdout, target, "execs") > execs, "{stdout}");
    assert!(figure(&stdout, target, "accepted") > 0, "no scene loaded: {stdout}");
    eprintln!("{} ({:.1} s)", stdout.trim(), t.elapsed().as_secs_f64());
}

#[test]
fn ci_ron_loader_and_validator() {
    ci_run("ron", 500_000);
}

#[test]
fn ci_rib_reader_state_machine_and_validator() {
    ci_run("rib", 500_000);
}

/// The shading-language compiler, and the grid machine on what compiles.
#[test]
fn ci_shading_language_compiler_and_grid_machine() {
    ci_run("sl", 100_000);
}

/// Texture files (issue #32): the prepared-TIFF reader, the picture decoders and the lookups.
#[test]
fn ci_texture_files() {
    ci_run("tex", 5_000);
}

/// 1,000 renders (with seed 20; before the dicer's work bounds, 400 already reached the endless
/// split of `regressions/dice-split-endless-huge-moving-mesh-point.ron`).
#[test]
fn ci_small_renders_under_a_memory_cap() {
    ci_run("render", 1_000);
}

/// A one-seed corpus for `target` whose seed has the canary word (a valid scene, so that it
/// also reaches the render child).
fn canary_corpus(target: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let (sub, name, text) = match target {
        "rib" => ("rib", "seed.rib", "# canary\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n"),
        _ => (
            if target == "render" { "ron" } else { target },
            "seed.ron",
            "// canary\nScene(image: (width: 8, height: 6), camera: (eye: (0.0, 0.0, -5.0), \
             look_at: (0.0, 0.0, 0.0), fov: 40.0), objects: [(shape: Sphere(radius: 1.0), \
             material: Matte(color: (1.0, 1.0, 1.0)))])\n",
        ),
    };
    std::fs::create_dir_all(dir.path().join(sub)).unwrap();
    std::fs::write(dir.path().join(sub).join(name), text).unwrap();
    dir
}

/// Plants `canary` and fuzzes `target`: the run must fail, blaming the seed with `kind`.
fn caught(target: &str, canary: &str, kind: &str) {
    let corpus = canary_corpus(target);
    let args = ["--targets", target, "--execs", "10", "--renders", "2", "--timeout", "1"];
    let dir = tempfile::tempdir().unwrap();
    let out = fuzz(&args, corpus.path(), dir.path(), Some(("REYES_FUZZ_CANARY", canary)));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    let saved: Vec<PathBuf> = std::fs::read_dir(dir.path().join("crashes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name().unwrap().to_string_lossy().starts_with(&format!("{target}-{kind}-"))
        })
        .collect();
    assert!(!saved.is_empty(), "no {target}-{kind}-* input saved: {stdout}");
    for p in saved {
        let input = std::fs::read(&p).unwrap();
        assert!(input.windows(6).any(|w| w == b"canary"), "{} is not the culprit", p.display());
    }
}

#[test]
fn a_loader_panic_is_caught_and_its_input_saved() {
    caught("ron", "panic", "panic");
}

#[test]
fn a_loader_abort_ends_the_worker_and_its_input_is_saved() {
    caught("rib", "abort", "abort");
}

#[test]
fn a_loader_hang_is_ended_by_the_watchdog_and_its_input_saved() {
    caught("ron", "hang", "hang");
}

#[test]
fn a_render_child_killed_by_a_signal_is_a_failure() {
    caught("render", "render-abort", "signal");
}

#[test]
fn a_render_child_over_its_time_is_killed_and_a_failure() {
    caught("render", "render-hang", "hang");
}

#[test]
fn a_render_child_panic_is_a_failure() {
    caught("render", "render-panic", "panic");
}

/// The same seed and corpus give the same run (what CI's fixed seeds rely on); another seed
/// another run.
#[test]
fn a_run_repeats_for_its_seed() {
    let run = |seed: &str| {
        let dir = tempfile::tempdir().unwrap();
        let args = ["--targets", "rib", "--execs", "5000", "--seed", seed];
        let out = fuzz(&args, &corpus(), dir.path(), None);
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        (figure(&stdout, "rib", "execs"), figure(&stdout, "rib", "accepted"))
    };
    let a = run("5");
    assert_eq!(a, run("5"));
    assert_ne!(a, run("6"));
}

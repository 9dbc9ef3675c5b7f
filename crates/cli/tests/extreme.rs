//! The extreme-but-valid catalogue (`tests/extreme/*.ron`): every scene either renders or is
//! answered with exit 1 or 2 and one line, under an address-space cap of 2 GB and within
//! 60 s, with nothing left in the output directory but a finished image. The cases are the
//! ones an independent reliability run found aborting, hanging or exhausting memory: fast
//! motion off screen and past the eye, a camera dolly, huge buckets, images and sample
//! counts, shading rate 1e-6, fov 1e-30, vertices at 1e30, glass at depth 64, and more.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The address-space cap of every run, as `prlimit --as` sets it.
const CAP_BYTES: u64 = 2_000_000_000;
/// The wall-clock limit of every run.
const LIMIT: Duration = Duration::from_secs(60);

fn extreme(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/extreme").join(name)
}

/// What a run did.
struct Run {
    code: i32,
    stderr: String,
    stdout: String,
    /// Names of the files in the output directory afterwards.
    left: Vec<String>,
    out: PathBuf,
    _dir: tempfile::TempDir,
}

/// Run `reyes-render SCENE -o DIR/out.exr ARGS` under `prlimit --as=CAP_BYTES`, killing it
/// after [`LIMIT`]. Panics (fails the test) on a signal, a timeout or a missing `prlimit`:
/// a cap that could not be set must not pass silently.
fn capped(scene: &Path, args: &[&str]) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.exr");
    let mut child = Command::new("prlimit")
        .arg(format!("--as={CAP_BYTES}"))
        .arg(env!("CARGO_BIN_EXE_reyes-render"))
        .arg(scene)
        .arg("-o")
        .arg(&out)
        .args(["--quiet", "--threads", "2"])
        .args(args)
        .env_remove("REYES_MEMORY_LIMIT")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("prlimit (util-linux) must be installed for the capped catalogue");
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > LIMIT {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{}: still running after {LIMIT:?}", scene.display());
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let output = child.wait_with_output().unwrap();
    let code = status
        .code()
        .unwrap_or_else(|| panic!("{}: killed by a signal ({status})", scene.display()));
    let left = reyes_testkit::files::names(dir.path());
    Run {
        code,
        stderr: String::from_utf8_lossy(&output.stderr).into_owned(),
        stdout: String::from_utf8_lossy(&output.stdout).into_owned(),
        left,
        out,
        _dir: dir,
    }
}

/// Every scene of the catalogue with the exit code it must give.
const CATALOGUE: &[(&str, i32)] = &[
    ("big-bucket.ron", 2),
    ("huge-bucket.ron", 2),
    ("huge-image.ron", 2),
    ("tiny-shading-rate.ron", 1),
    ("deep-transparency.ron", 1),
    ("deform-behind.ron", 0),
    ("deform-through-eye.ron", 0),
    ("dolly.ron", 0),
    ("fast-right.ron", 0),
    ("fast-up.ron", 0),
    ("glass-deep.ron", 0),
    ("huge-corner.ron", 0),
    ("motion-1e4.ron", 0),
    ("motion-to-eye.ron", 0),
    ("motion-toward-eye.ron", 0),
    ("tiny-fov.ron", 0),
    ("triangle-all-behind.ron", 0),
    ("triangle-behind.ron", 0),
    ("vertex-1e30.ron", 0),
];

#[test]
fn the_catalogue_lists_every_file() {
    let files = reyes_testkit::files::names(&extreme(""));
    let mut listed: Vec<String> = CATALOGUE.iter().map(|(n, _)| n.to_string()).collect();
    listed.sort();
    assert_eq!(files, listed);
}

#[test]
fn every_extreme_scene_renders_or_is_refused_in_one_line_under_a_2_gb_cap() {
    let mut failures = Vec::new();
    for &(name, expected) in CATALOGUE {
        let run = capped(&extreme(name), &[]);
        let lines: Vec<&str> = run.stderr.lines().collect();
        let ok = match run.code {
            0 => run.left == ["out.exr"],
            1 | 2 => run.left.is_empty() && lines.len() == 1,
            _ => false,
        };
        if !ok || run.code != expected {
            failures.push(format!(
                "{name}: exit {} (expected {expected}), left {:?}, stderr {:?}",
                run.code, run.left, run.stderr
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `Primary rays: N` and `Secondary rays: N` of a ray-hider `--stats` report.
fn ray_counts(stats: &str) -> (u64, u64) {
    let count = |label: &str| {
        let line = stats.lines().find(|l| l.trim_start().starts_with(label)).unwrap();
        line.trim_start()[label.len()..].split_whitespace().next().unwrap().parse().unwrap()
    };
    (count("Primary rays:"), count("Secondary rays:"))
}

#[test]
fn glass_at_depth_64_costs_a_bounded_multiple_of_depth_8() {
    let deep = extreme("glass-deep.ron");
    let dir = tempfile::tempdir().unwrap();
    let shallow = dir.path().join("glass8.ron");
    let text = std::fs::read_to_string(&deep).unwrap();
    std::fs::write(&shallow, text.replace("max_depth: 64", "max_depth: 8")).unwrap();
    let (p8, s8) = ray_counts(&capped(&shallow, &["--stats"]).stdout);
    let (p64, s64) = ray_counts(&capped(&deep, &["--stats"]).stdout);
    assert_eq!(p8, p64);
    // Every primary ray hits glass, so without a budget depth 64 would be 2^65 rays each.
    // The budget (reyes_shade::MAX_TREE_RAYS = 1024 per tree) bounds it absolutely, and the
    // issue's requirement is under 10 times the work of depth 8.
    assert!(s64 <= 1024 * p64, "{s64} secondary rays for {p64} primary");
    assert!(s64 < 10 * s8, "depth 64: {s64} secondary rays, depth 8: {s8}");
    assert!(s64 > s8, "the deeper tree traces more: {s64} vs {s8}");
}

/// The fast ball of `scenes/motion-blur.ron` moving 100 units in one shutter, alone on a black
/// background, shutter `[open, close]` with the ball's keys at its ends.
fn fast_ball(open: f32, close: f32) -> String {
    let x = |t: f32| -0.2 + 100.0 * t;
    format!(
        "Scene(
  image: (width: 320, height: 240),
  camera: (eye: (0.0, 1.5, -8.0), look_at: (0.0, 0.8, 0.0), fov: 40.0, hither: 0.1, yon: 100.0,
           shutter: (open: {open}, close: {close})),
  hider: (pixel_samples: (8, 8), filter: (kind: Box, width: 1.0), seed: 11),
  lights: [Ambient(intensity: 1.0)],
  objects: [(name: \"fast\", shape: Sphere(radius: 0.5),
     motion: [(time: {open}, transform: [Translate(({}, 1.8, 1.5))]),
              (time: {close}, transform: [Translate(({}, 1.8, 1.5))])],
     material: Constant(color: (1.0, 1.0, 1.0)))],
)
",
        x(open),
        x(close)
    )
}

fn alpha_sum(path: &Path) -> f64 {
    let film = reyes_film::read_exr(path).unwrap();
    film.rgba().iter().map(|p| f64::from(p[3])).sum()
}

#[test]
fn a_ball_moving_100_units_has_the_blur_of_its_motion_in_shorter_segments() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole.ron");
    std::fs::write(&whole, fast_ball(0.0, 1.0)).unwrap();
    let run = capped(&whole, &["--stats"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let full = alpha_sum(&run.out);
    // The same motion as 16 shutters of 1/16 each: the whole shutter's coverage is their mean.
    let segments = 16;
    let mut parts = 0.0;
    for k in 0..segments {
        let (open, close) = (k as f32 / segments as f32, (k + 1) as f32 / segments as f32);
        let path = dir.path().join(format!("part{k}.ron"));
        std::fs::write(&path, fast_ball(open, close)).unwrap();
        let r = capped(&path, &[]);
        assert_eq!(r.code, 0, "{}", r.stderr);
        parts += alpha_sum(&r.out);
    }
    let mean = parts / segments as f64;
    assert!(full > 20.0, "the ball is seen: summed alpha {full}");
    // Both are sums over pixels of the fraction of 64 samples (box filter of one pixel) that
    // hit the ball: an estimate of the time-integrated covered area in pixels. With at most
    // `full * 64` hits, the count's standard deviation is below sqrt(full * 64) samples, so
    // the summed alpha's is below sqrt(full / 64) (independent sampling; jitter only lowers
    // it); the mean of 16 segment renders has a quarter of that deviation, and the two
    // estimates stay within 4 standard deviations of their difference.
    let sigma = (full / 64.0).sqrt() * (1.0 + 1.0 / 16.0_f64).sqrt();
    assert!(
        (full - mean).abs() < 4.0 * sigma,
        "whole shutter {full}, segments {mean}, sigma {sigma}"
    );
    // And the dicer's work stays bounded: well under a million micropolygons.
    let line = run.stdout.lines().find(|l| l.contains("Dicer:")).unwrap();
    let mps: u64 = line
        .split(',')
        .find(|p| p.contains("micropolygons"))
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(mps < 1_000_000, "{line}");
}

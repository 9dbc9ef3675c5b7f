//! `cargo xtask bench [--runs N] [--threads T] [--baseline BIN] [SCENE...]`: render every
//! scene of `scenes/bench/` N times with the release binary and report wall time (min, median,
//! max), peak resident memory, micropolygons, sample tests per second and hits; also written as
//! JSON to `target/bench.json` so runs can be compared.
//!
//! With `--baseline BIN` (another build's `reyes-render`), every run renders each scene with
//! both binaries, alternating which goes first, so that a noisy machine slows both alike; the
//! table then adds the baseline's median and the ratio new / baseline.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// One scene's measurements.
struct Row {
    scene: String,
    times: Vec<f64>,
    /// The baseline binary's times (empty without `--baseline`).
    base_times: Vec<f64>,
    peak_mb: f64,
    micropolygons: u64,
    tests: u64,
    hits: u64,
    hide_s: f64,
}

fn field<'a>(stats: &'a str, prefix: &str) -> Option<&'a str> {
    stats.lines().find_map(|l| l.trim_start().strip_prefix(prefix))
}

fn number_after(text: &str, key: &str) -> Option<f64> {
    let i = text.find(key)? + key.len();
    text[i..]
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .find(|t| !t.is_empty())?
        .parse()
        .ok()
}

fn number_before(text: &str, key: &str) -> Option<f64> {
    let i = text.find(key)?;
    text[..i].split_whitespace().last()?.trim_start_matches('(').parse().ok()
}

pub fn run(root: &Path, args: &[String]) -> Result<(), String> {
    let mut runs = 3usize;
    let mut threads: Option<String> = None;
    let mut baseline: Option<PathBuf> = None;
    let mut only = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--baseline" => {
                baseline = Some(PathBuf::from(it.next().ok_or("--baseline takes a binary")?))
            }
            "--runs" => {
                runs = it.next().and_then(|v| v.parse().ok()).ok_or("--runs takes a number")?
            }
            "--threads" => threads = Some(it.next().ok_or("--threads takes a number")?.clone()),
            s => only.push(s.to_string()),
        }
    }
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "--quiet", "-p", "reyes-cli"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("cargo build: {e}"))?;
    if !status.success() {
        return Err("cargo build --release -p reyes-cli failed".into());
    }
    let bin = root.join("target/release/reyes-render");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root.join("scenes/bench"))
        .map_err(|e| format!("scenes/bench: {e}"))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        // RON scenes, and RIB scenes without a RON twin of the same name (`deep.rib` is
        // `deep.ron`'s; `shaded.rib` has none: its shaders need RIB).
        .filter(|p| {
            p.extension().is_some_and(|e| e == "ron")
                || (p.extension().is_some_and(|e| e == "rib") && !p.with_extension("ron").exists())
        })
        .filter(|p| {
            only.is_empty() || only.iter().any(|o| p.file_stem().is_some_and(|s| s == o.as_str()))
        })
        .collect();
    scenes.sort();
    let out_dir = root.join("target/bench");
    std::fs::create_dir_all(&out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let mut rows = Vec::new();
    for scene in &scenes {
        let name = scene.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let mut row = Row {
            scene: name.clone(),
            times: Vec::new(),
            base_times: Vec::new(),
            peak_mb: 0.0,
            micropolygons: 0,
            tests: 0,
            hits: 0,
            hide_s: f64::INFINITY,
        };
        for run in 0..runs {
            let base_out = out_dir.join(format!("{name}.baseline.exr"));
            let time_base = |row: &mut Row| -> Result<(), String> {
                if let Some(b) = &baseline {
                    let (wall, _) = render_timed(b, scene, &base_out, &threads)
                        .map_err(|e| format!("{name} (baseline): {e}"))?;
                    row.base_times.push(wall);
                }
                Ok(())
            };
            if run % 2 == 0 {
                time_base(&mut row)?;
            }
            let (wall, stats) =
                render_timed(&bin, scene, &out_dir.join(format!("{name}.exr")), &threads)
                    .map_err(|e| format!("{name}: {e}"))?;
            if run % 2 == 1 {
                time_base(&mut row)?;
            }
            row.times.push(wall);
            row.peak_mb = row.peak_mb.max(
                field(&stats, "Memory:").and_then(|m| number_after(m, "resident")).unwrap_or(0.0),
            );
            let dicer = field(&stats, "Dicer:").unwrap_or("");
            row.micropolygons = number_before(dicer, "micropolygons").unwrap_or(0.0) as u64;
            let samples = field(&stats, "Hider samples:").unwrap_or("");
            row.hits = number_after(samples, "(").unwrap_or(0.0) as u64;
            let misses = number_before(samples, "misses").unwrap_or(0.0) as u64;
            row.tests = row.hits + misses;
            let time = field(&stats, "Time:").unwrap_or("");
            row.hide_s = row.hide_s.min(number_after(time, "hide").unwrap_or(f64::INFINITY));
        }
        row.times.sort_by(f64::total_cmp);
        row.base_times.sort_by(f64::total_cmp);
        rows.push(row);
    }
    println!(
        "{:<14} {:>8} {:>8} {:>8} {:>9} {:>12} {:>14} {:>13} {:>7}",
        "scene",
        "min s",
        "median s",
        "max s",
        "peak MB",
        "micropolys",
        "sample tests",
        "tests/s (M)",
        "hits %"
    );
    let mut json = String::from("[\n");
    for (i, r) in rows.iter().enumerate() {
        let (min, med, max) = (r.times[0], r.times[r.times.len() / 2], r.times[r.times.len() - 1]);
        let rate = r.tests as f64 / r.hide_s / 1e6;
        let hit_pct = 100.0 * r.hits as f64 / r.tests.max(1) as f64;
        println!(
            "{:<14} {:>8.3} {:>8.3} {:>8.3} {:>9.1} {:>12} {:>14} {:>13.1} {:>7.2}",
            r.scene, min, med, max, r.peak_mb, r.micropolygons, r.tests, rate, hit_pct
        );
        json.push_str(&format!(
            "  {{\"scene\": \"{}\", \"runs\": {}, \"threads\": {}, \"min_s\": {min:.4}, \"median_s\": {med:.4}, \"max_s\": {max:.4}, \"peak_mb\": {:.1}, \"micropolygons\": {}, \"sample_tests\": {}, \"hits\": {}, \"tests_per_s\": {:.0}}}{}\n",
            r.scene,
            r.times.len(),
            threads.as_deref().unwrap_or("null"),
            r.peak_mb,
            r.micropolygons,
            r.tests,
            r.hits,
            rate * 1e6,
            if i + 1 < rows.len() { "," } else { "" }
        ));
    }
    json.push_str("]\n");
    if baseline.is_some() {
        println!(
            "\n{:<14} {:>14} {:>12} {:>12}",
            "scene", "baseline med s", "new med s", "new / base"
        );
        for r in &rows {
            let (b, n) = (r.base_times[r.base_times.len() / 2], r.times[r.times.len() / 2]);
            println!("{:<14} {:>14.3} {:>12.3} {:>12.3}", r.scene, b, n, n / b);
        }
    }
    let path = root.join("target/bench.json");
    std::fs::write(&path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The `heavy-motion` benchmark scene with `n x n` spheres: the same header, spheres spaced
/// 2.5 moving one unit to the right over the shutter, the camera distance scaled by
/// `n / 20` so the grid keeps its angular size (the spheres shrink on screen as they multiply).
fn heavy_motion_scene(header: &str, n: usize) -> String {
    let z = 60.235 * n as f64 / 20.0;
    let half = (n as f64 - 1.0) / 2.0;
    let shade = |k: usize| 0.3 + 0.7 * k as f64 / (n as f64 - 1.0).max(1.0);
    let mut s =
        format!("// `cargo xtask scaling`: heavy-motion with {n} x {n} spheres at depth {z:.3}.\n");
    s.push_str(header);
    for i in 0..n {
        for j in 0..n {
            let (x, y) = ((i as f64 - half) * 2.5, (j as f64 - half) * 2.5);
            s.push_str(&format!(
                "    (name: \"ball-{i}-{j}\", shape: Sphere(radius: 1.0), motion: [(time: 0.0, transform: [Translate(({:.6}, {y:.6}, {z:.6}))]), (time: 1.0, transform: [Translate(({:.6}, {y:.6}, {z:.6}))])],\n     material: Plastic(color: ({:.6}, 0.400000, {:.6}), ka: 1.0, kd: 0.7, ks: 0.5, roughness: 0.1)),\n",
                x - 0.5,
                x + 0.5,
                shade(i),
                shade(j)
            ));
        }
    }
    s.push_str("  ],\n)\n");
    s
}

/// `cargo xtask scaling [--threads T] [N...]`: render `heavy-motion` with N x N spheres
/// (default N = 20, 40, 80; scenes written to `target/scaling/`) and report primitives,
/// micropolygons, the most held at once, peak resident memory and time: with lazy dicing,
/// memory follows the buckets in flight, not the primitive count.
pub fn scaling(root: &Path, args: &[String]) -> Result<(), String> {
    let mut threads: Option<String> = None;
    let mut sizes = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--threads" => threads = Some(it.next().ok_or("--threads takes a number")?.clone()),
            s => sizes.push(s.parse::<usize>().map_err(|_| format!("not a size: {s}"))?),
        }
    }
    if sizes.is_empty() {
        sizes = vec![20, 40, 80];
    }
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "--quiet", "-p", "reyes-cli"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("cargo build: {e}"))?;
    if !status.success() {
        return Err("cargo build --release -p reyes-cli failed".into());
    }
    let bin = root.join("target/release/reyes-render");
    let source = root.join("scenes/bench/heavy-motion.ron");
    let text =
        std::fs::read_to_string(&source).map_err(|e| format!("{}: {e}", source.display()))?;
    let start = text.find("  objects: [\n").ok_or("heavy-motion.ron: no objects list")?;
    // From `Scene(` (without the comment lines) up to the first object: image, camera,
    // hider, lights.
    let from = text.find("Scene(").ok_or("heavy-motion.ron: no Scene(")?;
    let header = format!("{}  objects: [\n", &text[from..start]);
    let dir = root.join("target/scaling");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    println!(
        "{:>4} {:>10} {:>14} {:>12} {:>9} {:>8} {:>8}",
        "N", "primitives", "micropolygons", "most held", "peak MB", "dice s", "total s"
    );
    for n in sizes {
        let scene = dir.join(format!("heavy-motion-{n}.ron"));
        std::fs::write(&scene, heavy_motion_scene(&header, n))
            .map_err(|e| format!("{}: {e}", scene.display()))?;
        let (wall, stats) =
            render_timed(&bin, &scene, &dir.join(format!("heavy-motion-{n}.exr")), &threads)
                .map_err(|e| format!("N = {n}: {e}"))?;
        let dicer = field(&stats, "Dicer:").unwrap_or("");
        let memory = field(&stats, "Memory:").unwrap_or("");
        let time = field(&stats, "Time:").unwrap_or("");
        println!(
            "{:>4} {:>10} {:>14} {:>12} {:>9.1} {:>8.2} {:>8.2}",
            n,
            number_before(dicer, "primitives").unwrap_or(0.0) as u64,
            number_before(dicer, "micropolygons").unwrap_or(0.0) as u64,
            number_after(memory, "at most").unwrap_or(0.0) as u64,
            number_after(memory, "resident").unwrap_or(0.0),
            number_after(time, "dice").unwrap_or(0.0),
            wall
        );
    }
    Ok(())
}

/// Render `scene` to `out` with the release binary `bin` (and `--threads` when given) as a
/// child process: its wall time in seconds and its `--stats` text.
fn render_timed(
    bin: &Path,
    scene: &Path,
    out: &Path,
    threads: &Option<String>,
) -> Result<(f64, String), String> {
    let mut cmd = Command::new(bin);
    cmd.arg(scene).arg("-o").arg(out).args(["--stats", "-q"]);
    if let Some(t) = threads {
        cmd.args(["--threads", t]);
    }
    let t0 = Instant::now();
    let result = cmd.output().map_err(|e| format!("{}: {e}", bin.display()))?;
    let wall = t0.elapsed().as_secs_f64();
    if !result.status.success() {
        return Err(String::from_utf8_lossy(&result.stderr).trim().to_string());
    }
    Ok((wall, String::from_utf8_lossy(&result.stdout).into_owned()))
}

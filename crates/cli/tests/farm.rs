//! Rendering in pieces (docs/farm.md): tiles merged into the whole render byte for byte,
//! crop windows, bad merge inputs, checkpoints resumed after SIGKILL, and the progress lines
//! a farm reads. Render sizes are small (64 x 48 and below): every property here is exact,
//! so size adds nothing but time.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_reyes-render"))
}

fn run(dir: &Path, args: &[&str]) -> Output {
    bin().current_dir(dir).args(args).output().expect("run reyes-render")
}

fn ok(dir: &Path, args: &[&str]) {
    let o = run(dir, args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", String::from_utf8_lossy(&o.stderr));
}

fn bytes(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `scenes/NAME.ron` at `w x h` pixels (the same view: the field of view spans the shorter
/// side), with `edit` applied, written into `dir` as `file`.
fn scene(
    dir: &Path,
    name: &str,
    (w, h): (u32, u32),
    file: &str,
    edit: impl Fn(String) -> String,
) -> String {
    let text = std::fs::read_to_string(root().join(format!("scenes/{name}.ron")))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let start = text.find("image: (").expect("image");
    let end = start + text[start..].find(')').expect("image end") + 1;
    let text = format!("{}image: (width: {w}, height: {h}){}", &text[..start], &text[end..]);
    std::fs::write(dir.join(file), edit(text)).expect("write scene");
    file.to_string()
}

/// Render `scene` whole, then as 1, 4 and 7 tiles (each with a different thread count),
/// merge each split and compare the files byte for byte.
fn tiles_merge_exactly(dir: &Path, scene: &str, extra: &[&str], splits: &[usize]) {
    let full = format!("{scene}.full.exr");
    let mut args = vec![scene, "-o", &full];
    args.extend_from_slice(extra);
    ok(dir, &args);
    let whole = bytes(&dir.join(&full));
    for &n in splits {
        let mut tiles = Vec::new();
        for i in 1..=n {
            let tile = format!("{scene}.{n}.{i}.tile.exr");
            let spec = format!("{i}/{n}");
            let threads = (1 + i % 3).to_string();
            let mut args = vec![scene, "--tile", &spec, "--threads", &threads, "-o", &tile];
            args.extend_from_slice(extra);
            ok(dir, &args);
            tiles.push(tile);
        }
        // In reverse order: the merge sorts them.
        tiles.reverse();
        let merged = format!("{scene}.{n}.merged.exr");
        let mut args = vec!["merge"];
        args.extend(tiles.iter().map(String::as_str));
        args.extend(["-o", merged.as_str()]);
        ok(dir, &args);
        assert!(
            whole == bytes(&dir.join(&merged)),
            "{scene} {extra:?}: {n} tiles merge to another file"
        );
    }
}

#[test]
fn tiles_merge_into_the_whole_render_byte_for_byte() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    // Each scene's filter is 2 pixels wide (a border of 1): pixels along every bucket edge
    // take samples from two or four buckets, which may lie in different tiles. At 64 x 48
    // with 16 x 16 buckets the extended screen has 5 x 4 = 20 buckets: 7 tiles are of 3 and
    // 2 buckets, and tile borders fall inside bucket rows.
    let same = |t: String| t;
    let stat = scene(dir, "spheres", (64, 48), "static.ron", same);
    tiles_merge_exactly(dir, &stat, &[], &[1, 4, 7]);
    let motion = scene(dir, "motion-blur", (64, 48), "motion.ron", same);
    tiles_merge_exactly(dir, &motion, &[], &[1, 4, 7]);
    let dof = scene(dir, "depth-of-field", (64, 40), "dof.ron", same);
    tiles_merge_exactly(dir, &dof, &[], &[1, 4, 7]);
    // A crop window: tiles split the crop's buckets; both files hold the crop's pixels.
    tiles_merge_exactly(dir, &motion, &["--crop", "0.1,0.8,0.2,0.9"], &[1, 4, 7]);
    // AOV layers merge the same way (the AOV scene's filters include Nearest and Min).
    let aovs = scene(dir, "aovs", (48, 36), "aovs.ron", same);
    tiles_merge_exactly(dir, &aovs, &[], &[1, 7]);
    // The ray-tracing hider's buckets too.
    let rays = scene(dir, "spheres", (40, 30), "rays.ron", |t| {
        t.replacen("hider: (", "hider: (method: RayTrace, ", 1)
    });
    tiles_merge_exactly(dir, &rays, &[], &[4]);
}

#[test]
fn a_crop_window_keeps_each_pixel_of_the_whole_frame() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    ok(dir, &[&s, "-o", "full.exr"]);
    ok(dir, &[&s, "--crop", "0.25,0.75,0.125,0.5", "-o", "crop.exr"]);
    let full = reyes_film::read_exr(&dir.join("full.exr")).expect("full");
    let crop = reyes_film::read_exr(&dir.join("crop.exr")).expect("crop");
    // RI Spec 3.2: columns ceil(64 * 0.25) = 16 to ceil(64 * 0.75) - 1 = 47, rows 6 to 23.
    assert_eq!((crop.width(), crop.height()), (32, 18));
    for y in 0..18 {
        for x in 0..32 {
            let (a, b) = (full.pixel(x + 16, y + 6), crop.pixel(x, y));
            let bits = |p: Option<[f32; 4]>| p.map(|p| p.map(f32::to_bits));
            assert_eq!(bits(a), bits(b), "({x}, {y})");
        }
    }
    // The same crop from RIB's CropWindow.
    let rib = "Format 64 48 1\nCropWindow 0.25 0.75 0.125 0.5\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n\
               WorldBegin\nTranslate 0 0 5\nSurface \"matte\"\nSphere 1 -1 1 360\nWorldEnd\n";
    std::fs::write(dir.join("c.rib"), rib).expect("rib");
    let no_crop = rib.replace("CropWindow 0.25 0.75 0.125 0.5\n", "");
    std::fs::write(dir.join("n.rib"), no_crop).expect("rib");
    ok(dir, &["c.rib", "-o", "c.exr"]);
    ok(dir, &["n.rib", "--crop", "0.25,0.75,0.125,0.5", "-o", "n.exr"]);
    let (c, n) = (
        reyes_film::read_exr(&dir.join("c.exr")).expect("c"),
        reyes_film::read_exr(&dir.join("n.exr")).expect("n"),
    );
    assert_eq!((c.width(), c.height()), (32, 18));
    assert_eq!(c.rgba(), n.rgba());
}

/// One line on stderr, exit 2, naming what is wrong.
fn refused(o: &Output, what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{what}: {err}");
    assert_eq!(err.lines().count(), 1, "{what}: {err}");
    assert!(err.contains(what), "expected '{what}' in: {err}");
}

#[test]
fn bad_merge_inputs_are_refused_in_one_line() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    for i in 1..=3 {
        ok(dir, &[&s, "--tile", &format!("{i}/3"), "-o", &format!("t{i}.exr")]);
    }
    ok(dir, &[&s, "--tile", "2/3", "--seed", "99", "-o", "seed.exr"]);
    ok(dir, &[&s, "--tile", "2/3", "--samples", "2x2", "-o", "samples.exr"]);
    ok(dir, &[&s, "--tile", "2/4", "-o", "four.exr"]);
    ok(dir, &[&s, "-o", "plain.exr"]);
    let merge = |tiles: &[&str]| {
        let mut args = vec!["merge"];
        args.extend_from_slice(tiles);
        args.extend(["-o", "out.exr"]);
        run(dir, &args)
    };
    refused(&merge(&["t1.exr", "t3.exr"]), "tile 2/3 missing");
    refused(&merge(&["t1.exr", "t2.exr", "t2.exr", "t3.exr"]), "tile 2/3 given twice");
    refused(
        &merge(&["t1.exr", "seed.exr", "t3.exr"]),
        "seed.exr: a tile of a different render than t1.exr",
    );
    refused(&merge(&["t1.exr", "samples.exr", "t3.exr"]), "a tile of a different render");
    refused(&merge(&["t1.exr", "four.exr", "t3.exr"]), "split differently");
    refused(
        &merge(&["t1.exr", "t2.exr", "plain.exr"]),
        "plain.exr: unexpected OpenEXR contents: not a reyes-render tile",
    );
    std::fs::write(dir.join("junk.exr"), b"not an image").expect("junk");
    refused(&merge(&["t1.exr", "junk.exr"]), "junk.exr");
    let o = merge(&["t1.exr", "nowhere.exr"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!dir.join("out.exr").exists(), "no output after a refused merge");
    // Tiles of more tiles than the frame has buckets, and tiles as PNG, are refused too.
    refused(
        &run(dir, &[&s, "--tile", "1/21", "-o", "x.exr"]),
        "--tile 1/21: the frame has 20 buckets",
    );
    refused(&run(dir, &[&s, "--tile", "1/2", "-o", "x.png"]), "--tile: a tile is written as .exr");
    ok(dir, &["merge", "t3.exr", "t1.exr", "t2.exr", "-o", "out.png"]);
}

/// Parsed `reyes-render: progress: [frame F ][tile I/N ]P% (D/T buckets) E elapsed L left`.
#[derive(Debug, PartialEq)]
struct ProgressLine {
    frame: Option<i32>,
    tile: Option<(u32, u32)>,
    percent: u32,
    done: u64,
    total: u64,
    elapsed: u64,
    left: Option<u64>,
}

fn clock(s: &str) -> Option<u64> {
    let parts: Vec<u64> = s.split(':').map(|p| p.parse().ok()).collect::<Option<_>>()?;
    match parts[..] {
        [h, m, s] if m < 60 && s < 60 && s.to_string().len() <= 2 => Some(h * 3600 + m * 60 + s),
        _ => None,
    }
}

/// The documented grammar of docs/farm.md, word by word.
fn parse_progress(line: &str) -> Option<ProgressLine> {
    let rest = line.strip_prefix("reyes-render: progress: ")?;
    let mut w: Vec<&str> = rest.split(' ').collect();
    let mut frame = None;
    let mut tile = None;
    if w.first() == Some(&"frame") {
        frame = Some(w.get(1)?.parse().ok()?);
        w.drain(..2);
    }
    if w.first() == Some(&"tile") {
        let (i, n) = w.get(1)?.split_once('/')?;
        tile = Some((i.parse().ok()?, n.parse().ok()?));
        w.drain(..2);
    }
    let [pct, count, "buckets)", elapsed, "elapsed", left, "left"] = w[..] else { return None };
    let percent = pct.strip_suffix('%')?.parse().ok()?;
    let (done, total) = count.strip_prefix('(')?.split_once('/')?;
    let left = if left == "--:--:--" { None } else { Some(clock(left)?) };
    Some(ProgressLine {
        frame,
        tile,
        percent,
        done: done.parse().ok()?,
        total: total.parse().ok()?,
        elapsed: clock(elapsed)?,
        left,
    })
}

#[test]
fn progress_lines_parse_as_documented() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    let o =
        run(dir, &[&s, "--tile", "2/3", "--progress-every", "0", "--threads", "1", "-o", "t.exr"]);
    assert_eq!(o.status.code(), Some(0));
    let err = String::from_utf8_lossy(&o.stderr);
    // The progress lines, then the file written.
    assert_eq!(err.lines().last(), Some("reyes-render: wrote t.exr"), "{err}");
    let lines: Vec<ProgressLine> = err
        .lines()
        .filter(|l| !l.starts_with("reyes-render: wrote "))
        .map(|l| parse_progress(l).unwrap_or_else(|| panic!("not a progress line: {l}")))
        .collect();
    // Tile 2 of 3 of 20 buckets holds 7: a line after each of the first six, then 100%.
    assert_eq!(lines.len(), 7, "{err}");
    for (k, l) in lines.iter().enumerate() {
        assert_eq!((l.frame, l.tile, l.total), (None, Some((2, 3)), 7));
        assert_eq!(l.done, k as u64 + 1);
        assert_eq!(u64::from(l.percent), l.done * 100 / 7);
        assert!(l.left.is_some());
    }
    assert_eq!(lines.last().map(|l| (l.percent, l.left)), Some((100, Some(0))));
    // A render shorter than the interval prints none (only the file written); --quiet
    // prints none.
    let o = run(dir, &[&s, "-o", "a.exr"]);
    assert_eq!(String::from_utf8_lossy(&o.stderr), "reyes-render: wrote a.exr\n");
    let o = run(dir, &[&s, "--quiet", "--progress-every", "0", "-o", "b.exr"]);
    assert!(o.stderr.is_empty());
    assert_eq!(
        parse_progress(
            "reyes-render: progress: frame -3 37% (120/324 buckets) 101:00:42 elapsed --:--:-- left"
        ),
        Some(ProgressLine {
            frame: Some(-3),
            tile: None,
            percent: 37,
            done: 120,
            total: 324,
            elapsed: 363642,
            left: None
        })
    );
    assert_eq!(
        parse_progress("reyes-render: progress: 37% (120/324 buckets) 00:00:42 elapsed"),
        None
    );
}

/// Every entry of a checkpoint directory is a complete bucket file (or a complete one caught
/// between its link and its rename); the number of bucket files.
fn complete_bucket_files(dir: &Path) -> usize {
    let mut n = 0;
    for sub in std::fs::read_dir(dir).expect("checkpoint dir") {
        let sub = sub.expect("entry").path();
        for f in
            std::fs::read_dir(&sub).map(|d| d.flatten().collect::<Vec<_>>()).unwrap_or_default()
        {
            let p = f.path();
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default().to_string();
            // A complete file is linked to a temporary name and renamed over its own in the
            // next call (crates/film/src/atomic.rs): a listing may catch it in between.
            if name.starts_with(".reyes-film-") && name.ends_with(".tmp") {
                continue;
            }
            assert!(
                name.starts_with("bucket.") && name.ends_with(".exr"),
                "unexpected {}",
                p.display()
            );
            // A file renamed away between listing and reading is fine; one read is whole.
            if p.exists() {
                let read = reyes_film::read_buckets(&p);
                assert!(read.is_ok() || !p.exists(), "{}: {:?}", p.display(), read.err());
                n += 1;
            }
        }
    }
    n
}

#[test]
fn a_render_killed_at_half_resumes_to_the_same_file() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    // Heavier buckets (more samples) so that the kill lands mid-frame.
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| {
        t.replace("pixel_samples: (4, 4)", "pixel_samples: (8, 8)")
    });
    ok(dir, &[&s, "-o", "whole.exr"]);
    let ck = dir.join("ck");
    let mut child = bin()
        .current_dir(dir)
        .args([
            &s,
            "--checkpoint",
            "ck",
            "--progress-every",
            "0",
            "--threads",
            "1",
            "-o",
            "out.exr",
        ])
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let stderr = child.stderr.take().expect("stderr");
    let mut seen = 0;
    for line in BufReader::new(stderr).lines() {
        let line = line.expect("line");
        let p = parse_progress(&line).unwrap_or_else(|| panic!("{line}"));
        if ck.exists() {
            complete_bucket_files(&ck);
        }
        if p.percent >= 50 {
            seen = p.done;
            child.kill().expect("SIGKILL");
            break;
        }
    }
    let status = child.wait().expect("wait");
    assert_eq!(std::os::unix::process::ExitStatusExt::signal(&status), Some(9), "killed");
    assert!(!dir.join("out.exr").exists());
    let kept = complete_bucket_files(&ck);
    assert!(kept as u64 >= seen && kept < 20, "{kept} bucket files after {seen} buckets of 20");

    // Resumed with the same arguments: the first line already counts the kept buckets.
    let o = run(
        dir,
        &[&s, "--checkpoint", "ck", "--progress-every", "0", "--threads", "2", "-o", "out.exr"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    let first = err
        .lines()
        .next()
        .and_then(parse_progress)
        .unwrap_or_else(|| panic!("the first line is not a progress line:\n{err}"));
    assert_eq!(first.done, kept as u64 + 1, "{err}");
    assert!(bytes(&dir.join("whole.exr")) == bytes(&dir.join("out.exr")), "resumed file differs");
    assert_eq!(std::fs::read_dir(&ck).map(|d| d.count()).unwrap_or(0), 0, "checkpoint removed");
}

#[test]
fn a_checkpoint_of_other_arguments_is_never_mixed_in() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    ok(dir, &[&s, "--seed", "3", "-o", "seed3.exr"]);
    // Leave a checkpoint of seed 1 behind: a render killed after its first bucket.
    let killed = |seed: &str| {
        let mut child = bin()
            .current_dir(dir)
            .args([&s, "--seed", seed, "--checkpoint", "ck", "--threads", "1", "-o", "k.exr"])
            .env("REYES_TEST_PAUSE", "render")
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn");
        let stderr = child.stderr.take().expect("stderr");
        for line in BufReader::new(stderr).lines() {
            if line.expect("line").contains("test: paused rendering") {
                break;
            }
        }
        child.kill().expect("SIGKILL");
        child.wait().expect("wait");
    };
    killed("1");
    let folders: Vec<PathBuf> =
        std::fs::read_dir(dir.join("ck")).expect("ck").flatten().map(|e| e.path()).collect();
    assert_eq!(folders.len(), 1);
    let seed1 = folders[0].clone();
    let count = std::fs::read_dir(&seed1).expect("seed1").count();
    assert!(count > 0);
    // Another seed, the same directory: its own folder; the result is that seed's render.
    ok(dir, &[&s, "--seed", "3", "--checkpoint", "ck", "-o", "out.exr"]);
    assert!(bytes(&dir.join("seed3.exr")) == bytes(&dir.join("out.exr")));
    assert_eq!(std::fs::read_dir(&seed1).expect("seed1").count(), count, "seed 1 untouched");
    // A bucket file of seed 1 put into seed 5's folder is refused, not used.
    killed("5");
    let seed5 = std::fs::read_dir(dir.join("ck"))
        .expect("ck")
        .flatten()
        .map(|e| e.path())
        .find(|p| *p != seed1)
        .expect("seed 5");
    let stray =
        std::fs::read_dir(&seed1).expect("seed1").flatten().next().expect("a bucket").path();
    let name = stray.file_name().expect("name").to_owned();
    std::fs::copy(&stray, seed5.join(&name)).expect("copy");
    let o = run(dir, &[&s, "--seed", "5", "--checkpoint", "ck", "-o", "out5.exr"]);
    refused(&o, "--checkpoint: a bucket of another render");
    assert!(!dir.join("out5.exr").exists());
}

#[test]
fn a_ron_animation_renders_frame_by_frame_and_through_tiles() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let anim = scene(dir, "motion-blur", (48, 36), "anim.ron", |t| {
        t.replacen("seed: 5", "seed: ${frame}", 1).replacen(
            "eye: (0.0,",
            "eye: (${key(1, -1, 3, 1)},",
            1,
        )
    });
    let still =
        scene(dir, "motion-blur", (48, 36), "still.ron", |t| t.replacen("seed: 5", "seed: 2", 1));
    assert!(std::fs::read_to_string(dir.join(&anim)).expect("anim").contains("eye: (${key("));
    ok(dir, &[&anim, "--frames", "1-3", "-o", "out.####.exr"]);
    ok(dir, &[&still, "-o", "still.exr"]);
    let frame = |n: u32| reyes_film::read_exr(&dir.join(format!("out.{n:04}.exr"))).expect("frame");
    // Frame 2 is the key's midpoint (eye x + 0) with seed 2: the still scene's pixels.
    let still = reyes_film::read_exr(&dir.join("still.exr")).expect("still");
    assert_eq!(frame(2).rgba(), still.rgba());
    assert_ne!(frame(1).rgba(), frame(3).rgba());
    // Frame 3 through tiles merges to frame 3's file.
    for i in 1..=4 {
        ok(
            dir,
            &[
                &anim,
                "--frames",
                "3",
                "--tile",
                &format!("{i}/4"),
                "-o",
                &format!("f3.t{i}.####.exr"),
            ],
        );
    }
    let tiles: Vec<String> = (1..=4).map(|i| format!("f3.t{i}.0003.exr")).collect();
    let mut args = vec!["merge"];
    args.extend(tiles.iter().map(String::as_str));
    args.extend(["-o", "f3.exr"]);
    ok(dir, &args);
    assert!(bytes(&dir.join("f3.exr")) == bytes(&dir.join("out.0003.exr")));
    // Tiles of different frames do not merge.
    ok(dir, &[&anim, "--frames", "2", "--tile", "4/4", "-o", "f2.t4.####.exr"]);
    refused(
        &run(dir, &["merge", &tiles[0], &tiles[1], &tiles[2], "f2.t4.0002.exr", "-o", "x.exr"]),
        "a tile of a different render",
    );
    // An animated scene needs its frames chosen.
    refused(
        &run(dir, &[&anim, "-o", "x.exr"]),
        "anim.ron: ${...}: the scene is animated: choose its frames with --frames",
    );
}

#[test]
fn farm_slurm_writes_its_jobs_and_names_the_set_up_without_slurm() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    let args = [
        "farm",
        "slurm",
        &s,
        "--tiles",
        "3",
        "--frames",
        "4-5",
        "-o",
        "f.####.exr",
        "--partition",
        "render",
        "--account",
        "vfx",
    ];
    let mut no_submit = args.to_vec();
    no_submit.extend(["--no-submit", "--", "--seed", "7"]);
    ok(dir, &no_submit);
    let render =
        std::fs::read_to_string(dir.join("reyes-farm/render.sbatch")).expect("render.sbatch");
    for line in [
        "#SBATCH --array=0-5",
        "#SBATCH --partition=render",
        "#SBATCH --account=vfx",
        "frames=\"4 5\"",
        "'--seed' '7'",
    ] {
        assert!(render.contains(line), "{line} not in\n{render}");
    }
    let merge = std::fs::read_to_string(dir.join("reyes-farm/merge.sbatch")).expect("merge.sbatch");
    assert!(merge.contains("frame.0005.tile.3.exr' -o 'f.0005.exr'"), "{merge}");
    // Without Slurm on PATH: exit 1, one line naming the set-up script.
    let o = bin().current_dir(dir).args(args).env("PATH", "").output().expect("run");
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("sbatch: cannot run") && err.contains("tools/slurm/up.sh"), "{err}");
    // Bad requests are refused before anything is written or submitted.
    refused(
        &run(dir, &["farm", "slurm", &s, "--tiles", "21", "--frames", "1", "-o", "f.exr"]),
        "--tiles 21: the frame has 20 buckets",
    );
    refused(
        &run(dir, &["farm", "slurm", &s, "--tiles", "2", "--frames", "3-1", "-o", "f.exr"]),
        "--frames",
    );
    let o = run(dir, &["farm", "status", "--dir", "nowhere"]);
    assert_eq!(o.status.code(), Some(1));
}

/// docs/farm.md's `-o tiles/shot.t3.exr` without `tiles/` made first: a tile, a merge and a
/// farm make their output's directory, only when the file is written (never for a render
/// that fails), and it holds nothing but the finished file. A plain render's missing
/// directory stays an error, before any work.
#[test]
fn tiles_merges_and_farms_make_their_output_directories() {
    let tmp = tempfile::tempdir().expect("tempdir");
    let dir = tmp.path();
    let s = scene(dir, "motion-blur", (64, 48), "m.ron", |t| t);
    ok(dir, &[&s, "-o", "whole.exr"]);
    for i in 1..=3 {
        ok(dir, &[&s, "--tile", &format!("{i}/3"), "-o", &format!("tiles/deep/shot.t{i}.exr")]);
    }
    let names = |d: &str| reyes_testkit::files::names(&dir.join(d));
    assert_eq!(names("tiles/deep"), ["shot.t1.exr", "shot.t2.exr", "shot.t3.exr"]);
    let tiles = ["tiles/deep/shot.t1.exr", "tiles/deep/shot.t2.exr", "tiles/deep/shot.t3.exr"];
    ok(dir, &["merge", tiles[2], tiles[0], tiles[1], "-o", "out/frames/shot.exr"]);
    assert_eq!(names("out/frames"), ["shot.exr"]);
    assert!(bytes(&dir.join("whole.exr")) == bytes(&dir.join("out/frames/shot.exr")));
    // A tile render that fails, or a refused merge, makes no directory.
    refused(&run(dir, &[&s, "--tile", "1/21", "-o", "never/t.exr"]), "--tile 1/21");
    refused(&run(dir, &["merge", tiles[0], "-o", "never/m.exr"]), "tiles 2/3, 3/3 missing");
    assert!(!dir.join("never").exists());
    // A file in the directory's place is refused before any work (exit 1, one line).
    std::fs::write(dir.join("plain"), b"x").expect("file");
    let o = run(dir, &[&s, "--tile", "1/3", "-o", "plain/sub/t.exr"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!((o.status.code(), err.lines().count()), (Some(1), 1), "{err}");
    assert!(err.contains("plain/sub/t.exr: output directory: plain is not a directory"), "{err}");
    // A plain render does not make one: a mistyped directory is reported, not created.
    let o = run(dir, &[&s, "-o", "typo/whole.exr"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("typo/whole.exr: output directory does not exist"), "{err}");
    assert!(!dir.join("typo").exists());
    // farm slurm makes the merged frames' directory with its own.
    let args = ["farm", "slurm", &s, "--tiles", "2", "--frames", "1", "-o", "frames/f.####.exr"];
    let mut args = args.to_vec();
    args.push("--no-submit");
    ok(dir, &args);
    assert!(dir.join("frames").is_dir() && dir.join("reyes-farm/tiles").is_dir());
}

//! The `reyes-render` binary as a user meets it: exit codes, one-line errors, no partial
//! output, byte-identical output for any thread count, and text that must not drift.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_reyes-render"))
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().expect("run reyes-render")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A small valid scene (a sphere), with `edit` applied to its text.
fn scene_with(dir: &Path, name: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let text = "Scene(
  image: (width: 32, height: 24),
  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 40.0, hither: 0.1, yon: 100.0),
  hider: (pixel_samples: (2, 2), filter: (kind: Gaussian, width: 2.0)),
  lights: [Ambient(intensity: 1.0)],
  objects: [(name: \"ball\", shape: Sphere(radius: 1.0), material: Matte(color: (1.0, 0.5, 0.2)))],
)
";
    let path = dir.join(name);
    std::fs::write(&path, edit(text)).unwrap();
    path
}

/// Render `scene_with(dir, NAME.ron)` with its one occurrence of `from` replaced by `to`,
/// expecting a scene error: exit code 2 and exactly one line on stderr, which is returned,
/// and no `NAME.exr` written.
fn scene_error(dir: &Path, name: &str, from: &str, to: &str) -> String {
    let scene = scene_with(dir, &format!("{name}.ron"), |t| {
        assert_eq!(t.matches(from).count(), 1, "{name}");
        t.replacen(from, to, 1)
    });
    let out = dir.join(format!("{name}.exr"));
    let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{name}: {err}");
    assert_eq!(err.lines().count(), 1, "{name}: {err}");
    assert!(!out.exists(), "{name}: output written");
    err
}

use reyes_testkit::files::names as files_in;

#[test]
fn renders_the_demo_scene_to_exr_and_png() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["exr", "png"] {
        let out = dir.path().join(format!("spheres.{ext}"));
        let scene = root().join("scenes/spheres.ron");
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--quiet"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let film = if ext == "exr" { Some(reyes_film::read_exr(&out).unwrap()) } else { None };
        if let Some(f) = film {
            assert_eq!((f.width(), f.height()), (640, 480));
            // The middle of the green sphere is opaque, the sky above the ground is empty.
            assert_eq!(f.pixel(330, 200).unwrap()[3], 1.0);
            assert_eq!(f.pixel(320, 10).unwrap()[3], 0.0);
            assert!(f.depth(330, 200).unwrap().is_finite());
        }
    }
    assert_eq!(files_in(dir.path()), ["spheres.exr", "spheres.png"]);
}

#[test]
fn threads_one_and_two_give_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    let scene = root().join("scenes/transparency.ron");
    let mut bytes = Vec::new();
    for t in ["1", "2"] {
        let out = dir.path().join(format!("t{t}.exr"));
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--threads", t, "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        bytes.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(bytes[0], bytes[1]);
}

/// Each bad scene: exit 2, one line naming the file, a line:column, the field; no output.
#[test]
fn bad_scenes_exit_2_with_one_line_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str, &str, &str); 12] = [
        ("malformed", "objects: [", "objects: [[", ""),
        ("unknown-field", "fov: 40.0", "fov: 40.0, zoom: 2.0", "camera"),
        ("width-0", "width: 32", "width: 0", "image.width"),
        ("height-0", "height: 24", "height: 0", "image.height"),
        ("samples-0", "pixel_samples: (2, 2)", "pixel_samples: (0, 2)", "hider.pixel_samples"),
        ("fov-180", "fov: 40.0", "fov: 180.0", "camera.fov"),
        ("hither-yon", "hither: 0.1, yon: 100.0", "hither: 5.0, yon: 1.0", "camera.yon"),
        ("hither-0", "hither: 0.1", "hither: 0.0", "camera.hither"),
        ("filter-width", "width: 2.0)", "width: -1.0)", "hider.filter.width"),
        ("radius", "radius: 1.0", "radius: -1.0", "objects[0].shape.radius"),
        ("nan", "radius: 1.0", "radius: NaN", "objects[0].shape.radius"),
        ("inf", "fov: 40.0", "fov: inf", "camera.fov"),
    ];
    let mut snapshot = String::new();
    for (name, from, to, field) in cases {
        let err = scene_error(dir.path(), name, from, to);
        assert!(err.contains(&format!("{name}.ron:")), "{name}: {err}");
        assert!(err.contains(field), "{name}: {err}");
        let pos = err.split(&format!("{name}.ron:")).nth(1).unwrap();
        let mut parts = pos.split(':');
        assert!(parts.next().unwrap().parse::<u32>().is_ok(), "{name}: no line in {err}");
        assert!(parts.next().unwrap().parse::<u32>().is_ok(), "{name}: no column in {err}");
        snapshot.push_str(&err.replace(&dir.path().display().to_string(), "DIR"));
    }
    insta::assert_snapshot!("bad_scenes", snapshot);
}

/// Bad distributed ray tracing values: exit 2, exactly one line with the field and position,
/// no output.
#[test]
fn bad_ray_tracing_values_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let ball = "material: Matte(color: (1.0, 0.5, 0.2))";
    let cases: [(&str, &str, &str, &str); 5] = [
        (
            "ior-0",
            ball,
            "material: Matte(color: (1.0, 0.5, 0.2)), refract: Some((ior: 0.0))",
            "ior-0.ron:6:117: objects[0].refract.ior: must be > 0, got 0",
        ),
        (
            "gloss-negative",
            ball,
            "material: Matte(color: (1.0, 0.5, 0.2)), reflect: Some((color: (0.5, 0.5, 0.5), gloss: -2.0))",
            "gloss-negative.ron:6:143: objects[0].reflect.gloss: must be in [0, 90) degrees, got -2",
        ),
        (
            "depth-0",
            "(1.0, 0.5, 0.2)))],\n)",
            "(1.0, 0.5, 0.2)), reflect: Some((color: (0.5, 0.5, 0.5))))],\n  raytrace: (max_depth: 0),\n)",
            "depth-0.ron:7:25: raytrace.max_depth: must be >= 1 when an object reflects or refracts (objects[0].reflect asks for rays), got 0",
        ),
        (
            "area-radius",
            "Ambient(intensity: 1.0)",
            "Ambient(intensity: 1.0), Area(shape: Sphere(center: (0.0, 3.0, -1.0), radius: -0.5))",
            "area-radius.ron:5:90: lights[1].shape.radius: must be > 0, got -0.5",
        ),
        (
            "roll-steps",
            ball,
            "material: Matte(color: (1.0, 0.5, 0.2)), roll: Some((radius: 1.0, steps: 0, path: [(time: 0.0, position: (0.0, 0.0, 0.0)), (time: 1.0, position: (1.0, 0.0, 0.0))]))",
            "roll-steps.ron:6:129: objects[0].roll.steps: must be in 1..=1024, got 0",
        ),
    ];
    for (name, from, to, expected) in cases {
        let err = scene_error(dir.path(), name, from, to);
        let shown = err.trim_end().replace(&dir.path().display().to_string(), "DIR");
        assert_eq!(shown, format!("reyes-render: error: DIR/{expected}"), "{name}");
    }
}

#[test]
fn mesh_index_out_of_range_is_a_scene_error() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_with(dir.path(), "mesh.ron", |t| {
        t.replace(
            "Sphere(radius: 1.0)",
            "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1, 3]])",
        )
    });
    let o = run(&[scene.to_str().unwrap(), "-o", dir.path().join("m.exr").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("objects[0].shape.faces[0][2]"), "{}", stderr(&o));
}

#[test]
fn io_errors_exit_1_and_usage_errors_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_with(dir.path(), "ok.ron", |t| t.to_string());
    let s = scene.to_str().unwrap();
    // Missing scene file: I/O.
    let o = run(&[dir.path().join("nope.ron").to_str().unwrap(), "-o", "x.exr"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1);
    // Unwritable output path: I/O, and nothing created.
    let o = run(&[s, "-o", "/nonexistent-dir/out.exr"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("/nonexistent-dir/out.exr"));
    // A directory in the output's place: the atomic rename fails, nothing is left behind.
    let clash = dir.path().join("clash.exr");
    std::fs::create_dir(&clash).unwrap();
    let o = run(&[s, "-o", clash.to_str().unwrap(), "-q"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(files_in(dir.path()), ["clash.exr", "ok.ron"]);
    // Usage errors.
    for args in [
        vec![s, "-o", "out.tiff"],
        vec![s, "-o", "out.exr", "--samples", "0x4"],
        vec![s, "-o", "out.exr", "--samples", "4"],
        vec![s, "-o", "out.exr", "--threads", "0"],
        vec![s],
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn a_failed_render_leaves_an_existing_output_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("keep.exr");
    std::fs::write(&out, b"previous").unwrap();
    let bad = scene_with(dir.path(), "bad.ron", |t| t.replace("width: 32", "width: 0"));
    let o = run(&[bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read(&out).unwrap(), b"previous");
    assert_eq!(files_in(dir.path()), ["bad.ron", "keep.exr"]);
}

#[test]
fn overrides_change_the_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_with(dir.path(), "s.ron", |t| t.to_string());
    let s = scene.to_str().unwrap();
    let mut outs = Vec::new();
    for extra in [vec![], vec!["--seed", "7"], vec!["--samples", "3x3"]] {
        let out = dir.path().join(format!("o{}.exr", outs.len()));
        let mut args = vec![s, "-o", out.to_str().unwrap(), "-q"];
        args.extend(extra);
        assert!(run(&args).status.success());
        outs.push(std::fs::read(&out).unwrap());
    }
    assert_ne!(outs[0], outs[1], "--seed must change the jitter");
    assert_ne!(outs[0], outs[2], "--samples must change the sampling");
}

#[test]
fn help_text() {
    let o = run(&["--help"]);
    assert!(o.status.success());
    insta::assert_snapshot!("help", String::from_utf8_lossy(&o.stdout));
}

#[test]
fn stats_counts() {
    let dir = tempfile::tempdir().unwrap();
    let scene = root().join("scenes/transparency.ron");
    let out = dir.path().join("t.exr");
    let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "--stats", "-q"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("Hider samples:") && text.contains("Time: dice"), "{text}");
    // Counts are deterministic; times are not.
    let counts: String = text
        .lines()
        .filter(|l| {
            !l.starts_with(" Time")
                && !l.starts_with(" Sample tests per second")
                && !l.starts_with(" Memory")
                && !l.starts_with(" Hider time")
        })
        .map(|l| format!("{l}\n"))
        .collect();
    insta::assert_snapshot!("stats_transparency", counts);
}

/// A small RIB scene: a sphere in a 32 x 24 frame.
const RIB: &str = "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nPixelSamples 2 2\nWorldBegin\nLightSource \"ambientlight\" 1\nSurface \"matte\"\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n";

#[test]
fn rib_scenes_render_by_extension_by_content_from_gzip_and_from_stdin() {
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    let by_ext = dir.path().join("ball.rib");
    std::fs::write(&by_ext, RIB).unwrap();
    let by_content = dir.path().join("ball-scene");
    std::fs::write(&by_content, RIB).unwrap();
    let gz = dir.path().join("ball.rib.gz");
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(RIB.as_bytes()).unwrap();
    std::fs::write(&gz, enc.finish().unwrap()).unwrap();
    let mut outputs = Vec::new();
    for (name, scene) in [("ext", &by_ext), ("content", &by_content), ("gz", &gz)] {
        let out = dir.path().join(format!("{name}.exr"));
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        outputs.push(reyes_film::read_exr(&out).unwrap());
    }
    let out = dir.path().join("stdin.exr");
    let mut child = bin()
        .args(["-", "-o", out.to_str().unwrap()])
        .stdin(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child.stdin.take().unwrap().write_all(RIB.as_bytes()).unwrap();
    assert!(child.wait().unwrap().success());
    outputs.push(reyes_film::read_exr(&out).unwrap());
    // The same pixels, bit for bit (the files differ only in the header's `reyesScene`,
    // which names the scene file as given: docs/outputs.md).
    assert!(outputs.windows(2).all(|w| w[0] == w[1]), "the same scene four ways, the same image");
}

#[test]
fn rib_frames_go_to_numbered_files_and_frames_chooses_them() {
    let dir = tempfile::tempdir().unwrap();
    let body = RIB.replace("Format 32 24 1\n", "");
    let text = format!(
        "Format 32 24 1\nFrameBegin 1\n{body}FrameEnd\nFrameBegin 2\n{}FrameEnd\n",
        body.replace("Translate 0 0 5", "Translate 0 0 8")
    );
    let scene = dir.path().join("frames.rib");
    std::fs::write(&scene, text).unwrap();
    let o = run(&[scene.to_str().unwrap(), "-o", dir.path().join("f.exr").to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(files_in(dir.path()), ["f.0001.exr", "f.0002.exr", "frames.rib"]);
    let pattern = dir.path().join("g.##.png");
    let o = run(&[scene.to_str().unwrap(), "-o", pattern.to_str().unwrap(), "--frames", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("g.02.png").exists() && !dir.path().join("g.01.png").exists());
    let o = run(&[scene.to_str().unwrap(), "-o", pattern.to_str().unwrap(), "--frames", "3-1"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn rib_errors_and_warnings_are_one_line_each() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.exr");
    let bad = dir.path().join("bad.rib");
    std::fs::write(&bad, RIB.replace("Sphere 1 -1 1 360", "Sphere 0 -1 1 360")).unwrap();
    let o = run(&[bad.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let shown = stderr(&o).replace(&dir.path().display().to_string(), "DIR");
    assert_eq!(
        shown.trim_end(),
        "reyes-render: error: DIR/bad.rib:8:1: Sphere: objects[0].shape.radius: must be > 0, got 0"
    );
    assert!(!out.exists());
    let odd = dir.path().join("odd.rib");
    std::fs::write(&odd, RIB.replace("\"matte\"", "\"wood\"")).unwrap();
    let o = run(&[odd.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 2, "{err}");
    assert!(err.contains("odd.rib:6:1: warning: Surface: unknown shader \"wood\""), "{err}");
    let wrote = format!("reyes-render: wrote {}", out.display());
    assert_eq!(err.lines().last(), Some(wrote.as_str()), "{err}");
    let o = run(&[odd.to_str().unwrap(), "-o", out.to_str().unwrap(), "--strict"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let missing = dir.path().join("missing.rib");
    let o = run(&[missing.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));

    // A refused file still shows what was tolerated before its error, first, in file order.
    let both = dir.path().join("both.rib");
    let text = RIB
        .replace("\"matte\"", "\"wood\"")
        .replace("Sphere 1 -1 1 360", "Frobnicate 2\nSphere 0 -1 1 360");
    std::fs::write(&both, text).unwrap();
    let out = dir.path().join("both.exr");
    let o = run(&[both.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let lines: Vec<String> = stderr(&o).lines().map(String::from).collect();
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert!(lines[0].contains("both.rib:6:1: warning: Surface: unknown shader"), "{lines:?}");
    assert!(lines[1].contains("both.rib:8:1: warning:"), "{lines:?}");
    assert!(lines[1].contains("Frobnicate"), "{lines:?}");
    assert!(lines[2].starts_with("reyes-render: error: "), "{lines:?}");
    assert!(lines[2].contains("both.rib:9:1: Sphere:"), "{lines:?}");
    assert!(!out.exists());
}

/// Scenes that used to pass validation and fail at render time (exit 1, no position): a view
/// with no direction in single precision, an up vector that rounds parallel to it, a filter
/// that weighs no sample stratum. Each is now a scene error with its position; and a
/// `--samples` override that leaves the scene's filter no stratum to weigh is a usage error.
#[test]
fn setup_failures_are_scene_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (name, from, to, tail) in [
        (
            "denormal-view",
            "eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)",
            "eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1e-40)",
            "camera.look_at",
        ),
        ("far-view", "eye: (0.0, 0.0, -5.0)", "eye: (0.0, 0.0, -1e20)", "camera.look_at"),
        ("up-underflows", "fov: 40.0", "up: (1e-30, 1e-30, 0.0), fov: 40.0", "camera.up"),
        ("narrow-filter", "width: 2.0)", "width: 0.1)", "hider.filter"),
    ] {
        let err = scene_error(dir.path(), name, from, to);
        assert!(
            err.contains(&format!("{name}.ron:3:")) || err.contains(&format!("{name}.ron:4:")),
            "{err}"
        );
        assert!(err.contains(&format!(": {tail}: ")), "{name}: {err}");
    }
    let disk = scene_with(dir.path(), "disk.ron", |t| {
        t.replace(
            "pixel_samples: (2, 2), filter: (kind: Gaussian, width: 2.0)",
            "pixel_samples: (3, 3), filter: (kind: RiDisk, width: 0.6)",
        )
    });
    let out = dir.path().join("disk.exr");
    let (disk, out) = (disk.to_str().unwrap(), out.to_str().unwrap());
    assert!(run(&[disk, "-o", out, "-q"]).status.success());
    std::fs::remove_file(out).unwrap();
    let o = run(&[disk, "-o", out, "-q", "--samples", "2x2"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("disk.ron: --samples 2x2: hider.filter: the filter is zero"), "{err}");
    assert!(!Path::new(out).exists());
    // RIB: reported at the request that made the filter.
    let rib = dir.path().join("narrow.rib");
    let text = "PixelSamples 2 2\nPixelFilter \"gaussian\" 0.01 0.01\nProjection \"perspective\"\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n";
    std::fs::write(&rib, text).unwrap();
    let o = run(&[rib.to_str().unwrap(), "-o", out, "-q"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("narrow.rib:2:1: PixelFilter: hider.filter: the filter is zero"), "{err}");
    assert!(!Path::new(out).exists());
}

#[test]
fn sobol_patterns_without_power_of_two_samples_fall_back_with_a_warning() {
    // The fall-back to FIG. 6 is reported, once, on one line; a power-of-two count is silent,
    // and the fallen-back render is the FIG. 6 render byte for byte.
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (name, pattern, samples) in [
        ("j3", "SobolJoint", "(3, 3)"),
        ("s3", "Sobol", "(3, 3)"),
        ("f3", "Fig6", "(3, 3)"),
        ("j4", "SobolJoint", "(4, 2)"),
    ] {
        let scene = scene_with(dir.path(), &format!("{name}.ron"), |t| {
            t.replace(
                "pixel_samples: (2, 2)",
                &format!("pixel_samples: {samples}, pattern: {pattern}"),
            )
        });
        let out = dir.path().join(format!("{name}.exr"));
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap(), "-q"]);
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        if name.ends_with('3') && pattern != "Fig6" {
            assert_eq!(err.lines().count(), 1, "{err}");
            assert!(
                err.contains(&format!(
                    "{name}.ron: warning: hider.pattern: {pattern} needs power-of-two pixel_samples; 3 x 3 renders with Fig6"
                )),
                "{err}"
            );
        } else {
            assert!(err.is_empty(), "{name}: {err}");
        }
        files.push(reyes_film::read_exr(&out).unwrap());
    }
    // The same pixels, bit for bit (the files differ in the header's `reyesScene`, which
    // names the scene file).
    assert!(files[0] == files[2], "SobolJoint at 3 x 3 is FIG. 6");
    assert!(files[1] == files[2], "Sobol at 3 x 3 is FIG. 6");
}

/// A texture that is missing is an I/O error (exit 1), one that is not an image bad input
/// (exit 2): one line naming the file, relative names resolved beside the scene, no output.
#[test]
fn texture_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("junk.png"), b"\x89PNG\r\n\x1a\n not an image").unwrap();
    for (file, code, says) in
        [("missing.png", 1, "texture: cannot read"), ("junk.png", 2, "texture: cannot decode")]
    {
        let scene = scene_with(dir.path(), "tex.ron", |t| {
            t.replace(
                "material: Matte",
                &format!(
                    "maps: (color: Some((file: \"{file}\", color_space: Srgb))), material: Matte"
                ),
            )
        });
        let out = dir.path().join("tex.exr");
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{file}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        let named = dir.path().join(file);
        assert!(err.contains(&format!("{}: {says}", named.display())), "{err}");
        // Caught when the maps load, before any bucket: not a dicing failure.
        assert!(!err.contains("dicing"), "{err}");
        assert!(!out.exists());
    }
}

/// The look-development scene renders from RON and from its RIB twin, the displacement
/// counts in --stats.
#[test]
fn the_lookdev_scenes_render() {
    let dir = tempfile::tempdir().unwrap();
    for scene in ["lookdev.ron", "lookdev.rib"] {
        let out = dir.path().join("lookdev.exr");
        let path = root().join("scenes").join(scene);
        let o = run(&[
            path.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--stats",
            "--samples",
            "1x1",
        ]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(0), "{scene}: {err}");
        assert!(!err.contains("warning"), "{scene}: {err}");
        let stats = String::from_utf8_lossy(&o.stdout).into_owned() + &err;
        assert!(
            stats.contains("Look development:") && stats.contains("texture lookups"),
            "{stats}"
        );
    }
}

/// A `MeshFile` that is missing is an I/O error (exit 1), one that is malformed bad input
/// (exit 2): one line at the scene's `path` field naming the mesh file (and, malformed, its
/// line), the name resolved beside the scene; no output. A good one renders.
#[test]
fn mesh_file_errors_name_the_scene_field_and_the_mesh_file() {
    let dir = tempfile::tempdir().unwrap();
    // Line 4 refers to a fourth point the file does not have.
    std::fs::write(dir.path().join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n").unwrap();
    std::fs::write(dir.path().join("good.obj"), "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let shape = |file: &str| format!("shape: MeshFile(path: \"{file}\")");
    for (file, code, says) in [
        ("missing.obj", 1, "cannot read the mesh file: ".to_string()),
        ("bad.obj", 2, format!("{}:4: ", dir.path().join("bad.obj").display())),
        ("good.obj", 0, String::new()),
    ] {
        let scene = scene_with(dir.path(), "mesh.ron", |t| {
            t.replace("shape: Sphere(radius: 1.0)", &shape(file))
        });
        let out = dir.path().join("mesh.exr");
        let o = run(&[scene.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{file}: {err}");
        if code == 0 {
            assert!(out.exists(), "{file}: no output");
            continue;
        }
        assert_eq!(err.lines().count(), 1, "{err}");
        // The scene position of the `path` value: line 6, after `objects: [(name: "ball", `
        // and `shape: MeshFile(path: ` (two spaces, 25 and 22 characters).
        let at = format!("{}:6:50: objects[0].shape.path: ", scene.display());
        assert!(err.contains(&at), "{file}: {err}");
        assert!(err.contains(&says), "{file}: {err}");
        assert!(err.contains(&dir.path().join(file).display().to_string()), "{err}");
        assert!(!out.exists());
    }
}

/// Every error is one line, whatever the paths in it hold: a newline, a tab or an escape in a
/// path is written escaped (`\n`, `\t`, `\u{1b}`), for each command, and whichever part of
/// the program reports it.
#[test]
fn control_characters_in_paths_are_escaped_in_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = scene_with(d, "ok.ron", |t| t.to_string());
    let s = scene.to_str().unwrap();
    std::fs::write(d.join("file\n"), b"not a directory").unwrap();
    let odd = scene_with(d, "sc\u{1b}ene\n.ron", |t| t.to_string());
    let at = |name: &str| d.join(name).to_str().unwrap().to_string();
    let odd = odd.to_str().unwrap().to_string();
    let crop = vec![odd, "--crop".into(), "0,1,0.5,0.5".into(), "-o".into(), at("a.exr")];
    let cases: [(Vec<String>, i32); 7] = [
        (vec![s.into(), "-o".into(), at("no\nsuch/out.exr")], 1),
        (vec![s.into(), "-o".into(), at("out\u{1b}[31m.tiff")], 2),
        (vec![s.into(), "--tile".into(), "1/2".into(), "-o".into(), at("file\n/t.exr")], 1),
        (vec![at("no\nscene.ron"), "-o".into(), at("out.exr")], 1),
        (vec!["merge".into(), at("tile\t1.exr"), "-o".into(), at("out.exr")], 1),
        (vec!["farm".into(), "status".into(), "--dir".into(), at("no\r\nfarm")], 1),
        (crop, 2),
    ];
    let mut snapshot = String::new();
    for (args, code) in cases {
        let o = bin().args(&args).output().expect("run reyes-render");
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        snapshot.push_str(&err.replace(&d.display().to_string(), "DIR"));
    }
    assert_eq!(files_in(d), ["file\n", "ok.ron", "sc\u{1b}ene\n.ron"], "nothing written");
    insta::assert_snapshot!("control_characters_in_paths", snapshot);
}

/// `Procedural "RunProgram"` runs a program only with `--allow-run-program`: refused in one
/// line without it (exit 2, no output), rendered with it.
#[test]
fn run_program_needs_allow_run_program() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("gen.sh");
    let script = "#!/bin/sh\nwhile read detail data; do\n  echo \"Sphere 1 -1 1 360\"\n  printf '\\377'\ndone\n";
    std::fs::write(&program, script).unwrap();
    std::fs::set_permissions(&program, std::fs::Permissions::from_mode(0o755)).unwrap();
    let rib = dir.path().join("prog.rib");
    let procedural =
        format!("Procedural \"RunProgram\" [\"{}\" \"\"] [-1 1 -1 1 -1 1]", program.display());
    std::fs::write(&rib, RIB.replace("Sphere 1 -1 1 360", &procedural)).unwrap();
    let out = dir.path().join("prog.exr");
    let o = run(&[rib.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
    assert!(stderr(&o).contains("--allow-run-program"), "{}", stderr(&o));
    assert!(!out.exists());
    let o = run(&[rib.to_str().unwrap(), "-o", out.to_str().unwrap(), "--allow-run-program"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.exists());
}

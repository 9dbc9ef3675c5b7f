//! What the binary writes, read by the real tools a compositor's pipeline uses: OpenEXR's
//! `exrheader` and OpenImageIO's `oiiotool` (Debian packages `openexr` and
//! `openimageio-tools`; `.ci/run` installs them). A missing tool fails the test, unless
//! `REYES_SKIP_EXTERNAL_TOOLS=1` says to skip it, which the test then prints.
//!
//! Also here, without the tools: the file is byte-identical for any thread count and from run
//! to run (the header's attributes included), the render time appears only when asked for,
//! and the PNG preview's view transform.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn render(scene: &Path, out: &Path, extra: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_reyes-render"))
        .arg(scene)
        .arg("-o")
        .arg(out)
        .arg("--quiet")
        .args(extra)
        .output()
        .expect("run reyes-render");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `scenes/aovs.ron` at 64x48 with `edit` applied, written into `dir`.
fn aovs_scene(dir: &Path, name: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let text = std::fs::read_to_string(root().join("scenes/aovs.ron")).expect("scenes/aovs.ron");
    let text = text.replace("image: (width: 320, height: 240)", "image: (width: 64, height: 48)");
    let path = dir.join(name);
    std::fs::write(&path, edit(text)).expect("write the scene");
    path
}

/// Run an external tool, or `None` when it is missing and `REYES_SKIP_EXTERNAL_TOOLS=1`
/// allows skipping (printed); a missing tool without it fails the test.
fn tool(name: &str, args: &[&std::ffi::OsStr]) -> Option<Output> {
    match Command::new(name).args(args).output() {
        Ok(o) => Some(o),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if std::env::var("REYES_SKIP_EXTERNAL_TOOLS").as_deref() == Ok("1") {
                eprintln!(
                    "SKIPPED: `{name}` is not installed and REYES_SKIP_EXTERNAL_TOOLS=1 (install \
                     the Debian packages openexr and openimageio-tools, as .ci/run does)"
                );
                None
            } else {
                panic!(
                    "`{name}` is not installed: install the Debian packages openexr and \
                     openimageio-tools (.ci/run does), or set REYES_SKIP_EXTERNAL_TOOLS=1 to skip"
                )
            }
        }
        Err(e) => panic!("cannot run {name}: {e}"),
    }
}

fn text(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
}

/// Every layer the scene writes, with its channels.
const LAYERS: [(&str, &[&str]); 18] = [
    ("Ci", &["R", "G", "B"]),
    ("Oi", &["R", "G", "B"]),
    ("z", &["Z"]),
    ("N", &["X", "Y", "Z"]),
    ("P", &["X", "Y", "Z"]),
    ("s", &["Y"]),
    ("t", &["Y"]),
    ("dPdtime", &["X", "Y"]),
    ("object_id", &["id"]),
    ("material_id", &["id"]),
    ("__ambient", &["R", "G", "B"]),
    ("__diffuse", &["R", "G", "B"]),
    ("__specular", &["R", "G", "B"]),
    ("__diffuse_key", &["R", "G", "B"]),
    ("__specular_key", &["R", "G", "B"]),
    ("__ambient_fill", &["R", "G", "B"]),
    ("__diffuse_fill", &["R", "G", "B"]),
    ("__specular_fill", &["R", "G", "B"]),
];

/// The attributes every file carries, and their values where they are known.
const ATTRIBUTES: [&str; 10] = [
    "worldToCamera",
    "worldToNDC",
    "screenWindowCenter",
    "screenWindowWidth",
    "software",
    "reyesScene",
    "reyesSeed",
    "reyesPixelSamples",
    "reyesFilter",
    "renderTime",
];

#[test]
fn exrheader_and_oiiotool_read_every_layer_and_attribute() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let scene = aovs_scene(dir.path(), "aovs.ron", |t| {
        t.replace("outputs: (", "outputs: (\n    render_time: true,")
    });
    let exr = dir.path().join("aovs.exr");
    render(&scene, &exr, &[]);

    let Some(header) = tool("exrheader", &[exr.as_os_str()]) else { return };
    let header = text(&header);
    // Part 0 is the beauty at the top level; then one part per layer, in scene order.
    assert!(header.contains("name (type string): \"rgba\""), "{header}");
    for c in ["R", "G", "B", "A", "Z"] {
        assert!(header.contains(&format!("\n    {c}, 32-bit floating-point")), "{c}: {header}");
    }
    for (k, (layer, channels)) in LAYERS.iter().enumerate() {
        let part = format!(" part {}:", k + 1);
        let at = header.find(&part).unwrap_or_else(|| panic!("no{part} in {header}"));
        let body = &header[at..];
        let body = &body[..body[1..].find(" part ").map_or(body.len(), |e| e + 1)];
        assert!(body.contains(&format!("name (type string): \"{layer}\"")), "{layer}: {body}");
        for c in *channels {
            assert!(body.contains(&format!("\n    {layer}.{c}, ")), "{layer}.{c}: {body}");
        }
        for a in &ATTRIBUTES[..5] {
            assert!(body.contains(&format!("{a} (type ")), "{layer} lacks {a}: {body}");
        }
    }
    for a in ATTRIBUTES {
        assert!(header.contains(&format!("{a} (type ")), "no {a}: {header}");
    }
    assert!(header.contains("object_id.id, 32-bit unsigned integer"), "{header}");
    assert!(header.contains("N.X, 16-bit floating-point"), "{header}");
    for c in ["zip, multi-scanline blocks", "piz", "dwa, small scanline blocks", "none"] {
        assert!(header.contains(&format!("compression (type compression): {c}")), "{c}: {header}");
    }
    assert!(header.contains("reyesSeed (type string): \"0\""), "{header}");
    assert!(header.contains("reyesPixelSamples (type v2i): (4 4)"), "{header}");
    assert!(header.contains("reyesFilter (type string): \"Gaussian 2x2\""), "{header}");
    assert!(header.contains(&format!(
        "software (type string): \"reyes-render {}\"",
        env!("CARGO_PKG_VERSION")
    )));

    let info = ["--info", "-v", "-a"].map(std::ffi::OsStr::new);
    let info = [info[0], info[1], info[2], exr.as_os_str()];
    let Some(info) = tool("oiiotool", &info) else { return };
    let info = text(&info);
    assert!(info.contains("19 subimages"), "{info}");
    assert!(info.contains("channel list: R, G, B, A, Z"), "{info}");
    for (layer, channels) in LAYERS {
        assert!(info.contains(&format!("oiio:subimagename: \"{layer}\"")), "{layer}: {info}");
        let list: Vec<String> = channels.iter().map(|c| format!("{layer}.{c}")).collect();
        assert!(info.contains(&format!("channel list: {}", list.join(", "))), "{layer}: {info}");
    }
    // Every subimage carries the camera, screen window and software; the first the rest.
    for a in [
        "worldToCamera: ",
        "worldToNDC: ",
        "screenWindowCenter: ",
        "screenWindowWidth: ",
        "software: ",
    ] {
        assert_eq!(info.matches(a).count(), 19, "oiiotool: {a} in every subimage: {info}");
    }
    for a in
        ["reyesScene: ", "reyesSeed: ", "reyesPixelSamples: 4, 4", "reyesFilter: ", "renderTime: "]
    {
        assert!(info.contains(a), "oiiotool lacks {a}: {info}");
    }
}

#[test]
fn oiiotool_diff_of_two_renders_is_finite() {
    // Two seeds: the images differ in noise, and the background depth is finite in both, so
    // the error and PSNR are numbers (with +inf they are inf and nan).
    let dir = tempfile::tempdir().expect("temporary directory");
    let scene = aovs_scene(dir.path(), "aovs.ron", |t| t);
    let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
    render(&scene, &a, &["--seed", "1"]);
    render(&scene, &b, &["--seed", "2"]);
    let args = [std::ffi::OsStr::new("--diff"), a.as_os_str(), b.as_os_str()];
    let Some(o) = tool("oiiotool", &args) else { return };
    // `--diff` exits non-zero when the images differ beyond its threshold; only the report
    // matters here.
    let report = String::from_utf8_lossy(&o.stdout).into_owned();
    let number = |label: &str| -> f64 {
        let line = report.lines().find(|l| l.contains(label)).unwrap_or_else(|| panic!("{report}"));
        let v = line.split('=').nth(1).and_then(|v| v.split_whitespace().next());
        v.and_then(|v| v.parse().ok()).unwrap_or_else(|| panic!("{label}: {line}"))
    };
    for label in ["Mean error", "RMS error", "Peak SNR"] {
        let v = number(label);
        assert!(v.is_finite(), "{label} = {v}: {report}");
    }
    assert!(number("Mean error") > 0.0, "two seeds must differ: {report}");
}

#[test]
fn the_file_is_byte_identical_for_any_thread_count_and_run() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let scene = aovs_scene(dir.path(), "aovs.ron", |t| t);
    let mut files = Vec::new();
    for (k, threads) in ["1", "2", "2", "8"].into_iter().enumerate() {
        let out = dir.path().join(format!("t{k}.exr"));
        render(&scene, &out, &["--threads", threads]);
        files.push(std::fs::read(&out).expect("read the output"));
    }
    assert!(files.windows(2).all(|w| w[0] == w[1]), "outputs differ");
    // No render time unless asked for: it is the one value that changes from run to run.
    let header = String::from_utf8_lossy(&files[0][..4096.min(files[0].len())]).into_owned();
    assert!(!header.contains("renderTime") && header.contains("reyesScene"));
}

#[test]
fn png_preview_dithers_composites_and_exposes() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let read = |p: &Path| -> Vec<[u8; 4]> {
        let img = image::open(p).unwrap_or_else(|e| panic!("{e}")).to_rgba8();
        img.pixels().map(|p| p.0).collect()
    };
    let plain = aovs_scene(dir.path(), "plain.ron", |t| t);
    let over = aovs_scene(dir.path(), "over.ron", |t| {
        t.replace(
            "outputs: (",
            "outputs: (\n    png: (background: Some((0.0, 0.0, 1.0)), exposure: 1.0),",
        )
    });
    let (a, b) = (dir.path().join("plain.png"), dir.path().join("over.png"));
    render(&plain, &a, &[]);
    render(&over, &b, &[]);
    let (a, b) = (read(&a), read(&b));
    // Top-left is background: transparent black, then opaque blue over a background.
    assert_eq!(a[0], [0, 0, 0, 0]);
    assert_eq!(b[0], [0, 0, 255, 255]);
    assert!(b.iter().all(|p| p[3] == 255), "composited over a background: opaque");
}

#[test]
fn background_depth_is_finite_unless_z_infinite_is_given() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let scene = aovs_scene(dir.path(), "aovs.ron", |t| t);
    let (finite, infinite) = (dir.path().join("f.exr"), dir.path().join("i.exr"));
    render(&scene, &finite, &[]);
    render(&scene, &infinite, &["--z-infinite"]);
    let z = |p: &Path, name: &str| -> Vec<f32> {
        let layers = reyes_film::read_layers(p).unwrap_or_else(|e| panic!("{e}"));
        layers.into_iter().find(|c| c.name == name).map(|c| c.values).unwrap_or_default()
    };
    // Pixel (0, 0) sees the sky: nothing there.
    for name in ["Z", "z.Z"] {
        assert_eq!(z(&finite, name)[0], 1e30, "{name}");
        assert_eq!(z(&infinite, name)[0], f32::INFINITY, "{name}");
        // Elsewhere the same depths.
        let (a, b) = (z(&finite, name), z(&infinite, name));
        assert!(a.iter().zip(&b).all(|(a, b)| a == b || (*a == 1e30 && b.is_infinite())));
    }
}

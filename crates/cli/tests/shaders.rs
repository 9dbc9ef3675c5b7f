//! Shading-language shaders through the `reyes-render` binary (issue #30): a runaway shader
//! stops the render with one line and no output, a shader that does not compile stops the
//! load with the compiler's `file:line:col`, and a shader producing NaN still renders a
//! finite picture and says how many values it replaced.

use std::path::Path;
use std::process::{Command, Output};

/// Writes `name.sl` and `scene.rib` (a sphere shaded by the surface `name`) into `dir`.
fn scene(dir: &Path, name: &str, source: &str) -> std::path::PathBuf {
    std::fs::write(dir.join(format!("{name}.sl")), source).unwrap();
    let rib = format!(
        "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\n\
         LightSource \"distantlight\" 1\nTranslate 0 0 4\nAttributeBegin\n\
         Attribute \"identifier\" \"name\" [\"ball\"]\nSurface \"{name}\"\nSphere 1 -1 1 360\n\
         AttributeEnd\nWorldEnd\n"
    );
    let path = dir.join("scene.rib");
    std::fs::write(&path, rib).unwrap();
    path
}

fn render(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_reyes-render")).args(args).output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_runaway_loop_stops_the_render_with_one_line_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let rib = scene(
        dir.path(),
        "spin",
        "surface spin() { float x = 0; while (1 > 0) { x += 1; } Ci = x; }",
    );
    let out = dir.path().join("out.png");
    let o = render(&["-q", rib.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(lines[0].contains("shader \"spin\"") && lines[0].contains("object \"ball\""), "{err}");
    assert!(lines[0].contains("instruction budget"), "{err}");
    assert!(!out.exists(), "output written");
}

/// `--shader-max-ops` sets the budget: a shader of a few thousand instructions a grid
/// renders with the default budget and stops the render under a budget of 1,000.
#[test]
fn shader_max_ops_sets_the_instruction_budget() {
    let dir = tempfile::tempdir().unwrap();
    let rib = scene(
        dir.path(),
        "count",
        "surface count() { float x = 0, k; for (k = 0; k < 200; k += 1) { x += 1; } Ci = x / 200; }",
    );
    let out = dir.path().join("out.png");
    let (rib, path) = (rib.to_str().unwrap(), out.to_str().unwrap());
    let o = render(&["-q", rib, "-o", path]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    std::fs::remove_file(&out).unwrap();
    let o = render(&["-q", rib, "-o", path, "--shader-max-ops", "1000"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("shader \"count\"") && err.contains("instruction budget"), "{err}");
    assert!(!out.exists(), "output written");
    let o = render(&["-q", rib, "-o", path, "--shader-max-ops", "0"]);
    assert_eq!(o.status.code(), Some(2), "a budget of 0 is refused: {}", stderr(&o));
}

#[test]
fn a_shader_that_does_not_compile_stops_the_load_at_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let rib = scene(dir.path(), "broken", "surface broken() {\n  Ci = undefined_thing;\n}\n");
    let out = dir.path().join("out.png");
    let o = render(&["-q", rib.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    let file = dir.path().join("broken.sl");
    let at = format!("{}:2:", file.display());
    assert!(err.contains(&at) && err.contains("undefined_thing"), "{err}");
    assert!(!out.exists(), "output written");
}

#[test]
fn a_shader_producing_nan_renders_finite_pixels_and_counts_them() {
    let dir = tempfile::tempdir().unwrap();
    // sqrt of a negative number on the left half of the ball (x < 0 in camera space).
    let rib =
        scene(dir.path(), "nan", "surface nan() { Oi = 1; Ci = color(sqrt(xcomp(P)), 0.5, 0); }");
    let out = dir.path().join("out.exr");
    let o = render(&["-q", "--stats", rib.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(0), "{err}");
    let text = format!("{}{err}", String::from_utf8_lossy(&o.stdout));
    let line = text.lines().find(|l| l.contains("Shaders:")).expect("a Shaders line");
    let count: u64 = line
        .split_whitespace()
        .zip(line.split_whitespace().skip(1))
        .find(|(_, w)| *w == "non-finite")
        .and_then(|(n, _)| n.parse().ok())
        .expect("a count");
    assert!(count > 0, "{line}");
    assert!(err.contains("non-finite"), "a warning: {err}");
    let film = reyes_film::read_exr(&out).unwrap();
    assert!(film.rgba().iter().all(|p| p.iter().all(|c| c.is_finite())));
    assert!(film.rgba().iter().any(|p| p[1] > 0.4), "the ball is drawn");
}

/// An imager shader's pixels are what the EXR holds: the file is not written from the lines
/// as they were before the imager ran (the beauty's blocks are otherwise compressed while the
/// frame renders).
#[test]
fn an_imager_changes_the_exr_written() {
    let dir = tempfile::tempdir().unwrap();
    let rib = scene(dir.path(), "flat", "surface flat() { Oi = 1; Ci = 1; }");
    std::fs::write(
        dir.path().join("fill.sl"),
        "imager fill(color bgcolor = 0) { Ci += (1 - alpha) * bgcolor; alpha = 1; }",
    )
    .unwrap();
    let text = std::fs::read_to_string(&rib).unwrap();
    let text =
        text.replace("WorldBegin", "Imager \"fill\" \"bgcolor\" [0.25 0.5 0.75]\nWorldBegin");
    std::fs::write(&rib, text).unwrap();
    let out = dir.path().join("out.exr");
    let o = render(&["-q", rib.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let film = reyes_film::read_exr(&out).unwrap();
    // The top-left corner is background: the imager's colour, opaque.
    assert_eq!(film.rgba()[0], [0.25, 0.5, 0.75, 1.0]);
}

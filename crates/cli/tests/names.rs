//! Output names (issue #33): `-o` is optional for RIB (the `Display` name is used), a
//! single-frame file writes the plain name, numbered names only for several frames or a
//! pattern, and every file written is named on standard error unless `--quiet`.

use std::path::Path;
use std::process::{Command, Output};

/// Runs reyes-render in `dir` (relative output names resolve there).
fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_reyes-render"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run reyes-render")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// One world block: a sphere lit by an ambient light, 16x12 pixels.
const WORLD: &str = "WorldBegin\nLightSource \"ambientlight\" 1\nSurface \"matte\"\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n";

fn frame(n: i32, display: &str) -> String {
    format!("FrameBegin {n}\n{display}Format 16 12 1\nPixelSamples 1 1\n{WORLD}FrameEnd\n")
}

#[test]
fn a_single_frame_file_writes_the_plain_name_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("one.rib"), frame(7, "")).unwrap();
    let o = run_in(dir.path(), &["one.rib", "-o", "out.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(files_in(dir.path()), ["one.rib", "out.exr"]);
    assert_eq!(stderr(&o), "reyes-render: wrote out.exr\n");
    // --quiet says nothing; a pattern takes the frame number even for one frame.
    let o = run_in(dir.path(), &["one.rib", "-o", "p.###.png", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    assert!(dir.path().join("p.007.png").exists());
    // A file without FrameBegin is frame 1 for a pattern.
    let plain = format!("Format 16 12 1\nPixelSamples 1 1\n{WORLD}");
    std::fs::write(dir.path().join("plain.rib"), plain).unwrap();
    let o = run_in(dir.path(), &["plain.rib", "-o", "q.%02d.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "reyes-render: wrote q.01.exr\n");
}

#[test]
fn without_o_a_rib_file_writes_its_display_name() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        frame(1, "Display \"pic.png\" \"file\" \"rgba\"\nDisplay \"+pic.exr\" \"file\" \"rgba\"\n");
    std::fs::write(dir.path().join("d.rib"), text).unwrap();
    let o = run_in(dir.path(), &["d.rib"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "reyes-render: wrote pic.png\nreyes-render: wrote pic.exr\n");
    assert_eq!(files_in(dir.path()), ["d.rib", "pic.exr", "pic.png"]);
    // -o still wins.
    let o = run_in(dir.path(), &["d.rib", "-o", "mine.png", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("mine.png").exists());
}

#[test]
fn a_display_that_is_not_exr_or_png_is_written_as_exr_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let text = frame(1, "Display \"ball.tif\" \"tiff\" \"rgba\"\n");
    std::fs::write(dir.path().join("t.rib"), text).unwrap();
    let o = run_in(dir.path(), &["t.rib"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines,
        [
            "reyes-render: t.rib:2:1: warning: Display: \"ball.tif\" (driver \"tiff\"): only .exr \
             and .png files are written: writing ball.exr (use -o to choose)",
            "reyes-render: wrote ball.exr",
        ]
    );
    assert_eq!(files_in(dir.path()), ["ball.exr", "t.rib"]);
    // A framebuffer display's name is a window title: the same rule gives it a file.
    let text = frame(1, "Display \"balls\" \"framebuffer\" \"rgb\"\n");
    std::fs::write(dir.path().join("f.rib"), text).unwrap();
    let o = run_in(dir.path(), &["f.rib", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("balls.exr").exists());
}

#[test]
fn no_display_and_no_o_is_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("n.rib"), frame(1, "")).unwrap();
    let o = run_in(dir.path(), &["n.rib"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        "reyes-render: error: n.rib: no output: the file names no Display, give -o OUT.exr\n"
    );
    assert_eq!(files_in(dir.path()), ["n.rib"]);
}

#[test]
fn several_frames_are_numbered_only_when_their_names_would_collide() {
    let dir = tempfile::tempdir().unwrap();
    let same = format!(
        "{}{}",
        frame(1, "Display \"s.png\" \"file\" \"rgba\"\n"),
        frame(2, "Display \"s.png\" \"file\" \"rgba\"\n")
    );
    std::fs::write(dir.path().join("same.rib"), same).unwrap();
    let o = run_in(dir.path(), &["same.rib"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "reyes-render: wrote s.0001.png\nreyes-render: wrote s.0002.png\n");
    // Each frame its own Display name: written as named.
    let own = format!(
        "{}{}",
        frame(1, "Display \"a.png\" \"file\" \"rgba\"\n"),
        frame(2, "Display \"b.png\" \"file\" \"rgba\"\n")
    );
    std::fs::write(dir.path().join("own.rib"), own).unwrap();
    let o = run_in(dir.path(), &["own.rib", "--quiet"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("a.png").exists() && dir.path().join("b.png").exists());
    // With -o, a file of several frames is numbered even when one frame is chosen, so that a
    // frame has the same name whichever frames are rendered.
    let o = run_in(dir.path(), &["same.rib", "-o", "x.exr", "--frames", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o), "reyes-render: wrote x.0002.exr\n");
}

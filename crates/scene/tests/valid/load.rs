//! `load`: a valid file, an unreadable one (exit code 1), a bad scene and invalid UTF-8
//! (exit code 2), each error on one line.

use std::path::Path;

use reyes_scene::{LoadError, load};

use crate::common::{load_bad, temp_file};
use crate::{FULL, ok};

#[test]
fn load_reads_a_valid_file() {
    let path = temp_file("valid.ron", FULL.as_bytes());
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene, ok(FULL));
}

#[test]
fn load_reports_an_unreadable_file_with_exit_code_1() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no-such-dir/missing.ron");
    let err = load(&path).err().unwrap_or_else(|| panic!("loaded a missing file"));
    assert!(matches!(err, LoadError::Io { .. }), "{err:?}");
    assert_eq!(err.exit_code(), 1);
    let shown = err.to_string();
    assert!(shown.starts_with(&format!("{}: cannot read the scene file: ", path.display())));
    assert!(!shown.contains('\n'));
}

#[test]
fn load_reports_a_bad_scene_with_exit_code_2() {
    let path = temp_file("bad.ron", FULL.replace("radius: 1.0", "radius: -1.0").as_bytes());
    let err = load_bad(&path);
    let LoadError::Scene(scene_err) = &err else { panic!("{err:?}") };
    assert_eq!(scene_err.file, path);
    assert_eq!(scene_err.field, "objects[0].shape.radius");
    assert_eq!((scene_err.line, scene_err.col), (Some(10), Some(50)));
    assert_eq!(err.to_string(), scene_err.to_string());
}

#[test]
fn load_reports_invalid_utf8_as_a_bad_scene() {
    let mut bytes = b"Scene(\n  image: (width: 8, hei".to_vec();
    bytes.push(0xff);
    let path = temp_file("latin1.ron", &bytes);
    let err = load_bad(&path);
    let LoadError::Scene(e) = err else { panic!("not a scene error") };
    assert_eq!((e.line, e.col), (Some(2), Some(24)));
    assert_eq!(e.message, "the file is not valid UTF-8");
}

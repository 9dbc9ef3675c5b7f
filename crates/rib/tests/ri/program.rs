//! `Procedural "RunProgram"`: the Specification's protocol with a small shell script written
//! for the test, the detail it is given, and the refusal without the permission.

use std::fs;
use std::os::unix::fs::PermissionsExt;
use std::path::Path;

use reyes_rib::{Permissions, RiOptions, Source, load_with};
use reyes_scene::Shape;

/// A generator that answers each `detail data` line with a sphere of radius `data`, named
/// after the detail it was given, ended by the byte 0xff (`\377`).
const SCRIPT: &str = "#!/bin/sh
while read detail data; do
  echo \"AttributeBegin Attribute \\\"identifier\\\" \\\"name\\\" [\\\"detail $detail\\\"]\"
  echo \"Sphere $data -$data $data 360 AttributeEnd\"
  printf '\\377'
done
";

fn script(dir: &Path) -> String {
    let path = dir.join("gen.sh");
    fs::write(&path, SCRIPT).unwrap();
    fs::set_permissions(&path, fs::Permissions::from_mode(0o755)).unwrap();
    path.display().to_string()
}

/// A 64 x 64 perspective frame (fov 40) with a RunProgram procedural at distance 10, its
/// bound the cube [-1, 1]^3.
fn text(program: &str) -> String {
    format!(
        "Format 64 64 1
Projection \"perspective\" \"fov\" [40]
WorldBegin
Translate 0 0 10
Procedural \"RunProgram\" [\"{program}\" \"0.5\"] [-1 1 -1 1 -1 1]
WorldEnd
"
    )
}

fn load(text: &str, run_program: bool) -> Result<reyes_rib::Loaded, reyes_rib::RibError> {
    load_with(
        Source::from_bytes("test.rib", text.as_bytes().to_vec()),
        &RiOptions::default(),
        Permissions { run_program },
    )
}

#[test]
fn run_program_reads_the_rib_the_program_writes_in_place() {
    let dir = tempfile::tempdir().unwrap();
    let loaded = load(&text(&script(dir.path())), true).unwrap();
    let scene = &loaded.frames[0].scene;
    assert_eq!(scene.objects.len(), 1);
    let o = &scene.objects[0];
    assert!(matches!(o.shape, Shape::Sphere { radius, .. } if radius == 0.5), "{:?}", o.shape);
    // Placed by the transformation in force at the procedural: 10 in front of the camera.
    assert_eq!(o.transform.len(), 1, "{:?}", o.transform);
    // The detail it was given: the bound's nearest face at depth 9 spans
    // 2 / tan(20 deg) / 9 screen units of 32 pixels, both ways (f32 corners: 1e-4 relative).
    let side = 2.0 / 20f64.to_radians().tan() / 9.0 * 32.0;
    let detail: f64 = o.name.strip_prefix("detail ").unwrap().parse().unwrap();
    assert!((detail - side * side).abs() <= 1e-4 * side * side, "{detail} {}", side * side);
}

#[test]
fn run_program_is_refused_without_the_permission() {
    let dir = tempfile::tempdir().unwrap();
    let marker = dir.path().join("ran");
    // A program that would leave a mark if it ran.
    let path = dir.path().join("mark.sh");
    fs::write(&path, format!("#!/bin/sh\ntouch {}\nprintf '\\377'\n", marker.display())).unwrap();
    fs::set_permissions(&path, fs::Permissions::from_mode(0o755)).unwrap();
    let e = load(&text(&path.display().to_string()), false).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "test.rib:5:1: Procedural: \"RunProgram\" would run the program \"{}\", and running \
             programs named by a scene is off: allow it with --allow-run-program",
            path.display()
        )
    );
    assert!(!e.contains('\n'));
    assert!(!marker.exists());
}

#[test]
fn a_program_without_the_end_byte_or_that_cannot_start_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mute.sh");
    fs::write(&path, "#!/bin/sh\necho 'Sphere 1 -1 1 360'\n").unwrap();
    fs::set_permissions(&path, fs::Permissions::from_mode(0o755)).unwrap();
    let e = load(&text(&path.display().to_string()), true).unwrap_err().to_string();
    assert!(
        e.starts_with("test.rib:5:1: Procedural: program ") && e.contains("without the end byte"),
        "{e}"
    );
    let missing = dir.path().join("nowhere");
    let e = load(&text(&missing.display().to_string()), true).unwrap_err().to_string();
    assert!(e.contains("cannot be started"), "{e}");
    assert!(!e.contains('\n'));
}

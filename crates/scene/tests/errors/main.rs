//! Bad-input catalogue: every rejected scene yields one line naming the file, the field path and
//! the line:column of the offending text, for every field family of the model (one module per
//! family, each with its snapshot).
//!
//! Each case edits one spot of a valid base scene; `at` is the expected 1-based line and column.

#[path = "../common/mod.rs"]
mod common;

mod hider;
mod lights;
mod lookdev;
mod objects;
mod shapes;
mod solids;
mod syntax;
mod view;

use std::path::Path;

use reyes_scene::{SceneError, parse};

/// A valid scene that every case edits in one place.
const BASE: &str = r#"Scene(
  image: (width: 640, height: 480),
  camera: (eye: (0.0, 1.0, -10.0), look_at: (0.0, 0.0, 0.0), fov: 35.0, hither: 0.1, yon: 100.0),
  hider: (pixel_samples: (4, 4), filter: (kind: Gaussian, width: 2.0)),
  lights: [Ambient(intensity: 0.1), Distant(from: (1.0, 1.0, -1.0))],
  objects: [
    (name: "ball", shape: Sphere(radius: 1.0), material: Matte(color: (0.8, 0.1, 0.1))),
  ],
)
"#;

/// The file name every error must carry.
const FILE: &str = "scenes/bad.ron";

/// One bad input: replace `from` (which occurs once in [`BASE`]) by `to`.
pub(crate) struct Case {
    pub name: &'static str,
    pub from: &'static str,
    pub to: &'static str,
    pub field: &'static str,
    pub at: Option<(usize, usize)>,
}

/// Every family's cases.
const FAMILIES: &[&[Case]] = &[
    syntax::CASES,
    view::CASES,
    hider::CASES,
    lights::CASES,
    shapes::CASES,
    objects::CASES,
    solids::CASES,
    lookdev::CASES,
];

/// Every case of every family.
fn all_cases() -> impl Iterator<Item = &'static Case> {
    FAMILIES.iter().flat_map(|cases| cases.iter())
}

/// The text of `case` and the error it must produce.
fn run(case: &Case) -> SceneError {
    assert_eq!(BASE.matches(case.from).count(), 1, "{}: `from` must occur once", case.name);
    let text = BASE.replacen(case.from, case.to, 1);
    match parse(&text, Path::new(FILE)) {
        Ok(_) => panic!("{}: the scene was accepted:\n{text}", case.name),
        Err(e) => e,
    }
}

/// The case named `name`.
fn case(name: &str) -> &'static Case {
    all_cases().find(|c| c.name == name).unwrap_or_else(|| panic!("no case {name}"))
}

/// The one-line message of the error of the case named `name`.
fn shown(name: &str) -> String {
    run(case(name)).to_string()
}

/// Checks each case of a family (its error is one line naming the file, the case's field
/// and position) and returns the family's messages for its snapshot.
fn check(cases: &[Case]) -> String {
    let mut shown = Vec::new();
    for case in cases {
        let e = run(case);
        let line = e.to_string();
        assert!(!line.contains('\n') && !line.contains('\r'), "{}: {line:?}", case.name);
        assert!(line.starts_with(&format!("{FILE}:")), "{}: {line}", case.name);
        assert_eq!(e.file, Path::new(FILE), "{}", case.name);
        assert_eq!(e.field, case.field, "{}: {line}", case.name);
        assert_eq!(e.line.zip(e.col), case.at, "{}: {line}", case.name);
        assert!(!e.message.is_empty(), "{}", case.name);
        let (l, c) = case.at.unwrap_or_default();
        let expected = if case.field.is_empty() {
            format!("{FILE}:{l}:{c}: {}", e.message)
        } else {
            format!("{FILE}:{l}:{c}: {}: {}", case.field, e.message)
        };
        assert_eq!(line, expected, "{}", case.name);
        shown.push(format!("{}\n  {line}", case.name));
    }
    shown.join("\n")
}

#[test]
fn the_base_scene_is_valid() {
    let scene = parse(BASE, Path::new(FILE)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.objects.len(), 1);
}

/// No two cases share a name, so `case(name)` is unambiguous.
#[test]
fn case_names_are_unique() {
    let mut names: Vec<&str> = all_cases().map(|c| c.name).collect();
    names.sort_unstable();
    let before = names.len();
    names.dedup();
    assert_eq!(names.len(), before, "duplicate case names");
}

#[test]
fn the_catalogue_covers_the_required_inputs() {
    for required in [
        "malformed: missing comma between fields",
        "unknown field",
        "missing required field",
        "width 0",
        "height 0",
        "pixel samples 0",
        "fov 0",
        "fov 180",
        "fov 190",
        "hither 0",
        "hither negative",
        "hither equal to yon",
        "filter width 0",
        "filter width negative",
        "filter height 0",
        "filter height negative",
        "filter height NaN",
        "negative radius",
        "NaN fov",
        "inf yon",
        "mesh index out of range",
        "mesh zero normal",
        "mesh file missing",
        "mesh colours length mismatch",
        "gradual shutter ramp 0",
        "gradual shutter ramp above 0.5",
        "camera motion with one key",
        "camera motion key after shutter close",
        "camera motion keys out of order",
        "camera motion key eye at look_at",
        "camera motion key up zero",
        "camera motion key up parallel to view",
        "transform motion with one key",
        "transform motion key outside the shutter",
        "transform motion keys out of order",
        "transform motion rotate about a zero axis",
        "transform motion scale by zero",
        "transform motion singular matrix",
        "transform motion projective matrix",
        "closed shutter with a key after open",
        "deformation of a sphere",
        "deformation with one key",
        "deformation of a patch with 3 points",
        "deformation of a mesh with too many points",
        "deformation key outside the shutter",
        "deformation keys out of order",
        "deformation NaN point",
        "solid with a bare object",
        "union with one operand",
        "empty intersection",
        "unknown operand",
        "ambiguous operand",
        "object used twice in one solid",
        "object used by two solids",
        "disk operand",
        "bilinear patch operand",
        "sphere cut at zmax operand",
        "partial sphere operand",
        "partial cylinder operand",
        "partial cone operand",
        "torus with a partial tube",
        "torus with a partial sweep",
        "open mesh operand",
        "mesh edge shared by three faces",
        "inconsistently oriented mesh",
        "open operand deep in a tree",
        "glass above 1",
        "glass negative",
        "glass NaN",
        "screen window right not above left",
        "screen window top equal to bottom",
        "screen window NaN",
        "screen window inf",
        "screen window with 3 values",
        "screen window without Some",
        "unknown projection",
        "object shading rate 0",
        "object shading rate negative",
        "object shading rate NaN",
        "light set index out of range",
        "light set with a light twice",
        "light set without Some",
        "spot at its target",
        "spot without to",
        "spot NaN to",
        "spot negative intensity",
        "spot cone angle 0",
        "spot cone angle above 180",
        "spot cone delta negative",
        "spot cone delta above the cone angle",
        "spot beam distribution negative",
        "metal without colour",
        "metal roughness 0",
        "metal colour above 1",
        "metal ks negative",
        "metal with kd",
        // What used to pass validation and fail at render time (exit 1, no position).
        "look_at a denormal from eye",
        "look_at 4e20 from eye",
        "up too small to cross the view",
        "up too large to cross the view",
        "eye too far from the origin",
        "camera motion key with no view direction in single precision",
        "fov too narrow for single precision",
        "screen window too small for single precision",
        "screen window too large for single precision",
        "lens radius too large for single precision",
        "lens blur too large for single precision",
        "shutter too long for single precision",
        "narrow gaussian filter",
        "narrow RenderMan box filter",
        "disk filter between the strata",
        "filter missed by the original stratum pairing",
        // The positions an independent run found off.
        "negative mesh index",
        "float for an integer",
        "negative integer",
        "lone colon for a field value",
    ] {
        assert!(all_cases().any(|c| c.name == required), "missing case {required}");
    }
}

/// The exact text of a few errors, independent of the snapshot.
#[test]
fn exact_messages() {
    assert_eq!(
        shown("filter height negative"),
        "scenes/bad.ron:4:79: hider.filter.height: must be in (0, 16] pixels, got -1"
    );
    assert_eq!(
        shown("filter height NaN"),
        "scenes/bad.ron:4:79: hider.filter.height: must be finite, got NaN"
    );
    assert_eq!(
        shown("negative radius"),
        "scenes/bad.ron:7:42: objects[0].shape.radius: must be > 0, got -1"
    );
    assert_eq!(shown("width 0"), "scenes/bad.ron:2:18: image.width: must be in 1..=65536, got 0");
    assert_eq!(
        shown("fov 180"),
        "scenes/bad.ron:3:67: camera.fov: must be in (0, 180) degrees, got 180"
    );
    assert_eq!(shown("NaN fov"), "scenes/bad.ron:3:67: camera.fov: must be finite, got NaN");
    assert_eq!(shown("inf yon"), "scenes/bad.ron:3:91: camera.yon: must be finite, got inf");
    assert_eq!(
        shown("hither equal to yon"),
        "scenes/bad.ron:3:93: camera.yon: must be > hither (100), got 100"
    );
    assert_eq!(
        shown("pixel samples 0"),
        "scenes/bad.ron:4:30: hider.pixel_samples[1]: must be in 1..=64, got 0"
    );
    assert_eq!(
        shown("mesh index out of range"),
        "scenes/bad.ron:7:108: objects[0].shape.faces[0][2]: index 3 is out of range: the mesh has 3 points"
    );
    assert_eq!(
        shown("unknown field"),
        "scenes/bad.ron:2:36: image.depth: unknown field `depth`, expected `width`, `height` or `crop`"
    );
    assert_eq!(
        shown("missing required field"),
        "scenes/bad.ron:2:21: image.height: missing required field `height`"
    );
    assert_eq!(
        shown("gradual shutter ramp above 0.5"),
        "scenes/bad.ron:3:152: camera.shutter.shape.ramp: must be in (0, 0.5], got 0.6"
    );
    assert_eq!(
        shown("camera motion key after shutter close"),
        "scenes/bad.ron:3:177: camera.motion[1].time: motion key time 1.5 is outside the shutter [0, 1]"
    );
    assert_eq!(
        shown("camera motion key up zero"),
        "scenes/bad.ron:3:173: camera.motion[0].up: must be non-zero"
    );
    assert_eq!(
        shown("transform motion with one key"),
        "scenes/bad.ron:7:56: objects[0].motion: motion needs at least 2 keys (or none), got 1"
    );
    assert_eq!(
        shown("transform motion keys out of order"),
        "scenes/bad.ron:7:120: objects[0].motion[2].time: keys must be in increasing time order, got 0.5 after 0.7"
    );
    assert_eq!(
        shown("transform motion rotate about a zero axis"),
        "scenes/bad.ron:7:135: objects[0].motion[1].transform[0].axis: must be non-zero"
    );
    assert_eq!(
        shown("closed shutter with a key after open"),
        "scenes/bad.ron:3:211: camera.motion[1].time: motion key time 0.6 is outside the shutter [0.5, 0.5]"
    );
    assert_eq!(
        shown("deformation of a sphere"),
        "scenes/bad.ron:7:56: objects[0].deform: deformation keys need a Mesh, BilinearPatch, PatchMesh, NuPatch, SubdivisionMesh, Curves or Points shape, got Sphere"
    );
    assert_eq!(
        shown("deformation of a patch with 3 points"),
        "scenes/bad.ron:10:35: objects[1].deform[1].points: expected 4 points, got 3"
    );
    assert_eq!(
        shown("solid with a bare object"),
        "scenes/bad.ron:10:35: solids[0].tree: a solid needs an operator: Union, Intersection or Difference"
    );
    assert_eq!(
        shown("union with one operand"),
        "scenes/bad.ron:11:19: solids[0].tree: Union needs at least 2 operands, got 1"
    );
    assert_eq!(
        shown("empty intersection"),
        "scenes/bad.ron:11:19: solids[0].tree: Intersection needs at least 2 operands, got 0"
    );
    assert_eq!(
        shown("unknown operand"),
        "scenes/bad.ron:11:46: solids[0].tree[1]: no object is named \"hoel\""
    );
    assert_eq!(
        shown("ambiguous operand"),
        "scenes/bad.ron:11:42: solids[0].tree[1]: object name \"ball\" is ambiguous: objects[0] and objects[2] are both named \"ball\""
    );
    assert_eq!(
        shown("object used by two solids"),
        "scenes/bad.ron:11:100: solids[1].tree[1]: object \"ball\" is already used by solids[0] (at solids[0].tree[0])"
    );
    assert_eq!(
        shown("disk operand"),
        "scenes/bad.ron:11:46: solids[0].tree[1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("open operand deep in a tree"),
        "scenes/bad.ron:12:83: solids[0].tree[0][1][1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("open mesh operand"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"tet\" is not closed (Mesh: edge (2, 1) of faces[0] belongs to no other face); CSG operands must be closed solids"
    );
    assert_eq!(
        shown("inconsistently oriented mesh"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"tet\" is not consistently oriented (Mesh: faces[0] and faces[3] both run along edge (2, 1) from point 2 to point 1); the two faces at every edge of a closed mesh must run along it in opposite directions"
    );
    assert_eq!(
        shown("glass above 1"),
        "scenes/bad.ron:7:55: objects[0].glass: must be in [0, 1], got 1.5"
    );
}

/// `load` shows the case `name`, written to the file `file`, as a bad scene (exit code 2) on
/// one line ending in `tail`.
fn assert_load_shows(name: &str, file: &str, tail: &str) {
    let case = case(name);
    let path = common::temp_file(file, BASE.replacen(case.from, case.to, 1).as_bytes());
    let shown = common::load_bad(&path).to_string();
    assert!(shown.ends_with(tail), "{shown}");
}

/// A bad solid is a bad scene for `load` too: one line, exit code 2.
#[test]
fn a_bad_solid_is_exit_code_2() {
    assert_load_shows(
        "disk operand",
        "bad-solid.ron",
        ":11:46: solids[0].tree[1]: object \"plate\" is not closed (Disk); CSG operands must be closed solids",
    );
}

/// A bad motion key is a bad scene for `load` too: one line, exit code 2.
#[test]
fn a_bad_motion_key_is_exit_code_2() {
    assert_load_shows(
        "transform motion keys out of order",
        "bad-motion.ron",
        ":7:120: objects[0].motion[2].time: keys must be in increasing time order, got 0.5 after 0.7",
    );
}

/// Every shape, light and material keeps its path when the object is not the first.
#[test]
fn paths_index_lists() {
    let text = BASE.replacen(
        "  ],",
        "    (shape: Sphere(radius: 1.0), material: Matte(color: (0.5, 0.5, 0.5))),\n    (shape: Disk(radius: -2.0), material: Matte(color: (0.5, 0.5, 0.5))),\n  ],",
        1,
    );
    let e = parse(&text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("scenes/bad.ron:9:26: objects[2].shape.radius: must be > 0, got -2")
    );
}

/// Comments and strings holding brackets do not disturb positions.
#[test]
fn positions_survive_comments_and_strings() {
    let text = BASE.replacen("(name: \"ball\"", "(name: \"b(a)l[l]\" /* ( [ */", 1).replacen(
        "radius: 1.0",
        "// radius: 2.0\n      radius: -3.0",
        1,
    );
    let e = parse(&text, Path::new(FILE)).err().map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("scenes/bad.ron:8:15: objects[0].shape.radius: must be > 0, got -3")
    );
}

#[test]
fn new_geometry_messages() {
    assert_eq!(
        shown("nurbs knots decreasing"),
        "scenes/bad.ron:7:76: objects[0].shape.uknot[3]: must not decrease, got 0.5 after 1"
    );
    assert_eq!(
        shown("bicubic patch mesh with 5 points along u"),
        "scenes/bad.ron:7:56: objects[0].shape.nu: a nonperiodic bicubic mesh needs 4 + k * step points (step 3), got 5"
    );
    assert_eq!(
        shown("nurbs umin before the valid range"),
        "scenes/bad.ron:7:88: objects[0].shape.umin: must be >= uknot[1] (0), the start of the valid range, got -0.5"
    );
    assert_eq!(
        shown("hyperboloid operand"),
        "scenes/bad.ron:10:42: solids[0].tree[1]: object \"hyp\" is not closed (Hyperboloid); CSG operands must be closed solids"
    );
}

/// The exact text of the errors of the camera's screen window, an object's shading rate and
/// light set, the spot light and the metal material.
#[test]
fn exact_messages_of_the_renderman_fields() {
    assert_eq!(
        shown("screen window right not above left"),
        "scenes/bad.ron:3:100: camera.screen_window[1]: must be > left (-1), got -2"
    );
    assert_eq!(
        shown("screen window top equal to bottom"),
        "scenes/bad.ron:3:110: camera.screen_window[3]: must be > bottom (1), got 1"
    );
    assert_eq!(
        shown("object shading rate 0"),
        "scenes/bad.ron:7:62: objects[0].shading_rate: must be > 0, got 0"
    );
    assert_eq!(
        shown("light set index out of range"),
        "scenes/bad.ron:7:65: objects[0].lights[1]: index 2 is out of range: the scene has 2 lights"
    );
    assert_eq!(
        shown("light set with a light twice"),
        "scenes/bad.ron:7:68: objects[0].lights[2]: light 1 is listed twice (also at lights[0])"
    );
    assert_eq!(
        shown("spot cone delta above the cone angle"),
        "scenes/bad.ron:5:117: lights[1].cone_delta: must be <= cone_angle (10), got 12"
    );
    assert_eq!(
        shown("metal roughness 0"),
        "scenes/bad.ron:7:99: objects[0].material.roughness: must be > 0, got 0"
    );
}

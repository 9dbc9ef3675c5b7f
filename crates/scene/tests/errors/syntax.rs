//! Malformed RON, type errors and the exact positions of number and punctuation errors.

use super::{BASE, Case};

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "malformed: missing comma between fields", from: "480),\n  camera", to: "480)\n  camera", field: "", at: Some((3, 3)) },
    Case { name: "malformed: unclosed scene", from: "],\n)\n", to: "],\n", field: "", at: Some((8, 5)) },
    Case { name: "malformed: stray closing bracket", from: "fov: 35.0,", to: "fov: 35.0],", field: "camera", at: Some((3, 71)) },
    Case { name: "malformed: unclosed string", from: "\"ball\"", to: "\"ball", field: "objects[0].name", at: Some((7, 12)) },
    Case { name: "malformed: empty file", from: BASE, to: "", field: "", at: Some((1, 1)) },
    Case { name: "malformed: trailing text", from: "],\n)\n", to: "],\n)\nScene()\n", field: "", at: Some((10, 1)) },
    Case { name: "malformed: unclosed comment", from: "],\n)\n", to: "],\n)\n/* end\n", field: "", at: Some((10, 1)) },
    // Numbers: ron reports some from inside the number (after the sign, at the point); the
    // error is at the number's first character.
    Case { name: "negative mesh index", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, -1, 2]])", field: "objects[0].shape.faces[0][1]", at: Some((7, 105)) },
    Case { name: "float for an integer", from: "width: 640", to: "width: 640.5", field: "image.width", at: Some((2, 18)) },
    Case { name: "float for a mesh index", from: "Sphere(radius: 1.0)", to: "Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], faces: [[0, 1.0, 2]])", field: "objects[0].shape.faces[0][1]", at: Some((7, 105)) },
    Case { name: "exponent for an integer", from: "(4, 4)", to: "(4, 4e0)", field: "hider.pixel_samples[1]", at: Some((4, 30)) },
    Case { name: "negative pixel samples", from: "(4, 4)", to: "(4, -4)", field: "hider.pixel_samples[1]", at: Some((4, 30)) },
    Case { name: "integer too large for its field", from: "width: 640", to: "width: 4294967296", field: "image.width", at: Some((2, 18)) },
    Case { name: "letters run into a number", from: "fov: 35.0", to: "fov: 35.0deg", field: "camera.fov", at: Some((3, 67)) },
    // Punctuation where a value is due: the error names the value due there.
    Case { name: "lone colon for a field value", from: "width: 640", to: "width: : 640", field: "image.width", at: Some((2, 18)) },
    Case { name: "lone colon for a tuple element", from: "(0.0, 1.0, -10.0)", to: "(0.0, :, -10.0)", field: "camera.eye[1]", at: Some((3, 23)) },
    Case { name: "lone colon for a list element", from: "[Ambient(intensity: 0.1),", to: "[:, Ambient(intensity: 0.1),", field: "lights[0]", at: Some((5, 12)) },
    Case { name: "lone colon for a field name", from: "(width: 640,", to: "(: 640,", field: "image", at: Some((2, 11)) },
    Case { name: "field without a value", from: "intensity: 0.1", to: "intensity:", field: "lights[0].intensity", at: Some((5, 30)) },
    Case { name: "field without a colon", from: "width: 640", to: "width 640", field: "image.width", at: Some((2, 17)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}

/// The four positions an independent run found off by one or more columns, each pinned with
/// its whole line: ron reports a negative integer from the digit after the sign and a
/// fraction read as an integer from its point, and a colon where a value is due used to be
/// reported on the field that holds it.
#[test]
fn positions_of_numbers_and_lone_colons() {
    use super::shown;
    // Was 7:106 (the digit after the sign).
    assert_eq!(
        shown("negative mesh index"),
        "scenes/bad.ron:7:105: objects[0].shape.faces[0][1]: must be a non-negative integer, got -1"
    );
    // Was 2:21 (the point), "expected `,` or a closing bracket".
    assert_eq!(
        shown("float for an integer"),
        "scenes/bad.ron:2:18: image.width: expected an integer, got 640.5"
    );
    // Was 2:19 (the digit after the sign).
    assert_eq!(
        shown("negative integer"),
        "scenes/bad.ron:2:18: image.width: must be a non-negative integer, got -640"
    );
    // Was reported on `image`, the struct holding the field.
    assert_eq!(
        shown("lone colon for a field value"),
        "scenes/bad.ron:2:18: image.width: expected integer"
    );
    assert_eq!(
        shown("lone colon for a tuple element"),
        "scenes/bad.ron:3:23: camera.eye[1]: expected float"
    );
}

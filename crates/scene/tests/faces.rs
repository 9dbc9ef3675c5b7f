//! Mesh faces in RON: held flat in memory ([`reyes_scene::Faces`]), read, written and reported
//! exactly as the list of lists `Vec<Vec<u32>>` they were before, messages and positions
//! included (the expected lines below were recorded with `Vec<Vec<u32>>`).

use std::path::Path;

use reyes_scene::{Faces, Shape, parse};

/// A valid scene of one mesh of four points; `FACES` is replaced by each case.
const BASE: &str = "Scene(\n  image: (width: 8, height: 8),\n  camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0), fov: 35.0, hither: 0.1, yon: 100.0),\n  objects: [\n    (shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)], FACES), material: Matte(color: (0.8, 0.1, 0.1))),\n  ],\n)\n";

fn scene_with(faces: &str) -> String {
    BASE.replacen("FACES", faces, 1)
}

#[test]
fn faces_read_as_lists_of_lists() {
    for (faces, want) in [
        ("faces: [[0, 1, 2]]", vec![vec![0, 1, 2]]),
        ("faces: [[0, 1, 2], [1, 3, 2]]", vec![vec![0, 1, 2], vec![1, 3, 2]]),
        ("faces: [[0, 1, 2,], [1, 3, 2, 0, ],]", vec![vec![0, 1, 2], vec![1, 3, 2, 0]]),
        ("faces: [[0x1, /* c */ +0, 2], [-0, 1, 2]]", vec![vec![1, 0, 2], vec![0, 1, 2]]),
    ] {
        let scene = parse(&scene_with(faces), Path::new("p.ron")).unwrap_or_else(|e| panic!("{e}"));
        let Shape::Mesh { faces: got, .. } = &scene.objects[0].shape else { panic!("a mesh") };
        assert_eq!(*got, Faces::from(want.clone()), "{faces}");
        assert_eq!(format!("{got:?}"), format!("{want:?}"));
    }
}

#[test]
fn faces_write_as_lists_of_lists_and_read_back() {
    let scene = parse(&scene_with("faces: [[0, 1, 2, 3], [3, 2, 1]]"), Path::new("p.ron"))
        .unwrap_or_else(|e| panic!("{e}"));
    let text = ron::to_string(&scene.objects[0].shape).expect("the shape serialises");
    assert!(text.contains("faces:[[0,1,2,3],[3,2,1]]"), "{text}");
    let pretty = ron::ser::to_string_pretty(&scene, ron::ser::PrettyConfig::default())
        .expect("the scene serialises");
    let back = parse(&pretty, Path::new("p.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, scene);
}

#[test]
fn bad_faces_are_reported_as_before() {
    #[rustfmt::skip]
    let cases = [
        ("faces: [[0, -1, 2]]", "p.ron:5:108: objects[0].shape.faces[0][1]: must be a non-negative integer, got -1"),
        ("faces: [[0, 1.5, 2]]", "p.ron:5:108: objects[0].shape.faces[0][1]: expected an integer, got 1.5"),
        ("faces: [[1e0, 0, 2]]", "p.ron:5:105: objects[0].shape.faces[0][0]: expected an integer, got 1e0"),
        ("faces: [[0, \"a\", 2]]", "p.ron:5:108: objects[0].shape.faces[0][1]: expected integer"),
        ("faces: [[0, 1, NaN]]", "p.ron:5:111: objects[0].shape.faces[0][2]: expected integer"),
        ("faces: [[[0], 1, 2]]", "p.ron:5:105: objects[0].shape.faces[0][0]: expected integer"),
        ("faces: [[0, 1, 4294967296]]", "p.ron:5:111: objects[0].shape.faces[0][2]: integer out of range for this field, got 4294967296"),
        ("faces: [[0, 1, 4294967295]]", "p.ron:5:111: objects[0].shape.faces[0][2]: index 4294967295 is out of range: the mesh has 4 points"),
        ("faces: [0, 1, 2]", "p.ron:5:104: objects[0].shape.faces[0]: expected opening `[`"),
        ("faces: [(0, 1, 2)]", "p.ron:5:104: objects[0].shape.faces[0]: expected opening `[`"),
        ("faces: [[0, 1, 2], 3]", "p.ron:5:115: objects[0].shape.faces[1]: expected opening `[`"),
        ("faces: 5", "p.ron:5:103: objects[0].shape.faces: expected opening `[`"),
        ("faces: Some([[0, 1, 2]])", "p.ron:5:103: objects[0].shape.faces: expected opening `[`"),
        ("faces: [[0 1, 2]]", "p.ron:5:107: objects[0].shape.faces[0][1]: expected `,` or a closing bracket"),
        ("faces: [[0, 1, 2)]", "p.ron:5:112: objects[0].shape.faces[0]: expected `,` or a closing bracket"),
        ("faces: [[0, 1, 2], [1, 3, 2]", "p.ron:5:124: objects[0].shape.faces: expected `,` or a closing bracket"),
        ("faces: [[0, 1, 2]], faces: [[0, 1, 2]]", "p.ron:5:116: objects[0].shape.faces: field `faces` given twice"),
        ("colors: None", "p.ron:5:108: objects[0].shape.faces: missing required field `faces`"),
        ("faces: []", "p.ron:5:103: objects[0].shape.faces: must hold at least one face"),
        ("faces: [[0, 1, 2], []]", "p.ron:5:115: objects[0].shape.faces[1]: a face must have at least 3 indices, got 0"),
        ("faces: [[0, 1, 2], [1, 3, 2, 9]]", "p.ron:5:125: objects[0].shape.faces[1][3]: index 9 is out of range: the mesh has 4 points"),
    ];
    for (faces, want) in cases {
        let err = parse(&scene_with(faces), Path::new("p.ron")).err();
        assert_eq!(err.map(|e| e.to_string()).as_deref(), Some(want), "{faces}");
    }
}

//! `MeshFile` shapes read at parse time: the file's normals and uvs on the `Mesh`, faces
//! for a subdivision mesh with facevarying st, OBJ `Kd` as point colours only where exact,
//! and errors of the mesh that follows validated as any mesh.

use std::path::Path;

use reyes_scene::{LoadError, Shape, SubdivTag};

fn scene(shape: &str) -> String {
    format!(
        "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)),\n\
         objects: [(shape: {shape}, material: Matte(color: (1.0, 1.0, 1.0)))])"
    )
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap_or_else(|e| panic!("{e}"));
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                    vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1/1/1 2/2/2 3/3/3 4/4/4\n";

#[test]
fn a_mesh_file_becomes_a_mesh_with_normals_and_st() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    write(dir.path(), "quad.obj", QUAD);
    let file = dir.path().join("s.ron");
    let s = reyes_scene::parse(&scene("MeshFile(path: \"quad.obj\")"), &file)
        .unwrap_or_else(|e| panic!("{e}"));
    let Shape::Mesh { points, faces, normals, st, colors } = &s.objects[0].shape else {
        panic!("a mesh")
    };
    assert_eq!(points.len(), 4);
    assert_eq!(Vec::<Vec<u32>>::from(faces), vec![vec![0, 1, 2, 3]]);
    assert_eq!(normals.as_deref(), Some(&[[0.0, 0.0, 1.0]; 4][..]));
    assert_eq!(st.as_deref(), Some(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][..]));
    assert_eq!(colors, &None);
}

#[test]
fn a_subdivision_mesh_file_has_facevarying_st_and_an_interpolated_boundary() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    write(dir.path(), "quad.obj", QUAD);
    let file = dir.path().join("s.ron");
    let text = scene("MeshFile(path: \"quad.obj\", subdivision: true)");
    let s = reyes_scene::parse(&text, &file).unwrap_or_else(|e| panic!("{e}"));
    let Shape::SubdivisionMesh { points, st, tags, .. } = &s.objects[0].shape else {
        panic!("a subdivision mesh")
    };
    assert_eq!(points.len(), 4);
    assert_eq!(st.as_deref(), Some(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][..]));
    assert_eq!(tags, &vec![SubdivTag::InterpolateBoundary]);
}

#[test]
fn obj_diffuse_colours_become_point_colours_only_where_exact() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    write(dir.path(), "m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n");
    // Two triangles apart: each point has one colour.
    write(
        dir.path(),
        "apart.obj",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\n\
         usemtl red\nf 1 2 3\nusemtl blue\nf 4 5 6\n",
    );
    // A face without a material: no point colours (the object's material colours all).
    write(
        dir.path(),
        "partly.obj",
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nusemtl blue\nf 2 4 3\n",
    );
    let file = dir.path().join("s.ron");
    let colors = |name: &str| {
        let s = reyes_scene::parse(&scene(&format!("MeshFile(path: {name:?})")), &file)
            .unwrap_or_else(|e| panic!("{e}"));
        match &s.objects[0].shape {
            Shape::Mesh { colors, .. } => colors.clone(),
            _ => panic!("a mesh"),
        }
    };
    let red = [1.0, 0.0, 0.0];
    let blue = [0.0, 0.0, 1.0];
    assert_eq!(colors("apart.obj"), Some(vec![red, red, red, blue, blue, blue]));
    assert_eq!(colors("partly.obj"), None);
}

#[test]
fn the_mesh_read_is_validated_and_io_is_told_apart() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    write(dir.path(), "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n");
    let file = dir.path().join("s.ron");
    let e = reyes_scene::parse_files(&scene("MeshFile(path: \"flat.obj\")"), &file).unwrap_err();
    assert_eq!(e.exit_code(), 2);
    // At the MeshFile (the nearest value the scene text holds), naming the file.
    let want = format!(
        "s.ron:2:19: objects[0].shape.normals[0]: must be non-zero, got [0, 0, 0] (in the mesh \
         read from {})",
        dir.path().join("flat.obj").display()
    );
    assert!(e.to_string().ends_with(&want), "{e}");
    let e = reyes_scene::parse_files(&scene("MeshFile(path: \"none.ply\")"), &file).unwrap_err();
    assert!(matches!(e, LoadError::MeshIo(_)), "{e}");
    assert_eq!(e.exit_code(), 1);
    // Validation alone refuses a MeshFile: it has not been read.
    let mut s =
        reyes_scene::parse(&scene("Sphere(radius: 1.0)"), &file).unwrap_or_else(|e| panic!("{e}"));
    s.objects[0].shape =
        Shape::MeshFile { path: "flat.obj".into(), subdivision: false, group: None };
    let issue = reyes_scene::validate(s).unwrap_err();
    assert_eq!(issue.path, "objects[0].shape.path");
}

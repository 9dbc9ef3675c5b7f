//! Integration tests of the mesh readers: small sample files written here (OBJ with n-gons,
//! groups, normals, uvs and a material library; PLY ASCII and binary of both byte orders,
//! with and without normals and uvs), the catalogue of malformed files with their one-line
//! messages (an insta snapshot), and round trips of random meshes.
//!
//! Every sample's numbers are short decimals or small binary fractions that f32 holds
//! exactly or that parse to the same f32 as the literal in the test, so comparisons are exact
//! (no tolerance is needed: reading is parsing, not arithmetic).

use std::path::Path;

use proptest::prelude::*;
use reyes_meshio::{
    Format, Group, MeshData, MeshError, read, read_bytes, write_obj, write_ply_binary,
};

fn obj(text: &str) -> Result<MeshData, MeshError> {
    read_bytes(Path::new("m.obj"), text.as_bytes(), Format::Obj)
}

fn ply(bytes: &[u8]) -> Result<MeshData, MeshError> {
    read_bytes(Path::new("m.ply"), bytes, Format::Ply)
}

fn faces(m: &MeshData) -> Vec<Vec<u32>> {
    m.faces().map(<[u32]>::to_vec).collect()
}

#[test]
fn obj_with_ngons_groups_normals_uvs_and_materials() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.mtl"),
        "newmtl red\nKd 1 0 0\nKs 0.5 0.5 0.5\nNs 10\nmap_Kd red.png\nnewmtl blue\nKd 0 0 1\n",
    )
    .unwrap();
    let text = "\
# a pentagon and a triangle in group a (red), a quad in group b (blue)
mtllib m.mtl
v 0 0 0
v 1 0 0
v 2 1 0
v 1 2 0
v 0 1 0
v 3 3 3
vt 0 0
vt 1 0
vt 0.5 1
vn 0 0 1
vn 0 1 0
g a
usemtl red
f 1/1/1 2/2/1 3/3/1 4/1/1 5/2/1
f 1/1/1 2/2/1 -1/3/2
g b
usemtl blue
f 1/1/1 2/2/1 3/3/1 4/1/1
";
    let path = dir.path().join("m.obj");
    std::fs::write(&path, text).unwrap();
    let m = read(&path).unwrap();
    // Welding: a point is one (position, uv, normal) triple. Group a has 5 triples from the
    // pentagon and one new (6, 3, 2) from the triangle; group b re-welds its own 4.
    assert_eq!(m.points.len(), 6 + 4);
    assert_eq!(faces(&m), vec![vec![0, 1, 2, 3, 4], vec![0, 1, 5], vec![6, 7, 8, 9]]);
    assert_eq!(m.points[5], [3.0, 3.0, 3.0]);
    assert_eq!(m.points[3], [1.0, 2.0, 0.0]);
    let normals = m.normals.as_ref().unwrap();
    assert_eq!(normals[5], [0.0, 1.0, 0.0]);
    assert_eq!(normals[0], [0.0, 0.0, 1.0]);
    let uvs = m.uvs.as_ref().unwrap();
    assert_eq!(uvs[2], [0.5, 1.0]);
    assert_eq!(uvs[3], [0.0, 0.0]);
    assert_eq!(
        m.groups,
        vec![Group { name: "a".into(), faces: 0..2 }, Group { name: "b".into(), faces: 2..3 }]
    );
    assert_eq!(m.materials.len(), 2);
    assert_eq!(m.materials[0].name, "red");
    assert_eq!(m.materials[0].diffuse, Some([1.0, 0.0, 0.0]));
    assert_eq!(m.materials[0].specular, Some([0.5, 0.5, 0.5]));
    assert_eq!(m.materials[0].shininess, Some(10.0));
    assert_eq!(
        m.materials[0].diffuse_texture.as_deref(),
        Some(dir.path().join("red.png").as_path())
    );
    assert_eq!(m.materials[1].diffuse, Some([0.0, 0.0, 1.0]));
    assert_eq!(m.face_materials, vec![Some(0), Some(0), Some(1)]);
}

#[test]
fn obj_positions_only_and_all_triangles() {
    let m = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n").unwrap();
    assert_eq!(m.points.len(), 4);
    assert_eq!(faces(&m), vec![vec![0, 1, 2], vec![1, 3, 2]]);
    assert!(m.normals.is_none() && m.uvs.is_none());
    assert!(m.materials.is_empty() && m.face_materials.is_empty());
    assert_eq!(m.groups, vec![Group { name: "unnamed_object".into(), faces: 0..2 }]);
}

const PLY_ASCII: &str = "ply
format ascii 1.0
comment a unit quad and a triangle
element vertex 5
property float x
property float y
property float z
property float nx
property float ny
property float nz
property float u
property float v
element face 2
property list uchar int vertex_indices
end_header
0 0 0 0 0 1 0 0
1 0 0 0 0 1 1 0
1 1 0 0 0 1 1 1
0 1 0 0 0 1 0 1
0.5 2 0.25 0 1 0 0.5 0.5
4 0 1 2 3
3 3 2 4
";

#[test]
fn ply_ascii_with_normals_and_uvs() {
    let m = ply(PLY_ASCII.as_bytes()).unwrap();
    assert_eq!(
        m.points,
        vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.], [0.5, 2., 0.25]]
    );
    assert_eq!(faces(&m), vec![vec![0, 1, 2, 3], vec![3, 2, 4]]);
    assert_eq!(m.normals.as_ref().unwrap()[4], [0.0, 1.0, 0.0]);
    assert_eq!(m.uvs.as_ref().unwrap()[2], [1.0, 1.0]);
    assert!(m.groups.is_empty() && m.materials.is_empty());
}

#[test]
fn ply_ascii_with_st_and_other_properties() {
    // `s t` name the uvs; `red` and the `edge` element are read past.
    let text = "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\nproperty uchar red\r\n\
property double y\r\nproperty double z\r\nproperty float s\r\nproperty float t\r\n\
element edge 1\r\nproperty int a\r\nproperty int b\r\nelement face 1\r\n\
property list uchar uint vertex_index\r\nend_header\r\n\
0 255 0 0 0 0\r\n1 0 0 0 1 0\r\n0 7 1 0 0 1\r\n0 1\r\n3 0 1 2\r\n";
    let m = ply(text.as_bytes()).unwrap();
    assert_eq!(m.points, vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.]]);
    assert_eq!(m.uvs, Some(vec![[0., 0.], [1., 0.], [0., 1.]]));
    assert!(m.normals.is_none());
    assert_eq!(faces(&m), vec![vec![0, 1, 2]]);
}

/// A binary PLY of a quad (and a skipped `short` property and a skipped list), written byte
/// by byte in the given order.
fn binary_quad(big: bool, normals: bool) -> Vec<u8> {
    let order = if big { "big" } else { "little" };
    let mut out = format!(
        "ply\nformat binary_{order}_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nproperty short flag\n{}element face 1\nproperty list uchar int vertex_indices\n\
         property list uchar float weights\nend_header\n",
        if normals { "property double nx\nproperty double ny\nproperty double nz\n" } else { "" }
    )
    .into_bytes();
    let f = |x: f32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    let d = |x: f64| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.5], [0.0, 1.0, -0.25]] {
        for x in p {
            out.extend(f(x));
        }
        out.extend(if big { 7i16.to_be_bytes() } else { 7i16.to_le_bytes() });
        if normals {
            for x in [0.0, 0.0, 1.0] {
                out.extend(d(x));
            }
        }
    }
    out.push(4);
    for i in [0i32, 1, 2, 3] {
        out.extend(if big { i.to_be_bytes() } else { i.to_le_bytes() });
    }
    out.push(2);
    out.extend(f(0.5));
    out.extend(f(0.5));
    out
}

#[test]
fn ply_binary_both_byte_orders_with_and_without_normals() {
    for big in [false, true] {
        for normals in [false, true] {
            let m = ply(&binary_quad(big, normals)).unwrap();
            assert_eq!(
                m.points,
                vec![[0., 0., 0.], [1., 0., 0.], [1., 1., 0.5], [0., 1., -0.25]],
                "big {big}"
            );
            assert_eq!(faces(&m), vec![vec![0, 1, 2, 3]]);
            assert_eq!(m.normals, normals.then(|| vec![[0., 0., 1.]; 4]));
            assert!(m.uvs.is_none());
        }
    }
}

/// Every malformed file of the catalogue, and its one-line message.
#[test]
fn malformed_files_catalogue() {
    let mut out = String::new();
    let mut line = |name: &str, r: Result<MeshData, MeshError>| {
        let e = r.expect_err(name);
        let msg = e.to_string();
        assert!(!msg.contains('\n'), "{name}: {msg}");
        out += &format!("{name}: {msg}\n");
    };
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    line("obj index out of range", obj(&format!("{tri}f 1 2 3\nf 1 2 4\n")));
    line("obj negative index out of range", obj(&format!("{tri}f 1 2 -4\n")));
    line("obj uv index out of range", obj(&format!("{tri}vt 0 0\nf 1/1 2/2 3/1\n")));
    line("obj normal index out of range", obj(&format!("{tri}vn 0 0 1\nf 1//1 2//1 3//2\n")));
    line("obj nan coordinate", obj("v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"));
    line("obj infinite normal", obj(&format!("{tri}vn 0 inf 1\nf 1//1 2//1 3//1\n")));
    line("obj bad number", obj("v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n"));
    line("obj two-vertex face", obj(&format!("{tri}f 1 2 3\nf 1 2\n")));
    line("obj line element", obj(&format!("{tri}l 1 2\n")));
    line("obj bad corner", obj(&format!("{tri}f 1 2 3/a\n")));
    line("obj not utf-8", read_bytes(Path::new("m.obj"), b"v 0 0 0\nv \xff 0 0\n", Format::Obj));
    line("obj missing mtl", obj(&format!("mtllib /nonexistent/x.mtl\n{tri}f 1 2 3\n")));

    let quad = binary_quad(false, false);
    line("ply binary truncated", ply(&quad[..quad.len() - 3]));
    let big = binary_quad(true, true);
    line("ply binary big truncated in vertex", ply(&big[..big.len() - 40]));
    let mut bad_index = binary_quad(false, false);
    // The face record: a count byte, 4 indices, a count byte, 2 weights (26 bytes).
    let faces_at = bad_index.len() - 26;
    bad_index[faces_at + 1 + 8..faces_at + 1 + 12].copy_from_slice(&9i32.to_le_bytes());
    line("ply binary index out of range", ply(&bad_index));
    let mut nan = binary_quad(false, false);
    // Vertex 1's y: vertex records are 3 floats and a short (14 bytes).
    let data = nan.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    nan[data + 14 + 4..data + 14 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    line("ply binary nan", ply(&nan));
    let mut small = binary_quad(false, false);
    small[faces_at] = 2;
    line("ply binary two-vertex face", ply(&small[..faces_at + 9]));

    let ascii = |from: &str, to: &str| ply(PLY_ASCII.replacen(from, to, 1).as_bytes());
    line("ply ascii index out of range", ascii("3 3 2 4", "3 3 2 5"));
    line("ply ascii negative index", ascii("3 3 2 4", "3 3 -1 4"));
    line("ply ascii two-vertex face", ascii("3 3 2 4", "2 3 2"));
    line("ply ascii inf", ascii("1 1 0 0 0 1 1 1", "1 inf 0 0 0 1 1 1"));
    line("ply ascii short line", ascii("1 1 0 0 0 1 1 1", "1 1 0 0 0 1 1"));
    line("ply ascii long line", ascii("1 1 0 0 0 1 1 1", "1 1 0 0 0 1 1 1 9"));
    line("ply ascii truncated", ascii("3 3 2 4\n", ""));
    line("ply ascii not a number", ascii("0.5 2 0.25", "0.5 two 0.25"));
    line("ply ascii fractional index", ascii("3 3 2 4", "3 3 2.5 4"));
    line("ply header unknown type", ascii("property float nx", "property quad nx"));
    line("ply header bad format", ascii("format ascii 1.0", "format text 1.0"));
    line("ply header no end", ply(b"ply\nformat ascii 1.0\nelement vertex 0\n"));
    line("ply header unknown line", ascii("comment", "colour"));
    line("ply header no xyz", ascii("property float y\n", ""));
    line(
        "ply header no faces list",
        ascii("property list uchar int vertex_indices", "property list uchar int corners"),
    );
    let lying = |count: &str| {
        let mut b = format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {count}\nproperty float x\n\
             property float y\nproperty float z\nelement nothing 1000000000000\nend_header\n"
        )
        .into_bytes();
        b.extend([0u8; 12]);
        b
    };
    line("ply binary huge vertex count", ply(&lying("5000000000")));
    line("ply binary lying vertex count", ply(&lying("1000000000")));
    line("ply not ply", ply(b"plx\nformat ascii 1.0\nend_header\n"));

    let dir = tempfile::tempdir().unwrap();
    let strip = |r: Result<MeshData, MeshError>| {
        r.map_err(|e| {
            let io = e.is_io();
            let text = e.to_string().replace(&dir.path().display().to_string(), "DIR");
            MeshError::File { path: format!("io={io}").into(), what: text }
        })
    };
    line("missing file", strip(read(dir.path().join("none.obj"))));
    // A file read from disk streams through tobj and is read again to find the line.
    std::fs::write(dir.path().join("bad.obj"), format!("{tri}f 1 2 3\nf 3 2 7\n")).unwrap();
    line("obj file index out of range", strip(read(dir.path().join("bad.obj"))));
    std::fs::write(dir.path().join("m.stl"), "solid x\n").unwrap();
    line("unknown format", strip(read(dir.path().join("m.stl"))));
    insta::assert_snapshot!(out);
}

#[test]
fn io_errors_are_told_apart() {
    let e = read("/nonexistent/dir/m.ply").unwrap_err();
    assert!(e.is_io());
    assert!(!obj("f 1 2 3\n").unwrap_err().is_io());
}

/// A random mesh: up to 40 points with exactly representable random coordinates, optional
/// normals and uvs, and up to 30 faces of 3 to 7 distinct-or-not points each (a face may
/// repeat a point: the readers keep faces as written). Every point is used by some face, so
/// the OBJ reader's weld (which drops unused points) keeps them all.
fn mesh_strategy() -> impl Strategy<Value = MeshData> {
    (1usize..40, any::<bool>(), any::<bool>()).prop_flat_map(|(n, with_normals, with_uvs)| {
        let coord = -1.0e6f32..1.0e6;
        (
            proptest::collection::vec([coord.clone(), coord.clone(), coord.clone()], n),
            proptest::collection::vec([coord.clone(), coord.clone(), coord.clone()], n),
            proptest::collection::vec([coord.clone(), coord], n),
            proptest::collection::vec(proptest::collection::vec(0..n as u32, 3..8), 1..30),
        )
            .prop_map(move |(points, normals, uvs, mut face_list)| {
                // Every point appears: append a face of the unused ones (padded to 3).
                let mut used = vec![false; n];
                face_list.iter().flatten().for_each(|&i| used[i as usize] = true);
                let mut rest: Vec<u32> = (0..n as u32).filter(|&i| !used[i as usize]).collect();
                if !rest.is_empty() {
                    while rest.len() < 3 {
                        rest.push(rest[0]);
                    }
                    face_list.extend(rest.chunks(200).map(<[u32]>::to_vec));
                }
                let mut m = MeshData { points, ..MeshData::default() };
                m.normals = with_normals.then_some(normals);
                m.uvs = with_uvs.then_some(uvs);
                for f in face_list {
                    m.indices.extend(f);
                    m.ends.push(m.indices.len() as u32);
                }
                m
            })
    })
}

/// A face corner's point, normal and uv.
type Corner = ([f32; 3], Option<[f32; 3]>, Option<[f32; 2]>);

/// Each face corner's (point, normal, uv): what a mesh means independent of its numbering.
fn corners(m: &MeshData) -> Vec<Vec<Corner>> {
    m.faces()
        .map(|f| {
            f.iter()
                .map(|&i| {
                    let i = i as usize;
                    (m.points[i], m.normals.as_ref().map(|n| n[i]), m.uvs.as_ref().map(|t| t[i]))
                })
                .collect()
        })
        .collect()
}

proptest! {
    /// Random meshes written as binary PLY (both byte orders) read back identical, and written
    /// as OBJ read back with the same corners (OBJ's reader renumbers points by first use).
    #[test]
    fn round_trips(mesh in mesh_strategy()) {
        for big in [false, true] {
            let mut bytes = Vec::new();
            write_ply_binary(&mesh, &mut bytes, big).unwrap();
            prop_assert_eq!(&ply(&bytes).unwrap(), &mesh);
        }
        let mut text = Vec::new();
        write_obj(&mesh, &mut text).unwrap();
        let back = read_bytes(Path::new("r.obj"), &text, Format::Obj).unwrap();
        prop_assert_eq!(corners(&back), corners(&mesh));
        prop_assert_eq!(back.points.len(), mesh.points.len());
    }
}

#[test]
fn obj_materials_change_within_a_group() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.mtl"), "newmtl a\nKd 1 1 1\nnewmtl b\nKd 0.5 0.5 0.5\n")
        .unwrap();
    let text = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\ng only\nusemtl a\nf 1 2 3\nusemtl b\nf 3 2 1\nf 1 3 2\nusemtl nonesuch\nf 2 1 3\n";
    let path = dir.path().join("m.obj");
    std::fs::write(&path, text).unwrap();
    let m = read(&path).unwrap();
    assert_eq!(m.groups, vec![Group { name: "only".into(), faces: 0..4 }]);
    assert_eq!(m.face_materials, vec![Some(0), Some(1), Some(1), None]);
    assert_eq!(m.materials[1].diffuse, Some([0.5, 0.5, 0.5]));
}

/// Samples to mutate: each valid, in each format.
fn samples() -> Vec<(Format, Vec<u8>)> {
    vec![
        (Format::Obj, b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng a\nf 1/1/1 2/1/1 -1/1/1\no b\nf 1 2 3\n".to_vec()),
        (Format::Ply, PLY_ASCII.as_bytes().to_vec()),
        (Format::Ply, binary_quad(false, true)),
        (Format::Ply, binary_quad(true, false)),
    ]
}

proptest! {
    /// No input makes a reader panic: valid samples with bytes overwritten, cut short, or
    /// spliced with random bytes give a mesh meeting the invariants, or a one-line error.
    #[test]
    fn mutated_files_never_panic(
        which in 0usize..4,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..6),
        cut in any::<prop::sample::Index>(),
        cut_it in any::<bool>(),
    ) {
        let (format, mut bytes) = samples().swap_remove(which);
        for (at, b) in edits {
            let i = at.index(bytes.len());
            bytes[i] = b;
        }
        if cut_it {
            bytes.truncate(cut.index(bytes.len()));
        }
        match read_bytes(Path::new("f"), &bytes, format) {
            Ok(m) => {
                prop_assert!(m.indices.iter().all(|&i| (i as usize) < m.points.len()));
                prop_assert!(m.faces().all(|f| f.len() >= 3));
                prop_assert!(m.points.iter().flatten().all(|x| x.is_finite()));
                prop_assert_eq!(m.ends.last().map_or(0, |&e| e as usize), m.indices.len());
                prop_assert!(m.normals.as_ref().is_none_or(|n| n.len() == m.points.len()));
                prop_assert!(m.uvs.as_ref().is_none_or(|t| t.len() == m.points.len()));
            }
            Err(e) => prop_assert!(!e.to_string().contains('\n')),
        }
    }
}

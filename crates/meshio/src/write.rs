//! Writers of [`MeshData`] as OBJ and binary PLY: the inverse of the readers for the parts
//! both formats carry (points, normals, uvs, faces; OBJ also groups), used by the round-trip
//! tests, the benchmark and its example. Floats are written with Rust's shortest round-trip
//! formatting, so reading back gives the same bits.

use std::io::{self, Write};

use crate::MeshData;

/// Writes `mesh` as OBJ text: `v`, `vt`, `vn` lines, then faces by group (`g NAME` before
/// each group's faces; faces outside any group first). Every corner names its point's uv and
/// normal with the point's own index, so reading welds them back to the same points (points
/// no face uses are dropped by the reader, which renumbers by first use).
pub fn write_obj(mesh: &MeshData, w: &mut impl Write) -> io::Result<()> {
    for p in &mesh.points {
        writeln!(w, "v {} {} {}", p[0], p[1], p[2])?;
    }
    for t in mesh.uvs.iter().flatten() {
        writeln!(w, "vt {} {}", t[0], t[1])?;
    }
    for n in mesh.normals.iter().flatten() {
        writeln!(w, "vn {} {} {}", n[0], n[1], n[2])?;
    }
    let mut face = 0u32;
    let mut write_faces = |w: &mut dyn Write, until: u32| -> io::Result<()> {
        while face < until {
            w.write_all(b"f")?;
            for &i in mesh.face(face as usize) {
                let i = i + 1;
                match (mesh.uvs.is_some(), mesh.normals.is_some()) {
                    (false, false) => write!(w, " {i}")?,
                    (true, false) => write!(w, " {i}/{i}")?,
                    (false, true) => write!(w, " {i}//{i}")?,
                    (true, true) => write!(w, " {i}/{i}/{i}")?,
                }
            }
            w.write_all(b"\n")?;
            face += 1;
        }
        Ok(())
    };
    for g in &mesh.groups {
        write_faces(w, g.faces.start)?;
        writeln!(w, "g {}", g.name)?;
        write_faces(w, g.faces.end)?;
    }
    write_faces(w, mesh.face_count() as u32)
}

/// Writes `mesh` as binary PLY (`big_endian` chooses the byte order): `float x y z`, then
/// `nx ny nz` and `u v` where present, and faces as `list uchar uint vertex_indices`.
///
/// # Errors
///
/// An I/O error, or `InvalidInput` for a face of more than 255 vertices.
pub fn write_ply_binary(mesh: &MeshData, w: &mut impl Write, big_endian: bool) -> io::Result<()> {
    let order = if big_endian { "big" } else { "little" };
    writeln!(w, "ply\nformat binary_{order}_endian 1.0\ncomment written by reyes-meshio")?;
    writeln!(w, "element vertex {}", mesh.points.len())?;
    writeln!(w, "property float x\nproperty float y\nproperty float z")?;
    if mesh.normals.is_some() {
        writeln!(w, "property float nx\nproperty float ny\nproperty float nz")?;
    }
    if mesh.uvs.is_some() {
        writeln!(w, "property float u\nproperty float v")?;
    }
    writeln!(w, "element face {}", mesh.face_count())?;
    writeln!(w, "property list uchar uint vertex_indices\nend_header")?;
    let f = |x: f32| if big_endian { x.to_be_bytes() } else { x.to_le_bytes() };
    for (i, p) in mesh.points.iter().enumerate() {
        let mut values: Vec<f32> = p.to_vec();
        if let Some(n) = &mesh.normals {
            values.extend(n[i]);
        }
        if let Some(t) = &mesh.uvs {
            values.extend(t[i]);
        }
        for x in values {
            w.write_all(&f(x))?;
        }
    }
    for face in mesh.faces() {
        let n = u8::try_from(face.len()).map_err(|_| {
            io::Error::new(
                io::ErrorKind::InvalidInput,
                "a PLY face list holds at most 255 vertices",
            )
        })?;
        w.write_all(&[n])?;
        for &i in face {
            w.write_all(&if big_endian { i.to_be_bytes() } else { i.to_le_bytes() })?;
        }
    }
    Ok(())
}

//! The benchmark's mesh: a flat `n` x `n` grid of quads over the unit square, with normals
//! and uvs, shared by `benches/read.rs` and `examples/read.rs`.

use reyes_meshio::MeshData;

/// An `n` x `n` grid of quads ((n + 1)^2 points, n^2 faces).
pub fn grid(n: u32) -> MeshData {
    let side = n + 1;
    let mut mesh = MeshData::default();
    let mut uvs = Vec::new();
    for j in 0..side {
        for i in 0..side {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            mesh.points.push([u, v, 0.0]);
            uvs.push([u, v]);
        }
    }
    mesh.normals = Some(vec![[0.0, 0.0, 1.0]; mesh.points.len()]);
    mesh.uvs = Some(uvs);
    for j in 0..n {
        for i in 0..n {
            let a = j * side + i;
            mesh.indices.extend([a, a + 1, a + side + 1, a + side]);
            mesh.ends.push(mesh.indices.len() as u32);
        }
    }
    mesh
}

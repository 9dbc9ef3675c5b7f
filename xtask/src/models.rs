//! `cargo xtask models`: the mesh files of the scenes (scenes/models/), made by code so
//! they can be remade and checked.
//!
//! `knot.obj`: a (2, 3) torus knot as a tube of quads with exact normals and texture
//! coordinates. The tube follows a rotation-minimising frame (double reflection, Wang et
//! al. 2008) around the knot, its leftover twist at the end spread evenly along it so the
//! tube closes; the normal of a tube of constant radius about a curve is exactly the unit
//! vector from the curve to the point, so the file's normals are the true surface's. The
//! seam rows (`u = 1`, `v = 1`) repeat the first ones' points with their own coordinates.
//!
//! `--bench`: the benchmark models of docs/performance.md in `scenes/bench/models/` (not
//! committed: about 90 MB): `knot-1m.obj`, the same knot at 16,384 x 64 = 1,048,576 quads,
//! and `knot-100k.obj`, 1,600 x 64 = 102,400 quads welded across both seams (no texture
//! coordinates or normals), a closed control mesh for a subdivision surface.

use std::f64::consts::TAU;
use std::path::Path;

use glam::DVec3;
use reyes_meshio::MeshData;

/// Segments along the knot and around the tube, of the scene's model.
const ALONG: usize = 256;
const AROUND: usize = 16;
/// Tube radius, and the knot's scale (its torus has radii 2 and 1 before scaling).
const TUBE: f64 = 0.28;
const SCALE: f64 = 0.45;

fn knot(t: f64) -> DVec3 {
    let (p, q) = (2.0, 3.0);
    let r = 2.0 + (q * t).cos();
    DVec3::new(r * (p * t).cos(), r * (p * t).sin(), (q * t).sin()) * SCALE
}

/// The knot tube as a mesh of `along x around` quads: with seam rows of their own texture
/// coordinates and the exact normals, or `welded` across both seams without either.
pub fn knot_mesh(along: usize, around: usize, welded: bool) -> MeshData {
    let ts: Vec<f64> = (0..=along).map(|i| TAU * i as f64 / along as f64).collect();
    let pos: Vec<DVec3> = ts.iter().map(|&t| knot(t)).collect();
    let tangent = |i: usize| {
        let h = 1e-5;
        (knot(ts[i] + h) - knot(ts[i] - h)).normalize()
    };
    // Rotation-minimising frame by double reflection.
    let t0 = tangent(0);
    let mut r = t0.any_orthonormal_vector();
    let mut frames = vec![(r, t0)];
    for i in 0..along {
        let (ri, ti) = frames[i];
        let v1 = pos[i + 1] - pos[i];
        let c1 = v1.dot(v1);
        let rl = ri - v1 * (2.0 / c1 * v1.dot(ri));
        let tl = ti - v1 * (2.0 / c1 * v1.dot(ti));
        let tn = tangent(i + 1);
        let v2 = tn - tl;
        let c2 = v2.dot(v2);
        r = if c2 > 0.0 { rl - v2 * (2.0 / c2 * v2.dot(rl)) } else { rl };
        frames.push((r.normalize(), tn));
    }
    // The twist left at the end: the angle from the last frame's r to the first's.
    let (rend, tend) = frames[along];
    let twist = rend.cross(frames[0].0).dot(tend).atan2(rend.dot(frames[0].0));
    let mut mesh = MeshData::default();
    let (mut normals, mut uvs) = (Vec::new(), Vec::new());
    for (i, &(r, t)) in frames.iter().enumerate() {
        let (i, i0) = (i, i % along);
        let turn = twist * i as f64 / along as f64;
        let b = t.cross(r);
        for j in 0..=around {
            let a = TAU * (j % around) as f64 / around as f64 + turn;
            let n = r * a.cos() + b * a.sin();
            // The seam row repeats the first row's points exactly.
            let (n, centre) = if i == along {
                let (r0, t0) = frames[0];
                let b0 = t0.cross(r0);
                let a0 = TAU * (j % around) as f64 / around as f64;
                (r0 * a0.cos() + b0 * a0.sin(), pos[i0])
            } else {
                (n, pos[i])
            };
            let p = centre + n * TUBE;
            mesh.points.push(p.as_vec3().to_array());
            normals.push(n.as_vec3().to_array());
            uvs.push([i as f32 / along as f32, j as f32 / around as f32]);
        }
    }
    if welded {
        // Keep rows 0..along and columns 0..around; the seams' repeats are the first ones.
        let keep: Vec<[f32; 3]> = (0..along)
            .flat_map(|i| (0..around).map(move |j| (i, j)))
            .map(|(i, j)| mesh.points[i * (around + 1) + j])
            .collect();
        mesh.points = keep;
        let at = |i: usize, j: usize| ((i % along) * around + j % around) as u32;
        for i in 0..along {
            for j in 0..around {
                mesh.indices.extend([at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]);
                mesh.ends.push(mesh.indices.len() as u32);
            }
        }
        return mesh;
    }
    let at = |i: usize, j: usize| (i * (around + 1) + j) as u32;
    for i in 0..along {
        for j in 0..around {
            // Counter-clockwise seen from outside the tube (along, then around).
            mesh.indices.extend([at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)]);
            mesh.ends.push(mesh.indices.len() as u32);
        }
    }
    mesh.normals = Some(normals);
    mesh.uvs = Some(uvs);
    mesh
}

fn write(path: &Path, header: &str, mesh: &MeshData) -> Result<(), String> {
    let mut text = Vec::new();
    text.extend_from_slice(header.as_bytes());
    reyes_meshio::write_obj(mesh, &mut text).map_err(|e| e.to_string())?;
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// Writes the scenes' models into `root/scenes/models` (with `bench`, the benchmark models
/// into `root/scenes/bench/models` instead).
pub fn run(root: &Path, bench: bool) -> Result<(), String> {
    let dir = root.join(if bench { "scenes/bench/models" } else { "scenes/models" });
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let made = "made by `cargo xtask models`";
    if bench {
        let header = format!("# A (2, 3) torus knot tube of 16384 x 64 quads; {made} --bench.\n");
        write(&dir.join("knot-1m.obj"), &header, &knot_mesh(16_384, 64, false))?;
        let header =
            format!("# The knot welded, 1600 x 64 quads, a closed control mesh; {made} --bench.\n");
        return write(&dir.join("knot-100k.obj"), &header, &knot_mesh(1_600, 64, true));
    }
    let header = format!("# A (2, 3) torus knot tube with exact normals and uvs; {made}.\n");
    write(&dir.join("knot.obj"), &header, &knot_mesh(ALONG, AROUND, false))
}

//! The coarse mesh of a blobby's surface (marching tetrahedra), on which the dicer dices.
//!
//! Invariants: vertices lie on the surface to the bisection's tolerance, each lattice edge
//! gives one vertex whichever tetrahedron asks, and triangles wind outward.

use glam::DVec3;

use super::{MAX_CELLS, Program, THRESHOLD};

impl Program {
    /// A coarse triangle mesh of the surface: marching tetrahedra (six per cube, Kuhn's
    /// conforming split) over the bound grown by one cell, the cell a quarter of the
    /// smallest feature (at most [`MAX_CELLS`] along the bound's longest side), each vertex
    /// found on its lattice edge by bisection. Vertices are shared (each once per lattice
    /// edge); triangles wind outward. The dicer dices on these triangles, projecting every
    /// point onto the surface ([`Program::project`]); the lattice only has to catch the
    /// surface's topology. Also returns the cell size (the projection's reach).
    pub fn coarse_mesh(&self) -> (Vec<DVec3>, Vec<[u32; 3]>, f64) {
        let Some((lo, hi)) = self.bound else { return (Vec::new(), Vec::new(), 0.0) };
        let extent = (hi - lo).max_element();
        let h = (0.5 * self.feature).max(extent / MAX_CELLS as f64);
        if !(h > 0.0 && h.is_finite()) {
            return (Vec::new(), Vec::new(), 0.0);
        }
        let origin = lo - DVec3::splat(h);
        let n = ((hi - lo + DVec3::splat(2.0 * h)) / h).ceil().as_uvec3();
        let (nx, ny, nz) = (n.x as usize + 1, n.y as usize + 1, n.z as usize + 1);
        let index = |x: usize, y: usize, z: usize| (z * ny + y) * nx + x;
        let at =
            |x: usize, y: usize, z: usize| origin + DVec3::new(x as f64, y as f64, z as f64) * h;
        let mut values = vec![0.0; nx * ny * nz];
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    values[index(x, y, z)] = self.field(at(x, y, z)) - THRESHOLD;
                }
            }
        }
        let mut points: Vec<DVec3> = Vec::new();
        let mut on_edge: std::collections::HashMap<(usize, usize), u32> =
            std::collections::HashMap::new();
        let mut triangles = Vec::new();
        let corner = |x: usize, y: usize, z: usize, k: usize| {
            (x + (k & 1), y + ((k >> 1) & 1), z + ((k >> 2) & 1))
        };
        // Kuhn's six tetrahedra: 0 -> e_a -> e_a + e_b -> 7 for each order (a, b, c).
        const ORDERS: [[usize; 3]; 6] =
            [[1, 2, 4], [1, 4, 2], [2, 1, 4], [2, 4, 1], [4, 1, 2], [4, 2, 1]];
        for z in 0..nz - 1 {
            for y in 0..ny - 1 {
                for x in 0..nx - 1 {
                    for order in ORDERS {
                        let ks = [0, order[0], order[0] | order[1], 7];
                        let ids = ks.map(|k| {
                            let (a, b, c) = corner(x, y, z, k);
                            index(a, b, c)
                        });
                        let pos = ks.map(|k| {
                            let (a, b, c) = corner(x, y, z, k);
                            at(a, b, c)
                        });
                        self.tetrahedron(
                            ids,
                            pos,
                            &values,
                            h,
                            &mut points,
                            &mut on_edge,
                            &mut triangles,
                        );
                    }
                }
            }
        }
        (points, triangles, h)
    }

    #[allow(clippy::too_many_arguments)]
    fn tetrahedron(
        &self,
        ids: [usize; 4],
        pos: [DVec3; 4],
        values: &[f64],
        h: f64,
        points: &mut Vec<DVec3>,
        on_edge: &mut std::collections::HashMap<(usize, usize), u32>,
        triangles: &mut Vec<[u32; 3]>,
    ) {
        let inside: Vec<usize> = (0..4).filter(|&k| values[ids[k]] >= 0.0).collect();
        let outside: Vec<usize> = (0..4).filter(|&k| values[ids[k]] < 0.0).collect();
        if inside.is_empty() || outside.is_empty() {
            return;
        }
        let mut vertex = |a: usize, b: usize| -> u32 {
            let key = (ids[a].min(ids[b]), ids[a].max(ids[b]));
            *on_edge.entry(key).or_insert_with(|| {
                // Bisection from the inside end to the outside end, in lattice order so that
                // both tetrahedra sharing the edge find the same point.
                let (mut p_in, mut p_out) =
                    if values[ids[a]] >= 0.0 { (pos[a], pos[b]) } else { (pos[b], pos[a]) };
                for _ in 0..40 {
                    let mid = 0.5 * (p_in + p_out);
                    if self.field(mid) >= THRESHOLD {
                        p_in = mid;
                    } else {
                        p_out = mid;
                    }
                    if p_in.distance_squared(p_out) <= (1e-9 * h).powi(2) {
                        break;
                    }
                }
                points.push(0.5 * (p_in + p_out));
                (points.len() - 1) as u32
            })
        };
        let centre = |ks: &[usize]| ks.iter().map(|&k| pos[k]).sum::<DVec3>() / ks.len() as f64;
        let out_dir = centre(&outside) - centre(&inside);
        let mut emit = |t: [u32; 3], points: &Vec<DVec3>| {
            let [a, b, c] = t.map(|i| points[i as usize]);
            if (b - a).cross(c - a).dot(out_dir) >= 0.0 {
                triangles.push(t);
            } else {
                triangles.push([t[0], t[2], t[1]]);
            }
        };
        match (inside.len(), outside.len()) {
            (1, 3) | (3, 1) => {
                let (one, rest) =
                    if inside.len() == 1 { (inside[0], &outside) } else { (outside[0], &inside) };
                let t = [vertex(one, rest[0]), vertex(one, rest[1]), vertex(one, rest[2])];
                emit(t, points);
            }
            _ => {
                let (i0, i1, o0, o1) = (inside[0], inside[1], outside[0], outside[1]);
                let q = [vertex(i0, o0), vertex(i0, o1), vertex(i1, o1), vertex(i1, o0)];
                emit([q[0], q[1], q[2]], points);
                emit([q[0], q[2], q[3]], points);
            }
        }
    }
}

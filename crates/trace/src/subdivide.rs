//! Catmull-Clark subdivision surfaces for the ray engine: every limit patch of
//! `reyes_subdiv::limit_patches` (the dicer's surfaces, in its order) tessellated at build
//! time into triangles whose vertices and normals are the crate's limit positions and
//! normals (`dP/du x dP/dv`, the dicer's orientation).
//!
//! The rule: every patch of a mesh gets the same `n x n` grid of its own `(u, v)`, `n` a
//! power of two (at most [`MAX_N`]) and the smallest meeting [`TOLERANCE`] times the
//! patch's size on every patch at every deformation key. One `n` for the whole mesh makes
//! neighbours meet vertex to vertex: a shared edge has the same `n + 1` points on both
//! sides, and the crate evaluates a point with `u` or `v` exactly 0 or 1 through the edge's
//! owning patch, at the owner's parameter `t` or `1 - t`, so both sides get the same bits
//! when `1 - t` is exact, which it is for `t = i / n` with `n` a power of two. The mesh is
//! then as watertight as its triangles are (the triangle test is watertight on shared edges).
//!
//! The error of a patch's `n x n` grid:
//! * a regular patch (a uniform bicubic B-spline) is converted to its Bezier form and
//!   measured by the proven bound of `tessellate.rs` ([`tessellate::error_terms`]);
//! * an irregular patch (an extraordinary corner, a crease) has no polynomial form; its
//!   second derivatives are estimated by second differences of limit positions on a
//!   [`SAMPLES`]-cell grid, doubled for safety, and put in the same formula
//!   `(M_uu + 2 M_uv + M_vv) / (8 n^2)`. This is an estimate, not a bound: near an
//!   extraordinary point the curvature of a Catmull-Clark surface may grow without limit,
//!   but the surface is C1 there, so the error of a cell around it still falls with its size.
//!
//! Size is the diagonal of the patch's conservative box (`LimitPatch::bound`). Holes have no
//! patches (the crate drops them), so no triangles.

use glam::{DMat4, DVec3, Vec3};
use reyes_scene::Shape;
use reyes_subdiv::LimitPatch;

use crate::intake::PointKey;
use crate::tessellate::{self, Bake, MAX_N, TOLERANCE, Tessellation, param};

/// Cells per side of the grid of samples for the curvature estimate of an irregular patch.
const SAMPLES: u32 = 16;
/// Safety factor on the sampled second differences of an irregular patch.
const SAFETY: f64 = 2.0;

/// The limit patches of `shape` with its points replaced by `points` where given.
fn patches_at(shape: &Shape, points: &[Vec3]) -> Option<Vec<LimitPatch>> {
    let moved = |i: usize, own: Vec3| points.get(i).copied().unwrap_or(own);
    let mesh = reyes_scene::subdiv::control_mesh(shape, moved)?;
    reyes_subdiv::limit_patches(&mesh).ok()
}

/// The diagonal of a patch's conservative box.
fn size(patch: &LimitPatch) -> f64 {
    let (lo, hi) = patch.bound();
    (hi - lo).as_dvec3().length()
}

/// The error terms `(uu, uv, vv)` of a patch (see the module documentation): the error of
/// an `n x n` grid is `(uu + 2 uv + vv) / (8 n^2)`.
fn error_terms(patch: &LimitPatch) -> [f64; 3] {
    if let Some(g) = patch.bspline() {
        return tessellate::error_terms(&reyes_scene::subdiv::bspline_to_bezier(&g));
    }
    let s = SAMPLES;
    let h = 1.0 / f64::from(s);
    let grid: Vec<DVec3> = (0..=s)
        .flat_map(|j| (0..=s).map(move |i| (i, j)))
        .map(|(i, j)| patch.eval(param(i, s) as f32, param(j, s) as f32).0.as_dvec3())
        .collect();
    let at = |i: u32, j: u32| grid[(j * (s + 1) + i) as usize];
    let mut most = [0.0_f64; 3];
    for j in 0..=s {
        for i in 0..=s {
            if i + 2 <= s {
                most[0] = most[0].max((at(i + 2, j) - 2.0 * at(i + 1, j) + at(i, j)).length());
            }
            if i < s && j < s {
                let d = at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) + at(i, j);
                most[1] = most[1].max(d.length());
            }
            if j + 2 <= s {
                most[2] = most[2].max((at(i, j + 2) - 2.0 * at(i, j + 1) + at(i, j)).length());
            }
        }
    }
    most.map(|m| SAFETY * m / (h * h))
}

/// The smallest power of two `n <= MAX_N` whose `n x n` grid meets the tolerance on
/// `patch` ([`MAX_N`] when none does).
fn grid_for(patch: &LimitPatch) -> u32 {
    let terms = error_terms(patch);
    let target = TOLERANCE * size(patch);
    let mut n = 1;
    while n < MAX_N && tessellate::bound(terms, n, n) > target {
        n *= 2;
    }
    n
}

/// The unit normal `dP/du x dP/dv` of a patch at `(u, v)`; where it vanishes, the normal a
/// little way into the patch, then that of the corners' diagonals, then +z.
fn normal(patch: &LimitPatch, u: f32, v: f32, du: Vec3, dv: Vec3) -> Vec3 {
    let inward = |t: f32| if t < 0.5 { t + 1e-3 } else { t - 1e-3 };
    du.cross(dv)
        .try_normalize()
        .or_else(|| {
            let (_, du, dv) = patch.eval(inward(u), inward(v));
            du.cross(dv).try_normalize()
        })
        .or_else(|| {
            let c = |u, v| patch.eval(u, v).0;
            (c(1.0, 1.0) - c(0.0, 0.0)).cross(c(0.0, 1.0) - c(1.0, 0.0)).try_normalize()
        })
        .unwrap_or(Vec3::Z)
}

/// The tessellation of a subdivision mesh at every key of `keys` (control points; one key
/// for a still shape), every key with the same vertices in the same order. With `bake`,
/// vertices and normals are carried to world space by that affine matrix. Empty for a mesh
/// the crate refuses (validation refuses such a scene first).
pub(crate) fn tessellate(shape: &Shape, keys: &[PointKey], bake: Option<&DMat4>) -> Tessellation {
    let empty = || Tessellation { keys: Vec::new(), tris: Vec::new() };
    let sets: Option<Vec<(f32, Vec<LimitPatch>)>> = if keys.is_empty() {
        patches_at(shape, &[]).map(|p| vec![(0.0, p)])
    } else {
        keys.iter().map(|k| Some((k.time, patches_at(shape, &k.points)?))).collect()
    };
    let Some(sets) = sets else { return empty() };
    let count = sets.first().map_or(0, |(_, p)| p.len());
    if sets.iter().any(|(_, p)| p.len() != count) {
        return empty();
    }
    let n = sets.iter().flat_map(|(_, p)| p.iter().map(grid_for)).max().unwrap_or(1);
    let bake = bake.map(Bake::new);
    let mut out_keys = Vec::with_capacity(sets.len());
    let mut tris = Vec::new();
    for (key, (time, set)) in sets.iter().enumerate() {
        let mut points = Vec::with_capacity(set.len() * ((n + 1) * (n + 1)) as usize);
        let mut normals = Vec::with_capacity(points.capacity());
        for (k, patch) in set.iter().enumerate() {
            let base = points.len() as u32;
            for j in 0..=n {
                for i in 0..=n {
                    let (u, v) = (param(i, n) as f32, param(j, n) as f32);
                    let (p, du, dv) = patch.eval(u, v);
                    let nrm = normal(patch, u, v, du, dv);
                    let (p, nrm) = Bake::apply(bake.as_ref(), p.as_dvec3(), nrm.as_dvec3());
                    points.push(p);
                    normals.push(nrm);
                }
            }
            if key == 0 {
                tessellate::grid_triangles(k as u32, base, n, n, &mut tris);
            }
        }
        out_keys.push(PointKey { time: *time, points, normals });
    }
    Tessellation { keys: out_keys, tris }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reyes_scene::SubdivTag;
    use std::collections::HashMap;

    /// The cube of half-side 1, corners moved about, with a semi-sharp crease.
    fn creased_cube() -> Shape {
        use reyes_testkit::fixtures::{CUBE_QUADS, cube_corners};
        let points: Vec<[f32; 3]> = cube_corners()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let f = 1.0 + 0.05 * (i * 3 % 5) as f32;
                [p[0] * f + 0.1, p[1] * f, p[2]]
            })
            .collect();
        Shape::SubdivisionMesh {
            points,
            faces: CUBE_QUADS.iter().map(|f| f.to_vec()).collect::<Vec<_>>().into(),
            tags: vec![SubdivTag::Crease { vertices: vec![0, 1, 3], sharpness: 2.5 }],
            colors: None,
            st: None,
        }
    }

    #[test]
    fn neighbouring_patches_share_their_edge_vertices_bit_for_bit() {
        let t = tessellate(&creased_cube(), &[], None);
        let points = &t.keys[0].points;
        let per_patch = points.len() / 24;
        let n = (per_patch as f64).sqrt() as u32 - 1;
        assert_eq!(per_patch, ((n + 1) * (n + 1)) as usize);
        assert!(n.is_power_of_two() && n >= 4, "n = {n}");
        // Boundary vertices by their bits: the once-subdivided cube has 48 edges and 26
        // vertices, so a crack-free tessellation has 48 (n - 1) + 26 distinct boundary
        // points, each edge point twice (two patches), each corner once per patch at it.
        let mut seen: HashMap<[u32; 3], usize> = HashMap::new();
        for k in 0..24 {
            for j in 0..=n {
                for i in 0..=n {
                    if i == 0 || j == 0 || i == n || j == n {
                        let p = points[k * per_patch + (j * (n + 1) + i) as usize];
                        *seen.entry(p.to_array().map(f32::to_bits)).or_default() += 1;
                    }
                }
            }
        }
        assert_eq!(seen.len(), 48 * (n as usize - 1) + 26);
        assert_eq!(seen.values().sum::<usize>(), 24 * 4 * n as usize);
        assert!(seen.values().all(|&c| (2..=4).contains(&c)));
    }

    #[test]
    fn the_triangles_are_within_the_tolerance_of_the_limit_surface() {
        // The distance from the limit point at a cell's (u, v) centre, and at its edges'
        // midpoints, to the same (u, v) on the triangles bounds the distance of the surface
        // to the triangles from above there; it is within TOLERANCE of each patch's size.
        let shape = creased_cube();
        let patches = patches_at(&shape, &[]).unwrap_or_default();
        let t = tessellate(&shape, &[], None);
        let points = &t.keys[0].points;
        let per_patch = points.len() / patches.len();
        let n = (per_patch as f64).sqrt() as u32 - 1;
        let mut worst = 0.0_f64;
        for (k, patch) in patches.iter().enumerate() {
            let at = |i: u32, j: u32| points[k * per_patch + (j * (n + 1) + i) as usize];
            let limit = TOLERANCE * size(patch);
            for j in 0..n {
                for i in 0..n {
                    let uv = |di: f64, dj: f64| {
                        let h = 1.0 / f64::from(n);
                        ((f64::from(i) + di) * h, (f64::from(j) + dj) * h)
                    };
                    // (the point on the triangles, its (u, v)): the diagonal's midpoint,
                    // the midpoints of the bottom and left edges.
                    let probes = [
                        ((at(i, j) + at(i + 1, j + 1)) * 0.5, uv(0.5, 0.5)),
                        ((at(i, j) + at(i + 1, j)) * 0.5, uv(0.5, 0.0)),
                        ((at(i, j) + at(i, j + 1)) * 0.5, uv(0.0, 0.5)),
                    ];
                    for (on, (u, v)) in probes {
                        let p = patch.eval(u as f32, v as f32).0;
                        let d = f64::from((p - on).length());
                        worst = worst.max(d / limit);
                        assert!(d <= limit, "patch {k} cell ({i}, {j}): {d} > {limit}");
                    }
                }
            }
        }
        // Not absurdly fine either: half the grid would not do everywhere.
        assert!(worst > 0.1, "worst {worst} of the tolerance at n = {n}");
    }
}

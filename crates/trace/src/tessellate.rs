//! Bicubic patch meshes and NURBS for the ray engine: every sub-patch or knot span, as the
//! rational Bezier patch `reyes_scene::patches` makes of it, tessellated at build time into
//! triangles whose vertices and normals lie exactly on the surface.
//!
//! The rule: each patch (degree `p x q`, homogeneous net `H = (w P, w)`) gets an
//! `n_u x n_v` grid of its own `(u, v)`, each cell two triangles: the grid of fewest cells
//! (each side at most [`MAX_N`]) whose bound below is at most [`TOLERANCE`] times the
//! diagonal of the box of its projected control points. Every patch of a column of the grid of sub-patches shares
//! the largest `n_u` of the column and every patch of a row the largest `n_v` of the row
//! (over every deformation key too), so neighbours meet vertex to vertex without cracks.
//!
//! The bound: translate so the centroid `C` of the projected points is the origin; the
//! numerator `A` and weight `w` are polynomial Bezier patches, so their second derivatives
//! are bounded by the control net's second differences: `|A_uu| <= p (p-1) max |D2u H|`,
//! `|A_uv| <= p q max |DuDv H|`, `|A_vv| <= q (q-1) max |D2v H|` (spatial parts; the same for
//! `w`). Linear interpolation over a triangle of a cell `h x k` errs by at most
//! `E = (M_uu h^2 + 2 M_uv h k + M_vv k^2) / 8` (Taylor at the point, with sum of
//! `lambda_i (u_i - u)^2 <= h^2 / 4`). The projected triangle point is `T / t_w`, so the
//! distance from a surface point to the triangle is at most `(E_A + R E_w) / w_min`, with
//! `R` the largest distance of a projected control point from `C` and `w_min` the smallest
//! weight (positive by validation). For polynomial patches (`w = 1`) this is `E_A`.
//!
//! Invariants: triangles run `(i, j), (i+1, j), (i+1, j+1)` and `(i, j), (i+1, j+1),
//! (i, j+1)`, so `(b - a) x (c - a)` points along `dP/du x dP/dv`; every key has the same
//! vertices in the same order, so a deforming surface is the same triangles at every key.

use glam::{DMat4, DVec3, DVec4, Vec3};
use reyes_scene::Shape;
use reyes_scene::patches::{self, BezierPatch};

use crate::intake::PointKey;

/// Largest geometric error, as a fraction of a patch's size (its control box diagonal).
pub(crate) const TOLERANCE: f64 = 1e-3;
/// Most grid cells along one direction of one patch (beyond it the bound is not met).
pub(crate) const MAX_N: u32 = 64;

/// One triangle of a tessellation: its patch (the dicer's surface index), its vertex
/// indices, and each vertex's `(u, v)` on the patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tri {
    pub(crate) surface: u32,
    pub(crate) idx: [u32; 3],
    pub(crate) uv: [[f32; 2]; 3],
}

/// The tessellation of one object: vertices and normals per key, and the triangles.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tessellation {
    pub(crate) keys: Vec<PointKey>,
    pub(crate) tris: Vec<Tri>,
}

/// The three error terms `(uu, uv, vv)` of the bound for patch `b`: the error of an
/// `n_u x n_v` grid is `(uu / n_u^2 + 2 uv / (n_u n_v) + vv / n_v^2) / 8`.
pub(crate) fn error_terms(b: &BezierPatch) -> [f64; 3] {
    let (p, q) = (b.du, b.dv);
    let count = b.net.len() as f64;
    let centre = b.hull().fold(DVec3::ZERO, |s, x| s + x) / count;
    let radius = b.hull().map(|x| (x - centre).length()).fold(0.0, f64::max);
    let w_min = b.net.iter().map(|h| h.w).fold(f64::INFINITY, f64::min);
    // The net translated so that the centre is the origin: (w (P - C), w).
    let h = |i: usize, j: usize| {
        let x = b.at(i, j);
        DVec4::from((x.truncate() - centre * x.w, x.w))
    };
    // Second differences of the spatial part and of the weight, kept apart.
    let mut most = [[0.0_f64; 2]; 3];
    let mut keep = |slot: usize, d: DVec4| {
        most[slot][0] = most[slot][0].max(d.truncate().length());
        most[slot][1] = most[slot][1].max(d.w.abs());
    };
    for j in 0..=q {
        for i in 0..=p {
            if i + 2 <= p {
                keep(0, h(i + 2, j) - 2.0 * h(i + 1, j) + h(i, j));
            }
            if i < p && j < q {
                keep(1, h(i + 1, j + 1) - h(i + 1, j) - h(i, j + 1) + h(i, j));
            }
            if j + 2 <= q {
                keep(2, h(i, j + 2) - 2.0 * h(i, j + 1) + h(i, j));
            }
        }
    }
    let [uu, uv, vv] = most.map(|[a, w]| a + radius * w);
    let (p, q) = (p as f64, q as f64);
    [p * (p - 1.0) * uu / w_min, p * q * uv / w_min, q * (q - 1.0) * vv / w_min]
}

/// The bound for an `n_u x n_v` grid from [`error_terms`].
pub(crate) fn bound(terms: [f64; 3], nu: u32, nv: u32) -> f64 {
    let (a, b) = (f64::from(nu), f64::from(nv));
    (terms[0] / (a * a) + 2.0 * terms[1] / (a * b) + terms[2] / (b * b)) / 8.0
}

/// The diagonal of the box of a patch's projected control points.
fn size(b: &BezierPatch) -> f64 {
    let (lo, hi) =
        b.hull().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)));
    (hi - lo).length()
}

/// The grid of fewest cells meeting [`TOLERANCE`] for patch `b`, each side at most
/// [`MAX_N`] (ties to the smaller larger side, then the smaller `n_u`); `MAX_N x MAX_N` when
/// none does.
pub(crate) fn grid_for(b: &BezierPatch) -> (u32, u32) {
    let terms = error_terms(b);
    let target = TOLERANCE * size(b);
    let mut best: Option<(u32, u32)> = None;
    for nu in 1..=MAX_N {
        // The bound falls as nv grows: the first nv that meets it is this nu's best.
        let Some(nv) = (1..=MAX_N).find(|&nv| bound(terms, nu, nv) <= target) else { continue };
        let better = best.is_none_or(|(bu, bv)| (nu * nv, nu.max(nv)) < (bu * bv, bu.max(bv)));
        if better {
            best = Some((nu, nv));
        }
    }
    best.unwrap_or((MAX_N, MAX_N))
}

/// The tessellation of a bicubic patch mesh or NURBS at every key of `keys` (control
/// positions; one key for a still shape, whose own points are then used exactly). With
/// `bake`, vertices and normals are carried to world space by that affine matrix.
pub(crate) fn tessellate(shape: &Shape, keys: &[PointKey], bake: Option<&DMat4>) -> Tessellation {
    let Some((columns, rows)) = patches::bezier_grid(shape) else {
        return Tessellation { keys: Vec::new(), tris: Vec::new() };
    };
    let sets: Vec<(f32, Vec<BezierPatch>)> = if keys.len() <= 1 {
        vec![(keys.first().map_or(0.0, |k| k.time), patches::bezier_patches(shape, None))]
    } else {
        keys.iter()
            .map(|k| {
                let p: Vec<DVec3> = k.points.iter().map(|p| p.as_dvec3()).collect();
                (k.time, patches::bezier_patches(shape, Some(&p)))
            })
            .collect()
    };
    let mut nus = vec![1u32; columns];
    let mut nvs = vec![1u32; rows];
    for (_, set) in &sets {
        for (k, b) in set.iter().enumerate() {
            let (nu, nv) = grid_for(b);
            let (c, r) = (k % columns.max(1), k / columns.max(1));
            if let (Some(a), Some(b)) = (nus.get_mut(c), nvs.get_mut(r)) {
                *a = (*a).max(nu);
                *b = (*b).max(nv);
            }
        }
    }
    let bake = bake.map(Bake::new);
    let mut out_keys = Vec::with_capacity(sets.len());
    let mut tris = Vec::new();
    for (key, (time, set)) in sets.iter().enumerate() {
        let mut points = Vec::new();
        let mut normals = Vec::new();
        for (k, b) in set.iter().enumerate() {
            let (c, r) = (k % columns.max(1), k / columns.max(1));
            let (nu, nv) = (nus.get(c).copied().unwrap_or(1), nvs.get(r).copied().unwrap_or(1));
            let base = points.len() as u32;
            for j in 0..=nv {
                for i in 0..=nu {
                    let (u, v) = (param(i, nu), param(j, nv));
                    let (p, n) = Bake::apply(bake.as_ref(), b.eval(u, v).p, b.normal(u, v));
                    points.push(p);
                    normals.push(n);
                }
            }
            if key == 0 {
                grid_triangles(k as u32, base, nu, nv, &mut tris);
            }
        }
        out_keys.push(PointKey { time: *time, points, normals });
    }
    Tessellation { keys: out_keys, tris }
}

/// The parameter of grid line `i` of `n` (exactly 1 at the last).
pub(crate) fn param(i: u32, n: u32) -> f64 {
    if i >= n { 1.0 } else { f64::from(i) / f64::from(n) }
}

/// Appends the triangles of the `nu x nv` grid of surface `surface` whose vertex `(i, j)`
/// is `base + j (nu + 1) + i` (the order of the module's invariants).
pub(crate) fn grid_triangles(surface: u32, base: u32, nu: u32, nv: u32, tris: &mut Vec<Tri>) {
    let at = |i: u32, j: u32| base + j * (nu + 1) + i;
    let uv = |i: u32, j: u32| [param(i, nu) as f32, param(j, nv) as f32];
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1));
            for [x, y, z] in [[a, b, c], [a, c, d]] {
                tris.push(Tri {
                    surface,
                    idx: [at(x.0, x.1), at(y.0, y.1), at(z.0, z.1)],
                    uv: [uv(x.0, x.1), uv(y.0, y.1), uv(z.0, z.1)],
                });
            }
        }
    }
}

/// A still affine placement baked into tessellated vertices: the matrix and its inverse
/// transpose for the normals.
pub(crate) struct Bake {
    matrix: DMat4,
    normals: DMat4,
}

impl Bake {
    pub(crate) fn new(m: &DMat4) -> Bake {
        Bake { matrix: *m, normals: m.inverse().transpose() }
    }

    /// A vertex and its normal, carried to world space when there is a bake, in `f32`.
    pub(crate) fn apply(bake: Option<&Bake>, p: DVec3, n: DVec3) -> (Vec3, Vec3) {
        match bake {
            Some(b) => {
                let m = b.normals.transform_vector3(n).try_normalize().unwrap_or(n);
                (b.matrix.transform_point3(p).as_vec3(), m.as_vec3())
            }
            None => (p.as_vec3(), n.as_vec3()),
        }
    }
}

/// A unit normal interpolated with barycentric weights `(1 - wb - wc, wb, wc)`, or `None`
/// where the interpolation vanishes.
#[inline]
pub(crate) fn interpolate_normal(n: &[Vec3; 3], wb: f32, wc: f32) -> Option<Vec3> {
    (n[0] * (1.0 - wb - wc) + n[1] * wb + n[2] * wc).try_normalize()
}

/// Barycentric weights `(wb, wc)` of a triangle hit from the dicer's `(u, v)` convention of
/// `patch::triangle` (`v = wc`, `u = wb / (1 - wc)`).
#[inline]
pub(crate) fn weights(u: f32, v: f32) -> (f32, f32) {
    (u * (1.0 - v), v)
}

/// Control positions of a valid bicubic patch mesh or NURBS, in `f32` (as deformation keys
/// give them), or empty.
pub(crate) fn own_positions(shape: &Shape) -> Vec<Vec3> {
    patches::control_positions(shape)
        .map(|p| p.iter().map(|q| q.as_vec3()).collect())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bicubic Bezier patch bent into a quarter cylinder of radius 1 (approximately).
    fn bent() -> BezierPatch {
        let k = 0.5523;
        let arc = [(1.0, 0.0), (1.0, k), (k, 1.0), (0.0, 1.0)];
        let net = (0..16)
            .map(|n| {
                let (x, y) = arc[n % 4];
                DVec4::new(x, y, (n / 4) as f64 / 3.0, 1.0)
            })
            .collect();
        BezierPatch::new(3, 3, net)
    }

    #[test]
    fn the_bound_holds_and_is_met() {
        let b = bent();
        let (nu, nv) = grid_for(&b);
        let terms = error_terms(&b);
        assert!(bound(terms, nu, nv) <= TOLERANCE * size(&b));
        assert_eq!(nv, 1, "straight along v: one cell");
        // The actual error, sampled densely, is below the bound.
        let mut worst = 0.0_f64;
        for cell in 0..nu {
            for s in 0..=20 {
                let t = s as f64 / 20.0;
                let (u0, u1) = (cell as f64 / nu as f64, (cell + 1) as f64 / nu as f64);
                let (a, c) = (b.eval(u0, 0.0).p, b.eval(u1, 0.0).p);
                let chord = a.lerp(c, t);
                let exact = b.eval(u0 + t * (u1 - u0), 0.0).p;
                worst = worst.max((exact - chord).length());
            }
        }
        assert!(worst <= bound(terms, nu, nv), "{worst} > bound");
        assert!(worst > 0.1 * bound(terms, nu, nv), "the bound is not absurdly loose");
    }

    #[test]
    fn flat_patches_need_one_cell() {
        let net = (0..16).map(|n| DVec4::new((n % 4) as f64, (n / 4) as f64, 0.0, 1.0)).collect();
        assert_eq!(grid_for(&BezierPatch::new(3, 3, net)), (1, 1));
    }
}

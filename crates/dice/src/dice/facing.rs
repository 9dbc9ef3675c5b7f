//! Back faces (stage: dice): the winding sign of a grid, calibrated on a cell that clearly
//! faces one way, which cells of it face away from the eye over their whole segment, and
//! which objects may have their back faces culled at all. Invariant: a cell is culled only
//! where no sample could see its front (the margins below are conservative).

use glam::Vec3;
use reyes_hider::flags;

use super::{Emitter, Labels, Quad};

/// Relative margin of the winding tests: a corner counts as turned one way when its signed
/// area exceeds this fraction of the product of its edge lengths (a sine of 0.001).
pub(super) const WINDING_MARGIN: f32 = 1e-3;

/// Raster signed area (cross product) at corner `k` of a quad, from its two edges, and the
/// product of the edge lengths.
#[inline]
pub(super) fn corner_area(q: &Quad, k: usize) -> (f32, f32) {
    let (p, next, prev) = (q[k], q[(k + 1) % 4], q[(k + 3) % 4]);
    let e1 = [next[0] - p[0], next[1] - p[1]];
    let e2 = [prev[0] - p[0], prev[1] - p[1]];
    let area = e1[0] * e2[1] - e1[1] * e2[0];
    let scale = (e1[0].hypot(e1[1])) * (e2[0].hypot(e2[1]));
    (area, scale)
}

/// Whether back faces of `object` may be culled (see [`super::ObjectContext::cull_back`]): it is
/// one-sided (RenderMan's `Sides 1`), or they cannot be seen: a pinhole camera (under a lens a micropolygon turned away from the eye may face part
/// of the lens), a closed surface (a full sphere or torus, a closed mesh), opaque, and not
/// matte, glass or a CSG operand (CSG needs both sides: a difference shows the inside of
/// its subtracted operand). Affine placements only: a projective matrix can turn a surface
/// inside out between its parts.
pub(crate) fn cull_back_faces(
    object: &reyes_scene::Object,
    labels: &Labels,
    csg_operand: bool,
    pinhole: bool,
) -> bool {
    let f = labels.flags;
    let affine = |list: &[reyes_scene::Transform]| {
        let m = reyes_scene::object_to_world(list);
        m.row(3) == glam::Vec4::W && m.is_finite()
    };
    let placements_affine = if object.motion.is_empty() {
        affine(&object.transform)
    } else {
        object.motion.iter().all(|k| affine(&k.transform))
    };
    let hidden = f & flags::OPAQUE != 0
        && f & (flags::MATTE | flags::GLASS) == 0
        && reyes_scene::closed_alone(&object.shape);
    pinhole && !csg_operand && (hidden || object.one_sided) && placements_affine
}

/// True if the corner `k` of a cell moving from quad `from` to quad `to` as the hider moves
/// it under the perspective warp (straight in camera space: the homogeneous raster point
/// `(x z, y z, z)` of each vertex moves linearly) keeps `sign * (signed area) <
/// -WINDING_MARGIN * (edge lengths)` throughout. The signed area times the three depths is
/// the determinant of the corner's three homogeneous points, a cubic in the time of the
/// segment; it is below the margin throughout if its four Bernstein coefficients are.
fn corner_cubic_negative(sign: f32, from: &Quad, to: &Quad, k: usize) -> bool {
    let idx = [k, (k + 1) % 4, (k + 3) % 4];
    let h = |q: &Quad| idx.map(|i| Vec3::new(q[i][0] * q[i][2], q[i][1] * q[i][2], q[i][2]));
    let (a, b) = (h(from), h(to));
    let det = |x: Vec3, y: Vec3, z: Vec3| x.dot(y.cross(z));
    let bern = [
        det(a[0], a[1], a[2]),
        (det(b[0], a[1], a[2]) + det(a[0], b[1], a[2]) + det(a[0], a[1], b[2])) / 3.0,
        (det(a[0], b[1], b[2]) + det(b[0], a[1], b[2]) + det(b[0], b[1], a[2])) / 3.0,
        det(b[0], b[1], b[2]),
    ];
    let scale = |q: &Quad| {
        let (_, s) = corner_area(q, k);
        s * idx.iter().map(|&i| q[i][2]).product::<f32>()
    };
    let margin = -WINDING_MARGIN * scale(from).min(scale(to));
    bern.iter().all(|&c| sign * c < margin)
}

impl Emitter<'_> {
    /// The winding sign of the grid, from the first cell (in cell order) that is clearly
    /// turned one way in raster space (corner 0's sine above 0.1, so not a sliver at a
    /// pole) at a corner where the surface clearly faces toward or away from the eye
    /// (`|cos| > 0.2`, from `cosines`, per vertex at shutter open): its raster signed area
    /// times that side's sign. The sign holds for the whole grid: a smooth surface's
    /// parametrisation turns the same way about its outward normal everywhere, and the
    /// perspective projection of points in front of the eye keeps orientation. `None`
    /// (no culling) when no cell qualifies.
    pub(super) fn calibrate(&self, cosines: &[f32]) -> Option<f32> {
        let nu = self.grid.nu as usize;
        let nv = self.grid.count as usize / (nu + 1) - 1;
        // Interior cells first: a crack-free grid's boundary vertices lie on its sides'
        // polylines, a little off the surface whose normals `cosines` are.
        let interior = (1..nv.saturating_sub(1)).flat_map(|j| (1..nu - 1).map(move |i| (i, j)));
        let border = (0..nv)
            .flat_map(|j| (0..nu).map(move |i| (i, j)))
            .filter(|&(i, j)| i == 0 || j == 0 || i + 1 == nu || j + 1 == nv);
        interior.chain(border).find_map(|(i, j)| {
            let cell = (j * nu + i) as u32;
            let cos = *cosines.get(j * (nu + 1) + i)?;
            let q = self.grid.quad(cell, 0);
            let (area, scale) = corner_area(&q, 0);
            let edge = |a: usize, b: usize| (q[b][0] - q[a][0]).hypot(q[b][1] - q[a][1]);
            let (e1, e2) = (edge(0, 1), edge(0, 3));
            // Both edges a real fraction of a pixel and of each other: a cell collapsed
            // at a pole has an edge of rounding noise whose cross product has no sign.
            let proper = e1.min(e2) > 1e-2 * e1.max(e2) && e1.min(e2) > 1e-3;
            (proper && cos.abs() > 0.2 && area.abs() > 0.1 * scale)
                .then(|| area.signum() * cos.signum())
        })
    }

    /// True if cell quad `from` (moving to `to` over its segment, raster positions moving
    /// linearly as the hider moves them) faces away from the eye at every time, with a
    /// margin: every corner's signed area, `sign` times a quadratic in time, stays below
    /// `-WINDING_MARGIN` times the corner's edge lengths. A non-convex or nearly edge-on
    /// micropolygon is kept. Under the perspective warp (`warp`) a moving cell's corners are
    /// tested as the hider moves them ([`corner_cubic_negative`]).
    pub(super) fn backfacing(sign: f32, from: &Quad, to: Option<&Quad>, warp: bool) -> bool {
        if let (true, Some(to)) = (warp, to) {
            return (0..4).all(|k| corner_cubic_negative(sign, from, to, k));
        }
        let mid = to.map(|to| {
            let mut m = *from;
            for (p, q) in m.iter_mut().zip(to) {
                for a in 0..2 {
                    p[a] = 0.5 * (p[a] + q[a]);
                }
            }
            m
        });
        (0..4).all(|k| {
            let (a0, s0) = corner_area(from, k);
            if sign * a0 >= -WINDING_MARGIN * s0 {
                return false;
            }
            let (Some(to), Some(mid)) = (to, mid.as_ref()) else {
                return true;
            };
            let (a1, s1) = corner_area(to, k);
            let (am, sm) = corner_area(mid, k);
            let margin = -WINDING_MARGIN * s0.min(s1).min(sm);
            if sign * a1 >= margin || sign * am >= margin {
                return false;
            }
            // A(t) = a t^2 + b t + c through the three values; a concave parabola may peak
            // between them.
            let (c, a) = (a0, 2.0 * a1 + 2.0 * a0 - 4.0 * am);
            let b = a1 - a0 - a;
            let qa = sign * a;
            if qa < 0.0 {
                let t = -b / (2.0 * a);
                if t > 0.0 && t < 1.0 && sign * ((a * t + b) * t + c) >= margin {
                    return false;
                }
            }
            true
        })
    }
}

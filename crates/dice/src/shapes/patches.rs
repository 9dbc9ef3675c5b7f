//! Patch surfaces: the bilinear patch (every bilinear patch, mesh face and bilinear
//! patch-mesh sub-patch) and the rational Bezier patch (bicubic patch-mesh sub-patches and
//! NURBS spans).

use glam::Vec3;
use reyes_scene::patches::BezierPatch;

/// A bilinear patch: `P(u,v) = lerp(lerp(P0,P1,u), lerp(P2,P3,u), v)`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Bilinear {
    /// Corners in RenderMan order: (0,0), (1,0), (0,1), (1,1).
    pub(super) p: [Vec3; 4],
    /// Per-corner tint, interpolated the same way.
    pub(super) tint: [Vec3; 4],
    /// A fixed normal (mesh triangles use their flat face normal).
    pub(super) flat_normal: Option<Vec3>,
    /// The patch's average normal, used where the partial derivatives are degenerate.
    pub(super) average_normal: Vec3,
}

impl Bilinear {
    /// A patch from its corners, tints and an optional fixed normal.
    pub(super) fn new(p: [Vec3; 4], tint: [Vec3; 4], flat_normal: Option<Vec3>) -> Bilinear {
        // The vector area of a bilinear patch is half the cross product of its diagonals.
        let average_normal = (p[3] - p[0]).cross(p[2] - p[1]).try_normalize().unwrap_or(Vec3::Z);
        let flat_normal = flat_normal.map(|n| n.try_normalize().unwrap_or(average_normal));
        Bilinear { p, tint, flat_normal, average_normal }
    }
}

#[inline]
pub(super) fn lerp4(c: &[Vec3; 4], u: f32, v: f32) -> Vec3 {
    let bottom = c[0].lerp(c[1], u);
    let top = c[2].lerp(c[3], u);
    bottom.lerp(top, v)
}

/// A bicubic patch-mesh sub-patch or a NURBS span, as the rational Bezier patch
/// `reyes_scene::patches` makes of it (`f64`): position and partial derivatives exact up to
/// rounding, the unit normal `dP/du x dP/dv` with the fallbacks of
/// [`BezierPatch::normal`].
pub(super) fn bezier_position(patch: &BezierPatch, u: f32, v: f32) -> Vec3 {
    patch.eval(f64::from(u), f64::from(v)).p.as_vec3()
}

/// The unit normal of [`bezier_position`]'s patch at `(u, v)`.
pub(super) fn bezier_normal(patch: &BezierPatch, u: f32, v: f32) -> Vec3 {
    patch.normal(f64::from(u), f64::from(v)).as_vec3()
}

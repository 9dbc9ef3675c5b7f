//! Patch surfaces: the bilinear patch (every bilinear patch, mesh face and bilinear
//! patch-mesh sub-patch) and the rational Bezier patch (bicubic patch-mesh sub-patches and
//! NURBS spans).

use glam::{Vec2, Vec3};
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
    /// Per-corner shading normals (a mesh's `normals`), interpolated as the tint is.
    pub(super) normals: Option<[Vec3; 4]>,
    /// Per-corner texture coordinates (a mesh's `st`), interpolated as the tint is.
    pub(super) st: Option<[Vec2; 4]>,
}

impl Bilinear {
    /// A patch from its corners, tints and an optional fixed normal.
    pub(super) fn new(p: [Vec3; 4], tint: [Vec3; 4], flat_normal: Option<Vec3>) -> Bilinear {
        // The vector area of a bilinear patch is half the cross product of its diagonals.
        let average_normal = (p[3] - p[0]).cross(p[2] - p[1]).try_normalize().unwrap_or(Vec3::Z);
        let flat_normal = flat_normal.map(|n| n.try_normalize().unwrap_or(average_normal));
        Bilinear { p, tint, flat_normal, average_normal, normals: None, st: None }
    }

    /// The patch with per-corner shading normals and texture coordinates (RenderMan order).
    pub(super) fn with_vertex_data(
        mut self,
        normals: Option<[Vec3; 4]>,
        st: Option<[Vec2; 4]>,
    ) -> Bilinear {
        self.normals = normals;
        self.st = st;
        self
    }

    /// The geometric unit normal at `(u, v)`: the fixed one, else `dP/du x dP/dv`, else the
    /// average normal.
    pub(super) fn geometric_normal(&self, u: f32, v: f32) -> Vec3 {
        match self.flat_normal {
            Some(n) => n,
            None => {
                let p = &self.p;
                let dpdu = (p[1] - p[0]).lerp(p[3] - p[2], v);
                let dpdv = (p[2] - p[0]).lerp(p[3] - p[1], u);
                dpdu.cross(dpdv).try_normalize().unwrap_or(self.average_normal)
            }
        }
    }

    /// The unit shading normal at `(u, v)`: the corners' normals interpolated (bilinearly;
    /// over a triangle `[a, b, c, c]` that is the barycentric interpolation) and normalised,
    /// turned to the side of the geometric normal, which carries the patch's orientation
    /// (the winding of its micropolygons); the geometric normal where there are no corner
    /// normals or they cancel.
    pub(super) fn normal(&self, u: f32, v: f32) -> Vec3 {
        let geometric = self.geometric_normal(u, v);
        match self.normals.and_then(|n| lerp4(&n, u, v).try_normalize()) {
            Some(n) if n.dot(geometric) < 0.0 => -n,
            Some(n) => n,
            None => geometric,
        }
    }

    /// The texture coordinates at `(u, v)`, where the corners have them.
    pub(super) fn st(&self, u: f32, v: f32) -> Option<Vec2> {
        self.st.map(|st| {
            let bottom = st[0].lerp(st[1], u);
            let top = st[2].lerp(st[3], u);
            bottom.lerp(top, v)
        })
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

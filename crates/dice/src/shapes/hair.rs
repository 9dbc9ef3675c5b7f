//! Hair and implicit surfaces as parametric patches: a curve segment's ribbon (`u` across
//! the width, `v` along the curve) and a face of a blobby's coarse mesh whose every point is
//! moved onto the isosurface.
//!
//! Invariants: a ribbon's `u = 1/2` is the curve, its width at `v` is the curve's width
//! there, and it turns as its [`Facing`] says (a camera-facing ribbon faces the camera of the
//! breakpoint its surface set was made for); `dP/du x dP/dv` points along the normal
//! returned. A blobby face's points lie on the isosurface (to Newton's tolerance), are a
//! deterministic function of the point of the flat face they come from (so two faces sharing
//! an edge share its points bit for bit), and its normal is `-grad` of the field.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use reyes_scene::blobby::Program;
use reyes_scene::curves::{Facing, Segment};

/// One curve segment's ribbon.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Ribbon {
    pub(crate) segment: Segment,
    pub(crate) facing: Facing,
}

impl Ribbon {
    #[inline]
    pub(crate) fn position(&self, u: f32, v: f32) -> Vec3 {
        self.segment.ribbon(u, v, self.facing).0
    }

    /// Position, unit normal, colour and opacity at `(u, v)`.
    pub(crate) fn eval(&self, u: f32, v: f32) -> (Vec3, Vec3, Vec3, Vec3) {
        let (p, n) = self.segment.ribbon(u, v, self.facing);
        (p, n, self.segment.color_at(v), self.segment.opacity_at(v))
    }

    /// A hull of the part `[v0, v1]`: the corners of the cube of half the largest width
    /// about every Bezier control point of that part of the centre line, which holds the
    /// ribbon whichever way it turns.
    pub(crate) fn hull(&self, v: [f32; 2]) -> Vec<Vec3> {
        let part =
            if v == [0.0, 1.0] { self.segment.clone() } else { self.segment.sub(v[0], v[1]) };
        let r = 0.5 * part.max_width();
        part.p
            .iter()
            .flat_map(|c| {
                (0..8).map(move |k| {
                    let s = |bit: u32| if k & bit == 0 { -r } else { r };
                    *c + Vec3::new(s(1), s(2), s(4))
                })
            })
            .collect()
    }
}

/// One triangle of a blobby's coarse mesh, diced as the degenerate quad `[a, b, c, c]` whose
/// points are projected onto the isosurface.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BlobFace {
    /// The triangle's corners (on the surface), object space.
    pub(crate) corners: [DVec3; 3],
    /// Their vertex ids in the coarse mesh (the corners of the quad `[a, b, c, c]`).
    pub(crate) ids: [usize; 3],
    /// The field.
    pub(crate) program: Arc<Program>,
    /// The longest step of the projection (the coarse lattice's cell).
    pub(crate) reach: f64,
    /// Per-field colours and opacities, blended by the fields' weights.
    pub(crate) colors: Option<Arc<Vec<Vec3>>>,
    pub(crate) opacities: Option<Arc<Vec<Vec3>>>,
}

impl BlobFace {
    /// The flat face's point at `(u, v)`: bilinear over `[a, b, c, c]`.
    fn flat(&self, u: f32, v: f32) -> DVec3 {
        let [a, b, c] = self.corners;
        let (u, v) = (f64::from(u), f64::from(v));
        let bottom = a + (b - a) * u;
        bottom + (c - bottom) * v
    }

    #[inline]
    pub(crate) fn surface_point(&self, u: f32, v: f32) -> DVec3 {
        // Corners are already on the surface; keep them exactly.
        match (u, v) {
            (0.0, 0.0) => self.corners[0],
            (1.0, 0.0) => self.corners[1],
            (_, 1.0) => self.corners[2],
            _ => self.program.project(self.flat(u, v), self.reach),
        }
    }

    pub(crate) fn position(&self, u: f32, v: f32) -> Vec3 {
        self.surface_point(u, v).as_vec3()
    }

    /// Position, outward unit normal, colour and opacity at `(u, v)`.
    pub(crate) fn eval(&self, u: f32, v: f32) -> (Vec3, Vec3, Vec3, Vec3) {
        let p = self.surface_point(u, v);
        let n = self.program.normal(p).as_vec3();
        let blend = |values: &Option<Arc<Vec<Vec3>>>| {
            values.as_ref().map_or(Vec3::ONE, |c| {
                if c.len() == 1 {
                    return c[0];
                }
                let w = self.program.leaf_weights(p);
                w.iter().zip(c.iter()).map(|(w, c)| *c * *w as f32).sum()
            })
        };
        (p.as_vec3(), n, blend(&self.colors), blend(&self.opacities))
    }

    /// The quad's corner ids `[a, b, c, c]`, for sharing edges with neighbouring faces.
    pub(crate) fn corner_ids(&self) -> [usize; 4] {
        let [a, b, c] = self.ids;
        [a, b, c, c]
    }
}

/// The faces of a blobby's coarse mesh ([`Program::coarse_mesh`]), sharing its field.
pub(crate) fn blob_faces(shape: &reyes_scene::Shape) -> Vec<super::Surface> {
    let reyes_scene::Shape::Blobby { code, floats, strings, colors, opacities } = shape else {
        return Vec::new();
    };
    let Ok(program) = Program::parse(code, floats, strings) else { return Vec::new() };
    let (points, triangles, reach) = program.coarse_mesh();
    let program = Arc::new(program);
    let leaves = program.leaf_count();
    let per_field = |var: &Option<reyes_scene::Primvar<[f32; 3]>>| {
        var.as_ref().map(|v| {
            Arc::new(match v {
                reyes_scene::Primvar::Constant(c) => vec![Vec3::from(*c)],
                reyes_scene::Primvar::Uniform(c) => {
                    c.iter().take(1).map(|c| Vec3::from(*c)).collect()
                }
                _ => (0..leaves).map(|i| v.at(i).map_or(Vec3::ONE, Vec3::from)).collect(),
            })
        })
    };
    let (colors, opacities) = (per_field(colors), per_field(opacities));
    triangles
        .into_iter()
        .map(|t| {
            super::Surface::Blob(Box::new(BlobFace {
                corners: t.map(|i| points[i as usize]),
                ids: t.map(|i| i as usize),
                program: program.clone(),
                reach,
                colors: colors.clone(),
                opacities: opacities.clone(),
            }))
        })
        .collect()
}

//! Catmull-Clark subdivision surfaces as dicer surfaces: one [`SubdivPatch`] per quad of the
//! once-subdivided control mesh ([`reyes_subdiv::limit_patches`]), each over its own
//! `(u, v)` in `[0, 1]^2`, in the crate's order.
//!
//! Evaluation: a patch whose quad is regular (four valence-4 corners, no sharpness) is
//! exactly a uniform bicubic B-spline patch; it is converted once to its Bezier patch, which
//! evaluates inside the patch in a few dozen flops and gives the control hull the splitter
//! bounds with. Every other patch (an extraordinary corner, a crease, a corner tag) is
//! evaluated by the crate's local adaptive subdivision, and bounded by the hull of its
//! refined control points over the part asked for. Points on a patch's boundary
//! (`u` or `v` 0 or 1) are always evaluated by the crate, which routes them to the edge's
//! owning patch, so two neighbours compute the same point of their common edge bit for bit
//! whichever way each is evaluated inside; crack-free dicing shares the edges' polylines on
//! top of that (`lazy.rs`).
//!
//! Orientation: a patch's `u` runs from its first corner to its second and `v` from its first
//! to its fourth, in the order of the control face, so `dP/du x dP/dv` points the way the
//! right-hand rule gives around the faces, as for a polygon mesh.
//!
//! Vertex colours (`Cs`) are subdivided as the points are (a limit surface of the colours);
//! facevarying `st` is bilinear over each control face.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use reyes_scene::Shape;
use reyes_scene::patches::BezierPatch;
use reyes_subdiv::{LimitPatch, Mesh};

/// One limit surface patch (of the points, or of the colours), with its Bezier form when
/// the quad is regular.
#[derive(Debug, Clone)]
struct Limit {
    limit: LimitPatch,
    bezier: Option<BezierPatch>,
}

impl Limit {
    fn new(limit: LimitPatch) -> Limit {
        let bezier = limit.bspline().map(|g| reyes_scene::subdiv::bspline_to_bezier(&g));
        Limit { limit, bezier }
    }

    /// The inside of a regular patch through its Bezier form; the boundary, and every point of
    /// an irregular patch, through the crate (canonical on shared edges).
    #[inline]
    fn position(&self, u: f32, v: f32) -> Vec3 {
        match &self.bezier {
            Some(b) if !on_boundary(u, v) => b.eval(f64::from(u), f64::from(v)).p.as_vec3(),
            _ => self.limit.eval(u, v).0,
        }
    }
}

#[inline]
fn on_boundary(u: f32, v: f32) -> bool {
    u == 0.0 || u == 1.0 || v == 0.0 || v == 1.0
}

/// One patch of a subdivision surface (see the module documentation).
#[derive(Debug, Clone)]
pub(crate) struct SubdivPatch {
    points: Limit,
    /// The colours' limit patch, when the mesh has vertex colours.
    tint: Option<Limit>,
}

impl PartialEq for SubdivPatch {
    fn eq(&self, other: &SubdivPatch) -> bool {
        let same = |a: &Limit, b: &Limit| a.limit.same(&b.limit);
        same(&self.points, &other.points)
            && match (&self.tint, &other.tint) {
                (Some(a), Some(b)) => same(a, b),
                (None, None) => true,
                _ => false,
            }
    }
}

impl SubdivPatch {
    /// Level-1 point ids of the corners at `(0,0), (1,0), (1,1), (0,1)`: the same id is the
    /// same point in every patch of the mesh, so an edge is named by its two corners' ids.
    pub fn corners(&self) -> [usize; 4] {
        self.points.limit.corners
    }

    /// Object-space position at `(u, v)`.
    #[inline]
    pub fn position(&self, u: f32, v: f32) -> Vec3 {
        self.points.position(u, v)
    }

    /// Unit normal `dP/du x dP/dv` at `(u, v)`. Where it vanishes (a degenerate control
    /// mesh), the normal a little way into the patch, then that of the corners' diagonals.
    #[cfg(test)]
    pub fn normal(&self, u: f32, v: f32) -> Vec3 {
        self.point(u, v).1
    }

    /// Position and unit normal at `(u, v)`, from one evaluation.
    pub fn point(&self, u: f32, v: f32) -> (Vec3, Vec3) {
        let at = |u: f32, v: f32| -> (Vec3, Option<Vec3>) {
            match &self.points.bezier {
                Some(b) => {
                    let n = b.normal(f64::from(u), f64::from(v)).as_vec3().try_normalize();
                    (self.points.position(u, v), n)
                }
                None => {
                    let (p, du, dv) = self.points.limit.eval(u, v);
                    (p, du.cross(dv).try_normalize())
                }
            }
        };
        let (p, n) = at(u, v);
        let nudge = |t: f32| if t < 0.5 { t + 1e-3 } else { t - 1e-3 };
        let n = n.or_else(|| at(nudge(u), nudge(v)).1).unwrap_or_else(|| {
            let c = |u, v| self.points.limit.eval(u, v).0;
            (c(1.0, 1.0) - c(0.0, 0.0))
                .cross(c(0.0, 1.0) - c(1.0, 0.0))
                .try_normalize()
                .unwrap_or(Vec3::Z)
        });
        (p, n)
    }

    /// The colour multiplying the material's at `(u, v)` (white without vertex colours).
    pub fn tint(&self, u: f32, v: f32) -> Vec3 {
        self.tint.as_ref().map_or(Vec3::ONE, |t| t.position(u, v))
    }

    /// Facevarying `(s, t)` at `(u, v)`, when the mesh has them.
    #[allow(dead_code)]
    pub fn st(&self, u: f32, v: f32) -> Option<Vec2> {
        let st = self.points.limit.eval_facevarying(u, v);
        (st.len() == 2).then(|| Vec2::new(st[0], st[1]))
    }

    /// Object-space points whose convex hull encloses the part `u x v` of the patch: the
    /// Bezier net of that part of a regular patch, else the corners of the box of the
    /// refined control points over it.
    pub fn hull(&self, u: [f32; 2], v: [f32; 2]) -> Vec<Vec3> {
        let (u, v) = (u.map(f64::from), v.map(f64::from));
        match &self.points.bezier {
            Some(b) => {
                let sub = if u == [0.0, 1.0] && v == [0.0, 1.0] { b.clone() } else { b.sub(u, v) };
                sub.hull().map(|p| p.as_vec3()).collect()
            }
            None => {
                let (lo, hi) = self.points.limit.part(u, v).bound();
                super::box_corners(lo, hi).to_vec()
            }
        }
    }
}

/// The patches of a (valid) subdivision shape, with its points replaced by `points_object`
/// where given; empty for other shapes, or for a mesh the crate rejects (validation rejects
/// such a scene first).
pub(crate) fn patches(shape: &Shape, points_object: Option<&[Vec3]>) -> Vec<SubdivPatch> {
    let Shape::SubdivisionMesh { colors, .. } = shape else {
        return Vec::new();
    };
    let moved = |i: usize, own: Vec3| points_object.and_then(|p| p.get(i).copied()).unwrap_or(own);
    let Some(mesh) = reyes_scene::subdiv::control_mesh(shape, moved) else {
        return Vec::new();
    };
    let Ok(limits) = reyes_subdiv::limit_patches(&mesh) else {
        return Vec::new();
    };
    let tints: Option<Vec<LimitPatch>> = colors.as_ref().and_then(|c| {
        let flat: Vec<f32> = c.iter().flatten().copied().collect();
        let plain = Mesh { facevarying_width: 0, facevarying: Vec::new(), ..mesh.clone() };
        reyes_subdiv::varying_patches(&plain, 3, &flat).ok()?.pop()
    });
    let tints = tints.filter(|t| t.len() == limits.len());
    let shared_tint: Option<Arc<Vec<LimitPatch>>> = tints.map(Arc::new);
    limits
        .into_iter()
        .enumerate()
        .map(|(k, limit)| SubdivPatch {
            points: Limit::new(limit),
            tint: shared_tint.as_ref().map(|t| Limit::new(t[k].clone())),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cube of side 2 about the origin, faces wound counter-clockwise seen from outside.
    fn cube() -> Shape {
        use reyes_testkit::fixtures::{CUBE_QUADS, cube_corners};
        Shape::SubdivisionMesh {
            points: cube_corners(),
            faces: CUBE_QUADS.iter().map(|f| f.to_vec()).collect::<Vec<_>>().into(),
            tags: Vec::new(),
            colors: None,
            st: None,
        }
    }

    #[test]
    fn a_cube_has_24_patches_facing_out_and_lies_in_its_analytic_shell() {
        // The limit surface of the cube of half-side 1 touches the sphere of radius 68/81
        // at the face centres (the regular limit mask (16 F + 4 sum e + sum d) / 36 of the
        // once-subdivided face point) and that of sqrt(3)/2 at the corners (the valence-3 mask
        // (9 v + 4 sum e + sum f) / 24 = -(1, 1, 1) / 2): it lies between the two, so strictly
        // inside the cube's inscribed sphere (radius 1). The 1e-5 allows f32 rounding of
        // points of size 1.
        let patches = patches(&cube(), None);
        assert_eq!(patches.len(), 24);
        let (inner, outer) = (68.0_f32 / 81.0, 3.0_f32.sqrt() / 2.0);
        let (mut near, mut far) = (f32::INFINITY, 0.0_f32);
        for p in &patches {
            for j in 0..=8 {
                for i in 0..=8 {
                    let (u, v) = (i as f32 / 8.0, j as f32 / 8.0);
                    let q = p.position(u, v);
                    near = near.min(q.length());
                    far = far.max(q.length());
                    assert!(p.normal(u, v).dot(q) > 0.0, "normal faces in at {q}");
                }
            }
        }
        assert!(near >= inner - 1e-5 && far <= outer + 1e-5, "{near} .. {far}");
        assert!((near - inner).abs() < 1e-5 && (far - outer).abs() < 1e-5, "{near} .. {far}");
    }

    #[test]
    fn bezier_form_equals_the_limit_surface_inside_a_regular_patch() {
        // A 6x6 bumpy grid: the inner patches are regular.
        let n = 6u32;
        let points: Vec<[f32; 3]> = (0..=n)
            .flat_map(|j| {
                (0..=n).map(move |i| [i as f32, j as f32, ((i * 7 + j * 3) % 5) as f32 * 0.3])
            })
            .collect();
        let faces: Vec<Vec<u32>> = (0..n)
            .flat_map(|j| {
                (0..n).map(move |i| {
                    let c = |i: u32, j: u32| j * (n + 1) + i;
                    vec![c(i, j), c(i + 1, j), c(i + 1, j + 1), c(i, j + 1)]
                })
            })
            .collect();
        let shape = Shape::SubdivisionMesh {
            points,
            faces: faces.into(),
            tags: vec![],
            colors: None,
            st: None,
        };
        let mut regular = 0;
        for p in patches(&shape, None) {
            if p.points.bezier.is_none() {
                continue;
            }
            regular += 1;
            for (u, v) in [(0.25, 0.5), (0.5, 0.5), (0.9, 0.1)] {
                let (a, b) = (p.position(u, v), p.points.limit.eval(u, v).0);
                // Two f64 evaluations of one bicubic, each rounded to f32 (size 6).
                assert!((a - b).length() < 1e-5, "{a} vs {b}");
            }
            for &(u, v) in &[(0.0, 0.3), (1.0, 0.7), (0.4, 0.0), (0.6, 1.0)] {
                assert_eq!(p.position(u, v), p.points.limit.eval(u, v).0);
            }
        }
        assert!(regular > 0);
    }
}

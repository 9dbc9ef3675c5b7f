//! The control mesh of a [`Shape::SubdivisionMesh`] as `reyes_subdiv` takes it: the one
//! conversion the dicer and the ray engine both use, so that both see the same limit
//! patches in the same order.

use glam::{DVec3, Vec3};
use reyes_subdiv::{Mesh, Tag};

use crate::patches::{self, BezierPatch};
use crate::{Basis, PatchType, Shape, SubdivTag, Wrap};

/// The control mesh of a subdivision shape, each point `i` replaced by `moved(i, own)` (a
/// deformation key's point, or `own`, the shape's point, where the key has none); `None`
/// for other shapes. Facevarying data is the shape's `st` (width 2) when it has one.
pub fn control_mesh(shape: &Shape, moved: impl Fn(usize, Vec3) -> Vec3) -> Option<Mesh> {
    let Shape::SubdivisionMesh { points, faces, tags, st, .. } = shape else {
        return None;
    };
    let to_usize = |list: &[u32]| list.iter().map(|&i| i as usize).collect::<Vec<_>>();
    Some(Mesh {
        points: points.iter().enumerate().map(|(i, p)| moved(i, Vec3::from(*p))).collect(),
        face_counts: faces.iter().map(<[u32]>::len).collect(),
        faces: to_usize(faces.indices()),
        tags: tags
            .iter()
            .map(|t| match t {
                SubdivTag::InterpolateBoundary => Tag::InterpolateBoundary,
                SubdivTag::Crease { vertices, sharpness } => {
                    Tag::Crease { vertices: to_usize(vertices), sharpness: *sharpness }
                }
                SubdivTag::Corner { vertices, sharpness } => {
                    Tag::Corner { vertices: to_usize(vertices), sharpness: *sharpness }
                }
                SubdivTag::Hole { faces } => Tag::Hole { faces: to_usize(faces) },
            })
            .collect(),
        facevarying_width: if st.is_some() { 2 } else { 0 },
        facevarying: st.as_ref().map_or_else(Vec::new, |st| st.iter().flatten().copied().collect()),
    })
}

/// The 16 control points of a uniform bicubic B-spline patch (index `4 j + i`, `i` along u)
/// as the Bezier patch of the same surface over the same `(u, v)`.
pub fn bspline_to_bezier(g: &[Vec3; 16]) -> BezierPatch {
    let shape = Shape::PatchMesh {
        kind: PatchType::Bicubic,
        nu: 4,
        nv: 4,
        uwrap: Wrap::default(),
        vwrap: Wrap::default(),
        points: g.iter().map(|p| p.to_array()).collect(),
        ubasis: Basis::BSpline,
        ustep: None,
        vbasis: Basis::BSpline,
        vstep: None,
    };
    let positions: Vec<DVec3> = g.iter().map(|p| p.as_dvec3()).collect();
    patches::bezier_patches(&shape, Some(&positions))
        .pop()
        .unwrap_or_else(|| BezierPatch::new(1, 1, vec![DVec3::ZERO.extend(1.0); 4]))
}

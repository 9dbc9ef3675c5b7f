//! Patch-mesh and NURBS geometry, shared by validation, the dicer and the ray engine: the
//! RenderMan bases and steps, the sub-patch counts of `RiPatchMesh`, and every bicubic
//! sub-patch or NURBS span as a rational Bezier patch ([`BezierPatch`]).
//!
//! Invariants: sub-patches are listed row by row (v outer, u inner) in the order RenderMan
//! lays them out; a sub-patch's own `(u, v)` runs over `[0, 1]^2`; points are u-major
//! (`points[j * nu + i]`); arithmetic is in `f64`. A bicubic sub-patch in the Bezier basis
//! keeps its control points exactly; other bases are converted to Bezier form by
//! `B = Mb^-1 M G`, which changes the surface only by rounding. A NURBS span is extracted
//! by blossoming (de Boor's algorithm with a different parameter at each level), which is
//! exact for any knot multiplicities.

mod bezier;
mod nurbs;
pub mod trim;

pub use bezier::{BezierPatch, PatchEval};

use glam::{DVec3, DVec4};

use crate::model::{Basis, PatchType, Shape, Wrap};

/// Largest NURBS order the renderer accepts (degree 15).
pub const MAX_ORDER: u32 = 16;

impl Basis {
    /// The basis matrix `M[row][column]` of `P(u) = U M G`, `U = (u^3, u^2, u, 1)`.
    pub fn matrix(&self) -> [[f64; 4]; 4] {
        const SIXTH: f64 = 1.0 / 6.0;
        match self {
            Basis::Bezier => [
                [-1.0, 3.0, -3.0, 1.0],
                [3.0, -6.0, 3.0, 0.0],
                [-3.0, 3.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
            ],
            Basis::BSpline => [
                [-SIXTH, 0.5, -0.5, SIXTH],
                [0.5, -1.0, 0.5, 0.0],
                [-0.5, 0.0, 0.5, 0.0],
                [SIXTH, 4.0 * SIXTH, SIXTH, 0.0],
            ],
            Basis::CatmullRom => [
                [-0.5, 1.5, -1.5, 0.5],
                [1.0, -2.5, 2.0, -0.5],
                [-0.5, 0.0, 0.5, 0.0],
                [0.0, 1.0, 0.0, 0.0],
            ],
            Basis::Hermite => [
                [2.0, 1.0, -2.0, 1.0],
                [-3.0, -2.0, 3.0, -1.0],
                [0.0, 1.0, 0.0, 0.0],
                [1.0, 0.0, 0.0, 0.0],
            ],
            Basis::Power => [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
            Basis::Matrix(m) => m.map(|row| row.map(f64::from)),
        }
    }

    /// The standard step (`RiBezierStep` 3, `RiBSplineStep` 1, `RiCatmullRomStep` 1,
    /// `RiHermiteStep` 2, `RiPowerStep` 4); `None` for an explicit matrix.
    pub fn standard_step(&self) -> Option<u32> {
        match self {
            Basis::Bezier => Some(3),
            Basis::BSpline | Basis::CatmullRom => Some(1),
            Basis::Hermite => Some(2),
            Basis::Power => Some(4),
            Basis::Matrix(_) => None,
        }
    }

    /// `Mb^-1 M`: the matrix taking a geometry vector in this basis to the Bezier control
    /// points of the same cubic (the identity, exactly, for the Bezier basis).
    pub(crate) fn bezier_conversion(&self) -> [[f64; 4]; 4] {
        if *self == Basis::Bezier {
            return [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
                [0.0, 0.0, 0.0, 1.0],
            ];
        }
        // Bezier points of a u^3 + b u^2 + c u + d: d, d + c/3, d + 2c/3 + b/3, a + b + c + d.
        let third = 1.0 / 3.0;
        let inv_mb = [
            [0.0, 0.0, 0.0, 1.0],
            [0.0, 0.0, third, 1.0],
            [0.0, third, 2.0 * third, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        let m = self.matrix();
        let mut k = [[0.0; 4]; 4];
        for (r, row) in k.iter_mut().enumerate() {
            for (c, out) in row.iter_mut().enumerate() {
                *out = (0..4).map(|i| inv_mb[r][i] * m[i][c]).sum();
            }
        }
        k
    }
}

/// The step of one direction of a patch mesh: the given one, else the basis's standard
/// step; `None` for a matrix basis without a step.
pub fn step(basis: &Basis, given: Option<u32>) -> Option<u32> {
    given.or(basis.standard_step())
}

/// The number of sub-patches along one direction of `n` control points, RenderMan's rule:
/// bicubic `(n - 4) / step + 1` nonperiodic and `n / step` periodic, bilinear `n - 1`
/// nonperiodic and `n` periodic. `Err` says why the count is invalid (too few points, or
/// points that the step does not divide into whole sub-patches).
pub fn patch_count(kind: PatchType, n: u32, wrap: Wrap, step: u32) -> Result<u32, String> {
    match (kind, wrap) {
        (PatchType::Bilinear, Wrap::Nonperiodic) => {
            if n < 2 {
                return Err(format!(
                    "a nonperiodic bilinear mesh needs at least 2 points, got {n}"
                ));
            }
            Ok(n - 1)
        }
        (PatchType::Bilinear, Wrap::Periodic) => {
            if n < 2 {
                return Err(format!("a periodic bilinear mesh needs at least 2 points, got {n}"));
            }
            Ok(n)
        }
        (PatchType::Bicubic, _) if step == 0 => Err("the step must be >= 1, got 0".into()),
        (PatchType::Bicubic, Wrap::Nonperiodic) => {
            if n < 4 || !(n - 4).is_multiple_of(step) {
                return Err(format!(
                    "a nonperiodic bicubic mesh needs 4 + k * step points (step {step}), got {n}"
                ));
            }
            Ok((n - 4) / step + 1)
        }
        (PatchType::Bicubic, Wrap::Periodic) => {
            if n == 0 || !n.is_multiple_of(step) {
                return Err(format!(
                    "a periodic bicubic mesh needs a non-zero multiple of the step ({step}) \
                     points, got {n}"
                ));
            }
            Ok(n / step)
        }
    }
}

/// Index of control point `k` (0-based within the sub-patch) of sub-patch `p` along a
/// direction of `n` points.
fn wrap_index(p: u32, k: u32, step: u32, n: u32, wrap: Wrap) -> usize {
    let i = u64::from(p) * u64::from(step) + u64::from(k);
    (match wrap {
        Wrap::Periodic => i % u64::from(n.max(1)),
        Wrap::Nonperiodic => i,
    }) as usize
}

/// The sub-patch layout of a patch mesh: counts and steps in u and v, or `None` when the
/// shape is not a patch mesh or its counts are invalid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Sub-patches along u.
    pub nupatches: u32,
    /// Sub-patches along v.
    pub nvpatches: u32,
    /// Step along u (1 for bilinear meshes).
    pub ustep: u32,
    /// Step along v.
    pub vstep: u32,
}

/// The [`Layout`] of a (valid) patch mesh.
pub fn layout(shape: &Shape) -> Option<Layout> {
    let Shape::PatchMesh { kind, nu, nv, uwrap, vwrap, ubasis, ustep, vbasis, vstep, .. } = shape
    else {
        return None;
    };
    let (us, vs) = match kind {
        PatchType::Bilinear => (1, 1),
        PatchType::Bicubic => (step(ubasis, *ustep)?, step(vbasis, *vstep)?),
    };
    Some(Layout {
        nupatches: patch_count(*kind, *nu, *uwrap, us).ok()?,
        nvpatches: patch_count(*kind, *nv, *vwrap, vs).ok()?,
        ustep: us,
        vstep: vs,
    })
}

/// The corner indices (RenderMan order `(0,0), (1,0), (0,1), (1,1)`) of every sub-patch of
/// a valid bilinear patch mesh, row by row; empty for any other shape.
pub fn bilinear_corners(shape: &Shape) -> Vec<[u32; 4]> {
    let (Shape::PatchMesh { kind: PatchType::Bilinear, nu, nv, uwrap, vwrap, .. }, Some(l)) =
        (shape, layout(shape))
    else {
        return Vec::new();
    };
    let mut out = Vec::with_capacity((l.nupatches * l.nvpatches) as usize);
    for pv in 0..l.nvpatches {
        for pu in 0..l.nupatches {
            let at = |ku: u32, kv: u32| {
                let i = wrap_index(pu, ku, 1, *nu, *uwrap);
                let j = wrap_index(pv, kv, 1, *nv, *vwrap);
                (j * *nu as usize + i) as u32
            };
            out.push([at(0, 0), at(1, 0), at(0, 1), at(1, 1)]);
        }
    }
    out
}

/// Whether a shape is diced and traced as rational Bezier patches ([`bezier_patches`]):
/// bicubic patch meshes and NURBS.
pub fn is_bezier_shape(shape: &Shape) -> bool {
    matches!(shape, Shape::PatchMesh { kind: PatchType::Bicubic, .. } | Shape::NuPatch { .. })
}

/// The control points of a patch mesh or NURBS as positions (a NURBS point `(x, y, z, w)`
/// as `(x/w, y/w, z/w)`): what deformation keys replace. `None` for other shapes.
pub fn control_positions(shape: &Shape) -> Option<Vec<DVec3>> {
    match shape {
        Shape::PatchMesh { points, .. } => {
            Some(points.iter().map(|p| DVec3::from(p.map(f64::from))).collect())
        }
        Shape::NuPatch { points, .. } => Some(
            points
                .iter()
                .map(|p| DVec4::from(p.map(f64::from)))
                .map(|h| h.truncate() / h.w)
                .collect(),
        ),
        _ => None,
    }
}

/// The columns and rows of the grid [`bezier_patches`] lays out (sub-patches or knot
/// spans along u and along v), so that patch `k` is column `k % columns`, row
/// `k / columns`; `None` for other shapes.
pub fn bezier_grid(shape: &Shape) -> Option<(usize, usize)> {
    match shape {
        Shape::PatchMesh { kind: PatchType::Bicubic, .. } => {
            layout(shape).map(|l| (l.nupatches as usize, l.nvpatches as usize))
        }
        Shape::NuPatch { .. } => Some(nurbs::span_counts(shape)),
        _ => None,
    }
}

/// Every bicubic sub-patch (row by row) or NURBS span (v spans outer, u spans inner, empty
/// spans skipped) of a valid shape as a rational Bezier patch; empty for other shapes.
/// `positions`, when given, replaces the control positions (a deformation key: a NURBS
/// keeps its weights, `Pw = (w p, w)`); a missing position keeps the shape's own.
pub fn bezier_patches(shape: &Shape, positions: Option<&[DVec3]>) -> Vec<BezierPatch> {
    let moved = |i: usize, own: DVec3| positions.and_then(|p| p.get(i).copied()).unwrap_or(own);
    match shape {
        Shape::PatchMesh {
            kind: PatchType::Bicubic,
            nu,
            uwrap,
            vwrap,
            points,
            ubasis,
            vbasis,
            ..
        } => {
            let Some(l) = layout(shape) else { return Vec::new() };
            let point = |i: usize| {
                let own = points.get(i).map_or(DVec3::ZERO, |p| DVec3::from(p.map(f64::from)));
                moved(i, own)
            };
            let (ku, kv) = (ubasis.bezier_conversion(), vbasis.bezier_conversion());
            let (nu, nv) = (*nu, points.len() as u32 / (*nu).max(1));
            let mut out = Vec::with_capacity((l.nupatches * l.nvpatches) as usize);
            for pv in 0..l.nvpatches {
                for pu in 0..l.nupatches {
                    // g[b][a]: the point a along u, b along v.
                    let g: [[DVec3; 4]; 4] = std::array::from_fn(|b| {
                        std::array::from_fn(|a| {
                            let i = wrap_index(pu, a as u32, l.ustep, nu, *uwrap);
                            let j = wrap_index(pv, b as u32, l.vstep, nv, *vwrap);
                            point(j * nu as usize + i)
                        })
                    });
                    let mut net = Vec::with_capacity(16);
                    for kv_row in &kv {
                        for ku_row in &ku {
                            let mut p = DVec3::ZERO;
                            for (b, row) in g.iter().enumerate() {
                                for (a, q) in row.iter().enumerate() {
                                    let w = kv_row[b] * ku_row[a];
                                    if w != 0.0 {
                                        p += *q * w;
                                    }
                                }
                            }
                            net.push(p.extend(1.0));
                        }
                    }
                    out.push(BezierPatch::new(3, 3, net));
                }
            }
            out
        }
        Shape::NuPatch { .. } => nurbs::spans(shape, positions),
        _ => Vec::new(),
    }
}

//! Displacement and bump stage: a diced grid's vertices moved along their normals, and its
//! normals recomputed from the moved grid, before anything is shaded or projected.
//!
//! At shutter open every vertex `(i, j)` of an `nu x nv` grid gets `d = amount * (source -
//! center)` from the object's displacement ([`crate::lookdev::Field`]) and `b` likewise
//! from its bump, read at its surface parameters over the grid's parameter spacing (the
//! micropolygon's footprint) and at its undisplaced object-space point. The displaced vertex
//! is `P + d N` at every breakpoint of the motion, `P` and the unit object-space normal `N`
//! being the surface's at that breakpoint: the same displacement at every key, so a moving
//! displaced object keeps its shape. The shading normal is the normal of the grid `P + (d +
//! b) N` at shutter open, by central differences along the grid (one-sided at its edges),
//! turned to the side of the surface's own normal; where that grid is degenerate (a pole)
//! the surface's normal stays.
//!
//! Invariants: without displacement the positions are the surface's, bit for bit; the
//! displacement of a vertex depends on the vertex and its grid's spacing only; every cell
//! with a corner displaced further than its object's declared bound is counted.

use glam::Vec3;

use crate::lookdev::{At, Look};
use crate::motion::Pose;
use crate::split::Patch;

/// A grid's displaced positions and recomputed normals (object space).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Displaced {
    /// Vertices per breakpoint.
    count: usize,
    /// Positions at every breakpoint, `pos[b * count + c]`; empty when only bumped (the
    /// positions are the surface's).
    pos: Vec<Vec3>,
    /// Unit shading normals at shutter open.
    n: Vec<Vec3>,
    /// Cells with a corner displaced beyond the declared bound.
    pub escaped: u64,
}

impl Displaced {
    /// A displaced grid from its parts: `count` vertices per breakpoint, positions at every
    /// breakpoint, unit normals at shutter open, escaped cells.
    pub fn from_parts(count: usize, pos: Vec<Vec3>, n: Vec<Vec3>, escaped: u64) -> Displaced {
        Displaced { count, pos, n, escaped }
    }

    /// The displaced position of vertex `c` at breakpoint `b`, if the grid is displaced.
    #[inline]
    pub fn position(&self, b: usize, c: usize) -> Option<Vec3> {
        self.pos.get(b * self.count + c).copied()
    }

    /// The shading normal of vertex `c`.
    #[inline]
    pub fn normal(&self, c: usize) -> Vec3 {
        self.n[c]
    }
}

/// Displace (and bump) the `nu x nv` grid of `patch` in `poses` by `look`, or `None` if the
/// object has neither.
pub(crate) fn grid(
    look: &Look,
    poses: &[Pose<'_>],
    patch: &Patch,
    (nu, nv): (usize, usize),
) -> Option<Displaced> {
    let o = &look.object;
    if o.displace.is_none() && o.bump.is_none() {
        return None;
    }
    let open = poses.first()?;
    let row = nu + 1;
    let count = row * (nv + 1);
    let duv = [(patch.u[1] - patch.u[0]) / nu as f32, (patch.v[1] - patch.v[0]) / nv as f32];
    let mut base = Vec::with_capacity(count);
    let mut normal = Vec::with_capacity(count);
    let mut d = Vec::with_capacity(count);
    let mut bumped = Vec::with_capacity(count);
    for j in 0..=nv {
        let v = Patch::at(patch.v, j, nv);
        for i in 0..=nu {
            let u = Patch::at(patch.u, i, nu);
            let sp = open.surface.eval(u, v);
            let n = sp.n.normalize_or_zero();
            let (uv, duv) = open.surface.st(u, v, duv);
            let at = At { uv, duv, p_object: sp.p };
            let dv = o.displace.map_or(0.0, |f| f.eval(&look.system, &at));
            let bv = o.bump.map_or(0.0, |f| f.eval(&look.system, &at));
            base.push(sp.p);
            normal.push(n);
            d.push(dv);
            bumped.push(sp.p + (dv + bv) * n);
        }
    }
    let mut pos = Vec::new();
    if o.displace.is_some() {
        pos.reserve_exact(count * poses.len());
        for c in 0..count {
            pos.push(base[c] + d[c] * normal[c]);
        }
        for pose in &poses[1..] {
            for j in 0..=nv {
                let v = Patch::at(patch.v, j, nv);
                for i in 0..=nu {
                    let u = Patch::at(patch.u, i, nu);
                    let sp = pose.surface.eval(u, v);
                    pos.push(sp.p + d[j * row + i] * sp.n.normalize_or_zero());
                }
            }
        }
    }
    let n = (0..count)
        .map(|c| {
            let (i, j) = (c % row, c / row);
            let du = bumped[j * row + (i + 1).min(nu)] - bumped[j * row + i.saturating_sub(1)];
            let dv = bumped[(j + 1).min(nv) * row + i] - bumped[j.saturating_sub(1) * row + i];
            let g = du.cross(dv);
            // Degenerate where the grid collapses (a pole): keep the surface's normal.
            let scale = du.length() * dv.length();
            if !g.is_finite() || g.length() <= 1e-6 * scale {
                return normal[c];
            }
            let g = g.normalize();
            if g.dot(normal[c]) < 0.0 { -g } else { g }
        })
        .collect();
    let escaped = match o.declared {
        Some(bound) if o.displace.is_some() => {
            // A relative allowance for the float rounding of the bound's own arithmetic.
            let limit = bound * (1.0 + 1e-5) + 1e-30;
            let far = |i: usize, j: usize| d[j * row + i].abs() > limit;
            let mut cells = 0;
            for j in 0..nv {
                for i in 0..nu {
                    cells +=
                        u64::from(far(i, j) || far(i + 1, j) || far(i, j + 1) || far(i + 1, j + 1));
                }
            }
            cells
        }
        _ => 0,
    };
    Some(Displaced { count, pos, n, escaped })
}

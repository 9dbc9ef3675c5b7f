//! A grid shaded on the shading-language machine (stage: dice): the displacement shader
//! before the grid is projected, the surface and atmosphere shaders once its cells are
//! decided ([`crate::sl`]). Invariant: a failed run leaves the grid unshaded and records the
//! first error, which ends the render; nothing panics.

use glam::{Mat3, Vec3};

use super::Emitter;
use super::shading::Open;
use crate::aov::VertexAovs;
use crate::camera::CameraSetup;
use crate::displace::Displaced;
use crate::motion::Pose;
use crate::sl::{GridInput, SlSetup};
use crate::split::Patch;

/// A grid's parameters: `u`, `v` at every vertex and their steps.
fn parameters(patch: &Patch, (nu, nv): (usize, usize)) -> (Vec<f32>, Vec<f32>, f32, f32) {
    let count = (nu + 1) * (nv + 1);
    let u = (0..count).map(|c| Patch::at(patch.u, c % (nu + 1), nu)).collect();
    let v = (0..count).map(|c| Patch::at(patch.v, c / (nu + 1), nv)).collect();
    let du = (patch.u[1] - patch.u[0]) / nu as f32;
    let dv = (patch.v[1] - patch.v[0]) / nv as f32;
    (u, v, du, dv)
}

/// The `nu x nv` grid of `patch` as the machine reads it, its values owned: parameters and
/// texture coordinates (the surface's at shutter open, else `u`, `v`), and the positions,
/// normals and colours the caller gives ([`Inputs::input`] lends them).
struct Inputs {
    nu: usize,
    nv: usize,
    u: Vec<f32>,
    v: Vec<f32>,
    du: f32,
    dv: f32,
    s: Vec<f32>,
    t: Vec<f32>,
}

impl Inputs {
    fn new(patch: &Patch, (nu, nv): (usize, usize), open: &Pose<'_>) -> Inputs {
        let (u, v, du, dv) = parameters(patch, (nu, nv));
        let (s, t) = u
            .iter()
            .zip(&v)
            .map(|(&u, &v)| open.surface.st(u, v, [du, dv]).0)
            .map(|st| (st[0], st[1]))
            .unzip();
        Inputs { nu, nv, u, v, du, dv, s, t }
    }

    /// The machine's view of the grid with positions `p`, normals `n` (also the geometric
    /// ones), surface colour `cs`, vertex tint `tint` and opacity `os`.
    fn input<'a>(
        &'a self,
        p: &'a [Vec3],
        n: &'a [Vec3],
        (cs, tint): (&'a [Vec3], &'a [Vec3]),
        os: Vec3,
    ) -> GridInput<'a> {
        GridInput {
            nu: self.nu + 1,
            nv: self.nv + 1,
            p,
            n,
            ng: n,
            u: &self.u,
            v: &self.v,
            du: self.du,
            dv: self.dv,
            s: &self.s,
            t: &self.t,
            cs,
            tint,
            os,
        }
    }
}

impl Emitter<'_> {
    /// Run the displacement shader of `sl` over the `nu x nv` grid of `patch` at shutter
    /// open (`poses[0]`): the grid displaced by the same object-space offsets at every
    /// breakpoint, with its shading normals; `None` without a displacement shader or on an
    /// error (recorded).
    pub(super) fn sl_displace(
        &mut self,
        sl: &SlSetup,
        poses: &[Pose<'_>],
        patch: &Patch,
        (nu, nv): (usize, usize),
    ) -> Option<Displaced> {
        self.sl_displaced.clear();
        sl.shaders.displacement.as_ref()?;
        let open = poses.first()?;
        let o2c = *open.moment.object_to_camera()?;
        let c2o = o2c.inverse();
        let normal_to_camera = Mat3::from_mat4(o2c).inverse().transpose();
        let inputs = Inputs::new(patch, (nu, nv), open);
        let (u, v) = (&inputs.u, &inputs.v);
        let points: Vec<_> = u.iter().zip(v).map(|(&u, &v)| open.surface.eval(u, v)).collect();
        let p: Vec<Vec3> = points.iter().map(|sp| o2c.transform_point3(sp.p)).collect();
        let n: Vec<Vec3> =
            points.iter().map(|sp| (normal_to_camera * sp.n).normalize_or_zero()).collect();
        let cs: Vec<Vec3> = points.iter().map(|sp| sp.tint).collect();
        let grid = inputs.input(&p, &n, (&cs, &cs), Vec3::ONE);
        let (moved, normals) = match sl.displace(&grid, &mut self.sl_counts, &mut self.sl_displaced)
        {
            Ok(Some(r)) => r,
            Ok(None) => return None,
            Err(e) => {
                self.sl_error.get_or_insert(e);
                return None;
            }
        };
        let offsets: Vec<Vec3> =
            moved.iter().zip(&points).map(|(q, sp)| c2o.transform_point3(*q) - sp.p).collect();
        let to_object = Mat3::from_mat4(o2c).transpose();
        let normals: Vec<Vec3> = normals
            .iter()
            .zip(&points)
            .map(|(n, sp)| (to_object * *n).try_normalize().unwrap_or(sp.n))
            .collect();
        let count = offsets.len();
        let mut pos = Vec::with_capacity(count * poses.len());
        for (b, pose) in poses.iter().enumerate() {
            for c in 0..count {
                let base = if b == 0 { points[c].p } else { pose.surface.position(u[c], v[c]) };
                pos.push(base + offsets[c]);
            }
        }
        // Cells with a corner moved further than the declared bound.
        let limit = sl.shaders.displacement_bound * (1.0 + 1e-5) + 1e-30;
        let far = |i: usize, j: usize| offsets[j * (nu + 1) + i].length() > limit;
        let mut escaped = 0;
        for j in 0..nv {
            for i in 0..nu {
                escaped +=
                    u64::from(far(i, j) || far(i + 1, j) || far(i, j + 1) || far(i + 1, j + 1));
            }
        }
        Some(Displaced::from_parts(count, pos, normals, escaped))
    }

    /// Shade the whole grid with the surface (and atmosphere) shaders of `sl`, at shutter
    /// open (`open`); `opens` holds each vertex's surface point. With `aovs`, the shaders'
    /// output variables the scene writes go to the grid's AOV values.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sl_shade(
        &mut self,
        sl: &SlSetup,
        camera: &CameraSetup,
        material: (Vec3, Vec3),
        open: &Pose<'_>,
        patch: &Patch,
        (nu, nv): (usize, usize),
        opens: &[Open],
        aovs: Option<&VertexAovs>,
    ) {
        let w2c = Mat3::from_mat4(camera.world_to_camera());
        let inputs = Inputs::new(patch, (nu, nv), open);
        let p: Vec<Vec3> = opens.iter().map(|o| o.p_shaded).collect();
        let n: Vec<Vec3> = opens.iter().map(|o| (w2c * o.n_world).normalize_or_zero()).collect();
        let tint: Vec<Vec3> = opens.iter().map(|o| o.tint).collect();
        let cs: Vec<Vec3> = tint.iter().map(|&t| material.0 * t).collect();
        let grid = inputs.input(&p, &n, (&cs, &tint), material.1);
        let outputs = aovs.map_or(&[][..], |a| &a.outputs[..]);
        let displaced = std::mem::take(&mut self.sl_displaced);
        match sl.shade(&grid, &mut self.sl_counts, outputs, &displaced) {
            Ok(((color, trans), values)) => {
                self.grid.color = color;
                self.grid.trans = trans;
                self.shaded += opens.len() as u64;
                if let Some(a) = aovs {
                    // Each output variable at its offset of every vertex's AOV values.
                    let stride = self.grid.aov_stride;
                    self.grid.aov.resize(opens.len() * stride, 0.0);
                    for ((name, w), v) in a.outputs.iter().zip(&values) {
                        let Some((at, _)) = a.output(name) else { continue };
                        for (k, lane) in v.chunks_exact(*w).enumerate() {
                            self.grid.aov[k * stride + at..k * stride + at + w]
                                .copy_from_slice(lane);
                        }
                    }
                }
            }
            Err(e) => {
                self.sl_error.get_or_insert(e);
            }
        }
    }
}

//! Shading a diced grid (stage: dice, third pass): once its cells are decided, the vertices
//! that some kept micropolygon uses (its four corners) are shaded at shutter open under the
//! object's shader or vertex-shader hook, with look development, emission and AOVs; the
//! others are left at zero colour, transmittance and AOVs, which nothing reads (cull before
//! shading, as PRMan and Pixie do). Invariant: a vertex's shading depends only on its own
//! inputs, so the kept micropolygons are the same bit for bit whether or not every vertex is
//! shaded.

use glam::Vec3;

use super::{Emitter, Hook, ObjectContext};
use crate::camera::CameraSetup;
use crate::hook::VertexContext;
use crate::lookdev::{At, Looked};
use crate::motion::Pose;
use crate::split::Patch;

/// What shading a vertex at shutter open needs, kept from its evaluation in
/// [`Emitter::dice`] until its grid's cells are decided.
#[derive(Debug, Clone, Copy)]
pub(super) struct Open {
    /// Object-space position as evaluated, before displacement: where texture maps are
    /// looked up.
    pub(super) p_lookup: Vec3,
    /// Object-space position, displaced.
    pub(super) p_object: Vec3,
    /// Colour multiplying the material colour (mesh vertex colours; white otherwise).
    pub(super) tint: Vec3,
    /// Opacity multiplying the shaded opacity (curves', points' and blobbies' `Os`).
    pub(super) opacity: Vec3,
    /// World-space position (displaced) and its camera-space one: the surface point, not
    /// the crack-free corner on a side's polyline.
    pub(super) p_world: Vec3,
    pub(super) p_shaded: Vec3,
    /// World-space normal (displaced; not normalised).
    pub(super) n_world: Vec3,
}

impl Emitter<'_> {
    /// Shade, at shutter open (`open`, the first pose), the vertices of the grid that its
    /// kept micropolygons use (every vertex under [`Emitter::shade_all`]): colour and
    /// transmittance (premultiplied, with the object's emission), and the AOVs. `opens` holds
    /// each vertex's surface point, from [`Emitter::dice`].
    // Once per grid, and out of line, so that profiles show shading apart from dicing.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn shade(
        &mut self,
        camera: &CameraSetup,
        object: &ObjectContext<'_>,
        hook: Option<Hook<'_>>,
        open: &Pose<'_>,
        patch: &Patch,
        (nu, nv): (usize, usize),
        opens: &[Open],
    ) {
        if let Some(sl) = &object.sl {
            let material = (object.shader.color(), object.shader.opacity());
            let layout = object.aov.as_ref().map(|(a, _)| &**a);
            self.sl_shade(sl, camera, material, open, patch, (nu, nv), opens, layout);
            // AOVs: the geometric ones as the native path writes them, the output variables
            // as the shaders leave them; the shading components are 0.
            let stride = self.grid.aov_stride;
            self.grid.aov.resize(opens.len() * stride, 0.0);
            if let Some((_, ids)) = &object.aov {
                let w2c = camera.world_to_camera();
                for (vertex, o) in opens.iter().enumerate() {
                    let (i, j) = (vertex % (nu + 1), vertex / (nu + 1));
                    let (u, v) = (Patch::at(patch.u, i, nu), Patch::at(patch.v, j, nv));
                    let n = w2c.transform_vector3(o.n_world).normalize_or_zero();
                    let a = &mut self.grid.aov[vertex * stride..(vertex + 1) * stride];
                    let head = [n.x, n.y, n.z, o.p_shaded.x, o.p_shaded.y, o.p_shaded.z];
                    let values = head.into_iter().chain([u, v, ids[0], ids[1]]);
                    for (slot, value) in a.iter_mut().zip(values) {
                        *slot = value;
                    }
                }
            }
            return;
        }
        let count = opens.len();
        let mut used = vec![self.shade_all; count];
        if !self.shade_all {
            for k in &self.grid.kept {
                for c in self.grid.corners(k.cell) {
                    used[c] = true;
                }
            }
        }
        let world_to_camera = camera.world_to_camera();
        let duv = [(patch.u[1] - patch.u[0]) / nu as f32, (patch.v[1] - patch.v[0]) / nv as f32];
        let g = &mut self.grid;
        let stride = g.aov_stride;
        g.aov.reserve_exact(count * stride);
        g.aov.resize(count * stride, 0.0);
        let mut values = Vec::with_capacity(stride);
        let mut shaded = 0;
        for (vertex, o) in opens.iter().enumerate() {
            if !used[vertex] {
                continue;
            }
            shaded += 1;
            let (i, j) = (vertex % (nu + 1), vertex / (nu + 1));
            let (u, v) = (Patch::at(patch.u, i, nu), Patch::at(patch.v, j, nv));
            let looked = object.look.as_ref().map_or(Looked::NONE, |l| {
                let (uv, duv) = open.surface.st(u, v, duv);
                l.object.looked(&l.system, &At { uv, duv, p_object: o.p_lookup })
            });
            // The shader face-forwards the normal toward the eye (two-sided), which is what
            // CSG needs: where a difference A - B shows B's surface through a hole in A, the
            // eye sees B from B's inside, i.e. the outside of the result, whose outward
            // normal there is B's inward one. The geometric (outward) normal itself is not
            // stored: the orientation survives only in the vertex winding.
            let (color, trans) = match &hook {
                None => object.shader.shade_looked(o.p_world, o.n_world, o.tint, &looked),
                Some(hook) => hook.shader.shade(&VertexContext {
                    object: hook.object,
                    surface: hook.surface,
                    patch_u: patch.u,
                    patch_v: patch.v,
                    i: i as u32,
                    j: j as u32,
                    nu: nu as u32,
                    nv: nv as u32,
                    p_world: o.p_world,
                    n_world: o.n_world.normalize_or_zero(),
                    p_object: o.p_object,
                    tint: o.tint * looked.color,
                    looked,
                }),
            };
            let (mut color, mut trans) = (color, trans);
            if o.opacity != Vec3::ONE {
                // A primitive's own opacity (`Os`): the colour is premultiplied, so it
                // scales with the opacity, and what shows through grows.
                for a in 0..3 {
                    color[a] *= o.opacity[a];
                    trans[a] = 1.0 - (1.0 - trans[a]) * o.opacity[a];
                }
            }
            if let Some(e) = object.look.as_ref().and_then(|l| l.object.emission) {
                // Emission, premultiplied by the opacity (1 - trans).
                for a in 0..3 {
                    color[a] += e[a] * (1.0 - trans[a]);
                }
            }
            g.color[vertex] = color;
            g.trans[vertex] = trans;
            if let Some((layout, ids)) = &object.aov {
                values.clear();
                let n_camera = world_to_camera.transform_vector3(o.n_world).normalize_or_zero();
                values.extend_from_slice(&n_camera.to_array());
                values.extend_from_slice(&o.p_shaded.to_array());
                values.extend_from_slice(&[u, v, ids[0], ids[1]]);
                for group in &layout.groups {
                    // Local illumination's terms; the ray-traced shader's are not split (the
                    // render refuses component AOVs with it).
                    let terms = match &hook {
                        None => object.shader.components_looked(
                            o.p_world,
                            o.n_world,
                            o.tint,
                            group.as_deref(),
                            &looked,
                        ),
                        Some(_) => [glam::Vec3::ZERO; 3],
                    };
                    for t in terms {
                        values.extend_from_slice(&t.to_array());
                    }
                }
                // No shader, so no output variables: 0.
                values.resize(stride, 0.0);
                g.aov[vertex * stride..(vertex + 1) * stride].copy_from_slice(&values);
            }
        }
        self.shaded += shaded;
    }
}

#[cfg(test)]
mod tests {
    use crate::lazy::Dicer;
    use crate::{DiceOptions, DiceStats};

    /// A scene file of `scenes/`, 120 pixels across.
    fn scene_file(name: &str) -> reyes_scene::Scene {
        let root = reyes_testkit::golden::workspace_root();
        let mut scene = reyes_scene::load(&root.join(format!("scenes/{name}.ron"))).unwrap();
        let (w, h) = (scene.image.width, scene.image.height);
        scene.image.width = 120;
        scene.image.height = (120 * h / w).max(1);
        scene
    }

    fn dice(scene: &reyes_scene::Scene, all: bool) -> (Vec<crate::lazy::NewGrid>, DiceStats) {
        let frame = reyes_testkit::fixtures::frame_for(scene);
        let options = DiceOptions { shade_every_vertex: all, ..Default::default() };
        let (wave, _, _) = Dicer::new_eager(scene, &frame, &options).unwrap().dice_all();
        (wave.grids, wave.stats)
    }

    /// Every vertex a kept micropolygon uses is shaded and no other: the others keep zero
    /// colour, transmittance and AOVs, and the count is theirs. Shading every vertex instead
    /// gives every kept micropolygon and its AOVs bit for bit.
    #[test]
    fn only_the_corners_of_kept_cells_are_shaded() {
        // Back faces and off-screen cells (spheres), motion (cells kept over part of the
        // shutter), AOVs, displacement and texture maps.
        for name in ["spheres", "motion-blur", "aovs", "lookdev"] {
            let scene = scene_file(name);
            let (grids, stats) = dice(&scene, false);
            let (all_grids, all_stats) = dice(&scene, true);
            let mut shaded = 0u64;
            let mut unused = 0u64;
            for g in grids.iter().map(|g| &g.grid) {
                let st = g.aov_stride;
                let mut used = vec![false; g.count as usize];
                for k in &g.kept {
                    for c in g.corners(k.cell) {
                        used[c] = true;
                    }
                }
                for (c, &u) in used.iter().enumerate() {
                    if u {
                        shaded += 1;
                    } else {
                        unused += 1;
                        assert_eq!((g.color[c], g.trans[c]), ([0.0; 3], [0.0; 3]), "{name}");
                        assert!(g.aov[c * st..(c + 1) * st].iter().all(|&a| a == 0.0), "{name}");
                    }
                }
            }
            assert_eq!(stats.shaded, shaded, "{name}");
            assert!(stats.shaded < stats.vertices, "{name}: every vertex used");
            assert!(unused > 0, "{name}");
            assert_eq!(all_stats.shaded, all_stats.vertices, "{name}");
            assert_eq!(DiceStats { shaded: 0, ..stats }, DiceStats { shaded: 0, ..all_stats });
            assert_eq!(grids.len(), all_grids.len(), "{name}");
            let (mut a, mut b) = (Vec::new(), Vec::new());
            for (g, h) in grids.iter().zip(&all_grids) {
                assert_eq!(g.key, h.key, "{name}");
                assert_eq!(g.grid.len(), h.grid.len(), "{name}");
                for k in 0..g.grid.len() {
                    let (p, q) = (g.grid.micropolygon(k), h.grid.micropolygon(k));
                    assert_eq!(bytemuck::bytes_of(&p), bytemuck::bytes_of(&q), "{name}");
                    a.clear();
                    b.clear();
                    g.grid.micropolygon_aovs(k, &mut a);
                    h.grid.micropolygon_aovs(k, &mut b);
                    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&a), bits(&b), "{name}");
                }
            }
        }
    }
}

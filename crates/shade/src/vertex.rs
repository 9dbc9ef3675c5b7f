//! Ray-traced vertex shading in the REYES pipeline: a [`VertexShader`] over
//! [`Shading::shade_surface`], so that grids diced for the stochastic hider get soft shadows,
//! glossy reflection and translucency.
//!
//! Each vertex draws its own secondary-ray choices, stratified across its neighbours: the
//! vertices of a 4 x 4 tile of the grid (`(i/4, j/4)`) form one set of `16 R` members
//! (`R = raytrace.vertex_rays`), vertex `(i, j)` owning members
//! `((i%4) + 4 (j%4)) R + r` for `r` in `0..R`, and its colour is the mean of its `R`
//! results. Neighbouring vertices thus sample different parts of an area light or a glossy
//! lobe, and the micropolygons' interpolation averages them, as the pixel filter averages a
//! pixel's samples in the ray-tracing hider.
//!
//! The dicer shades once, at shutter open (REYES shades before motion): the point is seen
//! from the camera eye at shutter open (an orthographic camera sees it along its view
//! direction: [`Viewer::seen_from`], as the dicer's own shading). A vertex of a still object (no `motion`, `roll` or
//! `deform`) is where it is at every time, so its secondary rays sample the shutter: each
//! ray's time is one more stratified dimension of its set, warped by the shutter's shape
//! like the hider's sample times. The shadow of a moving ball on a still table is then
//! blurred along the ball's path, as the ray-tracing hider draws it. A vertex of a moving
//! object traces at time 0, the time its position belongs to: tracing it at another time
//! would let it shadow or reflect itself from where it is not.
//!
//! Invariant (determinism): the set of a vertex hashes the object, the surface, the exact
//! bits of the grid's parameter rectangle and the tile, so it depends only on the vertex,
//! never on the order in which grids are diced or on threads.

use std::sync::atomic::{AtomicU64, Ordering};

use reyes_dice::{CameraSetup, VertexContext, VertexShader, Viewer};
use reyes_sampling::{ShutterShape, Strata, hash};
use reyes_scene::Scene;

use crate::{RayCounts, Shading, SurfacePoint};

/// Key of the per-tile stratified sets ("vtile").
const TILE_SET: u64 = 0x0076_7469_6c65;

/// Side of the square tile of grid vertices forming one stratified set.
const TILE: u32 = 4;

/// Shades grid vertices with the distributed rays of [`Shading::shade_surface`].
pub struct RayVertexShader<'a> {
    shading: &'a Shading<'a>,
    /// The camera at shutter open, as a viewer.
    viewer: Viewer,
    seed: u64,
    /// Rays per effect per vertex (>= 1).
    rays: u32,
    /// Per object: still over the shutter, so its rays may sample time.
    still: Vec<bool>,
    /// The shutter's time density (None: closed shutter, everything at time 0).
    shutter: Option<ShutterShape>,
    /// Vertices shaded, then shadow, reflection, refraction and continuation rays traced
    /// (sums, so the same whatever the order of dicing).
    counts: [AtomicU64; 5],
}

impl<'a> RayVertexShader<'a> {
    /// The vertex shader of `scene` over `shading`, whose shutter has the time density
    /// `shutter`.
    pub fn new(
        scene: &Scene,
        shading: &'a Shading<'a>,
        shutter: ShutterShape,
    ) -> RayVertexShader<'a> {
        RayVertexShader {
            shading,
            viewer: CameraSetup::new(scene).viewer(),
            seed: scene.hider.seed,
            rays: scene.raytrace.vertex_rays.max(1),
            still: scene
                .objects
                .iter()
                .map(|o| o.motion.is_empty() && o.deform.is_empty())
                .collect(),
            shutter: (scene.camera.shutter.close > scene.camera.shutter.open).then_some(shutter),
            counts: Default::default(),
        }
    }

    /// The stratified set of the vertex's tile, and the first of its `rays` members.
    fn set_of(&self, v: &VertexContext) -> (u64, u32) {
        let bits = |r: [f32; 2]| u64::from(r[0].to_bits()) | (u64::from(r[1].to_bits()) << 32);
        let set = hash(
            self.seed,
            &[
                TILE_SET,
                v.object as u64,
                v.surface as u64,
                bits(v.patch_u),
                bits(v.patch_v),
                u64::from(v.i / TILE),
                u64::from(v.j / TILE),
            ],
        );
        (set, ((v.i % TILE) + TILE * (v.j % TILE)) * self.rays)
    }
}

impl VertexShader for RayVertexShader<'_> {
    fn shade(&self, v: &VertexContext) -> ([f32; 3], [f32; 3]) {
        let mut at = SurfacePoint {
            object: v.object as u32,
            p_world: v.p_world,
            n_world: v.n_world,
            p_object: v.p_object,
            tint: v.tint,
            from: self.viewer.seen_from(v.p_world),
            time: 0.0,
            looked: v.looked,
        };
        let (set, first) = self.set_of(v);
        let count = TILE * TILE * self.rays;
        let mut color = [0.0f32; 3];
        let mut trans = [0.0f32; 3];
        let mut rays = RayCounts::default();
        let shutter = self.shutter.filter(|_| self.still.get(v.object).copied().unwrap_or(false));
        for r in 0..self.rays {
            let mut strata = Strata::new(self.seed, set, first + r, count);
            if let Some(shape) = shutter {
                at.time = shape.warp(strata.next_1d());
            }
            let (c, t) = self.shading.shade_surface_counted(&at, &mut strata, &mut rays);
            for a in 0..3 {
                color[a] += c[a];
                trans[a] += t[a];
            }
        }
        let counts = [1, rays.shadow, rays.reflection, rays.refraction, rays.continuation];
        for (total, n) in self.counts.iter().zip(counts) {
            total.fetch_add(n, Ordering::Relaxed);
        }
        let w = 1.0 / self.rays as f32;
        (color.map(|c| c * w), trans.map(|t| t * w))
    }
}

impl RayVertexShader<'_> {
    /// Rays per effect per vertex (`raytrace.vertex_rays`, at least 1).
    pub fn rays(&self) -> u32 {
        self.rays
    }

    /// The vertices shaded so far, and the secondary rays they traced.
    pub fn counts(&self) -> (u64, RayCounts) {
        let c = |k: usize| self.counts[k].load(Ordering::Relaxed);
        let rays =
            RayCounts { shadow: c(1), reflection: c(2), refraction: c(3), continuation: c(4) };
        (c(0), rays)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use reyes_trace::Tracer;

    fn context(i: u32, j: u32) -> VertexContext {
        VertexContext {
            object: 2,
            surface: 1,
            patch_u: [0.25, 0.5],
            patch_v: [0.0, 0.125],
            i,
            j,
            nu: 16,
            nv: 16,
            p_world: Vec3::ZERO,
            n_world: Vec3::Z,
            p_object: Vec3::ZERO,
            tint: Vec3::ONE,
            looked: reyes_dice::Looked::NONE,
        }
    }

    #[test]
    fn a_tile_shares_one_set_and_its_vertices_take_distinct_members() {
        let scene = reyes_scene::parse(
            "Scene(image: (width: 8, height: 8), camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, 1.0)),
                   raytrace: (vertex_rays: 3))",
            std::path::Path::new("t.ron"),
        )
        .unwrap();
        let tracer = Tracer::new(&scene);
        let shading = Shading::new(&scene, &tracer);
        let shader = RayVertexShader::new(&scene, &shading, ShutterShape::Uniform);
        let (set, _) = shader.set_of(&context(4, 8));
        let mut members = Vec::new();
        for j in 8..12 {
            for i in 4..8 {
                let (s, first) = shader.set_of(&context(i, j));
                assert_eq!(s, set, "vertex ({i}, {j}) is in tile (1, 2)");
                members.extend(first..first + 3);
            }
        }
        members.sort_unstable();
        assert_eq!(members, (0..48).collect::<Vec<_>>(), "16 vertices x 3 rays: every member once");
        // Neighbouring tiles, other grids and other surfaces get other sets.
        assert_ne!(shader.set_of(&context(3, 8)).0, set);
        assert_ne!(shader.set_of(&context(4, 12)).0, set);
        let mut other = context(4, 8);
        other.patch_u = [0.5, 0.75];
        assert_ne!(shader.set_of(&other).0, set);
        other = context(4, 8);
        other.surface = 0;
        assert_ne!(shader.set_of(&other).0, set);
    }
}

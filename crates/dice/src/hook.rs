//! A seam for shading grid vertices outside the dicer: the ray-traced shading of the
//! distributed effects (shadows, glossy reflection, translucency) lives in a crate that
//! depends on the ray engine, which itself depends on this crate.
//!
//! Invariant: everything in a [`VertexContext`] depends only on the scene and the vertex,
//! never on the order in which grids are diced, so a shader that draws its pseudo-random
//! choices from it is deterministic.

use glam::Vec3;

use crate::lookdev::{Lookdev, Looked};

/// One grid vertex to shade, at shutter open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexContext {
    /// Index of the object in `Scene::objects`.
    pub object: usize,
    /// Index of the surface within the object, in the dicer's order.
    pub surface: usize,
    /// The grid's rectangle of the surface's parameter space: `[u0, u1]`.
    pub patch_u: [f32; 2],
    /// `[v0, v1]`.
    pub patch_v: [f32; 2],
    /// Vertex column, `0..=nu`.
    pub i: u32,
    /// Vertex row, `0..=nv`.
    pub j: u32,
    /// Grid cells across.
    pub nu: u32,
    /// Grid cells down.
    pub nv: u32,
    /// Position in world space.
    pub p_world: Vec3,
    /// Unit outward normal in world space (not face-forwarded).
    pub n_world: Vec3,
    /// Position in object space (before the object's transform).
    pub p_object: Vec3,
    /// Colour multiplying the material colour: mesh vertex colours (white otherwise) times
    /// the colour map's value.
    pub tint: Vec3,
    /// What the object's texture maps make of its material here (the colour map is in
    /// `tint` already).
    pub looked: Looked,
}

/// Shades grid vertices in place of the dicer's own local illumination.
pub trait VertexShader: Sync {
    /// Premultiplied colour `Os * Ci` and transmittance `1 - Os` of one vertex.
    fn shade(&self, vertex: &VertexContext) -> ([f32; 3], [f32; 3]);
}

/// Options of [`crate::dice_scene_with`].
#[derive(Clone, Copy, Default)]
pub struct DiceOptions<'a> {
    /// Shades every vertex instead of the dicer's local illumination when given.
    pub vertex_shader: Option<&'a dyn VertexShader>,
    /// The most micropolygons the lazy dicer may hold at once (the memory budget's share for
    /// grids); `None`: no limit. Exceeding it is [`crate::DiceError::MicropolygonBudget`].
    pub max_micropolygons: Option<u64>,
    /// The scene's textures and look development, loaded once for the render
    /// ([`Lookdev::load`]); `None`: the dicer loads its own when the scene has any.
    pub lookdev: Option<&'a Lookdev>,
    /// Shade every grid vertex, also those no kept micropolygon uses (which nothing reads).
    /// The image is the same either way; for tests and measurements of culling before
    /// shading.
    pub shade_every_vertex: bool,
    /// The instruction budget of a shading-language shader on one grid; `None`:
    /// `reyes_scene::sl::exec::DEFAULT_BUDGET`.
    pub shader_budget: Option<u64>,
}

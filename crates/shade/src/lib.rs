//! reyes-shade: the distributed ray tracing of patent FIGS. 19-22 and Appendix B, shared by
//! both hiders: lights with extent and their soft shadows, glossy reflection, blurry
//! translucency, recursion limits, and procedural patterns.
//!
//! [`Shading::shade_surface`] shades one point (the stochastic hider's grid vertices);
//! [`Shading::trace`] follows one ray through the scene (the ray-tracing hider's primary
//! rays, and every secondary ray). Every pseudo-random choice comes from a [`Strata`]
//! stream, one stratified dimension per effect and bounce.
#![deny(missing_docs)]

mod strata;

pub use strata::{Strata, permute};

use glam::Vec3;
use reyes_scene::Scene;
use reyes_trace::{Ray, Tracer};

/// What a ray sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced {
    /// Premultiplied colour and alpha composited front to back along the ray (zeros when it
    /// hits nothing).
    pub rgba: [f32; 4],
    /// Ray parameter of the opaque surface that ended the composite, or `f32::INFINITY`.
    pub t: f32,
}

/// A surface point to shade, as the stochastic hider's dicer sees a grid vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Index of the object in `Scene::objects`.
    pub object: u32,
    /// Position in world space.
    pub p_world: Vec3,
    /// Unit outward normal in world space (not face-forwarded).
    pub n_world: Vec3,
    /// Position in object space (patterns are evaluated here, so they move with the object).
    pub p_object: Vec3,
    /// Colour multiplying the material colour (mesh vertex colours).
    pub tint: Vec3,
    /// Where the point is seen from (the eye, or a ray's origin).
    pub from: Vec3,
    /// Time normalised over the shutter, for shadow and secondary rays.
    pub time: f32,
}

/// The shading of a scene against its ray engine.
pub struct Shading<'a> {
    #[allow(dead_code)]
    scene: &'a Scene,
    #[allow(dead_code)]
    tracer: &'a Tracer,
}

impl<'a> Shading<'a> {
    /// Set up the shading of `scene`, tracing rays against `tracer` (built from the same scene).
    pub fn new(scene: &'a Scene, tracer: &'a Tracer) -> Shading<'a> {
        Shading { scene, tracer }
    }

    /// Whether shading `scene` needs anything beyond the dicer's local illumination: a
    /// shadowing or area light, a reflecting or refracting object, or a pattern.
    pub fn needed(scene: &Scene) -> bool {
        let _ = scene;
        unimplemented!("reyes-shade: in progress")
    }

    /// Premultiplied colour `Os * Ci` and transmittance `1 - Os` at a surface point, with
    /// shadow, reflection and refraction rays drawn from `strata`.
    pub fn shade_surface(&self, at: &SurfacePoint, strata: &mut Strata) -> ([f32; 3], [f32; 3]) {
        let _ = (at, strata);
        unimplemented!("reyes-shade: in progress")
    }

    /// Follow `ray` (time normalised over the shutter) through the scene up to ray
    /// parameter `t_max`: composite the surfaces it meets front to back, shading each with
    /// the distributed rays.
    pub fn trace(&self, ray: &Ray, t_max: f32, strata: &mut Strata) -> Traced {
        let _ = (ray, t_max, strata);
        unimplemented!("reyes-shade: in progress")
    }
}

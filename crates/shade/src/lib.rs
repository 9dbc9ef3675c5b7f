//! reyes-shade: the distributed ray tracing of patent FIGS. 19-22 and Appendix B, shared by
//! both hiders: lights with extent and their soft shadows, glossy reflection, blurry
//! translucency, recursion limits, and procedural patterns.
//!
//! [`Shading::shade_surface`] shades one point (the stochastic hider's grid vertices);
//! [`Shading::trace`] follows one ray through the scene (the ray-tracing hider's primary
//! rays, and every secondary ray). Every pseudo-random choice comes from a [`Strata`]
//! stream, one stratified dimension per effect and bounce.
//!
//! # Shading a point
//!
//! * **Local illumination** is the dicer's ([`reyes_dice::Shader::illuminate`]): Constant,
//!   Matte, Plastic and Metal, two-sided (the normal is face-forwarded toward the viewer), so
//!   a scene without shadows, area lights, reflection, refraction or patterns shades exactly
//!   (bit for bit) as the dicer does.
//! * **Colour** `Cs` is the material colour, or the object's pattern ([`pool_ball`]) in its
//!   place, times the mesh vertex colour interpolated at the point (the dicer's tint).
//! * **Lights.** An object with a light set (`Object::lights`) is lit by those lights only,
//!   as in the dicer; every area light still takes its dimension (below). Ambient lights as
//!   in the dicer. Distant, point and spot lights as in the dicer (a spot light's cone and
//!   fall-off are [`reyes_dice::SpotLight`]'s), times the visibility of one shadow ray when
//!   `shadows` is on (hard shadows). Each area
//!   light gives one point per shading call, drawn from the stream's next dimension (see
//!   `lights.rs` for the shapes), contributing `intensity(t) color |cos at the light| / d^2`
//!   times the visibility of the shadow ray to it; the time `t` is the shading time, and the
//!   light's motion keys are normalised over the shutter as the tracer normalises objects'.
//!   Shadow rays are only traced to lights above the face-forwarded surface.
//! * **Shadow rays** see every object, matte ones included, except that a shadow ray toward an
//!   area light passes through the objects linked to that light (`Object::area_light`: the
//!   light's own visible surface, which would otherwise hide it). An opaque surface blocks; a
//!   surface with opacity `Os < 1` in some channel attenuates the light by `1 - Os` per
//!   channel, and the ray goes on behind it (so a pane of tinted, partly transparent
//!   material casts a tinted shadow); a refracting object (`refract`) blocks whatever its
//!   opacity: light bent by glass is not followed (no caustics), so glass casts a full
//!   shadow. After [`MAX_LAYERS`] surfaces the light counts as blocked.
//! * **Reflection** (`reflect`): the mirror direction of the viewing direction about the
//!   face-forwarded normal, dispersed in the cone of half-angle `gloss` ([`disperse`], one
//!   dimension); a dispersed direction that would go below the surface is mirrored about the
//!   tangent plane. Weight `reflect.color`.
//! * **Refraction** (`refract`): Snell's law; the ray enters when it meets the outward
//!   normal from outside (`eta = 1 / ior`) and leaves otherwise (`eta = ior`), objects being
//!   in vacuum and not nested. At total internal reflection the transmitted weight follows
//!   the mirror direction (Appendix B drops it, darkening glass at grazing angles). Blur as
//!   gloss, dispersed directions on the wrong side mirrored about the tangent plane. Weight
//!   `refract.color`.
//! * The shaded colour is `Os Ci + reflect.color * C(reflected ray) + refract.color *
//!   C(refracted ray)` (the traced colours premultiplied, their alpha unused), and the
//!   transmittance `1 - Os`. No Fresnel term, no energy balance (as Appendix B).
//! * **Recursion.** A surface met by a primary ray (or shaded by `shade_surface`) is at
//!   depth 0; the surfaces met by its reflected and refracted rays at depth 1, and so on
//!   (refraction counts, unlike Appendix B where it stays at the same level). Secondary
//!   rays leave a surface at depth `d` only if `d < raytrace.max_depth` (clamped to 64) and
//!   the path's weight (the product of the reflection or transmission colours along it, and
//!   of the transmittances of the surfaces in front on each ray; largest channel) is at
//!   least `raytrace.min_weight` and above 0.
//! * **Matte objects** (holdouts) shade as usual in `shade_surface` (the hider decides what
//!   the flag does) but trace no secondary rays from them; in `trace` they contribute
//!   nothing and attenuate what is behind by their transmittance, as the stochastic hider's
//!   holdout rule does, so an opaque matte ends the composite with nothing visible behind.
//!
//! # Tracing a ray
//!
//! [`Shading::trace`] composites front to back along the ray: each surface's premultiplied
//! colour `c` is added as `C += T c` with the per-channel transmittance `T` of the surfaces
//! in front, then `T *= 1 - Os`; the ray goes on behind non-opaque surfaces (without
//! counting a bounce) and stops at the first opaque one, whose ray parameter is
//! [`Traced::t`]. Alpha is 1 when an opaque non-matte surface ends the composite, else the
//! average over the channels of the coverage `sum T Os` of the non-matte surfaces (the
//! stochastic hider's rule). Lights are invisible to rays (Appendix B's are visible).
//!
//! # Strata dimensions
//!
//! Shading one surface takes, in order: one dimension per area light (in scene order, drawn
//! whether or not the light is needed there, so members of a set that shade different
//! materials stay aligned), one for the gloss cone if the object reflects with `gloss > 0`,
//! one for the blur cone if it refracts with `blur > 0`; then the reflected ray's surfaces
//! take theirs, then the refracted ray's, then the next surface behind a transparent one.
//!
//! Determinism: results depend only on the scene, the ray or point, and the stream; no
//! allocation per ray (the setup is done in [`Shading::new`]).
#![deny(missing_docs)]

mod lights;
mod pattern;
mod sample;
mod vertex;

pub use pattern::{BLACK, IVORY, pattern_color, pool_ball};
pub use sample::{concentric_disk, disperse};
pub use vertex::RayVertexShader;

use glam::Vec3;
use reyes_dice::{Looked, Shader, Viewer, facing};
use reyes_sampling::Strata;
use reyes_scene::{Object, Scene, Shape};
use reyes_trace::{Hit, Ray, Tracer};

use crate::lights::{DirectLight, MIN_DIST2, ShutterNorm};
use crate::sample::{mirror, snell, to_side};

/// Most surfaces a shadow ray passes through, or a ray composites, before it is stopped
/// (the light counts as blocked; the composite ends as if nothing were behind).
pub const MAX_LAYERS: u32 = 64;

/// Deepest bounce whatever `raytrace.max_depth` says (the scene validator's limit).
pub const MAX_DEPTH: u32 = 64;
/// Most reflected and refracted rays one primary ray or shaded point may cause, however
/// deep its tree: every tree of at most 9 levels of two branches (1,022 rays) is whole.
/// Beyond it the budget is shared out evenly between a surface's two branches, so an
/// exhausted tree loses its deepest rays, never the first bounces.
pub const MAX_TREE_RAYS: u32 = 1024;

/// The rays one tree has traced, and what is left of its [`MAX_TREE_RAYS`] budget.
struct Walk<'c> {
    counts: &'c mut RayCounts,
    /// Secondary rays this subtree may still trace, each counting itself.
    left: u32,
}

impl<'c> Walk<'c> {
    fn new(counts: &'c mut RayCounts) -> Walk<'c> {
        Walk { counts, left: MAX_TREE_RAYS }
    }

    /// Trace one secondary ray (`trace`), which `others` sibling rays will follow: it costs
    /// one, and its subtree gets an even share of what is then left, the rest kept for the
    /// siblings. What the subtree does not use comes back.
    fn branch<T>(&mut self, others: u32, trace: impl FnOnce(&mut Walk<'_>) -> T) -> T {
        self.left -= 1;
        let share = self.left / (others + 1);
        let mut sub = Walk { counts: &mut *self.counts, left: share };
        let seen = trace(&mut sub);
        self.left -= share - sub.left;
        seen
    }
}

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
    /// What the object's texture maps make of its opacity, roughness and specular
    /// coefficient at a grid vertex (the colour map is in `tint`); [`Looked::NONE`] at
    /// ray hits, which have no micropolygon footprint to filter over.
    pub looked: Looked,
}

/// Numbers of rays traced, by kind: each is one query of the ray engine.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Shadow rays (one per shadowing light per shaded point, plus one per surface a
    /// shadow ray passes through).
    pub shadow: u64,
    /// Reflected rays.
    pub reflection: u64,
    /// Refracted rays.
    pub refraction: u64,
    /// Rays continued behind a surface that is not opaque, within a composite.
    pub continuation: u64,
}

impl RayCounts {
    /// Adds `other`'s counts to these.
    pub fn add(&mut self, other: &RayCounts) {
        self.shadow += other.shadow;
        self.reflection += other.reflection;
        self.refraction += other.refraction;
        self.continuation += other.continuation;
    }

    /// All the rays counted.
    pub fn total(&self) -> u64 {
        self.shadow + self.reflection + self.refraction + self.continuation
    }
}

/// Per-object setup.
struct ObjectShading {
    /// The dicer's shader of the material (its colour, opacity, model and the ambient sum).
    shader: Shader,
    /// Mesh vertex colours per surface (the tracer's `Hit::surface`), as the dicer's four
    /// corner tints interpolated bilinearly in the hit's `(u, v)`; empty without colours.
    tints: Vec<[Vec3; 4]>,
}

/// Where a shadow ray goes.
#[derive(Debug, Clone, Copy)]
enum Toward {
    /// Along a direction, without end.
    Direction(Vec3),
    /// To a point (excluded).
    Point(Vec3),
}

/// The shading of a scene against its ray engine.
pub struct Shading<'a> {
    scene: &'a Scene,
    tracer: &'a Tracer,
    objects: Vec<ObjectShading>,
    /// The direct lights, each with its index in `Scene::lights` (for light sets).
    lights: Vec<(usize, DirectLight)>,
    /// Number of area lights (dimensions drawn per shaded point).
    area_lights: u32,
    /// Some object attenuates shadow rays instead of blocking them (opacity below 1 and no
    /// refraction); otherwise a shadow ray is a yes-or-no query.
    attenuating: bool,
    /// Per light of `Scene::lights`: whether some object is its visible surface
    /// (`Object::area_light`), which its shadow rays pass through.
    emitters: Vec<bool>,
    max_depth: u32,
    min_weight: f32,
}

impl<'a> Shading<'a> {
    /// Set up the shading of `scene`, tracing rays against `tracer` (built from the same scene).
    pub fn new(scene: &'a Scene, tracer: &'a Tracer) -> Shading<'a> {
        let objects: Vec<ObjectShading> = scene
            .objects
            .iter()
            .map(|o| ObjectShading {
                shader: Shader::for_object(o, &scene.lights, Viewer::Eye(Vec3::ZERO)),
                tints: mesh_tints(o),
            })
            .collect();
        let shutter = ShutterNorm::new(scene);
        let lights: Vec<(usize, DirectLight)> = scene
            .lights
            .iter()
            .enumerate()
            .filter_map(|(i, l)| Some((i, DirectLight::new(l, &shutter)?)))
            .collect();
        let area_lights = lights.iter().filter(|(_, l)| matches!(l, DirectLight::Area(_))).count();
        let attenuating = scene
            .objects
            .iter()
            .zip(&objects)
            .any(|(o, s)| o.refract.is_none() && !s.shader.opaque());
        Shading {
            scene,
            tracer,
            objects,
            lights,
            area_lights: area_lights as u32,
            attenuating,
            emitters: {
                let mut linked = vec![false; scene.lights.len()];
                for l in scene.objects.iter().filter_map(|o| o.area_light) {
                    if let Some(flag) = linked.get_mut(l as usize) {
                        *flag = true;
                    }
                }
                linked
            },
            max_depth: scene.raytrace.max_depth.min(MAX_DEPTH),
            min_weight: scene.raytrace.min_weight,
        }
    }

    /// Whether shading `scene` needs anything beyond the dicer's local illumination: a
    /// shadowing or area light, a reflecting or refracting object, or a pattern.
    pub fn needed(scene: &Scene) -> bool {
        scene.needs_ray_shading()
    }

    /// Premultiplied colour `Os * Ci` and transmittance `1 - Os` at a surface point, with
    /// shadow, reflection and refraction rays drawn from `strata`.
    pub fn shade_surface(&self, at: &SurfacePoint, strata: &mut Strata) -> ([f32; 3], [f32; 3]) {
        self.shade_surface_counted(at, strata, &mut RayCounts::default())
    }

    /// [`Shading::shade_surface`], adding the rays it traces to `counts`.
    pub fn shade_surface_counted(
        &self,
        at: &SurfacePoint,
        strata: &mut Strata,
        counts: &mut RayCounts,
    ) -> ([f32; 3], [f32; 3]) {
        let (c, trans) = self.shade_point(at, 0, Vec3::ONE, strata, &mut Walk::new(counts));
        (c.to_array(), trans.to_array())
    }

    /// Follow `ray` (time normalised over the shutter) through the scene up to ray
    /// parameter `t_max`: composite the surfaces it meets front to back, shading each with
    /// the distributed rays.
    pub fn trace(&self, ray: &Ray, t_max: f32, strata: &mut Strata) -> Traced {
        self.trace_counted(ray, t_max, strata, &mut RayCounts::default())
    }

    /// [`Shading::trace`], adding the rays it traces (beyond `ray` itself) to `counts`.
    pub fn trace_counted(
        &self,
        ray: &Ray,
        t_max: f32,
        strata: &mut Strata,
        counts: &mut RayCounts,
    ) -> Traced {
        self.composite(ray, t_max, 0, Vec3::ONE, strata, &mut Walk::new(counts))
    }

    /// The front-to-back composite along `ray` of the surfaces it meets before `t_max`,
    /// shaded at `depth` for a path of weight `weight`.
    fn composite(
        &self,
        ray: &Ray,
        t_max: f32,
        depth: u32,
        weight: Vec3,
        strata: &mut Strata,
        walk: &mut Walk<'_>,
    ) -> Traced {
        let mut color = Vec3::ZERO;
        let mut trans = Vec3::ONE;
        let mut coverage = Vec3::ZERO;
        let mut ray = *ray;
        let mut remaining = t_max;
        let mut passed = 0.0f32;
        let alpha = |coverage: Vec3| (coverage.x + coverage.y + coverage.z) / 3.0;
        for layer in 0..MAX_LAYERS {
            if layer > 0 {
                walk.counts.continuation += 1;
            }
            let Some(hit) = self.tracer.intersect(&ray, remaining) else {
                break;
            };
            let t_here = passed + hit.t;
            let (Some(object), Some(setup)) = (
                self.scene.objects.get(hit.object as usize),
                self.objects.get(hit.object as usize),
            ) else {
                break;
            };
            let os = setup.shader.opacity();
            let surface_trans = Vec3::ONE - os;
            if object.matte {
                // Holdout: no colour, no coverage; what is behind shows through only as far
                // as the matte surface is transparent.
                trans *= surface_trans;
                if setup.shader.opaque() || trans == Vec3::ZERO {
                    let rgb = color.to_array();
                    return Traced { rgba: [rgb[0], rgb[1], rgb[2], alpha(coverage)], t: t_here };
                }
            } else {
                let at = SurfacePoint {
                    object: hit.object,
                    p_world: hit.p_world,
                    n_world: hit.n_world,
                    p_object: hit.p_object,
                    tint: self.tint(setup, &hit),
                    from: ray.origin,
                    time: ray.time,
                    looked: Looked::NONE,
                };
                let (c, _) = self.shade_point(&at, depth, weight * trans, strata, walk);
                color += trans * c;
                coverage += trans * os;
                trans *= surface_trans;
                if setup.shader.opaque() {
                    let rgb = color.to_array();
                    return Traced { rgba: [rgb[0], rgb[1], rgb[2], 1.0], t: t_here };
                }
                if trans == Vec3::ZERO {
                    let rgb = color.to_array();
                    return Traced { rgba: [rgb[0], rgb[1], rgb[2], alpha(coverage)], t: t_here };
                }
            }
            // Go on behind the surface.
            remaining -= hit.t;
            passed = t_here;
            ray = hit.spawn(ray.dir, ray.time);
        }
        let rgb = color.to_array();
        Traced { rgba: [rgb[0], rgb[1], rgb[2], alpha(coverage)], t: f32::INFINITY }
    }

    /// The mesh vertex colour at a hit (white for other shapes and meshes without colours).
    fn tint(&self, setup: &ObjectShading, hit: &Hit) -> Vec3 {
        match setup.tints.get(hit.surface as usize) {
            Some(c) => {
                let (u, v) = (hit.u.clamp(0.0, 1.0), hit.v.clamp(0.0, 1.0));
                c[0].lerp(c[1], u).lerp(c[2].lerp(c[3], u), v)
            }
            None => Vec3::ONE,
        }
    }

    /// Premultiplied colour (local illumination plus traced reflection and refraction) and
    /// transmittance of a surface point at `depth`, on a path of weight `weight`.
    fn shade_point(
        &self,
        at: &SurfacePoint,
        depth: u32,
        weight: Vec3,
        strata: &mut Strata,
        walk: &mut Walk<'_>,
    ) -> (Vec3, Vec3) {
        let (Some(object), Some(setup)) =
            (self.scene.objects.get(at.object as usize), self.objects.get(at.object as usize))
        else {
            // Not an object of the scene: nothing there.
            return (Vec3::ZERO, Vec3::ONE);
        };
        let shader = &setup.shader;
        let os = shader.opacity() * at.looked.opacity;
        let base = match &object.pattern {
            Some(pattern) => pattern_color(pattern, at.p_object),
            None => shader.color(),
        };
        let cs = base * at.tint;
        let p = at.p_world;
        let (n, v) = facing(p, at.n_world, at.from);
        // Every area light has its dimension, used or not.
        let mut light_strata = strata.clone();
        strata.skip(self.area_lights);
        let ci = if shader.unlit() {
            cs
        } else {
            let lights = self.lights.iter().filter_map(|(index, light)| {
                if !object.lit_by(*index) {
                    // Not in the object's light set; an area light still uses its dimension.
                    if matches!(light, DirectLight::Area(_)) {
                        light_strata.next_2d();
                    }
                    return None;
                }
                let lit = (*index, light);
                self.light(lit, p, at.n_world, n, at.time, &mut light_strata, walk.counts)
            });
            shader.illuminate_looked(&at.looked, cs, n, v, lights)
        };
        let mut color = os * ci;

        // The cone dimensions of this surface, drawn before any secondary ray takes its own.
        let gloss = object.reflect.filter(|r| r.gloss > 0.0).map(|_| strata.next_2d());
        let blur = object.refract.filter(|r| r.blur > 0.0).map(|_| strata.next_2d());
        let i = -v;
        if object.matte || depth >= self.max_depth || i == Vec3::ZERO {
            return (color, Vec3::ONE - os);
        }
        // Whether a refracted ray will follow the reflected one (it shares the budget).
        let refracts = object.refract.is_some_and(|r| self.worth(weight * Vec3::from(r.color)));
        if let Some(reflect) = object.reflect {
            let tint = Vec3::from(reflect.color);
            let w = weight * tint;
            if self.worth(w) && walk.left > 0 {
                let mut dir = mirror(i, n);
                if let Some(u) = gloss {
                    dir = to_side(disperse(dir, reflect.gloss.to_radians(), u), n, 1.0);
                }
                walk.counts.reflection += 1;
                let ray = Ray::spawn(p, at.n_world, dir, at.time);
                let others = u32::from(refracts);
                let seen = walk.branch(others, |walk| {
                    self.composite(&ray, f32::INFINITY, depth + 1, w, strata, walk)
                });
                color += tint * Vec3::new(seen.rgba[0], seen.rgba[1], seen.rgba[2]);
            }
        }
        if let Some(refract) = object.refract {
            let tint = Vec3::from(refract.color);
            let w = weight * tint;
            if self.worth(w) && walk.left > 0 {
                let entering = i.dot(at.n_world) < 0.0;
                let eta = if entering { 1.0 / refract.ior } else { refract.ior };
                let (dir, side) = match snell(i, n, eta) {
                    Some(t) => (t, -1.0),
                    // Total internal reflection: the transmitted weight is reflected.
                    None => (mirror(i, n), 1.0),
                };
                let dir = match blur {
                    Some(u) => to_side(disperse(dir, refract.blur.to_radians(), u), n, side),
                    None => dir,
                };
                walk.counts.refraction += 1;
                let ray = Ray::spawn(p, at.n_world, dir, at.time);
                let seen = walk.branch(0, |walk| {
                    self.composite(&ray, f32::INFINITY, depth + 1, w, strata, walk)
                });
                color += tint * Vec3::new(seen.rgba[0], seen.rgba[1], seen.rgba[2]);
            }
        }
        (color, Vec3::ONE - os)
    }

    /// Is a secondary ray of path weight `w` worth tracing?
    fn worth(&self, w: Vec3) -> bool {
        let m = w.max_element();
        m > 0.0 && m >= self.min_weight
    }

    /// One direct light's `(L, Cl)` at `p` (geometric normal `n_geom`, face-forwarded unit
    /// normal `n`), shadowed; `None` when it adds nothing. Area lights draw their point from
    /// `light_strata` first of all, so each keeps its dimension.
    #[allow(clippy::too_many_arguments)]
    fn light(
        &self,
        (index, light): (usize, &DirectLight),
        p: Vec3,
        n_geom: Vec3,
        n: Vec3,
        time: f32,
        light_strata: &mut Strata,
        counts: &mut RayCounts,
    ) -> Option<(Vec3, Vec3)> {
        let (l, cl, toward) = match light {
            DirectLight::Distant { l, cl, shadows } => {
                (*l, *cl, shadows.then_some(Toward::Direction(*l)))
            }
            DirectLight::Point { from, cl, shadows } => {
                let d = *from - p;
                let d2 = d.length_squared();
                if !d2.is_finite() || d2 <= MIN_DIST2 {
                    return None;
                }
                (d / d2.sqrt(), *cl / d2, shadows.then_some(Toward::Point(*from)))
            }
            DirectLight::Spot { spot, shadows } => {
                let (l, cl) = spot.arriving(p)?;
                (l, cl, shadows.then_some(Toward::Point(spot.from())))
            }
            DirectLight::Area(area) => {
                let u = light_strata.next_2d();
                let s = area.sample(p, time, u)?;
                (s.l, s.cl, Some(Toward::Point(s.point)))
            }
        };
        // Below the surface a light adds nothing (the models skip N.L <= 0): no shadow ray.
        if n.dot(l) <= 0.0 {
            return None;
        }
        match toward {
            None => Some((l, cl)),
            Some(toward) => {
                let vis = self.visibility(p, n_geom, toward, time, index, counts);
                (vis != Vec3::ZERO).then_some((l, cl * vis))
            }
        }
    }

    /// The fraction of light, per channel, that reaches `p` (normal `n`) from `toward` at
    /// `time`: 0 behind an opaque or refracting surface, `prod (1 - Os)` through surfaces
    /// that are not opaque. The visible surfaces of light `light` (`Object::area_light`) are
    /// passed through.
    fn visibility(
        &self,
        p: Vec3,
        n: Vec3,
        toward: Toward,
        time: f32,
        light: usize,
        counts: &mut RayCounts,
    ) -> Vec3 {
        let (mut ray, t_max) = match toward {
            Toward::Direction(l) => (Ray::spawn(p, n, l, time), f32::INFINITY),
            Toward::Point(q) => {
                let mut ray = Ray::spawn(p, n, q - p, time);
                // Aim from the nudged origin, so that t = 1 is the light point itself.
                ray.dir = q - ray.origin;
                (ray, 1.0)
            }
        };
        let emitters = self.emitters.get(light).copied().unwrap_or(false);
        if !self.attenuating && !emitters {
            counts.shadow += 1;
            return if self.tracer.occluded(&ray, t_max) { Vec3::ZERO } else { Vec3::ONE };
        }
        let mut vis = Vec3::ONE;
        let mut remaining = t_max;
        for _ in 0..MAX_LAYERS {
            counts.shadow += 1;
            let Some(hit) = self.tracer.intersect(&ray, remaining) else {
                return vis;
            };
            let i = hit.object as usize;
            let (Some(object), Some(setup)) = (self.scene.objects.get(i), self.objects.get(i))
            else {
                return Vec3::ZERO;
            };
            if emitters && object.area_light.is_some_and(|l| l as usize == light) {
                // The light's own surface: not an occluder of its light.
            } else if object.refract.is_some() || setup.shader.opaque() {
                return Vec3::ZERO;
            } else {
                vis *= Vec3::ONE - setup.shader.opacity();
            }
            if vis.max_element() <= 0.0 {
                return Vec3::ZERO;
            }
            remaining -= hit.t;
            ray = hit.spawn(ray.dir, time);
        }
        Vec3::ZERO
    }
}

/// The dicer's corner tints of every surface of a mesh with vertex colours, in the
/// tracer's surface order (faces in order, faces with a bad index or fewer than three
/// vertices skipped, quads as one bilinear patch, other polygons as fan triangles).
fn mesh_tints(object: &Object) -> Vec<[Vec3; 4]> {
    let Shape::Mesh { points, faces, colors: Some(colors), .. } = &object.shape else {
        return Vec::new();
    };
    let tint = |i: u32| colors.get(i as usize).map_or(Vec3::ONE, |c| Vec3::from(*c));
    let mut out = Vec::new();
    for face in faces {
        if face.iter().any(|&i| i as usize >= points.len()) {
            continue;
        }
        match face.len() {
            0..=2 => {}
            // Around the face a, b, c, d: P0 = a, P1 = b, P2 = d, P3 = c.
            4 => out.push([tint(face[0]), tint(face[1]), tint(face[3]), tint(face[2])]),
            n => {
                for k in 1..n - 1 {
                    let (a, b, c) = (tint(face[0]), tint(face[k]), tint(face[k + 1]));
                    out.push([a, b, c, c]);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shading_is_shareable_across_threads() {
        fn check<T: Send + Sync>() {}
        check::<Shading<'static>>();
        check::<Strata>();
    }
}

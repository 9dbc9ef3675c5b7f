//! What an object brings to the dicing of each of its grids (stage: dice): its shader at
//! shutter open, the labels every micropolygon of it carries (flag bits, CSG slot, glass
//! opacity), an optional vertex-shader hook, and its back-face, AOV, look-development and
//! overlap switches. Invariant: made once per object, before any of its grids is diced, and
//! read only while dicing.

use glam::Mat3;
use reyes_hider::flags;

use crate::aov::VertexAovs;
use crate::camera::Viewer;
use crate::hook::VertexShader;
use crate::lookdev::Look;
use crate::motion::Placement;
use crate::shade::Shader;

/// A vertex shader from [`crate::DiceOptions`], with where the dicer is.
#[derive(Clone, Copy)]
pub(crate) struct Hook<'a> {
    /// The shader.
    pub shader: &'a dyn VertexShader,
    /// Index of the object in the scene.
    pub object: usize,
    /// Index of the surface being diced (set per grid by [`super::Emitter::dice`]).
    pub surface: usize,
}

/// One object's shading, flag bits and labels.
#[derive(Clone)]
pub(crate) struct ObjectContext<'a> {
    /// Object to world at shutter open, for normals (inverse transpose up to a positive
    /// factor).
    pub normal_to_world: Mat3,
    /// Shader of the object's material.
    pub shader: Shader,
    /// Labels every micropolygon of the object carries.
    pub labels: Labels,
    /// Shades the vertices instead of `shader` when present.
    pub hook: Option<Hook<'a>>,
    /// Back-facing micropolygons may be dropped: the object is a closed, opaque surface
    /// drawn on its own (not matte, glass or a CSG operand) and the camera is a pinhole, so
    /// a back-facing micropolygon always lies behind a front-facing one of the same object
    /// at every sample that could see it ([`super::cull_back_faces`]).
    pub cull_back: bool,
    /// The per-vertex AOV layout when the scene writes AOVs, and the object's ids.
    pub aov: Option<(std::sync::Arc<VertexAovs>, [f32; 2])>,
    /// Texture maps, displacement, bump and emission ([`crate::lookdev`]).
    pub look: Option<Look>,
    /// Push crack-free grids' boundary vertices out by [`crate::split::OVERLAP`] (not for CSG operands,
    /// for which a sample seeing a surface twice is as wrong as one seeing it not at all).
    pub overlap: bool,
    /// The trim loops of a trimmed NURBS patch ([`crate::trim`]).
    pub trim: Option<crate::trim::TrimSetup>,
    /// Shading-language shaders, which shade the object's grids instead of `shader` and
    /// `hook` ([`crate::sl`]).
    pub sl: Option<std::sync::Arc<crate::sl::SlSetup>>,
}

/// What every micropolygon of one object carries besides its geometry and colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Labels {
    /// Flag bits (`OPAQUE`, `MATTE`, `GOURAUD`, `GLASS`).
    pub flags: u32,
    /// CSG tree index and slot id (0, 0 when the object is not a CSG operand).
    pub csg_tree: u16,
    /// See `csg_tree`.
    pub csg_node: u16,
    /// Appendix A `glasshackopacity` (0 unless `GLASS`).
    pub glass_opacity: f32,
    /// The opacity is a shader's (shading language): not known until the grid is shaded, so
    /// `OPAQUE` is left off the object and set per micropolygon whose four corners came out
    /// of the shader fully opaque ([`super::grid::Grid::build`]).
    pub shaded_opacity: bool,
}

/// Per-object setup: shading (under the object's light set, seen by `viewer`, with the object
/// placed by `open`, its placement at shutter open), flags, and the CSG label `csg`
/// (`(tree index, slot id)` of a CSG operand, from [`crate::CsgSetup::leaf`]).
pub(crate) fn object_context(
    object: &reyes_scene::Object,
    lights: &[reyes_scene::Light],
    viewer: Viewer,
    open: &Placement,
    csg: Option<(u16, u16)>,
) -> ObjectContext<'static> {
    let shader = Shader::for_object(object, lights, viewer);
    let mut flags = 0;
    if shader.opaque() {
        flags |= flags::OPAQUE;
    }
    if object.matte {
        flags |= flags::MATTE;
    }
    if object.interpolation == reyes_scene::Interpolation::Gouraud {
        flags |= flags::GOURAUD;
    }
    let mut glass_opacity = 0.0;
    if let Some(a) = object.glass {
        flags |= flags::GLASS;
        glass_opacity = a;
    }
    let (csg_tree, csg_node) = csg.unwrap_or((0, 0));
    let labels = Labels { flags, csg_tree, csg_node, glass_opacity, shaded_opacity: false };
    ObjectContext {
        normal_to_world: open.normal_to_world(),
        shader,
        labels,
        hook: None,
        cull_back: false,
        aov: None,
        look: None,
        overlap: csg.is_none(),
        trim: None,
        sl: None,
    }
}

/// Sets up the shading-language shaders of object `index` of `scene`, placed by `place` at
/// shutter open, on `ctx` (with the instruction budget `budget`, default
/// `reyes_scene::sl::exec::DEFAULT_BUDGET`), and returns how far its displacement may move a
/// point (0 without one). The machine then shades the grids: no vertex hook, and the opacity
/// is the shader's, so the object is not taken as opaque; its micropolygons are, one by one,
/// where the shader leaves them fully opaque.
pub(crate) fn attach_sl(
    ctx: &mut ObjectContext<'_>,
    scene: &reyes_scene::Scene,
    index: usize,
    place: &Placement,
    camera: &crate::camera::CameraSetup,
    (budget, lookdev): (Option<u64>, Option<&crate::Lookdev>),
) -> f32 {
    let budget = budget.unwrap_or(reyes_scene::sl::exec::DEFAULT_BUDGET);
    let (Placement::Matrix(m) | Placement::Between { from: m, .. }) = place;
    let maps = lookdev.and_then(crate::Lookdev::shader_maps);
    ctx.sl = crate::sl::SlSetup::new(scene, index, m, camera, &ctx.shader, budget)
        .map(|s| std::sync::Arc::new(s.with_maps(maps)));
    let Some(sl) = &ctx.sl else { return 0.0 };
    ctx.hook = None;
    ctx.labels.flags &= !flags::OPAQUE;
    ctx.labels.shaded_opacity = true;
    if sl.shaders.displacement.is_some() { sl.shaders.displacement_bound } else { 0.0 }
}

/// Everything object `i` of `scene` brings to its grids but its geometry, placed at shutter
/// open by `open.0` (a CSG leaf `open.1`, seen by the camera `open.2`): its context with the
/// vertex hook of `options`, its AOVs (`aov.0` and the ids `aov.1`), its look development
/// (`aov.2`), its trim loops (registered in `trims`, whose index the micropolygons carry) and
/// its shading-language shaders; whether its back faces are culled; and how far
/// displacement may move a point (its reach; 0 without displacement).
pub(crate) fn setup_object<'a>(
    scene: &reyes_scene::Scene,
    i: usize,
    open: (&Placement, Option<(u16, u16)>, &crate::camera::CameraSetup),
    options: &crate::DiceOptions<'a>,
    aov: (Option<&std::sync::Arc<VertexAovs>>, &[[f32; 2]], Option<&crate::Lookdev>),
    trims: &mut Vec<std::sync::Arc<reyes_scene::patches::trim::TrimRegion>>,
) -> (ObjectContext<'a>, f32) {
    let (place, leaf, camera) = open;
    let object = &scene.objects[i];
    let mut ctx = object_context(object, &scene.lights, camera.viewer(), place, leaf);
    ctx.hook = options.vertex_shader.map(|shader| Hook { shader, object: i, surface: 0 });
    ctx.aov = aov.0.map(|a| (a.clone(), aov.1[i]));
    ctx.look = aov.2.and_then(|l| l.object(i));
    ctx.trim = crate::trim::TrimSetup::of(&object.shape, trims.len());
    trims.extend(ctx.trim.as_ref().map(|t| t.region.clone()));
    let mut reach = ctx.look.as_ref().map_or(0.0, |l| l.object.bound);
    reach = reach.max(attach_sl(&mut ctx, scene, i, place, camera, (options.shader_budget, aov.2)));
    if ctx.look.as_ref().is_some_and(|l| l.object.may_be_transparent())
        || crate::shapes::own_opacity_below_one(&object.shape)
    {
        ctx.labels.flags &= !flags::OPAQUE;
    }
    ctx.cull_back = reach == 0.0
        && (scene.hider.cull_back_faces || object.one_sided)
        && super::cull_back_faces(object, &ctx.labels, leaf.is_some(), camera.lens().is_none());
    (ctx, reach)
}

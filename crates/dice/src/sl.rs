//! Shading-language shading of a grid (issue #30): an object whose surface, displacement or
//! atmosphere is an RSL shader ([`reyes_scene::ObjectShaders`]) is shaded a whole grid at a
//! time on the grid machine (`reyes_scene::sl::exec`) instead of vertex by vertex.
//!
//! Conventions (RenderMan's): shaders run in "current" space, which is camera space; `E` is
//! the eye (the origin), `I = P - E` (orthographic: along +z); `N` is the unit outward
//! shading normal, `Ng` the surface's; `u`, `v`, `du`, `dv` are the grid's, `s`, `t` the
//! surface's texture coordinates; `Cs`, `Os` the material's colour (times a mesh's vertex
//! colours) and opacity. The grid's colour is `Ci` as the shader leaves it (shaders
//! premultiply by `Oi`, as the native path does) and its transmittance `1 - Oi`.
//!
//! Invariants: a grid is shaded whole (derivatives need every neighbour), so every vertex is
//! shaded; every non-finite float of `Ci`, `Oi` (and of a displaced `P`) is replaced by 0 and
//! counted; a run that fails (its instruction budget spent, a space unknown) is an error of
//! the render naming the object, never a panic.

use std::sync::Arc;

use glam::{Mat3, Mat4, Vec3};
use reyes_scene::sl::BaseType;
use reyes_scene::sl::exec::space::{Mat, mat_mul};
use reyes_scene::sl::exec::{
    ExecError, GridContext, LightQuery, LightSample, Lights, Num, ShaderLight, ShaderLights,
    Spaces, Value,
};
use reyes_scene::{ObjectShaders, PrimitiveValue, Scene, ShaderInstance};

use crate::camera::CameraSetup;
use crate::shade::Shader;

/// A transformation of a triple by a matrix (a point's, a vector's or a normal's).
type Carry = fn(&Mat, [f32; 3]) -> [f32; 3];
/// Per vertex: colours and transmittances (or positions and normals).
type PerVertex<T> = (Vec<T>, Vec<T>);
/// A shaded grid: colours and transmittances, and the output variables' values.
type Shaded = (PerVertex<[f32; 3]>, Vec<Vec<f32>>);

/// A glam matrix (column vectors) as the shading language's (row vectors, row by row).
fn sl(m: &Mat4) -> Mat {
    m.to_cols_array()
}

/// What shading an object's grids on the machine needs, set up once per object.
pub(crate) struct SlSetup {
    /// The object's shaders.
    pub shaders: Arc<ObjectShaders>,
    /// The object's name, for messages.
    pub object: String,
    /// The named spaces of the object's shaders, "shader" excepted (each instance has its own).
    spaces: Spaces,
    /// Model world to camera (current).
    world_to_camera: Mat,
    /// The native lights lighting the object, with the material's `Cs`, `Os`.
    native: Shader,
    camera_to_world: Mat4,
    /// The light shaders lighting the object.
    lights: Vec<ShaderLight>,
    /// Orthographic camera: `I` runs along +z.
    orthographic: bool,
    /// The instruction budget per grid and shader run.
    pub budget: u64,
    /// `attribute()`, `option()`, `rendererinfo()`, `time`, `dtime`.
    info: crate::slinfo::Info,
    /// The texture maps of `texture`, `environment`, `shadow` (issue #32; `crate::sltex`).
    maps: Option<Arc<crate::sltex::ShaderMaps>>,
    /// "current" to RenderMan's world (where shadow maps' matrices start).
    current_to_world: Mat,
}

/// What shading grids on the machine counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct SlCounts {
    /// Non-finite floats replaced by 0 (in `Ci`, `Oi`, displaced `P`), plus those the
    /// shaders stored.
    pub nonfinite: u64,
    /// Instructions run.
    pub instructions: u64,
}

impl SlSetup {
    /// The setup of `object` (index `index` of `scene`) placed by `object_to_world` at
    /// shutter open, lit as `native` lights it, or `None` if it has no shading-language shader.
    pub(crate) fn new(
        scene: &Scene,
        index: usize,
        object_to_world: &Mat4,
        camera: &CameraSetup,
        native: &Shader,
        budget: u64,
    ) -> Option<SlSetup> {
        let object = &scene.objects[index];
        let shaders = object.shaders.clone()?;
        let w2c = camera.world_to_camera();
        let world_to_camera = sl(&w2c);
        let rman_world = mat_mul(&scene.shaders.world_to_model, &world_to_camera);
        let mut spaces =
            Spaces { clipping: Some((camera.hither(), camera.yon())), ..Spaces::default() }
                .with("world", rman_world)
                .with("object", sl(&(w2c * *object_to_world)))
                .with("camera", reyes_scene::sl::exec::space::IDENTITY);
        spaces = with_raster(spaces, camera, scene.camera.screen_window);
        let lights = scene
            .shaders
            .lights
            .iter()
            .filter(|(i, _)| object.lit_by(*i as usize))
            .map(|(_, l)| {
                let mut s = spaces.clone();
                let to_current = mat_mul(&l.shader_to_world, &world_to_camera);
                s = s.with("shader", to_current);
                ShaderLight {
                    shader: l.shader.clone(),
                    params: params_in_current(l, &to_current),
                    spaces: s,
                    categories: categories(l),
                }
            })
            .collect();
        Some(SlSetup {
            shaders,
            object: object.name.clone(),
            spaces,
            world_to_camera,
            native: native.clone(),
            camera_to_world: w2c.inverse(),
            lights,
            orthographic: camera.projection() == reyes_scene::Projection::Orthographic,
            budget,
            info: crate::slinfo::Info::of(scene, object),
            maps: None,
            current_to_world: reyes_scene::sl::exec::space::mat_inverse(&rman_world),
        })
    }

    /// This setup reading the shaders' texture maps `maps`.
    pub(crate) fn with_maps(mut self, maps: Option<Arc<crate::sltex::ShaderMaps>>) -> SlSetup {
        self.maps = maps;
        self
    }

    /// The texture callback of a run (without maps, every lookup takes the fallback).
    fn textures(&self) -> Option<crate::sltex::SlTextures> {
        let maps = self.maps.clone().unwrap_or_else(|| Arc::new(crate::sltex::ShaderMaps::none()));
        Some(crate::sltex::SlTextures { maps, current_to_world: self.current_to_world })
    }

    /// The spaces of `instance` (its "shader" space added) and its parameters in "current".
    fn bind(&self, instance: &ShaderInstance) -> (Spaces, Vec<(String, Value)>) {
        let to_current = mat_mul(&instance.shader_to_world, &self.world_to_camera);
        let spaces = self.spaces.clone().with("shader", to_current);
        (spaces, params_in_current(instance, &to_current))
    }
}

/// "raster", "NDC" and "screen": the camera's projection to pixels (to the unit square; to
/// the screen window, RenderMan's default for the image's aspect ratio when none is given),
/// with the depth mapped as a projective z so that the matrix inverts.
fn with_raster(spaces: Spaces, camera: &CameraSetup, window: Option<[f32; 4]>) -> Spaces {
    let size = camera.image_size();
    let to_raster = camera_to_raster(camera);
    let raster_to_ndc: Mat =
        [1. / size.x, 0., 0., 0., 0., 1. / size.y, 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.];
    let from_raster = reyes_scene::sl::exec::space::mat_inverse(&to_raster);
    let ndc_to_raster = reyes_scene::sl::exec::space::mat_inverse(&raster_to_ndc);
    // Screen to raster: x from the window's left edge, y down from its top.
    let aspect = size.x / size.y;
    let [l, r, b, t] = window.unwrap_or(if aspect >= 1.0 {
        [-aspect, aspect, -1.0, 1.0]
    } else {
        [-1.0, 1.0, -1.0 / aspect, 1.0 / aspect]
    });
    let (sx, sy) = (size.x / (r - l), size.y / (t - b));
    let screen_to_raster: Mat =
        [sx, 0., 0., 0., 0., -sy, 0., 0., 0., 0., 1., 0., -l * sx, t * sy, 0., 1.];
    spaces
        .with("raster", from_raster)
        .with("NDC", mat_mul(&ndc_to_raster, &from_raster))
        .with("screen", mat_mul(&screen_to_raster, &from_raster))
}

/// Camera space to raster, homogeneous, row vectors: `[x y z 1] M = (kx x + cx z, -ky y + cy z,
/// a z + b, z)` for perspective.
fn camera_to_raster(camera: &CameraSetup) -> Mat {
    let (k, c) = (camera.raster_scale(), camera.raster_centre());
    let (n, f) = (camera.hither(), camera.yon().min(1e30));
    match camera.projection() {
        reyes_scene::Projection::Perspective => {
            let a = f / (f - n);
            let b = -f * n / (f - n);
            [k.x, 0., 0., 0., 0., -k.y, 0., 0., c.x, c.y, a, 1., 0., 0., b, 0.]
        }
        reyes_scene::Projection::Orthographic => {
            [k.x, 0., 0., 0., 0., -k.y, 0., 0., 0., 0., 1., 0., c.x, c.y, 0., 1.]
        }
    }
}

/// The matrices of a depth map that `scene`'s camera renders (`Display "zfile"`), as Pixar's
/// tags hold them (row vectors, row by row): RenderMan's world to the camera, whose `z` is
/// the depth stored; and world to the map's screen, where the picture spans `[-1, 1]` in `x`
/// and `y` (`y` up), as `shadow()` reads it (`s = (x/w + 1)/2`, `t = (1 - y/w)/2`,
/// docs/textures.md). Returns `(world_to_screen, world_to_camera)`.
pub fn depth_map_matrices(scene: &Scene) -> ([f32; 16], [f32; 16]) {
    let camera = CameraSetup::new(scene);
    let world_to_camera = mat_mul(&scene.shaders.world_to_model, &sl(&camera.world_to_camera()));
    let size = camera.image_size();
    let raster_to_unit: Mat =
        [2. / size.x, 0., 0., 0., 0., -2. / size.y, 0., 0., 0., 0., 1., 0., -1., 1., 0., 1.];
    let camera_to_unit = mat_mul(&camera_to_raster(&camera), &raster_to_unit);
    (mat_mul(&world_to_camera, &camera_to_unit), world_to_camera)
}

/// A light's categories (its `__category` parameter, comma-separated).
fn categories(l: &ShaderInstance) -> Vec<String> {
    l.params
        .iter()
        .find(|(n, _)| n == "__category")
        .map(|(_, v)| v.str().split(',').map(|s| s.trim().to_string()).collect())
        .unwrap_or_default()
}

/// The parameters of `instance` with points, vectors and normals carried from its "shader"
/// space (where the scene gave them) to "current" by `to_current`.
fn params_in_current(instance: &ShaderInstance, to_current: &Mat) -> Vec<(String, Value)> {
    use reyes_scene::sl::exec::space::{xform_normal, xform_point, xform_vector};
    let shader = &instance.shader;
    instance
        .params
        .iter()
        .map(|(name, v)| {
            let f: Option<Carry> = match shader.param(name).map(|p| p.ty.base) {
                Some(BaseType::Point) => Some(xform_point),
                Some(BaseType::Vector) => Some(xform_vector),
                Some(BaseType::Normal) => Some(xform_normal),
                _ => None,
            };
            let Some(f) = f else { return (name.clone(), v.clone()) };
            let one = |x: &Value| match x {
                Value::Num(n) if n.w == 3 && n.data.len() == 3 => {
                    Value::Num(Num::uniform(&f(to_current, n.v3(0))))
                }
                other => other.clone(),
            };
            let v = match v {
                Value::Array(xs) => Value::Array(xs.iter().map(one).collect()),
                x => one(x),
            };
            (name.clone(), v)
        })
        .collect()
}

/// One grid's points in camera space, with what the shaders read of them.
pub(crate) struct GridInput<'g> {
    /// Vertices across and down (`nu + 1`, `nv + 1`).
    pub nu: usize,
    pub nv: usize,
    /// Camera-space positions, unit shading normals and geometric normals.
    pub p: &'g [Vec3],
    pub n: &'g [Vec3],
    pub ng: &'g [Vec3],
    /// Surface parameters and their steps.
    pub u: &'g [f32],
    pub v: &'g [f32],
    pub du: f32,
    pub dv: f32,
    /// Texture coordinates.
    pub s: &'g [f32],
    pub t: &'g [f32],
    /// `Cs` per vertex and `Os`.
    pub cs: &'g [Vec3],
    /// The colour multiplying the material's colour per vertex (mesh vertex colours; white
    /// otherwise): what the native material takes where no surface shader runs. (`Cs` is
    /// the material colour times it.)
    pub tint: &'g [Vec3],
    pub os: Vec3,
}

fn flat(v: &[Vec3]) -> Vec<f32> {
    v.iter().flat_map(|p| p.to_array()).collect()
}

/// The triple `name` of a context after its run, as vectors (zeros where unset).
pub(crate) fn read_v3(g: &GridContext<'_>, name: &str, n: usize) -> Vec<Vec3> {
    (0..n).map(|i| Vec3::from(g.get_v3(name, i).unwrap_or([0.0; 3]))).collect()
}

impl SlSetup {
    /// A context for `instance` over `grid`, every global and parameter set.
    fn context<'s>(
        &self,
        instance: &'s ShaderInstance,
        grid: &GridInput<'_>,
    ) -> Result<GridContext<'s>, ExecError> {
        let mut g = GridContext::new(&instance.shader, grid.nu, grid.nv);
        g.set_budget(self.budget);
        if let Some(maps) = &self.maps {
            maps.set_messages(&mut g);
        }
        let (spaces, params) = self.bind(instance);
        g.set_spaces(spaces);
        g.set_varying("P", &flat(grid.p))?;
        g.set_varying("N", &flat(grid.n))?;
        g.set_varying("Ng", &flat(grid.ng))?;
        let i: Vec<Vec3> = if self.orthographic {
            grid.p.iter().map(|p| Vec3::new(0.0, 0.0, p.z)).collect()
        } else {
            grid.p.to_vec()
        };
        g.set_varying("I", &flat(&i))?;
        g.set_uniform("E", &[0.0; 3])?;
        g.set_varying("u", grid.u)?;
        g.set_varying("v", grid.v)?;
        g.set_uniform("du", &[grid.du])?;
        g.set_uniform("dv", &[grid.dv])?;
        g.set_varying("s", grid.s)?;
        g.set_varying("t", grid.t)?;
        let (dpdu, dpdv) = differences(grid.p, grid.nu, grid.nv, grid.du, grid.dv);
        g.set_varying("dPdu", &flat(&dpdu))?;
        g.set_varying("dPdv", &flat(&dpdv))?;
        self.info.bind(&mut g);
        // Message passing: the other shaders' parameters as the scene gives them (their
        // values after a run, where one ran before on this grid, replace them later).
        for (function, other) in [
            ("surface", &self.shaders.surface),
            ("displacement", &self.shaders.displacement),
            ("atmosphere", &self.shaders.atmosphere),
        ] {
            if let Some(other) = other.as_ref().filter(|o| !std::ptr::eq(*o, instance)) {
                for (name, v) in self.bind(other).1 {
                    g.set_message(function, &name, v);
                }
            }
        }
        if instance.shader.kind == reyes_scene::sl::ShaderKind::Surface {
            g.set_varying("Cs", &flat(grid.cs))?;
            g.set_uniform("Os", &grid.os.to_array())?;
            // What a surface shader that leaves them alone outputs: black and opaque, as
            // Aqsis and PRMan start them.
            let n = grid.nu * grid.nv;
            g.set_varying("Ci", &vec![0.0; 3 * n])?;
            g.set_varying("Oi", &vec![1.0; 3 * n])?;
        }
        for (name, v) in params {
            g.set_param(&name, v)?;
        }
        for (name, v) in &self.shaders.primitive {
            if instance.shader.param(name).is_none() {
                continue;
            }
            let v = match v {
                PrimitiveValue::Uniform(v) => v.clone(),
                PrimitiveValue::Corners { width, data } => corners(*width, data, grid.u, grid.v),
            };
            g.set_param(name, v)?;
        }
        Ok(g)
    }

    /// Run the surface shader (and the atmosphere) over `grid`: premultiplied colours and
    /// transmittances per vertex, non-finite values zeroed and counted in `counts`; and the
    /// output variables `outputs` (name, floats: 1 or 3), each `n * floats` values vertex by
    /// vertex, as the atmosphere leaves them if it has the output parameter, else the
    /// surface, else 0.
    pub(crate) fn shade(
        &self,
        grid: &GridInput<'_>,
        counts: &mut SlCounts,
        outputs: &[(String, usize)],
        displaced: &[(String, Value)],
    ) -> Result<Shaded, String> {
        let n = grid.nu * grid.nv;
        let named = |e: ExecError| format!("object \"{}\": {e}", self.object);
        let mut outs: Vec<Vec<f32>> = outputs.iter().map(|(_, w)| vec![0.0; n * w]).collect();
        let mut surfaced = Vec::new();
        let (mut ci, mut oi) = match &self.shaders.surface {
            Some(surface) => {
                let mut lights = GridLights {
                    native: &self.native,
                    camera_to_world: self.camera_to_world,
                    world_to_camera: self.world_to_camera,
                    shaders: ShaderLights { lights: self.lights.clone() },
                    textures: self.textures(),
                };
                let mut maps = self.textures();
                let mut g = self.context(surface, grid).map_err(named)?;
                for (name, v) in displaced {
                    g.set_message("displacement", name, v.clone());
                }
                g.set_lights(&mut lights);
                if let Some(m) = maps.as_mut() {
                    g.set_textures(m);
                }
                let stats = g.run().map_err(named)?;
                counts.instructions += stats.instructions;
                counts.nonfinite += stats.nonfinite;
                print(&g);
                read_outputs(&g, surface, outputs, &mut outs);
                surfaced = after_run(&g, surface);
                (read_v3(&g, "Ci", n), read_v3(&g, "Oi", n))
            }
            // No surface shader (only a displacement or atmosphere): the native material.
            None => {
                let mut ci = Vec::with_capacity(n);
                let mut oi = Vec::with_capacity(n);
                for k in 0..n {
                    let p_world = self.camera_to_world.transform_point3(grid.p[k]);
                    let n_world = Mat3::from_mat4(self.camera_to_world) * grid.n[k];
                    let (c, t) = self.native.shade(p_world, n_world, grid.tint[k]);
                    ci.push(Vec3::from(c));
                    oi.push(Vec3::ONE - Vec3::from(t));
                }
                (ci, oi)
            }
        };
        if let Some(atmosphere) = &self.shaders.atmosphere {
            let mut maps = self.textures();
            let mut g = self.context(atmosphere, grid).map_err(named)?;
            for (name, v) in &surfaced {
                g.set_message("surface", name, v.clone());
            }
            if let Some(m) = maps.as_mut() {
                g.set_textures(m);
            }
            g.set_varying("Ci", &flat(&ci)).map_err(named)?;
            g.set_varying("Oi", &flat(&oi)).map_err(named)?;
            let stats = g.run().map_err(named)?;
            counts.instructions += stats.instructions;
            counts.nonfinite += stats.nonfinite;
            print(&g);
            read_outputs(&g, atmosphere, outputs, &mut outs);
            ci = read_v3(&g, "Ci", n);
            oi = read_v3(&g, "Oi", n);
        }
        let mut finite = |v: Vec3| {
            let a = v.to_array();
            let bad = a.iter().filter(|x| !x.is_finite()).count() as u64;
            counts.nonfinite += bad;
            a.map(|x| if x.is_finite() { x } else { 0.0 })
        };
        let color: Vec<[f32; 3]> = ci.into_iter().map(&mut finite).collect();
        let trans: Vec<[f32; 3]> = oi.into_iter().map(|o| finite(o).map(|x| 1.0 - x)).collect();
        for x in outs.iter_mut().flatten() {
            if !x.is_finite() {
                counts.nonfinite += 1;
                *x = 0.0;
            }
        }
        Ok(((color, trans), outs))
    }

    /// Run the displacement shader over `grid`: the displaced camera-space positions and
    /// unit normals (`None`: no displacement shader).
    pub(crate) fn displace(
        &self,
        grid: &GridInput<'_>,
        counts: &mut SlCounts,
        params: &mut Vec<(String, Value)>,
    ) -> Result<Option<PerVertex<Vec3>>, String> {
        let Some(d) = &self.shaders.displacement else { return Ok(None) };
        let named = |e: ExecError| format!("object \"{}\": {e}", self.object);
        let n = grid.nu * grid.nv;
        let mut maps = self.textures();
        let mut g = self.context(d, grid).map_err(named)?;
        if let Some(m) = maps.as_mut() {
            g.set_textures(m);
        }
        let stats = g.run().map_err(named)?;
        counts.instructions += stats.instructions;
        counts.nonfinite += stats.nonfinite;
        print(&g);
        *params = after_run(&g, d);
        let mut p = read_v3(&g, "P", n);
        let mut nn = read_v3(&g, "N", n);
        for k in 0..n {
            if !p[k].is_finite() {
                counts.nonfinite += 1;
                p[k] = grid.p[k];
            }
            nn[k] = nn[k].try_normalize().unwrap_or(grid.n[k]);
        }
        Ok(Some((p, nn)))
    }
}

/// Every parameter of `instance` as its run `g` left it (for message passing).
fn after_run(g: &GridContext<'_>, instance: &ShaderInstance) -> Vec<(String, Value)> {
    let sh = &instance.shader;
    sh.params
        .iter()
        .filter_map(|&i| {
            let name = &sh.vars[i].name;
            Some((name.clone(), g.param(name)?.clone()))
        })
        .collect()
}

/// Writes the lines the shader's `printf` calls made during run `g` to standard error, as
/// RenderMan renderers do (grids shade in parallel, so lines of different grids may
/// interleave in any order).
fn print(g: &GridContext<'_>) {
    if g.printed().is_empty() {
        return;
    }
    let mut err = std::io::stderr().lock();
    for line in g.printed() {
        let _ = std::io::Write::write_all(&mut err, line.as_bytes());
    }
}

/// Copies the output parameters of `instance` among `outputs` from its run `g` into `outs`
/// (a float's one value, a triple's three, per vertex).
fn read_outputs(
    g: &GridContext<'_>,
    instance: &ShaderInstance,
    outputs: &[(String, usize)],
    outs: &mut [Vec<f32>],
) {
    for ((name, w), out) in outputs.iter().zip(outs.iter_mut()) {
        let Some(value) = instance.output(name).and(g.param(name)) else { continue };
        let num = value.num();
        for (i, lane) in out.chunks_exact_mut(*w).enumerate() {
            if *w == 1 {
                lane[0] = num.f(i);
            } else {
                lane.copy_from_slice(&num.v3(i));
            }
        }
    }
}

/// `dPdu`, `dPdv` of a grid by differences (central inside, one-sided at its edges).
fn differences(p: &[Vec3], nu: usize, nv: usize, du: f32, dv: f32) -> (Vec<Vec3>, Vec<Vec3>) {
    let d = |a: usize, b: usize, steps: f32, h: f32| {
        if steps == 0.0 || h == 0.0 { Vec3::ZERO } else { (p[b] - p[a]) / (steps * h) }
    };
    let mut dpdu = Vec::with_capacity(p.len());
    let mut dpdv = Vec::with_capacity(p.len());
    for k in 0..p.len() {
        let (i, j) = (k % nu, k / nu);
        let (a, b) = (i.saturating_sub(1), (i + 1).min(nu - 1));
        dpdu.push(d(j * nu + a, j * nu + b, (b - a) as f32, du));
        let (a, b) = (j.saturating_sub(1), (j + 1).min(nv - 1));
        dpdv.push(d(a * nu + i, b * nu + i, (b - a) as f32, dv));
    }
    (dpdu, dpdv)
}

/// A value given at the four corners of `(u, v)` in `[0, 1]^2`, bilinear at each point.
fn corners(width: usize, data: &[f32], u: &[f32], v: &[f32]) -> Value {
    let mut out = Vec::with_capacity(u.len() * width);
    for (&u, &v) in u.iter().zip(v) {
        for c in 0..width {
            let at = |k: usize| data.get(k * width + c).copied().unwrap_or(0.0);
            let bottom = at(0) * (1.0 - u) + at(1) * u;
            let top = at(2) * (1.0 - u) + at(3) * u;
            out.push(bottom * (1.0 - v) + top * v);
        }
    }
    Value::Num(Num { w: width, varying: true, data: out })
}

/// The scene's lights as the machine asks for them: the native lights (their `L` from the
/// light to the point, `Cl` arriving, as the native shading computes it, unshadowed), then
/// the light shaders run on the machine.
struct GridLights<'s> {
    native: &'s Shader,
    camera_to_world: Mat4,
    world_to_camera: Mat,
    shaders: ShaderLights,
    /// The light shaders' texture callback (issue #32).
    textures: Option<crate::sltex::SlTextures>,
}

impl Lights for GridLights<'_> {
    fn lights(&mut self, q: &LightQuery<'_>) -> Result<Vec<LightSample>, ExecError> {
        let n = q.nu * q.nv;
        let mut out = Vec::new();
        // Native lights have no category: an `illuminance` asking for one skips them.
        if q.category.is_empty() {
            let ambient = self.native.ambient();
            if ambient != Vec3::ZERO {
                out.push(LightSample {
                    ambient: true,
                    l: Num::zeros(3, true, n),
                    cl: Num::uniform(&ambient.to_array()).to_varying(n),
                    ol: Num::zeros(3, true, n),
                    lit: q.mask.on.clone(),
                    outputs: Vec::new(),
                });
            }
            let w2c = Mat4::from_cols_array(&self.world_to_camera);
            let count = self.native.direct_lights();
            let mut samples: Vec<LightSample> = (0..count)
                .map(|_| LightSample {
                    ambient: false,
                    l: Num::zeros(3, true, n),
                    cl: Num::zeros(3, true, n),
                    ol: Num::zeros(3, true, n),
                    lit: vec![false; n],
                    outputs: Vec::new(),
                })
                .collect();
            for &i in &q.mask.idx {
                let i = i as usize;
                let p = self.camera_to_world.transform_point3(Vec3::from(q.p.v3(i)));
                for (k, arriving) in self.native.light_vectors(p).enumerate() {
                    if let (Some((l, cl)), Some(s)) = (arriving, samples.get_mut(k)) {
                        let l = w2c.transform_vector3(l);
                        s.l.lane_mut(i).copy_from_slice(&l.to_array());
                        s.cl.lane_mut(i).copy_from_slice(&cl.to_array());
                        s.lit[i] = true;
                    }
                }
            }
            out.append(&mut samples);
        }
        let textures =
            self.textures.as_mut().map(|t| t as &mut dyn reyes_scene::sl::exec::Textures);
        out.append(&mut self.shaders.lights_with(q, textures)?);
        Ok(out)
    }
}

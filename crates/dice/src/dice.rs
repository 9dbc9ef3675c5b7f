//! Dice stage: evaluate, shade and project a patch's vertex grid, and emit its micropolygons.
//!
//! Invariants: vertex `k` of the micropolygon of grid cell `(i, j)` is grid vertex
//! `(i,j), (i+1,j), (i+1,j+1), (i,j+1)` for `k = 0..4`, stored as (raster x, raster y,
//! eye z); no vertex with `z <= 0` is ever projected; an emitted micropolygon has every
//! vertex finite with `z >= hither/2`, is not entirely in front of hither nor entirely
//! beyond yon, carries `HITHER_YON_CROSSING` iff some vertex is outside `[hither, yon]`,
//! and touches at least one bucket. Emission order is grid order, so it is deterministic.

use glam::{Mat3, Mat4, Vec3};
use reyes_hider::{Micropolygon, flags};

use crate::DiceError;
use crate::bucket::Bucketer;
use crate::camera::CameraSetup;
use crate::shade::Shader;
use crate::shapes::Surface;
use crate::split::Patch;

/// Largest number of micropolygons: bucket lists index them with `u32`.
pub(crate) const MAX_MICROPOLYGONS: usize = u32::MAX as usize;

/// One object's transforms, shading and flag bits.
#[derive(Debug, Clone)]
pub(crate) struct ObjectContext {
    /// Object to world, for points.
    pub to_world: Mat4,
    /// Object to world, for normals (inverse transpose up to a positive factor).
    pub normal_to_world: Mat3,
    /// Shader of the object's material.
    pub shader: Shader,
    /// Flag bits every micropolygon of the object carries (`OPAQUE`, `MATTE`).
    pub flags: u32,
}

/// One shaded, projected grid vertex.
#[derive(Debug, Clone, Copy)]
struct GridVertex {
    /// Raster x, raster y, eye z (x and y are NaN when z is not positive).
    v: [f32; 3],
    color: [f32; 3],
    trans: [f32; 3],
}

/// Where micropolygons go, with the running counts.
#[derive(Debug, Clone)]
pub(crate) struct Emitter {
    /// Emitted micropolygons.
    pub mpolys: Vec<Micropolygon>,
    /// Their bucket lists.
    pub bucketer: Bucketer,
    /// Diced micropolygons dropped (near the eye, outside `[hither, yon]`, off every bucket).
    pub culled: u64,
    /// Emitted micropolygons flagged `HITHER_YON_CROSSING`.
    pub crossing: u64,
    /// Depths: vertices nearer than `near` are not kept.
    hither: f32,
    yon: f32,
    near: f32,
    scratch: Vec<GridVertex>,
}

impl Emitter {
    /// An empty emitter dropping vertices nearer than `near` (`hither / 2`).
    pub fn new(bucketer: Bucketer, hither: f32, yon: f32, near: f32) -> Emitter {
        Emitter {
            mpolys: Vec::new(),
            bucketer,
            culled: 0,
            crossing: 0,
            hither,
            yon,
            near,
            scratch: Vec::new(),
        }
    }

    /// Dice `patch` of `surface` into `nu x nv` micropolygons, shade, project and bucket them.
    pub fn dice(
        &mut self,
        camera: &CameraSetup,
        object: &ObjectContext,
        surface: &Surface,
        patch: &Patch,
        (nu, nv): (u32, u32),
    ) -> Result<(), DiceError> {
        let (nu, nv) = (nu as usize, nv as usize);
        let world_to_camera = camera.world_to_camera();
        let mut grid = std::mem::take(&mut self.scratch);
        grid.clear();
        grid.reserve((nu + 1) * (nv + 1));
        for j in 0..=nv {
            let v = Patch::at(patch.v, j, nv);
            for i in 0..=nu {
                let u = Patch::at(patch.u, i, nu);
                let sp = surface.eval(u, v);
                let p_world = object.to_world.project_point3(sp.p);
                let n_world = object.normal_to_world * sp.n;
                let p_camera = world_to_camera.transform_point3(p_world);
                let v_raster = if p_camera.is_finite() && p_camera.z > 0.0 {
                    let r = camera.eye_to_raster(p_camera);
                    [r.x, r.y, p_camera.z]
                } else {
                    [f32::NAN, f32::NAN, p_camera.z]
                };
                let (color, trans) = object.shader.shade(p_world, n_world, sp.tint);
                grid.push(GridVertex { v: v_raster, color, trans });
            }
        }
        let row = nu + 1;
        let mut result = Ok(());
        'cells: for j in 0..nv {
            for i in 0..nu {
                let corners =
                    [j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i];
                let quad = corners.map(|c| grid[c]);
                if let Err(e) = self.emit(&quad, object.flags) {
                    result = Err(e);
                    break 'cells;
                }
            }
        }
        self.scratch = grid;
        result
    }

    /// Classify one micropolygon against the depth limits and buckets, and keep it or drop it.
    fn emit(&mut self, quad: &[GridVertex; 4], object_flags: u32) -> Result<(), DiceError> {
        let z = quad.map(|g| g.v[2]);
        let usable = quad.iter().all(|g| g.v.iter().all(|c| c.is_finite()) && g.v[2] >= self.near);
        let all_near = z.iter().all(|&z| z < self.hither);
        let all_far = z.iter().all(|&z| z > self.yon);
        if !usable || all_near || all_far {
            self.culled += 1;
            return Ok(());
        }
        let crossing = z.iter().any(|&z| z < self.hither || z > self.yon);
        let mut flags = object_flags;
        if crossing {
            flags |= flags::HITHER_YON_CROSSING;
        }
        let mp = Micropolygon {
            v: quad.map(|g| g.v),
            speed: [[0.0; 3]; 4],
            color: quad.map(|g| g.color),
            trans: quad.map(|g| g.trans),
            flags,
            csg_tree: 0,
            csg_node: 0,
            glass_opacity: 0.0,
            time: [0.0, 1.0],
        };
        let Some(range) = self.bucketer.range(&mp) else {
            self.culled += 1;
            return Ok(());
        };
        if self.mpolys.len() >= MAX_MICROPOLYGONS {
            return Err(DiceError::TooManyMicropolygons { limit: MAX_MICROPOLYGONS as u64 });
        }
        self.bucketer.insert(self.mpolys.len() as u32, range);
        self.mpolys.push(mp);
        if crossing {
            self.crossing += 1;
        }
        Ok(())
    }
}

/// Per-object setup: transforms, shader and flags.
pub(crate) fn object_context(
    object: &reyes_scene::Object,
    lights: &[reyes_scene::Light],
    eye_world: Vec3,
) -> ObjectContext {
    let to_world = crate::xform::object_to_world(&object.transform);
    let shader = Shader::new(&object.material, lights, eye_world);
    let mut flags = 0;
    if shader.opaque() {
        flags |= flags::OPAQUE;
    }
    if object.matte {
        flags |= flags::MATTE;
    }
    ObjectContext {
        normal_to_world: crate::xform::normal_matrix(&to_world),
        to_world,
        shader,
        flags,
    }
}

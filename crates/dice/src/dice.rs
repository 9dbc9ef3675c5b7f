//! Dice stage: evaluate, shade and project a patch's vertex grid at every breakpoint of its
//! motion, and emit its micropolygons, one per segment between breakpoints.
//!
//! Invariants: vertex `k` of the micropolygon of grid cell `(i, j)` is grid vertex
//! `(i,j), (i+1,j), (i+1,j+1), (i,j+1)` for `k = 0..4`, stored as (raster x, raster y,
//! eye z); no vertex with `z <= 0` is ever projected; colours come from the geometry at
//! shutter open (time 0) and are the same in every segment. For a segment `[t_a, t_b]` an
//! emitted micropolygon has `v` = the positions at `t_a`, `speed` = positions at `t_b` minus
//! those at `t_a`, `time = [t_a, t_b]`, and `MOVING` iff some speed is non-zero or the segment
//! is not the whole shutter; every vertex is finite with `z >= hither/2` at both ends; it is
//! not entirely in front of hither at both ends nor entirely beyond yon at both ends; it
//! carries `HITHER_YON_CROSSING` iff some vertex is outside `[hither, yon]` at either end;
//! and it touches at least one bucket. Consecutive segments over which a micropolygon does
//! not move (bit for bit) are merged, so a still micropolygon is one record with time
//! `[0, 1]` and zero speed, exactly as without motion. Emission order is grid order, then
//! time order, so it is deterministic.

use glam::{Mat3, Vec3};
use reyes_hider::{Micropolygon, flags};

use crate::DiceError;
use crate::bucket::Bucketer;
use crate::camera::CameraSetup;
use crate::motion::{Placement, Pose};
use crate::hook::{VertexContext, VertexShader};
use crate::shade::Shader;
use crate::split::Patch;

/// Largest number of micropolygons: bucket lists index them with `u32`.
pub(crate) const MAX_MICROPOLYGONS: usize = u32::MAX as usize;

/// A vertex shader from [`crate::DiceOptions`], with where the dicer is.
#[derive(Clone, Copy)]
pub(crate) struct Hook<'a> {
    /// The shader.
    pub shader: &'a dyn VertexShader,
    /// Index of the object in the scene.
    pub object: usize,
    /// Index of the surface being diced.
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
}

/// One grid vertex at shutter open: position, and the shading used at every time.
#[derive(Debug, Clone, Copy)]
struct GridVertex {
    /// Raster x, raster y, eye z (x and y are NaN when z is not positive).
    v: [f32; 3],
    color: [f32; 3],
    trans: [f32; 3],
}

/// A micropolygon's colours, flags and labels, the same in every segment.
#[derive(Debug, Clone, Copy)]
struct Shade {
    color: [[f32; 3]; 4],
    trans: [[f32; 3]; 4],
    /// The object's flag bits and labels.
    labels: Labels,
}

/// A micropolygon's vertices at one time: raster x, raster y, eye z (x and y NaN where z is
/// not positive).
type Quad = [[f32; 3]; 4];

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
    /// Grid vertices at shutter open.
    grid: Vec<GridVertex>,
    /// Grid vertex positions at the later breakpoints (`[(b - 1) * vertices + vertex]`).
    later: Vec<[f32; 3]>,
    /// One cell's positions at each breakpoint, with the breakpoint's time.
    quads: Vec<(f32, Quad)>,
    /// Emitted micropolygons flagged `MOVING`.
    pub moving: u64,
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
            grid: Vec::new(),
            later: Vec::new(),
            quads: Vec::new(),
            moving: 0,
        }
    }

    /// Dice `patch` of a surface into `nu x nv` micropolygons at every breakpoint of its
    /// motion (`poses`, in time order, the first at time 0), shade at time 0, and emit and
    /// bucket one micropolygon per cell and segment (merging still segments).
    pub fn dice(
        &mut self,
        camera: &CameraSetup,
        object: &ObjectContext<'_>,
        poses: &[Pose<'_>],
        patch: &Patch,
        (nu, nv): (u32, u32),
    ) -> Result<(), DiceError> {
        let (nu, nv) = (nu as usize, nv as usize);
        let count = (nu + 1) * (nv + 1);
        let mut grid = std::mem::take(&mut self.grid);
        let mut later = std::mem::take(&mut self.later);
        grid.clear();
        grid.reserve(count);
        later.clear();
        later.reserve(count * poses.len().saturating_sub(1));
        let project = |p_camera: Vec3| {
            if p_camera.is_finite() && p_camera.z > 0.0 {
                let r = camera.eye_to_raster(p_camera);
                [r.x, r.y, p_camera.z]
            } else {
                [f32::NAN, f32::NAN, p_camera.z]
            }
        };
        for (b, pose) in poses.iter().enumerate() {
            for j in 0..=nv {
                let v = Patch::at(patch.v, j, nv);
                for i in 0..=nu {
                    let u = Patch::at(patch.u, i, nu);
                    if b == 0 {
                        // Shutter open: shade here (REYES shades once, before motion). The
                        // shader face-forwards the normal toward the eye (two-sided), which is
                        // what CSG needs: where a difference A - B shows B's surface through
                        // a hole in A, the eye sees B from B's inside, i.e. the outside of
                        // the result, whose outward normal there is B's inward one. The
                        // geometric (outward) normal itself is not stored: the orientation
                        // survives only in the vertex winding.
                        let sp = pose.surface.eval(u, v);
                        let (p_world, p_camera) = pose.moment.world_and_camera(sp.p);
                        let n_world = object.normal_to_world * sp.n;
                        let (color, trans) = match &object.hook {
                            None => object.shader.shade(p_world, n_world, sp.tint),
                            Some(hook) => hook.shader.shade(&VertexContext {
                                object: hook.object,
                                surface: hook.surface,
                                patch_u: patch.u,
                                patch_v: patch.v,
                                i: i as u32,
                                j: j as u32,
                                nu: nu as u32,
                                nv: nv as u32,
                                p_world,
                                n_world: n_world.normalize_or_zero(),
                                p_object: sp.p,
                                tint: sp.tint,
                            }),
                        };
                        grid.push(GridVertex { v: project(p_camera), color, trans });
                    } else {
                        let p_object = pose.surface.position(u, v);
                        later.push(project(pose.moment.world_and_camera(p_object).1));
                    }
                }
            }
        }
        let row = nu + 1;
        let mut result = Ok(());
        let mut quads = std::mem::take(&mut self.quads);
        'cells: for j in 0..nv {
            for i in 0..nu {
                let corners =
                    [j * row + i, j * row + i + 1, (j + 1) * row + i + 1, (j + 1) * row + i];
                let v = corners.map(|c| grid[c].v);
                let shade = Shade {
                    color: corners.map(|c| grid[c].color),
                    trans: corners.map(|c| grid[c].trans),
                    labels: object.labels,
                };
                let emitted =
                    if poses.len() == 1 {
                        // No motion: the whole shutter, still.
                        self.emit(&v, None, [0.0, 1.0], &shade)
                    } else {
                        quads.clear();
                        quads.push((0.0, v));
                        quads.extend(poses.iter().skip(1).enumerate().map(|(b, pose)| {
                            (pose.moment.t, corners.map(|c| later[b * count + c]))
                        }));
                        self.emit_segments(&quads, &shade)
                    };
                if let Err(e) = emitted {
                    result = Err(e);
                    break 'cells;
                }
            }
        }
        self.grid = grid;
        self.later = later;
        self.quads = quads;
        result
    }

    /// Emit one cell from its positions at each breakpoint (`(time, quad)`, in time order):
    /// one micropolygon per segment, runs of segments over which it is still merged.
    fn emit_segments(&mut self, quads: &[(f32, Quad)], shade: &Shade) -> Result<(), DiceError> {
        let n = quads.len();
        if quads.windows(2).all(|w| w[0].1 == w[1].1) {
            // Still over the whole shutter (or a single breakpoint).
            return match quads.first() {
                Some((_, q)) => self.emit(q, None, [0.0, 1.0], shade),
                None => Ok(()),
            };
        }
        let mut a = 0;
        while a + 1 < n {
            let mut b = a + 1;
            let still = quads[a].1 == quads[b].1;
            if still {
                while b + 1 < n && quads[b].1 == quads[b + 1].1 {
                    b += 1;
                }
            }
            let (from, to) = (&quads[a].1, (!still).then_some(&quads[b].1));
            self.emit(from, to, [quads[a].0, quads[b].0], shade)?;
            a = b;
        }
        Ok(())
    }

    /// Classify one micropolygon over its segment `time` (at `from` at the start, at `to` at
    /// the end, or at `from` throughout when `to` is `None`) against the depth limits and
    /// buckets, and keep it or drop it.
    #[inline(always)]
    fn emit(
        &mut self,
        from: &Quad,
        to: Option<&Quad>,
        time: [f32; 2],
        shade: &Shade,
    ) -> Result<(), DiceError> {
        let mut usable = true;
        let (mut zmin, mut zmax) = (f32::INFINITY, f32::NEG_INFINITY);
        for q in [Some(from), to].into_iter().flatten() {
            for p in q {
                usable &= p[0].is_finite() && p[1].is_finite() && p[2] >= self.near;
                zmin = zmin.min(p[2]);
                zmax = zmax.max(p[2]);
            }
        }
        usable &= zmax.is_finite();
        // All in front of hither, or all beyond yon, at both ends.
        if !usable || zmax < self.hither || zmin > self.yon {
            self.culled += 1;
            return Ok(());
        }
        let crossing = zmin < self.hither || zmax > self.yon;
        let mut flags = shade.labels.flags;
        if crossing {
            flags |= flags::HITHER_YON_CROSSING;
        }
        let mut speed = [[0.0_f32; 3]; 4];
        if let Some(to) = to {
            for (s, (p, q)) in speed.iter_mut().zip(from.iter().zip(to)) {
                *s = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            }
        }
        let moves = speed.iter().flatten().any(|&c| c != 0.0);
        if moves || time != [0.0, 1.0] {
            flags |= flags::MOVING;
        }
        let mp = Micropolygon {
            v: *from,
            speed,
            color: shade.color,
            trans: shade.trans,
            flags,
            csg_tree: shade.labels.csg_tree,
            csg_node: shade.labels.csg_node,
            glass_opacity: shade.labels.glass_opacity,
            time,
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
        if flags & flags::MOVING != 0 {
            self.moving += 1;
        }
        Ok(())
    }
}

/// Per-object setup: shading (seen from `eye_world`, with the object placed by `open`, its
/// placement at shutter open), flags, and the CSG label `csg` (`(tree index, slot id)` of
/// a CSG operand, from [`crate::CsgSetup::leaf`]).
pub(crate) fn object_context(
    object: &reyes_scene::Object,
    lights: &[reyes_scene::Light],
    eye_world: Vec3,
    open: &Placement,
    csg: Option<(u16, u16)>,
) -> ObjectContext<'static> {
    let shader = Shader::new(&object.material, lights, eye_world);
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
    let labels = Labels { flags, csg_tree, csg_node, glass_opacity };
    ObjectContext { normal_to_world: open.normal_to_world(), shader, labels, hook: None }
}

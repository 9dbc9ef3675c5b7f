//! Geometric primitive requests: the current attributes and transformation turn each into
//! one model object (a mesh, a patch or a quadric), with deformation keys when it stands in a
//! motion block.
//!
//! Invariants: a primitive inside a motion block has one request per time, all of one kind;
//! a primitive with control points deforms through them, a quadric whose parameters change
//! takes its parameters at shutter open (a warning says so); nothing is emitted for a frame
//! that is not wanted, but every request is still checked.

use reyes_scene::{Object, PatchType, Shape, Wrap};

use super::build::{ObjectAttributes, Origin};
use super::frame::Machine;
use super::geometry::{self, PolyMesh};
use super::shaders::{SurfaceResult, material};
use crate::{Request, RequestKind as K, RibError};

/// The arguments of a quadric request, in order.
fn args(r: &Request, n: usize) -> Vec<f32> {
    (0..n).map(|i| r.float(i).unwrap_or(0.0)).collect()
}

impl Machine {
    /// A geometric primitive, with `motion = (times, requests)` inside a motion block.
    pub(super) fn primitive(
        &mut self,
        r: &Request,
        motion: Option<(&[f32], &[Request])>,
    ) -> Result<(), RibError> {
        if r.kind == K::Geometry {
            // Built-in geometry has no parameters to move: one shape over the shutter.
            return self.geometry(r);
        }
        let (shape, deform) = match motion {
            None => (self.shape(r)?, Vec::new()),
            Some((times, requests)) => {
                let mut shapes = Vec::with_capacity(requests.len());
                for q in requests {
                    shapes.push(self.shape(q)?);
                }
                let first = shapes[0].clone();
                let points: Vec<Option<Vec<[f32; 3]>>> =
                    shapes.iter().map(control_points).collect();
                let deform = match points.first() {
                    Some(Some(p0)) => {
                        let mut keys = Vec::with_capacity(times.len());
                        for (k, (t, p)) in times.iter().zip(&points).enumerate() {
                            match p {
                                Some(p)
                                    if p.len() == p0.len() && same_topology(&first, &shapes[k]) =>
                                {
                                    keys.push((*t, p.clone()));
                                }
                                _ => {
                                    return Err(requests[k].error(
                                        "a deforming primitive must keep its topology and point count at every time",
                                    ));
                                }
                            }
                        }
                        keys
                    }
                    _ => {
                        if shapes.iter().any(|s| *s != first) {
                            let w = r.warning(
                                "motion of a quadric's parameters is not supported: its shape at shutter open is used",
                            );
                            self.warn_once(format!("quadric motion {}", r.name()), w);
                        }
                        Vec::new()
                    }
                };
                (first, deform)
            }
        };
        let Some(shape) = shape else { return Ok(()) };
        self.emit(r, shape, deform)
    }

    /// `Geometry "teapot"`: PRMan's and BMRT's built-in teapot, 32 bicubic Bezier patches
    /// ([`super::teapot`]) under the current transformation and attributes (not the current
    /// `Basis`: the data are Bezier nets). Other types are skipped with a warning.
    fn geometry(&mut self, r: &Request) -> Result<(), RibError> {
        match r.string(0).unwrap_or_default() {
            "teapot" => {
                for net in super::teapot::patches() {
                    let shape = Shape::PatchMesh {
                        kind: PatchType::Bicubic,
                        nu: 4,
                        nv: 4,
                        uwrap: Wrap::Nonperiodic,
                        vwrap: Wrap::Nonperiodic,
                        points: net.to_vec(),
                        ubasis: reyes_scene::Basis::Bezier,
                        ustep: Some(3),
                        vbasis: reyes_scene::Basis::Bezier,
                        vstep: Some(3),
                    };
                    self.emit(r, shape, Vec::new())?;
                }
                Ok(())
            }
            other => {
                let w = r.warning(format!(
                    "geometry type {} is not supported (\"teapot\" is): skipped",
                    crate::error::quote(other)
                ));
                self.warn_once(format!("geometry {other}"), w);
                Ok(())
            }
        }
    }

    /// The object of `shape` (with its deformation keys), made by the request `r` under the
    /// current attributes and transformation, added to the frame. A primitive under a
    /// singular transformation (`Scale 0 1 1`) has no surface to render: it is skipped with
    /// a warning (an error under `--strict`).
    fn emit(
        &mut self,
        r: &Request,
        shape: Shape,
        deform: Vec<(f32, Vec<[f32; 3]>)>,
    ) -> Result<(), RibError> {
        let Some(shutter) = self.build.as_ref().filter(|b| b.wanted).map(|b| b.options.shutter)
        else {
            return Ok(());
        };
        if let Some(det) = singular(&self.to_world(), shutter) {
            return self.tolerate(
                &r.at,
                r.name(),
                format!(
                    "the transformation is singular (determinant {})",
                    super::xform::show(det as f32)
                ),
                "the primitive is skipped",
            );
        }
        let mut a = self.attributes.clone();
        // A level of detail out of range is not drawn; in a transition it blends by opacity.
        if a.detail_weight <= 0.0 {
            return Ok(());
        }
        a.opacity = a.opacity.map(|o| o * a.detail_weight);
        let (cs, colors_constant) = match &shape {
            Shape::Mesh { .. } | Shape::SubdivisionMesh { .. } => {
                (a.color, self.constant_color(r)?)
            }
            // A primitive's own Cs replaces the attribute colour, as the Specification has
            // it: the material is white under per-curve, per-point or per-field colours.
            Shape::Curves { colors: Some(_), .. }
            | Shape::Points { colors: Some(_), .. }
            | Shape::Blobby { colors: Some(_), .. } => ([1.0; 3], None),
            Shape::Curves { .. } | Shape::Points { .. } | Shape::Blobby { .. } => {
                (a.color, self.constant_color(r)?)
            }
            _ => (a.color, None),
        };
        let cs = colors_constant.unwrap_or(cs);
        let report = a
            .surface
            .at
            .as_ref()
            .is_some_and(|at| self.warned.insert(format!("surface params {at}")));
        let to_world = self.to_world();
        let sl = self.object_shaders(&a, r, &to_world.at(f32::NEG_INFINITY))?;
        let has = |f: fn(&reyes_scene::ObjectShaders) -> bool| sl.as_deref().is_some_and(f);
        let mat = match material(&a.surface, cs, a.opacity, &mut self.warnings, report) {
            SurfaceResult::Material(m) => m,
            // A shading-language surface: the stand-in material is kept for what the
            // renderer reads of it besides shading (none of its colours are used).
            SurfaceResult::Unknown(m, _) if has(|s| s.surface.is_some()) => m,
            SurfaceResult::Unknown(m, name) => {
                if self.options.strict {
                    let at = a.surface.at.clone().unwrap_or_else(|| r.at.clone());
                    return Err(RibError::Request {
                        at,
                        request: "Surface",
                        message: format!("unknown surface shader \"{name}\" (--strict)"),
                    });
                }
                let at = a.surface.at.clone().unwrap_or_else(|| r.at.clone());
                let w = crate::Warning {
                    at,
                    message: format!(
                        "Surface: unknown shader \"{name}\": stands in as plastic on the primitive's Cs and Os"
                    ),
                };
                self.warn_once(format!("surface {name}"), w);
                m
            }
        };
        let mut object = Object::new(shape, mat);
        let (reader, search) = (&self.reader, &self.frame_options.search);
        let not_found = std::cell::RefCell::new(Vec::new());
        let looks = super::shaders::lookdev(
            &a.surface,
            &a.displacement,
            a.displacement_bound,
            a.repeat,
            |name, at, request| {
                let w = &mut not_found.borrow_mut();
                super::archives::texture_path(search, reader, name, at, request, w)
            },
            &mut self.warnings,
            report,
        );
        for w in not_found.into_inner() {
            let key = w.to_string();
            self.warn_once(key, w);
        }
        match looks {
            Ok((maps, displacement)) => {
                object.maps = maps;
                object.displacement = displacement;
            }
            Err(_) if has(|s| s.displacement.is_some()) => object.maps = Default::default(),
            Err(name) => {
                let at = a.displacement.at.clone().unwrap_or_else(|| r.at.clone());
                if self.options.strict {
                    return Err(RibError::Request {
                        at,
                        request: "Displacement",
                        message: format!("unknown displacement shader \"{name}\" (--strict)"),
                    });
                }
                let w = crate::Warning {
                    at,
                    message: format!(
                        "Displacement: unknown shader \"{name}\": the primitive is not displaced"
                    ),
                };
                self.warn_once(format!("displacement {name}"), w);
            }
        }
        object.name = a.name.clone().unwrap_or_default();
        object.matte = a.matte;
        let attributes =
            ObjectAttributes { shading_rate: a.shading_rate, lights: a.lights_on.clone() };
        object.flatness = a.flatness;
        object.motion_factor = a.motion_factor;
        object.focus_factor = a.focus_factor;
        object.one_sided = a.sides == 1;
        if a.smooth {
            object.interpolation = reyes_scene::Interpolation::Gouraud;
        }
        object.shaders = sl;
        if let Some(area) = &a.area_light {
            self.emitter(r, area, &mut object, &to_world);
        }
        let origin = Origin { at: r.at.clone(), request: r.name() };
        if let Some(b) = &mut self.build {
            b.add_object(object, &to_world, deform, attributes, origin);
        }
        Ok(())
    }

    /// A constant `Cs` on a mesh primitive replaces the attribute colour.
    fn constant_color(&self, r: &Request) -> Result<Option<[f32; 3]>, RibError> {
        let Some(p) = r.param("Cs") else { return Ok(None) };
        if p.decl.as_ref().is_some_and(|d| d.class == crate::Class::Constant) {
            return match p.floats() {
                Some([r, g, b]) => Ok(Some([*r, *g, *b])),
                _ => Err(r.param_error(p, "a constant colour is 3 numbers")),
            };
        }
        Ok(None)
    }

    /// The model shape of one primitive request; None for a primitive that is skipped.
    fn shape(&mut self, r: &Request) -> Result<Option<Shape>, RibError> {
        let shape = match r.kind {
            K::Sphere => {
                let a = args(r, 4);
                geometry::sphere(a[0], a[1], a[2], a[3])
            }
            K::Cylinder => {
                let a = args(r, 4);
                Shape::Cylinder { radius: a[0], zmin: a[1], zmax: a[2], thetamax: a[3] }
            }
            K::Cone => {
                let a = args(r, 3);
                Shape::Cone { height: a[0], radius: a[1], thetamax: a[2] }
            }
            K::Disk => {
                let a = args(r, 3);
                Shape::Disk { height: a[0], radius: a[1], thetamax: a[2] }
            }
            K::Paraboloid => {
                let a = args(r, 4);
                Shape::Paraboloid { rmax: a[0], zmin: a[1], zmax: a[2], thetamax: a[3] }
            }
            K::Torus => {
                let a = args(r, 5);
                Shape::Torus {
                    major_radius: a[0],
                    minor_radius: a[1],
                    phimin: a[2],
                    phimax: a[3],
                    thetamax: a[4],
                }
            }
            K::Polygon => {
                let n = polygon_vertices(r)?;
                self.mesh(r, None, &[n as i32], None)?
            }
            K::GeneralPolygon => {
                let nv = r.ints(0).unwrap_or(&[]);
                self.mesh(r, Some(&[nv.len() as i32]), nv, None)?
            }
            K::PointsPolygons => self.mesh(r, None, r.ints(0).unwrap_or(&[]), r.ints(1))?,
            K::PointsGeneralPolygons => {
                let (nl, nv) = (r.ints(0).unwrap_or(&[]), r.ints(1).unwrap_or(&[]));
                self.mesh(r, Some(nl), nv, r.ints(2))?
            }
            K::Patch => {
                let kind = patch_type(r, 0)?;
                let n = if kind == PatchType::Bilinear { 2 } else { 4 };
                let points =
                    self.patch_points(r, (n, Wrap::Nonperiodic), (n, Wrap::Nonperiodic))?;
                if kind == PatchType::Bilinear {
                    Shape::BilinearPatch { points: [points[0], points[1], points[2], points[3]] }
                } else {
                    let n = n as u32;
                    self.patch_mesh(kind, n, Wrap::Nonperiodic, n, Wrap::Nonperiodic, points)
                }
            }
            K::PatchMesh => {
                let kind = patch_type(r, 0)?;
                let count = |i: usize| -> Result<u32, RibError> {
                    let n = r.int(i).unwrap_or(0);
                    u32::try_from(n).ok().filter(|&n| n >= 1).ok_or_else(|| {
                        r.error(format!(
                            "{} must be at least 1, got {n}",
                            if i == 1 { "nu" } else { "nv" }
                        ))
                    })
                };
                let (nu, nv) = (count(1)?, count(3)?);
                let (uwrap, vwrap) = (self.wrap(r, 2)?, self.wrap(r, 4)?);
                let points = self.patch_points(r, (nu as usize, uwrap), (nv as usize, vwrap))?;
                self.patch_mesh(kind, nu, uwrap, nv, vwrap, points)
            }
            K::NuPatch => {
                let int = |i: usize| r.int(i).unwrap_or(0).max(0) as u32;
                let (nu, uorder, nv, vorder) = (int(0), int(1), int(5), int(6));
                let n = nu as usize * nv as usize;
                let points: Vec<[f32; 4]> = match (r.param("Pw"), r.param("P")) {
                    (Some(p), _) => {
                        let v = p.floats().filter(|v| v.len() == 4 * n).ok_or_else(|| {
                            r.param_error(p, format!("needs nu x nv = {n} points of 4 numbers"))
                        })?;
                        v.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
                    }
                    (None, Some(_)) => geometry::positions(r, n)?
                        .into_iter()
                        .map(|p| [p[0], p[1], p[2], 1.0])
                        .collect(),
                    (None, None) => return Err(r.error("needs \"P\" or \"Pw\" positions")),
                };
                geometry::unused_primvars(r, &["P", "Pw"], &mut self.warnings);
                Shape::NuPatch {
                    nu,
                    uorder,
                    uknot: r.floats(2).unwrap_or(&[]).to_vec(),
                    umin: r.float(3).unwrap_or(0.0),
                    umax: r.float(4).unwrap_or(1.0),
                    nv,
                    vorder,
                    vknot: r.floats(7).unwrap_or(&[]).to_vec(),
                    vmin: r.float(8).unwrap_or(0.0),
                    vmax: r.float(9).unwrap_or(1.0),
                    points,
                    trim: self.attributes.trim.as_ref().clone(),
                    trim_outside: self.attributes.trim_outside,
                }
            }
            K::Hyperboloid => {
                let p = |i: usize| {
                    let v = r.floats(i).unwrap_or(&[0.0; 3]);
                    [v[0], v[1], v[2]]
                };
                Shape::Hyperboloid {
                    point1: p(0),
                    point2: p(1),
                    thetamax: r.float(2).unwrap_or(360.0),
                }
            }
            K::Curves => self.curves(r)?,
            K::Points => self.points(r)?,
            K::Blobby => self.blobby(r)?,
            K::SubdivisionMesh => match super::subdivision::shape(r, &mut self.warnings)? {
                Some(shape) => shape,
                None => return Ok(None),
            },
            _ => return self.unsupported(r, "this primitive is not supported"),
        };
        Ok(Some(shape))
    }

    /// The control points of a patch request of `nu` by `nv` points, each with its wrap
    /// mode: `P`, `Pw` of weight 1 (rational patch meshes are not in the model), or the
    /// height field `Pz`, whose x and y are the mesh's surface parameters: point `(i, j)` at
    /// `(i / (nu - 1), j / (nv - 1))`, spread uniformly over [0, 1] (`i / nu` along a
    /// periodic direction, whose last point comes back to the first).
    fn patch_points(
        &mut self,
        r: &Request,
        (nu, uwrap): (usize, Wrap),
        (nv, vwrap): (usize, Wrap),
    ) -> Result<Vec<[f32; 3]>, RibError> {
        let n = nu * nv;
        if let Some(p) = r.param("Pw")
            && p.floats().is_some_and(|v| v.chunks_exact(4).any(|c| c[3] != 1.0))
        {
            return Err(r.param_error(
                p,
                "rational patches are not supported (weights other than 1); use NuPatch",
            ));
        }
        let points = match (r.param("P"), r.param("Pw"), r.param("Pz")) {
            (None, None, Some(pz)) => {
                let counts = geometry::Counts { uniform: 1, vertex: n, facevarying: n };
                let (_, z) = geometry::groups(r, pz, 1, counts)?;
                let spread = |k: usize, count: usize, wrap: Wrap| match wrap {
                    Wrap::Periodic => k as f32 / count as f32,
                    Wrap::Nonperiodic => k as f32 / (count - 1).max(1) as f32,
                };
                z.iter()
                    .enumerate()
                    .map(|(k, &z)| [spread(k % nu, nu, uwrap), spread(k / nu, nv, vwrap), z])
                    .collect()
            }
            _ => geometry::positions(r, n)?,
        };
        geometry::unused_primvars(r, &["P", "Pw", "Pz"], &mut self.warnings);
        Ok(points)
    }

    fn wrap(&mut self, r: &Request, i: usize) -> Result<Wrap, RibError> {
        let which = if i == 2 { "uwrap" } else { "vwrap" };
        match r.string(i).unwrap_or_default() {
            "nonperiodic" => Ok(Wrap::Nonperiodic),
            "periodic" => Ok(Wrap::Periodic),
            "nowrap" => {
                self.tolerate(
                    &r.at,
                    r.name(),
                    format!("{which} \"nowrap\" is not a wrap mode of the Specification"),
                    "read as \"nonperiodic\"",
                )?;
                Ok(Wrap::Nonperiodic)
            }
            other => Err(r.error(format!(
                "{which} must be \"periodic\" or \"nonperiodic\", got \"{other}\""
            ))),
        }
    }

    /// A patch mesh under the current `Basis`.
    fn patch_mesh(
        &self,
        kind: PatchType,
        nu: u32,
        uwrap: Wrap,
        nv: u32,
        vwrap: Wrap,
        points: Vec<[f32; 3]>,
    ) -> Shape {
        let (ubasis, ustep, vbasis, vstep) = self.attributes.basis;
        Shape::PatchMesh {
            kind,
            nu,
            nv,
            uwrap,
            vwrap,
            points,
            ubasis,
            ustep: Some(ustep),
            vbasis,
            vstep: Some(vstep),
        }
    }

    fn unsupported(&mut self, r: &Request, why: &str) -> Result<Option<Shape>, RibError> {
        let w = r.warning(format!("{why}: skipped"));
        self.warnings.push(w);
        Ok(None)
    }

    /// A polygon mesh (see [`geometry::poly_mesh`] for the arguments) as a model mesh.
    fn mesh(
        &mut self,
        r: &Request,
        nloops: Option<&[i32]>,
        nvertices: &[i32],
        vertices: Option<&[i32]>,
    ) -> Result<Shape, RibError> {
        let mut mesh: PolyMesh = geometry::poly_mesh(r, nloops, nvertices, vertices)?;
        geometry::check_primvars(r, &mesh)?;
        let (mut normals, st) = geometry::vertex_normals_and_st(r, &mesh)?;
        // N dropped after its own warning: not reported again as unused.
        let mut n_dropped = false;
        if let (Some(n), Some(p)) = (normals.as_mut(), r.param("N")) {
            let at = r.param_location(p);
            let what = |count: usize, first: usize| {
                let s = if count == 1 { "" } else { "s" };
                format!("\"N\": {count} normal{s} zero or not finite (the first at point {first})")
            };
            match geometry::repair_normals(&mesh, n) {
                geometry::NormalRepair::Sound => {}
                geometry::NormalRepair::Recomputed { count, first } => {
                    self.tolerate(
                        &at,
                        r.name(),
                        what(count, first),
                        "recomputed from the faces around their points",
                    )?;
                }
                geometry::NormalRepair::Dropped { count, first } => {
                    self.tolerate(
                        &at,
                        r.name(),
                        what(count, first),
                        "the faces around a point have no area to take a normal from: N is dropped for this mesh, which shades by its faces' own normals",
                    )?;
                    normals = None;
                    n_dropped = true;
                }
            }
        }
        let (_, colors) = geometry::mesh_colors(r, &mut mesh)?;
        // Per-face colours unweld the points; the vertex normals and st do not follow them.
        let unwelded = geometry::colors_unweld(r);
        let used: &[&str] = match (&normals, &st, unwelded) {
            (_, _, true) => &["P", "Pw", "Cs"],
            (Some(_), Some(_), false) => &["P", "Pw", "Cs", "N", "st"],
            (Some(_), None, false) => &["P", "Pw", "Cs", "N"],
            (None, Some(_), false) => &["P", "Pw", "Cs", "st"],
            (None, None, false) => &["P", "Pw", "Cs"],
        };
        let used: Vec<&str> = used.iter().copied().chain(n_dropped.then_some("N")).collect();
        geometry::unused_primvars(r, &used, &mut self.warnings);
        let mut shape = geometry::to_model_mesh(r, mesh, colors)?;
        if !unwelded && let Shape::Mesh { normals: n, st: s, .. } = &mut shape {
            *n = normals;
            *s = st;
        }
        Ok(shape)
    }
}

/// The determinant of the first singular matrix of `to_world` over the shutter `(open,
/// close)`, if any: the keys the object will carry, taken as the scene model stores them
/// (single precision) and judged by the model's own rule (|determinant| <= 1e-12).
fn singular(to_world: &super::xform::Xform, (open, close): (f32, f32)) -> Option<f64> {
    super::build::fit_keys(&to_world.keys, open, close).iter().find_map(|(_, m)| {
        let stored = glam::DMat4::from_cols_array(&m.to_cols_array().map(|x| f64::from(x as f32)));
        let det = stored.determinant();
        (det.abs() <= 1e-12).then_some(det)
    })
}

/// The vertex count of a `Polygon`: its `P` (or `Pw`) values per point.
fn polygon_vertices(r: &Request) -> Result<usize, RibError> {
    let (p, per) = match (r.param("P"), r.param("Pw")) {
        (Some(p), _) => (p, 3),
        (None, Some(p)) => (p, 4),
        _ => return Err(r.error("needs \"P\" (or \"Pw\") positions")),
    };
    let n = p.floats().map_or(0, <[f32]>::len);
    if n % per != 0 || n / per < 3 {
        return Err(
            r.param_error(p, format!("needs at least 3 points of {per} numbers, got {n} numbers"))
        );
    }
    Ok(n / per)
}

/// `Patch` and `PatchMesh`'s type argument.
fn patch_type(r: &Request, i: usize) -> Result<PatchType, RibError> {
    match r.string(i).unwrap_or_default() {
        "bilinear" => Ok(PatchType::Bilinear),
        "bicubic" => Ok(PatchType::Bicubic),
        other => Err(r.error(format!("type must be \"bilinear\" or \"bicubic\", got \"{other}\""))),
    }
}

/// The control points of a shape that deforms through them (NURBS: the points, weights
/// divided out; the shape keeps its weights).
fn control_points(shape: &Option<Shape>) -> Option<Vec<[f32; 3]>> {
    match shape.as_ref()? {
        Shape::Mesh { points, .. }
        | Shape::PatchMesh { points, .. }
        | Shape::SubdivisionMesh { points, .. }
        | Shape::Curves { points, .. }
        | Shape::Points { points, .. } => Some(points.clone()),
        Shape::BilinearPatch { points } => Some(points.to_vec()),
        Shape::NuPatch { points, .. } => {
            Some(points.iter().map(|p| [p[0] / p[3], p[1] / p[3], p[2] / p[3]]).collect())
        }
        _ => None,
    }
}

/// Two shapes of one kind with the same connectivity (everything but their points equal).
fn same_topology(a: &Option<Shape>, b: &Option<Shape>) -> bool {
    let strip = |s: &Shape| -> Shape {
        let mut s = s.clone();
        match &mut s {
            Shape::Mesh { points, colors, .. } => {
                points.clear();
                *colors = None;
            }
            Shape::PatchMesh { points, .. }
            | Shape::Curves { points, .. }
            | Shape::Points { points, .. } => points.clear(),
            Shape::SubdivisionMesh { points, colors, .. } => {
                points.clear();
                *colors = None;
            }
            Shape::BilinearPatch { points } => *points = [[0.0; 3]; 4],
            Shape::NuPatch { points, .. } => {
                for p in points.iter_mut() {
                    p[0] = 0.0;
                    p[1] = 0.0;
                    p[2] = 0.0;
                }
            }
            _ => {}
        }
        s
    };
    match (a, b) {
        (Some(a), Some(b)) => strip(a) == strip(b),
        _ => false,
    }
}

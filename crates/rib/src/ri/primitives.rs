//! Geometric primitive requests: the current attributes and transformation turn each into
//! one model object (a mesh, a patch or a quadric), with deformation keys when it stands in a
//! motion block.
//!
//! Invariants: a primitive inside a motion block has one request per time, all of one kind;
//! a primitive with control points deforms through them, a quadric whose parameters change
//! takes its parameters at shutter open (a warning says so); nothing is emitted for a frame
//! that is not wanted, but every request is still checked.

use reyes_scene::{Object, Shape};

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
        let wanted = self.build.as_ref().is_some_and(|b| b.wanted);
        if !wanted {
            return Ok(());
        }
        let a = self.attributes.clone();
        let (cs, colors_constant) = match &shape {
            Shape::Mesh { .. } => (a.color, self.constant_color(r)?),
            _ => (a.color, None),
        };
        let cs = colors_constant.unwrap_or(cs);
        let report = a
            .surface
            .at
            .as_ref()
            .is_some_and(|at| self.warned.insert(format!("surface params {at}")));
        let mat = match material(&a.surface, cs, a.opacity, &mut self.warnings, report) {
            SurfaceResult::Material(m) => m,
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
        object.name = a.name.clone().unwrap_or_default();
        object.matte = a.matte;
        let attributes =
            ObjectAttributes { shading_rate: a.shading_rate, lights: a.lights_on.clone() };
        if a.sides == 1 {
            let w = r.warning("Sides 1 is not supported yet: the primitive is two-sided");
            self.warn_once("sides 1", w);
        }
        let to_world = self.to_world();
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
                self.mesh(r, &[1], &[n as i32], None)?
            }
            K::GeneralPolygon => {
                let nv = r.ints(0).unwrap_or(&[]).to_vec();
                self.mesh(r, &[nv.len() as i32], &nv, None)?
            }
            K::PointsPolygons => {
                let nv = r.ints(0).unwrap_or(&[]).to_vec();
                let ones = vec![1; nv.len()];
                self.mesh(r, &ones, &nv, r.ints(1))?
            }
            K::PointsGeneralPolygons => {
                let nl = r.ints(0).unwrap_or(&[]).to_vec();
                let nv = r.ints(1).unwrap_or(&[]).to_vec();
                self.mesh(r, &nl, &nv, r.ints(2))?
            }
            K::Patch => {
                let kind = r.string(0).unwrap_or_default();
                match kind {
                    "bilinear" => {
                        let p = geometry::positions(r, 4)?;
                        geometry::unused_primvars(r, &["P", "Pw"], &mut self.warnings);
                        Shape::BilinearPatch { points: [p[0], p[1], p[2], p[3]] }
                    }
                    "bicubic" => {
                        return self.unsupported(r, "bicubic patches are not supported yet");
                    }
                    other => {
                        return Err(r.error(format!(
                            "type must be \"bilinear\" or \"bicubic\", got \"{other}\""
                        )));
                    }
                }
            }
            K::PatchMesh => return self.unsupported(r, "patch meshes are not supported yet"),
            K::NuPatch => return self.unsupported(r, "NURBS patches are not supported yet"),
            K::Hyperboloid => return self.unsupported(r, "hyperboloids are not supported yet"),
            K::SubdivisionMesh => {
                return self.unsupported(
                    r,
                    "subdivision surfaces are not supported yet (the production-geometry issue adds them)",
                );
            }
            _ => return self.unsupported(r, "this primitive is not supported"),
        };
        Ok(Some(shape))
    }

    fn unsupported(&mut self, r: &Request, why: &str) -> Result<Option<Shape>, RibError> {
        let w = r.warning(format!("{why}: skipped"));
        self.warnings.push(w);
        Ok(None)
    }

    fn mesh(
        &mut self,
        r: &Request,
        nloops: &[i32],
        nvertices: &[i32],
        vertices: Option<&[i32]>,
    ) -> Result<Shape, RibError> {
        let mut mesh: PolyMesh = geometry::poly_mesh(r, nloops, nvertices, vertices)?;
        let (_, colors) = geometry::mesh_colors(r, &mut mesh)?;
        geometry::unused_primvars(r, &["P", "Pw", "Cs"], &mut self.warnings);
        geometry::to_model_mesh(r, &mesh, colors)
    }
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

/// The control points of a shape that deforms through them.
fn control_points(shape: &Option<Shape>) -> Option<Vec<[f32; 3]>> {
    match shape.as_ref()? {
        Shape::Mesh { points, .. } => Some(points.clone()),
        Shape::BilinearPatch { points } => Some(points.to_vec()),
        _ => None,
    }
}

/// Two shapes of one kind with the same connectivity.
fn same_topology(a: &Option<Shape>, b: &Option<Shape>) -> bool {
    match (a, b) {
        (Some(Shape::Mesh { faces: fa, .. }), Some(Shape::Mesh { faces: fb, .. })) => fa == fb,
        (Some(Shape::BilinearPatch { .. }), Some(Shape::BilinearPatch { .. })) => true,
        _ => false,
    }
}

//! Shapes stage: each object's surfaces as parametric patches over `(u, v)` in `[0, 1]^2`.
//!
//! Invariants: `eval` returns an object-space point on the analytic surface, a unit
//! geometric normal with the outward orientation of the conventions in the crate docs
//! (quadrics sweep around object z with `theta = u * thetamax`), and a colour tint (mesh
//! vertex colours, white elsewhere). Every returned value is finite for finite input.
//! A deforming shape (bilinear patch, mesh, patch mesh or NURBS) gives, for every set of
//! control points with the shape's point count, surfaces in the same order and number, so
//! surface `i` at one time and surface `i` at another are the same piece of the object.
//!
//! The parametric orientation agrees with the normal: `dP/du x dP/dv` points the same way
//! as `eval`'s `n` wherever it is not degenerate, for every surface but the side of a cone
//! of negative height (which winds inward; its `n` is flipped outward, and it is left so,
//! since changing it would change how existing scenes dice). The dicer emits micropolygon
//! vertices in the order (u, v), (u+, v), (u+, v+), (u, v+), so a micropolygon's vector
//! area `(v2 - v0) x (v3 - v1) / 2` points along `dP/du x dP/dv`.
//!
//! Patch meshes and NURBS (`reyes_scene::patches`): a bilinear mesh is one bilinear patch
//! per sub-patch; a bicubic mesh one rational Bezier patch per sub-patch and a NURBS one per
//! non-empty knot span, row by row, each over its own `(u, v)` in `[0, 1]^2`.
//!
//! Layout: this file holds the surface type, its dispatch and the shape-to-surfaces rules;
//! `quadrics.rs` the hyperboloid, `patches.rs` the bilinear and Bezier patches, `tests.rs`
//! the unit tests.
//!
//! CSG operands must be closed solids: [`end_caps`] gives the disks that close cylinders,
//! cones and paraboloids, each facing out of the solid.

mod hair;
mod patches;
pub(crate) mod points;
mod quadrics;
mod subdivision;

use glam::{DVec3, Vec2, Vec3};
use reyes_scene::patches::{self as rp, BezierPatch};
use reyes_scene::{Object, PatchType, Shape};

pub(crate) use hair::{BlobFace, Ribbon};
use patches::{Bilinear, bezier_normal, bezier_position, lerp4};
pub(crate) use points::PointBatch;
use quadrics::{hyperboloid_normal, hyperboloid_position};
use reyes_scene::curves::Facing;
pub(crate) use subdivision::SubdivPatch;

/// One evaluated surface point, in object space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SurfacePoint {
    /// Position.
    pub p: Vec3,
    /// Unit outward normal.
    pub n: Vec3,
    /// Colour multiplying the material colour (mesh vertex colours; white otherwise).
    pub tint: Vec3,
    /// Opacity multiplying the material opacity (curves', points' and blobbies' `Os`;
    /// opaque otherwise).
    pub opacity: Vec3,
}

/// A parametric surface. Angles are in radians.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Surface {
    /// Sphere; `v` runs over latitude `phi_min..phi_max`.
    Sphere { radius: f32, phi_min: f32, phi_max: f32, theta_max: f32 },
    /// Open cylinder.
    Cylinder { radius: f32, zmin: f32, zmax: f32, theta_max: f32 },
    /// Cone from the base circle (z = 0) to the apex (z = height).
    Cone { height: f32, radius: f32, theta_max: f32 },
    /// Paraboloid `r = rmax * sqrt(z / zmax)`, `v` running over `zmin..zmax`.
    Paraboloid { rmax: f32, zmin: f32, zmax: f32, theta_max: f32 },
    /// Disk (annulus-free) in the plane z = height, facing +z, or -z when `flip`. The flipped
    /// disk runs `v` the other way (`r = radius v`), so that its parametric orientation
    /// `dP/du x dP/dv` is -z too.
    Disk { height: f32, radius: f32, theta_max: f32, flip: bool },
    /// Torus; `v` runs over the tube angle `phi_min..phi_max`.
    Torus { major: f32, minor: f32, phi_min: f32, phi_max: f32, theta_max: f32 },
    /// Bilinear patch (also every mesh face and bilinear patch-mesh sub-patch).
    Bilinear(Bilinear),
    /// Hyperboloid: the segment `p1 -> p2` (`v` along it) turned about z by `u * theta_max`.
    Hyperboloid { p1: Vec3, p2: Vec3, theta_max: f32 },
    /// A rational Bezier patch: a bicubic patch-mesh sub-patch or a NURBS span.
    Bezier(Box<BezierPatch>),
    /// A patch of a Catmull-Clark subdivision surface.
    Subdiv(Box<SubdivPatch>),
    /// A curve segment's ribbon: `u` across the width, `v` along the curve.
    Ribbon(Box<Ribbon>),
    /// A face of a blobby's coarse mesh, its points on the isosurface.
    Blob(Box<BlobFace>),
    /// A batch of points, `u` over the points (diced by [`PointBatch::vertex`]).
    Points(Box<PointBatch>),
}

/// `(sin, cos)` of the sweep angle `u * theta_max`, exactly `(0, 1)` where a full turn
/// closes (`u = 1` with `|theta_max|` a full turn, to rounding): the seam `u = 1` is then
/// the seam `u = 0` bit for bit, so the two edges of a closed sweep dice to the same points
/// and crack-free dicing holds across it.
#[inline]
pub(crate) fn sweep(u: f32, theta_max: f32) -> (f32, f32) {
    if u == 1.0 && full_turn(theta_max) { (0.0, 1.0) } else { (u * theta_max).sin_cos() }
}

/// `(sin, cos)` of the tube angle at `v` over `[phi_min, phi_max]`, exact at a closed end:
/// where the range is a full turn, `v = 1` gives the point of `v = 0` bit for bit.
#[inline]
pub(crate) fn tube(phi_min: f32, phi_max: f32, v: f32) -> (f32, f32) {
    if v == 1.0 && full_turn(phi_max - phi_min) {
        phi_min.sin_cos()
    } else {
        (phi_min + v * (phi_max - phi_min)).sin_cos()
    }
}

/// True if `angle` is a whole turn either way, to the rounding of a conversion from degrees.
#[inline]
/// The eight corners of the box `[lo, hi]`: corner `k` takes `hi` along axis `a` where bit
/// `a` of `k` is set.
pub(crate) fn box_corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|k| {
        Vec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

fn full_turn(angle: f32) -> bool {
    (angle.abs() - std::f32::consts::TAU).abs() <= 4.0 * f32::EPSILON * std::f32::consts::TAU
}

impl Surface {
    /// Object-space position at `(u, v)`.
    pub fn position(&self, u: f32, v: f32) -> Vec3 {
        match self {
            Surface::Sphere { radius, phi_min, phi_max, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                let (sp, cp) = tube(*phi_min, *phi_max, v);
                Vec3::new(radius * cp * ct, radius * cp * st, radius * sp)
            }
            Surface::Cylinder { radius, zmin, zmax, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                Vec3::new(radius * ct, radius * st, zmin + v * (zmax - zmin))
            }
            Surface::Cone { height, radius, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                let r = radius * (1.0 - v);
                Vec3::new(r * ct, r * st, v * height)
            }
            Surface::Paraboloid { rmax, zmin, zmax, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                let z = zmin + v * (zmax - zmin);
                let r = rmax * (z / zmax).max(0.0).sqrt();
                Vec3::new(r * ct, r * st, z)
            }
            Surface::Disk { height, radius, theta_max, flip } => {
                let (st, ct) = sweep(u, *theta_max);
                let r = if *flip { radius * v } else { radius * (1.0 - v) };
                Vec3::new(r * ct, r * st, *height)
            }
            Surface::Torus { major, minor, phi_min, phi_max, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                let (sp, cp) = tube(*phi_min, *phi_max, v);
                let ring = major + minor * cp;
                Vec3::new(ring * ct, ring * st, minor * sp)
            }
            Surface::Bilinear(b) => lerp4(&b.p, u, v),
            Surface::Hyperboloid { p1, p2, theta_max } => {
                hyperboloid_position(*p1, *p2, *theta_max, u, v)
            }
            Surface::Bezier(b) => bezier_position(b, u, v),
            Surface::Subdiv(s) => s.position(u, v),
            Surface::Ribbon(r) => r.position(u, v),
            Surface::Blob(b) => b.position(u, v),
            Surface::Points(b) => b.position(u, v),
        }
    }

    /// Position, unit outward normal and tint at `(u, v)`.
    pub fn eval(&self, u: f32, v: f32) -> SurfacePoint {
        if let Surface::Subdiv(s) = self {
            // Position and normal from one evaluation of the limit surface.
            let (p, n) = s.point(u, v);
            return SurfacePoint { p, n, tint: s.tint(u, v), opacity: Vec3::ONE };
        }
        let hair = match self {
            Surface::Ribbon(r) => Some(r.eval(u, v)),
            Surface::Blob(b) => Some(b.eval(u, v)),
            _ => None,
        };
        if let Some((p, n, tint, opacity)) = hair {
            return SurfacePoint { p, n, tint, opacity };
        }
        let p = self.position(u, v);
        let white = Vec3::ONE;
        let (n, tint) = match self {
            Surface::Sphere { radius, .. } => {
                ((p / *radius).try_normalize().unwrap_or(Vec3::Z), white)
            }
            Surface::Cylinder { theta_max, .. } => {
                let (st, ct) = sweep(u, *theta_max);
                (Vec3::new(ct, st, 0.0), white)
            }
            Surface::Cone { height, radius, theta_max } => {
                let (st, ct) = sweep(u, *theta_max);
                // The parametric normal is (h cos, h sin, r); for h < 0 it points into the
                // cone, so flip it by sign(h) to keep the outward orientation.
                let s = height.signum();
                let n = Vec3::new(s * height * ct, s * height * st, s * radius);
                (n.try_normalize().unwrap_or(Vec3::Z), white)
            }
            Surface::Paraboloid { rmax, zmax, .. } => {
                // Gradient of x^2 + y^2 - (rmax^2 / zmax) z: away from the axis and down,
                // out of the solid bowl; (0, 0, -1) at the apex.
                let n = Vec3::new(2.0 * p.x, 2.0 * p.y, -rmax * rmax / zmax);
                (n.try_normalize().unwrap_or(-Vec3::Z), white)
            }
            Surface::Disk { flip, .. } => (if *flip { Vec3::NEG_Z } else { Vec3::Z }, white),
            Surface::Torus { phi_min, phi_max, theta_max, .. } => {
                let (st, ct) = sweep(u, *theta_max);
                let (sp, cp) = tube(*phi_min, *phi_max, v);
                (Vec3::new(cp * ct, cp * st, sp), white)
            }
            Surface::Bilinear(b) => (b.normal(u, v), lerp4(&b.tint, u, v)),
            Surface::Hyperboloid { p1, p2, theta_max } => {
                (hyperboloid_normal(*p1, *p2, *theta_max, u, v), white)
            }
            Surface::Bezier(b) => (bezier_normal(b, u, v), white),
            Surface::Subdiv(s) => (s.point(u, v).1, s.tint(u, v)),
            Surface::Ribbon(_) | Surface::Blob(_) | Surface::Points(_) => (Vec3::Z, white),
        };
        SurfacePoint { p, n, tint, opacity: Vec3::ONE }
    }
}

impl Surface {
    /// Vertex `(i, j)` of `patch` diced `nu` across, for surfaces whose grid is not a
    /// parametric one (point batches); `None` for every other surface, whose vertex is
    /// [`Surface::eval`] at the vertex's `(u, v)`.
    #[inline]
    pub fn grid_vertex(&self, u: [f32; 2], i: usize, j: usize, nu: usize) -> Option<SurfacePoint> {
        match self {
            Surface::Points(b) => Some(b.vertex(u, i, j, nu)),
            _ => None,
        }
    }

    /// True if cell `cell` of `patch` diced `nu` across is not part of the surface (the cell
    /// joining two points of a batch).
    #[inline]
    pub fn skips(&self, u: [f32; 2], cell: usize, nu: usize) -> bool {
        match self {
            Surface::Points(b) => b.skips(u, cell, nu),
            _ => false,
        }
    }

    /// The texture coordinates at `(u, v)` and their change over one step `duv` of the
    /// parameters (per axis, the larger of the changes along u and along v): a mesh's or a
    /// subdivision mesh's `st` where it has them, else `(u, v)` itself and `duv`.
    pub fn st(&self, u: f32, v: f32, duv: [f32; 2]) -> ([f32; 2], [f32; 2]) {
        let at = |u: f32, v: f32| match self {
            Surface::Bilinear(b) => b.st(u, v),
            Surface::Subdiv(s) => s.st(u, v),
            _ => None,
        };
        let Some(st) = at(u, v) else { return ([u, v], duv) };
        // One-sided differences, towards the inside of [0, 1]^2.
        let step = |x: f32, d: f32| if x + d <= 1.0 { d } else { -d };
        let (du, dv) = (step(u, duv[0]), step(v, duv[1]));
        let along_u = at(u + du, v).map_or(Vec2::ZERO, |s| s - st);
        let along_v = at(u, v + dv).map_or(Vec2::ZERO, |s| s - st);
        let d = along_u.abs().max(along_v.abs());
        (st.to_array(), d.to_array())
    }

    /// The object-space control hull of the part `[u0, u1] x [v0, v1]` of a rational Bezier
    /// patch: the projected net of that sub-patch, whose convex hull encloses it (weights
    /// are positive). `None` for every other surface, which the test grid and its margin bound.
    pub fn hull(&self, u: [f32; 2], v: [f32; 2]) -> Option<Vec<Vec3>> {
        match self {
            Surface::Bezier(b) => {
                let (u, v) = (u.map(f64::from), v.map(f64::from));
                let sub =
                    if u == [0.0, 1.0] && v == [0.0, 1.0] { (**b).clone() } else { b.sub(u, v) };
                Some(sub.hull().map(|p| p.as_vec3()).collect())
            }
            Surface::Subdiv(s) => Some(s.hull(u, v)),
            Surface::Ribbon(r) => Some(r.hull(v)),
            Surface::Points(b) => Some(b.hull(u)),
            _ => None,
        }
    }
}

/// The control points of a shape that can deform (bilinear patch corners, mesh points,
/// patch-mesh points, NURBS points as positions `(x/w, y/w, z/w)`); `None` for the quadrics.
pub(crate) fn control_points(shape: &Shape) -> Option<Vec<Vec3>> {
    match shape {
        Shape::BilinearPatch { points } => Some(points.iter().map(|p| Vec3::from(*p)).collect()),
        Shape::Mesh { points, .. }
        | Shape::SubdivisionMesh { points, .. }
        | Shape::Curves { points, .. }
        | Shape::Points { points, .. } => Some(points.iter().map(|p| Vec3::from(*p)).collect()),
        Shape::PatchMesh { .. } | Shape::NuPatch { .. } => {
            rp::control_positions(shape).map(|p| p.iter().map(|q| q.as_vec3()).collect())
        }
        _ => None,
    }
}

/// The surfaces of an object, in a fixed order (mesh faces in list order). Faces with
/// fewer than three valid indices are skipped; faces with more than four are fanned into
/// triangles around their first vertex.
pub(crate) fn surfaces(object: &Object, facing: Facing) -> Vec<Surface> {
    shape_surfaces(&object.shape, None, facing)
}

/// The surfaces of `shape` (as [`surfaces`]), with its control points replaced by
/// `points_object` when given (a deformation key). A point missing from `points_object`
/// keeps the shape's own, so the surfaces are always those of the shape's point count.
/// Camera-facing ribbons face as `facing` says.
pub(crate) fn shape_surfaces(
    shape: &Shape,
    points_object: Option<&[Vec3]>,
    facing: Facing,
) -> Vec<Surface> {
    let moved = |i: usize, own: Vec3| points_object.and_then(|p| p.get(i).copied()).unwrap_or(own);
    match shape {
        Shape::Sphere { radius, zmin, zmax, thetamax } => {
            let r = *radius;
            let z0 = zmin.unwrap_or(-r).clamp(-r, r);
            let z1 = zmax.unwrap_or(r).clamp(-r, r);
            vec![Surface::Sphere {
                radius: r,
                phi_min: (z0 / r).clamp(-1.0, 1.0).asin(),
                phi_max: (z1 / r).clamp(-1.0, 1.0).asin(),
                theta_max: thetamax.to_radians(),
            }]
        }
        Shape::Cylinder { radius, zmin, zmax, thetamax } => vec![Surface::Cylinder {
            radius: *radius,
            zmin: *zmin,
            zmax: *zmax,
            theta_max: thetamax.to_radians(),
        }],
        Shape::Cone { height, radius, thetamax } => vec![Surface::Cone {
            height: *height,
            radius: *radius,
            theta_max: thetamax.to_radians(),
        }],
        Shape::Paraboloid { rmax, zmin, zmax, thetamax } => vec![Surface::Paraboloid {
            rmax: *rmax,
            zmin: *zmin,
            zmax: *zmax,
            theta_max: thetamax.to_radians(),
        }],
        Shape::Disk { height, radius, thetamax } => vec![Surface::Disk {
            height: *height,
            radius: *radius,
            theta_max: thetamax.to_radians(),
            flip: false,
        }],
        Shape::Torus { major_radius, minor_radius, phimin, phimax, thetamax } => {
            vec![Surface::Torus {
                major: *major_radius,
                minor: *minor_radius,
                phi_min: phimin.to_radians(),
                phi_max: phimax.to_radians(),
                theta_max: thetamax.to_radians(),
            }]
        }
        Shape::BilinearPatch { points } => {
            let p = [0, 1, 2, 3].map(|i| moved(i, Vec3::from(points[i])));
            vec![Surface::Bilinear(Bilinear::new(p, [Vec3::ONE; 4], None))]
        }
        Shape::Mesh { points, faces, colors, normals, st } => {
            let point = |i: u32| points.get(i as usize).map(|p| moved(i as usize, Vec3::from(*p)));
            let tint = |i: u32| {
                colors
                    .as_ref()
                    .and_then(|c| c.get(i as usize))
                    .map_or(Vec3::ONE, |c| Vec3::from(*c))
            };
            // Normals are not keyed: a deforming mesh keeps its own at every time.
            let normal = |i: u32| {
                normals.as_ref().map(|n| n.get(i as usize).map_or(Vec3::Z, |n| Vec3::from(*n)))
            };
            let coords = |i: u32| {
                st.as_ref().map(|s| s.get(i as usize).map_or(Vec2::ZERO, |s| Vec2::from(*s)))
            };
            // The corners' normals and st in the order of the patch corners `k`.
            let data = |face: &[u32], k: [usize; 4]| {
                let n = normals.as_ref().map(|_| k.map(|k| normal(face[k]).unwrap_or(Vec3::Z)));
                let s = st.as_ref().map(|_| k.map(|k| coords(face[k]).unwrap_or(Vec2::ZERO)));
                (n, s)
            };
            let mut out = Vec::with_capacity(faces.len());
            for face in faces {
                if face.iter().any(|&i| point(i).is_none()) {
                    continue;
                }
                let pt = |k: usize| point(face[k]).unwrap_or(Vec3::ZERO);
                let tn = |k: usize| tint(face[k]);
                match face.len() {
                    0..=2 => {}
                    4 => {
                        // Around the face a, b, c, d: P0 = a, P1 = b, P2 = d, P3 = c.
                        let p = [pt(0), pt(1), pt(3), pt(2)];
                        let t = [tn(0), tn(1), tn(3), tn(2)];
                        let (n, s) = data(face, [0, 1, 3, 2]);
                        let b = Bilinear::new(p, t, None).with_vertex_data(n, s);
                        out.push(Surface::Bilinear(b));
                    }
                    n => {
                        for k in 1..n - 1 {
                            let (a, b, c) = (pt(0), pt(k), pt(k + 1));
                            let p = [a, b, c, c];
                            let t = [tn(0), tn(k), tn(k + 1), tn(k + 1)];
                            let flat = (b - a).cross(c - a);
                            let (n, s) = data(face, [0, k, k + 1, k + 1]);
                            let b = Bilinear::new(p, t, Some(flat)).with_vertex_data(n, s);
                            out.push(Surface::Bilinear(b));
                        }
                    }
                }
            }
            out
        }
        Shape::Hyperboloid { point1, point2, thetamax } => vec![Surface::Hyperboloid {
            p1: Vec3::from(*point1),
            p2: Vec3::from(*point2),
            theta_max: thetamax.to_radians(),
        }],
        Shape::PatchMesh { kind: PatchType::Bilinear, points, .. } => {
            let point = |i: u32| {
                let own = points.get(i as usize).map_or(Vec3::ZERO, |p| Vec3::from(*p));
                moved(i as usize, own)
            };
            rp::bilinear_corners(shape)
                .into_iter()
                .map(|c| Surface::Bilinear(Bilinear::new(c.map(point), [Vec3::ONE; 4], None)))
                .collect()
        }
        Shape::PatchMesh { .. } | Shape::NuPatch { .. } => {
            let positions: Option<Vec<DVec3>> = points_object.map(|p| {
                let own = rp::control_positions(shape).unwrap_or_default();
                own.iter().enumerate().map(|(i, q)| p.get(i).map_or(*q, |m| m.as_dvec3())).collect()
            });
            rp::bezier_patches(shape, positions.as_deref())
                .into_iter()
                .map(|b| Surface::Bezier(Box::new(b)))
                .collect()
        }
        Shape::SubdivisionMesh { .. } => subdivision::patches(shape, points_object)
            .into_iter()
            .map(|p| Surface::Subdiv(Box::new(p)))
            .collect(),
        Shape::Curves { normals, .. } => {
            let facing = if normals.is_some() { Facing::Normals } else { facing };
            reyes_scene::curves::segments(shape, points_object)
                .into_iter()
                .map(|segment| Surface::Ribbon(Box::new(Ribbon { segment, facing })))
                .collect()
        }
        Shape::Blobby { .. } => hair::blob_faces(shape),
        Shape::Points { .. } => points::batches(shape, points_object, facing),
        // Read into a Mesh or SubdivisionMesh when the scene was loaded.
        Shape::MeshFile { .. } => Vec::new(),
    }
}

/// True if `shape` carries an opacity (`Os`) below 1 somewhere: its micropolygons are then
/// not opaque.
pub(crate) fn own_opacity_below_one(shape: &Shape) -> bool {
    let opacities = match shape {
        Shape::Curves { opacities, .. }
        | Shape::Points { opacities, .. }
        | Shape::Blobby { opacities, .. } => opacities,
        _ => return false,
    };
    opacities.as_ref().is_some_and(|o| o.values().iter().flatten().any(|&a| a < 1.0))
}

/// The end caps that close `shape` into a solid, each facing out of it, for an object that
/// is a CSG operand (appended after the shape's own surfaces, with the same sweep): a
/// cylinder's disks at `zmin` (facing -z) and `zmax` (+z); a cone's base disk at z = 0
/// (facing away from the apex); a paraboloid's disk at `zmax` (+z) and, when `zmin > 0`, at
/// `zmin` (-z). Other shapes need none (spheres, tori and meshes are closed as they are, or
/// cannot be closed by disks) and give an empty list.
pub(crate) fn end_caps(shape: &Shape) -> Vec<Surface> {
    let disk = |height: f32, radius: f32, thetamax: f32, flip: bool| Surface::Disk {
        height,
        radius,
        theta_max: thetamax.to_radians(),
        flip,
    };
    match *shape {
        Shape::Cylinder { radius, zmin, zmax, thetamax } => {
            vec![disk(zmin, radius, thetamax, true), disk(zmax, radius, thetamax, false)]
        }
        // The cone lies on the apex's side of its base: a base below the apex faces -z.
        Shape::Cone { height, radius, thetamax } => vec![disk(0.0, radius, thetamax, height > 0.0)],
        Shape::Paraboloid { rmax, zmin, zmax, thetamax } => {
            let mut caps = Vec::with_capacity(2);
            if zmin > 0.0 {
                let r = rmax * (zmin / zmax).max(0.0).sqrt();
                caps.push(disk(zmin, r, thetamax, true));
            }
            caps.push(disk(zmax, rmax, thetamax, false));
            caps
        }
        Shape::Sphere { .. }
        | Shape::Disk { .. }
        | Shape::Torus { .. }
        | Shape::BilinearPatch { .. }
        | Shape::Mesh { .. }
        | Shape::Hyperboloid { .. }
        | Shape::PatchMesh { .. }
        | Shape::NuPatch { .. }
        | Shape::SubdivisionMesh { .. }
        | Shape::Curves { .. }
        | Shape::Points { .. }
        | Shape::Blobby { .. }
        | Shape::MeshFile { .. } => Vec::new(),
    }
}

#[cfg(test)]
mod tests;

//! Shapes stage: each object's surfaces as parametric patches over `(u, v)` in `[0, 1]^2`.
//!
//! Invariants: `eval` returns an object-space point on the analytic surface, a unit
//! geometric normal with the outward orientation of the conventions in the crate docs
//! (quadrics sweep around object z with `theta = u * thetamax`), and a colour tint (mesh
//! vertex colours, white elsewhere). Every returned value is finite for finite input.
//! A deforming shape (bilinear patch or mesh) gives, for every set of control points with
//! the shape's point count, surfaces in the same order and number, so surface `i` at one
//! time and surface `i` at another are the same piece of the object.
//!
//! The parametric orientation agrees with the normal: `dP/du x dP/dv` points the same way
//! as `eval`'s `n` wherever it is not degenerate, for every surface but the side of a cone
//! of negative height (which winds inward; its `n` is flipped outward, and it is left so,
//! since changing it would change how existing scenes dice). The dicer emits micropolygon
//! vertices in the order (u, v), (u+, v), (u+, v+), (u, v+), so a micropolygon's vector
//! area `(v2 - v0) x (v3 - v1) / 2` points along `dP/du x dP/dv`.
//!
//! CSG operands must be closed solids: [`end_caps`] gives the disks that close cylinders,
//! cones and paraboloids, each facing out of the solid.

use glam::Vec3;
use reyes_scene::{Object, Shape};

/// One evaluated surface point, in object space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SurfacePoint {
    /// Position.
    pub p: Vec3,
    /// Unit outward normal.
    pub n: Vec3,
    /// Colour multiplying the material colour (mesh vertex colours; white otherwise).
    pub tint: Vec3,
}

/// A bilinear patch: `P(u,v) = lerp(lerp(P0,P1,u), lerp(P2,P3,u), v)`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Bilinear {
    /// Corners in RenderMan order: (0,0), (1,0), (0,1), (1,1).
    p: [Vec3; 4],
    /// Per-corner tint, interpolated the same way.
    tint: [Vec3; 4],
    /// A fixed normal (mesh triangles use their flat face normal).
    flat_normal: Option<Vec3>,
    /// The patch's average normal, used where the partial derivatives are degenerate.
    average_normal: Vec3,
}

impl Bilinear {
    /// A patch from its corners, tints and an optional fixed normal.
    fn new(p: [Vec3; 4], tint: [Vec3; 4], flat_normal: Option<Vec3>) -> Bilinear {
        // The vector area of a bilinear patch is half the cross product of its diagonals.
        let average_normal = (p[3] - p[0]).cross(p[2] - p[1]).try_normalize().unwrap_or(Vec3::Z);
        let flat_normal = flat_normal.map(|n| n.try_normalize().unwrap_or(average_normal));
        Bilinear { p, tint, flat_normal, average_normal }
    }
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
    /// Bilinear patch (also every mesh face).
    Bilinear(Bilinear),
}

#[inline]
fn lerp4(c: &[Vec3; 4], u: f32, v: f32) -> Vec3 {
    let bottom = c[0].lerp(c[1], u);
    let top = c[2].lerp(c[3], u);
    bottom.lerp(top, v)
}

impl Surface {
    /// Object-space position at `(u, v)`.
    pub fn position(&self, u: f32, v: f32) -> Vec3 {
        match self {
            Surface::Sphere { radius, phi_min, phi_max, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
                let (sp, cp) = (phi_min + v * (phi_max - phi_min)).sin_cos();
                Vec3::new(radius * cp * ct, radius * cp * st, radius * sp)
            }
            Surface::Cylinder { radius, zmin, zmax, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
                Vec3::new(radius * ct, radius * st, zmin + v * (zmax - zmin))
            }
            Surface::Cone { height, radius, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
                let r = radius * (1.0 - v);
                Vec3::new(r * ct, r * st, v * height)
            }
            Surface::Paraboloid { rmax, zmin, zmax, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
                let z = zmin + v * (zmax - zmin);
                let r = rmax * (z / zmax).max(0.0).sqrt();
                Vec3::new(r * ct, r * st, z)
            }
            Surface::Disk { height, radius, theta_max, flip } => {
                let (st, ct) = (u * theta_max).sin_cos();
                let r = if *flip { radius * v } else { radius * (1.0 - v) };
                Vec3::new(r * ct, r * st, *height)
            }
            Surface::Torus { major, minor, phi_min, phi_max, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
                let (sp, cp) = (phi_min + v * (phi_max - phi_min)).sin_cos();
                let ring = major + minor * cp;
                Vec3::new(ring * ct, ring * st, minor * sp)
            }
            Surface::Bilinear(b) => lerp4(&b.p, u, v),
        }
    }

    /// Position, unit outward normal and tint at `(u, v)`.
    pub fn eval(&self, u: f32, v: f32) -> SurfacePoint {
        let p = self.position(u, v);
        let white = Vec3::ONE;
        let (n, tint) = match self {
            Surface::Sphere { radius, .. } => {
                ((p / *radius).try_normalize().unwrap_or(Vec3::Z), white)
            }
            Surface::Cylinder { theta_max, .. } => {
                let (st, ct) = (u * theta_max).sin_cos();
                (Vec3::new(ct, st, 0.0), white)
            }
            Surface::Cone { height, radius, theta_max } => {
                let (st, ct) = (u * theta_max).sin_cos();
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
                let (st, ct) = (u * theta_max).sin_cos();
                let (sp, cp) = (phi_min + v * (phi_max - phi_min)).sin_cos();
                (Vec3::new(cp * ct, cp * st, sp), white)
            }
            Surface::Bilinear(b) => {
                let n = match b.flat_normal {
                    Some(n) => n,
                    None => {
                        let dpdu = (b.p[1] - b.p[0]).lerp(b.p[3] - b.p[2], v);
                        let dpdv = (b.p[2] - b.p[0]).lerp(b.p[3] - b.p[1], u);
                        dpdu.cross(dpdv).try_normalize().unwrap_or(b.average_normal)
                    }
                };
                (n, lerp4(&b.tint, u, v))
            }
        };
        SurfacePoint { p, n, tint }
    }
}

/// The control points of a shape that can deform (bilinear patch corners, mesh points);
/// `None` for the quadrics.
pub(crate) fn control_points(shape: &Shape) -> Option<Vec<Vec3>> {
    match shape {
        Shape::BilinearPatch { points } => Some(points.iter().map(|p| Vec3::from(*p)).collect()),
        Shape::Mesh { points, .. } => Some(points.iter().map(|p| Vec3::from(*p)).collect()),
        _ => None,
    }
}

/// The surfaces of an object, in a fixed order (mesh faces in list order). Faces with
/// fewer than three valid indices are skipped; faces with more than four are fanned into
/// triangles around their first vertex.
pub(crate) fn surfaces(object: &Object) -> Vec<Surface> {
    shape_surfaces(&object.shape, None)
}

/// The surfaces of `shape` (as [`surfaces`]), with its control points replaced by
/// `points_object` when given (a deformation key). A point missing from `points_object`
/// keeps the shape's own, so the surfaces are always those of the shape's point count.
pub(crate) fn shape_surfaces(shape: &Shape, points_object: Option<&[Vec3]>) -> Vec<Surface> {
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
        Shape::Mesh { points, faces, colors } => {
            let point = |i: u32| points.get(i as usize).map(|p| moved(i as usize, Vec3::from(*p)));
            let tint = |i: u32| {
                colors
                    .as_ref()
                    .and_then(|c| c.get(i as usize))
                    .map_or(Vec3::ONE, |c| Vec3::from(*c))
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
                        out.push(Surface::Bilinear(Bilinear::new(p, t, None)));
                    }
                    n => {
                        for k in 1..n - 1 {
                            let (a, b, c) = (pt(0), pt(k), pt(k + 1));
                            let p = [a, b, c, c];
                            let t = [tn(0), tn(k), tn(k + 1), tn(k + 1)];
                            let flat = (b - a).cross(c - a);
                            out.push(Surface::Bilinear(Bilinear::new(p, t, Some(flat))));
                        }
                    }
                }
            }
            out
        }
    }
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
        | Shape::Mesh { .. } => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use reyes_scene::Material;

    fn object(shape: Shape) -> Object {
        Object::new(shape, Material::Constant { color: [1.0; 3], opacity: [1.0; 3] })
    }

    fn params() -> impl Iterator<Item = (f32, f32)> {
        (0..=10).flat_map(|i| (0..=10).map(move |j| (i as f32 / 10.0, j as f32 / 10.0)))
    }

    /// `dP/du x dP/dv` by central differences (None where degenerate).
    fn parametric_normal(s: &Surface, u: f32, v: f32) -> Option<Vec3> {
        let h = 1e-3;
        let (u0, u1) = ((u - h).max(0.0), (u + h).min(1.0));
        let (v0, v1) = ((v - h).max(0.0), (v + h).min(1.0));
        let du = s.position(u1, v) - s.position(u0, v);
        let dv = s.position(u, v1) - s.position(u, v0);
        du.cross(dv).try_normalize().filter(|_| du.length() > 1e-5 && dv.length() > 1e-5)
    }

    fn check_unit_and_consistent(s: &Surface) {
        for (u, v) in params() {
            let sp = s.eval(u, v);
            assert!(
                (sp.n.length() - 1.0).abs() < 1e-5,
                "{s:?} at ({u},{v}): |N| = {}",
                sp.n.length()
            );
            if let Some(pn) = parametric_normal(s, u, v) {
                assert!(pn.dot(sp.n) > 0.99, "{s:?} at ({u},{v}): N {} vs dPdu x dPdv {pn}", sp.n);
            }
        }
    }

    #[test]
    fn sphere_points_on_surface_with_outward_normals() {
        let obj =
            object(Shape::Sphere { radius: 2.0, zmin: Some(-1.0), zmax: None, thetamax: 300.0 });
        let s = &surfaces(&obj)[0];
        for (u, v) in params() {
            let sp = s.eval(u, v);
            assert!((sp.p.length() - 2.0).abs() < 1e-5);
            assert!(sp.p.z >= -1.0 - 1e-5 && sp.p.z <= 2.0 + 1e-5);
            assert!((sp.n - sp.p / 2.0).length() < 1e-5, "outward");
        }
        assert!((s.position(0.0, 0.0).z + 1.0).abs() < 1e-5);
        assert!((s.position(0.3, 1.0) - Vec3::new(0.0, 0.0, 2.0)).length() < 1e-5);
        let end = s.position(1.0, 0.5);
        assert!((end.y.atan2(end.x).to_degrees() + 60.0).abs() < 1e-3, "thetamax 300");
        check_unit_and_consistent(s);
    }

    #[test]
    fn cylinder_points_on_surface_with_outward_normals() {
        let obj = object(Shape::Cylinder { radius: 1.5, zmin: -1.0, zmax: 2.0, thetamax: 360.0 });
        let s = &surfaces(&obj)[0];
        for (u, v) in params() {
            let sp = s.eval(u, v);
            assert!((sp.p.truncate().length() - 1.5).abs() < 1e-5);
            assert!((sp.p.z - (-1.0 + 3.0 * v)).abs() < 1e-5);
            assert!(sp.n.dot(Vec3::new(sp.p.x, sp.p.y, 0.0)) > 0.0 && sp.n.z == 0.0);
        }
        check_unit_and_consistent(s);
    }

    #[test]
    fn cone_points_on_surface_with_outward_normals() {
        for height in [2.0_f32, -2.0] {
            let obj = object(Shape::Cone { height, radius: 1.0, thetamax: 360.0 });
            let s = &surfaces(&obj)[0];
            for (u, v) in params() {
                let sp = s.eval(u, v);
                // On the cone: radius shrinks linearly to the apex.
                let r = sp.p.truncate().length();
                assert!((r - (1.0 - sp.p.z / height)).abs() < 1e-5, "h {height}");
                // N is perpendicular to the generator (apex - base point) ...
                let base = Vec3::new(sp.p.x, sp.p.y, 0.0) / (1.0 - v).max(1e-6);
                let generator = Vec3::new(0.0, 0.0, height) - base;
                if v < 1.0 {
                    assert!(sp.n.dot(generator).abs() < 1e-4, "h {height}");
                }
                // ... and points away from the axis, and away from the base's inside.
                let (st, ct) = (u * std::f32::consts::TAU).sin_cos();
                assert!(sp.n.dot(Vec3::new(ct, st, 0.0)) > 0.0, "h {height}");
                assert!(sp.n.z * height > 0.0, "h {height}");
                assert!((sp.n.length() - 1.0).abs() < 1e-5);
            }
            if height > 0.0 {
                check_unit_and_consistent(s);
            }
        }
    }

    #[test]
    fn disk_points_on_surface_facing_plus_z() {
        let obj = object(Shape::Disk { height: 0.5, radius: 3.0, thetamax: 180.0 });
        let s = &surfaces(&obj)[0];
        for (u, v) in params() {
            let sp = s.eval(u, v);
            assert_eq!(sp.p.z, 0.5);
            assert!((sp.p.truncate().length() - 3.0 * (1.0 - v)).abs() < 1e-5);
            assert!(sp.p.y >= -1e-5, "half disk");
            assert_eq!(sp.n, Vec3::Z);
        }
        check_unit_and_consistent(s);
    }

    #[test]
    fn paraboloid_points_on_surface_with_outward_normals() {
        for (zmin, zmax, thetamax) in [(0.0_f32, 2.0_f32, 360.0_f32), (0.5, 3.0, 250.0)] {
            let rmax = 1.5_f32;
            let k = rmax * rmax / zmax;
            let obj = object(Shape::Paraboloid { rmax, zmin, zmax, thetamax });
            let s = &surfaces(&obj)[0];
            for (u, v) in params() {
                let sp = s.eval(u, v);
                // On the surface x^2 + y^2 = k z, with z running linearly over the cut.
                let rho2 = sp.p.x * sp.p.x + sp.p.y * sp.p.y;
                assert!((rho2 - k * sp.p.z).abs() < 1e-5, "({u},{v}): {}", sp.p);
                assert!((sp.p.z - (zmin + v * (zmax - zmin))).abs() < 1e-5);
                let theta = sp.p.y.atan2(sp.p.x).rem_euclid(std::f32::consts::TAU);
                if rho2 > 1e-8 && u < 1.0 {
                    assert!((theta - u * thetamax.to_radians()).abs() < 1e-4, "({u},{v})");
                }
                // Outward: the normalised gradient (2x, 2y, -k), down and away from the axis.
                let grad = Vec3::new(2.0 * sp.p.x, 2.0 * sp.p.y, -k).normalize();
                assert!((sp.n - grad).length() < 1e-5, "({u},{v}): {} vs {grad}", sp.n);
                assert!(sp.n.z < 0.0);
                // A point just along the normal is outside the solid bowl (x^2 + y^2 > k z).
                let q = sp.p + sp.n * 1e-2;
                assert!(q.x * q.x + q.y * q.y - k * q.z > 0.0, "({u},{v})");
            }
            assert_eq!(s.position(0.3, 0.0).z, zmin);
            let top = s.position(0.0, 1.0);
            assert!((top - Vec3::new(rmax, 0.0, zmax)).length() < 1e-5, "radius rmax at zmax");
            check_unit_and_consistent(s);
        }
    }

    #[test]
    fn end_caps_close_the_solids_facing_out() {
        let cap = |s: &Surface| match s {
            Surface::Disk { height, radius, flip, .. } => (*height, *radius, *flip),
            other => panic!("not a disk: {other:?}"),
        };
        let cyl = Shape::Cylinder { radius: 1.5, zmin: -1.0, zmax: 2.0, thetamax: 360.0 };
        let caps = end_caps(&cyl);
        assert_eq!(
            caps.iter().map(cap).collect::<Vec<_>>(),
            [(-1.0, 1.5, true), (2.0, 1.5, false)]
        );
        for (height, down) in [(2.0_f32, true), (-2.0, false)] {
            let caps = end_caps(&Shape::Cone { height, radius: 0.7, thetamax: 360.0 });
            assert_eq!(caps.iter().map(cap).collect::<Vec<_>>(), [(0.0, 0.7, down)], "h {height}");
        }
        let para = |zmin| Shape::Paraboloid { rmax: 2.0, zmin, zmax: 4.0, thetamax: 360.0 };
        let caps: Vec<_> = end_caps(&para(1.0)).iter().map(cap).collect();
        assert_eq!(caps, [(1.0, 1.0, true), (4.0, 2.0, false)], "rmax sqrt(zmin/zmax) at zmin");
        let caps: Vec<_> = end_caps(&para(0.0)).iter().map(cap).collect();
        assert_eq!(caps, [(4.0, 2.0, false)], "no cap at the apex");
        for closed in [
            Shape::Sphere { radius: 1.0, zmin: None, zmax: None, thetamax: 360.0 },
            Shape::Torus {
                major_radius: 2.0,
                minor_radius: 0.5,
                phimin: 0.0,
                phimax: 360.0,
                thetamax: 360.0,
            },
            Shape::Mesh { points: vec![], faces: vec![], colors: None },
        ] {
            assert!(end_caps(&closed).is_empty());
        }
        // Every cap: on its plane, inside its circle, with the parametric orientation of the
        // micropolygon winding equal to its geometric normal, which points out of the solid
        // (away from the side the rest of the solid lies on).
        for (shape, inside) in [
            (cyl, Vec3::new(0.0, 0.0, 0.5)),
            (Shape::Cone { height: 2.0, radius: 0.7, thetamax: 360.0 }, Vec3::new(0.0, 0.0, 1.0)),
            (Shape::Cone { height: -2.0, radius: 0.7, thetamax: 360.0 }, Vec3::new(0.0, 0.0, -1.0)),
            (para(1.0), Vec3::new(0.0, 0.0, 2.5)),
        ] {
            for c in end_caps(&shape) {
                let (height, radius, _) = cap(&c);
                check_unit_and_consistent(&c);
                for (u, v) in params() {
                    let sp = c.eval(u, v);
                    assert_eq!(sp.p.z, height);
                    assert!(sp.p.truncate().length() <= radius * (1.0 + 1e-6));
                    assert!(sp.n.dot(Vec3::new(0.0, 0.0, height) - inside) > 0.0, "{c:?}");
                }
            }
        }
    }

    #[test]
    fn torus_points_on_surface_with_outward_normals() {
        let obj = object(Shape::Torus {
            major_radius: 3.0,
            minor_radius: 1.0,
            phimin: -90.0,
            phimax: 270.0,
            thetamax: 360.0,
        });
        let s = &surfaces(&obj)[0];
        for (u, v) in params() {
            let sp = s.eval(u, v);
            // Distance from the tube's centre circle is the minor radius.
            let ring = sp.p.truncate().normalize() * 3.0;
            let centre = Vec3::new(ring.x, ring.y, 0.0);
            assert!(((sp.p - centre).length() - 1.0).abs() < 1e-5);
            assert!((sp.n - (sp.p - centre)).length() < 1e-5, "outward from the tube centre");
        }
        check_unit_and_consistent(s);
    }

    #[test]
    fn bilinear_patch_interpolates_corners() {
        let pts = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.5], [2.0, 1.0, -0.5]];
        let obj = object(Shape::BilinearPatch { points: pts });
        let s = &surfaces(&obj)[0];
        for (k, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].into_iter().enumerate()
        {
            assert_eq!(s.position(u, v), Vec3::from(pts[k]));
        }
        let mid = s.eval(0.5, 0.5);
        assert!((mid.p - Vec3::new(1.0, 0.5, 0.0)).length() < 1e-6);
        check_unit_and_consistent(s);
        // Degenerate: a patch collapsed to a segment falls back to a finite unit normal.
        let obj = object(Shape::BilinearPatch {
            points: [[0.0; 3], [1.0, 0.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]],
        });
        let n = surfaces(&obj)[0].eval(0.5, 0.5).n;
        assert!((n.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn mesh_faces_become_patches_with_tints() {
        let obj = object(Shape::Mesh {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
                [2.0, 0.0, 0.0],
            ],
            faces: vec![vec![0, 1, 2, 3], vec![1, 4, 2], vec![0, 1], vec![0, 9, 1]],
            colors: Some(vec![
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 1.0],
            ]),
        });
        let s = surfaces(&obj);
        assert_eq!(s.len(), 2, "the two-index face and the face with a bad index are skipped");
        // Quad a,b,c,d -> P0=a, P1=b, P2=d, P3=c.
        let q = &s[0];
        assert_eq!(q.eval(0.0, 0.0).tint, Vec3::X);
        assert_eq!(q.eval(1.0, 0.0).tint, Vec3::Y);
        assert_eq!(q.eval(1.0, 1.0).tint, Vec3::Z);
        assert_eq!(q.eval(0.0, 1.0).tint, Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(q.position(0.0, 1.0), Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(q.eval(0.3, 0.6).n, Vec3::Z);
        // Triangle a,b,c -> P0=a, P1=b, P2=P3=c, flat normal cross(b-a, c-a).
        let t = &s[1];
        assert_eq!(t.eval(0.0, 0.0).tint, Vec3::Y);
        assert_eq!(t.eval(1.0, 0.0).tint, Vec3::new(0.0, 1.0, 1.0));
        assert_eq!(t.eval(0.2, 1.0).tint, Vec3::Z);
        assert_eq!(t.eval(0.2, 1.0).p, Vec3::new(1.0, 1.0, 0.0));
        assert_eq!(t.eval(0.5, 1.0).n, Vec3::Z);
    }

    #[test]
    fn polygons_with_more_than_four_sides_are_fanned() {
        let obj = object(Shape::Mesh {
            points: vec![
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [1.5, 1.0, 0.0],
                [0.5, 2.0, 0.0],
                [-0.5, 1.0, 0.0],
            ],
            faces: vec![vec![0, 1, 2, 3, 4]],
            colors: None,
        });
        assert_eq!(surfaces(&obj).len(), 3);
    }
}

//! Unit tests of the shapes stage: every surface on its analytic shape, unit normals that
//! agree with the parametric orientation, end caps facing out of their solids.

use super::*;
use reyes_scene::{Basis, Faces, Material, PatchType, Wrap};
use reyes_testkit::fixtures;

/// The surfaces of an object whose ribbons (none here) face their normals.
fn surfaces(object: &Object) -> Vec<Surface> {
    super::surfaces(object, Facing::Normals)
}

/// [`super::shape_surfaces`] with ribbons facing their normals.
fn shape_surfaces(shape: &Shape, points: Option<&[Vec3]>) -> Vec<Surface> {
    super::shape_surfaces(shape, points, Facing::Normals)
}

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
        assert!((sp.n.length() - 1.0).abs() < 1e-5, "{s:?} at ({u},{v}): |N| = {}", sp.n.length());
        if let Some(pn) = parametric_normal(s, u, v) {
            assert!(pn.dot(sp.n) > 0.99, "{s:?} at ({u},{v}): N {} vs dPdu x dPdv {pn}", sp.n);
        }
    }
}

#[test]
fn sphere_points_on_surface_with_outward_normals() {
    let obj = object(Shape::Sphere { radius: 2.0, zmin: Some(-1.0), zmax: None, thetamax: 300.0 });
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
    assert_eq!(caps.iter().map(cap).collect::<Vec<_>>(), [(-1.0, 1.5, true), (2.0, 1.5, false)]);
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
        Shape::Mesh { points: vec![], faces: Faces::new(), colors: None, normals: None, st: None },
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
    for (k, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].into_iter().enumerate() {
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
        faces: Faces::from(vec![vec![0, 1, 2, 3], vec![1, 4, 2], vec![0, 1], vec![0, 9, 1]]),
        colors: Some(fixtures::five_colors()),
        normals: None,
        st: None,
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
        points: vec![[0.0; 3], [1.0, 0.0, 0.0], [1.5, 1.0, 0.0], [0.5, 2.0, 0.0], [-0.5, 1.0, 0.0]],
        faces: Faces::from(vec![vec![0, 1, 2, 3, 4]]),
        colors: None,
        normals: None,
        st: None,
    });
    assert_eq!(surfaces(&obj).len(), 3);
}

#[test]
fn cylinder_like_hyperboloid_is_the_cylinder() {
    let hyp = object(Shape::Hyperboloid {
        point1: [1.0, 0.0, -1.0],
        point2: [1.0, 0.0, 1.0],
        thetamax: 300.0,
    });
    let cyl = object(Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 300.0 });
    let (h, c) = (&surfaces(&hyp)[0], &surfaces(&cyl)[0]);
    for (u, v) in params() {
        let (a, b) = (h.eval(u, v), c.eval(u, v));
        assert!((a.p - b.p).length() < 1e-6, "({u},{v}): {} vs {}", a.p, b.p);
        assert!((a.n - b.n).length() < 1e-6, "({u},{v}): {} vs {}", a.n, b.n);
    }
    check_unit_and_consistent(h);
}

#[test]
fn cone_like_hyperboloid_is_the_cone() {
    for height in [2.0_f32, -1.5] {
        let hyp = object(Shape::Hyperboloid {
            point1: [0.75, 0.0, 0.0],
            point2: [0.0, 0.0, height],
            thetamax: 360.0,
        });
        let cone = object(Shape::Cone { height, radius: 0.75, thetamax: 360.0 });
        let (h, c) = (&surfaces(&hyp)[0], &surfaces(&cone)[0]);
        for (u, v) in params() {
            let (a, b) = (h.eval(u, v), c.eval(u, v));
            assert!((a.p - b.p).length() < 1e-6, "({u},{v})");
            if height > 0.0 {
                // The negative cone's normal is flipped outward; the hyperboloid keeps its
                // parametric orientation (which winds inward there).
                assert!((a.n - b.n).length() < 1e-5, "({u},{v}): {} vs {}", a.n, b.n);
            } else {
                assert!((a.n + b.n).length() < 1e-5, "({u},{v}): {} vs {}", a.n, b.n);
            }
        }
        check_unit_and_consistent(h);
    }
}

#[test]
fn hyperboloid_points_satisfy_the_implicit_equation() {
    // x^2 + y^2 = |L_xy(v)|^2 with v = (z - z1) / (z2 - z1): a one-sheet hyperboloid.
    let (p1, p2) = (Vec3::new(1.0, -0.6, -1.0), Vec3::new(0.4, 0.8, 1.5));
    let obj = object(Shape::Hyperboloid {
        point1: p1.to_array(),
        point2: p2.to_array(),
        thetamax: 250.0,
    });
    let s = &surfaces(&obj)[0];
    for (u, v) in params() {
        let sp = s.eval(u, v);
        let t = (sp.p.z - p1.z) / (p2.z - p1.z);
        let l = p1.lerp(p2, t);
        let rho2 = sp.p.x * sp.p.x + sp.p.y * sp.p.y;
        assert!((rho2 - (l.x * l.x + l.y * l.y)).abs() < 1e-5, "({u},{v})");
        // The normal is the implicit function's gradient direction, up to sign:
        // F = x^2 + y^2 - |L_xy((z - z1) / dz)|^2.
        let d = p2 - p1;
        let grad = Vec3::new(2.0 * sp.p.x, 2.0 * sp.p.y, -2.0 * (l.x * d.x + l.y * d.y) / d.z);
        assert!(grad.normalize().cross(sp.n).length() < 1e-4, "({u},{v})");
        assert!(grad.dot(sp.n) > 0.0, "outward, away from the axis");
    }
    check_unit_and_consistent(s);
}

/// Sixteen points of a bicubic patch with the given z heights, on a unit grid.
fn grid16(z: impl Fn(usize, usize) -> f32) -> Vec<[f32; 3]> {
    (0..16).map(|k| [(k % 4) as f32, (k / 4) as f32, z(k % 4, k / 4)]).collect()
}

#[test]
fn patch_meshes_give_one_surface_per_sub_patch() {
    let points = (0..28).map(|k| [(k % 4) as f32, (k / 4) as f32, ((k * 3) % 5) as f32]).collect();
    let bicubic = fixtures::patch_mesh(PatchType::Bicubic, 4, 7, points);
    let s = surfaces(&object(bicubic));
    assert_eq!(s.len(), 2, "(7 - 4) / 3 + 1 = 2 sub-patches along v");
    // Bezier sub-patches interpolate their corners, and neighbours share an edge.
    assert_eq!(s[0].position(0.0, 0.0), Vec3::new(0.0, 0.0, 0.0));
    assert_eq!(s[0].position(1.0, 1.0), s[1].position(1.0, 0.0));
    for u in [0.0, 0.3, 0.8, 1.0] {
        assert!((s[0].position(u, 1.0) - s[1].position(u, 0.0)).length() < 1e-6);
    }
    let bilinear = fixtures::patch_mesh_with(
        PatchType::Bilinear,
        3,
        2,
        (Wrap::Periodic, Wrap::Nonperiodic),
        (Basis::Bezier, Basis::Bezier),
        vec![
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.5, 1.0, 1.0],
        ],
    );
    let s = surfaces(&object(bilinear));
    assert_eq!(s.len(), 3, "periodic: 3 sub-patches around");
    assert_eq!(s[2].position(1.0, 0.0), Vec3::ZERO, "the last wraps to the first point");
    assert_eq!(s[2].position(0.0, 1.0), Vec3::new(0.5, 1.0, 1.0));
}

#[test]
fn a_bezier_patch_with_collinear_rows_is_flat() {
    // Control points on the plane z = 0.25 x - 0.5 y + 1 (collinear along each row and
    // column, unevenly spaced): the patch stays on the plane, its normal is the plane's.
    let pts = grid16(|_, _| 0.0)
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            let x = p[0] + 0.3 * ((k % 4) as f32).powi(2);
            [x, p[1], 0.25 * x - 0.5 * p[1] + 1.0]
        })
        .collect();
    let shape = fixtures::patch_mesh(PatchType::Bicubic, 4, 4, pts);
    let s = &surfaces(&object(shape))[0];
    let plane = Vec3::new(-0.25, 0.5, 1.0).normalize();
    for (u, v) in params() {
        let sp = s.eval(u, v);
        assert!((sp.p.z - (0.25 * sp.p.x - 0.5 * sp.p.y + 1.0)).abs() < 1e-5, "({u},{v})");
        assert!((sp.n - plane).length() < 1e-5, "({u},{v}): {}", sp.n);
    }
    check_unit_and_consistent(s);
}

#[test]
fn nurbs_circle_lies_on_the_unit_cylinder() {
    let shape = fixtures::nurbs_cylinder();
    let s = surfaces(&object(shape));
    assert_eq!(s.len(), 4, "four quarter-circle spans");
    for (k, surface) in s.iter().enumerate() {
        for (u, v) in params() {
            let sp = surface.eval(u, v);
            let r = sp.p.truncate().length();
            assert!((r - 1.0).abs() < 1e-6, "span {k} ({u},{v}): radius {r}");
            assert!((sp.p.z - (2.0 * v - 1.0)).abs() < 1e-6);
            let radial = Vec3::new(sp.p.x, sp.p.y, 0.0) / r;
            assert!((sp.n - radial).length() < 1e-5, "outward: {}", sp.n);
        }
        check_unit_and_consistent(surface);
    }
}

#[test]
fn deformation_keys_move_patch_meshes_and_nurbs() {
    let (wrap, bases) = ((Wrap::Nonperiodic, Wrap::Nonperiodic), (Basis::BSpline, Basis::Bezier));
    let points = grid16(|i, j| (i * j) as f32 * 0.1);
    let mesh = fixtures::patch_mesh_with(PatchType::Bicubic, 4, 4, wrap, bases, points);
    let own = control_points(&mesh).unwrap();
    assert_eq!(own.len(), 16);
    assert_eq!(shape_surfaces(&mesh, Some(&own)), surfaces(&object(mesh.clone())));
    let lifted: Vec<Vec3> = own.iter().map(|p| *p + Vec3::Z).collect();
    let moved = shape_surfaces(&mesh, Some(&lifted));
    let still = surfaces(&object(mesh));
    assert_eq!(moved.len(), still.len());
    for (u, v) in params() {
        let d = moved[0].position(u, v) - still[0].position(u, v);
        assert!((d - Vec3::Z).length() < 1e-5, "a translated net is the translated patch");
    }
    // A NURBS key gives positions and keeps the weights: a quarter circle of weight 1/sqrt(2)
    // moved up stays a (moved) circular arc.
    let w = std::f32::consts::FRAC_1_SQRT_2;
    let points = vec![
        [1.0, 0.0, 0.0, 1.0],
        [w, w, 0.0, w],
        [0.0, 1.0, 0.0, 1.0],
        [1.0, 0.0, 1.0, 1.0],
        [w, w, w, w],
        [0.0, 1.0, 1.0, 1.0],
    ];
    let nurbs = fixtures::nurbs_ruled(3, 3, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], points);
    let own = control_points(&nurbs).unwrap();
    assert!((own[1] - Vec3::new(1.0, 1.0, 0.0)).length() < 1e-6, "positions, not Pw");
    let lifted: Vec<Vec3> = own.iter().map(|p| *p + Vec3::Z * 2.0).collect();
    let moved = shape_surfaces(&nurbs, Some(&lifted));
    assert_eq!(moved.len(), surfaces(&object(nurbs)).len());
    for (u, v) in params() {
        let p = moved[0].position(u, v);
        assert!((p.truncate().length() - 1.0).abs() < 1e-6, "({u},{v}): still round");
        assert!((p.z - (2.0 + v)).abs() < 1e-6);
    }
}

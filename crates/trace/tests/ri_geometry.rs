//! The RenderMan geometry of the ray engine: the hyperboloid hit exactly at its analytic
//! points (and as the cylinder and cone it can be), bilinear patch meshes exactly, and the
//! tessellated bicubic patch meshes and NURBS within their stated error bound, with a wrapped
//! mesh closed (no ray escapes through a seam) and deformation keys followed; a trimmed
//! NURBS lets rays (and shadow rays) through its holes.

mod common;

use common::{Rng, close, close_v, deforming, object, placed, scene, shoot};
use glam::{DVec3, Mat3, Mat4, Vec3};
use reyes_scene::patches::{self, BezierPatch};
use reyes_scene::{Basis, PatchType, Shape, Transform, Wrap, object_to_world};
use reyes_testkit::fixtures::{nurbs_cylinder, nurbs_ruled, patch_mesh, patch_mesh_with};
use reyes_trace::{Ray, Tracer};

/// The hyperboloid's point and outward normal at `(u, v)`, written from the definition:
/// `Rz(u thetamax) lerp(p1, p2, v)` and `dP/du x dP/dv` by the product rule.
fn hyperboloid_at(p1: Vec3, p2: Vec3, thetamax: f32, u: f32, v: f32) -> (Vec3, Vec3) {
    let th = u * thetamax.to_radians();
    let rot = Mat3::from_rotation_z(th);
    let l = p1.lerp(p2, v);
    let dpdu = rot * Vec3::new(-l.y, l.x, 0.0);
    let dpdv = rot * (p2 - p1);
    (rot * l, dpdu.cross(dpdv).normalize())
}

#[test]
fn hyperboloid_points_hit_with_the_dicers_normal_and_uv() {
    let (p1, p2, tmax) = (Vec3::new(1.0, -0.6, -1.0), Vec3::new(0.4, 0.8, 1.5), 300.0);
    let shape = Shape::Hyperboloid { point1: p1.to_array(), point2: p2.to_array(), thetamax: tmax };
    for transform in [vec![], placed([1.0, 1.5, 0.75], 35.0, [1.0, 2.0, 0.5], [0.5, -1.0, 2.0])] {
        let m = object_to_world(&transform);
        let t = Tracer::new(&scene(vec![object(shape.clone(), transform)]));
        for (u, v) in [(0.1, 0.2), (0.45, 0.5), (0.8, 0.9), (0.95, 0.05)] {
            let (p, n) = hyperboloid_at(p1, p2, tmax, u, v);
            let pw = m.transform_point3(p);
            let nw = (Mat3::from_mat4(m).inverse().transpose() * n).normalize();
            // From outside along the normal, and from the inside of the sheet against it.
            for (origin, dir) in [(pw + nw * 0.5, -nw), (pw - nw * 0.05, nw)] {
                let hit = shoot(&t, origin, dir, 0.0).expect("hit");
                assert!(close_v(hit.p_world, pw, 2e-4), "({u},{v}): {} vs {pw}", hit.p_world);
                assert!(close_v(hit.n_world, nw, 2e-4), "({u},{v}): {} vs {nw}", hit.n_world);
                assert!(close(hit.u, u, 1e-4) && close(hit.v, v, 1e-4), "({u},{v})");
                assert!(close_v(hit.p_object, p, 2e-4));
            }
        }
        // Beyond the sweep (theta in (300, 360) degrees) the ray passes through.
        let (p, n) = hyperboloid_at(p1, p2, 360.0, 0.9, 0.5);
        let (pw, nw) = (m.transform_point3(p), Mat3::from_mat4(m).inverse().transpose() * n);
        let hit = shoot(&t, pw + nw.normalize() * 0.01, -nw, 0.0);
        assert!(hit.is_none_or(|h| (h.p_world - pw).length() > 1e-2), "the cut-away wedge");
    }
}

#[test]
fn a_cylinder_like_hyperboloid_is_hit_as_the_cylinder() {
    let hyp =
        Shape::Hyperboloid { point1: [1.0, 0.0, -1.0], point2: [1.0, 0.0, 1.0], thetamax: 270.0 };
    let cyl = Shape::Cylinder { radius: 1.0, zmin: -1.0, zmax: 1.0, thetamax: 270.0 };
    let cone_h =
        Shape::Hyperboloid { point1: [0.8, 0.0, 0.0], point2: [0.0, 0.0, 1.5], thetamax: 360.0 };
    let cone = Shape::Cone { height: 1.5, radius: 0.8, thetamax: 360.0 };
    let mut rng = Rng::new(7);
    for (a, b) in [(hyp, cyl), (cone_h, cone)] {
        let (ta, tb) = (
            Tracer::new(&scene(vec![object(a, vec![])])),
            Tracer::new(&scene(vec![object(b, vec![])])),
        );
        for _ in 0..2000 {
            let origin = rng.in_cube(3.0);
            let dir = (rng.in_cube(0.7) - origin).normalize();
            match (shoot(&ta, origin, dir, 0.0), shoot(&tb, origin, dir, 0.0)) {
                (None, None) => {}
                (Some(x), Some(y)) => {
                    assert!(close(x.t, y.t, 1e-4), "t {} vs {}", x.t, y.t);
                    assert!(close_v(x.n_world, y.n_world, 1e-4), "{} vs {}", x.n_world, y.n_world);
                    assert!(close(x.u, y.u, 1e-4) && close(x.v, y.v, 1e-4));
                }
                (x, y) => panic!("one hit, one miss: {x:?} vs {y:?} from {origin} along {dir}"),
            }
        }
    }
}

/// A bicubic patch mesh with the given bases and wraps.
fn mesh(nu: u32, nv: u32, wrap: (Wrap, Wrap), basis: Basis, points: Vec<[f32; 3]>) -> Shape {
    patch_mesh_with(PatchType::Bicubic, nu, nv, wrap, (basis, basis), points)
}

/// A B-spline tube of radius about 1 around z: 8 points around, 5 along, wrapped in u.
fn tube() -> Shape {
    let mut points = Vec::new();
    for j in 0..5 {
        for i in 0..8 {
            let a = i as f32 * std::f32::consts::TAU / 8.0;
            points.push([a.cos(), a.sin(), j as f32 - 2.0]);
        }
    }
    mesh(8, 5, (Wrap::Periodic, Wrap::Nonperiodic), Basis::BSpline, points)
}

/// The distance from `p` to the exact surface: the nearest point of a grid over every
/// patch, polished by Gauss-Newton steps on `|S(u, v) - p|^2` (clamped to the patch).
fn distance_to(patches: &[BezierPatch], p: DVec3) -> f64 {
    let n = 24;
    let mut best = f64::INFINITY;
    for b in patches {
        let (mut u, mut v, mut d) = (0.0, 0.0, f64::INFINITY);
        for j in 0..=n {
            for i in 0..=n {
                let (a, c) = (i as f64 / n as f64, j as f64 / n as f64);
                let q = (b.eval(a, c).p - p).length();
                if q < d {
                    (u, v, d) = (a, c, q);
                }
            }
        }
        for _ in 0..20 {
            let e = b.eval(u, v);
            let r = p - e.p;
            let (a, bb, c) = (e.dpdu.dot(e.dpdu), e.dpdu.dot(e.dpdv), e.dpdv.dot(e.dpdv));
            let (x, y) = (e.dpdu.dot(r), e.dpdv.dot(r));
            let det = a * c - bb * bb;
            if det.abs() < 1e-300 {
                break;
            }
            u = (u + (c * x - bb * y) / det).clamp(0.0, 1.0);
            v = (v + (a * y - bb * x) / det).clamp(0.0, 1.0);
        }
        best = best.min(d).min((b.eval(u, v).p - p).length());
    }
    best
}

#[test]
fn tessellated_hits_lie_on_the_surface_within_the_bound() {
    let wavy: Vec<[f32; 3]> =
        (0..16).map(|k| [(k % 4) as f32, (k / 4) as f32, ((k * 5) % 7) as f32 * 0.3]).collect();
    let circle = nurbs_cylinder();
    let mut rng = Rng::new(11);
    for (name, shape) in [
        ("bezier", mesh(4, 4, (Wrap::Nonperiodic, Wrap::Nonperiodic), Basis::Bezier, wavy.clone())),
        (
            "catmull-rom",
            mesh(4, 4, (Wrap::Nonperiodic, Wrap::Nonperiodic), Basis::CatmullRom, wavy),
        ),
        ("b-spline tube", tube()),
        ("nurbs cylinder", circle),
    ] {
        let exact = patches::bezier_patches(&shape, None);
        let t = Tracer::new(&scene(vec![object(shape.clone(), vec![])]));
        let mut hits = 0;
        let hull: Vec<DVec3> = exact.iter().flat_map(|b| b.hull().collect::<Vec<_>>()).collect();
        let centre = (hull.iter().sum::<DVec3>() / hull.len() as f64).as_vec3();
        for _ in 0..300 {
            let origin = centre + rng.in_cube(6.0);
            let dir = (centre + rng.in_cube(0.5) - origin).normalize();
            let Some(hit) = shoot(&t, origin, dir, 0.0) else { continue };
            hits += 1;
            // The bound is 1/1000 of the diagonal of the hit patch's control box.
            let b = &exact[hit.surface as usize];
            let (lo, hi) = b
                .hull()
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), x| (l.min(x), h.max(x)));
            let bound = 1e-3 * (hi - lo).length();
            let d = distance_to(std::slice::from_ref(b), hit.p_object.as_dvec3());
            assert!(d <= bound, "{name}: a hit {d} off the surface (bound {bound})");
            // The reported normal is the surface's, interpolated: within a few degrees.
            let n = b.normal(f64::from(hit.u), f64::from(hit.v)).as_vec3();
            assert!(hit.n_world.dot(n) > 0.99, "{name}: normal {} vs {n}", hit.n_world);
        }
        assert!(hits > 30, "{name}: only {hits} hits");
    }
}

#[test]
fn a_wrapped_b_spline_tube_is_closed() {
    // From points inside the tube, every ray across it hits the wall: no seam lets one out.
    let t = Tracer::new(&scene(vec![object(tube(), vec![])]));
    let mut rng = Rng::new(3);
    for k in 0..4000 {
        let a = k as f32 * 0.001571 + rng.range(0.0, 1e-3);
        let origin = Vec3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3), rng.range(-0.4, 0.4));
        let dir = Vec3::new(a.cos(), a.sin(), rng.range(-0.2, 0.2));
        let hit = shoot(&t, origin, dir, 0.0).unwrap_or_else(|| panic!("escaped at angle {a}"));
        // The uniform B-spline of a regular octagon of radius 1 has radius (4 + 2 cos 45) / 6
        // = 0.9024 at a knot and (46 cos 22.5 + 2 cos 67.5) / 48 = 0.9013 mid-span.
        let r = hit.p_world.truncate().length();
        assert!((0.8995..0.9035).contains(&r), "radius {r}");
        assert!(hit.n_world.truncate().dot(hit.p_world.truncate()) > 0.0, "outward normal");
    }
}

#[test]
fn bilinear_patch_meshes_are_hit_exactly() {
    let shape = patch_mesh(
        PatchType::Bilinear,
        3,
        2,
        vec![
            [0.0; 3],
            [1.0, 0.0, 0.5],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.5],
            [2.0, 1.0, 0.0],
        ],
    );
    let m = Mat4::from_translation(Vec3::new(0.5, 0.0, 1.0));
    let t = Tracer::new(&scene(vec![object(shape, vec![Transform::Translate([0.5, 0.0, 1.0])])]));
    for (x, y, surface) in [(0.5, 0.3, 0), (1.5, 0.7, 1)] {
        let z = if x < 1.0 { 0.5 * x } else { 0.5 * (2.0 - x) };
        let p = m.transform_point3(Vec3::new(x, y, z));
        let hit = shoot(&t, p - Vec3::Z * 3.0, Vec3::Z, 0.0).expect("hit");
        assert!(close_v(hit.p_world, p, 1e-5), "{} vs {p}", hit.p_world);
        assert_eq!(hit.surface, surface);
        assert!(close(hit.u, x.fract(), 1e-5) && close(hit.v, y, 1e-5));
    }
}

#[test]
fn deforming_patch_meshes_follow_their_keys() {
    let flat: Vec<[f32; 3]> = (0..16).map(|k| [(k % 4) as f32, (k / 4) as f32, 0.0]).collect();
    let lifted: Vec<[f32; 3]> = flat.iter().map(|p| [p[0], p[1], 2.0]).collect();
    let shape = mesh(4, 4, (Wrap::Nonperiodic, Wrap::Nonperiodic), Basis::Bezier, flat.clone());
    let t = Tracer::new(&scene(vec![deforming(shape, vec![(0.0, flat), (1.0, lifted)])]));
    for time in [0.0, 0.25, 0.5, 1.0] {
        let hit = common::shoot(&t, Vec3::new(1.3, 1.7, -5.0), Vec3::Z, time).expect("hit");
        assert!(close(hit.p_world.z, 2.0 * time, 1e-5), "at {time}: {}", hit.p_world);
    }
}

#[test]
fn a_horizontal_segment_sweeps_a_flat_ring() {
    // point1 -> point2 along +x in z = 0.5: the ring 0.5 <= r <= 1.5, whose normal
    // dP/du x dP/dv = (0, 0, -x dx) faces -z; v = r - 0.5.
    let shape =
        Shape::Hyperboloid { point1: [0.5, 0.0, 0.5], point2: [1.5, 0.0, 0.5], thetamax: 360.0 };
    let t = Tracer::new(&scene(vec![object(shape, vec![])]));
    for (x, y) in [(1.0_f32, 0.0_f32), (0.0, -0.7), (-1.2, 0.6)] {
        let hit = shoot(&t, Vec3::new(x, y, 3.0), Vec3::NEG_Z, 0.0).expect("hit");
        assert!(close(hit.t, 2.5, 1e-5));
        assert!(close_v(hit.n_world, Vec3::NEG_Z, 1e-6), "{}", hit.n_world);
        assert!(close(hit.v, Vec3::new(x, y, 0.0).length() - 0.5, 1e-5));
    }
    assert!(shoot(&t, Vec3::new(0.2, 0.1, 3.0), Vec3::NEG_Z, 0.0).is_none(), "the hole");
    assert!(shoot(&t, Vec3::new(1.6, 0.0, 3.0), Vec3::NEG_Z, 0.0).is_none(), "outside");
}

/// The square NuPatch over x, y in [-1, 1] at z = `z` (u along x, v along y), with a round
/// hole of radius 1/4 of (u, v) about (1/2, 1/2), a world radius of 1/2 about the z axis:
/// the nine-point circle, four exact quarter arcs.
fn holed_square(z: f32) -> Shape {
    let corners =
        vec![[-1.0, -1.0, z, 1.0], [1.0, -1.0, z, 1.0], [-1.0, 1.0, z, 1.0], [1.0, 1.0, z, 1.0]];
    let mut square = nurbs_ruled(2, 2, vec![0.0, 0.0, 1.0, 1.0], corners);
    if let Shape::NuPatch { trim, .. } = &mut square {
        *trim = vec![reyes_scene::TrimLoop::circle(0.5, 0.5, 0.25)];
    }
    square
}

#[test]
fn rays_pass_through_a_trim_hole_to_what_lies_behind() {
    // The holed square at z = 0 in front of a plain square at z = 1.
    let back = Shape::BilinearPatch {
        points: [[-2.0, -2.0, 1.0], [2.0, -2.0, 1.0], [-2.0, 2.0, 1.0], [2.0, 2.0, 1.0]],
    };
    let t = Tracer::new(&scene(vec![object(holed_square(0.0), vec![]), object(back, vec![])]));
    let dir = Vec3::Z;
    // Inside the hole (radius 1/2): the ray goes on to the back square, object 1.
    for (x, y) in [(0.0, 0.0), (0.45, 0.0), (-0.3, 0.3), (0.0, -0.49)] {
        let h = shoot(&t, Vec3::new(x, y, -5.0), dir, 0.0).expect("the back square");
        assert_eq!(h.object, 1, "({x}, {y}) through the hole");
        assert!(close(h.p_world.z, 1.0, 1e-5));
        // A shadow ray stopping short of the back square is not blocked either.
        assert!(!t.occluded(&Ray::new(Vec3::new(x, y, -5.0), dir, 0.0), 5.5), "({x}, {y})");
    }
    // Outside it: the holed square itself, at its own (u, v).
    for (x, y) in [(0.55, 0.0), (0.9, 0.9), (-0.8, 0.1), (0.0, 0.51)] {
        let h = shoot(&t, Vec3::new(x, y, -5.0), dir, 0.0).expect("the holed square");
        assert_eq!(h.object, 0, "({x}, {y}) off the hole");
        assert!(close(h.u, (x + 1.0) / 2.0, 1e-4) && close(h.v, (y + 1.0) / 2.0, 1e-4));
        assert!(t.occluded(&Ray::new(Vec3::new(x, y, -5.0), dir, 0.0), 5.5), "({x}, {y})");
    }
}
